//! Element matrices and sparse assembly of stiffness K and mass M, with rigid elements and
//! constraints eliminated by u = T u_r.
//!
//! ```text
//! Model ──► DofMap::from_model ──► assemble (K, M over the nodes' dofs and ccx C3D8I's
//!                                     │      interior mode dofs)
//!                                     │
//!                                     └──► constraints::eliminate ──► (K_r = TᵀKT, M_r = TᵀMT, T)
//! ```
//! * [`elements`] — one file per element kind: shape functions, quadrature, formulas.
//! * [`dofs::DofMap`] — node ↔ dof numbering (3 or 6 per node, 1 per scalar point,
//!   node-major, CD frames), then the elements' interior dofs (ccx's C3D8I modes).
//! * [`interior`] — those interior dofs recovered from the nodes' rows of an eigenvector.
//! * [`mass`] — lumping (row-sum, HRZ) and point masses.
//! * [`shell_section`] — shell section + materials → element shell constants.
//! * [`connectors`] — springs, scalar masses and bushes.
//! * [`assembly::assemble`] — parallel assembly into faer `SparseColMat` (full symmetric).
//! * [`constraints::eliminate`] — RBE2/RBE3/RBAR/RBE1/MPC/SPC elimination, keeps T for shape
//!   recovery.
//! * [`geometric`] — geometric (initial-stress) stiffness K_G(σ₀) of every element family.
//! * [`preload`] — the preload stage: static solve of a preload case, K_T = K + K_G, the
//!   buckling check, the modal geometric-stiffness terms.

// Index loops mirror the subscripts of the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod assembly;
pub mod connectors;
pub mod constraints;
pub mod dofs;
pub mod elements;
pub mod geometric;
pub mod interior;
pub mod loads;
pub mod mass;
pub mod pattern;
pub mod preload;
pub mod quadrature;
mod rigid_body;
pub mod rigid_mass;
pub mod shell_section;

pub use assembly::{assemble, Assembled, AssemblySpec, BeamTheory};
pub use constraints::{eliminate, ConstraintSpec, Reduced};
pub use dofs::DofMap;
pub use elements::element::{BeamLumping, Tet10MassRule};
pub use mass::MassKind;

use crate::model::ElementKind;

/// Errors of assembly and constraint elimination; each names the model file and the entity.
#[derive(Debug, thiserror::Error)]
pub enum FeError {
    /// An element's matrices could not be formed.
    #[error("{source_file}: element {id} ({kind:?}): {err}")]
    Element {
        /// Model file.
        source_file: String,
        /// External element id.
        id: u64,
        /// Element kind.
        kind: ElementKind,
        /// Cause.
        #[source]
        err: elements::ElementError,
    },
    /// The element (or its property) is of a kind the assembler does not handle.
    #[error("{source_file}: element {id} ({kind:?}) {message}")]
    Unsupported {
        /// Model file.
        source_file: String,
        /// External element id.
        id: u64,
        /// Element kind.
        kind: ElementKind,
        /// What is missing.
        message: String,
    },
    /// A dangling index in the model.
    #[error("{source_file}: {message}")]
    BadReference {
        /// Model file.
        source_file: String,
        /// What refers to what.
        message: String,
    },
    /// Inconsistent rigid elements or constraints.
    #[error("{source_file}: {message}")]
    Constraint {
        /// Model file.
        source_file: String,
        /// The conflict, naming the element / node ids.
        message: String,
    },
}
