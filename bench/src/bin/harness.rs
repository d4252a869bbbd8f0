//! Benchmark harness: `cargo run --release -p flexbody-bench --bin harness -- <suite> [args]`.
//!
//! Suites (results under `bench/results/`, generated inputs under /work/benchdata):
//! * `eigen NX NY NZ [--modes 30] [--ccx] [--no-superlu] [--baseline B] [--inertia]` —
//!   factorization + eigen phase vs SciPy/SuperLU, ARPACK/CHOLMOD (and ccx) on identical
//!   matrices; `--baseline B` also runs ours with B modes (many-mode ratio), `--inertia` counts
//!   the eigenvalues below the highest found (Sylvester) against both solvers' counts;
//! * `cb NX NY NZ [--modes 30] [--exudyn] [--ccx] [--repeat R]` — whole CB build vs exudyn HCB,
//!   ccx and one CHOLMOD factorization of the same K_ii (R alternating pairs);
//! * `assembly [N_SHELL [N_TET]] [--repeat R]` — `fe::assemble` (lumped and consistent) on a
//!   warped quad shell grid, the same grid in triangles and a tet10 block, each ≈10⁶ dofs;
//! * `accuracy [MODEL.inp]` — every reduction method × mode counts on the bundled conrod;
//! * `scene` — the scene's static and FRF error at the load points vs basis size (normal modes,
//!   Craig–Bampton, with and without residual vectors, scene selection) on a cantilever;
//! * `slepc NX NY NZ [--modes 30] [--mpi 2]` — the cb suite's interior solved by our engine and
//!   by `--engine slepc` (MUMPS + SLEPc under mpirun) in the same run: agreement and times;
//! * `chart` — the SVG charts and `docs/benchmarks.md` from the JSON results.
//!
//! `ours-eigen`, `ours-cb`, `ours-build`, `ours-assembly` and `inertia K.mtx M.mtx SIGMA` are the suites' own child processes; `solve-kernel K.mtx [B ...]`
//! times faer's multi-RHS solve against ours on one factorization (for tuning).

use flexbody_bench::{accuracy, amls, assembly, chart, scene_accuracy, suites, Res};

const USAGE: &str = "usage: harness eigen NX NY NZ [--modes N] [--ccx] [--no-superlu] [--baseline B] [--inertia] | cb NX NY NZ [--modes N] [--exudyn] [--ccx] [--repeat R] [--precision auto|f64|mixed] | modes NX NY NZ [--counts 30,100,200,300] | assembly [N_SHELL [N_TET]] [--repeat R] | slepc NX NY NZ [--modes N] [--mpi N] | amls NX NY NZ [--modes N] [--cutoffs 2,4,8] [--no-lanczos] | accuracy [MODEL.inp] | scene | chart";

fn dims(a: &[String]) -> Res<[usize; 3]> {
    let p = |i: usize| -> Res<usize> {
        a.get(i)
            .and_then(|s| s.parse().ok())
            .filter(|&v| v > 0)
            .ok_or_else(|| format!("expected three positive brick counts NX NY NZ\n{USAGE}"))
    };
    Ok([p(0)?, p(1)?, p(2)?])
}

fn modes(a: &[String]) -> Res<usize> {
    match a.iter().position(|s| s == "--modes") {
        Some(i) => a
            .get(i + 1)
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| "--modes N".to_string()),
        None => Ok(30),
    }
}

/// The value after `flag`, if given.
fn flag_value(a: &[String], flag: &str) -> Option<String> {
    a.iter()
        .position(|s| s == flag)
        .and_then(|i| a.get(i + 1).cloned())
}

fn repeat(a: &[String]) -> Res<usize> {
    match a.iter().position(|s| s == "--repeat") {
        Some(i) => a
            .get(i + 1)
            .and_then(|s| s.parse().ok())
            .filter(|&r| r > 0)
            .ok_or_else(|| "--repeat R (R >= 1)".to_string()),
        None => Ok(1),
    }
}

fn run(args: &[String]) -> Res<()> {
    let (suite, a) = args.split_first().ok_or(USAGE)?;
    let has = |f: &str| a.iter().any(|s| s == f);
    let out = match suite.as_str() {
        "modes" => {
            let counts: Vec<usize> = flag_value(a, "--counts")
                .unwrap_or_else(|| "30,100,200,300".into())
                .split(',')
                .map(|c| c.trim().parse().ok().filter(|&v| v > 0))
                .collect::<Option<_>>()
                .ok_or_else(|| "--counts N,N,...".to_string())?;
            suites::modes(dims(a)?, &counts)?
        }
        "eigen" => {
            let baseline = match a.iter().position(|s| s == "--baseline") {
                Some(i) => Some(
                    a.get(i + 1)
                        .and_then(|s| s.parse().ok())
                        .ok_or_else(|| "--baseline N".to_string())?,
                ),
                None => None,
            };
            let extras = suites::EigenExtras {
                baseline,
                inertia: has("--inertia"),
            };
            suites::eigen_with(
                dims(a)?,
                modes(a)?,
                has("--ccx"),
                !has("--no-superlu"),
                extras,
            )?
        }
        "cb" => suites::cb(
            dims(a)?,
            modes(a)?,
            has("--exudyn"),
            has("--ccx"),
            repeat(a)?,
            &flag_value(a, "--precision").unwrap_or_else(|| "auto".into()),
        )?,
        "assembly" => {
            // sizes before any flag; defaults 408² shell cells (1 003 686 dofs), 34³ tet bricks
            // (985 527 dofs)
            let sizes: Vec<usize> = a
                .iter()
                .take_while(|s| !s.starts_with("--"))
                .map(|s| s.parse().ok().filter(|&v| v > 0))
                .collect::<Option<_>>()
                .ok_or_else(|| format!("bad size\n{USAGE}"))?;
            let shell = sizes.first().copied().unwrap_or(408);
            let tet = sizes.get(1).copied().unwrap_or(34);
            assembly::run(shell, tet, repeat(a)?)?
        }
        "ours-assembly" if a.len() == 4 => {
            let n = a[1].parse().map_err(|_| "N".to_string())?;
            let r = a[3].parse().map_err(|_| "REPEATS".to_string())?;
            assembly::ours_assembly(&a[0], n, &a[2], r)?
        }
        "amls" => {
            let cutoffs: Vec<f64> = flag_value(a, "--cutoffs")
                .unwrap_or_else(|| "2,4,8".into())
                .split(',')
                .map(|c| c.trim().parse().ok().filter(|&v: &f64| v >= 1.0))
                .collect::<Option<_>>()
                .ok_or_else(|| "--cutoffs F,F,... (each >= 1)".to_string())?;
            let modes = modes(a)?;
            // Lanczos on fewer modes where the requested count would not fit (1M dofs, 500)
            let lanczos = match (has("--no-lanczos"), flag_value(a, "--lanczos-modes")) {
                (true, _) => None,
                (false, Some(m)) => Some(m.parse().map_err(|_| "--lanczos-modes N".to_string())?),
                (false, None) => Some(modes),
            };
            amls::run(dims(a)?, modes, &cutoffs, lanczos)?
        }
        "ours-amls" if (4..=6).contains(&a.len()) => {
            let m = a[2].parse().map_err(|_| "MODES".to_string())?;
            let c = a[3].parse().map_err(|_| "CUTOFF".to_string())?;
            let refine = a.get(4).and_then(|s| s.parse().ok());
            let leaf = a.get(5).and_then(|s| s.parse().ok());
            amls::ours_amls(&a[0], &a[1], m, c, refine, leaf)?
        }
        "accuracy" => accuracy::run(a.first().map(String::as_str))?,
        "scene" => scene_accuracy::run()?,
        "chart" => chart::run()?,
        "ours-eigen" if (3..=6).contains(&a.len()) => {
            let m = a[2].parse().map_err(|_| "MODES".to_string())?;
            let block = a.get(3).and_then(|s| s.parse().ok());
            let tol = a.get(4).and_then(|s| s.parse().ok());
            let basis = a.get(5).and_then(|s| s.parse().ok());
            suites::ours_eigen(&a[0], &a[1], m, block, tol, basis)?
        }
        "slepc" => {
            let ranks = match a.iter().position(|s| s == "--mpi") {
                Some(i) => a
                    .get(i + 1)
                    .and_then(|s| s.parse().ok())
                    .ok_or_else(|| "--mpi N".to_string())?,
                None => 2,
            };
            suites::slepc(dims(a)?, modes(a)?, ranks)?
        }
        "inertia" if a.len() == 3 => {
            let sigma = a[2].parse().map_err(|_| "SIGMA".to_string())?;
            suites::inertia_count(&a[0], &a[1], sigma)?
        }
        "solve-kernel" if !a.is_empty() => {
            let blocks: Vec<usize> = a[1..].iter().filter_map(|s| s.parse().ok()).collect();
            suites::solve_kernel(&a[0], &blocks)?
        }
        "ours-cb" if a.len() == 5 => {
            let m = a[3].parse().map_err(|_| "MODES".to_string())?;
            suites::ours_cb(dims(a)?, m, &a[4])?
        }
        "ours-build" if a.len() == 5 => {
            let m = a[3].parse().map_err(|_| "MODES".to_string())?;
            suites::ours_build(dims(a)?, m, &a[4])?
        }
        _ => return Err(USAGE.into()),
    };
    println!("{out}");
    Ok(())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Err(e) = run(&args) {
        eprintln!("harness: {e}");
        std::process::exit(1);
    }
}
