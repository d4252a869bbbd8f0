//! ANSYS connection elements written here, against closed form through the CLI: COMBIN14's 3-D
//! longitudinal spring (KEYOPT(2)=0: k along I→J) and 1-D spring (KEYOPT(2)=1…3: k between one
//! translation of I and J) holding a MASS21 point mass; the spring options not formed refused by
//! line naming the KEYOPT.

use std::path::Path;

use crate::common::{exe, generalized_eigenvalues, hz, scratch};
use faer::Mat;

/// An NBLOCK of `nodes` (id 1, 2, …).
fn nblock(nodes: &[[f64; 3]]) -> String {
    let mut s = format!("NBLOCK,6,SOLID,{0},{0}\n(3i9,6e21.13e3)\n", nodes.len());
    for (i, p) in nodes.iter().enumerate() {
        s.push_str(&format!(
            "{:>9}{:>9}{:>9}{:>21.13E}{:>21.13E}{:>21.13E}\n",
            i + 1,
            0,
            0,
            p[0],
            p[1],
            p[2]
        ));
    }
    s.push_str("N,R5.3,LOC,       -1,\n");
    s
}

/// An EBLOCK of (type, real constant set and section, id, nodes) records.
fn eblock(records: &[(usize, usize, usize, &[usize])]) -> String {
    let mut s = format!("EBLOCK,19,SOLID,{0},{0}\n(19i9)\n", records.len());
    // the section number is the real constant set's
    for (etype, real, id, nodes) in records {
        let head = [1, *etype, *real, *real, 0, 0, 0, 0, nodes.len(), 0, *id];
        for v in head.iter().chain(nodes.iter()) {
            s.push_str(&format!("{v:>9}"));
        }
        s.push('\n');
    }
    s.push_str("       -1\n");
    s
}

/// `flexbody build PATH --units si --method normal --modes N -o …`: the output.
fn build(path: &Path, modes: usize) -> std::process::Output {
    exe()
        .arg("build")
        .arg(path)
        .args(["--units", "si", "--method", "normal", "--modes"])
        .arg(modes.to_string())
        .arg("-o")
        .arg(path.with_extension("flexbody"))
        .output()
        .unwrap()
}

/// A spring of the test model: (node a, node b, stiffness, `None` along a→b or `Some(c)`
/// between translation c of a and b).
type Spring = (usize, usize, f64, Option<usize>);

/// K of the springs on the translations of the first `free` nodes (nodes past them grounded):
/// k e eᵀ on the blocks of a and b, −k e eᵀ between them (e the unit vector a→b, or the axis c).
fn spring_stiffness(x: &[[f64; 3]], springs: &[Spring], free: usize) -> Mat<f64> {
    let mut k = Mat::zeros(3 * free, 3 * free);
    for &(a, b, stiffness, axis) in springs {
        let e = match axis {
            Some(c) => {
                let mut e = [0.0; 3];
                e[c] = 1.0;
                e
            }
            None => {
                let d = [0, 1, 2].map(|i| x[b - 1][i] - x[a - 1][i]);
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                d.map(|c| c / n)
            }
        };
        for (p, sp) in [(a - 1, 1.0), (b - 1, -1.0)] {
            for (q, sq) in [(a - 1, 1.0), (b - 1, -1.0)] {
                if p < free && q < free {
                    for i in 0..3 {
                        for j in 0..3 {
                            k[(3 * p + i, 3 * q + j)] += sp * sq * stiffness * e[i] * e[j];
                        }
                    }
                }
            }
        }
    }
    k
}

/// Nodes: three masses (1–3, not on one line), grounded nodes 4–8 and 9–11 (coincident with
/// the masses, as a 1-D spring's nodes may be).
const X: [[f64; 3]; 11] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.2, -1.0, 0.3],
    [-1.0, 0.1, 0.2],
    [1.2, -0.9, 0.5],
    [0.1, 1.3, -0.8],
    [-0.7, 1.1, 0.4],
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
];
const MASSES: [f64; 3] = [2.0, 3.0, 1.5];
/// Longitudinal springs along skew lines (to grounded nodes and between the masses) and 1-D
/// springs (KEYOPT(2)=2, 3: UY, UZ; UX) to the coincident grounded nodes.
const SPRINGS: [Spring; 12] = [
    (1, 4, 1000.0, None),
    (1, 5, 2500.0, None),
    (1, 2, 1800.0, None),
    (2, 6, 1200.0, None),
    (2, 3, 900.0, None),
    (3, 7, 2100.0, None),
    (3, 8, 1500.0, None),
    (1, 9, 4000.0, Some(2)),
    (2, 10, 3000.0, Some(2)),
    (2, 10, 700.0, Some(1)),
    (3, 11, 3500.0, Some(2)),
    (3, 11, 600.0, Some(0)),
];

/// The archive of [`X`], [`MASSES`] (MASS21 KEYOPT(3)=2) and [`SPRINGS`] (COMBIN14: type 1 the
/// longitudinal spring, 2…4 the 1-D springs along UX, UY, UZ; the first spring's set also gives
/// a damping CV1, not read: a note), nodes 4–11 held; `extra_types` and `extra` (records of
/// type, real set, id, nodes) added.
fn springs_archive(extra_types: &str, extra: &[(usize, usize, usize, Vec<usize>)]) -> String {
    let mut cdb = format!(
        "/PREP7\nET,1,14\nET,2,14\nKEYOPT,2,2,1\nET,3,14\nKEYOPT,3,2,2\nET,4,14\n\
         KEYOPT,4,2,3\nET,5,21\nKEYOPT,5,3,2\n{extra_types}"
    );
    let mut records: Vec<(usize, usize, usize, Vec<usize>)> = Vec::new();
    for (i, &(a, b, k, axis)) in SPRINGS.iter().enumerate() {
        let damping = if i == 0 { ",5.0" } else { "" };
        cdb.push_str(&format!("R,{},{k:e}{damping}\n", i + 1));
        records.push((axis.map_or(1, |c| 2 + c), i + 1, i + 1, vec![a, b]));
    }
    for (i, m) in MASSES.iter().enumerate() {
        cdb.push_str(&format!("R,{},{m:e}\n", 20 + i));
        records.push((5, 20 + i, 20 + i, vec![i + 1]));
    }
    records.extend(extra.iter().cloned());
    cdb.push_str(&nblock(&X));
    let as_refs: Vec<(usize, usize, usize, &[usize])> = (records.iter())
        .map(|(t, r, id, n)| (*t, *r, *id, n.as_slice()))
        .collect();
    cdb.push_str(&eblock(&as_refs));
    for n in 4..=11 {
        cdb.push_str(&format!("D,{n},ALL,0\n"));
    }
    cdb.push_str("FINISH\n");
    cdb
}

/// `cdb` built through the CLI (normal modes, all `modes`) → the frequencies; the stderr must
/// name COMBIN14's damping.
fn frequencies(dir: &str, cdb: &str, modes: usize) -> Vec<f64> {
    let path = scratch(dir).join("springs.cdb");
    std::fs::write(&path, cdb).unwrap();
    let o = build(&path, modes);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("COMBIN14 damping"), "{stderr}");
    flexbody_reader::read(path.with_extension("flexbody"))
        .unwrap()
        .modes
        .frequency_hz
}

/// The largest relative difference of `ours` to the generalized eigenfrequencies of (k, m).
fn against(ours: &[f64], k: &Mat<f64>, m: &Mat<f64>) -> f64 {
    let expected: Vec<f64> = generalized_eigenvalues(k, m).into_iter().map(hz).collect();
    assert!(expected[0] > 1.0, "{expected:?}");
    assert_eq!(ours.len(), expected.len(), "{ours:?} {expected:?}");
    (ours.iter().zip(&expected))
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(0.0, f64::max)
}

/// The diagonal mass of [`MASSES`] on their translations.
fn mass_matrix() -> Mat<f64> {
    Mat::from_fn(9, 9, |i, j| if i == j { MASSES[i / 3] } else { 0.0 })
}

/// The nine frequencies of [`springs_archive`] are those of the springs' K (assembled here from
/// k e eᵀ) over the masses.
#[test]
fn combin14_springs_holding_masses_equal_closed_form() {
    let ours = frequencies("ansys-combin14", &springs_archive("", &[]), 9);
    let worst = against(&ours, &spring_stiffness(&X, &SPRINGS, 3), &mass_matrix());
    // measured 1.8e-15 (a 9-dof system)
    println!("COMBIN14 springs and masses against closed form: {worst:.2e}; {ours:?}");
    assert!(worst < 2e-14, "{ours:?}");
}

/// An MPC184 rigid link (KEYOPT(1)=0) from mass node 1 to grounded node 5 keeps their distance:
/// the eight frequencies are those of K and M on the motions with e·u₁ = 0 (e from node 1 to
/// node 5), u = P q with u₁ₓ eliminated.
#[test]
fn mpc184_rigid_link_equals_the_constrained_closed_form() {
    let cdb = springs_archive("ET,6,184\n", &[(6, 1, 100, vec![1, 5])]);
    let ours = frequencies("ansys-mpc184-link", &cdb, 8);
    let e = [X[4][0] - X[0][0], X[4][1] - X[0][1], X[4][2] - X[0][2]];
    // P: 9 × 8, q = u without u₁ₓ; u₁ₓ = −(e_y u₁y + e_z u₁z)/e_x
    let p = Mat::from_fn(9, 8, |row, col| match (row, col) {
        (0, 0 | 1) => -e[col + 1] / e[0],
        (0, _) => 0.0,
        _ => f64::from(u8::from(row - 1 == col)),
    });
    let k = p.transpose() * spring_stiffness(&X, &SPRINGS, 3) * &p;
    let m = p.transpose() * mass_matrix() * &p;
    let worst = against(&ours, &k, &m);
    // measured 7.4e-16
    println!("MPC184 rigid link against closed form: {worst:.2e}; {ours:?}");
    assert!(worst < 8e-15, "{ours:?}");
}

/// COMBIN14 KEYOPT(3)=1 (torsional) and KEYOPT(2)=4 (1-D rotational): exit 2, each named
/// with its element's line.
#[test]
fn combin14_options_not_formed_are_refused_by_line() {
    let x = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
    let cdb = format!(
        "/PREP7\nET,1,14\nKEYOPT,1,3,1\nET,2,COMBIN14\nKEYOPT,2,2,4\nR,1,10.0\n{}{}FINISH\n",
        nblock(&x),
        eblock(&[(1, 1, 1, &[1, 2]), (2, 1, 2, &[1, 2])])
    );
    let work = scratch("ansys-combin14-refused");
    let path = work.join("torsion.cdb");
    std::fs::write(&path, &cdb).unwrap();
    let o = build(&path, 3);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    // the NBLOCK takes lines 7–11, the EBLOCK's records are lines 14 and 15
    assert!(
        err.contains("torsion.cdb:14: EBLOCK element of type 1 (COMBIN14, ET line 2): COMBIN14 KEYOPT(3)=1 (torsional"),
        "{err}"
    );
    assert!(
        err.contains("torsion.cdb:15: EBLOCK element of type 2 (COMBIN14, ET line 4): COMBIN14 KEYOPT(2)=4 (a 1-D rotational spring"),
        "{err}"
    );
    assert!(!path.with_extension("flexbody").exists());
}

/// Five LINK180 along x (h = 0.4), node 1 clamped, the transverse translations held: the axial
/// modes of the discrete fixed–free bar, u_j = sin(jθ_k), θ_k = (2k − 1)π/(2n) (half of the
/// fixed–fixed bar of 2n elements), ω² = 6E/(ρ'h²)·(1 − cos θ)/(2 + cos θ) with the consistent
/// mass ρ'Ah/6·[2 1; 1 2] and 2E/(ρ'h²)·(1 − cos θ) with the lumped ρ'Ah/2, ρ' = ρ + ADDMAS/A.
/// Area and added mass from a LINK section, then from real constants.
#[test]
fn link180_bar_equals_the_discrete_closed_form() {
    let (n, h, e, rho, area, added) = (5usize, 0.4, 2.1e11, 7850.0, 1.0e-4, 0.5);
    let x: Vec<[f64; 3]> = (0..=n).map(|j| [j as f64 * h, 0.0, 0.0]).collect();
    let records: Vec<(usize, usize, usize, Vec<usize>)> =
        (1..=n).map(|j| (1, 1, j, vec![j, j + 1])).collect();
    let as_refs: Vec<(usize, usize, usize, &[usize])> = (records.iter())
        .map(|(t, r, id, nodes)| (*t, *r, *id, nodes.as_slice()))
        .collect();
    let mut held = String::from("D,1,ALL,0\n");
    for j in 2..=n + 1 {
        held.push_str(&format!("D,{j},UY,0\nD,{j},UZ,0\n"));
    }
    let material = format!(
        "MPTEMP,R5.0, 1, 1,  0.00000000    ,\nMPDATA,R5.0, 1,EX  ,       1, 1, {e:e},\n\
         MPTEMP,R5.0, 1, 1,  0.00000000    ,\nMPDATA,R5.0, 1,PRXY,       1, 1, 0.3,\n\
         MPTEMP,R5.0, 1, 1,  0.00000000    ,\nMPDATA,R5.0, 1,DENS,       1, 1, {rho:e},\n"
    );
    let archive = |section: &str| {
        format!(
            "/PREP7\nET,1,180\n{section}{}{}{material}{held}FINISH\n",
            nblock(&x),
            eblock(&as_refs)
        )
    };
    let by_section = archive(&format!(
        "SECTYPE,       1,LINK,     ,\nSECDATA, {area:e},\nSECCONTROL, {added:e},\n"
    ));
    let by_reals = archive(&format!("R,1,{area:e},{added:e}\n"));
    let rho_eff = rho + added / area;
    let theta = |k: usize| (2 * k - 1) as f64 * std::f64::consts::PI / (2 * n) as f64;
    let consistent: Vec<f64> = (1..=n)
        .map(|k| 6.0 * e / (rho_eff * h * h) * (1.0 - theta(k).cos()) / (2.0 + theta(k).cos()))
        .map(hz)
        .collect();
    let lumped: Vec<f64> = (1..=n)
        .map(|k| 2.0 * e / (rho_eff * h * h) * (1.0 - theta(k).cos()))
        .map(hz)
        .collect();
    let work = scratch("ansys-link180");
    let mut worst: f64 = 0.0;
    for (name, text) in [("section", &by_section), ("reals", &by_reals)] {
        let path = work.join(format!("{name}.cdb"));
        std::fs::write(&path, text).unwrap();
        for (mass, expected) in [("consistent", &consistent), ("lumped", &lumped)] {
            let o = exe()
                .arg("build")
                .arg(&path)
                .args([
                    "--units", "si", "--method", "normal", "--modes", "5", "--mass", mass,
                ])
                .arg("-o")
                .arg(path.with_extension("flexbody"))
                .output()
                .unwrap();
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            let ours = flexbody_reader::read(path.with_extension("flexbody"))
                .unwrap()
                .modes
                .frequency_hz;
            assert_eq!(ours.len(), n, "{ours:?}");
            let d = (ours.iter().zip(expected.iter()))
                .map(|(a, b)| ((a - b) / b).abs())
                .fold(0.0, f64::max);
            println!("LINK180 {name} {mass}: {d:.2e}; {ours:?}");
            worst = worst.max(d);
        }
    }
    // measured 9.0e-16 (lumped), 2.2e-16 (consistent)
    assert!(worst < 9e-15, "{worst:e}");
}
