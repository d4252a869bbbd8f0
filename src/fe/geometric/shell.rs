//! Membrane initial stress and geometric stiffness of the flat shells (MITC4 quadrilateral with
//! the QM6 membrane, DKT/DKMT triangle with the CST membrane).
//!
//! * Resultants: N = D_m (ε_m − αΔT (1 1 0)) per unit length at the membrane's points (the
//!   quadrilateral's 2×2 Gauss points, its incompatible modes recovered as the condensation
//!   does, α = K_ii⁻¹ (f_i,th − K_ic u); the triangle's constant strain).
//! * Geometric stiffness in the element frame: K_G,ac,bc = ∫ ∇N_a · N ∇N_b dA for each of the
//!   three local translations c = u, v, w — the membrane stress acting on the gradients of the
//!   deflection and of the in-plane displacements (Cook, Malkus, Plesha & Witt, *Concepts and
//!   Applications of FEA*, 4th ed. (2002) §18.5, plates: ∫ [w,x w,y] N [w,x w,y]ᵀ dA; Bathe,
//!   *Finite Element Procedures* (1996) §6.5.2 for the in-plane terms). Interpolation: the
//!   bilinear N_a of the quadrilateral (its own w), the linear area coordinates of the triangle
//!   (the DKT has no interior w; a linear w is the usual choice for its geometric stiffness).
//!   Left out, as for thin shells: the rotations' share t²/12 ∫ ∇β·N∇β dA (of relative size
//!   (t/λ)², λ the wavelength of the mode) and the bending moments' initial stress.
//! * Then the warping links and the rotation to the basic frame, as for K (elements::shell).
//! * Thermal load: f = ∫ B_mᵀ D_m αΔT (1 1 0) dA (mid-surface temperature; no gradient through
//!   the thickness).

use crate::fe::elements::quad4_shell::{membrane_blocks, membrane_points, solve4, MembranePoint};
use crate::fe::elements::shell::{self, ShellFrame, ShellProps};
use crate::fe::elements::tri3_shell::linear;
use crate::fe::elements::{ElementError, Xyz};

/// Membrane resultants `[N_xx N_yy N_xy]` (force per length, element frame).
pub type Resultant = [f64; 3];

/// A flat shell element prepared for initial-stress work.
#[derive(Debug, Clone)]
pub struct ShellElement {
    props: ShellProps,
    axes: [Xyz; 3],
    h: Vec<f64>,
    kind: ShellKind,
}

#[derive(Debug, Clone)]
enum ShellKind {
    /// Gauss points and R = −K_ii⁻¹ K_ic (4×8), K_ii (4×4) of the QM6 membrane.
    Quad {
        points: Vec<MembranePoint>,
        r: Vec<f64>,
        kii: Vec<f64>,
    },
    /// Area and area-coordinate gradients.
    Tri { area: f64, gl: [[f64; 2]; 3] },
}

fn mat_vec(d: &[[f64; 3]; 3], e: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|j| d[i][j] * e[j]).sum())
}

impl ShellElement {
    /// A quadrilateral (4 points) or triangle (3 points) shell with constants `props`.
    pub fn new(x: &[Xyz], props: &ShellProps) -> Result<ShellElement, ElementError> {
        props.check()?;
        let (axes, h, kind) = match x.len() {
            4 => {
                let f = ShellFrame::<4>::new(&std::array::from_fn(|a| x[a]))?;
                let points = membrane_points(&f.p)?;
                let (_, kci, kii) = membrane_blocks(&points, &props.d_membrane());
                let r = if props.membrane.is_some() {
                    solve4(&kii, &kci)?.into_iter().map(|v| -v).collect()
                } else {
                    vec![0.0; 32]
                };
                (f.axes, f.h.to_vec(), ShellKind::Quad { points, r, kii })
            }
            3 => {
                let f = ShellFrame::<3>::new(&std::array::from_fn(|a| x[a]))?;
                let (area, gl) = linear(&f.p);
                if area.is_nan() || area <= 0.0 {
                    return Err(ElementError::NonPositiveJacobian {
                        det: 2.0 * area,
                        point: 0,
                    });
                }
                (f.axes, f.h.to_vec(), ShellKind::Tri { area, gl })
            }
            n => {
                return Err(ElementError::BadConstants(format!(
                    "a flat shell has 3 or 4 nodes, not {n}"
                )))
            }
        };
        Ok(ShellElement {
            props: *props,
            axes,
            h,
            kind,
        })
    }

    fn nodes(&self) -> usize {
        self.h.len()
    }

    /// In-plane displacements of the flat element's nodes from the basic-frame element
    /// displacements (6 per node): rotated to the element frame, then through the warping links
    /// u_f = u − hθy, v_f = v + hθx (elements::shell::apply_warping).
    fn flat_in_plane(&self, u: &[f64]) -> Vec<f64> {
        let r = &self.axes;
        (0..self.nodes())
            .flat_map(|a| {
                let t = &u[6 * a..6 * a + 3];
                let th = &u[6 * a + 3..6 * a + 6];
                let loc = |v: &[f64], i: usize| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2];
                [
                    loc(t, 0) - self.h[a] * loc(th, 1),
                    loc(t, 1) + self.h[a] * loc(th, 0),
                ]
            })
            .collect()
    }

    /// The thermal membrane load on the quadrilateral's mode dofs, f_i = Σ w b_iᵀ D_m ε_th.
    fn mode_thermal_load(points: &[MembranePoint], dm: &[[f64; 3]; 3], theta: &[f64]) -> [f64; 4] {
        let mut fi = [0.0; 4];
        for pt in points {
            let th: f64 = pt.n.iter().zip(theta).map(|(n, t)| n * t).sum();
            let s = mat_vec(dm, [th, th, 0.0]);
            for (m, f) in fi.iter_mut().enumerate() {
                *f += pt.w * (0..3).map(|l| pt.bi[l][m] * s[l]).sum::<f64>();
            }
        }
        fi
    }

    /// Membrane resultants N = D_m(ε_m − αΔT (1 1 0)) at the membrane's points (4 Gauss points
    /// of the quadrilateral, 1 of the triangle), element frame, from the basic-frame element
    /// displacements `u` (6 per node) and the nodal αΔT `theta`.
    pub fn resultants(&self, u: &[f64], theta: &[f64]) -> Result<Vec<Resultant>, ElementError> {
        let dm = self.props.d_membrane();
        let uf = self.flat_in_plane(u);
        match &self.kind {
            ShellKind::Quad { points, r, kii } => {
                // α = R u + K_ii⁻¹ f_i,th (K_ii⁻¹ of one vector through solve4's 8×4 layout)
                let fi = Self::mode_thermal_load(points, &dm, theta);
                let mut rhs = vec![0.0; 32];
                rhs[..4].copy_from_slice(&fi);
                let alpha_th: Vec<f64> = if self.props.membrane.is_some() {
                    let s = solve4(kii, &rhs)?;
                    (0..4).map(|m| s[m * 8]).collect()
                } else {
                    vec![0.0; 4]
                };
                let alpha: Vec<f64> = (0..4)
                    .map(|m| alpha_th[m] + (0..8).map(|j| r[m * 8 + j] * uf[j]).sum::<f64>())
                    .collect();
                Ok(points
                    .iter()
                    .map(|pt| {
                        let th: f64 = pt.n.iter().zip(theta).map(|(n, t)| n * t).sum();
                        let e: [f64; 3] = std::array::from_fn(|l| {
                            (0..8).map(|j| pt.bc[l][j] * uf[j]).sum::<f64>()
                                + (0..4).map(|m| pt.bi[l][m] * alpha[m]).sum::<f64>()
                        });
                        mat_vec(&dm, [e[0] - th, e[1] - th, e[2]])
                    })
                    .collect())
            }
            ShellKind::Tri { gl, .. } => {
                let th = theta.iter().sum::<f64>() / 3.0;
                let mut e = [0.0; 3];
                for a in 0..3 {
                    e[0] += gl[a][0] * uf[2 * a];
                    e[1] += gl[a][1] * uf[2 * a + 1];
                    e[2] += gl[a][1] * uf[2 * a] + gl[a][0] * uf[2 * a + 1];
                }
                Ok(vec![mat_vec(&dm, [e[0] - th, e[1] - th, e[2]])])
            }
        }
    }

    /// K_G (6N × 6N, basic frame, node-major `[u v w θx θy θz]`) of the resultants `n` at the
    /// membrane's points (module formula).
    pub fn geometric_stiffness(&self, n: &[Resultant]) -> Vec<f64> {
        let nn = self.nodes();
        let nd = 6 * nn;
        let mut k = vec![0.0; nd * nd];
        let mut add = |w: f64, g: &[[f64; 2]], res: &Resultant| {
            for a in 0..nn {
                for b in 0..nn {
                    let ga = g[a];
                    let gb = g[b];
                    let v = w
                        * (ga[0] * (res[0] * gb[0] + res[2] * gb[1])
                            + ga[1] * (res[2] * gb[0] + res[1] * gb[1]));
                    for c in 0..3 {
                        k[(6 * a + c) * nd + 6 * b + c] += v;
                    }
                }
            }
        };
        match &self.kind {
            ShellKind::Quad { points, .. } => {
                for (pt, res) in points.iter().zip(n) {
                    add(pt.w, &pt.g, res);
                }
            }
            ShellKind::Tri { area, gl } => {
                if let Some(res) = n.first() {
                    add(*area, gl, res);
                }
            }
        }
        shell::apply_warping(&mut k, &self.h);
        shell::to_basic(&k, nn, &self.axes)
    }

    /// Consistent nodal forces (basic frame, 6 per node) of the membrane thermal strain
    /// αΔT (1 1 0) with the nodal αΔT `theta` (module doc).
    pub fn thermal_load(&self, theta: &[f64]) -> Vec<f64> {
        let nn = self.nodes();
        let dm = self.props.d_membrane();
        // flat in-plane forces [fu1 fv1 fu2 fv2 …]
        let mut ff = vec![0.0; 2 * nn];
        match &self.kind {
            ShellKind::Quad { points, r, .. } => {
                for pt in points {
                    let th: f64 = pt.n.iter().zip(theta).map(|(n, t)| n * t).sum();
                    let s = mat_vec(&dm, [th, th, 0.0]);
                    for (j, f) in ff.iter_mut().enumerate() {
                        *f += pt.w * (0..3).map(|l| pt.bc[l][j] * s[l]).sum::<f64>();
                    }
                }
                // condensed: f_c + Rᵀ f_i
                let fi = Self::mode_thermal_load(points, &dm, theta);
                for (j, f) in ff.iter_mut().enumerate() {
                    *f += (0..4).map(|m| r[m * 8 + j] * fi[m]).sum::<f64>();
                }
            }
            ShellKind::Tri { area, gl } => {
                let th = theta.iter().sum::<f64>() / 3.0;
                let s = mat_vec(&dm, [th, th, 0.0]);
                for a in 0..3 {
                    ff[2 * a] += area * (gl[a][0] * s[0] + gl[a][1] * s[2]);
                    ff[2 * a + 1] += area * (gl[a][1] * s[1] + gl[a][0] * s[2]);
                }
            }
        }
        // through the warping links (Wᵀ f) to the real nodes, then to the basic frame
        let mut local = vec![0.0; 6 * nn];
        for a in 0..nn {
            local[6 * a] = ff[2 * a];
            local[6 * a + 1] = ff[2 * a + 1];
            local[6 * a + 4] = -self.h[a] * ff[2 * a];
            local[6 * a + 3] = self.h[a] * ff[2 * a + 1];
        }
        let r = &self.axes;
        let mut out = vec![0.0; 6 * nn];
        for blk in 0..2 * nn {
            for i in 0..3 {
                out[3 * blk + i] = (0..3).map(|k| r[k][i] * local[3 * blk + k]).sum();
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::Isotropic;

    /// A uniform membrane tension N₁₁ on a distorted quadrilateral and a triangle: the energy
    /// of a deflection w = a x (linear, so every interpolation is exact) is N₁₁ (a e₁ₓ)² A, and a
    /// free thermal expansion is free of resultants.
    #[test]
    fn shell_kg_uniform_tension_and_free_expansion() {
        let props = ShellProps::isotropic(0.01, Isotropic::new(70e9, 0.33, 2700.0));
        let quad = [
            [0.0, 0.0, 0.0],
            [2.0, 0.3, 0.0],
            [2.4, 1.9, 0.0],
            [0.2, 1.2, 0.0],
        ];
        let tri = [[0.1, -0.2, 0.0], [2.0, 0.3, 0.0], [0.7, 1.6, 0.0]];
        for x in [&quad[..], &tri[..]] {
            let el = ShellElement::new(x, &props).unwrap();
            let th = vec![2e-4; x.len()];
            let u: Vec<f64> = x
                .iter()
                .flat_map(|p| [2e-4 * p[0], 2e-4 * p[1], 0.0, 0.0, 0.0, 0.0])
                .collect();
            for r in el.resultants(&u, &th).unwrap() {
                assert!(r.iter().all(|v| v.abs() < 1e-6), "{r:?}");
            }
            let nres = vec![[3e4, 0.0, 0.0]; if x.len() == 4 { 4 } else { 1 }];
            let k = el.geometric_stiffness(&nres);
            let v: Vec<f64> = x
                .iter()
                .flat_map(|p| [0.0, 0.0, 0.05 * p[0], 0.0, -0.05, 0.0])
                .collect();
            let nd = v.len();
            let e: f64 = (0..nd)
                .map(|i| v[i] * (0..nd).map(|j| k[i * nd + j] * v[j]).sum::<f64>())
                .sum();
            let area = match &el.kind {
                ShellKind::Quad { points, .. } => points.iter().map(|p| p.w).sum(),
                ShellKind::Tri { area, .. } => *area,
            };
            // N_11 acts along e₁ of the element frame: ∂w/∂e₁ = 0.05 e₁ₓ
            let want = 3e4 * (0.05 * el.axes[0][0]).powi(2) * area;
            assert!((e - want).abs() < 1e-10 * want, "{e} vs {want}");
        }
    }
}
