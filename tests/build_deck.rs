//! Real decks mean what their own solver makes of them (issue 15), through the CLI on the decks
//! as shipped: the case control selects the SPC set (none means none) and the eigenvalue
//! request, PARAM,COUPMASS picks the mass, subcases that disagree need `--subcase`.
//!
//! References: the CalculiX runs beside each `sol103_*.bdf` (`case.json`: `free_free` and
//! `fixed` eigenvalues, consistent mass, the same mesh as `mesh.bdf`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use flexbody_reader as file;

use crate::common::{external_reference, reference};

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
    let text = std::fs::read_to_string(reference(&format!("{case}/case.json"))).unwrap();
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
        let deck = reference(&format!("{case}/sol103_free.bdf"));
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
        let deck = reference(&format!("{case}/sol103_fixed.bdf"));
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
    let deck = reference("a_block_hex8/sol103_fixed.bdf");
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
    let mesh = reference("a_block_hex8/mesh.bdf");
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

fn planar(deck: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/models/planar_beam")
        .join(deck)
}

fn flexible(body: &file::ReducedBody) -> Vec<f64> {
    body.modes
        .frequency_hz
        .iter()
        .zip(&body.modes.labels)
        .filter(|(_, l)| **l != file::ModeLabel::Rigid)
        .map(|(f, _)| *f)
        .collect()
}

/// The planar beam of Wang, Niu & Feng 2023 as a Nastran deck (PS = 345 on every grid, PBAR,
/// COUPMASS 1) with the paper's own case `--interface 1,9 --reference-conditions 1:12,9:2`:
/// plain CB, improved CB methods 1 and 2 build through the CLI; the held components drop out of
/// the plain interface ids with one note; methods 1 and 2 agree to 1e-8 and give the extended
/// beam of tests/reduce_paper.rs (88.62, 209.38, 606.18 Hz with consistent mass).
#[test]
fn planar_beam_deck_reduces_with_the_papers_interface_and_reference_conditions() {
    let deck = planar("planar_beam.bdf");
    let (o, cb) = build(&deck, &["--interface", "1,9"], "planar-cb.flexbody");
    let cb = cb.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
    let r = report(&o);
    let notes = r["deck"].to_string();
    assert!(
        notes.contains("interface node 1 (345), interface node 9 (345)"),
        "{notes}"
    );
    let c = r["constraints"].as_array().unwrap();
    assert_eq!(c.len(), 1, "{c:?}");
    assert_eq!(
        (
            c[0]["card"].as_str(),
            c[0]["cards"].as_u64(),
            c[0]["dofs"].as_u64()
        ),
        (Some("GRID PS=345"), Some(13), Some(39))
    );
    assert_eq!(cb.method.mass_kind, file::MassKind::Consistent);
    // The interface records hold the free components 1, 2, 6 only.
    for i in &cb.method.interface {
        assert_eq!(i.dofs, [true, true, false, false, false, true]);
    }
    // Free-free planar beam: 3 in-plane rigid modes, then the paper's 138.91 Hz (Table 2).
    assert_eq!(cb.method.counts.rigid, 3);
    assert!(
        (flexible(&cb)[0] - 138.91).abs() < 0.04,
        "{:?}",
        flexible(&cb)
    );

    let rc = ["--interface", "1,9", "--reference-conditions", "1:12,9:2"];
    let mut sets = Vec::new();
    for m in ["1", "2"] {
        let args = [&rc[..], &["--reference-method", m]].concat();
        let (o, body) = build(&deck, &args, &format!("planar-m{m}.flexbody"));
        let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
        sets.push(body.modes.frequency_hz.clone());
    }
    let top = sets[0].last().copied().unwrap();
    for (a, b) in sets[0].iter().zip(&sets[1]) {
        assert!((a - b).abs() <= 1e-8 * top, "methods 1 and 2: {a} vs {b}");
    }
    for (got, want) in sets[0].iter().zip([88.62, 209.38, 606.18]) {
        assert!((got - want).abs() < 0.005, "{:?}", &sets[0][..3]);
    }
}

/// A held component given explicitly is an error naming the GRID, its PS field and line; the
/// same for a reference condition.
#[test]
fn held_components_given_explicitly_are_errors() {
    let deck = planar("planar_beam.bdf");
    for (args, what) in [
        (
            vec!["--interface", "1:123,9"],
            "interface 1:123: component 3",
        ),
        (
            vec!["--interface", "1,9", "--reference-conditions", "1:14"],
            "reference-condition 1:14: component 4",
        ),
    ] {
        let (o, body) = build(&deck, &args, "held.flexbody");
        assert!(body.is_none());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(what)
                && err.contains("the PS field of GRID 1 (PS=345, ")
                && err.contains("beam.blk:8"),
            "{err}"
        );
    }
    let (o, _) = build(&deck, &["--interface", "1:7"], "bad.flexbody");
    assert!(String::from_utf8_lossy(&o.stderr).contains("NODE:DOFS"));
}

/// ASET1 and BSET1 decks are the interface when `--interface` is absent: files identical to
/// `--interface 1,9` and `--interface 1:126,9:126` on the deck without them; the report says so.
#[test]
fn aset1_and_bset1_decks_equal_the_equivalent_interface_option() {
    // identical bodies; only the recipe's record of the options as given differs
    let read = |p: &str| {
        let mut b = file::read(tmp(p)).unwrap();
        let nodes: Vec<Vec<u64>> = (b.recipe.take().unwrap().interfaces.iter())
            .map(|i| i.nodes.clone())
            .collect();
        (b, nodes)
    };
    let (o, _) = build(
        &planar("planar_beam.bdf"),
        &["--interface", "1,9"],
        "i.flexbody",
    );
    assert!(o.status.success());
    let (o, _) = build(
        &planar("planar_beam.bdf"),
        &["--interface", "1:126,9:126"],
        "i2.flexbody",
    );
    assert!(o.status.success());
    assert_eq!(read("i.flexbody"), read("i2.flexbody"));
    for (deck, card) in [
        ("planar_beam_aset1.bdf", "1 ASET1"),
        ("planar_beam_bset1.bdf", "1 BSET1"),
    ] {
        let (o, _) = build(&planar(deck), &[], "set.flexbody");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let notes = report(&o)["deck"].to_string();
        assert!(
            notes.contains(&format!("interface: the deck's {card}")),
            "{notes}"
        );
        assert!(read("set.flexbody") == read("i.flexbody"), "{deck}");
    }
}

/// `nastran/beam_modes` (9 CBAR on PBARL ROD + 1 CBEAM on PBEAML ROD, CONM2 tip, `SPC = 1`,
/// `METHOD = 1` → EIGRL ND = 10, lumped mass) through the CLI as shipped: the importer derives
/// Nastran's shear factor 0.9 for ROD, the build bends shear-flexibly as Nastran's elements do,
/// and all ten frequencies equal the f06's to 1e-6.
#[test]
fn nastran_beam_modes_deck_through_the_cli_equals_the_f06() {
    let test = "nastran_beam_modes_deck_through_the_cli_equals_the_f06";
    let Some(dir) = external_reference(test, "nastran/beam_modes") else {
        return;
    };
    let (o, body) = build(
        &dir.join("beam_modes.dat"),
        &["--method", "normal"],
        "beam_modes.flexbody",
    );
    let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
    let text = std::fs::read_to_string(dir.join("case.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let want: Vec<f64> = v["freq_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(want.len(), 10);
    assert_eq!(body.mode_count(), 10, "EIGRL ND = 10");
    assert_eq!(body.method.mass_kind, file::MassKind::Lumped);
    assert_hz(&body.modes.frequency_hz, &want, 1e-6, "beam_modes");
    let c = report(&o)["constraints"].clone();
    assert_eq!(c[0]["card"], "SPC", "{c}");
    assert_eq!(c[0]["dofs"], 6, "{c}");
}

/// An Abaqus/CalculiX deck of the a_block mesh with its boundary conditions in steps.
fn abaqus_steps_deck(name: &str, history: &str) -> PathBuf {
    let deck = format!(
        "*INCLUDE, INPUT={}\n*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL\n{history}",
        reference("a_block_hex8/mesh.inp").display()
    );
    let path = tmp(name);
    std::fs::write(&path, deck).unwrap();
    path
}

/// `*BOUNDARY` inside a `*STEP` belongs to that step: the `*FREQUENCY` step's conditions hold
/// the body (CalculiX's fixed frequencies to 2e-6 with consistent mass); a `*STATIC` step's are
/// ignored with a warning naming the step and line — removed by OP=NEW, or in a deck with no
/// frequency step at all (then the body is free-free); every keyword after the frequency step
/// is ignored, with one warning naming them.
#[test]
fn abaqus_step_boundaries_belong_to_their_step() {
    let want = ccx_hz("a_block_hex8", "fixed");
    let cases = [
        (
            "freq_then_static.inp",
            "*STEP\n*FREQUENCY\n6\n*BOUNDARY\nFIXED, 1, 3\n*END STEP\n*STEP, NAME=pull\n*STATIC\n*BOUNDARY\nTIP, 1, 1\n*END STEP\n",
            "the keywords after the first *FREQUENCY step are ignored (only that step and what precedes it define the body): 1 *BOUNDARY (",
        ),
        (
            "static_then_new.inp",
            "*STEP\n*STATIC\n*BOUNDARY\nTIP, 1, 3\n*END STEP\n*STEP\n*FREQUENCY\n6\n*BOUNDARY, OP=NEW\nFIXED, 1, 3\n*END STEP\n",
            "static_then_new.inp: line 11: *BOUNDARY of step 1 (*STATIC) (1 lines) ignored: the *FREQUENCY step 2 removes it with *BOUNDARY, OP=NEW",
        ),
    ];
    for (name, history, warning) in cases {
        let deck = abaqus_steps_deck(name, history);
        let (o, body) = build(
            &deck,
            &["--method", "normal", "--mass", "consistent"],
            "steps.flexbody",
        );
        let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
        let r = report(&o);
        assert!(
            r["warnings"].to_string().contains(warning),
            "{name}: {}",
            r["warnings"]
        );
        assert_eq!(body.mode_count(), 6, "{name}: *FREQUENCY asks for 6");
        let c = r["constraints"].as_array().unwrap();
        assert_eq!(c.len(), 1, "{c:?}");
        assert_eq!(c[0]["set"], "FIXED");
        assert_hz(&body.modes.frequency_hz, &want, 2e-6, name);
    }
    // A *STATIC step's propagated conditions hold a later *FREQUENCY step (Abaqus propagates
    // boundary conditions from step to step).
    let deck = abaqus_steps_deck(
        "static_then_freq.inp",
        "*STEP\n*STATIC\n*BOUNDARY\nFIXED, 1, 3\n*END STEP\n*STEP\n*FREQUENCY\n6\n*END STEP\n",
    );
    let (o, body) = build(
        &deck,
        &["--method", "normal", "--mass", "consistent"],
        "s.flexbody",
    );
    let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
    assert_hz(&body.modes.frequency_hz, &want, 2e-6, "propagated");
    // No *FREQUENCY step: the static step's support is ignored, the body is free-free.
    let deck = abaqus_steps_deck(
        "static_only.inp",
        "*STEP\n*STATIC\n*BOUNDARY\nFIXED, 1, 3\n*END STEP\n",
    );
    let (o, body) = build(
        &deck,
        &["--method", "normal", "--modes", "8"],
        "so.flexbody",
    );
    let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
    assert_eq!(body.method.counts.rigid, 6);
    let w = report(&o)["warnings"].to_string();
    assert!(
        w.contains("static_only.inp: line 11: *BOUNDARY of step 1 (*STATIC)")
            && w.contains("the deck has no *FREQUENCY step"),
        "{w}"
    );
}

/// An SPC set the case control does not select is not applied but stays available by name: the
/// paper's reference conditions written as SPC1 set 7 and given as `--reference-conditions
/// SPC_7` give the same file as `1:12,9:2`.
#[test]
fn unselected_spc_set_serves_as_reference_conditions_by_name() {
    let deck = format!(
        "SOL 103\nCEND\nTITLE = Wang, Niu & Feng 2023 planar beam\nMETHOD = 1\nBEGIN BULK\nPARAM,COUPMASS,1\nEIGRL,1,,,20\nSPC1,7,12,1\nSPC1,7,2,9\nINCLUDE '{}'\nENDDATA\n",
        planar("beam.blk").display()
    );
    let path = tmp("planar_spc7.bdf");
    std::fs::write(&path, deck).unwrap();
    let (o, _) = build(
        &path,
        &["--interface", "1,9", "--reference-conditions", "SPC_7"],
        "by_name.flexbody",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let notes = report(&o)["deck"].to_string();
    assert!(
        notes.contains("SPC sets SPC_7") && notes.contains("not applied"),
        "{notes}"
    );
    let (o, _) = build(
        &path,
        &["--interface", "1,9", "--reference-conditions", "1:12,9:2"],
        "by_digits.flexbody",
    );
    assert!(o.status.success());
    // identical bodies; only the recipe's record of the options as given differs
    let read = |p: &str| {
        let mut b = file::read(tmp(p)).unwrap();
        let nodes: Vec<Vec<u64>> = (b.recipe.take().unwrap().interfaces.iter())
            .map(|i| i.nodes.clone())
            .collect();
        (b, nodes)
    };
    assert!(read("by_name.flexbody") == read("by_digits.flexbody"));
    let (o, _) = build(
        &path,
        &["--interface", "1,9", "--reference-conditions", "SPC_9"],
        "x.flexbody",
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("SPC_9: neither NODE:DOFS") && err.contains("SPC_7"),
        "{err}"
    );
}

/// `INCLUDE` in the case control is followed: the selection inside the included file holds.
#[test]
fn case_control_include_is_followed() {
    std::fs::write(tmp("cases.inc"), "$ the support\nSPC = 1\n").unwrap();
    let deck = format!(
        "SOL 103\nCEND\nMETHOD = 1\nINCLUDE 'cases.inc'\nBEGIN BULK\nPARAM,COUPMASS,1\nEIGRL,1,,,4\nINCLUDE '{}'\nENDDATA\n",
        reference("a_block_hex8/mesh.bdf").display()
    );
    let path = tmp("cc_include.bdf");
    std::fs::write(&path, deck).unwrap();
    let (o, body) = build(&path, &["--method", "normal"], "cc_include.flexbody");
    let body = body.unwrap_or_else(|| panic!("{}", String::from_utf8_lossy(&o.stderr)));
    assert_eq!(report(&o)["constraints"][0]["set"], "SPC_1");
    assert_hz(
        &body.modes.frequency_hz,
        &ccx_hz("a_block_hex8", "fixed"),
        2e-6,
        "include",
    );
}

/// A Nastran deck's quadratic solids lumped (`--mass lumped` over the deck's COUPMASS 1): a
/// warning says they are lumped by HRZ and that MSC's rule differs, with the element count
/// (its figures: tests/nastran_quad4.rs); the deck's own consistent mass and linear solids get
/// no such warning.
#[test]
fn lumped_quadratic_nastran_solids_are_noted_as_hrz() {
    let note = |case: &str, args: &[&str]| -> Option<String> {
        let deck = reference(&format!("{case}/sol103_fixed.bdf"));
        let (o, body) = build(&deck, args, &format!("{case}-lumping.flexbody"));
        assert!(body.is_some(), "{}", String::from_utf8_lossy(&o.stderr));
        let r = report(&o);
        let notes = r["warnings"].as_array().expect("warnings").clone();
        notes
            .iter()
            .filter_map(|n| n.as_str())
            .find(|n| n.contains("HRZ"))
            .map(str::to_owned)
    };
    let lumped = ["--method", "normal", "--modes", "4", "--mass", "lumped"];
    let tet10 = note("b_block_tet10", &lumped).expect("a note for lumped CTETRA(10)");
    let model = flexbody::import::nastran::read(&reference("b_block_tet10/mesh.bdf")).unwrap();
    assert!(
        tet10.contains(&format!("the {} CTETRA", model.elements.len())),
        "{tet10}"
    );
    assert!(tet10.contains("MSC Nastran"), "{tet10}");
    assert_eq!(
        note("b_block_tet10", &["--method", "normal", "--modes", "4"]),
        None
    );
    assert_eq!(note("a_block_hex8", &lumped), None);
}
