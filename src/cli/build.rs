//! `flexbody build`: the pipeline with progress on stderr, the file written, the report printed
//! (text on stderr, or `--json` on stdout).

use super::args::{build_spec, BuildArgs};
use super::progress::StageProgress;
use crate::pipeline::BuildOutput;

/// Runs `flexbody build`.
pub(crate) fn command(a: &BuildArgs) -> anyhow::Result<()> {
    use anyhow::Context;
    let spec = build_spec(a)?;
    if let Some(d) = &a.damping {
        // refuse a bad value before the build (the pipeline applies it, spec.damping)
        crate::body::damping::parse_damping(d)?;
    }
    if let Some(limit) = &a.max_memory {
        // Read by the solve layer right before each factorization; errors name the flag.
        crate::solve::cholesky::set_memory_limit_flag(limit)?;
    }
    // Refuse an unusable -o (a folder, a missing folder, no permission) before the build.
    crate::write::check_output_path(&a.output)?;
    let mut progress = StageProgress::new(a.quiet || a.json);
    let mut run = || -> anyhow::Result<BuildOutput> {
        let out = crate::pipeline::build_reporting(&spec, &mut |stage| progress.stage(stage))
            .map_err(|f| {
                // what the stages found before the failure is often its cause: print it too
                print_findings(&f.warnings, &f.notes);
                f.error
            })
            .with_context(|| format!("cannot build {}", a.model.display()))?;
        progress.stage("write");
        crate::write::write_reduced_body(&a.output, &out.body, &Default::default())?;
        if let (Some(dir), Some(sys)) = (&a.write_matrices, &out.constrained_system) {
            let source = crate::pipeline::matrices::source_name(&spec.model);
            crate::write::mtx::write_matrices(dir, sys, &source)?;
        }
        Ok(out)
    };
    let result = run();
    progress.finish();
    let out = result?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&json_report(a, &out))?);
    } else if !a.quiet {
        print_report(a, &out);
    } else {
        // quiet: no progress, notes or summary — but a warning is never silent
        print_findings(&out.report.warnings, &[]);
    }
    Ok(())
}

/// The `--json` report on stdout.
fn json_report(a: &BuildArgs, out: &BuildOutput) -> serde_json::Value {
    let r = &out.report;
    serde_json::json!({
        "output": a.output.display().to_string(),
        "dofs": r.dofs.0,
        "independent_dofs": r.dofs.1,
        "modes": out.body.mode_count(),
        "frequency_hz": out.body.modes.frequency_hz,
        // Craig–Bampton: the body with its interface held (empty for the other methods)
        "fixed_interface_hz": r.diagnostics.fixed_interface_omega2.iter()
            .map(|&w2| crate::solve::hz(w2)).collect::<Vec<_>>(),
        "stages_s": r.stages.iter().map(|(k, v)| (k.clone(), *v)).collect::<std::collections::BTreeMap<_, _>>(),
        "interfaces": r.interfaces.iter().map(|i| serde_json::json!({
            "entry": i.entry,
            "nodes": i.nodes.len(),
            "spider_centre": i.spider.as_ref().map(|s| s.centre),
            "spider_centre_node": i.spider.as_ref().map(|s| s.centre_node_id),
            "offset_from_node_average": i.spider.as_ref().map(|s| s.offset_from_node_average),
        })).collect::<Vec<_>>(),
        "orthonormality": r.diagnostics.orthonormality,
        "removed_dependent": r.diagnostics.removed.len(),
        "warnings": r.warnings,
        "notes": r.diagnostics.notes,
        "deck": r.notes,
        "constraints": r.constraints,
        // VmHWM of this process: the whole build, file writing included
        "peak_memory_mb": crate::solve::memory::peak_resident_bytes()
            .map(|b| b as f64 / 1048576.0),
    })
}

/// Warnings and notes on stderr. The reduction's phase times ("time factorization: …") are in
/// `--json`'s notes only: the stage lines already showed the time of each stage.
fn print_findings(warnings: &[String], notes: &[String]) {
    for w in warnings {
        eprintln!("flexbody: warning: {w}");
    }
    for n in notes.iter().filter(|n| !n.starts_with("time ")) {
        eprintln!("flexbody: note: {n}");
    }
}

/// The report on stderr: warnings, notes, constraints, spiders, sizes and the first modes.
fn print_report(a: &BuildArgs, out: &BuildOutput) {
    let r = &out.report;
    let notes: Vec<String> = r
        .notes
        .iter()
        .chain(&r.diagnostics.notes)
        .cloned()
        .collect();
    print_findings(&r.warnings, &notes);
    for c in &r.constraints {
        eprintln!("flexbody: constraint: {c}");
    }
    for i in &r.interfaces {
        if let Some(s) = &i.spider {
            eprintln!(
                "flexbody: interface {}: {} nodes → centre node {} at ({:.6e}, {:.6e}, {:.6e}) by {:?} ({:.3e} {} from the node average)",
                i.entry, s.set_nodes, s.centre_node_id, s.centre[0], s.centre[1], s.centre[2], s.method, s.offset_from_node_average,
                out.body.units.length.name
            );
        }
    }
    eprintln!(
        "flexbody: {} dofs ({} independent); total {:.2} s",
        r.dofs.0,
        r.dofs.1,
        r.stages.iter().map(|(_, t)| t).sum::<f64>()
    );
    let f = &out.body.modes.frequency_hz;
    eprintln!(
        "flexbody: wrote {} — {} modes ({} rigid), {} nodes; first flexible modes: {}",
        a.output.display(),
        f.len(),
        out.body.method.counts.rigid,
        out.body.node_count(),
        f.iter()
            .zip(&out.body.modes.labels)
            .filter(|(_, l)| **l != flexbody_reader::ModeLabel::Rigid)
            .take(6)
            .map(|(f, _)| format!("{f:.2} Hz"))
            .collect::<Vec<_>>()
            .join(", ")
    );
}
