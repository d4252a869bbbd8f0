//! Whole Craig–Bampton pipeline on a generated tet10 block (issue 5's speed figure): generate →
//! RBE2 spiders on both end faces (2 interface nodes, 12 dofs) → lumped assembly → elimination →
//! CB with 30 fixed-interface modes; phase times and peak RSS as JSON.
//!
//! `cargo run --release -p flexbody-bench --bin cb_pipeline_bench -- NX NY NZ [MODES]`
//! (default 80 16 16 30: 175k nodes, ≈526k dofs). Writes `bench/results/cb_pipeline_<dofs>.json`.

use std::time::Instant;

use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec};
use flexbody::interface::{resolve_interfaces, SpiderKind};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::Material;
use flexbody::reduce::craig_bampton::craig_bampton;
use flexbody::reduce::select::ModeCount;
use flexbody::solve::EigenSpec;

fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|x| x.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    let a: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    let n = [
        a.first().copied().unwrap_or(80),
        a.get(1).copied().unwrap_or(16),
        a.get(2).copied().unwrap_or(16),
    ];
    let modes = a.get(3).copied().unwrap_or(30);
    let mut phases: Vec<(String, f64)> = Vec::new();
    let mut t = Instant::now();
    let mut lap = |name: &str, phases: &mut Vec<(String, f64)>| {
        phases.push((name.to_string(), t.elapsed().as_secs_f64()));
        eprintln!(
            "{name}: {:.2} s (peak {:.0} MB)",
            t.elapsed().as_secs_f64(),
            peak_rss_mb()
        );
        t = Instant::now();
    };
    let steel = Material {
        id: 1,
        name: "STEEL".into(),
        e: 210e9,
        nu: 0.3,
        g: 210e9 / 2.6,
        rho: 7850.0,
    };
    let mut model = block(&BlockSpec {
        n,
        size: [0.5, 0.1, 0.1],
        element: BlockElement::Tet10Six,
        material: steel,
    });
    lap("generate", &mut phases);
    let itf = match resolve_interfaces(&mut model, &["X0".into(), "XL".into()], SpiderKind::Rbe2) {
        Ok(r) => r,
        Err(e) => return eprintln!("cb_pipeline_bench: {e}"),
    };
    lap("interfaces", &mut phases);
    let asm = match assemble(&model, &AssemblySpec::default()) {
        Ok(a) => a,
        Err(e) => return eprintln!("cb_pipeline_bench: {e}"),
    };
    lap("assembly", &mut phases);
    let red = match eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec::default(),
    ) {
        Ok(r) => r,
        Err(e) => return eprintln!("cb_pipeline_bench: {e}"),
    };
    lap("elimination", &mut phases);
    let mut pos = vec![usize::MAX; asm.dofs.n_dofs];
    for (i, &p) in red.retained.iter().enumerate() {
        pos[p] = i;
    }
    let interface: Vec<usize> = itf
        .iter()
        .flat_map(|r| r.nodes.iter())
        .flat_map(|&node| (0..6).map(move |c| (node, c)))
        .map(|(node, c)| pos[asm.dofs.first[node] + c])
        .collect();
    let eig = EigenSpec {
        dofs_per_node: Some(3),
        ..Default::default()
    };
    let set = match craig_bampton(&red.k, &red.m, &interface, ModeCount::Count(modes), &eig) {
        Ok(s) => s,
        Err(e) => return eprintln!("cb_pipeline_bench: {e}"),
    };
    lap("craig-bampton (total)", &mut phases);
    for note in &set.diagnostics.notes {
        eprintln!("  {note}");
    }
    let dofs = red.retained.len();
    let json = serde_json::json!({
        "model": format!("tet10 block {}x{}x{} bricks (6 tets each), 0.5x0.1x0.1 m steel, RBE2 spiders on x=0 and x=L", n[0], n[1], n[2]),
        "nodes": model.nodes.len(),
        "independent_dofs": dofs,
        "interface_dofs": interface.len(),
        "fixed_interface_modes": modes,
        "phases_s": phases.iter().map(|(k, v)| (k.clone(), *v)).collect::<std::collections::BTreeMap<_, _>>(),
        "cb_notes": set.diagnostics.notes,
        "first_flexible_hz": set.frequencies_hz().iter().copied().skip(6).take(6).collect::<Vec<_>>(),
        "orthonormality": set.diagnostics.orthonormality,
        "peak_rss_mb": peak_rss_mb(),
        "threads": "Par::Seq dense kernels; 2-core machine",
    });
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("results");
    let _ = std::fs::create_dir_all(&dir);
    let path = dir.join(format!("cb_pipeline_{dofs}.json"));
    match serde_json::to_string_pretty(&json).map(|s| std::fs::write(&path, s)) {
        Ok(Ok(())) => println!("{}", path.display()),
        _ => eprintln!("cb_pipeline_bench: cannot write {}", path.display()),
    }
}
