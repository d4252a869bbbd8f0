//! Model shell section ([`ShellSection`]) + materials → the element's [`ShellProps`].
//!
//! * Isotropic materials (MAT1, Abaqus, Gmsh) without plies: the PSHELL constants as they are
//!   ([`ShellProps`] module doc). A PCOMP whose plies all use one isotropic material is the same
//!   homogeneous section (its ply angles cannot matter).
//! * A laminate (plies of several materials, or of a plane-stress MAT8/MAT2): classical
//!   lamination from the bottom z = −t/2 up, ply k between z_k and z_{k+1} with Q̄_k its Q turned
//!   by the ply angle: A = Σ Q̄_k (z_{k+1} − z_k), B = ½ Σ Q̄_k (z²_{k+1} − z²_k), D = ⅓ Σ Q̄_k
//!   (z³_{k+1} − z³_k) (Reddy, *Mechanics of Laminated Composite Plates and Shells* (2004)
//!   eq. 3.3.17); transverse shear A_s = 5/6 Σ Q̄s_k (z_{k+1} − z_k), Q̄s the ply's (G13, G23)
//!   turned likewise — the first-order shear theory's correction factor (Reddy eq. 3.4.23),
//!   not Nastran's equilibrium-based PCOMP value (they differ on thick, strongly
//!   heterogeneous laminates; thin plates do not see it). Mass Σ ρ_k t_k, rotary inertia
//!   Σ ρ_k ∫ z² dz; a laminate whose first mass moment Σ ρ_k ∫ z dz is not zero (plies of
//!   different densities placed unsymmetrically) is an error: the shell mass has no
//!   translation–rotation coupling.
//! * A PSHELL of plane-stress materials: A = t Q₁ (MID1), D = (12I/t³) t³/12 Q₂ (MID2), B = 0,
//!   A_s = (t_s/t) t S₃ (MID3: MAT1 G I, MAT8 diag(G1Z, G2Z), MAT2 [G11 G12; G12 G22]).
//! * Shear-rigid plies and sections (MAT8 G1Z/G2Z blank, a MAT2 ply, PSHELL MID3 blank) take
//!   G12 (MAT2: G33) in their place, as the isotropic section takes 5/6 G (ShellProps::shear_modulus):
//!   MITC4 and the DKMT do not lock, so a thin plate gives the Kirchhoff answer.

use super::elements::element::{BeamLumping, ElementInput, MatricesError};
use super::elements::shell::{
    plane_stress, rotate_plane, rotate_shear, GeneralSection, Quad4Form, ShellProps, M2, M3,
};
use super::elements::Isotropic;
use crate::model::{Material, Model, Property, Section, ShellSection};

/// The element's shell section, or why it has none (a non-shell property).
fn shell_section<'a>(input: &ElementInput<'a>) -> Result<&'a ShellSection, MatricesError> {
    match &input.property.section {
        Section::Shell(s) => Ok(s),
        _ => Err(MatricesError::Unsupported(format!(
            "shell element with non-shell property {} (plane-stress/strain CPS/CPE elements are \
             not supported)",
            input.property.id
        ))),
    }
}

/// A flat shell's (CQUAD4/CTRIA3, S4/S3) section properties, and whether it has the drilling
/// membrane (CQUADR/CTRIAR).
pub(crate) fn flat_shell_props(input: &ElementInput) -> Result<(ShellProps, bool), MatricesError> {
    let s = shell_section(input)?;
    let (model, e) = (input.model, input.index);
    let mut p = shell_props(model, e, input.property, s).map_err(MatricesError::Unsupported)?;
    // Nastran lumps CQUAD4/CTRIA3 without rotary inertia (BeamLumping::Nastran doc).
    p.lumped_rotary = input.spec.beam_lumping != BeamLumping::Nastran;
    let drilling = model.drilling_membranes.contains(&e);
    if drilling && (p.general.is_some() || p.membrane.is_none()) {
        return Err(MatricesError::Unsupported(format!(
            "a CQUADR/CTRIAR needs a homogeneous section with a membrane (PSHELL MID1 of a \
             MAT1); property {} is a laminate, plane-stress or has no membrane (not implemented \
             for the drilling membrane)",
            input.property.id
        )));
    }
    Ok((p, drilling))
}

/// A curved shell's (CQUAD8/CTRIA6, S8/S6) section properties and its thickness at each of its
/// N nodes (the section's, or the element's nodal thicknesses).
pub(crate) fn curved_shell_props<const N: usize>(
    input: &ElementInput,
) -> Result<(ShellProps, [f64; N]), MatricesError> {
    let s = shell_section(input)?;
    let (model, e) = (input.model, input.index);
    let mut p = shell_props(model, e, input.property, s).map_err(MatricesError::Unsupported)?;
    if p.general.is_some() {
        return Err(MatricesError::Unsupported(format!(
            "property {} is a laminate or plane-stress (PCOMP of several materials, MAT8, MAT2) \
             section: the quadratic shells (CQUAD8/CTRIA6, S8/S8R/S6) take isotropic sections \
             only; mesh the part with CQUAD4/CTRIA3 (S4/S3)",
            input.property.id
        )));
    }
    p.lumped_rotary = input.spec.beam_lumping != BeamLumping::Nastran;
    let nodal = model.shell_thickness.get(&e);
    if nodal.is_some_and(|t| t.len() != input.nodes.len()) {
        return Err(MatricesError::Unsupported(
            "nodal thicknesses do not match the node count".into(),
        ));
    }
    let t = std::array::from_fn(|a| nodal.map_or(p.t, |t| t[a]));
    Ok((p, t))
}

fn material(model: &Model, m: usize) -> Result<&Material, String> {
    model
        .materials
        .get(m)
        .ok_or_else(|| format!("shell section names material index {m}, which does not exist"))
}

fn iso(model: &Model, m: usize) -> Result<Isotropic, String> {
    let mat = material(model, m)?;
    if mat.stiffness().is_some() || mat.plane_stress().is_some() {
        return Err(format!(
            "material {} '{}' is anisotropic: shells take isotropic (MAT1) and plane-stress \
             (MAT8, MAT2) materials, not a 3-D anisotropic one (MAT9, *ELASTIC ORTHO/ENGINEERING \
             CONSTANTS/ANISO)",
            mat.id, mat.name
        ));
    }
    Ok(Isotropic {
        e: mat.e,
        nu: mat.nu,
        g: mat.g,
        rho: mat.rho,
    })
}

/// In-plane Q, transverse shear S (given, or the shear-rigid stand-in, module doc) and ρ of a
/// shell material; `mid3`: S as a PSHELL MID3 (MAT2: its G11, G12, G22).
fn plane(model: &Model, m: usize, mid3: bool) -> Result<(M3, M2, f64), String> {
    let mat = material(model, m)?;
    if let Some(p) = mat.plane_stress() {
        let g12 = p.q[2][2];
        let s = match (mid3, p.as_mid3, p.transverse) {
            (true, Some(s), _) | (_, _, Some(s)) => s,
            _ => [[g12, 0.0], [0.0, g12]],
        };
        return Ok((p.q, s, mat.rho));
    }
    let i = iso(model, m)?;
    Ok((plane_stress(i.e, i.nu), [[i.g, 0.0], [0.0, i.g]], i.rho))
}

fn is_plane_stress(model: &Model, m: usize) -> bool {
    model
        .materials
        .get(m)
        .is_some_and(|x| x.plane_stress().is_some())
}

/// Element constants of a shell property for element `elem` (its material axis: the
/// element's THETA/MCID, else the section's): membrane from the property's material when the
/// section has one (Nastran MID1), bending and shear from their own materials; density from
/// the property's material; the drilling factor K6ROT·10⁻⁶ from the model's `PARAM,K6ROT`
/// (default [`DRILL_FACTOR`](super::elements::shell::DRILL_FACTOR), K6ROT = 100). Laminates
/// and plane-stress materials: module doc.
pub fn shell_props(
    model: &Model,
    elem: usize,
    prop: &Property,
    s: &ShellSection,
) -> Result<ShellProps, String> {
    if s.thickness.is_nan() {
        return Err(format!(
            "property {} has no thickness (PSHELL T blank) and the element gives none (T1..T4)",
            prop.id
        ));
    }
    let drill_factor = model
        .params
        .k6rot
        .map_or(super::elements::shell::DRILL_FACTOR, |k| k * 1e-6);
    let axis = model
        .shell_axes
        .get(&elem)
        .copied()
        .unwrap_or(s.material_axis);
    let homogeneous_plies = s
        .plies
        .iter()
        .all(|p| p.material == prop.material && !is_plane_stress(model, p.material));
    let pshell_mids = [
        Some(prop.material),
        s.bending.map(|b| b.0),
        s.shear.map(|b| b.0),
    ];
    let general = if !homogeneous_plies {
        Some(laminate(model, prop, s)?)
    } else if pshell_mids
        .iter()
        .flatten()
        .any(|&m| is_plane_stress(model, m))
    {
        Some(plane_stress_pshell(model, prop, s)?)
    } else {
        None
    };
    let (membrane, bending, shear, rho) = match general {
        // the general section's own rigidities and mass replace the isotropic fields
        Some(g) => (None, None, None, g.mass / s.thickness),
        None => {
            let primary = iso(model, prop.material)?;
            (
                s.membrane.then_some(primary),
                (s.bending.map(|(m, r)| iso(model, m).map(|i| (i, r)))).transpose()?,
                (s.shear.map(|(m, r)| iso(model, m).map(|i| (i, r)))).transpose()?,
                primary.rho,
            )
        }
    };
    Ok(ShellProps {
        t: s.thickness,
        membrane,
        bending,
        shear,
        rho,
        nsm: s.nsm,
        drill_factor,
        lumped_rotary: true,
        general: general.map(|g| GeneralSection { axis, ..g }),
        quad4: if model.params.nastran_deck {
            Quad4Form::NastranQuad4
        } else if model.params.ansys_shell181 {
            Quad4Form::AnsysShell181
        } else {
            Quad4Form::Mitc4
        },
    })
}

fn add(acc: &mut M3, q: &M3, f: f64) {
    for i in 0..3 {
        for j in 0..3 {
            acc[i][j] += f * q[i][j];
        }
    }
}

/// Classical lamination of the plies (module doc).
fn laminate(model: &Model, prop: &Property, s: &ShellSection) -> Result<GeneralSection, String> {
    let t: f64 = s.plies.iter().map(|p| p.thickness).sum();
    let mut g = GeneralSection {
        a: [[0.0; 3]; 3],
        b: [[0.0; 3]; 3],
        d: [[0.0; 3]; 3],
        shear: [[0.0; 2]; 2],
        mass: 0.0,
        rotary: 0.0,
        axis: s.material_axis,
    };
    let mut first = 0.0;
    let mut z = -0.5 * t;
    for ply in &s.plies {
        let (q, qs, rho) = plane(model, ply.material, false)?;
        let theta = ply.angle_deg.to_radians();
        let (qb, sb) = (rotate_plane(&q, theta), rotate_shear(&qs, theta));
        let z1 = z + ply.thickness;
        let (d1, d2, d3) = (
            z1 - z,
            (z1 * z1 - z * z) / 2.0,
            (z1.powi(3) - z.powi(3)) / 3.0,
        );
        add(&mut g.a, &qb, d1);
        add(&mut g.b, &qb, d2);
        add(&mut g.d, &qb, d3);
        for i in 0..2 {
            for j in 0..2 {
                g.shear[i][j] += 5.0 / 6.0 * sb[i][j] * d1;
            }
        }
        g.mass += rho * d1;
        first += rho * d2;
        g.rotary += rho * d3;
        z = z1;
    }
    // B of a symmetric laminate is zero up to rounding: make it exactly zero.
    let scale = g.a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())) * t;
    if g.b.iter().flatten().all(|v| v.abs() <= 1e-13 * scale) {
        g.b = [[0.0; 3]; 3];
    }
    if first.abs() > 1e-9 * g.mass * t {
        return Err(format!(
            "property {}: the laminate's first mass moment Σρ∫z dz = {first:e} is not zero \
             (plies of different densities placed unsymmetrically): it couples translations \
             and rotations, which the shell mass does not hold (not implemented)",
            prop.id
        ));
    }
    Ok(g)
}

/// A PSHELL of plane-stress materials (module doc).
fn plane_stress_pshell(
    model: &Model,
    prop: &Property,
    s: &ShellSection,
) -> Result<GeneralSection, String> {
    let t = s.thickness;
    let Some((m2, ratio)) = s.bending.filter(|_| s.membrane) else {
        return Err(format!(
            "property {}: a shell of plane-stress materials (MAT8, MAT2) needs both MID1 \
             (membrane) and MID2 (bending)",
            prop.id
        ));
    };
    let (q1, _, rho) = plane(model, prop.material, false)?;
    let (q2, _, _) = plane(model, m2, false)?;
    let mut g = GeneralSection {
        a: [[0.0; 3]; 3],
        b: [[0.0; 3]; 3],
        d: [[0.0; 3]; 3],
        shear: [[0.0; 2]; 2],
        mass: rho * t,
        rotary: rho * t.powi(3) / 12.0,
        axis: s.material_axis,
    };
    add(&mut g.a, &q1, t);
    add(&mut g.d, &q2, ratio * t.powi(3) / 12.0);
    let (s3, f) = match s.shear {
        Some((m3, ts)) => (plane(model, m3, true)?.1, ts * t),
        None => ([[q2[2][2], 0.0], [0.0, q2[2][2]]], 5.0 / 6.0 * t),
    };
    g.shear = s3.map(|r| r.map(|v| v * f));
    Ok(g)
}
