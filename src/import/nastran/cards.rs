//! The card table: what the reader does with every bulk-data card and every PARAM — the rule
//! "honoured or refused, never dropped" as one list.
//!
//! * [`Rule::Geometry`], [`Rule::Read`]: honoured (one reader function per card family, as
//!   pyNastran has one class per card; adding a card touches this list and its family's file).
//! * [`Rule::Note`]: not read because it cannot change the body's stiffness, mass,
//!   constraints or preload in a normal-modes analysis; reported once per card type as a
//!   note with its reason and lines.
//! * [`Rule::Refuse`], and **every card not listed**: refused. The import stops with one
//!   error listing every refused card of the deck with file:line
//!   ([`crate::import::ImportError::Refused`]), unless the user drops it on purpose
//!   ([`crate::import::ImportOptions::ignore_cards`]).
//!
//! PARAMs have their own list, [`PARAMS`], with the same rules (unlisted → refused); a
//! PARAM is known as `PARAM:NAME`.

use super::bulk::Bulk;
use super::fields::C;
use super::{bush, elements, mass, properties, rigid, scalar, sets, solution};
use crate::import::error::ImportError;

/// A card reader: one card into its family's raw records (external ids, resolved later).
pub(super) type Reader = for<'a> fn(&mut Bulk<'a>, &C<'a>) -> Result<(), ImportError>;

/// What the reader does with a card.
pub(super) enum Rule {
    /// Read in the first pass, before every other card: coordinate systems and grids place
    /// the nodes (`geometry`).
    Geometry,
    /// Honoured: read by this function.
    Read(Reader),
    /// Not read: it cannot change the body (the reason, for the note).
    Note(&'static str),
    /// Refused, with the reason.
    Refuse(&'static str),
}

use Rule::{Geometry, Note, Read, Refuse};

/// Reason of the notes on damping cards.
pub(super) const DAMPING: &str =
    "damping: a real normal-modes analysis has none (give the body damping with --damping)";
/// Reason of the notes on the cards of response analyses.
const DYNAMIC: &str =
    "dynamic excitation or steps of a response analysis: not part of the body or its modes";
/// Reason of the notes on output and bookkeeping cards.
pub(super) const OUTPUT: &str = "output, plotting or bookkeeping: does not change the body";
/// Reason of the notes on thermal cards.
const THERMAL: &str =
    "thermal data: neither thermal strain nor temperature-dependent properties are modelled, and a normal-modes analysis has no thermal load";
/// Reason of the notes on other analyses' eigenvalue methods.
const OTHER_METHOD: &str = "the eigenvalue method of another analysis (buckling, complex modes)";

/// Every card with a rule, sorted by name (checked by a test). Unlisted cards are refused.
const CARDS: &[(&str, Rule)] = &[
    // static loads the scene does not read: their set is kept by name, unusable (`loads`)
    ("ACCEL", Read(super::loads::card)),
    ("ACCEL1", Read(super::loads::card)),
    ("ASET", Read(sets::aset)),
    ("ASET1", Read(sets::aset1)),
    ("BAROR", Read(elements::orientation_defaults)),
    ("BEAMOR", Read(elements::orientation_defaults)),
    ("BSET", Read(sets::aset)),
    ("BSET1", Read(sets::aset1)),
    ("CBAR", Read(elements::element)),
    ("CBEAM", Read(elements::element)),
    ("CBUSH", Read(bush::cbush)),
    ("CBUSH1D", Read(bush::cbush1d)),
    ("CDAMP1", Note(DAMPING)),
    ("CDAMP2", Note(DAMPING)),
    ("CDAMP3", Note(DAMPING)),
    ("CDAMP4", Note(DAMPING)),
    ("CDAMP5", Note(DAMPING)),
    ("CELAS1", Read(scalar::element)),
    ("CELAS2", Read(scalar::element)),
    ("CELAS3", Read(scalar::element)),
    ("CELAS4", Read(scalar::element)),
    ("CGAP", Refuse(GAP)),
    ("CHEXA", Read(elements::element)),
    ("CMASS1", Read(scalar::element)),
    ("CMASS2", Read(scalar::element)),
    ("CMASS3", Read(scalar::element)),
    ("CMASS4", Read(scalar::element)),
    ("CONM1", Read(mass::conm1)),
    ("CONM2", Read(mass::conm2)),
    ("CONROD", Read(elements::conrod)),
    ("CORD2C", Geometry),
    ("CORD2R", Geometry),
    ("CORD2S", Geometry),
    ("CPENTA", Read(elements::element)),
    ("CPYRAM", Read(elements::element)),
    ("CQUAD4", Read(elements::element)),
    ("CQUAD8", Read(elements::element)),
    ("CQUADR", Read(elements::element)),
    ("CROD", Read(elements::element)),
    ("CSHEAR", Read(super::shear::cshear)),
    ("CTETRA", Read(elements::element)),
    ("CTRIA3", Read(elements::element)),
    ("CTRIA6", Read(elements::element)),
    ("CTRIAR", Read(elements::element)),
    ("CVISC", Note(DAMPING)),
    ("DAREA", Note(DYNAMIC)),
    ("DEFORM", Read(super::loads::card)),
    ("DELAY", Note(DYNAMIC)),
    ("DLOAD", Note(DYNAMIC)),
    ("DMIG", Read(super::dmig::dmig)),
    ("DPHASE", Note(DYNAMIC)),
    ("EIGB", Note(OTHER_METHOD)),
    ("EIGC", Note(OTHER_METHOD)),
    ("EIGP", Note(OTHER_METHOD)),
    ("EIGR", Read(solution::eigr)),
    ("EIGRL", Read(solution::eigr)),
    ("FORCE", Read(super::loads::card)),
    ("FORCE1", Read(super::loads::card)),
    ("FORCE2", Read(super::loads::card)),
    ("FREQ", Note(DYNAMIC)),
    ("FREQ1", Note(DYNAMIC)),
    ("FREQ2", Note(DYNAMIC)),
    ("FREQ3", Note(DYNAMIC)),
    ("FREQ4", Note(DYNAMIC)),
    ("FREQ5", Note(DYNAMIC)),
    ("GENEL", Read(super::genel::genel)),
    ("GRAV", Read(super::loads::card)),
    ("GRDSET", Geometry),
    ("GRID", Geometry),
    ("LOAD", Read(super::loads::card)),
    ("LSEQ", Note(DYNAMIC)),
    ("MAT1", Read(properties::mat1)),
    ("MAT2", Read(properties::mat2)),
    ("MAT4", Note(THERMAL)),
    ("MAT5", Note(THERMAL)),
    ("MAT8", Read(properties::mat8)),
    ("MAT9", Read(properties::mat9)),
    ("MOMENT", Read(super::loads::card)),
    ("MOMENT1", Read(super::loads::card)),
    ("MOMENT2", Read(super::loads::card)),
    ("MONPNT1", Note(OUTPUT)),
    ("MPC", Read(sets::mpc)),
    ("MPCADD", Read(sets::mpcadd)),
    ("NLPARM", Note(DYNAMIC)),
    ("PBAR", Read(properties::property)),
    ("PBARL", Read(properties::property)),
    ("PBEAM", Read(properties::property)),
    ("PBEAML", Read(properties::property)),
    ("PBUSH", Read(bush::pbush)),
    ("PBUSH1D", Read(bush::pbush1d)),
    ("PCOMP", Read(properties::pcomp)),
    ("PCOMPG", Read(properties::pcomp)),
    // damper properties keep their id (one property id space) and are a note
    ("PDAMP", Read(properties::damper)),
    ("PDAMP5", Read(properties::damper)),
    ("PDAMPT", Read(properties::damper)),
    ("PELAS", Read(scalar::property)),
    ("PLOAD", Read(super::loads::card)),
    ("PLOAD1", Read(super::loads::card)),
    ("PLOAD2", Read(super::loads::card)),
    ("PLOAD4", Read(super::loads::card)),
    ("PLOTEL", Note(OUTPUT)),
    ("PMASS", Read(scalar::property)),
    ("PROD", Read(properties::property)),
    ("PSHEAR", Read(super::shear::pshear)),
    ("PSHELL", Read(properties::property)),
    ("PSOLID", Read(properties::property)),
    ("PVISC", Read(properties::damper)),
    ("QSET", Read(sets::aset)),
    ("QSET1", Read(sets::aset1)),
    ("RANDPS", Note(DYNAMIC)),
    ("RANDT1", Note(DYNAMIC)),
    ("RBAR", Read(rigid::rbar)),
    ("RBAR1", Read(rigid::rbar1)),
    ("RBE1", Read(rigid::rbe1)),
    ("RBE2", Read(rigid::rbe2)),
    ("RBE3", Read(rigid::rbe3)),
    ("RFORCE", Read(super::loads::card)),
    ("RLOAD1", Note(DYNAMIC)),
    ("RLOAD2", Note(DYNAMIC)),
    ("SEQGP", Note(OUTPUT)),
    ("SLOAD", Read(super::loads::card)),
    ("SPC", Read(sets::spc)),
    ("SPC1", Read(sets::spc1)),
    ("SPCADD", Read(sets::spcadd)),
    ("SPCD", Read(super::loads::card)),
    ("SPOINT", Geometry),
    (
        "SUPORT",
        Note("the r-set Nastran computes its rigid-body modes on: it does not hold the body"),
    ),
    (
        "SUPORT1",
        Note("the r-set Nastran computes its rigid-body modes on: it does not hold the body"),
    ),
    ("TABDMP1", Note(DAMPING)),
    ("TABLED1", Note(DYNAMIC)),
    ("TABLED2", Note(DYNAMIC)),
    ("TABLED3", Note(DYNAMIC)),
    ("TABLED4", Note(DYNAMIC)),
    ("TEMP", Read(super::loads::temperature_card)),
    ("TEMPD", Read(super::loads::temperature_card)),
    ("TLOAD1", Note(DYNAMIC)),
    ("TLOAD2", Note(DYNAMIC)),
    ("TSTEP", Note(DYNAMIC)),
    ("TSTEPNL", Note(DYNAMIC)),
    ("USET", Note(OUTPUT)),
    ("USET1", Note(OUTPUT)),
];

/// Every PARAM with a rule, sorted by name. Unlisted PARAMs are refused (`PARAM:NAME`).
pub(super) const PARAMS: &[(&str, Rule)] = &[
    (
        "AUTOSPC",
        Note("the build removes the dofs with neither stiffness nor mass either way (they take no part in a mode)"),
    ),
    ("BAILOUT", Note(OUTPUT)),
    ("COUPMASS", Read(solution::coupmass)),
    ("G", Note(DAMPING)),
    ("GFL", Note(DAMPING)),
    ("GRDPNT", Note(OUTPUT)),
    ("K6ROT", Read(solution::k6rot)),
    ("KDAMP", Note(DAMPING)),
    ("MAXRATIO", Note(OUTPUT)),
    ("NOCOMPS", Note(OUTPUT)),
    ("OGEOM", Note(OUTPUT)),
    ("OUGCORD", Note(OUTPUT)),
    ("PATVER", Note(OUTPUT)),
    ("POST", Note(OUTPUT)),
    ("POSTEXT", Note(OUTPUT)),
    ("PRGPST", Note(OUTPUT)),
    ("PRTMAXIM", Note(OUTPUT)),
    ("RESVEC", Note(DYNAMIC)),
    ("SRCOMPS", Note(OUTPUT)),
    ("W3", Note(DAMPING)),
    ("W4", Note(DAMPING)),
    ("WH", Note(DAMPING)),
    ("WTMASS", Read(solution::wtmass)),
];

/// Reason of the refusal of gap elements.
const GAP: &str = "a gap is a contact element: its stiffness depends on whether it is open or \
                   closed, which a linear flexible body cannot carry (model the closed gap as a \
                   spring, CELAS/CBUSH, or drop it with --ignore CGAP)";

/// The reason of the refusal of a card or PARAM no list names.
pub(super) const NOT_READ: &str =
    "not read by this importer, and it may change the body's stiffness, mass or constraints";

/// Look `name` up in a sorted table.
fn lookup<'t>(table: &'t [(&str, Rule)], name: &str) -> Option<&'t Rule> {
    table
        .binary_search_by(|(n, _)| (*n).cmp(name))
        .ok()
        .map(|k| &table[k].1)
}

/// The name a card is known by in notes, refusals and `ignore_cards`: the card name, or
/// `PARAM:NAME` for a PARAM.
pub(super) fn key(g: &C) -> String {
    if g.card.name == "PARAM" {
        format!("PARAM:{}", g.text(0).to_ascii_uppercase())
    } else {
        g.card.name.clone()
    }
}

/// The rule of a card (a PARAM's from [`PARAMS`]); `None`: refused as not read.
pub(super) fn rule(g: &C) -> Option<&'static Rule> {
    match g.card.name.as_str() {
        "PARAM" => lookup(PARAMS, &g.text(0).to_ascii_uppercase()),
        name => lookup(CARDS, name),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn card_tables_are_sorted_and_unique() {
        for table in [CARDS, PARAMS] {
            for w in table.windows(2) {
                assert!(w[0].0 < w[1].0, "{} before {}", w[0].0, w[1].0);
            }
        }
        assert!(matches!(lookup(CARDS, "GRID"), Some(Rule::Geometry)));
        assert!(matches!(lookup(CARDS, "CDAMP1"), Some(Rule::Note(_))));
        assert!(lookup(CARDS, "NOSUCH").is_none() && lookup(PARAMS, "SNORM").is_none());
    }
}
