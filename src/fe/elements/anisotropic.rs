//! Solid elements with a general elasticity D (orthotropic or anisotropic materials,
//! [`crate::model::elasticity`]): K = Σ_p w_p Bᵀ D(x_p) B over each element's own rule (the
//! rules of the isotropic kernels), D rotated from the material axes at each integration point
//! x_p (so cylindrical axes follow the point, as CalculiX evaluates them); incompatible modes
//! condensed as in [`super::solid_incompatible`]. The isotropic elements keep their Lamé
//! kernels.

use super::element::SolidRules;
use super::solid_incompatible::{condense, full_stiffness_d};
use super::{kinds, ElementError, Xyz};
use crate::model::elasticity::{rotate, Stiffness6};
use crate::model::{ElementKind, MaterialAxes};

/// Stiffness (3N×3N, row-major) of a solid of `kind` through `x` with the material stiffness
/// `d` in the material `axes` (basic axes when `None`); `Ok(None)` for a kind without a
/// general-D formulation (module doc); `rules`: the model's ([`SolidRules::of`]).
pub fn stiffness(
    kind: ElementKind,
    x: &[Xyz],
    rules: SolidRules,
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
    let Some(points) = kinds::element(kind).stiffness_points(x, rules)? else {
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
    use crate::fe::elements::{hex8, solid_incompatible, Isotropic};
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
                stiffness(ElementKind::Hex8, &x, SolidRules::default(), &d, None)
                    .unwrap()
                    .unwrap(),
            ),
            (
                solid_incompatible::hex8_stiffness(&x, &mat).unwrap(),
                stiffness(
                    ElementKind::Hex8,
                    &x,
                    SolidRules {
                        incompatible: true,
                        ..SolidRules::default()
                    },
                    &d,
                    None,
                )
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
        let turned = stiffness(
            ElementKind::Hex8,
            &x,
            SolidRules::default(),
            &d,
            Some(&axes),
        )
        .unwrap()
        .unwrap();
        let want = hex8::stiffness(&x, &mat).unwrap();
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in want.iter().zip(&turned) {
            assert!((a - b).abs() < 1e-12 * scale);
        }
        assert!(
            stiffness(ElementKind::Hex8R, &x, SolidRules::default(), &d, None)
                .unwrap()
                .is_none()
        );
    }
}
