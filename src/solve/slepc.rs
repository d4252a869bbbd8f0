//! `--engine slepc`: eigenproblems on PETSc/SLEPc over MPI (issues 22 and 46, models past one
//! machine) — the lowest modes or a band of normal modes and of Craig–Chang's free-free modes
//! ([`lowest_modes`]), and the interior of a Craig–Bampton reduction ([`fixed_interface`]). K and
//! M (and K_ib) go to a scratch folder in PETSc's binary format; `mpirun -np N python3
//! slepc_engine.py` (the script is embedded here) factors K − σM once with MUMPS, solves
//! K_ii X = K_ib with it (Craig–Bampton, σ = 0) and runs SLEPc's Krylov–Schur with
//! shift-and-invert at σ; the eigenpairs and X are read back. The Rayleigh–Ritz check, the band's
//! inertia proof, the reduction, orthonormalization, invariants and the file stay ours.
//!
//! Needs `mpirun` and a Python with petsc4py/slepc4py (Debian: `openmpi-bin`,
//! `python3-slepc4py-real`); `FLEXBODY_SLEPC_PYTHON` and `FLEXBODY_MPIRUN` override the commands.
//! Debian's packages want `PETSC_DIR`/`SLEPC_DIR` when the `/usr/lib/petsc` alternatives are not
//! set; they are filled in from `/usr/lib/petscdir` and `/usr/lib/slepcdir` when found.

use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use faer::sparse::SparseColMatRef;
use faer::Mat;

use super::{EigenInfo, EigenSolution, EigenSpec, SolveError, SparseColMat};

/// PETSc's binary class ids (petscmat.h, petscvec.h).
const MAT_FILE_CLASSID: i32 = 1_211_216;
const VEC_FILE_CLASSID: i32 = 1_211_214;

/// The Python side, written next to the matrices for each run.
const SCRIPT: &str = include_str!("slepc_engine.py");

/// How to run the external engine.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SlepcEngine {
    /// MPI ranks (`mpirun -np`).
    pub ranks: usize,
}

/// What the engine returned for the interior of a Craig–Bampton reduction.
#[derive(Debug)]
pub struct SlepcSolution {
    /// X = K_ii⁻¹ K_ib (n_i × n_b); the constraint modes are −X.
    pub x: Mat<f64>,
    /// Lowest eigenvalues of K_ii φ = λ M_ii φ, ascending.
    pub eigenvalues: Vec<f64>,
    /// Their eigenvectors (n_i × count), as SLEPc normalized them.
    pub vectors: Mat<f64>,
    /// The script's timings and facts (one JSON object), and our wall time around it.
    pub report: String,
    /// Wall time of writing, running and reading back (s).
    pub seconds: f64,
}

fn err(what: impl Into<String>) -> SolveError {
    SolveError::Invalid(format!("--engine slepc: {}", what.into()))
}

fn io_err(path: &Path, e: std::io::Error) -> SolveError {
    err(format!("{}: {e}", path.display()))
}

/// Writes `a` (n × m, CSC) as a PETSc binary AIJ matrix (big-endian, 32-bit indices).
pub fn write_petsc_mat(path: &Path, a: SparseColMatRef<'_, usize, f64>) -> Result<(), SolveError> {
    let (nr, nc) = (a.nrows(), a.ncols());
    let i32_of = |v: usize, what: &str| {
        i32::try_from(v).map_err(|_| err(format!("{what} {v} exceeds PETSc's 32-bit indices")))
    };
    // CSC -> CSR
    let mut row_len = vec![0usize; nr];
    for j in 0..nc {
        for &i in a.row_idx_of_col_raw(j) {
            row_len[i] += 1;
        }
    }
    let mut start = vec![0usize; nr + 1];
    for i in 0..nr {
        start[i + 1] = start[i] + row_len[i];
    }
    let nnz = start[nr];
    let mut cols = vec![0i32; nnz];
    let mut vals = vec![0f64; nnz];
    let mut next = start.clone();
    for j in 0..nc {
        let jj = i32_of(j, "column")?;
        for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
            cols[next[i]] = jj;
            vals[next[i]] = v;
            next[i] += 1;
        }
    }
    let file = std::fs::File::create(path).map_err(|e| io_err(path, e))?;
    let mut w = BufWriter::new(file);
    let mut put = |bytes: &[u8]| w.write_all(bytes).map_err(|e| io_err(path, e));
    put(&MAT_FILE_CLASSID.to_be_bytes())?;
    put(&i32_of(nr, "rows")?.to_be_bytes())?;
    put(&i32_of(nc, "columns")?.to_be_bytes())?;
    put(&i32_of(nnz, "non-zeros")?.to_be_bytes())?;
    for &l in &row_len {
        put(&(l as i32).to_be_bytes())?;
    }
    for c in &cols {
        put(&c.to_be_bytes())?;
    }
    for v in &vals {
        put(&v.to_be_bytes())?;
    }
    w.flush().map_err(|e| io_err(path, e))
}

/// Reads `count` consecutive PETSc binary Vecs of length `n` into the columns of a matrix.
pub fn read_petsc_vecs(path: &Path, n: usize, count: usize) -> Result<Mat<f64>, SolveError> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .map_err(|e| io_err(path, e))?;
    let want = count * (8 + 8 * n);
    if bytes.len() != want {
        return Err(err(format!(
            "{}: {} bytes, expected {want} for {count} vectors of {n}",
            path.display(),
            bytes.len()
        )));
    }
    let mut out = Mat::<f64>::zeros(n, count);
    let mut at = 0;
    let word =
        |at: usize| i32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    for c in 0..count {
        if word(at) != VEC_FILE_CLASSID || word(at + 4) as usize != n {
            return Err(err(format!(
                "{}: vector {c} has a bad header",
                path.display()
            )));
        }
        at += 8;
        for r in 0..n {
            let mut b = [0u8; 8];
            b.copy_from_slice(&bytes[at..at + 8]);
            out[(r, c)] = f64::from_be_bytes(b);
            at += 8;
        }
    }
    Ok(out)
}

/// The Debian install folder of PETSc or SLEPc when the alternatives link is missing.
fn debian_dir(root: &str, prefix: &str) -> Option<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root)
        .ok()?
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with(prefix))
        .map(|e| e.path().join("x86_64-linux-gnu-real"))
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    dirs.pop()
}

/// The commands the engine runs: (mpirun, python), from `FLEXBODY_MPIRUN` and
/// `FLEXBODY_SLEPC_PYTHON`, else `mpirun` and the system's `/usr/bin/python3` (where Debian puts
/// slepc4py) or `python3`.
pub fn commands() -> (String, String) {
    let mpirun = std::env::var("FLEXBODY_MPIRUN").unwrap_or_else(|_| "mpirun".into());
    let python = std::env::var("FLEXBODY_SLEPC_PYTHON").unwrap_or_else(|_| {
        if Path::new("/usr/bin/python3").exists() {
            "/usr/bin/python3".into()
        } else {
            "python3".into()
        }
    });
    (mpirun, python)
}

/// `PETSC_DIR` / `SLEPC_DIR` to give the script when the environment has none and Debian's
/// install folders exist.
pub fn package_env() -> Vec<(&'static str, PathBuf)> {
    [
        ("PETSC_DIR", "/usr/lib/petscdir", "petsc"),
        ("SLEPC_DIR", "/usr/lib/slepcdir", "slepc"),
    ]
    .into_iter()
    .filter(|(var, _, _)| std::env::var_os(var).is_none())
    .filter_map(|(var, root, prefix)| Some((var, debian_dir(root, prefix)?)))
    .collect()
}

/// Whether the engine can run here: `mpirun` starts and its Python imports slepc4py; the error
/// names what is missing.
pub fn available() -> Result<(), String> {
    let (mpirun, python) = commands();
    if Command::new(&mpirun).arg("--version").output().is_err() {
        return Err(format!("{mpirun} not found"));
    }
    let probe = Command::new(&python)
        .args(["-c", "import slepc4py, petsc4py"])
        .envs(package_env())
        .output();
    match probe {
        Ok(o) if o.status.success() => Ok(()),
        _ => Err(format!("{python} cannot import slepc4py")),
    }
}

/// Engine runs started by this process.
static RUNS: AtomicUsize = AtomicUsize::new(0);

/// A new, empty directory for one engine run: `flexbody-slepc-<pid>-<run>` in the temporary
/// directory, `run` counting this process's runs (two builds of one process at once, e.g. tests
/// in parallel, never share one); a name that exists already is skipped, never reused.
fn run_dir() -> Result<PathBuf, SolveError> {
    let tmp = std::env::temp_dir();
    for _ in 0..1000 {
        let run = RUNS.fetch_add(1, Ordering::Relaxed);
        let dir = tmp.join(format!("flexbody-slepc-{}-{run}", std::process::id()));
        match std::fs::create_dir(&dir) {
            Ok(()) => return Ok(dir),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(io_err(&dir, e)),
        }
    }
    Err(io_err(
        &tmp,
        std::io::Error::new(
            std::io::ErrorKind::AlreadyExists,
            "1000 run directories of this process exist already",
        ),
    ))
}

/// What the engine is asked for: the eigenproblem's shift and how many eigenpairs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Request {
    /// The lowest `count` eigenpairs; with `upper`, the count the band starts from.
    pub count: usize,
    /// A band: every eigenvalue ≤ `upper` and the first one above it (the count grows as needed,
    /// one factorization).
    pub upper: Option<f64>,
    /// σ of the one factorization of K − σM (below the spectrum: 0 for K_ii, negative for a free
    /// body).
    pub shift: f64,
    /// SLEPc's relative tolerance.
    pub tol: f64,
}

/// Runs the engine on K_ii, M_ii, K_ib (full symmetric K_ii and M_ii) for the fixed-interface
/// modes of `request` (its shift is 0: the factorization also gives the constraint modes).
pub fn fixed_interface(
    kii: SparseColMatRef<'_, usize, f64>,
    mii: SparseColMatRef<'_, usize, f64>,
    kib: SparseColMatRef<'_, usize, f64>,
    request: Request,
    engine: &SlepcEngine,
) -> Result<SlepcSolution, SolveError> {
    run(kii, mii, Some(kib), request, engine)
}

/// Runs the engine on K and M (full symmetric) for the eigenpairs of `request`; the solution's
/// `x` is empty.
pub fn eigenpairs(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    request: Request,
    engine: &SlepcEngine,
) -> Result<SlepcSolution, SolveError> {
    run(k, m, None, request, engine)
}

/// [`crate::solve::lowest_modes`] on the engine: the eigenpairs of `spec` (count, band, shift —
/// automatic: [`super::automatic_shift`], as ours, so that free bodies factor) from SLEPc, then our
/// Rayleigh–Ritz step and checks ([`super::finish`]); a band (`spec.upper`) is always proven
/// complete by Sylvester's inertia count ([`super::verify_band`]): a missed mode is an error.
pub fn lowest_modes(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    spec: &EigenSpec,
    engine: &SlepcEngine,
) -> Result<EigenSolution, SolveError> {
    super::validate(k, m, spec.count)?;
    let request = Request {
        count: spec.count,
        upper: spec.upper,
        shift: spec
            .shift
            .unwrap_or_else(|| super::automatic_shift(super::trace_ratio(k, m))),
        // SLEPc's test is on the shift-inverted operator: a tenth of ours leaves our
        // residual check (below) its margin
        tol: 0.1 * spec.tol,
    };
    let sol = eigenpairs(k.as_ref(), m.as_ref(), request, engine)?;
    let info = EigenInfo {
        solver: super::Solver::Slepc,
        shift: request.shift,
        seconds_eigen: sol.seconds,
        engine_report: Some(format!(
            "engine slepc, {} MPI ranks: {}",
            engine.ranks, sol.report
        )),
        ..Default::default()
    };
    let mut vectors = sol.vectors;
    let checked = super::finish(k, m, &mut vectors, info, spec.tol)?;
    let band = EigenSpec {
        verify_band: spec.verify_band || spec.upper.is_some(),
        ..spec.clone()
    };
    super::verify_band(k, m, checked, &band)
}

fn run(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    kib: Option<SparseColMatRef<'_, usize, f64>>,
    request: Request,
    engine: &SlepcEngine,
) -> Result<SlepcSolution, SolveError> {
    let t = Instant::now();
    available().map_err(|why| {
        err(format!(
            "{why}: install MPI and slepc4py (Debian: openmpi-bin, python3-slepc4py-real) or \
             set FLEXBODY_MPIRUN / FLEXBODY_SLEPC_PYTHON"
        ))
    })?;
    let dir = run_dir()?;
    let result = run_in(&dir, k, m, kib, request, engine);
    let _ = std::fs::remove_dir_all(&dir);
    let (x, eigenvalues, vectors, report) = result?;
    Ok(SlepcSolution {
        x,
        eigenvalues,
        vectors,
        report,
        seconds: t.elapsed().as_secs_f64(),
    })
}

type Parts = (Mat<f64>, Vec<f64>, Mat<f64>, String);

fn run_in(
    dir: &Path,
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    kib: Option<SparseColMatRef<'_, usize, f64>>,
    request: Request,
    engine: &SlepcEngine,
) -> Result<Parts, SolveError> {
    let n = k.nrows();
    write_petsc_mat(&dir.join("K.petsc"), k)?;
    write_petsc_mat(&dir.join("M.petsc"), m)?;
    if let Some(kib) = kib {
        write_petsc_mat(&dir.join("Kib.petsc"), kib)?;
    }
    let script = dir.join("slepc_engine.py");
    std::fs::write(&script, SCRIPT).map_err(|e| io_err(&script, e))?;
    let (mpirun, python) = commands();
    let upper = request
        .upper
        .map_or_else(|| "none".to_string(), |u| format!("{u:e}"));
    let mut cmd = Command::new(&mpirun);
    cmd.arg("-np")
        .arg(engine.ranks.max(1).to_string())
        .arg(&python)
        .arg(&script)
        .arg(dir)
        .arg(request.count.to_string())
        .arg(format!("{:e}", request.tol))
        .arg(format!("{:e}", request.shift))
        .arg(upper)
        // OpenMPI refuses root without these; harmless otherwise
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .envs(package_env());
    let out = cmd.output().map_err(|e| {
        err(format!(
            "cannot run {mpirun} ({e}); install MPI and slepc4py (Debian: openmpi-bin, \
             python3-slepc4py-real) or set FLEXBODY_MPIRUN / FLEXBODY_SLEPC_PYTHON"
        ))
    })?;
    if !out.status.success() {
        return Err(script_failure(&out, &mpirun, &python, engine));
    }
    let report = String::from_utf8_lossy(&out.stdout)
        .lines()
        .last()
        .unwrap_or("")
        .to_string();
    let values_path = dir.join("values.txt");
    let text = std::fs::read_to_string(&values_path).map_err(|e| io_err(&values_path, e))?;
    let eigenvalues: Vec<f64> = text
        .lines()
        .map(|l| l.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| err(format!("values.txt: {e}")))?;
    let count = eigenvalues.len();
    // a band may hold fewer than the count it started from: its inertia count (always run on a
    // band, by the callers) decides whether it is complete
    let enough = match request.upper {
        None => count == request.count,
        Some(_) => count > 0,
    };
    if !enough || eigenvalues.iter().any(|v| !v.is_finite()) {
        return Err(err(format!(
            "values.txt holds {count} values, expected {} finite ones",
            request.count
        )));
    }
    let vectors = read_petsc_vecs(&dir.join("vectors.petsc"), n, count)?;
    let x = match kib {
        Some(kib) => read_petsc_vecs(&dir.join("psi.petsc"), n, kib.ncols())?,
        None => Mat::zeros(n, 0),
    };
    // ascending (the script sorts them; sort anyway)
    let mut order: Vec<usize> = (0..count).collect();
    order.sort_by(|&a, &b| eigenvalues[a].total_cmp(&eigenvalues[b]));
    let vals = order.iter().map(|&i| eigenvalues[i]).collect();
    let vecs = Mat::from_fn(n, count, |r, c| vectors[(r, order[c])]);
    Ok((x, vals, vecs, report))
}

/// The error of a failed script run: its own message (a Python exception or PETSc's) before
/// mpirun's banner.
fn script_failure(
    out: &std::process::Output,
    mpirun: &str,
    python: &str,
    engine: &SlepcEngine,
) -> SolveError {
    let stderr = String::from_utf8_lossy(&out.stderr);
    let errors: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("Error") || l.contains("error") || l.contains("SLEPc"))
        .take(6)
        .collect();
    let tail: Vec<&str> = if errors.is_empty() {
        stderr.lines().rev().take(8).collect()
    } else {
        errors.into_iter().rev().collect()
    };
    err(format!(
        "{mpirun} -np {} {python} slepc_engine.py failed ({}): {}",
        engine.ranks,
        out.status,
        tail.into_iter().rev().collect::<Vec<_>>().join(" | ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs of one process get distinct new directories, also when a name is taken already.
    #[test]
    fn each_run_gets_its_own_new_directory() {
        let a = run_dir().unwrap();
        // take the next name before the engine does: it is skipped, not shared
        let next = std::env::temp_dir().join(format!(
            "flexbody-slepc-{}-{}",
            std::process::id(),
            RUNS.load(Ordering::Relaxed)
        ));
        std::fs::create_dir(&next).unwrap();
        let b = run_dir().unwrap();
        assert!(
            a != b && b != next && a.is_dir() && b.is_dir(),
            "{a:?} {b:?} {next:?}"
        );
        for d in [a, b, next] {
            std::fs::remove_dir(d).unwrap();
        }
    }
}
