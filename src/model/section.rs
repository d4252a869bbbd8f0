//! Section constants (A, I1, I2, J) of the standard beam cross-section shapes of the Abaqus
//! *BEAM SECTION importer, and the shell section type (Nastran PBARL/PBEAML: `beam_library`).
//!
//! Convention (Nastran): local y is the first section axis, z the second; I1 = ∫y² dA (bending
//! in the x–y plane), I2 = ∫z² dA.

use super::{BeamSection, SectionShape};

/// The cross-section of a CalculiX B32R beam expanded into a 20-node brick (ccx 2.20
/// gen3dfrom1d, beamintscheme): the brick spans the section's bounding rectangle, its reference
/// coordinate ζ along the section's 1-direction (width a), η against its 2-direction (height b);
/// stiffness and mass are integrated at the section's own points (`fe::elements::hex20_beam`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BeamBrickSection {
    /// `*BEAM SECTION, SECTION=RECT`: the whole rectangle.
    Rect,
    /// `*BEAM SECTION, SECTION=CIRC`: an ellipse of diameters a × b (ccx reads the card's
    /// values as diameters), the brick's corner nodes on it; integrated as RECT.
    Circ,
    /// `*BEAM GENERAL SECTION, SECTION=PIPE`: `ratio` = inner / outer radius.
    Pipe {
        /// Inner over outer radius, 0 ≤ ratio < 1.
        ratio: f64,
    },
    /// `*BEAM GENERAL SECTION, SECTION=BOX`: outer a (1-direction) × b (2-direction), walls
    /// t1 … t4 in CalculiX's order.
    Box {
        /// Outer size along the 1-direction.
        a: f64,
        /// Outer size along the 2-direction.
        b: f64,
        /// Wall thicknesses t1, t2, t3, t4.
        t: [f64; 4],
    },
}
use std::f64::consts::PI;

/// Torsion constant of a solid rectangle a×b (a ≥ b): J = a b³ [1/3 − 0.21 (b/a)(1 − b⁴/(12 a⁴))]
/// (Roark, Table 10.7 case 4).
pub fn rect_torsion(w: f64, h: f64) -> f64 {
    let (a, b) = if w >= h { (w, h) } else { (h, w) };
    a * b.powi(3) * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b.powi(4) / (12.0 * a.powi(4))))
}

impl SectionShape {
    /// (A, I1, I2, J) of the shape, I about the centroidal axes.
    pub fn constants(&self) -> Option<(f64, f64, f64, f64)> {
        match *self {
            SectionShape::Circle { radius: r } => {
                let i = PI * r.powi(4) / 4.0;
                Some((PI * r * r, i, i, 2.0 * i))
            }
            SectionShape::Tube {
                outer_radius: ro,
                inner_radius: ri,
            } => {
                let i = PI * (ro.powi(4) - ri.powi(4)) / 4.0;
                Some((PI * (ro * ro - ri * ri), i, i, 2.0 * i))
            }
            SectionShape::Rectangle {
                width: w,
                height: h,
            } => Some((
                w * h,
                h * w.powi(3) / 12.0,
                w * h.powi(3) / 12.0,
                rect_torsion(w, h),
            )),
            SectionShape::Box {
                width: w,
                height: h,
                t_web: t1,
                t_flange: t2,
            } => {
                let (wi, hi) = (w - 2.0 * t1, h - 2.0 * t2);
                let a = w * h - wi * hi;
                let i1 = (h * w.powi(3) - hi * wi.powi(3)) / 12.0;
                let i2 = (w * h.powi(3) - wi * hi.powi(3)) / 12.0;
                // Bredt–Batho thin-walled closed section: J = 2 t1 t2 (w−t1)²(h−t2)² / (w t1 + h t2 − t1² − t2²).
                let j = 2.0 * t1 * t2 * (w - t1).powi(2) * (h - t2).powi(2)
                    / (w * t1 + h * t2 - t1 * t1 - t2 * t2);
                Some((a, i1, i2, j))
            }
            SectionShape::I {
                height: h,
                width_bottom: wb,
                width_top: wt,
                t_web: tw,
                t_bottom: tb,
                t_top: tt,
            } => {
                // Parts: bottom flange, web, top flange; z measured from the bottom.
                let hw = h - tb - tt;
                let parts = [
                    (wb * tb, tb / 2.0, wb, tb),
                    (tw * hw, tb + hw / 2.0, tw, hw),
                    (wt * tt, h - tt / 2.0, wt, tt),
                ];
                let a: f64 = parts.iter().map(|p| p.0).sum();
                let zc = parts.iter().map(|p| p.0 * p.1).sum::<f64>() / a;
                let i2 = parts
                    .iter()
                    .map(|&(ai, zi, b, t)| b * t.powi(3) / 12.0 + ai * (zi - zc).powi(2))
                    .sum();
                let i1 = parts.iter().map(|&(_, _, b, t)| t * b.powi(3) / 12.0).sum();
                // Open thin-walled section: J = Σ b t³ / 3.
                let j = (wb * tb.powi(3) + wt * tt.powi(3) + hw * tw.powi(3)) / 3.0;
                Some((a, i1, i2, j))
            }
            SectionShape::Other { .. } => None,
        }
    }

    /// A [`BeamSection`] from this shape (no shear factors, no NSM); `None` for `Other`.
    pub fn to_section(&self) -> Option<BeamSection> {
        let (area, i1, i2, j) = self.constants()?;
        Some(BeamSection {
            area,
            i1,
            i2,
            i12: 0.0,
            j,
            shear_factors: None,
            nsm: 0.0,
            shape: Some(self.clone()),
            taper: None,
        })
    }
}

/// Section of a shell element (Nastran PSHELL, Abaqus *SHELL SECTION, Gmsh `--thickness`).
///
/// The property's `material` is the membrane material (Nastran MID1) when `membrane` is true,
/// else the bending material; its density gives the structural mass ρt. PSHELL:
/// `PID MID1 T MID2 12I/T³ MID3 TS/T NSM`; a single-material section (Abaqus, Gmsh) has MID1 =
/// MID2 = MID3, 12I/T³ = 1 and TS/T = 5/6.
#[derive(Debug, Clone, PartialEq)]
pub struct ShellSection {
    /// Thickness t (an element's own thickness, Nastran CQUAD4 T1..T4, gets its own property).
    pub thickness: f64,
    /// Membrane stiffness from the property's material (Nastran MID1 given).
    pub membrane: bool,
    /// Bending material (index into `Model::materials`, Nastran MID2) and 12I/t³; `None` = no
    /// bending stiffness.
    pub bending: Option<(usize, f64)>,
    /// Transverse shear material (MID3) and t_s/t; `None` = shear-rigid (Nastran MID3 blank).
    pub shear: Option<(usize, f64)>,
    /// Non-structural mass per unit area.
    pub nsm: f64,
    /// Plies of a laminate (Nastran PCOMP, bottom to top, SYM already mirrored); empty for a
    /// PSHELL-like section. With plies, `thickness` is their sum and membrane, bending and shear
    /// come from classical lamination (src/fe/shell_section.rs), not from the fields above.
    pub plies: Vec<Ply>,
    /// The default material x-axis of the section's elements (Nastran: the G1→G2 side, THETA =
    /// 0; an element's own THETA/MCID is in `Model::shell_axes`).
    pub material_axis: ShellMaterialAxis,
}

/// What an ANSYS SHELL281's shell section adds to its element (`fe::elements::shell281`,
/// docs/ansys.md): ANSYS's user transverse shear stiffnesses (its offset is made by
/// [`super::shell_offset`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnsysShell281 {
    /// `SECCONTROL`'s transverse shear stiffnesses E11, E22, E12 (force per length, element
    /// axes); `None`: ANSYS's k G t with k = 5/6.
    pub shear: Option<[f64; 3]>,
}

/// One ply of a laminate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ply {
    /// Material index (into `Model::materials`; external id until the importer resolves it).
    pub material: usize,
    /// Thickness.
    pub thickness: f64,
    /// Fibre angle in degrees from the element's material x-axis, about the normal.
    pub angle_deg: f64,
}

/// How a shell element's material x-axis is found (the ply angles and an orthotropic material
/// are measured from it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ShellMaterialAxis {
    /// THETA degrees about the normal from the G1→G2 side (MSC Nastran QRG, CQUAD4/CTRIA3
    /// THETA: "material property orientation angle … measured from the line G1–G2").
    FromSide12 { theta_deg: f64 },
    /// The projection of a basic-frame vector onto the element plane (Nastran MCID: the x-axis
    /// of the coordinate system MCID projected onto the element, MSC QRG CQUAD4; Abaqus
    /// `*SHELL SECTION, ORIENTATION=`: axis 1 projected).
    Projected([f64; 3]),
    /// Abaqus's default local shell directions: global x projected onto the element, or global
    /// z when x is within 0.1° of the normal (Abaqus Analysis User's Guide §1.2.2
    /// "Conventions").
    AbaqusDefault,
}

impl Default for ShellMaterialAxis {
    fn default() -> Self {
        ShellMaterialAxis::FromSide12 { theta_deg: 0.0 }
    }
}

impl ShellSection {
    /// A homogeneous shell of one material (index `material`): membrane, bending (12I/t³ = 1)
    /// and transverse shear (t_s/t = 5/6).
    pub fn homogeneous(thickness: f64, material: usize) -> ShellSection {
        ShellSection {
            thickness,
            membrane: true,
            bending: Some((material, 1.0)),
            shear: Some((material, 5.0 / 6.0)),
            nsm: 0.0,
            plies: Vec::new(),
            material_axis: ShellMaterialAxis::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1e-30)
    }

    #[test]
    fn rectangle_and_circle_closed_form() {
        let (a, i1, i2, j) = SectionShape::Rectangle {
            width: 0.02,
            height: 0.01,
        }
        .constants()
        .unwrap();
        assert!(close(a, 2e-4) && close(i1, 0.01 * 0.02f64.powi(3) / 12.0));
        assert!(close(i2, 0.02 * 1e-6 / 12.0));
        // Roark for a/b = 2: J = 0.229 a b³ (table value, 3 digits).
        assert!((j / (0.02 * 1e-6) - 0.2287).abs() < 1e-3);
        let (a, i1, _, j) = SectionShape::Circle { radius: 0.5 }.constants().unwrap();
        assert!(close(a, PI * 0.25) && close(i1, PI / 64.0) && close(j, PI / 32.0));
    }

    #[test]
    fn symmetric_i_equals_box_difference_formula() {
        // Symmetric I: I2 = [b h³ − (b − tw)(h − 2t)³]/12.
        let (h, b, tw, t) = (0.2, 0.1, 0.006, 0.01);
        let (a, _, i2, _) = SectionShape::I {
            height: h,
            width_bottom: b,
            width_top: b,
            t_web: tw,
            t_bottom: t,
            t_top: t,
        }
        .constants()
        .unwrap();
        assert!(close(a, 2.0 * b * t + (h - 2.0 * t) * tw));
        assert!(close(
            i2,
            (b * h.powi(3) - (b - tw) * (h - 2.0 * t).powi(3)) / 12.0
        ));
    }
}
