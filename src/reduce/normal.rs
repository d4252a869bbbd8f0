//! Normal modes of the full model: free-free, or with dofs held at zero (constraints or the
//! reference conditions of Wang, Niu & Feng 2023, which then define the body frame).

use super::orthonormalize::{diagnose, rigid_flags};
use super::select::{solve_count, ModeCount};
use super::{check_dofs, Method, ModeLabel, ModeSet, ReduceError};
use crate::solve::sparse_ops::complement;
use crate::solve::{sparse_ops, trace_ratio, EigenSpec, SparseColMat};
use faer::Mat;

/// Lowest normal modes of K φ = ω² M φ with the dofs `fixed` held at zero; Φ is expanded to all
/// dofs (zero rows at `fixed`).
pub fn normal_modes(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    count: ModeCount,
    fixed: &[usize],
    eig: &EigenSpec,
) -> Result<ModeSet, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let n = k.nrows();
    check_dofs("fixed dofs", fixed, n)?;
    let free = complement(fixed, n);
    let (kf, mf);
    let (kr, mr) = if fixed.is_empty() {
        (k, m)
    } else {
        kf = sparse_ops::submatrix(k.as_ref(), &free, &free)?;
        mf = sparse_ops::submatrix(m.as_ref(), &free, &free)?;
        (&kf, &mf)
    };
    super::select::check_count(count, free.len(), "the model's free dofs")?;
    let s = solve_count(kr, mr, count, eig)?;
    let mut phi = Mat::<f64>::zeros(n, s.eigenvalues.len());
    for j in 0..phi.ncols() {
        for (r, &i) in free.iter().enumerate() {
            phi[(i, j)] = s.vectors[(r, j)];
        }
    }
    let scale = trace_ratio(k, m);
    let labels: Vec<ModeLabel> = rigid_flags(kr, &s.vectors, &s.eigenvalues, scale)
        .into_iter()
        .map(|r| {
            if r {
                ModeLabel::Rigid
            } else {
                ModeLabel::Normal
            }
        })
        .collect();
    let nr = labels_zero(&labels);
    if fixed.is_empty() && nr > super::FREE_BODY_RIGID_MODES {
        return Err(ReduceError::Mechanism {
            zero_modes: nr,
            at_least: nr == labels.len(),
        });
    }
    if let ModeCount::BelowHz(cut) = count {
        if nr == labels.len() {
            let next = solve_count(kr, mr, ModeCount::Count((nr + 1).min(free.len())), eig)?;
            let first = next.eigenvalues.last().copied().unwrap_or(0.0);
            return Err(super::select::cutoff_below_first(
                cut,
                crate::solve::hz(first),
            ));
        }
    }
    // checked on the free-dof problem: rows of held dofs carry the reactions, not an error
    let mut diagnostics = diagnose(kr, mr, &s.vectors, &s.eigenvalues)?;
    diagnostics
        .notes
        .extend(super::band_note(&s.info, "normal"));
    diagnostics.eigenproblem = Some(super::EigenRecord::of(
        super::EigenProblem::NormalModes,
        kr,
        mr,
        &s,
    ));
    let set = ModeSet {
        phi,
        omega2: s.eigenvalues,
        labels,
        method: Method::NormalModes,
        reference_dofs: fixed.to_vec(),
        selection: None,
        diagnostics,
    };
    super::check_held(&set)?;
    Ok(set)
}

fn labels_zero(labels: &[ModeLabel]) -> usize {
    labels.iter().filter(|l| **l == ModeLabel::Rigid).count()
}
