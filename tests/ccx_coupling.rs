//! CalculiX `*COUPLING` spiders (issue 45): a steel bar of 6 × 2 × 2 C3D20 with a reference
//! node beyond each end face, coupled to the face (`*SURFACE, TYPE=ELEMENT`) by `*KINEMATIC`
//! or `*DISTRIBUTING`, built by Craig–Bampton with the reference nodes as interfaces named by
//! the couplings' CONSTRAINT NAMEs. The fixed-interface modes (the build report's
//! `fixed_interface_hz`: the reference nodes held) against ccx 2.20 (`fixtures/ccx_coupling/results.json`, made by
//! `fixtures/ccx_frequencies.py`; ccx prints 7 significant digits):
//! * `*KINEMATIC`: ccx with the reference nodes clamped (`kinematic_clamped`);
//! * `*DISTRIBUTING`: ccx 2.20 adds no kinematic relation (clamping its reference nodes changes
//!   nothing: `distributing_clamped` equals the free bar), so the reference is the RBE3 with its
//!   reference node held written as ccx `*EQUATION`s with ccx's area weights computed in the
//!   deck writer (`distributing_held_equations`: Σ w u = 0, Σ w r × u = 0 per face).

use std::path::{Path, PathBuf};

use crate::common::{build_as_ccx, scratch};
use flexbody_reader as file;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/ccx_coupling")
        .join(name)
}

/// Builds `deck` (consistent mass, SI) with `extra` options; the body and stderr.
fn build(deck: &Path, extra: &[&str], out: &Path) -> (file::ReducedBody, String) {
    let o = build_as_ccx(deck, extra, out);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{}: {err}", deck.display());
    (file::read(out).unwrap(), err)
}

/// Largest relative difference of the first `n` frequencies.
fn worst(ours: &[f64], theirs: &[f64], n: usize) -> f64 {
    assert!(ours.len() >= n && theirs.len() >= n, "{ours:?} {theirs:?}");
    (ours.iter().zip(theirs).take(n))
        .map(|(a, b)| (a - b).abs() / b)
        .fold(0.0, f64::max)
}

/// The fixed-interface frequencies (the build report's `fixed_interface_hz`) of a
/// Craig–Bampton build with the couplings' reference nodes as interfaces, named by their
/// CONSTRAINT NAMEs `LEFT` and `RIGHT`.
fn fixed_interface(deck: &str, dir: &Path) -> Vec<f64> {
    let out = dir.join(format!("{deck}.flexbody"));
    let o = crate::common::exe()
        .arg("build")
        .arg(fixture(&format!("{deck}.inp")))
        .args(["--units", "si", "--mass", "consistent", "--method", "cb"])
        .args([
            "--modes",
            "12",
            "--interface",
            "LEFT,RIGHT",
            "--json",
            "-q",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let body = file::read(&out).unwrap();
    let iface: Vec<u64> = (body.nodes.iter())
        .filter(|n| n.interface)
        .map(|n| n.id)
        .collect();
    assert_eq!(iface, [9001, 9002], "the reference nodes are the interface");
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    (report["fixed_interface_hz"].as_array().unwrap().iter())
        .map(|f| f.as_f64().unwrap())
        .collect()
}

#[test]
fn kinematic_coupling_reference_nodes_clamped_match_calculix() {
    let dir = scratch("ccx-coupling-kinematic");
    let theirs = crate::common::ccx_frequencies("ccx_coupling", "kinematic_clamped");
    let ours = fixed_interface("kinematic", &dir);
    let w = worst(&ours, &theirs, 12);
    // measured 1.5e-7 (ccx prints 7 digits)
    assert!(w <= 2e-6, "{w:e}: {ours:?} against {theirs:?}");
    // the deck's own *BOUNDARY on the reference nodes, normal modes
    let out = dir.join("clamped.flexbody");
    let (body, _) = build(&fixture("kinematic_clamped.inp"), &[], &out);
    let w = worst(&body.modes.frequency_hz, &theirs, 10);
    assert!(w <= 2e-6, "{w:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn distributing_coupling_is_an_rbe3_with_calculix_area_weights() {
    let dir = scratch("ccx-coupling-distributing");
    let theirs = crate::common::ccx_frequencies("ccx_coupling", "distributing_held_equations");
    let ours = fixed_interface("distributing", &dir);
    let w = worst(&ours, &theirs, 12);
    // measured 3.4e-7
    assert!(w <= 2e-6, "{w:e}: {ours:?} against {theirs:?}");
    // free, the RBE3s add no stiffness: the free bar, as ccx's *DISTRIBUTING (6 rigid modes)
    let free = crate::common::ccx_frequencies("ccx_coupling", "distributing");
    assert_eq!(
        free,
        crate::common::ccx_frequencies("ccx_coupling", "distributing_clamped")
    );
    let out = dir.join("free.flexbody");
    let (body, _) = build(&fixture("distributing.inp"), &["--modes", "12"], &out);
    let w = worst(&body.modes.frequency_hz[6..], &free[6..], 6);
    // measured 2.0e-7
    assert!(w <= 2e-6, "{w:e}: {:?}", body.modes.frequency_hz);
    let _ = std::fs::remove_dir_all(&dir);
}
