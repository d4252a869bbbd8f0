//! The nine inertia invariants of the modal-flexibility method (Adams numbering).
//!
//! From lumped nodal mass m_p, nodal inertia I_p (3×3, about the node), undeformed position s_p,
//! translational mode rows Φ_p (3×M) and rotational rows Φ*_p (3×M) at **every** mass node
//! (docs/design.md §3; `../shared/research/formats.md` §1.3, checked there against a real MNF):
//!
//! | # | definition | size |
//! |---|---|---|
//! | I1 | Σ m_p | 1 |
//! | I2 | Σ m_p s_p | 3 |
//! | I3 | Σ m_p Φ_p | 3×M |
//! | I4 | Σ (m_p s̃_p Φ_p + I_p Φ*_p) | 3×M |
//! | I5_j | Σ m_p φ̃_pj Φ_p | 3×M, j = 1..M |
//! | I6 | Σ (m_p Φ_pᵀ Φ_p + Φ*_pᵀ I_p Φ*_p) | M×M |
//! | I7 | Σ (m_p s̃_pᵀ s̃_p + I_p) | 3×3 |
//! | I8_j | Σ m_p s̃_p φ̃_pj | 3×3, j = 1..M |
//! | I9_jk | Σ m_p φ̃_pj φ̃_pk | 3×3, j, k = 1..M |
//!
//! ã is the cross-product matrix (ã b = a × b). I7 is the true inertia tensor (products of
//! inertia negative).
//!
//! The modal sums are evaluated as Gram products instead of node loops: with
//! W_c = diag(√m) Φ^c (N×M, c ∈ {x, y, z}) and G^{cd} = W_cᵀ W_d,
//! I6 = Σ_c G^{cc} (+ rotary term), (I5_j)_{:,k} = Σ m φ_pj × φ_pk is read from G^{cd} − G^{dc},
//! and because ã b̃ = b aᵀ − (a·b) E₃, (I9_jk)_{rc} = G^{cr}_{jk} − δ_{rc} Σ_d G^{dd}_{jk}.
//! That is six dense N×M×M products (BLAS-3) for the M² invariants instead of 27·N·M² scalar
//! updates.

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par};

/// One lumped mass point of the body: a node (or a point mass) with its mass and inertia.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassPoint {
    /// Undeformed position s_p in the body frame.
    pub position: [f64; 3],
    /// Lumped mass m_p ≥ 0.
    pub mass: f64,
    /// Nodal inertia tensor I_p about the point (symmetric; zero for solid nodes).
    pub inertia: [[f64; 3]; 3],
}

/// Which invariants to compute: the file's selection (MSC Nastran `ADAMSMNF MINVAR`, Adams
/// "inertia modeling"), whose [`InvariantSet::mask`] says which of I1…I9 are on.
pub use flexbody_reader::InvariantSet;

/// Bytes needed to hold the selected invariants for `modes` modes (I9 grows as 9·M²·8 bytes).
pub fn storage_bytes(set: InvariantSet, modes: usize) -> usize {
    let m = modes;
    let sizes = [1, 3, 3 * m, 3 * m, 3 * m * m, m * m, 9, 9 * m, 9 * m * m];
    set.mask()
        .iter()
        .zip(sizes)
        .filter(|(on, _)| **on)
        .map(|(_, s)| s * 8)
        .sum()
}

/// The invariants; the ones not selected are `None`.
#[derive(Debug, Clone, PartialEq)]
pub struct Invariants {
    /// Which were computed.
    pub set: InvariantSet,
    /// I1: total mass.
    pub i1: f64,
    /// I2: first mass moment Σ m s.
    pub i2: [f64; 3],
    /// I3 (3×M).
    pub i3: Option<Mat<f64>>,
    /// I4 (3×M).
    pub i4: Option<Mat<f64>>,
    /// I5_j (3×M each), j = 0..M.
    pub i5: Option<Vec<Mat<f64>>>,
    /// I6 (M×M).
    pub i6: Option<Mat<f64>>,
    /// I7 (3×3), inertia tensor about the body origin.
    pub i7: [[f64; 3]; 3],
    /// I8_j (3×3 each), j = 0..M.
    pub i8: Option<Vec<[[f64; 3]; 3]>>,
    /// I9_jk (3×3 each), stored at index j·M + k.
    pub i9: Option<Vec<[[f64; 3]; 3]>>,
}

/// Errors computing invariants.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InvariantError {
    /// Shapes do not have 6 rows per mass point.
    #[error("mode shapes have {rows} rows but {points} mass points need {expected} (6 per point: ux uy uz rx ry rz)")]
    ShapeRows {
        /// Rows given.
        rows: usize,
        /// Mass points.
        points: usize,
        /// 6 × points.
        expected: usize,
    },
    /// A mass is negative or not finite.
    #[error("mass point {index} has mass {mass}; nodal masses must be finite and ≥ 0")]
    BadMass {
        /// 0-based mass-point index.
        index: usize,
        /// The value.
        mass: f64,
    },
}

/// Compute the selected invariants. `shapes` is 6N×M, node-major rows `[ux uy uz rx ry rz]` per
/// point, in the order of `points`.
pub fn compute_invariants(
    points: &[MassPoint],
    shapes: MatRef<'_, f64>,
    set: InvariantSet,
    par: Par,
) -> Result<Invariants, InvariantError> {
    let n = points.len();
    if shapes.nrows() != 6 * n {
        return Err(InvariantError::ShapeRows {
            rows: shapes.nrows(),
            points: n,
            expected: 6 * n,
        });
    }
    if let Some((index, p)) = points
        .iter()
        .enumerate()
        .find(|(_, p)| !(p.mass.is_finite() && p.mass >= 0.0))
    {
        return Err(InvariantError::BadMass {
            index,
            mass: p.mass,
        });
    }
    let mask = set.mask();
    let (i1, i2, i7) = rigid_terms(points);
    // W_c = diag(√m) Φ^c, c = x, y, z (N×M each).
    let sqrt_m: Vec<f64> = points.iter().map(|p| p.mass.sqrt()).collect();
    let w: [Mat<f64>; 3] = std::array::from_fn(|c| {
        Mat::from_fn(n, shapes.ncols(), |p, j| sqrt_m[p] * shapes[(6 * p + c, j)])
    });

    let (i3, i4, i8) = first_order_terms(points, shapes, &w, mask, par);
    let (i5, i6, i9) = second_order_terms(points, shapes, &w, mask, par);
    Ok(Invariants {
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
    })
}

/// I3, I4, I8 (those selected).
type FirstOrder = (
    Option<Mat<f64>>,
    Option<Mat<f64>>,
    Option<Vec<[[f64; 3]; 3]>>,
);
/// I5, I6, I9 (those selected).
type SecondOrder = (
    Option<Vec<Mat<f64>>>,
    Option<Mat<f64>>,
    Option<Vec<[[f64; 3]; 3]>>,
);

/// The constant terms: I1 = Σ m, I2 = Σ m s, I7 = Σ m ((s·s)E − s sᵀ) + I_p.
fn rigid_terms(points: &[MassPoint]) -> (f64, [f64; 3], [[f64; 3]; 3]) {
    let mut i1 = 0.0;
    let mut i2 = [0.0; 3];
    let mut i7 = [[0.0; 3]; 3];
    for p in points {
        let (m, s) = (p.mass, p.position);
        i1 += m;
        let ss = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
        for r in 0..3 {
            i2[r] += m * s[r];
            for c in 0..3 {
                let delta = if r == c { ss } else { 0.0 };
                i7[r][c] += m * (delta - s[r] * s[c]) + p.inertia[r][c];
            }
        }
    }

    (i1, i2, i7)
}

/// The selected invariants of first order in the modes, I3, I4 and I8, from P^r = W_rᵀ √m [s 1]
/// (`w`: W_c = diag(√m) Φ^c).
fn first_order_terms(
    points: &[MassPoint],
    shapes: MatRef<'_, f64>,
    w: &[Mat<f64>; 3],
    mask: [bool; 9],
    par: Par,
) -> FirstOrder {
    let (n, nm) = (points.len(), shapes.ncols());
    let sqrt_m: Vec<f64> = points.iter().map(|p| p.mass.sqrt()).collect();
    // P^r = Φ^rᵀ diag(m) [s 1] (M×4): column c < 3 is Σ m φ^r s^c, column 3 is Σ m φ^r.
    let need_p = mask[2] || mask[3] || mask[7];
    let p_mats: Option<[Mat<f64>; 3]> = need_p.then(|| {
        let ms = Mat::from_fn(n, 4, |p, c| {
            let s = points[p].position;
            sqrt_m[p] * if c < 3 { s[c] } else { 1.0 }
        });
        std::array::from_fn(|r| {
            let mut out = Mat::zeros(nm, 4);
            matmul(&mut out, Accum::Replace, w[r].transpose(), &ms, 1.0, par);
            out
        })
    });

    let i3 = (mask[2]).then(|| {
        let pm = p_mats
            .as_ref()
            .expect("P computed when I3 is selected (need_p)");
        Mat::from_fn(3, nm, |r, j| pm[r][(j, 3)])
    });

    let i4 = mask[3].then(|| {
        let pm = p_mats
            .as_ref()
            .expect("P computed when I4 is selected (need_p)");
        // Σ m s × φ_j : x = s_y φ_z − s_z φ_y = P^z[j,y] − P^y[j,z], and cyclic.
        let mut out = Mat::from_fn(3, nm, |r, j| {
            let (a, b) = ((r + 1) % 3, (r + 2) % 3);
            pm[b][(j, a)] - pm[a][(j, b)]
        });
        // + Σ I_p Φ*_p
        for (p, pt) in points.iter().enumerate() {
            if pt.inertia.iter().flatten().all(|v| *v == 0.0) {
                continue;
            }
            for j in 0..nm {
                for r in 0..3 {
                    out[(r, j)] += (0..3)
                        .map(|c| pt.inertia[r][c] * shapes[(6 * p + 3 + c, j)])
                        .sum::<f64>();
                }
            }
        }
        out
    });

    let i8 = mask[7].then(|| {
        let pm = p_mats
            .as_ref()
            .expect("P computed when I8 is selected (need_p)");
        // s̃ φ̃ = φ sᵀ − (s·φ) E, so (I8_j)_{rc} = Σ m φ^r s^c − δ_rc Σ m s·φ.
        (0..nm)
            .map(|j| {
                let a: [[f64; 3]; 3] =
                    std::array::from_fn(|r| std::array::from_fn(|c| pm[r][(j, c)]));
                let tr = a[0][0] + a[1][1] + a[2][2];
                std::array::from_fn(|r| {
                    std::array::from_fn(|c| a[r][c] - if r == c { tr } else { 0.0 })
                })
            })
            .collect()
    });

    (i3, i4, i8)
}

/// The selected invariants of second order in the modes, I5, I6 and I9, from the Gram blocks
/// G^{cd} = W_cᵀ W_d (`w`: W_c = diag(√m) Φ^c).
fn second_order_terms(
    points: &[MassPoint],
    shapes: MatRef<'_, f64>,
    w: &[Mat<f64>; 3],
    mask: [bool; 9],
    par: Par,
) -> SecondOrder {
    let (n, nm) = (points.len(), shapes.ncols());
    // Gram blocks G^{cd} = W_cᵀ W_d, only when an M×M invariant is selected.
    let need_g = mask[4] || mask[5] || mask[8];
    let gram = |c: usize, d: usize| {
        let mut g = Mat::zeros(nm, nm);
        matmul(&mut g, Accum::Replace, w[c].transpose(), &w[d], 1.0, par);
        g
    };
    let g: Option<[[Mat<f64>; 3]; 3]> = need_g.then(|| {
        let upper: [[Option<Mat<f64>>; 3]; 3] =
            std::array::from_fn(|c| std::array::from_fn(|d| (c <= d).then(|| gram(c, d))));
        std::array::from_fn(|c| {
            std::array::from_fn(|d| match &upper[c][d] {
                Some(m) => m.clone(),
                None => upper[d][c]
                    .as_ref()
                    .expect("upper triangle computed for c > d")
                    .transpose()
                    .to_owned(),
            })
        })
    });

    let i6 = mask[5].then(|| {
        let g = g
            .as_ref()
            .expect("Gram computed when I6 is selected (need_g)");
        let mut out = Mat::from_fn(nm, nm, |j, k| {
            g[0][0][(j, k)] + g[1][1][(j, k)] + g[2][2][(j, k)]
        });
        // Σ Φ*ᵀ I_p Φ* over the points that carry rotary inertia: Zᵀ Y with Z = Φ*, Y = I_p Φ*.
        let rotary: Vec<usize> = (0..n)
            .filter(|&p| points[p].inertia.iter().flatten().any(|v| *v != 0.0))
            .collect();
        if !rotary.is_empty() {
            let z = Mat::from_fn(3 * rotary.len(), nm, |row, j| {
                shapes[(6 * rotary[row / 3] + 3 + row % 3, j)]
            });
            let y = Mat::from_fn(3 * rotary.len(), nm, |row, j| {
                let p = rotary[row / 3];
                (0..3)
                    .map(|c| points[p].inertia[row % 3][c] * shapes[(6 * p + 3 + c, j)])
                    .sum::<f64>()
            });
            matmul(&mut out, Accum::Add, z.transpose(), &y, 1.0, par);
        }
        out
    });

    let i5 = mask[4].then(|| {
        let g = g
            .as_ref()
            .expect("Gram computed when I5 is selected (need_g)");
        // (I5_j)_{r,k} = Σ m (φ_j × φ_k)_r = G^{ab}_{jk} − G^{ba}_{jk}, (r, a, b) cyclic.
        (0..nm)
            .map(|j| {
                Mat::from_fn(3, nm, |r, k| {
                    let (a, b) = ((r + 1) % 3, (r + 2) % 3);
                    g[a][b][(j, k)] - g[b][a][(j, k)]
                })
            })
            .collect()
    });

    let i9 = mask[8].then(|| {
        let g = g
            .as_ref()
            .expect("Gram computed when I9 is selected (need_g)");
        let mut out = Vec::with_capacity(nm * nm);
        for j in 0..nm {
            for k in 0..nm {
                let tr = g[0][0][(j, k)] + g[1][1][(j, k)] + g[2][2][(j, k)];
                out.push(std::array::from_fn(|r| {
                    std::array::from_fn(|c| g[c][r][(j, k)] - if r == c { tr } else { 0.0 })
                }));
            }
        }
        out
    });

    (i5, i6, i9)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cross-product matrix ã.
    fn skew(a: [f64; 3]) -> [[f64; 3]; 3] {
        [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]
    }
    fn mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
        std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| a[r][k] * b[k][c]).sum()))
    }
    fn mulv(a: [[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|r| (0..3).map(|k| a[r][k] * v[k]).sum())
    }

    /// Deterministic pseudo-random numbers in [-1, 1) (xorshift), no dependency needed.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    fn random_body(n: usize, modes: usize, seed: u64) -> (Vec<MassPoint>, Mat<f64>) {
        let mut rng = Rng(seed);
        let points = (0..n)
            .map(|p| {
                let a: [f64; 3] = std::array::from_fn(|_| rng.next());
                let inertia = if p % 3 == 0 {
                    // symmetric positive: a aᵀ + diag
                    std::array::from_fn(|r| {
                        std::array::from_fn(|c| a[r] * a[c] + if r == c { 0.5 } else { 0.0 })
                    })
                } else {
                    [[0.0; 3]; 3]
                };
                MassPoint {
                    position: std::array::from_fn(|_| 2.0 * rng.next()),
                    mass: 1.0 + rng.next(),
                    inertia,
                }
            })
            .collect();
        let shapes = Mat::from_fn(6 * n, modes, |_, _| rng.next());
        (points, shapes)
    }

    fn trans(shapes: &Mat<f64>, p: usize, j: usize) -> [f64; 3] {
        std::array::from_fn(|c| shapes[(6 * p + c, j)])
    }
    fn rot(shapes: &Mat<f64>, p: usize, j: usize) -> [f64; 3] {
        std::array::from_fn(|c| shapes[(6 * p + 3 + c, j)])
    }

    /// The Gram-product evaluation equals the definitions summed node by node with explicit
    /// cross-product matrices (the table in the module doc, formats.md §1.3).
    #[test]
    fn gram_evaluation_equals_definitions_node_by_node() {
        let (n, nm) = (23, 4);
        let (pts, sh) = random_body(n, nm, 0x9E3779B97F4A7C15);
        let inv = compute_invariants(&pts, sh.as_ref(), InvariantSet::Full, Par::Seq).unwrap();
        let tol = 1e-12 * n as f64;
        let (i3, i4, i5, i6, i8, i9) = (
            inv.i3.as_ref().unwrap(),
            inv.i4.as_ref().unwrap(),
            inv.i5.as_ref().unwrap(),
            inv.i6.as_ref().unwrap(),
            inv.i8.as_ref().unwrap(),
            inv.i9.as_ref().unwrap(),
        );
        for j in 0..nm {
            let mut e3 = [0.0; 3];
            let mut e4 = [0.0; 3];
            let mut e8 = [[0.0; 3]; 3];
            for (p, pt) in pts.iter().enumerate() {
                let phi = trans(&sh, p, j);
                let s_phi = mulv(skew(pt.position), phi);
                let i_rot = mulv(pt.inertia, rot(&sh, p, j));
                let ss = mul(skew(pt.position), skew(phi));
                for r in 0..3 {
                    e3[r] += pt.mass * phi[r];
                    e4[r] += pt.mass * s_phi[r] + i_rot[r];
                    for c in 0..3 {
                        e8[r][c] += pt.mass * ss[r][c];
                    }
                }
            }
            for r in 0..3 {
                assert!((i3[(r, j)] - e3[r]).abs() < tol);
                assert!((i4[(r, j)] - e4[r]).abs() < tol);
                for c in 0..3 {
                    assert!((i8[j][r][c] - e8[r][c]).abs() < tol);
                }
            }
            for k in 0..nm {
                let mut e5 = [0.0; 3];
                let mut e6 = 0.0;
                let mut e9 = [[0.0; 3]; 3];
                for (p, pt) in pts.iter().enumerate() {
                    let (pj, pk) = (trans(&sh, p, j), trans(&sh, p, k));
                    let cross = mulv(skew(pj), pk);
                    let rj = rot(&sh, p, j);
                    let irk = mulv(pt.inertia, rot(&sh, p, k));
                    e6 += pt.mass * (0..3).map(|c| pj[c] * pk[c]).sum::<f64>()
                        + (0..3).map(|c| rj[c] * irk[c]).sum::<f64>();
                    let jj = mul(skew(pj), skew(pk));
                    for r in 0..3 {
                        e5[r] += pt.mass * cross[r];
                        for c in 0..3 {
                            e9[r][c] += pt.mass * jj[r][c];
                        }
                    }
                }
                assert!((i6[(j, k)] - e6).abs() < tol, "I6[{j},{k}]");
                for r in 0..3 {
                    assert!((i5[j][(r, k)] - e5[r]).abs() < tol, "I5_{j}[{r},{k}]");
                    for c in 0..3 {
                        assert!(
                            (i9[j * nm + k][r][c] - e9[r][c]).abs() < tol,
                            "I9_{j}{k}[{r},{c}]"
                        );
                    }
                }
            }
        }
    }

    /// A uniform 3×3×3 lattice of unit masses with spacing h: I1, I2/I1 and I7 in closed form,
    /// and the six mass-normalized rigid-body modes give I3 = √I1·[E₃ 0], I6 = E₆, and I4 = (I2 × e)/√I1
    /// for translations and √J·e for rotations about the centre — the rigid identities.
    #[test]
    fn lattice_rigid_identities_closed_form() {
        let h = 0.5;
        let c0 = [1.0, -2.0, 0.25];
        let mut pts = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    let d = [i as f64 - 1.0, j as f64 - 1.0, k as f64 - 1.0];
                    pts.push(MassPoint {
                        position: std::array::from_fn(|c| c0[c] + h * d[c]),
                        mass: 1.0,
                        inertia: [[0.0; 3]; 3],
                    });
                }
            }
        }
        let n = pts.len();
        let m_tot = n as f64;
        // Central second moment per axis: Σ d² h² = 9·2·h² (two of three layers at ±1).
        let j_c = 2.0 * 18.0 * h * h; // J about a centre axis = Σ (d_a² + d_b²) h²
                                      // Rigid modes: 3 translations e_c/√m, 3 rotations about the centre (ω × (s − c0))/√J.
        let shapes = Mat::from_fn(6 * n, 6, |row, mode| {
            let (p, comp) = (row / 6, row % 6);
            if comp >= 3 {
                return 0.0; // solid nodes: no rotational dofs carry inertia
            }
            if mode < 3 {
                return if comp == mode {
                    1.0 / m_tot.sqrt()
                } else {
                    0.0
                };
            }
            let mut w = [0.0; 3];
            w[mode - 3] = 1.0;
            let r: [f64; 3] = std::array::from_fn(|c| pts[p].position[c] - c0[c]);
            let v = [
                w[1] * r[2] - w[2] * r[1],
                w[2] * r[0] - w[0] * r[2],
                w[0] * r[1] - w[1] * r[0],
            ];
            v[comp] / j_c.sqrt()
        });
        let inv = compute_invariants(&pts, shapes.as_ref(), InvariantSet::Full, Par::Seq).unwrap();
        assert_eq!(inv.i1, 27.0);
        for (first_moment, centre) in inv.i2.iter().zip(c0) {
            assert!((first_moment / inv.i1 - centre).abs() < 1e-14);
        }
        // I7 about the origin = J_c E − parallel-axis term m((c0·c0)E − c0 c0ᵀ).
        let cc = c0.iter().map(|v| v * v).sum::<f64>();
        for r in 0..3 {
            for c in 0..3 {
                let expect = if r == c { j_c } else { 0.0 }
                    + m_tot * (if r == c { cc } else { 0.0 } - c0[r] * c0[c]);
                assert!(
                    (inv.i7[r][c] - expect).abs() < 1e-12 * m_tot,
                    "I7[{r}][{c}] {} vs {expect}",
                    inv.i7[r][c]
                );
            }
        }
        let i6 = inv.i6.unwrap();
        let i3 = inv.i3.unwrap();
        let i4 = inv.i4.unwrap();
        for a in 0..6 {
            for b in 0..6 {
                assert!(
                    (i6[(a, b)] - if a == b { 1.0 } else { 0.0 }).abs() < 1e-13,
                    "I6 = I"
                );
            }
            for r in 0..3 {
                let expect = if a == r { m_tot.sqrt() } else { 0.0 };
                assert!(
                    (i3[(r, a)] - expect).abs() < 1e-13,
                    "I3 of rigid modes = sqrt(I1)[E 0]"
                );
                // I4: translations give (I2 × e_a)/√I1; rotations about the centre give √J e_a.
                let expect4 = if a < 3 {
                    let mut e = [0.0; 3];
                    e[a] = 1.0;
                    let (u, v) = ((r + 1) % 3, (r + 2) % 3);
                    (inv.i2[u] * e[v] - inv.i2[v] * e[u]) / m_tot.sqrt()
                } else if a - 3 == r {
                    j_c.sqrt()
                } else {
                    0.0
                };
                assert!(
                    (i4[(r, a)] - expect4).abs() < 1e-12,
                    "I4[{r},{a}] {} vs {expect4}",
                    i4[(r, a)]
                );
            }
        }
    }

    #[test]
    fn selection_sets_and_errors() {
        let (pts, sh) = random_body(5, 3, 7);
        let rigid = compute_invariants(&pts, sh.as_ref(), InvariantSet::Rigid, Par::Seq).unwrap();
        assert!(rigid.i3.is_none() && rigid.i6.is_none() && rigid.i9.is_none());
        let partial =
            compute_invariants(&pts, sh.as_ref(), InvariantSet::Partial, Par::Seq).unwrap();
        assert!(partial.i5.is_none() && partial.i9.is_none() && partial.i8.is_some());
        assert_eq!(
            storage_bytes(InvariantSet::Full, 10) - storage_bytes(InvariantSet::Partial, 10),
            (30 * 10 + 9 * 100) * 8
        );
        let bad =
            compute_invariants(&pts[..4], sh.as_ref(), InvariantSet::Full, Par::Seq).unwrap_err();
        assert!(matches!(
            bad,
            InvariantError::ShapeRows {
                rows: 30,
                points: 4,
                expected: 24
            }
        ));
        let mut neg = pts.clone();
        neg[2].mass = -1.0;
        assert_eq!(
            compute_invariants(&neg, sh.as_ref(), InvariantSet::Full, Par::Seq).unwrap_err(),
            InvariantError::BadMass {
                index: 2,
                mass: -1.0
            }
        );
    }
}
