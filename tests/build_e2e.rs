//! End to end (issue 6): `flexbody build` from a model file to a file the reader accepts, with
//! invariants, `check`, and accuracy against full normal-mode solves of the same model.

// Index loops mirror the matrix formulas (RᵀMR, the 6×6 rigid identity).
#![allow(clippy::needless_range_loop)]

use std::path::{Path, PathBuf};
use std::process::Command;

use flexbody::build::{build, BuildMethod, BuildSpec, KeepNodes};
use flexbody::check::{check, ModelInput};
use flexbody::fe::{assemble, AssemblySpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody::interface::SpiderKind;
use flexbody_reader as file;

use crate::common::{external_reference, reference};

fn conrod() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp")
}

fn spec(model: PathBuf, method: BuildMethod, interface: &[&str]) -> BuildSpec {
    BuildSpec {
        method,
        ..BuildSpec::new(model, file::Units::si(), interface)
    }
}

fn write_and_read(body: &file::ReducedBody, name: &str) -> (PathBuf, file::ReducedBody) {
    let dir = std::env::temp_dir().join(format!("flexbody-e2e-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    flexbody::write::write_reduced_body(&path, body, &Default::default()).unwrap();
    let back = file::read(&path).unwrap();
    assert_check_passes(&back, None);
    (path, back)
}

/// `flexbody check` (library form) passes every item on a file the suite built.
fn assert_check_passes(body: &file::ReducedBody, model: Option<&ModelInput>) {
    let report = check(body, model).unwrap();
    for i in &report.items {
        assert!(
            i.pass,
            "check `{}` failed: {} > {} ({})",
            i.name, i.value, i.limit, i.detail
        );
    }
}

/// Frequencies (Hz) of the modes not labelled rigid, in file order.
fn flexible_hz(body: &file::ReducedBody) -> Vec<f64> {
    body.modes
        .frequency_hz
        .iter()
        .zip(&body.modes.labels)
        .filter(|(_, l)| **l != file::ModeLabel::Rigid)
        .map(|(f, _)| *f)
        .collect()
}

fn max_abs(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(0.0, |a, b| a.max(b.abs()))
}

/// a_block_hex8 free-free, lumped normal modes: I1 = ρV (case.json: 9.8125 kg), I2/I1 = the
/// block's centre, I7 = RᵀMR with the rigid rotation fields R and the assembled lumped M (an
/// independent path through the sparse matrix), I6 = I, and the rigid identity
/// [I3; I4][I3; I4]ᵀ = [[I1 E, −Ĩ2], [Ĩ2, I7]] over the six rigid modes (whatever basis of the rigid
/// space the eigensolver returned; it means I3_r/√I1 has orthonormal rows).
#[test]
fn a_block_free_body_invariants_equal_mesh_mass_properties() {
    let model_path = reference("a_block_hex8/ccx_free.inp");
    let mut s = spec(model_path.clone(), BuildMethod::Normal, &[]);
    s.modes = Some(10);
    let out = build(&s, &mut |_| {}).unwrap();
    let (_, body) = write_and_read(&out.body, "a_block_free.flexbody");
    assert_eq!(body, out.body, "reader returns what build made");
    let inv = &body.invariants;
    let i1 = inv.i1[0];
    assert!((i1 / 9.8125 - 1.0).abs() < 1e-12, "I1 = {i1}, ρV = 9.8125");
    let centre = [0.25, 0.025, 0.025];
    for k in 0..3 {
        assert!(
            (inv.i2[k] / i1 - centre[k]).abs() < 1e-14,
            "centre of mass {k}"
        );
    }
    // I7 against RᵀMR from the assembled lumped mass matrix.
    let model = read_model(&model_path, &ImportOptions::default()).unwrap();
    let a = assemble(&model, &AssemblySpec::default()).unwrap();
    let n = a.dofs.n_dofs;
    let rot = |axis: usize| -> Vec<f64> {
        let mut v = vec![0.0; n];
        for (p, node) in model.nodes.iter().enumerate() {
            let Some(d0) = a.dofs.dof(p, 0) else { continue };
            let mut w = [0.0; 3];
            w[axis] = 1.0;
            let x = node.x;
            let u = [
                w[1] * x[2] - w[2] * x[1],
                w[2] * x[0] - w[0] * x[2],
                w[0] * x[1] - w[1] * x[0],
            ];
            v[d0..d0 + 3].copy_from_slice(&u);
        }
        v
    };
    let mv = |x: &[f64]| -> Vec<f64> {
        let m = a.m.as_ref();
        let mut y = vec![0.0; n];
        for j in 0..n {
            for (i, v) in m.row_idx_of_col(j).zip(m.val_of_col(j)) {
                y[i] += v * x[j];
            }
        }
        y
    };
    let r: Vec<Vec<f64>> = (0..3).map(rot).collect();
    let i7_max = max_abs(inv.i7.iter().copied());
    for a_ in 0..3 {
        let mr = mv(&r[a_]);
        for b in 0..3 {
            let rmr: f64 = r[b].iter().zip(&mr).map(|(x, y)| x * y).sum();
            assert!(
                (inv.i7[3 * a_ + b] - rmr).abs() < 1e-10 * i7_max,
                "I7[{a_}][{b}] {} vs RᵀMR {rmr}",
                inv.i7[3 * a_ + b]
            );
        }
    }
    // I6 = I (lumped reduction mass = the invariants' nodal masses).
    let m = body.mode_count();
    let i6_err = max_abs((0..m * m).map(|i| inv.i6[i] - if i / m == i % m { 1.0 } else { 0.0 }));
    assert!(i6_err < 1e-10, "I6 − I = {i6_err:e}");
    // Rigid identity over the six rigid modes.
    let rigid: Vec<usize> = (0..m)
        .filter(|&j| body.modes.labels[j] == file::ModeLabel::Rigid)
        .collect();
    assert_eq!(rigid.len(), 6);
    let row = |k: usize, j: usize| {
        if k < 3 {
            inv.i3[k * m + j]
        } else {
            inv.i4[(k - 3) * m + j]
        }
    };
    let i2 = &inv.i2;
    let skew = [
        [0.0, -i2[2], i2[1]],
        [i2[2], 0.0, -i2[0]],
        [-i2[1], i2[0], 0.0],
    ];
    for a_ in 0..6 {
        for b in 0..6 {
            let got: f64 = rigid.iter().map(|&j| row(a_, j) * row(b, j)).sum();
            let want = match (a_ < 3, b < 3) {
                (true, true) => {
                    if a_ == b {
                        i1
                    } else {
                        0.0
                    }
                }
                (true, false) => -skew[a_][b - 3],
                (false, true) => skew[a_ - 3][b],
                (false, false) => inv.i7[3 * (a_ - 3) + (b - 3)],
            };
            let scale = if a_ < 3 && b < 3 {
                i1
            } else {
                i7_max.max(i1 * 0.25)
            };
            assert!(
                (got - want).abs() < 1e-10 * scale,
                "rigid identity [{a_}][{b}]: {got} vs {want}"
            );
        }
    }
}

/// a_block_hex8 with Craig–Bampton on both end faces through RBE2 spiders: with the scene's
/// fmax and the default cutoff factor, every reduced free-free frequency is ≥ the full model's
/// (same spiders) and within 1% below fmax; `check --model` passes.
#[test]
fn a_block_cb_on_end_faces_is_rayleigh_ritz_and_within_1pc_below_fmax() {
    let model_path = reference("a_block_hex8/ccx_free.inp");
    let mut s = spec(
        model_path.clone(),
        BuildMethod::CraigBampton,
        &["FIXED", "TIP"],
    );
    s.fmax_hz = Some(3000.0);
    let out = build(&s, &mut |_| {}).unwrap();
    let body = &out.body;
    assert_eq!(body.method.counts.constraint, 12);
    assert_eq!(body.method.counts.rigid, 6);
    let input = ModelInput {
        path: model_path,
        format: None,
        material: None,
        thickness: None,
        interface: s.interface.clone(),
        spider: SpiderKind::Rbe2,
        beam_mass: None,
        subcase: None,
        ignore: Vec::new(),
        inp_shells: Default::default(),
        scene: Default::default(),
    };
    let report = check(body, Some(&input)).unwrap();
    for i in &report.items {
        assert!(
            i.pass,
            "check `{}` failed: {} > {} ({})",
            i.name, i.value, i.limit, i.detail
        );
    }
    let freq = report
        .items
        .iter()
        .find(|i| i.name == "frequencies vs full normal-mode solve")
        .unwrap();
    assert!(
        freq.value < 0.01 && freq.detail.contains("below fmax = 3000 Hz"),
        "{freq:?}"
    );
    // The first bending pair: ccx gives 1043.155 Hz (consistent mass, no spiders); lumped mass
    // lowers it and the end-face spiders barely stiffen a slender block: measured 1040.57 Hz.
    let flex = flexible_hz(body);
    assert!(
        (flex[0] / 1043.155 - 1.0).abs() < 0.005,
        "first flexible {} Hz",
        flex[0]
    );
}

/// The bundled connecting rod, as the README builds it, through the real binary: the file is
/// written, `check --model` passes (exit 0); a copy with one mode scaled by 1% fails (exit 1)
/// with a FAIL line naming the broken identity.
#[test]
fn conrod_cli_build_check_and_corrupted_file_fails_check() {
    let exe = env!("CARGO_BIN_EXE_flexbody");
    let dir = std::env::temp_dir().join(format!("flexbody-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("conrod.flexbody");
    let model = conrod();
    let status = Command::new(exe)
        .args([
            "build",
            model.to_str().unwrap(),
            "--interface",
            "BIG_END,SMALL_END",
            "--fmax",
            "3000",
            "--units",
            "si",
            "--stress-modes",
            "-q",
            "-o",
        ])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let body = file::read(&out).unwrap();
    assert_eq!(body.nodes.iter().filter(|n| n.interface).count(), 2);
    // Stress shapes: every tet node carries values (not the two spider centres); rigid-body
    // modes are strain-free, so their stress is round-off next to the flexible modes'.
    let stress = body
        .stress_shapes
        .as_ref()
        .expect("--stress-modes stores stress");
    assert!(
        body.strain_shapes.is_some(),
        "--stress-modes stores strain too"
    );
    assert_eq!(stress.nodes.len(), body.node_count() - 2);
    let k = stress.nodes.len();
    let mode_max = |j: usize| max_abs(stress.values[j * k * 6..(j + 1) * k * 6].iter().copied());
    let labels = &body.modes.labels;
    let flexible_max = (0..labels.len())
        .filter(|&j| labels[j] != file::ModeLabel::Rigid)
        .map(mode_max)
        .fold(f64::INFINITY, f64::min);
    let rigid_max = (0..labels.len())
        .filter(|&j| labels[j] == file::ModeLabel::Rigid)
        .map(mode_max)
        .fold(0.0, f64::max);
    assert_eq!(body.method.counts.rigid, 6);
    assert!(
        rigid_max < 1e-6 * flexible_max,
        "rigid-mode stress {rigid_max:e} vs flexible {flexible_max:e}"
    );
    let inspected = Command::new(exe)
        .args(["inspect", "--json", out.to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&inspected.stdout);
    assert!(text.contains("stress_shapes.bin"), "{text}");
    let checked = Command::new(exe)
        .args([
            "check",
            out.to_str().unwrap(),
            "--model",
            model.to_str().unwrap(),
            "--interface",
            "BIG_END,SMALL_END",
        ])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&checked.stdout);
    assert_eq!(checked.status.code(), Some(0), "{text}");
    assert!(
        text.contains("failed: PASS") || text.contains("0 failed"),
        "{text}"
    );

    // Corrupt: scale the shapes of the first flexible mode by 1.01 (a valid file otherwise).
    let mut bad = body.clone();
    let (n, j) = (
        bad.node_count(),
        bad.modes
            .labels
            .iter()
            .position(|l| *l != file::ModeLabel::Rigid)
            .unwrap(),
    );
    for v in &mut bad.modes.shapes[j * n * 6..(j + 1) * n * 6] {
        *v *= 1.01;
    }
    let bad_path = dir.join("conrod_corrupted.flexbody");
    flexbody::write::write_reduced_body(&bad_path, &bad, &Default::default()).unwrap();
    let checked = Command::new(exe)
        .args(["check", bad_path.to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&checked.stdout);
    assert_eq!(checked.status.code(), Some(1), "{text}");
    assert!(
        text.lines().any(
            |l| l.starts_with("FAIL") && l.contains("I6 from stored shapes = generalized mass")
        ),
        "{text}"
    );
}

/// Normal modes with consistent mass of the bundled rod equal CalculiX's free-free run of the
/// same mesh (`fixtures/models/conrod/ccx_free.dat`, 7 printed digits) to 2e-6, and the reader
/// gets back bit-identical floats.
#[test]
fn conrod_consistent_normal_modes_equal_calculix() {
    let mut s = spec(conrod(), BuildMethod::Normal, &[]);
    s.modes = Some(12);
    s.mass = MassKind::Consistent;
    s.keep_nodes = KeepNodes::Interface;
    let out = build(&s, &mut |_| {}).unwrap();
    let ccx = [2116.229, 2496.791, 4764.353, 5062.158, 6178.535, 6572.526];
    let f = &out.body.modes.frequency_hz;
    assert_eq!(out.body.method.counts.rigid, 6);
    for (k, want) in ccx.iter().enumerate() {
        assert!(
            (f[6 + k] / want - 1.0).abs() < 2e-6,
            "mode {}: {} vs ccx {want}",
            7 + k,
            f[6 + k]
        );
    }
    let (_, back) = write_and_read(&out.body, "conrod_nm.flexbody");
    assert!(back
        .modes
        .frequency_hz
        .iter()
        .zip(f)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    // keep-nodes interface with no interface: only the 0 interface nodes are stored, but the
    // invariants still come from every node (mass of the whole rod).
    assert_eq!(back.node_count(), 0);
    assert!(
        (back.invariants.i1[0] - 0.9663223).abs() < 1e-6,
        "I1 = {}",
        back.invariants.i1[0]
    );
}

/// a_block_hex8 with Craig–Bampton on RBE3 (weighted-average) spiders at both end faces, their
/// centre nodes kept independent (the RBE3 relation is solved for dofs of the face nodes, as
/// Nastran's UM set does). An RBE3 adds no stiffness, so the full model's free-free spectrum is
/// the plain block's: CalculiX's consistent-mass run `ccx_free.dat`. Every reduced frequency
/// below fmax is ≥ it and within 1%; each mode moves the centre by the mean translation of its
/// face (the weighted least-squares fit with equal weights about the face centroid).
#[test]
fn a_block_cb_on_rbe3_spiders_keeps_centres_independent_and_matches_calculix() {
    let model_path = reference("a_block_hex8/ccx_free.inp");
    let mut s = spec(model_path, BuildMethod::CraigBampton, &["FIXED", "TIP"]);
    s.spider = SpiderKind::Rbe3;
    s.mass = MassKind::Consistent;
    s.fmax_hz = Some(3000.0);
    let out = build(&s, &mut |_| {}).unwrap();
    let (_, body) = write_and_read(&out.body, "a_block_rbe3.flexbody");
    let body = &body;
    assert_check_passes(
        body,
        Some(&ModelInput {
            path: s.model.clone(),
            format: None,
            material: None,
            thickness: None,
            interface: s.interface.clone(),
            spider: SpiderKind::Rbe3,
            beam_mass: None,
            subcase: None,
            ignore: Vec::new(),
            inp_shells: Default::default(),
            scene: Default::default(),
        }),
    );
    assert_eq!(body.method.counts.constraint, 12);
    let ccx = [1043.155, 1043.155, 2724.445, 2724.445, 2981.727];
    let flex = flexible_hz(body);
    for (k, want) in ccx.iter().enumerate() {
        let rel = flex[k] / want - 1.0;
        assert!(
            (-2e-6..0.01).contains(&rel),
            "mode {k}: {} Hz vs ccx {want} Hz",
            flex[k]
        );
    }
    // Centre translation = mean translation of the face nodes, in every mode.
    let model = read_model(&s.model, &ImportOptions::default()).unwrap();
    let n = body.node_count();
    let pos_of_id: std::collections::HashMap<u64, usize> = body
        .nodes
        .iter()
        .enumerate()
        .map(|(k, nd)| (nd.id, k))
        .collect();
    let mut worst = 0.0f64;
    for (k, set) in ["FIXED", "TIP"].iter().enumerate() {
        let centre = pos_of_id[&out.report.interfaces[k]
            .spider
            .as_ref()
            .unwrap()
            .centre_node_id];
        let face: Vec<usize> = model.node_sets[*set]
            .iter()
            .map(|&p| pos_of_id[&model.nodes[p].id])
            .collect();
        for j in 0..body.mode_count() {
            let sh = |p: usize, c: usize| body.modes.shapes[(j * n + p) * 6 + c];
            let scale = max_abs((0..n).map(|p| sh(p, 2)).chain((0..n).map(|p| sh(p, 1))));
            for c in 0..3 {
                let mean = face.iter().map(|&p| sh(p, c)).sum::<f64>() / face.len() as f64;
                worst = worst.max((sh(centre, c) - mean).abs() / scale);
            }
        }
    }
    println!(
        "RBE3 CB: flexible {:?} Hz; centre vs face mean {worst:.1e}",
        &flex[..5]
    );
    assert!(worst < 1e-9, "centre vs face mean translation: {worst:e}");
}

/// The rod's CB file with every node kept: the stored invariants equal a fresh node-by-node
/// evaluation of the spec's definitions (format-spec §5.6) from the stored nodes, nodal masses
/// and mode shapes, to 1e-12 relative to each invariant's largest entry. (The rod has no point
/// masses, so the stored nodes are all the mass points.)
#[test]
fn conrod_invariants_equal_node_by_node_recomputation_from_the_file() {
    let mut s = spec(
        conrod(),
        BuildMethod::CraigBampton,
        &["BIG_END", "SMALL_END"],
    );
    s.fmax_hz = Some(3000.0);
    let out = build(&s, &mut |_| {}).unwrap();
    let (_, body) = write_and_read(&out.body, "conrod_inv.flexbody");
    let (n, m) = (body.node_count(), body.mode_count());
    let skew = |a: [f64; 3]| [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]];
    let mul = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
    };
    let tr = |a: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
    };
    let phi = |p: usize, j: usize| -> [f64; 3] {
        std::array::from_fn(|c| body.modes.shapes[(j * n + p) * 6 + c])
    };
    let psi = |p: usize, j: usize| -> [f64; 3] {
        std::array::from_fn(|c| body.modes.shapes[(j * n + p) * 6 + 3 + c])
    };
    let mut i1 = 0.0;
    let mut i2 = [0.0; 3];
    let mut i3 = vec![0.0; 3 * m];
    let mut i4 = vec![0.0; 3 * m];
    let mut i5 = vec![0.0; m * 3 * m];
    let mut i6 = vec![0.0; m * m];
    let mut i7 = [0.0; 9];
    let mut i8 = vec![0.0; m * 9];
    let mut i9 = vec![0.0; m * m * 9];
    for p in 0..n {
        let (mp, ip, sp) = (
            body.nodal_mass[p].mass,
            body.nodal_mass[p].inertia,
            body.nodes[p].xyz,
        );
        let st = skew(sp);
        i1 += mp;
        for a in 0..3 {
            i2[a] += mp * sp[a];
        }
        let stst = mul(tr(st), st);
        for a in 0..3 {
            for b in 0..3 {
                i7[a * 3 + b] += mp * stst[a][b] + ip[a][b];
            }
        }
        for j in 0..m {
            let (fj, rj) = (phi(p, j), psi(p, j));
            let fjt = skew(fj);
            for a in 0..3 {
                i3[a * m + j] += mp * fj[a];
                i4[a * m + j] += (0..3)
                    .map(|b| mp * st[a][b] * fj[b] + ip[a][b] * rj[b])
                    .sum::<f64>();
            }
            let sf = mul(st, fjt);
            for a in 0..3 {
                for b in 0..3 {
                    i8[(j * 3 + a) * 3 + b] += mp * sf[a][b];
                }
            }
            for k in 0..m {
                let (fk, rk) = (phi(p, k), psi(p, k));
                for a in 0..3 {
                    i5[(j * 3 + a) * m + k] += mp * (0..3).map(|b| fjt[a][b] * fk[b]).sum::<f64>();
                }
                i6[j * m + k] += mp * (0..3).map(|a| fj[a] * fk[a]).sum::<f64>()
                    + (0..3)
                        .map(|a| (0..3).map(|b| rj[a] * ip[a][b] * rk[b]).sum::<f64>())
                        .sum::<f64>();
                let ff = mul(fjt, skew(fk));
                for a in 0..3 {
                    for b in 0..3 {
                        i9[((j * m + k) * 3 + a) * 3 + b] += mp * ff[a][b];
                    }
                }
            }
        }
    }
    let inv = &body.invariants;
    let cases: [(&str, &[f64], &[f64]); 9] = [
        ("I1", &inv.i1, &[i1]),
        ("I2", &inv.i2, &i2),
        ("I3", &inv.i3, &i3),
        ("I4", &inv.i4, &i4),
        ("I5", &inv.i5, &i5),
        ("I6", &inv.i6, &i6),
        ("I7", &inv.i7, &i7),
        ("I8", &inv.i8, &i8),
        ("I9", &inv.i9, &i9),
    ];
    for (name, stored, fresh) in cases {
        assert_eq!(stored.len(), fresh.len(), "{name} length");
        let scale = max_abs(fresh.iter().copied());
        let err = max_abs(stored.iter().zip(fresh).map(|(a, b)| a - b));
        assert!(
            err <= 1e-12 * scale,
            "{name}: max error {err:e} of {scale:e}"
        );
    }
}

/// A beam model (Nastran `beam_modes`: 9 CBAR + 1 CBEAM, clamped at GRID 1) has no faces; its
/// elements are stored as graphics lines (format 1.1 `lines.bin`), one per beam. Built files
/// carry the 1.2 recipe and label shares, so they say 1.2; without them the same body is 1.1.
#[test]
fn beam_model_is_drawn_with_lines_and_written_as_format_1_1() {
    let Some(model_path) = external_reference(
        "beam_model_is_drawn_with_lines_and_written_as_format_1_1",
        "nastran/beam_modes/beam_modes.dat",
    ) else {
        return;
    };
    let mut s = spec(model_path.clone(), BuildMethod::Normal, &[]);
    s.modes = Some(4);
    let out = build(&s, &mut |_| {}).unwrap();
    let (_, body) = write_and_read(&out.body, "beam_lines.flexbody");
    // every build records its eigenproblem (1.9); without it the recipe makes the file 1.2
    assert_eq!(body.version, file::Version { major: 1, minor: 9 });
    let mut bare = body.clone();
    bare.eigen_residuals = None;
    assert_eq!(
        file::version_for(&bare),
        file::Version { major: 1, minor: 2 }
    );
    bare.recipe = None;
    bare.label_shares = None;
    assert_eq!(
        file::version_for(&bare),
        file::Version { major: 1, minor: 1 }
    );
    assert!(body.faces.is_empty());
    let model = read_model(&model_path, &ImportOptions::default()).unwrap();
    let beams: Vec<[u64; 2]> = model
        .elements
        .iter()
        .filter(|e| e.nodes.len() == 2)
        .map(|e| [model.nodes[e.nodes[0]].id, model.nodes[e.nodes[1]].id])
        .collect();
    assert_eq!(beams.len(), 10);
    let lines: Vec<[u64; 2]> = body
        .lines
        .as_ref()
        .expect("lines stored")
        .iter()
        .map(|l| [body.nodes[l[0] as usize].id, body.nodes[l[1] as usize].id])
        .collect();
    assert_eq!(lines, beams);
}

/// `--threads 2` (parallel factorization, block solves split by subtrees of the elimination
/// tree, parallel products) builds the same body as one thread, in f64 and with the f32
/// factor of `--precision mixed` (solved in f32 arithmetic, refined): frequencies, mass and
/// inertia to 1e-10 relative.
#[test]
fn conrod_cb_with_two_threads_equals_one_thread() {
    let mut s = spec(
        conrod(),
        BuildMethod::CraigBampton,
        &["BIG_END", "SMALL_END"],
    );
    s.modes = Some(10);
    let one = build(&s, &mut |_| {}).unwrap().body;
    s.threads = 2;
    let two = build(&s, &mut |_| {}).unwrap().body;
    s.precision = flexbody::solve::Precision::Mixed;
    let mixed = build(&s, &mut |_| {}).unwrap().body;
    let f1 = flexible_hz(&one);
    assert_eq!(f1.len(), 10 + 12 - 6);
    for other in [&two, &mixed] {
        let f2 = flexible_hz(other);
        assert_eq!(f1.len(), f2.len());
        for (a, b) in f1.iter().zip(&f2) {
            assert!((a - b).abs() <= 1e-10 * a, "{a} vs {b}");
        }
        // mass and inertia tensor (sign-free invariants: mode signs may differ between runs)
        for (a, b) in [
            (&one.invariants.i1, &other.invariants.i1),
            (&one.invariants.i7, &other.invariants.i7),
        ] {
            let scale = max_abs(a.iter().copied());
            assert!(scale > 0.0);
            let d = max_abs(a.iter().zip(b).map(|(x, y)| x - y));
            assert!(d <= 1e-10 * scale, "{d:e}");
        }
    }
}

/// `--beam-mass`: a Nastran deck (9 CBAR + 1 CBEAM, CONM2 tip, GRID 1 clamped) built with the
/// automatic lumping has Nastran's torsion mode (f06: 3554.9230 Hz; the torsion mode does not
/// depend on the beam theory the CLI uses), and with `none` (no rotational inertia on any
/// element) the closed form √(GJ/(L·I_xx))/2π of the CONM2 on the shaft, 4226.5 Hz.
#[test]
fn nastran_deck_beam_mass_auto_is_nastran_lumping_and_none_is_the_closed_form() {
    let Some(path) = external_reference(
        "nastran_deck_beam_mass_auto_is_nastran_lumping_and_none_is_the_closed_form",
        "nastran/beam_modes/beam_modes.dat",
    ) else {
        return;
    };
    let mut s = spec(path, BuildMethod::Normal, &[]);
    s.modes = Some(10);
    assert_eq!(s.beam_lumping(), flexbody::fe::BeamLumping::Nastran);
    let auto = flexible_hz(&build(&s, &mut |_| {}).unwrap().body);
    let torsion = 3554.9230;
    let near = |f: &[f64], x: f64| f.iter().map(|v| (v - x).abs() / x).fold(1.0, f64::min);
    assert!(near(&auto, torsion) < 1e-6, "{auto:?}");
    s.beam_mass = Some(flexbody::fe::BeamLumping::TranslationsOnly);
    let none = flexible_hz(&build(&s, &mut |_| {}).unwrap().body);
    assert!(near(&none, torsion) > 0.1, "{none:?}");
    assert!(near(&none, 4226.5) < 1e-4, "{none:?}");
}
