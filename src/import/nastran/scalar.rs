//! Scalar elements: springs CELAS1–4 with PELAS and masses CMASS1–4 with PMASS (MSC QRG
//! "CELAS1" … "CMASS4"), into [`crate::model::ScalarSpring`] and [`crate::model::ScalarMass`].
//!
//! * `CELAS1 EID PID G1 C1 G2 C2`, `CELAS2 EID K G1 C1 G2 C2 GE S`: between component C1 of
//!   G1 and C2 of G2 (digits 1–6 in the grids' displacement frames; 0 or blank for a scalar
//!   point); a blank or zero G is ground. `CELAS3 EID PID S1 S2`, `CELAS4 EID K S1 S2`: between
//!   scalar points. `PELAS PID1 K1 GE1 S1 PID2 K2 GE2 S2`.
//! * `CMASS1 EID PID G1 C1 G2 C2`, `CMASS2 EID M G1 C1 G2 C2`, `CMASS3 EID PID S1 S2`,
//!   `CMASS4 EID M S1 S2`; `PMASS PID1 M1 PID2 M2 PID3 M3 PID4 M4`. Masses are scaled by WTMASS.
//! * GE (structural damping) is a note: a real normal-modes analysis has none. S (stress
//!   coefficient) is output.

use super::fields::C;
use super::reading::Bulk;
use super::records::ScalarElement;
use crate::import::error::ImportError;
use crate::model::{ScalarMass, ScalarSpring};

/// Reader of CELAS1–4 and CMASS1–4.
pub(super) fn element<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let name = g.card.name.as_str();
    let spring = name.starts_with("CELAS");
    let eid = g.id(0, "EID")?;
    d.elements.other_ids.push((eid, g.card));
    let by_property = name.ends_with('1') || name.ends_with('3');
    let value = if by_property {
        Err(match g.int(1)? {
            None => eid,
            Some(p) if p > 0 => p as u64,
            Some(p) => return Err(g.err(1, format!("bad property id {p}"))),
        })
    } else {
        Ok(g.real_or(1, 0.0)?)
    };
    let grids = name.ends_with('1') || name.ends_with('2');
    let (a, b) = if grids {
        (d.dof(g, 2, Some(3))?, d.dof(g, 4, Some(5))?)
    } else {
        (d.dof(g, 2, None)?, d.dof(g, 3, None)?)
    };
    let (a, b) = match (a, b) {
        (Some(a), b) => (a, b),
        (None, Some(b)) => (b, None),
        (None, None) => return Err(g.err(2, "both ends are ground: it connects nothing")),
    };
    if b == Some(a) {
        return Err(g.err(4, "both ends are the same dof"));
    }
    if spring && name == "CELAS2" && g.real_or(6, 0.0)? != 0.0 {
        d.note_as("CELAS2 GE".into(), g, super::cards::DAMPING);
    }
    d.scalars.elements.push(ScalarElement {
        spring,
        id: eid,
        value,
        a,
        b,
        card: g.card,
    });
    Ok(())
}

/// Reader of PELAS (two properties per card) and PMASS (four).
pub(super) fn property<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let pelas = g.card.name == "PELAS";
    let (stride, count) = if pelas { (4, 2) } else { (2, 4) };
    for i in 0..count {
        let k = i * stride;
        if i > 0 && g.text(k).is_empty() {
            continue;
        }
        let pid = g.id(k, "PID")?;
        let v = g.real_or(k + 1, 0.0)?;
        d.properties.others.push((pid, g.card));
        let table = if pelas {
            &mut d.scalars.pelas
        } else {
            &mut d.scalars.pmass
        };
        table.insert(pid, (v, g.card));
        if pelas && g.real_or(k + 2, 0.0)? != 0.0 {
            d.note_as("PELAS GE".into(), g, super::cards::DAMPING);
        }
    }
    Ok(())
}

/// Springs and masses into the model: property values looked up, masses times WTMASS.
pub(super) fn resolve(d: &mut Bulk) -> Result<(), ImportError> {
    let wtmass = d.solution.wtmass;
    for e in std::mem::take(&mut d.scalars.elements) {
        let g = C::new(e.card, d.files);
        let value = match e.value {
            Ok(v) => v,
            Err(pid) => {
                let (table, want) = if e.spring {
                    (&d.scalars.pelas, "PELAS")
                } else {
                    (&d.scalars.pmass, "PMASS")
                };
                table.get(&pid).map(|p| p.0).ok_or_else(|| {
                    g.err(
                        1,
                        format!("references {want} {pid}, which the deck does not define"),
                    )
                })?
            }
        };
        if !value.is_finite() {
            return Err(g.err(1, format!("value {value} is not finite")));
        }
        if e.spring {
            d.b.model.springs.push(ScalarSpring {
                id: e.id,
                a: e.a,
                b: e.b,
                k: value,
            });
        } else {
            if value < 0.0 {
                return Err(g.err(1, format!("negative mass {value}")));
            }
            d.b.model.scalar_masses.push(ScalarMass {
                id: e.id,
                a: e.a,
                b: e.b,
                m: value * wtmass,
            });
        }
    }
    Ok(())
}
