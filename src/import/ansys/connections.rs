//! The connection elements of an archive into the model's connectors: COMBIN14 springs
//! (bushes along I→J, scalar springs), LINK180 rod properties, MPC184 rigid links (linear MPCs,
//! their dependent dof a free one) and the check that a MASS21 rotary inertia sits on a node an
//! MPC184 rigid beam, a BEAM188 or a surface-based constraint's pilot joins.

use std::collections::{BTreeMap, BTreeSet};

use super::elements;
use crate::model::{
    Bush, Model, Mpc, NodeDof, NodeIndex, Property, RigidElement, ScalarSpring, Section,
};

/// A COMBIN14 spring into the model: a bush along I→J, or a scalar spring between the same
/// translation of both nodes; the refusal's reason when the longitudinal spring has no direction.
pub(super) fn place_spring(
    id: u64,
    s: &elements::Spring,
    a: NodeIndex,
    b: NodeIndex,
    model: &mut Model,
) -> Result<(), String> {
    match s.along {
        None => {
            let bush = Bush::axial(id, (a, model.nodes[a].x), (b, model.nodes[b].x), s.k)
                .ok_or("COMBIN14 KEYOPT(2)=0 on coincident nodes: the longitudinal spring has no direction")?;
            model.bushes.push(bush);
        }
        Some(component) => model.springs.push(ScalarSpring {
            id,
            a: NodeDof { node: a, component },
            b: Some(NodeDof { node: b, component }),
            k: s.k,
        }),
    }
    Ok(())
}

/// The MASS21 rotary inertias (`rotary`: line, element type, point mass) on nodes no MPC184
/// rigid beam joins: their rotations have no stiffness from any element read from an archive,
/// so they would be three zero-frequency modes (ANSYS would find them too). Each as its
/// refusal: (line, (element type, reason)).
pub(super) fn rotary_without_rotations(
    model: &Model,
    rotary: &[(usize, i64, usize)],
) -> Vec<(usize, (i64, String))> {
    let mut rotating = BTreeSet::new();
    for r in &model.rigid_elements {
        match r {
            // a spider's independent node moves with its dependents (an MPC184 rigid beam, a
            // rigid surface constraint's pilot); its dependents rotate with it when it ties
            // their rotations
            RigidElement::Rbe2 {
                independent,
                dependent,
                dofs,
                ..
            } => {
                rotating.insert(*independent);
                if dofs.0 & 0b11_1000 != 0 {
                    rotating.extend(dependent.iter().copied());
                }
            }
            // a force-distributed constraint's pilot: its rotations follow the surface's
            RigidElement::Rbe3 {
                reference,
                ref_dofs,
                ..
            } if ref_dofs.0 & 0b11_1000 == 0b11_1000 => {
                rotating.insert(*reference);
            }
            RigidElement::Rbe3 { .. } => {}
        }
    }
    // a BEAM188 gives its nodes' rotations stiffness (and consistent rotary inertia)
    for e in &model.elements {
        if matches!(
            e.kind,
            crate::model::ElementKind::Beam2Linear
                | crate::model::ElementKind::Beam3Quadratic
                | crate::model::ElementKind::Beam4Cubic
        ) {
            rotating.extend(e.nodes.iter().copied());
        }
    }
    let mut out = Vec::new();
    for &(line, etype, k) in rotary {
        let p = &model.point_masses[k];
        if !rotating.contains(&p.node) {
            let i = [p.inertia[0][0], p.inertia[1][1], p.inertia[2][2]];
            out.push((
                line,
                (
                    etype,
                    format!(
                        "MASS21 on node {} with rotary inertia IXX={}, IYY={}, IZZ={}: no MPC184 \
                         rigid beam, BEAM188 or surface-based constraint's pilot holds the node, and no other element read from an \
                         archive gives its rotations stiffness, so they would be free (set \
                         KEYOPT(3)=2 or zero inertias)",
                        model.nodes[p.node].id, i[0], i[1], i[2]
                    ),
                ),
            ));
        }
    }
    out
}

/// LINK180 properties by (material, area bits, added mass bits).
pub(super) type RodProperties = BTreeMap<(i64, u64, u64), usize>;

/// The rod property (no torsion) of a LINK180 of material `key.0`, area and added mass per
/// length `key.1`, `key.2` (as bits), made once; `None` when the material has no MPDATA.
pub(super) fn rod_property(
    model: &mut Model,
    rods: &mut RodProperties,
    property_of: &BTreeMap<i64, usize>,
    key: (i64, u64, u64),
) -> Option<usize> {
    if let Some(&p) = rods.get(&key) {
        return Some(p);
    }
    let material = model.properties[*property_of.get(&key.0)?].material;
    model.properties.push(Property {
        id: (model.properties.len() + 1) as u64,
        name: format!("LINK180 MAT{}", key.0),
        material,
        section: Section::Rod {
            area: f64::from_bits(key.1),
            j: 0.0,
            nsm: f64::from_bits(key.2),
        },
    });
    rods.insert(key, model.properties.len() - 1);
    Some(model.properties.len() - 1)
}

/// Each MPC184 rigid link's dependent (first) term on a dof no D holds, as ANSYS eliminates a
/// free dof: the one with the largest coefficient among them (none free: left as it is, for
/// the constraint stage to name).
pub(super) fn free_dependents(model: &mut Model, links: &[usize]) {
    let held: BTreeSet<(NodeIndex, u8)> = (model.spcs.iter())
        .flat_map(|s| {
            (0..6u8)
                .filter(|c| s.dofs.0 & (1 << c) != 0)
                .map(|c| (s.node, c))
        })
        .collect();
    for &i in links {
        let terms = &mut model.mpcs[i].terms;
        let free = (0..terms.len())
            .filter(|&k| !held.contains(&(terms[k].0.node, terms[k].0.component)))
            .max_by(|&a, &b| terms[a].1.abs().total_cmp(&terms[b].1.abs()));
        if let Some(k) = free {
            terms.swap(0, k);
        }
    }
}

/// An MPC184 rigid link from a to b: the linearized constant length e·(u_b − u_a) = 0, e the
/// unit vector a→b; b's component along which e is largest is the dependent (first) term. Refused
/// (the reason) when a and b coincide or either has a nodal coordinate system.
pub(super) fn rigid_link(
    id: u64,
    a: NodeIndex,
    b: NodeIndex,
    model: &Model,
) -> Result<Mpc, String> {
    if [a, b]
        .iter()
        .any(|&n| model.nodes[n].displacement_frame.is_some())
    {
        return Err(
            "MPC184 rigid link on a node with a nodal coordinate system (NBLOCK \
                    angles): its equation is formed on global components"
                .into(),
        );
    }
    let (xa, xb) = (model.nodes[a].x, model.nodes[b].x);
    let d = [xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]];
    let first = (0..3)
        .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
        .unwrap_or(0);
    let mut terms = Vec::with_capacity(6);
    for k in std::iter::once(first).chain((0..3).filter(|&k| k != first)) {
        for (node, sign) in [(b, 1.0), (a, -1.0)] {
            if d[k] != 0.0 {
                terms.push((
                    NodeDof {
                        node,
                        component: k as u8,
                    },
                    sign * d[k],
                ));
            }
        }
    }
    if terms.is_empty() {
        return Err("MPC184 rigid link on coincident nodes: no direction".into());
    }
    Ok(Mpc { id, terms })
}
