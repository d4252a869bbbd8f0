//! 20-node serendipity hexahedron: C3D20 (3×3×3 Gauss) and C3D20R (reduced 2×2×2 Gauss for K).
//!
//! ```text
//!        8----15----7         corners 1–8 as hex8; mid-edge nodes:
//!       /|         /|         9 (0,−,−) 10 (+,0,−) 11 (0,+,−) 12 (−,0,−)      bottom
//!     16 20      14 19        13 (0,−,+) 14 (+,0,+) 15 (0,+,+) 16 (−,0,+)     top
//!     /  |       /  |         17 (−,−,0) 18 (+,−,0) 19 (+,+,0) 20 (−,+,0)     verticals
//!    5----13----6   |
//!    |   4----11|---3         corner: N = (1+ξξ_a)(1+ηη_a)(1+ζζ_a)(ξξ_a+ηη_a+ζζ_a−2)/8
//!   17  /      18  /          mid-edge with ξ_a = 0: N = (1−ξ²)(1+ηη_a)(1+ζζ_a)/4 (and cyclic)
//!    | 12       | 10          (Zienkiewicz & Taylor, The Finite Element Method Vol. 1 §8.7)
//!    |/         |/
//!    1-----9----2
//! ```
//! The consistent mass uses the element's own rule: 3×3×3 for C3D20, 2×2×2 for C3D20R — as
//! CalculiX does (checked on its test case `beamf`, 10 modes to 2e-7). HRZ lumping always takes
//! the diagonal of the full 3×3×3 mass.

use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Reference coordinates of the 20 nodes.
pub const NODES: [Xyz; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, -1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// Serendipity shape functions and reference gradients.
pub fn shape(p: &Xyz) -> ([f64; 20], [Xyz; 20]) {
    let mut n = [0.0; 20];
    let mut dn = [[0.0; 3]; 20];
    for (a, r) in NODES.iter().enumerate() {
        let f = [1.0 + p[0] * r[0], 1.0 + p[1] * r[1], 1.0 + p[2] * r[2]];
        if a < 8 {
            let s = p[0] * r[0] + p[1] * r[1] + p[2] * r[2] - 2.0;
            n[a] = 0.125 * f[0] * f[1] * f[2] * s;
            for k in 0..3 {
                let (o1, o2) = ((k + 1) % 3, (k + 2) % 3);
                dn[a][k] = 0.125 * r[k] * f[o1] * f[o2] * (s + f[k]);
            }
        } else {
            // The zero reference coordinate k0 carries the bubble factor (1 − ξ_k0²).
            let k0 = (0..3).find(|&k| r[k] == 0.0).unwrap_or(0);
            let (o1, o2) = ((k0 + 1) % 3, (k0 + 2) % 3);
            let b = 1.0 - p[k0] * p[k0];
            n[a] = 0.25 * b * f[o1] * f[o2];
            dn[a][k0] = -0.5 * p[k0] * f[o1] * f[o2];
            dn[a][o1] = 0.25 * b * r[o1] * f[o2];
            dn[a][o2] = 0.25 * b * f[o1] * r[o2];
        }
    }
    (n, dn)
}

/// Stiffness 60×60; `reduced` = 2×2×2 (C3D20R), else 3×3×3 (C3D20).
pub fn stiffness(x: &[Xyz; 20], mat: &Isotropic, reduced: bool) -> Result<Vec<f64>, ElementError> {
    let rule = quadrature::cube(if reduced { 2 } else { 3 });
    solid_stiffness(x, shape, &rule, mat)
}

/// Scalar consistent mass 20×20; `reduced` = 2×2×2 Gauss (as CalculiX C3D20R), else 3×3×3.
pub fn scalar_mass(x: &[Xyz; 20], rho: f64, reduced: bool) -> Result<Vec<f64>, ElementError> {
    let rule = quadrature::cube(if reduced { 2 } else { 3 });
    solid_scalar_mass(x, shape, &rule, rho)
}

/// Stiffness 60×60 with Irons' 14-point rule (`quadrature::cube_irons14`): ANSYS's SOLID186 with
/// full integration, KEYOPT(2)=1 (MAPDL Theory Reference §13.186: "14 if KEYOPT(2) = 1").
pub fn stiffness_irons14(x: &[Xyz; 20], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::cube_irons14(), mat)
}

/// Scalar consistent mass 20×20 with Irons' 14-point rule (`quadrature::cube_irons14`), as ANSYS
/// forms SOLID186's (checked against the K and M of ansys-mapdl-reader's `file.full`).
pub fn scalar_mass_irons14(x: &[Xyz; 20], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::cube_irons14(), rho)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex20_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(shape, &NODES, &[[0.1, -0.2, 0.3], [0.7, 0.5, -0.9]]);
    }
}
