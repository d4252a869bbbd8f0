//! Springs, linear equations and rigid bodies of the Abaqus/CalculiX reader, into the model's
//! connectors ([`crate::model::connector`]) and rigid elements.
//!
//! * `*ELEMENT, TYPE=SPRINGA` + `*SPRING, ELSET=…` (a blank line, then k): an axial spring
//!   between two nodes, strain energy ½ k (e·(u_b − u_a))², e the unit vector from a to b
//!   (CalculiX User's Manual, "SPRINGA"): [`Bush::axial`].
//! * `SPRING1` (the dof line: one dof; then k): k on one dof of a node, to ground;
//!   `SPRING2` (dof at the first node, dof at the second; then k): ½ k (u_a,i − u_b,j)². Their
//!   dofs are global directions: a node with a `*TRANSFORM` frame is refused.
//! * `DASHPOTA` elements take no part (`*DASHPOT` is a note: damping).
//! * `*EQUATION`: the number of terms, then (node, dof, coefficient) triples; Σ cᵢ uᵢ = 0 with the
//!   first term's dof dependent (as CalculiX eliminates it), in the nodes' `*TRANSFORM` frames.
//! * `*RIGID BODY, NSET=… | ELSET=…, REF NODE=…, ROT NODE=…`: every node of the set follows
//!   the rigid motion of the reference node (an RBE2; without REF NODE the set's first node);
//!   the ROT NODE's three translations are the body's rotations (three equations).

use std::collections::HashMap;

use super::{fields, target, Parser, Target};
use crate::import::error::ImportError;
use crate::import::text::{parse_u64, IdMap, Loc};
use crate::model::{Bush, DofMask, Mpc, NodeDof, NodeIndex, RigidElement, ScalarSpring};

/// A spring or dashpot element: its type and node ids.
#[derive(Debug)]
pub(super) struct ConnElement {
    pub card: &'static str,
    pub nodes: Vec<u64>,
    pub loc: Loc,
}

/// One `*SPRING`: its element set and data lines (fields of each non-blank line).
#[derive(Debug)]
pub(super) struct RawSpring {
    pub elset: String,
    pub lines: Vec<(Vec<String>, Loc)>,
    pub loc: Loc,
}

/// One `*EQUATION`: its terms (node, dof 1–6, coefficient) and the number announced.
#[derive(Debug)]
pub(super) struct RawEquation {
    pub count: usize,
    pub terms: Vec<(Target, u8, f64)>,
    pub loc: Loc,
}

/// One `*RIGID BODY`.
#[derive(Debug)]
pub(super) struct RawRigidBody {
    /// `NSET=` (true) or `ELSET=` (false) and the set's name.
    pub node_set: bool,
    pub set: String,
    pub reference: Option<Target>,
    pub rotation: Option<Target>,
    pub loc: Loc,
}

/// The dofs (1 … 6) of a SPRING1 (first end) or SPRING2 (both ends); `None` for SPRINGA.
type SpringDofs = Option<(u8, Option<u8>)>;

/// Node count of the point and connector element types (`None`: not one of them).
pub(super) fn connector_node_count(card: &str) -> Option<usize> {
    match card {
        "MASS" | "ROTARYI" | "SPRING1" => Some(1),
        "SPRINGA" | "SPRING2" | "DASHPOTA" => Some(2),
        _ => None,
    }
}

impl Parser {
    /// A `*SPRING` data line of definition `k`.
    pub(super) fn spring_line(&mut self, k: usize, line: &str, loc: Loc) {
        let f = fields(line).map(str::to_owned).collect();
        self.springs[k].lines.push((f, loc));
    }

    /// A `*EQUATION` data line: the number of terms, or up to four terms.
    pub(super) fn equation_line(&mut self, line: &str, loc: Loc) -> Result<(), ImportError> {
        let f: Vec<&str> = fields(line).filter(|s| !s.is_empty()).collect();
        let open = self
            .equations
            .last()
            .is_some_and(|e| e.terms.len() < e.count);
        if !open {
            let count = f
                .first()
                .and_then(|s| parse_u64(s))
                .filter(|&n| n > 0 && f.len() == 1)
                .ok_or_else(|| {
                    self.err(
                        loc,
                        "*EQUATION",
                        format!("expected the number of terms, found '{}'", line.trim()),
                    )
                })?;
            self.equations.push(RawEquation {
                count: count as usize,
                terms: Vec::new(),
                loc,
            });
            return Ok(());
        }
        if f.len() % 3 != 0 {
            return Err(self.err(
                loc,
                "*EQUATION",
                format!("terms are node, dof, coefficient: '{}'", line.trim()),
            ));
        }
        for t in f.chunks(3) {
            let dof = parse_u64(t[1])
                .filter(|d| (1..=6).contains(d))
                .ok_or_else(|| {
                    self.err(loc, "*EQUATION", format!("dof '{}' is not 1 … 6", t[1]))
                })?;
            let c = self.real(t[2], "*EQUATION", loc)?;
            // `open` above: an equation with terms still to come exists
            if let Some(eq) = self.equations.last_mut() {
                eq.terms.push((target(t[0]), dof as u8, c));
            }
        }
        Ok(())
    }

    /// The resolved model's springs, equations and rigid bodies.
    pub(super) fn resolve_connectors(
        &mut self,
        nodes: &IdMap,
        node_sets: &std::collections::BTreeMap<String, Vec<NodeIndex>>,
        element_sets: &std::collections::BTreeMap<String, Vec<usize>>,
    ) -> Result<(), ImportError> {
        self.resolve_springs(nodes)?;
        self.resolve_equations(nodes, node_sets)?;
        self.resolve_rigid_bodies(nodes, node_sets, element_sets)
    }

    /// The node of a spring or equation: a node id, or a set of one node.
    fn one_node(
        &self,
        t: &Target,
        nodes: &IdMap,
        node_sets: &std::collections::BTreeMap<String, Vec<NodeIndex>>,
        ent: &str,
        loc: Loc,
    ) -> Result<NodeIndex, ImportError> {
        match t {
            Target::Node(id) => nodes
                .get(*id)
                .ok_or_else(|| self.err(loc, ent.to_owned(), format!("unknown node {id}"))),
            Target::Set(s) => match node_sets.get(s).map(Vec::as_slice) {
                Some([n]) => Ok(*n),
                Some(m) => Err(self.err(
                    loc,
                    ent.to_owned(),
                    format!(
                        "node set {s} has {} nodes: a term of one node (or a set of one) is supported",
                        m.len()
                    ),
                )),
                None => Err(self.err(loc, ent.to_owned(), format!("unknown node set {s}"))),
            },
        }
    }

    /// `*SPRING` definitions → bushes (SPRINGA) and scalar springs (SPRING1, SPRING2).
    fn resolve_springs(&mut self, nodes: &IdMap) -> Result<(), ImportError> {
        let mut stiffness: HashMap<u64, (f64, SpringDofs)> = HashMap::new();
        for s in &self.springs {
            let ent = format!("*SPRING ELSET={}", s.elset);
            let members = self.elsets.get(&s.elset).ok_or_else(|| {
                self.err(
                    s.loc,
                    ent.clone(),
                    format!("unknown element set {}", s.elset),
                )
            })?;
            for &(id, _) in members {
                let Some(e) = self.conn_elems.get(&id).filter(|e| e.card != "DASHPOTA") else {
                    return Err(self.err(
                        s.loc,
                        ent,
                        format!("element {id} of the set is not a SPRINGA/SPRING1/SPRING2 element"),
                    ));
                };
                let (k, dofs) = self.spring_data(s, e.card, &ent)?;
                stiffness.insert(id, (k, dofs));
            }
        }
        let mut ids: Vec<&u64> = self.conn_elems.keys().collect();
        ids.sort_unstable();
        for id in ids {
            let e = &self.conn_elems[id];
            if e.card == "DASHPOTA" {
                continue;
            }
            let ent = format!("*ELEMENT {id} ({})", e.card);
            let Some(&(k, dofs)) = stiffness.get(id) else {
                return Err(self.err(e.loc, ent, "no *SPRING gives its stiffness"));
            };
            let mut ends = Vec::new();
            for &n in &e.nodes {
                ends.push(nodes.get(n).ok_or_else(|| {
                    self.err(e.loc, ent.clone(), format!("references unknown node {n}"))
                })?);
            }
            match (e.card, dofs) {
                ("SPRINGA", _) => {
                    let bush = self.axial_spring(*id, ends[0], ends[1], k, e.loc, &ent)?;
                    self.b.model.bushes.push(bush);
                }
                (_, Some((da, db))) => {
                    if let Some(&n) = ends
                        .iter()
                        .find(|&&n| self.b.model.nodes[n].displacement_frame.is_some())
                    {
                        return Err(self.err(
                            e.loc,
                            ent,
                            format!(
                                "node {} has a *TRANSFORM frame: the spring's global dofs in a transformed node are not supported",
                                self.b.model.nodes[n].id
                            ),
                        ));
                    }
                    let b = match (ends.get(1), db) {
                        (Some(&nb), Some(db)) => Some(NodeDof {
                            node: nb,
                            component: db - 1,
                        }),
                        _ => None,
                    };
                    self.b.model.springs.push(ScalarSpring {
                        id: *id,
                        a: NodeDof {
                            node: ends[0],
                            component: da - 1,
                        },
                        b,
                        k,
                    });
                }
                _ => return Err(self.err(e.loc, ent, "no dof line in its *SPRING")),
            }
        }
        Ok(())
    }

    /// A `*SPRING`'s stiffness and (SPRING1/SPRING2) dofs, for elements of type `card`.
    fn spring_data(
        &self,
        s: &RawSpring,
        card: &str,
        ent: &str,
    ) -> Result<(f64, SpringDofs), ImportError> {
        // SPRINGA: (a blank line, skipped, then) the stiffness line; SPRING1/2: dofs, stiffness.
        let want = if card == "SPRINGA" { 1 } else { 2 };
        if s.lines.len() != want {
            let loc = s.lines.get(want).map_or(s.loc, |l| l.1);
            return Err(self.err(
                loc,
                ent.to_owned(),
                format!(
                    "{card} takes {}; found {} data lines (temperature tables are not supported)",
                    if want == 1 {
                        "one data line, the stiffness"
                    } else {
                        "two data lines, the dofs and the stiffness"
                    },
                    s.lines.len()
                ),
            ));
        }
        let (kf, kloc) = &s.lines[want - 1];
        let k = self.real(kf.first().map_or("", String::as_str), ent, *kloc)?;
        if !(k.is_finite() && k >= 0.0) {
            return Err(self.err(*kloc, ent.to_owned(), format!("stiffness {k} is not ≥ 0")));
        }
        if want == 1 {
            return Ok((k, None));
        }
        let (df, dloc) = &s.lines[0];
        let dof = |i: usize| -> Result<u8, ImportError> {
            let t = df.get(i).map_or("", String::as_str);
            parse_u64(t)
                .filter(|d| (1..=6).contains(d))
                .map(|d| d as u8)
                .ok_or_else(|| self.err(*dloc, ent.to_owned(), format!("dof '{t}' is not 1 … 6")))
        };
        let da = dof(0)?;
        let db = if card == "SPRING2" {
            Some(dof(1)?)
        } else {
            None
        };
        Ok((k, Some((da, db))))
    }

    /// SPRINGA between nodes a and b: a bush with stiffness k along the axis a → b alone.
    fn axial_spring(
        &self,
        id: u64,
        a: NodeIndex,
        b: NodeIndex,
        k: f64,
        loc: Loc,
        ent: &str,
    ) -> Result<Bush, ImportError> {
        let (xa, xb) = (self.b.model.nodes[a].x, self.b.model.nodes[b].x);
        Bush::axial(id, (a, xa), (b, xb), k).ok_or_else(|| {
            self.err(
                loc,
                ent.to_owned(),
                "its two nodes coincide: an axial spring needs a direction",
            )
        })
    }

    /// `*EQUATION`s → linear MPCs (first term dependent), numbered in deck order.
    ///
    /// Rotations of shell nodes that ccx 2.20 expands (`--inp-shells expanded`): ccx's
    /// `gen3dmpc` moves such a term onto the same rotational dof of the node's expanded nodes,
    /// which no brick has, so the equation constrains nothing (measured:
    /// `fixtures/ccx_shell_surfaces/equation_*_s8r.inp`, ccx's frequencies with and without it
    /// are equal). An equation of such rotations only is therefore left out as ccx leaves it,
    /// with a warning naming it; one that mixes them with other dofs is refused.
    fn resolve_equations(
        &mut self,
        nodes: &IdMap,
        node_sets: &std::collections::BTreeMap<String, Vec<NodeIndex>>,
    ) -> Result<(), ImportError> {
        let expanded_shell_nodes: std::collections::HashSet<NodeIndex> = match self.inp_shells {
            crate::import::InpShells::Expanded => (self.b.model.elements.iter())
                .zip(&self.b.elem_card)
                .filter(|(_, card)| super::shell_expansion::SHELL_TYPES.contains(card))
                .flat_map(|(e, _)| e.nodes.iter().copied())
                .collect(),
            crate::import::InpShells::Native => Default::default(),
        };
        let mut out = Vec::new();
        for (k, eq) in self.equations.iter().enumerate() {
            if eq.terms.len() != eq.count {
                return Err(self.err(
                    eq.loc,
                    "*EQUATION",
                    format!("{} terms announced, {} given", eq.count, eq.terms.len()),
                ));
            }
            if eq.terms[0].2 == 0.0 {
                return Err(self.err(
                    eq.loc,
                    "*EQUATION",
                    "the first term (the dependent dof) has coefficient 0",
                ));
            }
            let mut terms = Vec::with_capacity(eq.terms.len());
            for (t, dof, c) in &eq.terms {
                let node = self.one_node(t, nodes, node_sets, "*EQUATION", eq.loc)?;
                terms.push((
                    NodeDof {
                        node,
                        component: dof - 1,
                    },
                    *c,
                ));
            }
            let shell_rotation = |(d, _): &&(NodeDof, f64)| {
                d.component >= 3 && expanded_shell_nodes.contains(&d.node)
            };
            let rotations = terms.iter().filter(shell_rotation).count();
            if rotations > 0 {
                let id = self.b.model.nodes
                    [terms.iter().find(shell_rotation).map_or(0, |t| t.0.node)]
                .id;
                if rotations < terms.len() {
                    return Err(self.err(
                        eq.loc,
                        "*EQUATION",
                        format!(
                            "a rotation of shell node {id} beside other dofs: ccx 2.20 expands \
                             the shell into bricks, which have no rotations, and applies the \
                             term to nothing; not supported (--inp-shells native gives shell \
                             nodes rotations)"
                        ),
                    ));
                }
                self.b.model.warnings.push(crate::model::ImportWarning {
                    file: self.b.file_name(eq.loc).to_owned(),
                    message: format!(
                        "line {}: *EQUATION on rotations of shell nodes (node {id}) left out, as \
                         ccx 2.20 leaves it: its expanded shells' bricks have no rotations, so \
                         the equation constrains nothing (--inp-shells native applies it to the \
                         shells' rotations)",
                        eq.loc.line
                    ),
                });
                continue;
            }
            out.push(Mpc {
                id: k as u64 + 1,
                terms,
            });
        }
        self.b.model.mpcs.extend(out);
        Ok(())
    }

    /// `*RIGID BODY` → RBE2 to the reference node, and the ROT NODE's equations.
    fn resolve_rigid_bodies(
        &mut self,
        nodes: &IdMap,
        node_sets: &std::collections::BTreeMap<String, Vec<NodeIndex>>,
        element_sets: &std::collections::BTreeMap<String, Vec<usize>>,
    ) -> Result<(), ImportError> {
        let mut rbe2 = Vec::new();
        let mut mpcs = Vec::new();
        let first_mpc = self.b.model.mpcs.len() as u64;
        for r in &self.rigid {
            let ent = format!(
                "*RIGID BODY {}={}",
                if r.node_set { "NSET" } else { "ELSET" },
                r.set
            );
            let mut members: Vec<NodeIndex> = if r.node_set {
                node_sets.get(&r.set).cloned().ok_or_else(|| {
                    self.err(r.loc, ent.clone(), format!("unknown node set {}", r.set))
                })?
            } else {
                let els = element_sets.get(&r.set).ok_or_else(|| {
                    self.err(r.loc, ent.clone(), format!("unknown element set {}", r.set))
                })?;
                let mut m: Vec<NodeIndex> = (els.iter())
                    .flat_map(|&e| self.b.model.elements[e].nodes.iter().copied())
                    .collect();
                m.sort_unstable();
                m.dedup();
                m
            };
            let reference = match &r.reference {
                Some(t) => self.one_node(t, nodes, node_sets, &ent, r.loc)?,
                None => *members
                    .first()
                    .ok_or_else(|| self.err(r.loc, ent.clone(), "the set is empty"))?,
            };
            members.retain(|&n| n != reference);
            if let Some(t) = &r.rotation {
                let rot = self.one_node(t, nodes, node_sets, &ent, r.loc)?;
                if rot == reference || members.contains(&rot) {
                    return Err(self.err(
                        r.loc,
                        ent,
                        "the ROT NODE must be a node of its own (not the reference node or a node of the set)",
                    ));
                }
                // u_rot,i − θ_ref,i = 0: the rotation node's translations are the rotations.
                for i in 0..3u8 {
                    mpcs.push(Mpc {
                        id: first_mpc + mpcs.len() as u64 + 1,
                        terms: vec![
                            (
                                NodeDof {
                                    node: rot,
                                    component: i,
                                },
                                1.0,
                            ),
                            (
                                NodeDof {
                                    node: reference,
                                    component: i + 3,
                                },
                                -1.0,
                            ),
                        ],
                    });
                }
            }
            rbe2.push((reference, members));
        }
        let first_rigid = self.b.model.rigid_elements.len() as u64;
        for (k, (independent, dependent)) in rbe2.into_iter().enumerate() {
            self.b.model.rigid_elements.push(RigidElement::Rbe2 {
                id: first_rigid + k as u64 + 1,
                independent,
                dependent,
                dofs: DofMask::ALL,
            });
        }
        self.b.model.mpcs.extend(mpcs);
        Ok(())
    }
}
