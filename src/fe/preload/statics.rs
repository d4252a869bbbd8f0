//! The preload's linear static solve on the constrained system K_r u_r = f_r (f_r = Tᵀ f):
//! directly for a body its constraints hold, with inertia relief for a free (or partly free)
//! one — K_r u_r = P f_r, P = I − M_r X_r X_rᵀ, on a statically determinate support, purified
//! of rigid motion (`solve::inertia_relief`, the solver of the Craig–Chang attachment modes and
//! the residual vectors).
//!
//! The rigid-body motions the constraints leave free are found from geometry, not from an
//! eigensolve: the six rigid motions of the nodes (translations t + θ × (x − x̄) and rotations
//! θ, in the displacement frames); the combinations the elimination reproduces exactly
//! (T X_r = X: no held dof moves, every rigid element fits) on the independent dofs,
//! M_r-orthonormalized and rotated to the eigenvectors of X_rᵀK_rX_r; those with Rayleigh
//! quotient below [`RIGID_TOL`] × (the model's stiffness-over-mass scale) are free. (A motion
//! that is rigid only on the independent dofs — a lateral motion of a rod node between held
//! ends — is a mechanism, not a rigid-body mode.)

use faer::Mat;

use super::PreloadError;
use crate::fe::constraints::Reduced;
use crate::fe::dofs::DofMap;
use crate::model::Model;
use crate::solve::inertia_relief::{support_of, InertiaRelief};
use crate::solve::sparse_ops::complement;
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
                t = crate::model::geometry::cross(th, r);
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

/// Eigen-decomposition of a small symmetric matrix (its symmetric part).
fn small_eigen(a: &Mat<f64>, what: &str) -> Result<(Vec<f64>, Mat<f64>), PreloadError> {
    let s = Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    let e = s
        .self_adjoint_eigen(faer::Side::Lower)
        .map_err(|e| SolveError::DenseEigen(format!("{what}: {e:?}")))?;
    Ok(((0..a.nrows()).map(|i| e.S()[i]).collect(), e.U().to_owned()))
}

/// The rigid-body modes the constraints of `red` leave free (module doc): M_r-orthonormal
/// columns on the independent dofs. A rigid motion is free when the elimination reproduces it
/// (T X_r = X: it moves no held dof and fits every rigid element) and K_r does not resist it.
pub fn free_rigid_modes(
    model: &Model,
    dofs: &DofMap,
    red: &Reduced,
) -> Result<Mat<f64>, PreloadError> {
    let mut x_phys = geometric_rigid_motions(model, dofs);
    for j in 0..6 {
        let n = x_phys.col(j).norm_l2();
        if n > 0.0 {
            x_phys.as_mut().col_mut(j).iter_mut().for_each(|v| *v /= n);
        }
    }
    let nr = red.retained.len();
    let x = Mat::from_fn(nr, 6, |i, j| x_phys[(red.retained[i], j)]);
    // the combinations the elimination reproduces: null space of D = T X_r − X
    let d = &red.expand(x.as_ref()) - &x_phys;
    let (dv, du) = small_eigen(&(d.transpose() * &d), "rigid-mode constraints")?;
    let kept: Vec<usize> = (0..6).filter(|&i| dv[i] <= 1e-18).collect();
    let c0 = Mat::from_fn(6, kept.len(), |i, j| du[(i, kept[j])]);
    let x = &x * &c0;
    let kx = crate::solve::sparse_ops::spmm(red.k.as_ref(), x.as_ref());
    let mx = crate::solve::sparse_ops::spmm(red.m.as_ref(), x.as_ref());
    // a motion without mass (e.g. every rotation of point masses on a line) cannot be balanced
    // by its inertia: keep the motions with mass, by the eigenvectors of G = XᵀM_rX
    let (gv, gu) = small_eigen(&(x.transpose() * &mx), "rigid-mode mass")?;
    let gmax = gv.iter().copied().fold(0.0f64, f64::max);
    let massive: Vec<usize> = (0..gv.len()).filter(|&i| gv[i] > 1e-12 * gmax).collect();
    // G^{-1/2} on the massive directions, then the eigenvectors of XᵀK_rX there
    let w = Mat::from_fn(gv.len(), massive.len(), |i, j| {
        gu[(i, massive[j])] / gv[massive[j]].sqrt()
    });
    let (av, au) = small_eigen(
        &(w.transpose() * (x.transpose() * &kx) * &w),
        "rigid-mode stiffness",
    )?;
    let scale = trace_ratio(&red.k, &red.m);
    let free: Vec<usize> = (0..av.len())
        .filter(|&i| av[i] <= RIGID_TOL * scale)
        .collect();
    let coeff = &w * &au;
    let c = Mat::from_fn(coeff.nrows(), free.len(), |i, j| coeff[(i, free[j])]);
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
    let support = support_of(&xr)?;
    let free = complement(&support, n);
    let ir = InertiaRelief::on_support(&red.k, &red.m, xr, support, eig).map_err(|e| match e {
        SolveError::NonPositivePivot { dof } => {
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
        other => PreloadError::Solve(other),
    })?;
    let u = ir.solve_equilibrated(&ir.equilibrate(f_r));
    Ok((u, ir.support))
}
