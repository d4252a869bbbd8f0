//! Initial stress and geometric stiffness of the solid elements (tet4, tet10, hex8 with or
//! without incompatible modes, hex20, hex20R, prism6 with or without incompatible modes), at the
//! integration points of each element's stiffness.
//!
//! * Stress: σ = D (ε − αΔT I), ε = sym ∇u, isotropic Hooke σ = λ tr ε I + 2μ ε − (3λ + 2μ) αΔT I
//!   (αΔT interpolated from the nodes with the shape functions).
//! * Geometric stiffness: K_G,ai,bj = δ_ij ∫ ∇N_a · σ ∇N_b dV, the second variation of
//!   ∫ σ : E(u) dV with the Green–Lagrange strain E = ½(∇u + ∇uᵀ + ∇uᵀ∇u) (Bathe, *Finite
//!   Element Procedures* (1996) §6.3.3, eq. 6.62 with the initial Cauchy stress; Cook, Malkus,
//!   Plesha & Witt, *Concepts and Applications of FEA*, 4th ed. (2002) §18.3).
//! * Thermal load: f = ∫ Bᵀ D ε_th dV, ε_th = αΔT (1 1 1 0 0 0).
//! * Incompatible modes (elements::solid_incompatible): the modes' amplitudes follow the nodal
//!   displacements as the static condensation recovers them, α = R u + K_ii⁻¹ f_i,th with
//!   R = −K_ii⁻¹ K_ic; the stress uses the enhanced gradient, and K_G is the condensed
//!   linearization Lᵀ K_G,full L, L = [I; R] (the first-order change of
//!   (K + K_G)_cc − (K + K_G)_ci (K + K_G)_ii⁻¹ (K + K_G)_ic in σ).

use crate::fe::elements::element::{integration_points, SolidRules};
use crate::fe::elements::solid_incompatible::{full_stiffness, solve_modes, ModePoint};
use crate::fe::elements::{hex20, kinds, ElementError, Isotropic, Xyz};
use crate::fe::quadrature::QuadPoint;
use crate::model::ElementKind;

/// Symmetric stress (or strain) components `[xx yy zz xy yz zx]`.
pub type Stress = [f64; 6];

/// A solid element prepared for initial-stress work: its integration points and, with
/// incompatible modes, the recovery of their amplitudes.
#[derive(Debug, Clone)]
pub struct SolidElement {
    nodes: usize,
    points: Vec<ModePoint>,
    mat: Isotropic,
    /// With incompatible modes: the uncondensed stiffness ((3N + ni)²) and R = −K_ii⁻¹ K_ic
    /// (ni × 3N, row-major).
    modes: Option<(Vec<f64>, Vec<f64>)>,
}

impl SolidElement {
    /// The element of `kind` through the points `x` (model node order), with incompatible modes
    /// for hex8 and prism6 when `incompatible` (Nastran CHEXA/CPENTA,
    /// `ModelParams::solid_bubbles`).
    pub fn new(
        kind: ElementKind,
        x: &[Xyz],
        mat: Isotropic,
        incompatible: bool,
    ) -> Result<SolidElement, ElementError> {
        let rules = SolidRules {
            incompatible,
            ..SolidRules::default()
        };
        SolidElement::with_rules(kind, x, mat, rules)
    }

    /// [`SolidElement::new`] with the model's integration rules ([`SolidRules::of`]: CalculiX's
    /// C3D6 on two points, ANSYS's SOLID186 full integration on 14, as their stiffness).
    pub fn with_rules(
        kind: ElementKind,
        x: &[Xyz],
        mat: Isotropic,
        rules: SolidRules,
    ) -> Result<SolidElement, ElementError> {
        if x.len() != kind.node_count() {
            return Err(ElementError::BadConstants(format!(
                "{kind:?} needs {} nodes, got {}",
                kind.node_count(),
                x.len()
            )));
        }
        let bubbles = rules.incompatible && matches!(kind, ElementKind::Hex8 | ElementKind::Prism6);
        let Some(points) = kinds::element(kind).stiffness_points(x, rules)? else {
            return Err(ElementError::BadConstants(if kind == ElementKind::Hex8R {
                "C3D8R (one-point hexahedron with hourglass control) has no preload (initial \
                 stress) formulation: mesh the preloaded part with C3D8, C3D8I or C3D20R"
                    .into()
            } else {
                format!("{kind:?} has no solid formulation")
            }));
        };
        let nodes = x.len();
        let modes = if bubbles {
            let k = full_stiffness(&points, &mat);
            let (nc, nt) = (3 * nodes, 3 * points[0].grads.len());
            let ni = nt - nc;
            let kic: Vec<f64> = (0..ni * nc)
                .map(|r| k[(nc + r / nc) * nt + r % nc])
                .collect();
            let r = solve_modes(&k, nc, ni, kic, nc)?;
            Some((k, r.into_iter().map(|v| -v).collect()))
        } else {
            None
        };
        Ok(SolidElement {
            nodes,
            points,
            mat,
            modes,
        })
    }

    /// A 20-node brick integrated at `rule`: a CalculiX beam expanded into a brick, at its
    /// section's points (`fe::elements::hex20_beam`), as its stiffness.
    pub fn hex20_at(
        x: &[Xyz],
        mat: Isotropic,
        rule: &[QuadPoint],
    ) -> Result<SolidElement, ElementError> {
        if x.len() != 20 {
            return Err(ElementError::BadConstants(format!(
                "a 20-node brick needs 20 nodes, got {}",
                x.len()
            )));
        }
        Ok(SolidElement {
            nodes: 20,
            points: integration_points(x, hex20::shape, rule)?,
            mat,
            modes: None,
        })
    }

    /// The integration points (weight w_q det J, N_a, gradients of the nodal shape functions
    /// followed by the incompatible modes').
    pub fn points(&self) -> &[ModePoint] {
        &self.points
    }

    /// R = −K_ii⁻¹ K_ic (ni × 3N, row-major) of an element with incompatible modes.
    pub fn recovery(&self) -> Option<&[f64]> {
        self.modes.as_ref().map(|(_, r)| r.as_slice())
    }

    /// Incompatible-mode dofs (0 without modes).
    fn mode_dofs(&self) -> usize {
        3 * self.points[0].grads.len() - 3 * self.nodes
    }

    /// ∫ Bᵀ D ε_th dV over the nodal and mode dofs, ε_th = θ (1 1 1 0 0 0) with θ = αΔT
    /// interpolated from the nodal `theta`.
    fn full_thermal_load(&self, theta: &[f64]) -> Vec<f64> {
        let (lam, mu) = self.mat.lame();
        let bulk3 = 3.0 * lam + 2.0 * mu;
        let mut f = vec![0.0; 3 * self.points[0].grads.len()];
        for pt in &self.points {
            let th: f64 = pt.n.iter().zip(theta).map(|(n, t)| n * t).sum();
            for (a, g) in pt.grads.iter().enumerate() {
                for i in 0..3 {
                    f[3 * a + i] += pt.w * bulk3 * th * g[i];
                }
            }
        }
        f
    }

    /// Consistent nodal forces of the thermal strain: f = ∫ Bᵀ D ε_th dV (3N, module doc), the
    /// mode part condensed (f_c + Rᵀ f_i).
    pub fn thermal_load(&self, theta: &[f64]) -> Vec<f64> {
        let full = self.full_thermal_load(theta);
        let nc = 3 * self.nodes;
        let mut f = full[..nc].to_vec();
        if let Some((_, r)) = &self.modes {
            for (m, fi) in full[nc..].iter().enumerate() {
                for j in 0..nc {
                    f[j] += r[m * nc + j] * fi;
                }
            }
        }
        f
    }

    /// The displacement gradient ∂u_i/∂x_j (row-major 3×3) at each integration point for the
    /// element displacements `u` (3N) and nodal αΔT `theta` (which moves the modes).
    pub fn displacement_gradients(
        &self,
        u: &[f64],
        theta: &[f64],
    ) -> Result<Vec<[f64; 9]>, ElementError> {
        let nc = 3 * self.nodes;
        let mut amplitudes = u[..nc].to_vec();
        if let Some((k, r)) = &self.modes {
            let ni = self.mode_dofs();
            let fi = self.full_thermal_load(theta)[nc..].to_vec();
            let th = solve_modes(k, nc, ni, fi, 1)?;
            amplitudes.extend(
                (0..ni).map(|m| th[m] + (0..nc).map(|j| r[m * nc + j] * u[j]).sum::<f64>()),
            );
        }
        Ok(self
            .points
            .iter()
            .map(|pt| {
                let mut h = [0.0; 9];
                for (a, g) in pt.grads.iter().enumerate() {
                    for i in 0..3 {
                        for j in 0..3 {
                            h[3 * i + j] += amplitudes[3 * a + i] * g[j];
                        }
                    }
                }
                h
            })
            .collect())
    }

    /// σ = D(ε − αΔT I) at each integration point (module doc).
    pub fn stresses(&self, u: &[f64], theta: &[f64]) -> Result<Vec<Stress>, ElementError> {
        let (lam, mu) = self.mat.lame();
        let h = self.displacement_gradients(u, theta)?;
        Ok(self
            .points
            .iter()
            .zip(h)
            .map(|(pt, h)| {
                let th: f64 = pt.n.iter().zip(theta).map(|(n, t)| n * t).sum();
                let eps = [
                    h[0],
                    h[4],
                    h[8],
                    0.5 * (h[1] + h[3]),
                    0.5 * (h[5] + h[7]),
                    0.5 * (h[2] + h[6]),
                ];
                let p = lam * (eps[0] + eps[1] + eps[2]) - (3.0 * lam + 2.0 * mu) * th;
                [
                    p + 2.0 * mu * eps[0],
                    p + 2.0 * mu * eps[1],
                    p + 2.0 * mu * eps[2],
                    2.0 * mu * eps[3],
                    2.0 * mu * eps[4],
                    2.0 * mu * eps[5],
                ]
            })
            .collect())
    }

    /// The initial-displacement (large-deformation) stiffness of the static state u₀ (3N × 3N,
    /// row-major): K_L = ∫ B(F)ᵀ D B(F) − B₀ᵀ D B₀ dV₀ with F = I + ∇u₀, the material part of the
    /// total-Lagrangian tangent at u₀ less the linear K (Bathe, *Finite Element Procedures*
    /// (1996) eq. 6.56, B_L = B_L0 + B_L1(u₀)); what CalculiX's perturbation step adds to
    /// K + K_G (ccx e_c3d, "large displacement stiffness"). Not formed for incompatible modes.
    pub fn initial_displacement_stiffness(&self, u: &[f64]) -> Result<Vec<f64>, ElementError> {
        if self.modes.is_some() {
            return Err(ElementError::BadConstants(
                "an element with incompatible modes (C3D8I, CHEXA/CPENTA bubbles) has no \
                 initial-displacement stiffness here: mesh the preloaded part with C3D8, C3D20 \
                 or C3D20R"
                    .into(),
            ));
        }
        let d = isotropic_voigt(&self.mat);
        let h = self.displacement_gradients(u, &vec![0.0; self.nodes])?;
        let n = self.nodes;
        let nc = 3 * n;
        let mut k = vec![0.0; nc * nc];
        let identity = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        for (pt, h) in self.points.iter().zip(h) {
            let f: [f64; 9] = std::array::from_fn(|r| identity[r] + h[r]);
            let b: Vec<[[f64; 3]; 6]> = pt.grads[..n].iter().map(|g| strain_rows(&f, g)).collect();
            let b0: Vec<[[f64; 3]; 6]> = pt.grads[..n]
                .iter()
                .map(|g| strain_rows(&identity, g))
                .collect();
            for a in 0..n {
                let (db, db0) = (mul_voigt(&d, &b[a]), mul_voigt(&d, &b0[a]));
                for c in 0..n {
                    for i in 0..3 {
                        for j in 0..3 {
                            let mut v = 0.0;
                            for r in 0..6 {
                                v += db[r][i] * b[c][r][j] - db0[r][i] * b0[c][r][j];
                            }
                            k[(3 * a + i) * nc + 3 * c + j] += pt.w * v;
                        }
                    }
                }
            }
        }
        Ok(k)
    }

    /// K_G (3N × 3N, row-major, node-major dofs) of the stresses `sigma` at the integration
    /// points (module formula; the incompatible modes condensed as Lᵀ K_G,full L).
    pub fn geometric_stiffness(&self, sigma: &[Stress]) -> Vec<f64> {
        let ns = self.points[0].grads.len();
        // scalar s_ab = Σ_p w ∇N_a·σ∇N_b over nodes and modes; K_G,full = s ⊗ I₃
        let mut s = vec![0.0; ns * ns];
        for (pt, sg) in self.points.iter().zip(sigma) {
            let t = [
                [sg[0], sg[3], sg[5]],
                [sg[3], sg[1], sg[4]],
                [sg[5], sg[4], sg[2]],
            ];
            let tg: Vec<Xyz> = pt
                .grads
                .iter()
                .map(|g| std::array::from_fn(|i| (0..3).map(|j| t[i][j] * g[j]).sum()))
                .collect();
            for a in 0..ns {
                for b in a..ns {
                    let g = pt.grads[a];
                    s[a * ns + b] += pt.w * (g[0] * tg[b][0] + g[1] * tg[b][1] + g[2] * tg[b][2]);
                }
            }
        }
        for a in 0..ns {
            for b in 0..a {
                s[a * ns + b] = s[b * ns + a];
            }
        }
        let (n, nc) = (self.nodes, 3 * self.nodes);
        let mut k = vec![0.0; nc * nc];
        for a in 0..n {
            for b in 0..n {
                for i in 0..3 {
                    k[(3 * a + i) * nc + 3 * b + i] = s[a * ns + b];
                }
            }
        }
        if let Some((_, r)) = &self.modes {
            let ni = self.mode_dofs();
            // K_G,full entry between full dofs p and q (node-major, modes after the nodes)
            let full = |p: usize, q: usize| {
                if p % 3 == q % 3 {
                    s[(p / 3) * ns + q / 3]
                } else {
                    0.0
                }
            };
            // K_G,ci R + (K_G,ci R)ᵀ + Rᵀ K_G,ii R
            let mut cr = vec![0.0; nc * nc];
            for i in 0..nc {
                for j in 0..nc {
                    cr[i * nc + j] = (0..ni).map(|m| full(i, nc + m) * r[m * nc + j]).sum();
                }
            }
            let mut ir = vec![0.0; ni * nc];
            for m in 0..ni {
                for j in 0..nc {
                    ir[m * nc + j] = (0..ni).map(|l| full(nc + m, nc + l) * r[l * nc + j]).sum();
                }
            }
            for i in 0..nc {
                for j in 0..nc {
                    let rir: f64 = (0..ni).map(|m| r[m * nc + i] * ir[m * nc + j]).sum();
                    k[i * nc + j] += cr[i * nc + j] + cr[j * nc + i] + rir;
                }
            }
        }
        k
    }
}

/// Isotropic D (6×6, Voigt `[xx yy zz xy yz zx]`, engineering shear strains).
fn isotropic_voigt(mat: &Isotropic) -> [[f64; 6]; 6] {
    let (lam, mu) = mat.lame();
    let mut d = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            d[i][j] = lam;
        }
        d[i][i] = lam + 2.0 * mu;
        d[i + 3][i + 3] = mu;
    }
    d
}

/// The Green–Lagrange strain variation δE (Voigt, engineering shear) of a unit displacement of
/// one node in each direction i: δE_kl = ½(F_ik ∂_l N + F_il ∂_k N) (rows xx yy zz xy yz zx,
/// columns i; `f` row-major F_ik, `g` = ∇N in the reference frame).
fn strain_rows(f: &[f64; 9], g: &Xyz) -> [[f64; 3]; 6] {
    std::array::from_fn(|r| {
        std::array::from_fn(|i| {
            let fi = |k: usize| f[3 * i + k];
            match r {
                0 => fi(0) * g[0],
                1 => fi(1) * g[1],
                2 => fi(2) * g[2],
                3 => fi(0) * g[1] + fi(1) * g[0],
                4 => fi(1) * g[2] + fi(2) * g[1],
                _ => fi(2) * g[0] + fi(0) * g[2],
            }
        })
    })
}

/// D·B for a 6×3 B.
fn mul_voigt(d: &[[f64; 6]; 6], b: &[[f64; 3]; 6]) -> [[f64; 3]; 6] {
    std::array::from_fn(|r| std::array::from_fn(|i| (0..6).map(|s| d[r][s] * b[s][i]).sum()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::hex8;

    /// A constant uniaxial stress σ on any element: K_G gives vᵀK_Gv = σ V |∂v/∂x|² for a
    /// linear field v (closed form), and a free thermal expansion is stress free.
    #[test]
    fn solid_kg_linear_field_and_free_expansion() {
        let mat = Isotropic::new(200e9, 0.3, 7800.0);
        let x: Vec<Xyz> = hex8::NODES
            .iter()
            .map(|r| {
                [
                    1.0 + 0.6 * r[0] + 0.05 * r[1],
                    0.4 * r[1],
                    0.3 * r[2] + 0.02 * r[0],
                ]
            })
            .collect();
        for bubbles in [false, true] {
            let el = SolidElement::new(ElementKind::Hex8, &x, mat, bubbles).unwrap();
            let theta = [1e-3; 8];
            let u: Vec<f64> = x.iter().flat_map(|p| p.map(|c| 1e-3 * c)).collect();
            for s in el.stresses(&u, &theta).unwrap() {
                assert!(s.iter().all(|v| v.abs() < 1e-6 * mat.e * 1e-3), "{s:?}");
            }
            let v_ol: f64 = el.points().iter().map(|p| p.w).sum();
            let sig = vec![[5e6, 0.0, 0.0, 0.0, 0.0, 0.0]; el.points().len()];
            let k = el.geometric_stiffness(&sig);
            // v = (0, 0.01 x, −0.02 x): ∂v/∂x = (0, 0.01, −0.02)
            let v: Vec<f64> = x
                .iter()
                .flat_map(|p| [0.0, 0.01 * p[0], -0.02 * p[0]])
                .collect();
            let e: f64 = (0..24)
                .map(|i| v[i] * (0..24).map(|j| k[i * 24 + j] * v[j]).sum::<f64>())
                .sum();
            let want = 5e6 * v_ol * (0.01f64.powi(2) + 0.02f64.powi(2));
            assert!((e - want).abs() < 1e-10 * want, "{bubbles}: {e} vs {want}");
        }
    }
}
