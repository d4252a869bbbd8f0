//! Nastran bulk-data reader → [`Model`].
//!
//! Cards honoured: GRID (CP/CD), SPOINT, CORD2R/CORD2C/CORD2S (chained), CTETRA (4/10),
//! CHEXA (8/20), CPENTA (6/15), CPYRAM (5/13), CBAR, CBEAM, CROD, CONROD, CQUAD4, CTRIA3,
//! CELAS1–4, CMASS1–4, CBUSH, PSOLID, PBAR, PBARL, PBEAM, PBEAML, PROD, PSHELL, PCOMP (plies of
//! MAT1/MAT8/MAT2), PELAS, PMASS, PBUSH, MAT1, MAT2, MAT8, MAT9, CONM1, CONM2, RBE2, RBE3, RBAR, RBAR1, RBE1,
//! MPC, MPCADD, SPC, SPC1, SPCADD, GRDSET, ASET, ASET1, BSET, BSET1, QSET, QSET1, EIGRL, EIGR,
//! PARAM WTMASS/COUPMASS/K6ROT; the load cards FORCE, MOMENT, GRAV, PLOAD4 and LOAD (`loads`:
//! named scene loads `LOAD_<sid>`); the case control's TITLE, SUBCASE, SPC, MPC, METHOD and
//! LOAD (`case_control`). What every other card is — a note (it cannot change the body) or
//! refused — is the card table's (`cards`): honoured or refused, never dropped.
//!
//! Layout: `lex` (text → cards), `cards` (the card table: each card's rule), one file per
//! card family with its reader and its resolve step (`geometry`, `elements`, `properties`,
//! `shell`, `mass`, `scalar`, `bush`, `rigid`, `sets`, `solution`, `loads`), below them what
//! they fill — `reading` (`Bulk`, the state every reader shares) and `records` (each family's
//! raw records) — and above them `bulk` (the three passes: geometry, readers, resolve).
//!
//! Constraints as Nastran applies them: GRID PS / GRDSET always; an SPC/SPC1/SPCADD set only
//! when the case control selects it (`SPC = n`, global or in the one or chosen subcase; bare
//! bulk data selects none). Node sets: `SPC_<sid>` holds the nodes of SPC/SPC1/SPCADD set `sid`,
//! selected or not (the reference `.bdf` files write one SPC1 per named node set). Element
//! sets: `PID_<pid>` per property. CHEXA20/CPENTA15 mid-side nodes are permuted to Abaqus order
//! (Nastran lists the vertical edges before the top edges).

mod bulk;
mod bush;
mod cards;
mod case_control;
mod coord;
mod dmig;
mod elements;
mod fields;
mod genel;
mod geometry;
mod lex;
mod loads;
mod mass;
mod material_temperature;
mod properties;
mod reading;
mod records;
mod rigid;
mod scalar;
mod sets;
mod shear;
mod shell;
mod sol;
mod solution;
mod temperature;

use std::collections::BTreeMap;
use std::path::Path;

use super::error::ImportError;
use super::ImportOptions;
use crate::model::Model;

/// Card counts by card name (`GRID`, `CHEXA`, `PARAM`, …), supported or not.
pub type CardCounts = BTreeMap<String, usize>;

/// `docs/nastran-cards.md`: the catalogue of bulk data entries, PARAMs and case control
/// commands with each one's disposition (generated; a test keeps the page equal).
pub fn catalogue_markdown() -> String {
    cards::markdown()
}

/// `name` (upper case) is a bulk data entry of the catalogue (used to tell a Nastran deck by
/// its content).
pub(crate) fn is_card_name(name: &str) -> bool {
    name == "PARAM"
        || cards::bulk::CARDS
            .binary_search_by(|r| r.0.cmp(name))
            .is_ok()
}

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
