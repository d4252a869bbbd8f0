//! `SFE,Elem,LKEY,PRES,KVAL,VAL1,VAL2,VAL3,VAL4` (a pressure on an element face) → the scene
//! load named `SFE`: one uniform traction ([`LoadPart::Surface`]) per loaded face.
//!
//! What was read: the MAPDL Command Reference's `SFE` (LKEY the face number listed under
//! "Surface Loads" of each element type; KVAL 0 or 1 real, 2 imaginary pressures; VAL1…VAL4 the
//! values at the face's corners) and the Element Reference's face lists, quoted alike by
//! several public sources: SOLID185 and SOLID186 "face 1 (J-I-L-K), face 2 (I-J-N-M), face 3
//! (J-K-O-N), face 4 (K-L-P-O), face 5 (L-I-M-P), face 6 (M-N-O-P)" (their corners; a
//! degenerate brick keeps the brick's numbers, a face collapsed to a line or point has no
//! area); SOLID187 "face 1 (J-I-K), face 2 (I-J-L), face 3 (J-K-L), face 4 (K-I-L)"; SHELL181
//! "face 1 (I-J-K-L) (bottom, in +N direction), face 2 (I-J-K-L) (top, in −N direction), face
//! 3 (J-I), face 4 (K-J), face 5 (L-K), face 6 (I-L)". Each solid face is listed with its
//! right-hand normal out of the element and a positive pressure acts into the element: the
//! traction along the outward normal is −p. On a shell, face 1's pressure pushes along the
//! element normal N (I-J-K-L right-hand), face 2's against it.
//!
//! A face whose corner values differ (a varying pressure) keeps the load with its `problem`, as
//! the Nastran (PLOAD4) and Abaqus importers keep non-uniform pressures: the load stays known
//! by name and is not applied. The archive's form `SFE,Elem,LKEY,Lab,KVAL,R5.0` carries VAL1…VAL4
//! on the next line (four columns of 16, as archives written by MAPDL 2022 show). Labels that
//! cannot load a structure (thermal, acoustic, electromagnetic, the fluid–solid interface flag)
//! are noted. `SFEBLOCK` (MAPDL 2022 and later) is the same command in blocks: its records are
//! element, LKEY, KVAL and VAL1…VAL4 (two archives ANSYS wrote of the Turek–Hron beam show it:
//! each of their FSIN records names, by the faces below, a boundary face of the beam's wet
//! surface, docs/ansys.md). Refused by line: other labels than PRES, imaginary pressures,
//! element lists (ALL, components), the shells' edge faces 3…6, faces of other element types,
//! collapsed faces.

use std::collections::{BTreeMap, BTreeSet};

use super::blocks::Command;
use super::constraints::Refused;
use super::list;
use crate::import::error::{parse_err, ImportError};
use crate::import::text::IdMap;
use crate::model::load::{face_nodes, solid_faces, Load, LoadPart};
use crate::model::Model;

/// Surface-load labels that cannot load a structure (an `SFEBLOCK` of them is noted): the
/// fluid–solid interface flag, thermal, acoustic and electromagnetic loads.
pub(super) const NON_STRUCTURAL_LABELS: [&str; 11] = [
    "FSIN", "CONV", "HFLUX", "RAD", "RDSF", "IMPD", "SHLD", "MXWF", "CHRGS", "INF", "PORT",
];

/// One `SFE` pressure as read (external ids).
#[derive(Debug, Clone)]
pub(super) struct Pressure {
    pub line: usize,
    pub element: u64,
    pub face: i64,
    /// VAL1 (blank = 0) and VAL2…VAL4 (`None` when blank).
    pub first: f64,
    pub others: [Option<f64>; 3],
}

/// SOLID185/186 brick faces, 0-based among the corners I…P (the Element Reference's lists).
const BRICK_FACES: [[usize; 4]; 6] = [
    [1, 0, 3, 2],
    [0, 1, 5, 4],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [3, 0, 4, 7],
    [4, 5, 6, 7],
];
/// SOLID187 faces, 0-based among the corners I…L.
const TET_FACES: [[usize; 3]; 4] = [[1, 0, 2], [0, 1, 3], [1, 2, 3], [2, 0, 3]];

/// `SFE,…`: a pressure on one element face, or a refusal; a label that cannot load a structure
/// ([`NON_STRUCTURAL_LABELS`]) is noted. `record` is the value line of the archive's form
/// `SFE,Elem,LKEY,Lab,KVAL,R5.0` (VAL1…VAL4 in columns of 16, as `CDWRITE` writes them), which
/// the caller reads after the command.
pub(super) fn sfe(
    file: &str,
    c: &Command,
    record: Option<(usize, &str)>,
    out: &mut Vec<Pressure>,
    noted: &mut BTreeMap<String, Vec<usize>>,
    refused: &mut Vec<Refused>,
) -> Result<(), ImportError> {
    let element = c.field(0);
    if element.is_empty() || !element.chars().all(|ch| ch.is_ascii_digit()) {
        refused.push((
            c.line,
            format!("SFE on '{element}': only element numbers are read"),
        ));
        return Ok(());
    }
    let lab = c.field(2).to_ascii_uppercase();
    if NON_STRUCTURAL_LABELS.contains(&lab.as_str()) {
        noted.entry(format!("SFE {lab}")).or_default().push(c.line);
        return Ok(());
    }
    if lab != "PRES" {
        refused.push((
            c.line,
            format!("SFE of {lab}: only PRES (a structural pressure) is read"),
        ));
        return Ok(());
    }
    // the archive's form: the values on the next line; the command form: fields 4…7
    let values: Vec<&str> = match record {
        Some((_, text)) => {
            // separated numbers as written; touching ones by the columns of 16
            let words: Vec<&str> = text.split_whitespace().collect();
            let separated = words.len() <= 4
                && (words.iter()).all(|w| crate::import::text::parse_f64(w).is_some());
            if separated {
                (0..4)
                    .map(|k| words.get(k).copied().unwrap_or(""))
                    .collect()
            } else {
                let lay = super::blocks::Layout {
                    ints: 0,
                    reals: 4,
                    widths: vec![16; 4],
                };
                let cols = super::blocks::columns(text, &lay);
                cols.into_iter().map(|v| v.unwrap_or("")).collect()
            }
        }
        None => (4..8).map(|k| c.field(k)).collect(),
    };
    let line = record.map_or(c.line, |(n, _)| n);
    let real = |s: &str| -> Result<f64, ImportError> {
        if s.is_empty() {
            return Ok(0.0);
        }
        crate::import::text::parse_f64(s)
            .ok_or_else(|| parse_err(file, line, "SFE", crate::import::text::bad_number(s)))
    };
    let first = real(values[0])?;
    let mut others = [None; 3];
    for (k, v) in others.iter_mut().enumerate() {
        if !values[1 + k].is_empty() {
            *v = Some(real(values[1 + k])?);
        }
    }
    let kval = c.int(file, 3)?;
    match kval {
        0 | 1 => {}
        2 if first == 0.0 && others.iter().all(|v| v.unwrap_or(0.0) == 0.0) => return Ok(()),
        _ => {
            refused.push((
                c.line,
                format!("SFE with KVAL = {kval}: only real pressures (KVAL 0 or 1) are read"),
            ));
            return Ok(());
        }
    }
    out.push(Pressure {
        line: c.line,
        element: c.int(file, 0)?.max(0) as u64,
        face: c.int(file, 1)?,
        first,
        others,
    });
    Ok(())
}

/// `SFEBLOCK,NVAL,Lab,…`, format `(i9,i4,i4,6(pg20.9))`: the blocked `SFE` that `CDWRITE`
/// writes (MAPDL 2022 and later), one record per face and KVAL — element, LKEY, KVAL, VAL1…VAL4
/// (NVAL of them) — up to `SFE,end,LOC,-1`. Each record of PRES is read as its `SFE` command
/// (a KVAL 2 record of zeros, which `CDWRITE` writes after each real one, adds nothing); a
/// label that cannot load a structure is noted, any other refused by the block's line.
pub(super) fn sfeblock(
    file: &str,
    c: &Command,
    lines: &mut super::blocks::Lines<'_>,
    out: &mut Vec<Pressure>,
    noted: &mut BTreeMap<String, Vec<usize>>,
    refused: &mut Vec<Refused>,
) -> Result<(), ImportError> {
    let label = c.field(1).to_ascii_uppercase();
    let values = c.int(file, 0)?;
    let why = if NON_STRUCTURAL_LABELS.contains(&label.as_str()) {
        noted
            .entry(format!("SFEBLOCK {label}"))
            .or_default()
            .push(c.line);
        None
    } else if label != "PRES" {
        Some(format!(
            "SFEBLOCK of {label}: only PRES (a structural pressure) is read"
        ))
    } else if !(1..=4).contains(&values) {
        Some(format!(
            "SFEBLOCK with NVAL = {values}: a face's values are VAL1…VAL4 (1 to 4 of them)"
        ))
    } else {
        for (line, cols) in lines.sfeblock(c.line)? {
            let col = |k: usize| cols.get(k).copied().flatten().unwrap_or("");
            let given = (0..4).map(|k| if k < values as usize { col(3 + k) } else { "" });
            let record = Command {
                line,
                name: "SFE".into(),
                fields: [col(0), col(1), "PRES", col(2)]
                    .into_iter()
                    .chain(given)
                    .collect(),
            };
            sfe(file, &record, None, out, noted, refused)?;
        }
        return Ok(());
    };
    if let Some(why) = why {
        refused.push((c.line, why));
    }
    lines.skip_sfeblock();
    Ok(())
}

/// The face's uniform pressure, or why not: the corner values VAL2… (up to the face's
/// `corners`) all blank or all equal to VAL1.
fn uniform(p: &Pressure, corners: usize) -> Result<f64, String> {
    let given = &p.others[..corners - 1];
    if given.iter().all(Option::is_none) || given.iter().all(|v| *v == Some(p.first)) {
        return Ok(p.first);
    }
    Err(format!(
        "a varying pressure on face {} of element {} (VAL1 {}, VAL2…VAL4 {:?}) is not \
         supported: give one uniform VAL1",
        p.face, p.element, p.first, given
    ))
}

/// Where a pressure goes: the face's model nodes (outward right-hand order, mid-side nodes
/// after the corners) and the traction along that normal per unit pressure.
type Placed = (Vec<usize>, f64);

impl super::Archive {
    /// The `SFE` pressures → the scene load `SFE` (module doc). `elements`: element id → the
    /// model element formed (`None`: no stiffness).
    pub(super) fn surface_loads(
        &mut self,
        file: &str,
        node_map: &IdMap,
        elements: &BTreeMap<u64, Option<usize>>,
        model: &mut Model,
    ) -> Result<(), ImportError> {
        if self.pressures.is_empty() {
            return Ok(());
        }
        let records: BTreeMap<u64, usize> = (self.elements.iter().enumerate())
            .map(|(i, r)| (r.id, i))
            .collect();
        let mut parts = Vec::new();
        let mut problem = None;
        let mut refused = Vec::new();
        for p in &self.pressures {
            let Some(&r) = records.get(&p.element) else {
                return Err(parse_err(
                    file,
                    p.line,
                    "SFE",
                    format!("unknown element {}", p.element),
                ));
            };
            // an element not formed (refused or dropped) is reported by its own line
            let Some(slot) = elements.get(&p.element) else {
                continue;
            };
            let placed = match slot {
                None => Err(format!(
                    "SFE on element {}, which carries no stiffness",
                    p.element
                )),
                Some(e) => self.place(p, r, *e, node_map, model),
            };
            let (nodes, sign, corners) = match placed {
                Ok(x) => x,
                Err(why) => {
                    refused.push((p.line, why));
                    continue;
                }
            };
            match uniform(p, corners) {
                Ok(value) => parts.push(LoadPart::Surface {
                    nodes,
                    traction: sign * value,
                    element: p.element,
                }),
                Err(why) => {
                    problem.get_or_insert_with(|| format!("SFE at {file}:{}: {why}", p.line));
                }
            }
        }
        for (line, why) in refused {
            self.refuse(line, "SFE", why);
        }
        let lines: Vec<usize> = self.pressures.iter().map(|p| p.line).collect();
        model.loads.push(Load {
            name: "SFE".into(),
            source: format!("SFE ({file}:{})", list(&lines)),
            selected: true,
            parts,
            problem,
        });
        let warnings =
            crate::model::load::problem_warnings(&model.loads[model.loads.len() - 1..], file);
        model.warnings.extend(warnings);
        Ok(())
    }

    /// The face of pressure `p` on element record `r` formed as model element `e`: its nodes,
    /// the traction per unit pressure and the face's corner count.
    fn place(
        &self,
        p: &Pressure,
        r: usize,
        e: usize,
        node_map: &IdMap,
        model: &Model,
    ) -> Result<(Vec<usize>, f64, usize), String> {
        let record = &self.elements[r];
        let name = self
            .types
            .get(&record.etype)
            .map(|t| t.name())
            .unwrap_or_default();
        let face = usize::try_from(p.face).unwrap_or(0);
        let corner_ids: Vec<u64> = match name.as_str() {
            "SOLID185" | "SOLID186" => match BRICK_FACES.get(face.wrapping_sub(1)) {
                Some(f) => f.iter().map(|&c| record.nodes[c]).collect(),
                None => return Err(format!("SFE face {} of a {name} (faces 1…6)", p.face)),
            },
            "SOLID187" => match TET_FACES.get(face.wrapping_sub(1)) {
                Some(f) => f.iter().map(|&c| record.nodes[c]).collect(),
                None => return Err(format!("SFE face {} of a SOLID187 (faces 1…4)", p.face)),
            },
            "SHELL181" => {
                let el = &model.elements[e];
                let sign = match face {
                    1 => 1.0,
                    2 => -1.0,
                    _ => {
                        return Err(format!(
                            "SFE face {} of a SHELL181: only the surface pressures (faces 1 and \
                             2) are read, not the edge faces 3…6",
                            p.face
                        ))
                    }
                };
                return Ok((el.nodes.clone(), sign, el.nodes.len()));
            }
            _ => {
                return Err(format!(
                    "SFE on a {name} element: its face numbers are not read (SOLID185, SOLID186, \
                     SOLID187 and SHELL181 are)"
                ))
            }
        };
        let corners: BTreeSet<usize> = (corner_ids.iter())
            .filter_map(|&id| node_map.get(id))
            .collect();
        if corners.len() < 3 {
            return Err(format!(
                "SFE face {} of element {}: the face is collapsed (no area)",
                p.face, p.element
            ));
        }
        placed_on_solid(model, e, &corners)
            .map(|(nodes, t)| (nodes, t, corners.len()))
            .ok_or_else(|| {
                format!(
                    "SFE face {} of element {}: no face of the element formed has its corners",
                    p.face, p.element
                )
            })
    }
}

/// The face of solid model element `e` whose distinct corners are `corners`: its nodes and −1
/// (a positive pressure acts into the element, against the outward normal).
fn placed_on_solid(model: &Model, e: usize, corners: &BTreeSet<usize>) -> Option<Placed> {
    let el = &model.elements[e];
    let (faces, edges) = solid_faces(el.kind)?;
    let face = faces.iter().find(|f| {
        let set: BTreeSet<usize> = f.iter().map(|&c| el.nodes[c]).collect();
        set == *corners
    })?;
    Some((face_nodes(&el.nodes, face, edges)?, -1.0))
}
