//! Modal reduction: normal modes, Craig–Bampton (with the improved reference-condition methods of
//! Wang, Niu & Feng 2023), Craig–Chang and Dietz frequency-response modes, mode selection.
//!
//! Every method works on full symmetric sparse (K, M) over one dof numbering plus index lists
//! (interface dofs, reference-condition dofs) and returns a [`ModeSet`]: Φ over all dofs with
//! ΦᵀMΦ = I and ΦᵀKΦ = diag(ω²), a label per mode, and diagnostics that were checked.

pub mod craig_bampton;
pub mod craig_chang;
pub mod dietz;
pub mod eigen_record;
pub mod massless;
pub mod normal;
pub mod orthonormalize;
pub mod participation;
pub mod reference;
pub mod residual;
pub mod select;

use crate::solve::SolveError;
use faer::Mat;
use thiserror::Error;

pub use eigen_record::{EigenProblem, EigenRecord};
pub use orthonormalize::{orthonormalize, Orthonormalized, DEPENDENCY_TOL};

/// The build-report lines of an eigensolution: the solver's own line (`--engine slepc` with
/// its report, `--eigensolver amls` with its largest residual) and a band proven complete by
/// [`crate::solve::EigenSpec::verify_band`] (`problem` names the eigenproblem, e.g.
/// "fixed-interface").
pub(crate) fn band_note(info: &crate::solve::EigenInfo, problem: &str) -> Vec<String> {
    let engine = info.engine_report.clone();
    let band = info.band_proof.map(|(modes, sigma)| {
        format!(
            "band check: the eigensolver's {modes} lowest {problem} modes are all the \
             eigenvalues below {:.10e} Hz (Sylvester inertia count of K - sigma*M)",
            crate::solve::hz(sigma)
        )
    });
    engine.into_iter().chain(band).collect()
}

/// Errors of the reduction methods.
#[derive(Debug, Error)]
pub enum ReduceError {
    /// A factorization or eigensolve failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// A dof index list is invalid.
    #[error("{what}: {detail}")]
    Dofs { what: &'static str, detail: String },
    /// Nothing is left after removing dependent vectors.
    #[error("the reduction basis is empty after removing dependent vectors")]
    EmptyBasis,
    /// The rigid-body modes could not be found or supported.
    #[error("rigid-body modes: {0}")]
    Rigid(String),
    /// Craig–Bampton: K_ii is singular, the interface does not hold the interior.
    #[error(
        "Craig–Bampton: the fixed-interface stiffness K_ii is singular at dof {dof} (pivot/diagonal \
         {pivot:.1e}; its region has {region} dofs): {}",
        if *connected {
            "the interface dofs leave a rigid motion or mechanism of the interior free (e.g. one \
             node with only translational dofs on a solid leaves the rotations free); add \
             interface nodes or attach the interface through an RBE2 spider over a node set"
        } else {
            "this region is not connected to any interface dof; connect it to the rest of the \
             model or put one of its nodes in the interface"
        }
    )]
    UnrestrainedInterior {
        /// The dof (model numbering) of the zero pivot.
        dof: usize,
        /// L_jj² / A_jj there (≤ 0 when the factorization stopped).
        pivot: f64,
        /// Dofs of the interior region (connected through K_ii) that contains it.
        region: usize,
        /// Whether that region touches an interface dof.
        connected: bool,
    },
    /// A free-free analysis found more zero-frequency modes than a free body has.
    #[error(
        "free-free analysis found {zero_modes}{} zero-frequency modes where one free body has 6: \
         the model has disconnected parts or mechanisms (parts joined at a single node or along a \
         line, dofs without stiffness); connect them or build each part as its own body",
        if *at_least { " or more" } else { "" }
    )]
    Mechanism {
        /// Zero modes found.
        zero_modes: usize,
        /// Whether every computed mode was a zero mode (there may be more).
        at_least: bool,
    },
}

/// Errors when a set computed with dofs held (reference conditions) still has zero-frequency
/// modes: the held dofs do not remove all rigid motion, or the model has mechanisms.
pub(crate) fn check_held(set: &ModeSet) -> Result<(), ReduceError> {
    let zero = set
        .labels
        .iter()
        .filter(|l| **l == ModeLabel::Rigid)
        .count();
    if zero > 0 && !set.reference_dofs.is_empty() {
        return Err(ReduceError::Rigid(format!(
            "with the {} reference dofs held, {zero} zero-frequency mode(s) remain: the reference \
             conditions do not remove all rigid motion, or the model has mechanisms; hold 6 \
             independent dofs (e.g. all 6 dofs of one interface node)",
            set.reference_dofs.len()
        )));
    }
    Ok(())
}

/// Rigid-body modes of one free 3-D body.
pub const FREE_BODY_RIGID_MODES: usize = 6;

/// Where a basis vector (or, by its dominant component, a final mode) comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum ModeLabel {
    /// Rigid-body mode (ω² ≈ 0).
    Rigid,
    /// A normal (eigen) mode of the full model, free or constrained.
    Normal,
    /// Craig–Bampton constraint (static) mode of interface dof `dof`.
    Constraint { dof: usize },
    /// Craig–Bampton fixed-interface normal mode number `index`.
    FixedInterface { index: usize },
    /// Craig–Chang inertia-relief attachment mode for a unit load at `dof`.
    Attachment { dof: usize },
    /// Dietz frequency-response mode for a unit load at `dof`.
    FrequencyResponse { dof: usize },
    /// Residual vector: the (inertia-relief balanced) static response to scene load `load`
    /// (index into the build's load list), see [`residual`].
    Residual { load: usize },
}

/// A basis vector removed as dependent by the rank-revealing step.
#[derive(Clone, Debug, PartialEq)]
pub struct RemovedVector {
    /// Column of the basis before orthonormalization.
    pub column: usize,
    /// Its origin.
    pub label: ModeLabel,
    /// Remaining M-norm² of the (diagonally scaled) column after projecting out the kept ones.
    pub remaining: f64,
}

/// Checked quality figures of a mode set.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagnostics {
    /// ‖ΦᵀMΦ − I‖_max against the full M.
    pub orthonormality: f64,
    /// ‖ΦᵀKΦ − diag(ω²)‖_max / max ω² against the full K.
    pub stiffness_diag: f64,
    /// ‖Kφ − ω²Mφ‖/‖Kφ‖ against the full model (small only for exact eigenvectors; for reduced
    /// bases this measures the truncation, not an error).
    pub residuals: Vec<f64>,
    /// Vectors removed as dependent, with the tolerance used.
    pub removed: Vec<RemovedVector>,
    /// Relative pivot tolerance of the rank-revealing step.
    pub dependency_tol: f64,
    /// Massless basis directions (stiffness without mass) condensed statically by the
    /// orthonormalization (not counted in `removed`).
    pub massless_directions: usize,
    /// Massless dofs of the model (zero mass row and column), see [`massless`].
    pub massless_dofs: usize,
    /// Dofs held because a motion of the massless dofs has neither mass nor stiffness (one per
    /// such motion, e.g. the rotation about a line of point masses), see [`massless`].
    pub held_massless: Vec<usize>,
    /// Free-text notes (choices made automatically, e.g. the support dofs).
    pub notes: Vec<String>,
    /// ω² of the highest mode of the method's own eigenproblem: the last fixed-interface mode
    /// (Craig–Bampton) or free-free mode (Craig–Chang, Dietz) in the basis; `None` for normal
    /// modes (their own ω² are exact). Defines the accuracy band of a `--modes N` build.
    pub basis_top_omega2: Option<f64>,
    /// ω² of every fixed-interface mode of a Craig–Bampton basis (the body with its interface
    /// held), ascending; empty for the other methods. In the build report (`--json`).
    pub fixed_interface_omega2: Vec<f64>,
    /// Per mode: the participation share of the origin its label names (see
    /// [`orthonormalize::origin_labels`]); empty = every mode is pure (share 1).
    pub label_shares: Vec<f64>,
    /// The modes' weights on the method's original basis vectors (rows), from which the labels
    /// and shares come; `None` when every mode is its own basis vector (normal modes). Kept so
    /// that a later stage (residual vectors) composes its coefficients with them (SPEC §5.5).
    pub origin: Option<OriginWeights>,
    /// Elastic free-free normal modes in the basis (Craig–Chang, Dietz); `None` otherwise.
    pub basis_normal_modes: Option<usize>,
    /// Residual vectors (static load responses) added to the basis, dependent ones included
    /// (they are also in `removed`), see [`residual`].
    pub residual_vectors: usize,
    /// The method's eigenproblem as its basis took it: eigenvalues, residuals, solver
    /// ([`EigenRecord`]); `None` when no eigenproblem was solved.
    pub eigenproblem: Option<EigenRecord>,
}

/// w_cj = N_cj·√(T_cᵀMT_c): mode j's weight on basis vector T_c (SPEC.md §5.5), one row per
/// basis vector, one column per mode of the set.
#[derive(Clone, Debug, PartialEq)]
pub struct OriginWeights {
    /// The basis vectors' labels (their origin kinds), one per row of `weights`.
    pub basis: Vec<ModeLabel>,
    /// basis × modes.
    pub weights: faer::Mat<f64>,
}

/// Which method produced a mode set.
#[derive(Clone, Debug, PartialEq)]
pub enum Method {
    /// Normal modes with the given dofs fixed (empty = free-free).
    NormalModes,
    /// Craig–Bampton with interface dofs.
    CraigBampton {
        interface: Vec<usize>,
        fixed_interface_modes: usize,
    },
    /// Improved Craig–Bampton, Wang et al. 2023 §5.1 (reference columns removed from Φ_CB).
    ImprovedCraigBampton1 {
        interface: Vec<usize>,
        fixed_interface_modes: usize,
    },
    /// Improved Craig–Bampton, Wang et al. 2023 §5.2 (reference conditions imposed on K, M).
    ImprovedCraigBampton2 {
        interface: Vec<usize>,
        fixed_interface_modes: usize,
    },
    /// Craig–Chang with inertia-relief attachment modes at the given dofs.
    CraigChang {
        attachment: Vec<usize>,
        support: Vec<usize>,
    },
    /// Dietz frequency-response modes (static procedure), shift ℓ.
    Dietz { attachment: Vec<usize>, shift: f64 },
    /// Dietz modified procedure from an extended free-free set of `extended` modes, shift ℓ.
    DietzModified {
        attachment: Vec<usize>,
        shift: f64,
        extended: usize,
    },
}

/// A mass-orthonormal mode set over all dofs of the model it was computed from.
#[derive(Clone, Debug)]
pub struct ModeSet {
    /// Φ, n × modes, ΦᵀMΦ = I.
    pub phi: Mat<f64>,
    /// ω² per mode, ascending.
    pub omega2: Vec<f64>,
    /// Label per mode (rigid, or the dominant origin of the mode).
    pub labels: Vec<ModeLabel>,
    /// The producing method.
    pub method: Method,
    /// Dofs held at zero (reference conditions / constraints) that define the body frame.
    pub reference_dofs: Vec<usize>,
    /// The selection applied (set by [`select`]).
    pub selection: Option<select::Selection>,
    /// Checked diagnostics.
    pub diagnostics: Diagnostics,
}

impl ModeSet {
    /// Frequencies in Hz (negative ω² rounding noise maps to 0).
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.omega2.iter().map(|&l| crate::solve::hz(l)).collect()
    }

    /// Number of modes.
    pub fn len(&self) -> usize {
        self.omega2.len()
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.omega2.is_empty()
    }
}

/// Checks a dof list against n: in range and without duplicates.
pub(crate) fn check_dofs(what: &'static str, dofs: &[usize], n: usize) -> Result<(), ReduceError> {
    let mut seen = vec![false; n];
    for &d in dofs {
        if d >= n {
            return Err(ReduceError::Dofs {
                what,
                detail: format!("dof {d} out of range (n = {n})"),
            });
        }
        if seen[d] {
            return Err(ReduceError::Dofs {
                what,
                detail: format!("dof {d} listed twice"),
            });
        }
        seen[d] = true;
    }
    Ok(())
}
