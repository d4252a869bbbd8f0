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

use crate::build::BuildMethod;
use crate::fe::DofMap;
use crate::model::{DofMask, Model, NodeIndex, RigidElement};

/// Largest ratio of Young's moduli between the model's materials that the build accepts
/// (docs/stability.md, row 7).
pub const MAX_CONTRAST: f64 = 1e10;

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

/// "part 2 (120 elements, ids 501–620, element set INSERT; 180 nodes, e.g. node 733)".
pub fn describe_part(model: &Model, parts: &[Part], k: usize) -> String {
    let p = &parts[k];
    let mut s = format!("part {} of {} (", k + 1, parts.len());
    if p.elements.is_empty() {
        s.push_str("no elements");
    } else {
        let ids = p.elements.iter().map(|&e| model.elements[e].id);
        let (lo, hi) = ids.fold((u64::MAX, 0), |(a, b), i| (a.min(i), b.max(i)));
        s.push_str(&format!("{} elements, ids {lo}–{hi}", p.elements.len()));
        let mut mark = vec![false; model.elements.len()];
        p.elements.iter().for_each(|&e| mark[e] = true);
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
    }
    s.push_str(&format!(
        "; {} nodes, e.g. node {})",
        p.nodes.len(),
        model.nodes[p.nodes[0]].id
    ));
    s
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
    for &(n, c) in rows {
        let mut r = rigid_row(model, dofs, n, c, x0, len);
        let norm0 = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        for b in &q {
            let d: f64 = (0..6).map(|i| r[i] * b[i]).sum();
            (0..6).for_each(|i| r[i] -= d * b[i]);
        }
        let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm > RANK_TOL * norm0.max(RANK_TOL) && norm0 > 0.0 {
            q.push(std::array::from_fn(|i| r[i] / norm));
        } else {
            redundant.push((n, c));
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
    Restraint { redundant, free }
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
    let parts = parts(model, dofs);
    let mut part_of = vec![usize::MAX; model.nodes.len()];
    for (k, p) in parts.iter().enumerate() {
        p.nodes.iter().for_each(|&n| part_of[n] = k);
    }
    // mass of every part (translational diagonal of M)
    for (k, p) in parts.iter().enumerate() {
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
                describe_part(model, &parts, k),
                if mats.is_empty() {
                    "its mass matrix is zero".to_string()
                } else {
                    format!("ρ = 0 in {}", mats.join(", "))
                }
            ));
        }
    }
    // stiffness contrast between the materials of the structural elements
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
                 drown in the rounding of the stiff part (measured at 1e12: 0.5 % frequency error, \
                 rigid modes at 1 % of the first flexible one); model the stiff part as rigid (an \
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
    let spc_rows = |k: usize| -> Vec<(NodeIndex, usize)> {
        model
            .spcs
            .iter()
            .filter(|s| part_of.get(s.node) == Some(&k))
            .flat_map(|s| node_rows(dofs, s.node, s.dofs))
            .collect()
    };
    let node_label =
        |(n, c): (NodeIndex, usize)| format!("node {} dof {}", model.nodes[n].id, c + 1);
    let free_free = matches!(method, BuildMethod::CraigChang | BuildMethod::Dietz)
        || (method == BuildMethod::Normal && reference.is_empty());
    if free_free {
        let loose: Vec<usize> = (0..parts.len())
            .filter(|&k| {
                !restrain(model, dofs, &parts[k], &spc_rows(k))
                    .free
                    .is_empty()
            })
            .collect();
        if loose.len() > 1 {
            let list: Vec<String> = loose
                .iter()
                .map(|&k| describe_part(model, &parts, k))
                .collect();
            return Err(format!(
                "free-free analysis: the model has {} disconnected parts, so it has {} zero-frequency \
                 modes instead of 6: {}; connect them (merge coincident nodes, tie or RBE2) or \
                 build each part as its own body",
                loose.len(),
                6 * loose.len(),
                list.join("; ")
            ));
        }
    }
    if method == BuildMethod::CraigBampton {
        for k in 0..parts.len() {
            let mut rows = spc_rows(k);
            rows.extend(
                interface
                    .iter()
                    .filter(|&&n| part_of[n] == k)
                    .flat_map(|&n| node_rows(dofs, n, DofMask::ALL)),
            );
            let r = restrain(model, dofs, &parts[k], &rows);
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
                    describe_part(model, &parts, k),
                    if rows.is_empty() {
                        "connect it to the rest of the model or add one of its nodes to --interface"
                    } else {
                        "add interface nodes, or attach the interface through a node set (an RBE2 \
                         spider, --spider rbe2) so that it carries rotations"
                    }
                ));
            }
        }
    }
    if !reference.is_empty() {
        for k in 0..parts.len() {
            let base = spc_rows(k);
            let nb = base.len();
            let mut rows = base;
            rows.extend(
                reference
                    .iter()
                    .filter(|(n, _)| part_of[*n] == k)
                    .flat_map(|&(n, mask)| node_rows(dofs, n, mask)),
            );
            let r = restrain(model, dofs, &parts[k], &rows);
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
                    describe_part(model, &parts, k),
                    extra.join(", ")
                ));
            }
            if !r.free.is_empty() {
                return Err(format!(
                    "reference conditions do not remove all rigid motion of {}: {} left free; \
                     give 6 independent dofs (e.g. all 6 dofs of one interface node)",
                    describe_part(model, &parts, k),
                    r.free.join(", ")
                ));
            }
        }
    }
    Ok(())
}
