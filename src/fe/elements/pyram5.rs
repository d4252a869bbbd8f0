//! 5-node linear pyramid (CPYRAM 5, C3D5) as a collapsed hexahedron.
//!
//! ```text
//!            5            reference (cube) coordinates (r, s, t) ∈ [−1, 1]³; the face t = +1
//!          //|\           collapses into the apex 5, so the map x(r, s, t) = Σ N_a x_a is the
//!         // | \          trilinear hexahedron with nodes 5–8 merged:
//!        4---|--3         N_a = (1 + r r_a)(1 + s s_a)(1 − t)/8, a = 1…4 (base corners
//!       /    | /                (r_a, s_a) = (−,−) (+,−) (+,+) (−,+) at t = −1)
//!      1-----2            N_5 = (1 + t)/2
//! ```
//! In the pyramid's own coordinates ξ = r(1 − ζ), η = s(1 − ζ), ζ = (1 + t)/2 these are
//! Bedrosian's rational pyramid functions (Bedrosian, *IJNME* 35 (1992) 95); the collapse is
//! the Duffy transformation (Duffy, *SIAM J. Numer. Anal.* 19 (1982) 1260), under which the
//! Jacobian vanishes only on the apex face t = 1, where no Gauss point lies.
//!
//! Integration: the 3×3×3 Gauss–Legendre product rule on the cube (a conical product rule of
//! the pyramid, Stroud, *Approximate Calculation of Multiple Integrals* (1971) §2.4). On an
//! undistorted pyramid det J ∝ (1 − t)² and the gradients are polynomial, so K (degree 4 in
//! r, s; 2 in t) and M (degree 2 in r, s; 4 in t) are integrated exactly; ∫∇N_a dV is
//! polynomial on any pyramid, so the constant-strain patch test holds.

use super::element::{
    first, integration_points, nodal_gradients, Element, ElementInput, ElementMatrices,
    MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Reference coordinates of the 5 nodes (the apex stands for the whole face t = 1).
pub const NODES: [Xyz; 5] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [0.0, 0.0, 1.0],
];

/// The pyramid's centroid in reference coordinates (ζ = 1/4, t = −1/2).
const CENTROID: Xyz = [0.0, 0.0, -0.5];

/// Where nodal gradients are taken: at the nodes, except the apex, where the collapsed map's
/// Jacobian vanishes and a field's gradient depends on the direction of approach; the
/// centroid's gradients stand in there (exact for a linear field).
const GRADIENT_POINTS: [Xyz; 5] = {
    let mut points = NODES;
    points[4] = CENTROID;
    points
};

/// Shape functions and reference gradients (module formula).
pub fn shape(p: &Xyz) -> ([f64; 5], [Xyz; 5]) {
    let [r, s, t] = *p;
    let mut n = [0.0; 5];
    let mut dn = [[0.0; 3]; 5];
    for (a, x) in NODES[..4].iter().enumerate() {
        let (fr, fs) = (1.0 + r * x[0], 1.0 + s * x[1]);
        n[a] = 0.125 * fr * fs * (1.0 - t);
        dn[a] = [
            0.125 * x[0] * fs * (1.0 - t),
            0.125 * fr * x[1] * (1.0 - t),
            -0.125 * fr * fs,
        ];
    }
    n[4] = 0.5 * (1.0 + t);
    dn[4] = [0.0, 0.0, 0.5];
    (n, dn)
}

/// Stiffness 15×15, 3×3×3 Gauss on the collapsed cube.
pub fn stiffness(x: &[Xyz; 5], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::cube(3), mat)
}

/// Scalar consistent mass 5×5, 3×3×3 Gauss on the collapsed cube.
pub fn scalar_mass(x: &[Xyz; 5], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::cube(3), rho)
}

/// The 5-node pyramid as an [`Element`].
pub struct Pyram5Element;

impl Element for Pyram5Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<5>();
        let k = input.stiffness(|| stiffness(&x, &input.iso))?;
        let ms = scalar_mass(&x, input.iso.rho)?;
        Ok(input.solid(k, ms, 5, false))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(Some(integration_points(x, shape, &quadrature::cube(3))?))
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        let grads = nodal_gradients(&first(x), shape, &GRADIENT_POINTS, CENTROID)?;
        Ok(Some(grads))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pyram5_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(shape, &NODES, &[[0.1, -0.2, 0.3], [0.0; 3]]);
    }

    /// Nodal gradients of a linear field on a skewed pyramid are its gradient at every node; at
    /// the apex they are the centroid's.
    #[test]
    fn pyram5_nodal_gradients_of_a_linear_field_are_exact() {
        let x = [
            [0.0, 0.0, 0.0],
            [2.0, 0.1, 0.0],
            [2.2, 3.0, 0.2],
            [-0.1, 2.8, 0.0],
            [0.7, 1.1, 1.5],
        ];
        super::super::test_util::check_linear_field_gradients(&Pyram5Element, &x);
    }

    /// Volume and mass of a pyramid with a 2 × 3 base and height 1.5: V = A h / 3 = 3; the
    /// consistent mass totals ρV.
    #[test]
    fn pyram5_volume_and_mass_are_exact() {
        let x = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.7, 1.1, 1.5],
        ];
        let v = super::super::solid_volume(&x, shape, &quadrature::cube(3)).unwrap();
        assert!((v - 3.0).abs() < 1e-14, "{v}");
        let m = scalar_mass(&x, 2.0).unwrap();
        assert!((m.iter().sum::<f64>() - 6.0).abs() < 1e-13);
    }
}
