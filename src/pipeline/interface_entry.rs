//! The file's `interfaces.bin` (format 1.3) from what [`crate::pipeline::interface`] resolved: per
//! interface node of `method.bin`, in the same order, its name, how it is attached, the
//! external ids of the mesh nodes it depends on and the spider's centre fit.
use std::collections::HashMap;

use flexbody_reader as file;

use crate::model::Model;
use crate::pipeline::interface::{CentreMethod, InterfaceReport, SpiderKind};

/// One [`file::InterfaceInfo`] per interface node of `reports` (their `nodes` flattened, the
/// order `method.bin` lists them in); `body_nodes` are the stored nodes, whose positions the
/// entry indexes. `None` when there is no interface node (the body then stays at the oldest
/// version that has its other entries) or one is not stored (cannot happen for a build:
/// interface nodes are always kept).
pub fn interfaces_entry(
    model: &Model,
    reports: &[InterfaceReport],
    body_nodes: &[file::Node],
) -> Option<Vec<file::InterfaceInfo>> {
    let position: HashMap<u64, u32> = body_nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.id, i as u32))
        .collect();
    let mut out = Vec::new();
    for r in reports {
        for &n in &r.nodes {
            let node = *position.get(&model.nodes[n].id)?;
            let (kind, dependent, fit) = match &r.spider {
                None => (file::InterfaceKind::Node, Vec::new(), None),
                Some(s) => (
                    match s.kind {
                        SpiderKind::Rbe3 => file::InterfaceKind::Rbe3,
                        _ => file::InterfaceKind::Rbe2,
                    },
                    s.legs.iter().map(|&l| model.nodes[l].id).collect(),
                    Some(file::CentreFit {
                        method: match s.method {
                            CentreMethod::CylinderFit => file::FitMethod::CylinderFit,
                            CentreMethod::FaceAreaCentroid => file::FitMethod::FaceAreaCentroid,
                            CentreMethod::NodeAverage => file::FitMethod::NodeAverage,
                        },
                        centre: s.centre,
                        axis: s.axis,
                        radius: s.radius,
                        offset_from_node_average: s.offset_from_node_average,
                    }),
                ),
            };
            out.push(file::InterfaceInfo {
                node,
                name: r.name.clone(),
                kind,
                dependent,
                fit,
            });
        }
    }
    (!out.is_empty()).then_some(out)
}
