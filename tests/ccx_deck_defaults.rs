//! What a CalculiX deck means where it is silent or uses ccx's own forms (issue 45): a
//! `*BEAM SECTION` without its direction line takes ccx's default 1-direction (0, 0, −1); a
//! `*DSLOAD` pressure on an element-face surface is read as the `*DLOAD` Pn lines of its faces
//! (ccx's `dloads.f` reads both alike), so in a `*STATIC` preload it is refused as a follower
//! load naming `*DSLOAD` and its line, and `--preload` builds it as a dead load.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::{build_as_ccx, reference, scratch};
use flexbody_reader as file;

/// A B31 frame (RECT 0.1 × 0.04, clamped at node 1): 10 elements along x from the origin to
/// (1, 0, 0), then 10 along y to (1, 1, 0) — or, if `vertical`, one leg along z — with
/// `direction` as the section's second data line ("" for none).
fn beam_deck(dir: &Path, name: &str, direction: &str, vertical: bool) -> PathBuf {
    let mut s = String::from("*NODE, NSET=NALL\n");
    let legs = if vertical { 1 } else { 2 };
    for i in 0..=10_usize * legs {
        let a = 0.1 * i.min(10) as f64;
        let b = 0.1 * i.saturating_sub(10) as f64;
        let (x, y, z) = if vertical { (0.0, 0.0, a) } else { (a, b, 0.0) };
        s += &format!("{}, {x:?}, {y:?}, {z:?}\n", i + 1);
    }
    s += "*ELEMENT, TYPE=B31, ELSET=EALL\n";
    for i in 1..=10 * legs {
        s += &format!("{i}, {i}, {}\n", i + 1);
    }
    s += "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7800.\n";
    s += "*BEAM SECTION, ELSET=EALL, MATERIAL=STEEL, SECTION=RECT\n0.1, 0.04\n";
    s += direction;
    s += "*BOUNDARY\n1, 1, 6\n*STEP\n*FREQUENCY\n6\n*END STEP\n";
    let path = dir.join(name);
    std::fs::write(&path, s).unwrap();
    path
}

fn modes(deck: &Path, extra: &[&str]) -> Result<Vec<f64>, String> {
    let out = deck.with_extension("flexbody");
    let o: Output = build_as_ccx(deck, extra, &out);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    if !o.status.success() {
        return Err(err);
    }
    Ok(file::read(&out).unwrap().modes.frequency_hz)
}

#[test]
fn a_beam_section_without_direction_takes_calculix_default() {
    let dir = scratch("ccx-beam-direction");
    let silent = modes(&beam_deck(&dir, "silent.inp", "", false), &[]).unwrap();
    let written = modes(
        &beam_deck(&dir, "written.inp", "0.0, 0.0, -1.0\n", false),
        &[],
    )
    .unwrap();
    let turned = modes(
        &beam_deck(&dir, "turned.inp", "0.0, 0.6, -0.8\n", false),
        &[],
    )
    .unwrap();
    for (a, b) in silent.iter().zip(&written) {
        assert!((a - b).abs() <= 1e-12 * b, "{silent:?} against {written:?}");
    }
    // the sections turned about their axes: another frame (a straight beam's spectrum would
    // not tell)
    assert!(silent
        .iter()
        .zip(&turned)
        .any(|(a, b)| (a - b).abs() > 1e-3 * b));
    // a beam along z: the default is its own axis, refused naming the section and its line
    let vertical = beam_deck(&dir, "vertical.inp", "", true);
    let err = modes(&vertical, &[]).unwrap_err();
    for want in [
        "vertical.inp:",
        "*BEAM SECTION ELSET=EALL",
        "(0, 0, -1)",
        "element 1",
    ] {
        assert!(err.contains(want), "missing '{want}' in {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The a_block mesh (C3D8 cantilever, sets FIXED and TIP) with an element-face surface on the
/// tip face S2 of element 112 and `history`.
fn block_deck(dir: &Path, name: &str, history: &str) -> PathBuf {
    let deck = format!(
        "*INCLUDE, INPUT={}\n*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL\n*BOUNDARY\nFIXED, 1, 3\n*ELSET, ELSET=TIPFACE\n112\n*SURFACE, NAME=TIPS, TYPE=ELEMENT\nTIPFACE, S2\n{history}",
        reference("a_block_hex8/mesh.inp").display()
    );
    let path = dir.join(name);
    std::fs::write(&path, deck).unwrap();
    path
}

#[test]
fn a_dsload_preload_is_the_dload_of_its_faces() {
    let dir = scratch("ccx-dsload");
    let tail = "*END STEP\n*STEP, PERTURBATION\n*FREQUENCY\n4\n*END STEP\n";
    let ds = block_deck(
        &dir,
        "dsload.inp",
        &format!("*STEP\n*STATIC\n*DSLOAD\nTIPS, P, 1.e6\n{tail}"),
    );
    // refused as a follower pressure, naming the keyword and its line (line 16 of the deck)
    let err = modes(&ds, &["--modes", "4"]).unwrap_err();
    for want in [
        "dsload.inp:16: *DSLOAD",
        "pressure",
        "follower",
        "--preload STEP_1",
    ] {
        assert!(err.contains(want), "missing '{want}' in: {err}");
    }
    // as a dead load, the same body as the *DLOAD of its face
    let dl = block_deck(
        &dir,
        "dload.inp",
        &format!("*STEP\n*STATIC\n*DLOAD\n112, P2, 1.e6\n{tail}"),
    );
    let a = modes(&ds, &["--modes", "4", "--preload", "STEP_1"]).unwrap();
    let b = modes(&dl, &["--modes", "4", "--preload", "STEP_1"]).unwrap();
    assert_eq!(a, b);
    let _ = std::fs::remove_dir_all(&dir);
}
