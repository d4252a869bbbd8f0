//! Abaqus/CalculiX loads of the steps → named scene loads ([`Load`]): `*CLOAD` (node or node
//! set, dof 1–6, magnitude), `*DLOAD` `GRAV` (magnitude and direction) and `CENTRIF` (Ω², a
//! point of the axis, its direction) on the whole model, and
//! `Pn` / `P` (uniform pressure on face n of a solid, on a shell element), grouped per `*STEP`:
//! one load named after the step (`NAME=`, else `STEP_<k>`), every step with loads selected
//! (each is a load case of the scene). Signs (ccx manual, "*DLOAD": "for shell elements …
//! pressure in the direction of the normal on the shell"; Abaqus Analysis User's Guide,
//! "Distributed loads": for conventional shells the force points along the SPOS normal, for a
//! solid's facet against its outward normal): positive pressure acts into a solid's face and
//! along a shell's right-hand normal (`P` = `P1`, on the SNEG face; `P2` on SPOS against it).
//! Face numbering: C3D8/C3D20 S1 = 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3,
//! S5 = 3-7-8-4, S6 = 4-8-5-1; C3D4/C3D10 S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1;
//! C3D6/C3D15 S1 = 1-2-3, S2 = 4-6-5, S3 = 1-4-5-2, S4 = 2-5-6-3, S5 = 3-6-4-1 (the tables of
//! [`crate::model::load::solid_faces`]). Loads are not propagated from step to step here, and
//! `AMPLITUDE=` is ignored (a scene scales each load in time itself).

use std::collections::BTreeMap;

use crate::import::error::ImportError;
use crate::import::text::{parse_f64, parse_u64, IdMap, Loc};
use crate::model::load::{face_nodes, solid_faces};
use crate::model::{ElementKind, Load, LoadPart, Model};

/// The load keywords.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum LoadKeyword {
    Cload,
    Dload,
}

/// One data line of a load keyword, with its step.
#[derive(Debug, Clone)]
pub(super) struct RawLoad {
    pub keyword: LoadKeyword,
    /// 0-based step number and its name.
    pub step: (usize, Option<String>),
    pub fields: Vec<String>,
    pub loc: Loc,
}

/// What the resolve pass needs of the parsed deck.
pub(super) struct Resolve<'a> {
    pub model: &'a Model,
    pub nodes: &'a IdMap,
    pub elems: &'a IdMap,
    pub node_sets: &'a BTreeMap<String, Vec<usize>>,
    pub element_sets: &'a BTreeMap<String, Vec<usize>>,
    /// Whether element `e` (index) was written as a shell (S3, S4, …): after ccx's expansion its
    /// kind is the brick's, and a `P` on it is the brick's `P1`.
    pub written_as_shell: &'a dyn Fn(usize) -> bool,
    pub err: &'a dyn Fn(Loc, String, String) -> ImportError,
    pub at: &'a dyn Fn(Loc) -> String,
}

fn num(r: &Resolve, raw: &RawLoad, k: usize, ent: &str, what: &str) -> Result<f64, ImportError> {
    let s = raw.fields.get(k).map_or("", |s| s.trim());
    parse_f64(s).ok_or_else(|| {
        (r.err)(
            raw.loc,
            ent.to_owned(),
            format!("{what}: '{s}' is not a number"),
        )
    })
}

/// The name of step `k`'s (0-based) load: the step's `NAME=`, else `STEP_<k+1>`.
pub(super) fn step_load_name(k: usize, name: &Option<String>) -> String {
    name.as_ref()
        .map(|n| n.trim().to_ascii_uppercase().replace(' ', "_"))
        .filter(|n| !n.is_empty())
        .unwrap_or_else(|| format!("STEP_{}", k + 1))
}

/// Resolve the load lines into one load per step (module doc).
pub(super) fn resolve(raws: &[RawLoad], r: &Resolve) -> Result<Vec<Load>, ImportError> {
    let mut steps: BTreeMap<usize, Load> = BTreeMap::new();
    for raw in raws {
        let kw = match raw.keyword {
            LoadKeyword::Cload => "*CLOAD",
            LoadKeyword::Dload => "*DLOAD",
        };
        let first = raw.fields.first().map_or("", |s| s.trim());
        let ent = format!("{kw} {first}");
        let result = (|| -> Result<Vec<LoadPart>, ImportError> {
            let mut parts = Vec::new();
            match raw.keyword {
                LoadKeyword::Cload => {
                    let nodes: Vec<usize> = match parse_u64(first) {
                        Some(id) => vec![r.nodes.get(id).ok_or_else(|| {
                            (r.err)(raw.loc, ent.clone(), format!("unknown node {id}"))
                        })?],
                        None => r
                            .node_sets
                            .get(&first.to_ascii_uppercase())
                            .cloned()
                            .ok_or_else(|| {
                                (r.err)(raw.loc, ent.clone(), format!("unknown node set {first}"))
                            })?,
                    };
                    let dof = raw
                        .fields
                        .get(1)
                        .and_then(|s| parse_u64(s.trim()))
                        .filter(|d| (1..=6).contains(d))
                        .ok_or_else(|| {
                            (r.err)(raw.loc, ent.clone(), "the dof must be 1 … 6".into())
                        })? as usize;
                    let v = num(r, raw, 2, &ent, "magnitude")?;
                    for node in nodes {
                        if r.model.nodes[node].displacement_frame.is_some() {
                            return Err((r.err)(raw.loc, ent.clone(), format!("node {} has a *TRANSFORM: concentrated loads in a transformed system are not supported", r.model.nodes[node].id)));
                        }
                        let mut values = [0.0; 6];
                        values[dof - 1] = v;
                        parts.push(LoadPart::Nodal { node, values });
                    }
                }
                LoadKeyword::Dload => {
                    let ty = raw
                        .fields
                        .get(1)
                        .map_or(String::new(), |s| s.trim().to_ascii_uppercase());
                    let elements: Vec<usize> = if first.is_empty() {
                        (0..r.model.elements.len()).collect()
                    } else {
                        match parse_u64(first) {
                            Some(id) => vec![r.elems.get(id).ok_or_else(|| {
                                (r.err)(raw.loc, ent.clone(), format!("unknown element {id}"))
                            })?],
                            None => r
                                .element_sets
                                .get(&first.to_ascii_uppercase())
                                .cloned()
                                .ok_or_else(|| {
                                    (r.err)(
                                        raw.loc,
                                        ent.clone(),
                                        format!("unknown element set {first}"),
                                    )
                                })?,
                        }
                    };
                    if ty == "GRAV" || ty == "CENTRIF" {
                        let structural = r
                            .model
                            .elements
                            .iter()
                            .filter(|e| e.property.is_some())
                            .count();
                        let covered = elements
                            .iter()
                            .filter(|&&e| r.model.elements[e].property.is_some())
                            .count();
                        if covered < structural {
                            return Err((r.err)(raw.loc, ent, format!("{ty} on {covered} of the {structural} elements: a body force on part of the model is not supported (give the whole model's element set)")));
                        }
                        let v = |k: usize, what: &str| num(r, raw, k, &ent, what);
                        if ty == "GRAV" {
                            let g = v(2, "magnitude")?;
                            let d = [
                                v(3, "direction x")?,
                                v(4, "direction y")?,
                                v(5, "direction z")?,
                            ];
                            parts.push(LoadPart::Gravity {
                                accel: d.map(|x| x * g),
                            });
                        } else {
                            // ELSET, CENTRIF, Ω², a point of the axis, the axis direction
                            let omega2 = v(2, "Ω²")?;
                            let point = [
                                v(3, "axis point x")?,
                                v(4, "axis point y")?,
                                v(5, "axis point z")?,
                            ];
                            let axis = [
                                v(6, "axis direction x")?,
                                v(7, "axis direction y")?,
                                v(8, "axis direction z")?,
                            ];
                            if omega2.is_nan() || omega2 < 0.0 || axis == [0.0; 3] {
                                return Err((r.err)(raw.loc, ent, format!("CENTRIF needs Ω² ≥ 0 and a nonzero axis direction (got Ω² = {omega2}, axis {axis:?})")));
                            }
                            parts.push(LoadPart::Centrifugal {
                                omega2,
                                point,
                                axis,
                            });
                        }
                    } else if let Some(face) = ty.strip_prefix('P') {
                        let p = num(r, raw, 2, &ent, "pressure")?;
                        for e in elements {
                            let el = &r.model.elements[e];
                            // ccx applies a shell's P to its expanded brick's bottom face
                            let face = match face.is_empty()
                                && el.kind.is_solid()
                                && (r.written_as_shell)(e)
                            {
                                true => "1",
                                false => face,
                            };
                            let (nodes, traction) = match (el.kind, face) {
                            // flexbody's own shells (--inp-shells native): `P` and a pressure
                            // on SNEG (P1) push along the normal, on SPOS (P2) against it (ccx 2.20)
                            (ElementKind::Quad4 | ElementKind::Tri3, "" | "1") => (el.nodes.clone(), p),
                            (ElementKind::Quad4 | ElementKind::Tri3, "2") => (el.nodes.clone(), -p),
                            (k, n) if k.is_solid() && !n.is_empty() => {
                                let (faces, edges) = solid_faces(k).ok_or_else(|| {
                                    (r.err)(raw.loc, ent.clone(), format!("element {}: no faces", el.id))
                                })?;
                                let f = n
                                    .parse::<usize>()
                                    .ok()
                                    .filter(|f| (1..=faces.len()).contains(f))
                                    .ok_or_else(|| {
                                        (r.err)(raw.loc, ent.clone(), format!("load type {ty}: element {} ({k:?}) has faces P1 … P{}", el.id, faces.len()))
                                    })?;
                                let nodes = face_nodes(&el.nodes, faces[f - 1], edges).ok_or_else(|| {
                                    (r.err)(raw.loc, ent.clone(), format!("element {}: face {f} has no mid-side nodes", el.id))
                                })?;
                                (nodes, -p)
                            }
                            (k, _) => {
                                return Err((r.err)(raw.loc, ent.clone(), format!("load type {ty} on element {} ({k:?}): a solid takes its faces P1 … Pn, a 3- or 4-node shell P, P1 (SNEG) or P2 (SPOS)", el.id)))
                            }
                        };
                            parts.push(LoadPart::Surface {
                                nodes,
                                traction,
                                element: el.id,
                            });
                        }
                    } else {
                        return Err((r.err)(raw.loc, ent, format!("load type '{ty}' is not supported (GRAV, CENTRIF, P on shells, P1 … P6 on solids)")));
                    }
                }
            }
            Ok(parts)
        })();
        let (parts, problem) = match result {
            Ok(p) => (p, None),
            Err(e) => (Vec::new(), Some(e.to_string())),
        };
        let (k, name) = &raw.step;
        let load = steps.entry(*k).or_insert_with(|| Load {
            name: step_load_name(*k, name),
            source: String::new(),
            selected: true,
            parts: Vec::new(),
            problem: None,
        });
        load.parts.extend(parts);
        if load.problem.is_none() {
            load.problem = problem;
        }
        let here = format!("{kw} ({})", (r.at)(raw.loc));
        if !load.source.contains(&here) {
            if !load.source.is_empty() {
                load.source.push_str(", ");
            }
            load.source.push_str(&here);
        }
    }
    Ok(steps.into_values().collect())
}
