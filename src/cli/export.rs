//! `flexbody export`: a file to another solver's format, or with `--to mtx` the constrained
//! matrices of the build that made it.
use std::path::PathBuf;

use super::args::{model_overrides, ModelArgs};

/// What `flexbody export` was given besides the file and the target.
pub(crate) struct ExportArgs<'a> {
    pub(crate) output: &'a std::path::Path,
    pub(crate) model: Option<&'a PathBuf>,
    pub(crate) model_args: &'a ModelArgs,
    pub(crate) mass: Option<&'a str>,
}

/// Runs `flexbody export`.
pub(crate) fn command(file: &PathBuf, to: &str, a: ExportArgs) -> anyhow::Result<()> {
    use anyhow::Context;
    let output = a.output;
    let target = crate::export::Target::from_name(to)
        .ok_or_else(|| anyhow::anyhow!("--to {to}: expected exudyn, mbdyn, sid, vtu or mtx"))?;
    let body = flexbody_reader::read(file)
        .map_err(flexbody_reader::ReadError::named)
        .with_context(|| format!("{} is not a valid flexbody file", file.display()))?;
    // every target, before any work: the output's folder must exist
    if target == crate::export::Target::Mtx {
        // mtx writes into a folder of its own, made inside an existing one
        let parent = output.parent().filter(|p| !p.as_os_str().is_empty());
        if let Some(p) = parent.filter(|p| !p.is_dir()) {
            anyhow::bail!(
                "cannot write {}: its folder {} does not exist",
                output.display(),
                p.display()
            );
        }
        let model = a.model.ok_or_else(|| {
            anyhow::anyhow!(
                "--to mtx writes the FE model's K and M, which the file does not hold: give the \
                 model it was built from with --model MODEL (its recipe says how it was built)"
            )
        })?;
        let mass = a
            .mass
            .map(crate::pipeline::options::parse_mass)
            .transpose()?;
        let written = crate::pipeline::matrices::export_body_matrices(
            &body,
            model,
            model_overrides(a.model_args)?,
            mass,
            output,
        )
        .with_context(|| format!("cannot export the matrices of {}", model.display()))?;
        eprintln!(
            "flexbody: wrote {}",
            written
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
        return Ok(());
    }
    if let Some(model) = a.model {
        anyhow::bail!(
            "--model {}: only --to mtx reads the model; {to} is exported from the file alone",
            model.display()
        );
    }
    if let Some(mass) = a.mass {
        anyhow::bail!("--mass {mass}: only --to mtx writes a mass matrix");
    }
    a.model_args
        .refuse_without_model(&format!("--to {to} (exported from the file alone)"))?;
    crate::write::check_output_path(output)?;
    let summary = crate::export::export(&body, target, output)?;
    for n in &summary.notes {
        eprintln!("flexbody: note: {n}");
    }
    eprintln!(
        "flexbody: wrote {} — {} flexible modes, {} nodes",
        output.display(),
        summary.modes,
        summary.nodes
    );
    Ok(())
}
