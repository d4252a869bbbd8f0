//! Issues 22 and 46, `build --engine slepc --mpi 2`: normal modes (free-free, six rigid-body
//! modes), Craig–Bampton (MUMPS factorization of K_ii, constraint modes, SLEPc Krylov–Schur
//! fixed-interface modes) and Craig–Chang (free-free modes) under `mpirun -np 2`, each with
//! `--modes` and with `--fmax`, the rest ours. Through the real binary on the bundled conrod: the
//! file's frequencies equal the native engine's to 1e-8 and its mode shapes span the same
//! subspaces (per mode up to sign, per group of repeated eigenvalues — the rigid-body modes — as
//! a subspace), both files pass `check --model`, and a band (`--fmax`) is proven complete by
//! Sylvester's inertia count with either engine. Without `mpirun` or a Python with slepc4py
//! (Debian: openmpi-bin, python3-slepc4py-real) the comparisons are skipped with a visible
//! message (`crate::common::skipped_install`: a failure under `CI=true`, where `.ci/run` installs
//! them); the refusals that need no engine are always tested.

use crate::common::{exe, scratch};
use flexbody_reader::{ModeLabel, ReducedBody};
use std::path::{Path, PathBuf};
use std::process::Output;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn conrod() -> String {
    root()
        .join("fixtures/models/conrod/conrod.inp")
        .display()
        .to_string()
}

/// `flexbody build conrod --interface BIG_END,SMALL_END ARGS --engine ENGINE --mpi 2 -o OUT`
/// with `env` set.
fn build(args: &[&str], engine: &str, env: &[(&str, &str)], out: &Path) -> Output {
    exe()
        .args(["build", &conrod(), "--interface", "BIG_END,SMALL_END"])
        .args(["--units", "si"])
        .args(args)
        .args(["--engine", engine, "--mpi", "2", "-o"])
        .arg(out)
        .envs(env.iter().copied())
        .output()
        .unwrap()
}

fn engine_missing() -> bool {
    match flexbody::solve::slepc::available() {
        Ok(()) => false,
        Err(why) => {
            crate::common::skipped_install(
                &format!("the SLEPc engine check (engine_slepc): {why}"),
                "apt-get install openmpi-bin python3-slepc4py-real",
            );
            true
        }
    }
}

/// Builds `args` with both engines and checks what every build must: success, the engine's
/// note, `check --model`; returns (native, slepc) files and the slepc build's stderr.
fn both_engines(name: &str, args: &[&str]) -> (ReducedBody, ReducedBody, String, PathBuf) {
    let dir = scratch(name);
    let mut bodies = Vec::new();
    let mut slepc_err = String::new();
    for engine in ["native", "slepc"] {
        let out = dir.join(format!("{engine}.flexbody"));
        let o = build(args, engine, &[], &out);
        let stderr = String::from_utf8_lossy(&o.stderr).to_string();
        assert!(o.status.success(), "{name} {engine}: {stderr}");
        let c = exe()
            .args(["check"])
            .arg(&out)
            .args(["--model", &conrod()])
            .output()
            .unwrap();
        assert!(
            c.status.success(),
            "{name} {engine}: check --model failed: {}{}",
            String::from_utf8_lossy(&c.stdout),
            String::from_utf8_lossy(&c.stderr)
        );
        if engine == "slepc" {
            assert!(
                stderr.contains("engine slepc, 2 MPI ranks") && stderr.contains("\"ranks\": 2"),
                "{name}: {stderr}"
            );
            slepc_err = stderr;
        }
        bodies.push(flexbody_reader::read(&out).unwrap());
    }
    let slepc = bodies.pop().unwrap();
    let native = bodies.pop().unwrap();
    (native, slepc, slepc_err, dir)
}

/// Largest relative frequency difference over the flexible modes (rigid ones: by count).
fn frequency_difference(a: &ReducedBody, b: &ReducedBody) -> f64 {
    let (fa, fb) = (&a.modes.frequency_hz, &b.modes.frequency_hz);
    assert_eq!(fa.len(), fb.len(), "mode counts {fa:?} vs {fb:?}");
    assert_eq!(a.modes.labels, b.modes.labels);
    fa.iter()
        .zip(fb)
        .zip(&a.modes.labels)
        .filter(|(_, l)| **l != ModeLabel::Rigid)
        .map(|((x, y), _)| (x - y).abs() / x)
        .fold(0.0, f64::max)
}

/// The groups of modes compared as subspaces: the rigid-body modes together, and flexible modes
/// whose frequencies agree to 1e-6 (repeated eigenvalues).
fn groups(body: &ReducedBody) -> Vec<Vec<usize>> {
    let (f, labels) = (&body.modes.frequency_hz, &body.modes.labels);
    let mut out: Vec<Vec<usize>> = Vec::new();
    for j in 0..f.len() {
        let joins = out.last().is_some_and(|g| {
            let i = *g.last().unwrap(); // groups are never empty
            (labels[i] == ModeLabel::Rigid && labels[j] == ModeLabel::Rigid)
                || (f[j] - f[i]).abs() <= 1e-6 * f[j]
        });
        match out.last_mut() {
            Some(g) if joins => g.push(j),
            _ => out.push(vec![j]),
        }
    }
    out
}

fn shape(body: &ReducedBody, j: usize) -> &[f64] {
    let len = body.modes.shapes.len() / body.modes.frequency_hz.len();
    &body.modes.shapes[j * len..(j + 1) * len]
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Largest ‖φ − QQᵀφ‖/‖φ‖ of the native file's stored mode shapes φ against an orthonormal
/// basis Q of the slepc file's shapes of the same group (sign and rotation within repeated
/// eigenvalues do not count).
fn shape_difference(a: &ReducedBody, b: &ReducedBody) -> f64 {
    let mut worst = 0.0f64;
    for g in groups(a) {
        // Q: Gram–Schmidt (twice) on b's shapes of the group
        let mut q: Vec<Vec<f64>> = Vec::new();
        for &j in &g {
            let mut v = shape(b, j).to_vec();
            for _ in 0..2 {
                for u in &q {
                    let c = dot(u, &v);
                    v.iter_mut().zip(u).for_each(|(x, y)| *x -= c * y);
                }
            }
            let norm = dot(&v, &v).sqrt();
            q.push(v.into_iter().map(|x| x / norm).collect());
        }
        for &j in &g {
            let phi = shape(a, j);
            let mut r = phi.to_vec();
            for u in &q {
                let c = dot(u, phi);
                r.iter_mut().zip(u).for_each(|(x, y)| *x -= c * y);
            }
            worst = worst.max((dot(&r, &r) / dot(phi, phi)).sqrt());
        }
    }
    worst
}

/// Both engines on one request: frequencies and mode shapes agree; a band is proven complete.
fn engines_agree(name: &str, args: &[&str], band_modes: &str) -> (usize, f64, f64) {
    let (native, slepc, stderr, dir) = both_engines(name, args);
    if !band_modes.is_empty() {
        assert!(
            stderr.contains("band check: the eigensolver's")
                && stderr.contains(&format!(" {band_modes} are all the eigenvalues below")),
            "{name}: {stderr}"
        );
    }
    let df = frequency_difference(&native, &slepc);
    let ds = shape_difference(&native, &slepc);
    let _ = std::fs::remove_dir_all(&dir);
    (native.modes.frequency_hz.len(), df, ds)
}

#[test]
fn slepc_normal_modes_match_the_native_engine() {
    if engine_missing() {
        return;
    }
    for (args, band) in [
        (&["--method", "normal", "--modes", "12"][..], ""),
        (
            &["--method", "normal", "--fmax", "3000"][..],
            "lowest normal modes",
        ),
    ] {
        let (n, df, ds) = engines_agree("slepc-normal", args, band);
        println!("conrod normal modes {args:?}: {n} modes, native vs slepc frequencies {df:.2e}, shapes {ds:.2e}");
        // measured (2 ranks, 2026-12-07): frequencies <= 1.7e-11 over the six builds (CB with
        // --modes 12 the largest), shapes <= 2.4e-9 (the same build); 1e-8 is issue 46's bound
        assert!(df < 2e-10, "{args:?}: frequencies differ by {df:e}");
        assert!(ds < 1e-8, "{args:?}: mode shapes differ by {ds:e}");
    }
}

#[test]
fn slepc_craig_bampton_matches_the_native_engine() {
    if engine_missing() {
        return;
    }
    for (args, band) in [
        (
            &["--modes", "12", "--verify-band"][..],
            "12 lowest fixed-interface modes",
        ),
        (&["--fmax", "3000"][..], "lowest fixed-interface modes"),
    ] {
        let (n, df, ds) = engines_agree("slepc-cb", args, band);
        println!(
            "conrod CB {args:?}: {n} modes, native vs slepc frequencies {df:.2e}, shapes {ds:.2e}"
        );
        // measured (2 ranks, 2026-12-07): frequencies <= 1.7e-11 over the six builds (CB with
        // --modes 12 the largest), shapes <= 2.4e-9 (the same build); 1e-8 is issue 46's bound
        assert!(df < 2e-10, "{args:?}: frequencies differ by {df:e}");
        assert!(ds < 1e-8, "{args:?}: mode shapes differ by {ds:e}");
    }
}

#[test]
fn slepc_craig_chang_matches_the_native_engine() {
    if engine_missing() {
        return;
    }
    for (args, band) in [
        (&["--method", "craig-chang", "--modes", "12"][..], ""),
        (
            &["--method", "craig-chang", "--fmax", "3000"][..],
            "lowest free-free modes",
        ),
    ] {
        let (n, df, ds) = engines_agree("slepc-cc", args, band);
        println!("conrod Craig-Chang {args:?}: {n} modes, native vs slepc frequencies {df:.2e}, shapes {ds:.2e}");
        // measured (2 ranks, 2026-12-07): frequencies <= 1.7e-11 over the six builds (CB with
        // --modes 12 the largest), shapes <= 2.4e-9 (the same build); 1e-8 is issue 46's bound
        assert!(df < 2e-10, "{args:?}: frequencies differ by {df:e}");
        assert!(ds < 1e-8, "{args:?}: mode shapes differ by {ds:e}");
    }
}

/// A Python that drops the eighth eigenpair the engine's script returned (values.txt and
/// vectors.petsc), as an eigensolver that skipped a mode inside the band would; other uses (the
/// engine's probe) run the real one.
const DROP_A_MODE: &str = r#"#!/bin/sh
case "$1" in *slepc_engine.py) ;; *) exec /usr/bin/python3 "$@" ;; esac
/usr/bin/python3 "$@" || exit $?
[ "${OMPI_COMM_WORLD_RANK:-0}" = 0 ] || exit 0
exec /usr/bin/python3 - "$2" <<'EOF'
import os, sys
d = sys.argv[1]
vals = open(f"{d}/values.txt").read().splitlines()
raw = open(f"{d}/vectors.petsc", "rb").read()
size = len(raw) // len(vals)
del vals[7]
raw = raw[: 7 * size] + raw[8 * size :]
open(f"{d}/values.txt", "w").write("".join(v + "\n" for v in vals))
open(f"{d}/vectors.petsc", "wb").write(raw)
EOF
"#;

#[test]
fn slepc_engine_reports_an_incomplete_band() {
    if engine_missing() {
        return;
    }
    let dir = scratch("slepc-incomplete");
    let python = dir.join("drop-a-mode");
    std::fs::write(&python, DROP_A_MODE).unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&python, std::fs::Permissions::from_mode(0o755)).unwrap();
    let python = python.display().to_string();
    for args in [
        &["--method", "normal", "--fmax", "3000"][..],
        &["--fmax", "3000"][..],
        &["--method", "craig-chang", "--fmax", "3000"][..],
    ] {
        let out = dir.join("x.flexbody");
        let o = build(args, "slepc", &[("FLEXBODY_SLEPC_PYTHON", &python)], &out);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?}: {stderr}");
        assert!(
            stderr.contains("band check failed") && stderr.contains("has 1 more negative pivots"),
            "{args:?}: {stderr}"
        );
        assert!(!out.exists(), "{args:?}");
        let why = stderr.lines().find(|l| l.contains("band check failed"));
        println!("{args:?} with a mode dropped: {}", why.unwrap_or_default());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn slepc_engine_refuses_what_it_cannot_run() {
    let dir = scratch("slepc-refuse");
    let out = dir.join("x.flexbody");
    // Dietz is not routed through the engine
    let o = build(&["--method", "dietz", "--modes", "6"], "slepc", &[], &out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        stderr.contains("--engine slepc runs normal modes, Craig-Chang and the Craig-Bampton"),
        "{stderr}"
    );
    assert!(!out.exists());
    // AMLS is the native engine's eigensolver
    let o = build(
        &["--eigensolver", "amls", "--modes", "6"],
        "slepc",
        &[],
        &out,
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        stderr.contains("--eigensolver amls applies to the native engine only"),
        "{stderr}"
    );
    assert!(!out.exists());
    // an engine name we do not have
    let o = build(&["--modes", "6"], "petsc", &[], &out);
    assert!(!o.status.success());
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("expected native or slepc"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // no mpirun
    for method in ["normal", "cb", "craig-chang"] {
        let args = ["--method", method, "--modes", "8"];
        let missing = [("FLEXBODY_MPIRUN", "/nonexistent/mpirun")];
        let o = build(&args, "slepc", &missing, &out);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{method}: {stderr}");
        assert!(
            stderr.contains(
                "--engine slepc: /nonexistent/mpirun not found: install MPI and \
                             slepc4py (Debian: openmpi-bin, python3-slepc4py-real)"
            ),
            "{method}: {stderr}"
        );
        assert!(!out.exists(), "{method}");
    }
    // an mpirun, but a Python without slepc4py (-I -S: no site or dist-packages)
    let python = dir.join("python-without-slepc");
    std::fs::write(&python, "#!/bin/sh\nexec python3 -I -S \"$@\"\n").unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&python, std::fs::Permissions::from_mode(0o755)).unwrap();
    let python = python.display().to_string();
    let env = [
        ("FLEXBODY_MPIRUN", "true"),
        ("FLEXBODY_SLEPC_PYTHON", &python),
    ];
    let o = build(&["--method", "normal", "--modes", "8"], "slepc", &env, &out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "{python} cannot import slepc4py: install MPI and slepc4py"
        )),
        "{stderr}"
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
