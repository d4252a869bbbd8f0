//! Issue 32, "honoured or refused, never dropped": a Nastran card that can change stiffness,
//! mass, constraints or preload is either modelled or the import stops with one error listing
//! every such card with file:line; `ignore_cards` drops named cards on purpose (a warning with
//! their lines and counts); cards that cannot change the body are notes with their lines.

use crate::nastran_support::{build_refused, line_of, write};
use flexbody::import::{read_model, ImportError, ImportOptions};

/// A free CBAR line (steel, 1 m, 13 grids) the cases below add cards to.
fn base() -> String {
    let mut s = String::from(
        "SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\nEIGRL,1,,,4\nMAT1,1,2.1e11,,.3,7850.\n\
         PBAR,2,1,1.e-4,1.e-9,1.e-9,2.e-9\n",
    );
    for i in 0..13 {
        s += &format!("GRID,{},,{:?},0.,0.\n", i + 1, f64::from(i) / 12.0);
    }
    for i in 1..13 {
        s += &format!("CBAR,{i},2,{i},{},0.,1.,0.\n", i + 1);
    }
    s
}

/// Cards this importer does not model: a gap (refused with its own reason), a fastener and a
/// shell-normal PARAM. The last gap's free-field continuation starts with blanks before its
/// comma ("  ,1,2"), as MSC's own decks write them: it continues CGAP 51 (one refusal).
fn refused_deck() -> String {
    base()
        + "CGAP,50,60,3,4\nPARAM,SNORM,20.\nCFAST,70,2,1,2,3,4\nCGAP,51,60,5,6\n"
        + "  ,1,2\nENDDATA\n"
}

#[test]
fn unknown_stiffness_cards_are_refused_together_with_file_line_and_id() {
    let text = refused_deck();
    let path = write("rule_refused", "refused.bdf", &text);
    let e = read_model(&path, &ImportOptions::default()).unwrap_err();
    let ImportError::Refused { cards, .. } = &e else {
        panic!("not a refusal: {e}")
    };
    let got: Vec<(usize, &str, &str)> = cards
        .iter()
        .map(|c| (c.line, c.entity.as_str(), c.key.as_str()))
        .collect();
    assert_eq!(
        got,
        vec![
            (line_of(&text, "CGAP,50"), "CGAP 50", "CGAP"),
            (line_of(&text, "PARAM,SNORM"), "PARAM SNORM", "PARAM:SNORM"),
            (line_of(&text, "CFAST"), "CFAST 70", "CFAST"),
            (line_of(&text, "CGAP,51"), "CGAP 51", "CGAP"),
        ]
    );
    let msg = e.to_string();
    let file = path.display().to_string();
    for (line, entity, _) in &got {
        assert!(msg.contains(&format!("{file}:{line}: {entity}: ")), "{msg}");
    }
    assert!(msg.contains("CGAP 50: a gap is a contact element"), "{msg}");
    // the catalogue's reason for an element type it does not form
    assert!(
        msg.contains("CFAST 70: an element type this importer does not form"),
        "{msg}"
    );
    assert!(msg.contains("--ignore CFAST,CGAP,PARAM:SNORM "), "{msg}");
    assert_eq!(
        (e.file(), e.line()),
        (Some(file.as_str()), Some(line_of(&text, "CGAP,50")))
    );
}

#[test]
fn ignored_cards_are_dropped_with_a_warning_naming_lines_and_counts() {
    let text = refused_deck().replace("  ,1,2\n", "");
    let path = write("rule_ignored", "ignored.bdf", &text);
    let opts = ImportOptions {
        ignore_cards: vec![
            "cgap".into(),
            "param snorm".into(),
            "CFAST".into(),
            "CWELD".into(),
        ],
        ..Default::default()
    };
    let m = read_model(&path, &opts).unwrap();
    assert_eq!(
        m.elements.len(),
        12,
        "the CBARs are kept, the CFAST dropped"
    );
    let w: Vec<&str> = m.warnings.iter().map(|w| w.message.as_str()).collect();
    let file = path.display().to_string();
    let want = format!(
        "2 CGAP ({file}:{}, {})",
        line_of(&text, "CGAP,50"),
        line_of(&text, "CGAP,51")
    );
    assert!(
        w.iter().any(|m| m.starts_with("cards dropped on request")
            && m.contains(&want)
            && m.contains(&format!(
                "1 PARAM:SNORM ({file}:{})",
                line_of(&text, "PARAM")
            ))
            && m.contains("1 CFAST (")),
        "{w:?}"
    );
    assert!(
        w.contains(&"--ignore CWELD: the deck has no such card"),
        "{w:?}"
    );
}

/// Each is named with its line in a note: the catalogue's note of its category, or the
/// reader's own note (PDAMP).
#[test]
fn cards_that_cannot_change_the_body_are_notes_with_their_lines() {
    let text = base()
        + "CDAMP1,80,81,1,1\nPDAMP,81,10.\nTABLED1,5\n,0.,1.,1.,1.,ENDT\nPARAM,POST,-1\n\
           EIGC,9,CLAN\nENDDATA\n";
    let path = write("rule_notes", "notes.bdf", &text);
    let m = read_model(&path, &ImportOptions::default()).unwrap();
    let file = path.display().to_string();
    let has = |head: String, why: &str| {
        assert!(
            m.deck
                .notes
                .iter()
                .any(|n| n.contains(&head) && n.contains(why)),
            "{head}: {:?}",
            m.deck.notes
        )
    };
    has(
        format!("1 CDAMP1 ({file}:{})", line_of(&text, "CDAMP1")),
        "damping: a real normal-modes analysis has none",
    );
    has(
        format!("1 PDAMP ({file}:{})", line_of(&text, "PDAMP")),
        "damping",
    );
    has(
        format!("1 TABLED1 ({file}:{})", line_of(&text, "TABLED1")),
        "response analyses",
    );
    has(
        format!("1 PARAM:POST ({file}:{})", line_of(&text, "PARAM")),
        "output",
    );
    has(
        format!("1 EIGC ({file}:{})", line_of(&text, "EIGC")),
        "another analysis",
    );
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

/// A static load card the scene does not read keeps its set by name, unusable, with a warning
/// naming the card and its line (it does not change the body).
#[test]
fn an_unread_load_card_marks_its_load_set_unusable() {
    let text = base() + "FORCE,7,13,,1.,0.,0.,1.\nPLOAD1,7,3,FZ,FR,0.,1.,1.,1.\nENDDATA\n";
    let path = write("rule_loads", "loads.bdf", &text);
    let m = read_model(&path, &ImportOptions::default()).unwrap();
    let load = m.loads.iter().find(|l| l.name == "LOAD_7").unwrap();
    let problem = load.problem.as_deref().unwrap();
    assert!(
        problem.contains(&format!("loads.bdf:{}", line_of(&text, "PLOAD1")))
            && problem.contains("PLOAD1 is not read"),
        "{problem}"
    );
}

/// Through the CLI: the refusal exits 2 and names every card with file:line; the same deck
/// builds when the library drops the cards on purpose (`ImportOptions::ignore_cards`).
#[test]
fn cli_refuses_a_deck_with_an_unknown_stiffness_card_and_the_library_builds_it_ignored() {
    let text = base() + "CWELD,90,91,1,2\nENDDATA\n";
    let path = write("rule_cli", "weld.bdf", &text);
    let err = build_refused(&path);
    assert!(
        err.contains(&format!(
            "{}:{}: CWELD 90: an element type this importer does not form",
            path.display(),
            line_of(&text, "CWELD")
        )),
        "{err}"
    );
    let opts = ImportOptions {
        ignore_cards: vec!["CWELD".into()],
        ..Default::default()
    };
    let model = read_model(&path, &opts).unwrap();
    let spec = flexbody::build::BuildSpec {
        method: flexbody::build::BuildMethod::Normal,
        modes: Some(10),
        ..flexbody::build::BuildSpec::new(path.clone(), flexbody_reader::Units::si(), &[])
    };
    let built = flexbody::build::build_model(&spec, model, &mut |_| {}).unwrap();
    assert!(
        built
            .report
            .warnings
            .iter()
            .any(|w| w.contains("cards dropped on request") && w.contains("1 CWELD (")),
        "{:?}",
        built.report.warnings
    );
    // a free beam: 6 rigid modes first
    assert_eq!(built.body.method.counts.rigid, 6);
}

/// A case-control command that changes the body and is not modelled (a buckling preload, a
/// matrix added by DMIG) is refused with the cards, first, naming its line; it too can be
/// dropped on purpose. (STATSUB(PRELOAD) is honoured: tests/preload_nastran.rs.)
#[test]
fn case_control_preload_and_added_matrices_are_refused() {
    let text = base().replace(
        "METHOD = 1\n",
        "METHOD = 1\nSTATSUB(BUCKLE) = 2\nK2PP = KAAX\n",
    ) + "CGAP,50,60,3,4\nENDDATA\n";
    let path = write("rule_case", "statsub.bdf", &text);
    let e = read_model(&path, &ImportOptions::default()).unwrap_err();
    let ImportError::Refused { cards, .. } = &e else {
        panic!("not a refusal: {e}")
    };
    let got: Vec<(usize, &str)> = cards.iter().map(|c| (c.line, c.entity.as_str())).collect();
    assert_eq!(
        got,
        vec![
            (line_of(&text, "STATSUB"), "STATSUB(BUCKLE) (case control)"),
            (line_of(&text, "K2PP"), "K2PP (case control)"),
            (line_of(&text, "CGAP"), "CGAP 50"),
        ]
    );
    assert!(e.to_string().contains("buckling preload"), "{e}");
    let opts = ImportOptions {
        ignore_cards: vec!["STATSUB(BUCKLE)".into(), "K2PP".into(), "CGAP".into()],
        ..Default::default()
    };
    let m = read_model(&path, &opts).unwrap();
    assert!(
        m.warnings.iter().any(|w| w.message.contains(&format!(
            "1 STATSUB(BUCKLE) ({}:{})",
            path.display(),
            line_of(&text, "STATSUB")
        ))),
        "{:?}",
        m.warnings
    );
}

/// Every warning of a deck names file and line: an implausible material, shells with uneven
/// corner thicknesses, an RBE2 with a CBAR's id, mixed PSOLID formulations, an unusable load
/// set. (A PBARL BAR is a note since its shear factors are derived: no warning.)
#[test]
fn every_warning_names_file_and_line() {
    let text = base().replace("MAT1,1,2.1e11,,.3,7850.", "MAT1,1,2.1e11,,.3,7.85e-9")
        + "PSHELL,3,1,.002\nCQUAD4,40,3,1,2,3,4,,,+\n+,,,.002,.003,.002,.002\n\
           RBE2,5,13,123456,12\nPBARL,6,1,,BAR\n,.01,.02\nCBAR,41,6,1,2,0.,0.,1.\n\
           PSOLID,7,1,,,,FULL\nPSOLID,8,1\nPLOAD1,9,1,FZ,FR,0.,1.,1.,1.\nENDDATA\n";
    let path = write("rule_warnings", "warnings.bdf", &text);
    let m = match read_model(&path, &ImportOptions::default()) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    };
    assert!(m.warnings.len() >= 5, "{:?}", m.warnings);
    let file = path.display().to_string();
    for w in &m.warnings {
        let at_line = w
            .file
            .strip_prefix(&format!("{file}:"))
            .is_some_and(|l| l.parse::<usize>().is_ok());
        assert!(
            at_line || w.message.contains(&format!("{file}:")),
            "no line: {w:?}"
        );
    }
}

/// Issue 32 acceptance through the CLI: `--ignore CWELD` builds the deck the plain build
/// refuses, warns with the card's line, records the list in the recipe, `inspect` shows it and
/// `check --model` rebuilds the same model from the recipe (the card dropped again).
#[test]
fn cli_ignore_builds_records_the_cards_in_the_recipe_and_check_rebuilds() {
    let text = base() + "CWELD,90,91,1,2\nENDDATA\n";
    let path = write("rule_cli_ignore", "weld.bdf", &text);
    let out = path.with_extension("flexbody");
    let run = |args: &[&str]| crate::common::exe().args(args).output().unwrap();
    let (p, o) = (path.to_str().unwrap(), out.to_str().unwrap());
    let built = run(&[
        "build", p, "--units", "si", "--method", "normal", "--modes", "10", "--ignore", "CWELD",
        "-o", o,
    ]);
    let err = String::from_utf8_lossy(&built.stderr);
    assert_eq!(built.status.code(), Some(0), "{err}");
    assert!(
        err.contains("cards dropped on request")
            && err.contains(&format!(
                "1 CWELD ({}:{})",
                path.display(),
                line_of(&text, "CWELD")
            )),
        "{err}"
    );
    let body = flexbody_reader::read(&out).unwrap();
    let recipe = body.recipe.as_ref().unwrap();
    assert_eq!(recipe.options.ignore, ["CWELD"]);
    let shown = run(&["inspect", o]);
    assert!(
        String::from_utf8_lossy(&shown.stdout).contains("--ignore CWELD"),
        "{}",
        String::from_utf8_lossy(&shown.stdout)
    );
    let checked = run(&["check", o, "--model", p]);
    assert_eq!(
        checked.status.code(),
        Some(0),
        "{}{}",
        String::from_utf8_lossy(&checked.stdout),
        String::from_utf8_lossy(&checked.stderr)
    );
}
