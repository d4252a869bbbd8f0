//! CalculiX's quadratic beams B32 and B32R as ccx 2.20 computes them: each element becomes a
//! 20-node brick around the beam (ccx gen3dnor, gen3dfrom1d), integrated at the section's
//! points (`fe::elements::hex20_beam`, ccx beamintscheme); the beam's own nodes stay in the
//! model, tied to the section around them (ccx gen3dboun).
//!
//! * **Section axes** at a beam node, per element: the tangent t of the element's quadratic
//!   geometry at the node, n2 = t × n1 / |t × n1| with n1 the section card's direction line
//!   ((0, 0, −1) without it). Elements at a node share one set of axes when their n2 and t lie
//!   within 20° and their sections agree (ccx's test); then n2 is their mean, made normal to
//!   the mean tangent, and n1 = n2 × t. Where they do not agree, each group of agreeing
//!   elements has its own axes and expanded nodes, and all of them are joined at the node by
//!   ccx's knot ([`knot_tie`]: rigid, plus a uniform expansion).
//! * **Expanded nodes**: 8 around each end node, 4 (the corners) around the middle node, on
//!   the section's bounding rectangle: x = p + t₁ n1 (ζ/2 − o₁) − t₂ n2 (η/2 + o₂)
//!   (η, ζ ∈ {−1, 0, 1}; o₁, o₂ ccx's OFFSET1, OFFSET2 in section sizes),
//!   t₁ × t₂ the section's size (RECT a × b, BOX a × b, PIPE 2r × 2r, CIRC the two values as
//!   diameters, as ccx reads them, its corner nodes moved in by 1/√2 onto the ellipse). The
//!   brick's ξ runs from the first to the last beam node. B32R → C3D20R with the section's
//!   integration ([`crate::model::Model::beam_bricks`]); B32 (RECT and CIRC, as ccx) → C3D20,
//!   3 × 3 × 3.
//! * **The beam node** (not a knot) follows the section around it ([`section_tie`]): its
//!   translation is the mean of the four corners, its rotation about each axis the corners'
//!   linearized mean rotation (ccx's MEANROTBS MPC, umpc_mean_rot, at the undeformed state).
//!   Where the deck
//!   holds a rotation of the node, the mid-side nodes also stay between their corners (ccx's
//!   "midfix"). The equations are solved for dofs of the expanded nodes, so the beam node keeps
//!   independent dofs: a `*BOUNDARY` on it holds the section as ccx does, a load on it reaches
//!   the section through the same relation, and it can be an interface node. Where the deck
//!   does not constrain the node, ccx leaves it unconnected; here its dofs follow the section
//!   and add no stiffness or mass, so the frequencies are the same. A preload (`*STEP,
//!   PERTURBATION`) forms the bricks' initial stress at the same section points.
//!
//! Solid elements, masses and springs on a beam node join its translation, the mean of the
//! corners, as ccx's gen3dconnect joins them. Refused (errors naming the card and line):
//! sections other than RECT, CIRC (`*BEAM SECTION`) and PIPE, BOX (`*BEAM GENERAL SECTION`,
//! B32R only, as ccx), anisotropic materials, a *TRANSFORM on a beam node, beam nodes shared
//! with shells, rods or B31 beams, rotary inertia or rotational springs, MPCs or rigid
//! elements (ccx joins those with further MPCs).

use std::collections::{BTreeMap, HashMap};

use super::Parser;
use crate::import::error::ImportError;
use crate::model::geometry::{cross, dot, norm, unit_if};
use crate::model::{
    BeamBrickSection, ElementKind, Model, Mpc, Node, NodeDof, NodeIndex, Property, Section,
    SectionShape,
};

/// Reference coordinates (η, ζ) of the eight expanded nodes around a beam node, in ccx's
/// order (knor 1 … 8): the corners, then the mid-sides.
const EXPANDED: [[i8; 2]; 8] = [
    [-1, -1],
    [1, -1],
    [1, 1],
    [-1, 1],
    [0, -1],
    [1, 0],
    [0, 1],
    [-1, 0],
];

/// ccx's 20° test: cos 20°.
const SAME_AXES: f64 = 0.939693;

/// One B32/B32R element, checked.
struct BeamElement {
    /// Element index.
    e: usize,
    /// B32R (reduced integration at the section's points) or B32 (C3D20).
    reduced: bool,
    /// The section's integration; `None` for B32 (full integration of the brick).
    brick: Option<BeamBrickSection>,
    /// The section's kind (ccx compares it where elements meet).
    shape: BeamBrickSection,
    /// Section size along n1 and n2.
    size: [f64; 2],
    /// CalculiX's OFFSET1, OFFSET2 (in section sizes).
    offsets: [f64; 2],
    /// The card's 1-direction, unit.
    n1: [f64; 3],
}

/// Section axes shared at one beam node: (n1, n2).
type Axes = ([f64; 3], [f64; 3]);

/// (beam node, index into the beams) → (its group of axes at the node, the axes).
/// (beam node, index into the beams) → (the group of elements at the node sharing axes, the
/// axes).
type NodeAxes = HashMap<(NodeIndex, usize), (usize, Axes)>;

/// One element at a beam node: (element id, index of the beam, tangent, n2).
type AtNode = (u64, usize, [f64; 3], [f64; 3]);

impl Parser {
    /// Replace every B32/B32R element by ccx's brick, add the expanded nodes and tie the beam
    /// nodes to them (module doc).
    pub(super) fn expand_quadratic_beams(&mut self) -> Result<(), ImportError> {
        self.check_general_sections()?;
        let beams: Vec<BeamElement> = (0..self.b.model.elements.len())
            .filter(|&e| self.b.model.elements[e].kind == ElementKind::Beam3)
            .map(|e| self.beam_element(e))
            .collect::<Result<_, _>>()?;
        if beams.is_empty() {
            return Ok(());
        }
        self.check_beam_nodes_alone(&beams)?;
        let axes = self.node_axes(&beams)?;
        let model = &mut self.b.model;
        let mut next_id = model.max_node_id();
        // (beam node, group of axes at it, knor index) → expanded node
        let mut expanded: BTreeMap<(NodeIndex, usize, usize), NodeIndex> = BTreeMap::new();
        let mut solid_property: BTreeMap<usize, usize> = BTreeMap::new();
        for (bi, b) in beams.iter().enumerate() {
            let beam_nodes = model.elements[b.e].nodes.clone();
            let mut brick = Vec::with_capacity(20);
            for r in crate::fe::elements::hex20::NODES {
                let node = beam_nodes[(r[0] + 1.0) as usize];
                let key = [r[1] as i8, r[2] as i8];
                // `EXPANDED` lists every (η, ζ) but the centre, which no brick node has
                let k = EXPANDED.iter().position(|&q| q == key).unwrap_or(0);
                let (group, (n1, n2)) = axes[&(node, bi)];
                let idx = *expanded.entry((node, group, k)).or_insert_with(|| {
                    let p = model.nodes[node].x;
                    let (mut eta, mut zeta) = (f64::from(key[0]), f64::from(key[1]));
                    // CIRC: the corners on the circle (ccx gen3dfrom1d)
                    if b.shape == BeamBrickSection::Circ && eta != 0.0 && zeta != 0.0 {
                        eta /= std::f64::consts::SQRT_2;
                        zeta /= std::f64::consts::SQRT_2;
                    }
                    next_id += 1;
                    model.nodes.push(Node {
                        id: next_id,
                        x: std::array::from_fn(|c| {
                            p[c] + b.size[0] * n1[c] * (zeta / 2.0 - b.offsets[0])
                                - b.size[1] * n2[c] * (eta / 2.0 + b.offsets[1])
                        }),
                        displacement_frame: None,
                    });
                    model.nodes.len() - 1
                });
                brick.push(idx);
            }
            let prop = model.elements[b.e].property.unwrap_or(0);
            let solid = *solid_property.entry(prop).or_insert_with(|| {
                let p = &model.properties[prop];
                let id = model.properties.iter().map(|p| p.id).max().unwrap_or(0) + 1;
                model.properties.push(Property {
                    id,
                    name: p.name.clone(),
                    material: p.material,
                    section: Section::Solid,
                });
                model.properties.len() - 1
            });
            let el = &mut model.elements[b.e];
            el.kind = if b.reduced {
                ElementKind::Hex20R
            } else {
                ElementKind::Hex20
            };
            el.nodes = brick;
            el.property = Some(solid);
            el.orientation = None;
            if let Some(s) = b.brick {
                model.beam_bricks.insert(b.e, s);
            }
        }
        tie_beam_nodes(model, &expanded)
    }

    /// ccx 2.20 takes `*BEAM GENERAL SECTION` (PIPE, BOX) for B32R elements only.
    fn check_general_sections(&self) -> Result<(), ImportError> {
        let m = &self.b.model;
        for (k, s) in self.sections.iter().enumerate().filter(|(_, s)| s.general) {
            let other = (0..m.elements.len())
                .find(|&e| m.elements[e].property == Some(k) && self.b.elem_card[e] != "B32R");
            if let Some(e) = other {
                return Err(self.err(
                    s.loc,
                    format!("*BEAM GENERAL SECTION ELSET={}", s.elset),
                    format!(
                        "CalculiX 2.20 takes *BEAM GENERAL SECTION on B32R elements only \
                         (element {} is {})",
                        m.elements[e].id, self.b.elem_card[e]
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The element's section, checked against what ccx 2.20 accepts (module doc).
    fn beam_element(&self, e: usize) -> Result<BeamElement, ImportError> {
        let el = &self.b.model.elements[e];
        let card = self.b.elem_card[e];
        let reduced = card == "B32R";
        let loc = self.b.elem_loc[e];
        let ent = format!("*ELEMENT {} (TYPE={card})", el.id);
        let Some(k) = el.property else {
            return Err(self.err(loc, ent, "no *BEAM SECTION or *BEAM GENERAL SECTION"));
        };
        let s = &self.sections[k];
        let sent = format!(
            "*BEAM {}SECTION ELSET={}",
            if s.general { "GENERAL " } else { "" },
            s.elset
        );
        let Section::Beam(bs) = &s.section else {
            return Err(self.err(
                loc,
                ent,
                format!("its section ({sent}) is not a beam section"),
            ));
        };
        let refuse = |msg: String| Err(self.err(s.loc, sent.clone(), msg));
        if !s.offsets.iter().all(|o| o.is_finite()) {
            return refuse(format!("OFFSET1, OFFSET2 must be finite: {:?}", s.offsets));
        }
        let mat = &self.b.model.materials[self.b.model.properties[k].material];
        if mat.stiffness().is_some() {
            return refuse(format!(
                "material {} is anisotropic: {card} elements take an isotropic material",
                mat.name
            ));
        }
        let d = &s.dims;
        let positive = d.iter().all(|v| *v > 0.0 && v.is_finite());
        let (brick, size) = match (&bs.shape, s.general) {
            (Some(SectionShape::Rectangle { .. }), false) if positive && d.len() >= 2 => {
                (BeamBrickSection::Rect, [d[0], d[1]])
            }
            (Some(SectionShape::Tube { .. }), true) if positive && d[1] < d[0] => (
                BeamBrickSection::Pipe {
                    ratio: (d[0] - d[1]) / d[0],
                },
                [2.0 * d[0], 2.0 * d[0]],
            ),
            (Some(SectionShape::Box { .. }), true)
                if positive && d[2] + d[4] < d[0] && d[3] + d[5] < d[1] =>
            {
                (
                    BeamBrickSection::Box {
                        a: d[0],
                        b: d[1],
                        t: [d[2], d[3], d[4], d[5]],
                    },
                    [d[0], d[1]],
                )
            }
            // ccx: the values are the diameters along n1 and n2 (one value: a circle)
            (Some(SectionShape::Circle { .. }), false) if positive => (
                BeamBrickSection::Circ,
                [d[0], d.get(1).copied().unwrap_or(d[0])],
            ),
            (_, false) => {
                return refuse(format!(
                    "{card} elements take SECTION=RECT or CIRC under *BEAM SECTION (CalculiX \
                     2.20; PIPE and BOX under *BEAM GENERAL SECTION), with positive sizes: \
                     {d:?}"
                ))
            }
            (_, true) => {
                return refuse(format!(
                    "{card} elements take SECTION=PIPE (r > t > 0) or BOX (a, b, t1 … t4 > 0, \
                     walls thinner than the box) here: {d:?}"
                ))
            }
        };
        let n1 = s.orientation.unwrap_or([0.0, 0.0, -1.0]);
        let len = norm(n1);
        if !(len > 1e-10 && len.is_finite()) {
            return refuse("the direction of the section's 1-axis has zero length".into());
        }
        Ok(BeamElement {
            e,
            reduced,
            brick: reduced.then_some(brick),
            shape: brick,
            size,
            offsets: s.offsets,
            n1: n1.map(|c| c / len),
        })
    }

    /// Nothing but B32/B32R elements, SPCs and loads may use a beam node (module doc).
    fn check_beam_nodes_alone(&self, beams: &[BeamElement]) -> Result<(), ImportError> {
        let m = &self.b.model;
        let mut owner: HashMap<NodeIndex, usize> = HashMap::new();
        for b in beams {
            for &n in &m.elements[b.e].nodes {
                owner.entry(n).or_insert(b.e);
            }
        }
        let refuse = |n: NodeIndex, what: String| {
            let e = owner[&n];
            Err(self.err(
                self.b.elem_loc[e],
                format!(
                    "*ELEMENT {} (TYPE={})",
                    m.elements[e].id, self.b.elem_card[e]
                ),
                format!(
                    "beam node {} is also used by {what}: CalculiX joins that to the expanded \
                     beam with further MPCs, which flexbody does not form",
                    m.nodes[n].id
                ),
            ))
        };
        // solid elements join a beam node's translation, which is the mean of its section's
        // corners, as ccx's gen3dconnect joins them
        for el in (m.elements.iter()).filter(|e| e.kind != ElementKind::Beam3 && !e.kind.is_solid())
        {
            if let Some(&n) = el.nodes.iter().find(|n| owner.contains_key(n)) {
                return refuse(n, format!("element {}", el.id));
            }
        }
        for (n, node) in m.nodes.iter().enumerate() {
            if owner.contains_key(&n) && node.displacement_frame.is_some() {
                return Err(self.err(
                    self.b.elem_loc[owner[&n]],
                    format!("node {}", node.id),
                    "a *TRANSFORM on a node of a B32/B32R element is not supported",
                ));
            }
        }
        // masses and springs on translations likewise (gen3dconnect); on rotations not
        let rotary = |p: &crate::model::PointMass| {
            p.inertia.iter().flatten().any(|v| *v != 0.0) || p.offset != [0.0; 3]
        };
        let used: Vec<(NodeIndex, String)> = (m.point_masses.iter())
            .filter(|p| rotary(p))
            .map(|p| (p.node, format!("rotary inertia {}", p.id)))
            .chain(m.springs.iter().flat_map(|s| {
                std::iter::once(s.a)
                    .chain(s.b)
                    .filter(|d| d.component > 2)
                    .map(move |d| (d.node, format!("rotational spring {}", s.id)))
            }))
            .chain(m.scalar_masses.iter().flat_map(|s| {
                std::iter::once(s.a)
                    .chain(s.b)
                    .filter(|d| d.component > 2)
                    .map(move |d| (d.node, format!("rotational mass {}", s.id)))
            }))
            .chain(m.bushes.iter().flat_map(|b| {
                let rotational = b.k[3..].iter().any(|k| *k != 0.0);
                std::iter::once(b.a)
                    .chain(b.b)
                    .filter(move |_| rotational)
                    .map(move |n| (n, format!("spring {} with rotational stiffness", b.id)))
            }))
            .chain((m.mpcs.iter()).flat_map(|c| {
                (c.terms.iter()).map(move |t| (t.0.node, format!("*EQUATION / MPC {}", c.id)))
            }))
            .chain(
                m.rigid_bodies
                    .iter()
                    .flat_map(|r| r.nodes().map(move |n| (n, format!("rigid body {}", r.id)))),
            )
            .chain(m.rigid_elements.iter().flat_map(|r| {
                match r {
                    crate::model::RigidElement::Rbe2 {
                        id,
                        independent,
                        dependent,
                        ..
                    } => std::iter::once(*independent)
                        .chain(dependent.iter().copied())
                        .map(|n| (n, format!("rigid element {id}")))
                        .collect::<Vec<_>>(),
                    crate::model::RigidElement::Rbe3 {
                        id,
                        reference,
                        independent,
                        ..
                    } => std::iter::once(*reference)
                        .chain(independent.iter().map(|w| w.0))
                        .map(|n| (n, format!("coupling {id}")))
                        .collect(),
                }
            }))
            .collect();
        if let Some((n, what)) = used.into_iter().find(|(n, _)| owner.contains_key(n)) {
            return refuse(n, what);
        }
        Ok(())
    }

    /// The section axes (n1, n2) of every beam at each of its nodes, and the group of beams
    /// at the node that share them (0, 1, …; more than one group: a knot), keyed by (node,
    /// index into `beams`) (module doc; ccx gen3dnor).
    fn node_axes(&self, beams: &[BeamElement]) -> Result<NodeAxes, ImportError> {
        let m = &self.b.model;
        // per node: (element id, beam, tangent, n2)
        let mut at: BTreeMap<NodeIndex, Vec<AtNode>> = BTreeMap::new();
        for (bi, b) in beams.iter().enumerate() {
            let el = &m.elements[b.e];
            let x: Vec<[f64; 3]> = el.nodes.iter().map(|&n| m.nodes[n].x).collect();
            for (j, &node) in el.nodes.iter().enumerate() {
                // d/dξ of the quadratic map at ξ = −1, 0, 1
                let xi = j as f64 - 1.0;
                let t: [f64; 3] = std::array::from_fn(|c| {
                    (xi - 0.5) * x[0][c] - 2.0 * xi * x[1][c] + (xi + 0.5) * x[2][c]
                });
                let bad = |what: &str| {
                    self.err(
                        self.b.elem_loc[b.e],
                        format!("*ELEMENT {} (TYPE={})", el.id, self.b.elem_card[b.e]),
                        format!("{what} at node {} is zero", m.nodes[node].id),
                    )
                };
                let t = unit(t).ok_or_else(|| bad("the beam's tangent"))?;
                let n2 = unit(cross(t, b.n1)).ok_or_else(|| {
                    bad("the section's 2-axis (tangent × the card's 1-direction)")
                })?;
                at.entry(node).or_default().push((el.id, bi, t, n2));
            }
        }
        let mut out = HashMap::new();
        for (node, mut list) in at {
            list.sort_by_key(|l| l.0);
            let mut left: Vec<AtNode> = list;
            let mut group = 0;
            while !left.is_empty() {
                // ccx: the element with the smallest number, and those within 20° of it with
                // the same section, share the node's axes
                let (_, first, t_ref, n_ref) = left[0];
                let fits = |&(_, bi, t, n): &AtNode| {
                    let (a, b) = (&beams[bi], &beams[first]);
                    dot(n, n_ref) > SAME_AXES
                        && dot(t, t_ref) > SAME_AXES
                        && (a.size[0] - b.size[0]).abs() < 1e-10
                        && (a.size[1] - b.size[1]).abs() < 1e-10
                        && (a.offsets[0] - b.offsets[0]).abs() < 1e-10
                        && (a.offsets[1] - b.offsets[1]).abs() < 1e-10
                        && std::mem::discriminant(&a.shape) == std::mem::discriminant(&b.shape)
                };
                let (members, rest): (Vec<AtNode>, Vec<AtNode>) = left.into_iter().partition(fits);
                left = rest;
                let sum = |f: &dyn Fn(&AtNode) -> [f64; 3]| {
                    (members.iter()).fold([0.0; 3], |s, l| std::array::from_fn(|c| s[c] + f(l)[c]))
                };
                let t = unit(sum(&|l| l.2)).unwrap_or(t_ref);
                let n = sum(&|l| l.3);
                let n2 = unit(std::array::from_fn(|c| n[c] - dot(n, t) * t[c])).unwrap_or(n_ref);
                for l in &members {
                    out.insert((node, l.1), (group, (cross(n2, t), n2)));
                }
                group += 1;
            }
        }
        Ok(out)
    }
}

/// Tie every beam node to the section around it ([`section_tie`]; its held rotations, from
/// the model's SPCs, ask for the mid-side equations), or where the elements at it differ in
/// axes or section, to all their sections by ccx's knot ([`knot_tie`]).
fn tie_beam_nodes(
    model: &mut Model,
    expanded: &BTreeMap<(NodeIndex, usize, usize), NodeIndex>,
) -> Result<(), ImportError> {
    let mut held: HashMap<NodeIndex, bool> = HashMap::new();
    for s in &model.spcs {
        if s.dofs.dofs().any(|k| k >= 3) {
            held.insert(s.node, true);
        }
    }
    let mut at: BTreeMap<NodeIndex, Vec<(usize, usize, NodeIndex)>> = BTreeMap::new();
    for (&(b, group, k), &n) in expanded {
        at.entry(b).or_default().push((group, k, n));
    }
    for (b, around) in at {
        let id = model.nodes[b].id;
        let x = |n: NodeIndex| model.nodes[n].x;
        if around.iter().any(|a| a.0 > 0) {
            let dependent: Vec<(NodeIndex, [f64; 3])> =
                around.iter().map(|a| (a.2, x(a.2))).collect();
            let mpcs = knot_tie(b, x(b), &dependent).map_err(|message| ImportError::Parse {
                file: model.source.clone(),
                line: 0,
                entity: format!("node {id}"),
                message,
            })?;
            model
                .mpcs
                .extend(mpcs.into_iter().map(|terms| Mpc { id, terms }));
            continue;
        }
        let get = |k: usize| around.iter().find(|a| a.1 == k).map(|a| a.2);
        let corners: [NodeIndex; 4] = std::array::from_fn(|k| get(k).unwrap_or(b));
        let midsides: Option<[NodeIndex; 4]> = (4..8)
            .map(get)
            .collect::<Option<Vec<_>>>()
            .and_then(|v| v.try_into().ok());
        let mids = midsides.filter(|_| held.get(&b).copied().unwrap_or(false));
        let mpcs = section_tie(b, corners.map(|n| (n, x(n))), mids).map_err(|message| {
            ImportError::Parse {
                file: model.source.clone(),
                line: 0,
                entity: format!("node {id}"),
                message,
            }
        })?;
        model
            .mpcs
            .extend(mpcs.into_iter().map(|terms| Mpc { id, terms }));
    }
    Ok(())
}

/// ccx's knot (gen3dnor, knotmpc, fillknotmpc; KNOT1 linearized at the undeformed state):
/// every expanded node around `beam` follows the beam node's translation and rotation and a
/// uniform expansion α about it, u_i = u_b + θ_b × r_i + α r_i with r_i = x_i − x_b. α is
/// eliminated: the equation with the largest |r_c| defines it by that node's dof, which stays
/// independent; every other expanded dof is dependent.
pub(crate) fn knot_tie(
    beam: NodeIndex,
    at: [f64; 3],
    dependent: &[(NodeIndex, [f64; 3])],
) -> Result<Vec<Vec<(NodeDof, f64)>>, String> {
    let dof = |node: NodeIndex, c: usize| NodeDof {
        node,
        component: c as u8,
    };
    // α, a dof of no node: eliminated below
    let alpha = dof(usize::MAX, 0);
    let mut rows: Vec<Vec<(NodeDof, f64)>> = Vec::with_capacity(3 * dependent.len());
    for &(n, x) in dependent {
        let r: [f64; 3] = std::array::from_fn(|c| x[c] - at[c]);
        for c in 0..3 {
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            // (θ × r)_c = θ_c1 r_c2 − θ_c2 r_c1
            let terms = [
                (dof(n, c), 1.0),
                (dof(beam, c), -1.0),
                (dof(beam, 3 + c1), -r[c2]),
                (dof(beam, 3 + c2), r[c1]),
                (alpha, -r[c]),
            ];
            rows.push(terms.into_iter().filter(|t| t.1 != 0.0).collect());
        }
    }
    let weight =
        |r: &Vec<(NodeDof, f64)>| r.iter().find(|t| t.0 == alpha).map_or(0.0, |t| t.1.abs());
    let first = (0..rows.len())
        .max_by(|&i, &j| weight(&rows[i]).total_cmp(&weight(&rows[j])))
        .ok_or("a knot without expanded nodes")?;
    rows.swap(0, first);
    let solved = solve_for_section_dofs(beam, Some(alpha), rows)?;
    Ok(solved.into_iter().filter(|m| m[0].0 != alpha).collect())
}

/// The linear equations that make `beam` follow the section around it, solved for dofs of
/// the expanded nodes: each returned MPC's first term is a dof of a corner or mid-side node,
/// which appears in no other returned MPC (module doc). Equations, with the four corners
/// c₁ … c₄ (ccx gen3dboun, umpc_mean_rot linearized at the undeformed state):
///
/// * Σₖ u(cₖ) − 4 u(beam) = 0 per direction;
/// * Σₖ gₖ · u(cₖ) − 4 θ_r(beam) = 0 about each axis e_r, gₖ = hₖ − ¼ Σᵢ hᵢ,
///   hₖ = e_r × pₖ / |pₖ|², pₖ the corner's offset from the corners' centroid normal to e_r;
/// * with `midsides` m₁ … m₄ (a held rotation): 2 u(mₖ) − u(cₖ) − u(cₖ₊₁) = 0.
pub(crate) fn section_tie(
    beam: NodeIndex,
    corners: [(NodeIndex, [f64; 3]); 4],
    midsides: Option<[NodeIndex; 4]>,
) -> Result<Vec<Vec<(NodeDof, f64)>>, String> {
    let dof = |node: NodeIndex, c: usize| NodeDof {
        node,
        component: c as u8,
    };
    let mut rows: Vec<Vec<(NodeDof, f64)>> = Vec::new();
    for c in 0..3 {
        let mut r: Vec<(NodeDof, f64)> = corners.iter().map(|k| (dof(k.0, c), 1.0)).collect();
        r.push((dof(beam, c), -4.0));
        rows.push(r);
    }
    let centroid: [f64; 3] =
        std::array::from_fn(|c| corners.iter().map(|k| k.1[c]).sum::<f64>() / 4.0);
    let spread = corners
        .iter()
        .map(|k| (0..3).map(|c| (k.1[c] - centroid[c]).powi(2)).sum::<f64>())
        .sum::<f64>()
        / 4.0;
    for axis in 0..3 {
        let mut e = [0.0; 3];
        e[axis] = 1.0;
        let h: Vec<[f64; 3]> = corners
            .iter()
            .map(|k| {
                let d: [f64; 3] = std::array::from_fn(|c| k.1[c] - centroid[c]);
                let p: [f64; 3] = std::array::from_fn(|c| d[c] - dot(d, e) * e[c]);
                let pp = dot(p, p);
                // ccx leaves out a node on the axis through the centroid
                if pp < spread * 1e-10 {
                    [0.0; 3]
                } else {
                    cross(e, p).map(|v| v / pp)
                }
            })
            .collect();
        let mean: [f64; 3] = std::array::from_fn(|c| h.iter().map(|v| v[c]).sum::<f64>() / 4.0);
        let mut r = Vec::with_capacity(13);
        for (k, hk) in corners.iter().zip(&h) {
            for c in 0..3 {
                r.push((dof(k.0, c), hk[c] - mean[c]));
            }
        }
        r.push((dof(beam, 3 + axis), -4.0));
        rows.push(r);
    }
    if let Some(m) = midsides {
        for k in 0..4 {
            for c in 0..3 {
                rows.push(vec![
                    (dof(m[k], c), 2.0),
                    (dof(corners[k].0, c), -1.0),
                    (dof(corners[(k + 1) % 4].0, c), -1.0),
                ]);
            }
        }
    }
    solve_for_section_dofs(beam, None, rows)
}

/// Gauss–Jordan elimination of `rows` (Σ c u = 0) with pivots among the dofs of nodes other
/// than `beam` (`first` where it can, else the largest coefficient): each row becomes
/// u_pivot + Σ c u_free = 0 with no pivot among the free dofs.
fn solve_for_section_dofs(
    beam: NodeIndex,
    first: Option<NodeDof>,
    rows: Vec<Vec<(NodeDof, f64)>>,
) -> Result<Vec<Vec<(NodeDof, f64)>>, String> {
    let mut vars: Vec<NodeDof> = rows.iter().flatten().map(|t| t.0).collect();
    vars.sort_unstable();
    vars.dedup();
    let col: HashMap<NodeDof, usize> = vars.iter().enumerate().map(|(i, &v)| (v, i)).collect();
    let mut a: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| {
            let mut v = vec![0.0; vars.len()];
            for &(d, c) in r {
                v[col[&d]] += c;
            }
            v
        })
        .collect();
    let mut pivots: Vec<usize> = Vec::with_capacity(a.len());
    for i in 0..a.len() {
        let scale = a[i].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let preferred = first
            .and_then(|d| col.get(&d).copied())
            .filter(|&j| !pivots.contains(&j) && a[i][j].abs() > 1e-9 * scale);
        let p = preferred
            .or_else(|| {
                (0..vars.len())
                    .filter(|&j| vars[j].node != beam && !pivots.contains(&j))
                    .max_by(|&x, &y| a[i][x].abs().total_cmp(&a[i][y].abs()))
                    .filter(|&j| a[i][j].abs() > 1e-9 * scale)
            })
            .ok_or("the section's tie equations are singular (a degenerate section)")?;
        let piv = a[i][p];
        a[i].iter_mut().for_each(|v| *v /= piv);
        let row = a[i].clone();
        for (k, other) in a.iter_mut().enumerate() {
            let f = other[p];
            if k != i && f != 0.0 {
                other.iter_mut().zip(&row).for_each(|(v, r)| *v -= f * r);
            }
        }
        pivots.push(p);
    }
    Ok(pivots
        .iter()
        .zip(&a)
        .map(|(&p, row)| {
            let scale = row.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            std::iter::once((vars[p], 1.0))
                .chain(
                    (0..vars.len())
                        .filter(|&j| j != p && row[j].abs() > 1e-14 * scale)
                        .map(|j| (vars[j], row[j])),
                )
                .collect()
        })
        .collect())
}

/// a / |a|, or `None` below ccx's 1e-10.
fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    unit_if(a, |n| n >= 1e-10 && n.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rigid motion of a section in a coordinate plane (translation v of the centroid,
    /// small rotation w) puts the beam node at (v, w): every tie equation holds with those
    /// values, whichever dofs the elimination made dependent. (For a section oblique to the
    /// axes ccx's mean rotation about an axis also sees rotations about the others; the
    /// oblique beam of `fixtures/ccx_beams` checks that against ccx.)
    #[test]
    fn section_tie_is_satisfied_by_rigid_motion_of_the_section() {
        let p = [1.0, -2.0, 0.5];
        // beam along z: n1 = y, n2 = z × y = −x
        let (n1, n2) = ([0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]);
        let (a, b) = (0.3, 0.7);
        let at = |eta: f64, zeta: f64| -> [f64; 3] {
            std::array::from_fn(|c| p[c] + a * n1[c] * zeta / 2.0 - b * n2[c] * eta / 2.0)
        };
        let x: Vec<[f64; 3]> = EXPANDED
            .iter()
            .map(|q| at(f64::from(q[0]), f64::from(q[1])))
            .collect();
        let corners: [(NodeIndex, [f64; 3]); 4] = std::array::from_fn(|k| (k + 1, x[k]));
        let mpcs = section_tie(0, corners, Some([5, 6, 7, 8])).unwrap();
        assert_eq!(mpcs.len(), 6 + 12);
        let (v, w) = ([0.3, -0.1, 0.2], [0.01, -0.02, 0.015]);
        let u = |d: NodeDof| -> f64 {
            let c = usize::from(d.component);
            if d.node == 0 {
                return if c < 3 { v[c] } else { w[c - 3] };
            }
            let r: [f64; 3] = std::array::from_fn(|i| x[d.node - 1][i] - p[i]);
            v[c] + cross(w, r)[c]
        };
        for m in &mpcs {
            let residual: f64 = m.iter().map(|&(d, coef)| coef * u(d)).sum();
            assert!(residual.abs() < 1e-12, "{m:?}: {residual}");
            // the dependent dof is an expanded node's and appears in no other MPC
            assert_ne!(m[0].0.node, 0);
            let elsewhere = mpcs.iter().flatten().filter(|t| t.0 == m[0].0).count();
            assert_eq!(elsewhere, 1);
        }
        // a deformation of the section that keeps its mean: the beam node does not move
        let stretch = |d: NodeDof| -> f64 {
            let c = usize::from(d.component);
            if d.node == 0 {
                return 0.0;
            }
            let r: [f64; 3] = std::array::from_fn(|i| x[d.node - 1][i] - p[i]);
            0.1 * dot(r, n1) * n1[c]
        };
        for m in &mpcs {
            let residual: f64 = m.iter().map(|&(d, coef)| coef * stretch(d)).sum();
            assert!(residual.abs() < 1e-12, "{m:?}: {residual}");
        }
    }

    /// The knot: a rigid motion plus a uniform expansion of the expanded nodes satisfies
    /// every equation; all but one of their dofs are dependent (α took the other).
    #[test]
    fn knot_tie_is_rigid_motion_with_expansion() {
        let at = [0.5, 0.2, -0.1];
        let x: Vec<[f64; 3]> = (0..6)
            .map(|k| {
                let t = k as f64;
                [
                    at[0] + 0.1 * t.cos(),
                    at[1] + 0.07 * t.sin(),
                    at[2] + 0.03 * (t - 2.5),
                ]
            })
            .collect();
        let dependent: Vec<(NodeIndex, [f64; 3])> =
            x.iter().enumerate().map(|(i, &p)| (i + 1, p)).collect();
        let mpcs = knot_tie(0, at, &dependent).unwrap();
        assert_eq!(mpcs.len(), 3 * 6 - 1);
        let (v, w, alpha) = ([0.3, -0.1, 0.2], [0.01, -0.02, 0.015], 0.004);
        let u = |d: NodeDof| -> f64 {
            let c = usize::from(d.component);
            if d.node == 0 {
                return if c < 3 { v[c] } else { w[c - 3] };
            }
            let r: [f64; 3] = std::array::from_fn(|i| x[d.node - 1][i] - at[i]);
            v[c] + cross(w, r)[c] + alpha * r[c]
        };
        for m in &mpcs {
            let residual: f64 = m.iter().map(|&(d, coef)| coef * u(d)).sum();
            assert!(residual.abs() < 1e-12, "{m:?}: {residual}");
            assert!(m[0].0.node != 0 && m[0].0.node != usize::MAX);
            assert!(m.iter().all(|t| t.0.node != usize::MAX));
        }
    }
}
