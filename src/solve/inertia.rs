//! Sylvester inertia of K − σM from a sparse LDLᵀ: how many eigenvalues of K φ = λ M φ lie
//! below σ (issue 22, the missed-mode proof of a band of modes).
//!
//! With M positive semi-definite and K − σM non-singular, the number of negative pivots of
//! K − σM = L D Lᵀ equals the number of finite eigenvalues λ < σ (Sylvester's law of inertia).
//! A band [lo, hi) then holds exactly `count_below(hi) − count_below(lo)` modes, whatever an
//! iterative eigensolver returned: [`check_band`] compares the two and names what is missing.
//!
//! The factorization is faer's supernodal LDLᵀ without pivoting on the METIS order (the same
//! symbolic analysis as the LLᵀ); a zero or non-finite pivot (σ on an eigenvalue, or a
//! breakdown) is an error, not a count.

use super::{cholesky, sparse_ops, SolveError, SparseColMat};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use faer::sparse::SparseColMatRef;
use faer::{Par, Side};

/// Signs of the pivots of an LDLᵀ factorization.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Inertia {
    /// Negative pivots: eigenvalues below the shift.
    pub negative: usize,
    /// Positive pivots.
    pub positive: usize,
}

/// The inertia of the symmetric matrix `a` (both triangles stored, the lower one is read).
pub fn inertia(
    a: SparseColMatRef<'_, usize, f64>,
    block: Option<usize>,
    par: Par,
) -> Result<Inertia, SolveError> {
    if a.val().iter().any(|v| !v.is_finite()) {
        return Err(SolveError::NonFinite("matrix of the inertia count"));
    }
    let (symbolic, _) = cholesky::analyze(a, block)?;
    cholesky::check_memory(cholesky::factor_memory(&symbolic, par), a.nrows())?;
    let mut values = vec![0.0f64; symbolic.len_val()];
    let req = symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default());
    let mut buf = MemBuffer::new(req);
    symbolic
        .factorize_numeric_ldlt(
            &mut values,
            a,
            Side::Lower,
            LdltRegularization::default(),
            par,
            MemStack::new(&mut buf),
            Default::default(),
        )
        .map_err(|e| SolveError::Factor(format!("LDLT for the inertia count: {e:?}")))?;
    let mut d = Vec::with_capacity(a.nrows());
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let (cp, ri) = (s.col_ptr(), s.row_idx());
            for j in 0..a.nrows() {
                // faer's simplicial LDLᵀ stores D in the diagonal slot of each column
                let p = (cp[j]..cp[j + 1]).find(|&p| ri[p] == j).unwrap_or(cp[j]);
                d.push(values[p]);
            }
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let (beg, end, rp, vp) = (
                s.supernode_begin(),
                s.supernode_end(),
                s.col_ptr_for_row_idx(),
                s.col_ptr_for_val(),
            );
            for k in 0..s.n_supernodes() {
                let w = end[k] - beg[k];
                let rows = w + rp[k + 1] - rp[k];
                for t in 0..w {
                    d.push(values[vp[k] + t * rows + t]);
                }
            }
        }
    }
    if let Some(j) = d.iter().position(|x| !x.is_finite() || *x == 0.0) {
        return Err(SolveError::Factor(format!(
            "LDLT for the inertia count: zero or non-finite pivot {j} (the shift is an eigenvalue, or the factorization broke down without pivoting)"
        )));
    }
    let negative = d.iter().filter(|&&x| x < 0.0).count();
    Ok(Inertia {
        negative,
        positive: d.len() - negative,
    })
}

/// How many finite eigenvalues of K φ = λ M φ lie below `sigma` (K, M full symmetric, M
/// positive semi-definite): the negative pivots of K − σM.
pub fn count_below(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    sigma: f64,
    block: Option<usize>,
    par: Par,
) -> Result<usize, SolveError> {
    let a = sparse_ops::add_scaled(k.as_ref(), m.as_ref(), -sigma)?;
    Ok(inertia(a.as_ref(), block, par)?.negative)
}

/// The proof that a band of modes is complete: the eigenvalues `found` that lie in [lo, hi)
/// against the inertia count of the band. `Ok(n)` when all n modes of the band are found;
/// `Err(missing)` with the number of modes of the band the solver did not return.
pub fn check_band(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    found: &[f64],
    lo: f64,
    hi: f64,
    block: Option<usize>,
    par: Par,
) -> Result<Result<usize, usize>, SolveError> {
    let below_hi = count_below(k, m, hi, block, par)?;
    let below_lo = if lo > 0.0 {
        count_below(k, m, lo, block, par)?
    } else {
        0 // K positive semi-definite: nothing below 0
    };
    let want = below_hi.saturating_sub(below_lo);
    let got = found.iter().filter(|&&l| l >= lo && l < hi).count();
    Ok(if got >= want {
        Ok(want)
    } else {
        Err(want - got)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::{lowest_modes, EigenSpec, Triplet};

    /// A 3-d grid of springs (nx·ny·nz nodes, one dof each, grounded at x = 0) with masses that
    /// vary node to node: K positive definite, M diagonal positive.
    fn grid(
        nx: usize,
        ny: usize,
        nz: usize,
    ) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
        let id = |i: usize, j: usize, l: usize| (l * ny + j) * nx + i;
        let n = nx * ny * nz;
        let mut kt = Vec::new();
        let mut diag = vec![0.0; n];
        let mut spring = |a: usize, b: usize, s: f64, kt: &mut Vec<Triplet<usize, usize, f64>>| {
            diag[a] += s;
            diag[b] += s;
            kt.push(Triplet::new(a, b, -s));
            kt.push(Triplet::new(b, a, -s));
        };
        for l in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let p = id(i, j, l);
                    if i + 1 < nx {
                        spring(p, id(i + 1, j, l), 1.0 + 0.1 * (j % 3) as f64, &mut kt);
                    }
                    if j + 1 < ny {
                        spring(p, id(i, j + 1, l), 1.3, &mut kt);
                    }
                    if l + 1 < nz {
                        spring(p, id(i, j, l + 1), 0.7 + 0.05 * (i % 4) as f64, &mut kt);
                    }
                }
            }
        }
        for j in 0..ny {
            for l in 0..nz {
                diag[id(0, j, l)] += 2.0; // grounded face
            }
        }
        kt.extend(diag.iter().enumerate().map(|(i, &d)| Triplet::new(i, i, d)));
        let mt: Vec<_> = (0..n)
            .map(|i| Triplet::new(i, i, 1.0 + 0.5 * ((i * 7) % 5) as f64))
            .collect();
        (
            SparseColMat::try_new_from_triplets(n, n, &kt).unwrap(),
            SparseColMat::try_new_from_triplets(n, n, &mt).unwrap(),
        )
    }

    /// All eigenvalues of the diagonal-M pencil, densely: M^{-1/2} K M^{-1/2}.
    fn dense_eigenvalues(k: &SparseColMat<usize, f64>, m: &SparseColMat<usize, f64>) -> Vec<f64> {
        let n = k.nrows();
        let md = sparse_ops::to_dense(m.as_ref());
        let s: Vec<f64> = (0..n).map(|i| 1.0 / md[(i, i)].sqrt()).collect();
        let kd = sparse_ops::to_dense(k.as_ref());
        let a = faer::Mat::<f64>::from_fn(n, n, |i, j| s[i] * kd[(i, j)] * s[j]);
        let mut v: Vec<f64> = a
            .self_adjoint_eigenvalues(Side::Lower)
            .unwrap()
            .into_iter()
            .collect();
        v.sort_by(f64::total_cmp);
        v
    }

    #[test]
    fn counts_eigenvalues_below_the_shift_like_the_dense_spectrum() {
        for dims in [(9, 7, 5), (10, 9, 8)] {
            let (k, m) = grid(dims.0, dims.1, dims.2);
            let ev = dense_eigenvalues(&k, &m);
            // shifts between consecutive eigenvalues across the spectrum
            for idx in [0usize, 1, 5, 40, ev.len() / 3, ev.len() / 2, ev.len() - 2] {
                let sigma = 0.5 * (ev[idx] + ev[idx + 1]);
                let c = count_below(&k, &m, sigma, None, Par::Seq).unwrap();
                assert_eq!(c, idx + 1, "{dims:?}: σ between λ{idx} and λ{}", idx + 1);
            }
            // below the lowest eigenvalue: none
            assert_eq!(count_below(&k, &m, 0.5 * ev[0], None, Par::Seq).unwrap(), 0);
        }
    }

    #[test]
    fn the_band_check_proves_a_complete_band_and_catches_a_missed_mode() {
        let (k, m) = grid(10, 9, 8); // 720 dofs: the sparse block iteration
        let spec = EigenSpec {
            count: 12,
            shift: Some(0.0),
            ..Default::default()
        };
        let s = lowest_modes(&k, &m, &spec).unwrap();
        let ev = dense_eigenvalues(&k, &m);
        for (a, b) in s.eigenvalues.iter().zip(&ev) {
            assert!((a - b).abs() <= 1e-8 * b, "{a} vs dense {b}");
        }
        // the band up to between λ12 and λ13 holds exactly the 12 found modes: proven complete
        let hi = 0.5 * (ev[11] + ev[12]);
        assert_eq!(
            check_band(&k, &m, &s.eigenvalues, 0.0, hi, None, Par::Seq).unwrap(),
            Ok(12)
        );
        // a sub-band [lo, hi) with a lower shift too
        let lo = 0.5 * (ev[3] + ev[4]);
        assert_eq!(
            check_band(&k, &m, &s.eigenvalues, lo, hi, None, Par::Seq).unwrap(),
            Ok(8)
        );
        // a single shift that returned the modes nearest it but skipped one inside the band
        // (here the 7th): the inertia count catches it
        let mut skipped = s.eigenvalues.clone();
        skipped.remove(6);
        assert_eq!(
            check_band(&k, &m, &skipped, 0.0, hi, None, Par::Seq).unwrap(),
            Err(1)
        );
        // a band reaching past the last found mode: the modes above it are missing
        let hi2 = 0.5 * (ev[14] + ev[15]);
        assert_eq!(
            check_band(&k, &m, &s.eigenvalues, 0.0, hi2, None, Par::Seq).unwrap(),
            Err(3)
        );
    }
}
