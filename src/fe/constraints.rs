//! Rigid elements and constraints by elimination: u = T u_r, K_r = Tᵀ K T, M_r = Tᵀ M T
//! (Cook, Malkus, Plesha & Witt, *Concepts and Applications of FEA*, 4th ed. §9.2).
//!
//! * RBE2 (rigid spider): each constrained dof of a dependent node d follows the independent node
//!   i rigidly, u_d = u_i + θ_i × (x_d − x_i), θ_d = θ_i (in basic components; rotated into the
//!   nodes' displacement frames).
//! * RBE3 (weighted average): the reference node's motion q = [u θ] is the weighted least-squares
//!   rigid fit of the independent nodes, q = S⁻¹ Σ w Gᵀ u with G = [I, −r̃] per translation row
//!   (r = x_i − x_ref) and S = Σ w GᵀG (MSC Nastran QRG, RBE3 remarks). With only translations
//!   referenced and a degenerate S (one node, collinear nodes) the translation-only average is used.
//!   For an RBE3 whose reference node must stay independent (an interface node of a
//!   Craig–Bampton reduction), the same relation q = A u is solved instead for as many dofs u_m
//!   of the weighted nodes (Nastran's UM set), chosen by column-pivoted Gram–Schmidt on A so
//!   that A_m is well conditioned: u_m = A_m⁻¹ (q − A_o u_o).
//! * RBAR, RBAR1, RBE1 (rigid bodies with chosen independent dofs) and MPCs: the rows of
//!   [`super::rigid_body`].
//! * SPCs: the dofs are dropped (their T rows are empty).
//! * AUTOSPC (on by default): retained dofs whose K_r and M_r diagonals are both exactly zero
//!   (e.g. bending rotations of rod-only nodes) are dropped too, and listed.
//!
//! Chains (a dependent dof referring to another dependent dof) are resolved by substitution;
//! a cycle or a dof made dependent twice is an error naming the elements (or MPC sets).

use std::collections::HashMap;

use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Mat, MatRef};
use rayon::prelude::*;

use super::dofs::DofMap;
use super::rigid_body::Expr;
use super::FeError;
use crate::model::geometry::sub;
use crate::model::{DofMask, Model, NodeIndex, RigidElement};

/// Which constraints to apply.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintSpec {
    /// SPC set ids to apply; `None` = every SPC of the model.
    pub spc_sets: Option<Vec<u64>>,
    /// Further fixed dofs (e.g. an interface set clamped for fixed-interface modes).
    pub fixed: Vec<(NodeIndex, DofMask)>,
    /// Drop retained dofs with zero stiffness and zero mass diagonal (Nastran AUTOSPC).
    pub auto_spc: bool,
    /// RBE3 reference nodes whose dofs stay independent (interface nodes): the element's
    /// relation makes dofs of its weighted nodes dependent instead (module doc).
    pub independent_rbe3_reference: Vec<NodeIndex>,
}

impl Default for ConstraintSpec {
    fn default() -> Self {
        ConstraintSpec {
            spc_sets: None,
            fixed: Vec::new(),
            auto_spc: true,
            independent_rbe3_reference: Vec::new(),
        }
    }
}

/// The reduced system and the map back to physical dofs.
#[derive(Debug, Clone)]
pub struct Reduced {
    /// T (n_physical × n_reduced): u = T u_r.
    pub t: SparseColMat<usize, f64>,
    /// K_r = Tᵀ K T, full symmetric.
    pub k: SparseColMat<usize, f64>,
    /// M_r = Tᵀ M T, full symmetric.
    pub m: SparseColMat<usize, f64>,
    /// Physical dof of each reduced dof (reduced dofs are retained physical dofs).
    pub retained: Vec<usize>,
    /// Physical dofs dropped by AUTOSPC.
    pub auto_spc: Vec<usize>,
}

impl Reduced {
    /// Physical vectors from reduced ones: X = T X_r (mode shapes at every physical node).
    pub fn expand(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        let t = self.t.as_ref();
        let mut out = Mat::zeros(t.nrows(), x.ncols());
        for j in 0..t.ncols() {
            for (i, v) in t.row_idx_of_col(j).zip(t.val_of_col(j)) {
                for c in 0..x.ncols() {
                    out[(i, c)] += v * x[(j, c)];
                }
            }
        }
        out
    }
}

/// What made a dof dependent, for messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Owner {
    /// A rigid element (RBE2, RBE3, RBAR, RBAR1, RBE1) by id.
    Rigid(u64),
    /// An MPC set by id.
    Mpc(u64),
}

impl std::fmt::Display for Owner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Owner::Rigid(id) => write!(f, "rigid element {id}"),
            Owner::Mpc(id) => write!(f, "MPC {id}"),
        }
    }
}

/// Build T and the reduced K, M: the held dofs ([`held_dofs`]), the dependent dofs of rigid
/// elements, rigid bodies and MPCs ([`dependent_dofs`]), T by substitution over the dofs left
/// ([`substitution_rows`]), then the automatic SPCs of dofs with neither stiffness nor mass.
pub fn eliminate(
    model: &Model,
    dofs: &DofMap,
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    spec: &ConstraintSpec,
) -> Result<Reduced, FeError> {
    let fixed = held_dofs(model, dofs, spec)?;
    let dep = dependent_dofs(model, dofs, spec, &fixed)?;
    // in dof order, so the error names the same dof every run
    if let Some(d) = (0..dofs.n_dofs).find(|d| fixed[*d] && dep.contains_key(d)) {
        let (node, c) = dofs.node_of(d).unwrap_or((0, 0));
        return Err(constraint_error(
            model,
            format!(
                "dof {} of node {} is constrained by an SPC and is dependent in {}",
                c + 1,
                model.nodes[node].id,
                dep[&d].1
            ),
        ));
    }
    let (rows, retained) = substitution_rows(model, dofs, &dep, &fixed)?;
    let (t, k_r, m_r) = triple(&rows, retained.len(), k, m);
    if spec.auto_spc {
        return Ok(without_empty_dofs(rows, retained, (t, k_r, m_r), k, m));
    }
    Ok(Reduced {
        t,
        k: k_r,
        m: m_r,
        retained,
        auto_spc: Vec::new(),
    })
}

/// The constraint error of `model`.
fn constraint_error(model: &Model, message: String) -> FeError {
    FeError::Constraint {
        source_file: model.source.clone(),
        message,
    }
}

/// `node` is an index of `model`, else an error naming `what` refers to it.
fn check_node(model: &Model, node: usize, what: &str) -> Result<(), FeError> {
    if node < model.nodes.len() {
        Ok(())
    } else {
        Err(constraint_error(
            model,
            format!(
                "{what} refers to node index {node} beyond the {} nodes",
                model.nodes.len()
            ),
        ))
    }
}

/// The held dofs: the model's SPCs of the selected sets and `spec.fixed`.
fn held_dofs(model: &Model, dofs: &DofMap, spec: &ConstraintSpec) -> Result<Vec<bool>, FeError> {
    let mut fixed = vec![false; dofs.n_dofs];
    let mut fix = |node: usize, mask: DofMask| {
        for c in mask.dofs() {
            if let Some(d) = dofs.dof(node, c) {
                fixed[d] = true;
            }
        }
    };
    for s in &model.spcs {
        check_node(model, s.node, "SPC")?;
        if spec
            .spc_sets
            .as_ref()
            .is_none_or(|sets| sets.contains(&s.set_id))
        {
            fix(s.node, s.dofs);
        }
    }
    for &(node, mask) in &spec.fixed {
        check_node(model, node, "fixed dof")?;
        fix(node, mask);
    }
    Ok(fixed)
}

/// Dependent dof → (expression over physical dofs, what made it dependent): the rows of the
/// rigid elements, rigid bodies and MPCs; a dof dependent twice is an error.
fn dependent_dofs(
    model: &Model,
    dofs: &DofMap,
    spec: &ConstraintSpec,
    fixed: &[bool],
) -> Result<HashMap<usize, (Expr, Owner)>, FeError> {
    let mut dep: HashMap<usize, (Expr, Owner)> = HashMap::new();
    let mut add_dep = |d: usize, e: Expr, owner: Owner| -> Result<(), FeError> {
        if let Some((_, other)) = dep.get(&d) {
            let (node, c) = dofs.node_of(d).unwrap_or((usize::MAX, 0));
            let both = match (other, owner) {
                (Owner::Rigid(a), Owner::Rigid(b)) => format!("rigid elements {a} and {b}"),
                _ => format!("{other} and {owner}"),
            };
            return Err(constraint_error(
                model,
                format!(
                    "dof {} of node {} is dependent in {both}",
                    c + 1,
                    model.nodes.get(node).map_or(0, |n| n.id)
                ),
            ));
        }
        dep.insert(d, (e, owner));
        Ok(())
    };
    for r in &model.rigid_elements {
        for (dd, e, owner) in rigid_element_rows(model, dofs, spec, fixed, r)? {
            add_dep(dd, e, owner)?;
        }
    }
    for body in &model.rigid_bodies {
        for node in body.nodes() {
            check_node(model, node, "rigid element")?;
        }
        let rows = super::rigid_body::rigid_body_rows(model, dofs, body)
            .map_err(|m| constraint_error(model, format!("rigid element {}: {m}", body.id)))?;
        for (dd, e) in rows {
            add_dep(dd, e, Owner::Rigid(body.id))?;
        }
    }
    for mpc in &model.mpcs {
        for (d, _) in &mpc.terms {
            check_node(model, d.node, "MPC")?;
        }
        let (dd, e) = super::rigid_body::mpc_row(model, dofs, mpc)
            .map_err(|m| constraint_error(model, format!("MPC {}: {m}", mpc.id)))?;
        add_dep(dd, e, Owner::Mpc(mpc.id))?;
    }
    Ok(dep)
}

/// The dependent dofs of one RBE2 or RBE3, in order, with their expressions.
fn rigid_element_rows(
    model: &Model,
    dofs: &DofMap,
    spec: &ConstraintSpec,
    fixed: &[bool],
    r: &RigidElement,
) -> Result<Vec<(usize, Expr, Owner)>, FeError> {
    let err = |message: String| constraint_error(model, message);
    let mut out = Vec::new();
    match r {
        RigidElement::Rbe2 {
            id,
            independent,
            dependent,
            dofs: mask,
        } => {
            check_node(model, *independent, "RBE2")?;
            let i = *independent;
            for &d in dependent {
                check_node(model, d, "RBE2")?;
                if d == i {
                    return Err(err(format!(
                        "RBE2 {id}: node {} is both independent and dependent",
                        model.nodes[d].id
                    )));
                }
                let h = rbe2_map(model, dofs, i, d);
                for c in mask.dofs() {
                    let Some(dd) = dofs.dof(d, c) else { continue };
                    let e: Expr = (0..6)
                        .filter_map(|q| dofs.dof(i, q).map(|di| (di, h[c][q])))
                        .filter(|t| t.1 != 0.0)
                        .collect();
                    out.push((dd, e, Owner::Rigid(*id)));
                }
            }
        }
        RigidElement::Rbe3 {
            id,
            reference,
            ref_dofs,
            independent,
        } => {
            check_node(model, *reference, "RBE3")?;
            for &(nd, _, _) in independent {
                check_node(model, nd, "RBE3")?;
            }
            let rows = rbe3_rows(model, dofs, *reference, *ref_dofs, independent)
                .map_err(|m| err(format!("RBE3 {id}: {m}")))?;
            let rows: Vec<(usize, Expr)> = rows
                .into_iter()
                .filter_map(|(c, e)| dofs.dof(*reference, c).map(|dd| (dd, e)))
                .collect();
            let rows = if spec.independent_rbe3_reference.contains(reference) {
                let usable = |d: usize| !fixed[d];
                rbe3_solved_for_weighted(&rows, usable).map_err(|m| {
                    err(format!(
                        "RBE3 {id}: reference node {} cannot stay independent: {m}",
                        model.nodes[*reference].id
                    ))
                })?
            } else {
                rows
            };
            out.extend(rows.into_iter().map(|(dd, e)| (dd, e, Owner::Rigid(*id))));
        }
    }
    Ok(out)
}

/// The retained dofs (neither held nor dependent) and every dof's row of T over them, by
/// substitution of the dependent dofs' expressions.
fn substitution_rows(
    model: &Model,
    dofs: &DofMap,
    dep: &HashMap<usize, (Expr, Owner)>,
    fixed: &[bool],
) -> Result<(Vec<Expr>, Vec<usize>), FeError> {
    let n = dofs.n_dofs;
    let mut red = vec![usize::MAX; n];
    let mut retained = Vec::new();
    for d in 0..n {
        if !fixed[d] && !dep.contains_key(&d) {
            red[d] = retained.len();
            retained.push(d);
        }
    }
    let mut rows: Vec<Option<Expr>> = vec![None; n];
    let mut state = vec![0u8; n];
    for d in 0..n {
        resolve(d, dep, fixed, &red, &mut rows, &mut state).map_err(|(d, id)| {
            let (node, c) = dofs.node_of(d).unwrap_or((0, 0));
            constraint_error(
                model,
                format!(
                    "{id}: dependency cycle through dof {} of node {}",
                    c + 1,
                    model.nodes[node].id
                ),
            )
        })?;
    }
    let rows = rows.into_iter().map(Option::unwrap_or_default).collect();
    Ok((rows, retained))
}

/// The automatic SPCs: retained dofs with neither stiffness nor mass on K_r's and M_r's
/// diagonal are dropped from T (their physical dofs in `auto_spc`).
fn without_empty_dofs(
    rows: Vec<Expr>,
    mut retained: Vec<usize>,
    (mut t, mut k_r, mut m_r): (
        SparseColMat<usize, f64>,
        SparseColMat<usize, f64>,
        SparseColMat<usize, f64>,
    ),
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
) -> Reduced {
    let diag = |a: &SparseColMat<usize, f64>, j: usize| {
        let a = a.as_ref();
        a.row_idx_of_col(j)
            .zip(a.val_of_col(j))
            .find(|(i, _)| *i == j)
            .map_or(0.0, |(_, v)| *v)
    };
    let drop: Vec<bool> = (0..retained.len())
        .map(|j| diag(&k_r, j) == 0.0 && diag(&m_r, j) == 0.0)
        .collect();
    let mut auto = Vec::new();
    if drop.iter().any(|&b| b) {
        let mut new_idx = vec![usize::MAX; retained.len()];
        let mut kept = Vec::new();
        for (j, &d) in retained.iter().enumerate() {
            if drop[j] {
                auto.push(d);
            } else {
                new_idx[j] = kept.len();
                kept.push(d);
            }
        }
        let rows2: Vec<Expr> = rows
            .iter()
            .map(|r| {
                r.iter()
                    .filter(|(j, _)| !drop[*j])
                    .map(|&(j, v)| (new_idx[j], v))
                    .collect()
            })
            .collect();
        retained = kept;
        (t, k_r, m_r) = triple(&rows2, retained.len(), k, m);
    }
    Reduced {
        t,
        k: k_r,
        m: m_r,
        retained,
        auto_spc: auto,
    }
}

/// Resolve the T row of dof d over retained dofs; Err((dof, element id)) on a cycle.
fn resolve(
    d: usize,
    dep: &HashMap<usize, (Expr, Owner)>,
    fixed: &[bool],
    red: &[usize],
    rows: &mut [Option<Expr>],
    state: &mut [u8],
) -> Result<(), (usize, Owner)> {
    if state[d] == 2 {
        return Ok(());
    }
    let Some((expr, id)) = dep.get(&d) else {
        state[d] = 2;
        rows[d] = Some(if fixed[d] {
            Vec::new()
        } else {
            vec![(red[d], 1.0)]
        });
        return Ok(());
    };
    if state[d] == 1 {
        return Err((d, *id));
    }
    state[d] = 1;
    let mut acc: HashMap<usize, f64> = HashMap::new();
    for &(s, c) in expr {
        resolve(s, dep, fixed, red, rows, state)?;
        for &(j, v) in rows[s].as_deref().unwrap_or(&[]) {
            *acc.entry(j).or_insert(0.0) += c * v;
        }
    }
    let mut e: Expr = acc.into_iter().filter(|t| t.1 != 0.0).collect();
    e.sort_unstable_by_key(|t| t.0);
    rows[d] = Some(e);
    state[d] = 2;
    Ok(())
}

/// 6×6 map from the independent node's local dofs to the dependent node's local dofs of a rigid
/// link: H = R_d · [I, −r̃; 0, I] · R_iᵀ (r = x_d − x_i).
fn rbe2_map(model: &Model, dofs: &DofMap, i: usize, d: usize) -> [[f64; 6]; 6] {
    let r = sub(model.nodes[d].x, model.nodes[i].x);
    let mut g = [[0.0; 6]; 6];
    for k in 0..6 {
        g[k][k] = 1.0;
    }
    // −r̃ θ = θ × r: rows of −r̃
    let neg_rt = [[0.0, r[2], -r[1]], [-r[2], 0.0, r[0]], [r[1], -r[0], 0.0]];
    for a in 0..3 {
        for b in 0..3 {
            g[a][3 + b] = neg_rt[a][b];
        }
    }
    let rot6 = |f: Option<[[f64; 3]; 3]>| -> [[f64; 6]; 6] {
        let f = f.unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let mut o = [[0.0; 6]; 6];
        for blk in [0, 3] {
            for a in 0..3 {
                for b in 0..3 {
                    o[blk + a][blk + b] = f[a][b];
                }
            }
        }
        o
    };
    let (rd, ri) = (rot6(dofs.frames[d]), rot6(dofs.frames[i]));
    let mut out = [[0.0; 6]; 6];
    for a in 0..6 {
        for b in 0..6 {
            // Σ_p Σ_q rd[a][p] g[p][q] ri[b][q]   (R_iᵀ)
            out[a][b] = (0..6)
                .map(|p| rd[a][p] * (0..6).map(|q| g[p][q] * ri[b][q]).sum::<f64>())
                .sum();
        }
    }
    out
}

/// RBE3 rows: for each referenced component c of the reference node, its expression over the
/// independent nodes' physical dofs (module formula).
fn rbe3_rows(
    model: &Model,
    dofs: &DofMap,
    reference: usize,
    ref_dofs: DofMask,
    independent: &[(NodeIndex, f64, DofMask)],
) -> Result<Vec<(usize, Expr)>, String> {
    let xr = model.nodes[reference].x;
    let eye = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    // One observation row per independent dof: g · q ≈ u_dof, weight w.
    let mut obs: Vec<([f64; 6], f64, usize)> = Vec::new();
    for &(node, w, mask) in independent {
        // negative weights are allowed: CalculiX's area weights of a quadratic face's corners
        if !w.is_finite() {
            return Err(format!(
                "weight {w} of node {} is not a number",
                model.nodes[node].id
            ));
        }
        for c in mask.dofs() {
            let Some(d) = dofs.dof(node, c) else { continue };
            obs.push((super::rigid_body::rigid_row(model, dofs, node, c, xr), w, d));
        }
    }
    let want_rot = ref_dofs.dofs().any(|c| c >= 3);
    let solve = |nq: usize| -> Option<Mat<f64>> {
        // S = Σ w g gᵀ (nq × nq), Jacobi-scaled, inverted through a symmetric eigendecomposition.
        let s = Mat::from_fn(nq, nq, |a, b| {
            obs.iter().map(|(g, w, _)| w * g[a] * g[b]).sum::<f64>()
        });
        let sc: Vec<f64> = (0..nq)
            .map(|a| {
                if s[(a, a)] > 0.0 {
                    1.0 / s[(a, a)].sqrt()
                } else {
                    0.0
                }
            })
            .collect();
        if sc.contains(&0.0) {
            return None;
        }
        let ss = Mat::from_fn(nq, nq, |a, b| sc[a] * s[(a, b)] * sc[b]);
        let eig = ss.self_adjoint_eigen(faer::Side::Lower).ok()?;
        let lam: Vec<f64> = (0..nq).map(|k| eig.S()[k]).collect();
        let lmax = lam.iter().fold(0.0f64, |a, &b| a.max(b));
        if lam.iter().any(|&l| l <= 1e-10 * lmax) {
            return None;
        }
        let u = eig.U();
        Some(Mat::from_fn(nq, nq, |a, b| {
            sc[a] * sc[b] * (0..nq).map(|k| u[(a, k)] * u[(b, k)] / lam[k]).sum::<f64>()
        }))
    };
    let (sinv, nq) = match solve(6) {
        Some(s) => (s, 6),
        None if !want_rot => (solve(3).ok_or("independent nodes do not determine the reference translation (zero weights?)")?, 3),
        None => return Err("independent nodes do not determine the reference rotation (one node or collinear nodes)".into()),
    };
    let fr = dofs.frames[reference].unwrap_or(eye);
    let mut out = Vec::new();
    for c in ref_dofs.dofs() {
        let blk = if c < 3 { 0 } else { 3 };
        if blk + 3 > nq {
            continue;
        }
        // local component c = fr[c mod 3] · q[blk..blk+3]
        let mut coef: HashMap<usize, f64> = HashMap::new();
        for (g, w, d) in &obs {
            let mut v = 0.0;
            for a in 0..3 {
                let row = blk + a;
                v += fr[c % 3][a] * (0..nq).map(|b| sinv[(row, b)] * g[b]).sum::<f64>();
            }
            *coef.entry(*d).or_insert(0.0) += w * v;
        }
        let mut e: Expr = coef.into_iter().filter(|t| t.1 != 0.0).collect();
        e.sort_unstable_by_key(|t| t.0);
        out.push((c, e));
    }
    Ok(out)
}

/// The RBE3 relation q_c = Σ_s A_cs u_s (one row per reference dof q_c) solved for dofs u_m of
/// the weighted nodes instead: u_m = A_m⁻¹ (q − A_o u_o). The m columns are picked by
/// column-pivoted modified Gram–Schmidt on A among the `usable` dofs.
fn rbe3_solved_for_weighted(
    rows: &[(usize, Expr)],
    usable: impl Fn(usize) -> bool,
) -> Result<Vec<(usize, Expr)>, String> {
    use faer::linalg::solvers::Solve;
    let r = rows.len();
    let mut cols: Vec<usize> = rows
        .iter()
        .flat_map(|(_, e)| e.iter().map(|t| t.0))
        .collect();
    cols.sort_unstable();
    cols.dedup();
    let col_of: HashMap<usize, usize> = cols.iter().enumerate().map(|(k, &d)| (d, k)).collect();
    let mut a = Mat::<f64>::zeros(r, cols.len());
    for (c, (_, e)) in rows.iter().enumerate() {
        for &(d, v) in e {
            a[(c, col_of[&d])] += v;
        }
    }
    // Column-pivoted modified Gram–Schmidt: residual columns, pick the largest each step.
    let mut res = a.clone();
    let norm = |m: &Mat<f64>, j: usize| (0..r).map(|i| m[(i, j)].powi(2)).sum::<f64>().sqrt();
    let first = (0..cols.len()).map(|j| norm(&a, j)).fold(0.0f64, f64::max);
    let mut chosen: Vec<usize> = Vec::with_capacity(r);
    for _ in 0..r {
        let best = (0..cols.len())
            .filter(|&j| usable(cols[j]) && !chosen.contains(&j))
            .map(|j| (j, norm(&res, j)))
            .max_by(|x, y| x.1.total_cmp(&y.1));
        let Some((j, nj)) = best.filter(|b| b.1 > 1e-8 * first) else {
            return Err(format!(
                "its weighted nodes determine only {} of its {r} dofs (one node, collinear nodes or weights of zero)",
                chosen.len()
            ));
        };
        let qv: Vec<f64> = (0..r).map(|i| res[(i, j)] / nj).collect();
        for k in 0..cols.len() {
            let dot: f64 = (0..r).map(|i| qv[i] * res[(i, k)]).sum();
            for (i, q) in qv.iter().enumerate() {
                res[(i, k)] -= dot * q;
            }
        }
        chosen.push(j);
    }
    // X = A_m⁻¹ [I | A], then u_m = X[:, q] q − X[:, o] u_o.
    let am = Mat::from_fn(r, r, |i, k| a[(i, chosen[k])]);
    let rhs = Mat::from_fn(r, r + cols.len(), |i, k| {
        if k < r {
            f64::from(u8::from(i == k))
        } else {
            a[(i, k - r)]
        }
    });
    let x = am.as_ref().partial_piv_lu().solve(&rhs);
    Ok(chosen
        .iter()
        .enumerate()
        .map(|(k, &m)| {
            let mut e: Expr = rows
                .iter()
                .enumerate()
                .map(|(c, (q, _))| (*q, x[(k, c)]))
                .chain(
                    (0..cols.len())
                        .filter(|o| !chosen.contains(o))
                        .map(|o| (cols[o], -x[(k, r + o)])),
                )
                .filter(|t| t.1 != 0.0)
                .collect();
            e.sort_unstable_by_key(|t| t.0);
            (cols[m], e)
        })
        .collect())
}

/// T from its rows and the products Tᵀ K T, Tᵀ M T (Gustavson, column by column in parallel).
fn triple(
    rows: &[Expr],
    nr: usize,
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
) -> (
    SparseColMat<usize, f64>,
    SparseColMat<usize, f64>,
    SparseColMat<usize, f64>,
) {
    let n = rows.len();
    // Columns of T.
    let mut cnt = vec![0usize; nr + 1];
    for r in rows {
        for &(j, _) in r {
            cnt[j + 1] += 1;
        }
    }
    for j in 0..nr {
        cnt[j + 1] += cnt[j];
    }
    let mut fill = cnt.clone();
    let mut ti = vec![0usize; cnt[nr]];
    let mut tv = vec![0.0; cnt[nr]];
    for (i, r) in rows.iter().enumerate() {
        for &(j, v) in r {
            ti[fill[j]] = i;
            tv[fill[j]] = v;
            fill[j] += 1;
        }
    }
    let t = SparseColMat::new(
        SymbolicSparseColMat::new_checked(n, nr, cnt.clone(), None, ti.clone()),
        tv.clone(),
    );
    // Two passes so that only the result is allocated: count each column's entries, then fill
    // disjoint column slices in parallel. Marks hold rj + 1 (0 = untouched) so the per-thread
    // work arrays start zeroed (calloc, pages touched lazily).
    let product = |a: &SparseColMat<usize, f64>| -> SparseColMat<usize, f64> {
        let a = a.as_ref();
        // Calls f(row, first time seen in this column, contribution t_i,ri a_ij t_j,rj).
        let visit = |rj: usize, mark: &mut [usize], f: &mut dyn FnMut(usize, bool, f64)| {
            for p in cnt[rj]..cnt[rj + 1] {
                let (j, tj) = (ti[p], tv[p]);
                for (i, aij) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
                    for &(ri, tij) in &rows[i] {
                        let fresh = mark[ri] != rj + 1;
                        mark[ri] = rj + 1;
                        f(ri, fresh, tij * aij * tj);
                    }
                }
            }
        };
        const MIN_LEN: usize = 1 << 14;
        let counts: Vec<usize> = (0..nr)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map_init(
                || vec![0usize; nr],
                |mark, rj| {
                    let mut c = 0usize;
                    visit(rj, mark, &mut |_, fresh, _| c += usize::from(fresh));
                    c
                },
            )
            .collect();
        let mut cp = Vec::with_capacity(nr + 1);
        cp.push(0usize);
        for c in &counts {
            cp.push(cp[cp.len() - 1] + c);
        }
        let total = cp[nr];
        let mut ri = vec![0usize; total];
        let mut vv = vec![0.0f64; total];
        let mut slices = Vec::with_capacity(nr);
        let (mut rrest, mut vrest): (&mut [usize], &mut [f64]) = (&mut ri, &mut vv);
        for c in counts {
            let (rh, rt) = rrest.split_at_mut(c);
            let (vh, vt) = vrest.split_at_mut(c);
            slices.push((rh, vh));
            rrest = rt;
            vrest = vt;
        }
        slices
            .into_par_iter()
            .enumerate()
            .with_min_len(MIN_LEN)
            .for_each_init(
                || (vec![0usize; nr], vec![0.0f64; nr]),
                |(mark, acc), (rj, (rs, vs))| {
                    let mut t = 0usize;
                    visit(rj, mark, &mut |r, fresh, v| {
                        if fresh {
                            rs[t] = r;
                            t += 1;
                            acc[r] = v;
                        } else {
                            acc[r] += v;
                        }
                    });
                    rs.sort_unstable();
                    for (slot, &r) in vs.iter_mut().zip(rs.iter()) {
                        *slot = acc[r];
                    }
                },
            );
        SparseColMat::new(SymbolicSparseColMat::new_checked(nr, nr, cp, None, ri), vv)
    };
    (t, product(k), product(m))
}
