//! What the curved quadratic shells ([`super::quad8_shell`], [`super::tri6_shell`]) share: a
//! continuum-based shell with MITC assumed covariant strains, 6 dofs per node.
//!
//! * Geometry and kinematics (Bathe, *Finite Element Procedures* (1996) §5.4.2, linear part):
//!   X(r, s, ζ) = Σ N_a (x_a + ζ t_a/2 V_a), U = Σ N_a (u_a + ζ t_a/2 θ_a × V_a), ζ ∈ [−1, 1],
//!   with V_a the unit normal of the element's surface at node a (its director) and t_a the
//!   nodal thickness. θ is the node's rotation vector, as in the flat shells (shell.rs): a rigid
//!   motion u = c + θ × x of the nodes moves every point of the shell rigidly, so it costs no
//!   energy on any curved element.
//! * Strains: the covariant components e_ij = ½(g_i·U,j + g_j·U,i) (g_i = X,i) of e_rr, e_ss,
//!   e_rs and the transverse shears e_rζ, e_sζ are replaced by MITC assumed fields interpolated
//!   from tying points (the element's file says which), then turned into Cartesian components
//!   of a local lamina frame (ê₃ ∥ g_r × g_s, ê₁ along g_r) through the contravariant base g^k:
//!   ε_ij = (ê_i·g^k)(ê_j·g^l) e_kl; e_ζζ is left out (plane stress).
//! * Section: two points ζ = ±1/√3 through the thickness. The mean of the two in-plane strains
//!   is the membrane strain ε, their difference over 2z (z = t/(2√3)) the curvature κ; energy
//!   per area εᵀD_mε + κᵀD_bκ + G_s(γ₊² + γ₋²)/2 with the section's D_m, D_b and shear rigidity
//!   ([`ShellProps`]) at the local thickness t = Σ N_a t_a — for a homogeneous section exactly
//!   the two-point Gauss integral of the plane-stress continuum through the thickness.
//! * Drilling: the flat shells' penalty γ_d (θ·ê₃ − ω)², ω = ½(ê₂·∂U/∂ê₁ − ê₁·∂U/∂ê₂) at the
//!   mid-surface (Hughes & Brezzi 1989; shell.rs), at every stiffness point: zero for rigid
//!   rotations on curved elements too (∇U of u = θ × x has ω = θ·ê₃).
//! * Mass: ∫ (ρt + nsm) N_aN_b dA ⊗ I₃ and ∫ ρt³/12 N_aN_b dA ⊗ (I − (1 − ε) ê₃ê₃ᵀ) as in
//!   shell.rs (ε = DRILL_INERTIA); lumped by HRZ (Hinton, Rock & Zienkiewicz, *Earthq. Eng.
//!   Struct. Dyn.* 4 (1976) 245): each node the diagonal term scaled to the element's total, so
//!   that no node of a quadratic element gets a negative mass as by row sums (8-node
//!   serendipity corners: −1/12 of the area), rotations about the nodal director V_a.

use super::shell::{add_outer, ShellProps, DRILL_INERTIA};
use super::{ElementError, Xyz};
use crate::model::geometry::{cross, dot, norm, scale, sub};

/// Reference points of the 8-node quadrilateral's nodes: corners (±1, ±1), then the mid-sides
/// (0, −1), (1, 0), (0, 1), (−1, 0) (Abaqus, Nastran and ANSYS order).
pub(crate) const SERENDIPITY8: [[f64; 2]; 8] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];

/// 8-node serendipity shape functions (node order of [`SERENDIPITY8`]).
pub(crate) fn shape8(r: f64, s: f64) -> (Vec<f64>, Vec<[f64; 2]>) {
    let mut n = Vec::with_capacity(8);
    let mut d = Vec::with_capacity(8);
    for p in &SERENDIPITY8 {
        let (ra, sa) = (p[0], p[1]);
        if ra != 0.0 && sa != 0.0 {
            let (fr, fs) = (1.0 + ra * r, 1.0 + sa * s);
            let q = ra * r + sa * s - 1.0;
            n.push(0.25 * fr * fs * q);
            d.push([0.25 * ra * fs * (q + fr), 0.25 * sa * fr * (q + fs)]);
        } else if ra == 0.0 {
            n.push(0.5 * (1.0 - r * r) * (1.0 + sa * s));
            d.push([-r * (1.0 + sa * s), 0.5 * sa * (1.0 - r * r)]);
        } else {
            n.push(0.5 * (1.0 + ra * r) * (1.0 - s * s));
            d.push([0.5 * ra * (1.0 - s * s), -s * (1.0 + ra * r)]);
        }
    }
    (n, d)
}

/// Shape functions N_a and their (r, s) derivatives at a point.
pub(crate) type Shape = fn(f64, f64) -> (Vec<f64>, Vec<[f64; 2]>);

/// Assumed-strain weights at (r, s): for each tying point p a 5×5 matrix M_p with
/// ẽ_k(r, s) = Σ_p Σ_j M_p[k][j] e_j(r_p, s_p), components (e_rr, e_ss, e_rs, e_rζ, e_sζ).
pub(crate) type Weights<'a> = &'a dyn Fn(f64, f64) -> Vec<[[f64; 5]; 5]>;

/// The element's surface: node positions, nodal thicknesses and unit directors.
pub(crate) struct Lamina<'a> {
    /// Node positions.
    pub x: &'a [Xyz],
    /// Nodal thicknesses.
    pub t: &'a [f64],
    /// Unit directors (surface normals at the nodes).
    pub v: Vec<Xyz>,
    /// Shape functions of the nodes.
    pub shape: Shape,
}

/// One thickness point of the stiffness: ζ = ±1/√3.
const ZETA: f64 = 0.577_350_269_189_625_8;

impl Lamina<'_> {
    /// Lamina with directors the unit normals g_r × g_s at the nodes' reference points `rs`.
    pub fn new<'a>(
        x: &'a [Xyz],
        t: &'a [f64],
        shape: Shape,
        rs: &[[f64; 2]],
    ) -> Result<Lamina<'a>, ElementError> {
        let size = x
            .iter()
            .flat_map(|a| x.iter().map(move |b| norm(sub(*a, *b))))
            .fold(0.0, f64::max);
        if t.iter().any(|&v| !(v > 0.0 && v.is_finite())) {
            return Err(ElementError::BadConstants(format!(
                "shell nodal thicknesses {t:?}: each must be > 0"
            )));
        }
        let mut v = Vec::with_capacity(x.len());
        for (a, p) in rs.iter().enumerate() {
            let (_, dn) = shape(p[0], p[1]);
            let (gr, gs) = tangents(x, &dn);
            let nrm = cross(gr, gs);
            let len = norm(nrm);
            if len.is_nan() || len <= 1e-12 * size * size || size <= 0.0 {
                return Err(ElementError::NonPositiveJacobian { det: len, point: a });
            }
            v.push(scale(nrm, 1.0 / len));
        }
        Ok(Lamina { x, t, v, shape })
    }

    /// Covariant base (g_r, g_s, g_ζ) at shape values `n`, `dn` and ζ.
    fn bases(&self, n: &[f64], dn: &[[f64; 2]], zeta: f64) -> [Xyz; 3] {
        let mut g = [[0.0; 3]; 3];
        for a in 0..self.x.len() {
            let h = 0.5 * self.t[a];
            for i in 0..3 {
                let p = self.x[a][i] + zeta * h * self.v[a][i];
                g[0][i] += dn[a][0] * p;
                g[1][i] += dn[a][1] * p;
                g[2][i] += n[a] * h * self.v[a][i];
            }
        }
        g
    }

    /// Adds c · (g · U,k) (k = 0: r, 1: s, 2: ζ) to `row` (6 dofs per node);
    /// g·(θ × V) = θ·(V × g).
    #[allow(clippy::too_many_arguments)]
    fn add_dot(
        &self,
        row: &mut [f64],
        n: &[f64],
        dn: &[[f64; 2]],
        zeta: f64,
        g: Xyz,
        k: usize,
        c: f64,
    ) {
        for a in 0..self.x.len() {
            let h = 0.5 * self.t[a];
            let (tc, rc) = if k < 2 {
                (dn[a][k], zeta * h * dn[a][k])
            } else {
                (0.0, h * n[a])
            };
            let vg = cross(self.v[a], g);
            for i in 0..3 {
                row[6 * a + i] += c * tc * g[i];
                row[6 * a + 3 + i] += c * rc * vg[i];
            }
        }
    }

    /// Rows of the covariant strains (e_rr, e_ss, e_rs, e_rζ, e_sζ) at (r, s, ζ).
    fn covariant(&self, r: f64, s: f64, zeta: f64) -> [Vec<f64>; 5] {
        let nd = 6 * self.x.len();
        let (n, dn) = (self.shape)(r, s);
        let g = self.bases(&n, &dn, zeta);
        let mut e: [Vec<f64>; 5] = std::array::from_fn(|_| vec![0.0; nd]);
        // (component, [(i, j) pairs of g_i · U,j with their factor])
        // (component, the (i, j, factor) terms g_i · U,j)
        type Terms<'t> = [(usize, &'t [(usize, usize, f64)]); 5];
        let terms: Terms = [
            (0, &[(0, 0, 1.0)]),
            (1, &[(1, 1, 1.0)]),
            (2, &[(0, 1, 0.5), (1, 0, 0.5)]),
            (3, &[(0, 2, 0.5), (2, 0, 0.5)]),
            (4, &[(1, 2, 0.5), (2, 1, 0.5)]),
        ];
        for (comp, list) in terms {
            for &(i, j, c) in list {
                self.add_dot(&mut e[comp], &n, &dn, zeta, g[i], j, c);
            }
        }
        e
    }
}

/// Mid-surface tangents g_r, g_s of positions `x` at shape derivatives `dn`.
fn tangents(x: &[Xyz], dn: &[[f64; 2]]) -> (Xyz, Xyz) {
    let mut gr = [0.0; 3];
    let mut gs = [0.0; 3];
    for (a, xa) in x.iter().enumerate() {
        for i in 0..3 {
            gr[i] += dn[a][0] * xa[i];
            gs[i] += dn[a][1] * xa[i];
        }
    }
    (gr, gs)
}

/// Local lamina frame (ê₁ along g_r, ê₃ ∥ g_r × g_s) and the area factor |g_r × g_s|.
fn lamina_frame(gr: Xyz, gs: Xyz) -> ([Xyz; 3], f64) {
    let nrm = cross(gr, gs);
    let da = norm(nrm);
    let e3 = scale(nrm, 1.0 / da);
    let e1 = scale(gr, 1.0 / norm(gr));
    let e2 = cross(e3, e1);
    ([e1, e2, e3], da)
}

/// Contravariant base g^k of the covariant base g (rows), with det[g_r g_s g_ζ].
fn contravariant(g: &[Xyz; 3], point: usize) -> Result<[Xyz; 3], ElementError> {
    let det = dot(g[0], cross(g[1], g[2]));
    if det.is_nan() || det <= 0.0 {
        return Err(ElementError::NonPositiveJacobian { det, point });
    }
    Ok([
        scale(cross(g[1], g[2]), 1.0 / det),
        scale(cross(g[2], g[0]), 1.0 / det),
        scale(cross(g[0], g[1]), 1.0 / det),
    ])
}

/// Local engineering strain rows (ε₁₁, ε₂₂, γ₁₂, γ₁₃, γ₂₃) from covariant rows `e` with
/// c_ik = ê_i · g^k (module doc).
fn cartesian(e: &[Vec<f64>; 5], c: &[[f64; 3]; 3]) -> [Vec<f64>; 5] {
    let nd = e[0].len();
    // (i, j, engineering factor) of the five local components
    const IJ: [(usize, usize, f64); 5] = [
        (0, 0, 1.0),
        (1, 1, 1.0),
        (0, 1, 2.0),
        (0, 2, 2.0),
        (1, 2, 2.0),
    ];
    std::array::from_fn(|q| {
        let (i, j, f) = IJ[q];
        let coef = [
            c[i][0] * c[j][0],
            c[i][1] * c[j][1],
            c[i][0] * c[j][1] + c[i][1] * c[j][0],
            c[i][0] * c[j][2] + c[i][2] * c[j][0],
            c[i][1] * c[j][2] + c[i][2] * c[j][1],
        ];
        let mut row = vec![0.0; nd];
        for (k, ek) in e.iter().enumerate() {
            let w = f * coef[k];
            if w != 0.0 {
                for (r, v) in row.iter_mut().zip(ek) {
                    *r += w * v;
                }
            }
        }
        row
    })
}

/// Add c · Bᵀ D B for rows `b` (3 × nd) to the nd×nd `k`.
pub(crate) fn add_btdb_rows(k: &mut [f64], b: &[&[f64]; 3], d: &[[f64; 3]; 3], c: f64) {
    let nd = b[0].len();
    let db: [Vec<f64>; 3] = std::array::from_fn(|i| {
        (0..nd)
            .map(|q| (0..3).map(|l| d[i][l] * b[l][q]).sum())
            .collect()
    });
    for p in 0..nd {
        let bp = [b[0][p], b[1][p], b[2][p]];
        if bp == [0.0; 3] {
            continue;
        }
        for q in 0..nd {
            k[p * nd + q] += c * (bp[0] * db[0][q] + bp[1] * db[1][q] + bp[2] * db[2][q]);
        }
    }
}

/// The strain rows of one stiffness point (6N columns, node-major): membrane strains and
/// curvatures (ε₁₁, ε₂₂, γ₁₂ and κ₁₁, κ₂₂, κ₁₂ in the local lamina frame), the transverse shears
/// (γ₁₃, γ₂₃) at ζ = ∓1/√3, the drilling row θ·ê₃ − ω (module doc), the area factor
/// |g_r × g_s| and the local thickness Σ N_a t_a.
pub(crate) struct PointRows {
    pub mem: [Vec<f64>; 3],
    pub kap: [Vec<f64>; 3],
    pub shear: [[Vec<f64>; 2]; 2],
    pub drill: Vec<f64>,
    pub da: f64,
    pub t: f64,
}

/// Covariant strain rows at (r, s) for ζ = ∓1/√3 (no assumed strain: the displacement-based
/// shell).
pub(crate) fn covariant_pair(l: &Lamina, r: f64, s: f64) -> [[Vec<f64>; 5]; 2] {
    [l.covariant(r, s, -ZETA), l.covariant(r, s, ZETA)]
}

/// The rows of stiffness point `ip` at (r, s) from its covariant strain rows `cov` at
/// ζ = ∓1/√3 (assumed or not), turned into the local lamina frame (module doc).
pub(crate) fn point_rows(
    l: &Lamina,
    [r, s]: [f64; 2],
    cov: &[[Vec<f64>; 5]; 2],
    ip: usize,
) -> Result<PointRows, ElementError> {
    let nn = l.x.len();
    let nd = 6 * nn;
    let (n, dn) = (l.shape)(r, s);
    let g0 = l.bases(&n, &dn, 0.0);
    let (e, da) = lamina_frame(g0[0], g0[1]);
    if da.is_nan() || da <= 0.0 {
        return Err(ElementError::NonPositiveJacobian { det: da, point: ip });
    }
    let t: f64 = n.iter().zip(l.t).map(|(a, b)| a * b).sum();
    let mut local: Vec<[Vec<f64>; 5]> = Vec::with_capacity(2);
    for (zi, z) in [-ZETA, ZETA].into_iter().enumerate() {
        let gz = l.bases(&n, &dn, z);
        let gc = contravariant(&gz, ip)?;
        let c: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|q| dot(e[i], gc[q])));
        local.push(cartesian(&cov[zi], &c));
    }
    let zp = t * ZETA / 2.0;
    let mem: [Vec<f64>; 3] = std::array::from_fn(|q| {
        (0..nd)
            .map(|j| 0.5 * (local[1][q][j] + local[0][q][j]))
            .collect()
    });
    let kap: [Vec<f64>; 3] = std::array::from_fn(|q| {
        (0..nd)
            .map(|j| (local[1][q][j] - local[0][q][j]) / (2.0 * zp))
            .collect()
    });
    // θ·ê₃ − ½(ê₂·∂U/∂ê₁ − ê₁·∂U/∂ê₂), ∂U/∂ê_i = Σ_k (g^k·ê_i) U,k at ζ = 0
    let gc = contravariant(&g0, ip)?;
    let mut drill = vec![0.0; nd];
    for a in 0..nn {
        for i in 0..3 {
            drill[6 * a + 3 + i] += n[a] * e[2][i];
        }
    }
    for kk in 0..3 {
        let c1 = dot(gc[kk], e[0]);
        let c2 = dot(gc[kk], e[1]);
        l.add_dot(&mut drill, &n, &dn, 0.0, e[1], kk, -0.5 * c1);
        l.add_dot(&mut drill, &n, &dn, 0.0, e[0], kk, 0.5 * c2);
    }
    let [lo, hi] = [&local[0], &local[1]];
    Ok(PointRows {
        mem,
        kap,
        shear: [
            [lo[3].clone(), lo[4].clone()],
            [hi[3].clone(), hi[4].clone()],
        ],
        drill,
        da,
        t,
    })
}

/// Makes `k` (nd × nd) exactly symmetric (sums of outer products are symmetric up to rounding).
pub(crate) fn symmetrize(k: &mut [f64], nd: usize) {
    for i in 0..nd {
        for j in 0..i {
            let v = 0.5 * (k[i * nd + j] + k[j * nd + i]);
            k[i * nd + j] = v;
            k[j * nd + i] = v;
        }
    }
}

/// Stiffness (6N×6N, basic frame, node-major `[u v w θx θy θz]`) of the MITC shell (module
/// doc): tying points `points`, assumed-strain `weights`, in-plane `rule` ((r, s), weight).
pub(crate) fn stiffness(
    l: &Lamina,
    points: &[[f64; 2]],
    weights: Weights,
    rule: &[([f64; 2], f64)],
    props: &ShellProps,
) -> Result<Vec<f64>, ElementError> {
    let nd = 6 * l.x.len();
    let all: Vec<usize> = (0..nd).collect();
    let mut k = vec![0.0; nd * nd];
    // covariant strains at the tying points, for each thickness point
    let tied: [Vec<[Vec<f64>; 5]>; 2] =
        [-ZETA, ZETA].map(|z| points.iter().map(|p| l.covariant(p[0], p[1], z)).collect());
    for (ip, &([r, s], w)) in rule.iter().enumerate() {
        let wm = weights(r, s);
        let cov: [[Vec<f64>; 5]; 2] = std::array::from_fn(|zi| {
            let mut cov: [Vec<f64>; 5] = std::array::from_fn(|_| vec![0.0; nd]);
            for (pi, m) in wm.iter().enumerate() {
                for (kk, row) in cov.iter_mut().enumerate() {
                    for (j, ej) in tied[zi][pi].iter().enumerate() {
                        let c = m[kk][j];
                        if c != 0.0 {
                            for (x, y) in row.iter_mut().zip(ej) {
                                *x += c * y;
                            }
                        }
                    }
                }
            }
            cov
        });
        let rows = point_rows(l, [r, s], &cov, ip)?;
        let p = ShellProps {
            t: rows.t,
            ..*props
        };
        let (dm, db, ds, gd) = (p.d_membrane(), p.d_bending(), p.shear_modulus(), p.drill());
        let dw = rows.da * w;
        let m = &rows.mem;
        add_btdb_rows(&mut k, &[&m[0], &m[1], &m[2]], &dm, dw);
        let b = &rows.kap;
        add_btdb_rows(&mut k, &[&b[0], &b[1], &b[2]], &db, dw);
        if ds > 0.0 {
            for [g13, g23] in &rows.shear {
                add_outer(&mut k, nd, g13, &all, 0.5 * ds * dw);
                add_outer(&mut k, nd, g23, &all, 0.5 * ds * dw);
            }
        }
        if gd > 0.0 {
            add_outer(&mut k, nd, &rows.drill, &all, gd * dw);
        }
    }
    symmetrize(&mut k, nd);
    Ok(k)
}

/// Mass (6N×6N, module doc) of the lamina `l` by `rule`; lumped by HRZ.
pub(crate) fn mass(
    l: &Lamina,
    rule: &[([f64; 2], f64)],
    props: &ShellProps,
    lumped: bool,
) -> Result<Vec<f64>, ElementError> {
    let nn = l.x.len();
    let nd = 6 * nn;
    let rotary = !lumped || props.lumped_rotary;
    // scalar ∫ m_t N_a N_b dA, ∫ m_r N_a N_b dA and the normals of the rotary part
    let mut st = vec![0.0; nn * nn];
    let mut m = vec![0.0; nd * nd];
    let mut sr = vec![0.0; nn * nn];
    for (ip, &([r, s], w)) in rule.iter().enumerate() {
        let (n, dn) = (l.shape)(r, s);
        let (gr, gs) = tangents(l.x, &dn);
        let (e, da) = lamina_frame(gr, gs);
        if da.is_nan() || da <= 0.0 {
            return Err(ElementError::NonPositiveJacobian { det: da, point: ip });
        }
        let t: f64 = n.iter().zip(l.t).map(|(a, b)| a * b).sum();
        let p = ShellProps { t, ..*props };
        let (mt, mr) = (p.mass_per_area(), p.rotary_per_area());
        for a in 0..nn {
            for b in 0..nn {
                let v = n[a] * n[b] * da * w;
                st[a * nn + b] += mt * v;
                sr[a * nn + b] += mr * v;
                if !lumped && rotary {
                    for i in 0..3 {
                        for j in 0..3 {
                            let d = if i == j { 1.0 } else { 0.0 };
                            m[(6 * a + 3 + i) * nd + 6 * b + 3 + j] +=
                                mr * v * (d - (1.0 - DRILL_INERTIA) * e[2][i] * e[2][j]);
                        }
                    }
                }
            }
        }
    }
    if lumped {
        let (mt, mr) = (
            super::super::mass::hrz(&st, nn),
            super::super::mass::hrz(&sr, nn),
        );
        for a in 0..nn {
            let va = l.v[a];
            for i in 0..3 {
                m[(6 * a + i) * nd + 6 * a + i] = mt[a];
                if rotary {
                    for j in 0..3 {
                        let d = if i == j { 1.0 } else { 0.0 };
                        m[(6 * a + 3 + i) * nd + 6 * a + 3 + j] =
                            mr[a] * (d - (1.0 - DRILL_INERTIA) * va[i] * va[j]);
                    }
                }
            }
        }
    } else {
        for a in 0..nn {
            for b in 0..nn {
                for i in 0..3 {
                    m[(6 * a + i) * nd + 6 * b + i] = st[a * nn + b];
                }
            }
        }
    }
    Ok(m)
}

/// Mid-surface area ∫ |g_r × g_s| dr ds by `rule`.
pub(crate) fn area(l: &Lamina, rule: &[([f64; 2], f64)]) -> Result<f64, ElementError> {
    let mut a = 0.0;
    for (ip, &([r, s], w)) in rule.iter().enumerate() {
        let (_, dn) = (l.shape)(r, s);
        let (gr, gs) = tangents(l.x, &dn);
        let da = norm(cross(gr, gs));
        if da.is_nan() || da <= 0.0 {
            return Err(ElementError::NonPositiveJacobian { det: da, point: ip });
        }
        a += da * w;
    }
    Ok(a)
}

#[cfg(test)]
pub(crate) mod test_util {
    use super::*;

    /// Partition of unity, derivatives against central differences, Kronecker property.
    pub fn check_shape2(shape: Shape, nodes: &[[f64; 2]]) {
        for p in [[0.1, 0.2], [-0.3, 0.15], [0.2, 0.05]] {
            let (n, dn) = shape(p[0], p[1]);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            let h = 1e-6;
            let (np, _) = shape(p[0] + h, p[1]);
            let (nm, _) = shape(p[0] - h, p[1]);
            let (sp, _) = shape(p[0], p[1] + h);
            let (sm, _) = shape(p[0], p[1] - h);
            for a in 0..n.len() {
                assert!(
                    (dn[a][0] - (np[a] - nm[a]) / (2.0 * h)).abs() < 1e-8,
                    "{a} r"
                );
                assert!(
                    (dn[a][1] - (sp[a] - sm[a]) / (2.0 * h)).abs() < 1e-8,
                    "{a} s"
                );
            }
        }
        for (b, p) in nodes.iter().enumerate() {
            let (n, _) = shape(p[0], p[1]);
            for (a, v) in n.iter().enumerate() {
                assert!(
                    (v - f64::from(u8::from(a == b))).abs() < 1e-14,
                    "N{a} at {b}"
                );
            }
        }
    }

    /// Number of eigenvalues of the dense symmetric `k` below 1e-10 of its largest.
    pub fn zero_modes(k: &[f64]) -> usize {
        let n = (k.len() as f64).sqrt().round() as usize;
        let mat = faer::Mat::<f64>::from_fn(n, n, |i, j| k[i * n + j]);
        let ev = mat.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
        let top = ev.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        ev.iter().filter(|v| v.abs() < 1e-10 * top).count()
    }

    /// Σ of the x-translation block = area × (ρt + nsm); a flat element in the x–y plane.
    pub fn mass_totals(m: &[f64], a: f64, props: &ShellProps) {
        let nd = (m.len() as f64).sqrt().round() as usize;
        let nn = nd / 6;
        let tx: f64 = (0..nn)
            .flat_map(|i| (0..nn).map(move |j| (i, j)))
            .map(|(i, j)| m[6 * i * nd + 6 * j])
            .sum();
        let want = a * props.mass_per_area();
        assert!((tx - want).abs() < 1e-12 * want, "{tx} vs {want}");
        let rx: f64 = (0..nn)
            .flat_map(|i| (0..nn).map(move |j| (i, j)))
            .map(|(i, j)| m[(6 * i + 3) * nd + 6 * j + 3])
            .sum();
        let want = a * props.rotary_per_area();
        assert!((rx - want).abs() < 1e-12 * want, "{rx} vs {want}");
    }
}
