//! ANSYS orthotropic materials (`MPDATA` EX, EY, EZ, PRXY…/NUXY…, GXY…) and element coordinate
//! systems (`EBLOCK` ESYS naming a `LOCAL`), issue 50, through the CLI:
//!
//! - SOLID186 (KEYOPT(2)=0), SOLID187 and SOLID185 (KEYOPT(2)=3) archives of a strongly
//!   orthotropic cantilever (E1/E2 = 15) against ccx 2.20's C3D20R, C3D10 and C3D8I with
//!   `*ELASTIC, TYPE=ENGINEERING CONSTANTS` and `*ORIENTATION` on the same meshes
//!   (`fixtures/ccx_ansys_ortho`), in the basic axes and in a three-angle `LOCAL`; a swapped
//!   Poisson's ratio form or a missing ESYS fails by far;
//! - closed form: a bar's axial frequency √(E/ρ)/(4L) takes EX along the bar when the bar lies
//!   along the ESYS's X, rotated or not;
//! - refusals by line: a partial orthotropic set naming the label, both Poisson forms, a D not
//!   positive definite, an orthotropic shell and B-bar brick, a cylindrical ESYS.

use std::collections::BTreeMap;
use std::path::Path;

use crate::ansys_support::{build, build_modes, read_inp, solid_blocks, tet_as_brick};
use crate::common::{assert_frequencies, ccx_frequencies, exe, scratch};

/// E1, E2, E3, ν12, ν13, ν23, G12, G13, G23, ρ of `fixtures/ccx_ansys_ortho/make_decks.py`
/// (ν_ij = −ε_j/ε_i under σ_i: ANSYS's major PRXY, PRXZ, PRYZ).
const MAT: [f64; 10] = [
    1.5e11, 1.0e10, 8.0e9, 0.3, 0.28, 0.45, 6.0e9, 5.0e9, 3.0e9, 1600.0,
];

/// The `LOCAL` angles of the fixture's `*ORIENTATION` (THXY, THYZ, THZX).
const ANGLES: [f64; 3] = [30.0, 20.0, 40.0];

/// How the archive gives the Poisson's ratios.
#[derive(Clone, Copy, PartialEq)]
enum Poisson {
    /// PRXY, PRYZ, PRXZ: the major ratios.
    Major,
    /// NUXY, NUYZ, NUXZ: the minor ratios ν_yx = ν_xy E_y/E_x, ….
    Minor,
    /// The major values written under the minor labels (a wrong archive, for the contrast).
    MajorAsMinor,
    /// The minor values written under the major labels (likewise).
    MinorAsMajor,
}

/// The orthotropic material 1 as `MPTEMP`/`MPDATA` lines.
fn material(poisson: Poisson) -> String {
    let [ex, ey, ez, nxy, nxz, nyz, gxy, gxz, gyz, rho] = MAT;
    let nus = match poisson {
        Poisson::Major => [("PRXY", nxy), ("PRYZ", nyz), ("PRXZ", nxz)],
        Poisson::Minor => [
            ("NUXY", nxy * ey / ex),
            ("NUYZ", nyz * ez / ey),
            ("NUXZ", nxz * ez / ex),
        ],
        Poisson::MajorAsMinor => [("NUXY", nxy), ("NUYZ", nyz), ("NUXZ", nxz)],
        Poisson::MinorAsMajor => [
            ("PRXY", nxy * ey / ex),
            ("PRYZ", nyz * ez / ey),
            ("PRXZ", nxz * ez / ex),
        ],
    };
    let mut s = String::from("MPTEMP,R5.0, 1, 1,  0.00000000    ,\n");
    let labels = [("EX", ex), ("EY", ey), ("EZ", ez)]
        .into_iter()
        .chain(nus)
        .chain([("GXY", gxy), ("GYZ", gyz), ("GXZ", gxz), ("DENS", rho)]);
    for (label, v) in labels {
        s += &format!("MPDATA,R5.0, 1,{label:<4},       1, 1, {v:e},\n");
    }
    s
}

/// Nodes and elements of one of the fixture's decks.
fn read_deck(stem: &str) -> (BTreeMap<u64, [f64; 3]>, Vec<Vec<u64>>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/ccx_ansys_ortho")
        .join(format!("{stem}.inp"));
    let (nodes, elements) = read_inp(&path);
    (nodes.into_iter().collect(), elements)
}

/// An archive of element type `et` (its ET/KEYOPT lines) on the nodes and elements, material 1
/// as `poisson` says, every element's ESYS `esys`, `systems` (LOCAL lines) before the blocks,
/// the nodes at x = 0 held.
fn archive(
    et: &str,
    nodes: &BTreeMap<u64, [f64; 3]>,
    elements: &[Vec<u64>],
    poisson: Poisson,
    esys: u64,
    systems: &str,
) -> String {
    let mut s = format!("/PREP7\n{et}{systems}");
    s += &solid_blocks(nodes.iter(), elements, esys);
    s += &material(poisson);
    for (id, p) in nodes {
        if p[0] == 0.0 {
            s += &format!("D,{id},ALL,0\n");
        }
    }
    s + "FINISH\n"
}

/// `LOCAL,11` with [`ANGLES`] as CDWRITE writes it (LOC, ANG, PRM lines).
fn local_as_cdwrite() -> String {
    let [a, b, c] = ANGLES;
    format!(
        "LOCAL,R5.0,LOC,       11,  0,  0.0    ,  0.0    ,  0.0    \n\
         LOCAL,R5.0,ANG,       11,  0,  {a:?}   ,  {b:?}   ,  {c:?}   \n\
         LOCAL,R5.0,PRM,       11,  0,  1.0    ,  1.0    \n\
         CSYS,0\n"
    )
}

/// `LOCAL,11,0,0,0,0,THXY,THYZ,THZX` as typed.
fn local_as_command() -> String {
    let [a, b, c] = ANGLES;
    format!("LOCAL,11,0,0.,0.,0.,{a:?},{b:?},{c:?}\nCSYS,0\n")
}

/// `flexbody build` of `text` (written as `NAME.cdb` under `dir`), normal modes, SI: exit
/// code, stderr and, on success, the file.
fn try_build(
    dir: &Path,
    name: &str,
    text: &str,
    modes: usize,
) -> (Option<i32>, String, Option<flexbody_reader::ReducedBody>) {
    let cdb = dir.join(format!("{name}.cdb"));
    std::fs::write(&cdb, text).unwrap();
    let o = build(&cdb, "si", modes, &[]);
    let body = o
        .status
        .success()
        .then(|| flexbody_reader::read(cdb.with_extension("flexbody")).unwrap());
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        body,
    )
}

/// The frequencies of a build that must succeed.
fn frequencies(dir: &Path, name: &str, text: &str, modes: usize) -> Vec<f64> {
    let (code, err, body) = try_build(dir, name, text, modes);
    assert_eq!(code, Some(0), "{name}: {err}");
    body.unwrap().modes.frequency_hz
}

/// The largest relative difference of two frequency lists.
fn difference(a: &[f64], b: &[f64]) -> f64 {
    (a.iter().zip(b))
        .map(|(x, y)| ((x - y) / y).abs())
        .fold(0.0, f64::max)
}

/// The tetrahedra of `tet10_local` as ANSYS writes a degenerate SOLID186 (I J K K M M M M,
/// Q R K T, M M M M, Y Z A A).
fn tets_as_bricks(elements: &[Vec<u64>]) -> Vec<Vec<u64>> {
    elements.iter().map(|n| tet_as_brick(n)).collect()
}

/// `flexbody build DECK --mass lumped` (the deck through flexbody's Abaqus importer): the
/// frequencies.
fn deck_frequencies(dir: &Path, stem: &str, extra: &[&str], modes: usize) -> Vec<f64> {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/ccx_ansys_ortho")
        .join(format!("{stem}.inp"));
    let out = dir.join(format!("{stem}-deck.flexbody"));
    let o = exe()
        .arg("build")
        .arg(&deck)
        .args(["--units", "si", "--method", "normal", "--modes"])
        .arg(modes.to_string())
        .args(extra)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    flexbody_reader::read(&out).unwrap().modes.frequency_hz
}

/// SOLID186 with an orthotropic material in the three-angle LOCAL 11 as CDWRITE writes it
/// (minor ratios), written as ANSYS's degenerate tetrahedra, equals ccx's C3D10 with the
/// engineering constants and the `*ORIENTATION` (SOLID186's tetrahedron is the 10-node
/// tetrahedron on 4 points, K and M, as ccx's); the major values under the minor labels and
/// the rotated material without its ESYS fail by far.
#[test]
fn solid186_orthotropic_tetrahedra_equal_ccx_c3d10() {
    let dir = scratch("ansys-ortho-186-tet");
    let (nodes, elements) = read_deck("tet10_local");
    let bricks = tets_as_bricks(&elements);
    let et = "ET,1,186\n";
    let reference = ccx_frequencies("ccx_ansys_ortho", "tet10_local");
    let local = archive(et, &nodes, &bricks, Poisson::Minor, 11, &local_as_cdwrite());
    let ours = frequencies(&dir, "local", &local, 10);
    let worst = assert_frequencies("SOLID186 tetrahedra LOCAL 11", &ours, &reference, 0, 2e-6);
    // measured 1.8e-7 (ccx's 7 printed digits)
    println!("SOLID186 tetrahedra, orthotropic in LOCAL 11, against ccx C3D10: {worst:.2e}");

    // the major values under the minor labels: ν12 = 0.3 · 15 = 4.5, refused
    let swapped = archive(
        et,
        &nodes,
        &bricks,
        Poisson::MajorAsMinor,
        11,
        &local_as_cdwrite(),
    );
    let (code, err, _) = try_build(&dir, "swapped", &swapped, 10);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains(
            "material 1: EY = 10000000000 differs from EX = 150000000000 \
                          (orthotropic): the elasticity matrix is not positive definite"
        ),
        "{err}"
    );
    let swapped = archive(
        et,
        &nodes,
        &bricks,
        Poisson::MinorAsMajor,
        11,
        &local_as_cdwrite(),
    );
    let off = difference(&frequencies(&dir, "swapped", &swapped, 10), &reference);
    let global_axes = archive(et, &nodes, &bricks, Poisson::Minor, 0, &local_as_cdwrite());
    let unrotated = difference(&frequencies(&dir, "no-esys", &global_axes, 10), &reference);
    println!("NUXY values read as PRXY: {off:.2e} off; without the ESYS: {unrotated:.2e} off");
    // measured 2.2e-2 and 2.3: thousands of times the tolerance
    assert!(off > 5e-3 && unrotated > 0.3, "{off} {unrotated}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// SOLID186 KEYOPT(2)=0 bricks, orthotropic in the basic axes (major ratios) and in LOCAL 11
/// (minor ratios): ANSYS's consistent mass is Irons' 14-point one, ccx's C3D20R mass the
/// 27-point one, so the archive equals the same deck through flexbody's Abaqus importer with
/// lumped mass on both (the same K: 2 × 2 × 2 points, D in the same axes), and that deck
/// equals ccx's C3D20R with consistent mass.
#[test]
fn solid186_orthotropic_bricks_equal_the_c3d20r_deck() {
    let dir = scratch("ansys-ortho-186-hex");
    let lumped = ["--mass", "lumped"];
    let mut worst_twin: f64 = 0.0;
    let mut worst_ccx: f64 = 0.0;
    for (stem, poisson, esys, systems) in [
        ("hex20r_global", Poisson::Major, 0, String::new()),
        ("hex20r_local", Poisson::Minor, 11, local_as_cdwrite()),
    ] {
        let (nodes, elements) = read_deck(stem);
        let text = archive("ET,1,186\n", &nodes, &elements, poisson, esys, &systems);
        let cdb = dir.join(format!("{stem}.cdb"));
        std::fs::write(&cdb, &text).unwrap();
        let ours = build_modes(&cdb, 10, &lumped);
        let twin = deck_frequencies(&dir, stem, &lumped, 10);
        worst_twin = worst_twin.max(assert_frequencies(stem, &ours, &twin, 0, 1e-10));
        let consistent = deck_frequencies(&dir, stem, &["--mass", "consistent"], 10);
        let reference = ccx_frequencies("ccx_ansys_ortho", stem);
        worst_ccx = worst_ccx.max(assert_frequencies(stem, &consistent, &reference, 0, 2e-6));
    }
    // measured 1.8e-11 (the two builds' eigensolves) and 4.0e-7 (ccx's 7 digits)
    println!("SOLID186 bricks against the C3D20R deck (lumped): {worst_twin:.2e}; the deck against ccx: {worst_ccx:.2e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// SOLID187 in LOCAL 11 (typed as a command) equals ccx's C3D10. SOLID185 KEYOPT(2)=3 in
/// LOCAL 11 equals the numpy incompatible-mode bricks of `wilson_hex8.py` (Wilson's modes,
/// ANSYS's simplified enhanced strain on rectangular bricks); ccx 2.20's C3D8I differs from
/// that textbook form with an anisotropic D (fixtures/ccx_ansys_ortho/README.md).
#[test]
fn solid187_and_solid185_orthotropic_equal_their_references() {
    let dir = scratch("ansys-ortho-187-185");
    let (nodes, elements) = read_deck("tet10_local");
    let text = archive(
        "ET,1,187\n",
        &nodes,
        &elements,
        Poisson::Major,
        11,
        &local_as_command(),
    );
    let ours = frequencies(&dir, "tet", &text, 10);
    let reference = ccx_frequencies("ccx_ansys_ortho", "tet10_local");
    let worst = assert_frequencies("SOLID187 LOCAL 11", &ours, &reference, 0, 2e-6);
    // measured 1.8e-7
    println!("SOLID187 orthotropic in LOCAL 11 against ccx C3D10: {worst:.2e}");

    let (nodes, elements) = read_deck("hex8i_local");
    let text = archive(
        "ET,1,185\nKEYOPT,1,2,3\n",
        &nodes,
        &elements,
        Poisson::Minor,
        11,
        &local_as_cdwrite(),
    );
    let ours = frequencies(&dir, "hex8", &text, 10);
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/ccx_ansys_ortho/wilson_hex8.json");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let reference: Vec<f64> = (v["hex8i_local"].as_array().unwrap().iter())
        .map(|f| f.as_f64().unwrap())
        .collect();
    let worst = assert_frequencies("SOLID185 KEYOPT(2)=3 LOCAL 11", &ours, &reference, 0, 1e-9);
    // measured 1.1e-10 (numpy's and our eigensolves)
    println!(
        "SOLID185 KEYOPT(2)=3 orthotropic in LOCAL 11 against numpy's Wilson bricks: {worst:.2e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The unit axes of LOCAL 11: rows X, Y, Z in global components (A = R_z R_x R_y, its
/// columns; written out here from the Command Reference's order).
fn local_axes() -> [[f64; 3]; 3] {
    let [a, b, c] = ANGLES.map(f64::to_radians);
    let rz = [
        [a.cos(), -a.sin(), 0.0],
        [a.sin(), a.cos(), 0.0],
        [0.0, 0.0, 1.0],
    ];
    let rx = [
        [1.0, 0.0, 0.0],
        [0.0, b.cos(), -b.sin()],
        [0.0, b.sin(), b.cos()],
    ];
    let ry = [
        [c.cos(), 0.0, c.sin()],
        [0.0, 1.0, 0.0],
        [-c.sin(), 0.0, c.cos()],
    ];
    let mul = |p: [[f64; 3]; 3], q: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| p[i][k] * q[k][j]).sum()))
    };
    let m = mul(mul(rz, rx), ry);
    std::array::from_fn(|i| std::array::from_fn(|j| m[j][i]))
}

/// The mode of `body` whose shape lies most along `d` (the share of Σ (u·d)² in Σ |u|²):
/// its frequency and that share.
fn axial_mode(body: &flexbody_reader::ReducedBody, d: [f64; 3]) -> (f64, f64) {
    let m = &body.modes;
    let n = m.shapes.len() / 6 / m.frequency_hz.len();
    (0..m.frequency_hz.len())
        .map(|j| {
            let (mut along, mut all) = (0.0, 0.0);
            for p in 0..n {
                let u = &m.shapes[(j * n + p) * 6..(j * n + p) * 6 + 3];
                along += (u[0] * d[0] + u[1] * d[1] + u[2] * d[2]).powi(2);
                all += u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
            }
            (m.frequency_hz[j], along / all)
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap()
}

/// A slender SOLID186 bar (1 × 0.04 × 0.04, clamped at one end) along global X, and the same
/// bar turned onto LOCAL 11's X with ESYS 11: its first axial frequency is √(EX/ρ)/(4L) in
/// both; turned without the ESYS it takes the modulus of the global X direction instead.
#[test]
fn axial_frequency_takes_ex_along_the_esys_x() {
    let dir = scratch("ansys-ortho-bar");
    let (l, a) = (1.0, 0.04);
    let [ex, .., rho] = MAT;
    let closed = (ex / rho).sqrt() / (4.0 * l);
    let (cells, mut nodes, mut elements) = (20usize, BTreeMap::new(), Vec::new());
    // 20 × 1 × 1 twenty-node bricks, SOLID186's node order
    let id = |i: usize, j: usize, k: usize| {
        (k * 3 * (2 * cells + 1) + j * (2 * cells + 1) + i + 1) as u64
    };
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..=2 * cells {
                if (i % 2) + (j % 2) + (k % 2) <= 1 {
                    let x = [
                        l * i as f64 / (2 * cells) as f64,
                        a * j as f64 / 2.0,
                        a * k as f64 / 2.0,
                    ];
                    nodes.insert(id(i, j, k), x);
                }
            }
        }
    }
    for c in 0..cells {
        let i0 = 2 * c;
        let q = [(0, 0), (2, 0), (2, 2), (0, 2)];
        let mut e: Vec<u64> = Vec::new();
        for k in [0, 2] {
            e.extend(q.map(|(di, dj)| id(i0 + di, dj, k)));
        }
        for k in [0, 2] {
            e.extend([(1, 0), (2, 1), (1, 2), (0, 1)].map(|(di, dj)| id(i0 + di, dj, k)));
        }
        e.extend(q.map(|(di, dj)| id(i0 + di, dj, 1)));
        elements.push(e);
    }
    let et = "ET,1,186\nKEYOPT,1,2,1\n";
    let straight = archive(et, &nodes, &elements, Poisson::Major, 0, "");
    let (_, err, body) = try_build(&dir, "straight", &straight, 16);
    let (f_straight, share) = axial_mode(&body.expect(&err), [1.0, 0.0, 0.0]);
    let off = (f_straight - closed) / closed;
    println!(
        "bar along X: axial {f_straight:.3} Hz (share {share:.3}) against {closed:.3}: {off:.2e}"
    );
    // measured +1.2e-4 (the clamped end's held Poisson contraction)
    assert!(share > 0.9 && off.abs() < 1e-3, "{off} {share}");

    // the same bar turned onto LOCAL 11's X (rows of the axes: x' = Σ xᵢ eᵢ); the held root
    // is still the nodes of the old x = 0
    let r = local_axes();
    let turned: BTreeMap<u64, [f64; 3]> = (nodes.iter())
        .map(|(&n, x)| {
            (
                n,
                std::array::from_fn(|j| (0..3).map(|i| x[i] * r[i][j]).sum()),
            )
        })
        .collect();
    let root: Vec<u64> = nodes
        .iter()
        .filter(|(_, x)| x[0] == 0.0)
        .map(|(&n, _)| n)
        .collect();
    let with_root = |text: String| -> String {
        let held: String = root.iter().map(|n| format!("D,{n},ALL,0\n")).collect();
        text.replace("FINISH\n", &format!("{held}FINISH\n"))
    };
    let in_local = with_root(archive(
        et,
        &turned,
        &elements,
        Poisson::Major,
        11,
        &local_as_command(),
    ));
    let (_, err, body) = try_build(&dir, "turned", &in_local, 16);
    let (f_turned, share) = axial_mode(&body.expect(&err), r[0]);
    let rotation = (f_turned - f_straight) / f_straight;
    println!("bar along LOCAL 11's X with ESYS 11: axial {f_turned:.3} Hz, {rotation:.2e} from the straight bar");
    // measured 4.4e-14: the same body turned
    assert!(share > 0.9 && rotation.abs() < 1e-12, "{rotation} {share}");

    let no_esys = with_root(archive(et, &turned, &elements, Poisson::Major, 0, ""));
    let (_, err, body) = try_build(&dir, "turned-global", &no_esys, 16);
    let (f_global, _) = axial_mode(&body.expect(&err), r[0]);
    let wrong = (f_global - closed) / closed;
    println!("the turned bar without its ESYS: axial {f_global:.3} Hz, {wrong:.2e} off");
    // measured −0.73: the bar's direction has a far softer modulus than EX
    assert!(wrong.abs() > 0.3, "{wrong}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Refused by line, naming what is wrong: a partial orthotropic set (the missing label), both
/// Poisson forms of one pair, a D not positive definite, an orthotropic SHELL181 and SOLID185
/// B-bar brick, an orthotropic solid in a cylindrical ESYS; an isotropic solid in that ESYS is
/// built, as the system changes nothing.
#[test]
fn incomplete_or_unformed_orthotropic_input_is_refused() {
    let dir = scratch("ansys-ortho-refused");
    let (nodes, elements) = read_deck("hex8i_local");
    let k3 = "ET,1,185\nKEYOPT,1,2,3\n";
    let base = archive(k3, &nodes, &elements, Poisson::Major, 0, "");
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "no GYZ",
            base.replace("MPDATA,R5.0, 1,GYZ ,       1, 1, 3e9,\n", ""),
            "material 1: EY = 10000000000 differs from EX = 150000000000 (orthotropic): GYZ is not given",
        ),
        (
            "both forms",
            base.replace("FINISH\n", "MP,NUXY,1,0.02\nFINISH\n"),
            "PRXY and NUXY are both given",
        ),
        (
            "indefinite",
            base.replace("1, 1, 4.5e-1,", "1, 1, 2.5e0,"),
            "not positive definite",
        ),
        (
            "B-bar",
            archive("ET,1,185\n", &nodes, &elements, Poisson::Major, 0, ""),
            "orthotropic material 1 on SOLID185 KEYOPT(2)=0",
        ),
        (
            "cylindrical",
            archive(k3, &nodes, &elements, Poisson::Major, 12, "LOCAL,12,1,0,0,0\nCSYS,0\n"),
            "element coordinate system 12 of KCS 1 (LOCAL at line 4)",
        ),
    ];
    for (what, text, want) in cases {
        assert!(text.contains("FINISH"), "{what}");
        let (code, err, _) = try_build(&dir, what, &text, 4);
        assert_eq!(code, Some(2), "{what}: {err}");
        assert!(err.contains(want), "{what}: {err}");
    }
    // an orthotropic SHELL181 (KEYOPT(3)=2) plate
    let mut shell = String::from(
        "/PREP7\nET,1,181\nKEYOPT,1,3,2\nSECTYPE,1,SHELL\nSECDATA,0.01,1\n\
         NBLOCK,6,SOLID,4,4\n(3i9,6e21.13e3)\n",
    );
    for (id, x) in [
        (1, [0.0, 0.0]),
        (2, [1.0, 0.0]),
        (3, [1.0, 1.0]),
        (4, [0.0, 1.0]),
    ] {
        shell += &format!(
            "{id:>9}{:>9}{:>9}{:>21.13E}{:>21.13E}{:>21.13E}\n",
            0, 0, x[0], x[1], 0.0
        );
    }
    shell += "N,R5.3,LOC,       -1,\n";
    let record: String = [1u64, 1, 1, 1, 0, 0, 0, 0, 4, 0, 1, 1, 2, 3, 4]
        .iter()
        .map(|v| format!("{v:>10}"))
        .collect();
    let text = format!(
        "{shell}EBLOCK,19,SOLID,1,1\n(19i10)\n{record}\n        -1\n{}D,1,ALL,0\nD,4,ALL,0\nFINISH\n",
        material(Poisson::Major)
    );
    let (code, err, _) = try_build(&dir, "shell", &text, 4);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("orthotropic material 1 on a shell"), "{err}");

    // isotropic in the cylindrical ESYS: built, equal to no ESYS
    let iso = |esys: u64| {
        archive(k3, &nodes, &elements, Poisson::Major, esys, "LOCAL,12,1,0,0,0\nCSYS,0\n")
            .replace(&material(Poisson::Major), "MPTEMP,R5.0, 1, 1,  0.00000000    ,\nMPDATA,R5.0, 1,EX  ,       1, 1, 2.1e11,\nMPDATA,R5.0, 1,PRXY,       1, 1, 0.3,\nMPDATA,R5.0, 1,DENS,       1, 1, 7850.0,\n")
    };
    let a = frequencies(&dir, "iso-esys", &iso(12), 4);
    let b = frequencies(&dir, "iso-global", &iso(0), 4);
    assert_eq!(a, b);
    let _ = std::fs::remove_dir_all(&dir);
}
