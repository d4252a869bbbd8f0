//! ANSYS's higher-order beams as [`Element`]s, one formulation of two orders:
//!
//! - **quadratic** — BEAM189 (and BEAM188 KEYOPT(3)=2, whose table in the MAPDL Theory
//!   Reference §13.188 gives BEAM189's functions and points): the three-node Timoshenko beam of
//!   §13.189, displacements and rotations interpolated quadratically through I, the mid node
//!   and J (its equations 11–19…11–24), the stiffness on two points along the length, the
//!   consistent mass on three;
//! - **cubic** — BEAM188 KEYOPT(3)=3 (§13.188's table): four nodes I, J and the two internal
//!   nodes K, L at 1/3 and 2/3 of IJ (ξ = −1, 1, −1/3, 1/3), displacements and rotations
//!   interpolated cubically (equations 11–27…11–32, §11.3.4 "3D 4-Node Lines"), the stiffness
//!   on three points along the length, the consistent mass on four.
//!
//! In both, the consistent mass carries the section's rotary inertia (what VM50's published
//! frequency shows: docs/ansys.md). The generalized strains and rigidities are BEAM188's
//! ([`super::beam188`]): u', θx', θy', θz', γxy = v' − θz, γxz = w' + θy with EA, GJ, EIyy,
//! EIzz, k_y GA, k_z GA. With n nodes the stiffness takes n − 1 points: exact for the bending,
//! axial and torsion terms (degree 2n − 4), reduced for the shear (degree 2n − 2), which keeps
//! the element free of shear locking and of spurious zero-energy modes (a strain of degree
//! n − 2 vanishing at n − 1 points is zero). The element is straight with its inner nodes where
//! the order puts them (a curved or uneven one is refused by the importer); ANSYS's lumped mass
//! of either is not established here (`LUMPM,ON` with them is refused by the archive's line; the
//! build's nodal masses use the HRZ diagonal, [`lumped_mass`]).

use super::beam::{self, BeamProps};
use super::element::{
    Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{beam188, ElementError, Isotropic, Xyz};
use crate::fe::quadrature::gauss_legendre;

/// The interpolation of an ANSYS higher-order beam.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// Three nodes I, J, mid (BEAM189; BEAM188 KEYOPT(3)=2).
    Quadratic,
    /// Four nodes I, J, K (1/3 of IJ), L (2/3) (BEAM188 KEYOPT(3)=3).
    Cubic,
}

impl Order {
    /// The element's nodes.
    pub fn nodes(self) -> usize {
        match self {
            Order::Quadratic => 3,
            Order::Cubic => 4,
        }
    }

    /// The element's name in messages.
    fn name(self) -> &'static str {
        match self {
            Order::Quadratic => "BEAM189",
            Order::Cubic => "BEAM188 KEYOPT(3)=3",
        }
    }

    /// Where the nodes after I and J sit along IJ (fractions of the length from I).
    pub fn inner(self) -> &'static [f64] {
        match self {
            Order::Quadratic => &[0.5],
            Order::Cubic => &[1.0 / 3.0, 2.0 / 3.0],
        }
    }

    /// The functions of the nodes (I, J, then the inner ones) at ξ and their ξ-derivatives:
    /// the Theory Reference's equation 11–19 (quadratic) and 11–27 (cubic), the same functions
    /// for every displacement and rotation (11–20…11–24, 11–28…11–32).
    pub fn shape(self, xi: f64) -> (Vec<f64>, Vec<f64>) {
        match self {
            Order::Quadratic => (
                vec![xi * (xi - 1.0) / 2.0, xi * (xi + 1.0) / 2.0, 1.0 - xi * xi],
                vec![xi - 0.5, xi + 0.5, -2.0 * xi],
            ),
            Order::Cubic => {
                let (x2, x3) = (xi * xi, xi * xi * xi);
                (
                    vec![
                        (-9.0 * x3 + 9.0 * x2 + xi - 1.0) / 16.0,
                        (9.0 * x3 + 9.0 * x2 - xi - 1.0) / 16.0,
                        (27.0 * x3 - 9.0 * x2 - 27.0 * xi + 9.0) / 16.0,
                        (-27.0 * x3 - 9.0 * x2 + 27.0 * xi + 9.0) / 16.0,
                    ],
                    vec![
                        (-27.0 * x2 + 18.0 * xi + 1.0) / 16.0,
                        (27.0 * x2 + 18.0 * xi - 1.0) / 16.0,
                        (81.0 * x2 - 18.0 * xi - 27.0) / 16.0,
                        (-81.0 * x2 - 18.0 * xi + 27.0) / 16.0,
                    ],
                )
            }
        }
    }
}

/// BEAM189 (nodes I, J, mid: [`Order::Quadratic`]) or BEAM188 KEYOPT(3)=3 (nodes I, J, K, L:
/// [`Order::Cubic`]).
pub struct HigherOrderBeam {
    pub order: Order,
}

impl Element for HigherOrderBeam {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let p = beam188::ansys_section_props(self.order.name(), input)?;
        let x: Vec<Xyz> = input
            .nodes
            .iter()
            .map(|&n| input.model.nodes[n].x)
            .collect();
        let v = input.model.elements[input.index].orientation;
        let (k, m) = matrices(self.order, &x, v, &input.iso, &p)?;
        let m = if input.lumped() {
            lumped_mass(self.order, &x, &input.iso, &p)
        } else {
            m
        };
        Ok(ElementMatrices::nodal(6, k, m))
    }

    fn stiffness_points(
        &self,
        _: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(None)
    }

    fn nodal_gradients(&self, _: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        Ok(None)
    }
}

/// Basic-frame stiffness and mass (6n × 6n, row-major, nodes I, J, then the inner ones) of a
/// straight element of `order` (`x`: its n nodes); `v` orients the local y axis as for
/// [`beam::local_frame`]. K = Σ_{n−1 points} w (L/2) Bᵀ C B, M = Σ_{n points} w (L/2) Nᵀ μ N
/// (module doc: B the six generalized strains, C the rigidities, μ the inertias per length).
pub fn matrices(
    order: Order,
    x: &[Xyz],
    v: Option<Xyz>,
    mat: &Isotropic,
    p: &BeamProps,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    beam::check(mat, p)?;
    let name = order.name();
    let [ky, kz] = p.shear.ok_or_else(|| {
        ElementError::BadConstants(format!("{name} needs its shear factors k_y, k_z"))
    })?;
    let v = v.ok_or(ElementError::BadOrientation { v: [0.0; 3] })?;
    let (r, l) = beam::local_frame(&[x[0], x[1]], Some(v))?;
    let rigidity = [
        mat.e * p.area,
        mat.g * p.j,
        mat.e * p.iy,
        mat.e * p.iz,
        ky * mat.g * p.area,
        kz * mat.g * p.area,
    ];
    let inertia = [
        mat.rho * p.area + p.nsm,
        mat.rho * p.area + p.nsm,
        mat.rho * p.area + p.nsm,
        mat.rho * (p.iy + p.iz),
        mat.rho * p.iy,
        mat.rho * p.iz,
    ];
    let nodes = order.nodes();
    let nd = 6 * nodes;
    let jac = l / 2.0;
    let mut k = vec![0.0; nd * nd];
    for &(xi, w) in gauss_legendre(nodes - 1) {
        // B (6 × 6n): u', θx', θy', θz', v' − θz, w' + θy
        let (n, dn) = order.shape(xi);
        let mut b = vec![[0.0; 6]; nd];
        for a in 0..nodes {
            let (o, d) = (6 * a, dn[a] / jac);
            b[o][0] = d;
            b[o + 3][1] = d;
            b[o + 4][2] = d;
            b[o + 5][3] = d;
            b[o + 1][4] = d;
            b[o + 5][4] = -n[a];
            b[o + 2][5] = d;
            b[o + 4][5] = n[a];
        }
        for (s, c) in rigidity.iter().enumerate() {
            let f = w * jac * c;
            for i in 0..nd {
                if b[i][s] == 0.0 {
                    continue;
                }
                for j in 0..nd {
                    k[i * nd + j] += f * b[i][s] * b[j][s];
                }
            }
        }
    }
    let mut m = vec![0.0; nd * nd];
    for &(xi, w) in gauss_legendre(nodes) {
        let (n, _) = order.shape(xi);
        for a in 0..nodes {
            for bb in 0..nodes {
                for (d, mu) in inertia.iter().enumerate() {
                    m[(6 * a + d) * nd + 6 * bb + d] += w * jac * mu * n[a] * n[bb];
                }
            }
        }
    }
    Ok((rotate(&k, &r), rotate(&m, &r)))
}

/// flexbody's lumped mass of the element (ANSYS's `LUMPM` form of BEAM189 and BEAM188
/// KEYOPT(3)≥2 is not established: the archive refuses `LUMPM,ON` with them; this one serves
/// the build's nodal masses): the HRZ diagonal of the functions' translational mass — node a
/// gets (ρA + m_a)L · ∫N_a² / Σ_b ∫N_b², (1/6, 1/6, 2/3) on I, J and the mid node of the
/// quadratic, (8/97, 8/97, 81/194, 81/194) on I, J, K, L of the cubic — no rotary inertia (as
/// BEAM188's lumped mass).
pub fn lumped_mass(order: Order, x: &[Xyz], mat: &Isotropic, p: &BeamProps) -> Vec<f64> {
    let l = crate::model::geometry::norm(crate::model::geometry::sub(x[1], x[0]));
    let m = (mat.rho * p.area + p.nsm) * l;
    let nodes = order.nodes();
    let mut diagonal = vec![0.0; nodes];
    for &(xi, w) in gauss_legendre(nodes) {
        let (n, _) = order.shape(xi);
        for (d, na) in diagonal.iter_mut().zip(n) {
            *d += w * na * na;
        }
    }
    let total: f64 = diagonal.iter().sum();
    let nd = 6 * nodes;
    let mut out = vec![0.0; nd * nd];
    for (node, d) in diagonal.iter().enumerate() {
        for c in 0..3 {
            let i = 6 * node + c;
            out[i * nd + i] = d / total * m;
        }
    }
    out
}

/// Tᵀ A T for T = diag(R, …, R) (3×3 blocks), R's rows the local axes: a local matrix (n × n,
/// row-major) in the basic frame.
fn rotate(a: &[f64], r: &[Xyz; 3]) -> Vec<f64> {
    let n = a.len().isqrt();
    let t = |i: usize, j: usize| {
        if i / 3 == j / 3 {
            r[i % 3][j % 3]
        } else {
            0.0
        }
    };
    let mut at = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            let blk = j / 3 * 3;
            at[i * n + j] = (0..3).map(|q| a[i * n + blk + q] * t(blk + q, j)).sum();
        }
    }
    let mut out = vec![0.0; n * n];
    for i in 0..n {
        let blk = i / 3 * 3;
        for j in 0..n {
            out[i * n + j] = (0..3).map(|q| t(blk + q, i) * at[(blk + q) * n + j]).sum();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::shell::test_util::{form, residual, rigid};

    fn props() -> BeamProps {
        BeamProps {
            area: 2e-4,
            iz: 3e-9,
            iy: 5e-9,
            j: 6e-9,
            shear: Some([0.85, 0.8]),
            nsm: 0.0,
        }
    }

    /// A skewed element of `order`: its nodes at their places along IJ.
    fn skewed(order: Order) -> Vec<Xyz> {
        let (a, b) = ([0.1, 0.2, -0.3], [0.5, -0.1, 0.4]);
        let mut x = vec![a, b];
        for &t in order.inner() {
            x.push(std::array::from_fn(|c| a[c] + t * (b[c] - a[c])));
        }
        x
    }

    /// Six rigid motions give zero force on a skewed element; the mass is ρAL.
    #[test]
    fn higher_order_rigid_motions_are_free_of_force_and_the_mass_is_rho_a_l() {
        for order in [Order::Quadratic, Order::Cubic] {
            let x = skewed(order);
            let mat = Isotropic::new(210e9, 0.3, 7850.0);
            let (k, m) = matrices(order, &x, Some([0.0, 0.3, 1.0]), &mat, &props()).unwrap();
            for mode in 0..6 {
                let r = residual(&k, &rigid(&x, mode));
                assert!(r < 1e-11, "{order:?} mode {mode}: {r}");
            }
            let l = crate::model::geometry::norm(crate::model::geometry::sub(x[1], x[0]));
            let ux = rigid(&x, 0);
            let want = 7850.0 * 2e-4 * l;
            for mass in [&m, &lumped_mass(order, &x, &mat, &props())] {
                let got = form(mass, &ux, &ux);
                assert!((got - want).abs() < 1e-12 * want, "{order:?} {got} {want}");
            }
        }
    }

    /// The cubic functions are the Lagrange functions of ξ = −1, 1, −1/3, 1/3: one at their
    /// own node, zero at the others, summing to one with derivatives summing to zero anywhere.
    #[test]
    fn cubic_functions_interpolate_their_nodes() {
        let at = [-1.0, 1.0, -1.0 / 3.0, 1.0 / 3.0];
        for (a, &xi) in at.iter().enumerate() {
            let (n, _) = Order::Cubic.shape(xi);
            for (b, nb) in n.iter().enumerate() {
                let want = if a == b { 1.0 } else { 0.0 };
                assert!((nb - want).abs() < 1e-15, "N{b}({xi}) = {nb}");
            }
        }
        for xi in [-0.7, 0.1, 0.9] {
            let (n, dn) = Order::Cubic.shape(xi);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(dn.iter().sum::<f64>().abs() < 1e-14);
            // the derivative against a central difference
            let h = 1e-6;
            let (up, down) = (Order::Cubic.shape(xi + h).0, Order::Cubic.shape(xi - h).0);
            for a in 0..4 {
                let fd = (up[a] - down[a]) / (2.0 * h);
                assert!((fd - dn[a]).abs() < 1e-8, "{a} {fd} {}", dn[a]);
            }
        }
    }

    /// The cubic's points: with θz = ξ³ at the nodes (the cubic functions hold it) and no
    /// translation, the shear strain γ = −ξ³ is of degree 3, so three points give the shear
    /// energy k GA (L/2)·Σ w_q ξ_q⁶ = k GA (L/2)·0.24 (the exact ∫ξ⁶ = 2/7 would be four
    /// points'), the bending EI ∫(3ξ²·2/L)² (L/2) dξ = EI (2/L)·18/5 exactly; the mass four
    /// points: ρIz (L/2)·2/7 exactly.
    #[test]
    fn cubic_stiffness_takes_three_points_and_the_mass_four() {
        let l = 0.6;
        let (a, b) = ([0.0; 3], [l, 0.0, 0.0]);
        let x = vec![a, b, [l / 3.0, 0.0, 0.0], [2.0 * l / 3.0, 0.0, 0.0]];
        let mat = Isotropic::new(210e9, 0.3, 7850.0);
        let p = props();
        let (k, m) = matrices(Order::Cubic, &x, Some([0.0, 1.0, 0.0]), &mat, &p).unwrap();
        let mut u = vec![0.0; 24];
        for (node, xi) in [-1.0f64, 1.0, -1.0 / 3.0, 1.0 / 3.0]
            .into_iter()
            .enumerate()
        {
            u[6 * node + 5] = xi.powi(3);
        }
        let jac = l / 2.0;
        let want = 0.85 * mat.g * p.area * jac * 0.24 + mat.e * p.iz * 18.0 / 5.0 / jac;
        let got = form(&k, &u, &u);
        assert!((got / want - 1.0).abs() < 1e-13, "{got} {want}");
        let want = mat.rho * p.iz * jac * 2.0 / 7.0;
        let got = form(&m, &u, &u);
        assert!((got / want - 1.0).abs() < 1e-13, "{got} {want}");
    }

    /// The cubic's HRZ shares are the cubic bar's consistent-mass diagonal (Σ ∫N_a² ds over the
    /// element: 128, 128, 648, 648 over 1680, e.g. Zienkiewicz & Taylor's 4-node line)
    /// normalized: 8/97 and 81/194.
    #[test]
    fn cubic_lumped_mass_is_the_hrz_diagonal() {
        let x = skewed(Order::Cubic);
        let mat = Isotropic::new(210e9, 0.3, 1.0);
        let p = BeamProps {
            area: 1.0,
            ..props()
        };
        let m = lumped_mass(Order::Cubic, &x, &mat, &p);
        let l = crate::model::geometry::norm(crate::model::geometry::sub(x[1], x[0]));
        for (node, share) in [8.0 / 97.0, 8.0 / 97.0, 81.0 / 194.0, 81.0 / 194.0]
            .into_iter()
            .enumerate()
        {
            let i = 6 * node + 1;
            assert!((m[i * 24 + i] / l - share).abs() < 1e-15, "{node}");
            let r = 6 * node + 4;
            assert_eq!(m[r * 24 + r], 0.0);
        }
    }
}
