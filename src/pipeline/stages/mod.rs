//! The stages of the pipeline, one module each: what it takes (the previous stage's data) and
//! what it returns. [`super::build_model_with_hook`] calls them in order.
//!
//! | stage | module | takes → returns |
//! |---|---|---|
//! | import | [`import`](mod@import) | model file → [`Model`](crate::model::Model) |
//! | interfaces | [`interfaces`](mod@interfaces) | `Model` → [`WithInterfaces`](interfaces::WithInterfaces) (spiders attached) |
//! | assembly | [`assembly`](mod@assembly) | → [`Assembled`](crate::fe::Assembled) (K, M, dof map) |
//! | constraints | [`constraints`](mod@constraints) | → [`Constrained`](constraints::Constrained) (K_r, M_r, T, interface and reference dofs) |
//! | preload | [`preload`](mod@preload) | → the same, K_T,r = K_r + Tᵀ K_G T in place of K_r (only with a preload) |
//! | reduction | [`reduction`](mod@reduction) | → [`ReducedBasis`](reduction::ReducedBasis) (mode set, Φ = T Φ_r) |
//! | invariants | [`invariants`](mod@invariants) | → [`MassProperties`](invariants::MassProperties) (nodal masses, invariants) |
//! | geometric stiffness | [`geometric`](mod@geometric) | → `ReducedBasis::geometric_stiffness`: Φᵀ K_G Φ per unit inertia load (only when asked) |
//! | stress shapes | [`fields`](mod@fields) | → [`FieldShapes`](fields::FieldShapes) (only when asked) |
//! | assemble file | [`file`](mod@file) | → the file's [`ReducedBody`](flexbody_reader::ReducedBody) |
//! | verify | [`verify`](mod@verify) | → the same body, verified, or an error |

use faer::Mat;

use crate::fe::DofMap;
use crate::model::NodeIndex;
use crate::solve::SparseColMat;

pub mod assembly;
pub mod constraints;
pub mod fields;
pub mod file;
pub mod geometric;
pub mod import;
pub mod interfaces;
pub mod invariants;
pub mod lumping_check;
pub mod preload;
pub mod reduction;
pub mod verify;

/// A 0 × 0 sparse matrix (what a freed matrix is replaced by).
pub(crate) fn empty_matrix() -> SparseColMat<usize, f64> {
    SparseColMat::new(
        faer::sparse::SymbolicSparseColMat::new_checked(0, 0, vec![0], None, vec![]),
        vec![],
    )
}

/// Rows `[ux uy uz rx ry rz]` of node `p` for mode `j` in the basic frame (zeros where the node
/// has no such dof): u_basic = Aᵀ u_local with A's rows the local axes.
pub fn node_shape(dofs: &DofMap, phi: &Mat<f64>, p: NodeIndex, j: usize) -> [f64; 6] {
    let count = usize::from(dofs.count[p]);
    let mut local = [0.0; 6];
    for (c, v) in local.iter_mut().enumerate().take(count) {
        *v = phi[(dofs.first[p] + c, j)];
    }
    match dofs.frames[p] {
        None => local,
        Some(a) => {
            let rot = |v: &[f64]| -> [f64; 3] {
                std::array::from_fn(|i| (0..3).map(|k| a[k][i] * v[k]).sum())
            };
            let (t, r) = (rot(&local[..3]), rot(&local[3..]));
            [t[0], t[1], t[2], r[0], r[1], r[2]]
        }
    }
}
