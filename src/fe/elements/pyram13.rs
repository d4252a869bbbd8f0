//! 13-node quadratic pyramid (CPYRAM 13) as a collapsed 20-node hexahedron.
//!
//! ```text
//!              5           corners 1–4 (base, t = −1) and the apex 5 (the face t = +1);
//!            //|\          mid-side nodes 6–9 on the base edges 1-2, 2-3, 3-4, 4-1, and 10–13
//!          13  | 12        on the edges 1-5, 2-5, 3-5, 4-5 (t = 0), in reference (cube)
//!          /  11  \        coordinates (r, s, t) ∈ [−1, 1]³
//!         4----8---3
//!        9     |  7        p = r r_a, q = s s_a for the node's signs (r_a, s_a):
//!       /      | /         corner  N = −(1+p)(1+q)(1−t)(4 − 3p − 3q + 2pq + 2t − pt − qt + 2pqt)/16
//!      1---6---2           base mid (s edge) N = (1−r²)(1+q)(1−t)(2 − q − qt)/8 (r edge alike)
//! ```
//! lateral mid N = (1+p)(1+q)(1−t²)/4, apex N = t(1+t)/2. In the pyramid's own coordinates
//! (ξ = r(1 − ζ), η = s(1 − ζ), ζ = (1 + t)/2) these are Bedrosian's rational 13-node pyramid
//! functions (Bedrosian, *IJNME* 35 (1992) 95; the same polynomials in collapsed coordinates as
//! OpenGeoSys' `ShapePyra13`): on each triangular face they reduce to the quadratic triangle, so
//! the element conforms to a neighbouring 10-node tetrahedron.
//!
//! Integration: the 4×4×4 Gauss–Legendre product rule on the cube (a conical product rule of
//! the pyramid, Stroud (1971) §2.4; see [`super::pyram5`] for the collapse), exact for the mass
//! of an undistorted pyramid (degree 4 in r, s and 6 in t with det J ∝ (1 − t)²).

use super::element::{
    first, integration_points, nodal_gradients, Element, ElementInput, ElementMatrices,
    MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Reference coordinates of the 13 nodes (the apex stands for the whole face t = 1).
pub const NODES: [Xyz; 13] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [0.0, 0.0, 1.0],
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// The pyramid's centroid in reference coordinates (ζ = 1/4, t = −1/2).
pub(super) const CENTROID: Xyz = [0.0, 0.0, -0.5];

/// Where nodal gradients are taken: at the nodes, except the apex, where the collapsed map's
/// Jacobian vanishes and a field's gradient depends on the direction of approach; the
/// centroid's gradients stand in there (exact for a linear field).
pub(super) const GRADIENT_POINTS: [Xyz; 13] = {
    let mut points = NODES;
    points[4] = CENTROID;
    points
};

/// Shape functions and reference gradients (module formulas).
pub fn shape(x: &Xyz) -> ([f64; 13], [Xyz; 13]) {
    let [r, s, t] = *x;
    let mut n = [0.0; 13];
    let mut dn = [[0.0; 3]; 13];
    for a in 0..4 {
        let (ra, sa) = (NODES[a][0], NODES[a][1]);
        let (p, q) = (ra * r, sa * s);
        let g = 4.0 - 3.0 * p - 3.0 * q + 2.0 * p * q + 2.0 * t - p * t - q * t + 2.0 * p * q * t;
        let (gp, gq, gt) = (
            -3.0 + 2.0 * q - t + 2.0 * q * t,
            -3.0 + 2.0 * p - t + 2.0 * p * t,
            2.0 - p - q + 2.0 * p * q,
        );
        n[a] = -(1.0 + p) * (1.0 + q) * (1.0 - t) * g / 16.0;
        dn[a] = [
            -ra * (1.0 + q) * (1.0 - t) * (g + (1.0 + p) * gp) / 16.0,
            -sa * (1.0 + p) * (1.0 - t) * (g + (1.0 + q) * gq) / 16.0,
            -(1.0 + p) * (1.0 + q) * (-g + (1.0 - t) * gt) / 16.0,
        ];
        // lateral mid-side node 10 + a on the edge from corner a to the apex
        let l = 9 + a;
        n[l] = (1.0 + p) * (1.0 + q) * (1.0 - t * t) / 4.0;
        dn[l] = [
            ra * (1.0 + q) * (1.0 - t * t) / 4.0,
            sa * (1.0 + p) * (1.0 - t * t) / 4.0,
            -(1.0 + p) * (1.0 + q) * t / 2.0,
        ];
    }
    for m in 5..9 {
        let [rm, sm, _] = NODES[m];
        if rm == 0.0 {
            // on an edge s = s_m, r varying
            let q = sm * s;
            n[m] = (1.0 - r * r) * (1.0 + q) * (1.0 - t) * (2.0 - q - q * t) / 8.0;
            dn[m] = [
                -2.0 * r * (1.0 + q) * (1.0 - t) * (2.0 - q - q * t) / 8.0,
                sm * (1.0 - r * r) * (1.0 - t) * (1.0 - 2.0 * q - t - 2.0 * q * t) / 8.0,
                -(1.0 - r * r) * (1.0 + q) * (1.0 - q * t) / 4.0,
            ];
        } else {
            // on an edge r = r_m, s varying
            let p = rm * r;
            n[m] = (1.0 - s * s) * (1.0 + p) * (1.0 - t) * (2.0 - p - p * t) / 8.0;
            dn[m] = [
                rm * (1.0 - s * s) * (1.0 - t) * (1.0 - 2.0 * p - t - 2.0 * p * t) / 8.0,
                -2.0 * s * (1.0 + p) * (1.0 - t) * (2.0 - p - p * t) / 8.0,
                -(1.0 - s * s) * (1.0 + p) * (1.0 - p * t) / 4.0,
            ];
        }
    }
    n[4] = t * (1.0 + t) / 2.0;
    dn[4] = [0.0, 0.0, t + 0.5];
    (n, dn)
}

/// Stiffness 39×39, 4×4×4 Gauss on the collapsed cube.
pub fn stiffness(x: &[Xyz; 13], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::cube(4), mat)
}

/// Scalar consistent mass 13×13, 4×4×4 Gauss on the collapsed cube.
pub fn scalar_mass(x: &[Xyz; 13], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::cube(4), rho)
}

/// The 13-node pyramid as an [`Element`].
pub struct Pyram13Element;

impl Element for Pyram13Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<13>();
        let k = input.stiffness(|| stiffness(&x, &input.iso))?;
        let ms = scalar_mass(&x, input.iso.rho)?;
        Ok(input.solid(k, ms, 13, true))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(Some(integration_points(x, shape, &quadrature::cube(4))?))
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
    fn pyram13_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(
            shape,
            &NODES,
            &[[0.1, -0.2, 0.3], [0.0; 3], [-0.6, 0.4, -0.7]],
        );
    }

    /// On the triangular face s = −1 (corners 1, 2, 5; mid-sides 6, 10, 11) the interpolation
    /// is the 6-node quadratic triangle of those nodes: the element conforms to a tet10.
    #[test]
    fn pyram13_triangular_face_is_the_quadratic_triangle() {
        let vals: [f64; 13] = std::array::from_fn(|a| (a as f64 * 0.37).sin());
        for &(r, t) in &[(0.3, -0.4), (-0.8, 0.5), (0.0, 0.9), (0.6, -1.0)] {
            let (n, _) = shape(&[r, -1.0, t]);
            let got: f64 = (0..13).map(|a| n[a] * vals[a]).sum();
            // barycentric coordinates of the face triangle 1, 2, 5
            let z = (1.0 + t) / 2.0;
            let l = [(1.0 - z) * (1.0 - r) / 2.0, (1.0 - z) * (1.0 + r) / 2.0, z];
            let corner = |i: usize| l[i] * (2.0 * l[i] - 1.0);
            let want = corner(0) * vals[0]
                + corner(1) * vals[1]
                + corner(2) * vals[4]
                + 4.0 * l[0] * l[1] * vals[5]
                + 4.0 * l[0] * l[2] * vals[9]
                + 4.0 * l[1] * l[2] * vals[10];
            assert!((got - want).abs() < 1e-13, "r={r} t={t}: {got} vs {want}");
        }
    }

    /// Nodal gradients of a linear field on a skewed pyramid with curved edges are its gradient
    /// at every node; at the apex they are the centroid's.
    #[test]
    fn pyram13_nodal_gradients_of_a_linear_field_are_exact() {
        let c = [
            [0.0, 0.0, 0.0],
            [2.0, 0.1, 0.0],
            [2.2, 3.0, 0.2],
            [-0.1, 2.8, 0.0],
            [0.7, 1.1, 1.5],
        ];
        let mid = |a: usize, b: usize, bow: f64| -> Xyz {
            std::array::from_fn(|i| 0.5 * (c[a][i] + c[b][i]) + if i == 2 { bow } else { 0.0 })
        };
        let x = [
            c[0],
            c[1],
            c[2],
            c[3],
            c[4],
            mid(0, 1, 0.05),
            mid(1, 2, -0.03),
            mid(2, 3, 0.02),
            mid(3, 0, 0.0),
            mid(0, 4, 0.04),
            mid(1, 4, 0.0),
            mid(2, 4, -0.02),
            mid(3, 4, 0.0),
        ];
        super::super::test_util::check_linear_field_gradients(&Pyram13Element, &x);
    }

    /// Volume of a pyramid with straight edges (mid-sides at the midpoints) and its mass.
    #[test]
    fn pyram13_volume_and_mass_are_exact() {
        let c = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.7, 1.1, 1.5],
        ];
        let mid = |a: usize, b: usize| std::array::from_fn(|i| 0.5 * (c[a][i] + c[b][i]));
        let x: [Xyz; 13] = [
            c[0],
            c[1],
            c[2],
            c[3],
            c[4],
            mid(0, 1),
            mid(1, 2),
            mid(2, 3),
            mid(3, 0),
            mid(0, 4),
            mid(1, 4),
            mid(2, 4),
            mid(3, 4),
        ];
        let v = super::super::solid_volume(&x, shape, &quadrature::cube(4)).unwrap();
        assert!((v - 3.0).abs() < 1e-13, "{v}");
        let m = scalar_mass(&x, 2.0).unwrap();
        assert!((m.iter().sum::<f64>() - 6.0).abs() < 1e-12);
    }
}
