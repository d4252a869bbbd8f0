//! ANSYS BEAM188 with linear shape functions (KEYOPT(3)=0, its default) as an [`Element`]: the
//! two-node Timoshenko beam of the MAPDL Theory Reference §13.188 — displacements and rotations
//! interpolated linearly (its equations 11–6…11–11), the stiffness on one point along the length
//! (the element's centre), the consistent mass on two points (exact for the linear functions)
//! with the section's rotary inertia, the lumped mass from the translations' functions only
//! (11–6…11–8: m/2 on each node's translations, no rotary inertia).
//!
//! ```text
//! local x = (x_J − x_I)/L, local y ⟂ x in the plane of the orientation vector (as `beam`),
//! local z = x × y; dofs per node [u v w θx θy θz]
//! strain energy, one point (ξ = ½):  ½ EA u'² L + ½ GJ θx'² L
//!     + ½ EI_z θz'² L + ½ k_y GA (v' − θz)² L      (bending in x–y)
//!     + ½ EI_y θy'² L + ½ k_z GA (w' + θy)² L      (bending in x–z)
//! ```
//! With one point the shear strain is the centre's, so the element does not lock; a cantilever
//! of one element under a tip load P deflects PL³/(4EI) + PL/(kGA) (the exact Timoshenko beam
//! `Beam2`: PL³/(3EI) + PL/(kGA)); n elements give PL³/(3EI)·(1 − 1/(4n²)) + PL/(kGA) (tests).

use super::beam::{self, BeamProps};
use super::element::{
    Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{ElementError, Isotropic, Xyz};
use crate::model::Section;

/// BEAM188, KEYOPT(3)=0.
pub struct Beam188Element;

impl Element for Beam188Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let p = ansys_section_props("BEAM188", input)?;
        let x = input.coords::<2>();
        let v = input.model.elements[input.index].orientation;
        let (k, m) = matrices(&x, v, &input.iso, &p, input.lumped())?;
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

/// The section of an ANSYS beam (BEAM188, BEAM189) as [`BeamProps`]: ANSYS's beams are
/// Timoshenko beams on principal axes, so a tapered section, a product of inertia I_yz ≠ 0 or
/// a section without shear factors is not formed (the importer refuses them first; this guards
/// a model built otherwise). `name` is the element's name in the messages.
pub(super) fn ansys_section_props(
    name: &str,
    input: &ElementInput,
) -> Result<BeamProps, MatricesError> {
    let unsupported = |m: String| Err(MatricesError::Unsupported(m));
    let Section::Beam(s) = &input.property.section else {
        return unsupported(format!(
            "{name} element with non-beam property {}",
            input.property.id
        ));
    };
    if s.taper.is_some() {
        return unsupported(format!("{name} with a tapered section: not formed here"));
    }
    if s.i12 != 0.0 {
        return unsupported(format!(
            "{name} with a product of inertia I_yz = {} ≠ 0: not formed here",
            s.i12
        ));
    }
    let Some(shear) = s.shear_factors else {
        return unsupported(format!(
            "{name} without shear factors: its stiffness needs the section's shear stiffness"
        ));
    };
    Ok(BeamProps {
        area: s.area,
        iz: s.i1,
        iy: s.i2,
        j: s.j,
        shear: Some(shear),
        nsm: s.nsm,
    })
}

/// Basic-frame stiffness and mass (12×12 each, row-major) of one element; `v` orients the
/// local y axis as for [`beam::local_frame`]; `p.shear` must hold (k_y, k_z).
pub fn matrices(
    x: &[Xyz; 2],
    v: Option<Xyz>,
    mat: &Isotropic,
    p: &BeamProps,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    beam::check(mat, p)?;
    let [ky, kz] = p.shear.ok_or_else(|| {
        ElementError::BadConstants("BEAM188 needs its shear factors k_y, k_z".into())
    })?;
    if !(ky > 0.0 && kz > 0.0) {
        return Err(ElementError::BadConstants(format!(
            "BEAM188 needs positive shear factors (k_y = {ky}, k_z = {kz})"
        )));
    }
    let v = v.ok_or(ElementError::BadOrientation { v: [0.0; 3] })?;
    let (r, l) = beam::local_frame(x, Some(v))?;
    let k = stiffness_local(l, mat, p, [ky, kz]);
    let m = if lumped {
        lumped_mass_local(l, mat, p)
    } else {
        consistent_mass_local(l, mat, p)
    };
    Ok((beam::to_basic(&k, &r), beam::to_basic(&m, &r)))
}

/// Local 12×12 stiffness on one point (module doc): EA/L, GJ/L, EI/L on the bending rotations
/// and k G A L b bᵀ with the centre's shear strain b = (−1/L, ∓½, 1/L, ∓½).
pub fn stiffness_local(l: f64, mat: &Isotropic, p: &BeamProps, k: [f64; 2]) -> [[f64; 12]; 12] {
    let mut out = [[0.0; 12]; 12];
    let ea = mat.e * p.area / l;
    let gj = mat.g * p.j / l;
    add_bar(&mut out, 0, 6, ea);
    add_bar(&mut out, 3, 9, gj);
    add_bar(&mut out, 5, 11, mat.e * p.iz / l);
    add_bar(&mut out, 4, 10, mat.e * p.iy / l);
    // γ_xy = v' − θz on (v1, θz1, v2, θz2); γ_xz = w' + θy on (w1, θy1, w2, θy2)
    for (dofs, s, kk) in [([1, 5, 7, 11], -0.5, k[0]), ([2, 4, 8, 10], 0.5, k[1])] {
        let b = [-1.0 / l, s, 1.0 / l, s];
        let c = kk * mat.g * p.area * l;
        for i in 0..4 {
            for j in 0..4 {
                out[dofs[i]][dofs[j]] += c * b[i] * b[j];
            }
        }
    }
    out
}

/// Local 12×12 consistent mass, exact for the linear functions (two points): (ρA + m_a)L/6 ·
/// [2 1; 1 2] on each translation, ρ(I_y + I_z)L/6 · [2 1; 1 2] on θx, ρI_y L/6, ρI_z L/6 on θy,
/// θz (m_a: the added mass per length, on the translations only).
pub fn consistent_mass_local(l: f64, mat: &Isotropic, p: &BeamProps) -> [[f64; 12]; 12] {
    let mut out = [[0.0; 12]; 12];
    let per_length = [
        mat.rho * p.area + p.nsm,
        mat.rho * p.area + p.nsm,
        mat.rho * p.area + p.nsm,
        mat.rho * (p.iy + p.iz),
        mat.rho * p.iy,
        mat.rho * p.iz,
    ];
    for (d, m) in per_length.iter().enumerate() {
        let a = m * l / 6.0;
        out[d][d] += 2.0 * a;
        out[d + 6][d + 6] += 2.0 * a;
        out[d][d + 6] += a;
        out[d + 6][d] += a;
    }
    out
}

/// Local 12×12 lumped mass: (ρA + m_a)L/2 on each node's translations, none on its rotations
/// (the Theory Reference's lumped mass uses the translations' functions only).
pub fn lumped_mass_local(l: f64, mat: &Isotropic, p: &BeamProps) -> [[f64; 12]; 12] {
    let mut out = [[0.0; 12]; 12];
    let half = 0.5 * (mat.rho * p.area + p.nsm) * l;
    for n in [0, 6] {
        for i in 0..3 {
            out[n + i][n + i] = half;
        }
    }
    out
}

/// c·[1 −1; −1 1] on dofs a, b.
fn add_bar(k: &mut [[f64; 12]; 12], a: usize, b: usize, c: f64) {
    k[a][a] += c;
    k[b][b] += c;
    k[a][b] -= c;
    k[b][a] -= c;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::shell::test_util::{residual, rigid};

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

    /// Six rigid motions give zero force on a skewed element.
    #[test]
    fn beam188_rigid_motions_are_free_of_force() {
        let x = [[0.1, 0.2, -0.3], [0.5, -0.1, 0.4]];
        let mat = Isotropic::new(210e9, 0.3, 7850.0);
        let (k, _) = matrices(&x, Some([0.0, 0.3, 1.0]), &mat, &props(), false).unwrap();
        for mode in 0..6 {
            let r = residual(&k, &rigid(&x, mode));
            assert!(r < 1e-12, "mode {mode}: {r}");
        }
    }

    /// One element, clamped at I, tip load along local y and z: PL³/(4EI) + PL/(kGA).
    #[test]
    fn beam188_one_element_cantilever_is_the_one_point_form() {
        let mat = Isotropic::new(200e9, 0.3, 0.0);
        let p = props();
        let l = 0.7;
        let k = stiffness_local(l, &mat, &p, [0.85, 0.8]);
        for (a, b, i, ks) in [(7, 11, p.iz, 0.85), (8, 10, p.iy, 0.8)] {
            let (kaa, kab, kbb) = (k[a][a], k[a][b], k[b][b]);
            let tip = kbb / (kaa * kbb - kab * kab);
            let want = l.powi(3) / (4.0 * mat.e * i) + l / (ks * mat.g * p.area);
            assert!((tip - want).abs() < 1e-12 * want, "{tip} {want}");
        }
    }
}
