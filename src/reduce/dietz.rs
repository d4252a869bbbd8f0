//! Dietz frequency-response modes (MotionView flexbody theory): free-free modes Xn plus
//! Xf from (K − ℓM) Xf = Fa (static procedure) or Xf = Xe (De − ℓI)⁻¹ Xeᵀ Fa from an extended
//! free-free set (modified procedure); X = [Xn Xf] orthonormalized, dependent vectors removed.
//!
//! ℓ defaults to [`DEFAULT_SHIFT_FRACTION`]·λ₁ (λ₁ = first flexible free-free eigenvalue), i.e. the
//! documented "half of the first nonzero frequency": ℓ = (ω₁/2)².
//!
//! K − ℓM is indefinite for a free body (ℓ > 0 = rigid eigenvalues), so the static procedure
//! splits Fa: the rigid part gives −Xr XrᵀFa/ℓ exactly, and the elastic part y (Xrᵀ M y = 0)
//! solves K y = Fe + ℓ M y by the inertia-relief fixed point y ← G(Fe + ℓMy), which contracts
//! with rate ℓ/λ₁ (1/4 by default).

use super::craig_chang::{free_free, load_dof, stacked_basis};
use super::select::ModeCount;
use super::{Method, ModeLabel, ModeSet, ReduceError};
use crate::solve::inertia_relief::InertiaRelief;
use crate::solve::{sparse_ops, EigenSpec, SparseColMat};
use faer::Mat;

/// ℓ = DEFAULT_SHIFT_FRACTION · λ₁ (= (ω₁/2)², half the first flexible frequency).
pub const DEFAULT_SHIFT_FRACTION: f64 = 0.25;

/// Largest ℓ/λ₁ accepted: nearer to the first flexible eigenvalue, K − ℓM is nearly singular, the
/// frequency-response vectors collapse onto the first mode (and are removed as dependent) and the
/// static procedure's fixed point (rate ℓ/λ₁) needs ≥ 300 steps.
pub const MAX_SHIFT_FRACTION: f64 = 0.9;

/// Checks ℓ against the first flexible eigenvalue λ₁ (and λ₁ against nothing above it).
fn check_shift(ell: f64, l1: f64) -> Result<(), ReduceError> {
    if !(ell > 0.0 && ell.is_finite()) {
        return Err(ReduceError::Dofs {
            what: "Dietz shift",
            detail: format!("l = {ell:e} must be positive (default: {DEFAULT_SHIFT_FRACTION} x the first flexible eigenvalue {l1:e})"),
        });
    }
    if ell >= MAX_SHIFT_FRACTION * l1 {
        return Err(ReduceError::Dofs {
            what: "Dietz shift",
            detail: format!(
                "l = {ell:e} is {:.4} x the first flexible eigenvalue {l1:e}: K - l M is (nearly) \
                 singular there; choose l below {MAX_SHIFT_FRACTION} x lambda1 (default \
                 {DEFAULT_SHIFT_FRACTION} x lambda1, half the first frequency)",
                ell / l1
            ),
        });
    }
    Ok(())
}

/// Relative convergence of the static procedure's fixed point.
const FIXED_POINT_TOL: f64 = 1e-13;

/// A fixed point whose step stops shrinking below this relative size has reached the rounding
/// of its solves and is accepted (the build's verification checks the set against the model).
const FIXED_POINT_STALL: f64 = 1e-9;

fn finish_with_top(
    o: super::Orthonormalized,
    method: Method,
    note: String,
    (top, basis_normal): (Option<f64>, usize),
    eigenproblem: super::EigenRecord,
) -> ModeSet {
    let mut diagnostics = o.diagnostics;
    diagnostics.eigenproblem = Some(eigenproblem);
    diagnostics.notes.push(note);
    diagnostics.basis_top_omega2 = top;
    diagnostics.basis_normal_modes = Some(basis_normal);
    ModeSet {
        phi: o.phi,
        omega2: o.omega2,
        labels: o.labels,
        method,
        reference_dofs: vec![],
        selection: None,
        diagnostics,
    }
}

/// Dietz, static procedure: (K − ℓM) Xf = Fa. `shift` = ℓ (`None`: the default fraction).
pub fn dietz(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    fa: &Mat<f64>,
    modes: ModeCount,
    shift: Option<f64>,
    eig: &EigenSpec,
) -> Result<ModeSet, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let n = k.nrows();
    if fa.nrows() != n {
        return Err(ReduceError::Dofs {
            what: "attachment loads",
            detail: format!("{} rows for n = {n}", fa.nrows()),
        });
    }
    let (xn, nr) = free_free(k, m, modes, eig)?;
    let l1 = xn.eigenvalues[nr];
    let ell = shift.unwrap_or(DEFAULT_SHIFT_FRACTION * l1);
    check_shift(ell, l1)?;
    let xr = xn.vectors.as_ref().subcols(0, nr).to_owned();
    let ir = InertiaRelief::new(k, m, xr.clone(), eig)?;
    let fe = ir.equilibrate(fa);
    let mut y = ir.solve_equilibrated(&fe);
    let mut iters = 0;
    let mut last_d = f64::INFINITY;
    loop {
        let my = sparse_ops::spmm(m.as_ref(), y.as_ref());
        let rhs = &fe + &my * faer::Scale(ell);
        let y2 = ir.solve_equilibrated(&rhs);
        let d = (&y2 - &y).norm_max();
        let s = y2.norm_max();
        y = y2;
        iters += 1;
        // converged, or stalled at the rounding of the solves (the step no longer shrinks by
        // the contraction rate ℓ/λ₁ ≤ 0.9, MAX_SHIFT_FRACTION; measured on a free 1000-element
        // lumped CBAR line: the steps stop falling at ~1e-12 of the solution)
        if d <= FIXED_POINT_TOL * s || (d <= FIXED_POINT_STALL * s && d >= 0.95 * last_d) {
            break;
        }
        last_d = d;
        if iters > 2000 {
            return Err(ReduceError::Dofs {
                what: "Dietz shift",
                detail: format!("fixed point did not converge for l = {ell:e}"),
            });
        }
    }
    // rigid part: Xr (0 − ℓ)⁻¹ Xrᵀ Fa
    let xf = if nr > 0 {
        &y - &xr * (xr.transpose() * fa) * faer::Scale(1.0 / ell)
    } else {
        y
    };
    let o = stacked_basis(k, m, &xn.vectors, nr, &xf, fa, |dof| {
        ModeLabel::FrequencyResponse { dof }
    })?;
    let note = format!(
        "Dietz static procedure: l = {ell:e} ({iters} fixed-point steps), support {:?}",
        ir.support
    );
    let attachment = (0..fa.ncols()).map(|j| load_dof(fa, j)).collect();
    let top = xn.eigenvalues.last().copied();
    let basis_normal = xn.eigenvalues.len() - nr;
    let record = super::EigenRecord::of(super::EigenProblem::FreeFree, k, m, &xn);
    Ok(finish_with_top(
        o,
        Method::Dietz {
            attachment,
            shift: ell,
        },
        note,
        (top, basis_normal),
        record,
    ))
}

/// Dietz, modified procedure: Xf = Xe (De − ℓI)⁻¹ Xeᵀ Fa with the extended free-free set
/// (`extended` modes, a superset of the `modes` kept in Xn).
pub fn dietz_modified(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    fa: &Mat<f64>,
    modes: usize,
    extended: usize,
    shift: Option<f64>,
    eig: &EigenSpec,
) -> Result<ModeSet, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let n = k.nrows();
    if fa.nrows() != n || extended < modes {
        return Err(ReduceError::Dofs {
            what: "Dietz modified",
            detail: format!("extended {extended} < modes {modes} or Fa rows != {n}"),
        });
    }
    let (xe, nr) = free_free(k, m, ModeCount::Count(extended), eig)?;
    let l1 = xe.eigenvalues[nr];
    let ell = shift.unwrap_or(DEFAULT_SHIFT_FRACTION * l1);
    check_shift(ell, l1)?;
    let c = xe.vectors.transpose() * fa;
    let scaled = Mat::from_fn(c.nrows(), c.ncols(), |i, j| {
        c[(i, j)] / (xe.eigenvalues[i] - ell)
    });
    let xf = &xe.vectors * &scaled;
    let xn = xe
        .vectors
        .as_ref()
        .subcols(0, modes.min(xe.eigenvalues.len()))
        .to_owned();
    let o = stacked_basis(k, m, &xn, nr, &xf, fa, |dof| ModeLabel::FrequencyResponse {
        dof,
    })?;
    let note = format!("Dietz modified procedure: l = {ell:e}, extended set of {extended} modes");
    let attachment = (0..fa.ncols()).map(|j| load_dof(fa, j)).collect();
    let top = xe.eigenvalues[..modes.min(xe.eigenvalues.len())]
        .last()
        .copied();
    let basis_normal = modes.min(xe.eigenvalues.len()).saturating_sub(nr);
    // every extended mode reaches the basis (through Xf)
    let record = super::EigenRecord::of(super::EigenProblem::FreeFree, k, m, &xe);
    Ok(finish_with_top(
        o,
        Method::DietzModified {
            attachment,
            shift: ell,
            extended,
        },
        note,
        (top, basis_normal),
        record,
    ))
}
