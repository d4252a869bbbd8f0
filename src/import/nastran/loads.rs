//! Nastran static load cards → named scene loads ([`Load`]): FORCE, MOMENT, GRAV, PLOAD4
//! (uniform pressure on a solid face or a shell element), combined by LOAD.
//!
//! Every load set id becomes a load `LOAD_<sid>` (a LOAD combination is resolved into the
//! parts of the sets it names, scaled by S·Si, MSC QRG "LOAD"); the sets the case control
//! selects (`LOAD = n`) are marked selected, the others stay usable by name.
//! PLOAD4 signs (MSC QRG "PLOAD4"): on a solid face positive pressure acts inward; on a shell
//! along the element normal (right-hand rule over G1-G2-G3).

use std::collections::BTreeMap;

use super::case_control::Select;
use super::coord::dir_to_basic;
use super::fields::C;
use super::lex::Card;
use super::records::LoadCards;
use crate::import::error::ImportError;
use crate::import::text::IdMap;
use crate::model::load::{face_nodes, solid_faces};
use crate::model::{CoordKind, ElementKind, Load, LoadPart, Model};

/// Reader of the static load cards (FORCE, MOMENT, GRAV, PLOAD4, LOAD, and the ones the
/// scene does not read — PLOAD1, FORCE1, … — whose set is then kept by name, unusable): kept
/// for [`resolve`]. A load does not change the body.
pub(super) fn card<'a>(d: &mut super::reading::Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    d.loads.cards.push(g.card);
    Ok(())
}

/// Reader of TEMP and TEMPD: kept for a thermal preload (they change nothing else of normal
/// modes).
pub(super) fn temperature_card<'a>(
    d: &mut super::reading::Bulk<'a>,
    g: &C<'a>,
) -> Result<(), ImportError> {
    d.loads.temperatures.push(g.card);
    d.note(
        g,
        "temperatures: used only by a thermal preload (TEMP(LOAD) in the static subcase of a \
         STATSUB(PRELOAD)); normal modes have no thermal load",
    );
    Ok(())
}

/// A direction given in coordinate system `cid` (0 = basic) → basic.
fn direction(
    g: &C,
    k: usize,
    cid: i64,
    v: [f64; 3],
    model: &Model,
) -> Result<[f64; 3], ImportError> {
    if cid == 0 {
        return Ok(v);
    }
    let cs = model
        .coord_systems
        .iter()
        .find(|c| c.id as i64 == cid)
        .ok_or_else(|| g.err(k, format!("unknown coordinate system CID {cid}")))?;
    if cs.kind != CoordKind::Rectangular {
        return Err(g.err(
            k,
            format!("CID {cid} is not rectangular: load directions in cylindrical/spherical systems are not supported"),
        ));
    }
    Ok(dir_to_basic(cs, v))
}

/// The face nodes (corners in outward order, then mid-sides) of solid element `e` that PLOAD4
/// names by corner `g1` and diagonal corner `g34` (hex/prism quad face), or by `g1` and the
/// node off the face (tet), or by `g1` alone (prism triangle).
fn solid_face(
    kind: ElementKind,
    nodes: &[usize],
    g1: usize,
    g34: Option<usize>,
) -> Option<Vec<usize>> {
    let (faces, edges) = solid_faces(kind)?;
    let local = |node: usize| nodes.iter().position(|&n| n == node);
    let l1 = local(g1)?;
    let l34 = match g34 {
        Some(n) => Some(local(n)?),
        None => None,
    };
    let face = faces.iter().find(|f| {
        let at = |l: usize| f.iter().position(|&c| c == l);
        match (kind, l34) {
            (ElementKind::Tet4 | ElementKind::Tet10, Some(off)) => {
                at(l1).is_some() && at(off).is_none()
            }
            (_, Some(d)) => match (at(l1), at(d)) {
                (Some(a), Some(b)) => f.len() == 4 && (a + 2) % 4 == b,
                _ => false,
            },
            (ElementKind::Prism6 | ElementKind::Prism15, None) => f.len() == 3 && at(l1).is_some(),
            _ => false,
        }
    })?;
    face_nodes(nodes, face, edges)
}

/// The parts of one FORCE, MOMENT, GRAV or PLOAD4 card.
fn card_parts(
    g: &C,
    model: &Model,
    nodes: &IdMap,
    elements: &IdMap,
) -> Result<Vec<LoadPart>, ImportError> {
    let mut parts = Vec::new();
    let name = g.card.name.as_str();
    match name {
        "FORCE" | "MOMENT" => {
            let id = g.id(1, "G")?;
            let node = nodes
                .get(id)
                .ok_or_else(|| g.err(1, format!("references unknown node {id}")))?;
            let cid = g.int(2)?.unwrap_or(0);
            let f = g.real_or(3, 0.0)?;
            let n = [g.real_or(4, 0.0)?, g.real_or(5, 0.0)?, g.real_or(6, 0.0)?];
            let v = direction(g, 2, cid, n.map(|x| x * f), model)?;
            let mut values = [0.0; 6];
            let off = if name == "FORCE" { 0 } else { 3 };
            values[off..off + 3].copy_from_slice(&v);
            parts.push(LoadPart::Nodal { node, values });
        }
        "GRAV" => {
            let cid = g.int(1)?.unwrap_or(0);
            let a = g.real_or(2, 0.0)?;
            let n = [g.real_or(3, 0.0)?, g.real_or(4, 0.0)?, g.real_or(5, 0.0)?];
            if n == [0.0; 3] {
                return Err(g.err(3, "GRAV direction N1, N2, N3 is zero"));
            }
            if g.int(6)?.unwrap_or(0) != 0 {
                return Err(g.err(
                    6,
                    "GRAV MB ≠ 0 (main-bulk coordinate system) is not supported",
                ));
            }
            let accel = direction(g, 1, cid, n.map(|x| x * a), model)?;
            parts.push(LoadPart::Gravity { accel });
        }
        "PLOAD4" => {
            let p = g.real_or(2, 0.0)?;
            for k in 3..6 {
                if let Some(pk) = g.real(k)? {
                    if pk != p {
                        return Err(g.err(k, format!("non-uniform pressure (P{} = {pk}, P1 = {p}) is not supported; give one uniform P1", k - 1)));
                    }
                }
            }
            for k in 8..12 {
                if !g.text(k).is_empty() && g.real_or(k, 0.0)? != 0.0 {
                    return Err(g.err(k, "PLOAD4 with a load direction (CID/N1-N3) is not supported: only pressure normal to the face"));
                }
            }
            let eid = g.id(1, "EID")?;
            let thru = g.text(6).eq_ignore_ascii_case("THRU");
            let last = if thru { g.id(7, "EID2")? } else { eid };
            if last < eid || last - eid > 10_000_000 {
                return Err(g.err(7, format!("bad element range {eid} THRU {last}")));
            }
            for id in eid..=last {
                let Some(e) = elements.get(id) else {
                    if thru {
                        continue;
                    }
                    return Err(g.err(1, format!("references unknown element {id}")));
                };
                let el = &model.elements[e];
                let face_traction = match el.kind {
                        ElementKind::Quad4 | ElementKind::Tri3 => (el.nodes.clone(), p),
                        k @ (ElementKind::Tet4
                        | ElementKind::Tet10
                        | ElementKind::Hex8
                        | ElementKind::Hex8R
                        | ElementKind::Hex8Bbar
                        | ElementKind::Hex20
                        | ElementKind::Hex20R
                        | ElementKind::Prism6
                        | ElementKind::Prism15
                        | ElementKind::Pyram5
                        | ElementKind::Pyram13
                        | ElementKind::Pyram13Ansys) => {
                            if thru {
                                return Err(g.err(6, "THRU is for shell elements; a solid face needs G1 and G3/G4"));
                            }
                            let node_at = |k: usize| -> Result<Option<usize>, ImportError> {
                                if g.text(k).is_empty() {
                                    return Ok(None);
                                }
                                let id = g.id(k, "G")?;
                                nodes
                                    .get(id)
                                    .map(Some)
                                    .ok_or_else(|| g.err(k, format!("references unknown node {id}")))
                            };
                            let g1 = node_at(6)?.ok_or_else(|| {
                                g.err(6, "G1 is blank: a solid face needs G1 (and G3/G4)")
                            })?;
                            let g34 = node_at(7)?;
                            let face = solid_face(k, &el.nodes, g1, g34).ok_or_else(|| {
                                g.err(6, format!("G1/G3-G4 do not name a face of element {id} ({k:?})"))
                            })?;
                            // Positive pressure acts inward: against the outward normal.
                            (face, -p)
                        }
                        k @ (ElementKind::Beam2
                        | ElementKind::Bar2
                        | ElementKind::Beam2Linear
                        | ElementKind::Beam3Quadratic
                        | ElementKind::Beam4Cubic
                        | ElementKind::Rod2
                        | ElementKind::Beam3
                        | ElementKind::Tri6
                        | ElementKind::Quad8) => {
                            return Err(g.err(1, format!("PLOAD4 on element {id} of kind {k:?} is not supported (solids and CQUAD4/CTRIA3 shells)")))
                        }
                    };
                parts.push(LoadPart::Surface {
                    nodes: face_traction.0,
                    traction: face_traction.1,
                    element: id,
                });
            }
        }
        other => {
            return Err(g.err_card(format!(
                "{other} is not read as a scene load (FORCE, MOMENT, GRAV, PLOAD4 and LOAD are)"
            )))
        }
    }
    Ok(parts)
}

/// Resolve the load cards into named loads (module doc). `nodes`/`elements` map external ids;
/// `selected` are the case control's `LOAD =` selections.
pub(crate) fn resolve(
    cards: &LoadCards,
    files: &[String],
    model: &Model,
    nodes: &IdMap,
    elements: &IdMap,
    selected: &[Select],
) -> Result<Vec<Load>, ImportError> {
    // sid → (parts, sources)
    let mut sets: BTreeMap<u64, (Vec<LoadPart>, Vec<String>)> = BTreeMap::new();
    let mut combos: Vec<&Card> = Vec::new();
    let at = |card: &Card| {
        format!(
            "{} ({}:{})",
            card.name, files[card.loc.file as usize], card.loc.line
        )
    };
    let mut problems: BTreeMap<u64, String> = BTreeMap::new();
    for &card in &cards.cards {
        let g = C::new(card, files);
        let name = card.name.as_str();
        if name == "LOAD" {
            combos.push(card);
            continue;
        }
        let sid = g.id(0, "SID")?;
        let parts = match card_parts(&g, model, nodes, elements) {
            Ok(p) => p,
            Err(e) => {
                problems.entry(sid).or_insert_with(|| e.to_string());
                Vec::new()
            }
        };
        let entry = sets.entry(sid).or_default();
        entry.0.extend(parts);
        entry.1.push(at(card));
    }
    let mut loads: BTreeMap<u64, Load> = sets
        .iter()
        .map(|(sid, (parts, src))| {
            (
                *sid,
                Load {
                    name: format!("LOAD_{sid}"),
                    source: src.join(", "),
                    selected: false,
                    parts: parts.clone(),
                    problem: problems.get(sid).cloned(),
                },
            )
        })
        .collect();
    for card in combos {
        let g = C::new(card, files);
        let sid = g.id(0, "SID")?;
        if let Some(other) = loads.get(&sid) {
            return Err(g.err(
                0,
                format!(
                    "load set {sid} is also defined by {}: LOAD set ids must be unique",
                    other.source
                ),
            ));
        }
        let s = g.real_or(1, 1.0)?;
        let mut parts = Vec::new();
        let mut problem: Option<String> = None;
        for k in (2..card.fields.len()).step_by(2) {
            if g.text(k).is_empty() && g.text(k + 1).is_empty() {
                continue;
            }
            let si = g.real_or(k, 1.0)?;
            let li = g.id(k + 1, "Li")?;
            let (set_parts, _) = sets.get(&li).ok_or_else(|| {
                g.err(k + 1, format!("references load set {li}, which no FORCE, MOMENT, GRAV or PLOAD4 defines (a LOAD may not name another LOAD)"))
            })?;
            if let Some(p) = problems.get(&li) {
                problem.get_or_insert_with(|| p.clone());
            }
            parts.extend(Load::scaled(set_parts, s * si));
        }
        if parts.is_empty() {
            return Err(g.err_card("LOAD combines no load sets"));
        }
        loads.insert(
            sid,
            Load {
                name: format!("LOAD_{sid}"),
                source: at(card),
                selected: false,
                parts,
                problem,
            },
        );
    }
    for sel in selected {
        let load = loads.get_mut(&sel.id).ok_or_else(|| {
            sel.undefined(
                files,
                "LOAD",
                "load set",
                "FORCE, MOMENT, GRAV, PLOAD4 or LOAD",
            )
        })?;
        load.selected = true;
    }
    Ok(loads.into_values().collect())
}
