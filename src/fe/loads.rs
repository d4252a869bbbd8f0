//! Scene loads → load vectors over the model's physical dofs (then f_r = Tᵀ f on the
//! independent dofs, like K_r = TᵀKT).
//!
//! * Nodal force/moment: the basic-frame components rotated into the node's displacement frame.
//! * Gravity: f = M·g with g the rigid translation field of the acceleration (the build's own
//!   mass matrix, lumped or consistent, point masses included).
//! * Centrifugal (CalculiX CENTRIF): f = M·b with b = Ω² (I − n nᵀ)(x − p) (`preload::inertia`).
//! * Face traction (pressure): consistent nodal forces f_a = t ∫ N_a (x_ξ × x_η) dξ dη over the
//!   isoparametric face (Zienkiewicz & Taylor, *The FEM*, vol. 1, §6.4 surface loads), Gauss
//!   4×4 on quadrilaterals and a collapsed 4×4 rule on triangles (exact for these integrands up
//!   to the face's curvature).

use faer::sparse::SparseColMat;
use faer::Mat;

use super::dofs::DofMap;
use super::preload::inertia::{inertia_load, Spin};
use super::quadrature::gauss_legendre;
use super::FeError;
use crate::model::{Load, LoadPart, Model, NodeIndex};

/// Shape functions and their (ξ, η) derivatives of a face of `n` nodes (3, 4, 6, 8) at (ξ, η).
/// Triangles use area coordinates (ξ, η ≥ 0, ξ + η ≤ 1), quadrilaterals [−1, 1]².
fn face_shape(n: usize, xi: f64, eta: f64) -> Option<(Vec<f64>, Vec<[f64; 2]>)> {
    Some(match n {
        3 => (
            vec![1.0 - xi - eta, xi, eta],
            vec![[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]],
        ),
        6 => {
            let l = [1.0 - xi - eta, xi, eta];
            let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
            let mut nn = vec![0.0; 6];
            let mut d = vec![[0.0; 2]; 6];
            for a in 0..3 {
                nn[a] = l[a] * (2.0 * l[a] - 1.0);
                for c in 0..2 {
                    d[a][c] = (4.0 * l[a] - 1.0) * dl[a][c];
                }
            }
            for (m, (a, b)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                nn[3 + m] = 4.0 * l[a] * l[b];
                for c in 0..2 {
                    d[3 + m][c] = 4.0 * (dl[a][c] * l[b] + l[a] * dl[b][c]);
                }
            }
            (nn, d)
        }
        4 => {
            let s = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
            let nn = s
                .iter()
                .map(|p| 0.25 * (1.0 + p[0] * xi) * (1.0 + p[1] * eta))
                .collect();
            let d = s
                .iter()
                .map(|p| {
                    [
                        0.25 * p[0] * (1.0 + p[1] * eta),
                        0.25 * p[1] * (1.0 + p[0] * xi),
                    ]
                })
                .collect();
            (nn, d)
        }
        8 => {
            let s = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
            let mut nn = vec![0.0; 8];
            let mut d = vec![[0.0; 2]; 8];
            for a in 0..4 {
                let (p, q) = (s[a][0], s[a][1]);
                let (u, v) = (1.0 + p * xi, 1.0 + q * eta);
                nn[a] = 0.25 * u * v * (p * xi + q * eta - 1.0);
                d[a] = [
                    0.25 * p * v * (2.0 * p * xi + q * eta),
                    0.25 * q * u * (p * xi + 2.0 * q * eta),
                ];
            }
            // Mid-side nodes 5:(1,2) 6:(2,3) 7:(3,4) 8:(4,1).
            for (m, (a, b)) in [(0, 1), (1, 2), (2, 3), (3, 0)].into_iter().enumerate() {
                let mid = [0.5 * (s[a][0] + s[b][0]), 0.5 * (s[a][1] + s[b][1])];
                if mid[0] == 0.0 {
                    // on η = mid[1]: N = ½(1 − ξ²)(1 + η η_m)
                    nn[4 + m] = 0.5 * (1.0 - xi * xi) * (1.0 + mid[1] * eta);
                    d[4 + m] = [-xi * (1.0 + mid[1] * eta), 0.5 * (1.0 - xi * xi) * mid[1]];
                } else {
                    nn[4 + m] = 0.5 * (1.0 - eta * eta) * (1.0 + mid[0] * xi);
                    d[4 + m] = [0.5 * (1.0 - eta * eta) * mid[0], -eta * (1.0 + mid[0] * xi)];
                }
            }
            (nn, d)
        }
        _ => return None,
    })
}

/// Quadrature points (ξ, η, w) of a face of `n` nodes.
fn face_points(n: usize) -> Vec<(f64, f64, f64)> {
    let g = gauss_legendre(4);
    let mut out = Vec::new();
    for &(a, wa) in g {
        for &(b, wb) in g {
            if n == 3 || n == 6 {
                // Collapsed square: u, v ∈ [0, 1], ξ = u, η = v(1 − u), dξdη = (1 − u) du dv.
                let (u, v) = (0.5 * (a + 1.0), 0.5 * (b + 1.0));
                out.push((u, v * (1.0 - u), 0.25 * wa * wb * (1.0 - u)));
            } else {
                out.push((a, b, wa * wb));
            }
        }
    }
    out
}

/// Consistent nodal forces (basic frame) of a uniform traction `t` along the right-hand normal
/// of the face through `x` (3, 4, 6 or 8 points): f_a = t ∫ N_a (x_ξ × x_η) dξ dη.
pub fn face_forces(x: &[[f64; 3]], t: f64) -> Option<Vec<[f64; 3]>> {
    let n = x.len();
    face_shape(n, 0.0, 0.0)?;
    let mut f = vec![[0.0; 3]; n];
    for (xi, eta, w) in face_points(n) {
        let (nn, d) = face_shape(n, xi, eta)?;
        let mut g = [[0.0; 3]; 2];
        for a in 0..n {
            for c in 0..2 {
                for k in 0..3 {
                    g[c][k] += d[a][c] * x[a][k];
                }
            }
        }
        let normal = [
            g[0][1] * g[1][2] - g[0][2] * g[1][1],
            g[0][2] * g[1][0] - g[0][0] * g[1][2],
            g[0][0] * g[1][1] - g[0][1] * g[1][0],
        ];
        for a in 0..n {
            for k in 0..3 {
                f[a][k] += t * w * nn[a] * normal[k];
            }
        }
    }
    Some(f)
}

/// Rotate a basic-frame vector into the node's displacement frame (rows = local axes).
fn to_local(dofs: &DofMap, node: NodeIndex, v: [f64; 3]) -> [f64; 3] {
    match dofs.frames[node] {
        Some(r) => [0, 1, 2].map(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2]),
        None => v,
    }
}

/// Load vectors over the physical dofs of `dofs`, one column per load (module doc); `m` is the
/// build's mass matrix (for gravity).
pub fn load_vectors(
    model: &Model,
    dofs: &DofMap,
    m: &SparseColMat<usize, f64>,
    loads: &[Load],
) -> Result<Mat<f64>, FeError> {
    let n = dofs.n_dofs;
    let mut f = Mat::<f64>::zeros(n, loads.len());
    let err = |load: &Load, message: String| FeError::BadReference {
        source_file: model.source.clone(),
        message: format!("load {} ({}): {message}", load.name, load.source),
    };
    for (j, load) in loads.iter().enumerate() {
        let mut accel = [0.0; 3];
        for part in &load.parts {
            match part {
                LoadPart::Nodal { node, values } => {
                    let node = *node;
                    let count = dofs.count.get(node).copied().unwrap_or(0) as usize;
                    let id = model.nodes.get(node).map_or(0, |p| p.id);
                    if count == 0 {
                        return Err(err(load, format!("node {id} carries no dofs (no element, mass or rigid element attaches to it)")));
                    }
                    if count < 6 && values[3..].iter().any(|v| *v != 0.0) {
                        return Err(err(load, format!("a moment at node {id}, which has only translational dofs (solid elements); apply it through an RBE2/RBE3 spider node")));
                    }
                    for (half, off) in [(0, 0), (1, 3)] {
                        if off >= count {
                            continue;
                        }
                        let v = [0, 1, 2].map(|k| values[3 * half + k]);
                        let l = to_local(dofs, node, v);
                        for k in 0..3 {
                            f[(dofs.first[node] + off + k, j)] += l[k];
                        }
                    }
                }
                LoadPart::Gravity { accel: a } => {
                    for k in 0..3 {
                        accel[k] += a[k];
                    }
                }
                LoadPart::Centrifugal {
                    omega2,
                    point,
                    axis,
                } => {
                    let spin = Spin {
                        point: *point,
                        axis: *axis,
                        omega: omega2.sqrt(),
                    };
                    let field = (spin.field())
                        .filter(|_| omega2.is_finite() && *omega2 >= 0.0)
                        .ok_or_else(|| {
                            err(load, format!("a centrifugal load with Ω² = {omega2} about the axis {axis:?} (Ω² ≥ 0 and a nonzero axis needed)"))
                        })?;
                    let fi = inertia_load(model, dofs, m, &field);
                    for (i, v) in fi.into_iter().enumerate() {
                        f[(i, j)] += v;
                    }
                }
                LoadPart::Surface {
                    nodes,
                    traction,
                    element,
                } => {
                    let x: Vec<[f64; 3]> = nodes.iter().map(|&p| model.nodes[p].x).collect();
                    let fa = face_forces(&x, *traction).ok_or_else(|| {
                        err(
                            load,
                            format!(
                                "element {element}: a face of {} nodes (3, 4, 6 or 8 expected)",
                                nodes.len()
                            ),
                        )
                    })?;
                    for (&p, v) in nodes.iter().zip(fa) {
                        if dofs.count[p] == 0 {
                            return Err(err(
                                load,
                                format!(
                                    "element {element}: face node {} carries no dofs",
                                    model.nodes[p].id
                                ),
                            ));
                        }
                        let l = to_local(dofs, p, v);
                        for k in 0..3 {
                            f[(dofs.first[p] + k, j)] += l[k];
                        }
                    }
                }
            }
        }
        if accel != [0.0; 3] {
            // f += M g with g the rigid translation by `accel` (rotations zero).
            let mut g = Mat::<f64>::zeros(n, 1);
            for p in 0..model.nodes.len() {
                if dofs.count[p] == 0 {
                    continue;
                }
                let l = to_local(dofs, p, accel);
                for k in 0..3 {
                    g[(dofs.first[p] + k, 0)] = l[k];
                }
            }
            let mg = crate::solve::sparse_ops::spmm(m.as_ref(), g.as_ref());
            for i in 0..n {
                f[(i, j)] += mg[(i, 0)];
            }
        }
    }
    Ok(f)
}

/// f_r = Tᵀ f: load vectors on the independent dofs of an elimination `u = T u_r`.
pub fn reduce_loads(t: &SparseColMat<usize, f64>, f: &Mat<f64>) -> Mat<f64> {
    let t = t.as_ref();
    let mut out = Mat::<f64>::zeros(t.ncols(), f.ncols());
    for c in 0..t.ncols() {
        for (i, v) in t.row_idx_of_col(c).zip(t.val_of_col(c)) {
            for j in 0..f.ncols() {
                out[(c, j)] += v * f[(i, j)];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Total force of a uniform traction on a flat face is t·A·n; the nodal split of a linear
    /// quad is A/4 each, of a quadratic triangle 0 at corners and A/3 at mid-sides (closed form).
    #[test]
    fn face_forces_match_closed_form() {
        let quad = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
        ];
        let f = face_forces(&quad, 5.0).unwrap();
        for v in &f {
            assert!((v[2] - 5.0 * 6.0 / 4.0).abs() < 1e-12 && v[0].abs() < 1e-14);
        }
        let tri6 = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
        ];
        let f = face_forces(&tri6, 1.0).unwrap();
        for a in 0..3 {
            assert!(f[a][2].abs() < 1e-12, "corner {a}: {:?}", f[a]);
            assert!(
                (f[3 + a][2] - 0.5 / 3.0).abs() < 1e-12,
                "mid {a}: {:?}",
                f[3 + a]
            );
        }
        // Quad8: corners −A/12, mid-sides A/3 (serendipity consistent load).
        let q8 = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let f = face_forces(&q8, 1.0).unwrap();
        for a in 0..4 {
            assert!(
                (f[a][2] + 4.0 / 12.0).abs() < 1e-12,
                "corner {a}: {:?}",
                f[a]
            );
            assert!(
                (f[4 + a][2] - 4.0 / 3.0).abs() < 1e-12,
                "mid {a}: {:?}",
                f[4 + a]
            );
        }
        let tri3 = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
        let f = face_forces(&tri3, 3.0).unwrap();
        for v in &f {
            assert!((v[2] + 0.5).abs() < 1e-12, "{v:?}");
        }
    }
}
