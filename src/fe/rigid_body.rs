//! Constraint rows of a rigid motion and of linear equations: the relations that
//! [`super::constraints::eliminate`] turns into u = T u_r besides RBE2/RBE3.
//!
//! * Rigid row: the value of dof c of node n (displacement frame A_n, rows the local axes) under
//!   the rigid motion q = [t; θ] about x₀: translation c: e·(t + θ × r) = [e; r × e]·q with
//!   e = A_n[c], r = x_n − x₀; rotation c: [0; A_n[c−3]]·q.
//! * Rigid body with chosen independent dofs (MSC QRG "RBAR", "RBE1"): the six independent
//!   rows G_I fix q = G_I⁻¹ u_I; a dependent dof follows, u_d = g_d G_I⁻¹ u_I. G_I must be
//!   non-singular (the independent components must determine the rigid motion).
//! * MPC (MSC QRG "MPC"): Σ cᵢ uᵢ = 0 with the first term dependent, u₁ = −Σᵢ₌₂ (cᵢ/c₁) uᵢ.

use faer::linalg::solvers::Solve;
use faer::Mat;

use super::dofs::DofMap;
use crate::model::{Model, Mpc, NodeIndex, RigidBody};

/// A linear expression over physical dofs: Σ (dof, coefficient) — a constraint row.
pub(super) type Expr = Vec<(usize, f64)>;

/// The rigid row of dof `c` of node `n` about `x0` (module formula).
pub(super) fn rigid_row(
    model: &Model,
    dofs: &DofMap,
    n: NodeIndex,
    c: usize,
    x0: [f64; 3],
) -> [f64; 6] {
    let eye = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let f = dofs.frames[n].unwrap_or(eye);
    let x = model.nodes[n].x;
    let r = [x[0] - x0[0], x[1] - x0[1], x[2] - x0[2]];
    let mut g = [0.0; 6];
    if c < 3 {
        let e = f[c];
        g[..3].copy_from_slice(&e);
        // e · (θ × r) = θ · (r × e)
        g[3] = r[1] * e[2] - r[2] * e[1];
        g[4] = r[2] * e[0] - r[0] * e[2];
        g[5] = r[0] * e[1] - r[1] * e[0];
    } else {
        g[3..].copy_from_slice(&f[c - 3]);
    }
    g
}

/// The dependent dofs of a rigid body with their expressions over its independent dofs
/// (module formula); an error names what is wrong (not six independent components, a singular
/// choice, a dof both independent and dependent).
pub(super) fn rigid_body_rows(
    model: &Model,
    dofs: &DofMap,
    body: &RigidBody,
) -> Result<Vec<(usize, Expr)>, String> {
    let list = |set: &[(NodeIndex, crate::model::DofMask)]| -> Vec<(NodeIndex, usize, usize)> {
        set.iter()
            .flat_map(|&(n, m)| m.dofs().map(move |c| (n, c)))
            .filter_map(|(n, c)| dofs.dof(n, c).map(|d| (n, c, d)))
            .collect()
    };
    let (ind, dep) = (list(&body.independent), list(&body.dependent));
    if ind.len() != 6 {
        return Err(format!(
            "{} independent components; a rigid body needs six that fix its rigid motion",
            ind.len()
        ));
    }
    if let Some(&(n, c, _)) = dep.iter().find(|x| ind.iter().any(|y| y.2 == x.2)) {
        return Err(format!(
            "component {} of node {} is both independent and dependent",
            c + 1,
            model.nodes[n].id
        ));
    }
    // About the centroid of the independent nodes, rotations scaled by the body's size so that
    // the singularity test compares lengths with lengths.
    let k = ind.len() as f64;
    let x0: [f64; 3] = std::array::from_fn(|i| {
        ind.iter()
            .map(|&(n, _, _)| model.nodes[n].x[i])
            .sum::<f64>()
            / k
    });
    let len = body
        .nodes()
        .map(|n| {
            let x = model.nodes[n].x;
            (0..3).map(|i| (x[i] - x0[i]).powi(2)).sum::<f64>().sqrt()
        })
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let scaled = |n, c| {
        let mut g = rigid_row(model, dofs, n, c, x0);
        g[3..].iter_mut().for_each(|v| *v *= 1.0 / len);
        g
    };
    let gi = Mat::from_fn(6, 6, |i, j| scaled(ind[i].0, ind[i].1)[j]);
    let gram = gi.transpose() * &gi;
    let eig = gram
        .self_adjoint_eigen(faer::Side::Lower)
        .map_err(|_| "the independent components' rigid rows do not decompose".to_owned())?;
    let lam: Vec<f64> = (0..6).map(|i| eig.S()[i]).collect();
    let top = lam.iter().fold(0.0f64, |a, &b| a.max(b));
    if lam.iter().any(|&l| l <= 1e-12 * top) {
        return Err(
            "its independent components do not fix a rigid motion (e.g. CNA/CNB name the same \
             rotation twice, or translations along the bar only)"
                .into(),
        );
    }
    // X = G_I⁻ᵀ g_dᵀ for every dependent row at once: coefficients of u_I.
    let gd = Mat::from_fn(6, dep.len(), |j, i| scaled(dep[i].0, dep[i].1)[j]);
    let x = gi.transpose().partial_piv_lu().solve(&gd);
    Ok(dep
        .iter()
        .enumerate()
        .map(|(i, &(_, _, d))| {
            let e: Expr = (0..6)
                .map(|j| (ind[j].2, x[(j, i)]))
                .filter(|t| t.1 != 0.0)
                .collect();
            (d, e)
        })
        .collect())
}

/// The dependent dof of an MPC and its expression (module formula).
pub(super) fn mpc_row(model: &Model, dofs: &DofMap, mpc: &Mpc) -> Result<(usize, Expr), String> {
    let dof = |i: usize| -> Result<usize, String> {
        let (d, _) = mpc.terms[i];
        dofs.dof(d.node, usize::from(d.component)).ok_or_else(|| {
            format!(
                "node {} has no component {}",
                model.nodes[d.node].id,
                d.component + 1
            )
        })
    };
    let Some(&(_, c0)) = mpc.terms.first() else {
        return Err("no terms".into());
    };
    if c0 == 0.0 || !c0.is_finite() {
        return Err(format!(
            "the first coefficient (of the dependent dof) is {c0}"
        ));
    }
    let d0 = dof(0)?;
    let mut e: Expr = Vec::new();
    for (i, &(_, ci)) in mpc.terms.iter().enumerate().skip(1) {
        let di = dof(i)?;
        if di == d0 {
            return Err("the dependent dof appears again among the other terms".into());
        }
        match e.iter_mut().find(|t| t.0 == di) {
            Some(t) => t.1 -= ci / c0,
            None => e.push((di, -ci / c0)),
        }
    }
    e.retain(|t| t.1 != 0.0);
    Ok((d0, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{DofMask, Node};

    fn two_grids() -> Model {
        let node = |id, x| Node {
            id,
            x,
            displacement_frame: None,
        };
        Model {
            nodes: vec![node(1, [0.0; 3]), node(2, [2.0, 0.0, 0.0])],
            ..Default::default()
        }
    }

    /// A rigid bar with A's translations and B's rotations independent: B's translations
    /// follow u_B = u_A + θ × (x_B − x_A), A's rotations equal B's.
    #[test]
    fn split_independent_dofs_give_the_rigid_link() {
        let mut m = two_grids();
        let body = RigidBody {
            id: 9,
            independent: vec![(0, DofMask::TRANSLATIONS), (1, DofMask(0b111000))],
            dependent: vec![(0, DofMask(0b111000)), (1, DofMask::TRANSLATIONS)],
        };
        m.rigid_bodies.push(body.clone());
        let dofs = DofMap::from_model(&m).unwrap();
        let rows = rigid_body_rows(&m, &dofs, &body).unwrap();
        let row = |d: usize| -> Vec<(usize, f64)> {
            let mut e: Expr = rows.iter().find(|r| r.0 == d).unwrap().1.clone();
            e.iter_mut().for_each(|t| t.1 = (t.1 * 1e12).round() / 1e12);
            e.retain(|t| t.1 != 0.0);
            e.sort_by_key(|t| t.0);
            e
        };
        // u_By = u_Ay + θz·2, u_Bz = u_Az − θy·2 (θ of B, dofs 9–11), θ_A = θ_B
        assert_eq!(row(7), vec![(1, 1.0), (11, 2.0)]);
        assert_eq!(row(8), vec![(2, 1.0), (10, -2.0)]);
        assert_eq!(row(3), vec![(9, 1.0)]);
    }

    /// Translations at both ends of a bar leave its rotation about the bar free: refused.
    #[test]
    fn independent_dofs_that_miss_a_rigid_motion_are_an_error() {
        let mut m = two_grids();
        let body = RigidBody {
            id: 9,
            independent: vec![(0, DofMask::TRANSLATIONS), (1, DofMask::TRANSLATIONS)],
            dependent: vec![(1, DofMask(0b111000))],
        };
        m.rigid_bodies.push(body.clone());
        let dofs = DofMap::from_model(&m).unwrap();
        let e = rigid_body_rows(&m, &dofs, &body).unwrap_err();
        assert!(e.contains("do not fix a rigid motion"), "{e}");
    }
}
