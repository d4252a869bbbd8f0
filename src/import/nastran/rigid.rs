//! Rigid element cards.
//!
//! * `RBE2 EID GN CM GM1 GM2 … ALPHA`: the CM components of every GMi follow GN rigidly.
//! * `RBE3 EID – REFGRID REFC WT1 C1 G1,1 G1,2 … WT2 C2 G2,1 … "UM" … "ALPHA"`: the REFC
//!   components of REFGRID are the weighted average of the listed grids' Ci motion.

use super::bulk::Bulk;
use super::fields::C;
use crate::import::error::ImportError;
use crate::model::{DofMask, RigidElement};

/// Reader of RBE2.
pub(super) fn rbe2<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.rigid_ids.push((eid, g.card));
    let gn = d.node(g, 1, g.id(1, "GN")?)?;
    let cm = DofMask::from_digits(g.text(2))
        .filter(|m| m.0 != 0)
        .ok_or_else(|| g.err(2, "bad CM dof digits"))?;
    let mut dep = Vec::new();
    for (id, k) in g.id_list(3, &d.thru)? {
        dep.push(d.node(g, k, id)?);
    }
    if dep.is_empty() {
        return Err(g.err_card("no dependent grids"));
    }
    d.b.model.rigid_elements.push(RigidElement::Rbe2 {
        id: eid,
        independent: gn,
        dependent: dep,
        dofs: cm,
    });
    Ok(())
}

/// Reader of RBE3.
pub(super) fn rbe3<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.rigid_ids.push((eid, g.card));
    let reference = d.node(g, 2, g.id(2, "REFGRID")?)?;
    let ref_dofs = DofMask::from_digits(g.text(3))
        .filter(|m| m.0 != 0)
        .ok_or_else(|| g.err(3, "bad REFC dof digits"))?;
    let mut independent = Vec::new();
    let mut k = 4;
    let n = g.card.fields.len();
    let (mut w, mut c) = (None, None);
    while k < n {
        let s = g.text(k);
        if s.is_empty() {
            k += 1;
            continue;
        }
        let up = s.to_ascii_uppercase();
        if up == "UM" {
            return Err(g.err(k, "RBE3 UM (user-selected dependent dofs) not supported"));
        }
        if up == "ALPHA" {
            break;
        }
        if s.contains('.') || s.contains(['e', 'E']) {
            w = Some(g.real(k)?.unwrap_or(1.0));
            c = None;
        } else if c.is_none() {
            if w.is_none() {
                return Err(g.err(k, "component before a weight"));
            }
            c = Some(DofMask::from_digits(s).ok_or_else(|| g.err(k, "bad dof digits"))?);
        } else {
            let id = g.id(k, "G")?;
            independent.push((
                d.node(g, k, id)?,
                w.unwrap_or(1.0),
                c.unwrap_or(DofMask::TRANSLATIONS),
            ));
        }
        k += 1;
    }
    if independent.is_empty() {
        return Err(g.err_card("no independent grids"));
    }
    d.b.model.rigid_elements.push(RigidElement::Rbe3 {
        id: eid,
        reference,
        ref_dofs,
        independent,
    });
    Ok(())
}
