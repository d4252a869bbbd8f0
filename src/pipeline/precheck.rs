//! Model-level checks run by `flexbody build` before the reduction, so that a request the model
//! cannot satisfy stops with a message naming nodes, elements and element sets instead of a
//! singular factorization deep in the solver (docs/stability.md, rows 1, 2, 8 and 10):
//!
//! * the connected parts of the model (elements and rigid elements joining nodes);
//! * every part carries mass;
//! * free-free methods: exactly one unrestrained part;
//! * Craig–Bampton: the interface dofs (with SPCs) remove all rigid motion of every part;
//! * reference conditions: they remove all rigid motion and none is redundant.
//!
//! Rigid motion is judged from the geometry: each restrained dof is a row of the 6-column
//! rigid-body matrix R (u = t + θ × (x − x₀) in the dof's displacement frame); the restraints
//! hold a part when rank R_restraint = rank R_part, and a restraint is redundant when its row
//! lies in the span of the rows before it.

use faer::sparse::SparseColMat;
use faer::Mat;

use crate::fe::DofMap;
use crate::model::{DofMask, Model, NodeIndex, RigidElement};
use crate::pipeline::BuildMethod;

/// Largest ratio of Young's moduli between the model's materials that the build accepts
/// (docs/stability.md, row 7): the sparse iterative path meets its residual bounds to 1e8 (with
/// its refinement steps); at 1e10 the first flexible modes fall below the rounding floor that
/// separates them from rigid motion.
pub const MAX_CONTRAST: f64 = 1e8;

/// Relative size below which a rigid-matrix singular value or a row residual counts as zero.
const RANK_TOL: f64 = 1e-8;

/// A connected part of the model: nodes joined by elements and rigid elements.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Node indices, ascending.
    pub nodes: Vec<NodeIndex>,
    /// Element indices, ascending.
    pub elements: Vec<usize>,
}

/// Connected parts over the nodes that carry dofs, ordered by their first node.
pub fn parts(model: &Model, dofs: &DofMap) -> Vec<Part> {
    let nn = model.nodes.len();
    let mut parent: Vec<usize> = (0..nn).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let join = |p: &mut Vec<usize>, nodes: &mut dyn Iterator<Item = usize>| {
        let mut root = None;
        for n in nodes.filter(|&n| n < nn) {
            let r = find(p, n);
            match root {
                None => root = Some(r),
                Some(f) if f != r => p[r] = f,
                Some(_) => {}
            }
        }
    };
    for e in &model.elements {
        join(&mut parent, &mut e.nodes.iter().copied());
    }
    for r in &model.rigid_elements {
        match r {
            RigidElement::Rbe2 {
                independent,
                dependent,
                ..
            } => join(
                &mut parent,
                &mut std::iter::once(*independent).chain(dependent.iter().copied()),
            ),
            RigidElement::Rbe3 {
                reference,
                independent,
                ..
            } => join(
                &mut parent,
                &mut std::iter::once(*reference).chain(independent.iter().map(|x| x.0)),
            ),
        }
    }
    // springs, bushes, scalar masses, MPCs and RBAR/RBE1 join their nodes too
    for group in model.connector_node_groups() {
        join(&mut parent, &mut group.into_iter());
    }
    let mut index = vec![usize::MAX; nn];
    let mut out: Vec<Part> = Vec::new();
    for n in 0..nn {
        if dofs.count.get(n).copied().unwrap_or(0) == 0 {
            continue;
        }
        let r = find(&mut parent, n);
        if index[r] == usize::MAX {
            index[r] = out.len();
            out.push(Part {
                nodes: vec![],
                elements: vec![],
            });
        }
        out[index[r]].nodes.push(n);
    }
    for (i, e) in model.elements.iter().enumerate() {
        if let Some(&n) = e.nodes.first().filter(|&&n| n < nn) {
            let r = find(&mut parent, n);
            if index[r] != usize::MAX {
                out[index[r]].elements.push(i);
            }
        }
    }
    out
}

/// "part 2 of 3 (120 elements, ids 501–620, element sets INSERT; 180 nodes, e.g. node 733)".
pub fn describe_part(model: &Model, parts: &[Part], k: usize) -> String {
    let p = &parts[k];
    format!(
        "part {} of {} ({}; {} nodes, e.g. node {})",
        k + 1,
        parts.len(),
        describe_elements(model, &p.elements),
        p.nodes.len(),
        model.nodes[p.nodes[0]].id
    )
}

/// "120 elements, ids 501–620, element sets INSERT" (or "no elements").
fn describe_elements(model: &Model, elements: &[usize]) -> String {
    if elements.is_empty() {
        return "no elements".into();
    }
    let ids = elements.iter().map(|&e| model.elements[e].id);
    let (lo, hi) = ids.fold((u64::MAX, 0), |(a, b), i| (a.min(i), b.max(i)));
    let mut s = format!("{} elements, ids {lo}–{hi}", elements.len());
    let mut mark = vec![false; model.elements.len()];
    elements.iter().for_each(|&e| mark[e] = true);
    let sets: Vec<&str> = model
        .element_sets
        .iter()
        .filter(|(_, v)| v.iter().any(|&e| e < mark.len() && mark[e]))
        .map(|(k, _)| k.as_str())
        .take(4)
        .collect();
    if !sets.is_empty() {
        s.push_str(&format!(", element sets {}", sets.join(", ")));
    }
    s
}

/// Groups of the solid elements of a part bonded through shared faces (three non-collinear
/// shared nodes), each with its nodes, and the nodes where groups meet. A rigid element joins
/// the groups in which its nodes span a face (a spider over one face stays in its group and adds
/// its centre node to it). `None` when the part also holds beams or rods, whose joints carry
/// rotations. Solids meeting only at a node or along an edge are a mechanism (3 or 1 extra zero
/// modes).
pub fn solid_groups(model: &Model, part: &Part) -> Option<(Vec<Part>, Vec<NodeIndex>)> {
    // springs, MPCs and RBAR/RBE1 may hold groups together in ways the face test cannot judge
    if !model.connector_node_groups().is_empty() {
        return None;
    }
    if part
        .elements
        .iter()
        .any(|&e| !model.elements[e].kind.is_solid())
    {
        return None;
    }
    let els = &part.elements;
    let mut node_els: std::collections::HashMap<NodeIndex, Vec<usize>> = Default::default();
    for (a, &e) in els.iter().enumerate() {
        for &n in &model.elements[e].nodes {
            node_els.entry(n).or_default().push(a);
        }
    }
    let mut parent: Vec<usize> = (0..els.len()).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for a in 0..els.len() {
        let na = &model.elements[els[a]].nodes;
        for &n in na {
            for &b in &node_els[&n] {
                if b <= a || find(&mut parent, a) == find(&mut parent, b) {
                    continue;
                }
                let shared: Vec<[f64; 3]> = model.elements[els[b]]
                    .nodes
                    .iter()
                    .filter(|m| na.contains(m))
                    .map(|&m| model.nodes[m].x)
                    .collect();
                if spans_a_face(&shared) {
                    let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                    parent[rb] = ra;
                }
            }
        }
    }
    // rigid elements: join every group in which their nodes span a face
    let mut extra: Vec<(usize, Vec<NodeIndex>)> = Vec::new(); // (an element of the group, nodes)
    for r in &model.rigid_elements {
        let nodes: Vec<NodeIndex> = match r {
            RigidElement::Rbe2 {
                independent,
                dependent,
                ..
            } => std::iter::once(*independent)
                .chain(dependent.iter().copied())
                .collect(),
            RigidElement::Rbe3 {
                reference,
                independent,
                ..
            } => std::iter::once(*reference)
                .chain(independent.iter().map(|x| x.0))
                .collect(),
        };
        let mut by_root: std::collections::BTreeMap<usize, Vec<[f64; 3]>> = Default::default();
        for &n in &nodes {
            if let Some(v) = node_els.get(&n) {
                let mut roots: Vec<usize> = v.iter().map(|&a| find(&mut parent, a)).collect();
                roots.sort_unstable();
                roots.dedup();
                for r0 in roots {
                    by_root.entry(r0).or_default().push(model.nodes[n].x);
                }
            }
        }
        let joined: Vec<usize> = by_root
            .into_iter()
            .filter(|(_, pts)| spans_a_face(pts))
            .map(|(r0, _)| r0)
            .collect();
        if let Some(&first) = joined.first() {
            for &other in &joined[1..] {
                let (ra, rb) = (find(&mut parent, first), find(&mut parent, other));
                parent[rb] = ra;
            }
            extra.push((first, nodes));
        }
    }
    let mut index = std::collections::HashMap::new();
    let mut groups: Vec<Part> = Vec::new();
    let mut group_of = vec![0usize; els.len()];
    for a in 0..els.len() {
        let r = find(&mut parent, a);
        let g = *index.entry(r).or_insert_with(|| {
            groups.push(Part {
                nodes: vec![],
                elements: vec![],
            });
            groups.len() - 1
        });
        groups[g].elements.push(els[a]);
        groups[g]
            .nodes
            .extend(model.elements[els[a]].nodes.iter().copied());
        group_of[a] = g;
    }
    for (a, nodes) in extra {
        let g = index[&find(&mut parent, a)];
        groups[g].nodes.extend(nodes);
    }
    let mut count = vec![0u8; model.nodes.len()];
    for g in &mut groups {
        g.nodes.sort_unstable();
        g.nodes.dedup();
        g.nodes
            .iter()
            .for_each(|&n| count[n] = count[n].saturating_add(1));
    }
    let joints: Vec<NodeIndex> = (0..count.len()).filter(|&n| count[n] > 1).collect();
    Some((groups, joints))
}

/// Whether points include three that are not collinear.
fn spans_a_face(p: &[[f64; 3]]) -> bool {
    if p.len() < 3 {
        return false;
    }
    let d = |a: [f64; 3], b: [f64; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let n2 = |v: [f64; 3]| v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let far = p.iter().copied().fold(p[0], |best, q| {
        if n2(d(p[0], q)) > n2(d(p[0], best)) {
            q
        } else {
            best
        }
    });
    let u = d(p[0], far);
    p.iter().any(|&q| {
        let v = d(p[0], q);
        let c = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        n2(c) > 1e-12 * n2(u) * n2(u)
    })
}

fn node_ids(model: &Model, nodes: &[NodeIndex]) -> String {
    let ids: Vec<String> = nodes
        .iter()
        .take(6)
        .map(|&n| model.nodes[n].id.to_string())
        .collect();
    let more = if nodes.len() > 6 { ", …" } else { "" };
    format!("{}{more}", ids.join(", "))
}

/// Rigid-body row of dof `c` of node `n`: its value under the six unit rigid motions about `x0`
/// (rotations scaled by `len`, so every entry is a length).
fn rigid_row(
    model: &Model,
    dofs: &DofMap,
    n: NodeIndex,
    c: usize,
    x0: [f64; 3],
    len: f64,
) -> [f64; 6] {
    let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let a = dofs.frames[n].unwrap_or(id);
    let x = model.nodes[n].x;
    let d = [x[0] - x0[0], x[1] - x0[1], x[2] - x0[2]];
    let mut row = [0.0; 6];
    if c < 3 {
        let ax = a[c];
        for k in 0..3 {
            row[k] = ax[k];
            // e_k × d
            let mut ed = [0.0; 3];
            ed[(k + 1) % 3] = -d[(k + 2) % 3];
            ed[(k + 2) % 3] = d[(k + 1) % 3];
            // θ = e_k / len: u = (e_k × d) / len, scaled back by len for a length
            row[3 + k] = (0..3).map(|i| ax[i] * ed[i]).sum::<f64>() / len;
        }
    } else {
        row[3..].copy_from_slice(&a[c - 3]);
    }
    row
}

/// Centre and size of a part (node bounding box).
fn frame_of(model: &Model, nodes: &[NodeIndex]) -> ([f64; 3], f64) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &n in nodes {
        for k in 0..3 {
            lo[k] = lo[k].min(model.nodes[n].x[k]);
            hi[k] = hi[k].max(model.nodes[n].x[k]);
        }
    }
    let x0 = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let len = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    (x0, if len > 0.0 { len } else { 1.0 })
}

/// Outcome of holding a part at some dofs.
struct Restraint {
    /// Restraint rows that lie in the span of the ones before them: (node, dof 0-based).
    redundant: Vec<(NodeIndex, usize)>,
    /// Rigid motions left free, described.
    free: Vec<String>,
}

/// Greedy row-by-row rank of the restraints of a part against the part's own rigid space.
fn restrain(model: &Model, dofs: &DofMap, part: &Part, rows: &[(NodeIndex, usize)]) -> Restraint {
    let (x0, len) = frame_of(model, &part.nodes);
    let rigid_rows: Vec<[f64; 6]> = rows
        .iter()
        .map(|&(n, c)| rigid_row(model, dofs, n, c, x0, len))
        .collect();
    let (redundant, free) = restrain_rows(model, dofs, part, &rigid_rows);
    Restraint {
        redundant: redundant.into_iter().map(|i| rows[i]).collect(),
        free,
    }
}

/// [`restrain`] on rigid-body rows about the part's [`frame_of`]: the indices of the redundant
/// rows and the rigid motions left free, described.
fn restrain_rows(
    model: &Model,
    dofs: &DofMap,
    part: &Part,
    rows: &[[f64; 6]],
) -> (Vec<usize>, Vec<String>) {
    let (x0, len) = frame_of(model, &part.nodes);
    // the part's rigid space: eigenvectors of RᵀR over all its dofs
    let mut g = Mat::<f64>::zeros(6, 6);
    for &n in &part.nodes {
        for c in 0..usize::from(dofs.count[n]) {
            let r = rigid_row(model, dofs, n, c, x0, len);
            for i in 0..6 {
                for j in 0..6 {
                    g[(i, j)] += r[i] * r[j];
                }
            }
        }
    }
    let mut q: Vec<[f64; 6]> = Vec::new();
    let mut redundant = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        let mut r = *row;
        let norm0 = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        for b in &q {
            let d: f64 = (0..6).map(|i| r[i] * b[i]).sum();
            (0..6).for_each(|i| r[i] -= d * b[i]);
        }
        let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm > RANK_TOL * norm0.max(RANK_TOL) && norm0 > 0.0 {
            q.push(std::array::from_fn(|i| r[i] / norm));
        } else {
            redundant.push(i);
        }
    }
    // free motions: the part's rigid space with the restrained directions projected out
    let proj = |v: &mut [f64; 6]| {
        for b in &q {
            let d: f64 = (0..6).map(|i| v[i] * b[i]).sum();
            (0..6).for_each(|i| v[i] -= d * b[i]);
        }
    };
    let mut free = Vec::new();
    if let Ok((vals, vecs)) = crate::solve::dense::eigh(g.as_ref()) {
        let vmax = vals.iter().fold(0.0f64, |a, &b| a.max(b));
        let mut basis: Vec<[f64; 6]> = Vec::new();
        for j in (0..6).rev() {
            if vals[j] <= RANK_TOL * vmax {
                continue;
            }
            let mut v: [f64; 6] = std::array::from_fn(|i| vecs[(i, j)]);
            proj(&mut v);
            for b in &basis {
                let d: f64 = (0..6).map(|i| v[i] * b[i]).sum();
                (0..6).for_each(|i| v[i] -= d * b[i]);
            }
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm > 1e-6 {
                basis.push(std::array::from_fn(|i| v[i] / norm));
            }
        }
        // name the free space by the coordinate motions it contains: greedily the unit
        // translation/rotation (about the part's centre) with the largest projection onto it
        let mut chosen: Vec<[f64; 6]> = Vec::new();
        for _ in 0..basis.len() {
            let mut best = ([0.0; 6], 0.0);
            for e in 0..6 {
                let mut v = [0.0; 6];
                for b in &basis {
                    (0..6).for_each(|i| v[i] += b[e] * b[i]);
                }
                for c in &chosen {
                    let d: f64 = (0..6).map(|i| v[i] * c[i]).sum();
                    (0..6).for_each(|i| v[i] -= d * c[i]);
                }
                let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                if norm > best.1 + 1e-9 {
                    best = (v.map(|x| x / norm), norm);
                }
            }
            if best.1 <= 1e-6 {
                break;
            }
            chosen.push(best.0);
            free.push(describe_motion(&best.0, x0, len));
        }
    }
    (redundant, free)
}

/// "translation along (1, 0, 0)" or "rotation about (0, 0, 1) through (0.1, 0, 0)".
fn describe_motion(v: &[f64; 6], x0: [f64; 3], len: f64) -> String {
    let t = [v[0], v[1], v[2]];
    let w = [v[3] / len, v[4] / len, v[5] / len];
    let wn = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    let fmt = |a: [f64; 3]| {
        let a = a.map(|x| if x.abs() < 1e-9 { 0.0 } else { x });
        format!("({:.3}, {:.3}, {:.3})", a[0], a[1], a[2])
    };
    if wn * len < 1e-6 {
        return format!("translation along {}", fmt(t));
    }
    // axis point p = x0 + w × t / |w|²
    let c = [
        w[1] * t[2] - w[2] * t[1],
        w[2] * t[0] - w[0] * t[2],
        w[0] * t[1] - w[1] * t[0],
    ];
    let p = std::array::from_fn(|k| x0[k] + c[k] / (wn * wn));
    format!(
        "rotation about {} through {}",
        fmt(w.map(|x| x / wn)),
        fmt(p)
    )
}

fn node_rows(
    dofs: &DofMap,
    n: NodeIndex,
    mask: DofMask,
) -> impl Iterator<Item = (NodeIndex, usize)> + '_ {
    let count = usize::from(dofs.count[n]);
    mask.dofs().filter(move |&c| c < count).map(move |c| (n, c))
}

/// The checks of the module doc. `m` is the assembled (physical) mass matrix; `interface` the
/// interface nodes (all their dofs); `reference` the reference conditions. Returns what is wrong
/// and what to do.
pub fn before_reduction(
    model: &Model,
    dofs: &DofMap,
    m: &SparseColMat<usize, f64>,
    method: BuildMethod,
    interface: &[NodeIndex],
    reference: &[(NodeIndex, DofMask)],
) -> Result<(), String> {
    let parts = Parts::of(model, dofs);
    every_part_has_mass(&parts, m)?;
    stiffness_contrast(model)?;
    let free_free = matches!(method, BuildMethod::CraigChang | BuildMethod::Dietz)
        || (method == BuildMethod::Normal && reference.is_empty());
    if free_free {
        one_free_body(&parts)?;
    }
    if method == BuildMethod::CraigBampton {
        held_by_interfaces(&parts, interface)?;
    }
    if !reference.is_empty() {
        held_by_reference_conditions(&parts, reference)?;
    }
    Ok(())
}

/// The model's connected parts, and which part each node is in.
struct Parts<'a> {
    model: &'a Model,
    dofs: &'a DofMap,
    parts: Vec<Part>,
    /// Node → its part (`usize::MAX`: none).
    part_of: Vec<usize>,
}

impl<'a> Parts<'a> {
    fn of(model: &'a Model, dofs: &'a DofMap) -> Self {
        let parts = parts(model, dofs);
        let mut part_of = vec![usize::MAX; model.nodes.len()];
        for (k, p) in parts.iter().enumerate() {
            p.nodes.iter().for_each(|&n| part_of[n] = k);
        }
        Parts {
            model,
            dofs,
            parts,
            part_of,
        }
    }

    /// The rows the model's SPCs hold in part `k`.
    fn spc_rows(&self, k: usize) -> Vec<(NodeIndex, usize)> {
        self.model
            .spcs
            .iter()
            .filter(|s| self.part_of.get(s.node) == Some(&k))
            .flat_map(|s| node_rows(self.dofs, s.node, s.dofs))
            .collect()
    }

    /// Part `k` in words: its elements, sets and nodes.
    fn describe(&self, k: usize) -> String {
        describe_part(self.model, &self.parts, k)
    }
}

/// Every part has mass (the translational diagonal of M), else its modes have no frequency.
fn every_part_has_mass(parts: &Parts, m: &SparseColMat<usize, f64>) -> Result<(), String> {
    let (model, dofs) = (parts.model, parts.dofs);
    for (k, p) in parts.parts.iter().enumerate() {
        let mass: f64 = p
            .nodes
            .iter()
            .flat_map(|&n| (0..3.min(usize::from(dofs.count[n]))).map(move |c| dofs.first[n] + c))
            .map(|d| {
                m.as_ref()
                    .row_idx_of_col(d)
                    .zip(m.as_ref().val_of_col(d))
                    .find(|(r, _)| *r == d)
                    .map_or(0.0, |(_, v)| *v)
            })
            .sum();
        if mass <= 0.0 || !mass.is_finite() {
            let mut mats: Vec<String> = p
                .elements
                .iter()
                .filter_map(|&e| model.elements[e].property)
                .filter_map(|pr| model.properties.get(pr))
                .filter_map(|pr| model.materials.get(pr.material))
                .filter(|mat| mat.rho == 0.0)
                .map(|mat| format!("material {} '{}'", mat.id, mat.name))
                .collect();
            mats.sort();
            mats.dedup();
            return Err(format!(
                "{} has no mass ({}): its modes would have zero or undefined frequencies; \
                 give the material its density",
                parts.describe(k),
                if mats.is_empty() {
                    "its mass matrix is zero".to_string()
                } else {
                    format!("ρ = 0 in {}", mats.join(", "))
                }
            ));
        }
    }
    Ok(())
}

/// The stiffness contrast between the materials of the structural elements stays below
/// [`MAX_CONTRAST`].
fn stiffness_contrast(model: &Model) -> Result<(), String> {
    let used: Vec<&crate::model::Material> = {
        let mut ids: Vec<usize> = model
            .elements
            .iter()
            .filter_map(|e| e.property)
            .filter_map(|p| model.properties.get(p))
            .map(|p| p.material)
            .filter(|&m| m < model.materials.len())
            .collect();
        ids.sort_unstable();
        ids.dedup();
        ids.into_iter().map(|m| &model.materials[m]).collect()
    };
    let by_e = |a: &&&crate::model::Material, b: &&&crate::model::Material| a.e.total_cmp(&b.e);
    if let (Some(soft), Some(stiff)) = (used.iter().min_by(by_e), used.iter().max_by(by_e)) {
        if soft.e > 0.0 && stiff.e / soft.e > MAX_CONTRAST {
            return Err(format!(
                "stiffness contrast {:.1e} between material {} '{}' (E = {:e}) and material {} '{}' \
                 (E = {:e}) exceeds {MAX_CONTRAST:.0e}: in double precision the soft part's modes \
                 drown in the rounding of the stiff part (measured at 1e10 on a 1872-dof block: the \
                 first flexible modes no longer separate from rigid motion); model the stiff part as rigid (an \
                 RBE2 over its nodes) or lower its modulus",
                stiff.e / soft.e,
                stiff.id,
                stiff.name,
                stiff.e,
                soft.id,
                soft.name,
                soft.e
            ));
        }
    }
    Ok(())
}

/// Free-free: one free body — no second disconnected part, no solid groups turning against
/// each other about shared nodes.
fn one_free_body(parts: &Parts) -> Result<(), String> {
    let (model, dofs) = (parts.model, parts.dofs);
    let loose: Vec<usize> = (0..parts.parts.len())
        .filter(|&k| {
            !restrain(model, dofs, &parts.parts[k], &parts.spc_rows(k))
                .free
                .is_empty()
        })
        .collect();
    if loose.len() > 1 {
        let list: Vec<String> = loose.iter().map(|&k| parts.describe(k)).collect();
        return Err(format!(
            "free-free analysis: the model has {} disconnected parts, so it has {} zero-frequency \
             modes instead of 6: {}; connect them (merge coincident nodes, tie or RBE2) or \
             build each part as its own body",
            loose.len(),
            6 * loose.len(),
            list.join("; ")
        ));
    }
    for (k, part) in parts.parts.iter().enumerate() {
        if let Some((groups, joints)) = solid_groups(model, part).filter(|g| g.0.len() > 1) {
            let list: Vec<String> = groups
                .iter()
                .enumerate()
                .map(|(i, g)| format!("group {}: {}", i + 1, describe_elements(model, &g.elements)))
                .collect();
            return Err(format!(
                "free-free analysis: {} is a mechanism: its solid elements form {} groups that \
                 share no face, only node(s) {} ({}), so they can turn against each other \
                 (extra zero-frequency modes); merge or tie the groups over a face",
                parts.describe(k),
                groups.len(),
                node_ids(model, &joints),
                list.join("; ")
            ));
        }
    }
    Ok(())
}

/// Craig–Bampton: the model's SPCs and the interface nodes hold every part (and every
/// face-bonded solid group of it), else K_ii is singular.
fn held_by_interfaces(parts: &Parts, interface: &[NodeIndex]) -> Result<(), String> {
    let (model, dofs) = (parts.model, parts.dofs);
    for k in 0..parts.parts.len() {
        let mut rows = parts.spc_rows(k);
        rows.extend(
            interface
                .iter()
                .filter(|&&n| parts.part_of[n] == k)
                .flat_map(|&n| node_rows(dofs, n, DofMask::ALL)),
        );
        let r = restrain(model, dofs, &parts.parts[k], &rows);
        if r.free.is_empty() {
            // a mechanism inside the part: every face-bonded group must be held on its own
            if let Some((groups, joints)) = solid_groups(model, &parts.parts[k]) {
                for (i, g) in groups.iter().enumerate().filter(|_| groups.len() > 1) {
                    let mut mine = vec![false; model.nodes.len()];
                    g.nodes.iter().for_each(|&n| mine[n] = true);
                    let rows_g: Vec<(NodeIndex, usize)> =
                        rows.iter().copied().filter(|&(n, _)| mine[n]).collect();
                    let rg = restrain(model, dofs, g, &rows_g);
                    if !rg.free.is_empty() {
                        return Err(format!(
                            "Craig–Bampton: in {}, group {} of {} solid groups ({}) shares no face \
                             with the others (only node(s) {}) and is not held by its interface \
                             dofs: {} left free, so K_ii is singular; tie the groups over a face \
                             or give this group interface nodes",
                            parts.describe(k),
                            i + 1,
                            groups.len(),
                            describe_elements(model, &g.elements),
                            node_ids(model, &joints),
                            rg.free.join(", ")
                        ));
                    }
                }
            }
        }
        if !r.free.is_empty() {
            let what = if rows.is_empty() {
                "is not connected to any interface node".to_string()
            } else {
                format!(
                    "is not held by its interface dofs: {} left free",
                    r.free.join(", ")
                )
            };
            return Err(format!(
                "Craig–Bampton: {} {what}, so the fixed-interface stiffness K_ii is singular; \
                 {}",
                parts.describe(k),
                if rows.is_empty() {
                    "connect it to the rest of the model or add one of its nodes to --interface"
                } else {
                    "add interface nodes, or attach the interface through a node set (an RBE2 \
                     spider, --spider rbe2) so that it carries rotations"
                }
            ));
        }
    }
    Ok(())
}

/// Reference conditions remove every rigid motion of each part, and none twice.
fn held_by_reference_conditions(
    parts: &Parts,
    reference: &[(NodeIndex, DofMask)],
) -> Result<(), String> {
    let (model, dofs) = (parts.model, parts.dofs);
    let node_label =
        |(n, c): (NodeIndex, usize)| format!("node {} dof {}", model.nodes[n].id, c + 1);
    for k in 0..parts.parts.len() {
        let base = parts.spc_rows(k);
        let nb = base.len();
        let mut rows = base;
        rows.extend(
            reference
                .iter()
                .filter(|(n, _)| parts.part_of[*n] == k)
                .flat_map(|&(n, mask)| node_rows(dofs, n, mask)),
        );
        let r = restrain(model, dofs, &parts.parts[k], &rows);
        let extra: Vec<String> = r
            .redundant
            .iter()
            .filter(|x| rows.iter().position(|y| y == *x).is_some_and(|i| i >= nb))
            .map(|&x| node_label(x))
            .collect();
        if !extra.is_empty() {
            return Err(format!(
                "reference conditions over-constrain {}: {} repeat(s) a rigid motion already \
                 held by the others, so the body would be stiffened; give exactly 6 \
                 independent dofs (e.g. all 6 dofs of one interface node)",
                parts.describe(k),
                extra.join(", ")
            ));
        }
        if !r.free.is_empty() {
            return Err(format!(
                "reference conditions do not remove all rigid motion of {}: {} left free; \
                 give 6 independent dofs (e.g. all 6 dofs of one interface node)",
                parts.describe(k),
                r.free.join(", ")
            ));
        }
    }
    Ok(())
}

/// The rigid-body motions a model with several connected parts leaves free: the sum over its
/// parts of each part's free motions (6 − the rank of its restraint rows, [`restrain_rows`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidExpectation {
    /// Free rigid motions summed over the parts.
    pub count: usize,
    /// The parts and their free motions in words, for the check's detail line.
    pub detail: String,
}

/// The expected rigid-body modes of a model of several connected parts ([`parts`]): each part's
/// rigid motions (u = t + θ × x over its dofs) less those held by the model's SPCs, the
/// reference conditions `reference`, grounded springs and bushes and one-term MPCs (u = 0) on
/// its nodes. `None` for a model of one part: the file's own rule (its reference conditions,
/// [`crate::pipeline::file_checks`]) then says the same. An MPC or a spring between two dofs
/// of one part is taken to follow rigid motion (a ROT NODE's equations, an SPRINGA); one that
/// resists it leaves fewer zero modes than counted here, and the build's check says so.
pub fn expected_rigid_motions(
    model: &Model,
    dofs: &DofMap,
    reference: &[(NodeIndex, DofMask)],
) -> Option<RigidExpectation> {
    let parts = Parts::of(model, dofs);
    if parts.parts.len() < 2 {
        return None;
    }
    let mut count = 0;
    let mut words = Vec::new();
    for (k, part) in parts.parts.iter().enumerate() {
        let (x0, len) = frame_of(model, &part.nodes);
        let mine = |n: NodeIndex| parts.part_of.get(n) == Some(&k);
        let node_dofs: Vec<(NodeIndex, usize)> = parts
            .spc_rows(k)
            .into_iter()
            .chain(
                reference
                    .iter()
                    .filter(|(n, _)| mine(*n))
                    .flat_map(|&(n, mask)| node_rows(dofs, n, mask)),
            )
            .chain(
                (model.springs.iter())
                    .filter(|s| s.b.is_none() && s.k != 0.0 && mine(s.a.node))
                    .map(|s| (s.a.node, usize::from(s.a.component))),
            )
            .chain(
                (model.mpcs.iter())
                    .filter(|m| m.terms.len() == 1 && mine(m.terms[0].0.node))
                    .map(|m| (m.terms[0].0.node, usize::from(m.terms[0].0.component))),
            )
            .filter(|&(n, c)| c < usize::from(dofs.count[n]))
            .collect();
        let mut rows: Vec<[f64; 6]> = node_dofs
            .iter()
            .map(|&(n, c)| rigid_row(model, dofs, n, c, x0, len))
            .collect();
        for b in model.bushes.iter().filter(|b| b.b.is_none() && mine(b.a)) {
            for c in (0..6).filter(|&c| b.k[c] != 0.0) {
                rows.push(direction_row(b.location, b.axes[c % 3], c < 3, x0, len));
            }
        }
        let free = restrain_rows(model, dofs, part, &rows).1.len();
        count += free;
        words.push(format!("{}: {free} free", parts.describe(k)));
    }
    Some(RigidExpectation {
        count,
        detail: format!(
            "the model's {} connected parts, each less what its SPCs, reference conditions and \
             grounded springs hold: {}",
            parts.parts.len(),
            words.join("; ")
        ),
    })
}

/// Rigid-body row of a translation along the unit vector `e` at the point `x` (or, with
/// `translation` false, a rotation about `e`), as [`rigid_row`]: e·(t + θ × (x − x₀)) = e·t +
/// θ·((x − x₀) × e).
fn direction_row(x: [f64; 3], e: [f64; 3], translation: bool, x0: [f64; 3], len: f64) -> [f64; 6] {
    if !translation {
        return [0.0, 0.0, 0.0, e[0], e[1], e[2]];
    }
    let d = [x[0] - x0[0], x[1] - x0[1], x[2] - x0[2]];
    [
        e[0],
        e[1],
        e[2],
        (d[1] * e[2] - d[2] * e[1]) / len,
        (d[2] * e[0] - d[0] * e[2]) / len,
        (d[0] * e[1] - d[1] * e[0]) / len,
    ]
}
