//! Constraint and dof-set cards: SPC, SPC1, SPCADD (applied when the case control selects
//! them), ASET/ASET1/BSET/BSET1 (interface dofs), QSET/QSET1 (the component-mode count).
//!
//! * `SPC SID G1 C1 D1 G2 C2 D2`; `SPC1 SID C G1 G2 … | G1 THRU G2`; `SPCADD SID S1 S2 …`.
//!   Every set becomes a node set `SPC_<sid>`, selected or not (the reference `.bdf` files
//!   write one SPC1 per named node set); only the set `SPC = n` selects is applied (MSC QRG,
//!   "Case Control": no `SPC` command, no SPC set).
//! * `ASET ID1 C1 ID2 C2 …`, `ASET1 C G1 G2 … | G1 THRU G2` (BSET, QSET alike).
//! * `MPC SID G1 C1 A1 G2 C2 A2 / – G3 C3 A3 G4 C4 A4 …`: one equation Σ Aᵢ uᵢ = 0, the first
//!   dof dependent; `MPCADD SID S1 S2 …`. Only the set `MPC = n` selects is applied; the
//!   others are a note.
//!
//! On a scalar point (SPOINT) the component is 0 or blank (its one dof).

use std::collections::BTreeMap;

use super::case_control::{CaseControl, Effective};
use super::fields::C;
use super::lex::Card;
use super::reading::Bulk;
use super::records::{SetAdd, SetCards};
use crate::import::error::ImportError;
use crate::model::{ConstraintSource, DofMask, InterfaceDofs, Mpc, Spc};

/// Reader of SPC.
pub(super) fn spc<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let sid = g.id(0, "SID")?;
    for k in [1, 4] {
        if g.text(k).is_empty() {
            continue;
        }
        let n = d.node(g, k, g.id(k, "G")?)?;
        let m = d.components(g, k + 1, n, false)?;
        if g.real_or(k + 2, 0.0)? != 0.0 {
            return Err(g.err(k + 2, "enforced displacement not supported"));
        }
        d.sets.spc.entry(sid).or_default().push((n, m, g.card));
    }
    Ok(())
}

/// Reader of SPC1 (ids of a THRU range that name no grid are skipped).
pub(super) fn spc1<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let sid = g.id(0, "SID")?;
    let thru = (2..g.card.fields.len()).any(|k| g.text(k).eq_ignore_ascii_case("THRU"));
    for (id, k) in g.id_list(2, &d.thru)? {
        match d.nodes.get(id) {
            Some(n) => {
                let m = d.components(g, 1, n, false)?;
                d.sets.spc.entry(sid).or_default().push((n, m, g.card))
            }
            None if thru => {}
            None => return Err(g.err(k, format!("references unknown node {id}"))),
        }
    }
    Ok(())
}

/// Reader of SPCADD.
pub(super) fn spcadd<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let entry = (g.id(0, "SID")?, g.id_list(1, &d.thru)?, g.card);
    d.sets.spcadd.push(entry);
    Ok(())
}

/// Reader of MPC: one equation.
pub(super) fn mpc<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let sid = g.id(0, "SID")?;
    let mut terms = Vec::new();
    // (G, C, A) at fields 1 and 4 of the first line, 9 and 12 of each continuation
    let lines = g.card.fields.len().div_ceil(8);
    for at in (0..lines).flat_map(|l| [8 * l + 1, 8 * l + 4]) {
        if g.text(at).is_empty() {
            continue;
        }
        let Some(dof) = d.dof(g, at, Some(at + 1))? else {
            return Err(g.err(at, "a term on ground (grid 0)"));
        };
        let a = g
            .real(at + 2)?
            .ok_or_else(|| g.err(at + 2, "blank coefficient"))?;
        terms.push((dof, a));
    }
    match terms.first() {
        None => return Err(g.err_card("an MPC without terms")),
        Some(&(_, 0.0)) => {
            return Err(g.err(3, "the first coefficient (of the dependent dof) is 0"))
        }
        _ => {}
    }
    d.sets.mpc.entry(sid).or_default().push((terms, g.card));
    Ok(())
}

/// Reader of MPCADD.
pub(super) fn mpcadd<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let entry = (g.id(0, "SID")?, g.id_list(1, &d.thru)?, g.card);
    d.sets.mpcadd.push(entry);
    Ok(())
}

/// Reader of ASET, BSET and QSET (pairs of grid and components).
pub(super) fn aset<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let qset = g.card.name == "QSET";
    let mut k = 0;
    while !g.text(k).is_empty() {
        let n = d.node(g, k, g.id(k, "G")?)?;
        let m = d.components(g, k + 1, n, true)?;
        d.sets.add_dofs(&mut d.b.model, qset, n, m);
        k += 2;
    }
    d.sets.count_card(&g.card.name);
    Ok(())
}

/// Reader of ASET1, BSET1 and QSET1 (components, then grids; ids of a THRU range that name no
/// grid are skipped).
pub(super) fn aset1<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let qset = g.card.name == "QSET1";
    let thru = (1..g.card.fields.len()).any(|k| g.text(k).eq_ignore_ascii_case("THRU"));
    for (id, k) in g.id_list(1, &d.thru)? {
        let n = match d.nodes.get(id) {
            Some(n) => n,
            None if thru => continue,
            None => return Err(g.err(k, format!("references unknown node {id}"))),
        };
        let m = d.components(g, 0, n, true)?;
        d.sets.add_dofs(&mut d.b.model, qset, n, m);
    }
    d.sets.count_card(&g.card.name);
    Ok(())
}

impl SetCards<'_> {
    /// Dofs of an ASET/BSET (the model's interface) or a QSET.
    fn add_dofs(
        &mut self,
        model: &mut crate::model::Model,
        qset: bool,
        node: usize,
        dofs: DofMask,
    ) {
        if qset {
            self.qset.push((node, dofs));
        } else {
            model.interface.push(InterfaceDofs { node, dofs });
        }
    }

    fn count_card(&mut self, name: &str) {
        let (key, to) = match name {
            "ASET" => ("ASET", &mut self.aset_cards),
            "ASET1" => ("ASET1", &mut self.aset_cards),
            "BSET" => ("BSET", &mut self.aset_cards),
            "BSET1" => ("BSET1", &mut self.aset_cards),
            "QSET" => ("QSET", &mut self.qset_cards),
            _ => ("QSET1", &mut self.qset_cards),
        };
        *to.entry(key).or_default() += 1;
    }
}

/// The members of every SPCADD/MPCADD of `adds` by its SID, each named set checked against
/// `defined` (`what`: SPC, MPC).
fn combinations<'a>(
    adds: &[SetAdd<'a>],
    defined: impl Fn(u64) -> bool,
    what: &str,
    files: &[String],
) -> Result<BTreeMap<u64, (Vec<u64>, &'a Card)>, ImportError> {
    let mut out: BTreeMap<u64, (Vec<u64>, &Card)> = BTreeMap::new();
    for (sid, members, card) in adds {
        let entry = out.entry(*sid).or_insert((Vec::new(), card));
        for &(s, k) in members {
            if !defined(s) {
                return Err(
                    C::new(card, files).err(k, format!("references unknown {what} set {s}"))
                );
            }
            if !entry.0.contains(&s) {
                entry.0.push(s);
            }
        }
    }
    Ok(out)
}

/// The sets a case-control selection applies: an ADD's members, or the set itself; `None`
/// without a selection. `names` = (command, what it selects, the cards defining it).
fn applied_sets(
    selection: Option<super::case_control::Select>,
    adds: &BTreeMap<u64, (Vec<u64>, &Card)>,
    defined: impl Fn(u64) -> bool,
    files: &[String],
    names: (&str, &str, &str),
) -> Result<Vec<u64>, ImportError> {
    let Some(sel) = selection else {
        return Ok(Vec::new());
    };
    match adds.get(&sel.id) {
        Some((m, _)) => Ok(m.clone()),
        None if defined(sel.id) => Ok(vec![sel.id]),
        None => Err(sel.undefined(files, names.0, names.1, names.2)),
    }
}

/// The ids of `sets` and `adds` neither applied nor selected.
fn unapplied<T>(
    sets: &BTreeMap<u64, T>,
    adds: &BTreeMap<u64, (Vec<u64>, &Card)>,
    applied: &[u64],
    selection: Option<super::case_control::Select>,
) -> Vec<u64> {
    (sets.keys().chain(adds.keys()))
        .filter(|s| !applied.contains(s) && selection.is_none_or(|x| x.id != **s))
        .copied()
        .collect()
}

/// SPC sets into node sets `SPC_<sid>` and `deck.spc_sets`; the set the case control selects
/// into `Model::spcs` with its sources; a note naming the sets that are not applied.
pub(super) fn resolve_spc(
    d: &mut Bulk,
    case: &CaseControl,
    effective: &Effective,
) -> Result<(), ImportError> {
    let files = d.files;
    let sets = &d.sets;
    let model = &mut d.b.model;
    let defined = |s: u64| sets.spc.contains_key(&s);
    let spcadd_members = combinations(&sets.spcadd, defined, "SPC", files)?;
    let nodes_of = |members: &[u64]| {
        let mut ns: Vec<usize> = (members.iter())
            .flat_map(|s| sets.spc[s].iter().map(|p| p.0))
            .collect();
        ns.sort_unstable();
        ns.dedup();
        ns
    };
    let mut node_sets = BTreeMap::new();
    for sid in sets.spc.keys() {
        node_sets.insert(format!("SPC_{sid}"), nodes_of(&[*sid]));
    }
    for (sid, (members, _)) in &spcadd_members {
        node_sets.insert(format!("SPC_{sid}"), nodes_of(members));
    }
    for (sid, list) in &sets.spc {
        model.deck.spc_sets.insert(
            format!("SPC_{sid}"),
            list.iter().map(|&(n, m, _)| (n, m)).collect(),
        );
    }
    for (sid, (members, _)) in &spcadd_members {
        let all = members
            .iter()
            .flat_map(|s| sets.spc[s].iter().map(|&(n, m, _)| (n, m)))
            .collect();
        model.deck.spc_sets.insert(format!("SPC_{sid}"), all);
    }
    let selection = effective.scope.spc;
    let names = ("SPC", "SPC set", "SPC, SPC1 or SPCADD");
    let applied = applied_sets(selection, &spcadd_members, defined, files, names)?;
    let sel_id = selection.map_or(0, |s| s.id);
    for &s in &applied {
        for &(node, dofs, card) in &sets.spc[&s] {
            let at = model.spcs.len();
            model.spcs.push(Spc {
                node,
                dofs,
                set_id: sel_id,
            });
            match model.constraint_sources.last_mut() {
                Some(last)
                    if !last.permanent
                        && last.spcs.end == at
                        && last.line == card.loc.line as usize
                        && last.file == files[card.loc.file as usize] =>
                {
                    last.spcs.end = at + 1;
                }
                _ => model.constraint_sources.push(ConstraintSource {
                    card: card.name.clone(),
                    id: if s == sel_id {
                        format!("set {s}")
                    } else {
                        format!("set {s} (SPCADD {sel_id})")
                    },
                    file: files[card.loc.file as usize].clone(),
                    line: card.loc.line as usize,
                    set: Some(format!("SPC_{s}")),
                    spcs: at..at + 1,
                    permanent: false,
                }),
            }
        }
    }
    let unselected: Vec<String> = unapplied(&sets.spc, &spcadd_members, &applied, selection)
        .iter()
        .map(|s| format!("SPC_{s}"))
        .collect();
    if !unselected.is_empty() {
        let why = if !case.present {
            "the file has no case control (bare bulk data), so no SPC set is selected".to_owned()
        } else {
            match selection {
                None => "the case control selects no SPC set (free-free)".to_owned(),
                Some(s) => format!("the case control selects SPC = {}", s.id),
            }
        };
        model.deck.notes.push(format!(
            "{}: SPC sets {} in the bulk data are not applied: {why}; their nodes are node sets of these names (for --interface / --reference-conditions)",
            files[0],
            unselected.join(", ")
        ));
    }
    model.node_sets = node_sets;
    Ok(())
}

/// The MPC set the case control selects (with an MPCADD's members) into `Model::mpcs`, with a
/// note naming its equations; a note naming the sets that are not applied.
pub(super) fn resolve_mpc(d: &mut Bulk, effective: &Effective) -> Result<(), ImportError> {
    let files = d.files;
    let sets = &d.sets;
    let defined = |s: u64| sets.mpc.contains_key(&s);
    let adds = combinations(&sets.mpcadd, defined, "MPC", files)?;
    let selection = effective.scope.mpc;
    let names = ("MPC", "MPC set", "MPC or MPCADD");
    let applied = applied_sets(selection, &adds, defined, files, names)?;
    let mut cards = Vec::new();
    for s in &applied {
        for (terms, card) in &sets.mpc[s] {
            d.b.model.mpcs.push(Mpc {
                id: *s,
                terms: terms.clone(),
            });
            cards.push(card.loc);
        }
    }
    if let Some(sel) = selection {
        d.b.model.deck.notes.push(format!(
            "MPC = {} ({}:{}) applies {}",
            sel.id,
            files[sel.loc.file as usize],
            sel.loc.line,
            crate::import::text::places("MPC", &cards, files)
        ));
    }
    let unselected: Vec<String> = unapplied(&sets.mpc, &adds, &applied, selection)
        .iter()
        .map(|s| s.to_string())
        .collect();
    if !unselected.is_empty() {
        d.b.model.deck.notes.push(format!(
            "{}: MPC sets {} in the bulk data are not applied: {}",
            files[0],
            unselected.join(", "),
            match selection {
                None => "the case control selects no MPC set".to_owned(),
                Some(s) => format!("the case control selects MPC = {}", s.id),
            }
        ));
    }
    Ok(())
}

/// The deck's interface (ASET/BSET) description and QSET mode count.
pub(super) fn resolve_dof_sets(d: &mut Bulk) {
    let sets = &d.sets;
    let model = &mut d.b.model;
    if !sets.aset_cards.is_empty() {
        let cards: Vec<String> = sets
            .aset_cards
            .iter()
            .map(|(c, n)| format!("{n} {c}"))
            .collect();
        let mut ns: Vec<usize> = model.interface.iter().map(|i| i.node).collect();
        ns.sort_unstable();
        ns.dedup();
        model.deck.interface_source = Some(format!(
            "{} ({} dofs at {} nodes)",
            cards.join(", "),
            model
                .interface
                .iter()
                .map(|i| i.dofs.0.count_ones() as usize)
                .sum::<usize>(),
            ns.len()
        ));
    }
    if !sets.qset.is_empty() {
        let cards: Vec<String> = sets
            .qset_cards
            .iter()
            .map(|(c, n)| format!("{n} {c}"))
            .collect();
        let mut per_node: BTreeMap<usize, u8> = BTreeMap::new();
        for (n, m) in &sets.qset {
            *per_node.entry(*n).or_default() |= m.0;
        }
        let q = per_node.values().map(|m| m.count_ones() as usize).sum();
        model.deck.qset_modes = Some((q, cards.join(", ")));
    }
}
