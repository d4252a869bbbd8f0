//! The bulk data of a deck, read in three passes: the geometry cards place the nodes; every
//! other card goes through its reader in [`super::cards::CARDS`] into the raw records of its
//! family; then one resolve pass per family builds the [`Model`] (ids → indices, coordinate
//! systems → basic, WTMASS applied, the case control's selections).

use std::collections::BTreeMap;

use super::elements::ElementCards;
use super::fields::{ThruBudget, C};
use super::geometry::{CoordIndex, GeometryCards};
use super::lex::{Card, Lexer};
use super::loads::LoadCards;
use super::mass::MassCards;
use super::properties::PropertyCards;
use super::sets::SetCards;
use super::solution::SolutionCards;
use super::{cards, CardCounts};
use crate::import::error::ImportError;
use crate::import::text::{Builder, IdMap};
use crate::model::{ImportWarning, Model};

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
    /// Cards (and `PARAM,NAME`s) not interpreted, with their counts.
    pub unsupported: BTreeMap<String, usize>,
    pub elements: ElementCards<'a>,
    pub properties: PropertyCards<'a>,
    pub masses: MassCards<'a>,
    pub sets: SetCards<'a>,
    pub solution: SolutionCards<'a>,
    pub loads: LoadCards<'a>,
}

impl Bulk<'_> {
    /// Index of node `id`, named in field `k` of card `g`.
    pub(super) fn node(&self, g: &C, k: usize, id: u64) -> Result<usize, ImportError> {
        self.nodes
            .get(id)
            .ok_or_else(|| g.err(k, format!("references unknown node {id}")))
    }
}

/// Build the model from lexed cards; `subcase` picks the case-control subcase whose SPC and
/// METHOD selections apply.
pub(crate) fn build(
    lexer: Lexer,
    subcase: Option<u64>,
) -> Result<(Model, CardCounts), ImportError> {
    let Lexer {
        files,
        cards: all,
        case_lines,
        has_case_control,
        bytes,
    } = lexer;
    let case = super::case_control::parse(&case_lines, has_case_control, &files)?;
    let effective = case.effective(subcase, &files, &files[0])?;
    let mut b = Builder::new(&files[0]);
    b.files = files.clone();
    b.model.deck.title = case.title.clone();
    b.model.deck.subcase = effective.subcase;

    // Pass 1: the geometry cards place the nodes.
    let mut counts = CardCounts::new();
    let mut geometry = GeometryCards::default();
    let mut others: Vec<&Card> = Vec::new();
    for card in &all {
        *counts.entry(card.name.clone()).or_default() += 1;
        match cards::rule(&card.name) {
            Some(cards::Rule::Geometry) => geometry.take(card, &files)?,
            _ => others.push(card),
        }
    }
    let (coords, nodes) = super::geometry::place_nodes(&geometry, &files, &mut b)?;

    // Pass 2: every other card through its reader.
    let mut d = Bulk {
        files: &files,
        b,
        nodes,
        coords,
        thru: ThruBudget::for_bytes(bytes),
        unsupported: BTreeMap::new(),
        elements: ElementCards::default(),
        properties: PropertyCards::default(),
        masses: MassCards::new(),
        sets: SetCards::default(),
        solution: SolutionCards::default(),
        loads: LoadCards::default(),
    };
    for card in others {
        let g = C::new(card, &files);
        match cards::rule(&card.name) {
            Some(cards::Rule::Read(read)) => read(&mut d, &g)?,
            _ => *d.unsupported.entry(card.name.clone()).or_default() += 1,
        }
    }

    // Pass 3: resolve, family by family.
    d.b.resolve_element_nodes(&d.nodes)?;
    super::elements::check_ids(&d)?;
    let pids = super::properties::resolve(&mut d)?;
    let element_sets = super::elements::assign_properties(&mut d, &pids)?;
    super::elements::orient(&mut d)?;
    super::mass::resolve(&mut d)?;
    super::sets::resolve_spc(&mut d, &case, &effective)?;
    super::solution::resolve_method(&mut d, &effective)?;
    super::sets::resolve_dof_sets(&mut d);
    super::properties::warnings(&mut d);
    d.b.model.element_sets = element_sets;
    d.b.model.params.wtmass = d.solution.wtmass;
    for (name, n) in std::mem::take(&mut d.unsupported) {
        d.b.model.warnings.push(ImportWarning {
            file: files[0].clone(),
            message: format!("unsupported card {name} ignored ({n} cards)"),
        });
    }
    let elements = d.b.element_map()?;
    let load_sel = case.load_selections(effective.subcase);
    let mut b = d.b;
    b.model.loads =
        super::loads::resolve(&d.loads, &files, &b.model, &d.nodes, &elements, &load_sel)?;
    let load_warnings = crate::model::load::problem_warnings(&b.model.loads, &files[0]);
    b.model.warnings.extend(load_warnings);
    b.model.files = b.files.clone();
    b.record_element_sources();
    Ok((b.model, counts))
}
