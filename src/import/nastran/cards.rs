//! The card table: every bulk-data card this reader interprets, with the function that reads
//! it (one per card family, as pyNastran has one class per card). Adding a card touches this
//! list and its family's file.

use super::bulk::Bulk;
use super::fields::C;
use super::{elements, mass, properties, rigid, sets, solution};
use crate::import::error::ImportError;

/// A card reader: one card into its family's raw records (external ids, resolved later).
pub(super) type Reader = for<'a> fn(&mut Bulk<'a>, &C<'a>) -> Result<(), ImportError>;

/// What the reader does with a card.
pub(super) enum Rule {
    /// Read in the first pass, before every other card: coordinate systems and grids place
    /// the nodes (`geometry`).
    Geometry,
    /// Read by this function.
    Read(Reader),
}

use Rule::{Geometry, Read};

/// Every interpreted card, sorted by name (checked by a test).
const CARDS: &[(&str, Rule)] = &[
    ("ASET", Read(sets::aset)),
    ("ASET1", Read(sets::aset1)),
    ("BSET", Read(sets::aset)),
    ("BSET1", Read(sets::aset1)),
    ("CBAR", Read(elements::element)),
    ("CBEAM", Read(elements::element)),
    ("CHEXA", Read(elements::element)),
    ("CONM2", Read(mass::conm2)),
    ("CORD2C", Geometry),
    ("CORD2R", Geometry),
    ("CORD2S", Geometry),
    ("CPENTA", Read(elements::element)),
    ("CQUAD4", Read(elements::element)),
    ("CQUAD8", Read(elements::unsupported_shell)),
    ("CQUADR", Read(elements::unsupported_shell)),
    ("CROD", Read(elements::element)),
    ("CTETRA", Read(elements::element)),
    ("CTRIA3", Read(elements::element)),
    ("CTRIA6", Read(elements::unsupported_shell)),
    ("CTRIAR", Read(elements::unsupported_shell)),
    ("EIGR", Read(solution::eigr)),
    ("EIGRL", Read(solution::eigr)),
    ("FORCE", Read(super::loads::card)),
    ("GRAV", Read(super::loads::card)),
    ("GRDSET", Geometry),
    ("GRID", Geometry),
    ("LOAD", Read(super::loads::card)),
    ("MAT1", Read(properties::mat1)),
    ("MOMENT", Read(super::loads::card)),
    ("PARAM", Read(solution::param)),
    ("PBAR", Read(properties::property)),
    ("PBARL", Read(properties::property)),
    ("PBEAM", Read(properties::property)),
    ("PBEAML", Read(properties::property)),
    ("PBUSH", Read(properties::unsupported_property)),
    ("PCOMP", Read(properties::pcomp)),
    ("PCOMPG", Read(properties::unsupported_property)),
    ("PDAMP", Read(properties::unsupported_property)),
    ("PELAS", Read(properties::unsupported_property)),
    ("PGAP", Read(properties::unsupported_property)),
    ("PLOAD4", Read(super::loads::card)),
    ("PMASS", Read(properties::unsupported_property)),
    ("PROD", Read(properties::property)),
    ("PSHEAR", Read(properties::unsupported_property)),
    ("PSHELL", Read(properties::property)),
    ("PSOLID", Read(properties::property)),
    ("PVISC", Read(properties::unsupported_property)),
    ("QSET", Read(sets::aset)),
    ("QSET1", Read(sets::aset1)),
    ("RBE2", Read(rigid::rbe2)),
    ("RBE3", Read(rigid::rbe3)),
    ("SPC", Read(sets::spc)),
    ("SPC1", Read(sets::spc1)),
    ("SPCADD", Read(sets::spcadd)),
];

/// The rule of card `name`, if the reader interprets it.
pub(super) fn rule(name: &str) -> Option<&'static Rule> {
    CARDS
        .binary_search_by(|(n, _)| (*n).cmp(name))
        .ok()
        .map(|k| &CARDS[k].1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn card_table_is_sorted_and_unique() {
        for w in CARDS.windows(2) {
            assert!(w[0].0 < w[1].0, "{} before {}", w[0].0, w[1].0);
        }
        assert!(matches!(rule("GRID"), Some(Rule::Geometry)));
        assert!(rule("NOSUCH").is_none());
    }
}
