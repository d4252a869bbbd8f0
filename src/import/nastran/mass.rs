//! Concentrated mass cards and their resolution to the basic frame with WTMASS.
//!
//! * `CONM2 EID G CID M X1 X2 X3 – / I11 I21 I22 I31 I32 I33`: mass M with its centre of
//!   gravity offset X from G (CID = −1: X is the basic position of the centre of gravity) and
//!   the inertia tensor about the centre of gravity, in CID (MSC QRG "CONM2").
//! * `CONM1 EID G CID M11 M21 M22 M31 M32 M33 / M41 … M66`: the lower triangle of a 6×6 mass
//!   matrix on G's `[u θ]` in system CID (0 or blank: basic; MSC QRG "CONM1"). It is read as the
//!   rigid point mass it describes, M = [m I, −m ẽ; m ẽ, I_cg − m ẽẽ] (`fe::mass`): m from the
//!   translational block, which must be m·I, the centre of gravity offset e from the skew
//!   coupling block, I_cg = M₂₂ + m ẽẽ. A 6×6 matrix of another form (a direction-dependent
//!   translational mass, a non-skew coupling) is refused: one mass point per node has no place
//!   for it.

// Index loops mirror the subscripts of the 6×6 mass matrix.
#![allow(clippy::needless_range_loop)]

use super::coord::dir_to_basic;
use super::fields::C;
use super::reading::Bulk;
use crate::import::error::ImportError;
use crate::model::{CoordKind, PointMass};

/// Reader of CONM2.
pub(super) fn conm2<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.other_ids.push((eid, g.card));
    let n = d.grid(g, 1, g.id(1, "G")?)?;
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
    d.masses.conm2.push((
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

/// Reader of CONM1.
pub(super) fn conm1<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.other_ids.push((eid, g.card));
    let n = d.grid(g, 1, g.id(1, "G")?)?;
    let cid = g.int(2)?.unwrap_or(0);
    if cid < 0 {
        return Err(g.err(2, format!("bad coordinate system id CID {cid}")));
    }
    // The lower triangle row by row, M11 M21 M22 M31 M32 | M33 M41 … M53 | M54 … M66: one
    // sequence of data fields from field 3 on.
    let mut m = [[0.0; 6]; 6];
    let mut k = 3;
    for i in 0..6 {
        for j in 0..=i {
            m[i][j] = g.real_or(k, 0.0)?;
            m[j][i] = m[i][j];
            k += 1;
        }
    }
    d.masses.conm1.push((eid, n, cid, m, g.card));
    Ok(())
}

/// The rigid point mass a 6×6 CONM1 matrix (basic frame) describes (module doc), or why it
/// is not one.
fn point_mass_of(id: u64, node: usize, m: &[[f64; 6]; 6]) -> Result<PointMass, String> {
    let mass = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
    let scale = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let tol = 1e-9 * scale;
    for i in 0..3 {
        for j in 0..3 {
            let want = if i == j { mass } else { 0.0 };
            if (m[i][j] - want).abs() > tol {
                return Err(format!(
                    "its translational block is not m·I (M{}{} = {:e}): a direction-dependent \
                     translational mass",
                    i + 1,
                    j + 1,
                    m[i][j]
                ));
            }
        }
    }
    // M12 = −m ẽ: skew, e = (M₁₂[2][1], M₁₂[0][2], M₁₂[1][0]) / −m … from ẽ = −M12/m.
    let c = |i: usize, j: usize| m[i][3 + j];
    for i in 0..3 {
        for j in 0..3 {
            if (c(i, j) + c(j, i)).abs() > tol {
                return Err(format!(
                    "its coupling block M{}{} is not skew-symmetric (not the offset of a point mass)",
                    i + 1,
                    j + 4
                ));
            }
        }
    }
    let e = if mass != 0.0 {
        [-c(2, 1) / mass, -c(0, 2) / mass, -c(1, 0) / mass]
    } else if (0..3).all(|i| (0..3).all(|j| c(i, j).abs() <= tol)) {
        [0.0; 3]
    } else {
        return Err("a coupling block without translational mass".into());
    };
    let et = [[0.0, -e[2], e[1]], [e[2], 0.0, -e[0]], [-e[1], e[0], 0.0]];
    let inertia = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            m[3 + i][3 + j] + mass * (0..3).map(|k| et[i][k] * et[k][j]).sum::<f64>()
        })
    });
    Ok(PointMass {
        id,
        node,
        mass,
        offset: e,
        inertia,
    })
}

/// Point masses into the model: offsets and inertia to basic, WTMASS applied; CONM1 as the
/// point mass it describes.
pub(super) fn resolve(d: &mut Bulk) -> Result<(), ImportError> {
    let wtmass = d.solution.wtmass;
    for (eid, node, cid, m, card) in std::mem::take(&mut d.masses.conm1) {
        let g = C::new(card, d.files);
        let a = match cid {
            0 => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            _ => {
                let cs = &d.b.model.coord_systems[*d
                    .coords
                    .get(&cid)
                    .ok_or_else(|| g.err(2, format!("unknown coordinate system CID {cid}")))?];
                if cs.kind != CoordKind::Rectangular {
                    return Err(g.err(2, "CONM1 in a non-rectangular system not supported"));
                }
                cs.axes
            }
        };
        // M_basic = Eᵀ M E with E = diag(A, A), A's rows the local axes.
        let e6 = |i: usize, j: usize| if i / 3 == j / 3 { a[i % 3][j % 3] } else { 0.0 };
        let mb: [[f64; 6]; 6] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                (0..6)
                    .flat_map(|p| (0..6).map(move |q| (p, q)))
                    .map(|(p, q)| e6(p, i) * m[p][q] * e6(q, j))
                    .sum()
            })
        });
        let pm = point_mass_of(eid, node, &mb).map_err(|why| {
            g.err_card(format!(
                "{why}: a 6×6 mass that is not a rigid point mass is not supported (one mass \
                 point per node)"
            ))
        })?;
        d.masses.conm2.push((pm, 0, card));
    }
    let model = &mut d.b.model;
    for (mut pm, cid, card) in std::mem::take(&mut d.masses.conm2) {
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
