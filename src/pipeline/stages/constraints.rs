//! Constraints: rigid elements, SPCs and held components eliminated (u = T u_r, [`eliminate`]);
//! the interface and reference dofs numbered among the independent ones; the model checked
//! before the reduction ([`before_reduction`]); the model's own SPCs recorded as reference
//! conditions.

use std::collections::BTreeMap;

use crate::fe::{eliminate, Assembled, ConstraintSpec, DofMap, Reduced};
use crate::model::{DofMask, Model, NodeIndex};
use crate::pipeline::deck::{node_mask, reference_entries};
use crate::pipeline::interface::reference_names;
use crate::pipeline::plan::Plan;
use crate::pipeline::precheck::{before_reduction, expected_rigid_motions};
use crate::pipeline::stages::empty_matrix;
use crate::pipeline::stages::WithInterfaces;
use crate::pipeline::stages::{Constrained, ReferenceNodes};
use crate::pipeline::{BuildError, BuildReport};

/// The constraints stage.
pub fn constraints(
    plan: &Plan,
    interfaced: &WithInterfaces,
    mut assembled: Assembled,
    report: &mut BuildReport,
) -> Result<Constrained, BuildError> {
    let reduced = eliminate_constraints(interfaced, &assembled)?;
    // The physical K is not used past the elimination (the reduction works on reduced.k; the
    // invariants and mass points use M): free it before the factorization, the build's peak
    // (issue 22: 16 bytes per non-zero, ~0.6 GB at 519k tet10 dofs).
    assembled.k = empty_matrix();
    report.dofs = (assembled.dofs.n_dofs, reduced.retained.len());
    let independent = Independent::new(plan, &interfaced.model, &assembled.dofs, &reduced);
    // Interface and reference dofs: the free components (held ones drop out of plain ids; a
    // held component given explicitly is an error naming its constraint).
    let mut dropped: Vec<String> = Vec::new();
    let (interface_dofs, interface_masks) = interface_dofs(&independent, interfaced, &mut dropped)?;
    let (reference_dofs, mut reference_nodes) =
        reference_dofs(&independent, interfaced, &mut dropped)?;
    if !dropped.is_empty() {
        report.notes.push(format!(
            "held components (GRID PS / GRDSET / selected SPC) are not interface or reference dofs: {}",
            dropped.join(", ")
        ));
    }
    // what a flexible body cannot hold of springs, scalar masses and scalar points
    let lumped = plan.spec.mass == crate::fe::MassKind::Lumped;
    if let Some(why) = crate::fe::connectors::body_restrictions(
        &interfaced.model,
        &assembled.dofs,
        &assembled.m,
        lumped,
    ) {
        return Err(plan.request_error(why));
    }
    // parts, masses, interface and reference restraints, named by ids (docs/stability.md)
    before_reduction(
        &interfaced.model,
        &assembled.dofs,
        &assembled.m,
        plan.spec.method,
        &interfaced.interface_nodes,
        &reference_nodes,
    )
    .map_err(|e| plan.request_error(e))?;
    hold_model_spcs(
        &interfaced.model,
        &assembled.dofs,
        &mut reference_nodes,
        report,
    );
    let expected_rigid =
        expected_rigid_motions(&interfaced.model, &assembled.dofs, &reference_nodes);
    Ok(Constrained {
        assembled,
        reduced,
        interface_dofs,
        interface_masks,
        reference_dofs,
        reference_nodes,
        expected_rigid,
    })
}

/// u = T u_r for the model's rigid elements, SPCs and held components; RBE3 spiders at
/// interface nodes keep their centre independent (UM-style).
pub fn eliminate_constraints(
    interfaced: &WithInterfaces,
    assembled: &Assembled,
) -> Result<Reduced, BuildError> {
    Ok(eliminate(
        &interfaced.model,
        &assembled.dofs,
        &assembled.k,
        &assembled.m,
        &ConstraintSpec {
            independent_rbe3_reference: interfaced.interface_nodes.clone(),
            ..Default::default()
        },
    )?)
}

/// The independent numbering of a node's components.
struct Independent<'a> {
    plan: &'a Plan,
    model: &'a Model,
    dofs: &'a DofMap,
    /// Physical dof → independent (reduced) dof; `usize::MAX` where eliminated.
    reduced_index: Vec<usize>,
}

impl<'a> Independent<'a> {
    fn new(plan: &'a Plan, model: &'a Model, dofs: &'a DofMap, reduced: &Reduced) -> Self {
        let mut reduced_index = vec![usize::MAX; dofs.n_dofs];
        for (r, &p) in reduced.retained.iter().enumerate() {
            reduced_index[p] = r;
        }
        Independent {
            plan,
            model,
            dofs,
            reduced_index,
        }
    }

    /// The number of components of `node`.
    fn count(&self, node: NodeIndex) -> usize {
        usize::from(self.dofs.count[node])
    }

    /// The independent dofs of `mask`'s components of `node`; an error when the node carries no
    /// dofs or one of them is eliminated (`what` names the node's role).
    fn of(&self, node: NodeIndex, mask: DofMask, what: &str) -> Result<Vec<usize>, BuildError> {
        let id = self.model.nodes[node].id;
        let count = self.count(node);
        if count == 0 {
            return Err(self.plan.request_error(format!("{what} node {id} carries no dofs (no element, mass or rigid element attaches to it)")));
        }
        mask.dofs()
            .filter(|&c| c < count)
            .map(|c| {
                let r = self.reduced_index[self.dofs.first[node] + c];
                if r == usize::MAX {
                    Err(self.plan.request_error(format!(
                        "{what} node {id} dof {} is not independent: {}",
                        c + 1,
                        dependent_dof_cause(self.model, node, c)
                    )))
                } else {
                    Ok(r)
                }
            })
            .collect()
    }

    /// The free components of `node` (`explicit`: the ones asked for) and the held ones, by
    /// [`node_mask`].
    fn mask(
        &self,
        node: NodeIndex,
        explicit: Option<DofMask>,
        what: &str,
    ) -> Result<(DofMask, DofMask), BuildError> {
        node_mask(self.model, node, self.count(node), explicit, what)
            .map_err(|e| self.plan.request_error(e))
    }
}

/// Why component `c` (0-based) of `node` is eliminated, with advice that applies to a plain
/// node id (issue 47): the RBE2 that drives it (id, `file:line`, its independent node), else an
/// SPC, else the other dependent-dof makers.
fn dependent_dof_cause(model: &Model, node: NodeIndex, c: usize) -> String {
    use crate::model::RigidElement;
    let rbe2 = model.rigid_elements.iter().find_map(|r| match r {
        RigidElement::Rbe2 {
            id,
            independent,
            dependent,
            dofs,
        } if dofs.contains(c) && dependent.contains(&node) => Some((*id, *independent)),
        RigidElement::Rbe2 { .. } | RigidElement::Rbe3 { .. } => None,
    });
    if let Some((id, independent)) = rbe2 {
        let place = model
            .element_location(id)
            .map_or(String::new(), |l| format!(" ({l})"));
        return format!(
            "RBE2 {id}{place} makes it follow its independent node {}; give that node (--interface {}) \
             or a node no rigid element drives",
            model.nodes[independent].id, model.nodes[independent].id
        );
    }
    if model
        .spcs
        .iter()
        .any(|s| s.node == node && s.dofs.contains(c))
    {
        return "the model's SPC holds it; give a free node, or leave this component out with \
                NODE:DOFS (e.g. 7:123)"
            .to_owned();
    }
    "it is a dependent dof of a rigid element (RBE3 reference, RBAR, RBE1) or an MPC; give one \
     of that element's independent nodes or a node no constraint drives"
        .to_owned()
}

/// The interface dofs (independent numbering) and each interface node's components.
fn interface_dofs(
    independent: &Independent,
    interfaced: &WithInterfaces,
    dropped: &mut Vec<String>,
) -> Result<(Vec<usize>, Vec<DofMask>), BuildError> {
    let mut dofs = Vec::new();
    let mut masks = Vec::new();
    for r in &interfaced.interfaces {
        for &n in &r.nodes {
            let (mask, held) = independent.mask(n, r.dofs, "interface")?;
            if held.0 != 0 {
                dropped.push(format!(
                    "interface node {} ({})",
                    interfaced.model.nodes[n].id,
                    held.digits()
                ));
            }
            dofs.extend(independent.of(n, mask, "interface")?);
            masks.push(mask);
        }
    }
    Ok((dofs, masks))
}

/// The reference-condition dofs (independent numbering) and components per node: the
/// `NODE:DOFS` pairs, the entries by interface name, then node sets and the deck's constraint
/// sets.
fn reference_dofs(
    independent: &Independent,
    interfaced: &WithInterfaces,
    dropped: &mut Vec<String>,
) -> Result<(Vec<usize>, ReferenceNodes), BuildError> {
    let (model, plan) = (&interfaced.model, independent.plan);
    let by_id = model.node_index_by_id();
    let mut dofs = Vec::new();
    let mut nodes = Vec::new();
    // Reference conditions by interface name (`BIG_END:123456`) are node ids from here on.
    let (named_references, reference_sets) =
        reference_names(model, &interfaced.interfaces, &plan.spec.reference_sets)?;
    for &(id, mask) in plan
        .spec
        .reference_conditions
        .iter()
        .chain(&named_references)
    {
        let node = *by_id.get(&id).ok_or_else(|| {
            plan.request_error(format!("reference-condition node {id} does not exist"))
        })?;
        // All six digits mean "the node": its free components.
        let explicit = (mask != DofMask::ALL).then_some(mask);
        let (mask, held) = independent.mask(node, explicit, "reference-condition")?;
        if held.0 != 0 {
            dropped.push(format!("reference node {id} ({})", held.digits()));
        }
        dofs.extend(independent.of(node, mask, "reference-condition")?);
        nodes.push((node, mask));
    }
    for (node, explicit, entry) in
        reference_entries(model, &reference_sets).map_err(|e| plan.request_error(e))?
    {
        let (mask, held) = independent.mask(node, None, "reference-condition")?;
        // A constraint set's components, less the held ones (they are held already).
        let mask = DofMask(mask.0 & explicit.map_or(0x3f, |m| m.0));
        if held.0 != 0 && explicit.is_none_or(|m| m.0 & held.0 != 0) {
            dropped.push(format!(
                "reference {entry} node {} ({})",
                model.nodes[node].id,
                held.digits()
            ));
        }
        if mask.0 == 0 {
            continue;
        }
        dofs.extend(independent.of(node, mask, "reference-condition")?);
        merge_reference(&mut nodes, node, mask);
    }
    Ok((dofs, nodes))
}

/// `mask` added to `node`'s reference components (a new entry when it has none).
fn merge_reference(nodes: &mut ReferenceNodes, node: NodeIndex, mask: DofMask) {
    match nodes.iter_mut().find(|r| r.0 == node) {
        Some(r) => r.1 = DofMask(r.1 .0 | mask.0),
        None => nodes.push((node, mask)),
    }
}

/// The model's own SPCs hold the body too: recorded with the reference conditions, so the file
/// (and `check`) say the modes are those of a supported body; a note for permanent constraints
/// only (GRID PS / GRDSET: a planar or restricted model), a warning otherwise.
fn hold_model_spcs(
    model: &Model,
    dofs: &DofMap,
    reference_nodes: &mut ReferenceNodes,
    report: &mut BuildReport,
) {
    let mut held: BTreeMap<NodeIndex, u8> = Default::default();
    for s in &model.spcs {
        let existing = (1u8 << dofs.count.get(s.node).copied().unwrap_or(0)) - 1;
        if s.dofs.0 & existing != 0 {
            *held.entry(s.node).or_default() |= s.dofs.0 & existing;
        }
    }
    if held.is_empty() {
        return;
    }
    let only_permanent = model.constraint_sources.iter().all(|c| c.permanent)
        && model
            .constraint_sources
            .iter()
            .map(|c| c.spcs.len())
            .sum::<usize>()
            == model.spcs.len();
    let held_dofs = held.values().map(|m| m.count_ones()).sum::<u32>();
    if only_permanent {
        report.notes.push(format!(
            "the deck's permanent constraints (GRID PS / GRDSET) hold {held_dofs} dofs at {} nodes: the body moves only in its free components (recorded as reference conditions)",
            held.len()
        ));
    } else {
        report.warnings.push(format!(
            "the model's SPCs hold {held_dofs} dofs at {} nodes: the modes are those of the supported body, not free-free (recorded as reference conditions)",
            held.len()
        ));
    }
    for (node, m) in held {
        merge_reference(reference_nodes, node, DofMask(m));
    }
}
