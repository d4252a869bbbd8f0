//! Rigid element cards (MSC QRG "RBE2", "RBE3", "RBAR", "RBAR1", "RBE1").
//!
//! * `RBE2 EID GN CM GM1 GM2 … ALPHA`: the CM components of every GMi follow GN rigidly.
//! * `RBE3 EID – REFGRID REFC WT1 C1 G1,1 G1,2 … WT2 C2 G2,1 … "UM" … "ALPHA"`: the REFC
//!   components of REFGRID are the weighted average of the listed grids' Ci motion.
//! * `RBAR EID GA GB CNA CNB CMA CMB ALPHA`: a rigid bar; CNA at GA and CNB at GB are the six
//!   independent components, CMA and CMB the dependent ones (both blank: every component not
//!   independent).
//! * `RBAR1 EID GA GB CB ALPHA`: GA independent (all six), CB at GB dependent.
//! * `RBE1 EID GN1 CN1 … GN6 CN6 / "UM" GM1 CM1 … ALPHA`: a rigid body, independent (GNi, CNi)
//!   (six components in all) up to `UM`, dependent (GMi, CMi) after it.
//!
//! RBAR, RBAR1 and RBE1 become [`RigidBody`] (`fe` solves for the dependent dofs); their
//! six independent components must fix the rigid motion (checked there).

use super::fields::C;
use super::reading::Bulk;
use crate::import::error::ImportError;
use crate::model::{DofMask, RigidBody, RigidElement};

/// Reader of RBE2.
pub(super) fn rbe2<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.rigid_ids.push((eid, g.card));
    let gn = d.grid(g, 1, g.id(1, "GN")?)?;
    let cm = DofMask::from_digits(g.text(2))
        .filter(|m| m.0 != 0)
        .ok_or_else(|| g.err(2, "bad CM dof digits"))?;
    let mut dep = Vec::new();
    for (id, k) in g.id_list(3, &d.thru)? {
        dep.push(d.grid(g, k, id)?);
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
    let reference = d.grid(g, 2, g.id(2, "REFGRID")?)?;
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
                d.grid(g, k, id)?,
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

/// Components in field `k` (blank = none).
fn components(g: &C, k: usize) -> Result<DofMask, ImportError> {
    DofMask::from_digits(g.text(k)).ok_or_else(|| g.err(k, "bad dof digits"))
}

/// The six independent components of a rigid body, counted on its card.
fn six_independent(g: &C, independent: &[(usize, DofMask)]) -> Result<(), ImportError> {
    let n: u32 = independent.iter().map(|(_, m)| m.0.count_ones()).sum();
    if n != 6 {
        return Err(g.err_card(format!(
            "{n} independent components; a rigid body needs six that fix its rigid motion"
        )));
    }
    Ok(())
}

/// EID, GA and GB of a rigid bar (RBAR, RBAR1), the id kept in the rigid id space.
fn bar<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(u64, usize, usize), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.rigid_ids.push((eid, g.card));
    let ga = d.grid(g, 1, g.id(1, "GA")?)?;
    let gb = d.grid(g, 2, g.id(2, "GB")?)?;
    if ga == gb {
        return Err(g.err(2, "GA and GB are the same grid"));
    }
    Ok((eid, ga, gb))
}

/// Reader of RBAR.
pub(super) fn rbar<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let (eid, ga, gb) = bar(d, g)?;
    let (cna, cnb) = (components(g, 3)?, components(g, 4)?);
    let (mut cma, mut cmb) = (components(g, 5)?, components(g, 6)?);
    if cma.0 == 0 && cmb.0 == 0 {
        // every component that is not independent
        cma = DofMask(DofMask::ALL.0 & !cna.0);
        cmb = DofMask(DofMask::ALL.0 & !cnb.0);
    }
    for (k, n, m) in [(5, cna, cma), (6, cnb, cmb)] {
        if n.0 & m.0 != 0 {
            return Err(g.err(
                k,
                format!(
                    "components {} are both independent and dependent",
                    DofMask(n.0 & m.0).digits()
                ),
            ));
        }
    }
    let independent: Vec<(usize, DofMask)> = [(ga, cna), (gb, cnb)]
        .into_iter()
        .filter(|x| x.1 .0 != 0)
        .collect();
    six_independent(g, &independent)?;
    let dependent = [(ga, cma), (gb, cmb)]
        .into_iter()
        .filter(|x| x.1 .0 != 0)
        .collect();
    d.b.model.rigid_bodies.push(RigidBody {
        id: eid,
        independent,
        dependent,
    });
    Ok(())
}

/// Reader of RBAR1.
pub(super) fn rbar1<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let (eid, ga, gb) = bar(d, g)?;
    let cb = components(g, 3)?;
    if cb.0 == 0 {
        return Err(g.err(3, "CB is blank: no dependent component"));
    }
    d.b.model.rigid_bodies.push(RigidBody {
        id: eid,
        independent: vec![(ga, DofMask::ALL)],
        dependent: vec![(gb, cb)],
    });
    Ok(())
}

/// Reader of RBE1.
pub(super) fn rbe1<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.rigid_ids.push((eid, g.card));
    let (mut independent, mut dependent) = (Vec::new(), Vec::new());
    let mut after_um = false;
    let mut k = 1;
    while k < g.card.fields.len() {
        let s = g.text(k);
        if s.is_empty() {
            k += 1;
            continue;
        }
        if s.eq_ignore_ascii_case("UM") {
            after_um = true;
            k += 1;
            continue;
        }
        if s.contains('.') || s.contains(['e', 'E']) {
            break; // ALPHA
        }
        let node = d.grid(g, k, g.id(k, "G")?)?;
        let c = components(g, k + 1)?;
        if c.0 == 0 {
            return Err(g.err(k + 1, "a grid without components"));
        }
        if after_um {
            dependent.push((node, c));
        } else {
            independent.push((node, c));
        }
        k += 2;
    }
    six_independent(g, &independent)?;
    if dependent.is_empty() {
        return Err(g.err_card("no dependent grids (UM GM1 CM1 …)"));
    }
    d.b.model.rigid_bodies.push(RigidBody {
        id: eid,
        independent,
        dependent,
    });
    Ok(())
}
