//! Solid elements with a general elasticity D (orthotropic or anisotropic materials,
//! [`crate::model::elasticity`]): K = Σ_p w_p Bᵀ D(x_p) B over each element's own rule (the
//! rules of the isotropic kernels), D rotated from the material axes at each integration point
//! x_p (so cylindrical axes follow the point, as CalculiX evaluates them); incompatible modes
//! condensed as in [`super::solid_incompatible`]. The isotropic elements keep their Lamé
//! kernels.

use super::solid_incompatible::{
    condense, full_stiffness_d, hex8_points, mode_points_compatible, prism6_points, ModePoint,
};
use super::{hex20, hex8, prism6, pyram13, pyram5, tet10, tet4, ElementError, Xyz};
use crate::fe::quadrature;
use crate::model::elasticity::{rotate, Stiffness6};
use crate::model::{ElementKind, MaterialAxes};

/// The integration points of a solid of `kind` through `x` (model node order), with the
/// incompatible modes of hex8 and prism6 when `incompatible`; `None` for a kind without a
/// general-D formulation (C3D8R: its hourglass control is isotropic).
fn points(
    kind: ElementKind,
    x: &[Xyz],
    incompatible: bool,
    ccx_rules: bool,
) -> Result<Option<Vec<ModePoint>>, ElementError> {
    fn arr<const N: usize>(x: &[Xyz]) -> [Xyz; N] {
        std::array::from_fn(|a| x[a])
    }
    Ok(Some(match kind {
        ElementKind::Tet4 => {
            mode_points_compatible(&arr::<4>(x), tet4::shape, &quadrature::tet1())?
        }
        ElementKind::Tet10 => {
            mode_points_compatible(&arr::<10>(x), tet10::shape, &quadrature::tet4())?
        }
        ElementKind::Hex8 if incompatible => hex8_points(&arr::<8>(x))?,
        ElementKind::Hex8 => {
            mode_points_compatible(&arr::<8>(x), hex8::shape, &quadrature::cube(2))?
        }
        ElementKind::Hex20 => {
            mode_points_compatible(&arr::<20>(x), hex20::shape, &quadrature::cube(3))?
        }
        ElementKind::Hex20R => {
            mode_points_compatible(&arr::<20>(x), hex20::shape, &quadrature::cube(2))?
        }
        ElementKind::Prism6 if incompatible => prism6_points(&arr::<6>(x))?,
        ElementKind::Prism6 if ccx_rules => {
            mode_points_compatible(&arr::<6>(x), prism6::shape, &quadrature::wedge_centroid())?
        }
        ElementKind::Prism6 => {
            mode_points_compatible(&arr::<6>(x), prism6::shape, &quadrature::wedge(2))?
        }
        ElementKind::Pyram5 => {
            mode_points_compatible(&arr::<5>(x), pyram5::shape, &quadrature::cube(3))?
        }
        ElementKind::Pyram13 => {
            mode_points_compatible(&arr::<13>(x), pyram13::shape, &quadrature::cube(4))?
        }
        _ => return Ok(None),
    }))
}

/// Stiffness (3N×3N, row-major) of a solid of `kind` through `x` with the material stiffness
/// `d` in the material `axes` (basic axes when `None`); `Ok(None)` for a kind without a
/// general-D formulation (module doc). `ccx_rules`: CalculiX's two-point C3D6
/// (`ModelParams::ccx_solid_rules`).
pub fn stiffness(
    kind: ElementKind,
    x: &[Xyz],
    incompatible: bool,
    ccx_rules: bool,
    d: &Stiffness6,
    axes: Option<&MaterialAxes>,
) -> Result<Option<Vec<f64>>, ElementError> {
    if x.len() != kind.node_count() {
        return Err(ElementError::BadConstants(format!(
            "{kind:?} needs {} nodes, got {}",
            kind.node_count(),
            x.len()
        )));
    }
    let Some(points) = points(kind, x, incompatible, ccx_rules)? else {
        return Ok(None);
    };
    let at_point = |p: usize| -> Stiffness6 {
        match axes {
            None => *d,
            Some(axes) => {
                let pos: Xyz = std::array::from_fn(|i| {
                    (points[p].n.iter().zip(x)).map(|(n, xa)| n * xa[i]).sum()
                });
                rotate(d, &axes.at(&pos))
            }
        }
    };
    let k = full_stiffness_d(&points, &at_point);
    let nc = 3 * x.len();
    let nt = 3 * points[0].grads.len();
    Ok(Some(if nt > nc {
        condense(&k, nc, nt - nc)?
    } else {
        k
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::{solid_incompatible, Isotropic};
    use crate::model::elasticity::isotropic;

    fn hex() -> [Xyz; 8] {
        let mut x = hex8::NODES.map(|p| [1.0 + 0.5 * p[0], 0.3 * p[1], 0.2 + 0.4 * p[2]]);
        x[6][0] += 0.07;
        x[1][2] -= 0.03;
        x
    }

    /// With the isotropic D the general kernel gives the Lamé kernel's K (to rounding), for
    /// the compatible and the incompatible hexahedron and the tet10.
    #[test]
    fn general_kernel_with_isotropic_d_equals_lame_kernel() {
        let mat = Isotropic::new(210e9, 0.3, 7850.0);
        let (lam, mu) = mat.lame();
        let d = isotropic(lam, mu);
        let x = hex();
        let pairs = [
            (
                hex8::stiffness(&x, &mat).unwrap(),
                stiffness(ElementKind::Hex8, &x, false, false, &d, None)
                    .unwrap()
                    .unwrap(),
            ),
            (
                solid_incompatible::hex8_stiffness(&x, &mat).unwrap(),
                stiffness(ElementKind::Hex8, &x, true, false, &d, None)
                    .unwrap()
                    .unwrap(),
            ),
        ];
        for (want, got) in pairs {
            let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (a, b) in want.iter().zip(&got) {
                assert!((a - b).abs() < 1e-12 * scale);
            }
        }
        // any rotation of an isotropic D is the same D
        let axes = MaterialAxes::Cylindrical {
            a: [0.0; 3],
            b: [0.2, 1.0, 0.1],
        };
        let turned = stiffness(ElementKind::Hex8, &x, false, false, &d, Some(&axes))
            .unwrap()
            .unwrap();
        let want = hex8::stiffness(&x, &mat).unwrap();
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in want.iter().zip(&turned) {
            assert!((a - b).abs() < 1e-12 * scale);
        }
        assert!(stiffness(ElementKind::Hex8R, &x, false, false, &d, None)
            .unwrap()
            .is_none());
    }
}
