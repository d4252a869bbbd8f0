//! Assembly: K and M of the model with its spiders (lumped or consistent mass, [`assemble`]),
//! and the summary of the constraints the model applies, for the report.

use crate::fe::rigid_mass;
use crate::fe::{assemble, Assembled, MassKind};
use crate::pipeline::deck::constraint_summary;
use crate::pipeline::plan::Plan;
use crate::pipeline::stages::WithInterfaces;
use crate::pipeline::{BuildError, BuildReport};

/// The assembly stage.
pub fn assembly(
    plan: &Plan,
    interfaced: &WithInterfaces,
    report: &mut BuildReport,
) -> Result<Assembled, BuildError> {
    let assembled = assemble(&interfaced.model, &plan.assembly)?;
    report.constraints = constraint_summary(&interfaced.model, &assembled.dofs);
    if plan.assembly.mass == MassKind::Lumped {
        // the file's rigid-body inertia is the lumped mass's: say when it is off the exact one
        // (a model the consistent element matrices refuse keeps the lumped mass's silently)
        if let Ok(cmp) = rigid_mass::compare(&interfaced.model, &plan.assembly) {
            report
                .warnings
                .extend(rigid_mass::warning(&cmp, LUMPED_INERTIA_LIMIT));
        }
    }
    Ok(assembled)
}

/// The relative difference of the lumped mass's rigid-body properties (mass, centre, principal
/// inertia) from the consistent mass's beyond which the build warns (issue 47).
pub const LUMPED_INERTIA_LIMIT: f64 = 0.01;
