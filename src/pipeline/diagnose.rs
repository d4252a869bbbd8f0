//! Solver failures in the model's terms (issue 20): a factorization or eigensolve that fails
//! deep in the reduction ("K − σM is not positive definite for σ = …", a zero pivot, a
//! non-finite value) or a free-free solve that finds a mechanism is reported with the model file
//! and, where the cause is knowable from the model alone, the material that makes it so: an
//! implausible material (wave speed, ν, sign of E — [`crate::import::plausibility`]) or a
//! stiffness contrast between materials beyond what double precision separates. The connected
//! parts are judged before the reduction ([`crate::pipeline::precheck`]); what reaches here is what that
//! check cannot see.

use crate::model::Model;
use crate::pipeline::BuildError;
use crate::reduce::ReduceError;
use crate::solve::SolveError;

/// Stiffness contrast (largest E / smallest E) above which a failed solve names the two
/// materials: beyond ~1e8 the soft part's modes are lost in the stiff part's rounding
/// ([`crate::pipeline::precheck::MAX_CONTRAST`] refuses contrasts between connected parts above it).
pub const CONTRAST_HINT: f64 = 1e6;

/// What a failed solve is explained with: taken from the model before the build consumes it
/// (materials only: cheap for any model size).
#[derive(Debug, Clone)]
pub struct SolverContext {
    file: String,
    /// Implausible materials, one message each.
    implausible: Vec<String>,
    /// (name, E) of the stiffest and softest materials with E > 0.
    extremes: Option<((String, f64), (String, f64))>,
}

impl SolverContext {
    /// The context of `model`.
    pub fn of(model: &Model) -> SolverContext {
        let implausible = crate::import::plausibility::material_warnings(model, &model.source)
            .into_iter()
            .map(|w| w.message)
            .collect();
        let used: Vec<&crate::model::Material> =
            model.materials.iter().filter(|m| m.e > 0.0).collect();
        let extremes = used
            .iter()
            .max_by(|a, b| a.e.total_cmp(&b.e))
            .zip(used.iter().min_by(|a, b| a.e.total_cmp(&b.e)))
            .map(|(hi, lo)| ((hi.name.clone(), hi.e), (lo.name.clone(), lo.e)));
        SolverContext {
            file: model.source.clone(),
            implausible,
            extremes,
        }
    }

    /// The likely cause in the model's terms, or `None` when the model shows none.
    fn cause(&self) -> Option<String> {
        let mut why = self.implausible.clone();
        if let Some(((hi, e_hi), (lo, e_lo))) = &self.extremes {
            if e_hi / e_lo > CONTRAST_HINT {
                why.push(format!(
                    "material {hi} (E = {e_hi:e}) is {:.1e} times stiffer than material {lo} \
                     (E = {e_lo:e}): beyond ~{CONTRAST_HINT:.0e} the soft part's modes drown in \
                     the stiff part's rounding",
                    e_hi / e_lo
                ));
            }
        }
        (!why.is_empty()).then(|| why.join("; "))
    }

    /// A reduction error with the model file, and the likely cause when it is a solver failure
    /// or a mechanism; any other error unchanged.
    pub fn explain(&self, err: BuildError) -> BuildError {
        let BuildError::Reduce(e) = &err else {
            return err;
        };
        let hint = match e {
            ReduceError::Solve(
                SolveError::NotPositiveDefinite { .. }
                | SolveError::NonPositivePivot { .. }
                | SolveError::NonFinite(_)
                | SolveError::NotConverged { .. }
                | SolveError::CheckFailed { .. },
            ) => match self.cause() {
                Some(c) => format!("likely cause: {c}"),
                None => "no material is implausible and their stiffness contrast is moderate: \
                         look for distorted or inverted elements (a negative volume), \
                         zero-thickness or zero-area sections, or parts held only through \
                         stiffness-free dofs"
                    .to_owned(),
            },
            ReduceError::Mechanism { .. } => match self.cause() {
                Some(c) => format!("the materials may contribute: {c}"),
                None => return self.with_file(err),
            },
            _ => return self.with_file(err),
        };
        BuildError::Request {
            file: self.file.clone(),
            message: format!("{e} — {hint}"),
        }
    }

    fn with_file(&self, err: BuildError) -> BuildError {
        BuildError::Request {
            file: self.file.clone(),
            message: err.to_string(),
        }
    }
}
