//! Offset shells (Nastran CQUAD4/CTRIA3 ZOFFS, `model::shell_offset`), through the CLI.
//!
//! Reference: a plate of thickness 2t is the same as two plates of thickness t sharing its
//! grid points with their reference planes at ZOFFS = ±t/2 — membrane 2·Et, bending
//! 2·(t³/12 + t·(t/2)²)·E = (2t)³/12·E, mass 2ρt, rotary inertia 2ρ(t³/12 + t·t²/4) = ρ(2t)³/12.
//! Without the offsets the two layers would bend as 2·t³/12: a quarter of the stiffness, half
//! the frequency. Simply supported square plate (w held on the edges; in-plane and drilling
//! dofs held on every grid, so the modes are the bending modes): Navier/Leissa
//! f_mn = (π/2)(m² + n²)/a² · √(D/(ρh)).

use std::path::PathBuf;

use crate::common::exe;

const A: f64 = 1.0;
const T: f64 = 0.01;
const E: f64 = 210e9;
const NU: f64 = 0.3;
const RHO: f64 = 7850.0;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexbody-offsets-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// An n×n simply supported plate deck; `layers` = [(PID, thickness, ZOFFS)] one CQUAD4 per
/// cell and layer (`tria`: two CTRIA3 per cell instead).
fn plate_deck(n: usize, layers: &[(u32, f64, f64)], tria: bool) -> String {
    let mut s = String::from("SOL 103\nCEND\nMETHOD = 1\nSPC = 1\nBEGIN BULK\n");
    s += "PARAM,COUPMASS,1\nEIGRL,1,,,6\n";
    s += &format!("MAT1,1,{E},,{NU},{RHO}\n");
    for &(pid, t, _) in layers {
        s += &format!("PSHELL,{pid},1,{t},1,,1\n");
    }
    let id = |i: usize, j: usize| 1 + i + (n + 1) * j;
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (A * i as f64 / n as f64, A * j as f64 / n as f64);
            s += &format!("GRID,{},,{x},{y},0.0\n", id(i, j));
            let edge = i == 0 || j == 0 || i == n || j == n;
            s += &format!(
                "SPC1,1,{},{}\n",
                if edge { "1236" } else { "126" },
                id(i, j)
            );
        }
    }
    let mut eid = 1;
    for (l, &(pid, _, z)) in layers.iter().enumerate() {
        for j in 0..n {
            for i in 0..n {
                let g = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
                if tria {
                    for t in [[g[0], g[1], g[2]], [g[0], g[2], g[3]]] {
                        s += &format!("CTRIA3,{eid},{pid},{},{},{},,{z}\n", t[0], t[1], t[2]);
                        eid += 1;
                    }
                } else {
                    s += &format!(
                        "CQUAD4,{eid},{pid},{},{},{},{},,{z}\n",
                        g[0], g[1], g[2], g[3]
                    );
                    eid += 1;
                }
            }
        }
        let _ = l;
    }
    s + "ENDDATA\n"
}

/// Build `deck` (normal modes, the deck's mass and mode count) → (frequencies, stderr).
fn build(name: &str, deck: &str) -> (Vec<f64>, String) {
    crate::common::build_bdf_modes(&format!("offsets-{name}"), deck)
}

fn leissa_hz(h: f64, m: f64, n: f64) -> f64 {
    let d = E * h.powi(3) / (12.0 * (1.0 - NU * NU));
    std::f64::consts::FRAC_PI_2 * (m * m + n * n) / (A * A) * (d / (RHO * h)).sqrt()
}

#[test]
fn two_offset_layers_are_one_plate_of_twice_the_thickness() {
    let n = 16;
    let (single, _) = build("single", &plate_deck(n, &[(1, 2.0 * T, 0.0)], false));
    let (layered, stderr) = build(
        "layered",
        &plate_deck(n, &[(1, T, 0.5 * T), (2, T, -0.5 * T)], false),
    );
    assert!(stderr.contains("ZOFFS: 512 CQUAD4/CTRIA3"), "{stderr}");
    let (coincident, _) = build(
        "coincident",
        &plate_deck(n, &[(1, T, 0.0), (2, T, 0.0)], false),
    );
    let exact =
        [(1.0, 1.0), (1.0, 2.0), (2.0, 1.0), (2.0, 2.0)].map(|(m, k)| leissa_hz(2.0 * T, m, k));
    for i in 0..4 {
        let (s, l) = (single[i], layered[i]);
        // 2e-3 before issue 44: each layer's CQUAD4 carries the residual bending flexibility of
        // its own D (an eighth of the single plate's), which the offsets do not stiffen:
        // measured −2.3, −3.1, …, −4.75 % on modes 0 … 3 at 16 × 16 (it vanishes as h²)
        assert!(
            (l - s).abs() <= 0.06 * s,
            "mode {i}: layered {l} vs single {s}"
        );
        assert!(
            (s - exact[i]).abs() <= 0.02 * exact[i],
            "mode {i}: {s} vs Leissa {}",
            exact[i]
        );
        // without the offsets: half the frequency (a quarter of the bending stiffness)
        let ratio = coincident[i] / s;
        assert!(
            (ratio - 0.5).abs() < 0.01,
            "mode {i}: coincident/single = {ratio}"
        );
    }
    eprintln!(
        "single {:?}\nlayered {:?}\nLeissa {exact:?}",
        &single[..4],
        &layered[..4]
    );
}

/// Triangles: each layer's membrane is constant-strain, so the three quarters of the bending
/// that the offsets carry (d²·Et, d = t/2) see one curvature per element, from the linear
/// interpolation of the grids' rotations, while the single plate's DKMT curvature varies
/// within the element — the layered plate is softer and converges to the single one at first
/// order (measured: 12.8 % at 8×8, 4.7 % at 16×16 on the first four modes). MSC's CTRIA3
/// membrane is constant-strain too.
#[test]
fn offset_triangles_converge_to_one_plate_of_twice_the_thickness() {
    let gap = |n: usize| {
        let (single, _) = build(
            &format!("single-tria{n}"),
            &plate_deck(n, &[(1, 2.0 * T, 0.0)], true),
        );
        let (layered, _) = build(
            &format!("layered-tria{n}"),
            &plate_deck(n, &[(1, T, 0.5 * T), (2, T, -0.5 * T)], true),
        );
        eprintln!(
            "tria n = {n}: single {:?} layered {:?}",
            &single[..4],
            &layered[..4]
        );
        (0..4)
            .map(|i| (layered[i] - single[i]).abs() / single[i])
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (gap(8), gap(16));
    assert!(
        coarse < 0.15 && fine < 0.06 && fine < 0.45 * coarse,
        "gaps {coarse:e} → {fine:e}"
    );
}

/// One layer offset by ZOFFS = t/2 on the plate's grid plane: its reference plane is above the
/// supports, so it is no longer the mid-plane plate — the frequencies change (the offset is
/// honoured, not dropped); and a CQUAD8 with ZOFFS is refused naming its card and line.
#[test]
fn a_single_offset_layer_changes_the_plate_and_cquad8_offsets_are_refused() {
    let n = 8;
    let (mid, _) = build("mid", &plate_deck(n, &[(1, T, 0.0)], false));
    let (off, _) = build("off", &plate_deck(n, &[(1, T, 0.5 * T)], false));
    assert!(off[0] > 1.05 * mid[0], "{} vs {}", off[0], mid[0]);

    let deck = "SOL 103\nCEND\nBEGIN BULK\nMAT1,1,2.1e11,,0.3,7850.\nPSHELL,1,1,0.01\n\
                GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,1.,1.,0.\nGRID,4,,0.,1.,0.\n\
                GRID,5,,.5,0.,0.\nGRID,6,,1.,.5,0.\nGRID,7,,.5,1.,0.\nGRID,8,,0.,.5,0.\n\
                CQUAD8,1,1,1,2,3,4,5,6,\n,7,8,,,,,,0.005\nENDDATA\n";
    let path = scratch("quad8.bdf");
    std::fs::write(&path, deck).unwrap();
    let o = exe()
        .arg("build")
        .arg(&path)
        .args(["--units", "si", "--method", "normal", "-o"])
        .arg(scratch("quad8.flexbody"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        stderr.contains("quad8.bdf:15") && stderr.contains("ZOFFS"),
        "{stderr}"
    );
}

/// PCOMP Z0 (the bottom surface from the reference plane; the mid-plane at Z0 + T/2): a
/// one-ply PCOMP with Z0 = 0 is the PSHELL at ZOFFS = T/2 (to 1e-10), and two PCOMP layers with
/// Z0 = 0 and Z0 = −T on the same grids are the plate of 2T, as the ZOFFS layers are.
#[test]
fn pcomp_z0_offsets_the_mid_plane() {
    let n = 8;
    let pcomp = |deck: String, z0: [f64; 2]| {
        deck.replace(
            &format!("PSHELL,1,1,{T},1,,1\n"),
            &format!("PCOMP,1,{:?}\n,1,{T},0.\n", z0[0]),
        )
        .replace(
            &format!("PSHELL,2,1,{T},1,,1\n"),
            &format!("PCOMP,2,{:?}\n,1,{T},0.\n", z0[1]),
        )
    };
    let (zoffs, _) = build("z-zoffs", &plate_deck(n, &[(1, T, 0.5 * T)], false));
    let (z0, stderr) = build(
        "z-pcomp",
        &pcomp(plate_deck(n, &[(1, T, 0.0)], false), [0.0, 0.0]),
    );
    assert!(stderr.contains("ZOFFS: 64 CQUAD4/CTRIA3"), "{stderr}");
    for (a, b) in zoffs.iter().zip(&z0) {
        assert!((a - b).abs() <= 1e-10 * b, "{a} vs {b}");
    }
    let (layers, _) = build(
        "z-pcomp-layers",
        &pcomp(plate_deck(n, &[(1, T, 0.0), (2, T, 0.0)], false), [0.0, -T]),
    );
    let (zoffs_layers, _) = build(
        "z-zoffs-layers",
        &plate_deck(n, &[(1, T, 0.5 * T), (2, T, -0.5 * T)], false),
    );
    for (a, b) in layers.iter().zip(&zoffs_layers) {
        assert!((a - b).abs() <= 1e-10 * b, "{a} vs {b}");
    }
}
