//! Parsing of the textual option values of the command line (`--units si`, `--material
//! E=210e9,nu=0.3,rho=7850`, `--reference-conditions 1:12,9:2`, …) into library types, so that
//! the CLI stays a thin layer and every rule is tested here.

use flexbody_reader as file;

use crate::fe::{BeamLumping, MassKind};
use crate::model::{DofMask, Material};
use crate::pipeline::interface::SpiderKind;
use crate::pipeline::{BuildMethod, KeepNodes};

/// A bad option value: names the option and says what is accepted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("--{option} {value}: {expected}")]
pub struct OptionError {
    /// The option name without dashes.
    pub option: &'static str,
    /// The value given.
    pub value: String,
    /// What would have been accepted.
    pub expected: String,
}

/// `--inp-shells`: `expanded` or `native`.
pub fn parse_inp_shells(s: &str) -> Result<crate::import::InpShells, OptionError> {
    crate::import::InpShells::from_name(s).ok_or_else(|| bad("inp-shells", s, "expanded or native"))
}

fn bad(option: &'static str, value: &str, expected: &str) -> OptionError {
    OptionError {
        option,
        value: value.to_string(),
        expected: expected.to_string(),
    }
}

/// One unit as (display name, SI factor).
pub type UnitDef = (&'static str, f64);

/// Unit-system presets: (names, [mass, length, time, force]).
pub const UNIT_PRESETS: &[(&[&str], [UnitDef; 4])] = &[
    (
        &["si", "m-kg-s", "mks"],
        [("kg", 1.0), ("m", 1.0), ("s", 1.0), ("N", 1.0)],
    ),
    (
        &["mm-t-s", "mmts"],
        [("t", 1000.0), ("mm", 1e-3), ("s", 1.0), ("N", 1.0)],
    ),
    (
        &["mm-kg-ms"],
        [("kg", 1.0), ("mm", 1e-3), ("ms", 1e-3), ("kN", 1000.0)],
    ),
    (
        &["cm-g-s", "cgs"],
        [("g", 1e-3), ("cm", 1e-2), ("s", 1.0), ("dyn", 1e-5)],
    ),
    (
        &["in-lbf-s", "ips"],
        [
            ("lbf*s^2/in", 4.448_221_615_260_5 / 0.0254),
            ("in", 0.0254),
            ("s", 1.0),
            ("lbf", 4.448_221_615_260_5),
        ],
    ),
];

/// Every preset by its first name, as `--units` reads it.
pub fn unit_presets() -> Vec<(&'static str, file::Units)> {
    (UNIT_PRESETS.iter())
        .filter_map(|(names, _)| Some((names[0], parse_units(names[0]).ok()?)))
        .collect()
}

/// The `--units` preset `units` are (its first name), if any.
pub fn unit_preset_name(units: &file::Units) -> Option<&'static str> {
    (unit_presets().into_iter())
        .find(|(_, u)| u == units)
        .map(|(n, _)| n)
}

/// `--units`: a preset name (see [`UNIT_PRESETS`]).
pub fn parse_units(s: &str) -> Result<file::Units, OptionError> {
    let key = s.trim().to_ascii_lowercase();
    let (_, u) = UNIT_PRESETS
        .iter()
        .find(|(names, _)| names.contains(&key.as_str()))
        .ok_or_else(|| bad("units", s, "one of si, mm-t-s, mm-kg-ms, cm-g-s, in-lbf-s"))?;
    let unit = |(name, si): UnitDef| file::Unit {
        name: name.to_string(),
        si,
    };
    Ok(file::Units {
        mass: unit(u[0]),
        length: unit(u[1]),
        time: unit(u[2]),
        force: unit(u[3]),
    })
}

/// `--material E=…,nu=…,rho=…` (G derived as E / (2(1+ν))).
pub fn parse_material(s: &str) -> Result<Material, OptionError> {
    let expected =
        "E=<Young's modulus>,nu=<Poisson's ratio>,rho=<density>, e.g. E=210e9,nu=0.3,rho=7850";
    let (mut e, mut nu, mut rho) = (None, None, None);
    for part in s.split(',') {
        let (k, v) = part
            .split_once('=')
            .ok_or_else(|| bad("material", s, expected))?;
        let v: f64 = v.trim().parse().map_err(|_| bad("material", s, expected))?;
        match k.trim().to_ascii_lowercase().as_str() {
            "e" => e = Some(v),
            "nu" => nu = Some(v),
            "rho" => rho = Some(v),
            _ => return Err(bad("material", s, expected)),
        }
    }
    let (Some(e), Some(nu), Some(rho)) = (e, nu, rho) else {
        return Err(bad("material", s, expected));
    };
    if !(e > 0.0 && e.is_finite() && -1.0 < nu && nu < 0.5 && rho >= 0.0 && rho.is_finite()) {
        return Err(bad("material", s, "E > 0, −1 < ν < 0.5 and ρ ≥ 0"));
    }
    Ok(Material {
        id: 0,
        name: "CLI".into(),
        e,
        nu,
        g: e / (2.0 * (1.0 + nu)),
        rho,
        elasticity: crate::model::Elasticity::Isotropic,
    })
}

/// `--reference-conditions NODE:DOFS,…` with Nastran dof digits.
pub fn parse_reference_conditions(items: &[String]) -> Result<Vec<(u64, DofMask)>, OptionError> {
    items
        .iter()
        .filter(|s| !s.trim().is_empty())
        .map(|s| {
            let expected = "NODE:DOFS with Nastran dof digits 1–6, e.g. 1:12";
            let (n, d) = s
                .split_once(':')
                .ok_or_else(|| bad("reference-conditions", s, expected))?;
            let node: u64 = n
                .trim()
                .parse()
                .map_err(|_| bad("reference-conditions", s, expected))?;
            let dofs = DofMask::from_digits(d)
                .filter(|m| m.0 != 0)
                .ok_or_else(|| bad("reference-conditions", s, expected))?;
            Ok((node, dofs))
        })
        .collect()
}

/// Reference conditions as given: (`NODE:DOFS` pairs, entries by name or plain id).
pub type ReferenceEntries = (Vec<(u64, DofMask)>, Vec<String>);

/// `--reference-conditions`: `NODE:DOFS` items (see [`parse_reference_conditions`]), and the
/// other items — plain node ids (every free component), names with or without `:DOFS` (an
/// interface's name such as `BIG_END:123456` or `NODE17`, a node set, or a deck's constraint
/// set such as `SPC_1` with the components it holds) — as given.
pub fn parse_reference_entries(items: &[String]) -> Result<ReferenceEntries, OptionError> {
    let (with_dofs, other): (Vec<String>, Vec<String>) = items
        .iter()
        .map(|s| s.trim().to_owned())
        .filter(|s| !s.is_empty())
        .partition(|s| {
            s.split_once(':')
                .is_some_and(|(n, _)| n.trim().parse::<u64>().is_ok())
        });
    Ok((parse_reference_conditions(&with_dofs)?, other))
}

/// `--method`.
pub fn parse_method(s: &str) -> Result<BuildMethod, OptionError> {
    match s.to_ascii_lowercase().as_str() {
        "cb" | "craig-bampton" => Ok(BuildMethod::CraigBampton),
        "normal" | "normal-modes" => Ok(BuildMethod::Normal),
        "craig-chang" | "cc" => Ok(BuildMethod::CraigChang),
        "dietz" => Ok(BuildMethod::Dietz),
        _ => Err(bad("method", s, "cb, normal, craig-chang or dietz")),
    }
}

/// `--geometric-stiffness` (SPEC §5.16): `inertia`, the twelve unit inertia loads.
pub fn parse_geometric_stiffness(s: &str) -> Result<crate::pipeline::GeometricLoads, OptionError> {
    match s.to_ascii_lowercase().as_str() {
        "inertia" => Ok(crate::pipeline::GeometricLoads::Inertia),
        _ => Err(bad(
            "geometric-stiffness",
            s,
            "inertia (the twelve unit inertia loads: accelerations, angular-velocity products, angular accelerations)",
        )),
    }
}

/// The recipe's text of `--geometric-stiffness`.
pub fn geometric_stiffness_name(g: crate::pipeline::GeometricLoads) -> &'static str {
    match g {
        crate::pipeline::GeometricLoads::Inertia => "inertia",
    }
}

/// `--mass`.
pub fn parse_mass(s: &str) -> Result<MassKind, OptionError> {
    match s.to_ascii_lowercase().as_str() {
        "lumped" => Ok(MassKind::Lumped),
        "consistent" => Ok(MassKind::Consistent),
        _ => Err(bad("mass", s, "lumped or consistent")),
    }
}

/// `--beam-mass`: `None` for auto.
pub fn parse_beam_mass(s: &str) -> Result<Option<BeamLumping>, OptionError> {
    match s.to_ascii_lowercase().as_str() {
        "auto" => Ok(None),
        "section" => Ok(Some(BeamLumping::SectionRotary)),
        "torsion" => Ok(Some(BeamLumping::TorsionOnly)),
        "none" => Ok(Some(BeamLumping::TranslationsOnly)),
        "nastran" => Ok(Some(BeamLumping::Nastran)),
        _ => Err(bad(
            "beam-mass",
            s,
            "auto, section, torsion, none or nastran",
        )),
    }
}

/// `--spider`.
pub fn parse_spider(s: &str) -> Result<SpiderKind, OptionError> {
    match s.to_ascii_lowercase().as_str() {
        "rbe2" => Ok(SpiderKind::Rbe2),
        "rbe3" => Ok(SpiderKind::Rbe3),
        "none" => Ok(SpiderKind::None),
        _ => Err(bad("spider", s, "rbe2, rbe3 or none")),
    }
}

/// `--keep-nodes`: all, interface, surface, or a node-set name.
pub fn parse_keep_nodes(s: &str) -> KeepNodes {
    match s.to_ascii_lowercase().as_str() {
        "all" => KeepNodes::All,
        "interface" => KeepNodes::Interface,
        "surface" => KeepNodes::Surface,
        _ => KeepNodes::Set(s.to_string()),
    }
}

/// `--stress-modes [both|stress|strain]` (absent: none).
pub fn parse_field_request(
    s: Option<&str>,
) -> Result<crate::body::stress::FieldRequest, OptionError> {
    use crate::body::stress::FieldRequest;
    let (stress, strain) = match s.map(str::to_ascii_lowercase).as_deref() {
        None => (false, false),
        Some("both") => (true, true),
        Some("stress") => (true, false),
        Some("strain") => (false, true),
        Some(other) => return Err(bad("--stress-modes", other, "both, stress or strain")),
    };
    Ok(FieldRequest { stress, strain })
}

/// `--invariants`.
pub fn parse_invariants(s: &str) -> Result<file::InvariantSet, OptionError> {
    match s.to_ascii_lowercase().as_str() {
        "full" => Ok(file::InvariantSet::Full),
        "partial" => Ok(file::InvariantSet::Partial),
        "constant" => Ok(file::InvariantSet::Constant),
        "rigid" => Ok(file::InvariantSet::Rigid),
        _ => Err(bad("invariants", s, "full, partial, constant or rigid")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_presets_have_consistent_force() {
        // A consistent system has force = mass·length/time² in SI factors.
        for (names, _) in UNIT_PRESETS {
            let u = parse_units(names[0]).unwrap();
            let derived = u.mass.si * u.length.si / (u.time.si * u.time.si);
            assert!((derived / u.force.si - 1.0).abs() < 1e-12, "{}", names[0]);
        }
        assert_eq!(parse_units("MM-T-S").unwrap().length.name, "mm");
        assert_eq!(parse_units("furlong").unwrap_err().option, "units");
    }

    #[test]
    fn material_and_reference_conditions() {
        let m = parse_material("E=210e9, nu=0.3, rho=7850").unwrap();
        assert!((m.g - 210e9 / 2.6).abs() < 1.0);
        assert!(parse_material("E=210e9,nu=0.5,rho=7850").is_err());
        assert!(parse_material("E=210e9,rho=7850").is_err());
        let rc = parse_reference_conditions(&["1:12".into(), "9:2".into()]).unwrap();
        assert_eq!(rc, vec![(1, DofMask(0b11)), (9, DofMask(0b10))]);
        assert!(parse_reference_conditions(&["1:7".into()]).is_err());
        let (rc, named) =
            parse_reference_entries(&["1:12".into(), "SPC_1".into(), " 9 ".into()]).unwrap();
        assert_eq!(rc, vec![(1, DofMask::from_digits("12").unwrap())]);
        assert_eq!(named, vec!["SPC_1".to_owned(), "9".to_owned()]);
        assert!(parse_reference_conditions(&["x:1".into()]).is_err());
    }

    #[test]
    fn names() {
        assert_eq!(parse_method("CB").unwrap(), BuildMethod::CraigBampton);
        assert_eq!(parse_method("dietz").unwrap(), BuildMethod::Dietz);
        assert!(parse_method("guyan")
            .unwrap_err()
            .to_string()
            .contains("cb, normal, craig-chang or dietz"));
        assert_eq!(
            parse_keep_nodes("BIG_END"),
            KeepNodes::Set("BIG_END".into())
        );
        assert_eq!(parse_spider("none").unwrap(), SpiderKind::None);
        assert_eq!(
            parse_invariants("partial").unwrap(),
            file::InvariantSet::Partial
        );
        assert_eq!(parse_mass("consistent").unwrap(), MassKind::Consistent);
    }
}
