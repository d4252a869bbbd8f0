//! `*INITIAL CONDITIONS` (issue 32): what can change the body is refused by name, the rest is a
//! note — velocities and displacements (they start a dynamic or static step), temperatures
//! without `*EXPANSION`; stresses (a preload), temperatures beside `*EXPANSION` (thermal strain)
//! and every other type are refused with file:line.

mod common;

use flexbody::import::{abaqus, ImportError};
use flexbody::model::Model;

const CUBE: &str = "*NODE, NSET=NALL\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n\
5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n\
*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n1, 1, 2, 3, 4, 5, 6, 7, 8\n\
*MATERIAL, NAME=M\n*ELASTIC\n1e6, 0.3\n*DENSITY\n1000\n*SOLID SECTION, ELSET=BLOCK, MATERIAL=M\n";

const STEP: &str =
    "*BOUNDARY\n1, 1, 3\n2, 1, 3\n3, 1, 3\n4, 1, 3\n*STEP\n*FREQUENCY\n4\n*END STEP\n";

fn read(name: &str, text: &str) -> Result<Model, ImportError> {
    let dir = common::scratch(&format!("abaqus-ic-{name}"));
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
fn stresses_temperatures_beside_expansion_and_other_types_are_refused_by_line() {
    // line 18: the first keyword after the cube's 17 lines
    let stress = format!("{CUBE}*INITIAL CONDITIONS, TYPE=STRESS\n1, 1e6, 0, 0, 0, 0, 0\n{STEP}");
    let r = refused("stress", &stress);
    assert!(
        r.len() == 1 && r[0].0 == 18 && r[0].1.contains("TYPE=STRESS"),
        "{r:?}"
    );
    // *EXPANSION after the temperatures: decided when the deck is read
    let thermal = format!(
        "{CUBE}*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 350.\n\
         *MATERIAL, NAME=N\n*ELASTIC\n1e6, 0.3\n*EXPANSION\n1.2e-5\n{STEP}"
    );
    let r = refused("thermal", &thermal);
    assert!(
        r.len() == 1
            && r[0].0 == 18
            && r[0]
                .1
                .contains("TYPE=TEMPERATURE with *EXPANSION (line 23)"),
        "{r:?}"
    );
    let plastic = format!("{CUBE}*INITIAL CONDITIONS, TYPE=PLASTIC STRAIN\n1, 1, 0.01\n{STEP}");
    let r = refused("plastic", &plastic);
    assert!(
        r.len() == 1 && r[0].1.contains("TYPE=PLASTICSTRAIN"),
        "{r:?}"
    );
}
