//! Interfaces: the `--interface` entries → interface nodes; a node set becomes a spider to a
//! new centre node ([`resolve_interfaces`]), so the model leaves this stage with those nodes and
//! rigid elements added, and with a node at each point mass's offset centre of gravity
//! (`model::offset_mass`).

use crate::model::offset_mass::place_offset_masses;
use crate::model::Model;
use crate::pipeline::interface::resolve_interfaces;
use crate::pipeline::plan::Plan;
use crate::pipeline::scene::scene_loads;
use crate::pipeline::stages::WithInterfaces;
use crate::pipeline::{BuildError, BuildMethod};

/// The interfaces stage: the request checked against the method, the interfaces attached, the
/// scene's loads checked against the model (a bad `--load`/`--gravity` is reported now, not
/// after the reduction).
pub fn interfaces(plan: &Plan, model: Model) -> Result<WithInterfaces, BuildError> {
    let spec = &plan.spec;
    if spec.method != BuildMethod::Normal && spec.interface.is_empty() {
        return Err(plan.request_error(format!(
            "{:?} needs interface nodes: give --interface with node ids or node-set names",
            spec.method
        )));
    }
    if !spec.reference_conditions.is_empty()
        && matches!(spec.method, BuildMethod::CraigChang | BuildMethod::Dietz)
    {
        return Err(plan.request_error("reference conditions are defined for normal modes and Craig–Bampton (improved CB methods 1 and 2), not for Craig–Chang or Dietz".into()));
    }
    let interfaced = attach(plan, model)?;
    scene_loads(&interfaced.model, &spec.scene).map_err(|e| plan.request_error(e.to_string()))?;
    Ok(interfaced)
}

/// The interfaces attached to `model` as `plan` asks, nothing checked; then the offset point
/// masses placed on nodes of their own (after the spiders, so that spider centre ids do not
/// depend on them).
pub fn attach(plan: &Plan, mut model: Model) -> Result<WithInterfaces, BuildError> {
    let interfaces = resolve_interfaces(&mut model, &plan.spec.interface, plan.spec.spider)?;
    let mass_nodes = place_offset_masses(&mut model);
    let interface_nodes = interfaces
        .iter()
        .flat_map(|r| r.nodes.iter().copied())
        .collect();
    Ok(WithInterfaces {
        model,
        interfaces,
        interface_nodes,
        mass_nodes,
    })
}
