//! Shared pieces of the benchmark harness (`harness` binary): reproducible generated meshes,
//! Matrix Market and CalculiX deck writers for the peers, the peers' driver, process figures
//! (peak memory, load), and the suites themselves in their modules.

pub mod accuracy;
pub mod amls;
pub mod assembly;
pub mod chart;
pub mod scene_accuracy;
pub mod suites;

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::{ElementKind, Material, Model};
use flexbody::solve::SparseColMat;

/// Harness result: any failure is reported as a message naming what failed.
pub type Res<T> = Result<T, String>;

/// Peak resident memory of this process (VmHWM) in MB.
pub fn peak_rss_mb() -> f64 {
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

/// The 1/5/15-minute load averages (`/proc/loadavg`), recorded with every measurement.
pub fn loadavg() -> Vec<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .unwrap_or_default()
        .split_whitespace()
        .take(3)
        .filter_map(|s| s.parse().ok())
        .collect()
}

/// Steel in SI units.
pub fn steel() -> Material {
    Material {
        id: 1,
        name: "STEEL".into(),
        e: 210e9,
        nu: 0.3,
        g: 210e9 / 2.6,
        rho: 7850.0,
        elasticity: flexbody::model::Elasticity::Isotropic,
    }
}

/// The generated benchmark body: a 0.5 × 0.1 × 0.1 m steel block of `n` bricks, 6 tet10 each
/// (node sets X0 and XL on the end faces).
pub fn tet10_block(n: [usize; 3]) -> Model {
    block(&BlockSpec {
        n,
        size: [0.5, 0.1, 0.1],
        element: BlockElement::Tet10Six,
        material: steel(),
    })
}

/// Where generated inputs go (never into git): `$FLEXBODY_BENCHDATA` or /work/benchdata.
pub fn data_dir(name: &str) -> Res<PathBuf> {
    let root = std::env::var_os("FLEXBODY_BENCHDATA")
        .map_or_else(|| PathBuf::from("/work/benchdata"), PathBuf::from);
    let d = root.join(name);
    std::fs::create_dir_all(&d).map_err(|e| format!("cannot create {}: {e}", d.display()))?;
    Ok(d)
}

/// `bench/results/`.
pub fn results_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("results")
}

/// Writes `json` pretty-printed to `bench/results/<name>` (through a temporary file, so a
/// failure never leaves half a file).
pub fn write_result(name: &str, json: &serde_json::Value) -> Res<PathBuf> {
    let dir = results_dir();
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let path = dir.join(name);
    let tmp = dir.join(format!(".{name}.tmp"));
    let text = serde_json::to_string_pretty(json).map_err(|e| e.to_string())?;
    std::fs::write(&tmp, text + "\n").map_err(|e| format!("{}: {e}", tmp.display()))?;
    std::fs::rename(&tmp, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

fn io_err(path: &Path) -> impl Fn(std::io::Error) -> String + '_ {
    move |e| format!("{}: {e}", path.display())
}

/// Writes a full symmetric sparse matrix as Matrix Market `coordinate real symmetric` (lower
/// triangle, 1-based, 17 significant digits: the peers read exactly our numbers).
pub fn write_mtx(path: &Path, a: &SparseColMat<usize, f64>) -> Res<()> {
    let f = std::fs::File::create(path).map_err(io_err(path))?;
    let mut w = BufWriter::with_capacity(1 << 20, f);
    let mut nnz = 0usize;
    for j in 0..a.ncols() {
        nnz += a.row_idx_of_col_raw(j).iter().filter(|&&i| i >= j).count();
    }
    writeln!(
        w,
        "%%MatrixMarket matrix coordinate real symmetric\n{} {} {nnz}",
        a.nrows(),
        a.ncols()
    )
    .map_err(io_err(path))?;
    for j in 0..a.ncols() {
        for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
            if i >= j {
                writeln!(w, "{} {} {v:.17e}", i + 1, j + 1).map_err(io_err(path))?;
            }
        }
    }
    w.flush().map_err(io_err(path))
}

/// Writes a CalculiX deck of a tet10 model: nodes, C3D10 elements, the first material, a
/// `*FREQUENCY` step for `modes` modes (consistent mass, ccx's default solver) with every dof of
/// the nodes in `fixed` held.
pub fn write_ccx_deck(path: &Path, model: &Model, fixed: &[usize], modes: usize) -> Res<()> {
    let f = std::fs::File::create(path).map_err(io_err(path))?;
    let mut w = BufWriter::with_capacity(1 << 20, f);
    let mat = model.materials.first().ok_or("model without material")?;
    let mut s = String::from("*HEADING\nflexbody benchmark deck\n*NODE, NSET=NALL\n");
    for n in &model.nodes {
        s += &format!("{}, {}, {}, {}\n", n.id, n.x[0], n.x[1], n.x[2]);
    }
    s += "*ELEMENT, TYPE=C3D10, ELSET=EALL\n";
    for e in &model.elements {
        if e.kind != ElementKind::Tet10 {
            return Err(format!("element {} is not a tet10", e.id));
        }
        s += &format!("{}", e.id);
        for &n in &e.nodes {
            s += &format!(", {}", model.nodes[n].id);
        }
        s += "\n";
    }
    s += "*NSET, NSET=FIX\n";
    for &n in fixed {
        s += &format!("{}\n", model.nodes[n].id);
    }
    s += &format!(
        "*MATERIAL, NAME=STEEL\n*ELASTIC\n{}, {}\n*DENSITY\n{}\n*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n\
         *BOUNDARY\nFIX, 1, 3\n*STEP\n*FREQUENCY, STORAGE=NO\n{modes}\n*END STEP\n",
        mat.e, mat.nu, mat.rho
    );
    w.write_all(s.as_bytes()).map_err(io_err(path))?;
    w.flush().map_err(io_err(path))
}

/// Runs `python3 bench/peers/peers.py ARGS` (OpenMP/OpenBLAS threads: `FLEXBODY_PEER_THREADS`,
/// else `FLEXBODY_THREADS` as ours, else one) and parses its JSON; an error is recorded, not fatal.
pub fn run_peer(args: &[String]) -> serde_json::Value {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("peers/peers.py");
    let threads = std::env::var("FLEXBODY_PEER_THREADS")
        .or_else(|_| std::env::var("FLEXBODY_THREADS"))
        .unwrap_or_else(|_| "1".into());
    eprintln!("peer: {}", args.join(" "));
    let out = std::process::Command::new("python3")
        .arg(&script)
        .args(args)
        .env("OMP_NUM_THREADS", &threads)
        .env("OPENBLAS_NUM_THREADS", &threads)
        .env("CCX_NPROC_EQUATION_SOLVER", &threads)
        .output();
    match out {
        Ok(o) if o.status.success() => {
            let text = String::from_utf8_lossy(&o.stdout);
            let last = text.lines().last().unwrap_or("");
            serde_json::from_str(last).unwrap_or_else(
                |e| serde_json::json!({ "error": format!("bad JSON from peer: {e}") }),
            )
        }
        Ok(o) => {
            let err = String::from_utf8_lossy(&o.stderr);
            let tail: String = err.lines().rev().take(6).collect::<Vec<_>>().join(" | ");
            serde_json::json!({ "error": format!("peer failed ({}): {tail}", o.status) })
        }
        Err(e) => serde_json::json!({ "error": format!("cannot run python3: {e}") }),
    }
}

/// Runs this harness binary again with `args` (a suite's "ours" part in its own process, so its
/// peak memory is its own) and parses the JSON it prints last.
pub fn run_self(args: &[String]) -> Res<serde_json::Value> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    eprintln!("ours: {}", args.join(" "));
    let o = std::process::Command::new(exe)
        .args(args)
        .stderr(std::process::Stdio::inherit())
        .output()
        .map_err(|e| e.to_string())?;
    if !o.status.success() {
        return Err(format!("harness {} failed ({})", args.join(" "), o.status));
    }
    let text = String::from_utf8_lossy(&o.stdout);
    serde_json::from_str(text.lines().last().unwrap_or("")).map_err(|e| e.to_string())
}

/// Largest relative difference of the first `n` entries of two ascending lists (None when
/// either is shorter).
pub fn max_rel_diff(a: &[f64], b: &[f64], n: usize) -> Option<f64> {
    if a.len() < n || b.len() < n {
        return None;
    }
    Some(
        a.iter()
            .zip(b)
            .take(n)
            .map(|(x, y)| (x - y).abs() / y.abs().max(f64::MIN_POSITIVE))
            .fold(0.0, f64::max),
    )
}

/// JSON number (null when not finite).
pub fn num(x: f64) -> serde_json::Value {
    serde_json::Number::from_f64(x).map_or(serde_json::Value::Null, serde_json::Value::Number)
}
