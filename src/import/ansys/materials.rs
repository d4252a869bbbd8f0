//! `MPTEMP`/`MPDATA`/`MP`: material property tables → isotropic or orthotropic materials. A
//! table with one temperature is the constant; a table with several is read at `TREF` when one
//! of its temperatures is `TREF`, otherwise refused. A material whose values are isotropic (EY,
//! EZ equal to EX, one Poisson's ratio, G consistent) is read exactly as before; any other is
//! orthotropic, read as the Material Reference (§3.2, "Stress-Strain Relationships") says: EX,
//! EY, EZ, the three Poisson's ratios in major (PRXY, PRYZ, PRXZ) or minor (NUXY, NUYZ, NUXZ)
//! form — not both — and GXY, GYZ, GXZ "must all be input … There are no defaults", so a
//! missing one is refused by name. PRXY is ν_xy = −ε_y/ε_x under σ_x (Jones's ν12), NUXY the
//! minor ν_yx = ν_xy E_y/E_x (likewise YZ, XZ). Thermal, damping and friction labels cannot
//! change K or M of a linear body and are noted.

use std::collections::BTreeMap;

use super::blocks::{archive_form, Command};
use crate::import::error::ImportError;
use crate::model::{elasticity, Material};

/// What a property label is to the body.
enum Label {
    Modulus,
    Poisson,
    Shear,
    Density,
    /// No effect on K or M (the reason's word).
    NoEffect,
}

fn label(name: &str) -> Option<Label> {
    Some(match name {
        "EX" | "EY" | "EZ" => Label::Modulus,
        "PRXY" | "PRYZ" | "PRXZ" | "NUXY" | "NUYZ" | "NUXZ" => Label::Poisson,
        "GXY" | "GYZ" | "GXZ" => Label::Shear,
        "DENS" => Label::Density,
        "ALPX" | "ALPY" | "ALPZ" | "CTEX" | "CTEY" | "CTEZ" | "THSX" | "THSY" | "THSZ" | "REFT"
        | "KXX" | "KYY" | "KZZ" | "C" | "ENTH" | "HF" | "EMIS" | "QRATE" | "MU" | "DAMP"
        | "DMPR" | "DMPS" | "RSVX" | "RSVY" | "RSVZ" | "PERX" | "PERY" | "PERZ" | "MURX"
        | "MURY" | "MURZ" | "VISC" | "SONC" | "BETX" | "BETY" | "BETZ" | "DXX" | "DYY" | "DZZ"
        | "CSAT" | "CREF" | "LSST" | "SBKX" | "SBKY" | "SBKZ" => Label::NoEffect,
        // the material's unique ids of Workbench and ACP (a text value, e.g. a GUID)
        "UMID" | "UVID" => Label::NoEffect,
        _ => return None,
    })
}

/// A property's table: its first line and its (temperature, value) pairs.
type Table = (usize, Vec<(f64, f64)>);

/// The property tables read so far.
#[derive(Debug, Default)]
pub(super) struct Tables {
    /// The current MPTEMP temperatures.
    temps: Vec<f64>,
    /// (material, label) → (first line, (temperature, value) pairs).
    props: BTreeMap<(i64, String), Table>,
    /// Labels without effect: label → lines.
    pub noted: BTreeMap<String, Vec<usize>>,
}

/// A refusal: line and reason.
pub(super) type Refused = (usize, String);

impl Tables {
    /// `MPTEMP,R5.0,LENGTH,STLOC,T1,…` or `MPTEMP,STLOC,T1,…` (no fields: clear).
    pub fn mptemp(&mut self, file: &str, c: &Command) -> Result<(), ImportError> {
        let archive_form = archive_form(c.field(0));
        let first = if archive_form { 2 } else { 0 };
        if c.fields.iter().all(|f| f.is_empty()) {
            self.temps.clear();
            return Ok(());
        }
        let start = (c.int(file, first)?.max(1) - 1) as usize;
        let count = if archive_form {
            c.int(file, 1)?.max(0) as usize
        } else {
            c.fields.len().saturating_sub(first + 1)
        };
        if start > 10_000 || count > 100 {
            return Err(crate::import::error::parse_err(
                file,
                c.line,
                "MPTEMP",
                "table location or length out of range",
            ));
        }
        if start == 0 {
            self.temps.clear();
        }
        for k in 0..count {
            let t = c.real(file, first + 1 + k)?;
            if self.temps.len() <= start + k {
                self.temps.resize(start + k + 1, 0.0);
            }
            self.temps[start + k] = t;
        }
        Ok(())
    }

    /// `MPDATA,R5.0,LENGTH,LAB,MAT,STLOC,C1,…` or `MPDATA,LAB,MAT,STLOC,C1,…`; `MP,LAB,MAT,C0`.
    pub fn mpdata(
        &mut self,
        file: &str,
        c: &Command,
        refused: &mut Vec<Refused>,
    ) -> Result<(), ImportError> {
        let lab_at = if c.name != "MP" && archive_form(c.field(0)) {
            2
        } else {
            0
        };
        let lab = c.field(lab_at).to_ascii_uppercase();
        match label(&lab) {
            None => {
                refused.push((c.line, format!("material property {lab} is not read")));
                return Ok(());
            }
            Some(Label::NoEffect) => {
                self.noted.entry(lab).or_default().push(c.line);
                return Ok(());
            }
            Some(_) => {}
        }
        let values: Vec<f64> = if c.name == "MP" {
            // MP,Lab,MAT,C0,C1…C4: the coefficients are fields 3…6 after the name
            if (3..7).any(|k| !c.field(k).is_empty() && c.real(file, k).is_ok_and(|v| v != 0.0)) {
                refused.push((
                    c.line,
                    "MP with temperature coefficients C1…C4: a temperature-dependent property \
                     is not read"
                        .into(),
                ));
                return Ok(());
            }
            vec![c.real(file, 2)?]
        } else if lab_at == 2 {
            let count = c.int(file, 1)?.clamp(0, 100) as usize;
            (0..count)
                .map(|k| c.real(file, 5 + k))
                .collect::<Result<_, _>>()?
        } else {
            let count = c.fields.len().saturating_sub(3);
            (0..count)
                .map(|k| c.real(file, 3 + k))
                .collect::<Result<_, _>>()?
        };
        let mat = c.int(file, lab_at + 1)?;
        let start = if c.name == "MP" {
            0
        } else {
            (c.int(file, lab_at + 2)?.max(1) - 1) as usize
        };
        let entry = self
            .props
            .entry((mat, lab))
            .or_insert_with(|| (c.line, Vec::new()));
        if start == 0 {
            entry.1.clear();
        }
        for (k, v) in values.into_iter().enumerate() {
            let t = self.temps.get(start + k).copied().unwrap_or(0.0);
            entry.1.push((t, v));
        }
        Ok(())
    }

    /// The materials by number, read at `tref`; refusals for tables not readable there and
    /// for materials neither isotropic nor a complete positive-definite orthotropic set.
    pub fn resolve(&self, tref: f64, refused: &mut Vec<Refused>) -> BTreeMap<i64, Material> {
        let mut values: BTreeMap<i64, BTreeMap<&str, (usize, f64)>> = BTreeMap::new();
        for ((mat, lab), (line, table)) in &self.props {
            let v = match table.as_slice() {
                [(_, v)] => *v,
                many => match many.iter().find(|(t, _)| *t == tref) {
                    Some((_, v)) => *v,
                    None => {
                        refused.push((
                            *line,
                            format!(
                                "material {mat} {lab}: a table over {} temperatures without the \
                                 reference temperature TREF = {tref}: a temperature-dependent \
                                 property is not read",
                                many.len()
                            ),
                        ));
                        continue;
                    }
                },
            };
            values
                .entry(*mat)
                .or_default()
                .insert(lab.as_str(), (*line, v));
        }
        let mut out = BTreeMap::new();
        for (mat, v) in values {
            let line = v.values().map(|x| x.0).min().unwrap_or(0);
            let read = match isotropic(mat, &v) {
                Ok(m) => Ok(m),
                Err(Isotropy::NoModulus) => Err("no EX".to_owned()),
                Err(Isotropy::Orthotropic(why)) => orthotropic(mat, &v)
                    .map_err(|missing| format!("{why} (orthotropic): {missing}")),
            };
            match read {
                Ok(m) => drop(out.insert(mat, m)),
                Err(why) => refused.push((line, format!("material {mat}: {why}"))),
            }
        }
        out
    }
}

/// Why a material's values are not an isotropic material.
enum Isotropy {
    /// No EX (nor EY, EZ).
    NoModulus,
    /// The values differ by direction (the reason).
    Orthotropic(String),
}

/// One material's values as an isotropic material (the one path of isotropic materials).
fn isotropic(mat: i64, v: &BTreeMap<&str, (usize, f64)>) -> Result<Material, Isotropy> {
    let same = |labels: &[&str]| -> Result<Option<f64>, String> {
        let found: Vec<(&str, f64)> = labels
            .iter()
            .filter_map(|l| v.get(l).map(|x| (*l, x.1)))
            .collect();
        match found.split_first() {
            None => Ok(None),
            Some(((l0, v0), rest)) => {
                match rest.iter().find(|(_, x)| (x - v0).abs() > 1e-12 * v0.abs()) {
                    Some((l, x)) => Err(format!("{l} = {x} differs from {l0} = {v0}")),
                    None => Ok(Some(*v0)),
                }
            }
        }
    };
    let ortho = Isotropy::Orthotropic;
    let e = same(&["EX", "EY", "EZ"])
        .map_err(ortho)?
        .ok_or(Isotropy::NoModulus)?;
    let nu = same(&["PRXY", "PRYZ", "PRXZ", "NUXY", "NUYZ", "NUXZ"]).map_err(ortho)?;
    let g = same(&["GXY", "GYZ", "GXZ"]).map_err(ortho)?;
    let nu = match (nu, g) {
        (Some(nu), Some(g)) => {
            let iso = e / (2.0 * (1.0 + nu));
            if (g - iso).abs() > 1e-9 * iso {
                return Err(ortho(format!("GXY = {g} is not EX/(2(1+PRXY)) = {iso}")));
            }
            nu
        }
        (Some(nu), None) => nu,
        // ANSYS: PRXY from EX and GXY
        (None, Some(g)) => e / (2.0 * g) - 1.0,
        // ANSYS's default Poisson's ratio for an isotropic material is 0.3
        (None, None) => 0.3,
    };
    let rho = v.get("DENS").map_or(0.0, |x| x.1);
    Ok(Material::isotropic(
        mat.max(0) as u64,
        &format!("MAT{mat}"),
        e,
        nu,
        rho,
    ))
}

/// One material's values as an orthotropic material in its element axes (module doc: all nine
/// constants, Poisson's ratios major or minor, ν_ij = ν_ji E_i/E_j for the minor form), D by
/// Jones §2.4 ([`elasticity::from_engineering_constants`]); or why not (a label missing, both
/// forms, D not positive definite).
fn orthotropic(mat: i64, v: &BTreeMap<&str, (usize, f64)>) -> Result<Material, String> {
    let get = |l: &str| v.get(l).map(|x| x.1);
    let need =
        |l: &str| get(l).ok_or_else(|| format!("{l} is not given (ANSYS has no default for it)"));
    let [ex, ey, ez] = [need("EX")?, need("EY")?, need("EZ")?];
    let [gxy, gyz, gxz] = [need("GXY")?, need("GYZ")?, need("GXZ")?];
    // (major label, minor label, E_i, E_j): ν_ij = PRij, or NUij E_i/E_j
    let pairs = [
        ("PRXY", "NUXY", ex, ey),
        ("PRXZ", "NUXZ", ex, ez),
        ("PRYZ", "NUYZ", ey, ez),
    ];
    let mut nu = [0.0; 3];
    for (k, (major, minor, ei, ej)) in pairs.into_iter().enumerate() {
        nu[k] = match (get(major), get(minor)) {
            (Some(_), Some(_)) => {
                return Err(format!(
                    "{major} and {minor} are both given (ANSYS takes the major or the minor \
                     form, not both)"
                ))
            }
            (Some(p), None) => p,
            (None, Some(m)) => m * ei / ej,
            (None, None) => {
                return Err(format!(
                    "neither {major} nor {minor} is given (ANSYS has no default for it)"
                ))
            }
        };
    }
    let d = elasticity::from_engineering_constants([ex, ey, ez], nu, [gxy, gxz, gyz])?;
    match elasticity::check(&d)? {
        elasticity::Definiteness::Positive => {}
        elasticity::Definiteness::Singular { rank } => {
            return Err(format!(
                "the elasticity matrix is singular (rank {rank} of 6): not positive definite"
            ))
        }
    }
    let rho = v.get("DENS").map_or(0.0, |x| x.1);
    Ok(Material::anisotropic(
        mat.max(0) as u64,
        &format!("MAT{mat}"),
        d,
        rho,
    ))
}

/// What a `TB` table of this label does to a linear body at its undeformed state: `Ok` when
/// nothing (failure criteria, friction, plasticity, creep, damage: the elastic constants of
/// MP/MPDATA stay the stiffness), else why it is refused (it defines or changes the elastic
/// stiffness, or is not known here).
pub(super) fn table_effect(label: &str) -> Result<(), String> {
    const NO_EFFECT: [&str; 14] = [
        "FCLI", "FRIC", "PLAS", "BISO", "MISO", "BKIN", "MKIN", "KINH", "NLISO", "CHAB", "CREEP",
        "RATE", "DMGI", "DMGE",
    ];
    const ELASTIC: [&str; 6] = ["ELAS", "ANEL", "HYPE", "PRONY", "SHIFT", "MELAS"];
    if NO_EFFECT.contains(&label) {
        Ok(())
    } else if ELASTIC.contains(&label) {
        Err("the table defines or changes the elastic stiffness; not read".into())
    } else {
        Err("a material table not in the catalogue's list (docs/ansys-commands.md)".into())
    }
}
