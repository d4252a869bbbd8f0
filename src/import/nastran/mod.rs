//! Nastran bulk-data reader → [`Model`].
//!
//! Cards: GRID (CP/CD), CORD2R/CORD2C/CORD2S (chained), CTETRA (4/10), CHEXA (8/20),
//! CPENTA (6/15), CBAR, CBEAM, CROD, CQUAD4, CTRIA3, PSOLID, PBAR, PBARL, PBEAM, PBEAML, PROD,
//! PSHELL, PCOMP (one isotropic material), MAT1, CONM2, RBE2, RBE3, SPC, SPC1, SPCADD, GRDSET,
//! ASET, ASET1, BSET, BSET1, QSET, QSET1, EIGRL, EIGR, PARAM WTMASS/COUPMASS; the load cards
//! FORCE, MOMENT, GRAV, PLOAD4 and LOAD (`loads`: named scene loads `LOAD_<sid>`); the case
//! control's TITLE, SUBCASE, SPC, METHOD and LOAD (`case_control`).
//! Every other card is counted and reported once per card type as a warning; elements that
//! reference a property of an unsupported type (e.g. PCOMPG) get no property and a warning.
//!
//! Layout: `lex` (text → cards), `cards` (the card table: each card's reader), one file per
//! card family with its reader and its resolve step (`geometry`, `elements`, `properties`,
//! `shell`, `mass`, `rigid`, `sets`, `solution`, `loads`), and `bulk` (the three passes:
//! geometry, readers, resolve).
//!
//! Constraints as Nastran applies them: GRID PS / GRDSET always; an SPC/SPC1/SPCADD set only
//! when the case control selects it (`SPC = n`, global or in the one or chosen subcase; bare
//! bulk data selects none). Node sets: `SPC_<sid>` holds the nodes of SPC/SPC1/SPCADD set `sid`,
//! selected or not (the reference `.bdf` files write one SPC1 per named node set). Element
//! sets: `PID_<pid>` per property. CHEXA20/CPENTA15 mid-side nodes are permuted to Abaqus order
//! (Nastran lists the vertical edges before the top edges).

mod bulk;
mod cards;
mod case_control;
mod coord;
mod elements;
mod fields;
mod geometry;
mod lex;
mod loads;
mod mass;
mod properties;
mod rigid;
mod sets;
mod shell;
mod solution;

use std::collections::BTreeMap;
use std::path::Path;

use super::error::ImportError;
use super::ImportOptions;
use crate::model::Model;

/// Card counts by card name (`GRID`, `CHEXA`, `PARAM`, …), supported or not.
pub type CardCounts = BTreeMap<String, usize>;

/// Read a Nastran deck (bulk data after `BEGIN BULK`, or a bare bulk file; `INCLUDE` followed).
pub fn read(path: &Path) -> Result<Model, ImportError> {
    read_with_counts(path).map(|(m, _)| m)
}

/// [`read`], also returning how many cards of each type the deck holds.
pub fn read_with_counts(path: &Path) -> Result<(Model, CardCounts), ImportError> {
    read_subcase(path, None)
}

/// [`read_with_counts`] with the SPC and METHOD selections of case-control subcase `subcase`
/// (needed when the deck's subcases select different sets).
pub fn read_subcase(path: &Path, subcase: Option<u64>) -> Result<(Model, CardCounts), ImportError> {
    read_with_options(
        path,
        &ImportOptions {
            subcase,
            ..Default::default()
        },
    )
}

/// [`read_with_counts`] with the options that apply to a Nastran deck: the case-control
/// subcase ([`ImportOptions::subcase`]) and the cards to drop on purpose
/// ([`ImportOptions::ignore_cards`]).
pub fn read_with_options(
    path: &Path,
    opts: &ImportOptions,
) -> Result<(Model, CardCounts), ImportError> {
    let mut lexer = lex::Lexer::new(&path.display().to_string());
    lexer.lex_file(path, 0, 0)?;
    bulk::build(lexer, opts.subcase, &opts.ignore_cards)
}
