//! The Abaqus deck's ids and sets once resolved to dense indices: what every later step of the
//! resolve pass (materials, sections, boundaries, ties, thicknesses, temperatures) looks members
//! up in.

use std::collections::BTreeMap;

use super::{Parser, Target};
use crate::import::error::ImportError;
use crate::import::text::{IdMap, Loc};

/// The model's ids and sets, resolved: what every later step looks members up in.
pub(super) struct Sets {
    /// Node id → index.
    pub(super) nodes: IdMap,
    /// Element id → index.
    pub(super) elems: IdMap,
    pub(super) node_sets: BTreeMap<String, Vec<usize>>,
    pub(super) element_sets: BTreeMap<String, Vec<usize>>,
}

impl Sets {
    /// The nodes of a `*BOUNDARY`/`*RIGID BODY`/`*COUPLING` target: a node id or a node set.
    pub(super) fn target(
        &self,
        t: &Target,
        loc: Loc,
        ent: &str,
        p: &Parser,
    ) -> Result<Vec<usize>, ImportError> {
        match t {
            Target::Node(id) => self
                .nodes
                .get(*id)
                .map(|i| vec![i])
                .ok_or_else(|| p.err(loc, ent.to_owned(), format!("unknown node {id}"))),
            Target::Set(s) => self
                .node_sets
                .get(s)
                .cloned()
                .ok_or_else(|| p.err(loc, ent.to_owned(), format!("unknown node set {s}"))),
        }
    }
}
