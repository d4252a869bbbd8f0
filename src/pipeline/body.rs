//! The file's body from a mode set: mode shapes per stored node in the basic frame, the mass
//! points and their invariants, the stored nodes, labels, faces and field shapes — the part of
//! `build` after the reduction that turns compute types into the file's types.

use faer::Mat;
use flexbody_reader as file;

use super::{BuildError, BuildSpec, KeepNodes};
use crate::body::invariants::MassPoint;
use crate::body::stress::ModalFields;
use crate::fe::{self, assemble, AssemblySpec, BeamLumping, DofMap};
use crate::model::{DofMask, Model, NodeIndex};
use crate::reduce::{self, ModeSet};

/// Rows `[ux uy uz rx ry rz]` of node `p` for mode `j` in the basic frame (zeros where the node
/// has no such dof): u_basic = Aᵀ u_local with A's rows the local axes.
pub(super) fn node_shape(dofs: &DofMap, phi: &Mat<f64>, p: NodeIndex, j: usize) -> [f64; 6] {
    let count = usize::from(dofs.count[p]);
    let mut local = [0.0; 6];
    for (c, v) in local.iter_mut().enumerate().take(count) {
        *v = phi[(dofs.first[p] + c, j)];
    }
    match dofs.frames[p] {
        None => local,
        Some(a) => {
            let rot = |v: &[f64]| -> [f64; 3] {
                std::array::from_fn(|i| (0..3).map(|k| a[k][i] * v[k]).sum())
            };
            let (t, r) = (rot(&local[..3]), rot(&local[3..]));
            [t[0], t[1], t[2], r[0], r[1], r[2]]
        }
    }
}

/// Per-node lumped mass and inertia of the structure (point masses excluded), basic frame.
type NodalMass = Vec<(f64, [[f64; 3]; 3])>;

/// Mass points for the invariants: every node with its lumped structural mass (a lumped assembly
/// of the model without point masses, or `lumped` when that is already it), plus one point per point mass at its centre of gravity,
/// moving rigidly with its node (u + θ × d). Returns the points, their 6-row shapes, and the
/// per-node mass (structure + point masses lumped to the node, inertia shifted to the node) that
/// the file stores.
pub(super) fn mass_points(
    model: &Model,
    dofs: &DofMap,
    phi: &Mat<f64>,
    lumped: Option<&fe::Assembled>,
    beam_lumping: BeamLumping,
) -> Result<(Vec<MassPoint>, Mat<f64>, NodalMass), BuildError> {
    let own;
    let lumped = match lumped {
        Some(l) => l,
        None => {
            let mut bare = model.clone();
            bare.point_masses.clear();
            own = assemble(
                &bare,
                &AssemblySpec {
                    mass: fe::MassKind::Lumped,
                    beam_lumping,
                    ..Default::default()
                },
            )?;
            &own
        }
    };
    let (ld, lm) = (&lumped.dofs, lumped.m.as_ref());
    let entry = |row: usize, col: usize| -> f64 {
        lm.row_idx_of_col(col)
            .zip(lm.val_of_col(col))
            .find(|(r, _)| *r == row)
            .map_or(0.0, |(_, v)| *v)
    };
    let nn = model.nodes.len();
    let mut nodal: NodalMass = Vec::with_capacity(nn);
    for p in 0..nn {
        let count = usize::from(ld.count[p]);
        if count == 0 {
            nodal.push((0.0, [[0.0; 3]; 3]));
            continue;
        }
        let f = ld.first[p];
        let mass = (0..3).map(|c| entry(f + c, f + c)).sum::<f64>() / 3.0;
        let mut inertia = [[0.0; 3]; 3];
        if count == 6 {
            let local: [[f64; 3]; 3] =
                std::array::from_fn(|r| std::array::from_fn(|c| entry(f + 3 + r, f + 3 + c)));
            // I_basic = Aᵀ I_local A.
            inertia = match ld.frames[p] {
                None => local,
                Some(a) => std::array::from_fn(|r| {
                    std::array::from_fn(|c| {
                        (0..3)
                            .map(|i| (0..3).map(|k| a[i][r] * local[i][k] * a[k][c]).sum::<f64>())
                            .sum()
                    })
                }),
            };
        }
        nodal.push((mass, inertia));
    }
    let nm = phi.ncols();
    let np = nn + model.point_masses.len();
    let mut points = Vec::with_capacity(np);
    let mut shapes = Mat::<f64>::zeros(6 * np, nm);
    for (p, node) in model.nodes.iter().enumerate() {
        points.push(MassPoint {
            position: node.x,
            mass: nodal[p].0,
            inertia: nodal[p].1,
        });
        for j in 0..nm {
            let s = node_shape(dofs, phi, p, j);
            for (c, v) in s.iter().enumerate() {
                shapes[(6 * p + c, j)] = *v;
            }
        }
    }
    for (q, pm) in model.point_masses.iter().enumerate() {
        let row = 6 * (nn + q);
        let d = pm.offset;
        let x = model.nodes[pm.node].x;
        points.push(MassPoint {
            position: std::array::from_fn(|k| x[k] + d[k]),
            mass: pm.mass,
            inertia: pm.inertia,
        });
        for j in 0..nm {
            let s = node_shape(dofs, phi, pm.node, j);
            let cross = [
                s[4] * d[2] - s[5] * d[1],
                s[5] * d[0] - s[3] * d[2],
                s[3] * d[1] - s[4] * d[0],
            ];
            for c in 0..3 {
                shapes[(row + c, j)] = s[c] + cross[c];
                shapes[(row + 3 + c, j)] = s[3 + c];
            }
        }
        // Lumped to the node for the stored nodal mass: inertia about the node = J + m(d·d E − d dᵀ).
        let dd = d.iter().map(|v| v * v).sum::<f64>();
        let (m0, i0) = &mut nodal[pm.node];
        *m0 += pm.mass;
        for r in 0..3 {
            for c in 0..3 {
                i0[r][c] +=
                    pm.inertia[r][c] + pm.mass * (if r == c { dd } else { 0.0 } - d[r] * d[c]);
            }
        }
    }
    Ok((points, shapes, nodal))
}

/// The nodes whose shapes go into the file, ascending; `always` (interface and reference nodes)
/// are always included.
pub(super) fn stored_nodes(
    model: &Model,
    keep: &KeepNodes,
    always: &[NodeIndex],
    faces: &[crate::body::faces::GraphicsFace],
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

pub(super) fn file_label(l: &reduce::ModeLabel) -> file::ModeLabel {
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

pub(super) fn mask_bools(m: DofMask) -> [bool; 6] {
    std::array::from_fn(|k| m.contains(k))
}

pub(super) fn flat(m: &Mat<f64>) -> Vec<f64> {
    (0..m.nrows())
        .flat_map(|r| (0..m.ncols()).map(move |c| m[(r, c)]))
        .collect()
}

/// Convert everything into the file's records.
#[allow(clippy::too_many_arguments)]
pub(super) fn assemble_body(
    spec: &BuildSpec,
    model: &Model,
    dofs: &DofMap,
    phi: &Mat<f64>,
    set: &ModeSet,
    stored: &[NodeIndex],
    interface: &[NodeIndex],
    interface_masks: &[DofMask],
    reference: &[(NodeIndex, DofMask)],
    faces: &[crate::body::faces::GraphicsFace],
    nodal: &NodalMass,
    inv: &crate::body::invariants::Invariants,
    fields: Option<&ModalFields>,
) -> Result<file::ReducedBody, BuildError> {
    let mut position = vec![u32::MAX; model.nodes.len()];
    for (i, &n) in stored.iter().enumerate() {
        position[n] = i as u32;
    }
    let is_interface: std::collections::HashSet<NodeIndex> = interface.iter().copied().collect();
    let nodes = stored
        .iter()
        .map(|&n| file::Node {
            id: model.nodes[n].id,
            xyz: model.nodes[n].x,
            interface: is_interface.contains(&n),
        })
        .collect();
    let file_faces = faces
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
    let lines: Vec<[u32; 2]> = faces
        .iter()
        .filter(|f| f.nodes.len() == 2 && f.nodes.iter().all(|&n| position[n] != u32::MAX))
        .map(|f| [position[f.nodes[0]], position[f.nodes[1]]])
        .collect();
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
    let labels: Vec<file::ModeLabel> = set.labels.iter().map(file_label).collect();
    let count_of = |l: file::ModeLabel| labels.iter().filter(|x| **x == l).count() as u64;
    // Constraint columns: one per interface dof, less the reference dofs (improved CB).
    let held = set.reference_dofs.len() as u64;
    let (method, interface_count, fixed_count) = match &set.method {
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
    };
    let identity3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let interface_records = interface
        .iter()
        .zip(interface_masks)
        .map(|(&n, m)| file::InterfaceNode {
            node: position[n],
            dofs: std::array::from_fn(|k| k < usize::from(dofs.count[n]) && m.contains(k)),
            frame: dofs.frames[n].unwrap_or(identity3),
        })
        .collect();
    let mass_kind = match spec.mass {
        fe::MassKind::Lumped => file::MassKind::Lumped,
        fe::MassKind::Consistent => file::MassKind::Consistent,
    };
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
    let invariants = file::Invariants {
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
    };
    let removed = set.diagnostics.removed.len() as u64;
    let residual = set.diagnostics.residual_vectors as u64;
    let shift_fraction = matches!(
        set.method,
        reduce::Method::Dietz { .. } | reduce::Method::DietzModified { .. }
    )
    .then_some(reduce::dietz::DEFAULT_SHIFT_FRACTION);
    let mut body = file::ReducedBody {
        version: flexbody_reader::FORMAT_VERSION,
        generator: file::Generator {
            name: "flexbody".into(),
            version: env!("CARGO_PKG_VERSION").into(),
        },
        units: spec.units.clone(),
        header: file::Header {
            title: spec.title.clone().unwrap_or_else(|| {
                spec.model
                    .file_name()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default()
            }),
            created_utc: spec.created_utc.clone(),
            request: file::Request {
                method,
                fmax_hz: spec.fmax_hz,
                mode_count: spec.modes.map(|n| n as u64),
                keep_nodes,
                invariant_set: spec.invariants,
                mass_kind,
            },
        },
        nodes,
        faces: file_faces,
        nodal_mass: stored
            .iter()
            .map(|&n| file::NodalMass {
                mass: nodal[n].0,
                inertia: nodal[n].1,
            })
            .collect(),
        modes: file::Modes {
            frequency_hz: set.frequencies_hz(),
            omega2,
            labels: labels.clone(),
            generalized_mass: identity,
            generalized_stiffness: diag,
            shapes,
        },
        invariants,
        method: file::MethodRecord {
            method,
            mass_kind,
            interface: interface_records,
            reference_conditions: reference
                .iter()
                .map(|&(n, m)| file::ReferenceCondition {
                    node: position[n],
                    dofs: mask_bools(m),
                })
                .collect(),
            // SPEC §5.7: rigid = modes labelled Rigid; the others count basis vectors by origin.
            counts: match method {
                file::Method::NormalModes => file::ModeCounts {
                    rigid: count_of(file::ModeLabel::Rigid),
                    normal: nm as u64 - count_of(file::ModeLabel::Rigid),
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
                fmax_hz: spec.fmax_hz,
                shift_fraction,
                dependency_tolerance: (method != file::Method::NormalModes)
                    .then_some(set.diagnostics.dependency_tol),
            },
        },
        stress_shapes: fields.and_then(|f| field_shapes(f, f.stress.as_ref(), &position)),
        strain_shapes: fields.and_then(|f| field_shapes(f, f.strain.as_ref(), &position)),
        damping: None,
        lines: (!lines.is_empty()).then_some(lines),
        recipe: None,
        stress_shapes_bottom: None,
        strain_shapes_bottom: None,
        interfaces: None,
        label_shares: Some(if set.diagnostics.label_shares.len() == nm {
            set.diagnostics.label_shares.clone()
        } else {
            vec![1.0; nm]
        }),
        modal_loads: None,
    };
    body.version = flexbody_reader::version_for(&body);
    Ok(body)
}

/// Recovered fields → the file's entry: node indices become positions in the stored node list
/// (the fields were recovered at stored nodes only, so every position exists).
pub(super) fn field_shapes(
    f: &ModalFields,
    values: Option<&Vec<f64>>,
    position: &[u32],
) -> Option<file::FieldShapes> {
    values.map(|v| file::FieldShapes {
        nodes: f.nodes.iter().map(|&n| position[n]).collect(),
        values: v.clone(),
    })
}
