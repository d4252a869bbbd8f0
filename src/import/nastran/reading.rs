//! What every card reader shares while the bulk data is read ([`Bulk`]): the deck's files, the
//! model under construction and its node and coordinate-system maps, the `THRU` budget, the
//! notes and refusals, the lookups of grids and dofs a card names, and the raw records of each
//! card family (`records`). The readers fill it; `bulk` drives them and resolves it.

use std::collections::BTreeMap;

use super::cards;
use super::fields::{ThruBudget, C};
use super::geometry::CoordIndex;
use super::records::{
    BushCards, DmigCards, ElementCards, LoadCards, MassCards, PropertyCards, ScalarCards, SetCards,
    ShearCards, SolutionCards,
};
use crate::import::error::{ImportError, RefusedCard};
use crate::import::text::{Builder, IdMap, Loc};
use crate::model::{DofMask, NodeDof};

/// The cards noted by the catalogue: category → card key → (the row's own reason, places).
pub(super) type CategoryNotes =
    BTreeMap<cards::Category, BTreeMap<String, (Option<&'static str>, Vec<Loc>)>>;

/// What the card readers fill: the model under construction, the node map, and the raw records
/// of each card family that the resolve pass turns into the model.
pub(super) struct Bulk<'a> {
    /// Files of the deck (main file first), for messages.
    pub files: &'a [String],
    /// The model under construction (nodes placed, elements with external node ids).
    pub b: Builder,
    /// Node id → index.
    pub nodes: IdMap,
    /// Coordinate system id → index.
    pub coords: CoordIndex,
    /// How many ids `THRU` ranges may still expand to.
    pub thru: ThruBudget,
    /// Cards not read because they cannot change the body: key → (reason, places).
    pub notes: BTreeMap<String, (&'static str, Vec<Loc>)>,
    /// Cards the catalogue notes, by category: key → (own reason, places).
    pub noted: CategoryNotes,
    /// Every refused card, in deck order.
    pub refused: Vec<RefusedCard>,
    pub elements: ElementCards<'a>,
    pub properties: PropertyCards<'a>,
    pub masses: MassCards<'a>,
    pub scalars: ScalarCards<'a>,
    pub bushes: BushCards<'a>,
    pub sets: SetCards<'a>,
    pub solution: SolutionCards<'a>,
    pub loads: LoadCards<'a>,
    pub dmig: DmigCards<'a>,
    pub shear: ShearCards<'a>,
}

impl Bulk<'_> {
    /// Index of node `id`, named in field `k` of card `g`.
    pub(super) fn node(&self, g: &C, k: usize, id: u64) -> Result<usize, ImportError> {
        self.nodes
            .get(id)
            .ok_or_else(|| g.err(k, format!("references unknown node {id}")))
    }

    /// Index of grid `id`, named in field `k` of card `g`: a scalar point is an error.
    pub(super) fn grid(&self, g: &C, k: usize, id: u64) -> Result<usize, ImportError> {
        let n = self.node(g, k, id)?;
        if self.b.model.is_scalar_point(n) {
            return Err(g.err(
                k,
                format!("{id} is a scalar point (SPOINT), where a grid is needed"),
            ));
        }
        Ok(n)
    }

    /// The dof of the grid or scalar point in field `kg` with the component in field `kc`: a
    /// digit 1–6 for a grid, 0 or blank for a scalar point (`kc = None`: scalar points only).
    /// `None` when field `kg` is blank or 0 (ground).
    pub(super) fn dof(
        &self,
        g: &C,
        kg: usize,
        kc: Option<usize>,
    ) -> Result<Option<NodeDof>, ImportError> {
        let id = match g.int(kg)? {
            None | Some(0) => return Ok(None),
            Some(v) if v < 0 => return Err(g.err(kg, format!("bad grid or scalar point id {v}"))),
            Some(v) => v as u64,
        };
        let node = self.node(g, kg, id)?;
        let c = kc.map_or("", |k| g.text(k));
        let component = if self.b.model.is_scalar_point(node) {
            if !matches!(c, "" | "0") {
                return Err(g.err(
                    kc.unwrap_or(kg),
                    format!("component {c} of scalar point {id}: a scalar point has only 0"),
                ));
            }
            0
        } else {
            let Some(kc) = kc else {
                return Err(g.err(
                    kg,
                    format!(
                        "{id} is a grid; {} connects scalar points only",
                        g.card.name
                    ),
                ));
            };
            match c.as_bytes() {
                [d @ b'1'..=b'6'] => d - b'1',
                _ => {
                    return Err(g.err(
                        kc,
                        format!("component '{c}' of grid {id}: one digit 1–6 is needed"),
                    ))
                }
            }
        };
        Ok(Some(NodeDof { node, component }))
    }

    /// The components named by the digits in field `k` for `node`: Nastran digits 1–6 for a
    /// grid, 0 or blank for a scalar point (its one dof, bit 0). `nonzero`: an empty set is an
    /// error.
    pub(super) fn components(
        &self,
        g: &C,
        k: usize,
        node: usize,
        nonzero: bool,
    ) -> Result<DofMask, ImportError> {
        let text = g.text(k);
        let mask = if self.b.model.is_scalar_point(node) {
            matches!(text, "" | "0").then_some(DofMask(1))
        } else {
            DofMask::from_digits(text).filter(|m| m.0 != 0 || !nonzero)
        };
        mask.ok_or_else(|| g.err(k, "bad dof digits"))
    }

    /// Card `g` is not read because it cannot change the body, for `reason`.
    pub(super) fn note(&mut self, g: &C, reason: &'static str) {
        self.note_as(cards::key(g), g, reason);
    }

    /// A field of card `g` is not read because it cannot change the body (e.g. `PBUSH B`),
    /// noted under `key`.
    pub(super) fn note_as(&mut self, key: String, g: &C, reason: &'static str) {
        let entry = self
            .notes
            .entry(key)
            .or_insert_with(|| (reason, Vec::new()));
        entry.1.push(g.card.loc);
    }

    /// Card `g` is not read: the catalogue notes it in `category` (with its own reason).
    pub(super) fn note_in(&mut self, category: cards::Category, g: &C, why: Option<&'static str>) {
        let entry = (self.noted.entry(category).or_default())
            .entry(cards::key(g))
            .or_insert_with(|| (why, Vec::new()));
        entry.1.push(g.card.loc);
    }

    /// Card `g` is refused, for `reason`.
    pub(super) fn refuse(&mut self, g: &C, reason: impl Into<String>) {
        self.refused.push(RefusedCard {
            file: g.file.to_owned(),
            line: g.card.loc.line as usize,
            entity: if g.card.name.is_empty() {
                "(a line without a card name)".to_owned()
            } else {
                g.entity()
            },
            key: cards::key(g),
            reason: reason.into(),
        });
    }
}
