//! What the reader does with a card ([`Rule`]), and a row of the catalogue's tables: below the
//! card readers' shared state (`reading`), which the readers' function type names.

use super::Category;
use crate::import::error::ImportError;
use crate::import::nastran::fields::C;
use crate::import::nastran::reading::Bulk;

/// A card reader: one card into its family's raw records (external ids, resolved later).
pub(in crate::import::nastran) type Reader =
    for<'a> fn(&mut Bulk<'a>, &C<'a>) -> Result<(), ImportError>;

/// What the reader does with a card.
pub(in crate::import::nastran) enum Rule {
    /// Read in the first pass, before every other card: coordinate systems and grids place
    /// the nodes (`geometry`).
    Geometry,
    /// Honoured: read by this function.
    Read(Reader),
    /// Not read: it cannot change the body, for its category's reason ([`Category::why`]).
    Note,
    /// Not read: it cannot change the body, for its category's reason and this one.
    NoteWhy(&'static str),
    /// Refused, with the reason.
    Refuse(&'static str),
    /// A case control command honoured by the case control reader (`case_control`).
    Command,
}

/// A catalogue row: name, category, rule.
pub(in crate::import::nastran) type Row = (&'static str, Category, Rule);
