//! The equations joining an expanded shell node to its bottom, middle and top nodes, and its
//! held rotations, as ccx 2.20 writes them (gen3dconnect, gen3dmpc, gen3dboun, gen3dforc):
//! rules 1–3 and the held rotations of the module doc of [`super::shell_expansion`].

use std::collections::{BTreeMap, BTreeSet};

use super::shell_nodes::{parse_err, unit, Expanded, Place, Xyz, DRILLING, SAME_AXIS};
use crate::import::ImportError;
use crate::model::geometry::{cross, dot, sub};
use crate::model::{DofMask, Model, Mpc, NodeDof, NodeIndex, RigidElement};

/// How u_b,d of a shell node is joined (module doc, rules 1–3).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Rule {
    /// u_b + u_t − 2 u_n = 0.
    Mean,
    /// −u_b + 4 u_m − u_t − 2 u_n = 0.
    Quadratic,
}

/// How one shell node is joined: its rule per direction, the dofs its `*BOUNDARY` holds, the
/// tangent axes it holds with the held rotation each came from, whether it is free (rule 3).
type NodeJoining = ([Rule; 3], DofMask, Vec<(Xyz, usize)>, bool);

/// The joining of every shell node.
pub(super) struct Joining {
    nodes: BTreeMap<NodeIndex, NodeJoining>,
}

impl Joining {
    pub(super) fn of(
        model: &Model,
        expanded: &BTreeMap<NodeIndex, Expanded>,
        place: &BTreeMap<NodeIndex, &Place>,
    ) -> Result<Joining, ImportError> {
        let err = |n: NodeIndex, msg: String| {
            parse_err(place[&n], format!("node {}", model.nodes[n].id), msg)
        };
        // rule 1: solids, springs, masses, equations, rigid elements
        let mut joined: BTreeSet<NodeIndex> = BTreeSet::new();
        for e in &model.elements {
            if e.property.is_none() {
                continue;
            }
            for n in e.nodes.iter().filter(|n| expanded.contains_key(n)) {
                if !e.kind.is_solid() {
                    return Err(err(
                        *n,
                        format!(
                            "a shell node of element {} (not a solid): ccx joins expanded \
                             beams and shells with a rigid knot, which flexbody does not form",
                            e.id
                        ),
                    ));
                }
                // a brick of an expanded shell has only new nodes: this is a solid of the deck
                joined.insert(*n);
            }
        }
        let mut touch = |n: NodeIndex, component: Option<u8>, what: &str| {
            if !expanded.contains_key(&n) {
                return Ok(());
            }
            if component.is_some_and(|c| c >= 3) {
                return Err(err(
                    n,
                    format!(
                        "{what} names a rotation of this shell node; expanded as ccx does, \
                         a shell node has translations only (ccx would form a rigid knot)"
                    ),
                ));
            }
            joined.insert(n);
            Ok(())
        };
        for m in &model.point_masses {
            let rotary = m.inertia.iter().flatten().any(|v| *v != 0.0);
            touch(m.node, rotary.then_some(3), "a *ROTARY INERTIA")?;
        }
        for s in &model.springs {
            for d in std::iter::once(s.a).chain(s.b) {
                touch(d.node, Some(d.component), "a spring")?;
            }
        }
        for s in &model.scalar_masses {
            for d in std::iter::once(s.a).chain(s.b) {
                touch(d.node, Some(d.component), "a mass")?;
            }
        }
        for b in &model.bushes {
            for n in std::iter::once(b.a).chain(b.b) {
                touch(n, Some(3), "a bush")?;
            }
        }
        for m in &model.mpcs {
            for (d, _) in &m.terms {
                touch(d.node, Some(d.component), "an *EQUATION")?;
            }
        }
        for r in &model.rigid_bodies {
            for (n, mask) in r.independent.iter().chain(&r.dependent) {
                touch(*n, mask.dofs().max().map(|k| k as u8), "a rigid body")?;
            }
        }
        for r in &model.rigid_elements {
            match r {
                RigidElement::Rbe2 {
                    independent,
                    dependent,
                    ..
                } => {
                    touch(*independent, Some(3), "the reference node of a rigid body")?;
                    for n in dependent {
                        touch(*n, None, "a rigid body")?;
                    }
                }
                RigidElement::Rbe3 {
                    reference,
                    independent,
                    ..
                } => {
                    touch(*reference, Some(3), "the reference node of a coupling")?;
                    for (n, _, mask) in independent {
                        touch(*n, mask.dofs().max().map(|k| k as u8), "a coupling")?;
                    }
                }
            }
        }
        let mut held: BTreeMap<NodeIndex, DofMask> = BTreeMap::new();
        for s in model.spcs.iter().filter(|s| expanded.contains_key(&s.node)) {
            let h = held.entry(s.node).or_insert(DofMask(0));
            *h = h.union(s.dofs);
        }
        let mut nodes = BTreeMap::new();
        for (&n, e) in expanded {
            let held = held.get(&n).copied().unwrap_or(DofMask(0));
            let rule = |d: usize| {
                if joined.contains(&n) || held.contains(d) || e.middle.is_none() {
                    Rule::Mean
                } else {
                    Rule::Quadratic
                }
            };
            let axes = held_axes(held, e.normal);
            if !axes.is_empty() && model.nodes[n].displacement_frame.is_some() {
                return Err(err(
                    n,
                    "a rotation held in a *TRANSFORM frame of a shell node is not supported".into(),
                ));
            }
            let free = !joined.contains(&n) && held.0 == 0;
            nodes.insert(n, ([rule(0), rule(1), rule(2)], held, axes, free));
        }
        Ok(Joining { nodes })
    }

    /// The equations (`free_node_dependent`: [`expand_elements`]).
    pub(super) fn write(
        &self,
        model: &mut Model,
        expanded: &BTreeMap<NodeIndex, Expanded>,
        free_node_dependent: bool,
    ) {
        let dof = |node: NodeIndex, d: usize| NodeDof {
            node,
            component: d as u8,
        };
        for (&n, (rules, held, axes, free)) in &self.nodes {
            let e = expanded[&n];
            // the equations of a shell node are known by its id in messages
            let id = model.nodes[n].id;
            // u_b,d = Σ terms (the rule solved for the bottom node)
            let bottom = |d: usize| -> Vec<(NodeDof, f64)> {
                match rules[d] {
                    Rule::Mean => vec![(dof(n, d), 2.0), (dof(e.top, d), -1.0)],
                    Rule::Quadratic => {
                        let m = e.middle.expect("the quadratic rule is for middle nodes");
                        vec![(dof(m, d), 4.0), (dof(e.top, d), -1.0), (dof(n, d), -2.0)]
                    }
                }
            };
            let free = free_node_dependent && *free;
            for d in 0..3 {
                let mut terms = vec![(dof(e.bottom, d), 1.0)];
                terms.extend(bottom(d).into_iter().map(|(k, c)| (k, -c)));
                if free {
                    // the same equation with u_n first (its coefficient made 1)
                    let k = (terms.iter().position(|(k, _)| k.node == n))
                        .expect("rules 1 and 3 name the shell node n");
                    let (_, c) = terms[k];
                    terms.swap(0, k);
                    terms.iter_mut().for_each(|t| t.1 /= c);
                }
                model.mpcs.push(Mpc { id, terms });
                if let (true, Some(m)) = (held.contains(d), e.middle) {
                    let terms = vec![(dof(m, d), 1.0), (dof(n, d), -1.0)];
                    model.mpcs.push(Mpc { id, terms });
                }
            }
            // the held rotations: (e × n)·(u_t − u_b) − h θ_n,k = 0 with u_b substituted; the
            // held rotation k of n stands for ccx's angle node (held at 0 as n's rotation is)
            let x = |k: NodeIndex| model.nodes[k].x;
            let h = dot(sub(x(e.top), x(e.bottom)), e.normal);
            let mut rows: Vec<BTreeMap<NodeDof, f64>> = Vec::new();
            for &(a, k) in axes {
                let c = cross(a, e.normal);
                let mut row: BTreeMap<NodeDof, f64> = BTreeMap::new();
                row.insert(dof(n, k), -h);
                for (d, cd) in c.into_iter().enumerate() {
                    *row.entry(dof(e.top, d)).or_default() += cd;
                    for (k, v) in bottom(d) {
                        *row.entry(k).or_default() -= cd * v;
                    }
                }
                rows.push(row);
            }
            for row in eliminate_top(rows, e.top) {
                model.mpcs.push(Mpc { id, terms: row });
            }
        }
    }
}

/// The tangent axes ccx holds for a node whose `*BOUNDARY` holds rotations `held` (gen3dboun,
/// module doc), in the order ccx reads the dofs.
fn held_axes(held: DofMask, normal: Xyz) -> Vec<(Xyz, usize)> {
    let mut axes: Vec<(Xyz, usize)> = Vec::new();
    for k in (3..6).filter(|&k| held.contains(k)) {
        let mut a = [0.0; 3];
        a[k - 3] = 1.0;
        let along = dot(a, normal);
        if along.abs() > DRILLING {
            continue;
        }
        match axes.first() {
            None => {
                let p = sub(a, normal.map(|c| c * along));
                let e1 = unit(p).expect("an axis off the normal has a tangent part");
                axes.push((e1, k));
            }
            Some(&(e1, _)) if axes.len() == 1 && dot(a, e1) <= SAME_AXIS => {
                axes.push((unit(cross(normal, e1)).expect("n ⟂ e1, both unit"), k));
            }
            Some(_) => {}
        }
    }
    axes
}

/// Rows Σ c u = 0, each made an equation whose dependent dof is a top-node dof: the largest
/// coefficient on the top node, eliminated from the rows after it (no chain between them).
fn eliminate_top(
    mut rows: Vec<BTreeMap<NodeDof, f64>>,
    top: NodeIndex,
) -> Vec<Vec<(NodeDof, f64)>> {
    let mut out = Vec::new();
    for i in 0..rows.len() {
        let pivot = (rows[i].iter())
            .filter(|(k, v)| k.node == top && v.abs() > 1e-12)
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .map(|(k, v)| (*k, *v));
        let Some((pk, pv)) = pivot else {
            continue;
        };
        let this = rows[i].clone();
        for row in rows.iter_mut().skip(i + 1) {
            let f = row.get(&pk).copied().unwrap_or(0.0) / pv;
            if f != 0.0 {
                for (k, v) in &this {
                    *row.entry(*k).or_default() -= f * v;
                }
                row.remove(&pk);
            }
        }
        let mut terms = vec![(pk, pv)];
        terms.extend((this.into_iter()).filter(|(k, v)| *k != pk && v.abs() > 1e-14 * pv.abs()));
        out.push(terms);
    }
    out
}
