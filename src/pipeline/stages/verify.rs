//! Verify: the body as it will be written against the file checks and the constrained model
//! it was reduced from ([`verify_body`]); a violation is an error and nothing is written.

use flexbody_reader::ReducedBody;

use crate::pipeline::plan::Plan;
use crate::pipeline::stages::Constrained;
use crate::pipeline::stages::ReducedBasis;
use crate::pipeline::verify::verify_body;
use crate::pipeline::BuildError;

/// The verify stage: `body` back when it passes.
pub fn verify(
    plan: &Plan,
    body: ReducedBody,
    constrained: &Constrained,
    basis: &ReducedBasis,
) -> Result<ReducedBody, BuildError> {
    let reduced = &constrained.reduced;
    let model = (
        &reduced.k,
        &reduced.m,
        &basis.set.phi,
        &constrained.reference_dofs[..],
    );
    verify_body(&body, Some(model), constrained.expected_rigid.as_ref()).map_err(|failures| {
        BuildError::Verify {
            file: plan.file_name.clone(),
            failures,
        }
    })?;
    Ok(body)
}
