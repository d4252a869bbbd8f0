//! The 20-node brick CalculiX 2.20 makes of a B32R beam (`import::abaqus::beam_expansion`):
//! the serendipity hexahedron of [`super::hex20`] spanning the section's bounding rectangle,
//! ξ along the beam, integrated — stiffness and mass alike, as ccx's e_c3d does for its
//! C3D20RB elements — at points that follow the section's shape (ccx beamintscheme, gauss3d13):
//!
//! * RECT and CIRC: 2 Gauss points along ξ × a 5 × 5 product rule in (η, ζ) on the points 0,
//!   ±√(1/3), ±√(6/7) with the weights that make it exact to degree 5 (28/45, 27/55, 98/495)
//!   (for CIRC the brick's corner nodes lie on the circle: the map makes the square round);
//! * PIPE: 2 Gauss points along ξ × 8 points at 45° on the circle of radius √((1 + ρ²)/2)
//!   (ρ = inner / outer radius), each weighing (π/4)(1 − ρ²)/2, which integrates 1, η², ζ²
//!   over the annulus exactly;
//! * BOX: 2 Gauss points along ξ × composite Simpson (4 intervals) along the mid-line of each
//!   wall, times the wall's thickness; the four corner points belong to two walls.
//!
//! Section coordinates are reference coordinates of the bounding rectangle (η, ζ ∈ [−1, 1]).

use super::element::{
    first, integration_points, nodal_gradients, Element, ElementInput, ElementMatrices,
    MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::{hex20, solid_scalar_mass, solid_stiffness, ElementError, Isotropic, Xyz};
use crate::fe::quadrature::{self, QuadPoint};
use crate::model::BeamBrickSection;

/// The points (η, ζ) and weights of the section's rule on [−1, 1]² (module doc).
pub fn section_points(section: &BeamBrickSection) -> Vec<([f64; 2], f64)> {
    match *section {
        BeamBrickSection::Rect | BeamBrickSection::Circ => {
            let (a, b) = ((1.0f64 / 3.0).sqrt(), (6.0f64 / 7.0).sqrt());
            let line = [
                (-b, 98.0 / 495.0),
                (-a, 27.0 / 55.0),
                (0.0, 28.0 / 45.0),
                (a, 27.0 / 55.0),
                (b, 98.0 / 495.0),
            ];
            let mut out = Vec::with_capacity(25);
            for &(z, wz) in &line {
                for &(e, we) in &line {
                    out.push(([e, z], we * wz));
                }
            }
            out
        }
        BeamBrickSection::Pipe { ratio } => {
            let r = ((1.0 + ratio * ratio) / 2.0).sqrt();
            let dtheta = std::f64::consts::FRAC_PI_4;
            let w = dtheta * (1.0 - ratio * ratio) / 2.0;
            (0..8)
                .map(|j| {
                    let th = j as f64 * dtheta;
                    ([r * th.cos(), r * th.sin()], w)
                })
                .collect()
        }
        BeamBrickSection::Box { a, b, t } => box_points(a, b, t),
    }
}

/// BOX: the wall mid-lines in reference coordinates — t1 at ζ = 1 − t1/a, t3 at
/// ζ = −(1 − t3/a), t2 at η = −(1 − t2/b), t4 at η = 1 − t4/b — walked t1, t2, t3, t4 from the
/// t1/t4 corner; on each wall composite Simpson h/3 [1 4 2 4 1] times the wall's reference
/// thickness (2t/a or 2t/b). The weights add up to the exact area of the box.
fn box_points(a: f64, b: f64, t: [f64; 4]) -> Vec<([f64; 2], f64)> {
    let [t1, t2, t3, t4] = t;
    let (z1, z3) = (1.0 - t1 / a, -(1.0 - t3 / a));
    let (e2, e4) = (-(1.0 - t2 / b), 1.0 - t4 / b);
    // corners in walking order and the thickness of the wall that leaves each one
    let corners = [[e4, z1], [e2, z1], [e2, z3], [e4, z3]];
    let thickness = [2.0 * t1 / a, 2.0 * t2 / b, 2.0 * t3 / a, 2.0 * t4 / b];
    let mut out: Vec<([f64; 2], f64)> = Vec::with_capacity(16);
    for wall in 0..4 {
        let (p, q) = (corners[wall], corners[(wall + 1) % 4]);
        let length = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
        let h = length / 4.0;
        for (k, simpson) in [1.0, 4.0, 2.0, 4.0].into_iter().enumerate() {
            let s = k as f64 / 4.0;
            let pt = [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])];
            out.push((pt, simpson * h / 3.0 * thickness[wall]));
        }
        // the far corner's share of this wall goes to the next wall's first point
    }
    for wall in 0..4 {
        let length = {
            let (p, q) = (corners[wall], corners[(wall + 1) % 4]);
            ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt()
        };
        let next = 4 * ((wall + 1) % 4);
        out[next].1 += length / 12.0 * thickness[wall];
    }
    out
}

/// The element's rule: ξ = ∓1/√3 (weight 1 each) × the section's points.
pub fn rule(section: &BeamBrickSection) -> Vec<QuadPoint> {
    let g = (1.0f64 / 3.0).sqrt();
    let points = section_points(section);
    [-g, g]
        .iter()
        .flat_map(|&xi| {
            points.iter().map(move |&([eta, zeta], w)| QuadPoint {
                xi: [xi, eta, zeta],
                w,
            })
        })
        .collect()
}

/// Stiffness 60×60 at the section's points (module doc; isotropic kernel of `elements`).
pub fn stiffness(
    x: &[Xyz; 20],
    mat: &Isotropic,
    section: &BeamBrickSection,
) -> Result<Vec<f64>, ElementError> {
    solid_stiffness(x, hex20::shape, &rule(section), mat)
}

/// Scalar consistent mass 20×20 at the section's points.
pub fn scalar_mass(
    x: &[Xyz; 20],
    rho: f64,
    section: &BeamBrickSection,
) -> Result<Vec<f64>, ElementError> {
    solid_scalar_mass(x, hex20::shape, &rule(section), rho)
}

/// The 20-node hexahedron as an [`Element`] (here, as a CalculiX beam expanded into a C3D20R
/// is one of its forms): full 3×3×3 or, `reduced`, 2×2×2 integration.
pub struct Hex20Element {
    /// C3D20R: 2×2×2 points.
    pub reduced: bool,
}

impl Element for Hex20Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<20>();
        let (rho, lumped) = (input.iso.rho, input.lumped());
        if let Some(section) = (input.model.beam_bricks.get(&input.index)).filter(|_| self.reduced)
        {
            if input.general.is_some() {
                let mat = input.material;
                return Err(MatricesError::Unsupported(format!(
                    "material {} '{}' is anisotropic: a CalculiX beam expanded into a brick \
                     takes an isotropic material",
                    mat.id, mat.name
                )));
            }
            let k = stiffness(&x, &input.iso, section)?;
            let ms = scalar_mass(&x, rho, section)?;
            return Ok(input.solid(k, ms, 20, true));
        }
        // ANSYS: SOLID186's mass on Irons' 14 points, SOLID95 KEYOPT(11)=1's on its stiffness's
        // 2×2×2 (MAPDL Archived Elements Theory Reference §1.17: "2 x 2 x 2 if KEYOPT(11) = 1")
        let gauss2 = self.reduced && input.model.hex20_mass_2x2x2.contains(&input.index);
        let mass = if input.model.params.ansys_solid_rules && !lumped && !gauss2 {
            hex20::scalar_mass_irons14(&x, rho)
        } else {
            hex20::scalar_mass(&x, rho, self.reduced && !lumped)
        };
        let k = input.stiffness(|| {
            if input.model.params.ansys_solid_rules && !self.reduced {
                // SOLID186 KEYOPT(2)=1: ANSYS's full integration is the 14-point rule
                hex20::stiffness_irons14(&x, &input.iso)
            } else {
                hex20::stiffness(&x, &input.iso, self.reduced)
            }
        })?;
        Ok(input.solid(k, mass?, 20, true))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        rules: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        let rule = match (self.reduced, rules.ansys) {
            (true, _) => quadrature::cube(2),
            (false, true) => quadrature::cube_irons14(),
            (false, false) => quadrature::cube(3),
        };
        Ok(Some(integration_points(x, hex20::shape, &rule)?))
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        let grads = nodal_gradients(&first(x), hex20::shape, &hex20::NODES, [0.0; 3])?;
        Ok(Some(grads))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn integrate(section: &BeamBrickSection, f: impl Fn(f64, f64) -> f64) -> f64 {
        section_points(section)
            .iter()
            .map(|&([e, z], w)| w * f(e, z))
            .sum()
    }

    #[test]
    fn rect_rule_is_exact_to_degree_five_and_matches_ccx_weights() {
        let s = BeamBrickSection::Rect;
        assert!((integrate(&s, |_, _| 1.0) - 4.0).abs() < 1e-14);
        // ∫∫ η⁴ ζ² = (2/5)(2/3)
        assert!((integrate(&s, |e, z| e.powi(4) * z * z) - 4.0 / 15.0).abs() < 1e-14);
        assert!((integrate(&s, |e, z| e.powi(5) * z.powi(3))).abs() < 1e-14);
        // ccx gauss.f weight3d13: the centre point 0.387160493827161, the outer corner
        // 0.391960004081216e-1
        let p = section_points(&s);
        assert!((p[12].1 - 0.387160493827161).abs() < 1e-14);
        assert!((p[0].1 - 0.0391960004081216).abs() < 1e-15);
    }

    #[test]
    fn pipe_rule_integrates_area_and_second_moment_of_the_annulus() {
        let rho: f64 = 0.9;
        let s = BeamBrickSection::Pipe { ratio: rho };
        let pi = std::f64::consts::PI;
        // in units of the outer radius: A = π(1 − ρ²), I = π(1 − ρ⁴)/4
        assert!((integrate(&s, |_, _| 1.0) - pi * (1.0 - rho * rho)).abs() < 1e-14);
        let i = pi * (1.0 - rho.powi(4)) / 4.0;
        assert!((integrate(&s, |e, _| e * e) - i).abs() < 1e-14);
        assert!((integrate(&s, |_, z| z * z) - i).abs() < 1e-14);
    }

    #[test]
    fn box_rule_weighs_the_exact_area_with_ccx_corner_weight() {
        let (a, b, t) = (50.0, 40.0, [3.0, 2.0, 4.0, 1.0]);
        let s = BeamBrickSection::Box { a, b, t };
        let area = a * b - (a - t[0] - t[2]) * (b - t[1] - t[3]);
        // reference measure × (a/2)(b/2)
        assert!((integrate(&s, |_, _| 1.0) * a * b / 4.0 - area).abs() < 1e-11);
        // ccx beamintscheme point 1: −(((−2a + 2t1 + t3) t4 + t1 t2 − 2b t1)/(ab))/6
        let [t1, t2, t3, t4] = t;
        let w1 = -((((-2.0 * a) + 2.0 * t1 + t3) * t4 + t1 * t2 - 2.0 * b * t1) / (a * b)) / 6.0;
        let p = section_points(&s);
        assert!((p[0].1 - w1).abs() < 1e-15);
        assert!((p[0].0[0] - (1.0 - t4 / b)).abs() < 1e-15);
        assert!((p[0].0[1] - (1.0 - t1 / a)).abs() < 1e-15);
        // point 6 on the t2 wall: ζ = (t3 − 3 t1 + 2a)/(4a)
        assert!((p[5].0[1] - (t3 - 3.0 * t1 + 2.0 * a) / (4.0 * a)).abs() < 1e-15);
    }
}
