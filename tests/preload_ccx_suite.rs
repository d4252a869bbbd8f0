//! CalculiX's preloaded-modes test decks through the CLI (issue 35): beamf2, beampsensfreq
//! and beamft (`*STATIC`, then `*FREQUENCY` in a `*STEP, PERTURBATION`), against ccx 2.20's
//! results in `fixtures/ccx_suite/results.json` (`regenerate.py` there runs ccx).
//!
//! flexbody's preload is linear: K_T = K + K_G(σ₀) with σ₀ the linear static stress. ccx's
//! linear buckling (*BUCKLE, the same loads) solves K φ = −λ K_G φ with that K_G, so its
//! buckling factors are the independent reference of our K_G: equal to 4e-5 (beampsensfreq,
//! C3D8) and 1e-6 (beamf2, C3D20R). ccx's perturbation step adds the initial-displacement
//! (large-deformation) stiffness of the static state, which a linear preload does not have.
//! beampsensfreq pulls its 8 mm × 1 mm² beam axially with 1e5 N (linear strain 0.48, max
//! |u0| 4.52 mm): far outside a linear preload. Its stress-stiffened bending pair is ccx's to
//! 2.3e-3, the other modes differ by 1 % to 25 % (mode 3 +7.0e-2, mode 4 −2.5e-1, modes 5–6
//! −1.0e-2, mode 7 +7.2e-2, mode 10 −1.1e-1; measured 2026-11-27) — stated, not hidden; and beamf2's load is 0.99999 × its linear buckling load (ccx *BUCKLE
//! 0.9999908), so the linear preload buckles the part and the build is refused naming the
//! factor, where ccx's perturbation step still finds 705 Hz. beamft heats the part with zero
//! expansion: its modes are those of the material tables read at the heated state, ccx's to
//! its printed digits.
//!
//! The decks are CalculiX's (GPL) and are not in the repository: they are read from Debian's
//! `calculix-ccx-test` or the folder `FLEXBODY_CCX_TESTS` names; without them the tests print
//! SKIPPED.

use std::path::PathBuf;
use std::process::{Command, Output};

mod common;
use common::reference;

/// The deck `name` decompressed into a scratch folder, or `None` after a SKIPPED line.
fn deck(name: &str) -> Option<PathBuf> {
    let dir = std::env::var_os("FLEXBODY_CCX_TESTS")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/share/doc/calculix-ccx-test/examples/test"));
    let out_dir = std::env::temp_dir().join(format!("flexbody-ccx-suite-{}", std::process::id()));
    std::fs::create_dir_all(&out_dir).unwrap();
    let out = out_dir.join(format!("{name}.inp"));
    let plain = dir.join(format!("{name}.inp"));
    let gz = dir.join(format!("{name}.inp.gz"));
    if plain.exists() {
        std::fs::copy(&plain, &out).unwrap();
    } else if gz.exists() {
        let o = Command::new("gzip").arg("-dc").arg(&gz).output().unwrap();
        assert!(o.status.success());
        std::fs::write(&out, o.stdout).unwrap();
    } else {
        common::skipped(&format!(
            "preload_ccx_suite {name}: needs CalculiX's test deck {name}.inp(.gz) (Debian \
             calculix-ccx-test, or set FLEXBODY_CCX_TESTS to its folder; looked in {})",
            dir.display()
        ));
        return None;
    }
    Some(out)
}

/// ccx's results of `case` (`key`: perturbation_freq_hz or buckling_factor).
fn ccx(case: &str, key: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(reference("../ccx_suite/results.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    (v[case][key].as_array().unwrap().iter())
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn build(deck: &std::path::Path) -> Output {
    let out = deck.with_extension("flexbody");
    let _ = std::fs::remove_file(&out);
    common::build_as_ccx(deck, &["--modes", "10", "--json"], &out)
}

/// The number after `λ₁ = ` in `text`.
fn buckling_factor(text: &str) -> f64 {
    let at = text
        .find("λ₁ = ")
        .unwrap_or_else(|| panic!("no λ₁ in {text}"))
        + "λ₁ = ".len();
    let s: String = text[at..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    s.parse().unwrap()
}

/// beampsensfreq (C3D8 cantilever, 1e5 N tip load): preloaded, the buckling factor equals
/// ccx *BUCKLE's to 1e-4, the bending pair is ccx's perturbation pair to 3e-3 (the other
/// modes carry the initial-displacement stiffness ccx adds, module doc) where the unloaded
/// body is 7.5× off, and `check --model` rebuilds the same preload.
#[test]
fn beampsensfreq_is_preloaded_as_ccx() {
    let Some(deck) = deck("beampsensfreq") else {
        return;
    };
    let o = build(&deck);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let note = report["deck"].to_string();
    assert!(note.contains("preloaded: step 1 (*STATIC)"), "{note}");
    // a 4.5 mm stretch is no small displacement: the linear preload says so (modes 3–10 are
    // up to 25 % off ccx's nonlinear perturbation)
    let warnings = report["warnings"].to_string();
    assert!(
        warnings.contains("of the part's size: the linear preload"),
        "{warnings}"
    );
    let lambda = buckling_factor(&note);
    let want = ccx("beampsensfreq", "buckling_factor")[0];
    assert!(
        (lambda - want).abs() <= 1e-4 * want,
        "λ₁ {lambda} vs ccx {want}"
    );
    let body = flexbody_reader::read(deck.with_extension("flexbody")).unwrap();
    let want = ccx("beampsensfreq", "perturbation_freq_hz");
    for (i, (g, w)) in body
        .modes
        .frequency_hz
        .iter()
        .zip(&want)
        .enumerate()
        .take(2)
    {
        let rel = (g - w).abs() / w;
        assert!(rel <= 3e-3, "mode {i}: {g} Hz vs ccx {w} Hz (rel {rel:e})");
    }
    let recipe = body.recipe.as_ref().unwrap();
    let p = recipe
        .preload
        .as_ref()
        .expect("the recipe records the preload");
    assert_eq!(p.loads, vec!["STEP_1".to_string()]);
    assert_eq!(p.max_displacement_node, 100);
    let check = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("check")
        .arg(deck.with_extension("flexbody"))
        .arg("--model")
        .arg(&deck)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&check.stdout).to_string()
        + &String::from_utf8_lossy(&check.stderr);
    assert!(check.status.success(), "{text}");
    assert!(text.contains("preload as built"), "{text}");
}

/// beamf2 (C3D20R, compressed to 0.99999 × its linear buckling load): refused as buckled,
/// naming the buckling factor, which equals ccx *BUCKLE's 0.9999908 to 1e-6.
#[test]
fn beamf2_buckles_under_the_linear_preload_as_ccx_buckle_says() {
    let Some(deck) = deck("beamf2") else {
        return;
    };
    let o = build(&deck);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("buckles"), "{err}");
    let lambda = buckling_factor(&err);
    let want = ccx("beamf2", "buckling_factor")[0];
    assert!(
        (lambda - want).abs() <= 1e-6 * want,
        "λ₁ {lambda} vs ccx {want}"
    );
    assert!(lambda < 1.0);
    assert!(!deck.with_extension("flexbody").exists());
}

/// beamft: a static step of temperatures only (499.999° from 0°) with zero expansion, so no
/// thermal strain: the perturbation's modes differ from the unheated part only by the
/// temperature-dependent `*ELASTIC` (210000 at 0°, 30000 at 500°) and `*DENSITY`, read at
/// 499.999° as ccx interpolates them. Every one of the 10 modes equals ccx 2.20's to 1e-6
/// (acceptance: 1e-4); the notes name the table reading and that nothing preloads.
#[test]
fn beamft_modes_at_the_heated_state_equal_ccx() {
    let Some(deck) = deck("beamft") else {
        return;
    };
    let o = build(&deck);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    // --json: the report, notes included, is on stdout
    let report = String::from_utf8_lossy(&o.stdout);
    assert!(
        report.contains("*ELASTIC table read at the part's temperature 499.999")
            && report.contains("strains nothing"),
        "{report}"
    );
    let body = flexbody_reader::read(deck.with_extension("flexbody")).unwrap();
    let f = &body.modes.frequency_hz;
    let want = ccx("beamft", "perturbation_freq_hz");
    assert_eq!(f.len(), want.len());
    for (k, (a, b)) in f.iter().zip(&want).enumerate() {
        let e = (a - b).abs() / b;
        println!("mode {}: {a} vs ccx {b} ({e:.1e})", k + 1);
        assert!(e < 1e-6, "mode {}: {a} vs ccx {b}", k + 1);
    }
    assert!(body.recipe.as_ref().unwrap().preload.is_none());
}
