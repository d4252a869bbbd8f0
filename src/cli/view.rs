//! `flexbody view`: a file's modes as one self-contained HTML page ([`crate::export::view`]).
use std::path::Path;

/// Runs `flexbody view`.
pub(crate) fn command(file: &Path, output: &Path) -> anyhow::Result<()> {
    use anyhow::Context;
    // the output's folder first, as every command checks it (issue 31)
    crate::write::check_output_path(output)?;
    let body = flexbody_reader::read(file)
        .map_err(flexbody_reader::ReadError::named)
        .with_context(|| format!("{} is not a valid flexbody file", file.display()))?;
    let summary = crate::export::view::export_view(&body, output)?;
    eprintln!(
        "flexbody: wrote {} — {} modes, {} nodes drawn",
        output.display(),
        summary.modes,
        summary.nodes
    );
    Ok(())
}
