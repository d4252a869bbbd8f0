//! `*COUPLING, REF NODE=…, SURFACE=…, CONSTRAINT NAME=…[, ORIENTATION=…]` followed by
//! `*KINEMATIC` or `*DISTRIBUTING`, as CalculiX 2.20 reads them (`couplings.f`), into the
//! model's rigid elements:
//!
//! * the surface: element faces (`*SURFACE, TYPE=ELEMENT`, `S1 … S6` of solids; every face
//!   node, corners and mid-side nodes, as ccx collects them) or a node surface
//!   (`*SURFACE, TYPE=NODE`, Abaqus's form; ccx refuses it for `*DISTRIBUTING`);
//! * `*KINEMATIC` → an RBE2 from the reference node to every surface node (the reference node
//!   excepted) for the listed dofs: ccx's rigid MPCs (`rigidmpc`, linear in a frequency step)
//!   with the reference node's rotations as the rigid rotation. ccx takes dofs 1 … 3 (the
//!   solid nodes' translations); 4 … 6 couple structural nodes' rotations (Abaqus). A
//!   `*KINEMATIC` without a dof line is refused: ccx 2.20 then couples nothing, Abaqus every dof;
//! * `*DISTRIBUTING` → an RBE3 at the reference node over the surface nodes' translations with
//!   ccx's weights: the face shape functions integrated over the faces, normalised to a sum of 1
//!   (`dcs` of `couplings.f`, each element type's face rule: 1 point for C3D4, C3D6 and
//!   C3D8R, 2 × 2 for C3D8(I) and C3D20R, 3 × 3 for C3D20, 3 points for C3D10 and the C3D15
//!   triangles). The reference dofs are 1 … 3 and the listed rotations (ccx: "forces are always
//!   distributed"). ccx 2.20 uses these weights to spread a force or moment at the reference
//!   node over the surface (`coeffc`: w_i F, and w_i (M e_k) × r_i / Σ w |r⊥e_k|² about the
//!   principal axes of the weighted surface), which is exactly the RBE3's load distribution
//!   f = W G (Gᵀ W G)⁻¹ F; but ccx adds no kinematic relation (its manual: "applying
//!   displacement constraints in the reference node has no effect"), while the RBE3 makes the
//!   reference node's motion the weighted least-squares fit of the surface's — what an
//!   interface node needs. Mid-side nodes of quadratic faces carry the area (C3D10: corners 0,
//!   C3D20: corners −1/12 of a flat face's area).
//!
//! The reference node is usable as `--interface` by its id, or by the coupling's CONSTRAINT
//! NAME: a one-node node set of that name is added (unless the deck has a set so named), and
//! `pipeline::interface` takes a one-node set on a spider's reference node as that node.
//! `ORIENTATION` changes nothing when every translation (`*KINEMATIC`) or every rotation or none
//! (`*DISTRIBUTING`) is coupled; otherwise it is refused (local dofs are not formed).

use super::resolve::single;
use super::sets::Sets;
use super::tie::face_shape;
use super::{CouplingKind, Parser, RawCoupling};
use crate::import::error::ImportError;
use crate::model::{DofMask, NodeIndex, RigidElement};

/// A face rule: points (ξ, η) and weights.
pub(crate) type Rule = &'static [([f64; 2], f64)];

const G2: f64 = 0.577_350_269_189_626;
/// ccx's `gauss2d1`: quadrilateral, one point.
const QUAD_1: Rule = &[([0.0, 0.0], 4.0)];
/// ccx's `gauss2d2`: quadrilateral, 2 × 2.
pub(crate) const QUAD_4: Rule = &[
    ([-G2, -G2], 1.0),
    ([G2, -G2], 1.0),
    ([-G2, G2], 1.0),
    ([G2, G2], 1.0),
];
const G3: f64 = 0.774_596_669_241_483;
const W3A: f64 = 0.308_641_975_308_642;
const W3B: f64 = 0.493_827_160_493_827;
const W3C: f64 = 0.790_123_456_790_123;
/// ccx's `gauss2d3`: quadrilateral, 3 × 3.
pub(crate) const QUAD_9: Rule = &[
    ([-G3, -G3], W3A),
    ([0.0, -G3], W3B),
    ([G3, -G3], W3A),
    ([-G3, 0.0], W3B),
    ([0.0, 0.0], W3C),
    ([G3, 0.0], W3B),
    ([-G3, G3], W3A),
    ([0.0, G3], W3B),
    ([G3, G3], W3A),
];
/// ccx's `gauss2d4`: triangle, one point.
pub(crate) const TRI_1: Rule = &[([1.0 / 3.0, 1.0 / 3.0], 0.5)];
/// ccx's `gauss2d5`: triangle, three points.
pub(crate) const TRI_3: Rule = &[
    ([1.0 / 6.0, 1.0 / 6.0], 1.0 / 6.0),
    ([2.0 / 3.0, 1.0 / 6.0], 1.0 / 6.0),
    ([1.0 / 6.0, 2.0 / 3.0], 1.0 / 6.0),
];

/// The face rule ccx's `couplings.f` integrates a face of an element of type `card` with
/// (`nodes`: the face's node count).
fn face_rule(card: &str, nodes: usize) -> Option<Rule> {
    let tri = matches!(nodes, 3 | 6);
    Some(match card {
        "C3D4" => TRI_1,
        "C3D10" => TRI_3,
        "C3D6" if tri => TRI_1,
        "C3D6" => QUAD_1,
        "C3D15" if tri => TRI_3,
        "C3D15" => QUAD_4,
        "C3D8R" => QUAD_1,
        "C3D8" | "C3D8I" | "C3D20R" => QUAD_4,
        "C3D20" => QUAD_9,
        _ => return None,
    })
}

/// ∫ N_i dA of one face (corner and mid-side coordinates `x`) by `rule`, with |x_ξ × x_η| the
/// area element (ccx `couplings.f`: `areanodal`).
pub(crate) fn nodal_areas(x: &[[f64; 3]], rule: Rule) -> Vec<f64> {
    let mut out = vec![0.0; x.len()];
    for (p, w) in rule {
        let (n, d) = face_shape(x.len(), *p);
        let mut g = [[0.0; 3]; 2];
        for (k, xk) in x.iter().enumerate() {
            for c in 0..3 {
                g[0][c] += d[k][0] * xk[c];
                g[1][c] += d[k][1] * xk[c];
            }
        }
        let cross = [
            g[0][1] * g[1][2] - g[0][2] * g[1][1],
            g[0][2] * g[1][0] - g[0][0] * g[1][2],
            g[0][0] * g[1][1] - g[0][1] * g[1][0],
        ];
        let da = w * (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
        for (o, nk) in out.iter_mut().zip(&n) {
            *o += da * nk;
        }
    }
    out
}

/// The members of a coupling's surface: nodes with weights (area weights summing to 1 for
/// element faces; the node surface's weights as given).
struct Members {
    nodes: Vec<(NodeIndex, f64)>,
    faces: bool,
}

impl Parser {
    /// Every `*COUPLING` → RBE2 (`*KINEMATIC`) or RBE3 (`*DISTRIBUTING`); the CONSTRAINT
    /// NAMEs with their reference nodes, for the one-node sets of that name (module doc).
    pub(super) fn resolve_couplings(
        &mut self,
        sets: &Sets,
    ) -> Result<Vec<(String, NodeIndex)>, ImportError> {
        let first = self.b.model.rigid_elements.len() as u64 + 1;
        let mut rigid = Vec::new();
        let mut names = Vec::new();
        for (rid, c) in (first..).zip(&self.couplings) {
            let ent = match &c.name {
                Some(n) => format!("*COUPLING CONSTRAINT NAME={n}"),
                None => format!("*COUPLING SURFACE={}", c.surface),
            };
            let refs = sets.target(&c.reference, c.loc, &ent, self)?;
            let reference = single(refs, c.loc, &ent, self)?;
            let Some(kind) = &c.kind else {
                return Err(self.err(c.loc, ent, "no *KINEMATIC or *DISTRIBUTING follows"));
            };
            self.check_orientation(c, kind, &ent)?;
            let members = self.coupling_members(c, sets, &ent)?;
            rigid.push(match kind {
                CouplingKind::Kinematic(d) => {
                    if d.0 == 0 {
                        return Err(self.err(
                            c.loc,
                            ent,
                            "*KINEMATIC without a dof line: ccx 2.20 then couples nothing and \
                             Abaqus every dof; give the dofs (e.g. 1, 3)",
                        ));
                    }
                    let mut dependent: Vec<NodeIndex> = (members.nodes.iter())
                        .map(|m| m.0)
                        .filter(|&n| n != reference)
                        .collect();
                    dependent.sort_unstable();
                    dependent.dedup();
                    RigidElement::Rbe2 {
                        id: rid,
                        independent: reference,
                        dependent,
                        dofs: *d,
                    }
                }
                CouplingKind::Distributing(d) => {
                    if members.faces && members.nodes.iter().any(|m| m.0 == reference) {
                        return Err(self.err(
                            c.loc,
                            ent,
                            "the reference node is a node of the coupling surface",
                        ));
                    }
                    RigidElement::Rbe3 {
                        id: rid,
                        reference,
                        ref_dofs: DofMask::TRANSLATIONS.union(*d),
                        independent: (members.nodes.iter())
                            .map(|&(n, w)| (n, w, DofMask::TRANSLATIONS))
                            .collect(),
                    }
                }
            });
            if let Some(n) = &c.name {
                names.push((n.clone(), reference));
            }
        }
        self.b.model.rigid_elements.extend(rigid);
        Ok(names)
    }

    /// ORIENTATION: a known `*ORIENTATION`, and one that cannot change the coupled dofs.
    fn check_orientation(
        &self,
        c: &RawCoupling,
        kind: &CouplingKind,
        ent: &str,
    ) -> Result<(), ImportError> {
        let Some(o) = &c.orientation else {
            return Ok(());
        };
        if !self.orientation_exists(o) {
            return Err(self.err(c.loc, ent.to_owned(), format!("unknown *ORIENTATION {o}")));
        }
        let local = match kind {
            CouplingKind::Kinematic(d) => {
                let t = d.0 & DofMask::TRANSLATIONS.0;
                t != 0 && t != DofMask::TRANSLATIONS.0
            }
            CouplingKind::Distributing(d) => {
                let r = d.0 & !DofMask::TRANSLATIONS.0;
                r != 0 && r != DofMask::ALL.0 & !DofMask::TRANSLATIONS.0
            }
        };
        if local {
            return Err(self.err(
                c.loc,
                ent.to_owned(),
                format!(
                    "ORIENTATION={o} with only some of the translations (*KINEMATIC) or \
                     rotations (*DISTRIBUTING) coupled: dofs in a local system are not supported \
                     (couple all three, or give them in the global system)"
                ),
            ));
        }
        Ok(())
    }

    /// The surface's nodes and weights: element faces with ccx's area weights, or a node
    /// surface's nodes with their weights.
    fn coupling_members(
        &self,
        c: &RawCoupling,
        sets: &Sets,
        ent: &str,
    ) -> Result<Members, ImportError> {
        if let Some(faces) = self.surface_faces(&c.surface, sets, ent)? {
            let mut weight: std::collections::BTreeMap<NodeIndex, f64> = Default::default();
            for f in &faces {
                let e = sets.elems.get(f.element).ok_or_else(|| {
                    self.err(
                        c.loc,
                        ent.to_owned(),
                        format!("unknown element {}", f.element),
                    )
                })?;
                let card = self.b.elem_card[e];
                // a shell's face is its brick's (faces.rs): the brick's face rule
                let card = super::shell_expansion::brick_card(card).unwrap_or(card);
                let rule = face_rule(card, f.nodes.len()).ok_or_else(|| {
                    self.err(
                        c.loc,
                        ent.to_owned(),
                        format!(
                            "*SURFACE {}: faces of {card} elements (element {}) are not supported in a coupling",
                            c.surface, f.element
                        ),
                    )
                })?;
                let x: Vec<[f64; 3]> = f.nodes.iter().map(|&n| self.b.model.nodes[n].x).collect();
                for (&n, a) in f.nodes.iter().zip(nodal_areas(&x, rule)) {
                    *weight.entry(n).or_default() += a;
                }
            }
            let area: f64 = weight.values().sum();
            if !(area > 0.0 && area.is_finite()) {
                return Err(self.err(
                    c.loc,
                    ent.to_owned(),
                    format!("*SURFACE {} has no area", c.surface),
                ));
            }
            return Ok(Members {
                nodes: weight.into_iter().map(|(n, a)| (n, a / area)).collect(),
                faces: true,
            });
        }
        let Some(lines) = self.surfaces.get(&c.surface) else {
            return Err(self.err(
                c.loc,
                ent.to_owned(),
                format!(
                    "unknown surface {} (neither an element-face nor a node *SURFACE)",
                    c.surface
                ),
            ));
        };
        let mut nodes = Vec::new();
        for (t, w, at) in lines {
            for n in sets.target(t, *at, ent, self)? {
                nodes.push((n, *w));
            }
        }
        Ok(Members {
            nodes,
            faces: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat face's nodal areas are the integrals of its shape functions: linear faces share
    /// the area equally among the corners; quadratic triangles give the corners 0 and the
    /// mid-side nodes A/3; serendipity quadrilaterals −A/12 and A/3 (Zienkiewicz & Taylor,
    /// Vol. 1 §8.8, consistent nodal loads of a uniform pressure).
    #[test]
    fn nodal_areas_of_flat_faces_are_the_consistent_loads_of_a_unit_pressure() {
        let quad = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
        ];
        let mid = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]));
        let quad8: Vec<[f64; 3]> = (quad.iter().copied())
            .chain((0..4).map(|k| mid(quad[k], quad[(k + 1) % 4])))
            .collect();
        let tri = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 3.0, 0.0]];
        let tri6: Vec<[f64; 3]> = (tri.iter().copied())
            .chain((0..3).map(|k| mid(tri[k], tri[(k + 1) % 3])))
            .collect();
        let cases: [(&[[f64; 3]], Rule, f64, f64); 7] = [
            (&quad, QUAD_1, 1.5, 1.5),
            (&quad, QUAD_4, 1.5, 1.5),
            (&quad8, QUAD_4, -0.5, 2.0),
            (&quad8, QUAD_9, -0.5, 2.0),
            (&tri, TRI_1, 1.0, 1.0),
            (&tri, TRI_3, 1.0, 1.0),
            (&tri6, TRI_3, 0.0, 1.0),
        ];
        for (x, rule, corner, side) in cases {
            let a = nodal_areas(x, rule);
            let corners = if x.len() > 4 { x.len() / 2 } else { x.len() };
            for (k, v) in a.iter().enumerate() {
                let want = if k < corners { corner } else { side };
                assert!((v - want).abs() < 1e-12, "{} nodes: {a:?}", x.len());
            }
        }
    }
}
