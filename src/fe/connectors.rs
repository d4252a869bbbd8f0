//! Stiffness and mass of the connectors of a model ([`crate::model::connector`]): scalar springs,
//! scalar masses and bushes, as small matrices the assembler scatters like element matrices.
//!
//! * Scalar spring k between dofs a and b (MSC QRG "CELAS1"): K = k [1 −1; −1 1] on (u_a, u_b),
//!   k on u_a alone when grounded. The components are the nodes' own (displacement-frame) dofs.
//! * Scalar mass m (MSC QRG "CMASS1"): M = m [1 −1; −1 1] alike (a coupling mass between two
//!   dofs), m on u_a when grounded.
//! * Bush (MSC QRG "CBUSH"; [`crate::model::Bush`]): K_e = Cᵀ diag(k) C with
//!   C = [−E H_a, E H_b] (grounded: C = E H_a), H_n = [I, −d̃_n; 0, I], d_n = x_s − x_n, E =
//!   diag(R, R); basic frame, rotated to the nodes' frames by the assembler.
//! * A matrix given term by term ([`crate::model::DofMatrix`]: GENEL, DMIG): its terms as
//!   written, on the nodes' own dofs, one small matrix per node pair.

use super::FeError;
use crate::model::{Bush, DofMatrix, Model, NodeDof, NodeIndex};

/// One connector's matrices over its nodes, node-major with 6 slots per node: component c of
/// node i at row/column 6i + c (a scalar point's dof in slot 0), row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct ConnectorMatrices {
    /// What it is, for messages (`spring 12`).
    pub what: String,
    /// Its nodes, distinct.
    pub nodes: Vec<NodeIndex>,
    /// Stiffness (6n × 6n).
    pub k: Vec<f64>,
    /// Mass (6n × 6n).
    pub m: Vec<f64>,
    /// The matrices are in the basic frame (bush) and must be rotated into the nodes'
    /// displacement frames; otherwise they are on the nodes' own dofs.
    pub basic: bool,
}

/// The matrices of every spring, scalar mass and bush of `model`.
pub fn connector_matrices(model: &Model) -> Result<Vec<ConnectorMatrices>, FeError> {
    let mut out = Vec::new();
    let scalar = |what: String, a: NodeDof, b: Option<NodeDof>, v: f64, stiffness: bool| {
        let mut nodes = vec![a.node];
        if let Some(b) = b.filter(|b| b.node != a.node) {
            nodes.push(b.node);
        }
        let n = 6 * nodes.len();
        let slot = |d: NodeDof| {
            6 * nodes.iter().position(|&x| x == d.node).unwrap_or(0) + usize::from(d.component)
        };
        let mut mat = vec![0.0; n * n];
        let ends: Vec<(usize, f64)> = std::iter::once((slot(a), 1.0))
            .chain(b.map(|b| (slot(b), -1.0)))
            .collect();
        for &(i, si) in &ends {
            for &(j, sj) in &ends {
                mat[i * n + j] += v * si * sj;
            }
        }
        let (k, m) = if stiffness {
            (mat, vec![0.0; n * n])
        } else {
            (vec![0.0; n * n], mat)
        };
        ConnectorMatrices {
            what,
            nodes,
            k,
            m,
            basic: false,
        }
    };
    for s in &model.springs {
        out.push(scalar(format!("spring {}", s.id), s.a, s.b, s.k, true));
    }
    for s in &model.scalar_masses {
        out.push(scalar(
            format!("scalar mass {}", s.id),
            s.a,
            s.b,
            s.m,
            false,
        ));
    }
    for b in &model.bushes {
        out.push(bush(model, b)?);
    }
    for d in &model.dof_matrices {
        out.extend(dof_matrix(d));
    }
    Ok(out)
}

/// A matrix given term by term ([`DofMatrix`]) as one small matrix per node pair it couples
/// (and per node for its terms within one node): its size follows its terms, never n².
fn dof_matrix(d: &DofMatrix) -> Vec<ConnectorMatrices> {
    use std::collections::BTreeMap;
    type Terms = (Vec<(NodeDof, NodeDof, f64)>, Vec<(NodeDof, NodeDof, f64)>);
    let mut blocks: BTreeMap<(NodeIndex, NodeIndex), Terms> = BTreeMap::new();
    for (terms, stiffness) in [(&d.stiffness, true), (&d.mass, false)] {
        for &(a, b, v) in terms {
            let key = (a.node.min(b.node), a.node.max(b.node));
            let block = blocks.entry(key).or_default();
            let list = if stiffness {
                &mut block.0
            } else {
                &mut block.1
            };
            list.push((a, b, v));
        }
    }
    blocks
        .into_iter()
        .map(|((p, q), (k_terms, m_terms))| {
            let nodes = if p == q { vec![p] } else { vec![p, q] };
            let n = 6 * nodes.len();
            let slot = |x: NodeDof| 6 * usize::from(x.node != p) + usize::from(x.component);
            let fill = |terms: &[(NodeDof, NodeDof, f64)]| {
                let mut mat = vec![0.0; n * n];
                for &(a, b, v) in terms {
                    mat[slot(a) * n + slot(b)] += v;
                }
                mat
            };
            ConnectorMatrices {
                what: d.what.clone(),
                nodes,
                k: fill(&k_terms),
                m: fill(&m_terms),
                basic: d.basic,
            }
        })
        .collect()
}

/// The basic-frame stiffness of a bush (module formula).
pub fn bush(model: &Model, b: &Bush) -> Result<ConnectorMatrices, FeError> {
    let what = format!("bush {}", b.id);
    let bad = |message: String| FeError::BadReference {
        source_file: model.element_origin(b.id),
        message: format!("{what}: {message}"),
    };
    let nodes: Vec<NodeIndex> = std::iter::once(b.a).chain(b.b).collect();
    if nodes.iter().any(|&n| n >= model.nodes.len()) || b.b == Some(b.a) {
        return Err(bad(
            "its nodes are not two distinct nodes of the model".into()
        ));
    }
    let r = b.axes;
    let orthonormal = (0..3).all(|i| {
        (0..3).all(|j| {
            let d: f64 = (0..3).map(|k| r[i][k] * r[j][k]).sum();
            (d - f64::from(u8::from(i == j))).abs() < 1e-9
        })
    });
    if !orthonormal || b.k.iter().any(|k| !k.is_finite()) {
        return Err(bad(format!(
            "axes {r:?} are not orthonormal or stiffnesses {:?} are not finite",
            b.k
        )));
    }
    // C (6 × 6n): row i of E·H_n for each node, signed −1 for A when B exists.
    let n = 6 * nodes.len();
    let mut c = vec![0.0; 6 * n];
    for (slot, &node) in nodes.iter().enumerate() {
        let sign = if slot == 0 && nodes.len() == 2 {
            -1.0
        } else {
            1.0
        };
        let x = model.nodes[node].x;
        let d = [
            b.location[0] - x[0],
            b.location[1] - x[1],
            b.location[2] - x[2],
        ];
        // −d̃ θ = θ × d: rows of −d̃
        let neg_dt = [[0.0, d[2], -d[1]], [-d[2], 0.0, d[0]], [d[1], -d[0], 0.0]];
        for i in 0..3 {
            for j in 0..3 {
                // translation rows: R (u + θ × d); rotation rows: R θ
                c[i * n + 6 * slot + j] += sign * r[i][j];
                c[(3 + i) * n + 6 * slot + 3 + j] += sign * r[i][j];
                let rd: f64 = (0..3).map(|k| r[i][k] * neg_dt[k][j]).sum();
                c[i * n + 6 * slot + 3 + j] += sign * rd;
            }
        }
    }
    let mut k = vec![0.0; n * n];
    for (row, &kr) in b.k.iter().enumerate() {
        if kr == 0.0 {
            continue;
        }
        for p in 0..n {
            let cp = c[row * n + p];
            if cp == 0.0 {
                continue;
            }
            for q in 0..n {
                k[p * n + q] += kr * cp * c[row * n + q];
            }
        }
    }
    Ok(ConnectorMatrices {
        what,
        nodes,
        k,
        m: vec![0.0; n * n],
        basic: true,
    })
}

/// What a flexible body cannot hold of a model's connectors, as one message (`None`: nothing):
/// scalar points that carry dofs (the file's nodes have positions; a scalar dof has none),
/// springs and bushes to ground (a flexible body is free or held at its interfaces: its rigid
/// modes would be missing and the file has no record of the support), and with a lumped `m`
/// a direction-dependent translational mass at a node from scalar masses (the file holds one
/// mass per node; `--mass consistent` keeps it in M).
pub fn body_restrictions(
    model: &Model,
    dofs: &super::DofMap,
    m: &faer::sparse::SparseColMat<usize, f64>,
    lumped: bool,
) -> Option<String> {
    let ids = |v: Vec<String>| {
        let more = if v.len() > 6 { ", …" } else { "" };
        format!(
            "{}{more}",
            v.iter().take(6).cloned().collect::<Vec<_>>().join(", ")
        )
    };
    let mut why = Vec::new();
    let scalar: Vec<String> = (model.scalar_points.iter())
        .filter(|&&n| dofs.count.get(n).is_some_and(|&c| c > 0))
        .map(|&n| model.nodes[n].id.to_string())
        .collect();
    if !scalar.is_empty() {
        why.push(format!(
            "scalar points (SPOINT {}) carry dofs, and the file's nodes are points with a \
             position: a scalar dof has no place in it",
            ids(scalar)
        ));
    }
    let grounded: Vec<String> = (model.springs.iter())
        .filter(|s| s.b.is_none() && s.k != 0.0)
        .map(|s| format!("spring {} ({})", s.id, model.element_origin(s.id)))
        .chain(
            (model.bushes.iter())
                .filter(|b| b.b.is_none())
                .map(|b| format!("bush {} ({})", b.id, model.element_origin(b.id))),
        )
        .collect();
    if !grounded.is_empty() {
        why.push(format!(
            "springs or bushes to ground hold the body ({}): a flexible body is free or held at \
             its interfaces (its rigid modes would be missing, and the file has no record of \
             the support); model the mount in the multibody model, or hold the dofs with an SPC",
            ids(grounded)
        ));
    }
    if lumped {
        let m = m.as_ref();
        let entry = |i: usize, j: usize| {
            (m.row_idx_of_col(j).zip(m.val_of_col(j)))
                .find(|(r, _)| *r == i)
                .map_or(0.0, |(_, v)| *v)
        };
        let mut nodes: Vec<NodeIndex> = (model.scalar_masses.iter())
            .filter(|s| s.a.component < 3)
            .map(|s| s.a.node)
            .filter(|&n| !model.is_scalar_point(n))
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        let uneven: Vec<String> = nodes
            .into_iter()
            .filter(|&n| {
                let f = dofs.first[n];
                let b: [[f64; 3]; 3] =
                    std::array::from_fn(|i| std::array::from_fn(|j| entry(f + i, f + j)));
                let mean = (b[0][0] + b[1][1] + b[2][2]) / 3.0;
                let top = b.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
                (0..3).any(|i| {
                    (0..3).any(|j| {
                        let want = if i == j { mean } else { 0.0 };
                        (b[i][j] - want).abs() > 1e-9 * top
                    })
                })
            })
            .map(|n| model.nodes[n].id.to_string())
            .collect();
        if !uneven.is_empty() {
            why.push(format!(
                "scalar masses give nodes {} a different mass in different directions, and a \
                 lumped flexible body holds one mass per node; give the same mass on components \
                 1, 2 and 3 (or a CONM2), or build with --mass consistent",
                ids(uneven)
            ));
        }
    }
    (!why.is_empty()).then(|| why.join("; "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Node;

    fn model(xa: [f64; 3], xb: [f64; 3]) -> Model {
        let node = |id, x| Node {
            id,
            x,
            displacement_frame: None,
        };
        Model {
            nodes: vec![node(1, xa), node(2, xb)],
            ..Default::default()
        }
    }

    /// A bush between coincident nodes with identity axes is k_i on the relative motion: the
    /// stiffness of u_b,x − u_a,x is K1, of θ_b,z − θ_a,z K6, and a rigid motion costs nothing.
    #[test]
    fn bush_on_relative_motion_and_free_of_rigid_motion() {
        let m = model([1.0, 2.0, 0.0], [3.0, 2.0, 0.0]);
        let b = Bush {
            id: 7,
            a: 0,
            b: Some(1),
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            k: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            location: [1.5, 2.0, 0.3],
        };
        let c = bush(&m, &b).unwrap();
        // rigid motions about an arbitrary point: K q = 0
        let x0 = [0.3, -0.7, 0.2];
        for mode in 0..6 {
            let mut q = [0.0; 12];
            for (slot, node) in [0usize, 1].iter().enumerate() {
                let x = m.nodes[*node].x;
                let d = [x[0] - x0[0], x[1] - x0[1], x[2] - x0[2]];
                let mut t = [0.0; 3];
                let mut th = [0.0; 3];
                if mode < 3 {
                    t[mode] = 1.0;
                } else {
                    th[mode - 3] = 1.0;
                    // θ × d
                    t = [
                        th[1] * d[2] - th[2] * d[1],
                        th[2] * d[0] - th[0] * d[2],
                        th[0] * d[1] - th[1] * d[0],
                    ];
                }
                q[6 * slot..6 * slot + 3].copy_from_slice(&t);
                q[6 * slot + 3..6 * slot + 6].copy_from_slice(&th);
            }
            for i in 0..12 {
                let f: f64 = (0..12).map(|j| c.k[i * 12 + j] * q[j]).sum();
                assert!(f.abs() < 1e-12, "rigid mode {mode}: force {f} at {i}");
            }
        }
        // pulling B along x: K1; turning B about z at the spring point shifts it by θ × d_b
        assert!((c.k[6 * 12 + 6] - 1.0).abs() < 1e-15);
        // θz of B: spring point moves by θ × (x_s − x_b) = θ (0, −1.5, …) → K2·1.5² + K6
        assert!((c.k[11 * 12 + 11] - (2.0 * 1.5 * 1.5 + 6.0)).abs() < 1e-12);
    }
}
