//! K/M export in Matrix Market (`build --write-matrices`, the `mtx` export target) against
//! CalculiX 2.20's own matrix dumps of the shared reference blocks
//! (`../shared/reference/e_matrices/`, `*FREQUENCY, SOLVER=MATRIXSTORAGE`): entry by entry,
//! matched through the two dof tables, relative to the largest entry; plus the written matrices
//! against the modes `build` wrote (Φᵀ M Φ = I, Φᵀ K Φ = diag ω²), which shows they are the
//! matrices the build reduced.

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::reference;
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
    assert_eq!(written.len(), 3);
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
    std::fs::remove_dir_all(&dir).ok();
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
    std::fs::remove_dir_all(&dir).ok();
}
