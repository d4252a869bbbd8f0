//! A Nastran deck's CQUAD4 as MSC Nastran forms it (issue 44 a): MacNeal's QUAD4 with the
//! residual bending flexibility in its transverse shear (`fe::elements::quad4_shell` module
//! doc), so that one element over a panel's height bends as the beam does; the same strip read
//! from an Abaqus deck keeps plain MITC4. And (issue 44 b) a Nastran deck's lumped 10-node
//! tetrahedra: the build's warning gives the first elastic frequency with the lumped and with
//! the consistent mass, checked against two independent builds.

use crate::common::{build_bdf_modes, exe, scratch};

const E: f64 = 7e10;
const NU: f64 = 0.3;
const WIDTH: f64 = 0.01;
const HEIGHT: f64 = 0.02;
const T: f64 = 0.001;
/// The CONM2's mass at the strip's top (kg).
const TIP_MASS: f64 = 1e-3;

/// The strip of issue 44 (10 × 20 × 1 mm, E = 7e10, ν = 0.3), `n` CQUAD4 along its height (one
/// across), bottom edge clamped, the top edge's translations held by an RBE2 to a CONM2 (mass
/// [`TIP_MASS`], I33 = 1e-6) at its centre, the shell rotations at the top free. The strip
/// itself is massless (MAT1 RHO blank) so that the tip mass alone vibrates; every node's
/// rotation about the height axis (component 5) is held, so the strip bends cylindrically as a
/// slice of a wide plate (no anticlastic curvature, whose restraint at the clamp and at the
/// RBE2 would otherwise make the "beam" ambiguous by up to 1/(1 − ν²)). The CONM2 node's
/// rotation about the edge (component 4), which neither the RBE2 nor anything else reaches, is
/// held.
fn strip_deck(n: usize) -> String {
    let mut s = String::from("SOL 103\nCEND\nMETHOD = 1\nSPC = 1\nBEGIN BULK\n");
    s += "EIGRL,1,,,2\n";
    let id = |i: usize, j: usize| 1 + i + 2 * j;
    for j in 0..=n {
        for i in 0..2 {
            let (x, y) = (i as f64 * WIDTH, j as f64 * HEIGHT / n as f64);
            s += &format!("GRID,{},,{x:e},{y:e},0.0\n", id(i, j));
        }
    }
    for j in 0..n {
        s += &format!(
            "CQUAD4,{},1,{},{},{},{}\n",
            j + 1,
            id(0, j),
            id(1, j),
            id(1, j + 1),
            id(0, j + 1)
        );
    }
    s += &format!("PSHELL,1,1,{T:e},1,,1\nMAT1,1,{E:e},,{NU}\n");
    s += &format!("SPC1,1,123456,{},{}\n", id(0, 0), id(1, 0));
    let all: Vec<String> = (1..=2 * (n + 1)).map(|k| k.to_string()).collect();
    s += &format!("SPC1,1,5,{},THRU,{}\n", all[0], all[all.len() - 1]);
    s += &format!(
        "GRID,1000,,{:e},{HEIGHT:e},0.0\nSPC1,1,4,1000\n",
        WIDTH / 2.0
    );
    s += &format!("RBE2,2000,1000,123,{},{}\n", id(0, n), id(1, n));
    s += &format!("CONM2,3000,1000,,{TIP_MASS:e}\n,,,,,,1.0E-6\nENDDATA\n");
    s
}

/// Timoshenko's cantilever with a tip mass: a tip force P deflects the massless strip by
/// δ = P L³/(3 D b) + P L/(κ G t b) — bending of the cylindrically bent plate strip, D = E t³ /
/// (12 (1 − ν²)), plus transverse shear with κ = 5/6 (PSHELL TS/T default, the Reissner–Mindlin
/// factor), G = E / (2 (1 + ν)) — so the tip mass M on the spring k = P/δ vibrates at
/// f = √(k/M) / 2π. With the figures above: D b = 0.0641026 N m², L³/(3 D b) = 4.16000e-5 m/N,
/// L/(κ G t b) = 8.9143e-8 m/N, k = 23 986 N/m, f = 779.4 Hz.
fn timoshenko_hz() -> f64 {
    let d = E * T.powi(3) / (12.0 * (1.0 - NU * NU));
    let g = E / (2.0 * (1.0 + NU));
    let flexibility = HEIGHT.powi(3) / (3.0 * d * WIDTH) + HEIGHT / (5.0 / 6.0 * g * T * WIDTH);
    (1.0 / (flexibility * TIP_MASS)).sqrt() / (2.0 * std::f64::consts::PI)
}

/// The out-of-plane bending mode: the lowest (the in-plane modes of the 10 mm deep strip and the
/// I33 rotation are far stiffer).
fn first_hz(n: usize) -> f64 {
    let (f, stderr) = build_bdf_modes(&format!("quad4-strip-{n}"), &strip_deck(n));
    assert!(!f.is_empty(), "{stderr}");
    f[0]
}

/// One, two and four CQUAD4 over the height: each within 1 % of Timoshenko (measured 779.49 Hz
/// at every count against 779.487 Hz, +0.000 %; MITC4 alone: 899.75, 804.99, 785.64 Hz). Plain
/// MITC4 (the Abaqus S4 below) is 15 % stiff with one element: a linear-rotation element with
/// constant shear along its length bends under a linearly varying moment with a quarter of the
/// cubic beam's tip flexibility missing (L³/12 of L³/3).
#[test]
fn nastran_cquad4_strip_bends_as_timoshenko_with_one_two_and_four_elements() {
    let want = timoshenko_hz();
    assert!((want - 779.487).abs() < 1e-3, "{want}");
    for n in [1, 2, 4] {
        let got = first_hz(n);
        let err = got / want - 1.0;
        eprintln!(
            "CQUAD4 ×{n}: {got:.2} Hz, Timoshenko {want:.2} Hz ({:+.3} %)",
            100.0 * err
        );
        // the acceptance is 1 %; the residual bending flexibility makes a tip-loaded strip
        // exact at any count, so the tolerance is the eigen solve's
        assert!(err.abs() < 1e-6, "{n} elements: {got} Hz vs {want} Hz");
    }
}

/// The same strip read from an Abaqus deck with `--inp-shells native` (S4 → MITC4, the tip
/// mass split over the two top nodes: by symmetry they move together) keeps plain MITC4: one
/// element is 15.4 % stiff in frequency, √(4/3) as the missing L³/12 predicts (measured
/// 899.75 Hz against 779.49 Hz).
#[test]
fn abaqus_s4_strip_keeps_plain_mitc4() {
    let n = 1;
    let id = |i: usize, j: usize| 1 + i + 2 * j;
    let mut s = String::from("*NODE\n");
    for j in 0..=n {
        for i in 0..2 {
            s += &format!(
                "{}, {:e}, {:e}, 0.0\n",
                id(i, j),
                i as f64 * WIDTH,
                j as f64 * HEIGHT
            );
        }
    }
    s += "*ELEMENT, TYPE=S4, ELSET=STRIP\n1, 1, 2, 4, 3\n";
    s += &format!(
        "*ELEMENT, TYPE=MASS, ELSET=TIP\n100, 3\n101, 4\n*MASS, ELSET=TIP\n{:e}\n",
        TIP_MASS / 2.0
    );
    s += &format!("*SHELL SECTION, ELSET=STRIP, MATERIAL=AL\n{T:e}\n*MATERIAL, NAME=AL\n");
    s += &format!("*ELASTIC\n{E:e}, {NU}\n*NSET, NSET=ALL\n1, 2, 3, 4\n");
    s += "*BOUNDARY\n1, 1, 6\n2, 1, 6\nALL, 5, 5\n";
    let dir = scratch("quad4-strip-s4");
    let path = dir.join("strip.inp");
    std::fs::write(&path, s).unwrap();
    let out = dir.join("strip.flexbody");
    let o = exe()
        .arg("build")
        .arg(&path)
        .args([
            "--inp-shells",
            "native",
            "--units",
            "si",
            "--method",
            "normal",
        ])
        .args(["--modes", "2", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let f = flexbody_reader::read(&out).unwrap().modes.frequency_hz[0];
    let mitc4 = timoshenko_hz() * (4.0f64 / 3.0).sqrt();
    // the shear term makes it a little less than √(4/3): measured 899.75 vs 900.07
    assert!((f / mitc4 - 1.0).abs() < 2e-3, "{f} vs {mitc4}");
}

/// Two CTETRA(10) sharing a face, free, steel, no PARAM,COUPMASS (Nastran's lumped mass).
fn two_tet10_deck() -> String {
    let corners = [
        [0.0, 0.0, 0.0],
        [0.01, 0.0, 0.0],
        [0.0, 0.01, 0.0],
        [0.0, 0.0, 0.01],
        [0.01, 0.01, 0.01],
    ];
    let tets = [[0, 1, 2, 3], [1, 2, 3, 4]];
    // CTETRA's midside order: 1-2, 2-3, 3-1, 1-4, 2-4, 3-4
    let edges = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)];
    let mut nodes: Vec<[f64; 3]> = corners.to_vec();
    let mut mids: Vec<((usize, usize), usize)> = Vec::new();
    let mut s = String::from("SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\nEIGRL,1,,,8\n");
    let mut elems = String::new();
    for (e, t) in tets.iter().enumerate() {
        let mut g: Vec<usize> = t.iter().map(|&c| c + 1).collect();
        for &(a, b) in &edges {
            let key = (t[a].min(t[b]), t[a].max(t[b]));
            let m = match mids.iter().find(|(k, _)| *k == key) {
                Some(&(_, m)) => m,
                None => {
                    let (p, q) = (nodes[key.0], nodes[key.1]);
                    nodes.push(std::array::from_fn(|i| 0.5 * (p[i] + q[i])));
                    mids.push((key, nodes.len()));
                    nodes.len()
                }
            };
            g.push(m);
        }
        let ids: Vec<String> = g.iter().map(|v| v.to_string()).collect();
        elems += &format!(
            "CTETRA,{},1,{}\n,{}\n",
            e + 1,
            ids[..6].join(","),
            ids[6..].join(",")
        );
    }
    for (k, p) in nodes.iter().enumerate() {
        s += &format!("GRID,{},,{:e},{:e},{:e}\n", k + 1, p[0], p[1], p[2]);
    }
    s + &elems + "PSOLID,1,1\nMAT1,1,2.1E11,,0.3,7850.\nENDDATA\n"
}

/// The first flexible frequency of a build of `deck` with `extra` options, and its stderr.
fn first_flexible(name: &str, deck: &str, extra: &[&str]) -> (f64, String) {
    let dir = scratch(name);
    let path = dir.join(format!("{name}.bdf"));
    std::fs::write(&path, deck).unwrap();
    let out = dir.join(format!("{name}.flexbody"));
    let o = exe()
        .arg("build")
        .arg(&path)
        .args(["--units", "si", "--method", "normal"])
        .args(extra)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{stderr}");
    let f = flexbody_reader::read(&out).unwrap().modes.frequency_hz;
    // six rigid modes first (free body), at rounding level
    (f.into_iter().find(|&f| f > 1.0).unwrap(), stderr)
}

/// The number in `text` just before `before`.
fn number_before(text: &str, before: &str) -> f64 {
    let at = text
        .find(before)
        .unwrap_or_else(|| panic!("{before:?} in {text}"));
    let word = text[..at].trim_end().rsplit(' ').next().unwrap();
    word.parse()
        .unwrap_or_else(|_| panic!("{word:?} in {text}"))
}

/// A Nastran deck lumping 10-node tetrahedra: the build warns with the first elastic frequency
/// of the mesh with the lumped and with the consistent mass, and both equal the builds with
/// `--mass lumped` and `--mass consistent` (measured 116 158.69 Hz lumped, 173 237.01 Hz
/// consistent, −32.95 %, to the 6 printed decimals); the consistent build has no warning.
#[test]
fn nastran_lumped_tet10_warns_with_lumped_and_consistent_first_frequencies() {
    let deck = two_tet10_deck();
    let (deck_default, stderr) = first_flexible("tet10-default", &deck, &["--modes", "8"]);
    let warning = stderr
        .lines()
        .find(|l| l.contains("first elastic frequency of this mesh"))
        .unwrap_or_else(|| panic!("no warning in {stderr}"));
    assert!(warning.contains("the 2 CTETRA"), "{warning}");
    assert!(warning.contains("--mass consistent"), "{warning}");
    let lumped_hz = number_before(warning, "Hz with this lumped mass");
    let consistent_hz = number_before(warning, "Hz with the consistent mass");
    let (lumped, _) = first_flexible("tet10-lumped", &deck, &["--modes", "8", "--mass", "lumped"]);
    let (consistent, stderr_c) = first_flexible(
        "tet10-consistent",
        &deck,
        &["--modes", "8", "--mass", "consistent"],
    );
    assert!(!stderr_c.contains("first elastic frequency"), "{stderr_c}");
    assert!(
        (deck_default / lumped - 1.0).abs() < 1e-9,
        "{deck_default} vs {lumped}"
    );
    assert!(
        (lumped_hz / lumped - 1.0).abs() < 1e-8,
        "{lumped_hz} vs {lumped}"
    );
    assert!(
        (consistent_hz / consistent - 1.0).abs() < 1e-8,
        "{consistent_hz} vs {consistent}"
    );
    assert!(consistent > 1.3 * lumped, "{consistent} vs {lumped}");
}
