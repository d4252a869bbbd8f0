//! 15-node quadratic wedge (C3D15), as CalculiX integrates it.
//!
//! ```text
//!        6                reference: 1 (0,0,−1), 2 (1,0,−1), 3 (0,1,−1); 4–6 the same at ζ = +1;
//!       /|\               7 (1–2), 8 (2–3), 9 (3–1) bottom, 10–12 top, 13–15 verticals (1–4 …)
//!     12 | 11             L1 = 1 − ξ − η, L2 = ξ, L3 = η:
//!     /  15 \             corner a: N = L_a (2L_a − 1)(1 ± ζ)/2 − L_a (1 − ζ²)/2
//!    4---10--5            mid-edge (a, b): N = 2 L_a L_b (1 ± ζ); vertical a: L_a (1 − ζ²)
//!    |   3   |            (Zienkiewicz & Taylor, The Finite Element Method Vol. 1 §8.9)
//!   13  / \  14
//!    | 9   8 |
//!    |/     \|
//!    1---7---2
//! ```
//! K and M with CalculiX's 9-point rule (`quadrature::wedge_ccx`, ccx e_c3d `gauss3d8`: the
//! interior 3-point triangle rule × 3 Gauss points), stiffness and mass in one loop as ccx, for
//! every format: CalculiX C3D15 (and ccx's shells S6, `import::abaqus::shell_expansion`),
//! Nastran CPENTA with 15 grids, Gmsh's prism15 (type 18) — so one mesh gives the same
//! frequencies through the three importers (`tests/prism15_formats.rs`). The 3-point triangle
//! rule integrates the straight wedge's volume exactly but not N_a N_b (degree 4): the
//! consistent mass sums to ρV and has rank 9 of 15, as ccx's; HRZ lumping keeps its diagonal.

use super::element::{
    first, integration_points, nodal_gradients, Element, ElementInput, ElementMatrices,
    MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Reference coordinates of the 15 nodes.
pub const NODES: [Xyz; 15] = [
    [0.0, 0.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [0.5, 0.0, -1.0],
    [0.5, 0.5, -1.0],
    [0.0, 0.5, -1.0],
    [0.5, 0.0, 1.0],
    [0.5, 0.5, 1.0],
    [0.0, 0.5, 1.0],
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
];

/// Wedge shape functions and reference gradients (module doc).
pub fn shape(p: &Xyz) -> ([f64; 15], [Xyz; 15]) {
    let [x, y, z] = *p;
    let l = [1.0 - x - y, x, y];
    // dL_a/dξ, dL_a/dη
    let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
    let mut n = [0.0; 15];
    let mut dn = [[0.0; 3]; 15];
    let b = 1.0 - z * z;
    for a in 0..3 {
        for (s, off) in [(-1.0, 0), (1.0, 3)] {
            let h = 1.0 + s * z;
            let q = l[a] * (2.0 * l[a] - 1.0);
            let dq = 4.0 * l[a] - 1.0;
            n[a + off] = 0.5 * q * h - 0.5 * l[a] * b;
            for k in 0..2 {
                dn[a + off][k] = dl[a][k] * (0.5 * dq * h - 0.5 * b);
            }
            dn[a + off][2] = 0.5 * q * s + l[a] * z;
        }
        // the edge a–(a+1): nodes 7–9 bottom, 10–12 top
        let c = (a + 1) % 3;
        for (s, off) in [(-1.0, 6), (1.0, 9)] {
            let h = 1.0 + s * z;
            n[a + off] = 2.0 * l[a] * l[c] * h;
            for k in 0..2 {
                dn[a + off][k] = 2.0 * (dl[a][k] * l[c] + l[a] * dl[c][k]) * h;
            }
            dn[a + off][2] = 2.0 * l[a] * l[c] * s;
        }
        n[a + 12] = l[a] * b;
        dn[a + 12] = [dl[a][0] * b, dl[a][1] * b, -2.0 * z * l[a]];
    }
    (n, dn)
}

/// Stiffness 45×45 as CalculiX forms C3D15 (9 points).
pub fn stiffness_ccx(x: &[Xyz; 15], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, shape, &quadrature::wedge_ccx(), mat)
}

/// Scalar mass 15×15 as CalculiX forms C3D15: the same 9 points as its stiffness.
pub fn scalar_mass_ccx(x: &[Xyz; 15], rho: f64) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, shape, &quadrature::wedge_ccx(), rho)
}

/// The 15-node wedge as an [`Element`].
pub struct Prism15Element;

impl Element for Prism15Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        // every format's 15-node wedge as CalculiX integrates its C3D15
        let x = input.coords::<15>();
        let k = input.stiffness(|| stiffness_ccx(&x, &input.iso))?;
        let ms = scalar_mass_ccx(&x, input.iso.rho)?;
        Ok(input.solid(k, ms, 15, true))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(Some(integration_points(
            x,
            shape,
            &quadrature::wedge_ccx(),
        )?))
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        const THIRD: f64 = 1.0 / 3.0;
        let grads = nodal_gradients(&first(x), shape, &NODES, [THIRD, THIRD, 0.0])?;
        Ok(Some(grads))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prism15_shape_functions_partition_unity_and_derivatives() {
        super::super::test_util::check_shape(shape, &NODES, &[[0.1, 0.2, 0.3], [0.3, 0.3, -0.5]]);
    }

    /// The 9-point rule integrates the volume of a wedge exactly and the consistent mass sums
    /// to ρV: a right wedge of unit legs and height 2 has V = 1.
    #[test]
    fn prism15_mass_sums_to_rho_v() {
        let x: [Xyz; 15] = NODES;
        let m = scalar_mass_ccx(&x, 3.0).unwrap();
        let total: f64 = m.iter().sum();
        assert!((total - 3.0).abs() < 1e-12, "{total}");
    }
}
