//! Composite shells (issue 34): classical lamination in the flat shells (CQUAD4/CTRIA3 on PCOMP,
//! MAT8, MAT2, THETA/MCID), through the command line, against independent references.
//!
//! * Simply supported laminated plates against the Navier solution of classical lamination
//!   theory (Reddy, *Mechanics of Laminated Composite Plates and Shells*, 2nd ed. (2004):
//!   cross-ply §5.3 with the SS-1 conditions (eq. 5.3.1: w = 0 and the tangential in-plane
//!   displacement held on each edge), antisymmetric angle-ply §5.4 with SS-2 (eq. 5.4.1: w = 0
//!   and the normal in-plane displacement held)). For mode (m, n), α = mπ/a, β = nπ/b, the
//!   Navier fields (u, v, w) = (U cos αx sin βy, V sin αx cos βy, W sin αx sin βy) (SS-1) or
//!   (U sin αx cos βy, V cos αx sin βy, W sin αx sin βy) (SS-2) solve the CLT equations exactly,
//!   so ω² is the lowest eigenvalue of the 3×3 problem (Reddy eqs. 5.3.8, 5.4.7)
//!   [s_ij] − ω² diag(I₀, I₀, I₀ + I₂(α² + β²)); the test forms s_ij from the CLT energy of
//!   these fields (A, B, D of the plies computed here from Q̄(θ), Reddy eq. 2.3.17), and for the
//!   symmetric cross-ply also by the closed form ω² = [D11α⁴ + 2(D12 + 2D66)α²β² + D22β⁴]/
//!   (I₀ + I₂(α² + β²)) (Reddy eq. 5.3.10).
//! * Plates are thin (a/h = 200) so the shells' transverse shear (5/6 ∫G dz) stays below the
//!   tolerance; 20 × 20 CQUAD4.
//! * A one-ply PCOMP of MAT1 and a one-ply MAT8 of isotropic constants equal the PSHELL to
//!   1e-10; an orthotropic ply turned 90° by THETA or MCID equals the ply with E1/E2 swapped.
//! * Abaqus: `*SHELL SECTION, COMPOSITE` of `*ELASTIC, TYPE=LAMINA` plies is the PCOMP of
//!   MAT8 plies (to 1e-10, default local axes = global x projected), and `*ORIENTATION` on the
//!   section turns the material like THETA.
//! * What is not formed is an error naming card/keyword and line: MAT9 on a shell, PCOMP LAM =
//!   SMEAR, an `*ORIENTATION` per ply, a cylindrical orientation on a shell.

use crate::common::{exe, scratch};
use flexbody_reader as file;
use std::f64::consts::PI;
use std::fmt::Write as _;

/// A 0.4 × 0.3 m plate of 8 × 6 CQUAD4 (CTRIA3 in the last column) with the property and
/// material lines `cards`, free, 12 modes.
fn plate(cards: &str) -> String {
    let (nx, ny, a, b) = (8, 6, 0.4, 0.3);
    let mut s = String::from("SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\nEIGRL,1,,,12\n");
    s.push_str(cards);
    let id = |i: usize, j: usize| 1 + i + (nx + 1) * j;
    for j in 0..=ny {
        for i in 0..=nx {
            let (x, y) = (a * i as f64 / nx as f64, b * j as f64 / ny as f64);
            writeln!(s, "GRID,{},,{x},{y},0.", id(i, j)).unwrap();
        }
    }
    let mut e = 0;
    for j in 0..ny {
        for i in 0..nx {
            let c = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            e += 1;
            if i + 1 == nx {
                writeln!(s, "CTRIA3,{e},1,{},{},{}", c[0], c[1], c[2]).unwrap();
                e += 1;
                // G1→G2 along −x: a THETA from it turns the material as on the quads.
                writeln!(s, "CTRIA3,{e},1,{},{},{}", c[2], c[3], c[0]).unwrap();
            } else {
                writeln!(s, "CQUAD4,{e},1,{},{},{},{}", c[0], c[1], c[2], c[3]).unwrap();
            }
        }
    }
    s.push_str("ENDDATA\n");
    s
}

/// The boundary conditions of the simply supported plates (module doc).
#[derive(Clone, Copy, PartialEq)]
enum Support {
    /// SS-1: w and the tangential in-plane displacement held.
    Tangential,
    /// SS-2: w and the normal in-plane displacement held.
    Normal,
}

/// An a × b plate of n × n CQUAD4 on PCOMP/PSHELL `cards`, simply supported (`support`),
/// `modes` modes. Rotations about the edge normal (the FSDT's tangential φ) are held too.
fn supported_plate(
    cards: &str,
    (a, b): (f64, f64),
    n: usize,
    support: Support,
    modes: usize,
) -> String {
    let mut s = format!("SOL 103\nCEND\nSPC = 1\nMETHOD = 1\nBEGIN BULK\nEIGRL,1,,,{modes}\n");
    s.push_str(cards);
    let id = |i: usize, j: usize| 1 + i + (n + 1) * j;
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (a * i as f64 / n as f64, b * j as f64 / n as f64);
            writeln!(s, "GRID,{},,{x},{y},0.", id(i, j)).unwrap();
            let (on_x, on_y) = (i == 0 || i == n, j == 0 || j == n);
            // edges x = 0, a: w, θx (φy) and v (SS-1) or u (SS-2); edges y = 0, b likewise
            let mut dofs = String::new();
            if on_x || on_y {
                dofs.push('3');
            }
            match support {
                Support::Tangential => {
                    if on_y {
                        dofs.push('1');
                    }
                    if on_x {
                        dofs.push('2');
                    }
                }
                Support::Normal => {
                    if on_x {
                        dofs.push('1');
                    }
                    if on_y {
                        dofs.push('2');
                    }
                }
            }
            if on_x {
                dofs.push('4');
            }
            if on_y {
                dofs.push('5');
            }
            if !dofs.is_empty() {
                let mut d: Vec<char> = dofs.chars().collect();
                d.sort();
                writeln!(s, "SPC1,1,{},{}", d.iter().collect::<String>(), id(i, j)).unwrap();
            }
        }
    }
    let mut e = 0;
    for j in 0..n {
        for i in 0..n {
            e += 1;
            let c = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            writeln!(s, "CQUAD4,{e},1,{},{},{},{}", c[0], c[1], c[2], c[3]).unwrap();
        }
    }
    s.push_str("ENDDATA\n");
    s
}

fn build(name: &str, deck: &str, ext: &str) -> Result<file::ReducedBody, String> {
    build_with(name, deck, ext, "consistent")
}

/// `flexbody build` of `deck` with `--mass mass`, normal modes, SI; an Abaqus deck's shells as
/// flexbody's (`--inp-shells native`: ccx expands shells into bricks and refuses composites).
fn build_with(name: &str, deck: &str, ext: &str, mass: &str) -> Result<file::ReducedBody, String> {
    let dir = scratch(&format!("laminates-{name}"));
    let path = dir.join(format!("{name}.{ext}"));
    std::fs::write(&path, deck).unwrap();
    let out = dir.join(format!("{name}.flexbody"));
    let o = exe()
        .arg("build")
        .arg(&path)
        .args(if ext == "inp" {
            &["--inp-shells", "native"][..]
        } else {
            &[]
        })
        .args([
            "-q", "--units", "si", "--method", "normal", "--mass", mass, "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    if !o.status.success() {
        return Err(String::from_utf8_lossy(&o.stderr).into_owned());
    }
    Ok(file::read(&out).unwrap())
}

fn frequencies(name: &str, deck: &str) -> Vec<f64> {
    build(name, deck, "bdf")
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .modes
        .frequency_hz
}

fn assert_same(a: &[f64], b: &[f64], skip: usize, tol: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (x, y) in a.iter().zip(b).skip(skip) {
        assert!((x / y - 1.0).abs() < tol, "{what}: {x} {y}\n{a:?}\n{b:?}");
    }
    assert!(a[skip] > 1.0, "{what}: {a:?}");
}

const MAT1: &str = "MAT1,7,7.e10,,0.33,2700.\n";

/// Three plies of one aluminium (0/45/90: an isotropic material turns into itself) are the
/// PSHELL of the total thickness with MID2 = MID3 = MID1, 12I/T³ = 1, TS/T = 5/6; so are one
/// ply of it, and one ply of a MAT8 with the aluminium's constants (E1 = E2, G12 = G1Z = G2Z =
/// E/(2(1+ν))), formed by classical lamination.
#[test]
fn one_material_pcomp_and_isotropic_mat8_equal_pshell() {
    let pshell = frequencies(
        "pshell",
        &plate(&format!("{MAT1}PSHELL,1,7,0.006,7,1.,7,0.833333333333\n")),
    );
    let pcomp = frequencies(
        "pcomp",
        &plate(&format!(
            "{MAT1}PCOMP,1\n,7,0.002,0.,YES,7,0.002,45.,YES\n,7,0.002,90.,YES\n"
        )),
    );
    assert_same(&pshell, &pcomp, 6, 1e-10, "three plies of MAT1");
    let one_ply = frequencies("pcomp1", &plate(&format!("{MAT1}PCOMP,1\n,7,0.006,30.\n")));
    assert_same(&pshell, &one_ply, 6, 1e-10, "one ply of MAT1");
    let g = 7e10 / (2.0 * 1.33);
    let mat8 = format!("MAT8,7,7.e10,7.e10,0.33,{g:e},{g:e},{g:e},2700.\n");
    let lamina = frequencies(
        "mat8-iso",
        &plate(&format!("{mat8}PCOMP,1\n,7,0.006,30.\n")),
    );
    assert_same(&pshell, &lamina, 6, 1e-10, "one isotropic MAT8 ply");
    let mat8_pshell = frequencies(
        "mat8-pshell",
        &plate(&format!("{mat8}PSHELL,1,7,0.006,7,1.,7,0.833333333333\n")),
    );
    assert_same(
        &pshell,
        &mat8_pshell,
        6,
        1e-10,
        "PSHELL of an isotropic MAT8",
    );
}

/// A ply of the orthotropic MAT8 turned 90° by THETA (from the G1→G2 side) or by MCID (a
/// system whose x-axis is the basic y) is the ply with E1 ↔ E2 and G1Z ↔ G2Z swapped, on
/// quadrilaterals and triangles.
#[test]
fn theta_and_mcid_turn_the_material() {
    let ply = |e1: &str, e2: &str, g1z: &str, g2z: &str| {
        format!("MAT8,7,{e1},{e2},0.3,5.e9,{g1z},{g2z},1600.\nPCOMP,1\n,7,0.004,0.\n")
    };
    let along = ply("1.4e11", "1.e10", "5.e9", "3.e9");
    let swapped = ply("1.e10", "1.4e11", "3.e9", "5.e9");
    // ν12 E2 = ν21 E1: the swapped ply's ν12 is 0.3 · 1e10/1.4e11
    let swapped = swapped.replace(",0.3,", &format!(",{:e},", 0.3 * 1e10 / 1.4e11));
    let want = frequencies("swapped", &plate(&swapped));
    let plain = frequencies("along", &plate(&along));
    assert!((plain[7] / want[7] - 1.0).abs() > 0.2, "{plain:?} {want:?}");
    let theta = plate(&along)
        .lines()
        .map(|l| {
            if l.starts_with("CQUAD4") || l.starts_with("CTRIA3") {
                format!("{l},90.\n")
            } else {
                format!("{l}\n")
            }
        })
        .collect::<String>();
    // CQUAD4 has THETA in field 7, CTRIA3 in field 6: both the field after the grids
    assert_same(&want, &frequencies("theta", &theta), 6, 1e-10, "THETA = 90");
    let mcid = theta.replace(",90.\n", ",5\n").replace(
        "BEGIN BULK\n",
        "BEGIN BULK\nCORD2R,5,,0.,0.,0.,0.,0.,1.\n,0.,1.,0.\n",
    );
    // CORD2R 5: z along basic z, the x–z plane through (0, 1, 0): x along basic y
    assert_same(
        &want,
        &frequencies("mcid", &mcid),
        6,
        1e-10,
        "MCID x along y",
    );
}

/// PCOMPG (one ply a line, with its global ply id) is the PCOMP of the same plies, SYM too.
#[test]
fn pcompg_equals_pcomp() {
    let pcomp = frequencies(
        "pcomp-sym",
        &plate(&format!(
            "{MAT8}PCOMP,1,,,,,,,SYM\n,7,0.001,0.,,7,0.002,45.\n"
        )),
    );
    let pcompg = frequencies(
        "pcompg-sym",
        &plate(&format!(
            "{MAT8}PCOMPG,1,,,,,,,SYM\n,101,7,0.001,0.,,,,\n,102,7,0.002,45.\n"
        )),
    );
    assert_same(&pcomp, &pcompg, 6, 1e-12, "PCOMPG");
}

/// An orthotropic ply (Reddy's material: E1/E2 = 25 would need thinner plates; here E1/E2 =
/// 10, ν12 = 0.25, G12 = G13 = 0.6 E2, G23 = 0.5 E2).
const E1: f64 = 100e9;
const E2: f64 = 10e9;
const NU12: f64 = 0.25;
const G12: f64 = 6e9;
const RHO: f64 = 1600.0;
const MAT8: &str = "MAT8,7,1.e11,1.e10,0.25,6.e9,6.e9,5.e9,1600.\n";

type M3 = [[f64; 3]; 3];

/// Q̄ of a ply at θ (Reddy (2004) eq. 2.3.17, written out).
fn q_bar(theta_deg: f64) -> M3 {
    let den = 1.0 - NU12 * NU12 * E2 / E1;
    let (q11, q22, q12, q66) = (E1 / den, E2 / den, NU12 * E2 / den, G12);
    let (s, c) = theta_deg.to_radians().sin_cos();
    let b11 = q11 * c.powi(4) + 2.0 * (q12 + 2.0 * q66) * s * s * c * c + q22 * s.powi(4);
    let b12 = (q11 + q22 - 4.0 * q66) * s * s * c * c + q12 * (s.powi(4) + c.powi(4));
    let b22 = q11 * s.powi(4) + 2.0 * (q12 + 2.0 * q66) * s * s * c * c + q22 * c.powi(4);
    let b16 = (q11 - q12 - 2.0 * q66) * s * c.powi(3) + (q12 - q22 + 2.0 * q66) * s.powi(3) * c;
    let b26 = (q11 - q12 - 2.0 * q66) * s.powi(3) * c + (q12 - q22 + 2.0 * q66) * s * c.powi(3);
    let b66 = (q11 + q22 - 2.0 * q12 - 2.0 * q66) * s * s * c * c + q66 * (s.powi(4) + c.powi(4));
    [[b11, b12, b16], [b12, b22, b26], [b16, b26, b66]]
}

/// A, B, D of equal plies of thickness `t` at `angles`, bottom to top (Reddy eq. 3.3.17).
fn abd(angles: &[f64], t: f64) -> (M3, M3, M3) {
    let (mut a, mut b, mut d) = ([[0.0; 3]; 3], [[0.0; 3]; 3], [[0.0; 3]; 3]);
    let h = t * angles.len() as f64;
    for (k, &th) in angles.iter().enumerate() {
        let (z0, z1) = (-h / 2.0 + k as f64 * t, -h / 2.0 + (k + 1) as f64 * t);
        let q = q_bar(th);
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += q[i][j] * (z1 - z0);
                b[i][j] += q[i][j] * (z1 * z1 - z0 * z0) / 2.0;
                d[i][j] += q[i][j] * (z1.powi(3) - z0.powi(3)) / 3.0;
            }
        }
    }
    (a, b, d)
}

/// The Navier frequency (Hz) of mode (m, n) of the CLT plate (module doc): the 3×3 stiffness
/// of the Navier fields from their CLT energy (midpoint rule, exact for these trigonometric
/// products), then the lowest root of det(S − ω² M).
fn navier(
    (a_m, b_m, d_m): (M3, M3, M3),
    h: f64,
    (a, b): (f64, f64),
    (m, n): (usize, usize),
    support: Support,
) -> f64 {
    let (al, be) = (m as f64 * PI / a, n as f64 * PI / b);
    let np = 64;
    let mut s = [[0.0; 3]; 3];
    for ix in 0..np {
        for iy in 0..np {
            let (x, y) = (
                (ix as f64 + 0.5) * a / np as f64,
                (iy as f64 + 0.5) * b / np as f64,
            );
            let (sx, cx, sy, cy) = (
                (al * x).sin(),
                (al * x).cos(),
                (be * y).sin(),
                (be * y).cos(),
            );
            // strains (εx, εy, γxy, κx, κy, κxy) of unit U, V, W; κ = −(w,xx, w,yy, 2w,xy)
            let w = [
                0.0,
                0.0,
                0.0,
                al * al * sx * sy,
                be * be * sx * sy,
                -2.0 * al * be * cx * cy,
            ];
            let (u, v) = match support {
                Support::Tangential => (
                    [-al * sx * sy, 0.0, be * cx * cy, 0.0, 0.0, 0.0],
                    [0.0, -be * sx * sy, al * cx * cy, 0.0, 0.0, 0.0],
                ),
                Support::Normal => (
                    [al * cx * cy, 0.0, -be * sx * sy, 0.0, 0.0, 0.0],
                    [0.0, be * cx * cy, -al * sx * sy, 0.0, 0.0, 0.0],
                ),
            };
            let f = [u, v, w];
            let c6 = |i: usize, j: usize| match (i < 3, j < 3) {
                (true, true) => a_m[i][j],
                (false, false) => d_m[i - 3][j - 3],
                (true, false) => b_m[i][j - 3],
                (false, true) => b_m[j][i - 3],
            };
            for p in 0..3 {
                for q in 0..3 {
                    let e: f64 = (0..6)
                        .map(|i| f[p][i] * (0..6).map(|j| c6(i, j) * f[q][j]).sum::<f64>())
                        .sum();
                    s[p][q] += e * (a / np as f64) * (b / np as f64);
                }
            }
        }
    }
    // kinetic energy ∫ of sin²·cos² etc. = ab/4 for every field
    let i0 = RHO * h * a * b / 4.0;
    let mass = [i0, i0, i0 * (1.0 + h * h / 12.0 * (al * al + be * be))];
    // lowest root of det(S − λ M) on λ by bisection below the uncoupled w root
    let det = |l: f64| -> f64 {
        let k: M3 = std::array::from_fn(|i| {
            std::array::from_fn(|j| s[i][j] - if i == j { l * mass[i] } else { 0.0 })
        });
        k[0][0] * (k[1][1] * k[2][2] - k[1][2] * k[2][1])
            - k[0][1] * (k[1][0] * k[2][2] - k[1][2] * k[2][0])
            + k[0][2] * (k[1][0] * k[2][1] - k[1][1] * k[2][0])
    };
    let (mut lo, mut hi) = (0.0, s[2][2] / mass[2] * (1.0 + 1e-12));
    let sign0 = det(lo).signum();
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if det(mid).signum() == sign0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi)).sqrt() / (2.0 * PI)
}

/// The lowest `count` Navier frequencies over m, n ≤ 5, ascending.
fn navier_lowest(
    abd: (M3, M3, M3),
    h: f64,
    ab: (f64, f64),
    support: Support,
    count: usize,
) -> Vec<(f64, (usize, usize))> {
    let mut f: Vec<(f64, (usize, usize))> = (1..=5)
        .flat_map(|m| (1..=5).map(move |n| (m, n)))
        .map(|mn| (navier(abd, h, ab, mn, support), mn))
        .collect();
    f.sort_by(|x, y| x.0.total_cmp(&y.0));
    f.truncate(count);
    f
}

const SIDE: (f64, f64) = (1.0, 1.0);
const PLY_T: f64 = 0.00125; // 4 plies: h = 5 mm, a/h = 200

fn pcomp(angles: &[f64]) -> String {
    let mut s = format!("{MAT8}PCOMP,1\n");
    for th in angles {
        writeln!(s, ",7,{PLY_T},{th:.1}").unwrap();
    }
    s
}

/// The plate of `angles` under `support` at 20 × 20 against Navier: with lumped mass (Nastran's
/// default) the lowest `count` modes within 1 %; with consistent mass the fundamental within
/// 0.5 % and the others within 3 % (MITC4 with consistent mass is stiff by O(h²): measured
/// +1.1 % at 20 × 20 and +0.24 % at 40 × 40 on the cross-ply's mode (2, 1)). Returns the
/// consistent-mass frequencies.
fn compare(name: &str, angles: &[f64], support: Support, count: usize) -> Vec<f64> {
    let h = PLY_T * angles.len() as f64;
    let deck = supported_plate(&pcomp(angles), SIDE, 20, support, count);
    let want = navier_lowest(abd(angles, PLY_T), h, SIDE, support, count);
    let lumped = build_with(&format!("{name}-lumped"), &deck, "bdf", "lumped")
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .modes
        .frequency_hz;
    let consistent = frequencies(name, &deck);
    for (k, (w, mn)) in want.iter().enumerate() {
        let (l, c) = (lumped[k] / w - 1.0, consistent[k] / w - 1.0);
        eprintln!(
            "{name} {angles:?} mode {mn:?}: Navier {w:.4} Hz, lumped {:.4} Hz ({l:+.2e}), \
             consistent {:.4} Hz ({c:+.2e})",
            lumped[k], consistent[k]
        );
        // 1 % before issue 44; the QUAD4's residual bending flexibility removes MITC4's O(h²)
        // stiffness that offset the lumped mass's O(h²) softness: measured down to −1.79 %
        // (angle-ply (2, 2)), −1.06 % (cross-ply (2, 2))
        assert!(
            l.abs() < 0.025,
            "{name} lumped: {} against {w} ({mn:?})",
            lumped[k]
        );
        let tol = if k == 0 { 0.005 } else { 0.03 };
        assert!(
            c.abs() < tol,
            "{name} consistent: {} against {w} ({mn:?})",
            consistent[k]
        );
    }
    consistent
}

/// Symmetric cross-ply [0/90/90/0], SS-1: the lowest five modes within 1 % of Navier; the
/// 3×3 Navier root equals the closed form of eq. 5.3.10 (B = 0, no in-plane coupling).
#[test]
fn symmetric_cross_ply_matches_navier() {
    let angles = [0.0, 90.0, 90.0, 0.0];
    let h = 4.0 * PLY_T;
    let (_, _, d) = abd(&angles, PLY_T);
    let (al, be) = (PI, PI);
    let closed = ((d[0][0] * al.powi(4)
        + 2.0 * (d[0][1] + 2.0 * d[2][2]) * al * al * be * be
        + d[1][1] * be.powi(4))
        / (RHO * h * (1.0 + h * h / 12.0 * (al * al + be * be))))
        .sqrt()
        / (2.0 * PI);
    let ritz = navier(abd(&angles, PLY_T), h, SIDE, (1, 1), Support::Tangential);
    assert!((ritz / closed - 1.0).abs() < 1e-10, "{ritz} {closed}");
    compare("cross-sym", &angles, Support::Tangential, 5);
}

/// Antisymmetric cross-ply [0/90], SS-1: within 1 % of Navier; B lowers the fundamental by
/// what CLT predicts: the same A and D without B (a PSHELL of two MAT2: MID1 = A/h, MID2 =
/// 12D/h³) is higher by the Navier ratio, to 2e-4 (measured 1.3e-5).
#[test]
fn antisymmetric_cross_ply_matches_navier_and_its_coupling() {
    let angles = [0.0, 0.0, 90.0, 90.0];
    let coupled = compare("cross-anti", &angles, Support::Tangential, 5);
    let h = 4.0 * PLY_T;
    let (a, b, d) = abd(&angles, PLY_T);
    assert!(b[0][0].abs() > 1e-3 * a[0][0] * h, "{b:?}");
    let zero = [[0.0; 3]; 3];
    let with_b = navier((a, b, d), h, SIDE, (1, 1), Support::Tangential);
    let without_b = navier((a, zero, d), h, SIDE, (1, 1), Support::Tangential);
    let mat2 = |id: u32, q: M3, f: f64| {
        format!(
            "MAT2,{id},{:e},{:e},{:e},{:e},{:e},{:e},{:e}\n",
            q[0][0] * f,
            q[0][1] * f,
            q[0][2] * f,
            q[1][1] * f,
            q[1][2] * f,
            q[2][2] * f,
            if id == 11 { RHO } else { 0.0 }
        )
    };
    // MID3: a MAT8's G1Z/G2Z (the plies' 5/6 ∫G dz = 5/6 h (G13 + G23)/2 on both axes of the
    // cross-ply: diag(5.5e9, 5.5e9)), TS/T = 5/6
    let cards = format!(
        "{}{}MAT8,13,1.e10,1.e10,0.,5.5e9,5.5e9,5.5e9\nPSHELL,1,11,{h},12,1.,13,0.833333333333\n",
        mat2(11, a, 1.0 / h),
        mat2(12, d, 12.0 / h.powi(3)),
    );
    let uncoupled = frequencies(
        "cross-anti-b0",
        &supported_plate(&cards, SIDE, 20, Support::Tangential, 1),
    );
    // the same with a MID3 MAT2 of G11 = G22 = 5.5e9, G13, G23, G33 blank (MSC QRG MAT2)
    let mat2_mid3 = cards.replace(
        "MAT8,13,1.e10,1.e10,0.,5.5e9,5.5e9,5.5e9\n",
        "MAT2,13,5.5e9,0.,,5.5e9\n",
    );
    let by_mat2 = frequencies(
        "cross-anti-b0-mat2",
        &supported_plate(&mat2_mid3, SIDE, 20, Support::Tangential, 1),
    );
    assert!(
        (by_mat2[0] / uncoupled[0] - 1.0).abs() < 1e-12,
        "{by_mat2:?} {uncoupled:?}"
    );
    let (fe, clt) = (coupled[0] / uncoupled[0], with_b / without_b);
    eprintln!("[0/90] with B / without B: FE {fe:.5}, CLT {clt:.5}");
    assert!(clt < 0.95, "{clt}");
    // measured 5.5e-4 (1e-4 before the residual bending flexibility of issue 44)
    assert!((fe / clt - 1.0).abs() < 2e-3, "{fe} {clt}");
}

/// Antisymmetric angle-ply [45/−45/45/−45], SS-2: within 1 % of Navier.
#[test]
fn antisymmetric_angle_ply_matches_navier() {
    compare(
        "angle-anti",
        &[45.0, -45.0, 45.0, -45.0],
        Support::Normal,
        5,
    );
    compare(
        "angle-anti2",
        &[30.0, -30.0, 30.0, -30.0],
        Support::Normal,
        3,
    );
}

/// What is not formed is an error naming the card or keyword and its line.
#[test]
fn unsupported_laminates_are_refused_by_card_and_line() {
    let nastran = [
        (
            "mat9-shell",
            "MAT9,7,1.e11,3.e10,3.e10,0.,0.,0.,1.e11\n,3.e10,0.,0.,0.,1.e11,0.,0.,0.\n\
             ,3.5e10,0.,0.,3.5e10,0.,3.5e10,2700.\nPSHELL,1,7,0.006,7\n"
                .to_owned(),
            vec!["MAT9 7", "anisotropic", "only solid elements take it"],
        ),
        (
            "smear",
            format!("{MAT8}PCOMP,1,,,,,,,SMEAR\n,7,0.002,0.\n"),
            vec!["bdf:7: PCOMP 1", "LAM = SMEAR"],
        ),
        (
            // an aluminium ply under a MAT8 ply: the first mass moment is not zero
            "mass-moment",
            format!("{MAT8}{MAT1}PCOMP,1\n,7,0.002,0.,,1,0.002,0.\n").replace("MAT1,7,", "MAT1,1,"),
            vec!["property 1", "first mass moment"],
        ),
        (
            "mat8-one-gz",
            "MAT8,7,1.4e11,1.e10,0.3,5.e9,5.e9,,1600.\nPCOMP,1\n,7,0.002,0.\n".to_owned(),
            vec!["bdf:6: MAT8 7", "G1Z and G2Z"],
        ),
    ];
    for (name, cards, want) in nastran {
        let err = build(name, &plate(&cards), "bdf").unwrap_err();
        for w in want {
            assert!(err.contains(w), "{name}: no '{w}' in {err}");
        }
    }
    // corner thicknesses on a laminate's element
    let corner = plate(&format!("{MAT8}PCOMP,1\n,7,0.002,0.\n")).replace(
        "CQUAD4,1,1,1,2,11,10\n",
        "CQUAD4,1,1,1,2,11,10,,\n,,,0.003,0.003,0.003,0.003\n",
    );
    let err = build("corner", &corner, "bdf").unwrap_err();
    assert!(
        err.contains("element 1") && err.contains("corner thicknesses T1.. on a laminate"),
        "{err}"
    );
    let mesh = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n\
                *ELEMENT, TYPE=S4, ELSET=P\n1, 1, 2, 3, 4\n";
    let lamina = "*MATERIAL, NAME=PLY\n*ELASTIC, TYPE=LAMINA\n1.4e11, 1e10, 0.3, 5e9, 5e9, 3e9\n\
                  *DENSITY\n1600\n";
    let abaqus = [
        (
            "ply-orientation-name",
            format!(
                "{mesh}{lamina}*ORIENTATION, NAME=O\n1, 0, 0, 0, 1, 0\n\
                 *SHELL SECTION, ELSET=P, COMPOSITE\n0.002, 3, PLY, O\n"
            ),
            vec!["inp:16", "ply orientation O", "*SHELL SECTION ELSET=P"],
        ),
        (
            "unknown-ply-material",
            format!("{mesh}{lamina}*SHELL SECTION, ELSET=P, COMPOSITE\n0.002, 3, PLY, 0\n0.002, 3, AL, 90\n"),
            vec!["inp:15", "unknown material AL"],
        ),
        (
            "cylindrical",
            format!(
                "{mesh}{lamina}*ORIENTATION, NAME=C, SYSTEM=CYLINDRICAL\n0, 0, 0, 0, 0, 1\n\
                 *SHELL SECTION, ELSET=P, MATERIAL=PLY, ORIENTATION=C\n0.002\n"
            ),
            vec!["inp:15", "ORIENTATION=C is cylindrical"],
        ),
    ];
    for (name, deck, want) in abaqus {
        let err = build(name, &deck, "inp").unwrap_err();
        for w in want {
            assert!(err.contains(w), "{name}: no '{w}' in {err}");
        }
    }
}

/// The plate of `supported_plate` as an Abaqus deck of S4 with the section and material lines
/// `section` (`*BOUNDARY` for the SPC1 lines, a `*FREQUENCY` step of `modes`).
fn abaqus_plate(nastran: &str, section: &str, modes: usize) -> String {
    let mut s = String::from("*NODE, NSET=ALL\n");
    let mut elements = String::from("*ELEMENT, TYPE=S4, ELSET=P\n");
    let mut boundary = String::from("*BOUNDARY\n");
    for l in nastran.lines() {
        let f: Vec<&str> = l.split(',').collect();
        match f[0] {
            "GRID" => writeln!(s, "{}, {}, {}, {}", f[1], f[3], f[4], f[5]).unwrap(),
            "CQUAD4" => writeln!(elements, "{}, {}", f[1], f[3..7].join(", ")).unwrap(),
            "SPC1" => {
                for d in f[2].chars() {
                    writeln!(boundary, "{}, {d}, {d}", f[3]).unwrap();
                }
            }
            _ => {}
        }
    }
    format!("{s}{elements}{section}{boundary}*STEP\n*FREQUENCY\n{modes}\n*END STEP\n")
}

/// Abaqus `*SHELL SECTION, COMPOSITE` of `*ELASTIC, TYPE=LAMINA` plies equals the Nastran PCOMP
/// of MAT8 plies (the same constants) on the antisymmetric cross-ply and angle-ply plates, to
/// 1e-10; `*ORIENTATION` on the section (axis 1 along y) equals the plies turned by 90°.
#[test]
fn abaqus_composite_lamina_equals_nastran_pcomp() {
    let lamina = "*MATERIAL, NAME=PLY\n*ELASTIC, TYPE=LAMINA\n1e11, 1e10, 0.25, 6e9, 6e9, 5e9\n\
                  *DENSITY\n1600\n";
    let composite = |angles: &[f64], orientation: &str| {
        let mut s = format!("{lamina}*SHELL SECTION, ELSET=P, COMPOSITE{orientation}\n");
        for a in angles {
            writeln!(s, "{PLY_T}, 3, PLY, {a}").unwrap();
        }
        s
    };
    for (name, angles, support) in [
        ("abq-cross", [0.0, 0.0, 90.0, 90.0], Support::Tangential),
        ("abq-angle", [45.0, -45.0, 45.0, -45.0], Support::Normal),
    ] {
        let bdf = supported_plate(&pcomp(&angles), SIDE, 20, support, 6);
        let want = frequencies(name, &bdf);
        let inp = abaqus_plate(&bdf, &composite(&angles, ""), 6);
        let got = build(&format!("{name}-inp"), &inp, "inp")
            .unwrap()
            .modes
            .frequency_hz;
        // 1e-10 before issue 44: the Nastran deck's CQUAD4 now carries MacNeal's residual bending
        // flexibility, the Abaqus S4 is plain MITC4 (measured up to 0.49 % on the cross-ply, 1.17 % on
        // the angle-ply's mode 5)
        assert_same(&want, &got, 0, 1.5e-2, name);
        // turned 90° by the section's orientation = the plies at θ + 90°
        let turned: Vec<f64> = angles.iter().map(|a| a + 90.0).collect();
        let want = frequencies(
            &format!("{name}-turned"),
            &supported_plate(&pcomp(&turned), SIDE, 20, support, 6),
        );
        let orientation = "*ORIENTATION, NAME=TURN\n0, 1, 0, -1, 0, 0\n";
        let inp = abaqus_plate(
            &bdf,
            &format!("{orientation}{}", composite(&angles, ", ORIENTATION=TURN")),
            6,
        );
        let got = build(&format!("{name}-inp-turned"), &inp, "inp")
            .unwrap()
            .modes
            .frequency_hz;
        assert_same(&want, &got, 0, 1.5e-2, &format!("{name} turned"));
    }
}

/// What laminates do not have yet is an error naming element or property, and no file is
/// written: stress/strain shapes, a preload (its initial stress) and a laminate on the
/// quadratic shells (CQUAD8).
#[test]
fn laminate_stress_shapes_preload_and_quadratic_shells_are_refused() {
    let deck = plate(&pcomp(&[0.0, 90.0]));
    let dir = scratch("laminates-refused");
    let path = dir.join("plate.bdf");
    std::fs::write(&path, &deck).unwrap();
    let out = dir.join("plate.flexbody");
    let run = |path: &std::path::Path, extra: &[&str]| {
        let o = exe()
            .arg("build")
            .arg(path)
            .args([
                "--units", "si", "--method", "normal", "--modes", "3", "-q", "-o",
            ])
            .arg(&out)
            .args(extra)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2));
        assert!(!out.exists());
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let err = run(&path, &["--stress-modes"]);
    assert!(
        err.contains("element 1 (Quad4)") && err.contains("stress/strain shapes of laminate"),
        "{err}"
    );
    let err = run(&path, &["--gravity", "0,0,-9.81", "--preload", "GRAVITY"]);
    assert!(
        err.contains("property 1 is a laminate") && err.contains("preload"),
        "{err}"
    );
    // one CQUAD8 (mid-side grids added) on the laminate
    let quad8 = "GRID,901,,0.025,0.,0.\nGRID,902,,0.05,0.025,0.\nGRID,903,,0.025,0.05,0.\n\
                 GRID,904,,0.,0.025,0.\nGRID,905,,0.05,0.,0.\nGRID,906,,0.05,0.05,0.\n\
                 GRID,907,,0.,0.05,0.\nGRID,908,,0.,0.,0.\n\
                 CQUAD8,999,1,908,905,906,907,901,902\n,903,904\nENDDATA\n";
    let path8 = dir.join("quad8.bdf");
    std::fs::write(
        &path8,
        plate(&pcomp(&[0.0, 90.0])).replace("ENDDATA\n", quad8),
    )
    .unwrap();
    let err = run(&path8, &[]);
    assert!(
        err.contains("999") && err.contains("quadratic shells"),
        "{err}"
    );
}

/// Each CQUAD4 of a deck split into two CTRIA3 along its 1–3 diagonal (G1→G2 along an edge of
/// the quadrilateral in both: THETA = 0 means the same axis).
fn to_triangles(deck: &str) -> String {
    let mut out = String::new();
    let mut e = 0;
    for l in deck.lines() {
        if let Some(rest) = l.strip_prefix("CQUAD4,") {
            let f: Vec<&str> = rest.split(',').collect();
            e += 1;
            writeln!(out, "CTRIA3,{e},{},{},{},{}", f[1], f[2], f[3], f[4]).unwrap();
            e += 1;
            writeln!(out, "CTRIA3,{e},{},{},{},{}", f[1], f[4], f[5], f[2]).unwrap();
        } else {
            writeln!(out, "{l}").unwrap();
        }
    }
    out
}

/// The antisymmetric cross-ply and angle-ply plates of CTRIA3 (DKT/DKMT bending, CST
/// membrane, B coupling through both) at 20 × 20 cells: the lowest three modes within 1 % of
/// Navier with lumped and consistent mass (measured −0.19 … +0.34 %).
#[test]
fn laminated_triangles_match_navier() {
    for (name, angles, support) in [
        ("tri-cross", [0.0, 0.0, 90.0, 90.0], Support::Tangential),
        ("tri-angle", [45.0, -45.0, 45.0, -45.0], Support::Normal),
    ] {
        let deck = to_triangles(&supported_plate(&pcomp(&angles), SIDE, 20, support, 3));
        let want = navier_lowest(abd(&angles, PLY_T), 4.0 * PLY_T, SIDE, support, 3);
        for mass in ["lumped", "consistent"] {
            let f = build_with(&format!("{name}-{mass}"), &deck, "bdf", mass)
                .unwrap()
                .modes
                .frequency_hz;
            for (k, (w, mn)) in want.iter().enumerate() {
                let rel = f[k] / w - 1.0;
                eprintln!(
                    "{name} {mass} mode {mn:?}: {:.4} Hz, Navier {w:.4} Hz ({rel:+.2e})",
                    f[k]
                );
                assert!(rel.abs() < 0.01, "{name} {mass}: {} against {w}", f[k]);
            }
        }
    }
}

/// A symmetric laminate of two materials with NSM weighs area × (Σ ρ_k t_k + NSM) (I1 of the
/// file, lumped and consistent mass).
#[test]
fn laminate_mass_is_the_sum_of_its_plies() {
    let cards = format!(
        "{MAT8}{}PCOMP,1,,0.5\n,7,0.001,0.,,1,0.002,45.\n,7,0.001,90.\n",
        MAT1.replace("MAT1,7,", "MAT1,1,")
    );
    let want = 0.4 * 0.3 * (1600.0 * 0.002 + 2700.0 * 0.002 + 0.5);
    for mass in ["lumped", "consistent"] {
        let body = build_with(&format!("mass-{mass}"), &plate(&cards), "bdf", mass).unwrap();
        let m = body.invariants.i1[0];
        assert!((m / want - 1.0).abs() < 1e-12, "{mass}: {m} against {want}");
    }
}
