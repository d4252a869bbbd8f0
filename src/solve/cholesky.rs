//! Sparse LLᵀ of a symmetric positive definite matrix on faer's supernodal Cholesky with a METIS
//! ordering; typed errors (the dof of a non-positive pivot), fill/flop estimate, multi-RHS solves.

use super::{ordering, SolveError};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::SparseColMatRef;
use faer::{Conj, Mat, MatMut, MatRef, Par, Side};

/// Size of a factorization, from the symbolic analysis (before any numeric work).
#[derive(Clone, Debug, PartialEq)]
pub struct FactorStats {
    /// Matrix dimension.
    pub n: usize,
    /// Non-zeros of L (including the diagonal).
    pub nnz_l: usize,
    /// Floating-point operations of the numeric factorization, Σ_j c_j² with c_j = nnz(L[:, j]).
    pub flops: f64,
    /// Bytes of the numeric factor (the stored values of L, supernodal blocks included).
    pub factor_bytes: usize,
    /// Whether faer chose the supernodal variant.
    pub supernodal: bool,
}

/// A numeric LLᵀ factorization that owns its symbolic part and values.
#[derive(Debug)]
pub struct SparseLlt {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// Fill and cost of the factorization.
    pub stats: FactorStats,
    par: Par,
}

/// Symbolic analysis with a METIS nested-dissection ordering (`block` = dofs per node, if known).
pub fn analyze(
    a: SparseColMatRef<'_, usize, f64>,
    block: Option<usize>,
) -> Result<(SymbolicCholesky<usize>, FactorStats), SolveError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(SolveError::Dimension(format!(
            "matrix to factor is {}x{}",
            a.nrows(),
            a.ncols()
        )));
    }
    let fwd = ordering::nested_dissection(a.symbolic(), block)?;
    let inv = ordering::inverse(&fwd);
    let perm = PermRef::new_checked(&fwd, &inv, n);
    let symbolic = factorize_symbolic_cholesky(
        a.symbolic(),
        Side::Lower,
        SymmetricOrdering::Custom(perm),
        CholeskySymbolicParams::default(),
    )
    .map_err(|e| SolveError::Factor(format!("symbolic Cholesky: {e:?}")))?;
    let stats = stats_of(&symbolic);
    Ok((symbolic, stats))
}

fn stats_of(symbolic: &SymbolicCholesky<usize>) -> FactorStats {
    let n = symbolic.nrows();
    let mut nnz_l = 0usize;
    let mut flops = 0.0f64;
    let supernodal = match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let cp = s.col_ptr();
            for j in 0..n {
                let c = cp[j + 1] - cp[j];
                nnz_l += c;
                flops += (c * c) as f64;
            }
            false
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let (beg, end, rp) = (
                s.supernode_begin(),
                s.supernode_end(),
                s.col_ptr_for_row_idx(),
            );
            for k in 0..s.n_supernodes() {
                let w = end[k] - beg[k];
                let r = rp[k + 1] - rp[k];
                for t in 0..w {
                    let c = w - t + r;
                    nnz_l += c;
                    flops += (c * c) as f64;
                }
            }
            true
        }
    };
    FactorStats {
        n,
        nnz_l,
        flops,
        factor_bytes: symbolic.len_val() * 8,
        supernodal,
    }
}

impl SparseLlt {
    /// Orders, analyzes and factors the symmetric matrix `a` (both triangles stored, the lower one
    /// is read). A non-positive pivot is reported with its original dof index.
    pub fn factor(
        a: SparseColMatRef<'_, usize, f64>,
        block: Option<usize>,
        par: Par,
    ) -> Result<Self, SolveError> {
        let (symbolic, stats) = analyze(a, block)?;
        Self::factor_with(symbolic, stats, a, par)
    }

    /// Numeric factorization reusing a symbolic analysis of the same pattern.
    pub fn factor_with(
        symbolic: SymbolicCholesky<usize>,
        stats: FactorStats,
        a: SparseColMatRef<'_, usize, f64>,
        par: Par,
    ) -> Result<Self, SolveError> {
        if a.val().iter().any(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite("matrix to factor"));
        }
        let mut values = vec![0.0f64; symbolic.len_val()];
        let req = symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default());
        let mut buf = MemBuffer::new(req);
        let res = symbolic.factorize_numeric_llt(
            &mut values,
            a,
            Side::Lower,
            LltRegularization::default(),
            par,
            MemStack::new(&mut buf),
            Default::default(),
        );
        if let Err(faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index }) = res
        {
            // faer 0.24 reports the simplicial pivot 1-based and the supernodal one 0-based,
            // both in the permuted order
            let pos = match symbolic.raw() {
                SymbolicCholeskyRaw::Simplicial(_) => index.saturating_sub(1),
                SymbolicCholeskyRaw::Supernodal(_) => index,
            };
            let dof = symbolic
                .perm()
                .map_or(pos, |p| p.arrays().0[pos.min(p.arrays().0.len() - 1)]);
            return Err(SolveError::NonPositivePivot { dof });
        }
        Ok(Self {
            symbolic,
            values,
            stats,
            par,
        })
    }

    /// Dimension.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Solves A X = B in place for all columns of `rhs` at once.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let llt = LltRef::new(&self.symbolic, &self.values);
        let req = self
            .symbolic
            .solve_in_place_scratch::<f64>(rhs.ncols(), self.par);
        let mut buf = MemBuffer::new(req);
        llt.solve_in_place_with_conj(Conj::No, rhs, self.par, MemStack::new(&mut buf));
    }

    /// Returns A⁻¹ B.
    pub fn solve(&self, rhs: MatRef<'_, f64>) -> Mat<f64> {
        let mut x = rhs.to_owned();
        self.solve_in_place(x.as_mut());
        x
    }
}
