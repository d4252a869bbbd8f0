//! Interface definition: turn the user's `--interface` list (node ids, `NODE:DOFS` with Nastran
//! component digits, and node-set names) into
//! interface nodes, building a spider for each node set the way engineers attach joints to solid
//! meshes (docs/design.md §3 "Interface spiders").
//!
//! A node set becomes, by default, a rigid RBE2-type spider from a new centre node to every node
//! of the set (dependent dofs 123: the set's nodes are solid nodes); `Rbe3` makes the centre node
//! the weighted average of the set instead (unit weights, dofs 123; it adds no stiffness, and
//! `build` keeps its centre independent so it can be a Craig–Bampton interface node — see
//! `fe::constraints`); `None` makes every node of the set an interface node. A set of one node
//! that is already a spider's reference node (a CalculiX `*COUPLING`'s CONSTRAINT NAME) is that
//! node, with no new spider.
//!
//! The centre is never the plain node average: on an unevenly meshed bore that drifts off the
//! axis (0.77 mm on a 25 mm bore in the case that motivated this). In order of preference:
//! 1. **Cylinder fit** when the set's free faces form a (part of a) cylinder — their area-weighted
//!    normal scatter N = Σ A_f n_f n_fᵀ has one near-zero eigenvalue, whose eigenvector is the
//!    axis — and the set's nodes lie on a circle about it (algebraic circle fit in the plane ⊥
//!    axis, every node within 1e-3·R): the centre is on the fitted axis, at the area-weighted
//!    mean axial position. Exact for nodes on a true cylinder, whatever their spacing.
//! 2. **Area-weighted centroid of the set's free faces**, c = Σ A_f c_f / Σ A_f (plane patches).
//! 3. The node average, only if the set carries no free face (a cloud of nodes); reported.

use std::collections::BTreeSet;

use crate::body::faces::graphics_faces;
use crate::model::geometry::{cross, dot, norm, sub};
use crate::model::{DofMask, Model, Node, NodeIndex, RigidElement};

/// How a node set named as an interface is attached.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpiderKind {
    /// Rigid spider (RBE2-type) from a new centre node.
    #[default]
    Rbe2,
    /// Weighted-average spider (RBE3-type) to a new centre node.
    Rbe3,
    /// No spider: every node of the set is an interface node.
    None,
}

/// How the centre of a spider was placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CentreMethod {
    /// On the axis of a cylinder fitted to the set (bores).
    CylinderFit,
    /// Area-weighted centroid of the set's free faces.
    FaceAreaCentroid,
    /// Plain average of the set's nodes (no free face lies in the set).
    NodeAverage,
}

/// What was done for one entry of the interface list.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceReport {
    /// The entry as given (set name or node id, optionally with `:DOFS`).
    pub entry: String,
    /// The interface's name: the node set's name as the model spells it, or `NODE<id>`.
    pub name: String,
    /// Interface node(s) it produced (dense indices into the model's nodes).
    pub nodes: Vec<NodeIndex>,
    /// Components given explicitly (`NODE:DOFS`, Nastran digits); `None` = every free component.
    pub dofs: Option<DofMask>,
    /// For a spider: the centre, how it was found, and how far it is from the plain node average.
    pub spider: Option<SpiderReport>,
}

/// Where a spider's centre node went.
#[derive(Debug, Clone, PartialEq)]
pub struct SpiderReport {
    /// External id of the new centre node.
    pub centre_node_id: u64,
    /// Its position.
    pub centre: [f64; 3],
    /// How the centre was computed.
    pub method: CentreMethod,
    /// Distance between `centre` and the plain node average of the set.
    pub offset_from_node_average: f64,
    /// Number of nodes in the set.
    pub set_nodes: usize,
    /// RBE2 or RBE3.
    pub kind: SpiderKind,
    /// The set's nodes (the spider's legs), dense indices in the set's order.
    pub legs: Vec<NodeIndex>,
    /// Unit axis of the fitted cylinder (`CylinderFit` only).
    pub axis: Option<[f64; 3]>,
    /// Radius of the fitted cylinder (`CylinderFit` only).
    pub radius: Option<f64>,
}

/// A node set's centre as [`set_centre`] placed it.
struct Fit {
    centre: [f64; 3],
    method: CentreMethod,
    axis: Option<[f64; 3]>,
    radius: Option<f64>,
}

/// Errors resolving interfaces.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InterfaceError {
    /// Neither a node id nor a node-set name of the model.
    #[error("interface `{entry}` is neither a node id nor a node-set name in {source_file} (node sets: {known})")]
    Unknown {
        /// The entry.
        entry: String,
        /// Model file.
        source_file: String,
        /// The sets that exist.
        known: String,
    },
    /// A set with no nodes.
    #[error("interface node set `{0}` is empty")]
    EmptySet(String),
    /// `NODE:DOFS` with something other than a node id and Nastran component digits.
    #[error("interface `{0}`: expected NODE:DOFS with a node id and Nastran component digits 1–6, e.g. 1:126")]
    BadComponents(String),
    /// The same node is an interface node twice.
    #[error(
        "node {node_id} is named twice in the interface list (entries `{first}` and `{second}`)"
    )]
    Duplicate {
        /// External id.
        node_id: u64,
        /// First entry naming it.
        first: String,
        /// Second entry naming it.
        second: String,
    },
}

/// Whether `set` is one node that is the reference node of a spider the model already has (a
/// `*COUPLING`'s CONSTRAINT NAME): that node is the interface itself, no new spider.
fn spider_reference(model: &Model, set: &[NodeIndex]) -> bool {
    let [node] = set else { return false };
    model.rigid_elements.iter().any(|r| match r {
        RigidElement::Rbe2 { independent, .. } => independent == node,
        RigidElement::Rbe3 { reference, .. } => reference == node,
    })
}

/// Resolve `entries` into interface nodes, adding spider centre nodes and rigid elements to
/// `model` for node sets. An entry is a node id, `NODE<id>`, or a node-set name (matched
/// case-insensitively; a set wins over `NODE<id>`), optionally followed by `:DOFS` with Nastran
/// component digits (`BIG_END:123456`, `17:126`): the interface node(s) it names then carry
/// those components only.
pub fn resolve_interfaces(
    model: &mut Model,
    entries: &[String],
    spider: SpiderKind,
) -> Result<Vec<InterfaceReport>, InterfaceError> {
    let by_id = model.node_index_by_id();
    let mut reports = Vec::new();
    let mut seen: std::collections::HashMap<NodeIndex, String> = std::collections::HashMap::new();
    let mut faces = None;
    for entry in entries {
        let entry = entry.trim().to_string();
        // NAME:DOFS — explicit components.
        let (name, dofs) = match entry.split_once(':') {
            Some((n, d)) => {
                let mask = DofMask::from_digits(d)
                    .filter(|m| m.0 != 0)
                    .ok_or_else(|| InterfaceError::BadComponents(entry.clone()))?;
                (n.trim(), Some(mask))
            }
            None => (entry.as_str(), None),
        };
        let set = model
            .node_sets
            .iter()
            .find(|(set_name, _)| set_name.eq_ignore_ascii_case(name))
            .map(|(set_name, s)| (set_name.clone(), s.clone()));
        let report = match (set, node_by_name(name, &by_id)) {
            (Some((set_name, set)), _) => {
                if set.is_empty() {
                    return Err(InterfaceError::EmptySet(entry));
                }
                if spider == SpiderKind::None || spider_reference(model, &set) {
                    InterfaceReport {
                        entry: entry.clone(),
                        name: set_name,
                        nodes: set,
                        dofs,
                        spider: None,
                    }
                } else {
                    let faces = faces.get_or_insert_with(|| graphics_faces(model));
                    let fit = set_centre(model, &set, faces);
                    let centre = fit.centre;
                    let average = node_average(model, &set);
                    let centre_node_id = model.max_node_id() + 1;
                    let centre_index = model.nodes.len();
                    model.nodes.push(Node {
                        id: centre_node_id,
                        x: centre,
                        displacement_frame: None,
                    });
                    let rigid_id = model.max_element_id() + 1;
                    model.rigid_elements.push(match spider {
                        SpiderKind::Rbe3 => RigidElement::Rbe3 {
                            id: rigid_id,
                            reference: centre_index,
                            ref_dofs: DofMask::ALL,
                            independent: set
                                .iter()
                                .map(|&n| (n, 1.0, DofMask::TRANSLATIONS))
                                .collect(),
                        },
                        _ => RigidElement::Rbe2 {
                            id: rigid_id,
                            independent: centre_index,
                            dependent: set.clone(),
                            dofs: DofMask::TRANSLATIONS,
                        },
                    });
                    let offset = (0..3)
                        .map(|k| (centre[k] - average[k]).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    InterfaceReport {
                        entry: entry.clone(),
                        name: set_name,
                        nodes: vec![centre_index],
                        dofs,
                        spider: Some(SpiderReport {
                            centre_node_id,
                            centre,
                            method: fit.method,
                            offset_from_node_average: offset,
                            set_nodes: set.len(),
                            kind: spider,
                            legs: set,
                            axis: fit.axis,
                            radius: fit.radius,
                        }),
                    }
                }
            }
            (None, Some(index)) => InterfaceReport {
                entry: entry.clone(),
                name: format!("NODE{}", model.nodes[index].id),
                nodes: vec![index],
                dofs,
                spider: None,
            },
            (None, None) => {
                return Err(InterfaceError::Unknown {
                    entry,
                    source_file: model.source.clone(),
                    known: if model.node_sets.is_empty() {
                        "none".into()
                    } else {
                        model
                            .node_sets
                            .keys()
                            .cloned()
                            .collect::<Vec<_>>()
                            .join(", ")
                    },
                })
            }
        };
        for &n in &report.nodes {
            if let Some(first) = seen.insert(n, entry.clone()) {
                return Err(InterfaceError::Duplicate {
                    node_id: model.nodes[n].id,
                    first,
                    second: entry,
                });
            }
        }
        reports.push(report);
    }
    Ok(reports)
}

/// A node named by its id (`17`) or as `NODE17` (case-insensitive), if the model has it.
pub fn node_by_name(
    name: &str,
    by_id: &std::collections::HashMap<u64, NodeIndex>,
) -> Option<NodeIndex> {
    let digits = match name.get(..4) {
        Some(p) if p.eq_ignore_ascii_case("NODE") => &name[4..],
        _ => name,
    };
    digits
        .trim()
        .parse::<u64>()
        .ok()
        .and_then(|id| by_id.get(&id).copied())
}

/// Reference conditions resolved by name — (node id, components) — and the entries left over.
pub type NamedReferences = (Vec<(u64, DofMask)>, Vec<String>);

/// `--reference-conditions` entries that name interfaces: `NAME` or `NAME:DOFS` where NAME is
/// the name of an interface ([`InterfaceReport::name`] or its entry, case-insensitive) or
/// `NODE<id>`, resolved to (node id, components) — all six digits, or none, mean the node's
/// free components, as for `NODE:DOFS`. Returns those and the entries left for the deck's
/// sets (node sets that are not interfaces, SPC sets, plain ids).
pub fn reference_names(
    model: &Model,
    interfaces: &[InterfaceReport],
    entries: &[String],
) -> Result<NamedReferences, InterfaceError> {
    let by_id = model.node_index_by_id();
    let mut named = Vec::new();
    let mut rest = Vec::new();
    for entry in entries {
        let (name, dofs) = match entry.split_once(':') {
            Some((n, d)) => {
                let mask = DofMask::from_digits(d)
                    .filter(|m| m.0 != 0)
                    .ok_or_else(|| InterfaceError::BadComponents(entry.clone()))?;
                (n.trim(), Some(mask))
            }
            None => (entry.trim(), None),
        };
        let mask = dofs.unwrap_or(DofMask::ALL);
        let interface = interfaces.iter().find(|r| {
            r.name.eq_ignore_ascii_case(name)
                || r.entry
                    .split(':')
                    .next()
                    .is_some_and(|e| e.trim().eq_ignore_ascii_case(name))
        });
        if let Some(r) = interface {
            named.extend(r.nodes.iter().map(|&n| (model.nodes[n].id, mask)));
        } else if name
            .get(..4)
            .is_some_and(|p| p.eq_ignore_ascii_case("NODE"))
            && !model.node_sets.keys().any(|k| k.eq_ignore_ascii_case(name))
        {
            let index = node_by_name(name, &by_id).ok_or_else(|| InterfaceError::Unknown {
                entry: entry.clone(),
                source_file: model.source.clone(),
                known: "NODE<id> must name a node of the model".into(),
            })?;
            named.push((model.nodes[index].id, mask));
        } else if dofs.is_some() {
            // SET:DOFS for a node set that is not an interface: every node of the set.
            let set = model
                .node_sets
                .iter()
                .find(|(k, _)| k.eq_ignore_ascii_case(name))
                .ok_or_else(|| InterfaceError::Unknown {
                    entry: entry.clone(),
                    source_file: model.source.clone(),
                    known: model
                        .node_sets
                        .keys()
                        .cloned()
                        .collect::<Vec<_>>()
                        .join(", "),
                })?;
            named.extend(set.1.iter().map(|&n| (model.nodes[n].id, mask)));
        } else {
            rest.push(entry.clone());
        }
    }
    Ok((named, rest))
}

fn node_average(model: &Model, set: &[NodeIndex]) -> [f64; 3] {
    std::array::from_fn(|k| {
        set.iter().map(|&n| model.nodes[n].x[k]).sum::<f64>() / set.len() as f64
    })
}

/// Centre of a node set: cylinder fit, else area-weighted face centroid, else node average
/// (module doc). Faces are the free faces whose corners all lie in `set`, each split into a fan of
/// triangles from its first corner.
fn set_centre(model: &Model, set: &[NodeIndex], faces: &[crate::body::faces::GraphicsFace]) -> Fit {
    let members: BTreeSet<NodeIndex> = set.iter().copied().collect();
    // Triangles (area A, centroid c, unit normal n) of the set's faces.
    let mut tris: Vec<(f64, [f64; 3], [f64; 3])> = Vec::new();
    for f in faces
        .iter()
        .filter(|f| f.nodes.len() >= 3 && f.nodes.iter().all(|n| members.contains(n)))
    {
        let p0 = model.nodes[f.nodes[0]].x;
        for w in f.nodes[1..].windows(2) {
            let (p1, p2) = (model.nodes[w[0]].x, model.nodes[w[1]].x);
            let cr = cross(sub(p1, p0), sub(p2, p0));
            let norm = dot(cr, cr).sqrt();
            if norm > 0.0 {
                tris.push((
                    0.5 * norm,
                    std::array::from_fn(|k| (p0[k] + p1[k] + p2[k]) / 3.0),
                    cr.map(|v| v / norm),
                ));
            }
        }
    }
    let area: f64 = tris.iter().map(|t| t.0).sum();
    if area <= 0.0 {
        return Fit {
            centre: node_average(model, set),
            method: CentreMethod::NodeAverage,
            axis: None,
            radius: None,
        };
    }
    let centroid: [f64; 3] =
        std::array::from_fn(|k| tris.iter().map(|t| t.0 * t.1[k]).sum::<f64>() / area);
    match cylinder_axis_centre(model, set, &tris, area) {
        Some((centre, axis, radius)) => Fit {
            centre,
            method: CentreMethod::CylinderFit,
            axis: Some(axis),
            radius: Some(radius),
        },
        None => Fit {
            centre: centroid,
            method: CentreMethod::FaceAreaCentroid,
            axis: None,
            radius: None,
        },
    }
}

/// Cylinder fit of a face set: axis = eigenvector of the smallest eigenvalue of N = Σ A n nᵀ
/// (must be < 1e-2 of the largest while the middle one is not), then the algebraic (Kåsa) circle
/// fit x² + y² + D x + E y + F = 0 of the nodes in the plane ⊥ axis; `None` unless every node is
/// within 1e-3·R of the circle. Returns (centre, unit axis, radius).
fn cylinder_axis_centre(
    model: &Model,
    set: &[NodeIndex],
    tris: &[(f64, [f64; 3], [f64; 3])],
    area: f64,
) -> Option<([f64; 3], [f64; 3], f64)> {
    let n = faer::Mat::from_fn(3, 3, |r, c| {
        tris.iter().map(|t| t.0 * t.2[r] * t.2[c]).sum::<f64>() / area
    });
    let eig = n.self_adjoint_eigen(faer::Side::Lower).ok()?;
    let s = eig.S();
    let (l0, l1, l2) = (s[0], s[1], s[2]);
    if !(l0 < 1e-2 * l2 && l1 > 1e-2 * l2) {
        return None;
    }
    let axis: [f64; 3] = std::array::from_fn(|k| eig.U()[(k, 0)]);
    // Orthonormal u, v ⊥ axis.
    let seed = if axis[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let u = normalize(cross(axis, seed));
    let v = cross(axis, u);
    let pts: Vec<[f64; 2]> = set
        .iter()
        .map(|&i| [dot(model.nodes[i].x, u), dot(model.nodes[i].x, v)])
        .collect();
    // Normal equations of min Σ (D x + E y + F + x² + y²)², shifted to the mean for conditioning.
    let m = pts.len() as f64;
    let mean = [
        pts.iter().map(|p| p[0]).sum::<f64>() / m,
        pts.iter().map(|p| p[1]).sum::<f64>() / m,
    ];
    let mut a = [[0.0; 3]; 3];
    let mut b = [0.0; 3];
    for p in &pts {
        let (x, y) = (p[0] - mean[0], p[1] - mean[1]);
        let row = [x, y, 1.0];
        let rhs = -(x * x + y * y);
        for r in 0..3 {
            b[r] += row[r] * rhs;
            for c in 0..3 {
                a[r][c] += row[r] * row[c];
            }
        }
    }
    let sol = solve3(a, b)?;
    let (cx, cy) = (-sol[0] / 2.0, -sol[1] / 2.0);
    let radius = (cx * cx + cy * cy - sol[2]).sqrt();
    if !(radius.is_finite() && radius > 0.0) {
        return None;
    }
    let worst = pts
        .iter()
        .map(|p| {
            (((p[0] - mean[0] - cx).powi(2) + (p[1] - mean[1] - cy).powi(2)).sqrt() - radius).abs()
        })
        .fold(0.0, f64::max);
    if worst > 1e-3 * radius {
        return None;
    }
    let axial = tris.iter().map(|t| t.0 * dot(t.1, axis)).sum::<f64>() / area;
    let (cu, cv) = (cx + mean[0], cy + mean[1]);
    let centre = std::array::from_fn(|k| axial * axis[k] + cu * u[k] + cv * v[k]);
    Some((centre, axis, radius))
}

/// Cramer's rule for a 3×3 system; `None` when singular.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: [[f64; 3]; 3]| dot(m[0], cross(m[1], m[2]));
    let d = det(a);
    if d.abs() < f64::MIN_POSITIVE || !d.is_finite() {
        return None;
    }
    Some(std::array::from_fn(|col| {
        let mut m = a;
        for (row, rhs) in m.iter_mut().zip(b) {
            row[col] = rhs;
        }
        det(m) / d
    }))
}

/// a / |a| (the callers pass non-zero vectors).
fn normalize(a: [f64; 3]) -> [f64; 3] {
    let n = norm(a);
    a.map(|v| v / n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Element, ElementKind};

    /// A hex8 tube (bore radius r0, outer r1, length L along z) with *uneven* circumferential
    /// spacing: angles crowd on one side, as free meshers do near features. The bore node set
    /// holds the inner-surface nodes.
    fn uneven_tube() -> Model {
        let (r0, r1, len, nt, nz) = (0.0125, 0.02, 0.03, 24, 3);
        let theta = |i: usize| {
            let u = i as f64 / nt as f64;
            2.0 * std::f64::consts::PI * (u + 0.08 * (2.0 * std::f64::consts::PI * u).sin())
        };
        let id = |i: usize, j: usize, k: usize| (k * 2 + j) * nt + i % nt;
        let mut m = Model {
            source: "tube".into(),
            ..Default::default()
        };
        for k in 0..=nz {
            for j in 0..2 {
                for i in 0..nt {
                    let r = if j == 0 { r0 } else { r1 };
                    m.nodes.push(Node {
                        id: (id(i, j, k) + 1) as u64,
                        x: [
                            r * theta(i).cos(),
                            r * theta(i).sin(),
                            len * k as f64 / nz as f64,
                        ],
                        displacement_frame: None,
                    });
                }
            }
        }
        for k in 0..nz {
            for i in 0..nt {
                let nodes = vec![
                    id(i, 0, k),
                    id(i + 1, 0, k),
                    id(i + 1, 1, k),
                    id(i, 1, k),
                    id(i, 0, k + 1),
                    id(i + 1, 0, k + 1),
                    id(i + 1, 1, k + 1),
                    id(i, 1, k + 1),
                ];
                m.elements.push(Element {
                    id: m.elements.len() as u64 + 1,
                    kind: ElementKind::Hex8,
                    nodes,
                    property: Some(0),
                    orientation: None,
                });
            }
        }
        let bore: Vec<NodeIndex> = (0..=nz)
            .flat_map(|k| (0..nt).map(move |i| id(i, 0, k)))
            .collect();
        m.node_sets.insert("BORE".into(), bore);
        m
    }

    #[test]
    fn rbe2_spider_centre_is_on_the_bore_axis_where_the_node_average_is_not() {
        let mut m = uneven_tube();
        let nodes_before = m.nodes.len();
        let reports = resolve_interfaces(&mut m, &["bore".to_string()], SpiderKind::Rbe2).unwrap();
        let s = reports[0].spider.as_ref().unwrap();
        assert_eq!(s.method, CentreMethod::CylinderFit);
        assert_eq!(s.set_nodes, 96);
        assert_eq!(reports[0].nodes, vec![nodes_before]);
        // The bore's nodes lie on the true cylinder: the fitted centre is on the axis (x = y = 0)
        // to rounding, at mid-length …
        let radial = (s.centre[0].powi(2) + s.centre[1].powi(2)).sqrt();
        assert!(radial < 1e-15, "fitted centre {radial:e} m off axis");
        assert!((s.centre[2] - 0.015).abs() < 1e-15);
        // … while the crowded nodes pull the plain average well off it (> 5% of r0).
        assert!(
            s.offset_from_node_average > 0.05 * 0.0125,
            "{}",
            s.offset_from_node_average
        );
        match &m.rigid_elements[0] {
            RigidElement::Rbe2 {
                independent,
                dependent,
                dofs,
                ..
            } => {
                assert_eq!(*independent, nodes_before);
                assert_eq!(dependent.len(), 96);
                assert_eq!(*dofs, DofMask::TRANSLATIONS);
            }
            other => panic!("expected an RBE2, got {other:?}"),
        }
    }

    #[test]
    fn ids_sets_and_errors() {
        let mut m = uneven_tube();
        let r =
            resolve_interfaces(&mut m, &["30".into(), "BORE".into()], SpiderKind::None).unwrap();
        assert_eq!(r[0].nodes, vec![29]);
        assert_eq!(r[1].nodes.len(), 96);
        assert!(m.rigid_elements.is_empty());
        let mut m = uneven_tube();
        let dup =
            resolve_interfaces(&mut m, &["1".into(), "BORE".into()], SpiderKind::None).unwrap_err();
        assert!(
            matches!(dup, InterfaceError::Duplicate { node_id: 1, .. }),
            "{dup}"
        );
        let unknown = resolve_interfaces(&mut m, &["CRANK".into()], SpiderKind::Rbe2).unwrap_err();
        assert_eq!(
            unknown.to_string(),
            "interface `CRANK` is neither a node id nor a node-set name in tube (node sets: BORE)"
        );
        let mut m = uneven_tube();
        let r = resolve_interfaces(&mut m, &["BORE".into()], SpiderKind::Rbe3).unwrap();
        assert!(
            matches!(&m.rigid_elements[0], RigidElement::Rbe3 { reference, independent, .. } if *reference == r[0].nodes[0] && independent.len() == 96)
        );
    }

    #[test]
    fn names_with_components_and_node_names() {
        let mut m = uneven_tube();
        let r = resolve_interfaces(
            &mut m,
            &["bore:123".into(), "NODE30:126".into()],
            SpiderKind::Rbe2,
        )
        .unwrap();
        assert_eq!(r[0].name, "BORE");
        assert_eq!(r[0].dofs, DofMask::from_digits("123"));
        let s = r[0].spider.as_ref().unwrap();
        assert_eq!(s.legs.len(), 96);
        // Nodes on a true cylinder: the fitted radius is the bore's, the axis z.
        assert!((s.radius.unwrap() - 0.0125).abs() < 1e-15, "{:?}", s.radius);
        assert!((s.axis.unwrap()[2].abs() - 1.0).abs() < 1e-15);
        assert_eq!(
            (r[1].name.as_str(), r[1].nodes.clone()),
            ("NODE30", vec![29])
        );
        assert_eq!(r[1].dofs, DofMask::from_digits("126"));
        let (named, rest) = reference_names(
            &m,
            &r,
            &["Bore:123456".into(), "NODE30".into(), "SPC_1".into()],
        )
        .unwrap();
        assert_eq!(
            named,
            vec![
                (m.nodes[r[0].nodes[0]].id, DofMask::ALL),
                (30, DofMask::ALL)
            ]
        );
        assert_eq!(rest, vec!["SPC_1".to_string()]);
        let mut m = uneven_tube();
        let e = resolve_interfaces(&mut m, &["CRANK:123".into()], SpiderKind::Rbe2).unwrap_err();
        assert!(matches!(e, InterfaceError::Unknown { .. }), "{e}");
        let e = resolve_interfaces(&mut m, &["BORE:17".into()], SpiderKind::Rbe2).unwrap_err();
        assert!(matches!(e, InterfaceError::BadComponents(_)), "{e}");
    }

    #[test]
    fn flat_face_set_uses_the_area_centroid() {
        let mut m = uneven_tube();
        // The annular end face z = 0: flat, so no cylinder; its area centroid has z = 0.
        let end: Vec<NodeIndex> = (0..m.nodes.len())
            .filter(|&i| m.nodes[i].x[2] == 0.0)
            .collect();
        m.node_sets.insert("END".into(), end);
        let r = resolve_interfaces(&mut m, &["END".into()], SpiderKind::Rbe2).unwrap();
        let s = r[0].spider.as_ref().unwrap();
        assert_eq!(s.method, CentreMethod::FaceAreaCentroid);
        assert_eq!(s.centre[2], 0.0);
        let radial = (s.centre[0].powi(2) + s.centre[1].powi(2)).sqrt();
        // Measured 1.1% of r0: the 24 unequal flat facets bias the area centroid (the limit of
        // method 2, which is why bores get the cylinder fit).
        assert!(radial < 0.015 * 0.0125, "{radial:e}");
    }
}
