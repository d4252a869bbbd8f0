//! Issue 19: scene loads, residual vectors and modal loads. Every number is checked against the
//! full FE solution: the static response of the reduced body, computed from the FILE alone
//! (its modes and `modal_loads.bin`: q = Ω⁻²Φᵀf on the flexible modes, u = Φq), equals the
//! static solution of the assembled model solved here densely (K_r u = Tᵀf; for a free body the
//! inertia-relief system with the geometric rigid-body modes).

// Index loops mirror the subscripts of the formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::path::{Path, PathBuf};

use flexbody::build::{build, BuildMethod, BuildSpec};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec};
use flexbody::model::{LoadPart, Model};
use flexbody::reduce::residual::ResidualKind;
use flexbody::scene::SceneSpec;
use flexbody_reader as file;

const NX: usize = 12;
const NY: usize = 2;
const NZ: usize = 2;
const L: f64 = 1.2;
const B: f64 = 0.1;

fn nid(i: usize, j: usize, k: usize) -> usize {
    (k * (NY + 1) + j) * (NX + 1) + i + 1
}

/// A hex8 cantilever deck (clamped at x = 0 when `clamped`), steel, with load sets: 1 = tip
/// force, 2 = gravity, 10 = LOAD 1.0·(1 + 2·2) (selected by `LOAD = 10`), 3 = PLOAD4 on the
/// top faces of the last two elements in x (unselected).
fn deck(clamped: bool) -> String {
    let mut d = String::from("SOL 101\nCEND\nTITLE = cantilever\n");
    if clamped {
        d += "SPC = 1\n";
    }
    d += "LOAD = 10\nBEGIN BULK\n";
    for k in 0..=NZ {
        for j in 0..=NY {
            for i in 0..=NX {
                d += &format!(
                    "GRID,{},,{},{},{}\n",
                    nid(i, j, k),
                    i as f64 * L / NX as f64,
                    j as f64 * B / NY as f64,
                    k as f64 * B / NZ as f64
                );
            }
        }
    }
    let mut e = 0;
    let mut top_faces = Vec::new();
    for k in 0..NZ {
        for j in 0..NY {
            for i in 0..NX {
                e += 1;
                let n = [
                    nid(i, j, k),
                    nid(i + 1, j, k),
                    nid(i + 1, j + 1, k),
                    nid(i, j + 1, k),
                    nid(i, j, k + 1),
                    nid(i + 1, j, k + 1),
                    nid(i + 1, j + 1, k + 1),
                    nid(i, j + 1, k + 1),
                ];
                d += &format!(
                    "CHEXA,{e},1,{},{},{},{},{},{},+\n+,{},{}\n",
                    n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7]
                );
                if k == NZ - 1 && i >= NX - 2 {
                    // top face: G1 = node 5, diagonal G3 = node 7
                    top_faces.push((e, n[4], n[6]));
                }
            }
        }
    }
    d += "PSOLID,1,1\nMAT1,1,210e9,,0.3,7850.\n";
    if clamped {
        for k in 0..=NZ {
            for j in 0..=NY {
                d += &format!("SPC1,1,123,{}\n", nid(0, j, k));
            }
        }
    }
    // node set SPC_99 (an unselected SPC set): the end face x = L
    for k in 0..=NZ {
        for j in 0..=NY {
            d += &format!("SPC1,99,123,{}\n", nid(NX, j, k));
        }
    }
    d += &format!("FORCE,1,{},0,1000.,0.,0.3,-1.\n", nid(NX, NY, NZ));
    d += "GRAV,2,0,9.81,0.,0.,-1.\n";
    d += "LOAD,10,1.0,1.0,1,2.0,2\n";
    for (e, g1, g3) in top_faces {
        d += &format!("PLOAD4,3,{e},2.5e5,,,,{g1},{g3}\n");
    }
    d += "ENDDATA\n";
    d
}

fn write_deck(tag: &str, clamped: bool) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexbody-scene-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("cantilever.bdf");
    std::fs::write(&p, deck(clamped)).unwrap();
    p
}

fn spec(model: &Path, method: BuildMethod, modes: usize, interface: &[&str]) -> BuildSpec {
    BuildSpec {
        method,
        modes: Some(modes),
        ..BuildSpec::new(model.to_path_buf(), file::Units::si(), interface)
    }
}

/// Build, write, read back: the body as a solver sees it.
fn built(s: &BuildSpec) -> (file::ReducedBody, Vec<String>) {
    let out = build(s, &mut |_| {}).unwrap();
    let path = s.model.with_extension(format!(
        "{}.flexbody",
        s.scene.residual_vectors.map_or("plain", |_| "resvec")
    ));
    flexbody::write::write_reduced_body(&path, &out.body, &Default::default()).unwrap();
    let mut notes = out.report.notes.clone();
    notes.extend(out.report.diagnostics.notes.clone());
    (file::read(&path).unwrap(), notes)
}

/// The reduced static response at every stored node, translations, from the file alone.
fn reduced_static(body: &file::ReducedBody, load: &str) -> Vec<[f64; 3]> {
    let ml = body.modal_loads.as_ref().expect("modal_loads.bin");
    let g = &ml.loads.iter().find(|l| l.name == load).unwrap().values;
    let n = body.nodes.len();
    let mut u = vec![[0.0; 3]; n];
    for (j, &w2) in body.modes.omega2.iter().enumerate() {
        if body.modes.labels[j] == file::ModeLabel::Rigid {
            continue;
        }
        let q = g[j] / w2;
        for (p, up) in u.iter_mut().enumerate() {
            for c in 0..3 {
                up[c] += body.modes.shapes[(j * n + p) * 6 + c] * q;
            }
        }
    }
    u
}

/// Dense Gaussian elimination with partial pivoting: solves A x = b (A square).
fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap();
        a.swap(c, p);
        b.swap(c, p);
        let piv = a[c][c];
        assert!(piv.abs() > 0.0, "singular system");
        for r in c + 1..n {
            let f = a[r][c] / piv;
            if f != 0.0 {
                for k in c..n {
                    a[r][k] -= f * a[c][k];
                }
                b[r] -= f * b[c];
            }
        }
    }
    let mut x = vec![0.0; n];
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|k| a[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    x
}

fn dense(m: &faer::sparse::SparseColMat<usize, f64>) -> Vec<Vec<f64>> {
    let mut a = vec![vec![0.0; m.ncols()]; m.nrows()];
    for j in 0..m.ncols() {
        for (i, v) in m.row_idx_of_col(j).zip(m.val_of_col(j)) {
            a[i][j] += v;
        }
    }
    a
}

/// The full FE static solution of load `name` (translations per node, by node index): the
/// clamped body K_r u = Tᵀf; the free body by inertia relief with the geometric rigid-body
/// modes R: [K MR; RᵀM 0][u; λ] = [f; 0] (the response with no rigid-body content RᵀMu = 0).
fn full_static(
    model: &Model,
    loads: &[flexbody::model::Load],
    name: &str,
    free: bool,
) -> Vec<[f64; 3]> {
    let a = assemble(model, &AssemblySpec::default()).unwrap();
    let r = eliminate(model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    let load = loads.iter().find(|l| l.name == name).unwrap();
    let f = flexbody::fe::loads::load_vectors(model, &a.dofs, &a.m, std::slice::from_ref(load))
        .unwrap();
    let fr = flexbody::fe::loads::reduce_loads(&r.t, &f);
    let n = r.k.nrows();
    let mut k = dense(&r.k);
    let mut b: Vec<f64> = (0..n).map(|i| fr[(i, 0)]).collect();
    if free {
        // geometric rigid modes over the retained dofs (solids: 3 dofs per node, basic frame)
        let m = dense(&r.m);
        let mut rig = vec![vec![0.0; 6]; n];
        for (ri, &p) in r.retained.iter().enumerate() {
            let (node, comp) = a.dofs.node_of(p).unwrap();
            let x = model.nodes[node].x;
            rig[ri][comp] = 1.0;
            // rotation e_q × x, component comp
            let rot = |q: usize| -> f64 {
                let e = [0, 1, 2].map(|t| if t == q { 1.0 } else { 0.0 });
                let c = [
                    e[1] * x[2] - e[2] * x[1],
                    e[2] * x[0] - e[0] * x[2],
                    e[0] * x[1] - e[1] * x[0],
                ];
                c[comp]
            };
            for q in 0..3 {
                rig[ri][3 + q] = rot(q);
            }
        }
        let mr: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..6)
                    .map(|q| (0..n).map(|t| m[i][t] * rig[t][q]).sum())
                    .collect()
            })
            .collect();
        for (i, row) in k.iter_mut().enumerate() {
            row.extend(mr[i].iter().copied());
        }
        for q in 0..6 {
            let mut row: Vec<f64> = (0..n).map(|i| mr[i][q]).collect();
            row.extend([0.0; 6]);
            k.push(row);
        }
        b.extend([0.0; 6]);
    }
    let x = dense_solve(k, b);
    let mut u = vec![[0.0; 3]; model.nodes.len()];
    for (ri, &p) in r.retained.iter().enumerate() {
        let (node, comp) = a.dofs.node_of(p).unwrap();
        u[node][comp] = x[ri];
    }
    u
}

/// max |u_red − u_full| / max |u_full| over the stored nodes.
fn rel_error(body: &file::ReducedBody, model: &Model, red: &[[f64; 3]], full: &[[f64; 3]]) -> f64 {
    let by_id = model.node_index_by_id();
    let (mut err, mut top) = (0.0f64, 0.0f64);
    for (p, node) in body.nodes.iter().enumerate() {
        let Some(&n) = by_id.get(&node.id) else {
            continue;
        };
        for c in 0..3 {
            err = err.max((red[p][c] - full[n][c]).abs());
            top = top.max(full[n][c].abs());
        }
    }
    err / top
}

fn model_of(path: &Path) -> Model {
    flexbody::import::read_model(path, &Default::default()).unwrap()
}

/// The deck's load cards become named loads: LOAD 10 (selected) = tip force + 2·gravity, the
/// PLOAD4 set 3 unselected; the pressure resultant is p·A downward (closed form).
#[test]
fn nastran_load_cards_are_read_by_name() {
    let path = write_deck("cards", true);
    let model = model_of(&path);
    let names: Vec<(&str, bool)> = model
        .loads
        .iter()
        .map(|l| (l.name.as_str(), l.selected))
        .collect();
    assert_eq!(
        names,
        [
            ("LOAD_1", false),
            ("LOAD_2", false),
            ("LOAD_3", false),
            ("LOAD_10", true)
        ]
    );
    let l10 = &model.loads[3];
    assert!(l10.parts.iter().any(
        |p| matches!(p, LoadPart::Gravity { accel } if (accel[2] + 2.0 * 9.81).abs() < 1e-12)
    ));
    // PLOAD4 3: 2.5e5 Pa inward on the top faces of 2·NY elements of (L/NX)·(B/NY) each.
    let a = assemble(&model, &AssemblySpec::default()).unwrap();
    let f = flexbody::fe::loads::load_vectors(&model, &a.dofs, &a.m, &model.loads).unwrap();
    let fz: f64 = (0..model.nodes.len())
        .map(|p| f[(a.dofs.first[p] + 2, 2)])
        .sum();
    let area = 2.0 * NY as f64 * (L / NX as f64) * (B / NY as f64);
    assert!((fz + 2.5e5 * area).abs() < 1e-9 * 2.5e5 * area, "fz {fz}");
    // Gravity: Σ f_z = −m g with m = ρ V (lumped mass holds the whole mass).
    let fz: f64 = (0..model.nodes.len())
        .map(|p| f[(a.dofs.first[p] + 2, 1)])
        .sum();
    let mass = 7850.0 * L * B * B;
    assert!(
        (fz + mass * 9.81).abs() < 1e-9 * mass * 9.81,
        "gravity {fz}"
    );
}

/// Clamped cantilever, 4 normal modes: with residual vectors the file's static response to
/// every scene load equals the full FE solution to 1e-8; without them it does not.
#[test]
fn clamped_cantilever_static_response_is_exact_with_residual_vectors() {
    let path = write_deck("clamped", true);
    let model = model_of(&path);
    let scene = SceneSpec {
        gravity: Some("0,0,-9.81".into()),
        loads: vec![
            "LOAD_3".into(),
            format!("TIP:{}:0,500,-2000", nid(NX, 0, NZ)),
            "ENDP:SPC_99:1e5".into(),
        ],
        residual_vectors: None,
        ..Default::default()
    };
    let mut s = spec(&path, BuildMethod::Normal, 4, &[]);
    s.scene = scene.clone();
    let (plain, _) = built(&s);
    s.scene.residual_vectors = Some(ResidualKind::Loads);
    let (resvec, notes) = built(&s);
    let loads = flexbody::scene::scene_loads(&model, &scene).unwrap();
    let names: Vec<&str> = loads.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["LOAD_10", "GRAVITY", "LOAD_3", "TIP", "ENDP"]);
    let ml = resvec.modal_loads.as_ref().unwrap();
    assert_eq!(ml.loads.len(), 5);
    // 4 normal modes + 5 independent residual vectors; modes whose dominant origin is a
    // residual vector are marked (a label names the largest share, SPEC §5.5).
    assert_eq!(resvec.mode_count(), 9, "{notes:?}");
    assert!(
        ml.residual.iter().filter(|&&r| r == 1).count() >= 4,
        "{:?}",
        ml.residual
    );
    for name in names {
        let full = full_static(&model, &loads, name, false);
        let with = rel_error(&resvec, &model, &reduced_static(&resvec, name), &full);
        let without = rel_error(&plain, &model, &reduced_static(&plain, name), &full);
        println!("{name}: static error with residual vectors {with:.2e}, without {without:.2e} (4 normal modes)");
        assert!(with < 1e-8, "{name}: {with:e}");
        assert!(without > 1e-3, "{name}: {without:e}");
    }
}

fn exe() -> &'static str {
    env!("CARGO_BIN_EXE_flexbody")
}

/// Free-free cantilever block, Craig–Chang with a tip interface node and 10 free-free modes,
/// through the CLI: residual vectors of the scene loads and of the interface (the latter are
/// the attachment modes already in the basis: removed as dependent and reported). The rigid
/// modes and the rigid-body invariants are those of the build without residual vectors; every
/// residual mode is balanced (no rigid-body content); the file's static response equals the
/// full FE inertia-relief solution; `check --model` passes with nothing repeated.
#[test]
fn free_body_residual_vectors_are_balanced_and_exact() {
    let path = write_deck("free", false);
    let model = model_of(&path);
    let dir = path.parent().unwrap();
    let tip = nid(NX, NY, NZ).to_string();
    let side = format!("SIDE:{}:0,800,0", nid(NX / 2, 0, 0));
    let run = |out: &str, extra: &[&str]| -> std::process::Output {
        let mut args = vec![
            "build",
            path.to_str().unwrap(),
            "--method",
            "craig-chang",
            "--interface",
            &tip,
            "--modes",
            "10",
            "--units",
            "si",
            "-q",
            "--gravity",
            "0,0,-9.81",
            "--load",
            &side,
            "-o",
            out,
        ];
        args.extend(extra);
        std::process::Command::new(exe())
            .args(&args)
            .output()
            .unwrap()
    };
    let plain_p = dir.join("free_plain.flexbody");
    let res_p = dir.join("free_res.flexbody");
    let o = run(plain_p.to_str().unwrap(), &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run(res_p.to_str().unwrap(), &["--residual-vectors", "both"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report =
        String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    let plain = file::read(&plain_p).unwrap();
    let res = file::read(&res_p).unwrap();
    let ml = res.modal_loads.as_ref().unwrap();
    let names: Vec<&str> = ml.loads.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["LOAD_10", "GRAVITY", "SIDE"]);
    // Only SIDE adds a vector: GRAVITY alone is balanced by inertia (no response), LOAD_10 is
    // the tip force (at the interface node: its response is the attachment modes' combination)
    // plus 2·gravity, and the 3 interface unit loads are the attachment modes themselves —
    // all already in the basis, removed as dependent.
    let rigid = 6;
    assert_eq!(
        res.mode_count(),
        plain.mode_count() + 1,
        "{report}\n{:?}",
        res.modes.frequency_hz
    );
    assert_eq!(
        res.method.counts.removed_dependent,
        plain.method.counts.removed_dependent + 4,
        "{report}"
    );

    // rigid modes unchanged
    let n = res.nodes.len();
    for j in 0..rigid {
        assert_eq!(res.modes.labels[j], file::ModeLabel::Rigid);
        for i in 0..n * 6 {
            let (a, b) = (
                res.modes.shapes[j * n * 6 + i],
                plain.modes.shapes[j * n * 6 + i],
            );
            assert!(
                (a - b).abs() < 1e-12,
                "rigid mode {j} changed at {i}: {a} vs {b}"
            );
        }
    }
    // invariants of the rigid body unchanged: mass, first moment, inertia
    for (a, b) in [
        (&res.invariants.i1, &plain.invariants.i1),
        (&res.invariants.i2, &plain.invariants.i2),
        (&res.invariants.i7, &plain.invariants.i7),
    ] {
        for (x, y) in a.iter().zip(b.iter()) {
            assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "{x} vs {y}");
        }
    }
    // balanced: Σ_p m_p φ_rigid,p · φ_j,p = 0 for every residual mode (lumped nodal masses)
    let mass = &res.nodal_mass;
    for j in (0..res.mode_count()).filter(|&j| ml.residual[j] == 1) {
        for r in 0..rigid {
            let dot: f64 = (0..n)
                .map(|p| {
                    (0..3)
                        .map(|c| {
                            mass[p].mass
                                * res.modes.shapes[(r * n + p) * 6 + c]
                                * res.modes.shapes[(j * n + p) * 6 + c]
                        })
                        .sum::<f64>()
                })
                .sum();
            assert!(
                dot.abs() < 1e-10,
                "mode {j} has rigid content {dot:e} on rigid mode {r}"
            );
        }
    }
    // static response against the full FE inertia-relief solution
    let scene = SceneSpec {
        gravity: Some("0,0,-9.81".into()),
        loads: vec![side.clone()],
        residual_vectors: None,
        ..Default::default()
    };
    let loads = flexbody::scene::scene_loads(&model, &scene).unwrap();
    for name in ["LOAD_10", "SIDE"] {
        let full = full_static(&model, &loads, name, true);
        let with = rel_error(&res, &model, &reduced_static(&res, name), &full);
        let without = rel_error(&plain, &model, &reduced_static(&plain, name), &full);
        println!("free body {name}: static error with residual vectors {with:.2e}, without {without:.2e} (Craig–Chang, 10 free-free modes + 3 attachment)");
        assert!(with < 1e-8, "{name}: {with:e}");
        if name == "SIDE" {
            assert!(without > 1e-3, "{name}: {without:e}");
        } else {
            // the tip force acts at the interface: Craig–Chang's attachment modes hold it
            assert!(without < 1e-8, "{name}: {without:e}");
        }
    }
    // the gravity response of a free body is zero: its modal load acts on the rigid modes only
    let g = &ml.loads[1].values;
    let gmax = g.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for j in rigid..res.mode_count() {
        assert!(
            g[j].abs() < 1e-9 * gmax,
            "gravity on flexible mode {j}: {}",
            g[j]
        );
    }
    // check passes from the file's recipe alone
    let c = std::process::Command::new(exe())
        .args([
            "check",
            res_p.to_str().unwrap(),
            "--model",
            path.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        c.status.success(),
        "{}{}",
        String::from_utf8_lossy(&c.stdout),
        String::from_utf8_lossy(&c.stderr)
    );
}

/// The same cantilever as an Abaqus deck: step LOADS (*CLOAD at the tip, *DLOAD GRAV twice
/// g) and step PRESS (*DLOAD P2 on the top faces of the last elements).
fn abaqus_deck() -> String {
    let mut d = String::from("*HEADING\ncantilever\n*NODE\n");
    for k in 0..=NZ {
        for j in 0..=NY {
            for i in 0..=NX {
                d += &format!(
                    "{}, {}, {}, {}\n",
                    nid(i, j, k),
                    i as f64 * L / NX as f64,
                    j as f64 * B / NY as f64,
                    k as f64 * B / NZ as f64
                );
            }
        }
    }
    d += "*ELEMENT, TYPE=C3D8, ELSET=ALL\n";
    let mut e = 0;
    let mut top = Vec::new();
    for k in 0..NZ {
        for j in 0..NY {
            for i in 0..NX {
                e += 1;
                d += &format!(
                    "{e}, {}, {}, {}, {}, {}, {}, {}, {}\n",
                    nid(i, j, k),
                    nid(i + 1, j, k),
                    nid(i + 1, j + 1, k),
                    nid(i, j + 1, k),
                    nid(i, j, k + 1),
                    nid(i + 1, j, k + 1),
                    nid(i + 1, j + 1, k + 1),
                    nid(i, j + 1, k + 1)
                );
                if k == NZ - 1 && i >= NX - 2 {
                    top.push(e);
                }
            }
        }
    }
    d += "*NSET, NSET=ROOT\n";
    for k in 0..=NZ {
        for j in 0..=NY {
            d += &format!("{}\n", nid(0, j, k));
        }
    }
    d += "*ELSET, ELSET=TOP\n";
    for e in &top {
        d += &format!("{e}\n");
    }
    d += "*MATERIAL, NAME=STEEL\n*ELASTIC\n210e9, 0.3\n*DENSITY\n7850.\n";
    d += "*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL\n*BOUNDARY\nROOT, 1, 3\n";
    d += "*STEP, NAME=LOADS\n*STATIC\n*CLOAD\n";
    d += &format!(
        "{}, 2, 300.\n{}, 3, -1000.\n",
        nid(NX, NY, NZ),
        nid(NX, NY, NZ)
    );
    d += "*DLOAD\nALL, GRAV, 19.62, 0., 0., -1.\n*END STEP\n";
    d += "*STEP, NAME=PRESS\n*STATIC\n*DLOAD\nTOP, P2, 2.5e5\n*END STEP\n";
    d
}

/// Abaqus *CLOAD/*DLOAD give the same load vectors as the equivalent Nastran cards, and the
/// file's static response to the step loads equals the full FE solution.
#[test]
fn abaqus_step_loads_match_nastran_and_the_full_solution() {
    let bdf = write_deck("abq", true);
    let inp = bdf.with_file_name("cantilever.inp");
    std::fs::write(&inp, abaqus_deck()).unwrap();
    let (mn, ma) = (model_of(&bdf), model_of(&inp));
    let names: Vec<(&str, bool)> = ma
        .loads
        .iter()
        .map(|l| (l.name.as_str(), l.selected))
        .collect();
    assert_eq!(names, [("LOADS", true), ("PRESS", true)]);
    let vectors = |m: &Model, which: &[&str]| {
        let a = assemble(m, &AssemblySpec::default()).unwrap();
        let loads: Vec<_> = which
            .iter()
            .map(|w| m.loads.iter().find(|l| l.name == *w).unwrap().clone())
            .collect();
        let f = flexbody::fe::loads::load_vectors(m, &a.dofs, &a.m, &loads).unwrap();
        // by node id and component
        let mut out = std::collections::BTreeMap::new();
        for (p, node) in m.nodes.iter().enumerate() {
            for c in 0..3 {
                for q in 0..which.len() {
                    out.insert((node.id, c, q), f[(a.dofs.first[p] + c, q)]);
                }
            }
        }
        out
    };
    let fa = vectors(&ma, &["LOADS", "PRESS"]);
    let fn_ = vectors(&mn, &["LOAD_10", "LOAD_3"]);
    let top = fn_.values().fold(0.0f64, |a, v| a.max(v.abs()));
    for (k, v) in &fn_ {
        assert!(
            (fa[k] - v).abs() <= 1e-12 * top,
            "{k:?}: abaqus {} nastran {v}",
            fa[k]
        );
    }
    let mut s = spec(&inp, BuildMethod::Normal, 4, &[]);
    s.scene.residual_vectors = Some(ResidualKind::Loads);
    let (body, _) = built(&s);
    for name in ["LOADS", "PRESS"] {
        let full = full_static(&ma, &ma.loads, name, false);
        let err = rel_error(&body, &ma, &reduced_static(&body, name), &full);
        println!("abaqus {name}: static error with residual vectors {err:.2e}");
        assert!(err < 1e-8, "{name}: {err:e}");
    }
}

/// A load card the tool cannot use leaves the deck importable: the set is kept by name with
/// the reason (file, line, card) as a warning, and asking for it by name is a clear error.
#[test]
fn unsupported_load_cards_warn_and_refuse_by_name() {
    let path = write_deck("nonuniform", true);
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("ENDDATA", "PLOAD4,7,1,1.,2.,1.,1.\nENDDATA");
    std::fs::write(&path, text).unwrap();
    let model = model_of(&path);
    let w: Vec<&str> = model.warnings.iter().map(|w| w.message.as_str()).collect();
    assert!(
        w.iter().any(|m| m.contains("LOAD_7")
            && m.contains("non-uniform pressure")
            && m.contains("PLOAD4")),
        "{w:?}"
    );
    let scene = SceneSpec {
        loads: vec!["LOAD_7".into()],
        ..Default::default()
    };
    let e = flexbody::scene::scene_loads(&model, &scene)
        .unwrap_err()
        .to_string();
    assert!(e.contains("LOAD_7") && e.contains("non-uniform"), "{e}");
    // a moment on a solid node (3 dofs) is refused when assembled, naming load and node
    let scene = SceneSpec {
        loads: vec![format!("M:{}:0,0,0,1,0,0", nid(NX, 0, 0))],
        ..Default::default()
    };
    let loads = flexbody::scene::scene_loads(&model, &scene).unwrap();
    let a = assemble(&model, &AssemblySpec::default()).unwrap();
    let e = flexbody::fe::loads::load_vectors(&model, &a.dofs, &a.m, &loads[1..])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("load M") && e.contains(&format!("node {}", nid(NX, 0, 0))),
        "{e}"
    );
}

/// Residual vectors on every method's basis: Craig–Bampton (clamped cantilever, tip interface
/// node, 2 fixed-interface modes) and Dietz (free body, tip interface, 8 free-free modes): the
/// file's static response to the scene's loads equals the full FE solution.
#[test]
fn residual_vectors_on_craig_bampton_and_dietz() {
    let tip = nid(NX, NY, NZ).to_string();
    let side = format!("SIDE:{}:0,800,0", nid(NX / 2, 0, 0));
    for (method, clamped, modes) in [
        (BuildMethod::CraigBampton, true, 2),
        (BuildMethod::Dietz, false, 8),
    ] {
        let path = write_deck(&format!("{method:?}"), clamped);
        let model = model_of(&path);
        let mut s = spec(&path, method, modes, &[tip.as_str()]);
        s.scene = SceneSpec {
            gravity: Some("0,0,-9.81".into()),
            loads: vec![side.clone(), "LOAD_3".into()],
            residual_vectors: Some(ResidualKind::Loads),
            ..Default::default()
        };
        let (body, notes) = built(&s);
        let loads = flexbody::scene::scene_loads(&model, &s.scene).unwrap();
        let check: &[&str] = if clamped {
            &["LOAD_10", "GRAVITY", "SIDE", "LOAD_3"]
        } else {
            &["LOAD_10", "SIDE", "LOAD_3"]
        };
        for name in check {
            let full = full_static(&model, &loads, name, !clamped);
            let err = rel_error(&body, &model, &reduced_static(&body, name), &full);
            println!("{method:?} {name}: static error with residual vectors {err:.2e}");
            assert!(err < 1e-8, "{method:?} {name}: {err:e} {notes:?}");
        }
    }
}

/// Consistent mass on the native Craig–Bampton path (clamped cantilever, tip interface), where
/// the physical M is not held through the reduction but assembled again after it (issue 22):
/// the file's gravity modal load is Φᵀ Tᵀ (M g) with an independently assembled consistent M,
/// and its mass invariant I1 is the model's mass 1ᵀ M 1 over a translation.
#[test]
fn consistent_mass_craig_bampton_uses_the_consistent_m_for_gravity_and_invariants() {
    use flexbody::fe::MassKind;
    let path = write_deck("clamped_consistent", true);
    let model = model_of(&path);
    let tip = nid(NX, NY, NZ).to_string();
    let mut s = spec(&path, BuildMethod::CraigBampton, 6, &[tip.as_str()]);
    s.mass = MassKind::Consistent;
    s.scene = SceneSpec {
        gravity: Some("0,0,-9.81".into()),
        ..Default::default()
    };
    let mut phi = None;
    let out = flexbody::build::build_model_with_hook(&s, model.clone(), &mut |_| {}, &mut |set| {
        phi = Some(set.phi.clone())
    })
    .unwrap();
    let phi = phi.unwrap();
    let a = assemble(
        &model,
        &AssemblySpec {
            mass: MassKind::Consistent,
            ..Default::default()
        },
    )
    .unwrap();
    let r = eliminate(&model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    let loads = flexbody::scene::scene_loads(&model, &s.scene).unwrap();
    let gravity = loads.iter().find(|l| l.name == "GRAVITY").unwrap();
    let f = flexbody::fe::loads::load_vectors(&model, &a.dofs, &a.m, std::slice::from_ref(gravity))
        .unwrap();
    let want = phi.transpose() * flexbody::fe::loads::reduce_loads(&r.t, &f);
    let ml = out.body.modal_loads.as_ref().unwrap();
    let got = &ml
        .loads
        .iter()
        .find(|l| l.name == "GRAVITY")
        .unwrap()
        .values;
    let scale = (0..want.nrows())
        .map(|j| want[(j, 0)].abs())
        .fold(0.0, f64::max);
    for (j, g) in got.iter().enumerate() {
        assert!(
            (g - want[(j, 0)]).abs() <= 1e-10 * scale,
            "mode {j}: {g} vs {}",
            want[(j, 0)]
        );
    }
    // I1 = 1ᵀ M 1 over the x translation of every node
    let ones: Vec<f64> = (0..a.dofs.n_dofs)
        .map(|p| f64::from(u8::from(a.dofs.node_of(p).unwrap().1 == 0)))
        .collect();
    let mass: f64 = (0..a.m.ncols())
        .flat_map(|j| {
            let ones = &ones;
            a.m.row_idx_of_col_raw(j)
                .iter()
                .zip(a.m.val_of_col(j))
                .map(move |(&i, &v)| ones[i] * v * ones[j])
        })
        .sum();
    let i1 = out.body.invariants.i1[0];
    assert!((i1 - mass).abs() <= 1e-12 * mass, "I1 {i1} vs 1ᵀM1 {mass}");
}

/// SPEC §5.7 (1.6) for normal modes with residual vectors: a dependent residual vector is a
/// basis vector removed — `normal` counts it, `removed_dependent` too, and
/// `rigid + normal − removed_dependent = M` — while gravity on the free body (no static
/// response) is reported as "no residual vector" and counted nowhere. SIDE2 is SIDE doubled
/// (its response is SIDE's, so it is removed as dependent).
#[test]
fn normal_modes_count_removed_residual_vectors_as_basis_vectors() {
    let path = write_deck("free_nm", false);
    let side = format!("SIDE:{}:0,800,0", nid(NX / 2, 0, 0));
    let side2 = format!("SIDE2:{}:0,1600,0", nid(NX / 2, 0, 0));
    let axial = format!("AXIAL:{}:500,0,0", nid(NX, NY, NZ));
    let out = path.parent().unwrap().join("free_nm_res.flexbody");
    let o = std::process::Command::new(exe())
        .args([
            "build",
            path.to_str().unwrap(),
            "--method",
            "normal",
            "--modes",
            "10",
            "--units",
            "si",
            "--gravity",
            "0,0,-9.81",
            "--load",
            &side,
            "--load",
            &side2,
            "--load",
            &axial,
            "--residual-vectors",
            "loads",
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let report =
        String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{report}");
    let body = file::read(&out).unwrap();
    let c = &body.method.counts;
    let m = body.mode_count() as u64;
    assert_eq!(c.rigid, 6, "{report}");
    assert_eq!(c.removed_dependent, 1, "SIDE2 dependent on SIDE: {report}");
    assert_eq!(c.rigid + c.normal - c.removed_dependent, m, "{c:?}");
    let mut bare = body.clone();
    bare.eigen_residuals = None; // 1.9, in every build
    assert_eq!(
        file::version_for(&bare).minor,
        6,
        "a removed count in a normal-modes file is 1.6"
    );
    // SPEC §5.11: the normal-modes band is the highest mode not flagged residual; the
    // residual modes' pseudo-frequencies lie beyond it
    let band = &body.recipe.as_ref().unwrap().accuracy_band;
    let ml = body.modal_loads.as_ref().unwrap();
    let f = &body.modes.frequency_hz;
    let top_eigen = (0..f.len())
        .filter(|&j| ml.residual[j] == 0)
        .map(|j| f[j])
        .fold(0.0, f64::max);
    let top_residual = (0..f.len())
        .filter(|&j| ml.residual[j] == 1)
        .map(|j| f[j])
        .fold(0.0, f64::max);
    assert_eq!(band.rule, "normal-modes");
    assert!(
        (band.fmax_hz - top_eigen).abs() <= 1e-12 * top_eigen && top_residual > 0.0,
        "band {band:?}, highest eigenmode {top_eigen} Hz, highest residual mode {top_residual} Hz"
    );
    assert!(
        report.contains("SIDE2 (remaining")
            && report.contains("no residual vector for GRAVITY")
            && !report.contains("GRAVITY (remaining"),
        "{report}"
    );
}

/// SPEC §5.11 on the bundled conrod: normal modes `--modes 8` with a scene load and its
/// residual vector. The accuracy band is the highest eigenmode kept (2881.8 Hz), that of the
/// same build without loads — not the residual mode's static pseudo-frequency (17.9 kHz).
#[test]
fn normal_modes_band_ignores_the_residual_mode_on_the_conrod() {
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp");
    let dir = std::env::temp_dir().join(format!("flexbody-band-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let build = |name: &str, extra: &[&str]| -> file::ReducedBody {
        let out = dir.join(name);
        let mut args = vec![
            "build",
            model.to_str().unwrap(),
            "--method",
            "normal",
            "--modes",
            "8",
            "--units",
            "si",
            "--interface",
            "BIG_END,SMALL_END",
            "-q",
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        let o = std::process::Command::new(exe())
            .args(&args)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        file::read(&out).unwrap()
    };
    let plain = build("plain.flexbody", &[]);
    let loaded = build(
        "loaded.flexbody",
        &["--load", "P:1:0,0,1000", "--residual-vectors", "loads"],
    );
    let band = |b: &file::ReducedBody| b.recipe.as_ref().unwrap().accuracy_band.fmax_hz;
    let ml = loaded.modal_loads.as_ref().unwrap();
    let residual_top = (0..loaded.mode_count())
        .filter(|&j| ml.residual[j] == 1)
        .map(|j| loaded.modes.frequency_hz[j])
        .fold(0.0, f64::max);
    println!(
        "conrod normal --modes 8: band {:.4} Hz plain, {:.4} Hz with the residual mode at {residual_top:.1} Hz",
        band(&plain),
        band(&loaded)
    );
    assert_eq!(loaded.mode_count(), plain.mode_count() + 1);
    assert!(
        (band(&loaded) - band(&plain)).abs() <= 1e-6 * band(&plain),
        "{} vs {}",
        band(&loaded),
        band(&plain)
    );
    assert!(residual_top > 2.0 * band(&plain), "{residual_top}");
    let _ = std::fs::remove_dir_all(&dir);
}
