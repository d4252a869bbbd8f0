//! Preload: the deck's preload request (a CalculiX `*STATIC` step before a `*STEP,
//! PERTURBATION` / `*FREQUENCY`) — refused until the stage honours it, so a preloaded deck is
//! never built as the unloaded body.

use crate::pipeline::plan::Plan;
use crate::pipeline::stages::interfaces::WithInterfaces;
use crate::pipeline::BuildError;

/// The preload stage: an error naming the deck's preload (file, line, keyword) when it has one.
pub fn preload(plan: &Plan, interfaced: &WithInterfaces) -> Result<(), BuildError> {
    match &interfaced.model.deck.preload {
        None => Ok(()),
        Some(request) => Err(plan.request_error(format!(
            "{}: {} preloads the modes of the *FREQUENCY, PERTURBATION step: a preloaded modal analysis is not supported yet (the unloaded body's modes would differ)",
            request.problem.as_deref().unwrap_or(&request.first_load),
            request.source
        ))),
    }
}
