//! ANSYS BEAM189 as an [`Element`]: the three-node Timoshenko beam of the MAPDL Theory Reference
//! §13.189 — displacements and rotations interpolated quadratically through I, the mid node and
//! J (its equations 11–19…11–24), the stiffness on two points along the length, the consistent
//! mass on three with the section's rotary inertia (what VM50's published frequency shows:
//! docs/ansys.md). The generalized strains and rigidities are BEAM188's
//! ([`super::beam188`]): u', θx', θy', θz', γxy = v' − θz, γxz = w' + θy with EA, GJ, EIyy,
//! EIzz, k_y GA, k_z GA. The element is straight with its mid node at the middle (a curved or
//! uneven one is refused by the importer); ANSYS's lumped mass of it is not established here
//! (`LUMPM,ON` with BEAM189 is refused by the archive's line; the build's nodal masses use the
//! HRZ diagonal, [`lumped_mass`]).

use super::beam::{self, BeamProps};
use super::element::{
    Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{beam188, ElementError, Isotropic, Xyz};

/// BEAM189 (nodes I, J, mid).
pub struct Beam189Element;

impl Element for Beam189Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let p = beam188::ansys_section_props("BEAM189", input)?;
        let x = input.coords::<3>();
        let v = input.model.elements[input.index].orientation;
        let (k, m) = matrices(&x, v, &input.iso, &p)?;
        let m = if input.lumped() {
            lumped_mass(&x, &input.iso, &p)
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

/// The quadratic functions of nodes I (ξ = −1), J (ξ = 1) and the mid node (ξ = 0) and their
/// ξ-derivatives.
fn shape(xi: f64) -> ([f64; 3], [f64; 3]) {
    (
        [xi * (xi - 1.0) / 2.0, xi * (xi + 1.0) / 2.0, 1.0 - xi * xi],
        [xi - 0.5, xi + 0.5, -2.0 * xi],
    )
}

/// Basic-frame stiffness and mass (18×18, row-major, nodes I, J, mid) of a straight element;
/// `v` orients the local y axis as for [`beam::local_frame`].
pub fn matrices(
    x: &[Xyz; 3],
    v: Option<Xyz>,
    mat: &Isotropic,
    p: &BeamProps,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    beam::check(mat, p)?;
    let [ky, kz] = p.shear.ok_or_else(|| {
        ElementError::BadConstants("BEAM189 needs its shear factors k_y, k_z".into())
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
    let jac = l / 2.0;
    let mut k = vec![[0.0; 18]; 18];
    let g = 1.0 / 3f64.sqrt();
    for xi in [-g, g] {
        // B (6 × 18): u', θx', θy', θz', v' − θz, w' + θy; weight 1 each
        let (n, dn) = shape(xi);
        let mut b = [[0.0; 18]; 6];
        for a in 0..3 {
            let (o, d) = (6 * a, dn[a] / jac);
            b[0][o] = d;
            b[1][o + 3] = d;
            b[2][o + 4] = d;
            b[3][o + 5] = d;
            b[4][o + 1] = d;
            b[4][o + 5] = -n[a];
            b[5][o + 2] = d;
            b[5][o + 4] = n[a];
        }
        for (row, c) in b.iter().zip(rigidity) {
            for i in 0..18 {
                for j in 0..18 {
                    k[i][j] += jac * c * row[i] * row[j];
                }
            }
        }
    }
    let mut m = vec![[0.0; 18]; 18];
    let s = (0.6f64).sqrt();
    for (xi, w) in [(-s, 5.0 / 9.0), (0.0, 8.0 / 9.0), (s, 5.0 / 9.0)] {
        let (n, _) = shape(xi);
        for a in 0..3 {
            for bb in 0..3 {
                for (d, mu) in inertia.iter().enumerate() {
                    m[6 * a + d][6 * bb + d] += w * jac * mu * n[a] * n[bb];
                }
            }
        }
    }
    Ok((rotate(&k, &r), rotate(&m, &r)))
}

/// flexbody's lumped mass of the element (ANSYS's `LUMPM` form of BEAM189 is not established:
/// the archive refuses `LUMPM,ON` with BEAM189; this one serves the build's nodal masses): the
/// HRZ diagonal of the quadratic functions' translational mass, (ρA + m_a)L·(1/6, 1/6, 2/3) on
/// I, J and the mid node, no rotary inertia (as BEAM188's lumped mass).
fn lumped_mass(x: &[Xyz; 3], mat: &Isotropic, p: &BeamProps) -> Vec<f64> {
    let l = crate::model::geometry::norm(crate::model::geometry::sub(x[1], x[0]));
    let m = (mat.rho * p.area + p.nsm) * l;
    let mut out = vec![0.0; 18 * 18];
    for (node, share) in [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0].into_iter().enumerate() {
        for c in 0..3 {
            let d = 6 * node + c;
            out[d * 18 + d] = share * m;
        }
    }
    out
}

/// Tᵀ A T for T = diag(R, …, R) (six 3×3 blocks), R's rows the local axes: an 18×18 local
/// matrix in the basic frame, row-major.
fn rotate(a: &[[f64; 18]], r: &[Xyz; 3]) -> Vec<f64> {
    let t = |i: usize, j: usize| {
        if i / 3 == j / 3 {
            r[i % 3][j % 3]
        } else {
            0.0
        }
    };
    let mut at = vec![[0.0; 18]; 18];
    for i in 0..18 {
        for j in 0..18 {
            let blk = j / 3 * 3;
            at[i][j] = (0..3).map(|q| a[i][blk + q] * t(blk + q, j)).sum();
        }
    }
    let mut out = vec![0.0; 18 * 18];
    for i in 0..18 {
        let blk = i / 3 * 3;
        for j in 0..18 {
            out[i * 18 + j] = (0..3).map(|q| t(blk + q, i) * at[blk + q][j]).sum();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::shell::test_util::{form, residual, rigid};

    /// Six rigid motions give zero force on a skewed element; the mass is ρAL.
    #[test]
    fn beam189_rigid_motions_are_free_of_force_and_the_mass_is_rho_a_l() {
        let (a, b) = ([0.1, 0.2, -0.3], [0.5, -0.1, 0.4]);
        let x = [a, b, std::array::from_fn(|c| (a[c] + b[c]) / 2.0)];
        let mat = Isotropic::new(210e9, 0.3, 7850.0);
        let p = BeamProps {
            area: 2e-4,
            iz: 3e-9,
            iy: 5e-9,
            j: 6e-9,
            shear: Some([0.85, 0.8]),
            nsm: 0.0,
        };
        let (k, m) = matrices(&x, Some([0.0, 0.3, 1.0]), &mat, &p).unwrap();
        for mode in 0..6 {
            let r = residual(&k, &rigid(&x, mode));
            assert!(r < 1e-11, "mode {mode}: {r}");
        }
        let l = crate::model::geometry::norm(crate::model::geometry::sub(b, a));
        let ux = rigid(&x, 0);
        let mass = form(&m, &ux, &ux);
        let want = 7850.0 * 2e-4 * l;
        assert!((mass - want).abs() < 1e-12 * want, "{mass} {want}");
    }
}
