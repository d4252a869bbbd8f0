//! Solution cards: the eigenvalue methods EIGRL/EIGR (selected by the case control's
//! `METHOD = n`) and PARAM.
//!
//! * `EIGRL SID V1 V2 ND`; `EIGR SID METHOD F1 F2 NE ND`: the band and the number of roots.
//! * `PARAM,WTMASS,w`: every structural and concentrated mass times w; `PARAM,COUPMASS,c`:
//!   c > 0 asks for consistent mass; `PARAM,K6ROT,k`: the shells' drilling stiffness.

use super::case_control::Effective;
use super::fields::C;
use super::reading::Bulk;
use crate::import::error::{ImportError, RefusedCard};
use crate::model::EigenRequest;

/// Reader of EIGRL and EIGR.
pub(super) fn eigr<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let sid = g.id(0, "SID")?;
    if let Some(prev) = d.solution.eigen.insert(sid, g.card) {
        return Err(g.err(
            0,
            format!(
                "duplicate eigenvalue method id {sid} (also {} on line {})",
                prev.name, prev.loc.line
            ),
        ));
    }
    Ok(())
}

/// Reader of PARAM,WTMASS.
pub(super) fn wtmass<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    d.solution.wtmass = g
        .real(1)?
        .filter(|w| *w > 0.0)
        .ok_or_else(|| g.err(1, "WTMASS must be > 0"))?;
    Ok(())
}

/// Reader of PARAM,K6ROT: the drilling stiffness factor of CQUAD4/CTRIA3 (MSC QRG
/// "Parameters": K6ROT, default 100), γ_d = K6ROT·10⁻⁶·G t (`fe::elements::shell`). K6ROT = 0
/// (no drilling stiffness: Nastran's AUTOSPC then holds the normal rotation of flat shell
/// grids) is refused.
pub(super) fn k6rot<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let k = g.real(1)?.unwrap_or(100.0);
    if k <= 0.0 {
        return Err(g.err(
            1,
            format!(
                "K6ROT = {k}: a shell without drilling stiffness (Nastran then holds the normal \
                 rotations by AUTOSPC) is not supported; give K6ROT > 0 (MSC's default is 100)"
            ),
        ));
    }
    d.b.model.params.k6rot = Some(k);
    Ok(())
}

/// Reader of PARAM,COUPMASS.
pub(super) fn coupmass<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let value = g.real_or(1, -1.0)?;
    d.b.model.params.coupled_mass = Some(crate::model::DeckMass {
        consistent: value > 0.0,
        asked_by: format!("PARAM,COUPMASS,{value} at {}:{}", g.file, g.card.loc.line),
    });
    Ok(())
}

/// METHOD → EIGRL/EIGR: the deck's default mode count or band.
pub(super) fn resolve_method(d: &mut Bulk, effective: &Effective) -> Result<(), ImportError> {
    let Some(sel) = effective.scope.method else {
        return Ok(());
    };
    let files = d.files;
    let card = (d.solution.eigen.get(&sel.id))
        .ok_or_else(|| sel.undefined(files, "METHOD", "eigenvalue method", "EIGRL or EIGR"))?;
    let g = C::new(card, files);
    // EIGRL: SID V1 V2 ND; EIGR: SID METHOD F1 F2 NE ND.
    let (lo, hi, nd) = if card.name == "EIGRL" {
        (g.real(1)?, g.real(2)?, g.int(3)?)
    } else {
        (g.real(2)?, g.real(3)?, g.int(5)?)
    };
    let count = match nd {
        Some(n) if n > 0 => Some(n as usize),
        Some(n) => {
            return Err(g.err(
                if card.name == "EIGRL" { 3 } else { 5 },
                format!("ND = {n} must be > 0"),
            ))
        }
        None => None,
    };
    if count.is_none() && hi.is_none() {
        return Err(g.err_card("neither ND nor an upper frequency V2/F2 is given: no mode count"));
    }
    d.b.model.deck.eigen = Some(EigenRequest {
        source: format!(
            "METHOD = {} ({}:{}) → {} {} ({}:{})",
            sel.id,
            files[sel.loc.file as usize],
            sel.loc.line,
            card.name,
            sel.id,
            files[card.loc.file as usize],
            card.loc.line
        ),
        count,
        lower_hz: lo,
        upper_hz: hi,
    });
    Ok(())
}

/// Reader of MDLPRM (MSC QRG "MDLPRM": `MDLPRM NAME1 V1 NAME2 V2 …`): each pair through its row
/// of the MDLPRM table (`cards::mdlprm`): a note, honoured at MSC's default behaviour (a blank
/// value is the default), or refused with the reason; a name in no row is refused.
pub(super) fn mdlprm<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    use super::cards::mdlprm::{is_accepted, model_param, ModelParamRule};
    let mut k = 0;
    while k < g.card.fields.len() {
        let name = g.text(k).to_ascii_uppercase();
        let value = g.text(k + 1);
        k += 2;
        if name.is_empty() {
            if !value.is_empty() {
                return Err(g.err(k - 1, format!("value '{value}' without a parameter name")));
            }
            continue;
        }
        let refuse = |d: &mut Bulk, reason: String| {
            d.refused.push(RefusedCard {
                file: g.file.to_owned(),
                line: g.line(k - 2),
                entity: format!("MDLPRM {name} = {value}"),
                key: "MDLPRM".to_owned(),
                reason,
            })
        };
        match model_param(&name) {
            Some((_, category, ModelParamRule::Note(why))) => {
                let entry = (d.noted.entry(*category).or_default())
                    .entry(format!("MDLPRM:{name}"))
                    .or_insert_with(|| (Some(*why), Vec::new()));
                entry.1.push(g.card.loc);
            }
            Some((_, _, ModelParamRule::Only(accepted, why))) => {
                if !(value.is_empty() || is_accepted(value, accepted)) {
                    refuse(d, (*why).to_owned());
                }
            }
            None => refuse(d, super::cards::NOT_READ.to_owned()),
        }
    }
    Ok(())
}
