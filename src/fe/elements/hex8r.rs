//! CalculiX's C3D8R: the 8-node hexahedron with one-point (uniform-strain) integration and
//! Flanagan–Belytschko hourglass control, as ccx 2.20 forms it for a linear frequency step
//! (Flanagan & Belytschko, "A uniform strain hexahedron and quadrilateral with orthogonal
//! hourglass control", IJNME 17 (1981) 679–706; ccx `shape8hr`, `hgstiffness`, `e_c3d`).
//!
//! * uniform gradients b_a = (1/V) ∫ ∇N_a dV (FB eq. 16; 2×2×2 Gauss integrates the trilinear
//!   element's cofactors exactly), V = ∫ dV;
//! * K = V B̄ᵀ D B̄ (one point) + E·α Γ Γᵀ ⊗ I₃ on each displacement component, with
//!   α = 0.0005·V·Σ_a |b_a|² and the hourglass vectors γ_k = h_k − b_z (z·h_k) over the four
//!   base vectors h_k: ccx's `shape8hr` resets γ before each coordinate's term, so only the z
//!   term of FB's γ_k = h_k − Σ_j b_j (x_j·h_k) stays — reproduced here, since the point is
//!   CalculiX's frequencies (a distorted element differs from FB's by that);
//! * consistent mass: the one-point rule, ρV/64 for every node pair (N_a = 1/8 at the centre);
//!   lumped: its row sums, ρV/8 per node, as C3D8.

use super::element::{
    first, Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients,
    SolidRules,
};
use super::hex8::shape;
use super::{map_point, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// FB's hourglass base vectors h_k over the nodes (ccx's order of the C3D8 nodes).
const HOURGLASS: [[f64; 8]; 4] = [
    [1.0, 1.0, -1.0, -1.0, -1.0, -1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0],
    [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0],
];

/// Volume V and the uniform gradients b_a = (1/V) ∫ ∇N_a dV (FB eq. 16).
pub fn uniform_gradients(x: &[Xyz; 8]) -> Result<(f64, [Xyz; 8]), ElementError> {
    let mut vol = 0.0;
    let mut b = [[0.0; 3]; 8];
    for (p, q) in quadrature::cube(2).iter().enumerate() {
        let (_, g, det) = map_point(x, shape, &q.xi, p)?;
        let w = q.w * det;
        vol += w;
        for a in 0..8 {
            for j in 0..3 {
                b[a][j] += w * g[a][j];
            }
        }
    }
    b.iter_mut().flatten().for_each(|v| *v /= vol);
    Ok((vol, b))
}

/// Stiffness 24×24: one-point uniform strain plus ccx's hourglass stiffness (module doc).
pub fn stiffness(x: &[Xyz; 8], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    super::check_solid_material(mat)?;
    let (vol, b) = uniform_gradients(x)?;
    let (lam, mu) = mat.lame();
    let mut k = vec![0.0; 24 * 24];
    let (lw, mw) = (lam * vol, mu * vol);
    // hourglass: α = 0.0005 Σ (V b)² / V, γ_k = h_k − b_z (z · h_k)
    let alpha = 0.0005 * vol * b.iter().flatten().map(|v| v * v).sum::<f64>();
    let mut gamma = [[0.0; 4]; 8];
    for (k_, h) in HOURGLASS.iter().enumerate() {
        let zh: f64 = (0..8).map(|l| x[l][2] * h[l]).sum();
        for a in 0..8 {
            gamma[a][k_] = h[a] - b[a][2] * zh;
        }
    }
    for a in 0..8 {
        for c in 0..8 {
            let dot = mw * (b[a][0] * b[c][0] + b[a][1] * b[c][1] + b[a][2] * b[c][2]);
            let hg = mat.e * alpha * (0..4).map(|m| gamma[a][m] * gamma[c][m]).sum::<f64>();
            for i in 0..3 {
                let row = (3 * a + i) * 24 + 3 * c;
                for j in 0..3 {
                    let mut v = lw * b[a][i] * b[c][j] + mw * b[a][j] * b[c][i];
                    if i == j {
                        v += dot + hg;
                    }
                    k[row + j] += v;
                }
            }
        }
    }
    Ok(k)
}

/// Scalar consistent mass 8×8 of the one-point rule: ρV/64 for every node pair.
pub fn scalar_mass(x: &[Xyz; 8], rho: f64) -> Result<Vec<f64>, ElementError> {
    let (vol, _) = uniform_gradients(x)?;
    Ok(vec![rho * vol / 64.0; 64])
}

/// The one-point hexahedron with hourglass control (C3D8R) as an [`Element`].
pub struct Hex8rElement;

impl Element for Hex8rElement {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<8>();
        let k = input.stiffness(|| stiffness(&x, &input.iso))?;
        let ms = scalar_mass(&x, input.iso.rho)?;
        Ok(input.solid(k, ms, 8, false))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        // its hourglass control is isotropic: no general-material or initial-stress form
        let _ = x;
        Ok(None)
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        // one-point integration: the uniform strain at every node, as ccx's C3D8R stress
        let (_, b) = uniform_gradients(&first(x))?;
        Ok(Some((vec![b.to_vec(); 8], 0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sheared, tapered hexahedron.
    const X: [Xyz; 8] = [
        [0.0, 0.0, 0.0],
        [2.0, 0.1, 0.0],
        [2.2, 1.1, 0.1],
        [0.1, 1.0, 0.0],
        [0.0, 0.1, 1.5],
        [2.1, 0.0, 1.4],
        [2.0, 1.2, 1.6],
        [0.2, 1.0, 1.5],
    ];

    #[test]
    fn uniform_gradients_reproduce_linear_fields_and_the_volume() {
        let (vol, b) = uniform_gradients(&X).unwrap();
        let (v8, _) = (
            super::super::solid_volume(&X, shape, &quadrature::cube(3)).unwrap(),
            0,
        );
        assert!((vol - v8).abs() < 1e-12 * v8);
        // Σ_a b_a x_a,j = δ_ij (a linear field's gradient is exact), Σ_a b_a = 0
        for i in 0..3 {
            for j in 0..3 {
                let s: f64 = (0..8).map(|a| b[a][i] * X[a][j]).sum();
                assert!(
                    (s - f64::from(u8::from(i == j))).abs() < 1e-12,
                    "{i}{j}: {s}"
                );
            }
            assert!((0..8).map(|a| b[a][i]).sum::<f64>().abs() < 1e-12);
        }
    }

    #[test]
    fn rigid_motions_have_no_energy_on_a_box() {
        // on a box, x·h_k = y·h_k = 0 for every base vector: ccx's γ is FB's, orthogonal to
        // the linear fields, so rigid motions and uniform strains carry no hourglass energy
        let x: [Xyz; 8] = std::array::from_fn(|a| {
            let r = super::super::hex8::NODES[a];
            [1.0 + r[0], 0.5 * (1.0 + r[1]), 0.25 * (1.0 + r[2])]
        });
        let k = stiffness(&x, &Isotropic::new(2.1e11, 0.3, 7800.0)).unwrap();
        for mode in 0..6 {
            let u: Vec<f64> = (0..24)
                .map(|d| {
                    let (a, c) = (d / 3, d % 3);
                    if mode < 3 {
                        f64::from(u8::from(c == mode))
                    } else {
                        // θ × x, θ = e_(mode−3)
                        let t = mode - 3;
                        let p = x[a];
                        let cross = [[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]];
                        cross[t][c]
                    }
                })
                .collect();
            let f: f64 = (0..24)
                .map(|r| (0..24).map(|c| k[r * 24 + c] * u[c]).sum::<f64>().abs())
                .fold(0.0, f64::max);
            assert!(f < 1e-12 * 2.1e11, "mode {mode}: {f}");
        }
    }
}
