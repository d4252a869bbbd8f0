//! 10-node quadratic tetrahedron (C3D10, CTETRA 10).
//!
//! ```text
//!            4            reference: 1 (0,0,0), 2 (1,0,0), 3 (0,1,0), 4 (0,0,1)
//!           /|\           mid-side:  5 (1,2)  6 (2,3)  7 (1,3)  8 (1,4)  9 (2,4)  10 (3,4)
//!          8 | 10         L1 = 1 − ξ − η − ζ, L2 = ξ, L3 = η, L4 = ζ
//!         /  9  \         corners N_i = L_i (2 L_i − 1); mid-side N_ij = 4 L_i L_j
//!        1---|7--3        (Zienkiewicz & Taylor, The Finite Element Method Vol. 1 §8.8)
//!         \  |  /
//!          5 | 6
//!            2
//! ```
//! K uses the 4-point degree-2 rule (exact for straight edges), as CalculiX C3D10. The mass has
//! two rules: the same 4-point rule, as CalculiX does (rank 4 per direction, so a coarse assembled M
//! can be singular), or an exact degree-5 collapsed Gauss rule (the classical consistent matrix,
//! ρV/420 × [6 on corner diagonals, 32 on mid-side diagonals, …]).

use super::element::{
    first, integration_points, nodal_gradients, Element, ElementInput, ElementMatrices,
    MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use std::sync::OnceLock;

use crate::fe::quadrature;

pub use super::element::Tet10MassRule;

/// Reference coordinates of the 10 nodes.
pub const NODES: [Xyz; 10] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.0, 0.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.0],
    [0.0, 0.0, 0.5],
    [0.5, 0.0, 0.5],
    [0.0, 0.5, 0.5],
];

/// Mid-side node k (5..=10, 0-based 4..=9) joins corners EDGES[k − 4] (0-based).
pub const EDGES: [(usize, usize); 6] = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)];

/// Quadratic shape functions and reference gradients.
pub fn shape(p: &Xyz) -> ([f64; 10], [Xyz; 10]) {
    let [x, y, z] = *p;
    let l = [1.0 - x - y - z, x, y, z];
    // ∂L_i/∂ξ_k
    let dl = [
        [-1.0, -1.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let mut n = [0.0; 10];
    let mut dn = [[0.0; 3]; 10];
    for i in 0..4 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
        for k in 0..3 {
            dn[i][k] = (4.0 * l[i] - 1.0) * dl[i][k];
        }
    }
    for (e, &(i, j)) in EDGES.iter().enumerate() {
        n[4 + e] = 4.0 * l[i] * l[j];
        for k in 0..3 {
            dn[4 + e][k] = 4.0 * (dl[i][k] * l[j] + l[i] * dl[j][k]);
        }
    }
    (n, dn)
}

/// Stiffness 30×30 (4-point rule).
pub fn stiffness(x: &[Xyz; 10], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::tet4(), mat)
}

/// Scalar consistent mass 10×10 by the chosen rule. A straight-edged element (mid-side nodes at
/// the edge midpoints, to 1e-10 of the edge length) has a constant Jacobian, so its mass is the
/// reference-element mass times ρ·det J, computed once per rule.
pub fn scalar_mass(x: &[Xyz; 10], rho: f64, rule: Tet10MassRule) -> Result<Vec<f64>, ElementError> {
    static REF: [OnceLock<Vec<f64>>; 2] = [OnceLock::new(), OnceLock::new()];
    let points = || match rule {
        Tet10MassRule::CalculixFourPoint => quadrature::tet4(),
        Tet10MassRule::Exact => quadrature::tet_duffy(4),
    };
    if is_straight(x) {
        let det = super::map_point(x, shape, &[0.25; 3], 0)?.2;
        let reference = REF[rule as usize].get_or_init(|| {
            let unit: [Xyz; 10] = NODES;
            // The unit element has det J = 1 everywhere; the map cannot fail.
            solid_scalar_mass(&unit, shape, &points(), 1.0).unwrap_or_default()
        });
        return Ok(reference.iter().map(|v| v * rho * det).collect());
    }
    solid_scalar_mass(x, shape, &points(), rho)
}

/// Are the mid-side nodes at the edge midpoints (affine element)?
fn is_straight(x: &[Xyz; 10]) -> bool {
    EDGES.iter().enumerate().all(|(e, &(i, j))| {
        let len2: f64 = (0..3).map(|k| (x[i][k] - x[j][k]).powi(2)).sum();
        let off2: f64 = (0..3)
            .map(|k| (x[4 + e][k] - 0.5 * (x[i][k] + x[j][k])).powi(2))
            .sum();
        off2 <= 1e-20 * len2
    })
}

/// The 10-node tetrahedron as an [`Element`].
pub struct Tet10Element;

impl Element for Tet10Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<10>();
        // HRZ lumping uses the exact consistent diagonal (the 4-point one is a cruder estimate).
        let rule = if input.lumped() {
            Tet10MassRule::Exact
        } else {
            input.spec.tet10_mass
        };
        let k = input.stiffness(|| stiffness(&x, &input.iso))?;
        let ms = scalar_mass(&x, input.iso.rho, rule)?;
        Ok(input.solid(k, ms, 10, true))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(Some(integration_points(x, shape, &quadrature::tet4())?))
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        Ok(Some(nodal_gradients(&first(x), shape, &NODES, [0.25; 3])?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tet10_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(shape, &NODES, &[[0.1, 0.2, 0.3], [0.25; 3]]);
    }

    /// Exact consistent mass in units of ρV/420 (Zienkiewicz & Taylor; row sums −1/20 at corners,
    /// +1/5 at mid-sides).
    #[test]
    fn tet10_exact_mass_matches_closed_form_coefficients() {
        let x: [Xyz; 4] = [
            [0.0, 0.0, 0.0],
            [2.0, 0.1, 0.0],
            [0.3, 1.5, 0.2],
            [0.1, 0.2, 3.0],
        ];
        let mut xs = [[0.0; 3]; 10];
        xs[..4].copy_from_slice(&x);
        for (e, &(i, j)) in EDGES.iter().enumerate() {
            xs[4 + e] = std::array::from_fn(|k| 0.5 * (x[i][k] + x[j][k]));
        }
        let rho = 3.0;
        let m = scalar_mass(&xs, rho, Tet10MassRule::Exact).unwrap();
        let v = super::super::solid_volume(&xs, shape, &crate::fe::quadrature::tet1()).unwrap();
        let unit = rho * v / 420.0;
        let touches = |e: usize, c: usize| EDGES[e].0 == c || EDGES[e].1 == c;
        for a in 0..10 {
            for b in 0..10 {
                let coef = match (a < 4, b < 4) {
                    (true, true) => {
                        if a == b {
                            6.0
                        } else {
                            1.0
                        }
                    }
                    (true, false) => {
                        if touches(b - 4, a) {
                            -4.0
                        } else {
                            -6.0
                        }
                    }
                    (false, true) => {
                        if touches(a - 4, b) {
                            -4.0
                        } else {
                            -6.0
                        }
                    }
                    (false, false) => {
                        let (ea, eb) = (EDGES[a - 4], EDGES[b - 4]);
                        if a == b {
                            32.0
                        } else if touches(b - 4, ea.0)
                            || touches(b - 4, ea.1)
                            || touches(a - 4, eb.0)
                        {
                            16.0
                        } else {
                            8.0
                        }
                    }
                };
                assert!(
                    (m[a * 10 + b] - coef * unit).abs() < 1e-13 * unit,
                    "({a},{b})"
                );
            }
        }
    }
}
