//! Decks whose modes are asked on a preloaded state (issue 35): CalculiX/Abaqus `*STATIC` with
//! loads, then `*FREQUENCY` in a `*STEP, PERTURBATION`. A preload the tool does not honour is
//! an error naming file, line and keyword — never a build of the unloaded body; an NLGEOM base
//! step is refused naming NLGEOM (the preload is linear). A `*FREQUENCY` step without
//! PERTURBATION is the unloaded body's (as in CalculiX), whatever static step precedes it.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::reference;

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexbody-preload-deck-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The a_block mesh (C3D8 cantilever 0.5 × 0.05 × 0.05 m, sets FIXED and TIP) with `history`.
fn block_deck(name: &str, history: &str) -> PathBuf {
    let deck = format!(
        "*INCLUDE, INPUT={}\n*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL\n*BOUNDARY\nFIXED, 1, 3\n{history}",
        reference("a_block_hex8/mesh.inp").display()
    );
    let path = tmp(name);
    std::fs::write(&path, deck).unwrap();
    path
}

/// `flexbody build MODEL ARGS… --units si --method normal --mass consistent -o OUT`.
fn build(model: &Path, args: &[&str]) -> Output {
    let out = model.with_extension("flexbody");
    let _ = std::fs::remove_file(&out);
    crate::common::build_as_ccx(model, args, &out)
}

/// The build fails, writes nothing, and its message contains every piece of `want`.
fn assert_refused(deck: &Path, args: &[&str], want: &[&str]) {
    let o = build(deck, &[&["--modes", "4"], args].concat());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    for w in want {
        assert!(err.contains(w), "missing '{w}' in: {err}");
    }
    assert!(!deck.with_extension("flexbody").exists());
}

/// The base step is NLGEOM: refused naming `*STEP, NLGEOM` and its line (the history starts
/// at line 10).
#[test]
fn nlgeom_preload_step_is_refused_naming_nlgeom() {
    let deck = block_deck(
        "nlgeom.inp",
        "*STEP, NLGEOM\n*STATIC\n*CLOAD\nTIP, 1, 1000.\n*END STEP\n*STEP, PERTURBATION\n*FREQUENCY\n4\n*END STEP\n",
    );
    assert_refused(
        &deck,
        &[],
        &[
            "nlgeom.inp:10: *STEP, NLGEOM",
            "NLGEOM",
            "preload is linear",
        ],
    );
}

/// Loads in two steps before the perturbation step: refused naming the second one's keyword.
#[test]
fn preload_from_two_steps_is_refused() {
    let deck = block_deck(
        "two_steps.inp",
        "*STEP\n*STATIC\n*CLOAD\nTIP, 1, 1000.\n*END STEP\n*STEP\n*STATIC\n*DLOAD\nSOLID, GRAV, 9.81, 0., 0., -1.\n*END STEP\n*STEP, PERTURBATION\n*FREQUENCY\n4\n*END STEP\n",
    );
    assert_refused(&deck, &[], &["two_steps.inp:17: *DLOAD", "several steps"]);
}

/// Without PERTURBATION the frequency step is the unloaded body's, as in CalculiX: the build
/// equals the deck without the static step, mode for mode.
#[test]
fn frequency_step_without_perturbation_is_the_unloaded_body() {
    let loaded = block_deck(
        "no_perturbation.inp",
        "*STEP\n*STATIC\n*CLOAD\nTIP, 1, -1.e6\n*END STEP\n*STEP\n*FREQUENCY\n4\n*END STEP\n",
    );
    let plain = block_deck("plain.inp", "*STEP\n*FREQUENCY\n4\n*END STEP\n");
    let hz = |deck: &Path| {
        let o = build(deck, &["--modes", "4", "--json"]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let body = flexbody_reader::read(deck.with_extension("flexbody")).unwrap();
        body.modes.frequency_hz.clone()
    };
    assert_eq!(hz(&loaded), hz(&plain));
}

/// A `*STATIC` step with a tip tension before `*STEP, PERTURBATION` / `*FREQUENCY`: the
/// deck's preload is applied as ccx perturbs it (a note names the tangent K + K_G + K_L(u₀);
/// tension raises every bending frequency), and `--preload STEP_1` on the same loads without
/// PERTURBATION is the linear preload K + K_G: the same static state, without the
/// initial-displacement stiffness, so its modes differ (this 2 MN pull: 3.6e-3 on the bending
/// pair, 14 % on mode 4) and are stiffened too. (Both tangents are checked against ccx in `preload_ccx_suite.rs`.)
#[test]
fn perturbation_preload_and_the_preload_option() {
    let history = |perturbation: &str| {
        format!("*STEP\n*STATIC\n*CLOAD\nTIP, 1, 2.e6\n*END STEP\n*STEP{perturbation}\n*FREQUENCY\n4\n*END STEP\n")
    };
    let deck = block_deck("cload.inp", &history(", PERTURBATION"));
    let option = block_deck("cload_option.inp", &history(""));
    let plain = block_deck("cload_plain.inp", "*STEP\n*FREQUENCY\n4\n*END STEP\n");
    let hz = |deck: &Path, args: &[&str]| {
        let o = build(deck, &[&["--modes", "4", "--json"], args].concat());
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let body = flexbody_reader::read(deck.with_extension("flexbody")).unwrap();
        (body.modes.frequency_hz.clone(), r["deck"].to_string())
    };
    let (loaded, note) = hz(&deck, &[]);
    assert!(note.contains("preloaded: step 1 (*STATIC)"), "{note}");
    assert!(note.contains("K + K_G + K_L(u0)"), "{note}");
    let (by_option, note) = hz(&option, &["--preload", "STEP_1"]);
    assert!(note.contains("preloaded: --preload STEP_1"), "{note}");
    assert!(note.contains("those of K + K_G\""), "{note}");
    let (unloaded, _) = hz(&plain, &[]);
    for i in 0..4 {
        let rel = (loaded[i] - by_option[i]).abs() / loaded[i];
        println!(
            "mode {}: {} (K_L) vs {} ({rel:.1e})",
            i + 1,
            loaded[i],
            by_option[i]
        );
        assert!(rel > 1e-4, "{loaded:?} vs {by_option:?}");
        for f in [loaded[i], by_option[i]] {
            assert!(f > unloaded[i] * (1.0 + 1e-4), "{f} vs {unloaded:?}");
        }
    }
}

/// `--preload` of a name the scene does not have is an error listing the names it has.
#[test]
fn unknown_preload_name_is_refused() {
    let deck = block_deck(
        "unknown.inp",
        "*STEP\n*STATIC\n*CLOAD\nTIP, 1, 1000.\n*END STEP\n*STEP\n*FREQUENCY\n4\n*END STEP\n",
    );
    assert_refused(&deck, &["--preload", "NOPE"], &["--preload NOPE", "STEP_1"]);
}

/// A pressure in the static step (`*DLOAD … P2` on a tip face): CalculiX's perturbation step
/// adds the pressure's follower (load) stiffness, which is not formed here — refused naming the
/// keyword, the reason and the way to build it as a dead load (`--preload STEP_1`, which then
/// builds).
#[test]
fn pressure_preload_of_a_perturbation_step_is_refused() {
    // element 112's face S2 lies on the tip set TIP of the a_block mesh
    let deck = block_deck(
        "pressure.inp",
        "*STEP\n*STATIC\n*DLOAD\n112, P2, 1.e6\n*END STEP\n*STEP, PERTURBATION\n*FREQUENCY\n4\n*END STEP\n",
    );
    assert_refused(
        &deck,
        &[],
        &[
            "pressure.inp:12: *DLOAD",
            "pressure",
            "follower",
            "--preload STEP_1",
        ],
    );
    let o = build(&deck, &["--modes", "4", "--preload", "STEP_1"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
