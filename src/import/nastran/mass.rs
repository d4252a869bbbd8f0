//! Concentrated mass cards and their resolution to the basic frame with WTMASS.
//!
//! * `CONM2 EID G CID M X1 X2 X3 – / I11 I21 I22 I31 I32 I33`: mass M with its centre of
//!   gravity offset X from G (CID = −1: X is the basic position of the centre of gravity) and
//!   the inertia tensor about the centre of gravity, in CID (MSC QRG "CONM2").

use super::bulk::Bulk;
use super::coord::dir_to_basic;
use super::fields::C;
use super::lex::Card;
use crate::import::error::ImportError;
use crate::model::{CoordKind, PointMass};

/// The raw records of the mass cards: (point mass with CID-frame offset and inertia, CID, card).
pub(super) type MassCards<'a> = Vec<(PointMass, i64, &'a Card)>;

/// Reader of CONM2.
pub(super) fn conm2<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.other_ids.push((eid, g.card));
    let n = d.node(g, 1, g.id(1, "G")?)?;
    let cid = g.int(2)?.unwrap_or(0);
    let m = g.real_or(3, 0.0)?;
    let x = [g.real_or(4, 0.0)?, g.real_or(5, 0.0)?, g.real_or(6, 0.0)?];
    let mut i = [0.0; 6];
    for (k, v) in i.iter_mut().enumerate() {
        *v = g.real_or(8 + k, 0.0)?;
    }
    let [i11, i21, i22, i31, i32, i33] = i;
    // Nastran CONM2 tensor: [I11 −I21 −I31; −I21 I22 −I32; −I31 −I32 I33].
    let inertia = [[i11, -i21, -i31], [-i21, i22, -i32], [-i31, -i32, i33]];
    d.masses.push((
        PointMass {
            id: eid,
            node: n,
            mass: m,
            offset: x,
            inertia,
        },
        cid,
        g.card,
    ));
    Ok(())
}

/// Point masses into the model: offsets and inertia to basic, WTMASS applied.
pub(super) fn resolve(d: &mut Bulk) -> Result<(), ImportError> {
    let wtmass = d.solution.wtmass;
    let model = &mut d.b.model;
    for (mut pm, cid, card) in std::mem::take(&mut d.masses) {
        let g = C::new(card, d.files);
        match cid {
            -1 => {
                let xn = model.nodes[pm.node].x;
                pm.offset = [
                    pm.offset[0] - xn[0],
                    pm.offset[1] - xn[1],
                    pm.offset[2] - xn[2],
                ];
            }
            0 => {}
            _ => {
                let cs = &model.coord_systems[*d
                    .coords
                    .get(&cid)
                    .ok_or_else(|| g.err(2, format!("unknown coordinate system CID {cid}")))?];
                if cs.kind != CoordKind::Rectangular {
                    return Err(g.err(2, "CONM2 in a non-rectangular system not supported"));
                }
                pm.offset = dir_to_basic(cs, pm.offset);
                // I_basic = Aᵀ I A with A's rows the local axes.
                let a = cs.axes;
                let mut ib = [[0.0; 3]; 3];
                for (i, row) in ib.iter_mut().enumerate() {
                    for (j, v) in row.iter_mut().enumerate() {
                        *v = (0..3)
                            .flat_map(|p| (0..3).map(move |q| (p, q)))
                            .map(|(p, q)| a[p][i] * pm.inertia[p][q] * a[q][j])
                            .sum();
                    }
                }
                pm.inertia = ib;
            }
        }
        pm.mass *= wtmass;
        pm.inertia = pm.inertia.map(|r| r.map(|v| v * wtmass));
        model.point_masses.push(pm);
    }
    Ok(())
}
