//! Element library: stiffness and mass matrices of single elements as pure functions of the
//! node coordinates (basic frame) and the material.
//!
//! Solid elements share the isoparametric kernels below; each element file supplies its shape
//! functions, reference nodes and integration rules. Matrices are dense, row-major, with the dofs
//! node-major (`[u1x u1y u1z u2x …]` for solids, `[ux uy uz rx ry rz]` per node for beams and
//! shells; the shells' shared parts are in [`shell`]).
//!
//! Isotropic linear elasticity in index form (Hughes, *The Finite Element Method* (1987) §2.7):
//! K_{ai,bj} = ∫ λ ∂_i N_a ∂_j N_b + μ ∂_j N_a ∂_i N_b + μ δ_ij ∇N_a·∇N_b dV, λ = Eν/((1+ν)(1−2ν)),
//! μ = E/(2(1+ν)); consistent mass M_{ai,bj} = δ_ij ∫ ρ N_a N_b dV.

pub mod anisotropic;
pub mod beam;
pub mod beam188;
pub mod beam189;
pub mod beam_element;
pub mod curved_shell;
pub mod dense;
pub mod drill_membrane;
pub mod element;
pub mod hex20;
pub mod hex20_beam;
pub mod hex8;
pub mod hex8_bbar;
pub mod hex8r;
pub mod kinds;
pub mod planar_frame;
pub mod prism15;
pub mod prism6;
pub mod pyram13;
pub mod pyram13_ansys;
pub mod pyram5;
pub mod quad4_shell;
pub mod quad8_shell;
pub mod rod;
pub mod shell;
pub mod shell281;
pub mod solid_incompatible;
pub mod tapered_beam;
pub mod tet10;
pub mod tet4;
pub mod tri3_shell;
pub mod tri6_shell;

use super::quadrature::QuadPoint;
use crate::model::geometry::{det3, inverse3};

/// A point in 3D (basic frame).
pub type Xyz = [f64; 3];

/// Isotropic linear-elastic material constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Isotropic {
    /// Young's modulus E.
    pub e: f64,
    /// Poisson's ratio ν.
    pub nu: f64,
    /// Shear modulus G (E / (2(1+ν)) for a true isotropic material).
    pub g: f64,
    /// Mass density ρ.
    pub rho: f64,
}

impl Isotropic {
    /// From E, ν, ρ with G = E / (2(1+ν)).
    pub fn new(e: f64, nu: f64, rho: f64) -> Isotropic {
        Isotropic {
            e,
            nu,
            g: e / (2.0 * (1.0 + nu)),
            rho,
        }
    }

    /// Lamé constants (λ, μ) of the solid: λ = Eν/((1+ν)(1−2ν)), μ = E/(2(1+ν)).
    pub fn lame(&self) -> (f64, f64) {
        let l = self.e * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu));
        (l, self.e / (2.0 * (1.0 + self.nu)))
    }
}

/// Why a single element's matrices could not be formed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ElementError {
    /// The isoparametric map folds or collapses (wrong node order or a degenerate element).
    #[error("Jacobian determinant {det:.4e} ≤ 0 at integration point {point} (inverted or degenerate element)")]
    NonPositiveJacobian {
        /// det J at the point.
        det: f64,
        /// 0-based integration point.
        point: usize,
    },
    /// The two nodes of a line element coincide.
    #[error("zero length (both nodes at the same place)")]
    ZeroLength,
    /// A beam's orientation vector is missing, zero or parallel to its axis.
    #[error("orientation vector {v:?} is zero or parallel to the beam axis")]
    BadOrientation {
        /// The vector given.
        v: Xyz,
    },
    /// Non-physical material or section constants.
    #[error("{0}")]
    BadConstants(String),
}

/// Shape functions N_a(ξ) and their reference gradients ∂N_a/∂ξ_k of an N-node solid.
pub type ShapeFn<const N: usize> = fn(&Xyz) -> ([f64; N], [Xyz; N]);

/// Values, physical gradients ∂N_a/∂x_i and det J at one reference point (J_ki = ∂x_i/∂ξ_k).
pub fn map_point<const N: usize>(
    x: &[Xyz; N],
    shape: ShapeFn<N>,
    xi: &Xyz,
    point: usize,
) -> Result<([f64; N], [Xyz; N], f64), ElementError> {
    let (n, dn) = shape(xi);
    let mut j = [[0.0; 3]; 3];
    for a in 0..N {
        for k in 0..3 {
            for i in 0..3 {
                j[k][i] += dn[a][k] * x[a][i];
            }
        }
    }
    let det = det3(&j);
    if det.is_nan() || det <= 0.0 {
        return Err(ElementError::NonPositiveJacobian { det, point });
    }
    let inv = inverse3(&j, det);
    // ∂N/∂x_i = Σ_k (J⁻¹)_ik ∂N/∂ξ_k
    let mut g = [[0.0; 3]; N];
    for a in 0..N {
        for i in 0..3 {
            g[a][i] = inv[i][0] * dn[a][0] + inv[i][1] * dn[a][1] + inv[i][2] * dn[a][2];
        }
    }
    Ok((n, g, det))
}

/// Isotropic solid stiffness (3N×3N, row-major), module formula K_{ai,bj} above.
pub fn solid_stiffness<const N: usize>(
    x: &[Xyz; N],
    shape: ShapeFn<N>,
    rule: &[QuadPoint],
    mat: &Isotropic,
) -> Result<Vec<f64>, ElementError> {
    check_solid_material(mat)?;
    let (lam, mu) = mat.lame();
    let nd = 3 * N;
    let mut k = vec![0.0; nd * nd];
    for (p, q) in rule.iter().enumerate() {
        let (_, g, det) = map_point(x, shape, &q.xi, p)?;
        let w = q.w * det;
        let (lw, mw) = (lam * w, mu * w);
        for a in 0..N {
            for b in a..N {
                let dot = mw * (g[a][0] * g[b][0] + g[a][1] * g[b][1] + g[a][2] * g[b][2]);
                for i in 0..3 {
                    let row = (3 * a + i) * nd + 3 * b;
                    for jj in 0..3 {
                        let mut v = lw * g[a][i] * g[b][jj] + mw * g[a][jj] * g[b][i];
                        if i == jj {
                            v += dot;
                        }
                        k[row + jj] += v;
                    }
                }
            }
        }
    }
    mirror_upper_blocks(&mut k, N, 3);
    Ok(k)
}

/// Scalar consistent mass m_ab = ∫ ρ N_a N_b dV (N×N, row-major); M = m ⊗ I₃.
pub fn solid_scalar_mass<const N: usize>(
    x: &[Xyz; N],
    shape: ShapeFn<N>,
    rule: &[QuadPoint],
    rho: f64,
) -> Result<Vec<f64>, ElementError> {
    let mut m = vec![0.0; N * N];
    for (p, q) in rule.iter().enumerate() {
        let (n, _, det) = map_point(x, shape, &q.xi, p)?;
        let w = rho * q.w * det;
        for a in 0..N {
            for b in 0..N {
                m[a * N + b] += w * n[a] * n[b];
            }
        }
    }
    Ok(m)
}

/// Volume ∫ dV by the given rule.
pub fn solid_volume<const N: usize>(
    x: &[Xyz; N],
    shape: ShapeFn<N>,
    rule: &[QuadPoint],
) -> Result<f64, ElementError> {
    let mut v = 0.0;
    for (p, q) in rule.iter().enumerate() {
        v += q.w * map_point(x, shape, &q.xi, p)?.2;
    }
    Ok(v)
}

/// Expand a scalar N×N mass to the 3N×3N solid mass m ⊗ I₃.
pub fn expand_scalar_mass(ms: &[f64], n: usize) -> Vec<f64> {
    let nd = 3 * n;
    let mut m = vec![0.0; nd * nd];
    for a in 0..n {
        for b in 0..n {
            for i in 0..3 {
                m[(3 * a + i) * nd + 3 * b + i] = ms[a * n + b];
            }
        }
    }
    m
}

/// Copy the upper node blocks (a ≤ b) of a node-major matrix onto the lower ones, transposed.
fn mirror_upper_blocks(k: &mut [f64], n: usize, d: usize) {
    let nd = n * d;
    for a in 0..n {
        for b in 0..a {
            for i in 0..d {
                for j in 0..d {
                    k[(d * a + i) * nd + d * b + j] = k[(d * b + j) * nd + d * a + i];
                }
            }
        }
    }
}

pub(crate) fn check_solid_material(mat: &Isotropic) -> Result<(), ElementError> {
    let ok = mat.e > 0.0
        && mat.e.is_finite()
        && mat.nu > -1.0
        && mat.nu < 0.5
        && mat.rho >= 0.0
        && mat.rho.is_finite();
    if !ok {
        return Err(ElementError::BadConstants(format!(
            "solid needs E > 0, −1 < ν < 0.5 and ρ ≥ 0 (E = {}, ν = {}, ρ = {})",
            mat.e, mat.nu, mat.rho
        )));
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod test_util {
    use super::*;

    /// Partition of unity, gradients summing to zero and gradients matching central
    /// differences of the values, at a few interior points.
    pub fn check_shape<const N: usize>(shape: ShapeFn<N>, nodes: &[Xyz; N], points: &[Xyz]) {
        for p in points {
            let (n, dn) = shape(p);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            for k in 0..3 {
                assert!(dn.iter().map(|d| d[k]).sum::<f64>().abs() < 1e-13);
                let h = 1e-6;
                let (mut pp, mut pm) = (*p, *p);
                pp[k] += h;
                pm[k] -= h;
                let (np, nm) = (shape(&pp).0, shape(&pm).0);
                for a in 0..N {
                    assert!((dn[a][k] - (np[a] - nm[a]) / (2.0 * h)).abs() < 1e-8);
                }
            }
        }
        // Kronecker property at the nodes.
        for (b, x) in nodes.iter().enumerate() {
            let (n, _) = shape(x);
            for (a, v) in n.iter().enumerate() {
                assert!(
                    (v - f64::from(u8::from(a == b))).abs() < 1e-14,
                    "N{a} at node {b}"
                );
            }
        }
    }
    /// The element's nodal gradients of a linear field f = a·x + c are `a` at every node, with
    /// no centroid fallback counted (what nodal stress recovery needs for a constant strain).
    pub fn check_linear_field_gradients(element: &dyn element::Element, x: &[Xyz]) {
        let a = [0.7, -1.3, 2.1];
        let f: Vec<f64> = x
            .iter()
            .map(|p| 0.4 + (0..3).map(|i| a[i] * p[i]).sum::<f64>())
            .collect();
        let (grads, fallbacks) = element
            .nodal_gradients(x)
            .unwrap() // valid element: cannot fail
            .expect("the element recovers nodal gradients");
        assert_eq!(fallbacks, 0);
        assert_eq!(grads.len(), x.len());
        for (node, g) in grads.iter().enumerate() {
            for i in 0..3 {
                let got: f64 = g.iter().zip(&f).map(|(gb, fb)| gb[i] * fb).sum();
                assert!(
                    (got - a[i]).abs() < 1e-12,
                    "node {node} ∂{i}: {got} vs {}",
                    a[i]
                );
            }
        }
    }
}
