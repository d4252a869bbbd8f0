//! `harness assembly`: times `flexbody::fe::assemble` (K and M, lumped and consistent) on three
//! generated models of about 10⁶ dofs, built in memory (no deck):
//!
//! * `quad`: an n×n grid of MITC4/QM6 quads (6 dofs per node) on the warped square
//!   z = w·(2x−1)(2y−1) over [0,1]² (a hyperbolic paraboloid: no four corners of a cell are
//!   coplanar, so every element goes through the warping links), t = 5 mm steel;
//! * `tri`: the same grid with each cell split into two DKMT triangles (alternating diagonals);
//! * `tet10`: the harness's tet10 block generator (1 m cube, 6 tets per brick), 3 dofs per node.
//!
//! Every (mesh, mass) pair runs in its own child process (`harness ours-assembly`), so its peak
//! memory is its own. The child times, best of R repeats, the whole `assemble`; then, once, the
//! stages inside it: the dof map + sparsity pattern (`Pattern::build`) and the element matrices
//! alone on one thread (`element_matrices` over every element, nothing scattered), so
//! scatter ≈ whole − pattern − matrices / threads.

use std::time::Instant;

use flexbody::fe::assembly::element_matrices;
use flexbody::fe::pattern::Pattern;
use flexbody::fe::{assemble, AssemblySpec, DofMap, MassKind};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::{Element, ElementKind, Model, Node, Property, Section, ShellSection};
use serde_json::{json, Value};

use crate::{loadavg, num, peak_rss_mb, run_self, steel, write_result, Res};

/// Shell thickness of the generated plates (m).
const THICKNESS: f64 = 0.005;
/// Rise of the warped square's corners (m).
const WARP: f64 = 0.05;

/// Warped n×n shell grid over the unit square (see the module doc): quads, or each cell split
/// into two triangles along alternating diagonals.
pub fn shell_grid(n: usize, tris: bool) -> Model {
    let mut model = Model {
        source: format!(
            "generated {n}x{n} {} shell grid",
            if tris { "tri3" } else { "quad4" }
        ),
        ..Model::default()
    };
    let h = 1.0 / n as f64;
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 * h, j as f64 * h);
            model.nodes.push(Node {
                id: (j * (n + 1) + i + 1) as u64,
                x: [x, y, WARP * (2.0 * x - 1.0) * (2.0 * y - 1.0)],
                displacement_frame: None,
            });
        }
    }
    model.materials.push(steel());
    model.properties.push(Property {
        id: 1,
        name: "SHELL".into(),
        material: 0,
        section: Section::Shell(ShellSection::homogeneous(THICKNESS, 0)),
    });
    let idx = |i: usize, j: usize| j * (n + 1) + i;
    let cells = n * n;
    model.elements.reserve(if tris { 2 * cells } else { cells });
    let mut push = |kind, nodes: Vec<usize>| {
        let id = model.elements.len() as u64 + 1;
        model.elements.push(Element {
            id,
            kind,
            nodes,
            property: Some(0),
            orientation: None,
        });
    };
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            if !tris {
                push(ElementKind::Quad4, vec![a, b, c, d]);
            } else if (i + j) % 2 == 0 {
                push(ElementKind::Tri3, vec![a, b, c]);
                push(ElementKind::Tri3, vec![a, c, d]);
            } else {
                push(ElementKind::Tri3, vec![a, b, d]);
                push(ElementKind::Tri3, vec![b, c, d]);
            }
        }
    }
    model
}

/// The tet10 block of the assembly benchmark: n³ bricks of a 1 m steel cube, 6 tets each.
pub fn tet10_cube(n: usize) -> Model {
    block(&BlockSpec {
        n: [n, n, n],
        size: [1.0, 1.0, 1.0],
        element: BlockElement::Tet10Six,
        material: steel(),
    })
}

fn model_of(mesh: &str, n: usize) -> Res<Model> {
    match mesh {
        "quad" => Ok(shell_grid(n, false)),
        "tri" => Ok(shell_grid(n, true)),
        "tet10" => Ok(tet10_cube(n)),
        _ => Err(format!("unknown mesh '{mesh}' (quad, tri, tet10)")),
    }
}

fn mass_of(s: &str) -> Res<MassKind> {
    match s {
        "lumped" => Ok(MassKind::Lumped),
        "consistent" => Ok(MassKind::Consistent),
        _ => Err(format!("unknown mass '{s}' (lumped, consistent)")),
    }
}

/// The child process: one mesh, one mass kind, `repeats` assemblies, then the stage timings.
pub fn ours_assembly(mesh: &str, n: usize, mass: &str, repeats: usize) -> Res<Value> {
    let mass = mass_of(mass)?;
    let spec = AssemblySpec {
        mass,
        ..Default::default()
    };
    let t = Instant::now();
    let model = model_of(mesh, n)?;
    let t_generate = t.elapsed().as_secs_f64();
    let mut runs = Vec::new();
    let mut sizes = None;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        let asm = assemble(&model, &spec).map_err(|e| e.to_string())?;
        runs.push(t.elapsed().as_secs_f64());
        sizes = Some((asm.dofs.n_dofs, asm.k.compute_nnz(), asm.m.compute_nnz()));
    }
    let (dofs, nnz_k, nnz_m) = sizes.ok_or("no assembly run")?;
    let best = runs.iter().copied().fold(f64::INFINITY, f64::min);
    let peak_after_assembly = peak_rss_mb();

    // Stages, once: dof map + pattern, then element matrices on one thread (nothing scattered).
    let t = Instant::now();
    let dofmap = DofMap::from_model(&model).map_err(|e| e.to_string())?;
    let conn: Vec<&[usize]> = model.elements.iter().map(|e| e.nodes.as_slice()).collect();
    let pattern = Pattern::build(&dofmap, &conn);
    let t_pattern = t.elapsed().as_secs_f64();
    drop(pattern);
    let t = Instant::now();
    let mut checksum = 0.0;
    for e in 0..model.elements.len() {
        let em = element_matrices(&model, e, &spec).map_err(|e| e.to_string())?;
        checksum += em.k[0] + em.m[0];
    }
    let t_matrices_1t = t.elapsed().as_secs_f64();
    let ne = model.elements.len();
    let threads = flexbody_threads();
    Ok(json!({
        "mesh": mesh,
        "size_parameter": n,
        "mass": format!("{mass:?}").to_lowercase(),
        "nodes": model.nodes.len(),
        "elements": ne,
        "dofs": dofs,
        "nnz_k": nnz_k,
        "nnz_m": nnz_m,
        "threads": threads,
        "seconds_generate": num(t_generate),
        "seconds_assemble_runs": runs,
        "seconds_assemble": num(best),
        "us_per_element": num(best * 1e6 / ne as f64),
        "ns_per_nnz_k": num(best * 1e9 / nnz_k as f64),
        "us_per_kdof": num(best * 1e6 / (dofs as f64 / 1e3)),
        "stages": {
            "seconds_dofmap_pattern": num(t_pattern),
            "seconds_element_matrices_one_thread": num(t_matrices_1t),
            "us_per_element_matrices_one_thread": num(t_matrices_1t * 1e6 / ne as f64),
            "checksum": num(checksum),
        },
        "peak_rss_mb_after_assembly": num(peak_after_assembly),
        "peak_rss_mb": num(peak_rss_mb()),
    }))
}

/// Threads the assembly's rayon pool uses (`RAYON_NUM_THREADS`, else the machine's cores).
fn flexbody_threads() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|s| s.parse().ok())
        .filter(|&t: &usize| t > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// The suite: quad and triangle grids of `n_shell`² cells and the tet10 block of `n_tet`³
/// bricks, lumped and consistent mass, `repeats` assemblies each; writes
/// `bench/results/assembly_<dofs>.json` (dofs of the quad grid).
pub fn run(n_shell: usize, n_tet: usize, repeats: usize) -> Res<Value> {
    let load_before = loadavg();
    let mut rows = Vec::new();
    for (mesh, n) in [("quad", n_shell), ("tri", n_shell), ("tet10", n_tet)] {
        for mass in ["lumped", "consistent"] {
            let args: Vec<String> = vec![
                "ours-assembly".into(),
                mesh.into(),
                n.to_string(),
                mass.into(),
                repeats.to_string(),
            ];
            let load = loadavg();
            let mut r = run_self(&args)?;
            r["loadavg_before"] = json!(load);
            eprintln!(
                "assembly {mesh} {mass}: {} dofs, {} s",
                r["dofs"], r["seconds_assemble"]
            );
            rows.push(r);
        }
    }
    // shell per-dof and per-element cost relative to the tet10 block, same mass kind
    let tet = |mass: &str| {
        rows.iter()
            .find(|r| r["mesh"] == "tet10" && r["mass"] == mass)
            .cloned()
            .unwrap_or(Value::Null)
    };
    let mut ratios = Vec::new();
    for r in &rows {
        if r["mesh"] == "tet10" {
            continue;
        }
        let t = tet(r["mass"].as_str().unwrap_or(""));
        let per_dof = |v: &Value| {
            v["seconds_assemble"].as_f64().unwrap_or(f64::NAN)
                / v["dofs"].as_f64().unwrap_or(f64::NAN)
        };
        ratios.push(json!({
            "mesh": r["mesh"],
            "mass": r["mass"],
            "seconds_over_tet10": num(r["seconds_assemble"].as_f64().unwrap_or(f64::NAN)
                / t["seconds_assemble"].as_f64().unwrap_or(f64::NAN)),
            "per_dof_over_tet10": num(per_dof(r) / per_dof(&t)),
        }));
    }
    let quad_dofs = rows.first().map_or(0, |r| r["dofs"].as_u64().unwrap_or(0));
    let out = json!({
        "suite": "assembly",
        "dofs": quad_dofs,
        "repeats": repeats,
        "loadavg_before": load_before,
        "rows": rows,
        "shell_over_tet10": ratios,
    });
    let path = write_result(&format!("assembly_{quad_dofs}.json"), &out)?;
    eprintln!("wrote {}", path.display());
    Ok(out)
}

fn cell(v: &Value, digits: usize) -> String {
    v.as_f64()
        .map_or_else(|| "–".into(), |x| format!("{x:.digits$}"))
}

/// The markdown section of `docs/benchmarks.md` for the assembly results (`harness chart`).
pub fn table(results: &[Value]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    for res in results {
        let _ = writeln!(
            s,
            "\n## Assembly of K and M (`harness assembly`, {} dofs)\n",
            res["dofs"]
        );
        let _ = writeln!(s, "`fe::assemble` on generated models: a warped quad shell grid (MITC4/QM6, t = 5 mm, z = 0.05(2x−1)(2y−1) over a 1 m square), the same grid split into DKMT triangles, and the tet10 block (1 m cube, 6 tets per brick). Best of {} runs per row, each row in its own process; all threads of the machine. Stage columns, measured once: dof map + sparsity pattern, and the element matrices alone on one thread (the rest of the time is the scatter into the compressed columns). Shell/tet10 = this row's seconds per dof over the tet10 row's with the same mass.\n", res["repeats"]);
        let _ = writeln!(s, "| mesh | mass | dofs | elements | nnz(K) | nnz(M) | assemble s | µs / element | ns / nnz(K) | pattern s | element matrices s (1 thread) | peak MB | per dof / tet10 | load (1 min) |");
        let _ = writeln!(
            s,
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
        );
        for r in res["rows"].as_array().into_iter().flatten() {
            let ratio = res["shell_over_tet10"]
                .as_array()
                .into_iter()
                .flatten()
                .find(|q| q["mesh"] == r["mesh"] && q["mass"] == r["mass"])
                .map_or_else(|| "1".into(), |q| cell(&q["per_dof_over_tet10"], 2));
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                r["mesh"].as_str().unwrap_or("?"),
                r["mass"].as_str().unwrap_or("?"),
                r["dofs"],
                r["elements"],
                r["nnz_k"],
                r["nnz_m"],
                cell(&r["seconds_assemble"], 2),
                cell(&r["us_per_element"], 1),
                cell(&r["ns_per_nnz_k"], 1),
                cell(&r["stages"]["seconds_dofmap_pattern"], 2),
                cell(&r["stages"]["seconds_element_matrices_one_thread"], 2),
                cell(&r["peak_rss_mb"], 0),
                ratio,
                cell(&r["loadavg_before"][0], 2),
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Σ M_ij over the x-translation dofs = the body's mass (M times a rigid x translation).
    fn x_mass(model: &Model, mass: MassKind) -> (usize, usize, f64) {
        let asm = assemble(
            model,
            &AssemblySpec {
                mass,
                ..Default::default()
            },
        )
        .expect("generated grid assembles");
        let m = &asm.m;
        let mut total = 0.0;
        for j in (0..m.ncols()).step_by(6) {
            for (&i, &v) in m.row_idx_of_col_raw(j).iter().zip(m.val_of_col(j)) {
                if i % 6 == 0 {
                    total += v;
                }
            }
        }
        (asm.dofs.n_dofs, asm.k.compute_nnz(), total)
    }

    /// The benchmark's shell grids are what the suite says: 6 dofs per node, the quad grid's
    /// nnz(K) = 36 Σ_nodes (neighbours + 1) = 36 (9(n−1)² + 24(n−1) + 16), and the mass of the
    /// warped sheet ρ t ∫∫ √(1 + z_x² + z_y²) dx dy (midpoint rule on a 400² grid, independent
    /// of the elements), lumped and consistent, quads and triangles.
    #[test]
    fn shell_grid_has_six_dofs_per_node_closed_form_pattern_and_sheet_mass() {
        let n = 32;
        let k = 400;
        let mut area = 0.0;
        for i in 0..k {
            for j in 0..k {
                let (x, y) = ((i as f64 + 0.5) / k as f64, (j as f64 + 0.5) / k as f64);
                let (zx, zy) = (2.0 * WARP * (2.0 * y - 1.0), 2.0 * WARP * (2.0 * x - 1.0));
                area += (1.0 + zx * zx + zy * zy).sqrt() / (k * k) as f64;
            }
        }
        let want = steel().rho * THICKNESS * area;
        assert!(area > 1.003, "the sheet is warped: area {area}");
        for tris in [false, true] {
            let model = shell_grid(n, tris);
            for mass in [MassKind::Lumped, MassKind::Consistent] {
                let (dofs, nnz, total) = x_mass(&model, mass);
                assert_eq!(dofs, 6 * (n + 1) * (n + 1));
                if !tris {
                    assert_eq!(nnz, 36 * (9 * (n - 1) * (n - 1) + 24 * (n - 1) + 16));
                }
                let err = (total - want) / want;
                eprintln!("tris={tris} {mass:?}: mass {total:.6} kg vs {want:.6} ({err:+.2e})");
                assert!(err.abs() < 1e-4, "tris={tris} {mass:?}: {total} vs {want}");
            }
        }
    }
}
