//! What a build tells: the [`BuildReport`] beside the body, the [`BuildError`] instead of one,
//! and the names of the [`Stage`]s that progress and timing are reported by.

use flexbody_reader as file;

use crate::fe;
use crate::import;
use crate::pipeline::interface::InterfaceReport;
use crate::reduce;

/// What happened, for the user.
#[derive(Debug, Clone, Default)]
pub struct BuildReport {
    /// (stage, seconds).
    pub stages: Vec<(String, f64)>,
    /// Interfaces and spiders.
    pub interfaces: Vec<InterfaceReport>,
    /// Import warnings and pipeline notes.
    pub warnings: Vec<String>,
    /// Number of physical and independent dofs.
    pub dofs: (usize, usize),
    /// Checked diagnostics of the mode set.
    pub diagnostics: reduce::Diagnostics,
    /// What the build took from the deck (mass, mode count, interface, subcase), and
    /// constraint components dropped from interface/reference nodes.
    pub notes: Vec<String>,
    /// Every applied constraint: card, line, set, dofs held.
    pub constraints: Vec<crate::pipeline::deck::ConstraintSummary>,
}

/// A built body with its report.
#[derive(Debug, Clone)]
pub struct BuildOutput {
    /// The reduced body, ready to write.
    pub body: file::ReducedBody,
    /// What was done.
    pub report: BuildReport,
    /// The constrained K_r, M_r the reduction started from, with their dof table
    /// (`BuildSpec::constrained_system`, `--write-matrices`).
    pub constrained_system: Option<crate::write::mtx::ConstrainedSystem>,
}

/// Errors of the pipeline; each names the file and the entity.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// Import failed.
    #[error(transparent)]
    Import(#[from] import::ImportError),
    /// Interface resolution failed.
    #[error(transparent)]
    Interface(#[from] crate::pipeline::interface::InterfaceError),
    /// Assembly or constraint elimination failed.
    #[error(transparent)]
    Fe(#[from] fe::FeError),
    /// The reduction failed.
    #[error(transparent)]
    Reduce(#[from] reduce::ReduceError),
    /// The preload stage failed (its static solve, or the preload buckles the part).
    #[error(transparent)]
    Preload(fe::preload::PreloadError),
    /// Invariants could not be formed.
    #[error(transparent)]
    Invariants(#[from] crate::body::invariants::InvariantError),
    /// Stress/strain shapes could not be recovered.
    #[error(transparent)]
    Fields(#[from] crate::body::stress::StressError),
    /// `--damping` does not fit the body's modes (or is no damping specification).
    #[error(transparent)]
    Damping(#[from] crate::body::damping::DampingError),
    /// The built body failed its own verification (nothing was written).
    #[error("{file}: {failures}")]
    Verify {
        /// Model file.
        file: String,
        /// The failed checks.
        failures: crate::pipeline::verify::VerifyError,
    },
    /// The request does not fit the model.
    #[error("{file}: {message}")]
    Request {
        /// Model file.
        file: String,
        /// What is wrong and what to do.
        message: String,
    },
}

/// Stages reported to the progress callback, in order.
pub const STAGES: [&str; 11] = [
    "import",
    "interfaces",
    "assembly",
    "constraints",
    "preload",
    "reduction",
    "invariants",
    "geometric stiffness",
    "stress shapes",
    "assemble file",
    "verify",
];

/// One stage of the pipeline, in order ([`STAGES`] holds their names).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Model file → [`crate::model::Model`].
    Import,
    /// Interface entries → interface nodes and spiders.
    Interfaces,
    /// K and M of the model.
    Assembly,
    /// Elimination u = T u_r, interface and reference dofs, the checks before the reduction.
    Constraints,
    /// The preload's static solve and K_T = K + K_G (only when the build has a preload).
    Preload,
    /// The mode set.
    Reduction,
    /// Mass points and the inertia invariants.
    Invariants,
    /// The modal geometric stiffness per unit inertia load (only when asked).
    GeometricStiffness,
    /// Modal stress/strain shapes (only when asked).
    StressShapes,
    /// The file's records.
    AssembleFile,
    /// The body against the file checks and the model it was reduced from.
    Verify,
}

impl Stage {
    /// The name reported to the progress callback and in [`BuildReport::stages`].
    pub fn name(self) -> &'static str {
        STAGES[self as usize]
    }
}
