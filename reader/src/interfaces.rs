//! Entry `interfaces.bin` (format 1.3, optional): what each interface node of `method.bin`
//! stands for — its name (the node set it came from, or `NODE<id>`), how it is attached to the
//! mesh (a rigid RBE2 or averaging RBE3 spider, or a mesh node itself), the external ids of the
//! mesh nodes it depends on, and where a spider's centre was placed (SPEC.md §5.13). A solver
//! uses it to attach joints by name and to build markers over a bore's nodes without reading
//! the model again.
use serde::{Deserialize, Serialize};

use crate::codec::INTERFACES;
use crate::error::ReadError;
use crate::types::ReducedBody;

/// How an interface node is attached to the mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum InterfaceKind {
    /// A mesh node named directly (no dependent nodes).
    Node,
    /// Centre node of a rigid (RBE2-type) spider: the dependent nodes' translations follow it
    /// rigidly.
    Rbe2,
    /// Reference node of a weighted-average (RBE3-type) spider: it moves with the average of
    /// the dependent nodes (unit weights, translations).
    Rbe3,
}

/// How a spider's centre was placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FitMethod {
    /// On the axis of a cylinder fitted to the set's faces (bores); `axis` and `radius` given.
    CylinderFit,
    /// Area-weighted centroid of the set's free faces.
    FaceAreaCentroid,
    /// Plain average of the set's nodes (the set carries no free face).
    NodeAverage,
}

/// Where a spider's centre went and how.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CentreFit {
    /// How the centre was found.
    pub method: FitMethod,
    /// The centre (equals the interface node's position).
    pub centre: [f64; 3],
    /// Unit axis of the fitted cylinder (present exactly for `CylinderFit`).
    pub axis: Option<[f64; 3]>,
    /// Radius of the fitted cylinder (present exactly for `CylinderFit`), > 0.
    pub radius: Option<f64>,
    /// Distance from the plain average of the dependent nodes (≥ 0).
    pub offset_from_node_average: f64,
}

/// One interface node's metadata; `interfaces.bin` holds one per `method.interface` element, in
/// the same order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InterfaceInfo {
    /// 0-based index into the node list; equals `method.interface[i].node`.
    pub node: u32,
    /// The node set's name as the model spells it, or `NODE<id>` for a node named by its id.
    /// Several nodes share a name when a node set was attached without a spider.
    pub name: String,
    /// How the node is attached.
    pub kind: InterfaceKind,
    /// External ids of the mesh nodes the interface node depends on (the spider's legs), in the
    /// set's order; empty for `Node`. They need not be stored nodes.
    pub dependent: Vec<u64>,
    /// The spider's centre fit (present exactly for `Rbe2` and `Rbe3`).
    pub fit: Option<CentreFit>,
}

fn inconsistent(rule: String) -> ReadError {
    ReadError::Inconsistent {
        entry: INTERFACES.into(),
        rule,
    }
}

fn finite(field: String, values: &[f64]) -> Result<(), ReadError> {
    match values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        Some((i, v)) => Err(ReadError::NonFinite {
            entry: INTERFACES.into(),
            field,
            index: i as u64,
            value: *v,
        }),
        None => Ok(()),
    }
}

/// Tolerance of the unit-axis and centre-at-node rules (relative).
pub const FIT_TOL: f64 = 1e-9;

/// Rule 14 (SPEC.md §6): `interfaces.bin` describes exactly the interface nodes of `method.bin`.
pub(crate) fn validate_interfaces(
    list: &[InterfaceInfo],
    body: &ReducedBody,
) -> Result<(), ReadError> {
    let method = &body.method.interface;
    if list.len() != method.len() {
        return Err(ReadError::CountMismatch {
            entry: INTERFACES.into(),
            field: "interfaces".into(),
            expected: method.len() as u64,
            found: list.len() as u64,
            rule: "one per interface node of method.bin".into(),
        });
    }
    for (i, (info, rec)) in list.iter().zip(method).enumerate() {
        if info.node != rec.node {
            return Err(inconsistent(format!(
                "interfaces[{i}].node = {} but method.interface[{i}].node = {}",
                info.node, rec.node
            )));
        }
        if info.name.is_empty() {
            return Err(inconsistent(format!("interfaces[{i}].name is empty")));
        }
        // Rule 8 checked rec.node < N.
        let node = &body.nodes[rec.node as usize];
        let spider = info.kind != InterfaceKind::Node;
        if spider == info.dependent.is_empty() || spider != info.fit.is_some() {
            return Err(inconsistent(format!(
                "interfaces[{i}] ({}): a {:?} node has {} dependent nodes and {} centre fit",
                info.name,
                info.kind,
                info.dependent.len(),
                if info.fit.is_some() { "a" } else { "no" }
            )));
        }
        let mut ids = info.dependent.clone();
        ids.sort_unstable();
        if let Some(w) = ids.windows(2).find(|w| w[0] == w[1]) {
            return Err(inconsistent(format!(
                "interfaces[{i}] ({}): dependent node {} is listed twice",
                info.name, w[0]
            )));
        }
        if ids.binary_search(&node.id).is_ok() {
            return Err(inconsistent(format!(
                "interfaces[{i}] ({}): node {} depends on itself",
                info.name, node.id
            )));
        }
        let Some(fit) = &info.fit else { continue };
        finite(format!("interfaces[{i}].fit.centre"), &fit.centre)?;
        if let Some(a) = &fit.axis {
            finite(format!("interfaces[{i}].fit.axis"), a)?;
        }
        if let Some(r) = fit.radius {
            finite(format!("interfaces[{i}].fit.radius"), &[r])?;
        }
        finite(
            format!("interfaces[{i}].fit.offset_from_node_average"),
            &[fit.offset_from_node_average],
        )?;
        let cylinder = fit.method == FitMethod::CylinderFit;
        if cylinder != fit.axis.is_some() || cylinder != fit.radius.is_some() {
            return Err(inconsistent(format!(
                "interfaces[{i}] ({}): axis and radius must be given exactly for CylinderFit",
                info.name
            )));
        }
        if let Some(a) = fit.axis {
            let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            if (norm - 1.0).abs() > FIT_TOL {
                return Err(inconsistent(format!(
                    "interfaces[{i}] ({}): axis length {norm} is not 1",
                    info.name
                )));
            }
        }
        if let Some(r) = fit.radius {
            if r <= 0.0 {
                return Err(inconsistent(format!(
                    "interfaces[{i}] ({}): radius {r} must be > 0",
                    info.name
                )));
            }
        }
        if fit.offset_from_node_average < 0.0 {
            return Err(inconsistent(format!(
                "interfaces[{i}] ({}): offset_from_node_average {} must be ≥ 0",
                info.name, fit.offset_from_node_average
            )));
        }
        let scale = fit
            .centre
            .iter()
            .chain(&node.xyz)
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let gap = (0..3).fold(0.0f64, |m, k| m.max((fit.centre[k] - node.xyz[k]).abs()));
        if gap > FIT_TOL * scale {
            return Err(inconsistent(format!(
                "interfaces[{i}] ({}): centre {:?} is not node {}'s position {:?}",
                info.name, fit.centre, node.id, node.xyz
            )));
        }
    }
    Ok(())
}
