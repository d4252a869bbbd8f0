//! `*INITIAL CONDITIONS` (issue 32): what can change the body is refused by name, the rest is a
//! note — velocities and displacements (they start a dynamic or static step); stresses (a
//! preload) and every other type are refused with file:line. Temperatures are read (issue 35):
//! the reference of a thermal strain — none in a plain frequency step, α (T − T₀) in the static
//! step a perturbation step perturbs — and the state temperature tables are read at.

use flexbody::import::{abaqus, ImportError};
use flexbody::model::Model;

const CUBE: &str = "*NODE, NSET=NALL\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n\
5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n\
*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n1, 1, 2, 3, 4, 5, 6, 7, 8\n\
*MATERIAL, NAME=M\n*ELASTIC\n1e6, 0.3\n*DENSITY\n1000\n*SOLID SECTION, ELSET=BLOCK, MATERIAL=M\n";

const STEP: &str =
    "*BOUNDARY\n1, 1, 3\n2, 1, 3\n3, 1, 3\n4, 1, 3\n*STEP\n*FREQUENCY\n4\n*END STEP\n";

fn read(name: &str, text: &str) -> Result<Model, ImportError> {
    let dir = crate::common::scratch(&format!("abaqus-ic-{name}"));
    let path = dir.join(format!("{name}.inp"));
    std::fs::write(&path, text).unwrap();
    abaqus::read(&path)
}

/// The refused cards' (line, reason) of a deck.
fn refused(name: &str, text: &str) -> Vec<(usize, String)> {
    match read(name, text) {
        Err(ImportError::Refused { cards, .. }) => {
            assert!(cards.iter().all(|c| c.entity == "*INITIAL CONDITIONS"));
            cards.into_iter().map(|c| (c.line, c.reason)).collect()
        }
        other => panic!("{name}: {other:?}"),
    }
}

#[test]
fn velocities_displacements_and_plain_temperatures_are_notes_that_change_nothing() {
    let plain = read("plain", &format!("{CUBE}{STEP}")).unwrap();
    let deck = format!(
        "{CUBE}*INITIAL CONDITIONS, TYPE=VELOCITY\nNALL, 1, 2.5\n\
         *INITIAL CONDITIONS, TYPE=DISPLACEMENT\n5, 3, 0.01\n\
         *INITIALCONDITIONS, TYPE=TEMPERATURE\nNALL, 293.\n{STEP}"
    );
    let m = read("notes", &deck).unwrap();
    assert!(
        m.deck
            .notes
            .iter()
            .any(|n| n.contains("*INITIAL CONDITIONS")),
        "{:?}",
        m.deck.notes
    );
    // the same body: nodes, elements, materials, constraints
    assert_eq!(m.nodes, plain.nodes);
    assert_eq!(m.elements, plain.elements);
    assert_eq!(m.materials, plain.materials);
    assert_eq!(m.spcs, plain.spcs);
}

#[test]
fn stresses_and_other_types_are_refused_by_line() {
    // line 18: the first keyword after the cube's 17 lines
    let stress = format!("{CUBE}*INITIAL CONDITIONS, TYPE=STRESS\n1, 1e6, 0, 0, 0, 0, 0\n{STEP}");
    let r = refused("stress", &stress);
    assert!(
        r.len() == 1 && r[0].0 == 18 && r[0].1.contains("TYPE=STRESS"),
        "{r:?}"
    );
    let plastic = format!("{CUBE}*INITIAL CONDITIONS, TYPE=PLASTIC STRAIN\n1, 1, 0.01\n{STEP}");
    let r = refused("plastic", &plastic);
    assert!(
        r.len() == 1 && r[0].1.contains("TYPE=PLASTICSTRAIN"),
        "{r:?}"
    );
}

/// Temperatures with `*EXPANSION`: a plain frequency step has no thermal strain (the state is
/// the initial one); the static step of a perturbation step that heats the part carries the
/// thermal preload α (T − T₀) per node; a temperature table over a non-uniform field, and a
/// table without any temperature, are refused naming the material.
#[test]
fn initial_temperatures_are_the_reference_of_a_thermal_strain() {
    let heated = |ic: &str, step_t: &str| {
        format!(
            "{CUBE}*INITIAL CONDITIONS, TYPE=TEMPERATURE\n{ic}\n\
             *MATERIAL, NAME=N\n*ELASTIC\n1e6, 0.3\n*EXPANSION\n1.2e-5\n\
             *BOUNDARY\n1, 1, 3\n2, 1, 3\n3, 1, 3\n4, 1, 3\n\
             *STEP\n*STATIC\n*TEMPERATURE\n{step_t}\n*END STEP\n\
             *STEP, PERTURBATION\n*FREQUENCY\n4\n*END STEP\n"
        )
    };
    // a plain frequency step: no strain, no preload
    let plain = format!(
        "{CUBE}*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 350.\n\
         *MATERIAL, NAME=N\n*ELASTIC\n1e6, 0.3\n*EXPANSION\n1.2e-5\n{STEP}"
    );
    let m = read("plain-thermal", &plain).unwrap();
    assert!(m.deck.preload.is_none());
    // heated by 30° from 20° in the perturbed static step
    let m = read("heated", &heated("NALL, 20.", "NALL, 50.")).unwrap();
    let request = m.deck.preload.expect("a thermal preload");
    let (dt, alpha) = request.thermal.expect("thermal strain");
    assert!(dt.iter().all(|&t| t == 30.0), "{dt:?}");
    assert_eq!(alpha[0], 0.0); // M: no *EXPANSION
    assert_eq!(alpha[1], 1.2e-5);
    // the same temperature as the initial one: nothing strains, nothing preloads
    let m = read("unheated", &heated("NALL, 20.", "NALL, 20.")).unwrap();
    assert!(m.deck.preload.is_none());
    assert!(
        m.deck.notes.iter().any(|n| n.contains("strains nothing")),
        "{:?}",
        m.deck.notes
    );
    // a mechanical preload beside a temperature-dependent *EXPANSION: nothing heats, no strain
    let loaded = format!(
        "{CUBE}*MATERIAL, NAME=N\n*ELASTIC\n1e6, 0.3\n*EXPANSION\n1e-5, 0.\n2e-5, 100.\n\
         *BOUNDARY\n1, 1, 3\n2, 1, 3\n3, 1, 3\n4, 1, 3\n\
         *STEP\n*STATIC\n*CLOAD\n7, 3, -10.\n*END STEP\n\
         *STEP, PERTURBATION\n*FREQUENCY\n4\n*END STEP\n"
    );
    let m = read("loaded", &loaded).unwrap();
    let request = m.deck.preload.expect("the *CLOAD preload");
    assert!(
        request.thermal.is_none() && request.loads.len() == 1,
        "{request:?}"
    );
    // a temperature table read at a non-uniform field, and without any temperature
    let table = |ic: &str| {
        format!("{CUBE}{ic}*MATERIAL, NAME=N\n*ELASTIC\n1e6, 0.3, 0.\n2e6, 0.3, 100.\n{STEP}")
    };
    let e = read(
        "field",
        &table("*INITIAL CONDITIONS, TYPE=TEMPERATURE\n1, 10.\n2, 20.\n"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("*MATERIAL N") && e.contains("not uniform (10 to 20"),
        "{e}"
    );
    let e = read("none", &table("")).unwrap_err().to_string();
    assert!(
        e.contains("*MATERIAL N") && e.contains("gives the part no temperature"),
        "{e}"
    );
    // a uniform temperature reads the table: 1.5e6 at 50°
    let m = read(
        "table",
        &table("*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 50.\n"),
    )
    .unwrap();
    assert_eq!(m.materials[1].e, 1.5e6);
}
