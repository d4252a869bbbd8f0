//! `*TIE` (tied contact) and the element-face `*SURFACE`s it names, as CalculiX reads them
//! (ccx User's Manual, "*TIE"): every node of the slave surface (a node surface or element
//! faces) within the position tolerance of a master face (element faces of solids) is held on
//! that face by its shape functions, u_s = Σᵢ Nᵢ(ξ, η) u_i for the three translations — one
//! MPC per component ([`crate::model::Mpc`], eliminated as `*EQUATION`).
//!
//! * the faces of element-face surfaces are read in `faces.rs` (solids' `Sn`, shells' `SNEG`
//!   and `SPOS`); a native shell's face lies off its nodes by a lever d, and a tie holds the
//!   face point u + θ × d of such a node (`face_point_terms`);
//! * where a slave node lies on the master surface, and whether it is within the tolerances,
//!   is found as ccx 2.20 finds it ([`super::tie_search`]: the master faces of all ties cut
//!   into triangles; the in-face tolerance 2.5 % of their mean centroid-to-edge distance; the
//!   position tolerance POSITION TOLERANCE, or that in-face tolerance when absent or below
//!   1e-10); the MPC's coefficients are the face's shape functions at the node's nearest point
//!   of that face (its projection clamped to the face);
//! * ADJUST=YES (the default) moves each tied slave node onto the master face, ADJUST=NO keeps it;
//! * slave nodes with no master face opposite or farther than the position tolerance stay
//!   untied, and so do the components of a slave node already held by a `*BOUNDARY` or
//!   dependent in an equation (as ccx: "DOF not active"): one warning per tie counts them by
//!   reason and names every node (ccx writes them to `WarnNodeMissTiedContact.nam`; the build's
//!   `--json` report carries the warning); a slave node that
//!   is also a node of the master surface is not tied to it;
//! * CYCLIC SYMMETRY, MULTISTAGE and the fluid ties are refused; nodes in a `*TRANSFORM` frame
//!   are refused (the equations are in global components).

use std::collections::{BTreeSet, HashMap, HashSet};

use super::faces::Face;
use super::keywords::Keyword;
use super::sets::Sets;
use super::tie_search::{Found, MasterTriangles};
use super::{fields, Block, Parser};
use crate::import::error::ImportError;
use crate::import::text::{parse_f64, Loc};
use crate::model::{Mpc, NodeDof, NodeIndex};

/// One `*TIE`: its parameters and its data line.
#[derive(Debug)]
pub(super) struct RawTie {
    pub name: String,
    pub tolerance: Option<f64>,
    pub adjust: bool,
    /// (slave surface, master surface), from the data line.
    pub surfaces: Option<(String, String)>,
    pub loc: Loc,
}

impl Parser {
    /// `*TIE, NAME=…[, POSITION TOLERANCE=…][, ADJUST=YES|NO]`.
    pub(super) fn tie_keyword(&mut self, kw: &Keyword) -> Result<Block, ImportError> {
        let name = kw.need("NAME", self)?;
        let ent = format!("*TIE NAME={name}");
        for p in [
            "CYCLIC SYMMETRY",
            "MULTISTAGE",
            "FLUID PERIODIC",
            "FLUID CYCLIC",
        ] {
            if kw.param(p).is_some() {
                return Err(self.err(
                    kw.loc,
                    ent,
                    format!("{p} ties are not supported (only the tied contact of two surfaces)"),
                ));
            }
        }
        let tolerance = match kw.param("POSITION TOLERANCE") {
            Some(t) => Some(parse_f64(t).filter(|v| *v >= 0.0).ok_or_else(|| {
                self.err(
                    kw.loc,
                    ent.clone(),
                    format!("POSITION TOLERANCE={t} is not a length"),
                )
            })?),
            None => None,
        };
        let adjust = match kw.param("ADJUST").map(str::to_ascii_uppercase).as_deref() {
            None | Some("YES") => true,
            Some("NO") => false,
            Some(o) => return Err(self.err(kw.loc, ent, format!("ADJUST={o}: YES or NO"))),
        };
        self.ties.push(RawTie {
            name,
            tolerance,
            adjust,
            surfaces: None,
            loc: kw.loc,
        });
        Ok(Block::Tie(self.ties.len() - 1))
    }

    /// The data line of `*TIE` k: slave surface, master surface.
    pub(super) fn tie_line(&mut self, k: usize, line: &str, loc: Loc) -> Result<(), ImportError> {
        let v: Vec<String> = fields(line)
            .map(|s| s.trim().to_ascii_uppercase())
            .collect();
        let ent = format!("*TIE NAME={}", self.ties[k].name);
        match (v.first(), v.get(1)) {
            (Some(s), Some(m))
                if !s.is_empty() && !m.is_empty() && self.ties[k].surfaces.is_none() =>
            {
                self.ties[k].surfaces = Some((s.clone(), m.clone()));
                Ok(())
            }
            _ => Err(self.err(loc, ent, "one data line: slave surface, master surface")),
        }
    }

    /// Every `*TIE` → MPCs of its slave nodes on the master faces (module doc).
    pub(super) fn resolve_ties(&mut self, sets: &Sets) -> Result<(), ImportError> {
        let ties = std::mem::take(&mut self.ties);
        // the master faces of every tie, numbered over all ties (ccx triangulates them all)
        let mut faces: Vec<Face> = Vec::new();
        let mut per_tie: Vec<Vec<(usize, Vec<NodeIndex>)>> = Vec::new();
        for tie in &ties {
            let ent = format!("*TIE NAME={}", tie.name);
            let Some((_, master)) = &tie.surfaces else {
                return Err(self.err(tie.loc, ent, "no data line (slave surface, master surface)"));
            };
            let mine = self.surface_faces(master, sets, &ent)?.ok_or_else(|| {
                self.err(
                    tie.loc,
                    ent.clone(),
                    format!("the master surface {master} must be an element-face *SURFACE"),
                )
            })?;
            per_tie.push(
                (mine.iter().enumerate())
                    .map(|(k, f)| (faces.len() + k, f.nodes.clone()))
                    .collect(),
            );
            faces.extend(mine);
        }
        // a native shell's face lies off its nodes: each node's lever to the face (faces.rs)
        let mut lever: HashMap<NodeIndex, [f64; 3]> = HashMap::new();
        let mut slave_faces: Vec<Option<Vec<Face>>> = Vec::new();
        for tie in &ties {
            let ent = format!("*TIE NAME={}", tie.name);
            let slave = tie.surfaces.as_ref().map_or("", |s| s.0.as_str());
            slave_faces.push(self.surface_faces(slave, sets, &ent)?);
        }
        for f in faces.iter().chain(slave_faces.iter().flatten().flatten()) {
            for (n, d) in f.nodes.iter().zip(f.lever.iter().flatten()) {
                lever.entry(*n).or_insert(*d);
            }
        }
        let at = |nodes: &[crate::model::Node], n: NodeIndex| {
            let (x, d) = (nodes[n].x, lever.get(&n).copied());
            d.map_or(x, |d| [0, 1, 2].map(|k| x[k] + d[k]))
        };
        let search = MasterTriangles::new(&per_tie, |n| at(&self.b.model.nodes, n));
        let mut untied: Vec<Untied> = Vec::new();
        // components already held by *BOUNDARY or dependent in an equation (ccx: not active)
        let model = &self.b.model;
        let mut inactive: HashSet<(NodeIndex, u8)> = (model.spcs.iter())
            .flat_map(|s| {
                (0..6u8)
                    .filter(move |c| s.dofs.0 & (1 << c) != 0)
                    .map(move |c| (s.node, c))
            })
            .chain(
                model
                    .mpcs
                    .iter()
                    .map(|m| (m.terms[0].0.node, m.terms[0].0.component)),
            )
            .collect();
        for (k, tie) in ties.iter().enumerate() {
            let ent = format!("*TIE NAME={}", tie.name);
            let Some((slave, _)) = &tie.surfaces else {
                continue; // checked above
            };
            let on_master: BTreeSet<NodeIndex> = (per_tie[k].iter())
                .flat_map(|(_, nodes)| nodes.iter().copied())
                .collect();
            let slaves: BTreeSet<NodeIndex> = match &slave_faces[k] {
                Some(f) => f.iter().flat_map(|f| f.nodes.iter().copied()).collect(),
                None => self.node_surface(slave, sets, &ent, tie.loc)?,
            };
            let tolerance = match tie.tolerance {
                Some(t) if t >= 1e-10 => t,
                _ => search.in_face_tolerance,
            };
            let mut missed = Untied {
                tie: tie.name.clone(),
                tolerance,
                in_face: search.in_face_tolerance,
                ..Untied::default()
            };
            if let Some(&n) = slaves
                .iter()
                .find(|n| self.expanded_shell_nodes.contains(n))
            {
                return Err(self.err(
                    tie.loc,
                    ent,
                    format!(
                        "slave node {} is a shell node itself, in a deck whose ties or couplings \
                         also name faces of shells (SPOS, SNEG): not supported (name the \
                         shell's faces)",
                        self.b.model.nodes[n].id
                    ),
                ));
            }
            for &n in slaves.iter().filter(|n| !on_master.contains(n)) {
                let p = at(&self.b.model.nodes, n);
                let id = self.b.model.nodes[n].id;
                let face = match search.find(k, p, tolerance) {
                    Found::Face(f) => &faces[f],
                    Found::TooFar(d) => {
                        missed.too_far.push(id);
                        missed.farthest = missed.farthest.max(d);
                        continue;
                    }
                    Found::NoFace => {
                        missed.no_face.push(id);
                        continue;
                    }
                };
                let x: Vec<[f64; 3]> = (face.nodes.iter())
                    .map(|&m| at(&self.b.model.nodes, m))
                    .collect();
                let Some((xi, foot)) = project(&x, p) else {
                    return Err(self.err(
                        tie.loc,
                        ent,
                        format!("the master face of element {} is degenerate", face.element),
                    ));
                };
                for &m in face.nodes.iter().chain(std::iter::once(&n)) {
                    if self.b.model.nodes[m].displacement_frame.is_some() {
                        return Err(self.err(
                            tie.loc,
                            ent,
                            format!(
                                "node {} (face of element {}) has a *TRANSFORM frame: tied nodes must be in the global frame",
                                self.b.model.nodes[m].id, face.element
                            ),
                        ));
                    }
                }
                let (shape, _) = face_shape(face.nodes.len(), xi);
                for c in 0..3u8 {
                    if !inactive.insert((n, c)) {
                        missed.held.push(id);
                        continue;
                    }
                    let mut terms = face_point_terms(n, 1.0, c, &lever);
                    for (&m, &w) in face.nodes.iter().zip(&shape) {
                        if w.abs() > 1e-12 {
                            terms.extend(face_point_terms(m, -w, c, &lever));
                        }
                    }
                    let id = self.b.model.mpcs.len() as u64 + 1;
                    self.b.model.mpcs.push(Mpc { id, terms });
                }
                if tie.adjust {
                    let d = lever.get(&n).copied().unwrap_or_default();
                    self.b.model.nodes[n].x = [0, 1, 2].map(|k| foot[k] - d[k]);
                }
            }
            untied.push(missed);
        }

        for u in untied.iter().filter(|u| u.count() > 0) {
            self.b.model.warnings.push(crate::import::ImportWarning {
                file: self.b.files[0].clone(),
                message: u.message(),
            });
        }
        Ok(())
    }

    /// The nodes of a node surface (`*SURFACE, TYPE=NODE`).
    pub(super) fn node_surface(
        &self,
        name: &str,
        sets: &Sets,
        ent: &str,
        loc: Loc,
    ) -> Result<BTreeSet<NodeIndex>, ImportError> {
        let lines = self
            .surfaces
            .get(name)
            .ok_or_else(|| self.err(loc, ent.to_owned(), format!("unknown surface {name}")))?;
        let mut out = BTreeSet::new();
        for (t, _, at) in lines {
            out.extend(sets.target(t, *at, ent, self)?);
        }
        Ok(out)
    }
}

/// The slave nodes one tie leaves untied, by reason (ccx writes each to
/// `WarnNodeMissTiedContact.nam`: a node per search failure, a node per held component).
#[derive(Default)]
struct Untied {
    tie: String,
    tolerance: f64,
    in_face: f64,
    /// Opposite a master face, farther from it than the position tolerance.
    too_far: Vec<u64>,
    farthest: f64,
    /// No master face opposite within the in-face tolerance.
    no_face: Vec<u64>,
    /// One entry per component already held by `*BOUNDARY` or an equation.
    held: Vec<u64>,
}

impl Untied {
    /// The entries ccx writes to `WarnNodeMissTiedContact.nam` for this tie.
    fn count(&self) -> usize {
        self.too_far.len() + self.no_face.len() + self.held.len()
    }

    /// The warning: how many, why, and every node id.
    fn message(&self) -> String {
        let mut parts = Vec::new();
        if !self.too_far.is_empty() {
            parts.push(format!(
                "{} opposite a master face but farther from it than the position tolerance {:.4e} (up to {:.4e}): nodes {}",
                self.too_far.len(),
                self.tolerance,
                self.farthest,
                id_ranges(&self.too_far)
            ));
        }
        if !self.no_face.is_empty() {
            parts.push(format!(
                "{} with no master face opposite (in-face tolerance {:.4e}): nodes {}",
                self.no_face.len(),
                self.in_face,
                id_ranges(&self.no_face)
            ));
        }
        if !self.held.is_empty() {
            parts.push(format!(
                "{} component(s) already held by *BOUNDARY or an equation: nodes {}",
                self.held.len(),
                id_ranges(&self.held)
            ));
        }
        format!(
            "*TIE {}: {} slave node(s) not tied (as CalculiX 2.20, which lists them in WarnNodeMissTiedContact.nam): {}",
            self.tie,
            self.count(),
            parts.join("; ")
        )
    }
}

/// The terms `coefficient` · (u + θ × d)_c of the face point of node `n` (d its lever, none for
/// a node of a solid): (θ × d)_c = θ_{c+1} d_{c+2} − θ_{c+2} d_{c+1}.
fn face_point_terms(
    n: NodeIndex,
    coefficient: f64,
    c: u8,
    lever: &HashMap<NodeIndex, [f64; 3]>,
) -> Vec<(NodeDof, f64)> {
    let dof = |component: u8| NodeDof { node: n, component };
    let mut out = vec![(dof(c), coefficient)];
    if let Some(d) = lever.get(&n) {
        let (a, b) = ((c + 1) % 3, (c + 2) % 3);
        out.push((dof(3 + a), coefficient * d[b as usize]));
        out.push((dof(3 + b), -coefficient * d[a as usize]));
    }
    out
}

/// Node ids as sorted runs: "3-7, 12, 15-16".
fn id_ranges(ids: &[u64]) -> String {
    let mut v = ids.to_vec();
    v.sort_unstable();
    v.dedup();
    let mut out: Vec<String> = Vec::new();
    let mut k = 0;
    while k < v.len() {
        let mut j = k;
        while j + 1 < v.len() && v[j + 1] == v[j] + 1 {
            j += 1;
        }
        out.push(if j == k {
            v[k].to_string()
        } else {
            format!("{}-{}", v[k], v[j])
        });
        k = j + 1;
    }
    out.join(", ")
}

/// Shape functions of a face of `n` nodes (3: linear triangle, 6: quadratic, 4: bilinear
/// quadrilateral, 8: serendipity; corners then mid-side nodes of edges 1-2, 2-3, …) at (ξ, η),
/// and their derivatives (Zienkiewicz & Taylor, Vol. 1 §8.5, §8.8). Triangles use (ξ, η) with
/// L = (1 − ξ − η, ξ, η); quadrilaterals (ξ, η) ∈ [−1, 1]².
pub(crate) fn face_shape(n: usize, p: [f64; 2]) -> (Vec<f64>, Vec<[f64; 2]>) {
    let (s, t) = (p[0], p[1]);
    match n {
        3 => (
            vec![1.0 - s - t, s, t],
            vec![[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]],
        ),
        6 => {
            let l = [1.0 - s - t, s, t];
            let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
            let mut n = Vec::with_capacity(6);
            let mut d = Vec::with_capacity(6);
            for k in 0..3 {
                n.push(l[k] * (2.0 * l[k] - 1.0));
                d.push(dl[k].map(|v| (4.0 * l[k] - 1.0) * v));
            }
            for k in 0..3 {
                let (a, b) = (k, (k + 1) % 3);
                n.push(4.0 * l[a] * l[b]);
                d.push([0, 1].map(|j| 4.0 * (dl[a][j] * l[b] + l[a] * dl[b][j])));
            }
            (n, d)
        }
        4 | 8 => {
            const C: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
            let mut n = vec![0.0; n];
            let mut d = vec![[0.0; 2]; n.len()];
            let quadratic = n.len() == 8;
            for (k, c) in C.iter().enumerate() {
                let (a, b) = (1.0 + c[0] * s, 1.0 + c[1] * t);
                if quadratic {
                    let e = c[0] * s + c[1] * t - 1.0;
                    n[k] = 0.25 * a * b * e;
                    d[k] = [0.25 * c[0] * (b * e + a * b), 0.25 * c[1] * (a * e + a * b)];
                } else {
                    n[k] = 0.25 * a * b;
                    d[k] = [0.25 * c[0] * b, 0.25 * c[1] * a];
                }
            }
            if quadratic {
                // mid-side nodes of edges 1-2 (η = −1), 2-3 (ξ = 1), 3-4 (η = 1), 4-1 (ξ = −1)
                for (k, (axis, sign)) in [(1, -1.0), (0, 1.0), (1, 1.0), (0, -1.0)]
                    .iter()
                    .enumerate()
                {
                    let (u, v) = if *axis == 1 { (s, t) } else { (t, s) };
                    // N = ½ (1 − u²)(1 + sign v); u runs along the edge
                    n[4 + k] = 0.5 * (1.0 - u * u) * (1.0 + sign * v);
                    let du = -u * (1.0 + sign * v);
                    let dv = 0.5 * (1.0 - u * u) * sign;
                    d[4 + k] = if *axis == 1 { [du, dv] } else { [dv, du] };
                }
            }
            (n, d)
        }
        _ => (vec![], vec![]),
    }
}

/// The point of a face (corner and mid-side coordinates `x`) nearest to `p`: Gauss–Newton on
/// min |x(ξ, η) − p|², the parameters clamped to the face. `None` for a degenerate face.
pub(crate) fn project(x: &[[f64; 3]], p: [f64; 3]) -> Option<([f64; 2], [f64; 3])> {
    let tri = matches!(x.len(), 3 | 6);
    let clamp = |q: [f64; 2]| -> [f64; 2] {
        if tri {
            let (mut s, mut t) = (q[0].max(0.0), q[1].max(0.0));
            if s + t > 1.0 {
                let e = 0.5 * (s + t - 1.0);
                s = (s - e).clamp(0.0, 1.0);
                t = (t - e).clamp(0.0, 1.0);
            }
            [s, t]
        } else {
            [q[0].clamp(-1.0, 1.0), q[1].clamp(-1.0, 1.0)]
        }
    };
    let at = |q: [f64; 2]| -> ([f64; 3], [[f64; 3]; 2]) {
        let (n, d) = face_shape(x.len(), q);
        let mut r = [0.0; 3];
        let mut g = [[0.0; 3]; 2];
        for k in 0..x.len() {
            for c in 0..3 {
                r[c] += n[k] * x[k][c];
                g[0][c] += d[k][0] * x[k][c];
                g[1][c] += d[k][1] * x[k][c];
            }
        }
        (r, g)
    };
    let mut q = if tri { [1.0 / 3.0; 2] } else { [0.0; 2] };
    for _ in 0..30 {
        let (r, g) = at(q);
        let e = [p[0] - r[0], p[1] - r[1], p[2] - r[2]];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let (a, b, c) = (dot(g[0], g[0]), dot(g[0], g[1]), dot(g[1], g[1]));
        let det = a * c - b * b;
        if det.is_nan() || det <= 1e-30 * (a + c) * (a + c) {
            return None;
        }
        let (f0, f1) = (dot(g[0], e), dot(g[1], e));
        let step = [(c * f0 - b * f1) / det, (a * f1 - b * f0) / det];
        let next = clamp([q[0] + step[0], q[1] + step[1]]);
        let moved = (next[0] - q[0]).abs() + (next[1] - q[1]).abs();
        q = next;
        if moved < 1e-14 {
            break;
        }
    }
    Some((q, at(q).0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    }

    #[test]
    fn face_shape_functions_interpolate_their_nodes_and_sum_to_one() {
        let tri6 = [
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [0.5, 0.0],
            [0.5, 0.5],
            [0.0, 0.5],
        ];
        let quad8 = [
            [-1.0, -1.0],
            [1.0, -1.0],
            [1.0, 1.0],
            [-1.0, 1.0],
            [0.0, -1.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [-1.0, 0.0],
        ];
        for nodes in [&tri6[..3], &tri6[..], &quad8[..4], &quad8[..]] {
            for (k, q) in nodes.iter().enumerate() {
                let (n, _) = face_shape(nodes.len(), *q);
                for (j, v) in n.iter().enumerate() {
                    assert!(
                        (v - f64::from(u8::from(j == k))).abs() < 1e-14,
                        "{} {k} {j}",
                        nodes.len()
                    );
                }
            }
            // derivatives against central differences at an inner point
            let p = [0.21, 0.17];
            let (n0, d) = face_shape(nodes.len(), p);
            assert!((n0.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            for j in 0..2 {
                let mut q = p;
                q[j] += 1e-7;
                let (n1, _) = face_shape(nodes.len(), q);
                for k in 0..nodes.len() {
                    assert!(
                        ((n1[k] - n0[k]) / 1e-7 - d[k][j]).abs() < 1e-6,
                        "{} {k} {j}",
                        nodes.len()
                    );
                }
            }
        }
    }

    #[test]
    fn projection_finds_the_foot_point_and_clamps_to_the_face() {
        let quad = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let (q, at) = project(&quad, [0.5, 0.25, 0.3]).unwrap();
        assert!(
            (q[0] + 0.5).abs() < 1e-12 && (q[1] + 0.5).abs() < 1e-12,
            "{q:?}"
        );
        assert!(dist(at, [0.5, 0.25, 0.0]) < 1e-12);
        let (_, at) = project(&quad, [2.5, 0.5, 0.0]).unwrap();
        assert!(dist(at, [2.0, 0.5, 0.0]) < 1e-12);
    }
}
