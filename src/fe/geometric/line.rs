//! Axial force and geometric stiffness of the line elements (beams, rods).
//!
//! * Axial force: N = EA ((u₂ − u₁)·e_x / L − αΔT), αΔT the mean of the two nodes'.
//! * Beam (Przemieniecki, *Theory of Matrix Structural Analysis* (1968) §15.3, eq. 15.48 for the
//!   Euler–Bernoulli beam-column): per bending plane K_G = N ∫₀ᴸ N_i′ N_j′ dx over the deflection
//!   shape functions of the element's stiffness — the cubic Hermite functions for Euler–Bernoulli
//!   (N/(30L)·[36 3L −36 3L; 3L 4L² −3L −L²; …]), and for a Timoshenko beam the interdependent
//!   interpolation with Φ = 12EI/(kGAL²) (Friedman & Kosmatka, *Comput. Struct.* 47 (1993) 473),
//!   N₁ = (2ξ³ − 3ξ² − Φξ + 1 + Φ)/(1 + Φ), N₂ = L(ξ³ − (2 + Φ/2)ξ² + (1 + Φ/2)ξ)/(1 + Φ),
//!   N₃ = (−2ξ³ + 3ξ² + Φξ)/(1 + Φ), N₄ = L(ξ³ − (1 − Φ/2)ξ² − (Φ/2)ξ)/(1 + Φ), integrated by
//!   3-point Gauss (exact). With them, as the second variation of ∫ N ε dx with the
//!   Green–Lagrange axial strain of the section's points ε = u′ + ½(u′² + v′² + w′²) +
//!   ½ (y² + z²) θₓ′² (so that beams agree with the solids' ∫ σ : E dV, SPEC §5.16; McGuire,
//!   Gallagher & Ziemian, *Matrix Structural Analysis*, 2nd ed. (2000) eq. 9.19): the axial
//!   term N/L [1 −1; −1 1] on u and the torsional (Wagner) term N I_p/(A L) [1 −1; −1 1] on the
//!   twist θₓ, I_p = I_y + I_z the polar moment of area about the centroid (the shear centre of
//!   a doubly symmetric section; N I_p/A is the torsional buckling load's P r₀² of Timoshenko
//!   & Gere, *Theory of Elastic Stability* (1961) §5.3, without warping). No bending-moment
//!   coupling (the element's moments are not in the terms).
//! * Rod: K_G = N/L I ⊗ [1 −1; −1 1] on the translations (the string N/L (I − e eᵀ) of Cook,
//!   Malkus, Plesha & Witt, *Concepts and Applications of FEA*, 4th ed. (2002) §18.2, with the
//!   axial term N/L e eᵀ of the same Green–Lagrange strain).
//! * Thermal load: ±EA αΔT e_x at the two nodes.

use crate::fe::elements::beam::{local_frame, shear_parameters, to_basic, BeamProps};
use crate::fe::elements::{ElementError, Isotropic, Xyz};
use crate::fe::quadrature::gauss_legendre;

/// Axial force N = EA((u₂ − u₁)·e_x/L − αΔT) of a line element through `x` with basic-frame
/// displacements `u` (6 per node) and nodal αΔT `theta` (module doc).
pub fn axial_force(
    x: &[Xyz; 2],
    ea: f64,
    u: &[f64],
    theta: &[f64; 2],
) -> Result<f64, ElementError> {
    let ([ex, _, _], l) = local_frame(x, None)?;
    let du: f64 = (0..3).map(|i| ex[i] * (u[6 + i] - u[i])).sum();
    Ok(ea * (du / l - 0.5 * (theta[0] + theta[1])))
}

/// Consistent nodal forces (12, basic frame) of the thermal strain of a line element.
pub fn thermal_load(x: &[Xyz; 2], ea: f64, theta: &[f64; 2]) -> Result<Vec<f64>, ElementError> {
    let ([ex, _, _], _) = local_frame(x, None)?;
    let p = ea * 0.5 * (theta[0] + theta[1]);
    let mut f = vec![0.0; 12];
    for i in 0..3 {
        f[i] = -p * ex[i];
        f[6 + i] = p * ex[i];
    }
    Ok(f)
}

/// ∫₀ᴸ N_i′ N_j′ dx of the deflection shape functions on [w₁ θ₁ w₂ θ₂] (θ = w′) with shear
/// parameter Φ (module doc; Φ = 0: the cubic Hermite functions).
pub fn slope_products(l: f64, phi: f64) -> [[f64; 4]; 4] {
    let c = 1.0 / (1.0 + phi);
    // dN_i/dξ; dN/dx = (dN/dξ)/L
    let d = |xi: f64| -> [f64; 4] {
        [
            c * (6.0 * xi * xi - 6.0 * xi - phi),
            c * l * (3.0 * xi * xi - (4.0 + phi) * xi + 1.0 + 0.5 * phi),
            c * (-6.0 * xi * xi + 6.0 * xi + phi),
            c * l * (3.0 * xi * xi - (2.0 - phi) * xi - 0.5 * phi),
        ]
    };
    let mut s = [[0.0; 4]; 4];
    for &(g, w) in gauss_legendre(3) {
        let xi = 0.5 * (g + 1.0);
        let dn = d(xi);
        for i in 0..4 {
            for j in 0..4 {
                // dx = L/2 dg, N′ = dN/dξ / L
                s[i][j] += 0.5 * w * dn[i] * dn[j] / l;
            }
        }
    }
    s
}

/// Basic-frame K_G (12×12) of a beam with axial force `n` (module formula): local bending
/// planes x–y (v, θz; θz = v′) and x–z (w, θy; θy = −w′), then rotated like K.
pub fn beam_geometric_stiffness(
    x: &[Xyz; 2],
    v: Option<Xyz>,
    mat: &Isotropic,
    p: &BeamProps,
    n: f64,
) -> Result<Vec<f64>, ElementError> {
    let v = v.ok_or(ElementError::BadOrientation { v: [0.0; 3] })?;
    let (r, l) = local_frame(x, Some(v))?;
    let (phy, phz) = shear_parameters(l, mat, p);
    let mut k = [[0.0; 12]; 12];
    // axial u and twist θx (module doc): N/L and N I_p/(A L) times [1 −1; −1 1]
    let torsion = if p.area > 0.0 {
        (p.iy + p.iz) / p.area
    } else {
        0.0
    };
    for (dof, c) in [(0, n / l), (3, n * torsion / l)] {
        k[dof][dof] += c;
        k[dof + 6][dof + 6] += c;
        k[dof][dof + 6] -= c;
        k[dof + 6][dof] -= c;
    }
    for (dofs, ph, s) in [([1, 5, 7, 11], phy, 1.0), ([2, 4, 8, 10], phz, -1.0)] {
        let m = slope_products(l, ph);
        // rotation dofs carry the sign s of θ = s·w′
        let sign = [1.0, s, 1.0, s];
        for a in 0..4 {
            for b in 0..4 {
                k[dofs[a]][dofs[b]] += n * sign[a] * sign[b] * m[a][b];
            }
        }
    }
    Ok(to_basic(&k, &r))
}

/// Basic-frame K_G (12×12, 6 dofs per node) of a rod with axial force `n`: N/L I on the
/// translations (module formula).
pub fn rod_geometric_stiffness(x: &[Xyz; 2], n: f64) -> Result<Vec<f64>, ElementError> {
    let (_, l) = local_frame(x, None)?;
    let mut k = vec![0.0; 144];
    for (a, b, sign) in [(0, 0, 1.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 1.0)] {
        for i in 0..3 {
            k[(6 * a + i) * 12 + 6 * b + i] = sign * n / l;
        }
    }
    Ok(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Φ = 0 gives Przemieniecki's N/(30L)·[36 3L −36 3L; 3L 4L² −3L −L²; …].
    #[test]
    fn beam_slope_products_euler_bernoulli_closed_form() {
        let l = 0.7;
        let s = slope_products(l, 0.0);
        let want = [
            [36.0, 3.0 * l, -36.0, 3.0 * l],
            [3.0 * l, 4.0 * l * l, -3.0 * l, -l * l],
            [-36.0, -3.0 * l, 36.0, -3.0 * l],
            [3.0 * l, -l * l, -3.0 * l, 4.0 * l * l],
        ];
        for i in 0..4 {
            for j in 0..4 {
                let w = want[i][j] / (30.0 * l);
                assert!((s[i][j] - w).abs() < 1e-14, "{i}{j}: {} vs {w}", s[i][j]);
            }
        }
        // any Φ: a rigid translation and a rigid rotation (w = x, θ = 1) have the slopes 0, 1
        for phi in [0.0, 0.3, 2.0] {
            let s = slope_products(l, phi);
            let rot = [0.0, 1.0, l, 1.0];
            let e: f64 = (0..4)
                .map(|i| rot[i] * (0..4).map(|j| s[i][j] * rot[j]).sum::<f64>())
                .sum();
            assert!((e - l).abs() < 1e-14, "{phi}: {e}");
            let tr: f64 = (0..4).map(|j| s[0][j] + s[2][j]).sum();
            assert!(tr.abs() < 1e-13);
        }
    }
}
