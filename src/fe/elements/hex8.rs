//! 8-node trilinear hexahedron (C3D8, CHEXA 8), full 2×2×2 Gauss integration for K and M as
//! CalculiX C3D8 (not the reduced C3D8R or incompatible-mode C3D8I).
//!
//! ```text
//!        8-------7        reference node a at (ξ_a, η_a, ζ_a) ∈ {−1, 1}³:
//!       /|      /|        1 (−,−,−) 2 (+,−,−) 3 (+,+,−) 4 (−,+,−), 5–8 the same at ζ = +1
//!      5-------6 |        N_a = (1 + ξ ξ_a)(1 + η η_a)(1 + ζ ζ_a) / 8
//!      | 4-----|-3        (Zienkiewicz & Taylor, The Finite Element Method Vol. 1 §8.7)
//!      |/      |/
//!      1-------2
//! ```

use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Reference coordinates of the 8 nodes.
pub const NODES: [Xyz; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// Trilinear shape functions and reference gradients.
pub fn shape(p: &Xyz) -> ([f64; 8], [Xyz; 8]) {
    let mut n = [0.0; 8];
    let mut dn = [[0.0; 3]; 8];
    for (a, r) in NODES.iter().enumerate() {
        let f = [1.0 + p[0] * r[0], 1.0 + p[1] * r[1], 1.0 + p[2] * r[2]];
        n[a] = 0.125 * f[0] * f[1] * f[2];
        dn[a] = [
            0.125 * r[0] * f[1] * f[2],
            0.125 * f[0] * r[1] * f[2],
            0.125 * f[0] * f[1] * r[2],
        ];
    }
    (n, dn)
}

/// Stiffness 24×24, 2×2×2 Gauss.
pub fn stiffness(x: &[Xyz; 8], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::cube(2), mat)
}

/// Scalar consistent mass 8×8, 2×2×2 Gauss.
pub fn scalar_mass(x: &[Xyz; 8], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::cube(2), rho)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex8_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(shape, &NODES, &[[0.1, -0.2, 0.3], [0.0; 3]]);
    }
}
