//! Reference conditions (Wang, Niu & Feng 2023 §5): the improved Craig–Bampton methods that turn
//! the free-free CB set into one with the body frame defined by dofs held at zero.
//!
//! * Method 1 (§5.1, eqs. 32–37): remove from Φ_CB the identity-block columns of the reference
//!   dofs (their constraint modes), then solve the second eigenproblem on the rest.
//! * Method 2 (§5.2, eqs. 38–43): impose the reference conditions on K and M (remove the reference
//!   dofs), then form Craig–Bampton with the remaining interface dofs and orthonormalize.
//!
//! Both span the same space (the constraint modes of the remaining interface dofs and the same
//! fixed-interface modes), so their frequencies agree to rounding. Normal modes with reference
//! conditions are [`super::normal::normal_modes`] with `fixed` = the reference dofs.

use super::craig_bampton::{craig_bampton, craig_bampton_basis};
use super::orthonormalize::orthonormalize_held;
use super::select::ModeCount;
use super::{check_dofs, Method, ModeLabel, ModeSet, ReduceError};
use crate::solve::sparse_ops::complement;
use crate::solve::{sparse_ops, EigenSpec, SparseColMat};
use faer::Mat;

fn check_subset(reference: &[usize], interface: &[usize], n: usize) -> Result<(), ReduceError> {
    check_dofs("reference dofs", reference, n)?;
    if let Some(d) = reference.iter().find(|d| !interface.contains(d)) {
        return Err(ReduceError::Dofs {
            what: "reference dofs",
            detail: format!(
                "dof {d} is not an interface dof (reference conditions act on the identity block)"
            ),
        });
    }
    Ok(())
}

/// Improved CB, method 1: Φ_CBrc = Φ_CB without the reference dofs' constraint-mode columns.
pub fn improved_cb_method1(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    interface: &[usize],
    reference: &[usize],
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<ModeSet, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let n = k.nrows();
    check_dofs("interface dofs", interface, n)?;
    check_subset(reference, interface, n)?;
    let basis = craig_bampton_basis(k, m, interface, modes, eig)?;
    let keep: Vec<usize> = (0..basis.t.ncols())
        .filter(|&c| !matches!(basis.labels[c], ModeLabel::Constraint { dof } if reference.contains(&dof)))
        .collect();
    let t = Mat::from_fn(n, keep.len(), |i, j| basis.t[(i, keep[j])]);
    let labels: Vec<ModeLabel> = keep.iter().map(|&c| basis.labels[c].clone()).collect();
    let mut o = orthonormalize_held(k, m, &t, &labels, reference)?;
    o.diagnostics.basis_top_omega2 = basis.fixed_omega2.last().copied();
    o.diagnostics.eigenproblem = basis.record.clone();
    let set = ModeSet {
        phi: o.phi,
        omega2: o.omega2,
        labels: o.labels,
        method: Method::ImprovedCraigBampton1 {
            interface: interface.to_vec(),
            fixed_interface_modes: basis.fixed_omega2.len(),
        },
        reference_dofs: reference.to_vec(),
        selection: None,
        diagnostics: o.diagnostics,
    };
    super::check_held(&set)?;
    Ok(set)
}

/// Improved CB, method 2: reference dofs removed from K and M (B_frᵀ K B_fr), then CB.
pub fn improved_cb_method2(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    interface: &[usize],
    reference: &[usize],
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<ModeSet, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let n = k.nrows();
    check_dofs("interface dofs", interface, n)?;
    check_subset(reference, interface, n)?;
    let free = complement(reference, n);
    let mut pos = vec![usize::MAX; n];
    for (r, &i) in free.iter().enumerate() {
        pos[i] = r;
    }
    let kr = sparse_ops::submatrix(k.as_ref(), &free, &free)?;
    let mr = sparse_ops::submatrix(m.as_ref(), &free, &free)?;
    let iface: Vec<usize> = interface
        .iter()
        .filter(|d| !reference.contains(d))
        .map(|&d| pos[d])
        .collect();
    let set = craig_bampton(&kr, &mr, &iface, modes, eig)?;
    let mut phi = Mat::<f64>::zeros(n, set.len());
    for j in 0..set.len() {
        for (r, &i) in free.iter().enumerate() {
            phi[(i, j)] = set.phi[(r, j)];
        }
    }
    let labels = set
        .labels
        .into_iter()
        .map(|l| match l {
            ModeLabel::Constraint { dof } => ModeLabel::Constraint { dof: free[dof] },
            other => other,
        })
        .collect();
    let nq = match set.method {
        Method::CraigBampton {
            fixed_interface_modes,
            ..
        } => fixed_interface_modes,
        _ => 0,
    };
    let mut diagnostics = super::orthonormalize::diagnose(k, m, &phi, &set.omega2)?;
    diagnostics.removed = set.diagnostics.removed;
    diagnostics.dependency_tol = set.diagnostics.dependency_tol;
    diagnostics.notes = set.diagnostics.notes;
    diagnostics.basis_top_omega2 = set.diagnostics.basis_top_omega2;
    diagnostics.label_shares = set.diagnostics.label_shares;
    diagnostics.origin = set.diagnostics.origin;
    diagnostics.eigenproblem = set.diagnostics.eigenproblem;
    let out = ModeSet {
        phi,
        omega2: set.omega2,
        labels,
        method: Method::ImprovedCraigBampton2 {
            interface: interface.to_vec(),
            fixed_interface_modes: nq,
        },
        reference_dofs: reference.to_vec(),
        selection: None,
        diagnostics,
    };
    super::check_held(&out)?;
    Ok(out)
}
