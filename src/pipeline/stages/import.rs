//! Import: the model file → [`Model`], in the format the spec names or its extension says.

use crate::import::{read_model, ImportOptions};
use crate::model::Model;
use crate::pipeline::{BuildError, BuildSpec};

/// Reads `spec.model`.
pub fn import(spec: &BuildSpec) -> Result<Model, BuildError> {
    Ok(read_model(
        &spec.model,
        &ImportOptions {
            format: spec.format,
            material: spec.material.clone(),
            subcase: spec.subcase,
            shell_thickness: spec.thickness,
            ignore_cards: spec.ignore.clone(),
            inp_shells: spec.inp_shells,
        },
    )?)
}
