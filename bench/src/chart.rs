//! `harness chart`: regenerates, from the JSON in `bench/results/`, the two charts under `docs/`
//! and the tables of `docs/benchmarks.md`:
//!
//! * `docs/accuracy_vs_time.svg` — wall time (x, log) against frequency error and interface
//!   static error (y, log), one series per method, points labelled by mode count;
//! * `docs/scaling.svg` — time and peak memory against dofs (log–log), ours and the peers.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use plotters::prelude::*;
use serde_json::{json, Value};

use crate::{results_dir, Res};

/// Errors below this are drawn on this floor (exact to rounding).
const FLOOR: f64 = 1e-15;

fn docs_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs")
}

fn load(prefix: &str) -> Res<Vec<Value>> {
    let mut out = Vec::new();
    let dir = results_dir();
    let rd = std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for e in rd.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        if name.starts_with(prefix) && name.ends_with(".json") {
            let text = std::fs::read_to_string(e.path()).map_err(|e| e.to_string())?;
            let v: Value = serde_json::from_str(&text).map_err(|err| format!("{name}: {err}"))?;
            // other benchmarks' files share prefixes (cb_pipeline_*): only this suite's
            if v["suite"].as_str() == Some(prefix.trim_end_matches('_')) {
                out.push(v);
            }
        }
    }
    out.sort_by_key(|v| {
        (
            v["dofs"].as_u64().unwrap_or(0),
            v["modes"].as_u64().unwrap_or(0),
        )
    });
    Ok(out)
}

pub(crate) fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("chart: {e:?}")
}

fn color(i: usize) -> RGBColor {
    const C: [RGBColor; 7] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(23, 190, 207),
    ];
    C[i % C.len()]
}

pub(crate) type Series = (String, Vec<(f64, f64, String)>);

fn bounds(series: &[Series]) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (_, pts) in series {
        for &(x, y, _) in pts {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if x0 > x1 {
        return ((0.1, 10.0), (0.1, 10.0));
    }
    ((x0 / 1.5, x1 * 1.5), (y0 / 3.0, y1 * 3.0))
}

/// 1-2-5 ticks per decade inside [a, b].
fn key_points(a: f64, b: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut d = 10f64.powf(a.log10().floor());
    while d <= b {
        for m in [1.0, 2.0, 5.0] {
            let v = m * d;
            if v >= a && v <= b {
                out.push(v);
            }
        }
        d *= 10.0;
    }
    out
}

/// 20000 → "20k", 0.5 → "0.5".
fn short(v: f64) -> String {
    if v >= 1e6 {
        format!("{}M", v / 1e6)
    } else if v >= 1e3 {
        format!("{}k", v / 1e3)
    } else {
        format!("{}", (v * 1e3).round() / 1e3)
    }
}

pub(crate) fn panel(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    title: &str,
    xdesc: &str,
    ydesc: &str,
    series: &[Series],
    legend: SeriesLabelPosition,
) -> Res<()> {
    let ((x0, x1), (y0, y1)) = bounds(series);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(
            (x0..x1).log_scale().with_key_points(key_points(x0, x1)),
            (y0..y1).log_scale(),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(xdesc)
        .y_desc(ydesc)
        .light_line_style(RGBColor(235, 235, 235))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| short(*v))
        .draw()
        .map_err(err)?;
    for (i, (name, pts)) in series.iter().enumerate() {
        let c = color(i);
        let xy: Vec<(f64, f64)> = pts.iter().map(|p| (p.0, p.1)).collect();
        chart
            .draw_series(LineSeries::new(xy.clone(), c.stroke_width(2)))
            .map_err(err)?
            .label(name.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        chart
            .draw_series(xy.iter().map(|&p| Circle::new(p, 3, c.filled())))
            .map_err(err)?;
        chart
            .draw_series(pts.iter().map(|(x, y, l)| {
                Text::new(
                    l.clone(),
                    (*x, *y),
                    ("sans-serif", 11).into_font().color(&c),
                )
            }))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .position(legend)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    Ok(())
}

fn accuracy_chart(acc: &Value, path: &Path) -> Res<()> {
    let mut freq: Vec<Series> = Vec::new();
    let mut stat: Vec<Series> = Vec::new();
    for s in acc["series"].as_array().into_iter().flatten() {
        let name = s["method"].as_str().unwrap_or("?").to_string();
        let pick = |key: &str| -> Vec<(f64, f64, String)> {
            s["points"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|p| {
                    Some((
                        p["seconds"].as_f64()?,
                        p[key].as_f64()?.max(FLOOR),
                        p["modes"].as_u64()?.to_string(),
                    ))
                })
                .collect()
        };
        freq.push((name.clone(), pick("freq_error")));
        stat.push((name, pick("static_error")));
    }
    let root = SVGBackend::new(path, (1400, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let areas = root.split_evenly((1, 2));
    let model = acc["model"]
        .as_str()
        .unwrap_or("model")
        .rsplit('/')
        .next()
        .unwrap_or("model");
    panel(
        &areas[0],
        &format!("frequency error up to fmax ({model})"),
        "wall time of the reduction (s)",
        "max relative frequency error",
        &freq,
        SeriesLabelPosition::UpperRight,
    )?;
    panel(
        &areas[1],
        "static error at the interface (unit loads)",
        "wall time of the reduction (s)",
        "max |dG_ij| / sqrt(G_ii G_jj)",
        &stat,
        SeriesLabelPosition::UpperRight,
    )?;
    root.present().map_err(err)
}

/// The scene suite's chart: static and FRF error at the load points against basis vectors.
fn scene_chart(v: &Value, path: &Path) -> Res<()> {
    let mut stat: Vec<Series> = Vec::new();
    let mut frf: Vec<Series> = Vec::new();
    for s in v["series"].as_array().into_iter().flatten() {
        let name = s["series"].as_str().unwrap_or("?").to_string();
        let pick = |key: &str| -> Vec<(f64, f64, String)> {
            (s["points"].as_array().into_iter().flatten())
                .filter_map(|p| {
                    Some((
                        p["vectors"].as_f64()?,
                        p[key].as_f64()?.max(FLOOR),
                        p["label"].as_str()?.to_string(),
                    ))
                })
                .collect()
        };
        stat.push((name.clone(), pick("static_error")));
        frf.push((name, pick("frf_error")));
    }
    let root = SVGBackend::new(path, (1400, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let areas = root.split_evenly((1, 2));
    panel(
        &areas[0],
        "scene: static error at the load points",
        "basis vectors (flexible modes + residual vectors)",
        "max |dH(0)| / H(0) over loads",
        &stat,
        SeriesLabelPosition::LowerLeft,
    )?;
    panel(
        &areas[1],
        "scene: FRF error at the load points over [0, fmax]",
        "basis vectors (flexible modes + residual vectors)",
        "max |dH(w)| / H(0) over loads and band",
        &frf,
        SeriesLabelPosition::LowerLeft,
    )?;
    root.present().map_err(err)
}

fn scaling_series(eigen: &[Value], cb: &[Value], what: &str) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    let mut add = |name: &str, runs: &[Value], pick: &dyn Fn(&Value) -> Option<f64>| {
        let pts: Vec<(f64, f64, String)> = runs
            .iter()
            .filter_map(|r| Some((r["dofs"].as_f64()?, pick(r)?, String::new())))
            .collect();
        if !pts.is_empty() {
            out.push((name.to_string(), pts));
        }
    };
    let get = |who: &'static str, peer: bool| {
        move |r: &Value| -> Option<f64> {
            let v = if peer { &r["peers"][who] } else { &r[who] };
            match what {
                "time" => v["phases_s"]["total"].as_f64(),
                _ => v["peak_rss_mb"].as_f64(),
            }
        }
    };
    add("eigen: flexbody", eigen, &get("ours", false));
    add(
        "eigen: ARPACK + CHOLMOD",
        eigen,
        &get("arpack_cholmod", true),
    );
    add("eigen: eigsh + SuperLU", eigen, &get("scipy_superlu", true));
    add("eigen: ccx", eigen, &get("ccx", true));
    add("CB build: flexbody", cb, &get("ours", false));
    add("CB: exudyn HCB", cb, &get("exudyn_hcb", true));
    add("CB: ccx frequency only", cb, &get("ccx", true));
    add(
        "CB: CHOLMOD, one factorization of K_ii",
        cb,
        &get("cholmod_factor_kii", true),
    );
    out
}

fn scaling_chart(eigen: &[Value], cb: &[Value], path: &Path) -> Res<()> {
    let root = SVGBackend::new(path, (1400, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let areas = root.split_evenly((1, 2));
    panel(
        &areas[0],
        "wall time vs size",
        "dofs",
        "seconds",
        &scaling_series(eigen, cb, "time"),
        SeriesLabelPosition::UpperLeft,
    )?;
    panel(
        &areas[1],
        "peak memory vs size",
        "dofs",
        "MB",
        &scaling_series(eigen, cb, "memory"),
        SeriesLabelPosition::UpperLeft,
    )?;
    root.present().map_err(err)
}

fn f(v: &Value) -> String {
    match v.as_f64() {
        Some(x) if x != 0.0 && (x.abs() < 1e-2 || x.abs() >= 1e5) => format!("{x:.2e}"),
        Some(x) => format!("{x:.3}"),
        None => "–".into(),
    }
}

fn tables(eigen: &[Value], cb: &[Value], acc: &[Value]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "## Eigen phase on identical matrices (`harness eigen`)\n"
    );
    let _ = writeln!(s, "Clamped tet10 block, consistent mass, lowest modes at σ = 0. Times in s (analyse+factor / eigen / total), peak memory in MB; ratio = ours / peer; agreement = max relative eigenvalue difference.\n");
    let _ = writeln!(s, "| dofs | modes | peer | analyse+factor | eigen | total | peak MB | ratio factor | ratio eigen | ratio total | agreement | load (1 min) |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|");
    for r in eigen {
        let rows = [
            ("flexbody", &r["ours"], &Value::Null),
            (
                "ARPACK + CHOLMOD",
                &r["peers"]["arpack_cholmod"],
                &r["ratios_ours_over"]["arpack_cholmod"],
            ),
            (
                "eigsh + SuperLU",
                &r["peers"]["scipy_superlu"],
                &r["ratios_ours_over"]["scipy_superlu"],
            ),
            (
                "ccx *FREQUENCY",
                &r["peers"]["ccx"],
                &r["ratios_ours_over"]["ccx"],
            ),
        ];
        for (name, p, q) in rows {
            let note = p["error"].as_str().or(p["skipped"].as_str());
            if let Some(n) = note {
                let _ = writeln!(
                    s,
                    "| {} | {} | {name} | {n} | | | | | | | | |",
                    r["dofs"], r["modes"]
                );
                continue;
            }
            let _ = writeln!(
                s,
                "| {} | {} | {name} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                r["dofs"],
                r["modes"],
                f(&p["phases_s"]["analyse_factor"]),
                f(&p["phases_s"]["eigen"]),
                f(&p["phases_s"]["total"]),
                f(&p["peak_rss_mb"]),
                f(&q["analyse_factor"]),
                f(&q["eigen"]),
                f(&q["total"]),
                f(&q["eigenvalue_max_rel_diff"]),
                f(&r["loadavg_before"][0]),
            );
        }
    }
    many_modes_table(&mut s, eigen);
    let _ = writeln!(s, "\n## Whole Craig–Bampton build (`harness cb`)\n");
    let _ = writeln!(s, "Ours: generate → RBE2 spiders (2 interface nodes) → assembly → elimination → CB → orthonormalization. exudyn: `ComputeHurtyCraigBamptonModes` (RBE2) on our assembled K, M (reading excluded). ccx: frequency-only run, both end faces clamped, same mode count. CHOLMOD: one analyse + supernodal factorization (f64, scikit-sparse, default ordering) of the same K_ii the CB build factors, in the same run and with the same threads — the ratio is the whole CB build over that one factorization (the fastest of the alternating repeats of each side). Agreement: fixed-interface eigenvalues.\n");
    let _ = writeln!(
        s,
        "| dofs | modes | who | total s | peak MB | ours / peer | agreement | load (1 min) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for r in cb {
        // ours / one CHOLMOD factorization (analyse + factor) of the same K_ii
        let chol_ratio = serde_json::json!({
            "total": r["ratios_ours_over"]["cholmod_factor_kii"]["total_over_factor"]
        });
        let rows = [
            ("flexbody CB build", &r["ours"], &Value::Null),
            (
                "exudyn HCB",
                &r["peers"]["exudyn_hcb"],
                &r["ratios_ours_over"]["exudyn_hcb"],
            ),
            (
                "ccx frequency only",
                &r["peers"]["ccx"],
                &r["ratios_ours_over"]["ccx"],
            ),
            (
                "CHOLMOD: one factorization of K_ii",
                &r["peers"]["cholmod_factor_kii"],
                &chol_ratio,
            ),
        ];
        for (name, p, q) in rows {
            if p.is_null() {
                continue; // a result from before the CHOLMOD peer row
            }
            if let Some(n) = p["error"].as_str().or(p["skipped"].as_str()) {
                let _ = writeln!(
                    s,
                    "| {} | {} | {name} | {n} | | | | |",
                    r["dofs"], r["modes"]
                );
                continue;
            }
            let _ = writeln!(
                s,
                "| {} | {} | {name} | {} | {} | {} | {} | {} |",
                r["dofs"],
                r["modes"],
                f(&p["phases_s"]["total"]),
                f(&p["peak_rss_mb"]),
                f(&q["total"]),
                f(&q["eigenvalue_max_rel_diff"]),
                f(&r["loadavg_before"][0]),
            );
        }
    }
    for a in acc {
        let _ = writeln!(
            s,
            "\n## Accuracy by method (`harness accuracy`, {}, {} dofs)\n",
            a["model"].as_str().unwrap_or("?"),
            a["dofs"]
        );
        let _ = writeln!(
            s,
            "fmax = {} Hz (10th flexible free-free mode). {}. Mode count = {}.\n",
            f(&a["fmax_hz"]),
            a["interfaces"].as_str().unwrap_or(""),
            a["mode_counts"].as_str().unwrap_or("")
        );
        let _ = writeln!(s, "| method | modes | basis | time s | frequency error | static error | ‖ΦᵀMΦ−I‖ | ‖ΦᵀKΦ−Λ‖/‖Λ‖ |");
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
        for m in a["series"].as_array().into_iter().flatten() {
            for p in m["points"].as_array().into_iter().flatten() {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {} | {} | {} | {} |",
                    m["method"].as_str().unwrap_or("?"),
                    p["modes"],
                    p["basis_size"],
                    f(&p["seconds"]),
                    f(&p["freq_error"]),
                    f(&p["static_error"]),
                    f(&p["orthonormality"]),
                    f(&p["stiffness_diag"]),
                );
            }
        }
    }
    s
}

/// The many-mode runs (`harness eigen ... --baseline B --inertia`): our eigen phase against our
/// own baseline-mode eigen phase in the same run, and the inertia count of the band.
/// `harness modes`: eigen time and peak memory against the mode count, with the target
/// line (3× the smallest count's eigen time).
fn many_modes_chart(v: &Value, path: &Path) -> Res<()> {
    let rows = v["rows"].as_array().cloned().unwrap_or_default();
    let pick = |key: &str| -> Vec<(f64, f64, String)> {
        rows.iter()
            .filter_map(|r| Some((r["modes"].as_f64()?, r[key].as_f64()?, String::new())))
            .collect()
    };
    let time = pick("eigen_s");
    let mut target = vec![];
    if let (Some(first), Some(last)) = (time.first(), time.last()) {
        target = vec![
            (first.0, 3.0 * first.1, String::new()),
            (last.0, 3.0 * first.1, "3x".into()),
        ];
    }
    let root = SVGBackend::new(path, (1400, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let areas = root.split_evenly((1, 2));
    panel(
        &areas[0],
        &format!("eigen phase vs modes ({} dofs)", v["dofs"]),
        "modes",
        "seconds",
        &[
            ("flexbody eigen phase".into(), time),
            ("target: 3 x the first count".into(), target),
            ("orthogonalization".into(), pick("orthogonalization_s")),
        ],
        SeriesLabelPosition::UpperLeft,
    )?;
    panel(
        &areas[1],
        "peak memory vs modes",
        "modes",
        "MB",
        &[("flexbody (factor + eigen)".into(), pick("peak_rss_mb"))],
        SeriesLabelPosition::UpperLeft,
    )?;
    root.present().map_err(err)
}

fn many_modes_sweep_table(v: &Value) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\n### Eigen phase against the mode count (`harness modes`)\n"
    );
    let _ = writeln!(s, "{}: {} dofs, one child process per count (peak memory per run), load {} before. Ratio: eigen time over the first count's; the issue's target is ≤ 3 at 300 modes.\n\n![many modes](many_modes.svg)\n", v["model"].as_str().unwrap_or("?"), v["dofs"], f(&v["loadavg_before"][0]));
    let _ = writeln!(s, "| modes | eigen s | ratio | solved vectors | restarts | orthogonalization s | factor s | peak MB | max residual |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
    for r in v["rows"].as_array().into_iter().flatten() {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r["modes"],
            f(&r["eigen_s"]),
            f(&r["eigen_over_first"]),
            r["solves"],
            r["restarts"],
            f(&r["orthogonalization_s"]),
            f(&r["analyse_factor_s"]),
            f(&r["peak_rss_mb"]),
            f(&r["max_residual"]),
        );
    }
    s
}

/// `harness cb … --precision mixed` beside the f64 run of the same size: phases, peak memory,
/// the ratio to CHOLMOD's factorization in each run, and the fixed-interface eigenvalues of the
/// mixed build against the f64 build's.
fn mixed_precision_table(cb: &[Value], mixed: &[Value]) -> String {
    let mut s = String::new();
    if mixed.is_empty() {
        return s;
    }
    let _ = writeln!(
        s,
        "\n## Mixed precision (`harness cb … --precision mixed`)\n"
    );
    let _ = writeln!(s, "`build --precision mixed`: K_ii factored in f32, every solve refined against K_ii to f64 accuracy (Wilkinson's iterative refinement, the residual in f64; the triangular solves in f32 arithmetic since session 11, 0.55× an f64 solve's time at 6 columns). Each row is its own run with its own CHOLMOD factorization of the same K_ii (f64); the f64 row is the `cb` suite's run of the same size. Agreement: fixed-interface eigenvalues of the mixed build vs the f64 build (max relative difference). Times in s, memory in MB.\n");
    let _ = writeln!(s, "| dofs | precision | factorization | constraint modes | eigen (solves) | extra refinement solves | total | peak MB | factor MB | total / CHOLMOD factor | peak / CHOLMOD peak | agreement | load (1 min) |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for m in mixed {
        let f64_run = cb
            .iter()
            .find(|r| r["dofs"] == m["dofs"] && r["modes"] == m["modes"]);
        let agreement = f64_run.map_or(Value::Null, |r| {
            let (a, b) = (eigen_list(&r["ours"]), eigen_list(&m["ours"]));
            if a.is_empty() || a.len() != b.len() {
                return Value::Null;
            }
            let d = a
                .iter()
                .zip(&b)
                .map(|(x, y)| (x - y).abs() / x.abs())
                .fold(0.0f64, f64::max);
            serde_json::json!(d)
        });
        for (name, r, agree) in [("f64", f64_run, Value::Null), ("mixed", Some(m), agreement)] {
            let Some(r) = r else { continue };
            let o = &r["ours"];
            let q = &r["ratios_ours_over"]["cholmod_factor_kii"];
            let _ = writeln!(
                s,
                "| {} | {name} | {} | {} | {} ({}) | {} | {} | {} | {} | {} | {} | {} | {} |",
                r["dofs"],
                f(&o["phases_s"]["cb factorization"]),
                f(&o["phases_s"]["cb constraint modes"]),
                f(&o["phases_s"]["cb eigen"]),
                f(&o["phases_s"]["cb eigen solves"]),
                o["eigen_refinement_solves"]
                    .as_u64()
                    .map_or("–".into(), |v| v.to_string()),
                f(&o["phases_s"]["total"]),
                f(&o["peak_rss_mb"]),
                f(&o["factor_bytes"]
                    .as_f64()
                    .map_or(Value::Null, |b| serde_json::json!(b / 1048576.0))),
                f(&q["total_over_factor"]),
                f(&q["peak_memory"]),
                f(&agree),
                f(&r["loadavg_before"][0]),
            );
        }
    }
    s
}

fn eigen_list(v: &Value) -> Vec<f64> {
    v["eigenvalues"]
        .as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default()
}

fn many_modes_table(s: &mut String, eigen: &[Value]) {
    let runs: Vec<&Value> = eigen
        .iter()
        .filter(|r| !r["baseline"].is_null() || !r["inertia"].is_null())
        .collect();
    if runs.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "\n### Many modes (`harness eigen … --modes N --baseline B --inertia`)\n"
    );
    let _ = writeln!(s, "Ours with N and with B modes in the same run (eigen phase, solves, basis orthogonalization), ARPACK + CHOLMOD with N; the band [0, σ) with σ just above the highest eigenvalue found: Sylvester's count (negative pivots of the LDLᵀ of K − σM) against how many eigenvalues each solver returned below σ.\n");
    let _ = writeln!(s, "| dofs | N / B | eigen N s | eigen B s | ratio | solves N / B | orthogonalization N s | ARPACK eigen N s | inertia count | ours below σ | ARPACK below σ | LDLᵀ s | load (1 min) |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for r in runs {
        let (o, b, i) = (&r["ours"], &r["baseline"], &r["inertia"]);
        let _ = writeln!(
            s,
            "| {} | {} / {} | {} | {} | {} | {} / {} | {} | {} | {} | {} | {} | {} | {} |",
            r["dofs"],
            r["modes"],
            b["modes"],
            f(&o["phases_s"]["eigen"]),
            f(&b["phases_s"]["eigen"]),
            f(&b["eigen_ratio"]),
            o["solves"],
            b["solves"],
            f(&o["phases_s"]["eigen_orthogonalization"]),
            f(&r["peers"]["arpack_cholmod"]["phases_s"]["eigen"]),
            i["count_below"],
            i["ours_below"],
            i["arpack_below"],
            f(&i["seconds"]),
            f(&r["loadavg_before"][0]),
        );
    }
}

/// `harness slepc`: the CB interior by our engine and by `--engine slepc` in the same run.
fn slepc_table(runs: &[Value]) -> String {
    if runs.is_empty() {
        return String::new();
    }
    let mut s = String::from("\n## `--engine slepc`: the CB interior on PETSc/SLEPc (`harness slepc`)\n\nThe cb suite's K_ii, M_ii, K_ib: ours (faer LLᵀ, constraint modes, block Krylov–Schur; one thread) against MUMPS Cholesky + SLEPc Krylov–Schur shift-invert under `mpirun -np N` (times from the script; \"incl. I/O\" adds writing the PETSc files, MPI start-up and reading back). Agreement: fixed-interface eigenvalues and constraint modes, max relative difference.\n\n| dofs | modes | ours total s (factor / constraint / eigen) | ranks | SLEPc factor / constraint / eigen s | SLEPc incl. I/O s | eigenvalues | constraint modes | load (1 min) |\n|---|---|---|---|---|---|---|---|---|\n");
    for r in runs {
        let o = &r["ours"];
        let phase = |name: &str| {
            o["timings"]
                .as_array()
                .and_then(|a| a.iter().find(|t| t["phase"] == name))
                .map(|t| f(&t["s"]))
                .unwrap_or_else(|| "–".into())
        };
        let sc = &r["slepc"]["script"];
        let _ = writeln!(
            s,
            "| {} | {} | {} ({} / {} / {}) | {} | {} / {} / {} | {} | {} | {} | {} |",
            r["dofs"],
            r["modes"],
            f(&o["seconds"]),
            phase("factorization"),
            phase("constraint modes"),
            phase("eigen"),
            r["slepc"]["ranks"],
            f(&sc["factor_s"]),
            f(&sc["constraint_s"]),
            f(&sc["eigen_s"]),
            f(&r["slepc"]["seconds_incl_io"]),
            f(&r["fixed_interface_eigenvalue_max_rel_diff"]),
            f(&r["constraint_modes_max_rel_diff"]),
            f(&r["loadavg_before"][0]),
        );
    }
    s
}

/// Draws both charts and writes `docs/benchmarks.md`.
pub fn run() -> Res<Value> {
    let docs = docs_dir();
    std::fs::create_dir_all(&docs).map_err(|e| e.to_string())?;
    let eigen = load("eigen_")?;
    // `cb … --precision mixed` runs have their own table; the cb table and chart are f64 builds
    let (mixed, cb): (Vec<Value>, Vec<Value>) = load("cb_")?
        .into_iter()
        .partition(|r| r["precision"].as_str() == Some("mixed"));
    let acc = load("accuracy_")?;
    let asm = load("assembly_")?;
    if let Some(a) = acc.first() {
        accuracy_chart(a, &docs.join("accuracy_vs_time.svg"))?;
    }
    // the scaling chart compares sizes at the default 30 modes; many-mode runs have a table
    let eigen30: Vec<Value> = eigen
        .iter()
        .filter(|r| r["modes"].as_u64() == Some(30))
        .cloned()
        .collect();
    scaling_chart(&eigen30, &cb, &docs.join("scaling.svg"))?;
    let slepc_md = slepc_table(&load("slepc_")?);
    let modes_md = match load("modes_")?.last() {
        Some(v) => {
            many_modes_chart(v, &docs.join("many_modes.svg"))?;
            many_modes_sweep_table(v)
        }
        None => String::new(),
    };
    let amls_runs: Vec<Value> = load("amls_")?
        .into_iter()
        .filter(|v| v["version"].as_u64() == Some(2))
        .collect();
    if !amls_runs.is_empty() {
        crate::amls::chart(&amls_runs, &docs.join("amls_error_vs_time.svg"))?;
    }
    let scene = load("scene_")?;
    let scene_md = match scene.first() {
        Some(v) => {
            scene_chart(v, &docs.join("scene_accuracy.svg"))?;
            format!(
                "\n## Scene loads: static and FRF error vs basis size (`harness scene`)\n\n{}; \
                 loads: {}; band 0-{} Hz. Points are labelled by mode count (selection: by ε).\n\n\
                 ![scene accuracy](scene_accuracy.svg)\n",
                v["model"].as_str().unwrap_or("?"),
                v["loads"].as_str().unwrap_or("?"),
                v["fmax_hz"]
            )
        }
        None => String::new(),
    };
    let head = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"))
        .unwrap_or_default();
    let md = format!(
        "# Benchmarks\n\n<!-- generated by `cargo run --release -p flexbody-bench --bin harness -- chart` from bench/results/*.json; edit bench/README.md instead -->\n\n{head}\n\
         ![accuracy vs time](accuracy_vs_time.svg)\n\n![time and memory vs dofs](scaling.svg)\n\n{}",
        tables(&eigen, &cb, &acc) + &crate::assembly::table(&asm)
    ) + &modes_md
        + &mixed_precision_table(&cb, &mixed)
        + &slepc_md
        + &scene_md;
    let path = docs.join("benchmarks.md");
    std::fs::write(&path, md).map_err(|e| format!("{}: {e}", path.display()))?;
    let written: Vec<String> = [
        docs.join("accuracy_vs_time.svg"),
        docs.join("scaling.svg"),
        docs.join("scene_accuracy.svg"),
        docs.join("many_modes.svg"),
        docs.join("amls_error_vs_time.svg"),
        path,
    ]
    .iter()
    .map(|p| p.display().to_string())
    .collect();
    Ok(json!({ "written": written }))
}
