//! 4-node linear tetrahedron (C3D4, CTETRA 4): constant strain.
//!
//! ```text
//!         4
//!        /|\        reference: 1 (0,0,0), 2 (1,0,0), 3 (0,1,0), 4 (0,0,1)
//!       / | \       N1 = 1 − ξ − η − ζ, N2 = ξ, N3 = η, N4 = ζ
//!      1--|--3      Zienkiewicz & Taylor, The Finite Element Method Vol. 1 §6.3
//!       \ | /
//!         2
//! ```
//! K: 1-point rule (exact, constant B); M: 4-point degree-2 rule (exact, M = ρV/20 (1 + δ_ab)).

use super::element::{
    first, integration_points, nodal_gradients, Element, ElementInput, ElementMatrices,
    MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Reference coordinates of the 4 nodes.
pub const NODES: [Xyz; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];

/// Linear shape functions and reference gradients.
pub fn shape(p: &Xyz) -> ([f64; 4], [Xyz; 4]) {
    let [x, y, z] = *p;
    (
        [1.0 - x - y - z, x, y, z],
        [
            [-1.0, -1.0, -1.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
    )
}

/// Stiffness 12×12.
pub fn stiffness(x: &[Xyz; 4], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::tet1(), mat)
}

/// Scalar consistent mass 4×4 (exact).
pub fn scalar_mass(x: &[Xyz; 4], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::tet4(), rho)
}

/// Scalar mass 4×4 as CalculiX forms C3D4: one point, as its stiffness (ccx integrates mass and
/// stiffness in one loop, e_c3d `gauss3d4`): every entry ρV/16 — the right mass and row sums,
/// but not the consistent matrix.
pub fn scalar_mass_one_point(x: &[Xyz; 4], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::tet1(), rho)
}

/// The 4-node tetrahedron as an [`Element`].
pub struct Tet4Element;

impl Element for Tet4Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<4>();
        let k = input.stiffness(|| stiffness(&x, &input.iso))?;
        let ms = if input.model.params.ccx_solid_rules {
            scalar_mass_one_point(&x, input.iso.rho)
        } else {
            scalar_mass(&x, input.iso.rho)
        }?;
        Ok(input.solid(k, ms, 4, false))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(Some(integration_points(x, shape, &quadrature::tet1())?))
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        Ok(Some(nodal_gradients(&first(x), shape, &NODES, [0.25; 3])?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tet4_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(shape, &NODES, &[[0.1, 0.2, 0.3], [0.25; 3]]);
    }

    #[test]
    fn tet4_mass_is_rho_v_over_20_times_one_plus_delta() {
        let x = [
            [0.0, 0.0, 0.0],
            [2.0, 0.1, 0.0],
            [0.3, 1.5, 0.2],
            [0.1, 0.2, 3.0],
        ];
        let m = scalar_mass(&x, 2.0).unwrap();
        let j = super::super::map_point(&x, shape, &[0.2; 3], 0).unwrap().2;
        let v = j / 6.0;
        for a in 0..4 {
            for b in 0..4 {
                let want = 2.0 * v / 20.0 * if a == b { 2.0 } else { 1.0 };
                assert!((m[a * 4 + b] - want).abs() < 1e-14 * want);
            }
        }
    }
}
