//! ANSYS's archived solids SOLID45 and SOLID95 (issue 50), each through the CLI from an archive
//! written here against an independent reference, and what stays refused:
//!
//! - SOLID95 with KEYOPT(11)=0 (Irons' 14 points for K and M) and KEYOPT(11)=1 (2×2×2 for K and
//!   M, the Archived Elements Theory Reference §1.17) against the numpy implementation of
//!   `tests/data/ansys/solid186_full.py` on its skewed, curved mesh;
//! - SOLID95 written as ANSYS's wedge and tetrahedron patterns against ccx 2.20's C3D15 and C3D10
//!   on the same meshes (the rules of SOLID186's table, which SOLID95's repeats);
//! - SOLID45 with its extra shapes (KEYOPT(1)=0, the default) against SOLID185 KEYOPT(2)=3 on the
//!   same mesh (shown against ANSYS's own solution in `tests/ansys_solids.rs`), its collapsed
//!   wedges against SOLID185's (shown against ANSYS's element forces there); without them
//!   (KEYOPT(1)=1) against the same mesh as an Abaqus C3D8 deck;
//! - SOLID92, SOLID45 KEYOPT(2)=1, SOLID95 KEYOPT(3)=1 and the other refusals by line.

use std::path::Path;

use crate::ansys_support::writers::{block, eblock, material, nblock, root, Block, STEEL};
use crate::ansys_support::{
    assert_refused_at, build, ccx_deck_as_bricks, data, line_of, solid186_archive,
};
use crate::common::{assert_frequencies, ccx_frequencies, scratch};

/// The frequencies of a normal-modes build of `path` with `extra` arguments (it must succeed).
fn frequencies(path: &Path, modes: usize, extra: &[&str]) -> Vec<f64> {
    let o = build(path, "si", modes, extra);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let body = flexbody_reader::read(path.with_extension("flexbody")).unwrap();
    body.modes.frequency_hz
}

/// The numpy reference's frequencies under `key` (`tests/data/ansys/solid186_full.json`).
fn numpy_hz(key: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(data("solid186_full.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    (v[key].as_array().unwrap_or_else(|| panic!("{key}")).iter())
        .map(|f| f.as_f64().unwrap())
        .collect()
}

/// The largest relative difference of two frequency lists of one length.
fn spread(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    (a.iter().zip(b))
        .map(|(x, y)| (x - y).abs() / y.abs())
        .fold(0.0, f64::max)
}

/// SOLID95 on the skewed, curved 3 × 2 × 2 cantilever of `solid186_full.py`: KEYOPT(11)=0 (the
/// default, written by number and by name) equals the script's K and M on Irons' 14 points,
/// KEYOPT(11)=1 its K and M on 2 × 2 × 2 points. The 2 × 2 × 2 mass is 1.5e-2 away from the
/// 14-point one SOLID186 KEYOPT(2)=0 takes with the same stiffness: the rules are told apart.
#[test]
fn solid95_equals_the_numpy_reference_for_both_integration_rules() {
    let dir = scratch("ansys-solid95-rules");
    let archive = std::fs::read_to_string(data("solid186_full.cdb")).unwrap();
    let header = "ET,        1,186\nKEYOP,        1, 2,        1\n";
    assert!(archive.contains(header));
    let mut worst: f64 = 0.0;
    for (name, et, key) in [
        ("default", "ET,        1,95\n", "keyopt2_1_irons14"),
        (
            "named",
            "ET,1,SOLID95\nKEYOPT,1,11,0\n",
            "keyopt2_1_irons14",
        ),
        (
            "reduced",
            "ET,        1,95\nKEYOP,        1,11,        1\n",
            "solid95_keyopt11_1_gauss2",
        ),
    ] {
        let cdb = dir.join(format!("{name}.cdb"));
        std::fs::write(&cdb, archive.replace(header, et)).unwrap();
        let ours = frequencies(&cdb, 8, &[]);
        worst = worst.max(assert_frequencies(name, &ours, &numpy_hz(key), 0, 2e-11));
    }
    // the 2×2×2 mass against the 14-point one, same stiffness: measured 1.5e-2
    let apart = spread(
        &numpy_hz("solid95_keyopt11_1_gauss2"),
        &numpy_hz("keyopt2_0_gauss2"),
    );
    assert!(apart > 1e-2, "{apart:e}");
    // measured 2.0e-12
    println!("SOLID95 against numpy: {worst:.2e} (the two masses {apart:.2e} apart)");
    let _ = std::fs::remove_dir_all(&dir);
}

/// SOLID95 written as ANSYS's wedge (K = L = S, O = P = W, A = B) and tetrahedron
/// (K = L = S, M…P = U…X, A = B) equals ccx 2.20's C3D15 and C3D10 on the same meshes with
/// either KEYOPT(11): the Archived Elements Theory Reference's table forms the wedge on 3 × 3
/// points and the tetrahedron on 4, K and mass, whatever KEYOPT(11) says.
#[test]
fn solid95_degenerate_shapes_equal_ccx() {
    let mut worst: f64 = 0.0;
    for (folder, stem) in [
        ("ccx_prism15", "bar_4x2x2"),
        ("ccx_solid186_tet", "bar_tet10_distorted"),
    ] {
        let (nodes, bricks) = ccx_deck_as_bricks(folder, stem);
        let solid186 = solid186_archive(&nodes, &bricks, 0);
        let header = "ET,        1,186\nKEYOP,        1, 2,        0\n";
        assert!(solid186.contains(header));
        let dir = scratch(&format!("ansys-solid95-{stem}"));
        for keyopt11 in [0, 1] {
            let et = format!("ET,        1,95\nKEYOP,        1,11,        {keyopt11}\n");
            let cdb = dir.join(format!("{stem}_{keyopt11}.cdb"));
            std::fs::write(&cdb, solid186.replace(header, &et)).unwrap();
            let ours = frequencies(&cdb, 10, &[]);
            let what = format!("{stem} as SOLID95 KEYOPT(11)={keyopt11}");
            // ccx prints 7 significant digits
            let d = assert_frequencies(&what, &ours, &ccx_frequencies(folder, stem), 0, 2e-6);
            worst = worst.max(d);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    // measured 4.6e-7 (ccx's 7 printed digits)
    println!("SOLID95 wedges and tetrahedra against ccx: {worst:.2e}");
}

/// A cantilever of 8-node bricks, 0.4 × 0.1 × 0.1 steel in 4 × 2 × 2 cells, clamped at x = 0.
fn cantilever() -> Block {
    block([4, 2, 2], [0.4, 0.1, 0.1], false)
}

/// An archive of `records` (element type, nodes) on the block's nodes with the element types
/// `types`, steel, clamped at x = 0.
fn archive(m: &Block, types: &str, records: &[(usize, Vec<u64>)]) -> String {
    let nodes: Vec<(u64, [f64; 3], [f64; 3])> = (m.nodes.iter())
        .map(|(&id, &x)| (id, x, [0.0; 3]))
        .collect();
    let records: Vec<(usize, usize, Vec<u64>)> =
        (records.iter()).map(|(t, n)| (*t, 1, n.clone())).collect();
    let clamp: String = root(m).iter().map(|id| format!("D,{id},ALL,0\n")).collect();
    format!(
        "/PREP7\n{types}{}{}{}{clamp}FINISH\n",
        nblock(&nodes),
        eblock(&records),
        material(STEEL)
    )
}

/// The frequencies of `text` written as `name` in `dir`, 8 modes, consistent mass (an
/// archive's default; an Abaqus deck's is lumped).
fn built(dir: &Path, name: &str, text: &str) -> Vec<f64> {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    frequencies(&path, 8, &["--mass", "consistent"])
}

/// SOLID45's default (KEYOPT(1)=0: Wilson's incompatible modes with Taylor's correction, the
/// trilinear mass, 2×2×2 points) is SOLID185 KEYOPT(2)=3's element: the same cantilever as
/// both, and with every other cell split into two of ANSYS's collapsed wedges (K = L, O = P:
/// the brick as written on 2×2×2 points, SOLID185's wedge), has the same frequencies.
#[test]
fn solid45_default_equals_solid185_enhanced_strain_and_its_wedges() {
    let m = cantilever();
    let dir = scratch("ansys-solid45-default");
    let bricks: Vec<(usize, Vec<u64>)> = m.elements.iter().map(|e| (1, e.clone())).collect();
    let solid45 = built(&dir, "s45.cdb", &archive(&m, "ET,1,45\n", &bricks));
    let solid185 = archive(&m, "ET,1,185\nKEYOPT,1,2,3\n", &bricks);
    let reference = built(&dir, "s185.cdb", &solid185);
    // measured 0 (the same element): to 1e-12
    let d_bricks = assert_frequencies("SOLID45 bricks", &solid45, &reference, 0, 1e-12);
    // every other cell as two wedges I J K K M N O O, I K L L M O P P
    let mut mixed: Vec<(usize, Vec<u64>)> = Vec::new();
    for (k, e) in m.elements.iter().enumerate() {
        if k % 2 == 0 {
            mixed.push((1, e.clone()));
            continue;
        }
        for [a, b, c] in [[0, 1, 2], [0, 2, 3]] {
            let w = vec![
                e[a],
                e[b],
                e[c],
                e[c],
                e[a + 4],
                e[b + 4],
                e[c + 4],
                e[c + 4],
            ];
            mixed.push((2, w));
        }
    }
    let as45: Vec<(usize, Vec<u64>)> = mixed.iter().map(|(_, n)| (1, n.clone())).collect();
    let solid45 = built(&dir, "w45.cdb", &archive(&m, "ET,1,45\n", &as45));
    let types185 = "ET,1,185\nKEYOPT,1,2,3\nET,2,185\n";
    let reference = built(&dir, "w185.cdb", &archive(&m, types185, &mixed));
    let d_wedges = assert_frequencies("SOLID45 with wedges", &solid45, &reference, 0, 1e-12);
    println!("SOLID45 against SOLID185: bricks {d_bricks:.2e}, with wedges {d_wedges:.2e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// SOLID45 without its extra shapes (KEYOPT(1)=1) is the trilinear brick on 2×2×2 points, K and
/// mass: the same cantilever as an Abaqus C3D8 deck has the same frequencies, which the extra
/// shapes lower (measured: 0.15 on the first bending pair).
#[test]
fn solid45_without_extra_shapes_equals_c3d8() {
    let m = cantilever();
    let dir = scratch("ansys-solid45-plain");
    let bricks: Vec<(usize, Vec<u64>)> = m.elements.iter().map(|e| (1, e.clone())).collect();
    let plain = built(
        &dir,
        "plain.cdb",
        &archive(&m, "ET,1,45\nKEYOPT,1,1,1\n", &bricks),
    );
    let [e, nu, rho] = STEEL;
    let mut deck = String::from("*NODE\n");
    for (id, x) in &m.nodes {
        deck += &format!("{id}, {:?}, {:?}, {:?}\n", x[0], x[1], x[2]);
    }
    deck += "*ELEMENT, TYPE=C3D8, ELSET=EALL\n";
    for (k, el) in m.elements.iter().enumerate() {
        let ids: Vec<String> = el.iter().map(u64::to_string).collect();
        deck += &format!("{}, {}\n", k + 1, ids.join(", "));
    }
    deck += &format!(
        "*MATERIAL, NAME=STEEL\n*ELASTIC\n{e:?}, {nu:?}\n*DENSITY\n{rho:?}\n\
         *SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n*BOUNDARY\n"
    );
    for id in root(&m) {
        deck += &format!("{id}, 1, 3\n");
    }
    deck += "*STEP\n*FREQUENCY\n8\n*END STEP\n";
    let reference = built(&dir, "c3d8.inp", &deck);
    // measured: equal to the printed digits (the same trilinear brick)
    let d = assert_frequencies("SOLID45 KEYOPT(1)=1", &plain, &reference, 0, 1e-12);
    let default = built(&dir, "modes.cdb", &archive(&m, "ET,1,45\n", &bricks));
    let apart = spread(&default, &plain);
    assert!(apart > 1e-2, "the extra shapes change nothing: {apart:e}");
    println!("SOLID45 KEYOPT(1)=1 against C3D8: {d:.2e} (the extra shapes {apart:.2e} apart)");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Refused by line through the CLI (exit 2): SOLID45 KEYOPT(2)=1 (hourglass control), SOLID45
/// collapsed into a pyramid, SOLID45 KEYOPT(4)=1, SOLID95 KEYOPT(3)=1 (lumped), SOLID92 (its
/// Theory page not at hand); and SOLID45 KEYOPT(1)=1 beside bricks with incompatible modes.
#[test]
fn legacy_solid_options_are_refused_by_line() {
    let m = cantilever();
    let e = &m.elements[0];
    let pyramid = vec![e[0], e[1], e[2], e[3], e[4], e[4], e[4], e[4]];
    let types = "ET,1,45\nKEYOPT,1,2,1\nET,2,45\nET,3,45\nKEYOPT,3,4,1\nET,4,95\nKEYOPT,4,3,1\n\
                 ET,5,92\n";
    // a 20-node record and a 10-node one on the block's nodes (the refusal is by type)
    let ids: Vec<u64> = m.nodes.keys().copied().take(20).collect();
    let records = vec![
        (1, e.clone()),
        (2, pyramid),
        (3, e.clone()),
        (4, ids.clone()),
        (5, ids[..10].to_vec()),
    ];
    let s = archive(&m, types, &records);
    let first = line_of(&s, "(19i9)") + 1;
    let expected = [
        (first, "SOLID45 KEYOPT(2)=1 (uniform reduced integration"),
        (
            first + 1,
            "SOLID45 with repeated nodes other than ANSYS's wedge",
        ),
        (first + 2, "SOLID45 KEYOPT(4)=1"),
        (first + 3, "SOLID95 KEYOPT(3)=1 (lumped mass"),
        (first + 5, "SOLID92"),
    ];
    assert_refused_at(&s, "ansys-legacy-refusals", "si", &expected);
    // KEYOPT(1)=1 bricks beside KEYOPT(1)=0 ones: the incompatible modes are model-wide
    let records: Vec<(usize, Vec<u64>)> = (m.elements.iter().enumerate())
        .map(|(k, e)| (1 + k % 2, e.clone()))
        .collect();
    let s = archive(&m, "ET,1,45\nET,2,45\nKEYOPT,2,1,1\n", &records);
    let second = line_of(&s, "(19i9)") + 2;
    let expected = [(second, "SOLID45 KEYOPT(1)=1 (no extra shapes: 8 brick(s)")];
    assert_refused_at(&s, "ansys-legacy-mixed", "si", &expected);
}
