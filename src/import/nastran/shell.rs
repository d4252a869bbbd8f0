//! Nastran shell cards: PSHELL, PCOMP (isotropic single-material laminates only), and the
//! element-level thickness and offset fields of CQUAD4/CTRIA3.
//!
//! * PSHELL `PID MID1 T MID2 12I/T³ MID3 TS/T NSM / Z1 Z2 MID4`: MID1 membrane, MID2 bending
//!   with 12I/T³ (default 1), MID3 transverse shear with TS/T (default 5/6), NSM per area.
//!   Z1/Z2 are stress-recovery fibres only. MID4 (membrane–bending coupling) is an error.
//! * PCOMP `PID Z0 NSM SB FT TREF GE LAM / MIDi Ti THETAi SOUTi …` (MSC QRG): plies bottom to
//!   top (blank MIDi/Ti: the previous ply's), LAM blank or SYM (the plies mirrored), NSM per
//!   area; classical lamination in src/fe/shell_section.rs (plies of one isotropic MAT1 are
//!   exactly that PSHELL). Z0 other than −T/2 offsets the mid-plane by Z0 + T/2 (with the element's ZOFFS,
//!   `model::shell_offset`); LAM = MEM, BEND, SMEAR,
//!   SMCORE are errors naming the field; SB, FT (failure), TREF (thermal), GE (damping) and
//!   SOUTi (output) cannot change stiffness or mass and are read past. PCOMPG: the same with
//!   one ply a continuation line `GPLYIDi MIDi Ti THETAi SOUTi` (the global ply id only names
//!   it). Corner thicknesses T1.. on a laminate's element are an error (the plies give it).
//! * CQUAD4 `EID PID G1-G4 THETA ZOFFS / – TFLAG T1-T4`, CTRIA3 `EID PID G1-G3 THETA ZOFFS /
//!   – – TFLAG T1-T3`: corner thicknesses override the property's T (TFLAG = 1: relative to
//!   it). The element gets its own copy of the property with the mean corner thickness (a
//!   warning when the corners differ). A non-zero ZOFFS puts the element on nodes at its
//!   reference plane, rigidly linked to the grids (`model::shell_offset`).
//! * CQUAD8 `EID PID G1-G8 / T1-T4 THETA ZOFFS / TFLAG`, CTRIA6 `EID PID G1-G6 / THETA ZOFFS
//!   T1-T3 TFLAG` (MSC QRG; a non-zero ZOFFS is an error): the quadratic shells interpolate the corner thicknesses over the
//!   element (`Model::shell_thickness`; a mid-side grid has the mean of its edge's corners,
//!   the linear variation along the edge).
//! * CQUADR/CTRIAR: the CQUAD4/CTRIA3 fields, formed with the drilling membrane
//!   (`Model::drilling_membranes`, `fe::elements::drill_membrane`).
//! * THETA/MCID of CQUAD4/CTRIA3 (field 7; CTRIA3 field 6, CQUAD8 field 15, CTRIA6 field 9): a
//!   real THETA turns the material x-axis from the G1→G2 side, an integer MCID is the x-axis of
//!   that (rectangular) system projected onto the element (`Model::shell_axes`,
//!   [`ShellMaterialAxis`]). It orients the material only: an isotropic MAT1 does not depend
//!   on it.

use super::fields::C;
use super::records::{ElementAxis, ElementThickness, ThetaOrMcid};
use crate::import::error::ImportError;
use crate::import::text::IdMap;
use crate::model::shell_offset::ShellOffset;
use crate::model::{
    CoordKind, ElementKind, ImportWarning, Model, Ply, Property, Section, ShellMaterialAxis,
    ShellSection,
};

/// PSHELL → (primary material id: MID1, else MID2; section with *external* material ids in
/// `bending`/`shear`, replaced by indices in [`resolve_mids`]).
pub(super) fn pshell(g: &C) -> Result<(u64, Section), ImportError> {
    let mid = |k: usize| -> Result<Option<u64>, ImportError> {
        match g.int(k)? {
            None | Some(0) => Ok(None),
            Some(v) if v > 0 => Ok(Some(v as u64)),
            Some(v) => Err(g.err(k, format!("bad material id {v}"))),
        }
    };
    let (mid1, mid2, mid3) = (mid(1)?, mid(3)?, mid(5)?);
    if let Some(m4) = mid(10)? {
        return Err(g.err(
            10,
            format!("MID4 {m4} (membrane–bending coupling) is not supported"),
        ));
    }
    let primary = mid1
        .or(mid2)
        .ok_or_else(|| g.err(1, "neither MID1 nor MID2 is given"))?;
    // T blank: every element must give its own (checked when the thickness is resolved).
    let thickness = g.real(2)?.unwrap_or(f64::NAN);
    let ratio = g.real_or(4, 1.0)?;
    let ts = g.real_or(6, 5.0 / 6.0)?;
    Ok((
        primary,
        Section::Shell(ShellSection {
            thickness,
            membrane: mid1.is_some(),
            bending: mid2.map(|m| (m as usize, ratio)),
            shear: mid3.filter(|_| mid2.is_some()).map(|m| (m as usize, ts)),
            nsm: g.real_or(7, 0.0)?,
            plies: Vec::new(),
            material_axis: Default::default(),
        }),
    ))
}

/// PCOMP → (first ply's material id, section with the plies, external material ids until
/// [`resolve_mids`]) (module doc).
pub(super) fn pcomp(g: &C) -> Result<(u64, Section, f64), ImportError> {
    let n = g.card.fields.len();
    // PCOMPG: one ply a continuation line, GPLYID MID T THETA SOUT (the ply id only names it)
    let (first, stride) = match g.card.name.as_str() {
        "PCOMPG" => (9, 8),
        _ => (8, 4),
    };
    let mut plies: Vec<Ply> = Vec::new();
    let mut k = first;
    while k < n {
        let m = g.int(k)?;
        let t = g.real(k + 1)?;
        if m.is_none() && t.is_none() && g.text(k + 2).is_empty() {
            k += stride;
            continue;
        }
        let prev = plies.last().copied();
        let m = match m {
            Some(v) if v > 0 => v as usize,
            Some(v) => return Err(g.err(k, format!("bad ply material id {v}"))),
            None => {
                prev.ok_or_else(|| g.err(k, "first ply has no MID"))?
                    .material
            }
        };
        let t = match t {
            Some(v) if v > 0.0 => v,
            Some(v) => return Err(g.err(k + 1, format!("ply thickness {v} ≤ 0"))),
            None => {
                prev.ok_or_else(|| g.err(k + 1, "first ply has no thickness"))?
                    .thickness
            }
        };
        // SOUT (k + 3) asks for ply stress output only.
        plies.push(Ply {
            material: m,
            thickness: t,
            angle_deg: g.real_or(k + 2, 0.0)?,
        });
        k += stride;
    }
    let mid = plies
        .first()
        .ok_or_else(|| g.err_card("PCOMP without plies"))?
        .material as u64;
    match g.text(7).to_ascii_uppercase().as_str() {
        "" => {}
        "SYM" => {
            let mirror: Vec<Ply> = plies.iter().rev().copied().collect();
            plies.extend(mirror);
        }
        lam => {
            return Err(g.err(
                7,
                format!(
                    "LAM = {lam} is not supported (blank or SYM): MEM, BEND, SMEAR and SMCORE \
                     change which plies carry membrane and bending stiffness"
                ),
            ));
        }
    }
    let total: f64 = plies.iter().map(|p| p.thickness).sum();
    // Z0: the bottom surface from the reference plane; the mid-plane lies Z0 + T/2 above it
    let offset = match g.real(1)? {
        Some(z0) if !z0.is_finite() => return Err(g.err(1, format!("Z0 = {z0}"))),
        Some(z0) if (z0 + total / 2.0).abs() > 1e-9 * total => z0 + total / 2.0,
        _ => 0.0,
    };
    // SB, FT (failure), TREF (thermal), GE (damping): no stiffness or mass.
    let mut s = ShellSection::homogeneous(total, mid as usize);
    s.nsm = g.real_or(2, 0.0)?;
    s.plies = plies;
    Ok((mid, Section::Shell(s), offset))
}

/// Replace the external MID2/MID3 of a parsed PSHELL by material indices.
pub(super) fn resolve_mids(s: &mut ShellSection, mids: &IdMap, g: &C) -> Result<(), ImportError> {
    let get = |ext: usize, k: usize| {
        mids.get(ext as u64)
            .ok_or_else(|| g.err(k, format!("references unknown material {ext}")))
    };
    if let Some((m, r)) = s.bending {
        s.bending = Some((get(m, 3)?, r));
    }
    if let Some((m, r)) = s.shear {
        s.shear = Some((get(m, 5)?, r));
    }
    let (first, stride) = if g.card.name == "PCOMPG" {
        (9, 8)
    } else {
        (8, 4)
    };
    for (i, p) in s.plies.iter_mut().enumerate() {
        // SYM's mirrored plies point at their originals' fields
        let n = (g.card.fields.len().saturating_sub(first))
            .div_ceil(stride)
            .max(1);
        p.material = get(p.material, first + stride * (i % n))?;
    }
    Ok(())
}

/// THETA (a real: it has a decimal point) or MCID (an integer) of a CQUAD4/CTRIA3/CQUAD8/CTRIA6
/// card; `None` when blank or THETA = 0 (the default axis).
pub(super) fn element_axis(g: &C, elem: usize) -> Result<Option<ElementAxis>, ImportError> {
    let k = match g.card.name.as_str() {
        "CQUAD4" | "CQUADR" => 6,
        "CQUAD8" => 14,
        "CTRIA6" => 8,
        _ => 5,
    };
    let text = g.text(k);
    let value = if text.is_empty() {
        return Ok(None);
    } else if text.contains('.') {
        match g.real(k)? {
            Some(t) if t != 0.0 => ThetaOrMcid::Theta(t),
            _ => return Ok(None),
        }
    } else {
        match g.int(k)? {
            Some(c) if c >= 0 => ThetaOrMcid::Mcid(c as u64),
            Some(c) => return Err(g.err(k, format!("MCID {c} < 0"))),
            None => return Ok(None),
        }
    };
    Ok(Some(ElementAxis {
        elem,
        value,
        file: g.file.to_owned(),
        line: g.line(k),
    }))
}

/// The elements' THETA/MCID into `Model::shell_axes` (MCID: the x-axis of a rectangular
/// system, 0 the basic one; a curvilinear MCID is an error naming the card).
pub(super) fn apply_axes(model: &mut Model, list: &[ElementAxis]) -> Result<(), ImportError> {
    for a in list {
        let axis = match a.value {
            ThetaOrMcid::Theta(t) => ShellMaterialAxis::FromSide12 { theta_deg: t },
            ThetaOrMcid::Mcid(0) => ShellMaterialAxis::Projected([1.0, 0.0, 0.0]),
            ThetaOrMcid::Mcid(c) => {
                let err = |m: String| {
                    let eid = model.elements[a.elem].id;
                    crate::import::error::parse_err(&a.file, a.line, format!("element {eid}"), m)
                };
                let cs = (model.coord_systems.iter())
                    .find(|cs| cs.id == c)
                    .ok_or_else(|| err(format!("MCID {c}: no such coordinate system")))?;
                if cs.kind != CoordKind::Rectangular {
                    return Err(err(format!(
                        "MCID {c} is not rectangular: a curvilinear material system of a shell \
                         is not supported"
                    )));
                }
                ShellMaterialAxis::Projected(cs.axes[0])
            }
        };
        model.shell_axes.insert(a.elem, axis);
    }
    Ok(())
}

/// ZOFFS check and corner thicknesses of a CQUAD4/CTRIA3/CQUAD8/CTRIA6 card (`elem` = its
/// model index).
pub(super) fn element_fields(g: &C, elem: usize) -> Result<Option<ElementThickness>, ImportError> {
    // (corners, ZOFFS field, TFLAG field, T1 field)
    let (nn, zoffs, tflag, t1) = match g.card.name.as_str() {
        "CQUAD4" | "CQUADR" => (4, 7, 9, 10),
        "CQUAD8" => (4, 15, 16, 10),
        "CTRIA6" => (3, 9, 13, 10),
        _ => (3, 6, 9, 10),
    };
    // CQUAD4/CTRIA3 offsets are read by `element_offset`
    let quadratic = matches!(g.card.name.as_str(), "CQUAD8" | "CTRIA6");
    if let Some(z) = g.real(zoffs)?.filter(|z| *z != 0.0 && quadratic) {
        return Err(g.err(
            zoffs,
            format!(
                "ZOFFS = {z}: offsets of curved shells (CQUAD8/CTRIA6) are not supported \
                 (CQUAD4/CTRIA3 offsets are)"
            ),
        ));
    }
    let relative = match g.int(tflag)? {
        None | Some(0) => false,
        Some(1) => true,
        Some(v) => return Err(g.err(tflag, format!("TFLAG = {v} (0 or 1)"))),
    };
    let corners: Vec<Option<f64>> = (0..nn).map(|i| g.real(t1 + i)).collect::<Result<_, _>>()?;
    if corners.iter().all(Option::is_none) {
        return Ok(None);
    }
    Ok(Some(ElementThickness {
        elem,
        corners,
        relative,
        file: g.file.to_owned(),
        line: g.line(t1),
    }))
}

/// The ZOFFS of a CQUAD4/CTRIA3 card (`elem` = its model index), when given and non-zero:
/// applied by `model::shell_offset` once the grids are placed.
pub(super) fn element_offset(g: &C, elem: usize) -> Result<Option<ShellOffset>, ImportError> {
    let field = match g.card.name.as_str() {
        "CQUAD4" | "CQUADR" => 7,
        "CTRIA3" | "CTRIAR" => 6,
        _ => return Ok(None),
    };
    match g.real(field)? {
        Some(z) if !z.is_finite() => Err(g.err(field, format!("ZOFFS = {z}"))),
        Some(z) if z != 0.0 => Ok(Some(ShellOffset { elem, zoffs: z })),
        _ => Ok(None),
    }
}

/// Give each element with corner thicknesses its own copy of its shell property with the mean
/// thickness (module doc). Elements without a shell property are left to the assembler.
pub(super) fn apply_thickness(
    model: &mut Model,
    list: &[ElementThickness],
) -> Result<(), ImportError> {
    let mut varying = 0usize;
    let mut first_varying = None;
    let mut derived_of: std::collections::HashMap<(usize, u64), usize> = Default::default();
    for et in list {
        let Some(p) = model.elements[et.elem].property else {
            continue;
        };
        let prop = &model.properties[p];
        let Section::Shell(sh) = &prop.section else {
            continue;
        };
        let base = sh.thickness;
        let ts: Vec<f64> = et
            .corners
            .iter()
            .map(|c| match (c, et.relative) {
                (Some(t), false) => *t,
                (Some(f), true) => f * base,
                (None, _) => base,
            })
            .collect();
        let eid = model.elements[et.elem].id;
        if !sh.plies.is_empty() {
            return Err(crate::import::error::parse_err(
                &et.file,
                et.line,
                format!("element {eid}"),
                format!(
                    "corner thicknesses T1.. on a laminate (property {}): its plies give the \
                     thickness",
                    prop.id
                ),
            ));
        }
        // MSC QRG CQUAD4/CTRIA3: Ti ≥ 0.0 or blank, not all zero (a corner may taper to 0)
        if ts.iter().any(|t| !(t.is_finite() && *t >= 0.0)) || ts.iter().all(|t| *t == 0.0) {
            let hint = if base > 0.0 { "" } else { " (PSHELL T blank?)" };
            return Err(crate::import::error::parse_err(
                &et.file,
                et.line,
                format!("element {eid}"),
                format!("corner thicknesses {ts:?}: each must be ≥ 0 and not all 0{hint}"),
            ));
        }
        let kind = model.elements[et.elem].kind;
        if matches!(kind, ElementKind::Quad8 | ElementKind::Tri6) {
            // mid-side grids: the mean of their edge's corners (module doc)
            let n = ts.len();
            let mids: Vec<f64> = (0..n).map(|i| 0.5 * (ts[i] + ts[(i + 1) % n])).collect();
            model.shell_thickness.insert(et.elem, [ts, mids].concat());
            continue;
        }
        let mean = ts.iter().sum::<f64>() / ts.len() as f64;
        if ts.iter().any(|t| (t - mean).abs() > 1e-9 * mean) {
            varying += 1;
            first_varying.get_or_insert((eid, format!("{}:{}", et.file, et.line)));
        }
        if (mean - base).abs() <= 1e-12 * mean {
            continue;
        }
        let key = (p, mean.to_bits());
        if let Some(&d) = derived_of.get(&key) {
            model.elements[et.elem].property = Some(d);
            continue;
        }
        let mut section = sh.clone();
        section.thickness = mean;
        let derived = Property {
            id: prop.id,
            name: format!("{} (element T = {mean})", prop.name),
            material: prop.material,
            section: Section::Shell(section),
        };
        model.properties.push(derived);
        let d = model.properties.len() - 1;
        derived_of.insert(key, d);
        model.elements[et.elem].property = Some(d);
    }
    if let Some((first, place)) = first_varying {
        model.warnings.push(ImportWarning {
            file: place,
            message: format!(
                "{varying} shell elements (first: {first}) have different corner thicknesses: \
                 each uses the mean of its corners"
            ),
        });
    }
    Ok(())
}

/// CQUAD8/CTRIA6 with blank mid-side grids: each such edge straight, as MSC Nastran forms it
/// (QRG CQUAD8 remark: a deleted mid-side grid makes the edge straight, the displacement linear
/// along it). A node at the edge's mid-point takes the slot, and an MPC on each of its six dofs
/// makes it move with the mean of the edge's corners, u_m = ½ (u_a + u_b): it is no dof of
/// its own. The corners must have the basic displacement frame (the MPC is on the nodes' own
/// components). One note lists what was made.
pub(super) fn blank_midsides(d: &mut super::reading::Bulk) -> Result<(), ImportError> {
    let list = std::mem::take(&mut d.elements.blank_midsides);
    if list.is_empty() {
        return Ok(());
    }
    let b = &mut d.b;
    let mut next = b.model.max_node_id();
    let first = next + 1;
    for (k, slots, loc) in list {
        let (kind, id) = (b.model.elements[k].kind, b.model.elements[k].id);
        let corners = if kind == ElementKind::Quad8 { 4 } else { 3 };
        for slot in slots {
            let edge = slot - corners;
            let nodes = &b.model.elements[k].nodes;
            let (na, nb) = (nodes[edge], nodes[(edge + 1) % corners]);
            let (a, c) = (&b.model.nodes[na], &b.model.nodes[nb]);
            if a.displacement_frame.is_some() || c.displacement_frame.is_some() {
                return Err(b.err(
                    loc,
                    format!("{} {id}", b.elem_card[k]),
                    format!(
                        "mid-side grid {} is blank between grids {} and {}, one of which has a \
                         displacement frame (CD): not supported (write the mid-side grid)",
                        slot + 1,
                        a.id,
                        c.id
                    ),
                ));
            }
            let x = std::array::from_fn(|i| 0.5 * (a.x[i] + c.x[i]));
            next += 1;
            let m = b.model.nodes.len();
            b.add_node(next, x, loc);
            b.model.elements[k].nodes[slot] = m;
            for component in 0..6u8 {
                let dof = |node| crate::model::NodeDof { node, component };
                b.model.mpcs.push(crate::model::Mpc {
                    id,
                    terms: vec![(dof(m), 1.0), (dof(na), -0.5), (dof(nb), -0.5)],
                });
            }
        }
    }
    b.model.deck.notes.push(format!(
        "CQUAD8/CTRIA6 with blank mid-side grids: {} edges made straight, as MSC Nastran forms \
         them: a node at each edge's mid-point (ids {first} … {next}) moving with the mean of its \
         corners (an MPC on each dof, with the element's id)",
        next + 1 - first
    ));
    Ok(())
}
