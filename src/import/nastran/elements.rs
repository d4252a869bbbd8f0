//! Structural element cards — CTETRA, CHEXA, CPENTA, CBAR, CBEAM, CROD, CQUAD4, CTRIA3, CQUAD8,
//! CTRIA6 — and
//! their resolution: one element id space, the property of every element, bar/beam orientation.
//!
//! * `CTETRA/CHEXA/CPENTA EID PID G1 …`: 4/10, 8/20, 6/15 nodes. CHEXA20/CPENTA15 mid-side
//!   nodes are permuted to Abaqus order (Nastran lists the vertical edges before the top edges).
//! * `CBAR/CBEAM EID PID GA GB X1/G0 X2 X3`: the orientation vector v from GA, or towards grid
//!   G0; X1–X3 are in the displacement frame of GA (MSC QRG "CBAR").
//! * `CPYRAM EID PID G1 … G5 G6 … G13`: 5 or 13 nodes (base, apex, mid-sides 1-2 2-3 3-4 4-1
//!   1-5 2-5 3-5 4-5), with a PSOLID.
//! * `CROD EID PID G1 G2`; `CQUAD4/CTRIA3 EID PID G1 …`, `CQUAD8/CTRIA6 EID PID G1 … G8/G6`
//!   (a blank mid-side grid makes its edge straight, `shell::blank_midsides`; thickness
//!   fields: `shell`).
//! * `CONROD EID G1 G2 MID A J C NSM`: a rod with its property on the card (as CROD + PROD).

use std::collections::BTreeMap;

use super::coord::dir_to_basic;
use super::fields::C;
use super::lex::Card;
use super::reading::Bulk;
use super::records::{ElementProperty, Orientation};
use crate::import::error::{parse_err, ImportError};
use crate::import::text::{IdMap, Loc};
use crate::model::{CoordKind, ElementKind, Property, Section};

use ElementKind::*;
/// An element card: its name, how many node fields it has, its kind by node count.
type ElementCard = (&'static str, usize, &'static [(usize, ElementKind)]);
/// The element cards.
const ELEMENTS: &[ElementCard] = &[
    ("CTETRA", 10, &[(4, Tet4), (10, Tet10)]),
    ("CHEXA", 20, &[(8, Hex8), (20, Hex20)]),
    ("CPENTA", 15, &[(6, Prism6), (15, Prism15)]),
    ("CPYRAM", 13, &[(5, Pyram5), (13, Pyram13)]),
    ("CBAR", 2, &[(2, Bar2)]),
    ("CBEAM", 2, &[(2, Beam2)]),
    ("CROD", 2, &[(2, Rod2)]),
    ("CTUBE", 2, &[(2, Rod2)]),
    ("CQUAD4", 4, &[(4, Quad4)]),
    ("CQUADR", 4, &[(4, Quad4)]),
    ("CTRIAR", 3, &[(3, Tri3)]),
    ("CTRIA3", 3, &[(3, Tri3)]),
    ("CQUAD8", 8, &[(8, Quad8)]),
    ("CTRIA6", 6, &[(6, Tri6)]),
];

/// Reader of BAROR and BEAMOR (MSC QRG "BAROR": `BAROR – PID – – X1/G0 X2 X3 OFFT`): the
/// PID, orientation (X1–X3 or G0, taken together when X1/G0 is blank) and OFFT of every CBAR
/// (BEAMOR: CBEAM) that leaves them blank. One of each per deck.
pub(super) fn orientation_defaults<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let slot = usize::from(g.card.name == "BEAMOR");
    if let Some(first) = d.elements.bar_defaults[slot] {
        return Err(g.err_card(format!(
            "second {} card (the first is on line {}): only one may appear",
            g.card.name, first.loc.line
        )));
    }
    if g.int(1)?.is_some_and(|p| p <= 0) {
        return Err(g.err(1, "bad property id"));
    }
    d.elements.bar_defaults[slot] = Some(g.card);
    Ok(())
}

/// A CBAR/CBEAM card with its blank PID, X1–X3/G0 and OFFT fields taken from the BAROR /
/// BEAMOR (`None`: no default applies).
fn with_defaults(d: &Bulk, g: &C) -> Option<Card> {
    let slot = match g.card.name.as_str() {
        "CBAR" => 0,
        "CBEAM" => 1,
        _ => return None,
    };
    let defaults = d.elements.bar_defaults[slot]?;
    let mut card = g.card.clone();
    let blank = |c: &Card, k: usize| c.fields.get(k).is_none_or(|f| f.text.is_empty());
    let mut take: Vec<usize> = Vec::new();
    if blank(g.card, 1) {
        take.push(1);
    }
    if (4..7).all(|k| blank(g.card, k)) {
        take.extend(4..7);
    }
    if blank(g.card, 7) {
        take.push(7);
    }
    take.retain(|&k| !blank(defaults, k));
    if take.is_empty() {
        return None;
    }
    let line = g.card.loc.line;
    for k in take {
        if card.fields.len() <= k {
            card.fields.resize_with(k + 1, || super::lex::Field {
                text: String::new(),
                line,
            });
        }
        card.fields[k].text = defaults.fields[k].text.clone();
    }
    Some(card)
}

/// Reader of the structural element cards (module doc).
pub(super) fn element<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let filled = with_defaults(d, g);
    let filled = filled.as_ref().map(|c| C::new(c, d.files));
    let g: &C = filled.as_ref().unwrap_or(g);
    if old_orientation_flag(g).is_some() {
        d.note_as(
            format!("{} field 9 = 1 or 2", g.card.name),
            g,
            "as OFFT: it is the orientation flag F of older decks (NASTRAN-95: 1 = X1–X3 \
             given, 2 = G0 given), read as that flag, and OFFT takes its default GGG",
        );
    }
    let (name, kind, ids, o, blank) = parse(g)?;
    let eid = g.id(0, "EID")?;
    let pid = match g.int(1)? {
        Some(p) if p > 0 => p as u64,
        Some(_) => return Err(g.err(1, "bad property id")),
        None => eid,
    };
    let k = d.b.model.elements.len();
    if !blank.is_empty() {
        d.elements.blank_midsides.push((k, blank, g.card.loc));
    }
    if let Some(o) = o {
        d.elements.orient.push((k, o, g.card.loc));
    }
    if matches!(name, "CQUADR" | "CTRIAR") {
        // the CQUAD4/CTRIA3 plate with a drilling membrane (`fe::elements::drill_membrane`)
        d.b.model.drilling_membranes.insert(k);
    }
    if matches!(
        name,
        "CQUAD4" | "CTRIA3" | "CQUAD8" | "CTRIA6" | "CQUADR" | "CTRIAR"
    ) {
        d.elements
            .shell_t
            .extend(super::shell::element_fields(g, k)?);
        let offset = super::shell::element_offset(g, k)?;
        d.elements
            .shell_offsets
            .extend(offset.map(|o| (o, g.card.loc)));
        d.elements
            .shell_axes
            .extend(super::shell::element_axis(g, k)?);
    }
    if matches!(kind, Bar2 | Beam2) {
        if let Some(w) = offsets(g, name)? {
            d.elements.offsets.push((k, w, g.card.loc));
        }
        let pins = [pin_flags(g, 8)?, pin_flags(g, 9)?];
        if pins.iter().any(|p| p.0 != 0) {
            d.b.model.beam_pins.insert(k, pins);
        }
    }
    d.b.add_element(eid, kind, ids, None, name, g.card.loc);
    d.elements.pid.push((ElementProperty::Id(pid), g.card.loc));
    Ok(())
}

/// Reader of CONROD.
pub(super) fn conrod<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    let mut ids = Vec::with_capacity(2);
    for k in [1, 2] {
        match g.int(k)? {
            Some(v) if v > 0 => ids.push(v as usize),
            _ => return Err(g.err(k, "a CONROD needs grids G1 and G2")),
        }
    }
    let mid = g.id(3, "MID")?;
    let section = Section::Rod {
        area: g.real_or(4, 0.0)?,
        j: g.real_or(5, 0.0)?,
        nsm: g.real_or(7, 0.0)?,
    };
    d.b.add_element(eid, Rod2, ids, None, "CONROD", g.card.loc);
    d.elements
        .pid
        .push((ElementProperty::Rod { mid, section }, g.card.loc));
    Ok(())
}

/// An element card read: card name, kind, external node ids in Abaqus order, orientation,
/// the slots of blank CQUAD8/CTRIA6 mid-side grids.
type Parsed = (
    &'static str,
    ElementKind,
    Vec<usize>,
    Option<Orientation>,
    Vec<usize>,
);

/// Element card → [`Parsed`].
fn parse(g: &C) -> Result<Parsed, ImportError> {
    let &(name, range, kinds) = ELEMENTS
        .iter()
        .find(|e| e.0 == g.card.name)
        .ok_or_else(|| g.err_card("not an element card"))?;
    let mut ids = Vec::with_capacity(range);
    let mut last = 0;
    // CQUAD8/CTRIA6: a blank mid-side grid makes its edge straight (`shell::blank_midsides`)
    let corners = match name {
        "CQUAD8" => 4,
        "CTRIA6" => 3,
        _ => range,
    };
    let mut blank = Vec::new();
    for k in 2..2 + range {
        if let Some(v) = g.int(k)? {
            if v <= 0 {
                return Err(g.err(k, format!("bad node id {v}")));
            }
            while ids.len() < k - 2 && ids.len() >= corners {
                // a blank mid-side grid before this one: its edge's first corner holds the slot
                blank.push(ids.len());
                ids.push(ids[ids.len() - corners]);
            }
            if ids.len() != k - 2 {
                return Err(g.err(
                    k,
                    "blank node field before a given node (only CQUAD8/CTRIA6 mid-side grids may be blank)",
                ));
            }
            ids.push(v as usize);
            last = k;
        }
    }
    if ids.len() >= corners && ids.len() < range && corners < range {
        while ids.len() < range {
            blank.push(ids.len());
            ids.push(ids[ids.len() - corners]);
        }
    }
    let Some(&(_, kind)) = kinds.iter().find(|(n, _)| *n == ids.len()) else {
        let want: Vec<String> = kinds.iter().map(|k| k.0.to_string()).collect();
        return Err(g.err(
            last.max(2),
            format!(
                "{name} needs {} nodes, has {} (missing continuation line?)",
                want.join(" or "),
                ids.len()
            ),
        ));
    };
    // Nastran CHEXA20 / CPENTA15: vertical edges before top edges; Abaqus: top edges first.
    if kind == Hex20 {
        ids = [&ids[..12], &ids[16..20], &ids[12..16]].concat();
    } else if kind == Prism15 {
        ids = [&ids[..9], &ids[12..15], &ids[9..12]].concat();
    }
    let orientation = if kind == Beam2 || kind == Bar2 {
        unsupported_bar_fields(g, name)?;
        let s = g.text(4);
        if s.is_empty() {
            return Err(g.err(
                4,
                format!(
                    "orientation X1/G0 is blank, and no {} gives it",
                    if name == "CBAR" { "BAROR" } else { "BEAMOR" }
                ),
            ));
        }
        let integer = !s.contains('.') && !s.contains(['e', 'E']);
        if old_orientation_flag(g) == Some(2) || (integer && old_orientation_flag(g).is_none()) {
            Some(Orientation::Node(g.id(4, "G0")?))
        } else {
            let v = [g.real_or(4, 0.0)?, g.real_or(5, 0.0)?, g.real_or(6, 0.0)?];
            Some(match offt(g, name)?[0] {
                b'B' => Orientation::Basic(v),
                _ => Orientation::Vector(v),
            })
        }
    } else {
        None
    };
    Ok((name, kind, ids, orientation, blank))
}

/// The integer 1 or 2 that older decks carry in CBAR/CBEAM field 9 (NASTRAN-95 "F": 1 the
/// orientation is X1–X3, 2 it is grid G0), where OFFT (or CBEAM's real BIT) now stands.
fn old_orientation_flag(g: &C) -> Option<u8> {
    match g.text(7) {
        "1" => Some(1),
        "2" => Some(2),
        _ => None,
    }
}

/// OFFT (CBAR/CBEAM field 9; MSC QRG CBAR Remark 8): the frames of the orientation vector (G
/// the displacement frame of GA, the default, or B basic) and of the offsets at end A and end
/// B (G the displacement frame of GA resp. GB, or O the element frame); default GGG. A code
/// not in the QRG's list is an error.
fn offt(g: &C, name: &str) -> Result<[u8; 3], ImportError> {
    let t = g.text(7).to_ascii_uppercase();
    if t.is_empty()
        || old_orientation_flag(g).is_some()
        || (name == "CBEAM" && !t.bytes().any(|b| b.is_ascii_alphabetic()))
    {
        return Ok(*b"GGG");
    }
    const CODES: [&str; 8] = ["GGG", "BGG", "GGO", "BGO", "GOG", "BOG", "GOO", "BOO"];
    if !CODES.contains(&t.as_str()) {
        return Err(g.err(
            7,
            format!(
                "OFFT {t}: one of {} expected (or, in an older deck, the orientation flag 1 or 2)",
                CODES.join(", ")
            ),
        ));
    }
    let b = t.as_bytes();
    Ok([b[0], b[1], b[2]])
}

/// Offsets WA, WB (fields W1A…W3B) when nonzero, with their OFFT frames checked: G (the
/// grids' displacement frames, resolved in `orient`) is honoured, O (element frame) is an
/// error naming the field.
fn offsets(g: &C, name: &str) -> Result<Option<[[f64; 3]; 2]>, ImportError> {
    let mut w = [[0.0; 3]; 2];
    for (i, x) in w.iter_mut().flatten().enumerate() {
        *x = g.real_or(10 + i, 0.0)?;
    }
    if w.iter().flatten().all(|&x| x == 0.0) {
        return Ok(None);
    }
    let letters = offt(g, name)?;
    for (end, wk) in w.iter().enumerate() {
        if letters[1 + end] == b'O' && wk.iter().any(|&x| x != 0.0) {
            return Err(g.err(
                7,
                format!(
                    "offset of end {} in the element frame (OFFT {}) is not implemented (G: the grid's frame)",
                    if end == 0 { 'A' } else { 'B' },
                    g.text(7)
                ),
            ));
        }
    }
    Ok(Some(w))
}

/// Pin flags PA or PB in field `k`: the element-frame dofs released at that end (digits
/// 1–6; blank or 0 none).
fn pin_flags(g: &C, k: usize) -> Result<crate::model::DofMask, ImportError> {
    let t = g.text(k);
    if t.is_empty() || t == "0" {
        return Ok(crate::model::DofMask(0));
    }
    crate::model::DofMask::from_digits(t)
        .ok_or_else(|| g.err(k, format!("pin flags {t}: digits 1–6 expected")))
}

/// CBAR/CBEAM fields after the orientation that change the element and are not implemented:
/// CBEAM's built-in twist BIT (the real in OFFT's place) and warping scalar points SA/SB: each
/// nonzero one is an error naming it.
fn unsupported_bar_fields(g: &C, name: &str) -> Result<(), ImportError> {
    let f8 = g.text(7);
    let bit = name == "CBEAM"
        && !f8.is_empty()
        && old_orientation_flag(g).is_none()
        && !f8.bytes().any(|b| b.is_ascii_alphabetic());
    if bit && g.real(7)?.is_some_and(|v| v != 0.0) {
        return Err(g.err(7, "built-in twist BIT is not implemented"));
    }
    if name == "CBEAM" {
        for (k, what) in [(16, "SA"), (17, "SB")] {
            if g.int(k)?.is_some_and(|v| v != 0) {
                return Err(g.err(k, format!("warping scalar point {what} is not implemented")));
            }
        }
    }
    Ok(())
}

/// A structural element on a scalar point is an error naming its card and the point.
pub(super) fn no_scalar_points(d: &Bulk) -> Result<(), ImportError> {
    let b = &d.b;
    if b.model.scalar_points.is_empty() {
        return Ok(());
    }
    for (k, e) in b.model.elements.iter().enumerate() {
        if let Some(&n) = e.nodes.iter().find(|&&n| b.model.is_scalar_point(n)) {
            return Err(b.err(
                b.elem_loc[k],
                format!("{} {}", b.elem_card[k], e.id),
                format!(
                    "node {} is a scalar point (SPOINT), where a grid is needed",
                    b.model.nodes[n].id
                ),
            ));
        }
    }
    Ok(())
}

/// Element ids: structural, mass and spring elements share one id space (MSC/NX Nastran);
/// rigid elements are unique among themselves. A rigid element with the id of another element
/// is a warning naming both lines: MSC Nastran keeps the two apart and runs such a deck.
pub(super) fn check_ids(d: &mut Bulk) -> Result<(), ImportError> {
    let b = &d.b;
    fn at<'c>(&(id, c): &(u64, &'c Card)) -> (u64, &'c str, Loc) {
        (id, c.name.as_str(), c.loc)
    }
    let eids: Vec<(u64, &str, Loc)> = (b.model.elements.iter().enumerate())
        .map(|(k, e)| (e.id, b.elem_card[k], b.elem_loc[k]))
        .chain(d.elements.other_ids.iter().map(at))
        .collect();
    unique_ids(
        &eids,
        d.files,
        "element id",
        "elements and concentrated masses share one id space",
    )?;
    let rigid: Vec<(u64, &str, Loc)> = d.elements.rigid_ids.iter().map(at).collect();
    unique_ids(
        &rigid,
        d.files,
        "rigid element id",
        "rigid elements share one id space",
    )?;
    let by_id: std::collections::HashMap<u64, (&str, Loc)> =
        eids.iter().map(|&(id, c, l)| (id, (c, l))).collect();
    let place = |l: Loc| format!("{}:{}", d.files[l.file as usize], l.line);
    let mut warnings = Vec::new();
    for &(id, card, loc) in &rigid {
        if let Some(&(other, oloc)) = by_id.get(&id) {
            warnings.push(crate::model::ImportWarning {
                file: place(loc),
                message: format!(
                    "{card} {id} has the id of {other} {id} ({}): MSC Nastran keeps rigid \
                     elements apart from the others and runs the deck; both are kept",
                    place(oloc)
                ),
            });
        }
    }
    d.b.model.warnings.extend(warnings);
    Ok(())
}

/// Give every element its property (`pids`: property id → index of the structural
/// properties; `mids`: material id → index). A CONROD gets a property of its own (one per
/// distinct material and section, named after the first CONROD that has it). Returns the
/// element sets `PID_<pid>`.
pub(super) fn assign_properties(
    d: &mut Bulk,
    pids: &IdMap,
    mids: &IdMap,
) -> Result<BTreeMap<String, Vec<usize>>, ImportError> {
    let (b, wtmass) = (&mut d.b, d.solution.wtmass);
    let mut element_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    let mut rods: Vec<(u64, Section, usize)> = Vec::new();
    for (k, (property, loc)) in d.elements.pid.iter().enumerate() {
        let entity = || format!("{} {}", b.elem_card[k], b.model.elements[k].id);
        let fail = |msg: String| {
            parse_err(
                &d.files[loc.file as usize],
                loc.line as usize,
                entity(),
                msg,
            )
        };
        let p = match property {
            ElementProperty::Id(pid) => {
                let Some(p) = pids.get(*pid) else {
                    let other = d.properties.others.iter().find(|o| o.0 == *pid);
                    return Err(fail(match other {
                        Some((_, c)) => format!(
                            "references property {pid}, a {} ({}:{}) of another element family",
                            c.name, d.files[c.loc.file as usize], c.loc.line
                        ),
                        None => format!("references unknown property {pid}"),
                    }));
                };
                element_sets
                    .entry(format!("PID_{pid}"))
                    .or_default()
                    .push(k);
                p
            }
            ElementProperty::Rod { mid, section } => {
                let material = mids
                    .get(*mid)
                    .ok_or_else(|| fail(format!("references unknown material {mid}")))?;
                let mut section = section.clone();
                if let Section::Rod { nsm, .. } = &mut section {
                    *nsm *= wtmass;
                }
                match rods.iter().find(|r| r.0 == *mid && r.1 == section) {
                    Some(r) => r.2,
                    None => {
                        let eid = b.model.elements[k].id;
                        b.model.properties.push(Property {
                            id: eid,
                            name: format!("CONROD {eid}"),
                            material,
                            section: section.clone(),
                        });
                        rods.push((*mid, section, b.model.properties.len() - 1));
                        b.model.properties.len() - 1
                    }
                }
            }
        };
        b.model.elements[k].property = Some(p);
    }
    super::shell::apply_thickness(&mut b.model, &d.elements.shell_t)?;
    super::shell::apply_axes(&mut b.model, &d.elements.shell_axes)?;
    Ok(element_sets)
}

/// Bar/beam orientation vectors to basic: X1–X3 from GA's displacement frame, or towards G0.
pub(super) fn orient(d: &mut Bulk) -> Result<(), ImportError> {
    let b = &mut d.b;
    for (k, o, loc) in std::mem::take(&mut d.elements.orient) {
        let e = &b.model.elements[k];
        let ga = e.nodes[0];
        let v = match o {
            Orientation::Basic(v) => v,
            Orientation::Vector(v) => match b.model.nodes[ga].displacement_frame {
                Some(cs) if b.model.coord_systems[cs].kind == CoordKind::Rectangular => {
                    dir_to_basic(&b.model.coord_systems[cs], v)
                }
                _ => v,
            },
            Orientation::Node(g0) => {
                let n0 = d.nodes.get(g0).ok_or_else(|| {
                    parse_err(
                        b.file_name(loc),
                        loc.line as usize,
                        format!("{} {}", b.elem_card[k], e.id),
                        format!("orientation node G0 {g0} unknown"),
                    )
                })?;
                let (x0, xa) = (b.model.nodes[n0].x, b.model.nodes[ga].x);
                [x0[0] - xa[0], x0[1] - xa[1], x0[2] - xa[2]]
            }
        };
        b.model.elements[k].orientation = Some(v);
    }
    for (k, w, loc) in std::mem::take(&mut d.elements.offsets) {
        let e = &b.model.elements[k];
        let mut basic = w;
        for (end, wb) in basic.iter_mut().enumerate() {
            match b.model.nodes[e.nodes[end]].displacement_frame {
                Some(cs) if b.model.coord_systems[cs].kind == CoordKind::Rectangular => {
                    *wb = dir_to_basic(&b.model.coord_systems[cs], *wb)
                }
                Some(_) => {
                    return Err(parse_err(
                        b.file_name(loc),
                        loc.line as usize,
                        format!("{} {}", b.elem_card[k], e.id),
                        "offset at a grid whose displacement frame is cylindrical or spherical \
                         is not implemented",
                    ))
                }
                None => {}
            }
        }
        b.model.beam_offsets.insert(k, basic);
    }
    Ok(())
}

/// Fail on the first id of `items` (id, card name, location) seen twice, naming both places.
pub(super) fn unique_ids(
    items: &[(u64, &str, Loc)],
    files: &[String],
    what: &str,
    rule: &str,
) -> Result<(), ImportError> {
    IdMap::build(items.iter().map(|i| i.0))
        .map(|_| ())
        .map_err(|(a, k)| {
            let ((id, card, loc), (_, first, floc)) = (items[k], items[a]);
            parse_err(
                &files[loc.file as usize],
                loc.line as usize,
                format!("{card} {id}"),
                format!(
                    "duplicate {what} {id}: also {first} {id} at {}:{} ({rule})",
                    files[floc.file as usize], floc.line
                ),
            )
        })
}
