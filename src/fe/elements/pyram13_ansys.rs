//! ANSYS's 13-node pyramid: SOLID186 written as a brick whose top face (M…P, U…X) is one node.
//!
//! The MAPDL Theory Reference (§11.9.4 "13-Node Pyramids", equations 11–192…197: "based on a
//! condensation of a 20-node brick element"; SOLID186's table, §13.186: the pyramid's stiffness
//! and mass on 2 × 2 × 2 points). In the collapsed cube's coordinates (r, s, t) ∈ [−1, 1]³ of
//! [`super::pyram13`] (same nodes, same order), with Q = (1 − t)/2 the distance from the apex
//! (Q = 1 on the base) and p = r r_a, q = s s_a for a base corner's signs:
//!
//! ```text
//! corner        N = (Q/4)(1 + p)(1 + q)(Q p + Q q − 1)
//! base mid      N = (Q²/2)(1 − r²)(1 + q)   (edge s = s_m; the edges r = r_m alike)
//! lateral mid   N = Q(1 − Q)(1 + p)(1 + q)
//! apex          N = (1 − Q)(1 − 2Q)
//! ```
//!
//! The lateral and apex functions are Bedrosian's ([`super::pyram13`]); the corner and base
//! mid-side functions are not: the two differ by multiples of Q(1 − Q)(1 − r²)(1 − s²), so the
//! elements differ on any pyramid. Both reproduce every quadratic field and reduce to the
//! quadratic triangle on the four triangular faces (tests below). The equations' images were not
//! readable in the copies of the Theory Reference at hand: these functions are the ones that
//! reproduce ANSYS's own strain energies of 684 SOLID186 pyramids (the `hemisphere.rst` result
//! of ansys/example-data, `tests/ansys_solids_pyramid.rs`) to their single precision, 5.9e-8,
//! on the 2 × 2 × 2 Gauss rule of the collapsed cube; Bedrosian's functions on 2×2×2 or 4×4×4
//! points miss them by up to 3.8e-2 and 5.8e-2, the collapsed 20-node brick by 0.12.
//!
//! A lone element has one zero-energy mode besides the rigid ones (8 points × 6 strains for 39
//! dofs; not communicable in a mesh, as C3D20R's). Its consistent mass on the same 8 points
//! (the table's "same as stiffness") has rank 8 of 13 per direction — not shown against ANSYS.

use super::element::{
    first, integration_points, nodal_gradients, Element, ElementInput, ElementMatrices,
    MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::pyram13::{CENTROID, GRADIENT_POINTS, NODES};
use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Shape functions and reference gradients (module formulas; ∂/∂t = −½ ∂/∂Q).
pub fn shape(x: &Xyz) -> ([f64; 13], [Xyz; 13]) {
    let [r, s, t] = *x;
    let big_q = (1.0 - t) / 2.0;
    let mut n = [0.0; 13];
    let mut dn = [[0.0; 3]; 13];
    for a in 0..4 {
        let (ra, sa) = (NODES[a][0], NODES[a][1]);
        let (p, q) = (ra * r, sa * s);
        let (fp, fq) = (1.0 + p, 1.0 + q);
        n[a] = big_q / 4.0 * fp * fq * (big_q * (p + q) - 1.0);
        dn[a] = [
            ra * big_q / 4.0 * fq * (2.0 * big_q * p + big_q * q + big_q - 1.0),
            sa * big_q / 4.0 * fp * (big_q * p + 2.0 * big_q * q + big_q - 1.0),
            -fp * fq * (2.0 * big_q * (p + q) - 1.0) / 8.0,
        ];
        // lateral mid-side node 10 + a on the edge from corner a to the apex
        let l = 9 + a;
        n[l] = big_q * (1.0 - big_q) * fp * fq;
        dn[l] = [
            ra * big_q * (1.0 - big_q) * fq,
            sa * big_q * (1.0 - big_q) * fp,
            -(1.0 - 2.0 * big_q) * fp * fq / 2.0,
        ];
    }
    let q2 = big_q * big_q / 2.0;
    for m in 5..9 {
        let [rm, sm, _] = NODES[m];
        if rm == 0.0 {
            // on an edge s = s_m, r varying
            let fq = 1.0 + sm * s;
            n[m] = q2 * (1.0 - r * r) * fq;
            dn[m] = [
                -2.0 * q2 * r * fq,
                sm * q2 * (1.0 - r * r),
                -big_q * (1.0 - r * r) * fq / 2.0,
            ];
        } else {
            // on an edge r = r_m, s varying
            let fp = 1.0 + rm * r;
            n[m] = q2 * (1.0 - s * s) * fp;
            dn[m] = [
                rm * q2 * (1.0 - s * s),
                -2.0 * q2 * s * fp,
                -big_q * (1.0 - s * s) * fp / 2.0,
            ];
        }
    }
    n[4] = (1.0 - big_q) * (1.0 - 2.0 * big_q);
    dn[4] = [0.0, 0.0, (3.0 - 4.0 * big_q) / 2.0];
    (n, dn)
}

/// Stiffness 39×39, 2×2×2 Gauss on the collapsed cube.
pub fn stiffness(x: &[Xyz; 13], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::cube(2), mat)
}

/// Scalar consistent mass 13×13, 2×2×2 Gauss on the collapsed cube.
pub fn scalar_mass(x: &[Xyz; 13], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::cube(2), rho)
}

/// ANSYS's 13-node pyramid as an [`Element`].
pub struct Pyram13AnsysElement;

impl Element for Pyram13AnsysElement {
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
        Ok(Some(integration_points(x, shape, &quadrature::cube(2))?))
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        let grads = nodal_gradients(&first(x), shape, &GRADIENT_POINTS, CENTROID)?;
        Ok(Some(grads))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight pyramid: base corners (0,0,0), (2,0,0), (2,3,0), (0,3,0), apex (0.7,1.1,1.5),
    /// mid-side nodes at the edges' middles; `bow` lifts the mid-side nodes off them.
    fn pyramid(bow: f64) -> [Xyz; 13] {
        let c = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.7, 1.1, 1.5],
        ];
        let mid = |a: usize, b: usize, k: f64| -> Xyz {
            std::array::from_fn(|i| 0.5 * (c[a][i] + c[b][i]) + if i == 2 { k * bow } else { 0.0 })
        };
        [
            c[0],
            c[1],
            c[2],
            c[3],
            c[4],
            mid(0, 1, 1.0),
            mid(1, 2, -0.6),
            mid(2, 3, 0.4),
            mid(3, 0, 0.0),
            mid(0, 4, 0.8),
            mid(1, 4, 0.0),
            mid(2, 4, -0.4),
            mid(3, 4, 0.0),
        ]
    }

    #[test]
    fn pyram13_ansys_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(
            shape,
            &NODES,
            &[[0.1, -0.2, 0.3], [0.0; 3], [-0.6, 0.4, -0.7]],
        );
    }

    /// Every quadratic field of x, y, z on a straight pyramid is interpolated exactly.
    #[test]
    fn pyram13_ansys_reproduces_quadratic_fields() {
        let x = pyramid(0.0);
        let fields: [fn(&Xyz) -> f64; 4] = [
            |p| p[0] * p[0] - 0.3 * p[1] * p[2],
            |p| p[1] * p[1] + p[0] * p[1],
            |p| p[2] * p[2] - p[0] * p[2] + 2.0 * p[1],
            |p| 1.0 + p[0] - p[1] + 0.5 * p[2],
        ];
        for xi in [[0.3, -0.5, 0.2], [-0.8, 0.6, -0.9], [0.1, 0.1, 0.7]] {
            let (n, _) = shape(&xi);
            let at: Xyz = std::array::from_fn(|i| (0..13).map(|a| n[a] * x[a][i]).sum());
            for f in fields {
                let got: f64 = (0..13).map(|a| n[a] * f(&x[a])).sum();
                assert!((got - f(&at)).abs() < 1e-13, "{xi:?}: {got} vs {}", f(&at));
            }
        }
    }

    /// On the triangular face s = −1 (corners 1, 2, 5; mid-sides 6, 10, 11) the interpolation
    /// is the 6-node quadratic triangle of those nodes: the element conforms to a tet10.
    #[test]
    fn pyram13_ansys_triangular_face_is_the_quadratic_triangle() {
        let vals: [f64; 13] = std::array::from_fn(|a| (a as f64 * 0.37).sin());
        for &(r, t) in &[(0.3, -0.4), (-0.8, 0.5), (0.0, 0.9), (0.6, -1.0)] {
            let (n, _) = shape(&[r, -1.0, t]);
            let got: f64 = (0..13).map(|a| n[a] * vals[a]).sum();
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

    /// Not Bedrosian's element: the corner functions differ inside the pyramid.
    #[test]
    fn pyram13_ansys_differs_from_bedrosian_inside() {
        let xi = [0.3, -0.2, 0.1];
        let (a, _) = shape(&xi);
        let (b, _) = super::super::pyram13::shape(&xi);
        // Bedrosian's corner is ANSYS's less Q(1 − Q)(1 − r²)(1 − s²)/2: 0.108 at Q = 0.45
        assert!((a[0] - b[0] - 0.45 * 0.55 * 0.91 * 0.96 / 2.0).abs() < 1e-14);
    }

    /// Nodal gradients of a linear field on a pyramid with curved edges are its gradient at
    /// every node; at the apex they are the centroid's.
    #[test]
    fn pyram13_ansys_nodal_gradients_of_a_linear_field_are_exact() {
        super::super::test_util::check_linear_field_gradients(&Pyram13AnsysElement, &pyramid(0.05));
    }

    /// Volume of the straight pyramid (2 × 3 base, height 1.5) and its mass: exact on 2×2×2.
    #[test]
    fn pyram13_ansys_volume_and_mass_are_exact() {
        let x = pyramid(0.0);
        let v = super::super::solid_volume(&x, shape, &quadrature::cube(2)).unwrap();
        assert!((v - 3.0).abs() < 1e-13, "{v}");
        let m = scalar_mass(&x, 2.0).unwrap();
        assert!((m.iter().sum::<f64>() - 6.0).abs() < 1e-12);
    }
}
