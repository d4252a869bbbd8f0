//! Nastran CQUADR/CTRIAR: the CQUAD4/CTRIA3 plate with a membrane that carries the drilling
//! rotation (`fe::elements::drill_membrane`), through the CLI.
//!
//! References: a flat plate's bending modes do not involve the membrane, so a CQUADR/CTRIAR
//! plate bends exactly as the CQUAD4/CTRIA3 one; in-plane, a clamped strip L × h (t thin)
//! vibrates as a Timoshenko beam bending in its plane, f₁ ≈ (1.8751²/2π)·√(EI/(ρA L⁴)) with
//! I = t h³/12 (slender: the shear correction is below 0.5 %); and PARAM,K6ROT, the CQUAD4's
//! drilling penalty, does not enter a CQUADR (its drilling stiffness is the membrane's own).

use std::path::PathBuf;

use crate::common::exe;

const E: f64 = 2.1e11;
const NU: f64 = 0.3;
const RHO: f64 = 7850.0;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexbody-drilling-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// An nx × ny strip lx × ly in the x–y plane, clamped at x = 0, of `card` elements (CQUAD4,
/// CQUADR; CTRIA3/CTRIAR: two per cell); `held`: components held on every grid.
fn strip(
    card: &str,
    (nx, ny): (usize, usize),
    (lx, ly): (f64, f64),
    held: &str,
    extra: &str,
) -> String {
    let mut s = format!(
        "SOL 103\nCEND\nMETHOD = 1\nSPC = 1\nBEGIN BULK\nPARAM,COUPMASS,1\n{extra}EIGRL,1,,,4\n\
         MAT1,1,{E:?},,{NU},{RHO:?}\nPSHELL,1,1,0.01,1,,1\n"
    );
    let id = |i: usize, j: usize| 1 + i + (nx + 1) * j;
    for j in 0..=ny {
        for i in 0..=nx {
            s += &format!(
                "GRID,{},,{:?},{:?},0.\n",
                id(i, j),
                lx * i as f64 / nx as f64,
                ly * j as f64 / ny as f64
            );
            let c = if i == 0 { "123456" } else { held };
            if !c.is_empty() {
                s += &format!("SPC1,1,{c},{}\n", id(i, j));
            }
        }
    }
    let mut eid = 1;
    for j in 0..ny {
        for i in 0..nx {
            let g = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if card.starts_with("CTRIA") {
                for t in [[g[0], g[1], g[2]], [g[0], g[2], g[3]]] {
                    s += &format!("{card},{eid},1,{},{},{}\n", t[0], t[1], t[2]);
                    eid += 1;
                }
            } else {
                s += &format!("{card},{eid},1,{},{},{},{}\n", g[0], g[1], g[2], g[3]);
                eid += 1;
            }
        }
    }
    s + "ENDDATA\n"
}

/// Build `deck` with normal modes (the deck's consistent mass and 4 modes) → frequencies.
fn freqs(name: &str, deck: &str) -> Vec<f64> {
    crate::common::build_bdf_modes(&format!("drilling-{name}"), deck).0
}

/// Out of plane (in-plane dofs 1, 2, 6 held): the CQUADR/CTRIAR plate is the CQUAD4/CTRIA3 one.
#[test]
fn bending_is_the_cquad4_plate() {
    for (r, base) in [("CQUADR", "CQUAD4"), ("CTRIAR", "CTRIA3")] {
        let a = freqs(r, &strip(r, (8, 4), (1.0, 0.5), "126", ""));
        let b = freqs(base, &strip(base, (8, 4), (1.0, 0.5), "126", ""));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() <= 1e-9 * y, "{r}: {x} vs {base} {y}");
        }
    }
}

/// In plane (out-of-plane dofs 3, 4, 5 held): the strip's first in-plane bending frequency
/// against the beam, converging from above (the clamp holds the drilling rotation too, which
/// the in-plane rotation at a clamped root need not be): CQUADR +1.24 % on 20×2, +0.26 % on
/// 40×4 (CQUAD4's QM6: +0.05 %, −0.05 %); independent of K6ROT; CTRIAR (Allman's triangle,
/// stiff in bending) +16.2 % on 20×2, +4.5 % on 40×4: second order.
#[test]
fn in_plane_bending_against_the_beam_and_k6rot_does_not_enter() {
    let (l, h): (f64, f64) = (2.0, 0.1);
    let i = 0.01 * h.powi(3) / 12.0;
    let beam = 1.875_104_f64.powi(2) / (2.0 * std::f64::consts::PI)
        * (E * i / (RHO * 0.01 * h * l.powi(4))).sqrt();
    let quadr = freqs(
        "quadr-in-plane",
        &strip("CQUADR", (20, 2), (l, h), "345", ""),
    );
    let finer = freqs("quadr-finer", &strip("CQUADR", (40, 4), (l, h), "345", ""))[0] / beam;
    let coarse_q = quadr[0] / beam;
    assert!(
        coarse_q < 1.015 && finer < coarse_q && (finer - 1.0).abs() < 0.005,
        "{coarse_q} → {finer}"
    );
    let stiff = strip("CQUADR", (20, 2), (l, h), "345", "PARAM,K6ROT,1.e4\n");
    assert_eq!(freqs("quadr-k6rot", &stiff)[0], quadr[0]);
    let coarse = freqs("triar-coarse", &strip("CTRIAR", (20, 2), (l, h), "345", ""))[0] / beam;
    let fine = freqs("triar-fine", &strip("CTRIAR", (40, 4), (l, h), "345", ""))[0] / beam;
    assert!(
        fine > 1.0 && fine - 1.0 < 0.05 && fine - 1.0 < 0.35 * (coarse - 1.0),
        "{coarse} → {fine}"
    );
    eprintln!("beam {beam}: CQUADR {coarse_q} → {finer}, CTRIAR {coarse} → {fine}");
}

/// What the drilling membrane does not have yet is refused naming it: stress/strain shapes.
#[test]
fn cquadr_stress_shapes_are_refused() {
    let path = scratch("stress.bdf");
    std::fs::write(&path, strip("CQUADR", (4, 2), (1.0, 0.5), "", "")).unwrap();
    let o = exe()
        .arg("build")
        .arg(&path)
        .args([
            "--units",
            "si",
            "--method",
            "normal",
            "--stress-modes",
            "-o",
        ])
        .arg(scratch("stress.flexbody"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("CQUADR/CTRIAR"),
        "{err}"
    );
    assert!(!scratch("stress.flexbody").exists());
}
