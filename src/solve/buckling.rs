//! The lowest buckling factor of a preload: the smallest λ > 0 with (K + λ K_G) φ = 0, i.e. of
//! K φ = −λ K_G φ (K positive definite, K_G indefinite).
//!
//! With μ = 1/λ this is the largest eigenvalue of −K_G φ = μ K φ, found by Lanczos in the K
//! inner product on the operator K⁻¹(−K_G) (self-adjoint in that inner product), with full
//! reorthogonalization (Golub & Van Loan, *Matrix Computations*, 4th ed. (2013) §10.1 and
//! §8.7.2 for the symmetric-definite pencil). Each step costs one solve with the Cholesky factor
//! of K and two sparse products. The extreme eigenvalue of this pencil is well separated for
//! the usual structures (a column's μ_n ∝ 1/n²), so a few dozen steps give it to ~1e-10.

use super::{sparse_ops, SolveError, SparseColMat, SparseLlt};
use faer::{Mat, Par};

/// Largest Lanczos steps.
const MAX_STEPS: usize = 80;

/// Relative change of the largest Ritz value between two steps that ends the iteration.
const CONVERGED: f64 = 1e-12;

/// A largest μ = 1/λ at most this fraction of the spectrum's largest |μ| is a zero eigenvalue of
/// −K_G up to rounding (a null direction of the stress, e.g. the axial dofs of a beam in
/// tension), not compression: nothing in compression, no buckling factor. Measured: a beam in
/// pure tension gives μ_max/max|μ| ≈ 1e-16 (it wrote λ₁ = 1.85e22 before this test).
const NO_COMPRESSION: f64 = 1e-9;

/// The lowest positive buckling factor λ₁ of K φ = −λ K_G φ (K positive definite, both full
/// symmetric, module doc); `None` when no λ > 0 exists (no compression anywhere: −K_G has no
/// positive eigenvalue against K, or only one of at most [`NO_COMPRESSION`] of the largest |μ|:
/// a zero eigenvalue up to rounding).
pub fn lowest_buckling_factor(
    k: &SparseColMat<usize, f64>,
    kg: &SparseColMat<usize, f64>,
    par: Par,
) -> Result<Option<f64>, SolveError> {
    super::check_pair(k.as_ref(), kg.as_ref(), "buckling factor: ")?;
    let n = k.nrows();
    if n == 0 {
        return Ok(None);
    }
    let llt = SparseLlt::factor(k.as_ref(), None, par)?;
    let k_inner = |a: &Mat<f64>, b: &Mat<f64>| -> f64 {
        let kb = sparse_ops::spmm(k.as_ref(), b.as_ref());
        (0..n).map(|i| a[(i, 0)] * kb[(i, 0)]).sum()
    };
    // deterministic start with every component present
    let mut v = Mat::from_fn(n, 1, |i, _| {
        1.0 + 0.5 * ((i as f64) * 0.618_033_988_749_895).sin()
    });
    let nv = k_inner(&v, &v).sqrt();
    v /= nv;
    let mut basis: Vec<Mat<f64>> = vec![v];
    let (mut alpha, mut beta): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
    let (mut last, mut scale) = (f64::NAN, 0.0f64);
    for j in 0..MAX_STEPS.min(n) {
        // w = K⁻¹(−K_G v_j)
        let mut w = -sparse_ops::spmm(kg.as_ref(), basis[j].as_ref());
        llt.solve_in_place(w.as_mut());
        alpha.push(k_inner(&w, &basis[j]));
        // full reorthogonalization (twice) in the K inner product
        for _ in 0..2 {
            for q in &basis {
                let c = k_inner(&w, q);
                w -= q * c;
            }
        }
        let b = k_inner(&w, &w).max(0.0).sqrt();
        let (bottom, top) = extreme_ritz(&alpha, &beta)?;
        scale = bottom.abs().max(top.abs());
        let done = (top - last).abs() <= CONVERGED * top.abs().max(f64::MIN_POSITIVE);
        if done || b <= 1e-14 * alpha.iter().fold(0.0f64, |m, a| m.max(a.abs())) {
            last = top;
            break;
        }
        last = top;
        beta.push(b);
        w /= b;
        basis.push(w);
    }
    Ok((last > NO_COMPRESSION * scale).then(|| 1.0 / last))
}

/// Smallest and largest eigenvalue of the symmetric tridiagonal matrix with diagonal `alpha`
/// and off-diagonal `beta` (the first alpha.len() − 1 values).
fn extreme_ritz(alpha: &[f64], beta: &[f64]) -> Result<(f64, f64), SolveError> {
    let m = alpha.len();
    let t = Mat::from_fn(m, m, |i, j| {
        if i == j {
            alpha[i]
        } else if i + 1 == j || j + 1 == i {
            beta[i.min(j)]
        } else {
            0.0
        }
    });
    let ev = t
        .self_adjoint_eigenvalues(faer::Side::Lower)
        .map_err(|e| SolveError::DenseEigen(format!("Lanczos tridiagonal: {e:?}")))?;
    let (lo, hi) = (ev.iter().copied()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), e| {
        (lo.min(e), hi.max(e))
    });
    Ok((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A diagonal pencil: K = diag(k), K_G = diag(g): λ₁ = min over g < 0 of k/(−g).
    #[test]
    fn buckling_factor_of_a_diagonal_pencil() {
        let kd = [4.0, 2.0, 9.0, 1.0, 5.0];
        let gd = [-1.0, 0.5, -2.0, 0.0, -0.1];
        let diag = |d: &[f64]| {
            let t: Vec<_> = (0..d.len())
                .map(|i| faer::sparse::Triplet::new(i, i, d[i]))
                .collect();
            SparseColMat::try_new_from_triplets(d.len(), d.len(), &t).unwrap()
        };
        let l = lowest_buckling_factor(&diag(&kd), &diag(&gd), Par::Seq)
            .unwrap()
            .unwrap();
        assert!((l - 4.0).abs() < 1e-12, "{l}");
        let none = lowest_buckling_factor(&diag(&kd), &diag(&[1.0; 5]), Par::Seq).unwrap();
        assert_eq!(none, None);
    }
}
