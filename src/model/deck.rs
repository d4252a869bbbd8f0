//! What a deck asks of the analysis besides the model itself — the case control's choices, the
//! eigenvalue request, the interface and mode-count sets — and where every constraint came
//! from. Plain data filled by the importers and read by `build` for its defaults and report.

use std::ops::Range;

/// An eigenvalue request (Nastran `METHOD = n` → `EIGRL`/`EIGR` n).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EigenRequest {
    /// Where it came from, e.g. `METHOD = 1 → EIGRL 1 (deck.bdf:12)`.
    pub source: String,
    /// Number of roots wanted (ND).
    pub count: Option<usize>,
    /// Lower end of the band, Hz (V1 / F1).
    pub lower_hz: Option<f64>,
    /// Upper end of the band, Hz (V2 / F2).
    pub upper_hz: Option<f64>,
}

/// The deck's own analysis choices.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DeckRequest {
    /// The case control's `TITLE`.
    pub title: Option<String>,
    /// The subcase whose selections were used (when the deck has subcases).
    pub subcase: Option<u64>,
    /// The eigenvalue request selected by the case control.
    pub eigen: Option<EigenRequest>,
    /// Interface dofs from the bulk data (ASET/ASET1/BSET/BSET1): a description of the cards.
    pub interface_source: Option<String>,
    /// Number of component modes fixed by QSET/QSET1 (their dof count), with the cards' description.
    pub qset_modes: Option<(usize, String)>,
    /// Notes for the build report (e.g. SPC sets present but not selected).
    pub notes: Vec<String>,
    /// Every constraint set of the deck by name (`SPC_1`), selected or not, with the components
    /// it holds per node: usable as reference conditions by name.
    pub spc_sets:
        std::collections::BTreeMap<String, Vec<(crate::model::NodeIndex, crate::model::DofMask)>>,
    /// The preload the deck asks the modes under (CalculiX `*STATIC` then `*STEP,
    /// PERTURBATION` / `*FREQUENCY`), if any.
    pub preload: Option<PreloadRequest>,
}

/// A linear static preload of the deck's modes (issue 35): the base state of a perturbation
/// frequency step.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PreloadRequest {
    /// What and where, e.g. `step 1 (*STATIC) at deck.inp:376`.
    pub source: String,
    /// The first load keyword of the preload, `file:line: *KEYWORD` (what an error names).
    pub first_load: String,
    /// The names of the scene loads (`Model::loads`) the preload is made of.
    pub loads: Vec<String>,
    /// Temperature change ΔT from the stress-free state per node (indexed like
    /// `Model::nodes`), with the expansion coefficient α per material (like
    /// `Model::materials`).
    pub thermal: Option<(Vec<f64>, Vec<f64>)>,
    /// What of it the tool cannot honour (`file:line: *KEYWORD: why`): the build refuses the
    /// deck with it.
    pub problem: Option<String>,
    /// The deck's solver perturbs the deformed static state: the modes' tangent adds the
    /// initial-displacement stiffness K_L(u₀) (CalculiX `*STEP, PERTURBATION`); `false`: the
    /// linear preload K + K_G(σ₀) (Nastran STATSUB's differential stiffness, `--preload`).
    pub initial_displacement: bool,
    /// The modes' tangent adds the spin softening of the preload's centrifugal loads (the
    /// rotating frame's modes, as CalculiX's perturbation step forms them).
    pub spin_softening: bool,
}

/// Where a group of [`crate::model::Spc`] records came from.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintSource {
    /// The card or keyword, e.g. `GRID PS`, `SPC1`, `*BOUNDARY`.
    pub card: String,
    /// The card's id or set, e.g. `GRID 7`, `set 1`.
    pub id: String,
    /// File and 1-based line of the card.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// The set name under which its nodes are available (`SPC_1`), if any.
    pub set: Option<String>,
    /// The records in `Model::spcs` it produced.
    pub spcs: Range<usize>,
    /// A permanent constraint (GRID PS, GRDSET), as opposed to a selected constraint set.
    pub permanent: bool,
}
