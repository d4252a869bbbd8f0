//! 2-node rod (CROD, T3D2 with torsion): axial and torsional stiffness only.
//!
//! ```text
//!   1 ────────── 2     local x = (x2 − x1)/L; dofs per node [ux uy uz rx ry rz] (basic)
//! ```
//! K = EA/L (e_x e_xᵀ) ⊗ [1 −1; −1 1] on translations + GJ/L (e_x e_xᵀ) ⊗ [1 −1; −1 1] on
//! rotations (Przemieniecki, *Theory of Matrix Structural Analysis* (1968) §5.2).
//! Consistent mass: m/6·[2 1; 1 2] ⊗ I₃ on translations (Nastran CROD coupled mass) plus
//! ρJL/6·[2 1; 1 2] (e_x e_xᵀ) on rotations; lumped: m/2·I₃ and ρJL/2 (e_x e_xᵀ).

use super::beam::local_frame;
use super::element::{
    Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{ElementError, Isotropic, Xyz};
use crate::model::Section;

/// Basic-frame stiffness and mass (12×12, 6 dofs per node) of a rod.
pub fn matrices(
    x: &[Xyz; 2],
    mat: &Isotropic,
    area: f64,
    j: f64,
    nsm: f64,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    if !(mat.e > 0.0 && mat.g > 0.0 && area > 0.0 && j >= 0.0 && mat.rho >= 0.0 && nsm >= 0.0) {
        return Err(ElementError::BadConstants(format!(
            "rod needs E, G, A > 0 and J, ρ, nsm ≥ 0 (E = {}, A = {area}, J = {j})",
            mat.e
        )));
    }
    let ([ex, _, _], l) = local_frame(x, None)?;
    let ea = mat.e * area / l;
    let gj = mat.g * j / l;
    let mass = (mat.rho * area + nsm) * l;
    let tors = mat.rho * j * l;
    let mut k = vec![0.0; 144];
    let mut m = vec![0.0; 144];
    let pair = [[1.0, -1.0], [-1.0, 1.0]];
    let (mc, ml) = ([[2.0, 1.0], [1.0, 2.0]], [[3.0, 0.0], [0.0, 3.0]]);
    let mm = if lumped { ml } else { mc };
    for a in 0..2 {
        for b in 0..2 {
            for i in 0..3 {
                for jj in 0..3 {
                    let pp = ex[i] * ex[jj];
                    k[(6 * a + i) * 12 + 6 * b + jj] += ea * pair[a][b] * pp;
                    k[(6 * a + 3 + i) * 12 + 6 * b + 3 + jj] += gj * pair[a][b] * pp;
                    m[(6 * a + 3 + i) * 12 + 6 * b + 3 + jj] += tors / 6.0 * mm[a][b] * pp;
                }
                m[(6 * a + i) * 12 + 6 * b + i] += mass / 6.0 * mm[a][b];
            }
        }
    }
    Ok((k, m))
}

/// The 2-node rod (axial and torsion) as an [`Element`].
pub struct RodElement;

impl Element for RodElement {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let (area, j, nsm) = match &input.property.section {
            Section::Rod { area, j, nsm } => (*area, *j, *nsm),
            _ => {
                return Err(MatricesError::Unsupported(format!(
                    "rod element with non-rod property {}",
                    input.property.id
                )))
            }
        };
        let x = input.coords::<2>();
        let (k, m) = matrices(&x, &input.iso, area, j, nsm, input.lumped())?;
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
    use super::*;

    #[test]
    fn rod_axial_stiffness_and_mass_total() {
        let mat = Isotropic::new(70e9, 0.33, 2700.0);
        let x = [[0.0, 0.0, 0.0], [0.3, 0.4, 0.0]];
        let (k, m) = matrices(&x, &mat, 1e-4, 2e-9, 0.0, false).unwrap();
        // Pull node 2 along the axis by 1: force EA/L along the axis.
        let u = [0.6, 0.8, 0.0];
        let f: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| k[(6 + i) * 12 + 6 + j] * u[j]).sum())
            .collect();
        let ea_l = 70e9 * 1e-4 / 0.5;
        for i in 0..3 {
            assert!((f[i] - ea_l * u[i]).abs() < 1e-9 * ea_l);
        }
        // Total translational mass in x is ρAL.
        let mx: f64 = (0..2)
            .flat_map(|a| (0..2).map(move |b| (a, b)))
            .map(|(a, b)| m[(6 * a) * 12 + 6 * b])
            .sum();
        assert!((mx - 2700.0 * 1e-4 * 0.5).abs() < 1e-15);
    }
}
