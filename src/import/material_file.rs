//! The small material side file for formats that carry no material (Gmsh `.msh`, a bare mesh):
//! `key = value` lines, `#` comments, keys case-insensitive:
//!
//! ```text
//! name = STEEL      # optional
//! E    = 2.1e11     # Young's modulus (required)
//! nu   = 0.3        # Poisson's ratio (required)
//! rho  = 7850       # density (required)
//! G    = 8.0e10     # optional; default E / (2(1 + nu))
//! ```

use std::path::Path;

use super::error::{parse_err, ImportError};
use super::text::{bad_number, parse_f64, read_text};
use crate::model::Material;

/// Read a material side file.
pub fn read_material_file(path: &Path) -> Result<Material, ImportError> {
    let file = path.display().to_string();
    let text = read_text(path)?;
    let (mut name, mut e, mut nu, mut rho, mut g) =
        (String::from("MATERIAL"), None, None, None, None);
    for (i, raw) in text.lines().enumerate() {
        let s = raw.split('#').next().unwrap_or("").trim();
        if s.is_empty() {
            continue;
        }
        let Some((k, v)) = s.split_once('=') else {
            return Err(parse_err(
                &file,
                i + 1,
                "material",
                format!("expected `key = value`, found `{s}`"),
            ));
        };
        let (k, v) = (k.trim().to_ascii_lowercase(), v.trim());
        let num = || {
            parse_f64(v)
                .ok_or_else(|| parse_err(&file, i + 1, format!("material {k}"), bad_number(v)))
        };
        match k.as_str() {
            "name" => name = v.trim_matches('"').to_ascii_uppercase(),
            "e" => e = Some(num()?),
            "nu" => nu = Some(num()?),
            "rho" => rho = Some(num()?),
            "g" => g = Some(num()?),
            _ => {
                return Err(parse_err(
                    &file,
                    i + 1,
                    format!("material {k}"),
                    "unknown key (name, E, nu, rho, G)",
                ))
            }
        }
    }
    let last = text.lines().count().max(1);
    let need = |x: Option<f64>, k: &str| {
        x.ok_or_else(|| parse_err(&file, last, "material", format!("{k} is missing")))
    };
    let (e, nu, rho) = (need(e, "E")?, need(nu, "nu")?, need(rho, "rho")?);
    let mut m = Material::isotropic(1, &name, e, nu, rho);
    if let Some(g) = g {
        m.g = g;
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_keys_and_reports_missing_ones() {
        let dir = std::env::temp_dir().join(format!("flexbody_matfile_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("steel.material");
        std::fs::write(
            &p,
            "# steel\nname = steel\nE = 2.1e11\nNU=0.3\nrho = 7850 # kg/m3\n",
        )
        .unwrap();
        let m = read_material_file(&p).unwrap();
        assert_eq!(
            (m.name.as_str(), m.e, m.nu, m.rho),
            ("STEEL", 2.1e11, 0.3, 7850.0)
        );
        assert!((m.g - 2.1e11 / 2.6).abs() < 1e-3);
        std::fs::write(&p, "E = 2.1e11\nnu = x\n").unwrap();
        let e = read_material_file(&p).unwrap_err();
        assert_eq!((e.line(), e.entity()), (Some(2), Some("material nu")));
        std::fs::write(&p, "E = 2.1e11\nnu = 0.3\n").unwrap();
        assert!(read_material_file(&p)
            .unwrap_err()
            .to_string()
            .contains("rho is missing"));
    }
}
