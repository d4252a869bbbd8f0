//! Material plausibility: warnings (never errors) for values no real material has in any common
//! unit system. The file's units are not declared, so the test uses a unit-free quantity where it
//! can: the bar wave speed c = √(E/ρ), which for engineering solids lies between ~20 m/s (soft
//! elastomers) and ~18,000 m/s (diamond, beryllium). Across length units m, mm, in and ft and
//! time units s and ms that is 6 … 2·10⁷ length/time; the warning range is one decade wider.

use crate::model::{ImportWarning, Model};

/// Wave speeds √(E/ρ) outside this range (in any length/time units) are warned about.
const WAVE_SPEED_RANGE: (f64, f64) = (0.6, 2e8);

/// Warnings for implausible materials of `model`, attributed to the material's `file:line`
/// when the importer recorded it ([`Model::material_sources`]), else to `file`.
pub fn material_warnings(model: &Model, file: &str) -> Vec<ImportWarning> {
    let mut out = Vec::new();
    for (k, m) in model.materials.iter().enumerate() {
        let mut why = Vec::new();
        if !(m.nu > -1.0 && m.nu < 0.5) {
            why.push(format!("Poisson's ratio ν = {} is outside (−1, 0.5)", m.nu));
        }
        if m.e <= 0.0 {
            why.push(format!("Young's modulus E = {:e} is not positive", m.e));
        }
        if m.rho < 0.0 {
            why.push(format!("density ρ = {:e} is negative", m.rho));
        }
        if m.e > 0.0 && m.rho > 0.0 {
            let c = (m.e / m.rho).sqrt();
            if c < WAVE_SPEED_RANGE.0 || c > WAVE_SPEED_RANGE.1 {
                why.push(format!(
                    "wave speed √(E/ρ) = {c:.3e} length/time (E = {:e}, ρ = {:e}) is outside {:e} … {:e}, the range of real solids in any of m, mm, in, ft per s or ms: check the units of E and ρ",
                    m.e, m.rho, WAVE_SPEED_RANGE.0, WAVE_SPEED_RANGE.1
                ));
            }
        }
        if !why.is_empty() {
            let place = match model.material_sources.get(k) {
                Some(&(f, line)) => {
                    format!("{}:{line}", model.files.get(f as usize).map_or(file, |s| s))
                }
                None => file.to_owned(),
            };
            out.push(ImportWarning {
                file: place,
                message: format!("material {}: {}", m.name, why.join("; ")),
            });
        }
    }
    out
}

/// Young's moduli of real solids in Pa: soft foams and elastomers (~1e5) … diamond (1.2e12),
/// one decade wider.
const E_PA_RANGE: (f64, f64) = (1e4, 1e13);
/// Densities of real solids in kg/m³: foams and aerogels (~10) … osmium (2.26e4), a decade wider.
const RHO_KG_M3_RANGE: (f64, f64) = (1.0, 3e5);

/// E in Pa and ρ in kg/m³ of numbers `e`, `rho` read in `units`.
fn in_si(e: f64, rho: f64, u: &flexbody_reader::Units) -> (f64, f64) {
    let l = u.length.si;
    (e * u.force.si / (l * l), rho * u.mass.si / (l * l * l))
}

/// Bar wave speeds √(E/ρ) of real solids in m/s: soft elastomers (~20) … diamond (1.8e4), a
/// factor 2–3 wider. Steel's E in MPa read as Pa with ρ in kg/m³ gives 5.2 m/s.
const WAVE_SPEED_SI_RANGE: (f64, f64) = (10.0, 5e4);

/// Which of E (Pa) and ρ (kg/m³) is no real solid's, in words ("ρ is off (… kg/m³)"), or
/// `None` when the pair is plausible: each in its range and, with mass, their wave speed too.
fn quantity_off(e: f64, rho: f64) -> Option<String> {
    let inside = |x: f64, (lo, hi): (f64, f64)| x >= lo && x <= hi;
    let e_ok = inside(e, E_PA_RANGE);
    let rho_ok = rho == 0.0 || inside(rho, RHO_KG_M3_RANGE);
    match (e_ok, rho_ok) {
        (false, false) => Some(format!(
            "E and ρ are both off (no solid has E = {e:.3e} Pa or ρ = {rho:.3e} kg/m³)"
        )),
        (false, true) => Some(format!("E is off (no solid has E = {e:.3e} Pa)")),
        (true, false) => Some(format!("ρ is off (no solid has ρ = {rho:.3e} kg/m³)")),
        (true, true) if rho > 0.0 && !inside((e / rho).sqrt(), WAVE_SPEED_SI_RANGE) => Some(format!(
            "E and ρ do not belong together (wave speed √(E/ρ) = {:.3e} m/s, outside the {:e} … {:e} m/s of real solids): one of them is in other units",
            (e / rho).sqrt(),
            WAVE_SPEED_SI_RANGE.0,
            WAVE_SPEED_SI_RANGE.1
        )),
        (true, true) => None,
    }
}

/// The materials whose E and ρ can be judged (positive, finite; `material_warnings` says what
/// is wrong with the others).
fn judged(model: &Model) -> impl Iterator<Item = &crate::model::Material> {
    (model.materials.iter())
        .filter(|m| m.e > 0.0 && m.rho >= 0.0 && m.e.is_finite() && m.rho.is_finite())
}

/// Warnings for materials whose E and ρ, read in the declared unit system `units` (named
/// `units_name`), are no real solid's — the mark of a wrong `--units` (steel's 7850 read as
/// t/mm³, 210e9 read as MPa) — naming the material, the quantity that is off and the preset of
/// `candidates` in which *every* material of the model is plausible, or saying that none is (a
/// material that mixes unit systems: E in MPa with ρ in kg/m³; issue 47).
pub fn unit_system_warnings(
    model: &Model,
    units: &flexbody_reader::Units,
    units_name: &str,
    candidates: &[(&str, flexbody_reader::Units)],
) -> Vec<String> {
    let off_in = |u: &flexbody_reader::Units, m: &crate::model::Material| {
        let (e, rho) = in_si(m.e, m.rho, u);
        quantity_off(e, rho)
    };
    let fits: Vec<&str> = (candidates.iter())
        .filter(|(_, u)| judged(model).all(|m| off_in(u, m).is_none()))
        .map(|(name, _)| *name)
        .collect();
    let mut out = Vec::new();
    for m in judged(model) {
        let Some(off) = off_in(units, m) else {
            continue;
        };
        let (e, rho) = in_si(m.e, m.rho, units);
        let hint = if fits.is_empty() {
            format!(
                "no --units preset makes every material plausible (none of {}): a material's numbers mix unit systems; fix the one that is off in the model (or --material)",
                candidates.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
            )
        } else {
            format!(
                "they fit --units {} (every material of the model does): check --units",
                fits.join(" or ")
            )
        };
        out.push(format!(
            "material {}: E = {:e}, ρ = {:e} read in {units_name} ({}, {}, {}, {}) are E = {e:.3e} Pa and ρ = {rho:.3e} kg/m³, which no solid has: {off}; {hint}",
            m.name, m.e, m.rho, units.mass.name, units.length.name, units.time.name, units.force.name
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Material;

    fn units(mass: (&str, f64), length: (&str, f64), force: (&str, f64)) -> flexbody_reader::Units {
        let u = |(name, si): (&str, f64)| flexbody_reader::Unit {
            name: name.into(),
            si,
        };
        flexbody_reader::Units {
            mass: u(mass),
            length: u(length),
            time: u(("s", 1.0)),
            force: u(force),
        }
    }

    /// Steel in SI read as t/mm/s is refused with si named; in t/mm/s it passes; the same
    /// numbers read as SI pass.
    #[test]
    fn a_unit_system_that_contradicts_the_material_is_named() {
        let si = units(("kg", 1.0), ("m", 1.0), ("N", 1.0));
        let mmts = units(("t", 1000.0), ("mm", 1e-3), ("N", 1.0));
        let candidates = [("si", si.clone()), ("mm-t-s", mmts.clone())];
        let model = |m: Material| Model {
            materials: vec![m],
            ..Default::default()
        };
        let steel_si = model(Material::steel());
        let w = unit_system_warnings(&steel_si, &mmts, "mm-t-s", &candidates);
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].contains("material STEEL") && w[0].contains("fit --units si"),
            "{}",
            w[0]
        );
        assert!(w[0].contains("ρ = 7.850e15 kg/m³"), "{}", w[0]);
        assert!(unit_system_warnings(&steel_si, &si, "si", &candidates).is_empty());
        let steel_mm = model(Material::isotropic(1, "S", 2.1e5, 0.3, 7.85e-9));
        assert!(unit_system_warnings(&steel_mm, &mmts, "mm-t-s", &candidates).is_empty());
        let w = unit_system_warnings(&steel_mm, &si, "si", &candidates);
        assert!(w.len() == 1 && w[0].contains("fit --units mm-t-s"), "{w:?}");
    }

    /// Two materials that fit different presets (steel in SI, aluminium in mm-t-s): no preset
    /// makes every material plausible, and the hint says so instead of naming either.
    #[test]
    fn a_preset_is_named_only_when_every_material_fits_it() {
        let si = units(("kg", 1.0), ("m", 1.0), ("N", 1.0));
        let mmts = units(("t", 1000.0), ("mm", 1e-3), ("N", 1.0));
        let candidates = [("si", si.clone()), ("mm-t-s", mmts.clone())];
        let model = Model {
            materials: vec![
                Material::steel(),
                Material::isotropic(2, "ALU", 7.0e4, 0.33, 2.7e-9),
            ],
            ..Default::default()
        };
        let w = unit_system_warnings(&model, &si, "si", &candidates);
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].contains("material ALU")
                && w[0].contains("ρ is off")
                && w[0].contains("no --units preset makes every material plausible"),
            "{}",
            w[0]
        );
        assert!(!w[0].contains("they fit"), "{}", w[0]);
    }

    fn warn(m: Material) -> Vec<ImportWarning> {
        let model = Model {
            materials: vec![m],
            ..Default::default()
        };
        material_warnings(&model, "f")
    }

    #[test]
    fn real_materials_in_common_units_pass() {
        // Steel SI (c = 5.17e3 m/s), steel mm-t-s (5.17e6 mm/s), rubber SI, aluminium in-lbf-s.
        assert!(warn(Material::steel()).is_empty());
        assert!(warn(Material::isotropic(1, "S", 2.1e5, 0.3, 7.85e-9)).is_empty());
        assert!(warn(Material::isotropic(1, "R", 1e6, 0.49, 1100.0)).is_empty());
        assert!(warn(Material::isotropic(1, "A", 1.0e7, 0.33, 2.59e-4)).is_empty());
    }

    #[test]
    fn extreme_values_are_warned_about() {
        let w = warn(Material::isotropic(1, "X", 1e100, 0.3, 7850.0));
        assert_eq!(w.len(), 1);
        assert!(w[0].message.contains("wave speed"), "{}", w[0].message);
        // Steel E in Pa with ρ in t/mm³: a unit mix-up (c = 5.2e9).
        assert_eq!(
            warn(Material::isotropic(1, "M", 2.1e11, 0.3, 7.85e-9)).len(),
            1
        );
        assert!(warn(Material::isotropic(1, "N", 2.1e11, 0.5, 7850.0))[0]
            .message
            .contains("Poisson"));
    }
}
