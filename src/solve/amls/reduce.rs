//! The substructure bases of AMLS, bottom-up: a leaf's eigenvectors of (A_ll, M_ll) below the
//! cutoff; at a separator S of two subtrees c = 1, 2 with bases Φ_c, the Craig–Bampton basis
//! [Φ_1, Φ_2, Ψ] (Ψ = [−A_11⁻¹A_1S; −A_22⁻¹A_2S; I], the separator's static extension), whose
//! projected pencil is reduced again to its eigenvectors below the cutoff.
//!
//! A = K − σM (σ < 0, positive definite). With Φ_cᵀA_ccΦ_c = diag(μ_c), Φ_cᵀM_ccΦ_c = I and
//! A_cc Ψ_c = −A_cS, the projected pencil is (Bennighof & Lehoucq 2004, eq. 3.3–3.5)
//!
//! ```text
//! K_r = diag(μ_1, μ_2, A_SS + Σ_c A_Sc Ψ_c)
//! M_r = [ I  0  Φ_1ᵀW_1 ; 0  I  Φ_2ᵀW_2 ; ·  ·  M_SS + Σ_c (M_Sc Ψ_c + Ψ_cᵀW_c) ],  W_c = M_cc Ψ_c + M_cS
//! ```
//!
//! computed in column chunks of the separator (Ψ_c is never held whole: Ψ_cᵀW = −A_Sc A_cc⁻¹W
//! costs a second solve instead), so a level holds the two children's sparse factors, their
//! bases (n_c × k_c), the dense s × s separator blocks and one n_T × chunk block.

use super::super::{cholesky::SparseLlt, dense, sparse_ops, SolveError, SparseColMat};
use super::tree::Substructure;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, MatRef, Par};

/// Separator columns per chunk of the static extension.
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
    let n = a.nrows();
    let l = dense::cholesky(a).ok_or(SolveError::NotPositiveDefinite { shift: 0.0 })?;
    let mut s = dense::sym(m);
    solve_lower_triangular_in_place(l.as_ref(), s.as_mut(), Par::Seq);
    let mut st = s.transpose().to_owned();
    solve_lower_triangular_in_place(l.as_ref(), st.as_mut(), Par::Seq);
    let (theta, u) = dense::eigh(st.as_ref())?;
    let theta_max = theta.iter().fold(0.0f64, |x, &t| x.max(t.abs()));
    // descending θ = ascending μ; θ ≤ 1e-13·θ_max are infinite eigenvalues
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
    solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
    Ok((order.iter().map(|&i| 1.0 / theta[i]).collect(), y))
}

/// Eigenvalues μ of a leaf's dense pencil (A_ll, M_ll), all finite ones, ascending: the count
/// mode's cutoff estimate (Cauchy interlacing: the c-th lowest over all leaves bounds λ_c from
/// above).
pub fn leaf_eigenvalues(ctx: &Context<'_>, dofs: &[usize]) -> Result<Vec<f64>, SolveError> {
    let (a, m) = blocks(ctx, dofs)?;
    let (mu, _) = pencil_below(a.as_ref(), m.as_ref(), f64::INFINITY, 0)?;
    Ok(mu)
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
pub fn basis(ctx: &Context<'_>, node: &Substructure, at_least: usize) -> Result<Basis, SolveError> {
    match node {
        Substructure::Leaf(dofs) => leaf_basis(ctx, dofs, at_least),
        Substructure::Split {
            separator,
            children,
        } => {
            let b1 = basis(ctx, &children[0], 0)?;
            let b2 = basis(ctx, &children[1], 0)?;
            split_basis(ctx, [b1, b2], separator, at_least)
        }
    }
}

fn leaf_basis(ctx: &Context<'_>, dofs: &[usize], at_least: usize) -> Result<Basis, SolveError> {
    if dofs.len() <= DENSE_LEAF {
        let (a, m) = blocks(ctx, dofs)?;
        let (mu, phi) = pencil_below(a.as_ref(), m.as_ref(), ctx.mu_cut, at_least)?;
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

/// One child's factor and its couplings to the separator.
struct Child {
    basis: Basis,
    llt: SparseLlt,
    a_cs: SparseColMat<usize, f64>,
    a_sc: SparseColMat<usize, f64>,
    m_cc: SparseColMat<usize, f64>,
    m_cs: SparseColMat<usize, f64>,
    m_sc: SparseColMat<usize, f64>,
}

fn child(ctx: &Context<'_>, basis: Basis, sep: &[usize]) -> Result<Child, SolveError> {
    let d = &basis.dofs;
    let a_cc = sparse_ops::submatrix(ctx.a.as_ref(), d, d)?;
    let llt = SparseLlt::factor(a_cc.as_ref(), ctx.block, ctx.par)?;
    drop(a_cc);
    Ok(Child {
        llt,
        a_cs: sparse_ops::submatrix(ctx.a.as_ref(), d, sep)?,
        a_sc: sparse_ops::submatrix(ctx.a.as_ref(), sep, d)?,
        m_cc: sparse_ops::submatrix(ctx.m.as_ref(), d, d)?,
        m_cs: sparse_ops::submatrix(ctx.m.as_ref(), d, sep)?,
        m_sc: sparse_ops::submatrix(ctx.m.as_ref(), sep, d)?,
        basis,
    })
}

/// Y = B X for a rectangular sparse B.
fn mul(b: &SparseColMat<usize, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let mut y = Mat::<f64>::zeros(b.nrows(), x.ncols());
    faer::sparse::linalg::matmul::sparse_dense_matmul(
        y.as_mut(),
        faer::Accum::Replace,
        b.as_ref(),
        x,
        1.0,
        Par::Seq,
    );
    y
}

/// The projected pencil at a separator (module doc), then its eigenvectors below the cutoff
/// expanded to the subtree's dofs (children's rows, then the separator's).
fn split_basis(
    ctx: &Context<'_>,
    bases: [Basis; 2],
    sep: &[usize],
    at_least: usize,
) -> Result<Basis, SolveError> {
    let [b1, b2] = bases;
    let children = [child(ctx, b1, sep)?, child(ctx, b2, sep)?];
    let s = sep.len();
    let a_ss = sparse_ops::to_dense(sparse_ops::submatrix(ctx.a.as_ref(), sep, sep)?.as_ref());
    let mut kr_ss = a_ss;
    let mut mr_ss = sparse_ops::to_dense(sparse_ops::submatrix(ctx.m.as_ref(), sep, sep)?.as_ref());
    let mut coupling: Vec<Mat<f64>> = children
        .iter()
        .map(|c| Mat::zeros(c.basis.mu.len(), s))
        .collect();
    let mut start = 0;
    while start < s {
        let w = CHUNK.min(s - start);
        for (c, cp) in children.iter().zip(coupling.iter_mut()) {
            // Ψ_C = −A_cc⁻¹ A_cS[:, C]
            let mut psi = sparse_ops::to_dense(
                sparse_ops::submatrix(
                    c.a_cs.as_ref(),
                    &(0..c.a_cs.nrows()).collect::<Vec<_>>(),
                    &(start..start + w).collect::<Vec<_>>(),
                )?
                .as_ref(),
            );
            c.llt.solve_in_place(psi.as_mut());
            psi *= faer::Scale(-1.0);
            // S[:, C] += A_Sc Ψ_C
            let t = mul(&c.a_sc, psi.as_ref());
            let sum = kr_ss.as_ref().subcols(start, w) + &t;
            kr_ss.as_mut().subcols_mut(start, w).copy_from(&sum);
            // W = M_cc Ψ_C + M_cS[:, C]
            let mut wmat = sparse_ops::spmm(c.m_cc.as_ref(), psi.as_ref());
            let m_cs_c = sparse_ops::to_dense(
                sparse_ops::submatrix(
                    c.m_cs.as_ref(),
                    &(0..c.m_cs.nrows()).collect::<Vec<_>>(),
                    &(start..start + w).collect::<Vec<_>>(),
                )?
                .as_ref(),
            );
            wmat += &m_cs_c;
            cp.as_mut()
                .subcols_mut(start, w)
                .copy_from(c.basis.phi.transpose() * &wmat);
            // M̃[:, C] += M_Sc Ψ_C + Ψ_cᵀ W, Ψ_cᵀ W = −A_Sc A_cc⁻¹ W
            let m_sc_psi = mul(&c.m_sc, psi.as_ref());
            drop(psi);
            c.llt.solve_in_place(wmat.as_mut());
            let psi_t_w = mul(&c.a_sc, wmat.as_ref());
            let upd = &m_sc_psi - &psi_t_w;
            let sum = mr_ss.as_ref().subcols(start, w) + &upd;
            mr_ss.as_mut().subcols_mut(start, w).copy_from(&sum);
        }
        start += w;
    }
    let (k1, k2) = (children[0].basis.mu.len(), children[1].basis.mu.len());
    let r = k1 + k2 + s;
    let mut kr = Mat::<f64>::zeros(r, r);
    let mut mr = Mat::<f64>::zeros(r, r);
    for (i, &mu) in children[0]
        .basis
        .mu
        .iter()
        .chain(&children[1].basis.mu)
        .enumerate()
    {
        kr[(i, i)] = mu;
        mr[(i, i)] = 1.0;
    }
    let o = k1 + k2;
    kr.as_mut()
        .submatrix_mut(o, o, s, s)
        .copy_from(dense::sym(kr_ss.as_ref()));
    mr.as_mut()
        .submatrix_mut(o, o, s, s)
        .copy_from(dense::sym(mr_ss.as_ref()));
    for (off, cp) in [(0, &coupling[0]), (k1, &coupling[1])] {
        mr.as_mut()
            .submatrix_mut(off, o, cp.nrows(), s)
            .copy_from(cp);
        mr.as_mut()
            .submatrix_mut(o, off, s, cp.nrows())
            .copy_from(cp.transpose());
    }
    drop((kr_ss, mr_ss, coupling));
    let (mu, y) = pencil_below(kr.as_ref(), mr.as_ref(), ctx.mu_cut, at_least)?;
    drop((kr, mr));
    expand(children, sep, &mu, y)
}

/// The subtree's basis from the reduced eigenvectors Y = [Y_1; Y_2; Y_S]: rows of child c are
/// Φ_c Y_c − A_cc⁻¹ (A_cS Y_S), the separator's rows Y_S.
fn expand(
    children: [Child; 2],
    sep: &[usize],
    mu: &[f64],
    y: Mat<f64>,
) -> Result<Basis, SolveError> {
    let k = mu.len();
    let s = sep.len();
    let n1 = children[0].basis.dofs.len();
    let n2 = children[1].basis.dofs.len();
    let (k1, k2) = (children[0].basis.mu.len(), children[1].basis.mu.len());
    let y_s = y.as_ref().subrows(k1 + k2, s);
    let mut phi = Mat::<f64>::zeros(n1 + n2 + s, k);
    let mut dofs = Vec::with_capacity(n1 + n2 + s);
    let mut row = 0;
    for (c, (off, kc)) in children.iter().zip([(0, k1), (k1, k2)]) {
        let mut ext = mul(&c.a_cs, y_s);
        c.llt.solve_in_place(ext.as_mut());
        let part = &c.basis.phi * y.as_ref().subrows(off, kc) - &ext;
        let nc = c.basis.dofs.len();
        phi.as_mut().subrows_mut(row, nc).copy_from(&part);
        dofs.extend_from_slice(&c.basis.dofs);
        row += nc;
    }
    phi.as_mut().subrows_mut(row, s).copy_from(y_s);
    dofs.extend_from_slice(sep);
    Ok(Basis {
        dofs,
        phi,
        mu: mu.to_vec(),
    })
}
