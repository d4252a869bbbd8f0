//! The preload's linear static solve on the constrained system K_r u_r = f_r (f_r = Tᵀ f):
//! directly for a body its constraints hold, with inertia relief for a free (or partly free)
//! one — K_r u_r = P f_r, P = I − M_r X_r X_rᵀ, on a statically determinate support, purified
//! of rigid motion (the solver of the Craig–Chang attachment modes and the residual vectors,
//! `reduce::craig_chang`).
//!
//! The rigid-body motions the constraints leave free are found from geometry, not from an
//! eigensolve: the six rigid motions of the nodes (translations t + θ × (x − x̄) and rotations
//! θ, in the displacement frames) on the independent dofs, X (n_r × 6), M_r-orthonormalized
//! and rotated to the eigenvectors of XᵀK_rX; those with Rayleigh quotient below
//! [`RIGID_TOL`] × (the model's stiffness-over-mass scale) are free.

use faer::Mat;

use super::PreloadError;
use crate::fe::constraints::Reduced;
use crate::fe::dofs::DofMap;
use crate::model::Model;
use crate::reduce::craig_chang::{determinate_support, InertiaRelief};
use crate::reduce::{complement, ReduceError};
use crate::solve::{trace_ratio, EigenSpec, SolveError};

/// A geometric rigid motion with ω² below this fraction of the model's K/M scale (the median
/// K_ii/M_ii, `solve::trace_ratio`) is free. A free motion's ω² is rounding (≈ 1e-13 of the
/// scale); a motion through a held dof costs about the local stiffness over the body's mass,
/// ≥ 1/(number of nodes) of the scale.
pub const RIGID_TOL: f64 = 1e-9;

/// The six rigid motions of the nodes on the physical dofs (displacement frames), rotations
/// about the nodes' centroid.
fn geometric_rigid_motions(model: &Model, dofs: &DofMap) -> Mat<f64> {
    let live: Vec<usize> = (0..model.nodes.len())
        .filter(|&p| dofs.count[p] > 0)
        .collect();
    let mut c = [0.0; 3];
    for &p in &live {
        for k in 0..3 {
            c[k] += model.nodes[p].x[k] / live.len() as f64;
        }
    }
    let mut x = Mat::<f64>::zeros(dofs.n_dofs, 6);
    for &p in &live {
        let r: [f64; 3] = std::array::from_fn(|k| model.nodes[p].x[k] - c[k]);
        for mode in 0..6 {
            let (mut t, mut th) = ([0.0; 3], [0.0; 3]);
            if mode < 3 {
                t[mode] = 1.0;
            } else {
                th[mode - 3] = 1.0;
                t = crate::fe::elements::beam::cross(th, r);
            }
            for (off, v) in [(0, t), (3, th)] {
                if off < usize::from(dofs.count[p]) {
                    let l = super::inertia::to_node_frame(dofs, p, v);
                    for k in 0..3 {
                        x[(dofs.first[p] + off + k, mode)] = l[k];
                    }
                }
            }
        }
    }
    x
}

/// The rigid-body modes the constraints of `red` leave free (module doc): M_r-orthonormal
/// columns on the independent dofs.
pub fn free_rigid_modes(
    model: &Model,
    dofs: &DofMap,
    red: &Reduced,
) -> Result<Mat<f64>, PreloadError> {
    let x_phys = geometric_rigid_motions(model, dofs);
    let nr = red.retained.len();
    let x = Mat::from_fn(nr, 6, |i, j| x_phys[(red.retained[i], j)]);
    let kx = crate::solve::sparse_ops::spmm(red.k.as_ref(), x.as_ref());
    let mx = crate::solve::sparse_ops::spmm(red.m.as_ref(), x.as_ref());
    let g = x.transpose() * &mx;
    let r = x.transpose() * &kx;
    // a motion without mass (e.g. every rotation of a model of point masses on a line) cannot be
    // balanced by its inertia: keep the motions with mass, by the eigenvectors of G
    let ge = g
        .self_adjoint_eigen(faer::Side::Lower)
        .map_err(|e| SolveError::DenseEigen(format!("rigid-mode mass: {e:?}")))?;
    let gmax = (0..6).map(|i| ge.S()[i]).fold(0.0f64, f64::max);
    let keep: Vec<usize> = (0..6).filter(|&i| ge.S()[i] > 1e-12 * gmax).collect();
    // G^{-1/2} on the massive directions
    let w = Mat::from_fn(6, keep.len(), |i, j| {
        ge.U()[(i, keep[j])] / ge.S()[keep[j]].sqrt()
    });
    let a = w.transpose() * &r * &w;
    let a = Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    let ae = a
        .self_adjoint_eigen(faer::Side::Lower)
        .map_err(|e| SolveError::DenseEigen(format!("rigid-mode stiffness: {e:?}")))?;
    let scale = trace_ratio(&red.k, &red.m);
    let free: Vec<usize> = (0..a.nrows())
        .filter(|&i| ae.S()[i] <= RIGID_TOL * scale)
        .collect();
    let coeff = &w * ae.U();
    let c = Mat::from_fn(6, free.len(), |i, j| coeff[(i, free[j])]);
    Ok(&x * &c)
}

/// Static displacements on the independent dofs (n_r × L) for the loads `f_r` (n_r × L), held
/// or with inertia relief against the rigid modes `xr` (module doc), and the support dofs.
pub fn solve(
    model: &Model,
    dofs: &DofMap,
    red: &Reduced,
    xr: Mat<f64>,
    f_r: &Mat<f64>,
    eig: &EigenSpec,
) -> Result<(Mat<f64>, Vec<usize>), PreloadError> {
    let n = red.k.nrows();
    // the support the inertia relief will choose, to name a singular pivot's dof
    let support = if xr.ncols() > 0 {
        determinate_support(&xr)?
    } else {
        Vec::new()
    };
    let free = complement(&support, n);
    let ir = InertiaRelief::new(&red.k, &red.m, xr, eig).map_err(|e| match e {
        ReduceError::Solve(SolveError::NonPositivePivot { dof }) => {
            let (node, comp) = free
                .get(dof)
                .and_then(|&r| dofs.node_of(red.retained[r]))
                .map_or((0, 0), |(p, c)| (model.nodes[p].id, c + 1));
            PreloadError::Singular {
                source_file: model.source.clone(),
                node,
                dof: comp,
            }
        }
        other => PreloadError::Reduce(other),
    })?;
    let u = ir.solve_equilibrated(&ir.equilibrate(f_r));
    Ok((u, support))
}
