//! 6-node linear wedge (C3D6, CPENTA 6).
//!
//! ```text
//!      6                 reference: 1 (0,0,−1), 2 (1,0,−1), 3 (0,1,−1); 4–6 the same at ζ = +1
//!     /|\                N_a = L_a (1 − ζ)/2 (bottom), L_a (1 + ζ)/2 (top),
//!    4---5               L1 = 1 − ξ − η, L2 = ξ, L3 = η
//!    | 3 |               (Zienkiewicz & Taylor, The Finite Element Method Vol. 1 §8.9)
//!    |/ \|
//!    1---2
//! ```
//! K and M with the full 6-point rule (3-point triangle × 2-point Gauss), exact for the mass of
//! an undistorted wedge. (CalculiX C3D6 integrates K with 2 points; no CalculiX reference here.)

use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Reference coordinates of the 6 nodes.
pub const NODES: [Xyz; 6] = [
    [0.0, 0.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
];

/// Wedge shape functions and reference gradients.
pub fn shape(p: &Xyz) -> ([f64; 6], [Xyz; 6]) {
    let [x, y, z] = *p;
    let l = [1.0 - x - y, x, y];
    let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
    let mut n = [0.0; 6];
    let mut dn = [[0.0; 3]; 6];
    for i in 0..3 {
        for (s, off) in [(-1.0, 0), (1.0, 3)] {
            let h = 0.5 * (1.0 + s * z);
            n[i + off] = l[i] * h;
            dn[i + off] = [dl[i][0] * h, dl[i][1] * h, 0.5 * s * l[i]];
        }
    }
    (n, dn)
}

/// Stiffness 18×18.
pub fn stiffness(x: &[Xyz; 6], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::wedge(2), mat)
}

/// Scalar consistent mass 6×6.
pub fn scalar_mass(x: &[Xyz; 6], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::wedge(2), rho)
}

/// Stiffness 18×18 as CalculiX forms C3D6: two points (`quadrature::wedge_centroid`, ccx
/// e_c3d `gauss3d7`).
pub fn stiffness_ccx(x: &[Xyz; 6], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::wedge_centroid(), mat)
}

/// Scalar mass 6×6 as CalculiX forms C3D6: the same two points as its stiffness (ccx integrates
/// mass and stiffness in one loop).
pub fn scalar_mass_ccx(x: &[Xyz; 6], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::wedge_centroid(), rho)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prism6_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(shape, &NODES, &[[0.1, 0.2, 0.3], [0.3, 0.3, -0.5]]);
    }
}
