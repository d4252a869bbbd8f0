//! The stages of the pipeline, one module each: what it takes (the previous stage's data) and
//! what it returns. [`super::build_model_with_hook`] calls them in order. The data passed between
//! stages is defined here, below every stage, so no stage names a later one.
//!
//! | stage | module | takes → returns |
//! |---|---|---|
//! | import | [`import`](mod@import) | model file → [`Model`](crate::model::Model) |
//! | interfaces | [`interfaces`](mod@interfaces) | `Model` → [`WithInterfaces`] (spiders attached) |
//! | assembly | [`assembly`](mod@assembly) | → [`Assembled`](crate::fe::Assembled) (K, M, dof map) |
//! | constraints | [`constraints`](mod@constraints) | → [`Constrained`] (K_r, M_r, T, interface and reference dofs) |
//! | preload | [`preload`](mod@preload) | → [`PreloadSummary`] (only with a preload), K_T,r = K_r + Tᵀ K_G T in place of `Constrained`'s K_r |
//! | reduction | [`reduction`](mod@reduction) | → [`ReducedBasis`] (mode set, Φ = T Φ_r) |
//! | invariants | [`invariants`](mod@invariants) | → [`MassProperties`] (nodal masses, invariants) |
//! | geometric stiffness | [`geometric`](mod@geometric) | → `ReducedBasis::geometric_stiffness`: Φᵀ K_G Φ per unit inertia load (only when asked) |
//! | stress shapes | [`fields`](mod@fields) | → [`FieldShapes`] (only when asked) |
//! | assemble file | [`file`](mod@file) | → the file's [`ReducedBody`](flexbody_reader::ReducedBody) |
//! | verify | [`verify`](mod@verify) | → the same body, verified, or an error |

use faer::Mat;

use crate::body::faces::GraphicsFace;
use crate::body::invariants::Invariants;
use crate::body::stress::ModalFields;
use crate::fe::{Assembled, DofMap, Reduced};
use crate::model::offset_mass::MassNode;
use crate::model::{DofMask, Model, NodeIndex};
use crate::pipeline::interface::InterfaceReport;
use crate::pipeline::precheck::RigidExpectation;
use crate::pipeline::scene::SceneLoads;
use crate::reduce::ModeSet;
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

/// Per-node lumped mass and inertia of the structure (point masses excluded), basic frame.
pub type NodalMass = Vec<(f64, [[f64; 3]; 3])>;

/// The model with its interface spiders, and the interfaces as resolved.
#[derive(Debug, Clone)]
pub struct WithInterfaces {
    /// The model, spider centre nodes and rigid elements included.
    pub model: Model,
    /// One per `--interface` entry.
    pub interfaces: Vec<InterfaceReport>,
    /// Every interface's nodes, in entry order (a spider's centre node for a node set).
    pub interface_nodes: Vec<NodeIndex>,
    /// The nodes made at offset centres of gravity of point masses (`model::offset_mass`).
    pub mass_nodes: Vec<MassNode>,
}

/// Reference conditions per node: the components held.
pub type ReferenceNodes = Vec<(NodeIndex, DofMask)>;

/// The system the reduction starts from.
#[derive(Debug, Clone)]
pub struct Constrained {
    /// The physical assembly: its dof map and M (K is freed once eliminated).
    pub assembled: Assembled,
    /// K_r = Tᵀ K T, M_r = Tᵀ M T over the independent dofs, and T.
    pub reduced: Reduced,
    /// Interface dofs in the independent numbering.
    pub interface_dofs: Vec<usize>,
    /// The components of each interface node (in `WithInterfaces::interface_nodes` order).
    pub interface_masks: Vec<DofMask>,
    /// Reference-condition dofs in the independent numbering.
    pub reference_dofs: Vec<usize>,
    /// Reference conditions per node, the model's own SPCs included (what the file records).
    pub reference_nodes: ReferenceNodes,
    /// The rigid-body modes a model of several connected parts must have (`None`: one part,
    /// the file's reference conditions tell), for the verify stage.
    pub expected_rigid: Option<RigidExpectation>,
}

/// What the preload was and what it did (report and recipe).
#[derive(Debug, Clone, PartialEq)]
pub struct PreloadSummary {
    /// Where it came from: `--preload NAMES` or the deck's step.
    pub source: String,
    /// The scene loads it is made of (a CENTRIF is a part of its step's load).
    pub loads: Vec<String>,
    /// The largest translation |u₀| of the static solution.
    pub max_displacement: f64,
    /// The external id of the node where it is.
    pub max_displacement_node: u64,
    /// The lowest buckling factor λ₁ (`None`: nothing in compression).
    pub buckling_factor: Option<f64>,
    /// The tangent carries K_L(u₀) too (CalculiX's perturbation of the static state).
    pub initial_displacement: bool,
    /// The tangent carries the spin softening of the preload's centrifugal loads.
    pub spin_softening: bool,
}

impl PreloadSummary {
    /// The build report's note.
    pub fn note(&self) -> String {
        let factor = match self.buckling_factor {
            Some(l) => format!("lowest buckling factor λ₁ = {l:.6}"),
            None => "no buckling factor (nothing in compression)".into(),
        };
        let tangent = match (self.initial_displacement, self.spin_softening) {
            (true, true) => "K + K_G + K_L(u0) − Ω²M⊥ (the perturbed static state with the spin softening of its centrifugal loads, as CalculiX's *STEP, PERTURBATION)",
            (true, false) => "K + K_G + K_L(u0) (the perturbed static state, as CalculiX's *STEP, PERTURBATION)",
            (false, true) => "K + K_G − Ω²M⊥ (with the spin softening of its centrifugal loads)",
            (false, false) => "K + K_G",
        };
        format!(
            "preloaded: {} ({}): linear static preload, max |u0| {:.6e} at node {}, {factor}; the modes are those of {tangent}",
            self.source,
            self.loads.join(", "),
            self.max_displacement,
            self.max_displacement_node
        )
    }
}

/// The reduced basis of the body.
#[derive(Debug, Clone)]
pub struct ReducedBasis {
    /// The mode set over the independent dofs.
    pub set: ModeSet,
    /// Its shapes over the physical dofs, Φ = T Φ_r.
    pub phi: Mat<f64>,
    /// The scene's loads on the independent dofs.
    pub scene: SceneLoads,
    /// The physical consistent M was released for the native Craig–Bampton reduction (issue 22:
    /// as large as K); the invariants stage assembles it again.
    pub mass_released: bool,
    /// The preload the modes are of (their K_r is K_T,r; from the preload stage).
    pub preload: Option<PreloadSummary>,
    /// The modal geometric stiffness per unit load (`--geometric-stiffness`; set by the
    /// geometric-stiffness stage).
    pub geometric_stiffness: Option<flexbody_reader::GeometricStiffness>,
}

/// The body's mass as the file stores it and its invariants.
#[derive(Debug, Clone)]
pub struct MassProperties {
    /// Per node: structure and point masses lumped to it, inertia about it (basic frame).
    pub nodal: NodalMass,
    /// The nine invariants (those the spec selects).
    pub invariants: Invariants,
}

/// The nodes the file stores, and the graphics faces they are picked from.
#[derive(Debug, Clone)]
pub struct StoredNodes {
    /// The free outer faces of the mesh (and beam lines).
    pub faces: Vec<GraphicsFace>,
    /// The stored nodes, ascending: `--keep-nodes`, plus every interface and reference node.
    pub nodes: Vec<NodeIndex>,
}

/// The field shapes of the file.
#[derive(Debug, Clone, Default)]
pub struct FieldShapes {
    /// Solids and the shells' top fibre (`None`: not asked, or no stored node has any).
    pub top: Option<ModalFields>,
    /// The shells' bottom fibre.
    pub bottom: Option<ModalFields>,
}
