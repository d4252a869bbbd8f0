//! The nine inertia invariants from a consistent mass matrix (SPEC.md §5.6, `mass_kind =
//! Consistent`): the same matrix the modes are orthonormal in, so I6 = ΦᵀMΦ = I and a solver
//! that rebuilds its mass matrix from the invariants gets the file's frequencies.
//!
//! With R the six rigid-body vectors of the model's dofs (translations t_a; rotations r_b: e_b × x
//! on translational dofs, e_b on rotational dofs; each in the node's displacement frame):
//! I1 = t_aᵀMt_a, I2 from t_aᵀMr_b (= −[Ĩ2]_ab), I3 = TᵀMΦ, I4 = R_rotᵀMΦ, I6 = ΦᵀMΦ,
//! I7 = R_rotᵀMR_rot — the consistent-mass integrals of SID/MBSim/exudyn. The cross-product
//! invariants I5, I8, I9 use the node-pair scalar masses m_pq = tr(M_pq)/3 of the translational
//! 3×3 blocks (exact for solid elements, whose blocks are m_pq·E):
//! I5_j = Σ m_pq φ̃_jp Φ_q, I8_j = Σ m_pq s̃_p φ̃_jq, I9_jk = Σ m_pq φ̃_jp φ̃_kq.
//!
//! Interior dofs (ccx's C3D8I: the amplitudes of its incompatible modes, xyz triples in the
//! basic frame) are translational fields with mass too: each triple is one more point q of the
//! sums with s_q = 0 (a rigid motion excites no interior dof) and φ_jq its rows of Φ.

use faer::sparse::SparseColMat;
use faer::Mat;

use crate::body::invariants::{InvariantSet, Invariants};
use crate::fe::DofMap;
use crate::solve::sparse_ops::spmm;

/// Rigid-body vectors of the dofs: columns tx ty tz rx ry rz (basic axes, local dof frames).
fn rigid_vectors(dofs: &DofMap, x: &[[f64; 3]]) -> Mat<f64> {
    let mut r = Mat::<f64>::zeros(dofs.n_dofs, 6);
    for (p, xp) in x.iter().enumerate() {
        let count = usize::from(dofs.count[p]);
        let to_local = |v: [f64; 3]| -> [f64; 3] {
            match dofs.frames[p] {
                None => v,
                Some(a) => std::array::from_fn(|i| (0..3).map(|k| a[i][k] * v[k]).sum()),
            }
        };
        for b in 0..6 {
            let e: [f64; 3] = std::array::from_fn(|k| if k == b % 3 { 1.0 } else { 0.0 });
            let (trans, rot) = if b < 3 {
                (e, [0.0; 3])
            } else {
                // e × x
                let t = [
                    e[1] * xp[2] - e[2] * xp[1],
                    e[2] * xp[0] - e[0] * xp[2],
                    e[0] * xp[1] - e[1] * xp[0],
                ];
                (t, e)
            };
            let (tl, rl) = (to_local(trans), to_local(rot));
            for c in 0..count.min(6) {
                r[(dofs.first[p] + c, b)] = if c < 3 { tl[c] } else { rl[c - 3] };
            }
        }
    }
    r
}

/// The translational point and component of a dof: (node, c) for a node's c < 3, (nn + k, c)
/// for the k-th xyz triple of the interior dofs; `None` for rotations and scalar points.
fn translation_of(dofs: &DofMap, dof: usize) -> Option<(usize, usize)> {
    if dof >= dofs.n_physical {
        let k = dof - dofs.n_physical;
        return Some((dofs.count.len() + k / 3, k % 3));
    }
    dofs.node_of(dof).filter(|&(_, c)| c < 3)
}

/// Point-pair scalar masses m_pq = tr(A_pᵀ M_pq A_q)/3 of the translational blocks (basic axes)
/// over the nodes and the interior triples ([`translation_of`]).
fn pair_masses(m: &SparseColMat<usize, f64>, dofs: &DofMap) -> Vec<(usize, usize, f64)> {
    let mut blocks: std::collections::BTreeMap<(usize, usize), [[f64; 3]; 3]> = Default::default();
    let mr = m.as_ref();
    for col in 0..mr.ncols() {
        let Some((q, b)) = translation_of(dofs, col) else {
            continue;
        };
        for (row, v) in mr.row_idx_of_col(col).zip(mr.val_of_col(col)) {
            if let Some((p, a)) = translation_of(dofs, row) {
                blocks.entry((p, q)).or_insert([[0.0; 3]; 3])[a][b] += *v;
            }
        }
    }
    let eye = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let frame = |p: usize| dofs.frames.get(p).copied().flatten().unwrap_or(eye);
    blocks
        .into_iter()
        .map(|((p, q), blk)| {
            let (ap, aq) = (frame(p), frame(q));
            // tr(A_pᵀ B A_q) = Σ_{i,a,b} A_p[a][i] B[a][b] A_q[b][i]
            let mut tr = 0.0;
            for i in 0..3 {
                for a in 0..3 {
                    for b in 0..3 {
                        tr += ap[a][i] * blk[a][b] * aq[b][i];
                    }
                }
            }
            (p, q, tr / 3.0)
        })
        .collect()
}

/// ã b̃ = b aᵀ − (a·b) E as the 3×3 of the sums C[a][b] = Σ m u[a] v[b]: Cᵀ − tr(C) E.
fn skew_product(c: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let tr = c[0][0] + c[1][1] + c[2][2];
    std::array::from_fn(|r| std::array::from_fn(|k| c[k][r] - if r == k { tr } else { 0.0 }))
}

/// The invariants of `set` from the consistent mass `m` over the model's dofs, node positions
/// `x` (basic frame) and the mode shapes `phi` (model dofs × M, local dof frames); `shape(p, j)`
/// returns node p's translations of mode j in the basic frame.
pub fn consistent_invariants(
    m: &SparseColMat<usize, f64>,
    dofs: &DofMap,
    x: &[[f64; 3]],
    phi: &Mat<f64>,
    shape: &dyn Fn(usize, usize) -> [f64; 3],
    set: InvariantSet,
) -> Invariants {
    let nm = phi.ncols();
    let mask = set.mask();
    let r = rigid_vectors(dofs, x);
    let mr = spmm(m.as_ref(), r.as_ref());
    let rmr = r.transpose() * &mr; // 6×6
    let i1 = (rmr[(0, 0)] + rmr[(1, 1)] + rmr[(2, 2)]) / 3.0;
    // t_aᵀ M r_b = e_a · (e_b × I2): I2_x = t_yᵀMr_z = −t_zᵀMr_y, and cyclically.
    let i2 = [
        0.5 * (rmr[(1, 5)] - rmr[(2, 4)]),
        0.5 * (rmr[(2, 3)] - rmr[(0, 5)]),
        0.5 * (rmr[(0, 4)] - rmr[(1, 3)]),
    ];
    let i7: [[f64; 3]; 3] = std::array::from_fn(|a| std::array::from_fn(|b| rmr[(3 + a, 3 + b)]));
    let rphi = mr.transpose() * phi; // 6×M: R ᵀ M Φ
    let i3 = mask[2].then(|| Mat::from_fn(3, nm, |a, j| rphi[(a, j)]));
    let i4 = mask[3].then(|| Mat::from_fn(3, nm, |a, j| rphi[(3 + a, j)]));
    let i6 = mask[5].then(|| {
        let mphi = spmm(m.as_ref(), phi.as_ref());
        let g = phi.transpose() * &mphi;
        Mat::from_fn(nm, nm, |a, b| 0.5 * (g[(a, b)] + g[(b, a)]))
    });
    let (mut i5, mut i8, mut i9) = (None, None, None);
    if mask[4] || mask[7] || mask[8] {
        let pairs = pair_masses(m, dofs);
        let nn = x.len();
        let np = nn + (dofs.n_dofs - dofs.n_physical) / 3;
        // U[p][3j + a]: translation a of point p in mode j (basic); W = M_s U.
        let u = Mat::from_fn(np, 3 * nm, |p, c| {
            if p < nn {
                shape(p, c / 3)[c % 3]
            } else {
                phi[(dofs.n_physical + 3 * (p - nn) + c % 3, c / 3)]
            }
        });
        let position = |q: usize| if q < nn { x[q] } else { [0.0; 3] };
        let mut w = Mat::<f64>::zeros(np, 3 * nm);
        let mut ms = Mat::<f64>::zeros(np, 3); // M_s s (for I8)
        for &(p, q, mpq) in &pairs {
            for c in 0..3 * nm {
                w[(p, c)] += mpq * u[(q, c)];
            }
            for a in 0..3 {
                ms[(p, a)] += mpq * position(q)[a];
            }
        }
        // C[(3j + a), (3k + b)] = Σ_pq m_pq φ_jp[a] φ_kq[b]
        let c = u.transpose() * &w;
        let block = |j: usize, k: usize| -> [[f64; 3]; 3] {
            std::array::from_fn(|a| std::array::from_fn(|b| c[(3 * j + a, 3 * k + b)]))
        };
        if mask[4] {
            // (φ_j × φ_k)_a = ε_abc φ_j[b] φ_k[c]
            i5 = Some(
                (0..nm)
                    .map(|j| {
                        Mat::from_fn(3, nm, |a, k| {
                            let cc = block(j, k);
                            let (b, d) = ((a + 1) % 3, (a + 2) % 3);
                            cc[b][d] - cc[d][b]
                        })
                    })
                    .collect(),
            );
        }
        if mask[7] {
            // D_j[a][b] = Σ m_pq s_p[a] φ_jq[b] = Σ_q (M_s s)_q[a] φ_jq[b]
            let d = ms.transpose() * &u; // 3 × 3M
            i8 = Some(
                (0..nm)
                    .map(|j| {
                        let dj: [[f64; 3]; 3] =
                            std::array::from_fn(|a| std::array::from_fn(|b| d[(a, 3 * j + b)]));
                        skew_product(&dj)
                    })
                    .collect(),
            );
        }
        if mask[8] {
            i9 = Some(
                (0..nm * nm)
                    .map(|jk| skew_product(&block(jk / nm, jk % nm)))
                    .collect(),
            );
        }
    }
    Invariants {
        set,
        i1,
        i2,
        i3,
        i4,
        i5,
        i6,
        i7,
        i8,
        i9,
    }
}
