//! MATT1, MATT2, MATT8, MATT9: temperature-dependent material properties through TABLEMi
//! tables (MSC QRG "MATT1"). References decide: a MATTi on a material that a property in the
//! deck uses is refused by its line (its properties at the part's temperature are not
//! evaluated); a MATTi on a material no property uses is a note, and so is every TABLEMi
//! (catalogue category "material tables": it acts only through a MATTi).

use std::collections::BTreeSet;

use super::cards::Category;
use super::fields::C;
use super::lex::Card;
use super::reading::Bulk;
use crate::import::error::ImportError;
use crate::model::Section;

/// Reason of the refusal of a MATTi on a material in use.
const IN_USE: &str = "temperature-dependent properties (MATTi → TABLEMi) of a material in use: \
                      not evaluated at the part's temperature (TEMPD / TEMP(INIT)); give the \
                      material's values at that temperature on its MATi, or drop the MATTi with \
                      --ignore to use the MATi's own values";

/// Reason of the note on a MATTi whose material no property uses.
const UNUSED: &str = "its material is used by no property";

/// Reader of MATT1, MATT2, MATT8, MATT9: kept until every property is read ([`decide`]).
pub(super) fn matt<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    g.id(0, "MID")?;
    d.properties.temperature_tables.push(g.card);
    Ok(())
}

/// Every MATTi: refused when a property uses its material, else a note.
pub(super) fn decide(d: &mut Bulk) -> Result<(), ImportError> {
    let cards: Vec<&Card> = std::mem::take(&mut d.properties.temperature_tables);
    if cards.is_empty() {
        return Ok(());
    }
    let used = materials_in_use(d);
    for card in cards {
        let g = C::new(card, d.files);
        let mid = g.id(0, "MID")?;
        if used.contains(&mid) {
            d.refuse(&g, IN_USE);
        } else {
            d.note_in(Category::Material, &g, Some(UNUSED));
        }
    }
    Ok(())
}

/// The external ids of the materials the deck's properties name (shells: membrane, bending,
/// shear and ply materials).
fn materials_in_use(d: &Bulk) -> BTreeSet<u64> {
    let mut used = BTreeSet::new();
    for (_, mid, section, _) in &d.properties.props {
        used.insert(*mid);
        if let Section::Shell(s) = section {
            used.extend(s.bending.map(|(m, _)| m as u64));
            used.extend(s.shear.map(|(m, _)| m as u64));
            used.extend(s.plies.iter().map(|p| p.material as u64));
        }
    }
    used
}
