//! Element-face `*SURFACE`s as CalculiX 2.20 reads them, resolved in one place for `*TIE`
//! (`tie.rs`) and `*COUPLING` (`coupling.rs`):
//!
//! * a solid's `Sn` is ccx's face n (`tie_search::ccx_face_nodes`: its corners, then its
//!   mid-side nodes, in ccx's order);
//! * a shell's (S3, S4, S4R, S6, S8, S8R) `SNEG` is `S1` and `SPOS` is `S2` (ccx's
//!   `surfaces.f` turns the labels NEG and POS into 1 and 2 and keeps them for shells). ccx
//!   expands the shell into a brick whose face 1 is its bottom (the −n side, nodes x − t/2·n) and
//!   face 2 its top: under `--inp-shells expanded` the face is that brick face (the expansion then
//!   runs before the ties and couplings, `resolve::finish`); under `--inp-shells native` it is
//!   the shell's own nodes (corners, then mid-side nodes), each with its lever d = (±1/2 −
//!   OFFSET)·t·n to the face (n: the unit normal of the element's interpolation at the node, t: its thickness), so
//!   that a tie holds the face point u + θ × d of a node. A shell's `S3` … `S6` (its edges) are
//!   refused.

use std::collections::BTreeSet;

use super::sets::Sets;
use super::shell_expansion::{node_normal, Expansion, SHELL_TYPES};
use super::tie_search::ccx_face_nodes;
use super::{fields, Parser};
use crate::import::error::ImportError;
use crate::import::text::{parse_u64, Loc};
use crate::model::{NodeIndex, RigidElement, Section};

/// One face of an element-face surface: its element id and nodes (corners, then mid-side
/// nodes), and for a native shell's face each node's lever from the node to the face.
pub(super) struct Face {
    pub(super) element: u64,
    pub(super) nodes: Vec<NodeIndex>,
    pub(super) lever: Option<Vec<[f64; 3]>>,
}

impl Parser {
    /// A data line of an element-face `*SURFACE`: element id or element set, face `Sn`
    /// (n = 1 … 6), `SNEG` (= `S1`) or `SPOS` (= `S2`).
    pub(super) fn element_surface_line(
        &mut self,
        name: String,
        line: &str,
        loc: Loc,
    ) -> Result<(), ImportError> {
        let v: Vec<&str> = fields(line).collect();
        let face = v
            .get(1)
            .map(|s| s.trim().to_ascii_uppercase())
            .and_then(|s| match s.as_str() {
                "SNEG" => Some(1),
                "SPOS" => Some(2),
                _ => s.strip_prefix('S').and_then(|n| n.parse::<usize>().ok()),
            })
            .filter(|n| (1..=6).contains(n));
        let Some(face) = face else {
            return Err(self.err(
                loc,
                format!("*SURFACE NAME={name}"),
                "element faces are given as 'element or element set, Sn' (n = 1 … 6), SNEG or \
                 SPOS",
            ));
        };
        (self.element_surfaces.entry(name).or_default()).push((
            v[0].trim().to_ascii_uppercase(),
            face,
            loc,
        ));
        Ok(())
    }

    /// The elements (indices) of one element-face surface line's target.
    fn face_elements(
        &self,
        name: &str,
        target: &str,
        sets: &Sets,
        at: Loc,
        ent: &str,
    ) -> Result<Vec<usize>, ImportError> {
        match parse_u64(target) {
            Some(id) => Ok(vec![sets.elems.get(id).ok_or_else(|| {
                self.err(
                    at,
                    ent.to_owned(),
                    format!("*SURFACE {name}: unknown element {id}"),
                )
            })?]),
            None => sets.element_sets.get(target).cloned().ok_or_else(|| {
                self.err(
                    at,
                    ent.to_owned(),
                    format!("*SURFACE {name}: unknown element set {target}"),
                )
            }),
        }
    }

    /// Whether a surface named by a `*TIE` or `*COUPLING` holds faces of shell elements, or a
    /// face pressure `Pn` (`*DLOAD`, or `*DSLOAD` on `SNEG`/`SPOS`) acts on a shell: then the
    /// expanded shells' bricks must exist before the ties are searched and the loads resolved
    /// (a shell's `P1`/`P2` are its brick's bottom and top faces, as ccx applies them).
    pub(super) fn shell_faces_in_use(&self, sets: &Sets) -> bool {
        let is_shell = |e: usize| SHELL_TYPES.contains(&self.b.elem_card[e]);
        let face_pressure_on_shell = (self.loads.iter())
            .filter(|l| l.keyword == super::loads::LoadKeyword::Dload)
            .filter(|l| l.fields.get(1).is_some_and(|t| is_face_pressure(t)))
            .filter_map(|l| l.fields.first())
            .filter_map(|t| {
                let t = t.trim().to_ascii_uppercase();
                self.face_elements("", &t, sets, Loc::default(), "").ok()
            })
            .flatten()
            .any(is_shell);
        if face_pressure_on_shell {
            return true;
        }
        let mut names: BTreeSet<&str> = BTreeSet::new();
        for t in &self.ties {
            if let Some((s, m)) = &t.surfaces {
                names.extend([s.as_str(), m.as_str()]);
            }
        }
        names.extend(self.couplings.iter().map(|c| c.surface.as_str()));
        (names.iter().filter_map(|n| self.element_surfaces.get(*n)))
            .flatten()
            .filter_map(|(target, _, at)| self.face_elements("", target, sets, *at, "").ok())
            .flatten()
            .any(is_shell)
    }

    /// The faces of an element-face surface (`None`: no such surface), module doc.
    pub(super) fn surface_faces(
        &self,
        name: &str,
        sets: &Sets,
        ent: &str,
    ) -> Result<Option<Vec<Face>>, ImportError> {
        let Some(lines) = self.element_surfaces.get(name) else {
            return Ok(None);
        };
        let mut out = Vec::new();
        for (target, face, at) in lines {
            for e in self.face_elements(name, target, sets, *at, ent)? {
                let el = &self.b.model.elements[e];
                let card = self.b.elem_card[e];
                let err = |why: String| {
                    self.err(
                        *at,
                        ent.to_owned(),
                        format!("*SURFACE {name}: element {} ({card}) {why}", el.id),
                    )
                };
                let shell = SHELL_TYPES.contains(&card);
                if shell && *face > 2 {
                    return Err(err(format!(
                        "has no face S{face}: a shell's faces are SNEG (S1) and SPOS (S2); its \
                         edges are not supported"
                    )));
                }
                if shell && !el.kind.is_solid() {
                    out.push(self.native_shell_face(e, *face).map_err(err)?);
                    continue;
                }
                let nodes = ccx_face_nodes(el.kind, &el.nodes, *face)
                    .ok_or_else(|| err(format!("has no solid face S{face}")))?;
                out.push(Face {
                    element: el.id,
                    nodes,
                    lever: None,
                });
            }
        }
        Ok(Some(out))
    }

    /// The face SNEG (1) or SPOS (2) of native shell element `e`: its nodes, each with its
    /// lever (∓1/2 − OFFSET)·t·n (module doc).
    fn native_shell_face(&self, e: usize, face: usize) -> Result<Face, String> {
        let model = &self.b.model;
        let el = &model.elements[e];
        let section = el.property.map(|p| &model.properties[p].section);
        let Some(Section::Shell(sh)) = section else {
            return Err("has no shell section".into());
        };
        let thickness = match model.shell_thickness.get(&e) {
            Some(t) => t.clone(),
            None => vec![sh.thickness; el.nodes.len()],
        };
        let x: Vec<[f64; 3]> = el.nodes.iter().map(|&n| model.nodes[n].x).collect();
        // the section's OFFSET puts the mid-surface −OFFSET·t from the nodes
        let offset = el.property.map_or(0.0, |p| self.sections[p].shell_offset);
        let side = if face == 2 { 0.5 } else { -0.5 } - offset;
        let mut lever = Vec::with_capacity(x.len());
        for (j, t) in thickness.iter().enumerate() {
            let n = node_normal(el.kind, &x, j);
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if !(len > 0.0 && len.is_finite()) {
                return Err(format!("is degenerate at its node {}", j + 1));
            }
            lever.push(n.map(|c| side * t * c / len));
        }
        Ok(Face {
            element: el.id,
            nodes: el.nodes.clone(),
            lever: Some(lever),
        })
    }

    /// Ties and couplings resolved after the expansion (`finish`) must not name the shell nodes
    /// themselves: the expansion's equations did not see them (ccx would join such a node as a
    /// connected one).
    pub(super) fn refuse_shell_nodes_after_expansion(
        &self,
        x: &Expansion,
        (mpcs, rigid): (usize, usize),
        tie_loc: Option<Loc>,
    ) -> Result<(), ImportError> {
        let m = &self.b.model;
        let in_mpc = (m.mpcs[mpcs..].iter())
            .flat_map(|c| c.terms.iter().map(|t| t.0.node))
            .find(|&n| x.is_shell_node(n))
            .map(|n| (n, "*TIE"));
        let in_rigid = (m.rigid_elements[rigid..].iter())
            .flat_map(|r| match r {
                RigidElement::Rbe2 {
                    independent,
                    dependent,
                    ..
                } => std::iter::once(*independent)
                    .chain(dependent.iter().copied())
                    .collect::<Vec<_>>(),
                RigidElement::Rbe3 {
                    reference,
                    independent,
                    ..
                } => std::iter::once(*reference)
                    .chain(independent.iter().map(|t| t.0))
                    .collect(),
            })
            .find(|&n| x.is_shell_node(n))
            .map(|n| (n, "*COUPLING"));
        let Some((n, what)) = in_mpc.or(in_rigid) else {
            return Ok(());
        };
        let loc = match what {
            "*TIE" => tie_loc,
            _ => self.couplings.first().map(|c| c.loc),
        };
        Err(self.err(
            loc.unwrap_or_default(),
            what,
            format!(
                "names shell node {} itself, in a deck whose ties or couplings also name faces \
                 of shells (SPOS, SNEG): not supported (name the shell's faces, or the nodes of \
                 a node surface in a deck without shell faces)",
                m.nodes[n].id
            ),
        ))
    }
}

/// `Pn` (n = 1 … 9): a face pressure, as against a shell's `P`.
fn is_face_pressure(load_type: &str) -> bool {
    let t = load_type.trim().to_ascii_uppercase();
    t.strip_prefix('P')
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
}
