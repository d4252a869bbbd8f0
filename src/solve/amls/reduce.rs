//! The substructure bases of AMLS, bottom-up: a leaf's eigenvectors of (A_ll, M_ll) below the
//! cutoff; at a separator S of two subtrees c = 1, 2 with bases Φ_c, the Craig–Bampton basis
//! [Φ_1, Φ_2, Ψ] (Ψ = [−A_11⁻¹A_1S; −A_22⁻¹A_2S; I], the separator's static extension), whose
//! projected pencil is reduced again to its eigenvectors below the cutoff.
//!
//! A = K − σM (σ < 0, positive definite). With Φ_cᵀA_ccΦ_c = diag(μ_c), Φ_cᵀM_ccΦ_c = I, the
//! subtree T = [c_1, c_2, S] factored once in that order, A_TT = LLᵀ (so L's leading blocks are
//! the children's factors), and Ψ̂ = L⁻ᵀE_S = Ψ L_SS⁻ᵀ (the static extension in another basis of
//! its span: A_TTΨ̂ = L E_S is zero outside S), the projected pencil on [Φ̂_1, Φ̂_2, Ψ̂] is
//! (Bennighof & Lehoucq 2004, eq. 3.3–3.5, in the transformed coordinates of their §4)
//!
//! ```text
//! K_r = diag(μ_1, μ_2, I_s)
//! M_r = [ I  0  Φ_1ᵀ(MΨ̂)_1 ; 0  I  Φ_2ᵀ(MΨ̂)_2 ; ·  ·  E_SᵀL⁻¹(MΨ̂) ]
//! ```
//!
//! computed in column chunks of the separator: per column one backward half solve (L⁻ᵀ) and one
//! forward half solve (L⁻¹), where the former construction took two full solves with each
//! child's own factor; the separator's condensed stiffness needs no solve (it is L_SSL_SSᵀ, the
//! identity in these coordinates). A level holds the subtree's factor, the children's bases
//! (n_c × k_c), the dense r × r pencil (r = k_1 + k_2 + s) and two n_T × chunk blocks.

use super::super::{
    cholesky::{self, SparseLlt},
    dense, sparse_ops, SolveError, SparseColMat,
};
use super::profile::Profile;
use super::tree::Substructure;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, MatRef, Par};

/// Separator columns per chunk of the static extension (at most).
const CHUNK: usize = 128;

/// Leaves up to this many dofs are solved densely; larger ones (METIS found no split) by the
/// sparse eigensolver in band mode.
pub const DENSE_LEAF: usize = 4000;

/// A subtree's basis: rows in the order of `dofs`, A-orthogonal and M-orthonormal columns.
pub struct Basis {
    /// Global dofs of the rows.
    pub dofs: Vec<usize>,
    /// n_T × k.
    pub phi: Mat<f64>,
    /// μ = λ − σ per column, ascending.
    pub mu: Vec<f64>,
}

/// What the reduction needs everywhere.
pub struct Context<'a> {
    /// A = K − σM.
    pub a: &'a SparseColMat<usize, f64>,
    /// M.
    pub m: &'a SparseColMat<usize, f64>,
    /// Keep eigenvectors with μ ≤ this at every level.
    pub mu_cut: f64,
    /// Dofs per node for the child factorizations' ordering.
    pub block: Option<usize>,
    /// Parallelism of the factorizations and dense kernels.
    pub par: Par,
    /// Counts and seconds per phase.
    pub profile: &'a Profile,
    /// Leaves solved ahead (by the count mode's cutoff estimate), by their first dof.
    pub leaf_modes: std::cell::RefCell<std::collections::HashMap<usize, LeafModes>>,
}

/// Eigenpairs of the dense positive definite pencil (A, M) with μ ≤ `mu_cut`, at least
/// `at_least` of them (the lowest ones) when that many are finite: ascending μ, vectors with
/// YᵀMY = I. By A = LLᵀ and eig(L⁻¹ M L⁻ᵀ) = θ, μ = 1/θ (massless directions: θ = 0).
pub fn pencil_below(
    a: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    mu_cut: f64,
    at_least: usize,
) -> Result<(Vec<f64>, Mat<f64>), SolveError> {
    let l = dense::cholesky(a).ok_or(SolveError::NotPositiveDefinite { shift: 0.0 })?;
    let mut s = dense::sym(m);
    solve_lower_triangular_in_place(l.as_ref(), s.as_mut(), Par::Seq);
    let mut st = s.transpose().to_owned();
    solve_lower_triangular_in_place(l.as_ref(), st.as_mut(), Par::Seq);
    let (mu, mut y) = lowest_of_standard(st.as_ref(), mu_cut, at_least)?;
    solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
    Ok((mu, y))
}

/// [`pencil_below`] for a diagonal A = diag(`a`) (a separator's projected pencil): L⁻¹ M L⁻ᵀ is
/// M scaled by 1/√(a_i a_j), no triangular solves.
pub fn pencil_below_diagonal(
    a: &[f64],
    m: MatRef<'_, f64>,
    mu_cut: f64,
    at_least: usize,
) -> Result<(Vec<f64>, Mat<f64>), SolveError> {
    if a.iter().any(|&d| d.is_nan() || d <= 0.0) {
        return Err(SolveError::NotPositiveDefinite { shift: 0.0 });
    }
    let inv: Vec<f64> = a.iter().map(|&d| 1.0 / d.sqrt()).collect();
    let st = Mat::from_fn(a.len(), a.len(), |i, j| {
        0.5 * (m[(i, j)] + m[(j, i)]) * inv[i] * inv[j]
    });
    let (mu, mut y) = lowest_of_standard(st.as_ref(), mu_cut, at_least)?;
    for c in 0..y.ncols() {
        for (r, &f) in inv.iter().enumerate() {
            y[(r, c)] *= f;
        }
    }
    Ok((mu, y))
}

/// The eigenvectors U θ^(-1/2) of the symmetric S = L⁻¹ M L⁻ᵀ with μ = 1/θ ≤ `mu_cut` (at least
/// `at_least`), ascending μ; θ ≤ 1e-13·θ_max are infinite eigenvalues.
fn lowest_of_standard(
    st: MatRef<'_, f64>,
    mu_cut: f64,
    at_least: usize,
) -> Result<(Vec<f64>, Mat<f64>), SolveError> {
    let n = st.nrows();
    let (theta, u) = dense::eigh(st)?;
    let theta_max = theta.iter().fold(0.0f64, |x, &t| x.max(t.abs()));
    // descending θ = ascending μ
    let order: Vec<usize> = (0..n)
        .rev()
        .filter(|&i| theta[i] > 1e-13 * theta_max)
        .enumerate()
        .take_while(|&(rank, i)| rank < at_least || 1.0 / theta[i] <= mu_cut)
        .map(|(_, i)| i)
        .collect();
    let mut y = Mat::<f64>::zeros(n, order.len());
    for (c, &i) in order.iter().enumerate() {
        let scale = 1.0 / theta[i].sqrt();
        for r in 0..n {
            y[(r, c)] = u[(r, i)] * scale;
        }
    }
    Ok((order.iter().map(|&i| 1.0 / theta[i]).collect(), y))
}

/// A leaf's eigenpairs computed once: every finite eigenvalue μ (ascending) and the vectors of
/// the lowest ones, as many as the leaf's basis can need (see [`leaf_eigenpairs`]).
pub struct LeafModes {
    /// All finite eigenvalues μ of (A_ll, M_ll), ascending.
    pub mu: Vec<f64>,
    /// The vectors of the lowest `phi.ncols()` of them (YᵀM_llY = I).
    pub phi: Mat<f64>,
}

/// A leaf's dense pencil (A_ll, M_ll) solved once, keeping the vectors with μ ≤ `keep_below`
/// (or the lowest `at_least`): the count mode's cutoff estimate reads every eigenvalue (Cauchy
/// interlacing: the c-th lowest over all leaves bounds λ_c from above), and the leaf's basis
/// later takes its vectors from here instead of solving the pencil again.
pub fn leaf_eigenpairs(
    ctx: &Context<'_>,
    dofs: &[usize],
    keep_below: f64,
    at_least: usize,
) -> Result<LeafModes, SolveError> {
    let (a, m) = blocks(ctx, dofs)?;
    let p = ctx.profile;
    Profile::count(&p.leaf_pencils, 1);
    let (mu, phi) = Profile::time(&p.leaf_seconds, || {
        pencil_below(a.as_ref(), m.as_ref(), f64::INFINITY, 0)
    })?;
    let kept = mu
        .iter()
        .enumerate()
        .take_while(|&(i, &x)| i < at_least || x <= keep_below)
        .count();
    let phi = phi.as_ref().subcols(0, kept).to_owned();
    Ok(LeafModes { mu, phi })
}

fn blocks(ctx: &Context<'_>, dofs: &[usize]) -> Result<(Mat<f64>, Mat<f64>), SolveError> {
    let a = sparse_ops::submatrix(ctx.a.as_ref(), dofs, dofs)?;
    let m = sparse_ops::submatrix(ctx.m.as_ref(), dofs, dofs)?;
    Ok((
        sparse_ops::to_dense(a.as_ref()),
        sparse_ops::to_dense(m.as_ref()),
    ))
}

/// The basis of `node`'s subtree; `at_least` modes are kept at this level even above the cutoff.
/// With `keep_factor`, a split's factorization of its subtree's A (rows in the basis's order)
/// comes back too.
pub fn basis(
    ctx: &Context<'_>,
    node: &Substructure,
    at_least: usize,
    keep_factor: bool,
) -> Result<(Basis, Option<SparseLlt>), SolveError> {
    match node {
        Substructure::Leaf(dofs) => Ok((leaf_basis(ctx, dofs, at_least)?, None)),
        Substructure::Split {
            separator,
            children,
        } => {
            let (b1, _) = basis(ctx, &children[0], 0, false)?;
            let (b2, _) = basis(ctx, &children[1], 0, false)?;
            split_basis(ctx, [b1, b2], separator, at_least, keep_factor)
        }
    }
}

fn leaf_basis(ctx: &Context<'_>, dofs: &[usize], at_least: usize) -> Result<Basis, SolveError> {
    let solved = dofs
        .first()
        .and_then(|d| ctx.leaf_modes.borrow_mut().remove(d));
    if let Some(LeafModes { mu, phi }) = solved {
        let keep = (mu.iter().enumerate())
            .take_while(|&(i, &x)| i < at_least || x <= ctx.mu_cut)
            .count();
        if keep <= phi.ncols() {
            return Ok(Basis {
                dofs: dofs.to_vec(),
                phi: phi.as_ref().subcols(0, keep).to_owned(),
                mu: mu[..keep].to_vec(),
            });
        }
    }
    if dofs.len() <= DENSE_LEAF {
        let (a, m) = blocks(ctx, dofs)?;
        let p = ctx.profile;
        Profile::count(&p.leaf_pencils, 1);
        let (mu, phi) = Profile::time(&p.leaf_seconds, || {
            pencil_below(a.as_ref(), m.as_ref(), ctx.mu_cut, at_least)
        })?;
        return Ok(Basis {
            dofs: dofs.to_vec(),
            phi,
            mu,
        });
    }
    // a leaf METIS could not split: the sparse band solver on (A_ll, M_ll), λ' = μ
    let a = sparse_ops::submatrix(ctx.a.as_ref(), dofs, dofs)?;
    let m = sparse_ops::submatrix(ctx.m.as_ref(), dofs, dofs)?;
    let spec = super::super::EigenSpec {
        count: at_least.clamp(1, dofs.len() / 8 + 1),
        shift: Some(0.0),
        upper: Some(ctx.mu_cut),
        dofs_per_node: ctx.block,
        par: ctx.par,
        ..Default::default()
    };
    let s = super::super::lowest_modes(&a, &m, &spec)?;
    let keep = s
        .eigenvalues
        .iter()
        .enumerate()
        .take_while(|&(i, &mu)| i < at_least || mu <= ctx.mu_cut)
        .count();
    Ok(Basis {
        dofs: dofs.to_vec(),
        phi: s.vectors.as_ref().subcols(0, keep).to_owned(),
        mu: s.eigenvalues[..keep].to_vec(),
    })
}

/// The columns of the static-extension chunk: 128 (wide products in the half solves), fewer on
/// large subtrees so that the two n_T × chunk blocks stay near 256 MB each.
fn chunk_width(n_t: usize) -> usize {
    (CHUNK_BYTES / (8 * n_t.max(1))).clamp(32, CHUNK)
}

/// Bytes of one n_T × chunk block at most (above 32 columns).
const CHUNK_BYTES: usize = 256 << 20;

/// The projected pencil at a separator (module doc) from one factorization A_TT = LLᵀ of the
/// subtree in the order [child 1, child 2, separator]: with Ψ̂ = L⁻ᵀE_S (the separator's static
/// extension Ψ times L_SS⁻ᵀ, the same span), Ψ̂ᵀAΨ̂ = I, Φ̂_cᵀAΨ̂ = 0, Φ̂_cᵀMΨ̂ = Φ_cᵀ(MΨ̂)_c and
/// Ψ̂ᵀMΨ̂ = E_SᵀL⁻¹(MΨ̂): one backward and one forward half solve per separator column. Then its
/// eigenvectors below the cutoff expanded to the subtree's dofs (children's rows, then the
/// separator's). Returns the factor too when `keep_factor` (the root's: the refinement solves
/// with it, rows in the basis's order).
pub fn split_basis(
    ctx: &Context<'_>,
    bases: [Basis; 2],
    sep: &[usize],
    at_least: usize,
    keep_factor: bool,
) -> Result<(Basis, Option<SparseLlt>), SolveError> {
    let [b1, b2] = bases;
    let (n1, n2, s) = (b1.dofs.len(), b2.dofs.len(), sep.len());
    let (k1, k2) = (b1.mu.len(), b2.mu.len());
    let mut dofs = Vec::with_capacity(n1 + n2 + s);
    dofs.extend_from_slice(&b1.dofs);
    dofs.extend_from_slice(&b2.dofs);
    dofs.extend_from_slice(sep);
    let n_t = dofs.len();
    let p = ctx.profile;
    let llt = Profile::time(&p.factor_seconds, || -> Result<SparseLlt, SolveError> {
        let a_tt = sparse_ops::submatrix(ctx.a.as_ref(), &dofs, &dofs)?;
        let (symbolic, stats) = cholesky::analyze_in_order(a_tt.as_ref())?;
        SparseLlt::factor_with(symbolic, stats, a_tt.as_ref(), ctx.par)
    })?;
    Profile::count(&p.factorizations, 1);
    Profile::add(&p.factor_flops, llt.stats.flops);
    let m_tt = sparse_ops::submatrix(ctx.m.as_ref(), &dofs, &dofs)?;
    let o = k1 + k2;
    let r = o + s;
    let mut mr = Mat::<f64>::zeros(r, r);
    for i in 0..o {
        mr[(i, i)] = 1.0;
    }
    let width = chunk_width(n_t);
    let mut start = 0;
    while start < s {
        let w = width.min(s - start);
        // X = L⁻ᵀ E_S[:, C]
        let mut x = Mat::<f64>::zeros(n_t, w);
        for j in 0..w {
            x[(n1 + n2 + start + j, j)] = 1.0;
        }
        half_solve_counted(p, &llt, x.as_mut(), true)?;
        let mut y = sparse_ops::spmm(m_tt.as_ref(), x.as_ref());
        drop(x);
        // Φ_cᵀ (M X)_c
        Profile::time(&p.basis_seconds, || {
            for (phi, row, off) in [(&b1.phi, 0, 0), (&b2.phi, n1, k1)] {
                let c = phi.transpose() * y.as_ref().subrows(row, phi.nrows());
                mr.as_mut()
                    .submatrix_mut(off, o + start, phi.ncols(), w)
                    .copy_from(&c);
            }
        });
        Profile::add(&p.basis_flops, 2.0 * ((n1 * k1 + n2 * k2) * w) as f64);
        // E_Sᵀ L⁻¹ (M X)
        half_solve_counted(p, &llt, y.as_mut(), false)?;
        mr.as_mut()
            .submatrix_mut(o, o + start, s, w)
            .copy_from(y.as_ref().subrows(n1 + n2, s));
        start += w;
    }
    // the lower triangle from the upper: couplings and the separator block (symmetrized)
    for j in o..r {
        for i in 0..o {
            mr[(j, i)] = mr[(i, j)];
        }
    }
    let mss = dense::sym(mr.as_ref().submatrix(o, o, s, s));
    mr.as_mut().submatrix_mut(o, o, s, s).copy_from(&mss);
    drop(mss);
    let kd: Vec<f64> = (b1.mu.iter().chain(&b2.mu).copied())
        .chain(std::iter::repeat_n(1.0, s))
        .collect();
    Profile::count(&p.split_pencils, 1);
    p.largest_pencil.set(p.largest_pencil.get().max(r));
    Profile::add(&p.pencil_cubes, (r as f64).powi(3));
    let (mu, yr) = Profile::time(&p.pencil_seconds, || {
        pencil_below_diagonal(&kd, mr.as_ref(), ctx.mu_cut, at_least)
    })?;
    drop(mr);
    // Φ_T = [Φ_1 Y_1; Φ_2 Y_2; 0] + L⁻ᵀ E_S Y_S
    let k = mu.len();
    let mut phi = Mat::<f64>::zeros(n_t, k);
    phi.as_mut()
        .subrows_mut(n1 + n2, s)
        .copy_from(yr.as_ref().subrows(o, s));
    half_solve_counted(p, &llt, phi.as_mut(), true)?;
    Profile::time(&p.basis_seconds, || {
        for (b, row, off) in [(&b1, 0, 0), (&b2, n1, k1)] {
            let part = &b.phi * yr.as_ref().subrows(off, b.mu.len());
            let sum = phi.as_ref().subrows(row, b.phi.nrows()) + &part;
            phi.as_mut().subrows_mut(row, b.phi.nrows()).copy_from(&sum);
        }
    });
    Profile::add(&p.basis_flops, 2.0 * ((n1 * k1 + n2 * k2) * k) as f64);
    let basis = Basis {
        dofs,
        phi,
        mu: mu.to_vec(),
    };
    Ok((basis, keep_factor.then_some(llt)))
}

/// X ← L⁻ᵀX (`transpose`) or L⁻¹X with the subtree's factor, counted (a half solve counts half
/// a column).
fn half_solve_counted(
    profile: &Profile,
    llt: &SparseLlt,
    x: faer::MatMut<'_, f64>,
    transpose: bool,
) -> Result<(), SolveError> {
    Profile::add(&profile.solved_columns, x.ncols() as f64 / 2.0);
    Profile::time(&profile.solve_seconds, || {
        if transpose {
            llt.lt_solve_in_place(x)
        } else {
            llt.l_solve_in_place(x)
        }
    })
}
