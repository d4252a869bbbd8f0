//! `flexbody inspect` run as a real binary on the golden fixtures.
use std::path::Path;
use std::process::Command;

fn golden(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/golden/v1.0")
        .join(name)
}

#[test]
fn inspect_prints_counts_units_mass_and_frequencies() {
    let out = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .args(["inspect"])
        .arg(golden("three_node_chain.flexbody"))
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("utf8");
    assert!(
        text.contains("3 nodes (2 interface), 1 faces, 0 lines, 3 modes"),
        "{text}"
    );
    assert!(
        text.contains("mass kg (= 1 SI), length m (= 1 SI)"),
        "{text}"
    );
    // Total mass 3 × 2 kg; mode 3 at √(3k/m)/2π = √1200/2π = 5.513289 Hz.
    assert!(text.contains("6.000000e0"), "{text}");
    assert!(
        text.contains("5.513289") && text.contains("Rigid"),
        "{text}"
    );
    assert!(text.contains("damping.bin"), "{text}");
}

#[test]
fn inspect_json_reports_mass_properties_from_invariants() {
    let out = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .args(["inspect", "--json"])
        .arg(golden("twenty_node_chain.flexbody"))
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    // Σ m_p = 20 × 0.0005 + 0.00005 × 5 × (0+1+2+3) = 0.0115 t.
    let m = v["mass"]["total_mass"].as_f64().expect("mass");
    assert!((m - 0.0115).abs() < 1e-15, "{m}");
    // Centre x = Σ m_p · 50p / Σ m_p, computed independently here.
    let mx: f64 = (0..20)
        .map(|p| (0.0005 + 0.00005 * (p % 4) as f64) * 50.0 * p as f64)
        .sum();
    let cx = v["mass"]["center_of_mass"][0].as_f64().expect("cx");
    assert!((cx - mx / 0.0115).abs() < 1e-9, "{cx} vs {}", mx / 0.0115);
    assert_eq!(v["counts"]["modes"], 8);
    assert_eq!(v["invariant_set"], "Partial");
    assert_eq!(v["units"]["length"]["name"], "mm");
    assert_eq!(v["modes"][0]["label"], "Rigid");
}

#[test]
fn inspect_on_a_broken_file_exits_2_with_the_reason() {
    let broken =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/broken/checksum_mismatch.flexbody");
    let out = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("inspect")
        .arg(&broken)
        .output()
        .expect("run");
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("flexbody: ")
            && err.contains("checksum_mismatch.flexbody")
            && err.contains("Checksum: ")
            && err.contains("modes.bin: SHA-256"),
        "{err}"
    );
}

/// SPEC §8: `check` and `export` name the error as `inspect` does (`Checksum: …`).
#[test]
fn check_and_export_name_the_read_error_by_its_spec_name() {
    let broken =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/broken/checksum_mismatch.flexbody");
    let dir = std::env::temp_dir().join(format!("flexbody-named-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let runs: [Vec<std::ffi::OsString>; 2] = [
        vec!["check".into(), broken.clone().into()],
        vec![
            "export".into(),
            broken.clone().into(),
            "--to".into(),
            "mbdyn".into(),
            "-o".into(),
            dir.join("x.fem").into(),
        ],
    ];
    for args in runs {
        let out = Command::new(env!("CARGO_BIN_EXE_flexbody"))
            .args(&args)
            .output()
            .expect("run");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("Checksum: ") && err.contains("modes.bin: SHA-256"),
            "{args:?}: {err}"
        );
    }
    assert!(!dir.join("x.fem").exists(), "no output from a broken file");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 31: the recipe's options read as options a user can type: `--units si`, not the
/// unit names `kg/m/s/N` that `--units` does not accept.
#[test]
fn inspect_shows_the_recipe_units_as_the_preset_name() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/golden/v1.2/three_node_chain_recipe.flexbody");
    let out = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("inspect")
        .arg(&file)
        .output()
        .expect("run");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("--units si") && !text.contains("kg/m/s/N"),
        "{text}"
    );
}

/// Issue 37 item 4: `check` holds a file to the one limit of SPEC §5 (1e-9), not 1e-8.
#[test]
fn check_uses_the_spec_orthonormality_limit() {
    let out = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("check")
        .arg(golden("three_node_chain.flexbody"))
        .output()
        .expect("run");
    let text = String::from_utf8_lossy(&out.stdout);
    let line = |name: &str| {
        text.lines()
            .find(|l| l.contains(name))
            .unwrap_or_else(|| panic!("no {name} in {text}"))
            .to_owned()
    };
    assert!(
        line("generalized mass = I").contains("(limit 1.0e-9)"),
        "{text}"
    );
    assert!(
        line("generalized stiffness = diag").contains("(limit 1.0e-9)"),
        "{text}"
    );
}
