//! The `amls` suite: AMLS (`solve::amls`, cutoff factor swept) and our Lanczos on the eigen
//! suite's clamped tet10 block (same K, M), each in its own process (peak memory per run):
//! wall time, peak memory, the largest relative eigenvalue error against Lanczos over the
//! lowest min(N, 100) and over all N, the largest per-mode residual, and the Sylvester count.

use std::time::Instant;

use flexbody::solve::amls::{amls, AmlsParams};
use flexbody::solve::{EigenMethod, EigenSpec};
use serde_json::{json, Value};

use crate::suites::{eigen_system, eigenvalues, read_full_mtx, threads, EigenSystem};
use crate::{loadavg, max_rel_diff, num, peak_rss_mb, run_self, write_result, Res};

/// `ours-amls K.mtx M.mtx MODES CUTOFF [REFINE [LEAF]]`: AMLS on the files (one JSON line).
pub fn ours_amls(
    kp: &str,
    mp: &str,
    modes: usize,
    cutoff: f64,
    refine: Option<usize>,
    leaf: Option<usize>,
) -> Res<Value> {
    let (k, m) = (read_full_mtx(kp)?, read_full_mtx(mp)?);
    let params = AmlsParams {
        cutoff_factor: cutoff,
        refine: refine.unwrap_or(flexbody::solve::amls::DEFAULT_REFINE),
        leaf_dofs: leaf.unwrap_or(flexbody::solve::amls::DEFAULT_LEAF_DOFS),
    };
    let spec = EigenSpec {
        count: modes,
        shift: None,
        dofs_per_node: Some(3),
        par: threads(),
        method: EigenMethod::Amls(params),
        ..Default::default()
    };
    let t = Instant::now();
    let s = amls(&k, &m, &spec, &params).map_err(|e| e.to_string())?;
    let total = t.elapsed().as_secs_f64();
    let r = &s.report;
    let p = &r.profile;
    let profile = json!({
        "leaf_pencils": p.leaf_pencils.get(), "leaf_s": p.leaf_seconds.get(),
        "factorizations": p.factorizations.get(), "factor_gflop": p.factor_flops.get() / 1e9,
        "factor_s": p.factor_seconds.get(),
        "solved_columns": p.solved_columns.get(), "solve_s": p.solve_seconds.get(),
        "basis_gflop": p.basis_flops.get() / 1e9, "basis_s": p.basis_seconds.get(),
        "split_pencils": p.split_pencils.get(), "largest_pencil": p.largest_pencil.get(),
        "pencil_cubes_g": p.pencil_cubes.get() / 1e9, "pencil_s": p.pencil_seconds.get(),
        "refine_factor_s": p.refine_factor_seconds.get(),
        "refine_columns": p.refine_columns.get(), "refine_solve_s": p.refine_solve_seconds.get(),
        "ritz_s": p.ritz_seconds.get(),
    });
    Ok(json!({
        "n": k.nrows(),
        "cutoff_factor": cutoff,
        "refine": params.refine,
        "leaf_dofs": params.leaf_dofs,
        "seconds": total,
        "phases_s": {"substructures": r.seconds_reduce, "refine_and_ritz": r.seconds_ritz,
                     "inertia": r.seconds_inertia},
        "profile": profile,
        "leaves": r.leaves, "largest_leaf": r.largest_leaf, "separator_dofs": r.separator_dofs,
        "depth": r.depth, "root_modes": r.root_modes, "cutoff_omega2": num(r.cutoff),
        "band_top": num(r.band_top), "count_below_top": r.below_top,
        "returned_below_top": r.returned_below_top, "missing": s.missing(),
        "orthonormality": num(s.solution.info.orthonormality),
        "stiffness_diag": num(s.solution.info.stiffness_diag),
        "max_residual": num(s.solution.residuals.iter().copied().fold(0.0, f64::max)),
        "residuals": s.solution.residuals,
        "peak_rss_mb": peak_rss_mb(),
        "eigenvalues": s.solution.eigenvalues,
        "threads": format!("faer {:?}", threads()),
        "loadavg": loadavg(),
    }))
}

/// The suite: Lanczos for `lanczos_modes` modes (none: not run) then AMLS for each cutoff
/// factor; the errors are over the modes both computed.
pub fn run(
    n: [usize; 3],
    modes: usize,
    cutoffs: &[f64],
    lanczos_modes: Option<usize>,
) -> Res<Value> {
    let EigenSystem { dofs, kp, mp, .. } = eigen_system(n)?;
    let (kp, mp) = (kp.display().to_string(), mp.display().to_string());
    let load_before = loadavg();
    let lanczos = match lanczos_modes {
        Some(lm) => Some(run_self(&[
            "ours-eigen".into(),
            kp.clone(),
            mp.clone(),
            lm.to_string(),
        ])?),
        None => None,
    };
    let compared = lanczos_modes.unwrap_or(modes).min(modes);
    let exact = lanczos.as_ref().map(eigenvalues);
    let lanczos_s = lanczos.as_ref().and_then(|l| {
        Some(l["phases_s"]["analyse_factor"].as_f64()? + l["phases_s"]["eigen"].as_f64()?)
    });
    let mut rows = Vec::new();
    let mut runs = Vec::new();
    for &c in cutoffs {
        let r = run_self(&[
            "ours-amls".into(),
            kp.clone(),
            mp.clone(),
            modes.to_string(),
            c.to_string(),
        ])?;
        let vals = eigenvalues(&r);
        let err = |count: usize| {
            exact
                .as_ref()
                .and_then(|e| max_rel_diff(&vals, e, count.min(compared)))
                .map(num)
        };
        let secs = r["seconds"].as_f64().unwrap_or(f64::NAN);
        rows.push(json!({
            "cutoff_factor": c,
            "seconds": num(secs),
            "lanczos_over_amls": lanczos_s.map(|l| num(l / secs)),
            "peak_rss_mb": r["peak_rss_mb"],
            "max_rel_error_lowest_100": err(100),
            "max_rel_error_all": err(modes),
            "max_residual": r["max_residual"],
            "count_below_top": r["count_below_top"],
            "returned_below_top": r["returned_below_top"],
            "missing": r["missing"],
            "root_modes": r["root_modes"],
        }));
        runs.push(r);
    }
    let json = json!({
        "suite": "amls",
        "version": 2,
        "construction": "one factorization per split in the tree's order, half solves (docs/amls.md)",
        "model": format!("tet10 block {}x{}x{} bricks, x=0 clamped, consistent mass (the eigen suite's K, M)", n[0], n[1], n[2]),
        "dofs": dofs,
        "modes": modes,
        "lanczos_modes": lanczos_modes,
        "lanczos_seconds": lanczos_s.map(num),
        "lanczos_peak_rss_mb": lanczos.as_ref().map(|l| l["peak_rss_mb"].clone()),
        "loadavg_before": load_before,
        "loadavg_after": loadavg(),
        "rows": rows,
        "lanczos": lanczos,
        "amls": runs,
    });
    write_result(&format!("amls_{dofs}_{modes}modes_v2.json"), &json)?;
    Ok(json)
}

/// `docs/amls_error_vs_time.svg`: per mode count a panel of the largest relative eigenvalue
/// error against Lanczos (all N modes) over wall time, one AMLS series per model size (points
/// labelled by the cutoff factor F) and Lanczos's time drawn at its 1e-10 tolerance.
pub fn chart(runs: &[Value], path: &std::path::Path) -> Res<()> {
    use crate::chart::{err, panel, Series};
    use plotters::prelude::*;
    let mut counts: Vec<u64> = runs.iter().filter_map(|v| v["modes"].as_u64()).collect();
    counts.sort_unstable();
    counts.dedup();
    let root = SVGBackend::new(path, (700 * counts.len().max(1) as u32, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let areas = root.split_evenly((1, counts.len().max(1)));
    for (area, &modes) in areas.iter().zip(&counts) {
        let mut series: Vec<Series> = Vec::new();
        let mut loads = Vec::new();
        for v in runs.iter().filter(|v| v["modes"].as_u64() == Some(modes)) {
            let dofs = v["dofs"].as_u64().unwrap_or(0);
            loads.push(format!("{}", v["loadavg_before"][0]));
            let pts = (v["rows"].as_array().into_iter().flatten())
                .filter_map(|r| {
                    Some((
                        r["seconds"].as_f64()?,
                        r["max_rel_error_all"].as_f64()?.max(1e-15),
                        format!("F={}", r["cutoff_factor"].as_f64()?),
                    ))
                })
                .collect();
            series.push((format!("AMLS {}k dofs", dofs / 1000), pts));
            if let Some(t) = v["lanczos_seconds"].as_f64() {
                series.push((
                    format!("Lanczos {}k dofs", dofs / 1000),
                    vec![(t, 1e-10, "Lanczos".into())],
                ));
            }
        }
        panel(
            area,
            &format!(
                "AMLS vs Lanczos, {modes} modes (1 thread, load {})",
                loads.join("/")
            ),
            "wall time (s)",
            "max rel. eigenvalue error",
            &series,
            SeriesLabelPosition::LowerRight,
        )?;
    }
    root.present().map_err(err)?;
    Ok(())
}
