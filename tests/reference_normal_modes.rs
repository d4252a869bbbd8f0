//! `--method normal --reference-conditions`: the modes of the body with the reference node held
//! (Wang, Niu & Feng's reference conditions on normal modes). The build's own verification
//! leaves the held dofs out of the eigen residuals (there Kφ − ω²Mφ is the reaction force), so
//! the build succeeds and `check --model` passes; the frequencies equal SciPy's ARPACK on the
//! constrained K, M of `export --to mtx --model` with the held node's dofs removed
//! (`tests/python/held_normal_modes_check.py`; skipped visibly without SciPy).

use crate::common::{exe, scratch};
use std::path::Path;
use std::process::Command;

#[test]
fn normal_modes_with_the_big_end_held_build_check_and_match_scipy() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let model = root.join("fixtures/models/conrod/conrod.inp");
    let dir = scratch("held-normal");
    let body = dir.join("rod.flexbody");
    let o = exe()
        .arg("build")
        .arg(&model)
        .args([
            "--interface",
            "BIG_END,SMALL_END",
            "--method",
            "normal",
            "--modes",
            "10",
        ])
        .args([
            "--reference-conditions",
            "BIG_END:123456",
            "--units",
            "si",
            "-q",
            "-o",
        ])
        .arg(&body)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "build failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let c = exe()
        .arg("check")
        .arg(&body)
        .arg("--model")
        .arg(&model)
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&c.stdout);
    assert!(c.status.success(), "check --model failed:\n{report}");
    assert!(report.contains("eigen residuals"), "{report}");
    let file = flexbody_reader::read(&body).unwrap();
    assert!(
        !file
            .modes
            .labels
            .contains(&flexbody_reader::ModeLabel::Rigid),
        "a held body has no rigid modes"
    );
    // the file records the reference condition on the BIG_END spider centre, all six components
    let rc = &file.method.reference_conditions;
    assert_eq!(rc.len(), 1);
    assert_eq!(rc[0].dofs, [true; 6]);
    let held = file.nodes[rc[0].node as usize].id;
    let mats = dir.join("mats");
    let o = exe()
        .arg("export")
        .arg(&body)
        .args(["--to", "mtx", "--model"])
        .arg(&model)
        .arg("-o")
        .arg(&mats)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let has_scipy = Command::new("python3")
        .args(["-c", "import scipy"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !has_scipy {
        crate::common::skipped_install(
            "the SciPy comparison of reference_normal_modes: python3 cannot import scipy",
            "pip install scipy",
        );
        return;
    }
    let freqs: Vec<String> = file
        .modes
        .frequency_hz
        .iter()
        .map(|f| format!("{f:e}"))
        .collect();
    let o = Command::new("python3")
        .arg(root.join("tests/python/held_normal_modes_check.py"))
        .arg(&mats)
        .arg(held.to_string())
        .arg(freqs.join(","))
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    println!("{out}");
    assert!(
        o.status.success(),
        "{out}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
