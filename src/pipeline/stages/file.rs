//! Assemble file: the build's results in the file's records — the stored nodes with their
//! mode shapes in the basic frame, faces and lines, nodal masses, the modes and their labels,
//! the method record with its counts, the invariants, field shapes, modal loads, the recipe and
//! the interfaces entry. The part of the pipeline that turns compute types into the file's.

use std::collections::HashSet;

use faer::Mat;
use flexbody_reader as file;

use crate::body::faces::{graphics_faces, GraphicsFace};
use crate::body::stress::ModalFields;
use crate::fe::{DofMap, MassKind};
use crate::model::{DofMask, Model, NodeIndex};
use crate::pipeline::interface_entry::interfaces_entry;
use crate::pipeline::plan::Plan;
use crate::pipeline::recipe::{accuracy_band, recipe};
use crate::pipeline::scene::modal_loads;
use crate::pipeline::stages::node_shape;
use crate::pipeline::stages::Constrained;
use crate::pipeline::stages::FieldShapes;
use crate::pipeline::stages::MassProperties;
use crate::pipeline::stages::ReducedBasis;
use crate::pipeline::stages::StoredNodes;
use crate::pipeline::stages::WithInterfaces;
use crate::pipeline::{BuildError, BuildSpec, KeepNodes};
use crate::reduce::{self, ModeSet};

/// The nodes whose shapes go into the file (`--keep-nodes`).
pub fn stored_nodes(
    plan: &Plan,
    interfaced: &WithInterfaces,
    constrained: &Constrained,
) -> Result<StoredNodes, BuildError> {
    let faces = graphics_faces(&interfaced.model);
    let always: Vec<NodeIndex> = interfaced
        .interface_nodes
        .iter()
        .copied()
        .chain(constrained.reference_nodes.iter().map(|r| r.0))
        .collect();
    let mut nodes = select_nodes(&interfaced.model, &plan.spec.keep_nodes, &always, &faces)
        .map_err(|e| plan.request_error(e))?;
    // A point mass's centre-of-gravity node goes with the node it hangs on.
    let extra: Vec<NodeIndex> = (interfaced.mass_nodes.iter())
        .filter(|m| nodes.binary_search(&m.attached_to).is_ok())
        .map(|m| m.node)
        .collect();
    nodes.extend(extra);
    nodes.sort_unstable();
    nodes.dedup();
    Ok(StoredNodes { faces, nodes })
}

/// The assemble-file stage.
pub fn assemble_file(
    plan: &Plan,
    interfaced: &WithInterfaces,
    constrained: &Constrained,
    basis: &ReducedBasis,
    mass: &MassProperties,
    stored: &StoredNodes,
    fields: &FieldShapes,
) -> Result<file::ReducedBody, BuildError> {
    let (spec, model, set) = (&plan.spec, &interfaced.model, &basis.set);
    let position = positions(model, &stored.nodes);
    let is_interface: HashSet<NodeIndex> = interfaced.interface_nodes.iter().copied().collect();
    let (nodes, faces, lines) = geometry(model, stored, &position, &is_interface);
    let dofs = &constrained.assembled.dofs;
    let modes = modes_record(set, &stored.nodes, dofs, &basis.phi);
    let method = method_record(plan, set, interfaced, constrained, &position, &modes.labels);
    let top = fields.top.as_ref();
    let mut body = file::ReducedBody {
        version: flexbody_reader::FORMAT_VERSION,
        generator: file::Generator {
            name: "flexbody".into(),
            version: env!("CARGO_PKG_VERSION").into(),
        },
        units: spec.units.clone(),
        header: header(plan, model, method.method, &stored.nodes, &is_interface),
        nodes,
        faces,
        nodal_mass: stored
            .nodes
            .iter()
            .map(|&n| file::NodalMass {
                mass: mass.nodal[n].0,
                inertia: mass.nodal[n].1,
            })
            .collect(),
        modes,
        invariants: invariants_record(spec, &mass.invariants),
        method,
        stress_shapes: top.and_then(|f| field_shapes(f, f.stress.as_ref(), &position)),
        strain_shapes: top.and_then(|f| field_shapes(f, f.strain.as_ref(), &position)),
        damping: None,
        lines: (!lines.is_empty()).then_some(lines),
        recipe: None,
        stress_shapes_bottom: None,
        strain_shapes_bottom: None,
        interfaces: None,
        label_shares: Some(if set.diagnostics.label_shares.len() == set.len() {
            set.diagnostics.label_shares.clone()
        } else {
            vec![1.0; set.len()]
        }),
        modal_loads: None,
        geometric_stiffness: None,
        eigen_residuals: eigen_residuals(set),
    };
    body.modal_loads = modal_loads(&basis.scene, set);
    body.geometric_stiffness = basis.geometric_stiffness.clone();
    let band = accuracy_band(spec, &plan.modes, set);
    let recipe = recipe(
        spec,
        &plan.modes,
        model,
        &interfaced.interfaces,
        band,
        basis.preload.as_ref(),
    )
    .map_err(|e| plan.request_error(e))?;
    body.recipe = Some(recipe);
    if let Some(b) = &fields.bottom {
        body.stress_shapes_bottom = field_shapes(b, b.stress.as_ref(), &position);
        body.strain_shapes_bottom = field_shapes(b, b.strain.as_ref(), &position);
    }
    body.interfaces = interfaces_entry(model, &interfaced.interfaces, &body.nodes);
    if let Some(text) = &spec.damping {
        // the ratios per mode, and the text in the recipe
        crate::body::damping::apply(&mut body, text)?;
    }
    body.version = file::version_for(&body);
    Ok(body)
}

/// `eigen_residuals.bin` (format 1.9, SPEC §5.17): the method's eigenproblem as its basis took
/// it; `None` when none was solved (a Craig–Bampton set of constraint modes only).
fn eigen_residuals(set: &ModeSet) -> Option<file::EigenResiduals> {
    use crate::reduce::EigenProblem;
    use crate::solve::Solver;
    let r = set.diagnostics.eigenproblem.as_ref()?;
    Some(file::EigenResiduals {
        problems: vec![file::EigenProblem {
            kind: match r.problem {
                EigenProblem::NormalModes => file::EigenProblemKind::NormalModes,
                EigenProblem::FixedInterface => file::EigenProblemKind::FixedInterface,
                EigenProblem::FreeFree => file::EigenProblemKind::FreeFree,
            },
            solver: match r.solver {
                Solver::Lanczos => file::EigenSolverKind::Lanczos,
                Solver::Amls => file::EigenSolverKind::Amls,
                Solver::Dense => file::EigenSolverKind::Dense,
                Solver::Slepc => file::EigenSolverKind::Slepc,
            },
            scale: r.scale,
            omega2: r.omega2.clone(),
            residual: r.residuals.clone(),
            inertia: r.inertia.map(|(below, shift)| file::InertiaCount {
                shift,
                below: below as u64,
            }),
        }],
    })
}

/// Node index → its position among the stored nodes (`u32::MAX`: not stored).
fn positions(model: &Model, stored: &[NodeIndex]) -> Vec<u32> {
    let mut position = vec![u32::MAX; model.nodes.len()];
    for (i, &n) in stored.iter().enumerate() {
        position[n] = i as u32;
    }
    position
}

/// The stored nodes, and the faces and beam lines whose nodes are all stored.
fn geometry(
    model: &Model,
    stored: &StoredNodes,
    position: &[u32],
    is_interface: &HashSet<NodeIndex>,
) -> (Vec<file::Node>, Vec<file::Face>, Vec<[u32; 2]>) {
    let nodes = stored
        .nodes
        .iter()
        .map(|&n| file::Node {
            id: model.nodes[n].id,
            xyz: model.nodes[n].x,
            interface: is_interface.contains(&n),
        })
        .collect();
    let faces = stored
        .faces
        .iter()
        .filter(|f| f.nodes.iter().all(|&n| position[n] != u32::MAX))
        .filter_map(|f| match f.nodes.len() {
            3 => Some(file::Face::Tri(std::array::from_fn(|k| {
                position[f.nodes[k]]
            }))),
            4 => Some(file::Face::Quad(std::array::from_fn(|k| {
                position[f.nodes[k]]
            }))),
            _ => None, // beam/rod lines go to `lines`
        })
        .collect();
    let lines = stored
        .faces
        .iter()
        .filter(|f| f.nodes.len() == 2 && f.nodes.iter().all(|&n| position[n] != u32::MAX))
        .map(|f| [position[f.nodes[0]], position[f.nodes[1]]])
        .collect();
    (nodes, faces, lines)
}

/// The modes: frequencies, ω², labels, the generalized mass I and stiffness diag(ω²) (exact, not
/// a noisy triple product) and the shapes per stored node in the basic frame.
fn modes_record(set: &ModeSet, stored: &[NodeIndex], dofs: &DofMap, phi: &Mat<f64>) -> file::Modes {
    let nm = set.len();
    let ns = stored.len();
    let mut shapes = vec![0.0; nm * ns * 6];
    for j in 0..nm {
        for (q, &p) in stored.iter().enumerate() {
            shapes[(j * ns + q) * 6..(j * ns + q) * 6 + 6]
                .copy_from_slice(&node_shape(dofs, phi, p, j));
        }
    }
    let omega2 = set.omega2.clone();
    let identity: Vec<f64> = (0..nm * nm)
        .map(|i| if i / nm == i % nm { 1.0 } else { 0.0 })
        .collect();
    let diag: Vec<f64> = (0..nm * nm)
        .map(|i| {
            if i / nm == i % nm {
                omega2[i / nm]
            } else {
                0.0
            }
        })
        .collect();
    file::Modes {
        frequency_hz: set.frequencies_hz(),
        omega2,
        labels: set.labels.iter().map(file_label).collect(),
        generalized_mass: identity,
        generalized_stiffness: diag,
        shapes,
    }
}

/// The method record: method, mass, interface dofs and frames, reference conditions, the mode
/// counts by origin (SPEC §5.7) and the cutoffs.
fn method_record(
    plan: &Plan,
    set: &ModeSet,
    interfaced: &WithInterfaces,
    constrained: &Constrained,
    position: &[u32],
    labels: &[file::ModeLabel],
) -> file::MethodRecord {
    let spec = &plan.spec;
    let dofs = &constrained.assembled.dofs;
    let (method, interface_count, fixed_count) = method_counts(set);
    let identity3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let interface = interfaced
        .interface_nodes
        .iter()
        .zip(&constrained.interface_masks)
        .map(|(&n, m)| file::InterfaceNode {
            node: position[n],
            dofs: std::array::from_fn(|k| k < usize::from(dofs.count[n]) && m.contains(k)),
            frame: dofs.frames[n].unwrap_or(identity3),
        })
        .collect();
    let nm = set.len();
    let count_of = |l: file::ModeLabel| labels.iter().filter(|x| **x == l).count() as u64;
    let removed = set.diagnostics.removed.len() as u64;
    let residual = set.diagnostics.residual_vectors as u64;
    let shift_fraction = matches!(
        set.method,
        reduce::Method::Dietz { .. } | reduce::Method::DietzModified { .. }
    )
    .then_some(reduce::dietz::DEFAULT_SHIFT_FRACTION);
    file::MethodRecord {
        method,
        mass_kind: file_mass_kind(spec),
        interface,
        reference_conditions: constrained
            .reference_nodes
            .iter()
            .map(|&(n, m)| file::ReferenceCondition {
                node: position[n],
                dofs: mask_bools(m),
            })
            .collect(),
        // SPEC §5.7: rigid = modes labelled Rigid; the others count basis vectors by origin.
        counts: match method {
            // every basis vector kept is a mode; residual vectors removed as dependent were
            // basis vectors too (SPEC §5.7, since 1.6)
            file::Method::NormalModes => file::ModeCounts {
                rigid: count_of(file::ModeLabel::Rigid),
                normal: nm as u64 - count_of(file::ModeLabel::Rigid) + removed,
                removed_dependent: removed,
                ..Default::default()
            },
            file::Method::CraigBampton => file::ModeCounts {
                rigid: count_of(file::ModeLabel::Rigid),
                constraint: interface_count,
                // residual vectors count with the component modes (SPEC §5.14)
                fixed_interface: fixed_count + residual,
                removed_dependent: removed,
                ..Default::default()
            },
            file::Method::CraigChang | file::Method::Dietz => file::ModeCounts {
                rigid: count_of(file::ModeLabel::Rigid),
                normal: set.diagnostics.basis_normal_modes.unwrap_or(0) as u64,
                attachment: interface_count + residual,
                removed_dependent: removed,
                ..Default::default()
            },
        },
        cutoffs: file::Cutoffs {
            fmax_hz: plan.modes.fmax_hz,
            shift_fraction,
            dependency_tolerance: (method != file::Method::NormalModes)
                .then_some(set.diagnostics.dependency_tol),
        },
    }
}

/// The file's method of a set, with its constraint (or attachment) columns — one per interface
/// dof, less the reference dofs (improved CB) — and fixed-interface modes.
fn method_counts(set: &ModeSet) -> (file::Method, u64, u64) {
    let held = set.reference_dofs.len() as u64;
    match &set.method {
        reduce::Method::NormalModes => (file::Method::NormalModes, 0, 0),
        reduce::Method::CraigBampton {
            interface,
            fixed_interface_modes,
        } => (
            file::Method::CraigBampton,
            interface.len() as u64,
            *fixed_interface_modes as u64,
        ),
        reduce::Method::ImprovedCraigBampton1 {
            interface,
            fixed_interface_modes,
        }
        | reduce::Method::ImprovedCraigBampton2 {
            interface,
            fixed_interface_modes,
        } => (
            file::Method::CraigBampton,
            (interface.len() as u64).saturating_sub(held),
            *fixed_interface_modes as u64,
        ),
        reduce::Method::CraigChang { attachment, .. } => {
            (file::Method::CraigChang, attachment.len() as u64, 0)
        }
        reduce::Method::Dietz { attachment, .. }
        | reduce::Method::DietzModified { attachment, .. } => {
            (file::Method::Dietz, attachment.len() as u64, 0)
        }
    }
}

fn file_mass_kind(spec: &BuildSpec) -> file::MassKind {
    match spec.mass {
        MassKind::Lumped => file::MassKind::Lumped,
        MassKind::Consistent => file::MassKind::Consistent,
    }
}

/// The header: title (default: the model file name), creation time when asked, and the request.
fn header(
    plan: &Plan,
    model: &Model,
    method: file::Method,
    stored: &[NodeIndex],
    is_interface: &HashSet<NodeIndex>,
) -> file::Header {
    let spec = &plan.spec;
    let keep_nodes = match &spec.keep_nodes {
        KeepNodes::All => file::KeepNodes::All,
        KeepNodes::Surface => file::KeepNodes::InterfaceAndSurface,
        KeepNodes::Interface => file::KeepNodes::List(vec![]),
        KeepNodes::Set(_) => file::KeepNodes::List(
            stored
                .iter()
                .filter(|n| !is_interface.contains(n))
                .map(|&n| model.nodes[n].id)
                .collect(),
        ),
    };
    file::Header {
        title: spec.title.clone().unwrap_or_else(|| {
            spec.model
                .file_name()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default()
        }),
        created_utc: spec.created_utc.clone(),
        request: file::Request {
            method,
            fmax_hz: plan.modes.fmax_hz,
            mode_count: plan.modes.count.map(|n| n as u64),
            keep_nodes,
            invariant_set: spec.invariants,
            mass_kind: file_mass_kind(spec),
        },
    }
}

/// The invariants entry: the selection mask and each invariant flattened row by row.
fn invariants_record(
    spec: &BuildSpec,
    inv: &crate::body::invariants::Invariants,
) -> file::Invariants {
    file::Invariants {
        mask: spec.invariants.mask(),
        i1: vec![inv.i1],
        i2: inv.i2.to_vec(),
        i3: inv.i3.as_ref().map(flat).unwrap_or_default(),
        i4: inv.i4.as_ref().map(flat).unwrap_or_default(),
        i5: inv
            .i5
            .as_ref()
            .map(|v| v.iter().flat_map(flat).collect())
            .unwrap_or_default(),
        i6: inv.i6.as_ref().map(flat).unwrap_or_default(),
        i7: inv.i7.iter().flatten().copied().collect(),
        i8: inv
            .i8
            .as_ref()
            .map(|v| v.iter().flat_map(|m| m.iter().flatten().copied()).collect())
            .unwrap_or_default(),
        i9: inv
            .i9
            .as_ref()
            .map(|v| v.iter().flat_map(|m| m.iter().flatten().copied()).collect())
            .unwrap_or_default(),
    }
}

/// The nodes `keep` selects, ascending; `always` (interface and reference nodes) are always
/// included.
fn select_nodes(
    model: &Model,
    keep: &KeepNodes,
    always: &[NodeIndex],
    faces: &[GraphicsFace],
) -> Result<Vec<NodeIndex>, String> {
    let mut on = vec![false; model.nodes.len()];
    for &n in always {
        on[n] = true;
    }
    match keep {
        KeepNodes::All => on.iter_mut().for_each(|v| *v = true),
        KeepNodes::Interface => {}
        KeepNodes::Surface => faces
            .iter()
            .flat_map(|f| f.nodes.iter())
            .for_each(|&n| on[n] = true),
        KeepNodes::Set(name) => {
            let set = model
                .node_sets
                .iter()
                .find(|(k, _)| k.eq_ignore_ascii_case(name))
                .ok_or_else(|| {
                    format!(
                        "--keep-nodes {name}: no such node set (node sets: {})",
                        model
                            .node_sets
                            .keys()
                            .cloned()
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                })?;
            set.1.iter().for_each(|&n| on[n] = true);
        }
    }
    Ok((0..on.len()).filter(|&n| on[n]).collect())
}

/// The file's label of a mode.
fn file_label(l: &reduce::ModeLabel) -> file::ModeLabel {
    match l {
        reduce::ModeLabel::Rigid => file::ModeLabel::Rigid,
        reduce::ModeLabel::Normal => file::ModeLabel::Normal,
        reduce::ModeLabel::Constraint { .. } => file::ModeLabel::Constraint,
        reduce::ModeLabel::FixedInterface { .. } => file::ModeLabel::FixedInterface,
        reduce::ModeLabel::Attachment { .. } => file::ModeLabel::Attachment,
        reduce::ModeLabel::FrequencyResponse { .. } => file::ModeLabel::FrequencyResponse,
        // A static load response is an attachment mode of a distributed load; the file's
        // `modal_loads.bin` (format 1.4) marks it residual (the label enum keeps its 1.0 tags).
        reduce::ModeLabel::Residual { .. } => file::ModeLabel::Attachment,
    }
}

/// A dof mask as six flags.
fn mask_bools(m: DofMask) -> [bool; 6] {
    std::array::from_fn(|k| m.contains(k))
}

/// A matrix row by row.
fn flat(m: &Mat<f64>) -> Vec<f64> {
    (0..m.nrows())
        .flat_map(|r| (0..m.ncols()).map(move |c| m[(r, c)]))
        .collect()
}

/// Recovered fields → the file's entry: node indices become positions in the stored node list
/// (the fields were recovered at stored nodes only, so every position exists).
fn field_shapes(
    f: &ModalFields,
    values: Option<&Vec<f64>>,
    position: &[u32],
) -> Option<file::FieldShapes> {
    values.map(|v| file::FieldShapes {
        nodes: f.nodes.iter().map(|&n| position[n]).collect(),
        values: v.clone(),
    })
}
