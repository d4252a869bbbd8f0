//! `flexbody check`: the report of [`crate::pipeline::check`], printed (text, or `--json`).

use super::args::{model_overrides, CheckArgs};
use crate::pipeline::check::check;

/// Runs `flexbody check`: prints the report (text, or `--json`); `Ok(false)` when a check
/// failed.
pub(crate) fn command(a: &CheckArgs) -> anyhow::Result<bool> {
    use anyhow::Context;
    let body = flexbody_reader::read(&a.file)
        .map_err(flexbody_reader::ReadError::named)
        .with_context(|| format!("{} is not a valid flexbody file", a.file.display()))?;
    let model = match &a.model {
        None => {
            a.model_args.refuse_without_model("check without --model")?;
            None
        }
        Some(path) => Some(crate::pipeline::recipe::model_input(
            body.recipe.as_ref(),
            path.clone(),
            model_overrides(&a.model_args)?,
        )?),
    };
    let report = check(&body, model.as_ref())?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        for i in &report.items {
            // an item without a limit is a figure for information, not a check
            let (tag, limit) = match (i.limit.is_finite(), i.pass) {
                (false, _) => ("info", "(no limit) ".to_string()),
                (true, true) => ("ok  ", format!("(limit {:.1e})", i.limit)),
                (true, false) => ("FAIL", format!("(limit {:.1e})", i.limit)),
            };
            println!(
                "{tag} {:<52} {:>12.3e} {limit}  {}",
                i.name, i.value, i.detail
            );
        }
        for s in &report.skipped {
            println!("skip {s}");
        }
        let failed = report.items.iter().filter(|i| !i.pass).count();
        println!(
            "{} checks, {} failed: {}",
            report.items.iter().filter(|i| i.limit.is_finite()).count(),
            failed,
            if failed == 0 { "PASS" } else { "FAIL" }
        );
    }
    Ok(report.passed())
}
