//! The plain, versioned records of a reduced-body file (format v1).
//!
//! Every type here is a compatibility promise: its serde layout *is* the byte layout described
//! in `format-spec/SPEC.md`. Field order matters (bincode writes fields in declaration order);
//! enum variant order matters (the variant index is the tag). Never reorder, only append in a
//! new minor version through a new optional entry.
use serde::{Deserialize, Serialize};

/// Format version `major.minor` as written in the manifest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Version {
    /// Incompatible layout changes bump the major version; readers refuse a newer major.
    pub major: u32,
    /// Compatible additions (new optional entries) bump the minor version.
    pub minor: u32,
}

/// The program that wrote the file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Generator {
    /// Program name, e.g. `flexbody`.
    pub name: String,
    /// Program version, e.g. `0.1.0`.
    pub version: String,
}

/// One unit: a display name and the factor that converts one of it into SI.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Unit {
    /// Display name, e.g. `kg`, `mm`, `s`, `N`.
    pub name: String,
    /// Value of one unit in SI (kg, m, s, N): `mm` → 0.001.
    pub si: f64,
}

/// The model's consistent unit system. Recorded, never guessed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Units {
    /// Mass unit.
    pub mass: Unit,
    /// Length unit.
    pub length: Unit,
    /// Time unit.
    pub time: Unit,
    /// Force unit.
    pub force: Unit,
}

impl Units {
    /// SI units: kg, m, s, N.
    pub fn si() -> Self {
        let u = |n: &str| Unit {
            name: n.to_string(),
            si: 1.0,
        };
        Units {
            mass: u("kg"),
            length: u("m"),
            time: u("s"),
            force: u("N"),
        }
    }
}

/// Reduction method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Method {
    /// Free or constrained normal modes (tag 0).
    NormalModes,
    /// Craig–Bampton: constraint + fixed-interface modes (tag 1).
    CraigBampton,
    /// Craig–Chang: free-free + inertia-relief attachment modes (tag 2).
    CraigChang,
    /// Dietz frequency-response modes (tag 3).
    Dietz,
}

/// Mass matrix used for the reduction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum MassKind {
    /// Diagonal (lumped) mass (tag 0).
    Lumped,
    /// Consistent mass (tag 1).
    Consistent,
}

/// Which nodes the user asked to keep in the file.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum KeepNodes {
    /// Every node of the model (tag 0).
    All,
    /// Interface nodes and the nodes of the graphics faces (tag 1).
    InterfaceAndSurface,
    /// Interface nodes plus these external node ids (tag 2).
    List(Vec<u64>),
}

/// Named invariant selections. Each maps to one fixed 9-flag mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum InvariantSet {
    /// I1…I9 (tag 0).
    Full,
    /// All but I5 and I9 (tag 1).
    Partial,
    /// I1, I2, I6, I7 (tag 2).
    Constant,
    /// I1, I2, I7 (tag 3).
    Rigid,
}

impl InvariantSet {
    /// The selection mask, `mask[k]` for invariant I(k+1).
    pub fn mask(self) -> [bool; 9] {
        let pick = |ks: &[usize]| {
            let mut m = [false; 9];
            for &k in ks {
                m[k - 1] = true;
            }
            m
        };
        match self {
            InvariantSet::Full => [true; 9],
            InvariantSet::Partial => pick(&[1, 2, 3, 4, 6, 7, 8]),
            InvariantSet::Constant => pick(&[1, 2, 6, 7]),
            InvariantSet::Rigid => pick(&[1, 2, 7]),
        }
    }
}

/// What the user asked for (entry `header.bin`, field `request`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Request {
    /// Reduction method.
    pub method: Method,
    /// Frequency band upper limit in Hz, if given.
    pub fmax_hz: Option<f64>,
    /// Requested number of modes, if given.
    pub mode_count: Option<u64>,
    /// Node selection.
    pub keep_nodes: KeepNodes,
    /// Invariant selection.
    pub invariant_set: InvariantSet,
    /// Mass matrix kind.
    pub mass_kind: MassKind,
}

/// Entry `header.bin`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// Free text title.
    pub title: String,
    /// Creation time (RFC 3339, UTC), only when the user asked for it; default `None` keeps
    /// output deterministic.
    pub created_utc: Option<String>,
    /// The user's choices.
    pub request: Request,
}

/// One stored node (entry `nodes.bin`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Node {
    /// External id from the input model.
    pub id: u64,
    /// Undeformed position x, y, z in the body frame (length unit).
    pub xyz: [f64; 3],
    /// True for interface (attachment) nodes.
    pub interface: bool,
}

/// One graphics face by 0-based index into the node list (entry `faces.bin`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum Face {
    /// Triangle (tag 0), counter-clockwise seen from outside.
    Tri([u32; 3]),
    /// Quadrilateral (tag 1), counter-clockwise seen from outside.
    Quad([u32; 4]),
}

/// Lumped mass and rotary inertia of one stored node (entry `nodal_mass.bin`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodalMass {
    /// Lumped translational mass (mass unit), ≥ 0.
    pub mass: f64,
    /// 3×3 rotary inertia about the node, row-major, true tensor (negative products of
    /// inertia off the diagonal), symmetric (mass·length²).
    pub inertia: [[f64; 3]; 3],
}

/// What a mode is (per mode, entry `modes.bin`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ModeLabel {
    /// Rigid-body mode (tag 0).
    Rigid,
    /// Elastic normal mode of the (free or constrained) body (tag 1).
    Normal,
    /// Craig–Bampton constraint mode (tag 2).
    Constraint,
    /// Craig–Bampton fixed-interface mode (tag 3).
    FixedInterface,
    /// Craig–Chang inertia-relief attachment mode (tag 4).
    Attachment,
    /// Dietz frequency-response mode (tag 5).
    FrequencyResponse,
}

/// Entry `modes.bin`. M modes over the N stored nodes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Modes {
    /// ω² per mode in rad²/s² (time unit⁻²), ascending.
    pub omega2: Vec<f64>,
    /// Frequency per mode in Hz: √max(ω², 0)/(2π).
    pub frequency_hz: Vec<f64>,
    /// Label per mode.
    pub labels: Vec<ModeLabel>,
    /// Generalized mass Φᵀ M Φ, M×M row-major, symmetric.
    pub generalized_mass: Vec<f64>,
    /// Generalized stiffness Φᵀ K Φ, M×M row-major, symmetric.
    pub generalized_stiffness: Vec<f64>,
    /// Mode shapes, mode-major: `shapes[(j*N + p)*6 + c]`, c = ux uy uz rx ry rz.
    pub shapes: Vec<f64>,
}

/// Entry `invariants.bin`: the nine inertia invariants (Adams numbering) from every mass
/// node of the model. An unselected invariant is an empty vector; a selected one has exactly
/// the length of its shape (see the field docs; all row-major).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Invariants {
    /// `mask[k]` true when I(k+1) is stored.
    pub mask: [bool; 9],
    /// I1 = Σ m, shape \[1\].
    pub i1: Vec<f64>,
    /// I2 = Σ m s, shape \[3\].
    pub i2: Vec<f64>,
    /// I3 = Σ m Φ, shape \[3\]\[M\].
    pub i3: Vec<f64>,
    /// I4 = Σ (m s̃ Φ + I_p Φ*), shape \[3\]\[M\].
    pub i4: Vec<f64>,
    /// I5_j = Σ m φ̃_j Φ, shape \[M (j)\]\[3\]\[M\].
    pub i5: Vec<f64>,
    /// I6 = Σ (m Φᵀ Φ + Φ*ᵀ I_p Φ*), shape \[M\]\[M\].
    pub i6: Vec<f64>,
    /// I7 = Σ (m s̃ᵀ s̃ + I_p), shape \[3\]\[3\]: inertia tensor about the origin.
    pub i7: Vec<f64>,
    /// I8_j = Σ m s̃ φ̃_j, shape \[M (j)\]\[3\]\[3\].
    pub i8: Vec<f64>,
    /// I9_jk = Σ m φ̃_j φ̃_k, shape \[M (j)\]\[M (k)\]\[3\]\[3\].
    pub i9: Vec<f64>,
}

/// One interface node of the method record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InterfaceNode {
    /// 0-based index into the node list; that node's `interface` flag must be true.
    pub node: u32,
    /// Active dofs `[ux uy uz rx ry rz]` in the local frame.
    pub dofs: [bool; 6],
    /// Local frame, row-major; row r is local axis r in body coordinates (orthonormal, det +1).
    pub frame: [[f64; 3]; 3],
}

/// A reference condition: these components of this node have zero deformation.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ReferenceCondition {
    /// 0-based index into the node list.
    pub node: u32,
    /// Constrained components `[ux uy uz rx ry rz]`.
    pub dofs: [bool; 6],
}

/// Counts of the basis vectors the method built (before the final orthonormalization).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct ModeCounts {
    /// Rigid-body modes.
    pub rigid: u64,
    /// Elastic normal modes.
    pub normal: u64,
    /// Constraint modes.
    pub constraint: u64,
    /// Fixed-interface modes.
    pub fixed_interface: u64,
    /// Attachment / frequency-response modes.
    pub attachment: u64,
    /// Dependent vectors detected and removed.
    pub removed_dependent: u64,
}

/// Cutoffs the method applied.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Cutoffs {
    /// Highest kept frequency in Hz.
    pub fmax_hz: Option<f64>,
    /// Dietz shift ℓ as a fraction of the first flexible eigenvalue.
    pub shift_fraction: Option<f64>,
    /// Relative tolerance under which a vector was treated as dependent.
    pub dependency_tolerance: Option<f64>,
}

/// Entry `method.bin`: what the reduction actually did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MethodRecord {
    /// Reduction method (equals `header.request.method`).
    pub method: Method,
    /// Mass matrix kind (equals `header.request.mass_kind`).
    pub mass_kind: MassKind,
    /// Interface nodes with their dofs and frames.
    pub interface: Vec<InterfaceNode>,
    /// Reference conditions defining the body frame (empty for a free body).
    pub reference_conditions: Vec<ReferenceCondition>,
    /// Basis counts.
    pub counts: ModeCounts,
    /// Cutoffs.
    pub cutoffs: Cutoffs,
}

/// Entries `stress_shapes.bin` / `strain_shapes.bin`: 6 tensor components per listed node per
/// mode, order xx yy zz xy yz zx. Strain shear components are engineering strains (γ = 2ε).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldShapes {
    /// 0-based node indices (into the node list) that carry values, strictly ascending.
    pub nodes: Vec<u32>,
    /// Values, mode-major: `values[(j*K + q)*6 + c]` for K listed nodes.
    pub values: Vec<f64>,
}

/// Entry `damping.bin`: modal damping ratio per mode (fraction of critical, ≥ 0).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Damping {
    /// Ratio per mode.
    pub ratio: Vec<f64>,
}

/// Entry `modal_loads.bin` (format 1.4): the scene's named loads projected on the modes, so a
/// solver applies gravity, a point load or a pressure to the reduced body without the mesh,
/// and which modes are residual vectors (static load responses).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModalLoads {
    /// One per scene load, in the build's order.
    pub loads: Vec<ModalLoad>,
    /// Per mode (length M), or empty when the body has no residual vectors: 1 when the mode's
    /// dominant origin is a residual vector (static response to a scene load, labelled
    /// `Attachment` in `modes.bin`), else 0.
    pub residual: Vec<u8>,
}

/// One named load of [`ModalLoads`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModalLoad {
    /// The load's name (`GRAVITY`, `LOAD_10`, a `--load` name), unique in the entry.
    pub name: String,
    /// Where it came from (deck cards with file and line, or the CLI option).
    pub source: String,
    /// Generalized force Φᵀf per mode (length M): force × length per unit modal coordinate.
    pub values: Vec<f64>,
}

/// Entry `geometric_stiffness.bin` (format 1.7, SPEC §5.16): the modal geometric stiffness
/// K̂_G = Φᵀ K_G(σ(unit load)) Φ of each unit inertia load, so a solver stiffens the body by
/// K̂ + Σ_j s_j K̂_G,j with s_j the current accelerations and angular-velocity products.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GeometricStiffness {
    /// How the unit loads' static displacement was solved.
    pub support: StaticSupport,
    /// One per unit load, each load at most once.
    pub fields: Vec<GeometricField>,
}

/// What held the body in the static solve of [`GeometricStiffness`] (SPEC §5.16).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum StaticSupport {
    /// The model's constraints hold the body: the direct solution.
    Held,
    /// Free rigid-body motions balanced by the inertia of the rigid acceleration.
    InertiaRelief,
}

/// One unit load and its modal geometric stiffness.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GeometricField {
    /// The unit load.
    pub load: UnitLoad,
    /// K̂_G, row-major [M][M], symmetric.
    pub matrix: Vec<f64>,
}

/// A unit inertia load of the body frame (axes 0, 1, 2 = x, y, z; SPEC §5.16).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum UnitLoad {
    /// Unit acceleration of the frame along the axis (body force −e_a per unit mass).
    Acceleration(u8),
    /// Unit product ω_iω_j (i ≤ j) of the angular velocity.
    AngularVelocity([u8; 2]),
    /// Unit angular acceleration about the axis (body force −e_a × r).
    AngularAcceleration(u8),
}

impl UnitLoad {
    /// The twelve loads flexbody writes, in its order: accelerations, the six products
    /// ω_iω_j (i ≤ j, row by row), angular accelerations.
    pub fn inertia() -> Vec<UnitLoad> {
        let mut out: Vec<UnitLoad> = (0..3).map(UnitLoad::Acceleration).collect();
        for i in 0..3u8 {
            for j in i..3 {
                out.push(UnitLoad::AngularVelocity([i, j]));
            }
        }
        out.extend((0..3).map(UnitLoad::AngularAcceleration));
        out
    }

    /// The load's name in summaries (`a_x`, `omega_x*omega_y`, `alpha_z`); `None` when an
    /// axis is out of range.
    pub fn name(&self) -> Option<String> {
        let axis = |a: u8| ["x", "y", "z"].get(usize::from(a)).copied();
        Some(match *self {
            UnitLoad::Acceleration(a) => format!("a_{}", axis(a)?),
            UnitLoad::AngularVelocity([i, j]) => format!("omega_{}*omega_{}", axis(i)?, axis(j)?),
            UnitLoad::AngularAcceleration(a) => format!("alpha_{}", axis(a)?),
        })
    }

    /// Whether the axes are valid (≤ 2; i ≤ j for an angular-velocity product).
    pub fn is_valid(&self) -> bool {
        match *self {
            UnitLoad::Acceleration(a) | UnitLoad::AngularAcceleration(a) => a <= 2,
            UnitLoad::AngularVelocity([i, j]) => i <= j && j <= 2,
        }
    }
}

/// Entry `eigen_residuals.bin` (format 1.9, SPEC §5.17): for each eigenproblem the build
/// solved whose vectors reach the basis, which problem and solver it was, each mode's
/// eigenvalue and relative residual, and the Sylvester inertia count when one was made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EigenResiduals {
    /// One per eigenproblem, each kind at most once.
    pub problems: Vec<EigenProblem>,
}

/// One eigenproblem K φ = λ M φ of [`EigenResiduals`] and the quality of its solution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EigenProblem {
    /// Which problem (the method's own).
    pub kind: EigenProblemKind,
    /// Which solver produced its eigenpairs.
    pub solver: EigenSolverKind,
    /// s, the median of K_ii/M_ii over the problem's dofs (SPEC §5.17): the rigid threshold is
    /// 10⁻⁸ s.
    pub scale: f64,
    /// λ_j = ω_j² per mode as the solver returned it, ascending.
    pub omega2: Vec<f64>,
    /// r_j = ‖Kφ_j − λ_j Mφ_j‖₂ / max(‖Kφ_j‖₂, 10⁻⁸ s ‖Mφ_j‖₂) per mode (SPEC §5.17), ≥ 0.
    pub residual: Vec<f64>,
    /// Sylvester's inertia count of K − σM, when the band was verified.
    pub inertia: Option<InertiaCount>,
}

impl EigenProblem {
    /// The largest residual of a flexible mode (ω² > 10⁻⁸ · `scale`) and its index.
    pub fn largest_flexible_residual(&self) -> Option<(usize, f64)> {
        (self.omega2.iter().zip(&self.residual).enumerate())
            .filter(|(_, (&l, _))| l > 1e-8 * self.scale)
            .fold(None, |w, (j, (_, &r))| match w {
                Some((_, wr)) if wr >= r => w,
                _ => Some((j, r)),
            })
    }
}

/// Which eigenproblem (SPEC §5.17).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum EigenProblemKind {
    /// Normal modes of the constrained model: the file's modes (tag 0).
    NormalModes,
    /// Craig–Bampton's fixed-interface modes: the interior problem K_ii, M_ii (tag 1).
    FixedInterface,
    /// Craig–Chang's and Dietz's free-free modes of the constrained model (tag 2).
    FreeFree,
}

/// Which eigensolver (SPEC §5.17).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum EigenSolverKind {
    /// Block shift-invert Lanczos (tag 0).
    Lanczos,
    /// Automated multilevel substructuring with Rayleigh–Ritz on the full K, M (tag 1).
    Amls,
    /// A dense eigen-decomposition (tag 2).
    Dense,
    /// PETSc/SLEPc under MPI, `--engine slepc` (tag 3).
    Slepc,
}

/// Sylvester's count of K − σM: `below` eigenvalues lie below `shift` (SPEC §5.17).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct InertiaCount {
    /// σ (ω², rad²/time²).
    pub shift: f64,
    /// The number of negative pivots of an LDLᵀ of K − σM.
    pub below: u64,
}

/// A whole reduced body: everything a file holds, validated when read. (Serde derives are
/// for tools, e.g. a JSON dump; the file itself stores the parts as separate entries.)
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReducedBody {
    /// Format version of the file read (written files carry [`crate::FORMAT_VERSION`]).
    pub version: Version,
    /// Writer program (manifest).
    pub generator: Generator,
    /// Unit system (manifest).
    pub units: Units,
    /// `header.bin`.
    pub header: Header,
    /// `nodes.bin`.
    pub nodes: Vec<Node>,
    /// `faces.bin`.
    pub faces: Vec<Face>,
    /// `nodal_mass.bin`, one per stored node.
    pub nodal_mass: Vec<NodalMass>,
    /// `modes.bin`.
    pub modes: Modes,
    /// `invariants.bin`.
    pub invariants: Invariants,
    /// `method.bin`.
    pub method: MethodRecord,
    /// Optional `stress_shapes.bin`.
    pub stress_shapes: Option<FieldShapes>,
    /// Optional `strain_shapes.bin`.
    pub strain_shapes: Option<FieldShapes>,
    /// Optional `damping.bin`.
    pub damping: Option<Damping>,
    /// Optional `lines.bin` (format 1.1): 2-node graphics lines (beams, rods) as 0-based node
    /// indices.
    pub lines: Option<Vec<[u32; 2]>>,
    /// Optional `recipe.json` (format 1.2): how the body was built.
    pub recipe: Option<crate::Recipe>,
    /// Optional `label_shares.bin` (format 1.2): per mode, the participation share (0…1) of the
    /// origin its label names; 1 for `Rigid` and for modes of a single-stage basis.
    pub label_shares: Option<Vec<f64>>,
    /// Optional `interfaces.bin` (format 1.3): per interface node (in `method.interface` order)
    /// its name, kind, dependent mesh nodes and centre fit.
    pub interfaces: Option<Vec<crate::InterfaceInfo>>,
    /// Optional `stress_shapes_bottom.bin` (format 1.5): the bottom-fibre stress of the shell
    /// nodes, whose `stress_shapes` values are then the top fibre (SPEC §5.15).
    pub stress_shapes_bottom: Option<FieldShapes>,
    /// Optional `strain_shapes_bottom.bin` (format 1.5): as `stress_shapes_bottom` for strain.
    pub strain_shapes_bottom: Option<FieldShapes>,
    /// Optional `modal_loads.bin` (format 1.4): modal loads and residual-vector origins.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modal_loads: Option<ModalLoads>,
    /// Optional `geometric_stiffness.bin` (format 1.7): the modal geometric stiffness per
    /// unit inertia load.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub geometric_stiffness: Option<GeometricStiffness>,
    /// Optional `eigen_residuals.bin` (format 1.9): per eigenproblem, each mode's eigenvalue
    /// and relative residual.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eigen_residuals: Option<EigenResiduals>,
}

impl ReducedBody {
    /// Number of stored nodes N.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
    /// Number of modes M.
    pub fn mode_count(&self) -> usize {
        self.modes.omega2.len()
    }
}
