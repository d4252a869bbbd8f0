//! 6-node curved shell triangle (CTRIA6, S6): a MITC6 continuum shell; 6 dofs per node.
//!
//! ```text
//!  3 (0,1)          r, s: area coordinates L₂, L₃ (L₁ = 1 − r − s); mid-side nodes 4 (1–2),
//!  │ \              5 (2–3), 6 (3–1) (Abaqus and Nastran order); quadratic Lagrange functions.
//!  6   5
//!  │     \
//!  1 ── 4 ── 2
//! ```
//! * MITC6, after Lee & Bathe, *Comput. Struct.* 82 (2004) 945 (the continuum shell of
//!   [`super::curved_shell`]):
//!   - transverse shear (e_rζ, e_sζ): the assumed field of the second-order rotated
//!     Raviart–Thomas (Nédélec) space, ẽ_rζ = a₁ + b₁r + c₁s − s(dr + es),
//!     ẽ_sζ = a₂ + b₂r + c₂s + r(dr + es), tied to the tangential covariant shear at the two
//!     Gauss points of each edge (e_rζ on s = 0, e_sζ on r = 0, e_sζ − e_rζ on r + s = 1) and to
//!     e_rζ, e_sζ at the centroid — in the manner of Lee & Bathe's MITC6a (these tying points
//!     are ours: the edges' Gauss points and the centroid, not checked against the paper's
//!     table); the tangential edge strains are shared by neighbours, which is what frees the
//!     element of shear locking;
//!   - in-plane strains, the same way along the edges (MITC6a): the normal strains along the
//!     three edge tangents, e_rr, e_ss and e_qq = e_rr − 2e_rs + e_ss, each linear through its
//!     values at the edge's two Gauss points and the centroid, e_rs = ½(e_rr + e_ss − e_qq):
//!     exact for a flat straight-sided element (whose strains are linear), and on curved ones
//!     the relief of membrane locking;
//! * 6-point (degree 4) rule for stiffness and mass; drilling as the quadrilateral.
//! * Mass: HRZ lumping (curved_shell.rs): a flat straight-sided triangle of constant thickness
//!   with centred mid-side nodes puts 3/57 of its mass on each corner and 16/57 on each mid-side
//!   (consistent diagonal 6/180 and 32/180 of the mass).

use super::curved_shell::{self, Lamina};
use super::dense::solve_dense;
use super::element::{
    Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::shell::ShellProps;
use super::{ElementError, Xyz};
use crate::fe::shell_section;

/// Reference points of the 6 nodes.
const REF: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];

/// Quadratic triangle shape functions.
fn shape6(r: f64, s: f64) -> (Vec<f64>, Vec<[f64; 2]>) {
    let l1 = 1.0 - r - s;
    (
        vec![
            l1 * (2.0 * l1 - 1.0),
            r * (2.0 * r - 1.0),
            s * (2.0 * s - 1.0),
            4.0 * l1 * r,
            4.0 * r * s,
            4.0 * s * l1,
        ],
        vec![
            [1.0 - 4.0 * l1, 1.0 - 4.0 * l1],
            [4.0 * r - 1.0, 0.0],
            [0.0, 4.0 * s - 1.0],
            [4.0 * (l1 - r), -4.0 * r],
            [4.0 * s, 4.0 * r],
            [-4.0 * s, 4.0 * (l1 - s)],
        ],
    )
}

/// Dunavant's 6-point rule (degree 4) on the reference triangle (weights sum to ½).
fn rule6() -> Vec<([f64; 2], f64)> {
    const A: f64 = 0.445_948_490_915_965;
    const WA: f64 = 0.223_381_589_678_011;
    const B: f64 = 0.091_576_213_509_771;
    const WB: f64 = 0.109_951_743_655_322;
    let mut r = Vec::with_capacity(6);
    for (a, w) in [(A, WA), (B, WB)] {
        let c = 1.0 - 2.0 * a;
        for p in [[a, a], [c, a], [a, c]] {
            r.push((p, 0.5 * w));
        }
    }
    r
}

/// Edge Gauss points on [0, 1].
const G1: f64 = 0.5 - 0.288_675_134_594_812_9;
const G2: f64 = 0.5 + 0.288_675_134_594_812_9;
/// Tying points: s = 0 edge ×2, hypotenuse ×2, r = 0 edge ×2, centroid.
const POINTS: [[f64; 2]; 7] = [
    [G1, 0.0],
    [G2, 0.0],
    [G2, G1],
    [G1, G2],
    [0.0, G1],
    [0.0, G2],
    [1.0 / 3.0, 1.0 / 3.0],
];

/// The tying points of the in-plane strains along each edge's tangent: e_rr on s = 0, e_ss on
/// r = 0, e_qq = e_rr − 2e_rs + e_ss on r + s = 1, each with the centroid.
const EDGE_POINTS: [[usize; 3]; 3] = [[0, 1, 6], [4, 5, 6], [2, 3, 6]];

/// Weights of the linear function through the values at points p₀, p₁, p₂, at (r, s).
fn linear3(p: [[f64; 2]; 3], r: f64, s: f64) -> [f64; 3] {
    let det = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    let l1 = ((r - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (s - p[0][1])) / det;
    let l2 = ((p[1][0] - p[0][0]) * (s - p[0][1]) - (r - p[0][0]) * (p[1][1] - p[0][1])) / det;
    [1.0 - l1 - l2, l1, l2]
}

/// The 8 basis fields (ẽ_rζ, ẽ_sζ) of the assumed shear space at (r, s).
fn shear_basis(r: f64, s: f64) -> [[f64; 2]; 8] {
    [
        [1.0, 0.0],
        [r, 0.0],
        [s, 0.0],
        [0.0, 1.0],
        [0.0, r],
        [0.0, s],
        [-s * r, r * r],
        [-s * s, r * s],
    ]
}

/// The 8 shear tying functionals: (tying point index among the shear points, coefficients on
/// (e_rζ, e_sζ)).
const FUNCTIONALS: [(usize, [f64; 2]); 8] = [
    (0, [1.0, 0.0]),
    (1, [1.0, 0.0]),
    (2, [-1.0, 1.0]),
    (3, [-1.0, 1.0]),
    (4, [0.0, 1.0]),
    (5, [0.0, 1.0]),
    (6, [1.0, 0.0]),
    (6, [0.0, 1.0]),
];

/// A⁻¹ of the shear interpolation: A[q][m] = functional q of basis field m (8×8).
fn shear_inverse() -> Result<Vec<f64>, ElementError> {
    let pts = &POINTS;
    let mut a = vec![0.0; 64];
    for (q, &(p, c)) in FUNCTIONALS.iter().enumerate() {
        let b = shear_basis(pts[p][0], pts[p][1]);
        for m in 0..8 {
            a[q * 8 + m] = c[0] * b[m][0] + c[1] * b[m][1];
        }
    }
    let mut inv: Vec<f64> = (0..64)
        .map(|q| f64::from(u8::from(q / 8 == q % 8)))
        .collect();
    solve_dense(&mut a, 8, &mut inv, 8).ok_or_else(|| {
        ElementError::BadConstants("MITC6 shear interpolation is singular".into())
    })?;
    Ok(inv)
}

/// MITC6 weights at (r, s) (curved_shell::Weights) from the shear inverse `inv`.
fn weights(inv: &[f64], r: f64, s: f64) -> Vec<[[f64; 5]; 5]> {
    let mut w = vec![[[0.0; 5]; 5]; 7];
    // in-plane: ẽ_rr, ẽ_ss, ẽ_qq linear; ẽ_rs = ½(ẽ_rr + ẽ_ss − ẽ_qq)
    for (edge, idx) in EDGE_POINTS.iter().enumerate() {
        let l = linear3(idx.map(|p| POINTS[p]), r, s);
        for (c, &p) in idx.iter().enumerate() {
            let v = l[c];
            match edge {
                0 => {
                    w[p][0][0] += v;
                    w[p][2][0] += 0.5 * v;
                }
                1 => {
                    w[p][1][1] += v;
                    w[p][2][1] += 0.5 * v;
                }
                _ => {
                    w[p][2][0] -= 0.5 * v;
                    w[p][2][1] -= 0.5 * v;
                    w[p][2][2] += v;
                }
            }
        }
    }
    let b = shear_basis(r, s);
    for (q, &(p, c)) in FUNCTIONALS.iter().enumerate() {
        for comp in 0..2 {
            // ẽ_comp = Σ_m b_m,comp Σ_q A⁻¹[m][q] ℓ_q
            let f: f64 = (0..8).map(|m| b[m][comp] * inv[m * 8 + q]).sum();
            w[p][3 + comp][3] += f * c[0];
            w[p][3 + comp][4] += f * c[1];
        }
    }
    w
}

/// Basic-frame stiffness and mass (36×36 each, node-major `[u v w θx θy θz]`) with nodal
/// thicknesses `t` (the section's other constants from `props`).
pub fn matrices(
    x: &[Xyz; 6],
    t: &[f64; 6],
    props: &ShellProps,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    props.check()?;
    let lam = Lamina::new(x, t, shape6, &REF)?;
    let rule = rule6();
    let inv = shear_inverse()?;
    let w = |r: f64, s: f64| weights(&inv, r, s);
    let k = curved_shell::stiffness(&lam, &POINTS, &w, &rule, props)?;
    let m = curved_shell::mass(&lam, &rule, props, lumped)?;
    Ok((k, m))
}

/// Area of the element's mid-surface (6-point rule).
pub fn area(x: &[Xyz; 6]) -> Result<f64, ElementError> {
    let t = [1.0; 6];
    let lam = Lamina::new(x, &t, shape6, &REF)?;
    curved_shell::area(&lam, &rule6())
}

/// The 6-node curved shell as an [`Element`].
pub struct Tri6Element;

impl Element for Tri6Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let (p, t) = shell_section::curved_shell_props::<6>(input)?;
        let (k, m) = matrices(&input.coords::<6>(), &t, &p, input.lumped())?;
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

    /// A distorted flat triangle, mid-side nodes at the edge middles (an affine map).
    fn distorted() -> [Xyz; 6] {
        let c = [[0.0, 0.0], [2.0, 0.3], [0.7, 1.6]];
        let along = [0.5; 3];
        std::array::from_fn(|a| {
            if a < 3 {
                [c[a][0], c[a][1], 0.0]
            } else {
                let (i, j) = (a - 3, (a - 2) % 3);
                let f = along[i];
                [
                    c[i][0] + f * (c[j][0] - c[i][0]),
                    c[i][1] + f * (c[j][1] - c[i][1]),
                    0.0,
                ]
            }
        })
    }

    fn curved() -> [Xyz; 6] {
        std::array::from_fn(|a| {
            let p = REF[a];
            let (u, v) = (0.5 * p[0] + 0.05 * p[1] * p[1], 0.4 * p[1]);
            [
                2.0 * u.sin() * v.cos(),
                2.0 * v.sin(),
                2.0 * u.cos() * v.cos(),
            ]
        })
    }

    #[test]
    fn tri6_shapes_partition_unity_and_derivatives() {
        check_shape2(shape6, &REF);
        let w: f64 = rule6().iter().map(|p| p.1).sum();
        assert!((w - 0.5).abs() < 1e-14);
    }

    #[test]
    fn tri6_shell_rigid_motions_cost_no_energy_on_curved_element() {
        let x = curved();
        let t = [0.02, 0.03, 0.025, 0.02, 0.021, 0.022];
        let (k, _) = matrices(&x, &t, &steel(0.02), false).unwrap();
        for mode in 0..6 {
            let res = residual(&k, &rigid(&x, mode));
            assert!(res < 1e-10, "mode {mode}: {res}");
        }
    }

    #[test]
    fn tri6_shell_patch_test_constant_strain_and_curvature_on_distorted_element() {
        let x = distorted();
        let props = steel(0.02);
        let (k, _) = matrices(&x, &[0.02; 6], &props, false).unwrap();
        patch_energy(&k, &x, area(&x).unwrap(), &props, 1e-8);
    }

    #[test]
    fn tri6_shell_free_element_has_six_zero_modes() {
        for (x, t) in [(distorted(), 0.01), (curved(), 0.05)] {
            let (k, _) = matrices(&x, &[t; 6], &steel(t), false).unwrap();
            assert_eq!(zero_modes(&k), 6);
        }
    }

    #[test]
    fn tri6_shell_mass_totals_and_hrz_lumping() {
        let x = distorted();
        let props = ShellProps {
            nsm: 0.5,
            ..steel(0.01)
        };
        let a = area(&x).unwrap();
        mass_totals(
            &matrices(&x, &[0.01; 6], &props, false).unwrap().1,
            a,
            &props,
        );
        let m = matrices(&x, &[0.01; 6], &props, true).unwrap().1;
        mass_totals(&m, a, &props);
        let x: [Xyz; 6] =
            std::array::from_fn(|i| [2.0 * REF[i][0] + 0.3 * REF[i][1], REF[i][1], 0.0]);
        let m = matrices(&x, &[0.01; 6], &props, true).unwrap().1;
        let total = area(&x).unwrap() * props.mass_per_area();
        for n in 0..6 {
            let want = if n < 3 { 3.0 / 57.0 } else { 16.0 / 57.0 } * total;
            assert!((m[6 * n * 36 + 6 * n] - want).abs() < 1e-12 * total, "{n}");
        }
    }
}
