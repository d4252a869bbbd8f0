//! Geometry cards, read before every other card because they place the nodes: GRDSET (defaults
//! of the blank GRID fields), CORD2R/CORD2C/CORD2S (chained through RID) and GRID.
//!
//! * `GRID ID CP X1 X2 X3 CD PS SEID`: the position in system CP (→ basic), the displacement
//!   frame CD, the permanent single-point constraints PS (MSC QRG "GRID").
//! * `GRDSET – CP – – – CD PS SEID`: the CP, CD and PS of every GRID that leaves them blank.
//! * `CORD2R CID RID A1 A2 A3 B1 B2 B3 / C1 C2 C3`: origin A, z axis towards B, x–z plane
//!   through C, all given in system RID.
//! * `SPOINT ID1 ID2 … | ID1 THRU ID2`: scalar points, nodes with one dof and no position, in
//!   the grids' id space (MSC QRG "SPOINT"); an id listed twice is one scalar point.

use std::collections::HashMap;

use super::coord::{from_points, to_basic};
use super::fields::{ThruBudget, C};
use super::lex::Card;
use crate::import::error::ImportError;
use crate::import::text::{Builder, IdMap};
use crate::model::{ConstraintSource, CoordKind, CoordSystem, DofMask, Spc};

/// The geometry cards of a deck, gathered in the first pass.
#[derive(Default)]
pub(super) struct GeometryCards<'a> {
    pub grids: Vec<&'a Card>,
    pub coords: Vec<&'a Card>,
    pub grdset: Option<&'a Card>,
    pub spoints: Vec<&'a Card>,
    /// CELAS3/CELAS4/CMASS3/CMASS4: their S1, S2 that no GRID or SPOINT declares are scalar
    /// points all the same (MSC QRG "SPOINT" remark 2: scalar points may be defined implicitly
    /// by their use on such connection cards).
    pub scalar_users: Vec<&'a Card>,
}

impl<'a> GeometryCards<'a> {
    /// Keep a GRID, CORD2x or GRDSET card (a second GRDSET is an error).
    pub(super) fn take(&mut self, card: &'a Card, files: &[String]) -> Result<(), ImportError> {
        match card.name.as_str() {
            "GRID" => self.grids.push(card),
            "SPOINT" => self.spoints.push(card),
            "GRDSET" => {
                if let Some(first) = self.grdset {
                    return Err(C::new(card, files).err_card(format!(
                        "second GRDSET card (the first is on line {})",
                        first.loc.line
                    )));
                }
                self.grdset = Some(card);
            }
            _ => self.coords.push(card),
        }
        Ok(())
    }
}

/// Coordinate system id → index into `Model::coord_systems`.
pub(super) type CoordIndex = HashMap<i64, usize>;

/// Place the nodes: coordinate systems resolved to basic, every GRID added to `b` in its basic
/// position with its displacement frame, then the scalar points; then the node map (duplicate
/// ids are an error) and the permanent constraints of GRID PS / GRDSET PS.
pub(super) fn place_nodes(
    geom: &GeometryCards,
    files: &[String],
    thru: &ThruBudget,
    b: &mut Builder,
) -> Result<(CoordIndex, IdMap), ImportError> {
    // GRDSET: defaults for the blank CP, CD and PS fields of every GRID.
    let (cp0, cd0, ps0, gs) = match geom.grdset {
        Some(card) => {
            let g = C::new(card, files);
            let ps = if g.text(6).is_empty() {
                None
            } else {
                Some(DofMask::from_digits(g.text(6)).ok_or_else(|| g.err(6, "bad PS dof digits"))?)
            };
            (
                g.int(1)?.unwrap_or(0),
                g.int(5)?.unwrap_or(0),
                ps,
                Some(card),
            )
        }
        None => (0, 0, None, None),
    };
    let coord_index = resolve_coords(&geom.coords, files, &mut b.model.coord_systems)?;
    let mut perm_spc = Vec::new();
    let mut grid_cd = Vec::new();
    for card in &geom.grids {
        let g = C::new(card, files);
        let id = g.id(0, "ID")?;
        let cp = g.int(1)?.unwrap_or(cp0);
        let mut x = [g.real_or(2, 0.0)?, g.real_or(3, 0.0)?, g.real_or(4, 0.0)?];
        if cp != 0 {
            let cs = coord_index
                .get(&cp)
                .ok_or_else(|| g.err(1, format!("unknown coordinate system CP {cp}")))?;
            x = to_basic(&b.model.coord_systems[*cs], x);
        }
        let cd = g.int(5)?.unwrap_or(cd0);
        if cd > 0 {
            let cs = coord_index
                .get(&cd)
                .ok_or_else(|| g.err(5, format!("unknown coordinate system CD {cd}")))?;
            grid_cd.push((b.model.nodes.len(), *cs));
        }
        if !g.text(6).is_empty() {
            let m = DofMask::from_digits(g.text(6)).ok_or_else(|| g.err(6, "bad PS dof digits"))?;
            perm_spc.push((b.model.nodes.len(), m, *card));
        } else if let (Some(m), Some(gs)) = (ps0, gs) {
            perm_spc.push((b.model.nodes.len(), m, gs));
        }
        b.add_node(id, x, card.loc);
    }
    for (n, cs) in grid_cd {
        b.model.nodes[n].displacement_frame = Some(cs);
    }
    let mut spoints = std::collections::HashSet::new();
    for card in &geom.spoints {
        let g = C::new(card, files);
        for (id, _) in g.id_list(0, thru)? {
            if spoints.insert(id) {
                b.model.scalar_points.push(b.model.nodes.len());
                b.add_node(id, [0.0; 3], card.loc);
            }
        }
    }
    implicit_scalar_points(geom, files, &mut spoints, b)?;
    let nodes = b.node_map("GRID")?;
    for (n, m, card) in perm_spc {
        if m.0 == 0 {
            continue;
        }
        let at = b.model.spcs.len();
        b.model.spcs.push(Spc {
            node: n,
            dofs: m,
            set_id: 0,
        });
        b.model.constraint_sources.push(ConstraintSource {
            card: format!("{} PS={}", card.name, m.digits()),
            id: format!("GRID {}", b.model.nodes[n].id),
            file: files[card.loc.file as usize].clone(),
            line: card.loc.line as usize,
            set: None,
            spcs: at..at + 1,
            permanent: true,
        });
    }
    Ok((coord_index, nodes))
}

/// The scalar points CELAS3/CELAS4/CMASS3/CMASS4 name and no GRID or SPOINT declares, made
/// as an SPOINT would make them (after the declared ones, ascending id), with a note listing
/// them: the deck reads as if an SPOINT card declared them.
fn implicit_scalar_points(
    geom: &GeometryCards,
    files: &[String],
    spoints: &mut std::collections::HashSet<u64>,
    b: &mut Builder,
) -> Result<(), ImportError> {
    let grids: std::collections::HashSet<u64> = b.model.nodes.iter().map(|n| n.id).collect();
    let mut made: std::collections::BTreeMap<u64, crate::import::text::Loc> = Default::default();
    for card in &geom.scalar_users {
        let g = C::new(card, files);
        for k in [2, 3] {
            // a bad id is reported by the element's own reader
            let Ok(Some(id)) = g.int(k) else { continue };
            let id = id as u64;
            if id > 0 && !grids.contains(&id) && !spoints.contains(&id) {
                made.entry(id).or_insert(card.loc);
            }
        }
    }
    if made.is_empty() {
        return Ok(());
    }
    let list: Vec<String> = made.keys().map(u64::to_string).collect();
    for (&id, &loc) in &made {
        spoints.insert(id);
        b.model.scalar_points.push(b.model.nodes.len());
        b.add_node(id, [0.0; 3], loc);
    }
    b.model.deck.notes.push(format!(
        "scalar points {} declared by no SPOINT: made from their CELAS3/CELAS4/CMASS3/CMASS4, as \
         MSC Nastran defines scalar points implicitly (QRG SPOINT)",
        list.join(", ")
    ));
    Ok(())
}

/// Resolve CORD2R/C/S chains into `out`; returns CID → index. Errors: unknown RID, cycles,
/// duplicate CID, degenerate points.
fn resolve_coords(
    cards: &[&Card],
    files: &[String],
    out: &mut Vec<CoordSystem>,
) -> Result<CoordIndex, ImportError> {
    let mut by_id: HashMap<i64, usize> = HashMap::new();
    for (k, card) in cards.iter().enumerate() {
        let g = C::new(card, files);
        let cid = g.req_int(0, "CID")?;
        if cid <= 0 {
            return Err(g.err(0, "CID must be > 0"));
        }
        if by_id.insert(cid, k).is_some() {
            return Err(g.err(0, "duplicate coordinate system id"));
        }
    }
    let mut index: CoordIndex = HashMap::new();
    for start in 0..cards.len() {
        let mut chain = vec![start];
        // Walk down to a resolved system or the basic frame.
        loop {
            let g = C::new(cards[*chain.last().unwrap_or(&start)], files);
            let rid = g.int(1)?.unwrap_or(0);
            if rid == 0 || index.contains_key(&rid) {
                break;
            }
            let next = *by_id.get(&rid).ok_or_else(|| {
                g.err(1, format!("unknown reference coordinate system RID {rid}"))
            })?;
            if chain.contains(&next) {
                return Err(g.err(1, format!("cycle of coordinate systems through RID {rid}")));
            }
            chain.push(next);
        }
        for &k in chain.iter().rev() {
            let card = cards[k];
            let g = C::new(card, files);
            let cid = g.req_int(0, "CID")?;
            if index.contains_key(&cid) {
                continue;
            }
            let rid = g.int(1)?.unwrap_or(0);
            let mut p = [[0.0; 3]; 3];
            for (i, pt) in p.iter_mut().enumerate() {
                for (d, v) in pt.iter_mut().enumerate() {
                    *v = g.real_or(2 + 3 * i + d, 0.0)?;
                }
            }
            if rid != 0 {
                let r = &out[index[&rid]];
                p = p.map(|q| to_basic(r, q));
            }
            let kind = match card.name.as_str() {
                "CORD2R" => CoordKind::Rectangular,
                "CORD2C" => CoordKind::Cylindrical,
                _ => CoordKind::Spherical,
            };
            let cs = from_points(cid as u64, kind, p[0], p[1], p[2])
                .ok_or_else(|| g.err_card("degenerate points A, B, C"))?;
            out.push(cs);
            index.insert(cid, out.len() - 1);
        }
    }
    Ok(index)
}
