//! Real decks mean what their own solver makes of them (issue 15), through the CLI on the decks
//! as shipped: the case control selects the SPC set (none means none) and the eigenvalue
//! request, PARAM,COUPMASS picks the mass, subcases that disagree need `--subcase`.
//!
//! References: the CalculiX runs beside each `sol103_*.bdf` (`case.json`: `free_free` and
//! `fixed` eigenvalues, consistent mass, the same mesh as `mesh.bdf`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use flexbody_reader as file;

fn shared(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/reference")
        .join(rel)
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexbody-deck-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// `flexbody build MODEL ARGS… --units si --json -o OUT`; returns the output and the file.
fn build(model: &Path, args: &[&str], out: &str) -> (Output, Option<file::ReducedBody>) {
    let out_path = tmp(out);
    let _ = std::fs::remove_file(&out_path);
    let output = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("build")
        .arg(model)
        .args(args)
        .args(["--units", "si", "--json", "-o"])
        .arg(&out_path)
        .output()
        .unwrap();
    let body = output
        .status
        .success()
        .then(|| file::read(&out_path).unwrap());
    (output, body)
}

fn report(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout).unwrap_or_else(|_| {
        panic!(
            "no JSON report; stderr: {}",
            String::from_utf8_lossy(&o.stderr)
        )
    })
}

/// CalculiX's frequencies from its eigenvalues (7 digits), f = √λ / 2π.
fn ccx_hz(case: &str, which: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(shared(&format!("{case}/case.json"))).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v[which]["eigenvalue_rad2_s2"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap().max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect()
}

fn assert_hz(got: &[f64], want: &[f64], rel: f64, what: &str) {
    assert!(!want.is_empty());
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= rel * w,
            "{what}: mode {i}: {g} vs CalculiX {w} (rel {:e})",
            (g - w).abs() / w
        );
    }
}

const CASES: [&str; 3] = ["a_block_hex8", "b_block_tet10", "d_plate_hex8"];

/// sol103_free.bdf has both SPC1 sets in its bulk data and no `SPC =`: Nastran applies none.
/// The build is free-free with 6 rigid modes, consistent mass (COUPMASS 1) and ND = 20 modes
/// from METHOD → EIGRL, all said in the report; the 14 flexible modes equal CalculiX's to 2e-6.
#[test]
fn sol103_free_decks_are_free_free_with_the_decks_mass_and_mode_count() {
    for case in CASES {
        let deck = shared(&format!("{case}/sol103_free.bdf"));
        let (o, body) = build(
            &deck,
            &["--method", "normal"],
            &format!("{case}-free.flexbody"),
        );
        let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
        let r = report(&o);
        assert_eq!(body.method.counts.rigid, 6, "{case}");
        assert_eq!(body.mode_count(), 20, "{case}: EIGRL ND = 20");
        assert_eq!(body.method.mass_kind, file::MassKind::Consistent, "{case}");
        assert!(body.method.reference_conditions.is_empty(), "{case}");
        let notes = r["deck"].to_string();
        assert!(
            notes.contains("COUPMASS") && notes.contains("EIGRL 1"),
            "{notes}"
        );
        assert!(
            notes.contains("SPC_1, SPC_2") && notes.contains("not applied"),
            "{notes}"
        );
        assert_eq!(r["constraints"].as_array().unwrap().len(), 0, "{case}");
        let want = ccx_hz(case, "free_free");
        assert_hz(&body.modes.frequency_hz[6..], &want[6..], 2e-6, case);
    }
}

/// sol103_fixed.bdf selects `SPC = 1` (the FIXED face) and only that set holds; set 2 (TIP) is
/// not applied. Frequencies equal CalculiX's fixed run to 2e-6; the report lists the one SPC1.
#[test]
fn sol103_fixed_decks_hold_only_the_selected_set() {
    for case in CASES {
        let deck = shared(&format!("{case}/sol103_fixed.bdf"));
        let (o, body) = build(
            &deck,
            &["--method", "normal"],
            &format!("{case}-fixed.flexbody"),
        );
        let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
        let r = report(&o);
        assert_eq!(body.method.counts.rigid, 0, "{case}");
        let c = r["constraints"].as_array().unwrap();
        assert_eq!(c.len(), 1, "{case}: {c:?}");
        assert_eq!(c[0]["card"], "SPC1");
        assert_eq!(c[0]["set"], "SPC_1");
        assert!(c[0]["line"].as_u64().unwrap() > 0);
        let fixed_nodes = c[0]["nodes"].as_u64().unwrap();
        assert_eq!(c[0]["dofs"].as_u64().unwrap(), 3 * fixed_nodes);
        assert_eq!(
            body.method.reference_conditions.len() as u64,
            fixed_nodes,
            "{case}"
        );
        let want = ccx_hz(case, "fixed");
        assert_hz(&body.modes.frequency_hz, &want, 2e-6, case);
    }
}

/// `--mass lumped` overrides the deck's COUPMASS, and the report says so.
#[test]
fn mass_option_overrides_coupmass() {
    let deck = shared("a_block_hex8/sol103_fixed.bdf");
    let (o, body) = build(
        &deck,
        &["--method", "normal", "--mass", "lumped", "--modes", "4"],
        "a-lumped.flexbody",
    );
    let body = body.unwrap();
    assert_eq!(body.method.mass_kind, file::MassKind::Lumped);
    assert_eq!(body.mode_count(), 4);
    let notes = report(&o)["deck"].to_string();
    assert!(
        notes.contains("as --mass asks") && notes.contains("COUPMASS"),
        "{notes}"
    );
    // Lumped mass on linear hexes lowers the frequencies (consistent mass bounds from above).
    let ccx = ccx_hz("a_block_hex8", "fixed");
    assert!(body.modes.frequency_hz[0] < ccx[0] * (1.0 - 1e-4));
}

fn two_subcase_deck(spcadd: bool) -> PathBuf {
    let mesh = shared("a_block_hex8/mesh.bdf");
    let (name, cases, extra) = if spcadd {
        ("spcadd.bdf", "SPC = 12\n", "SPCADD,12,1,2\n")
    } else {
        (
            "two_subcases.bdf",
            "SUBCASE 1\n  LABEL = clamped at x = 0\n  SPC = 1\nSUBCASE 2\n  SPC = 2\n",
            "",
        )
    };
    let deck = format!(
        "SOL 103\nCEND\nTITLE = block, two supports\nMETHOD = 7\n{cases}BEGIN BULK\nPARAM,COUPMASS,1\nEIGRL,7,,,6\n{extra}INCLUDE '{}'\nENDDATA\n",
        mesh.display()
    );
    let path = tmp(name);
    std::fs::write(&path, deck).unwrap();
    path
}

/// Two subcases selecting different SPC sets: an error naming both without `--subcase`; each
/// builds with it. The block is symmetric about x = L/2, so clamping the TIP face (set 2) gives
/// the same spectrum as clamping the FIXED face (set 1): CalculiX's `fixed` frequencies.
#[test]
fn two_subcases_need_a_choice_and_each_builds() {
    let deck = two_subcase_deck(false);
    let (o, body) = build(&deck, &["--method", "normal"], "two.flexbody");
    assert!(body.is_none());
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("two_subcases.bdf:8: SUBCASE 2")
            && err.contains("subcases 1 (SPC = 1, METHOD = 7) and 2 (SPC = 2, METHOD = 7)")
            && err.contains("--subcase"),
        "{err}"
    );
    let want = ccx_hz("a_block_hex8", "fixed");
    for (sub, set) in [("1", "SPC_1"), ("2", "SPC_2")] {
        let (o, body) = build(
            &deck,
            &["--method", "normal", "--subcase", sub],
            &format!("sub{sub}.flexbody"),
        );
        let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
        let r = report(&o);
        assert_eq!(body.mode_count(), 6, "EIGRL 7 ND = 6");
        assert_eq!(r["constraints"][0]["set"], set);
        assert!(r["deck"]
            .to_string()
            .contains(&format!("subcase {sub} used")));
        assert_eq!(body.header.title, "block, two supports");
        assert_hz(&body.modes.frequency_hz, &want, 2e-6, set);
    }
    let (o, _) = build(
        &deck,
        &["--subcase", "3", "--method", "normal"],
        "x.flexbody",
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("subcase 3 asked for") && err.contains("1, 2"),
        "{err}"
    );
}

/// `SPC = 12` selecting an SPCADD of sets 1 and 2 clamps both end faces; the report names both
/// SPC1 cards with their sets and the SPCADD.
#[test]
fn spcadd_selects_its_members() {
    let deck = two_subcase_deck(true);
    let (o, body) = build(&deck, &["--method", "normal"], "spcadd.flexbody");
    let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
    let r = report(&o);
    let c = r["constraints"].as_array().unwrap();
    assert_eq!(c.len(), 2, "{c:?}");
    assert_eq!(c[0]["id"], "set 1 (SPCADD 12)");
    assert_eq!(c[1]["id"], "set 2 (SPCADD 12)");
    assert_eq!(body.method.counts.rigid, 0);
    // Clamped at both ends: stiffer than the cantilever.
    let cantilever = ccx_hz("a_block_hex8", "fixed");
    assert!(body.modes.frequency_hz[0] > 3.0 * cantilever[0]);
    // A selected set the bulk data lacks is an error at the case-control line.
    let text = std::fs::read_to_string(&deck)
        .unwrap()
        .replace("SPC = 12", "SPC = 13");
    let bad = tmp("spc13.bdf");
    std::fs::write(&bad, text).unwrap();
    let (o, _) = build(&bad, &["--method", "normal"], "spc13.flexbody");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("spc13.bdf:5: SPC = 13") && err.contains("no SPC, SPC1 or SPCADD"),
        "{err}"
    );
}
