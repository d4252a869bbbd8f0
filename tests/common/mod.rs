//! Test support: the reference-data paths, reading the reference meshes through the `.inp`
//! importer, dense copies of sparse matrices, a dense generalized symmetric eigen-solve for small
//! systems, the engine's assemble → eliminate → lowest modes in one call, and for the CLI tests the binary, a scratch folder and a Python module probe.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

use faer::sparse::SparseColMat;
use faer::Mat;
use flexbody::model::{
    Element, ElementKind, Material, Model, Node, Property, Section, ShellSection,
};

/// A file of the CalculiX reference cases the repository holds (`fixtures/reference/`, made by
/// `fixtures/reference/regenerate.py` from the decks beside them).
pub fn reference(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/reference")
        .join(rel)
}

/// The environment variable naming the folder of reference data the project may not
/// redistribute (real Nastran decks with their f06 results, CalculiX's own test decks).
pub const EXTERNAL_REFERENCE_ENV: &str = "FLEXBODY_REFERENCE";

/// The external reference folder: `$FLEXBODY_REFERENCE`, else `../shared/reference` beside the
/// repository.
pub fn external_reference_dir() -> PathBuf {
    match std::env::var_os(EXTERNAL_REFERENCE_ENV) {
        Some(dir) if !dir.is_empty() => PathBuf::from(dir),
        _ => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/reference"),
    }
}

/// `rel` inside the external reference folder, or `None` after printing a SKIPPED line for
/// `test` that names the variable to set. Tests that need the data return early on `None`.
pub fn external_reference(test: &str, rel: &str) -> Option<PathBuf> {
    let path = external_reference_dir().join(rel);
    if path.exists() {
        return Some(path);
    }
    skipped(&format!(
        "{test}: needs {rel} from the external reference data (not redistributable, not in the \
         repository); set {EXTERNAL_REFERENCE_ENV} to the folder that holds it (default \
         ../shared/reference beside the repository; looked in {})",
        external_reference_dir().display()
    ));
    None
}

/// Debian's `calculix-ccx-test` folder: CalculiX's test decks with their `.dat.ref` results
/// (ccx 2.11's), many gzipped.
pub const DEBIAN_CCX_SUITE: &str = "/usr/share/doc/calculix-ccx-test/examples/test";

/// A folder holding the CalculiX test-suite files `names` (decks, `.dat.ref`s): `ccx_tests/` of
/// the external reference data when it has them all, else a scratch copy from Debian's
/// `calculix-ccx-test` (`NAME` or `NAME.gz`, decompressed); `None` after a skip without either
/// (a failure under `CI=true`: `.ci/run` installs the package).
pub fn ccx_suite(test: &str, names: &[&str]) -> Option<PathBuf> {
    let external = external_reference_dir().join("ccx_tests");
    if names.iter().all(|n| external.join(n).exists()) {
        return Some(external);
    }
    let debian = Path::new(DEBIAN_CCX_SUITE);
    let find = |n: &str| {
        let plain = debian.join(n);
        let zipped = debian.join(format!("{n}.gz"));
        (plain.exists().then_some(plain)).or(zipped.exists().then_some(zipped))
    };
    if names.iter().any(|n| find(n).is_none()) {
        skipped_install(
            &format!(
                "{test}: needs {names:?} from CalculiX's test suite: neither {} nor {DEBIAN_CCX_SUITE} \
                 holds them",
                external.display()
            ),
            "apt-get install calculix-ccx-test",
        );
        return None;
    }
    let dir = scratch(&format!("ccx-suite-{test}"));
    for n in names {
        // find(n) is Some: every name was found just above
        let from = find(n).unwrap();
        let text = if from.extension().is_some_and(|e| e == "gz") {
            let o = Command::new("gzip").arg("-dc").arg(&from).output().unwrap();
            assert!(o.status.success(), "gzip -dc {}", from.display());
            o.stdout
        } else {
            std::fs::read(&from).unwrap()
        };
        std::fs::write(dir.join(n), text).unwrap();
    }
    Some(dir)
}

/// Prints `SKIPPED <what>` where the test runner shows it: straight to the process's stderr,
/// past the harness's capture of `println!`/`eprintln!`, so a skip is never silent (`.ci/run`
/// counts these lines). For what `.ci/run` does not install (data outside the repository, a
/// library the user points to); a check of something `.ci/run` installs skips through
/// [`skipped_install`].
pub fn skipped(what: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "SKIPPED {what}");
}

/// Whether this run is CI's (`CI=true`, as CI runs `.ci/run`).
pub fn on_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true")
}

/// A check that cannot run because `install` (a Debian or PyPI package `.ci/run` installs) is
/// missing: a visible skip ([`skipped`]) on a developer's machine, a failure under `CI=true`,
/// where `.ci/run` has installed it and a missing tool means the check silently stopped running.
pub fn skipped_install(what: &str, install: &str) {
    if on_ci() {
        panic!(
            "{what}: this check needs what `{install}` installs, and CI=true: .ci/run installs \
             it, so the check must run in CI, not skip"
        );
    }
    skipped(&format!("{what} (install: {install})"));
}

/// The relative differences |ours − reference| / reference of the modes after the first `rigid`
/// (zero-frequency modes, compared by count only), or why the two cannot be compared: not the
/// same number of modes (a build that lost a mode never "matches" on the rest).
pub fn frequency_differences(
    ours: &[f64],
    reference: &[f64],
    rigid: usize,
) -> Result<Vec<f64>, String> {
    if ours.len() != reference.len() {
        return Err(format!(
            "{} modes against the reference's {} (ours {ours:?}, reference {reference:?})",
            ours.len(),
            reference.len()
        ));
    }
    if rigid > ours.len() {
        return Err(format!(
            "{rigid} rigid modes of {} (ours {ours:?})",
            ours.len()
        ));
    }
    Ok((ours[rigid..].iter().zip(&reference[rigid..]))
        .map(|(a, b)| (a - b).abs() / b.abs())
        .collect())
}

/// The one comparison of frequencies with a reference: asserts the mode counts are equal, then
/// that each mode after the first `rigid` is within `tol` (relative) of the reference's;
/// returns the worst relative difference. Compare the first n of a longer list by passing
/// `&x[..n]` after asserting the list is that long.
pub fn assert_frequencies(
    what: &str,
    ours: &[f64],
    reference: &[f64],
    rigid: usize,
    tol: f64,
) -> f64 {
    let rel =
        frequency_differences(ours, reference, rigid).unwrap_or_else(|e| panic!("{what}: {e}"));
    let worst = rel.iter().cloned().fold(0.0, f64::max);
    assert!(
        rel.iter().all(|r| *r <= tol),
        "{what}: worst relative difference {worst:.2e} > {tol:.0e}\nours      {ours:?}\nreference {reference:?}"
    );
    worst
}

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

/// Read a reference mesh.inp with the `.inp` importer; solids without a section get steel.
pub fn read_mesh_inp(path: &Path) -> Model {
    let opts = flexbody::import::ImportOptions {
        material: Some(steel()),
        ..Default::default()
    };
    flexbody::import::read_model(path, &opts).expect("reference mesh.inp imports")
}

pub fn dense(a: &SparseColMat<usize, f64>) -> Mat<f64> {
    let a = a.as_ref();
    let mut d = Mat::zeros(a.nrows(), a.ncols());
    for j in 0..a.ncols() {
        for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            d[(i, j)] += v;
        }
    }
    d
}

/// Eigenvalues λ of K x = λ M x (M positive definite), ascending, via M = LLᵀ and
/// L⁻¹ K L⁻ᵀ (dense; for n up to a few thousand).
pub fn generalized_eigenvalues(k: &Mat<f64>, m: &Mat<f64>) -> Vec<f64> {
    let n = k.nrows();
    let llt = m.llt(faer::Side::Lower).expect("M positive definite");
    let l = llt.L();
    // A = L⁻¹ K L⁻ᵀ
    let mut a = k.clone();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, a.as_mut(), faer::Par::Seq);
    let mut at = a.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, at.as_mut(), faer::Par::Seq);
    let sym = Mat::from_fn(n, n, |i, j| 0.5 * (at[(i, j)] + at[(j, i)]));
    let mut ev = sym
        .self_adjoint_eigenvalues(faer::Side::Lower)
        .expect("eigenvalues converge");
    ev.sort_by(f64::total_cmp);
    ev
}

/// The lowest eigenvalues λ = ω² of `model` as the pipeline's engine forms them: assembled by
/// `spec`, the constraints eliminated as `constraints` says, solved by `solve::lowest_modes`
/// with `eigen` (its count, shift, dofs per node).
pub fn lowest_eigenvalues(
    model: &Model,
    spec: &flexbody::fe::AssemblySpec,
    constraints: &flexbody::fe::ConstraintSpec,
    eigen: &flexbody::solve::EigenSpec,
) -> Vec<f64> {
    let asm = flexbody::fe::assemble(model, spec).expect("assembly");
    let red = flexbody::fe::eliminate(model, &asm.dofs, &asm.k, &asm.m, constraints)
        .expect("constraints");
    flexbody::solve::lowest_modes(&red.k, &red.m, eigen)
        .expect("eigen-solve")
        .eigenvalues
}

/// `flexbody build` of the Nastran deck `text` (written as `NAME.bdf` in a scratch folder) with
/// normal modes and SI units (the deck's mass and mode count); panics with the build's stderr
/// on failure → (frequencies, stderr).
pub fn build_bdf_modes(name: &str, text: &str) -> (Vec<f64>, String) {
    let dir = scratch(name);
    let path = dir.join(format!("{name}.bdf"));
    std::fs::write(&path, text).unwrap();
    let out = dir.join(format!("{name}.flexbody"));
    let o = exe()
        .arg("build")
        .arg(&path)
        .args(["--units", "si", "--method", "normal", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{name}: {stderr}");
    let body = flexbody_reader::read(&out).unwrap();
    (body.modes.frequency_hz, stderr)
}

/// Hz from ω².
pub fn hz(lambda: f64) -> f64 {
    lambda.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// ccx 2.20's frequencies of `key` (a deck stem, or `stem:BASE`) in `fixtures/FOLDER/results.json`
/// (our own small decks, written by `fixtures/ccx_frequencies.py`).
pub fn ccx_frequencies(folder: &str, key: &str) -> Vec<f64> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join(folder)
        .join("results.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    (v[key].as_array())
        .unwrap_or_else(|| panic!("{key} in {}", path.display()))
        .iter()
        .map(|f| f.as_f64().unwrap())
        .collect()
}

/// The `flexbody` binary under test.
pub fn exe() -> Command {
    Command::new(env!("CARGO_BIN_EXE_flexbody"))
}

/// `flexbody build DECK EXTRA… --units si --method normal --mass consistent -o OUT`: a deck
/// built as CalculiX's `*FREQUENCY` step solves it (consistent mass, the deck's SI numbers).
pub fn build_as_ccx(deck: &Path, extra: &[&str], out: &Path) -> std::process::Output {
    exe()
        .arg("build")
        .arg(deck)
        .args(extra)
        .args([
            "--units",
            "si",
            "--method",
            "normal",
            "--mass",
            "consistent",
            "-o",
        ])
        .arg(out)
        .output()
        .unwrap()
}

/// The README's first build of the bundled conrod (spiders on both bores, `--fmax 3000`, SI,
/// quiet) with `extra` options, written to `out`; panics with the build's stderr on failure.
pub fn build_conrod(out: &Path, extra: &[&str]) {
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp");
    let o = exe()
        .arg("build")
        .arg(&model)
        .args(["--interface", "BIG_END,SMALL_END", "--fmax", "3000"])
        .args(["--units", "si", "-q"])
        .args(extra)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "build failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A fresh folder under the system temp dir for one test (`name` unique within the test binary).
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexbody-test-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `python3 SCRIPT ARGS…` (SCRIPT relative to the repository) in `dir` (None: here), with the
/// package `python/` on PYTHONPATH and FLEXBODY naming the binary under test: its stdout,
/// printed; panics with stdout and stderr when it fails.
pub fn run_python<S: AsRef<std::ffi::OsStr>>(
    script: &str,
    args: &[S],
    dir: Option<&Path>,
) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut cmd = Command::new("python3");
    cmd.arg(root.join(script))
        .args(args)
        .env("PYTHONPATH", root.join("python"))
        .env("FLEXBODY", env!("CARGO_BIN_EXE_flexbody"));
    if let Some(dir) = dir {
        cmd.current_dir(dir);
    }
    let o = cmd.output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    println!("{out}");
    assert!(
        o.status.success(),
        "{script} failed:\n{out}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    out
}

/// `flexbody export BODY --to TO -o OUT`.
pub fn export(body: &Path, to: &str, out: &Path) -> std::process::Output {
    exe()
        .arg("export")
        .arg(body)
        .args(["--to", to, "-o"])
        .arg(out)
        .output()
        .unwrap()
}

/// RFC 4648 base64 → bytes, up to and including the first padded block; also how many
/// characters that used (a VTK binary array is two such blocks: byte count, then data).
pub fn base64_block(text: &str) -> (Vec<u8>, usize) {
    let value = |c: u8| -> u32 {
        match c {
            b'A'..=b'Z' => u32::from(c - b'A'),
            b'a'..=b'z' => u32::from(c - b'a') + 26,
            b'0'..=b'9' => u32::from(c - b'0') + 52,
            b'+' => 62,
            b'/' => 63,
            _ => panic!("not base64: {c}"),
        }
    };
    let mut out = Vec::new();
    let mut used = 0;
    for quad in text.as_bytes().chunks(4) {
        used += 4;
        let pad = quad.iter().filter(|&&c| c == b'=').count();
        let mut triple = 0u32;
        for &c in quad {
            triple = (triple << 6) | if c == b'=' { 0 } else { value(c) };
        }
        out.extend_from_slice(&triple.to_be_bytes()[1..4 - pad]);
        if pad > 0 {
            break;
        }
    }
    (out, used)
}

/// Whether `python3` imports `module` (the Python checks skip visibly without it).
pub fn python_has(module: &str) -> bool {
    Command::new("python3")
        .args(["-c", &format!("import {module}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Structured n×m mesh of the map (s, r) ∈ [0,1]² → `at(s, r)`; quads, or each quad split
/// into two triangles along alternating diagonals.
pub fn shell_grid(
    n: usize,
    m: usize,
    tris: bool,
    t: f64,
    mat: Material,
    at: impl Fn(f64, f64) -> [f64; 3],
) -> Model {
    let mesh = if tris {
        ShellMesh::Tri3
    } else {
        ShellMesh::Quad4
    };
    shell_mesh(mesh, n, m, t, mat, at)
}

/// The element kind of a [`shell_mesh`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShellMesh {
    /// 4-node quadrilaterals.
    Quad4,
    /// 3-node triangles, two per cell along alternating diagonals.
    Tri3,
    /// 8-node quadrilaterals (mid-side nodes on the map).
    Quad8,
    /// 6-node triangles, two per cell along alternating diagonals.
    Tri6,
}

impl ShellMesh {
    /// The four kinds.
    pub const ALL: [ShellMesh; 4] = [
        ShellMesh::Quad4,
        ShellMesh::Tri3,
        ShellMesh::Quad8,
        ShellMesh::Tri6,
    ];

    /// Quadratic elements (mid-side nodes).
    pub fn quadratic(self) -> bool {
        matches!(self, ShellMesh::Quad8 | ShellMesh::Tri6)
    }

    /// Triangles.
    pub fn tris(self) -> bool {
        matches!(self, ShellMesh::Tri3 | ShellMesh::Tri6)
    }
}

/// Structured n×m mesh of `mesh` elements on the map (s, r) ∈ [0,1]² → `at(s, r)`
/// (quadratic elements: mid-side nodes on the map; no unused node).
pub fn shell_mesh(
    mesh: ShellMesh,
    n: usize,
    m: usize,
    t: f64,
    mat: Material,
    at: impl Fn(f64, f64) -> [f64; 3],
) -> Model {
    let mut model = Model {
        source: "generated".into(),
        ..Model::default()
    };
    let q = if mesh.quadratic() { 2 } else { 1 };
    let (gn, gm) = (q * n, q * m);
    // grid point (i, j) → node index; quad8 cells leave their centres out
    let mut index = vec![usize::MAX; (gn + 1) * (gm + 1)];
    for j in 0..=gm {
        for i in 0..=gn {
            if mesh == ShellMesh::Quad8 && i % 2 == 1 && j % 2 == 1 {
                continue;
            }
            index[j * (gn + 1) + i] = model.nodes.len();
            model.nodes.push(Node {
                id: (j * (gn + 1) + i + 1) as u64,
                x: at(i as f64 / gn as f64, j as f64 / gm as f64),
                displacement_frame: None,
            });
        }
    }
    model.materials.push(mat);
    model.properties.push(Property {
        id: 1,
        name: "SHELL".into(),
        material: 0,
        section: Section::Shell(ShellSection::homogeneous(t, 0)),
    });
    let idx = |i: usize, j: usize| index[j * (gn + 1) + i];
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
    for j in 0..m {
        for i in 0..n {
            let (i0, j0) = (q * i, q * j);
            let (a, b, c, d) = (
                idx(i0, j0),
                idx(i0 + q, j0),
                idx(i0 + q, j0 + q),
                idx(i0, j0 + q),
            );
            let alt = (i + j) % 2 == 0;
            match mesh {
                ShellMesh::Quad4 => push(ElementKind::Quad4, vec![a, b, c, d]),
                ShellMesh::Tri3 if alt => {
                    push(ElementKind::Tri3, vec![a, b, c]);
                    push(ElementKind::Tri3, vec![a, c, d]);
                }
                ShellMesh::Tri3 => {
                    push(ElementKind::Tri3, vec![a, b, d]);
                    push(ElementKind::Tri3, vec![b, c, d]);
                }
                ShellMesh::Quad8 => push(
                    ElementKind::Quad8,
                    vec![
                        a,
                        b,
                        c,
                        d,
                        idx(i0 + 1, j0),
                        idx(i0 + 2, j0 + 1),
                        idx(i0 + 1, j0 + 2),
                        idx(i0, j0 + 1),
                    ],
                ),
                ShellMesh::Tri6 => {
                    let (ab, bc, cd, da, mid) = (
                        idx(i0 + 1, j0),
                        idx(i0 + 2, j0 + 1),
                        idx(i0 + 1, j0 + 2),
                        idx(i0, j0 + 1),
                        idx(i0 + 1, j0 + 1),
                    );
                    if alt {
                        push(ElementKind::Tri6, vec![a, b, c, ab, bc, mid]);
                        push(ElementKind::Tri6, vec![a, c, d, mid, cd, da]);
                    } else {
                        push(ElementKind::Tri6, vec![a, b, d, ab, mid, da]);
                        push(ElementKind::Tri6, vec![b, c, d, bc, cd, mid]);
                    }
                }
            }
        }
    }
    model
}
