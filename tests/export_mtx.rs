//! K/M export in Matrix Market (`build --write-matrices`, the `mtx` export target) against
//! CalculiX 2.20's own matrix dumps of the shared reference blocks
//! (`fixtures/reference/e_matrices/`, `*FREQUENCY, SOLVER=MATRIXSTORAGE`): entry by entry,
//! matched through the two dof tables, relative to the largest entry; plus the written matrices
//! against the modes `build` wrote (Φᵀ M Φ = I, Φᵀ K Φ = diag ω²), which shows they are the
//! matrices the build reduced.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::reference;
use flexbody::build::BuildSpec;
use flexbody::export::mtx::export_mtx;
use flexbody::import::ccx_matrices::read_ccx_matrices;
use flexbody::import::matrix_market::read_matrix;
use flexbody_reader as file;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("flexbody-mtx-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `dofs.txt`: equation k → (node id, component 0…5); checks the numbering is 1, 2, ….
fn read_dofs(path: &Path) -> Vec<(u64, usize)> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .enumerate()
        .map(|(k, l)| {
            let f: Vec<u64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            assert_eq!(f[0], k as u64 + 1, "{l}");
            assert!((1..=6).contains(&f[2]), "{l}");
            (f[1], f[2] as usize - 1)
        })
        .collect()
}

type Keyed = HashMap<((u64, usize), (u64, usize)), f64>;

fn keyed(entries: Vec<(usize, usize, f64)>, dofs: &[(u64, usize)]) -> Keyed {
    entries
        .into_iter()
        .map(|(r, c, v)| ((dofs[r], dofs[c]), v))
        .collect()
}

/// max |ours − ccx| / max |ccx| over the union of stored entries.
fn rel_diff(ours: &Keyed, ccx: &Keyed) -> f64 {
    let scale = ccx.values().fold(0.0f64, |a, v| a.max(v.abs()));
    let diff = ours
        .keys()
        .chain(ccx.keys())
        .map(|k| (ours.get(k).unwrap_or(&0.0) - ccx.get(k).unwrap_or(&0.0)).abs())
        .fold(0.0f64, f64::max);
    diff / scale
}

/// Exports `case/stem.inp` (consistent mass, CalculiX's 4-point tet10 rule, the default) and
/// compares with `case/stem.{sti,mas,dof}`; returns (K, M) relative differences.
fn compare(case: &str, stem: &str) -> (f64, f64) {
    let model = reference(&format!("e_matrices/{case}/{stem}.inp"));
    let mut spec = BuildSpec::new(model, file::Units::si(), &[]);
    spec.mass = flexbody::fe::MassKind::Consistent;
    spec.mass_explicit = true;
    let dir = tmp(&format!("{case}-{stem}"));
    let written = export_mtx(&spec, &dir).unwrap();
    assert_eq!(written.len(), 4, "K.mtx, M.mtx, dofs.txt, coords.csv");
    let d = compare_written(case, stem, &dir);
    std::fs::remove_dir_all(&dir).ok();
    d
}

/// `dir`'s `K.mtx`, `M.mtx`, `dofs.txt` against `case/stem.{sti,mas,dof}`: the dof tables must
/// be equal; returns (K, M) relative differences.
fn compare_written(case: &str, stem: &str, dir: &Path) -> (f64, f64) {
    let dofs = read_dofs(&dir.join("dofs.txt"));
    let ccx = read_ccx_matrices(&reference(&format!("e_matrices/{case}/{stem}"))).unwrap();
    let ccx_dofs: Vec<(u64, usize)> = ccx.dofs.iter().map(|d| (d.node, d.dir as usize)).collect();
    // Same dofs in the same order: the documented order is CalculiX's equation order here.
    assert_eq!(dofs, ccx_dofs, "{case}/{stem}: dof tables");
    let k = read_matrix(&dir.join("K.mtx")).unwrap();
    let m = read_matrix(&dir.join("M.mtx")).unwrap();
    assert_eq!((k.n, m.n), (dofs.len(), dofs.len()));
    let ek = rel_diff(&keyed(k.full(), &dofs), &keyed(ccx.k.full(), &ccx_dofs));
    let em = rel_diff(
        &keyed(m.full(), &dofs),
        &keyed(ccx.m.as_ref().unwrap().full(), &ccx_dofs),
    );
    eprintln!("{case}/{stem}: max rel. difference K {ek:.2e}, M {em:.2e}");
    (ek, em)
}

#[test]
fn hex8_single_mtx_equals_ccx_dump() {
    let (ek, em) = compare("hex8_single", "ccx_matrix_free");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}

#[test]
fn tet10_single_mtx_equals_ccx_dump() {
    let (ek, em) = compare("tet10_single", "ccx_matrix_free");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}

#[test]
fn hex8_block_free_and_fixed_mtx_equal_ccx_dumps() {
    for stem in ["ccx_matrix_free", "ccx_matrix_fixed"] {
        let (ek, em) = compare("hex8_block_coarse", stem);
        assert!(ek < 1e-10 && em < 1e-10, "{stem}: K {ek:e}, M {em:e}");
    }
}

#[test]
fn tet10_block_mtx_equals_ccx_dump() {
    let (ek, em) = compare("tet10_block_coarse", "ccx_matrix_free");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}

/// Φᵀ A Φ from the written matrix and the file's shapes at the equations' dofs.
fn project(a: &flexbody::import::ccx_matrices::SymmetricTriplets, phi: &[Vec<f64>]) -> Vec<f64> {
    let nm = phi.len();
    let mut out = vec![0.0; nm * nm];
    for (r, c, v) in a.full() {
        for i in 0..nm {
            for j in 0..nm {
                out[i * nm + j] += phi[i][r] * v * phi[j][c];
            }
        }
    }
    out
}

/// `build --write-matrices` on the conrod (lumped mass, two RBE2 bore spiders, CB): the written
/// K_r, M_r with the file's modes at the independent dofs give Φᵀ M Φ = I and Φᵀ K Φ = diag ω²
/// — the matrices are the ones the build reduced, spider centres included, legs eliminated.
#[test]
fn conrod_build_write_matrices_are_the_reduced_system() {
    let dir = tmp("conrod");
    let out = dir.join("rod.flexbody");
    let mats = dir.join("mats");
    let status = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("build")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp"))
        .args([
            "--interface",
            "BIG_END,SMALL_END",
            "--modes",
            "6",
            "--units",
            "si",
            "-q",
        ])
        .arg("-o")
        .arg(&out)
        .arg("--write-matrices")
        .arg(&mats)
        .status()
        .unwrap();
    assert!(status.success());
    let body = file::read(&out).unwrap();
    let dofs = read_dofs(&mats.join("dofs.txt"));
    let k = read_matrix(&mats.join("K.mtx")).unwrap();
    let m = read_matrix(&mats.join("M.mtx")).unwrap();
    let header = std::fs::read_to_string(mats.join("M.mtx")).unwrap();
    assert!(header.lines().nth(1).unwrap().contains("lumped mass"));
    let centres: Vec<u64> = body
        .interfaces
        .as_ref()
        .unwrap()
        .iter()
        .map(|i| body.nodes[i.node as usize].id)
        .collect();
    // Every dependent leg is gone, every centre has its six dofs.
    for i in body.interfaces.as_ref().unwrap() {
        assert!(i.dependent.iter().all(|d| !dofs.iter().any(|x| x.0 == *d)));
    }
    for c in &centres {
        assert_eq!(dofs.iter().filter(|x| x.0 == *c).count(), 6);
    }
    let index: HashMap<u64, usize> = body
        .nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.id, i))
        .collect();
    let n = body.node_count();
    let nm = body.mode_count();
    let phi: Vec<Vec<f64>> = (0..nm)
        .map(|j| {
            dofs.iter()
                .map(|&(id, c)| body.modes.shapes[(j * n + index[&id]) * 6 + c])
                .collect()
        })
        .collect();
    let pm = project(&m, &phi);
    let pk = project(&k, &phi);
    let kmax = body.modes.omega2.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let (mut em, mut ek) = (0.0f64, 0.0f64);
    for i in 0..nm {
        for j in 0..nm {
            let id = if i == j { 1.0 } else { 0.0 };
            em = em.max((pm[i * nm + j] - id).abs());
            let w = if i == j { body.modes.omega2[i] } else { 0.0 };
            ek = ek.max((pk[i * nm + j] - w).abs() / kmax);
        }
    }
    eprintln!("conrod: |ΦᵀMΦ − I| {em:.2e}, |ΦᵀKΦ − Ω²|/max ω² {ek:.2e}");
    assert!(em < 1e-8 && ek < 1e-8, "M {em:e}, K {ek:e}");
    // `export --to mtx --model` rebuilds the same system from the file's recipe (interfaces,
    // spiders, lumped mass): the same three files, byte for byte.
    let again = dir.join("again");
    let status = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("export")
        .arg(&out)
        .args(["--to", "mtx", "--model"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp"))
        .arg("-o")
        .arg(&again)
        .status()
        .unwrap();
    assert!(status.success());
    for f in ["K.mtx", "M.mtx", "dofs.txt", "coords.csv"] {
        assert!(
            std::fs::read(mats.join(f)).unwrap() == std::fs::read(again.join(f)).unwrap(),
            "{f} differs between build --write-matrices and export --to mtx"
        );
    }
    // coords.csv: each node of dofs.txt once, in the order of its first dof, at the position
    // the .flexbody file stores for it (spider centres included).
    let coords = read_coords(&mats.join("coords.csv"));
    let mut order: Vec<u64> = Vec::new();
    for &(id, _) in &dofs {
        if order.last() != Some(&id) {
            assert!(!order.contains(&id), "node {id}'s dofs are not together");
            order.push(id);
        }
    }
    assert_eq!(coords.iter().map(|c| c.0).collect::<Vec<_>>(), order);
    for (id, x) in &coords {
        assert_eq!(*x, body.nodes[index[id]].xyz, "node {id}");
    }
    for c in &centres {
        assert!(coords.iter().any(|x| x.0 == *c));
    }
    eprintln!(
        "conrod: coords.csv {} nodes, equal to the file's",
        coords.len()
    );

    // `--spider none`: the bores stay free (no leg eliminated, no centre added), so a peer can
    // run its own Craig–Bampton on the same K, M with the bore nodes as its boundary.
    let free = dir.join("free");
    let status = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("export")
        .arg(&out)
        .args(["--to", "mtx", "--spider", "none", "--model"])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp"))
        .arg("-o")
        .arg(&free)
        .status()
        .unwrap();
    assert!(status.success());
    let free_dofs = read_dofs(&free.join("dofs.txt"));
    let free_coords = read_coords(&free.join("coords.csv"));
    let mesh_nodes = body.node_count() - centres.len();
    assert_eq!(free_coords.len(), mesh_nodes);
    assert_eq!(
        free_dofs.len(),
        3 * mesh_nodes,
        "tet10: three dofs per node, none held"
    );
    for c in &centres {
        assert!(!free_dofs.iter().any(|x| x.0 == *c), "centre {c} added");
    }
    for i in body.interfaces.as_ref().unwrap() {
        for d in &i.dependent {
            assert_eq!(free_dofs.iter().filter(|x| x.0 == *d).count(), 3, "leg {d}");
            assert!(
                free_coords.iter().any(|x| x.0 == *d),
                "leg {d}'s coordinates"
            );
        }
    }
    // The free K, M are the whole mesh: a rigid translation has the body's mass and no strain
    // energy.
    let k = read_matrix(&free.join("K.mtx")).unwrap();
    let m = read_matrix(&free.join("M.mtx")).unwrap();
    let ex: Vec<Vec<f64>> = vec![free_dofs
        .iter()
        .map(|&(_, c)| if c == 0 { 1.0 } else { 0.0 })
        .collect()];
    let mass = project(&m, &ex)[0];
    let energy = project(&k, &ex)[0];
    let kscale = project(
        &k,
        &[free_dofs
            .iter()
            .enumerate()
            .map(|(i, &(_, c))| if c == 0 && i % 2 == 0 { 1.0 } else { 0.0 })
            .collect()],
    )[0];
    let i1 = body.invariants.i1[0];
    eprintln!(
        "conrod --spider none: {} dofs, rigid x translation: mass {mass} (file I1 {i1}), energy {:.1e} of a non-rigid field's",
        free_dofs.len(),
        energy.abs() / kscale
    );
    assert!((mass - i1).abs() < 1e-12 * i1);
    assert!(energy.abs() < 1e-10 * kscale);
    std::fs::remove_dir_all(&dir).ok();
}

/// `coords.csv`: (node id, x, y, z) after the `node,x,y,z` header.
fn read_coords(path: &Path) -> Vec<(u64, [f64; 3])> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("node,x,y,z"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 4, "{l}");
            let x = |i: usize| f[i].parse::<f64>().unwrap();
            (f[0].parse().unwrap(), [x(1), x(2), x(3)])
        })
        .collect()
}

/// Runs the CLI; returns (success, stderr).
fn flexbody_cli(args: &[&std::ffi::OsStr]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// Copies `case/stem.inp` and its `mesh.inp` into a fresh folder (so a test can change them).
fn copy_case(case: &str, stem: &str, dir: &Path) -> PathBuf {
    for f in [format!("{stem}.inp"), "mesh.inp".into()] {
        std::fs::copy(reference(&format!("e_matrices/{case}/{f}")), dir.join(&f)).unwrap();
    }
    dir.join(format!("{stem}.inp"))
}

/// `flexbody build` (normal modes, consistent mass) then `flexbody export --to mtx --model`:
/// the matrices the export writes from the file's recipe — no option repeated, the mass kind
/// taken from the file — equal CalculiX's dumps. Returns (K, M) relative differences.
fn build_then_export(case: &str, stem: &str) -> (f64, f64) {
    let dir = tmp(&format!("cli-{case}-{stem}"));
    let model = copy_case(case, stem, &dir);
    let body = dir.join("block.flexbody");
    let (ok, err) = flexbody_cli(&[
        "build".as_ref(),
        model.as_os_str(),
        "--method".as_ref(),
        "normal".as_ref(),
        "--modes".as_ref(),
        "8".as_ref(),
        "--mass".as_ref(),
        "consistent".as_ref(),
        "--units".as_ref(),
        "si".as_ref(),
        "-q".as_ref(),
        "-o".as_ref(),
        body.as_os_str(),
    ]);
    assert!(ok, "build: {err}");
    let mats = dir.join("mats");
    let (ok, err) = flexbody_cli(&[
        "export".as_ref(),
        body.as_os_str(),
        "--to".as_ref(),
        "mtx".as_ref(),
        "--model".as_ref(),
        model.as_os_str(),
        "-o".as_ref(),
        mats.as_os_str(),
    ]);
    assert!(ok, "export: {err}");
    let header = std::fs::read_to_string(mats.join("M.mtx")).unwrap();
    assert!(header.lines().nth(1).unwrap().contains("consistent mass"));
    let d = compare_written(case, stem, &mats);
    std::fs::remove_dir_all(&dir).ok();
    d
}

#[test]
fn cli_export_mtx_of_fixed_hex8_block_equals_ccx_dump() {
    let (ek, em) = build_then_export("hex8_block_coarse", "ccx_matrix_fixed");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}

#[test]
fn cli_export_mtx_of_free_tet10_block_equals_ccx_dump() {
    let (ek, em) = build_then_export("tet10_block_coarse", "ccx_matrix_free");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}

/// `--to mtx` without `--model` and with a model changed since the build: clear errors (the
/// latter `check`'s "changed since the build" naming the file), exit code 2, nothing written.
#[test]
fn cli_export_mtx_refuses_missing_or_changed_model() {
    let dir = tmp("cli-errors");
    let model = copy_case("hex8_single", "ccx_matrix_free", &dir);
    let body = dir.join("one.flexbody");
    let (ok, err) = flexbody_cli(&[
        "build".as_ref(),
        model.as_os_str(),
        "--method".as_ref(),
        "normal".as_ref(),
        "--modes".as_ref(),
        "8".as_ref(),
        "--units".as_ref(),
        "si".as_ref(),
        "-q".as_ref(),
        "-o".as_ref(),
        body.as_os_str(),
    ]);
    assert!(ok, "build: {err}");
    let mats = dir.join("mats");
    let export = |extra: &[&std::ffi::OsStr]| {
        let mut args: Vec<&std::ffi::OsStr> = vec![
            "export".as_ref(),
            body.as_os_str(),
            "--to".as_ref(),
            "mtx".as_ref(),
            "-o".as_ref(),
            mats.as_os_str(),
        ];
        args.extend_from_slice(extra);
        flexbody_cli(&args)
    };
    let (ok, err) = export(&[]);
    assert!(!ok && err.contains("--model MODEL"), "{err}");
    assert!(!mats.exists());
    // The include changes: refused, naming the changed file.
    let mesh = dir.join("mesh.inp");
    let mut text = std::fs::read_to_string(&mesh).unwrap();
    text.push_str("** edited after the build\n");
    std::fs::write(&mesh, text).unwrap();
    let (ok, err) = export(&["--model".as_ref(), model.as_os_str()]);
    assert!(
        !ok && err.contains("mesh.inp: changed since the build"),
        "{err}"
    );
    assert!(!mats.exists());
    // `check` names the same file with the same words.
    let out = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("check")
        .arg(&body)
        .arg("--model")
        .arg(&model)
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        report.contains("mesh.inp: changed since the build"),
        "{report}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
