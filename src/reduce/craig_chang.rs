//! Craig–Chang reduction (MotionView flexbody theory, "Craig-Chang modes"): free-free modes
//! Xn = [Xr X1 … Xk] plus inertia-relief attachment modes Xa from K Xa = P Fa, P = I − M Xr Xrᵀ,
//! solved on an automatically chosen statically determinate support, purified of rigid content
//! (Xa ← Xa − Xr XrᵀM Xa), then orthonormalized with dependent vectors removed and reported.
//!
//! K̂ is formed as XᵀKX, which equals the documented [Dn, XnᵀFe; FeᵀXn, XaᵀFe] because the
//! support reactions of an equilibrated load vanish.

use super::orthonormalize::{orthonormalize, rigid_flags};
use super::select::{solve_count, ModeCount};
use super::{Method, ModeLabel, ModeSet, ReduceError};
use crate::solve::inertia_relief::InertiaRelief;
use crate::solve::{trace_ratio, EigenSolution, EigenSpec, SparseColMat};
use faer::Mat;

/// Unit loads: column j has 1 at `dofs[j]` (duplicates allowed: they give dependent vectors).
pub fn unit_loads(n: usize, dofs: &[usize]) -> Result<Mat<f64>, ReduceError> {
    if let Some(&d) = dofs.iter().find(|&&d| d >= n) {
        return Err(ReduceError::Dofs {
            what: "attachment dofs",
            detail: format!("dof {d} out of range (n = {n})"),
        });
    }
    Ok(Mat::from_fn(n, dofs.len(), |i, j| {
        if dofs[j] == i {
            1.0
        } else {
            0.0
        }
    }))
}

/// Label dof of a load column: its largest entry.
pub(crate) fn load_dof(f: &Mat<f64>, j: usize) -> usize {
    (0..f.nrows()).fold(0, |b, i| {
        if f[(i, j)].abs() > f[(b, j)].abs() {
            i
        } else {
            b
        }
    })
}

/// Free-free modes and the number of rigid ones (leading, by [`rigid_flags`]).
pub(crate) fn free_free(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<(EigenSolution, usize), ReduceError> {
    super::select::check_count(modes, k.nrows(), "the model")?;
    let s = solve_count(k, m, modes, eig)?;
    let scale = trace_ratio(k, m);
    let nr = rigid_flags(k, &s.vectors, &s.eigenvalues, scale)
        .into_iter()
        .take_while(|&r| r)
        .count();
    if nr > super::FREE_BODY_RIGID_MODES {
        return Err(ReduceError::Mechanism {
            zero_modes: nr,
            at_least: nr == s.eigenvalues.len(),
        });
    }
    if let (ModeCount::BelowHz(cut), true) = (modes, nr == s.eigenvalues.len()) {
        let next = solve_count(k, m, ModeCount::Count((nr + 1).min(k.nrows())), eig)?;
        let first = next.eigenvalues.last().copied().unwrap_or(0.0);
        return Err(super::select::cutoff_below_first(
            cut,
            crate::solve::hz(first),
        ));
    }
    if nr == s.eigenvalues.len() {
        return Err(ReduceError::Rigid(format!(
            "all {nr} computed free-free modes are rigid; ask for more modes"
        )));
    }
    Ok((s, nr))
}

/// X = [Xn Xl] (free-free modes, the first `nr` rigid, then one load response per column of
/// `fa`) labelled and orthonormalized by K̂N = M̂NΛ with dependent vectors removed — the last
/// step shared by Craig–Chang and Dietz.
pub(crate) fn stacked_basis(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    xn: &Mat<f64>,
    nr: usize,
    xl: &Mat<f64>,
    fa: &Mat<f64>,
    load_label: fn(usize) -> ModeLabel,
) -> Result<super::Orthonormalized, ReduceError> {
    let (n, nn, na) = (xn.nrows(), xn.ncols(), xl.ncols());
    let mut x = Mat::<f64>::zeros(n, nn + na);
    x.as_mut().subcols_mut(0, nn).copy_from(xn.as_ref());
    x.as_mut().subcols_mut(nn, na).copy_from(xl.as_ref());
    let mut labels: Vec<ModeLabel> = (0..nn)
        .map(|j| {
            if j < nr {
                ModeLabel::Rigid
            } else {
                ModeLabel::Normal
            }
        })
        .collect();
    labels.extend((0..na).map(|j| load_label(load_dof(fa, j))));
    orthonormalize(k, m, &x, &labels)
}

/// Craig–Chang mode set from free-free modes (`modes`, rigid ones included) and attachment loads
/// `fa` (n × na, e.g. [`unit_loads`] of the interface dofs).
pub fn craig_chang(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    fa: &Mat<f64>,
    modes: ModeCount,
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
    let xr = xn.vectors.as_ref().subcols(0, nr).to_owned();
    let ir = InertiaRelief::new(k, m, xr, eig)?;
    let fe = ir.equilibrate(fa);
    let xa = ir.solve_equilibrated(&fe);
    let o = stacked_basis(k, m, &xn.vectors, nr, &xa, fa, |dof| {
        ModeLabel::Attachment { dof }
    })?;
    let mut diagnostics = o.diagnostics;
    diagnostics.basis_top_omega2 = xn.eigenvalues.last().copied();
    diagnostics.basis_normal_modes = Some(xn.eigenvalues.len() - nr);
    diagnostics
        .notes
        .extend(super::band_note(&xn.info, "free-free"));
    diagnostics.eigenproblem = Some(super::EigenRecord::of(
        super::EigenProblem::FreeFree,
        k,
        m,
        &xn,
    ));
    diagnostics.notes.push(format!(
        "statically determinate support (automatic): dofs {:?}",
        ir.support
    ));
    if !diagnostics.removed.is_empty() {
        diagnostics.notes.push(format!(
            "{} dependent vector(s) removed (remaining M-norm² below {:e} of their own)",
            diagnostics.removed.len(),
            diagnostics.dependency_tol
        ));
    }
    let attachment = (0..fa.ncols()).map(|j| load_dof(fa, j)).collect();
    Ok(ModeSet {
        phi: o.phi,
        omega2: o.omega2,
        labels: o.labels,
        method: Method::CraigChang {
            attachment,
            support: ir.support.clone(),
        },
        reference_dofs: vec![],
        selection: None,
        diagnostics,
    })
}
