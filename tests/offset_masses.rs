//! A point mass off its node (CONM2 X1–X3) on a Nastran beam line, as engineers hang a motor or
//! a counterweight on a bar model: it builds by every method with Nastran's default lumped
//! mass (CBAR: translations only), the file's nodal masses give the body's mass and first
//! moment exactly (closed form), `check --model` passes, and the frequencies equal those of the
//! model assembled with the offset mass's own 6×6 matrix (an independent path: no mass node).

use std::path::{Path, PathBuf};

use crate::common::{exe, generalized_eigenvalues, hz, scratch};
use flexbody::fe::{assemble, AssemblySpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody_reader as file;

/// Mass 2 at offset (0.1, 0.05, −0.02) from the tip of a free line of four CBARs along x
/// (ρA = 0.27 kg/m, L = 0.8 m), with inertia about its centre of gravity.
const TIP_MASS: f64 = 2.0;
const OFFSET: [f64; 3] = [0.1, 0.05, -0.02];

fn deck(dir: &Path) -> PathBuf {
    let mut s = String::from(
        "SOL 103\nCEND\nBEGIN BULK\nMAT1,1,7.e10,,.33,2700.\n\
         PBAR,2,1,1.e-4,2.e-9,1.e-9,3.e-9\n",
    );
    for i in 1..=5 {
        s += &format!("GRID,{i},,{:?},0.,0.\n", (i - 1) as f64 * 0.2);
    }
    for i in 1..=4 {
        s += &format!("CBAR,{i},2,{i},{},0.,1.,0.\n", i + 1);
    }
    s += &format!(
        "CONM2,30,5,,{TIP_MASS:?},{:?},{:?},{:?},,+\n+,0.01,,0.02,,,0.015\nENDDATA\n",
        OFFSET[0], OFFSET[1], OFFSET[2]
    );
    let path = dir.join("tip_mass.bdf");
    std::fs::write(&path, s).unwrap();
    path
}

fn run(args: &[&str]) -> (bool, String) {
    let o = exe().args(args).output().unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

fn flexible_hz(body: &file::ReducedBody) -> Vec<f64> {
    (body.modes.frequency_hz.iter().zip(&body.modes.labels))
        .filter(|(_, l)| **l != file::ModeLabel::Rigid)
        .map(|(f, _)| *f)
        .collect()
}

/// Body mass I1 and first moment I2 from the deck by hand: the bars' mass ρAL/2 at each end of
/// each bar (Nastran's lumped CBAR mass), the point mass at node 5 + offset.
fn closed_form_i1_i2() -> (f64, [f64; 3]) {
    let bar = 2700.0 * 1e-4 * 0.2;
    let mut m = TIP_MASS;
    let mut s = [0.0; 3];
    for i in 0..4 {
        for x in [0.2 * i as f64, 0.2 * (i + 1) as f64] {
            m += bar / 2.0;
            s[0] += bar / 2.0 * x;
        }
    }
    for (k, sk) in s.iter_mut().enumerate() {
        *sk += TIP_MASS * ([0.8, 0.0, 0.0][k] + OFFSET[k]);
    }
    (m, s)
}

#[test]
fn offset_point_mass_on_a_lumped_beam_line_builds_by_every_method_and_checks() {
    let dir = scratch("offset-mass");
    let bdf = deck(&dir);
    let (m_exact, s_exact) = closed_form_i1_i2();
    // normal modes first: the Craig–Bampton build with every interior mode is compared with it
    // cb8: a truncated basis whose twist column moves only the offset mass — M-dependent on the
    // rigid rotation; the rigid one is kept and the twist condensed (it is massless)
    let cases: [(&str, &[&str]); 5] = [
        ("normal", &["--method", "normal", "--modes", "18"]),
        ("cb1", &["--interface", "1", "--modes", "15"]),
        ("cb8", &["--interface", "1", "--modes", "8"]),
        ("cb2", &["--interface", "1,5", "--modes", "6"]),
        (
            "cc2",
            &[
                "--method",
                "craig-chang",
                "--interface",
                "1,5",
                "--modes",
                "12",
            ],
        ),
    ];
    let mut normal_hz = Vec::new();
    for (name, extra) in cases {
        let out = dir.join(format!("{name}.flexbody"));
        let mut args = vec!["build", bdf.to_str().unwrap(), "--units", "si", "-o"];
        args.push(out.to_str().unwrap());
        args.extend_from_slice(extra);
        let (ok, err) = run(&args);
        assert!(ok, "{name}: {err}");
        assert!(
            err.contains("point mass 30: its centre of gravity, off node 5, is node 6"),
            "{name}: {err}"
        );
        let body = file::read(&out).unwrap();
        assert_eq!(
            body.modes
                .labels
                .iter()
                .filter(|l| **l == file::ModeLabel::Rigid)
                .count(),
            6,
            "{name}"
        );
        // the mass node: at the centre of gravity, holding the mass and its inertia
        let k = body
            .nodes
            .iter()
            .position(|n| n.id == 6)
            .expect("mass node 6 stored");
        let x = body.nodes[k].xyz;
        for c in 0..3 {
            assert!(
                (x[c] - [0.8, 0.0, 0.0][c] - OFFSET[c]).abs() < 1e-15,
                "{name}: {x:?}"
            );
        }
        assert_eq!(body.nodal_mass[k].mass, TIP_MASS, "{name}");
        assert_eq!(body.nodal_mass[k].inertia[1][1], 0.02, "{name}");
        // I1 and I2 from the file against the deck's closed form
        let inv = &body.invariants;
        assert!(
            (inv.i1[0] - m_exact).abs() < 1e-12 * m_exact,
            "{name}: I1 {}",
            inv.i1[0]
        );
        for c in 0..3 {
            assert!(
                (inv.i2[c] - s_exact[c]).abs() < 1e-12 * m_exact,
                "{name}: I2 {:?} vs {s_exact:?}",
                inv.i2
            );
        }
        let (ok, report) = {
            let o = exe()
                .args([
                    "check",
                    out.to_str().unwrap(),
                    "--model",
                    bdf.to_str().unwrap(),
                ])
                .output()
                .unwrap();
            (
                o.status.success(),
                String::from_utf8_lossy(&o.stdout).to_string(),
            )
        };
        assert!(ok && report.contains("0 failed: PASS"), "{name}: {report}");
        if name == "normal" {
            normal_hz = flexible_hz(&body);
        } else if name == "cb1" {
            // every interior mode kept (15 with mass): the Craig–Bampton body is the free body
            let cb = flexible_hz(&body);
            assert_eq!(cb.len(), normal_hz.len(), "{cb:?} vs {normal_hz:?}");
            for (a, b) in cb.iter().zip(&normal_hz) {
                assert!((a - b).abs() < 1e-6 * b, "cb1 {a} vs normal {b}");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Consistent mass: the normal modes of the built body equal the generalized eigenvalues of the
/// model assembled as read (the point mass's 6×6 matrix at node 5, no mass node) to 1e-8.
#[test]
fn offset_point_mass_frequencies_equal_the_six_by_six_point_mass() {
    let dir = scratch("offset-mass-consistent");
    let bdf = deck(&dir);
    let model = read_model(&bdf, &ImportOptions::default()).unwrap();
    let a = assemble(
        &model,
        &AssemblySpec {
            mass: MassKind::Consistent,
            ..Default::default()
        },
    )
    .unwrap();
    let lambda = generalized_eigenvalues(&crate::common::dense(&a.k), &crate::common::dense(&a.m));
    let reference: Vec<f64> = lambda.iter().skip(6).take(8).map(|&l| hz(l)).collect();
    let out = dir.join("c.flexbody");
    let (ok, err) = run(&[
        "build",
        bdf.to_str().unwrap(),
        "--units",
        "si",
        "--method",
        "normal",
        "--mass",
        "consistent",
        "--modes",
        "14",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let f = flexible_hz(&file::read(&out).unwrap());
    assert!(f.len() >= 8);
    for (q, (a, b)) in f.iter().zip(&reference).enumerate() {
        assert!(
            (a - b).abs() < 1e-8 * b,
            "mode {q}: {a} vs 6×6 point mass {b}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
