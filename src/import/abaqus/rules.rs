//! The keyword table of the Abaqus/CalculiX reader: what it does with every keyword — the rule
//! "honoured or refused, never dropped" as one list, as the Nastran card table
//! (`import::nastran::cards`) is for cards.
//!
//! * [`HONOURED`]: read by the keyword table of [`super::keywords`].
//! * [`Rule::Note`]: not read because it cannot change the body's stiffness, mass,
//!   constraints or preload in a normal-modes analysis; one note per keyword with its lines.
//! * [`Rule::Refuse`], and **every keyword not listed**: refused. The import stops with one
//!   error listing every refused keyword (and element type) of the deck with file:line
//!   ([`crate::import::ImportError::Refused`]), unless the user drops it on purpose
//!   ([`crate::import::ImportOptions::ignore_cards`], the keyword's name with or without `*`,
//!   or an element type's name).
//!
//! CalculiX ignores blanks in keyword and parameter names (`*RIGIDBODY` = `*RIGID BODY`,
//! `REFNODE` = `REF NODE`): [`canonical`] gives every spelling the table's name.

/// What the reader does with a keyword it does not read.
pub(super) enum Rule {
    /// Not read: it cannot change the body (the reason, for the note).
    Note(&'static str),
    /// Refused, with the reason.
    Refuse(&'static str),
}

use Rule::{Note, Refuse};

/// Keywords the reader honours (`super::keywords`), and the step procedures (`super::steps`).
pub(super) const HONOURED: &[&str] = &[
    "BEAM GENERAL SECTION",
    "BEAM SECTION",
    "BOUNDARY",
    "CLOAD",
    "COUPLING",
    "DENSITY",
    "DISTRIBUTING",
    "DLOAD",
    "DSLOAD",
    "ELASTIC",
    "ELEMENT",
    "ELSET",
    "END STEP",
    "EQUATION",
    "EXPANSION",
    "INCLUDE",
    "INITIAL CONDITIONS",
    "KINEMATIC",
    "MASS",
    "MATERIAL",
    "NODAL THICKNESS",
    "NODE",
    "NSET",
    "ORIENTATION",
    "RESTART",
    "RIGID BODY",
    "ROTARY INERTIA",
    "SHELL SECTION",
    "SOLID SECTION",
    "SPRING",
    "STEP",
    "SURFACE",
    "TIE",
    "TRANSFORM",
];

const OUTPUT: &str = "output or bookkeeping: does not change the body";
const DAMPING: &str =
    "damping: a real normal-modes analysis has none (give the body damping with --damping)";
const DYNAMIC: &str = "excitation or settings of a response analysis: not part of the body";
const THERMAL: &str =
    "thermal data: neither thermal strain nor temperature-dependent properties are modelled, and a normal-modes analysis has no thermal load";
const CONTACT: &str = "contact is not supported";
const MATERIAL: &str = "only linear elastic materials are supported";
const CHANGE: &str = "a change of the model inside a step is not supported";

/// Every keyword with a rule, sorted by name (checked by a test). Unlisted (and not
/// [`HONOURED`]) keywords are refused.
const KEYWORDS: &[(&str, Rule)] = &[
    ("ADJUST", Refuse(CONTACT)),
    ("AMPLITUDE", Note(DYNAMIC)),
    ("BASE MOTION", Note(DYNAMIC)),
    ("CFLUX", Note(THERMAL)),
    ("CHANGE FRICTION", Refuse(CHANGE)),
    ("CHANGE MATERIAL", Refuse(CHANGE)),
    ("CHANGE PLASTIC", Refuse(CHANGE)),
    ("CHANGE SOLID SECTION", Refuse(CHANGE)),
    ("CHANGE SURFACE BEHAVIOR", Refuse(CHANGE)),
    ("CLEARANCE", Refuse(CONTACT)),
    ("CONDUCTIVITY", Note(THERMAL)),
    ("CONSTRAINT", Note("design optimization: does not change the body")),
    ("CONTACT DAMPING", Refuse(CONTACT)),
    ("CONTACT FILE", Note(OUTPUT)),
    ("CONTACT OUTPUT", Note(OUTPUT)),
    ("CONTACT PAIR", Refuse(CONTACT)),
    ("CONTACT PRINT", Note(OUTPUT)),
    ("CONTROLS", Note("solver controls: do not change the body")),
    ("CREEP", Refuse(MATERIAL)),
    ("CYCLIC SYMMETRY MODEL", Refuse("cyclic symmetry is not supported")),
    ("DAMPING", Note(DAMPING)),
    ("DASHPOT", Note(DAMPING)),
    ("DEFORMATION PLASTICITY", Refuse(MATERIAL)),
    ("DEPVAR", Refuse(MATERIAL)),
    (
        "DESIGN VARIABLES",
        Note("design optimization: does not change the body"),
    ),
    ("DFLUX", Note(THERMAL)),
    (
        "DISTRIBUTING COUPLING",
        Refuse("use *COUPLING with *DISTRIBUTING"),
    ),
    ("EL FILE", Note(OUTPUT)),
    ("EL PRINT", Note(OUTPUT)),
    ("ELEMENT OUTPUT", Note(OUTPUT)),
    ("FACE PRINT", Note(OUTPUT)),
    ("FILM", Note(THERMAL)),
    ("FLUID SECTION", Refuse("fluid sections are not supported")),
    ("FRICTION", Refuse(CONTACT)),
    ("GAP", Refuse("gap elements are not supported")),
    ("HEADING", Note(OUTPUT)),
    ("HYPERELASTIC", Refuse(MATERIAL)),
    ("HYPERFOAM", Refuse(MATERIAL)),
    ("MEMBRANE SECTION", Refuse("membranes are not supported")),
    ("MODAL DAMPING", Note(DAMPING)),
    ("MODEL CHANGE", Refuse(CHANGE)),
    (
        "MPC",
        Refuse("CalculiX's nonlinear MPCs (PLANE, STRAIGHT, BEAM, …) are not supported"),
    ),
    ("NODE FILE", Note(OUTPUT)),
    ("NODE OUTPUT", Note(OUTPUT)),
    ("NODE PRINT", Note(OUTPUT)),
    (
        "NORMAL",
        Refuse("given shell normals are not supported (normals come from the node order)"),
    ),
    ("OBJECTIVE", Note("design optimization: does not change the body")),
    ("OUTPUT", Note(OUTPUT)),
    ("PHYSICAL CONSTANTS", Note(THERMAL)),
    ("PLASTIC", Refuse(MATERIAL)),
    (
        "PRE-TENSION SECTION",
        Refuse("pretension (a preload) is not supported"),
    ),
    ("PREPRINT", Note(OUTPUT)),
    ("RADIATE", Note(THERMAL)),
    (
        "RETAINED NODAL DOFS",
        Note("the retained dofs of a CalculiX substructure generation: the body's interface is --interface"),
    ),
    ("SECTION PRINT", Note(OUTPUT)),
    (
        "SELECT CYCLIC SYMMETRY MODES",
        Refuse("cyclic symmetry is not supported"),
    ),
    ("SELECT EIGENMODES", Note(DYNAMIC)),
    ("SENSITIVITY", Note("design sensitivities: do not change the body")),
    ("SPECIFIC HEAT", Note(THERMAL)),
    (
        "SUBMODEL",
        Refuse("submodel boundary conditions are not supported"),
    ),
    ("SUBSTRUCTURE MATRIX OUTPUT", Note(OUTPUT)),
    ("SURFACE BEHAVIOR", Refuse(CONTACT)),
    ("SURFACE INTERACTION", Refuse(CONTACT)),
    ("TIME POINTS", Note(OUTPUT)),
    ("USER ELEMENT", Refuse("user elements are not supported")),
    ("USER MATERIAL", Refuse(MATERIAL)),
    ("VALUES AT INFINITY", Note(THERMAL)),
];

/// The reason of the refusal of a keyword the table does not name.
pub(super) const NOT_READ: &str =
    "not read by this importer, and it may change the body's stiffness, mass, constraints or preload";

/// `s` upper-cased without blanks: how CalculiX compares keyword and parameter names.
pub(super) fn blankless(s: &str) -> String {
    s.chars()
        .filter(|c| !c.is_whitespace())
        .map(|c| c.to_ascii_uppercase())
        .collect()
}

/// The table's name of a keyword written `raw` (`RigidBody` → `RIGID BODY`); a keyword the
/// table does not know keeps its blank-less upper-case spelling.
pub(super) fn canonical(raw: &str) -> String {
    let b = blankless(raw);
    (HONOURED.iter().copied())
        .chain(super::steps::PROCEDURES)
        .chain(KEYWORDS.iter().map(|(n, _)| *n))
        .find(|n| blankless(n) == b)
        .map_or(b, str::to_owned)
}

/// The rule of a keyword that is not honoured (`None`: refused as not read).
pub(super) fn rule(name: &str) -> Option<&'static Rule> {
    KEYWORDS
        .binary_search_by(|(n, _)| (*n).cmp(name))
        .ok()
        .map(|k| &KEYWORDS[k].1)
}

/// An `ignore_cards` name as this table compares it: upper case, no blanks, no leading `*`.
pub(super) fn ignore_key(name: &str) -> String {
    blankless(name.trim().trim_start_matches('*'))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keyword_table_is_sorted_unique_and_apart_from_the_honoured_list() {
        for w in KEYWORDS.windows(2) {
            assert!(w[0].0 < w[1].0, "{} before {}", w[0].0, w[1].0);
        }
        for w in HONOURED.windows(2) {
            assert!(w[0] < w[1], "{} before {}", w[0], w[1]);
        }
        for (n, _) in KEYWORDS {
            assert!(!HONOURED.contains(n), "{n} both honoured and in the table");
        }
        assert!(matches!(rule("CONTACT PAIR"), Some(Refuse(_))));
        assert!(matches!(rule("NODE PRINT"), Some(Note(_))));
        assert!(rule("NO SUCH").is_none());
    }

    #[test]
    fn blanks_in_keyword_names_do_not_matter() {
        assert_eq!(canonical("RigidBody"), "RIGID BODY");
        assert_eq!(canonical("rigid  body"), "RIGID BODY");
        assert_eq!(canonical("NODEPRINT"), "NODE PRINT");
        assert_eq!(canonical("SOLIDSECTION"), "SOLID SECTION");
        assert_eq!(canonical("Modal Dynamic"), "MODAL DYNAMIC");
        assert_eq!(canonical("no such thing"), "NOSUCHTHING");
        assert_eq!(ignore_key(" *rigid body"), "RIGIDBODY");
    }
}
