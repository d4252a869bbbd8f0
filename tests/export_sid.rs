//! Issue 18, `flexbody export --to sid`: Wallrapp's Standard Input Data through the real binary.
//! `tests/python/sid_export_check.py` parses the `.SID_FEM` text from the standard's layout and
//! recomputes every Taylor term (mass, mdCM, J, Ct, Cr, Me, Gr, Ge, Oe and their first orders,
//! Ke, De, the frames) from the file's nodes, nodal masses and shapes to 1e-12; welib's
//! `generalizedMassMatrix` recomputes the zeroth-order terms of the beam (welib writes SID but has
//! no SID reader). With `FLEXBODY_EMBSLIB_INCLUDE` naming the folder of EMBSlib's
//! `ReadSID_C.h` (github.com/vwaurich/EMBS_ModelicaLib, `EMBSlib/Resources/Include`), EMBSlib's
//! own reader loads each file too and must hold the same numbers. Without python3 + numpy the
//! Python part is skipped with a visible message.
//!
//! Bodies: the conrod (CB, 6,963 nodes, frame attached at the big end by reference conditions,
//! so Ct and Cr are not zero; 2 % damping) and the planar beam (rotations and rotary inertia;
//! mean-axis normal modes and a CB body with reference conditions).

use crate::common::{exe, python_has, scratch};
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn run(args: &[&str]) -> String {
    let o = exe().args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "flexbody {args:?}: {stderr}");
    stderr
}

/// EMBSlib's reader compiled with our stand-in header, or None (with the reason printed).
fn embslib_dumper(dir: &Path) -> Option<PathBuf> {
    let Ok(include) = std::env::var("FLEXBODY_EMBSLIB_INCLUDE") else {
        crate::common::skipped(
            "the EMBSlib check of export_sid: set FLEXBODY_EMBSLIB_INCLUDE to the folder holding \
             EMBSlib's ReadSID_C.h to load the files with EMBSlib's own reader",
        );
        return None;
    };
    let exe = dir.join("sid_dump");
    let shim = root().join("tests/python/embslib");
    let o = Command::new("cc")
        .args(["-O1", "-w"])
        .arg(format!("-I{}", shim.display()))
        .arg(format!("-I{include}"))
        .arg("-o")
        .arg(&exe)
        .arg(shim.join("sid_dump.c"))
        .arg("-lm")
        .output()
        .expect("FLEXBODY_EMBSLIB_INCLUDE is set but cc cannot run");
    assert!(
        o.status.success(),
        "compiling EMBSlib's reader from {include} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    Some(exe)
}

/// Builds `model`, exports SID and runs the Python check (and EMBSlib's reader when asked).
fn check_sid(name: &str, model: &str, build_args: &[&str]) -> String {
    let dir = scratch(name);
    let body = dir.join("body.flexbody");
    let sid = dir.join("body.SID_FEM");
    let model = root().join(model);
    let mut args = vec!["build", model.to_str().unwrap()];
    args.extend_from_slice(build_args);
    args.extend_from_slice(&["--units", "si", "-q", "-o", body.to_str().unwrap()]);
    run(&args);
    let summary = run(&[
        "export",
        body.to_str().unwrap(),
        "--to",
        "sid",
        "-o",
        sid.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&sid).unwrap();
    assert!(text.ends_with(" end part\n"), "{name}: truncated SID file");
    if !python_has("numpy") {
        crate::common::skipped_install(
            &format!("the SID check of {name} (export_sid): python3 cannot import numpy"),
            "pip install numpy",
        );
        return summary;
    }
    let mut check = Command::new("python3");
    check
        .arg(root().join("tests/python/sid_export_check.py"))
        .arg(&sid)
        .arg(&body);
    if let Some(dumper) = embslib_dumper(&dir) {
        let o = Command::new(&dumper).arg(&sid).output().unwrap();
        assert!(o.status.success(), "EMBSlib's reader failed on {name}");
        let json = dir.join("embslib.json");
        std::fs::write(&json, &o.stdout).unwrap();
        check.arg(&json);
    }
    let o = check.output().unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    println!("{stdout}");
    assert!(
        o.status.success(),
        "{name}: SID check failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // the script's own skips (welib missing; a model too big for welib's dense mass matrix)
    for line in stdout
        .lines()
        .filter(|l| l.starts_with("welib check skipped:"))
    {
        if line.contains("cannot import welib") {
            crate::common::skipped_install(
                &format!("the welib check of {name} (export_sid): {line}"),
                "pip install welib==4.2.0",
            );
        } else {
            crate::common::skipped(&format!("the welib check of {name} (export_sid): {line}"));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    summary
}

#[test]
fn conrod_sid_terms_equal_the_sums_over_its_nodes() {
    let summary = check_sid(
        "conrod",
        "fixtures/models/conrod/conrod.inp",
        &[
            "--interface",
            "BIG_END,SMALL_END",
            "--fmax",
            "3000",
            "--damping",
            "2%",
            "--reference-conditions",
            "BIG_END:123456",
        ],
    );
    // Frames are the two interface nodes (spider centres); 8 flexible modes.
    assert!(
        summary.contains("8 flexible modes, 2 nodes"),
        "summary: {summary}"
    );
}

#[test]
fn beam_sid_carries_rotations_and_rotary_inertia() {
    // Mean-axis normal modes; no interface node, so every stored node is a frame (with a note).
    let summary = check_sid(
        "beam",
        "fixtures/models/planar_beam/planar_beam.bdf",
        &[
            "--method",
            "normal",
            "--modes",
            "6",
            "--mass",
            "lumped",
            "--beam-mass",
            "section",
        ],
    );
    assert!(
        summary.contains("all 13 stored nodes are written as SID frames"),
        "summary: {summary}"
    );
    // Frame attached at node 1: Ct and Cr (with the nodes' rotary inertia) are not zero.
    check_sid(
        "beam-rc",
        "fixtures/models/planar_beam/planar_beam.bdf",
        &[
            "--interface",
            "1,13",
            "--modes",
            "4",
            "--mass",
            "lumped",
            "--beam-mass",
            "section",
            "--reference-conditions",
            "1:123456",
        ],
    );
}

/// Format 1.7: a file with the modal geometric stiffness (`--geometric-stiffness inertia`, the
/// free beam: inertia relief) exports it as the first-order terms of `Ct`, `Cr` and `Oe`; the
/// Python check takes the node sums off and finds the file's K̂_G (read by the reference
/// reader), not zero for the ω products.
#[test]
fn beam_sid_carries_the_files_geometric_stiffness() {
    let out = check_sid(
        "beam-kg",
        "fixtures/models/planar_beam/planar_beam.bdf",
        &[
            "--method",
            "normal",
            "--modes",
            "6",
            "--mass",
            "lumped",
            "--beam-mass",
            "section",
            "--geometric-stiffness",
            "inertia",
        ],
    );
    assert!(out.contains("flexible modes"), "summary: {out}");
}

#[test]
fn sid_export_refuses_a_file_without_the_second_order_invariants() {
    let dir = scratch("sid-partial");
    let body = dir.join("rod.flexbody");
    crate::common::build_conrod(&body, &["--invariants", "partial"]);
    let out = dir.join("rod.SID_FEM");
    let o = exe()
        .args(["export", body.to_str().unwrap(), "--to", "sid", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "a partial-invariant file was exported");
    assert!(
        stderr.contains("lacks I5") && stderr.contains("--invariants full"),
        "{stderr}"
    );
    assert!(!out.exists(), "a refused export left a file");
    let _ = std::fs::remove_dir_all(&dir);
}
