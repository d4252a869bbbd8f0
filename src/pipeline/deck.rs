//! What a deck asks for, applied to a build the way its own solver would apply it (the deck's
//! defaults — mass, mode count or band, interface, title — are resolved with the rest of the
//! build's options in [`super::plan`]):
//!
//! * **held components** — a dof held by GRID PS / GRDSET or by a selected SPC set is in
//!   Nastran's s-set and so cannot be in the a-set (interface) or be a reference dof: a node
//!   given as a plain id loses its held components (one note names them); a held component
//!   given explicitly (`1:3` with PS 3) is an error that names the constraint's card and line.
//! * **constraint summary** — every applied constraint with its card, line, set and the number
//!   of dofs it holds, for the report.

use std::collections::BTreeMap;

use crate::fe::DofMap;
use crate::model::{DofMask, Model, NodeIndex};

/// The components of `node` held by the model's constraints, with the card that holds each
/// (`card id (file:line)`), in Nastran component order.
pub fn held_components(model: &Model, node: NodeIndex) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    for src in &model.constraint_sources {
        for s in &model.spcs[src.spcs.clone()] {
            if s.node != node {
                continue;
            }
            for c in s.dofs.dofs() {
                if !out.iter().any(|(k, _)| *k == c) {
                    let at = format!("{}:{}", src.file, src.line);
                    let by = match (src.permanent, src.card.strip_prefix("GRID ")) {
                        (true, Some(ps)) => format!("the PS field of {} ({ps}, {at})", src.id),
                        (true, None) => format!("{} ({at}), the default of {}", src.card, src.id),
                        (false, _) => {
                            let set = src.set.as_ref().map_or(String::new(), |s| format!(", {s}"));
                            format!("{} {} ({at}{set})", src.card, src.id)
                        }
                    };
                    out.push((c, by));
                }
            }
        }
    }
    // Constraints without a recorded source (models built in memory).
    for s in model.spcs.iter().filter(|s| s.node == node) {
        for c in s.dofs.dofs() {
            if !out.iter().any(|(k, _)| *k == c) {
                out.push((c, format!("an SPC of set {}", s.set_id)));
            }
        }
    }
    out.sort_by_key(|p| p.0);
    out
}

/// The dofs of an interface or reference node: `explicit` components (error if one is held), or
/// every free component of the node (`count` dofs) when given as a plain id. Returns the mask and
/// the dropped held components (for the note).
pub fn node_mask(
    model: &Model,
    node: NodeIndex,
    count: usize,
    explicit: Option<DofMask>,
    what: &str,
) -> Result<(DofMask, DofMask), String> {
    let held = held_components(model, node);
    let id = model.nodes[node].id;
    match explicit {
        Some(m) => {
            if let Some((c, by)) = held.iter().find(|(c, _)| m.contains(*c)) {
                let article = if what.starts_with(['a', 'e', 'i', 'o', 'u']) {
                    "an"
                } else {
                    "a"
                };
                return Err(format!(
                    "{what} {id}:{}: component {} of node {id} is held by {by}; a held dof cannot be {article} {what} dof (Nastran: a dof of the s-set is in no other set) — leave it out, or give the node as a plain id to take its free components",
                    m.digits(),
                    c + 1
                ));
            }
            Ok((m, DofMask(0)))
        }
        None => {
            let all = DofMask((1u8 << count.min(6)) - 1);
            let h = DofMask(held.iter().fold(0u8, |m, (c, _)| m | 1 << c) & all.0);
            Ok((DofMask(all.0 & !h.0), h))
        }
    }
}

/// One applied constraint (a card or a group of like cards) and how many dofs it holds.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ConstraintSummary {
    /// Card or keyword (`GRID PS=345`, `SPC1`, `*BOUNDARY`).
    pub card: String,
    /// Its id or set (`set 1`), or the first card of a group (`GRID 1`).
    pub id: String,
    /// Set name the nodes are available under, if any.
    pub set: Option<String>,
    /// File and line of the (first) card.
    pub file: String,
    /// Line.
    pub line: usize,
    /// Number of cards grouped here.
    pub cards: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Number of existing dofs held.
    pub dofs: usize,
    /// Permanent (GRID PS / GRDSET) rather than a selected set.
    pub permanent: bool,
}

/// Every applied constraint grouped by card and set (permanent ones by card and digits), with
/// the dofs it holds among those the elements give the nodes.
pub fn constraint_summary(model: &Model, dofs: &DofMap) -> Vec<ConstraintSummary> {
    let mut groups: Vec<ConstraintSummary> = Vec::new();
    let mut nodes_of: Vec<std::collections::BTreeSet<NodeIndex>> = Vec::new();
    let held = |node: NodeIndex, m: DofMask| -> usize {
        let count = dofs.count.get(node).copied().unwrap_or(0).min(6);
        (m.0 & ((1u8 << count) - 1)).count_ones() as usize
    };
    for src in &model.constraint_sources {
        let key_id = if src.permanent {
            String::new()
        } else {
            src.id.clone()
        };
        let k = match groups.iter().position(|g| {
            g.card == src.card && g.permanent == src.permanent && (src.permanent || g.id == key_id)
        }) {
            Some(k) => k,
            None => {
                groups.push(ConstraintSummary {
                    card: src.card.clone(),
                    id: src.id.clone(),
                    set: src.set.clone(),
                    file: src.file.clone(),
                    line: src.line,
                    cards: 0,
                    nodes: 0,
                    dofs: 0,
                    permanent: src.permanent,
                });
                nodes_of.push(Default::default());
                groups.len() - 1
            }
        };
        groups[k].cards += 1;
        for s in &model.spcs[src.spcs.clone()] {
            groups[k].dofs += held(s.node, s.dofs);
            nodes_of[k].insert(s.node);
        }
    }
    for (g, n) in groups.iter_mut().zip(&nodes_of) {
        g.nodes = n.len();
    }
    let covered: usize = model.constraint_sources.iter().map(|s| s.spcs.len()).sum();
    if covered < model.spcs.len() {
        // Constraints with no recorded source (models built in memory): one line.
        let mut nodes = std::collections::BTreeSet::new();
        let mut d = 0;
        let mut in_source = vec![false; model.spcs.len()];
        for src in &model.constraint_sources {
            for k in src.spcs.clone() {
                in_source[k] = true;
            }
        }
        for (s, _) in model.spcs.iter().zip(&in_source).filter(|(_, c)| !**c) {
            d += held(s.node, s.dofs);
            nodes.insert(s.node);
        }
        groups.push(ConstraintSummary {
            card: "SPC".into(),
            id: "model".into(),
            set: None,
            file: model.source.clone(),
            line: 0,
            cards: model.spcs.len() - covered,
            nodes: nodes.len(),
            dofs: d,
            permanent: false,
        });
    }
    groups
}

impl std::fmt::Display for ConstraintSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let set = self
            .set
            .as_ref()
            .map_or(String::new(), |s| format!(" ({s})"));
        let first = if self.cards > 1 {
            format!("({} cards, the first {})", self.cards, self.id)
        } else {
            self.id.clone()
        };
        write!(
            f,
            "{} {first}{set} at {}:{}: holds {} dofs at {} nodes{}",
            self.card,
            self.file,
            self.line,
            self.dofs,
            self.nodes,
            if self.permanent { " (permanent)" } else { "" }
        )
    }
}

/// `--reference-conditions` entries by name → (node, components or `None` for every free one,
/// entry): a deck's constraint set (`SPC_1`, its components per node), a node set (each node),
/// or a plain node id.
pub fn reference_entries(
    model: &Model,
    entries: &[String],
) -> Result<Vec<(NodeIndex, Option<DofMask>, String)>, String> {
    let by_id = model.node_index_by_id();
    let mut out = Vec::new();
    for e in entries {
        let find = |mut names: std::collections::btree_map::Keys<'_, String, _>| {
            names.find(|k| k.eq_ignore_ascii_case(e)).cloned()
        };
        if let Some(k) = find(model.deck.spc_sets.keys()) {
            let mut per_node: BTreeMap<NodeIndex, u8> = BTreeMap::new();
            for &(n, m) in &model.deck.spc_sets[&k] {
                *per_node.entry(n).or_default() |= m.0;
            }
            out.extend(
                per_node
                    .into_iter()
                    .map(|(n, m)| (n, Some(DofMask(m)), k.clone())),
            );
        } else if let Some(k) = model
            .node_sets
            .keys()
            .find(|k| k.eq_ignore_ascii_case(e))
            .cloned()
        {
            out.extend(model.node_sets[&k].iter().map(|&n| (n, None, k.clone())));
        } else if let Some(&n) = e.parse::<u64>().ok().and_then(|id| by_id.get(&id)) {
            out.push((n, None, e.clone()));
        } else {
            let sets: Vec<&str> = model.node_sets.keys().map(String::as_str).collect();
            return Err(format!(
                "--reference-conditions {e}: neither NODE:DOFS, a node id nor a set name of the model (sets: {})",
                if sets.is_empty() { "none".to_owned() } else { sets.join(", ") }
            ));
        }
    }
    Ok(out)
}
