//! Model shell section ([`ShellSection`]) + materials → the element's [`ShellProps`].

use super::elements::shell::ShellProps;
use super::elements::Isotropic;
use crate::model::{Model, Property, ShellSection};

fn iso(model: &Model, m: usize) -> Result<Isotropic, String> {
    let mat = model
        .materials
        .get(m)
        .ok_or_else(|| format!("shell section names material index {m}, which does not exist"))?;
    if mat.stiffness().is_some() {
        return Err(format!(
            "material {} '{}' is anisotropic: shells take isotropic materials only (laminates, \
             MAT8/MAT2 and *ELASTIC, TYPE=LAMINA are not supported)",
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

/// Element constants of a shell property: membrane from the property's material when the
/// section has one (Nastran MID1), bending and shear from their own materials; density from
/// the property's material; the drilling factor K6ROT·10⁻⁶ from the model's `PARAM,K6ROT`
/// (default [`DRILL_FACTOR`](super::elements::shell::DRILL_FACTOR), K6ROT = 100).
pub fn shell_props(model: &Model, prop: &Property, s: &ShellSection) -> Result<ShellProps, String> {
    if s.thickness.is_nan() {
        return Err(format!(
            "property {} has no thickness (PSHELL T blank) and the element gives none (T1..T4)",
            prop.id
        ));
    }
    let primary = iso(model, prop.material)?;
    let bending = match s.bending {
        Some((m, r)) => Some((iso(model, m)?, r)),
        None => None,
    };
    let shear = match s.shear {
        Some((m, r)) => Some((iso(model, m)?, r)),
        None => None,
    };
    Ok(ShellProps {
        t: s.thickness,
        membrane: s.membrane.then_some(primary),
        bending,
        shear,
        rho: primary.rho,
        nsm: s.nsm,
        drill_factor: model
            .params
            .k6rot
            .map_or(super::elements::shell::DRILL_FACTOR, |k| k * 1e-6),
        lumped_rotary: true,
    })
}
