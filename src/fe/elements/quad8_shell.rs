//! 8-node curved shell quadrilateral (CQUAD8, S8, S8R): the MITC9 shell with its centre node
//! condensed statically; 6 dofs per node. An element the ANSYS importer made of a SHELL281
//! (`Model::ansys_shell281`) is formed by [`super::shell281`] instead.
//!
//! ```text
//!  4 ── 7 ── 3      s        corners (±1, ±1), mid-sides 5 (0,−1), 6 (1,0), 7 (0,1), 8 (−1,0)
//!  │         │      ↑        (Abaqus and Nastran order); the internal node 9 at (0, 0) sits at
//!  8    9    6      └─► r    the serendipity centre Σ N_a(0,0) x_a (its thickness likewise), so
//!  │         │               the 9-node geometry is the 8-node one exactly.
//!  1 ── 5 ── 2
//! ```
//! * MITC9: Bucalem & Bathe, *IJNME* 36 (1993) 3729 — the continuum shell of
//!   [`super::curved_shell`] on the 9-node Lagrangian field with assumed covariant strains:
//!   e_rr and e_rζ tied at r = ±a, s ∈ {−b, 0, b} (linear in r, quadratic in s), e_ss and e_sζ
//!   the same with r ↔ s, e_rs at (±a, ±a) (bilinear); a = 1/√3, b = √(3/5); 3×3 Gauss. Free
//!   of shear and membrane locking, no spurious zero-energy mode (a free element has the 6
//!   rigid motions only).
//! * The centre node carries no load and no mass: its 6 dofs are condensed statically, so an
//!   8-node mesh is exactly a MITC9 mesh whose centre nodes are free (static), and joins the
//!   8-node edges of its neighbours conformingly.
//! * Mass: the 8-node serendipity functions, 3×3 Gauss (curved_shell.rs; lumped by HRZ: a flat
//!   rectangle of constant thickness puts 3/76 of its mass on each corner, 4/19 on each mid-side,
//!   the consistent diagonal's ratio 6 : 32; rotations about the nodal normal).

use super::curved_shell::{self, shape8, Lamina};
use super::element::{
    Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::shell::ShellProps;
use super::{ElementError, Xyz};
use crate::fe::shell_section;

/// Reference points of the 9 nodes.
const REF: [[f64; 2]; 9] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
    [0.0, 0.0],
];
/// MITC9 tying coordinates a = 1/√3, b = √(3/5).
const A: f64 = 0.577_350_269_189_625_8;
const B: f64 = 0.774_596_669_241_483_4;

/// 1D quadratic Lagrange values and derivatives at −1, 0, 1.
fn lag3(x: f64) -> ([f64; 3], [f64; 3]) {
    (
        [0.5 * x * (x - 1.0), 1.0 - x * x, 0.5 * x * (x + 1.0)],
        [x - 0.5, -2.0 * x, x + 0.5],
    )
}

/// Index −1, 0, 1 → 0, 1, 2.
fn idx(c: f64) -> usize {
    (c + 1.0).round() as usize
}

/// 9-node Lagrangian shape functions (node order of `REF`).
fn shape9(r: f64, s: f64) -> (Vec<f64>, Vec<[f64; 2]>) {
    let (lr, dr) = lag3(r);
    let (ls, ds) = lag3(s);
    let mut n = Vec::with_capacity(9);
    let mut d = Vec::with_capacity(9);
    for p in REF {
        let (i, j) = (idx(p[0]), idx(p[1]));
        n.push(lr[i] * ls[j]);
        d.push([dr[i] * ls[j], lr[i] * ds[j]]);
    }
    (n, d)
}

/// 3×3 Gauss rule on [−1, 1]².
fn gauss3x3() -> Vec<([f64; 2], f64)> {
    let g = [(-B, 5.0 / 9.0), (0.0, 8.0 / 9.0), (B, 5.0 / 9.0)];
    g.iter()
        .flat_map(|&(r, wr)| g.iter().map(move |&(s, ws)| ([r, s], wr * ws)))
        .collect()
}

/// The 16 MITC9 tying points: 6 of e_rr/e_rζ, 6 of e_ss/e_sζ, 4 of e_rs (module doc).
fn tying_points() -> Vec<[f64; 2]> {
    let mut p = Vec::with_capacity(16);
    for r in [-A, A] {
        for s in [-B, 0.0, B] {
            p.push([r, s]);
        }
    }
    for s in [-A, A] {
        for r in [-B, 0.0, B] {
            p.push([r, s]);
        }
    }
    for r in [-A, A] {
        for s in [-A, A] {
            p.push([r, s]);
        }
    }
    p
}

/// Linear Lagrange through ±a, quadratic through −b, 0, b.
fn lin_a(x: f64) -> [f64; 2] {
    [(A - x) / (2.0 * A), (A + x) / (2.0 * A)]
}
fn quad_b(x: f64) -> [f64; 3] {
    [
        x * (x - B) / (2.0 * B * B),
        (B * B - x * x) / (B * B),
        x * (x + B) / (2.0 * B * B),
    ]
}

/// MITC9 weights at (r, s) (curved_shell::Weights).
fn weights(r: f64, s: f64) -> Vec<[[f64; 5]; 5]> {
    let mut w = vec![[[0.0; 5]; 5]; 16];
    let (lr, ls) = (lin_a(r), lin_a(s));
    let (qr, qs) = (quad_b(r), quad_b(s));
    for i in 0..2 {
        for j in 0..3 {
            // e_rr, e_rζ: points 0..6 at (±a, {−b, 0, b})
            let v = lr[i] * qs[j];
            w[3 * i + j][0][0] = v;
            w[3 * i + j][3][3] = v;
            // e_ss, e_sζ: points 6..12 at ({−b, 0, b}, ±a)
            let v = ls[i] * qr[j];
            w[6 + 3 * i + j][1][1] = v;
            w[6 + 3 * i + j][4][4] = v;
        }
        for j in 0..2 {
            w[12 + 2 * i + j][2][2] = lr[i] * ls[j];
        }
    }
    w
}

/// The 9-node lamina: the 8 nodes and the serendipity centre.
fn nine(x: &[Xyz; 8], t: &[f64; 8]) -> ([Xyz; 9], [f64; 9]) {
    let (n0, _) = shape8(0.0, 0.0);
    let mut xc = [0.0; 3];
    let mut tc = 0.0;
    for a in 0..8 {
        for i in 0..3 {
            xc[i] += n0[a] * x[a][i];
        }
        tc += n0[a] * t[a];
    }
    (
        std::array::from_fn(|a| if a < 8 { x[a] } else { xc }),
        std::array::from_fn(|a| if a < 8 { t[a] } else { tc }),
    )
}

/// Basic-frame stiffness and mass (48×48 each, node-major `[u v w θx θy θz]`) with nodal
/// thicknesses `t` (the section's other constants from `props`).
pub fn matrices(
    x: &[Xyz; 8],
    t: &[f64; 8],
    props: &ShellProps,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    props.check()?;
    let (x9, t9) = nine(x, t);
    let lam9 = Lamina::new(&x9, &t9, shape9, &REF)?;
    let rule = gauss3x3();
    let k9 = curved_shell::stiffness(&lam9, &tying_points(), &weights, &rule, props)?;
    let k = super::dense::condense(&k9, 48, 6, "internal-node stiffness")?;
    let lam8 = Lamina::new(x, t, shape8, &REF[..8])?;
    let m = curved_shell::mass(&lam8, &rule, props, lumped)?;
    Ok((k, m))
}

/// Area of the element's mid-surface (3×3 Gauss).
pub fn area(x: &[Xyz; 8]) -> Result<f64, ElementError> {
    let t = [1.0; 8];
    let lam = Lamina::new(x, &t, shape8, &REF[..8])?;
    curved_shell::area(&lam, &gauss3x3())
}

/// The 8-node curved shell as an [`Element`].
pub struct Quad8Element;

impl Element for Quad8Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let (p, t) = shell_section::curved_shell_props::<8>(input)?;
        let (k, m) = match input.model.ansys_shell281.get(&input.index) {
            Some(sec) => {
                super::shell281::matrices(&input.coords::<8>(), p.t, &p, sec, input.lumped())?
            }
            None => matrices(&input.coords::<8>(), &t, &p, input.lumped())?,
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

#[cfg(test)]
mod tests {
    use super::super::curved_shell::test_util::*;
    use super::super::shell::test_util::*;
    use super::super::Isotropic;
    use super::*;

    fn steel(t: f64) -> ShellProps {
        ShellProps::isotropic(t, Isotropic::new(210e9, 0.3, 7850.0))
    }

    /// A distorted flat quadrilateral, straight edges, mid-side nodes at their middles (the
    /// MacNeal–Harder patch of quadratic elements: a bilinear map).
    fn distorted() -> [Xyz; 8] {
        let c = [[0.0, 0.0], [2.0, 0.3], [2.4, 1.9], [0.2, 1.2]];
        let along = [0.5; 4];
        std::array::from_fn(|a| {
            if a < 4 {
                [c[a][0], c[a][1], 0.0]
            } else {
                let (i, j) = (a - 4, (a - 3) % 4);
                let f = along[i];
                [
                    c[i][0] + f * (c[j][0] - c[i][0]),
                    c[i][1] + f * (c[j][1] - c[i][1]),
                    0.0,
                ]
            }
        })
    }

    /// A doubly curved element on a sphere of radius 2.
    fn curved() -> [Xyz; 8] {
        std::array::from_fn(|a| {
            let p = REF[a];
            let (u, v) = (0.4 * p[0] + 0.05 * p[1] * p[1], 0.3 * p[1]);
            [
                2.0 * u.sin() * v.cos(),
                2.0 * v.sin(),
                2.0 * u.cos() * v.cos(),
            ]
        })
    }

    #[test]
    fn quad8_serendipity_shapes_partition_unity_and_derivatives() {
        check_shape2(shape8, &REF[..8]);
        check_shape2(shape9, &REF);
    }

    #[test]
    fn quad8_shell_rigid_motions_cost_no_energy_on_curved_element() {
        let x = curved();
        let t = [0.02, 0.03, 0.025, 0.02, 0.021, 0.022, 0.03, 0.026];
        let (k, _) = matrices(&x, &t, &steel(0.02), false).unwrap();
        for mode in 0..6 {
            let u = rigid(&x, mode);
            let res = residual(&k, &u);
            assert!(res < 1e-10, "mode {mode}: {res}");
        }
    }

    /// Constant membrane strain and curvature: uᵀKu = A(εᵀD_mε + κᵀD_bκ) on a distorted element.
    #[test]
    fn quad8_shell_patch_test_constant_strain_and_curvature_on_distorted_element() {
        let x = distorted();
        let props = steel(0.02);
        let (k, _) = matrices(&x, &[0.02; 8], &props, false).unwrap();
        patch_energy(&k, &x, area(&x).unwrap(), &props, 1e-8);
    }

    #[test]
    fn quad8_shell_free_element_has_six_zero_modes() {
        for (x, t) in [(distorted(), 0.01), (curved(), 0.05)] {
            let (k, _) = matrices(&x, &[t; 8], &steel(t), false).unwrap();
            assert_eq!(zero_modes(&k), 6);
        }
    }

    #[test]
    fn quad8_shell_mass_totals_and_hrz_lumping() {
        let x = distorted();
        let props = ShellProps {
            nsm: 0.5,
            ..steel(0.01)
        };
        let a = area(&x).unwrap();
        mass_totals(
            &matrices(&x, &[0.01; 8], &props, false).unwrap().1,
            a,
            &props,
        );
        let m = matrices(&x, &[0.01; 8], &props, true).unwrap().1;
        mass_totals(&m, a, &props);
        // rectangle: corners 3/76, mid-sides 4/19 of the mass (HRZ of the serendipity element)
        let rect: [Xyz; 8] = std::array::from_fn(|i| [REF[i][0] + 1.0, 0.5 * REF[i][1], 0.0]);
        let m = matrices(&rect, &[0.01; 8], &steel(0.01), true).unwrap().1;
        let total = 2.0 * 7850.0 * 0.01;
        for a in 0..8 {
            let want = if a < 4 {
                total * 3.0 / 76.0
            } else {
                total * 4.0 / 19.0
            };
            assert!(
                (m[6 * a * 48 + 6 * a] - want).abs() < 1e-12 * total,
                "{a}: {} vs {want}",
                m[6 * a * 48 + 6 * a]
            );
        }
    }
}
