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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Material;

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
