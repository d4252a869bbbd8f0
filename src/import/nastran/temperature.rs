//! Nastran temperatures of a thermal preload (`TEMP(LOAD) = n` in the static subcase that
//! `STATSUB(PRELOAD)` names, module `case_control`): TEMP (SID, then grid–temperature pairs)
//! and TEMPD (SID–default-temperature pairs) give every grid's temperature T of set n, and
//! MAT1 A (α, field 6) and TREF (field 7) the thermal strain α (T − TREF) (MSC QRG "TEMP",
//! "TEMPD", "MAT1"; a linear static solution strains from TREF).
//!
//! The preload takes one ΔT per grid, so every expanding material (α ≠ 0) must share one TREF;
//! a grid of an element without a TEMP and without a TEMPD default, a grid named twice, or an
//! unknown grid is an error naming the card.

use super::case_control::Select;
use super::fields::C;
use super::lex::Card;
use crate::import::error::{parse_err, ImportError};
use crate::import::text::IdMap;
use crate::model::{Material, Model};

/// ΔT per node (like `Model::nodes`) and α per material (like `Model::materials`) of
/// temperature set `sel`.
pub(super) fn thermal_preload(
    cards: &[&Card],
    mats: &[(u64, Material, &Card)],
    sel: Select,
    nodes: &IdMap,
    model: &Model,
    files: &[String],
) -> Result<(Vec<f64>, Vec<f64>), ImportError> {
    let sid = sel.id;
    let n_nodes = model.nodes.len();
    let mut temp: Vec<Option<(f64, usize)>> = vec![None; n_nodes];
    let mut default: Option<f64> = None;
    let mut found = false;
    for &card in cards {
        let g = C::new(card, files);
        if card.name == "TEMPD" {
            for k in (0..card.fields.len()).step_by(2) {
                if !g.text(k).is_empty() && g.id(k, "SID")? == sid {
                    default = Some(
                        g.real(k + 1)?
                            .ok_or_else(|| g.err(k + 1, "TEMPD needs a temperature"))?,
                    );
                    found = true;
                }
            }
            continue;
        }
        if g.id(0, "SID")? != sid {
            continue;
        }
        found = true;
        for k in (1..card.fields.len()).step_by(2) {
            if g.text(k).is_empty() {
                continue;
            }
            let gid = g.id(k, "G")?;
            let n = nodes
                .get(gid)
                .ok_or_else(|| g.err(k, format!("grid {gid} is not defined")))?;
            let t = g
                .real(k + 1)?
                .ok_or_else(|| g.err(k + 1, format!("grid {gid} has no temperature")))?;
            if let Some((_, line)) = temp[n] {
                return Err(g.err(
                    k,
                    format!("grid {gid} has a temperature in set {sid} already (line {line})"),
                ));
            }
            temp[n] = Some((t, g.line(k)));
        }
    }
    let at = |why: String| {
        parse_err(
            &files[sel.loc.file as usize],
            sel.loc.line as usize,
            format!("TEMP(LOAD) = {sid}"),
            why,
        )
    };
    if !found {
        return Err(at(format!(
            "the bulk data has no TEMP or TEMPD of set {sid}"
        )));
    }
    let mut alpha = Vec::with_capacity(mats.len());
    let mut tref: Option<(f64, u64)> = None;
    for (mid, _, card) in mats {
        let g = C::new(card, files);
        if card.name == "MAT9" {
            if (23..=28).any(|k| g.real_or(k, 0.0).is_ok_and(|a| a != 0.0)) {
                return Err(g.err(
                    23,
                    "MAT9 thermal expansion A1–A6 in a thermal preload is not supported",
                ));
            }
            alpha.push(0.0);
            continue;
        }
        let a = g.real_or(5, 0.0)?;
        let t0 = g.real_or(6, 0.0)?;
        if a != 0.0 {
            match tref {
                Some((t, other)) if t != t0 => {
                    return Err(g.err(6, format!("TREF {t0} differs from MAT1 {other}'s {t}: a thermal preload takes one reference temperature for every expanding material")));
                }
                _ => tref = Some((t0, *mid)),
            }
        }
        alpha.push(a);
    }
    let t0 = tref.map_or(0.0, |t| t.0);
    // grids of no element (scalar points, mass-only grids) strain nothing
    let mut on_element = vec![false; n_nodes];
    for e in &model.elements {
        for &n in &e.nodes {
            on_element[n] = true;
        }
    }
    let mut delta_t = Vec::with_capacity(n_nodes);
    for (n, t) in temp.iter().enumerate() {
        let t = match (t, default) {
            (Some((t, _)), _) => *t,
            (None, Some(d)) => d,
            (None, None) if !on_element[n] => t0,
            (None, None) => {
                let id = model.nodes[n].id;
                return Err(at(format!(
                    "grid {id} has no temperature in set {sid} (no TEMP, no TEMPD default)"
                )));
            }
        };
        delta_t.push(t - t0);
    }
    Ok((delta_t, alpha))
}
