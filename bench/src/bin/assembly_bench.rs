//! Assembly benchmark (not a test): a structured tet10 block of about 10⁶ dofs from the block
//! generator, assembled with lumped and consistent mass; prints wall times per phase and the
//! process's peak resident memory (VmHWM) as JSON; then clamps the x = 0 face and times the
//! elimination K_r = TᵀKT, M_r = TᵀMT.
//!
//! `cargo run --release -p flexbody-bench --bin assembly_bench -- [bricks_per_side] [lumped|consistent]`
//! (default 34 → 69³ = 328 509 nodes, 985 527 dofs, 235 824 tet10 elements).

use std::time::Instant;

use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec, MassKind};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::DofMask;
use flexbody::model::Material;

fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|v| v.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kib| kib / 1024.0)
}

/// User + system CPU seconds of this process so far (/proc/self/stat fields 14 and 15, at the
/// usual 100 ticks per second).
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            let rest = s.rsplit_once(')')?.1.to_owned();
            let f: Vec<&str> = rest.split_whitespace().collect();
            // After the command name: field 3 is f[0], so utime (14) is f[11], stime (15) f[12].
            Some((f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?) / 100.0)
        })
        .unwrap_or(f64::NAN)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(34);
    let mass = match args.get(2).map(String::as_str) {
        Some("consistent") => MassKind::Consistent,
        _ => MassKind::Lumped,
    };
    let steel = Material {
        id: 1,
        name: "STEEL".into(),
        e: 210e9,
        nu: 0.3,
        g: 210e9 / 2.6,
        rho: 7850.0,
        elasticity: flexbody::model::Elasticity::Isotropic,
    };
    let t0 = Instant::now();
    let model = block(&BlockSpec {
        n: [n, n, n],
        size: [1.0, 1.0, 1.0],
        element: BlockElement::Tet10Six,
        material: steel,
    });
    let t_gen = t0.elapsed().as_secs_f64();
    let rss_model = peak_rss_mib();
    let (t1, c1) = (Instant::now(), cpu_seconds());
    let asm = match assemble(
        &model,
        &AssemblySpec {
            mass,
            ..Default::default()
        },
    ) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("assembly_bench: {e}");
            std::process::exit(2);
        }
    };
    let t_asm = t1.elapsed().as_secs_f64();
    let cpu_asm = cpu_seconds() - c1;
    let rss_asm = peak_rss_mib();
    // Clamp the x = 0 face and eliminate (u = T u_r, K_r = TᵀKT, M_r = TᵀMT).
    let fixed: Vec<_> = model.node_sets.get("X0").map_or(Vec::new(), |s| {
        s.iter().map(|&n| (n, DofMask::TRANSLATIONS)).collect()
    });
    let t2 = Instant::now();
    let red = match eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec {
            fixed,
            ..Default::default()
        },
    ) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("assembly_bench: {e}");
            std::process::exit(2);
        }
    };
    let t_elim = t2.elapsed().as_secs_f64();
    let out = serde_json::json!({
        "bench": "assembly",
        "mesh": format!("tet10 block {n}x{n}x{n} bricks, 6 tets each"),
        "mass": format!("{mass:?}"),
        "threads": std::thread::available_parallelism().map_or(1, |n| n.get()),
        "nodes": model.nodes.len(),
        "elements": model.elements.len(),
        "dofs": asm.dofs.n_dofs,
        "nnz_k": asm.k.compute_nnz(),
        "nnz_m": asm.m.compute_nnz(),
        "seconds_generate": t_gen,
        "seconds_assemble": t_asm,
        "cpu_seconds_assemble": cpu_asm,
        "seconds_eliminate_x0_clamped": t_elim,
        "reduced_dofs": red.retained.len(),
        "peak_rss_mib_after_generate": rss_model,
        "peak_rss_mib_after_assemble": rss_asm,
        "peak_rss_mib": peak_rss_mib(),
    });
    println!("{}", serde_json::to_string_pretty(&out).unwrap_or_default());
}
