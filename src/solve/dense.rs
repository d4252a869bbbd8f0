//! Dense symmetric generalized eigenproblems K x = λ M x (small models, reduced matrices).
//!
//! With K − σM = LLᵀ positive definite, S = L⁻¹ M L⁻ᵀ has eigenpairs (μ, u) with λ = σ + 1/μ and
//! x = L⁻ᵀu/√μ, so a semi-definite M (massless dofs, infinite eigenvalues at μ = 0) is allowed.

use super::SolveError;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, MatRef, Par, Side};

/// Symmetric part (A + Aᵀ)/2.
pub fn sym(a: MatRef<'_, f64>) -> Mat<f64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}

/// Eigen-decomposition of a symmetric matrix: ascending eigenvalues and orthonormal vectors.
///
/// The matrix is scaled to max |a_ij| = 1 first: faer 0.24's `self_adjoint_eigen` was measured
/// here to lose accuracy on unscaled stiffness-sized matrices (‖AU − UΛ‖/‖A‖ = 1e-4 at
/// ‖A‖ = 3.5e10 on the hex8 block, 3e-15 after scaling).
pub fn eigh(a: MatRef<'_, f64>) -> Result<(Vec<f64>, Mat<f64>), SolveError> {
    let mut s = sym(a);
    let amax = s.norm_max();
    if !amax.is_finite() {
        return Err(SolveError::NonFinite("dense eigenproblem"));
    }
    let scale = if amax > 0.0 { 1.0 / amax } else { 1.0 };
    s *= faer::Scale(scale);
    let evd = s
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| SolveError::DenseEigen(format!("{e:?}")))?;
    let vals: Vec<f64> = (0..s.nrows()).map(|i| evd.S()[i] / scale).collect();
    if vals.iter().any(|v| !v.is_finite()) {
        return Err(SolveError::NonFinite("dense eigenvalues"));
    }
    Ok((vals, evd.U().to_owned()))
}

/// Lower Cholesky factor of a symmetric matrix, `None` if it is not numerically positive definite.
pub fn cholesky(a: MatRef<'_, f64>) -> Option<Mat<f64>> {
    let s = sym(a);
    s.llt(Side::Lower).ok().map(|l| l.L().to_owned())
}

/// The `count` lowest eigenpairs of the dense pencil (K, M), M positive semi-definite:
/// ascending λ and vectors with XᵀMX = I. `shift` = σ with K − σM positive definite
/// (`None`: 0 if K is positive definite, else a negative shift scaled to tr K / tr M).
pub fn lowest(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    count: usize,
    shift: Option<f64>,
) -> Result<(Vec<f64>, Mat<f64>), SolveError> {
    let n = k.nrows();
    if count > n {
        return Err(SolveError::TooManyModes {
            requested: count,
            available: n,
        });
    }
    let sigmas: Vec<f64> = match shift {
        Some(s) => vec![s],
        None => super::automatic_shifts(super::trace_ratio_dense(k, m)),
    };
    let mut last_err = SolveError::NonPositivePivot { dof: 0 };
    for sigma in sigmas {
        let a = Mat::from_fn(n, n, |i, j| k[(i, j)] - sigma * m[(i, j)]);
        let Some(l) = cholesky(a.as_ref()) else {
            last_err = SolveError::NotPositiveDefinite { shift: sigma };
            continue;
        };
        // S = L⁻¹ M L⁻ᵀ
        let mut s = sym(m);
        solve_lower_triangular_in_place(l.as_ref(), s.as_mut(), Par::Seq);
        let mut st = s.transpose().to_owned();
        solve_lower_triangular_in_place(l.as_ref(), st.as_mut(), Par::Seq);
        let (mu, u) = eigh(st.as_ref())?;
        // largest μ first; μ ≤ tiny are the infinite eigenvalues of massless directions
        let mu_max = mu.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        let finite: Vec<usize> = (0..n).rev().filter(|&i| mu[i] > 1e-13 * mu_max).collect();
        if count > finite.len() {
            return Err(SolveError::TooManyModes {
                requested: count,
                available: finite.len(),
            });
        }
        let mut x = Mat::<f64>::zeros(n, count);
        for (c, &i) in finite.iter().take(count).enumerate() {
            for r in 0..n {
                x[(r, c)] = u[(r, i)];
            }
        }
        // x = L⁻ᵀ u
        solve_upper_triangular_in_place(l.transpose(), x.as_mut(), Par::Seq);
        return rayleigh_ritz(k, m, x.as_ref());
    }
    Err(last_err)
}

/// Rayleigh–Ritz cleanup of a basis X (n×p, full M-rank): returns ascending λ and X' = X·Y with
/// X'ᵀMX' = I and X'ᵀKX' = diag(λ) to rounding (the projected problem solved by Cholesky of XᵀMX).
pub fn rayleigh_ritz(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    x: MatRef<'_, f64>,
) -> Result<(Vec<f64>, Mat<f64>), SolveError> {
    let kx = k * x;
    let mx = m * x;
    let kp = x.transpose() * &kx;
    let mp = x.transpose() * &mx;
    let (vals, y) = projected(kp.as_ref(), mp.as_ref())?;
    Ok((vals, x * &y))
}

/// Eigenpairs of the small projected pencil (Kp, Mp) with Mp positive definite: ascending λ and
/// Y with YᵀMpY = I (by Mp = LLᵀ, eig of L⁻¹KpL⁻ᵀ).
pub fn projected(
    kp: MatRef<'_, f64>,
    mp: MatRef<'_, f64>,
) -> Result<(Vec<f64>, Mat<f64>), SolveError> {
    let l = cholesky(mp).ok_or(SolveError::DependentBasis)?;
    let mut s = sym(kp);
    solve_lower_triangular_in_place(l.as_ref(), s.as_mut(), Par::Seq);
    let mut st = s.transpose().to_owned();
    solve_lower_triangular_in_place(l.as_ref(), st.as_mut(), Par::Seq);
    let (vals, mut u) = eigh(st.as_ref())?;
    solve_upper_triangular_in_place(l.transpose(), u.as_mut(), Par::Seq);
    Ok((vals, u))
}

/// `r` dofs at which the rigid modes Xr (n × r) are independent (greedy pivoted QR on the rows of
/// Xr): holding them at zero is a statically determinate support; `None` when the modes are
/// not independent at any dof set ([`super::SolveError::NoDeterminateSupport`]).
pub fn determinate_support(xr: &Mat<f64>) -> Option<Vec<usize>> {
    let (n, r) = (xr.nrows(), xr.ncols());
    let mut res = xr.clone();
    let mut support = Vec::with_capacity(r);
    let norm0 = (0..n)
        .map(|i| (0..r).map(|j| xr[(i, j)].powi(2)).sum::<f64>())
        .fold(0.0, f64::max);
    for _ in 0..r {
        let (mut best, mut bv) = (usize::MAX, 0.0);
        for i in 0..n {
            let v: f64 = (0..r).map(|j| res[(i, j)].powi(2)).sum();
            if v > bv {
                best = i;
                bv = v;
            }
        }
        if best == usize::MAX || bv <= 1e-12 * norm0 {
            return None;
        }
        support.push(best);
        let q: Vec<f64> = (0..r).map(|j| res[(best, j)] / bv.sqrt()).collect();
        for i in 0..n {
            let d: f64 = (0..r).map(|j| res[(i, j)] * q[j]).sum();
            for j in 0..r {
                res[(i, j)] -= d * q[j];
            }
        }
    }
    support.sort_unstable();
    Some(support)
}
