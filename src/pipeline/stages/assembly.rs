//! Assembly: K and M of the model with its spiders (lumped or consistent mass, [`assemble`]),
//! and the summary of the constraints the model applies, for the report.

use crate::fe::{assemble, Assembled};
use crate::pipeline::deck::constraint_summary;
use crate::pipeline::plan::Plan;
use crate::pipeline::stages::interfaces::WithInterfaces;
use crate::pipeline::{BuildError, BuildReport};

/// The assembly stage.
pub fn assembly(
    plan: &Plan,
    interfaced: &WithInterfaces,
    report: &mut BuildReport,
) -> Result<Assembled, BuildError> {
    let assembled = assemble(&interfaced.model, &plan.assembly)?;
    report.constraints = constraint_summary(&interfaced.model, &assembled.dofs);
    Ok(assembled)
}
