//! Direct matrix input DMIG (MSC QRG "DMIG"), added to the body's stiffness or mass when the
//! case control selects it by `K2GG` or `M2GG` (module `case_control`), into a
//! [`crate::model::DofMatrix`].
//!
//! * Header `DMIG NAME 0 IFO TIN TOUT POLAR – NCOL`: IFO 6 (symmetric: each off-diagonal term
//!   written once, above or below the diagonal — both is an error, as MSC's fatal message) or 1
//!   (square, which must be symmetric here: a normal-modes analysis has symmetric K and M); TIN
//!   1 or 2 (real). Complex (TIN 3, 4) and rectangular (IFO 2, 9) matrices are refused for
//!   K2GG/M2GG.
//! * Column `DMIG NAME GJ CJ – G1 C1 A1 B1 / G2 C2 A2 B2 …`: the terms A_i at row (G_i, C_i) of
//!   column (GJ, CJ); components 1–6 of a grid (in its displacement frame: the g-set) or 0 (or
//!   blank) of a scalar point. A term written twice is an error.
//! * `K2GG = s*NAME, …`: the sum of the named matrices, each times its factor; `M2GG` alike,
//!   also times WTMASS (the g-set mass is in WTMASS units, MSC QRG "WTMASS"). A DMIG no
//!   selection names is a note; a selected name no DMIG defines is an error at the command.

use std::collections::{BTreeMap, BTreeSet};

use super::case_control::{CaseControl, Effective, MatrixSelection};
use super::fields::C;
use super::lex::Card;
use super::reading::Bulk;
use crate::import::error::{parse_err, ImportError};
use crate::import::text::places;
use crate::model::{DofMatrix, NodeDof};

/// Reader of DMIG: header and column cards kept by name (read when selected).
pub(super) fn dmig<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let name = g.text(0).to_ascii_uppercase();
    if name.is_empty() {
        return Err(g.err(0, "a DMIG needs a matrix NAME"));
    }
    if name == "UACCEL" {
        d.note_as(
            "DMIG UACCEL".into(),
            g,
            "the accelerations of inertia relief in a static analysis: not part of the body",
        );
        return Ok(());
    }
    if g.int(1)? == Some(0) {
        if let Some(first) = d.dmig.headers.get(&name) {
            return Err(g.err(
                0,
                format!(
                    "second header of DMIG {name} (the first is on line {})",
                    first.loc.line
                ),
            ));
        }
        d.dmig.headers.insert(name, g.card);
    } else {
        d.dmig.columns.entry(name).or_default().push(g.card);
    }
    Ok(())
}

/// The DMIG matrices the case control selects into the model; a note for each DMIG not
/// selected.
pub(super) fn resolve(
    d: &mut Bulk,
    case: &CaseControl,
    effective: &Effective,
) -> Result<(), ImportError> {
    let files = d.files;
    let mut used: BTreeSet<String> = BTreeSet::new();
    for sel in case.matrix_selections(effective.subcase) {
        let matrix = selected(d, sel, &mut used)?;
        d.b.model.dof_matrices.push(matrix);
    }
    for name in d.dmig.columns.keys() {
        if !d.dmig.headers.contains_key(name) {
            let c = C::new(d.dmig.columns[name][0], files);
            return Err(c.err(
                0,
                format!("DMIG {name} has columns but no header (DMIG {name} 0 IFO TIN …)"),
            ));
        }
    }
    let unused: Vec<String> = (d.dmig.headers.iter())
        .filter(|(name, _)| !used.contains(*name))
        .map(|(name, card)| places(&format!("DMIG {name}"), &[card.loc], files))
        .collect();
    if !unused.is_empty() {
        d.b.model.deck.notes.push(format!(
            "{} not read: no K2GG or M2GG of the case control selects it, so it is not part of \
             the structure",
            unused.join("; ")
        ));
    }
    Ok(())
}

/// The matrix of one `K2GG`/`M2GG` command: its DMIGs, each times its factor (and WTMASS for
/// a mass).
fn selected(
    d: &Bulk,
    sel: &MatrixSelection,
    used: &mut BTreeSet<String>,
) -> Result<DofMatrix, ImportError> {
    let command = if sel.mass { "M2GG" } else { "K2GG" };
    let files = d.files;
    let scale = if sel.mass { d.solution.wtmass } else { 1.0 };
    let mut terms = Vec::new();
    for (factor, name) in &sel.terms {
        let Some(header) = d.dmig.headers.get(name) else {
            return Err(parse_err(
                &files[sel.loc.file as usize],
                sel.loc.line as usize,
                format!("{command} (case control)"),
                format!("selects DMIG {name}, but the bulk data has no DMIG {name} header"),
            ));
        };
        used.insert(name.clone());
        let columns = d.dmig.columns.get(name).map_or(&[][..], Vec::as_slice);
        for (a, b, v) in matrix(d, header, columns)? {
            terms.push((a, b, v * factor * scale));
        }
    }
    let names: Vec<String> = (sel.terms.iter())
        .map(|(f, n)| {
            if *f == 1.0 {
                n.clone()
            } else {
                format!("{f}*{n}")
            }
        })
        .collect();
    let what = format!("{command} = {}", names.join(", "));
    Ok(if sel.mass {
        DofMatrix {
            what,
            stiffness: Vec::new(),
            mass: terms,
            basic: false,
        }
    } else {
        DofMatrix {
            what,
            stiffness: terms,
            mass: Vec::new(),
            basic: false,
        }
    })
}

/// One DMIG matrix as terms (row, column, value), both triangles (module doc).
fn matrix(
    d: &Bulk,
    header: &Card,
    columns: &[&Card],
) -> Result<Vec<(NodeDof, NodeDof, f64)>, ImportError> {
    let h = C::new(header, d.files);
    let ifo = h.int(2)?;
    if !matches!(ifo, Some(1 | 6)) {
        return Err(h.err(
            2,
            format!(
                "IFO {}: a matrix added to K or M (K2GG, M2GG) is square (1) or symmetric (6)",
                h.text(2)
            ),
        ));
    }
    match h.int(3)? {
        Some(1 | 2) => {}
        Some(3 | 4) => {
            return Err(h.err(
                3,
                "TIN 3/4: a complex matrix cannot be added to a real normal-modes analysis",
            ))
        }
        _ => return Err(h.err(3, format!("TIN {}: 1 or 2 (real) expected", h.text(3)))),
    }
    let mut terms: BTreeMap<(NodeDof, NodeDof), (f64, &Card, usize)> = BTreeMap::new();
    for &card in columns {
        let g = C::new(card, d.files);
        let col = d
            .dof(&g, 1, Some(2))?
            .ok_or_else(|| g.err(1, "column grid GJ is blank"))?;
        let mut k = 4;
        while k < card.fields.len() {
            if (k..k + 4).all(|f| g.text(f).is_empty()) {
                k += 4;
                continue;
            }
            let row = d
                .dof(&g, k, Some(k + 1))?
                .ok_or_else(|| g.err(k, "row grid is blank, with a term given"))?;
            let v = g
                .real(k + 2)?
                .ok_or_else(|| g.err(k + 2, "the term's value is blank"))?;
            if !v.is_finite() {
                return Err(g.err(k + 2, format!("value {v} is not finite")));
            }
            if let Some((_, first, _)) = terms.insert((row, col), (v, card, k)) {
                return Err(g.err(
                    k,
                    format!("this term is also given on line {}", first.loc.line),
                ));
            }
            k += 4;
        }
    }
    let mut out = Vec::with_capacity(2 * terms.len());
    let largest = terms.values().fold(0.0f64, |a, t| a.max(t.0.abs()));
    for (&(row, col), &(v, card, k)) in &terms {
        let g = C::new(card, d.files);
        let mirror = terms.get(&(col, row));
        if ifo == Some(6) {
            if row != col && mirror.is_some() {
                return Err(g.err(
                    k,
                    "term given both above and below the diagonal of a symmetric (IFO 6) matrix",
                ));
            }
            out.push((row, col, v));
            if row != col {
                out.push((col, row, v));
            }
        } else {
            let w = mirror.map_or(0.0, |m| m.0);
            if (v - w).abs() > 1e-9 * largest {
                return Err(g.err(
                    k + 2,
                    format!(
                        "the square (IFO 1) matrix is not symmetric: {v} here, {w} at the mirror \
                         term; K and M of a normal-modes analysis are symmetric"
                    ),
                ));
            }
            out.push((row, col, v));
        }
    }
    Ok(out)
}
