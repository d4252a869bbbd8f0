//! CalculiX shell faces, shell offsets and equations on shell rotations (issue 45), through the
//! CLI against ccx 2.20 (`fixtures/ccx_shell_surfaces/`: decks by `make_decks.py`, ccx's
//! frequencies in `results.json` by `fixtures/ccx_frequencies.py`):
//!
//! * S8R plates tied to C3D20 and C3D10 blocks by their shells' `SPOS`/`SNEG` faces, with and
//!   without `*SHELL SECTION, OFFSET`; a plate with `OFFSET` sharing nodes with a block;
//! * `*EQUATION` on rotations of expanded shell nodes, which ccx 2.20 applies to nothing;
//! * a `*COUPLING` on a plate's `SPOS` face, against the plate written out as ccx's C3D20R layer
//!   (ccx 2.20 itself resolves a coupling's shell faces before it expands the shells);
//! * `--inp-shells native`: the same decks with flexbody's shells.

use std::path::{Path, PathBuf};

use crate::common::{build_as_ccx, ccx_frequencies, scratch};
use flexbody_reader as file;

fn deck(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/ccx_shell_surfaces")
        .join(format!("{name}.inp"))
}

/// `deck` built as ccx solves it (`extra`: more options): its frequencies and stderr.
fn build(dir: &Path, deck: &Path, extra: &[&str]) -> (Vec<f64>, String) {
    let out = dir.join(format!(
        "{}{}.flexbody",
        deck.file_stem().unwrap().to_string_lossy(),
        extra.join("")
    ));
    let o = build_as_ccx(deck, extra, &out);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{}: {stderr}", deck.display());
    (file::read(&out).unwrap().modes.frequency_hz, stderr)
}

/// The largest relative difference of modes `from..` of `ours` to `reference`.
fn worst(ours: &[f64], reference: &[f64], from: usize) -> f64 {
    assert!(
        ours.len() >= reference.len(),
        "{ours:?} against {reference:?}"
    );
    (ours.iter().zip(reference).skip(from))
        .map(|(a, b)| (a - b).abs() / b)
        .fold(0.0, f64::max)
}

#[test]
fn plates_tied_by_their_spos_and_sneg_faces_equal_calculix() {
    let dir = scratch("ccx-shell-faces");
    // free: modes 7 … 14 (ccx's six rigid modes are round-off)
    for name in [
        "tie_spos_s8r",
        "tie_sneg_c3d10",
        "tie_spos_offset_s8r",
        "tie_spos_offset03_s8r",
    ] {
        let (ours, stderr) = build(&dir, &deck(name), &["--modes", "14"]);
        assert!(!stderr.contains("not tied"), "{name}: {stderr}");
        let ccx = ccx_frequencies("ccx_shell_surfaces", name);
        let w = worst(&ours, &ccx, 6);
        // measured 2.3e-7 (S8R on C3D20, also with OFFSET = −0.5 and 0.3) and 3.2e-7 (SNEG on
        // C3D10): ccx prints 7 digits
        assert!(w <= 1e-6, "{name}: {w:e}: {ours:?} against {ccx:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_offset_plate_sharing_nodes_with_a_block_equals_calculix() {
    let dir = scratch("ccx-shell-offset-shared");
    for name in ["shared_offset_s8r", "shared_s8r"] {
        let (ours, _) = build(&dir, &deck(name), &["--modes", "10"]);
        let ccx = ccx_frequencies("ccx_shell_surfaces", name);
        let w = worst(&ours, &ccx, 0);
        // measured 1.1e-7 for both: ccx's equations join a shell node to the mean of its
        // expanded nodes, so an OFFSET only moves the layer (the two decks agree in ccx too)
        assert!(w <= 1e-6, "{name}: {w:e}: {ours:?} against {ccx:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn equations_on_expanded_shell_rotations_are_left_out_as_calculix_leaves_them() {
    let dir = scratch("ccx-shell-equations");
    let none = ccx_frequencies("ccx_shell_surfaces", "equation_none_s8r");
    for name in ["equation_tie_s8r", "equation_hold_s8r"] {
        let ccx = ccx_frequencies("ccx_shell_surfaces", name);
        // ccx 2.20: the same frequencies with and without the equation
        assert_eq!(ccx, none, "{name}");
        let (ours, stderr) = build(&dir, &deck(name), &["--modes", "10"]);
        assert!(
            stderr.contains("*EQUATION on rotations of shell nodes (node 39) left out"),
            "{stderr}"
        );
        let w = worst(&ours, &ccx, 0);
        // measured 3.6e-7
        assert!(w <= 1e-6, "{name}: {w:e}");
    }
    // native shells have rotations: a one-term equation on θy of node 39 is that dof held
    let hold = deck("equation_hold_s8r");
    let (by_equation, _) = build(&dir, &hold, &["--modes", "10", "--inp-shells", "native"]);
    let text = std::fs::read_to_string(&hold).unwrap();
    let spc = dir.join("hold_by_boundary.inp");
    std::fs::write(
        &spc,
        text.replace("*EQUATION\n1\n39, 5, 1.0\n", "*BOUNDARY\n39, 5, 5\n"),
    )
    .unwrap();
    let (by_boundary, _) = build(&dir, &spc, &["--modes", "10", "--inp-shells", "native"]);
    let (free, _) = build(
        &dir,
        &deck("equation_none_s8r"),
        &["--modes", "10", "--inp-shells", "native"],
    );
    let w = worst(&by_equation, &by_boundary, 0);
    // measured 0 (the same constraint)
    assert!(w <= 1e-12, "{w:e}");
    // and it acts: the first (torsion-free bending) mode stiffens by 18 %
    assert!(by_equation[0] > 1.1 * free[0], "{by_equation:?} {free:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_kinematic_coupling_on_a_spos_face_equals_the_brick_layer_written_out() {
    let dir = scratch("ccx-shell-coupling");
    let by_hand = ccx_frequencies("ccx_shell_surfaces", "coupling_by_hand_c3d20r");
    for name in ["coupling_spos_s8r", "coupling_spos_offset_s8r"] {
        let (ours, _) = build(&dir, &deck(name), &["--modes", "10"]);
        let w = worst(&ours, &by_hand, 0);
        // measured 3.0e-7 (the OFFSET moves the layer rigidly with the held face)
        assert!(w <= 1e-6, "{name}: {w:e}: {ours:?} against {by_hand:?}");
        // ccx 2.20 on this deck: the faces read on the unexpanded shell, three rigid modes left
        let ccx = ccx_frequencies("ccx_shell_surfaces", name);
        assert!(ccx[2] < 1.0, "{ccx:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn native_shells_tied_by_their_faces_stay_near_calculix() {
    let dir = scratch("ccx-shell-faces-native");
    let native = ["--modes", "14", "--inp-shells", "native"];
    // the plate alone: flexbody's curved 8-node shell against ccx's C3D20R layer
    let (ours, _) = build(&dir, &deck("plate_s8r"), &native);
    let w = worst(
        &ours,
        &ccx_frequencies("ccx_shell_surfaces", "plate_s8r"),
        6,
    );
    // measured 6.3e-3
    assert!(w <= 1e-2, "plate: {w:e}");
    for name in ["tie_spos_s8r", "tie_sneg_c3d10"] {
        let (ours, stderr) = build(&dir, &deck(name), &native);
        assert!(!stderr.contains("not tied"), "{name}: {stderr}");
        let w = worst(&ours, &ccx_frequencies("ccx_shell_surfaces", name), 6);
        // measured 4.3e-2 and 4.5e-2 (lower: the shell's rotations carry the tie's lever arm,
        // the brick layer joins its faces by translations; the plate sharing nodes with a
        // block, shared_s8r, differs by up to 5.4e-2 the same way)
        assert!(w <= 6e-2, "{name}: {w:e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_native_offset_shell_is_its_mid_surface_moved_by_the_offset() {
    // OFFSET = −0.5 puts the plate's mid-surface t/2 above its nodes and its SPOS face t above
    // them, where the block stands (tie_spos_offset_s4); without OFFSET the same plate and block
    // lie t/2 lower (tie_spos_s4): the same body, free, so the same frequencies. Native shells
    // take OFFSET as Nastran's ZOFFS = −OFFSET·t (`model::shell_offset`) and the face's lever
    // (1/2 − OFFSET)·t·n (faces.rs): a sign wrong in either unties the block or bends it off.
    let dir = scratch("ccx-shell-offset-native");
    let native = ["--modes", "14", "--inp-shells", "native"];
    let (offset, stderr) = build(&dir, &deck("tie_spos_offset_s4"), &native);
    assert!(!stderr.contains("not tied"), "{stderr}");
    let (plain, _) = build(&dir, &deck("tie_spos_s4"), &native);
    let w = worst(&offset, &plain, 6);
    // measured 1.2e-13
    assert!(w <= 1e-12, "{w:e}: {offset:?} against {plain:?}");
    // a quadratic native shell has no ZOFFS: refused naming the section and its line
    let path = dir.join("quadratic_offset.inp");
    std::fs::copy(deck("tie_spos_offset_s8r"), &path).unwrap();
    let o = build_as_ccx(&path, &native, &dir.join("q.flexbody"));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        e.contains("quadratic_offset.inp:") && e.contains("*SHELL SECTION ELSET=PLATE: OFFSET"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_s4_plate_tied_by_its_spos_face_equals_calculix() {
    let dir = scratch("ccx-shell-faces-s4");
    for name in ["tie_spos_s4", "tie_spos_offset_s4"] {
        let (ours, _) = build(&dir, &deck(name), &["--modes", "14"]);
        let w = worst(&ours, &ccx_frequencies("ccx_shell_surfaces", name), 6);
        // measured 2.6e-7 for both (ccx's printed digits): the C3D8I's incompatible modes are
        // interior dofs of the eigenproblem, as ccx keeps them (8.2e-3 when they were condensed
        // statically)
        assert!(w <= 1e-6, "{name}: {w:e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn shell_faces_refused_name_the_surface_and_its_line() {
    let dir = scratch("ccx-shell-faces-refused");
    let text = std::fs::read_to_string(deck("tie_spos_s8r")).unwrap();
    let run = |name: &str, text: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let o = crate::common::exe()
            .args(["build"])
            .arg(&path)
            .args(["--units", "si", "--method", "normal", "-o"])
            .arg(dir.join("x.flexbody"))
            .output()
            .unwrap();
        assert!(!o.status.success());
        assert!(!dir.join("x.flexbody").exists());
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    // a shell's edge face
    let e = run("edge.inp", text.replace("PLATE, SPOS", "PLATE, S3"));
    assert!(
        e.contains("*TIE NAME=T1") && e.contains("has no face S3") && e.contains("edge.inp:"),
        "{e}"
    );
    // a tie on shell nodes themselves beside shell faces
    let nodes = text.replace(
        "*TIE, NAME=T1\nBLOCKBOT, PLATETOP\n",
        "*TIE, NAME=T1\nBLOCKBOT, PLATETOP\n*NSET, NSET=PLN, ELSET=PLATE\n\
         *SURFACE, NAME=PN, TYPE=NODE\nPLN\n\
         *TIE, NAME=T2, POSITION TOLERANCE=0.01\nPN, BLOCKBOT\n",
    );
    let e = run("nodes.inp", nodes);
    assert!(
        e.contains("*TIE NAME=T2") && e.contains("is a shell node itself"),
        "{e}"
    );
    // an equation mixing a shell rotation with a translation
    let mixed = std::fs::read_to_string(deck("equation_tie_s8r"))
        .unwrap()
        .replace("39, 4, 1.0, 119, 4, -1.0", "39, 4, 1.0, 119, 3, -1.0");
    let e = run("mixed.inp", mixed);
    assert!(
        e.contains("*EQUATION") && e.contains("rotation of shell node 39 beside other dofs"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
