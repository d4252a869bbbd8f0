//! The generalized spring CBUSH with its property PBUSH, into [`crate::model::Bush`] (MSC QRG
//! "CBUSH", "PBUSH").
//!
//! * `CBUSH EID PID GA GB GO/X1 X2 X3 CID / S OCID S1 S2 S3`:
//!   - element axes: CID ≥ 0 (0 = basic) gives them directly (it overrides GO/X); else x from
//!     GA to GB, the orientation vector v towards grid GO or X1–X3 (in GA's displacement
//!     frame), z = x × v, y = z × x, as for CBAR. GB blank (grounded) or GA and GB coincident
//!     need a CID; so does a blank v.
//!   - spring point: on the line GA–GB at fraction S (default 0.5) when OCID is −1 or blank;
//!     at GA + (S1, S2, S3) given in system OCID ≥ 0 otherwise. A grounded CBUSH without an
//!     offset acts at GA.
//! * `PBUSH PID "K" K1 … K6 / "B" B1 … / "GE" GE1 … / "RCV" SA ST EA ET / "M" M`: the stiffness
//!   K1–K6 along and about the element axes is read (blank = 0); B (viscous damping) and GE
//!   (structural damping) are notes, RCV (stress recovery) is output; a non-zero M (a mass of
//!   the bush) is refused.
//!
//! * `CBUSH1D EID PID GA GB CID` with `PBUSH1D PID K C M – SA SE` (MSC QRG "CBUSH1D",
//!   "PBUSH1D"): a spring K along the element axis (from GA to GB, or the x axis of system
//!   CID), on the grids' translations (the line of action passes through both grids: no
//!   rotation takes part); a grounded one (GB blank) is refused, as a grounded CBUSH is by
//!   the build. C (damping) is a note; a non-zero M (the element's mass) is an error where a
//!   CBUSH1D uses the property (a PBUSH1D no element uses forms nothing); the SHOCKA, SPRING, DAMPER and GENER lines (nonlinear force–velocity and
//!   force–deflection laws) are a note: MSC uses them in nonlinear transient solutions only,
//!   a normal-modes analysis uses K.
//!
//! Coordinate systems CID and OCID must be rectangular (a cylindrical one is refused).

use super::coord::{cross, dir_to_basic, sub, unit};
use super::fields::C;
use super::reading::Bulk;
use crate::import::error::ImportError;
use crate::model::{Bush, CoordKind, DofMatrix, NodeDof};

/// Reader of CBUSH1D (module doc).
pub(super) fn cbush1d<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let (eid, a, b) = ends(d, g)?;
    d.elements.other_ids.push((eid, g.card));
    d.bushes.cbush1d.push((g.card, a, b));
    Ok(())
}

/// Reader of PBUSH1D (module doc).
pub(super) fn pbush1d<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let pid = g.id(0, "PID")?;
    d.properties.others.push((pid, g.card));
    let k = g.real_or(1, 0.0)?;
    if !k.is_finite() {
        return Err(g.err(1, format!("stiffness {k} is not finite")));
    }
    if g.real_or(2, 0.0)? != 0.0 {
        d.note_as("PBUSH1D C".into(), g, super::cards::DAMPING);
    }
    let mass = g.real_or(3, 0.0)?;
    for at in (8..g.card.fields.len()).step_by(8) {
        match g.text(at).to_ascii_uppercase().as_str() {
            "" => {}
            word @ ("SHOCKA" | "SPRING" | "DAMPER" | "GENER") => d.note_as(
                format!("PBUSH1D {word}"),
                g,
                "a nonlinear force law, used by MSC Nastran in nonlinear transient solutions \
                 only: a normal-modes analysis uses the linear K",
            ),
            other => {
                return Err(g.err(
                    at,
                    format!("unknown PBUSH1D keyword '{other}' (SHOCKA, SPRING, DAMPER or GENER)"),
                ))
            }
        }
    }
    d.bushes.pbush1d.insert(pid, (k, mass, g.card));
    Ok(())
}

/// The element id and end grids of a CBUSH or CBUSH1D (GB blank or 0: grounded).
fn ends(d: &mut Bulk, g: &C) -> Result<(u64, usize, Option<usize>), ImportError> {
    let eid = g.id(0, "EID")?;
    let ga = d.grid(g, 2, g.id(2, "GA")?)?;
    let gb = match g.int(3)? {
        None | Some(0) => None,
        Some(v) if v > 0 => Some(d.grid(g, 3, v as u64)?),
        Some(v) => return Err(g.err(3, format!("bad grid id GB {v}"))),
    };
    if gb == Some(ga) {
        return Err(g.err(3, "GA and GB are the same grid"));
    }
    Ok((eid, ga, gb))
}

/// The CBUSH1D springs as matrices on the grids' translations: k (e·(u_b − u_a))², e the
/// unit axis, in the basic frame (module doc). The spring acts along the line GA–GB, so no
/// rotation takes part: it is not a CBUSH with an offset spring point.
fn resolve_1d(d: &mut Bulk) -> Result<(), ImportError> {
    let model = &d.b.model;
    let mut out = Vec::new();
    for &(card, a, b) in &d.bushes.cbush1d {
        let g = C::new(card, d.files);
        let eid = g.id(0, "EID")?;
        let pid = match g.int(1)? {
            None => eid,
            Some(p) if p > 0 => p as u64,
            Some(p) => return Err(g.err(1, format!("bad property id {p}"))),
        };
        let (k, mass, property) = *d.bushes.pbush1d.get(&pid).ok_or_else(|| {
            g.err(
                1,
                format!("references PBUSH1D {pid}, which the deck does not define"),
            )
        })?;
        if mass != 0.0 {
            // a PBUSH1D no CBUSH1D uses forms nothing: its M is refused where it is used
            return Err(C::new(property, d.files).err(
                3,
                format!(
                    "M = {mass}, used by CBUSH1D {eid}: a mass of the bush is not supported \
                     (model it with CONM2)"
                ),
            ));
        }
        let Some(b) = b else {
            return Err(g.err(
                3,
                "GB is blank: a CBUSH1D to ground would hold the body (a flexible body is free \
                 or held at its interfaces); model the mount in the multibody model",
            ));
        };
        let (xa, xb) = (model.nodes[a].x, model.nodes[b].x);
        let x = match g.int(4)? {
            Some(cid) if cid >= 0 => system_axes(d, &g, 4, cid)?[0],
            Some(cid) => return Err(g.err(4, format!("bad coordinate system id CID {cid}"))),
            None => sub(xb, xa),
        };
        let e = unit(x)
            .filter(|_| x.iter().map(|c| c * c).sum::<f64>() > 1e-16)
            .ok_or_else(|| {
                g.err(
                    4,
                    "CID is blank, but GB is at GA: the element axis needs a CID",
                )
            })?;
        let mut terms = Vec::new();
        axial_spring(k, e, a, b, &mut terms);
        out.push(DofMatrix {
            what: format!("CBUSH1D {eid}"),
            stiffness: terms,
            mass: Vec::new(),
            basic: true,
        });
    }
    d.b.model.dof_matrices.extend(out);
    Ok(())
}

/// The terms of a spring k along the unit vector e (basic) between the translations of
/// grids a and b: k (e·(u_b − u_a))², i.e. ±k e eᵀ in the four blocks.
pub(super) fn axial_spring(
    k: f64,
    e: [f64; 3],
    a: usize,
    b: usize,
    out: &mut Vec<(NodeDof, NodeDof, f64)>,
) {
    let dof = |node, component| NodeDof { node, component };
    for (p, sp) in [(a, -1.0), (b, 1.0)] {
        for (q, sq) in [(a, -1.0), (b, 1.0)] {
            for i in 0..3u8 {
                for j in 0..3u8 {
                    let v = k * sp * sq * e[usize::from(i)] * e[usize::from(j)];
                    out.push((dof(p, i), dof(q, j), v));
                }
            }
        }
    }
}

/// The axes (rows, in basic) of rectangular system `cid` (0 = basic) named in field `field`.
fn system_axes(d: &Bulk, g: &C, field: usize, cid: i64) -> Result<[[f64; 3]; 3], ImportError> {
    if cid == 0 {
        return Ok([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    }
    let cs = (d.coords.get(&cid))
        .map(|&i| &d.b.model.coord_systems[i])
        .ok_or_else(|| g.err(field, format!("unknown coordinate system {cid}")))?;
    if cs.kind != CoordKind::Rectangular {
        return Err(g.err(
            field,
            format!(
                "coordinate system {cid} is not rectangular: not supported for a {}",
                g.card.name
            ),
        ));
    }
    Ok(cs.axes)
}

/// Reader of CBUSH.
pub(super) fn cbush<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let (eid, ga, gb) = ends(d, g)?;
    d.elements.other_ids.push((eid, g.card));
    d.bushes.cbush.push((g.card, ga, gb));
    Ok(())
}

/// Reader of PBUSH.
pub(super) fn pbush<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let pid = g.id(0, "PID")?;
    d.properties.others.push((pid, g.card));
    let mut k = [0.0; 6];
    let lines = g.card.fields.len().div_ceil(8);
    for line in 0..lines {
        let at = 8 * line + 1;
        let values = |g: &C| -> Result<Vec<f64>, ImportError> {
            (at + 1..at + 7).map(|f| g.real_or(f, 0.0)).collect()
        };
        match g.text(at).to_ascii_uppercase().as_str() {
            "" => {}
            "K" => k.copy_from_slice(&values(g)?),
            "B" if values(g)?.iter().any(|&v| v != 0.0) => {
                d.note_as("PBUSH B".into(), g, super::cards::DAMPING);
            }
            "GE" if values(g)?.iter().any(|&v| v != 0.0) => {
                d.note_as("PBUSH GE".into(), g, super::cards::DAMPING);
            }
            "B" | "GE" => {}
            "RCV" => d.note_as("PBUSH RCV".into(), g, super::cards::OUTPUT),
            "M" if g.real_or(at + 1, 0.0)? != 0.0 => d.refuse(
                g,
                "PBUSH M: a mass of the bush is not supported (model it with CONM2)",
            ),
            "M" => {}
            other => {
                return Err(g.err(
                    at,
                    format!("unknown PBUSH keyword '{other}' (K, B, GE, RCV or M)"),
                ))
            }
        }
    }
    if k.iter().any(|v| !v.is_finite()) {
        return Err(g.err_card(format!("stiffness {k:?} is not finite")));
    }
    d.bushes.pbush.insert(pid, k);
    Ok(())
}

/// The bushes into the model: PBUSH stiffness, element axes and spring point (module doc).
pub(super) fn resolve(d: &mut Bulk) -> Result<(), ImportError> {
    let model = &d.b.model;
    let mut out = Vec::new();
    for &(card, a, b) in &d.bushes.cbush {
        let g = C::new(card, d.files);
        let eid = g.id(0, "EID")?;
        let pid = match g.int(1)? {
            None => eid,
            Some(p) if p > 0 => p as u64,
            Some(p) => return Err(g.err(1, format!("bad property id {p}"))),
        };
        let k = *d.bushes.pbush.get(&pid).ok_or_else(|| {
            g.err(
                1,
                format!("references PBUSH {pid}, which the deck does not define"),
            )
        })?;
        // a rectangular system by id (0 = basic): its axes (rows) in basic
        let system = |field: usize, cid: i64| system_axes(d, &g, field, cid);
        let xa = model.nodes[a].x;
        let xb = b.map(|b| model.nodes[b].x);
        let axis = xb
            .map(|xb| sub(xb, xa))
            .filter(|v| v.iter().map(|c| c * c).sum::<f64>() > 1e-8);
        let axes = match g.int(7)? {
            Some(cid) if cid >= 0 => system(7, cid)?,
            Some(cid) => return Err(g.err(7, format!("bad coordinate system id CID {cid}"))),
            None => {
                let x = axis.ok_or_else(|| {
                    g.err(
                        7,
                        "CID is blank, but GB is blank or at GA: the element axes need a CID",
                    )
                })?;
                let v = orientation(d, &g, a)?.ok_or_else(|| {
                    g.err(
                        4,
                        "neither CID nor an orientation vector GO/X1–X3: no element axes",
                    )
                })?;
                frame_from(x, v).ok_or_else(|| {
                    g.err(
                        4,
                        "the orientation vector is parallel to GA–GB: no element axes",
                    )
                })?
            }
        };
        let ocid = g.int(9)?.unwrap_or(-1);
        let location = if ocid >= 0 {
            let o = [
                g.real_or(10, 0.0)?,
                g.real_or(11, 0.0)?,
                g.real_or(12, 0.0)?,
            ];
            let r = system(9, ocid)?;
            std::array::from_fn(|i| xa[i] + (0..3).map(|j| r[j][i] * o[j]).sum::<f64>())
        } else if ocid == -1 {
            match xb {
                Some(xb) => {
                    let s = g.real_or(8, 0.5)?;
                    if !(0.0..=1.0).contains(&s) {
                        return Err(g.err(8, format!("S = {s}: must lie in [0, 1]")));
                    }
                    std::array::from_fn(|i| xa[i] + s * (xb[i] - xa[i]))
                }
                None => xa,
            }
        } else {
            return Err(g.err(9, format!("bad OCID {ocid} (−1 or a coordinate system id)")));
        };
        out.push(Bush {
            id: eid,
            a,
            b,
            axes,
            k,
            location,
        });
    }
    d.b.model.bushes = out;
    resolve_1d(d)
}

/// The orientation vector of a CBUSH in basic: towards grid GO, or X1–X3 in GA's displacement
/// frame (rectangular); `None` when fields 4–6 are blank.
fn orientation(d: &Bulk, g: &C, a: usize) -> Result<Option<[f64; 3]>, ImportError> {
    let model = &d.b.model;
    let s = g.text(4);
    if s.is_empty() && g.text(5).is_empty() && g.text(6).is_empty() {
        return Ok(None);
    }
    if !s.is_empty() && !s.contains('.') && !s.contains(['e', 'E']) {
        let go = d.grid(g, 4, g.id(4, "GO")?)?;
        return Ok(Some(sub(model.nodes[go].x, model.nodes[a].x)));
    }
    let v = [g.real_or(4, 0.0)?, g.real_or(5, 0.0)?, g.real_or(6, 0.0)?];
    Ok(Some(match model.nodes[a].displacement_frame {
        Some(cs) if model.coord_systems[cs].kind == CoordKind::Rectangular => {
            dir_to_basic(&model.coord_systems[cs], v)
        }
        Some(_) => {
            return Err(g.err(
                4,
                "X1–X3 in GA's non-rectangular displacement frame: not supported",
            ))
        }
        None => v,
    }))
}

/// Element axes (rows) from the x direction and the orientation vector v in the x–y plane:
/// z = x × v, y = z × x; `None` when v is parallel to x.
fn frame_from(x: [f64; 3], v: [f64; 3]) -> Option<[[f64; 3]; 3]> {
    let ex = unit(x)?;
    let z = cross(ex, v);
    let len = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    if len(z) <= 1e-9 * len(v) {
        return None;
    }
    let ez = unit(z)?;
    Some([ex, cross(ez, ex), ez])
}
