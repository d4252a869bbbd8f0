//! Rule 13 (SPEC.md §6): `recipe.json` agrees with itself and with the rest of the file.

use super::*;

/// Rule 13 (SPEC.md §6): `recipe.json` agrees with itself and with the rest of the file.
pub(super) fn recipe(r: &crate::Recipe, body: &ReducedBody) -> Result<(), ReadError> {
    for (q, f) in r.model_files.iter().enumerate() {
        let hex_ok = f.sha256.len() == 64
            && f.sha256
                .bytes()
                .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b));
        if !hex_ok {
            return Err(inconsistent(
                RECIPE,
                format!("model_files[{q}].sha256 must be 64 lowercase hex digits"),
            ));
        }
        let want = if q == 0 { "main" } else { "include" };
        if f.role != want {
            return Err(inconsistent(
                RECIPE,
                format!("model_files[{q}].role is {:?}, must be {want:?}", f.role),
            ));
        }
    }
    if r.options.units != body.units {
        return Err(inconsistent(
            RECIPE,
            "options.units differ from the manifest's units".into(),
        ));
    }
    if let Some(f) = r.options.fmax_hz {
        finite(RECIPE, "options.fmax_hz", [&f])?;
        if f <= 0.0 {
            return Err(inconsistent(
                RECIPE,
                format!("options.fmax_hz {f} must be > 0"),
            ));
        }
    }
    finite(RECIPE, "options.thickness", r.options.thickness.iter())?;
    for (q, itf) in r.interfaces.iter().enumerate() {
        for &id in &itf.nodes {
            if !body.nodes.iter().any(|p| p.id == id && p.interface) {
                return Err(inconsistent(
                    RECIPE,
                    format!(
                        "interfaces[{q}] ({}) names node {id}, which is not a stored interface node",
                        itf.entry
                    ),
                ));
            }
        }
        if let Some(s) = &itf.spider {
            finite(RECIPE, &format!("interfaces[{q}].spider.centre"), &s.centre)?;
            finite(
                RECIPE,
                &format!("interfaces[{q}].spider.offset_from_node_average"),
                [&s.offset_from_node_average],
            )?;
        }
    }
    let band = r.accuracy_band.fmax_hz;
    finite(RECIPE, "accuracy_band.fmax_hz", [&band])?;
    if band <= 0.0 {
        return Err(inconsistent(
            RECIPE,
            format!("accuracy_band.fmax_hz {band} must be > 0"),
        ));
    }
    finite(
        RECIPE,
        "accuracy_band.basis_cutoff_hz",
        r.accuracy_band.basis_cutoff_hz.iter(),
    )?;
    if let Some(p) = &r.preload {
        preload_numbers(p)?;
    }
    recipe_against_entries(r, body)
}

/// Rule 13, the preload's numbers (SPEC §5.11): `max_displacement` finite and ≥ 0,
/// `buckling_factor` (when not null) finite and > 0.
fn preload_numbers(p: &crate::RecipePreload) -> Result<(), ReadError> {
    let d = p.max_displacement;
    finite(RECIPE, "preload.max_displacement", [&d])?;
    if d < 0.0 {
        return Err(inconsistent(
            RECIPE,
            format!("preload.max_displacement {d} must be >= 0"),
        ));
    }
    if let Some(l) = p.buckling_factor {
        finite(RECIPE, "preload.buckling_factor", [&l])?;
        if l <= 0.0 {
            return Err(inconsistent(
                RECIPE,
                format!("preload.buckling_factor {l} must be > 0 (null: nothing in compression)"),
            ));
        }
    }
    Ok(())
}

/// Rule 13, last checks (SPEC §5.7, §5.11, §5.16): the recipe's statements about other entries.
fn recipe_against_entries(r: &crate::Recipe, body: &ReducedBody) -> Result<(), ReadError> {
    use crate::types::{Method, ModeLabel};
    let has_gs = body.geometric_stiffness.is_some();
    if r.options.geometric_stiffness.is_some() != has_gs {
        return Err(inconsistent(
            RECIPE,
            format!(
                "options.geometric_stiffness is {} but geometric_stiffness.bin is {}",
                if has_gs { "absent" } else { "present" },
                if has_gs { "present" } else { "absent" }
            ),
        ));
    }
    if r.preload.is_some() {
        if has_gs {
            return Err(inconsistent(
                RECIPE,
                "a preloaded build has no geometric_stiffness.bin (§5.16)".into(),
            ));
        }
        if let Some(j) = body
            .modes
            .labels
            .iter()
            .position(|l| *l == ModeLabel::Rigid)
        {
            return Err(inconsistent(
                RECIPE,
                format!("a preload needs a held body, but mode {j} is labelled Rigid (§5.11)"),
            ));
        }
    }
    let removed = body.method.counts.removed_dependent;
    if body.method.method == Method::NormalModes
        && removed > 0
        && r.options.residual_vectors.is_none()
    {
        return Err(inconsistent(
            RECIPE,
            format!(
                "counts.removed_dependent = {removed} for normal modes without \
                 options.residual_vectors (only residual vectors can be removed, §5.7)"
            ),
        ));
    }
    Ok(())
}
