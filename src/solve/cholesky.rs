//! Sparse LLᵀ of a symmetric positive definite matrix on faer's supernodal Cholesky with a METIS
//! ordering; typed errors (the dof of a non-positive pivot), fill/flop estimate, multi-RHS solves.
//!
//! Two guards for the stability matrix (docs/stability.md): the memory of the numeric factor is
//! estimated from the symbolic analysis and checked against the available memory *before* any
//! numeric work ([`memory_limit`]), and the smallest pivot relative to its diagonal entry is kept
//! ([`SparseLlt::min_pivot`]) so that callers can tell a singular matrix whose rounding left a
//! tiny positive pivot from a merely ill-conditioned one.

use super::{ordering, sparse_ops, supernodal, SolveError};
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

/// The stored values of L: f64, or f32 for a mixed-precision factor (supernodal only).
#[derive(Debug)]
enum Values {
    F64(Vec<f64>),
    F32(Vec<f32>),
}

/// Relative refinement correction below which corrections that stop shrinking are f64 rounding
/// (the f64 direct solve's own error on these matrices is 1e-13 … 1e-11), not a failure.
pub const REFINE_FLOOR: f64 = 1e-9;

/// The f64-accuracy target of a refined solve: the error an f64 direct solve leaves.
pub const REFINE_F64: f64 = 1e-14;

/// Most refinement steps of one solve: with the contraction the stop rule demands (≤ 1/2 per
/// step) the f32 start reaches f64 rounding well within this.
const MAX_REFINE: usize = 12;

/// A numeric LLᵀ factorization that owns its symbolic part and values.
#[derive(Debug)]
pub struct SparseLlt {
    symbolic: SymbolicCholesky<usize>,
    values: Values,
    /// Fill and cost of the factorization.
    pub stats: FactorStats,
    par: Par,
    min_pivot: (f64, usize),
    /// The two-thread split of the elimination tree, found at the first parallel solve.
    schedule: std::sync::OnceLock<Option<supernodal::Schedule>>,
}

/// A symbolic analysis (ordering and structure of L) and its statistics, as [`analyze`] gives
/// them.
pub type Analysis = (SymbolicCholesky<usize>, FactorStats);

/// A pivot with L_jj² ≤ SINGULAR_PIVOT · A_jj is taken as a zero pivot: the matrix is singular
/// and rounding left a tiny positive value (rounding alone leaves ~1e-16·growth of A_jj).
/// Measured on K_ii of the stability rows: a stiff insert gives 1.3e-12 at contrast 1e10 and
/// 1.1e-14 at 1e12 (which the build refuses, docs/stability.md row 7); the singular K_ii of rows
/// 1 stopped at a non-positive pivot.
pub const SINGULAR_PIVOT: f64 = 1e-14;

/// Environment variable overriding the memory available to a factorization (bytes, or with a
/// `K`, `M`, `G` suffix for KiB, MiB, GiB).
pub const MEMORY_ENV: &str = "FLEXBODY_MAX_MEMORY";

/// The limit `flexbody build --max-memory` set for this process (bytes), named by its flag in
/// the errors it causes.
static FLAG_LIMIT: std::sync::OnceLock<u64> = std::sync::OnceLock::new();

/// Sets the memory limit from the `--max-memory` flag's text (its errors name the flag, not
/// [`MEMORY_ENV`]); the first call wins.
pub fn set_memory_limit_flag(text: &str) -> Result<(), SolveError> {
    let bytes = parse_bytes(text).ok_or_else(|| {
        SolveError::Invalid(format!(
            "--max-memory {text}: expected bytes, optionally with a K, M or G suffix"
        ))
    })?;
    let _ = FLAG_LIMIT.set(bytes); // a second call keeps the first limit
    Ok(())
}

/// Bytes a numeric factorization may use and where that figure came from: `--max-memory`
/// ([`set_memory_limit_flag`]), else [`MEMORY_ENV`] when set, else `MemAvailable` of
/// `/proc/meminfo`; `None` when none is known (no check).
pub fn memory_limit() -> Result<Option<(u64, &'static str)>, SolveError> {
    if let Some(&bytes) = FLAG_LIMIT.get() {
        return Ok(Some((bytes, "--max-memory")));
    }
    if let Ok(v) = std::env::var(MEMORY_ENV) {
        return parse_bytes(&v)
            .map(|b| Some((b, MEMORY_ENV)))
            .ok_or_else(|| {
                SolveError::Invalid(format!(
                    "{MEMORY_ENV}={v}: expected bytes, optionally with a K, M or G suffix"
                ))
            });
    }
    let Ok(text) = std::fs::read_to_string("/proc/meminfo") else {
        return Ok(None);
    };
    Ok(text
        .lines()
        .find_map(|l| l.strip_prefix("MemAvailable:"))
        .and_then(|rest| rest.trim().strip_suffix("kB"))
        .and_then(|kb| kb.trim().parse::<u64>().ok())
        .map(|kb| (kb * 1024, "MemAvailable in /proc/meminfo")))
}

/// "123", "64K", "1.5G" → bytes (binary multiples).
pub fn parse_bytes(s: &str) -> Option<u64> {
    let s = s.trim();
    let (num, mult) = match s.char_indices().last()? {
        (i, 'k' | 'K') => (&s[..i], 1u64 << 10),
        (i, 'm' | 'M') => (&s[..i], 1 << 20),
        (i, 'g' | 'G') => (&s[..i], 1 << 30),
        _ => (s, 1),
    };
    let v: f64 = num.trim().parse().ok()?;
    (v.is_finite() && v >= 0.0).then_some((v * mult as f64) as u64)
}

/// Bytes as "1.50 GiB" / "12.0 MiB" / "16.0 KiB" / "900 B".
pub fn format_bytes(b: u64) -> String {
    let f = b as f64;
    if f >= (1u64 << 30) as f64 {
        format!("{:.2} GiB", f / (1u64 << 30) as f64)
    } else if f >= (1u64 << 20) as f64 {
        format!("{:.1} MiB", f / (1u64 << 20) as f64)
    } else if f >= 1024.0 {
        format!("{:.1} KiB", f / 1024.0)
    } else {
        format!("{b} B")
    }
}

/// Bytes of a numeric factorization: the values of L plus faer's scratch, from the symbolic
/// analysis alone.
pub fn factor_memory(symbolic: &SymbolicCholesky<usize>, par: Par) -> usize {
    let req = symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default());
    symbolic.len_val() * std::mem::size_of::<f64>() + req.size_bytes()
}

/// Bytes of a mixed-precision factorization: the f32 values of L, faer's f32 scratch and the f32
/// copy of the matrix.
pub fn factor_memory_mixed(
    symbolic: &SymbolicCholesky<usize>,
    a: SparseColMatRef<'_, usize, f64>,
    par: Par,
) -> usize {
    let req = symbolic.factorize_numeric_llt_scratch::<f32>(par, Default::default());
    symbolic.len_val() * std::mem::size_of::<f32>()
        + req.size_bytes()
        + a.val().len() * std::mem::size_of::<f32>()
}

/// Errors with [`SolveError::OutOfMemory`] when `needed` bytes exceed the [`memory_limit`].
pub fn check_memory(needed: usize, n: usize) -> Result<(), SolveError> {
    if let Some((limit, from)) = memory_limit()? {
        if needed as u64 > limit {
            return Err(SolveError::OutOfMemory {
                n,
                needed: needed as u64,
                available: limit,
                from,
            });
        }
    }
    Ok(())
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

/// Symbolic analysis of `a` in its own order (no fill-reducing permutation: the caller ordered
/// it, e.g. AMLS's substructure tree), always supernodal, so that L's rows are `a`'s and the
/// half solves [`SparseLlt::l_solve_in_place`] and [`SparseLlt::lt_solve_in_place`] apply.
pub fn analyze_in_order(a: SparseColMatRef<'_, usize, f64>) -> Result<Analysis, SolveError> {
    if a.ncols() != a.nrows() {
        return Err(SolveError::Dimension(format!(
            "matrix to factor is {}x{}",
            a.nrows(),
            a.ncols()
        )));
    }
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold:
            faer::sparse::linalg::SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    let symbolic = factorize_symbolic_cholesky(
        a.symbolic(),
        Side::Lower,
        SymmetricOrdering::Identity,
        params,
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

/// min_j L_jj² / A_jj over the permuted order, with the original dof of j (A_jj ≤ 0 counts as 0).
fn min_pivot(
    symbolic: &SymbolicCholesky<usize>,
    value: impl Fn(usize) -> f64,
    a: SparseColMatRef<'_, usize, f64>,
) -> (f64, usize) {
    let n = symbolic.nrows();
    let fwd = |j: usize| symbolic.perm().map_or(j, |p| p.arrays().0[j]);
    let diag_a = |i: usize| {
        a.row_idx_of_col(i)
            .zip(a.val_of_col(i))
            .find(|(r, _)| *r == i)
            .map_or(0.0, |(_, v)| *v)
    };
    let mut best = (f64::INFINITY, 0usize);
    let mut visit = |j: usize, l: f64| {
        let i = fwd(j);
        let d = diag_a(i);
        let r = if d > 0.0 { l * l / d } else { 0.0 };
        if r < best.0 {
            best = (r, i);
        }
    };
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let (cp, ri) = (s.col_ptr(), s.row_idx());
            for j in 0..n {
                if let Some(p) = (cp[j]..cp[j + 1]).find(|&p| ri[p] == j) {
                    visit(j, value(p));
                }
            }
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let (beg, end, rp, vp) = (
                s.supernode_begin(),
                s.supernode_end(),
                s.col_ptr_for_row_idx(),
                s.col_ptr_for_val(),
            );
            for k in 0..s.n_supernodes() {
                let w = end[k] - beg[k];
                let rows = w + rp[k + 1] - rp[k];
                for t in 0..w {
                    visit(beg[k] + t, value(vp[k] + t * rows + t));
                }
            }
        }
    }
    best
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
        check_memory(factor_memory(&symbolic, par), a.nrows())?;
        let mut values = vec![0.0f64; symbolic.len_val()];
        super::progress::report(super::progress::Event::FactorStart {
            n: a.nrows(),
            flops: stats.flops,
            single: false,
        });
        let factored = factor_numeric(&symbolic, &mut values, a, par, stats.flops);
        super::progress::report(super::progress::Event::FactorEnd);
        factored?;
        let min_pivot = min_pivot(&symbolic, |p| values[p], a);
        Ok(Self {
            symbolic,
            values: Values::F64(values),
            stats,
            par,
            min_pivot,
            schedule: Default::default(),
        })
    }

    /// Mixed precision: the numeric factorization of `a` rounded to f32 (half the memory and
    /// bandwidth of an f64 L); the solves run in f32 arithmetic on it (0.55× the f64 solve's
    /// time at 6 columns), and [`SparseLlt::solve_refined_in_place`] recovers the f64 solution
    /// by iterative refinement against `a`. Only for a supernodal analysis (a simplicial one is
    /// factored in f64). A non-positive f32 pivot is [`SolveError::NonPositivePivot`], as in
    /// f64: the caller decides whether to factor in f64 instead.
    pub fn factor_mixed_with(
        symbolic: SymbolicCholesky<usize>,
        stats: FactorStats,
        a: SparseColMatRef<'_, usize, f64>,
        par: Par,
    ) -> Result<Self, SolveError> {
        if !matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)) {
            return Self::factor_with(symbolic, stats, a, par);
        }
        if a.val().iter().any(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite("matrix to factor"));
        }
        check_memory(factor_memory_mixed(&symbolic, a, par), a.nrows())?;
        let mut values = vec![0.0f32; symbolic.len_val()];
        {
            let (pattern, val) = a.parts();
            let rounded: Vec<f32> = val.iter().map(|&v| v as f32).collect();
            if rounded.iter().any(|v| !v.is_finite()) {
                return Err(SolveError::Invalid(
                    "matrix entries overflow single precision: factor in f64".into(),
                ));
            }
            let a32 = SparseColMatRef::<usize, f32>::new(pattern, &rounded);
            super::progress::report(super::progress::Event::FactorStart {
                n: a.nrows(),
                flops: stats.flops,
                single: true,
            });
            let factored = factor_numeric(&symbolic, &mut values, a32, par, stats.flops);
            super::progress::report(super::progress::Event::FactorEnd);
            factored?;
        }
        let min_pivot = min_pivot(&symbolic, |p| f64::from(values[p]), a);
        let factor_bytes = values.len() * std::mem::size_of::<f32>();
        Ok(Self {
            symbolic,
            values: Values::F32(values),
            stats: FactorStats {
                factor_bytes,
                ..stats
            },
            par,
            min_pivot,
            schedule: Default::default(),
        })
    }

    /// X ← L⁻¹ X (the forward half of a solve), rows in the factor's own order: for an f64
    /// supernodal factor without permutation ([`analyze_in_order`]); others are
    /// [`SolveError::Factor`].
    pub fn l_solve_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), SolveError> {
        self.half_solve(rhs, false)
    }

    /// X ← L⁻ᵀ X (the backward half of a solve), as [`SparseLlt::l_solve_in_place`].
    pub fn lt_solve_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), SolveError> {
        self.half_solve(rhs, true)
    }

    /// faer's column-wise kernels: AMLS solves 128 columns at a time, where they beat our
    /// row-wise ones (16 lanes a pass; measured 41 s against 27 s for the 69k-dof AMLS's solves).
    fn half_solve(&self, rhs: MatMut<'_, f64>, transpose: bool) -> Result<(), SolveError> {
        use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
        let (SymbolicCholeskyRaw::Supernodal(s), Values::F64(v), None) =
            (self.symbolic.raw(), &self.values, self.symbolic.perm())
        else {
            return Err(SolveError::Factor(
                "half solves need an f64 supernodal factor in its own order".into(),
            ));
        };
        let llt = SupernodalLltRef::new(s, v);
        let req = s.solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq);
        let mut buf = MemBuffer::new(req);
        let stack = MemStack::new(&mut buf);
        if transpose {
            llt.l_transpose_solve_with_conj(Conj::No, rhs, Par::Seq, stack);
        } else {
            llt.l_solve_with_conj(Conj::No, rhs, Par::Seq, stack);
        }
        Ok(())
    }

    /// Whether L is stored in f32 ([`SparseLlt::factor_mixed_with`]).
    pub fn is_mixed(&self) -> bool {
        matches!(self.values, Values::F32(_))
    }

    /// The smallest L_jj² / A_jj over all pivots and the (original) dof where it occurs: ≈ 1 for a
    /// well-conditioned matrix, ≤ [`SINGULAR_PIVOT`] for a singular one.
    pub fn min_pivot(&self) -> (f64, usize) {
        self.min_pivot
    }

    /// The symbolic analysis and its statistics, L's values dropped: to factor the same matrix
    /// again (in f64 after an f32 factor proved too inaccurate) without ordering it again
    /// (METIS and the symbolic factorization: about 20 s at 519k dofs).
    pub fn into_analysis(self) -> Analysis {
        let Self {
            symbolic,
            values,
            mut stats,
            ..
        } = self;
        drop(values);
        // as `analyze` gives them: an f64 factor's size (an f32 factor halved it)
        stats.factor_bytes = 8 * symbolic.len_val();
        (symbolic, stats)
    }

    /// The symbolic analysis (ordering and structure of L).
    #[cfg(test)]
    pub(crate) fn symbolic(&self) -> &SymbolicCholesky<usize> {
        &self.symbolic
    }

    /// The stored values of an f32 factor.
    #[cfg(test)]
    pub(crate) fn values_f32(&self) -> &[f32] {
        match &self.values {
            Values::F32(v) => v,
            Values::F64(_) => panic!("f64 factor"),
        }
    }

    /// The stored values of L (f64 factors).
    #[cfg(test)]
    pub(crate) fn values(&self) -> &[f64] {
        match &self.values {
            Values::F64(v) => v,
            Values::F32(_) => panic!("f32 factor"),
        }
    }

    /// Dimension.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Solves A X = B in place for all columns of `rhs` at once. With a parallel factorization
    /// (`par` of degree t > 1): on two threads that each take their own subtrees of the
    /// supernodal elimination tree ([`supernodal::tree`]), so that L is read once between them;
    /// where the tree does not split (or without AVX2) the columns are split into t groups
    /// instead, each solved with sequential kernels and reading all of L (memory bandwidth
    /// bounds that: 6 columns at 178k dofs, 7.1 s → 6.2 s for the eigen phase's solves).
    pub fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) {
        let threads = self.par.degree();
        let nc = rhs.ncols();
        if threads > 1 && supernodal::simd_available() {
            if let Some(split) = self.split() {
                self.solve_with(rhs, self.par, Some(split));
                return;
            }
        }
        if threads > 1 && nc >= 2 {
            let per = nc.div_ceil(threads);
            std::thread::scope(|sc| {
                let mut rest = rhs.as_mut();
                while rest.ncols() > 0 {
                    let w = per.min(rest.ncols());
                    let (a, b) = rest.split_at_col_mut(w);
                    sc.spawn(move || self.solve_with(a, Par::Seq, None));
                    rest = b;
                }
            });
            return;
        }
        self.solve_with(rhs, self.par, None);
    }

    /// The two-thread split of a supernodal factor's tree (computed once).
    fn split(&self) -> Option<&supernodal::Schedule> {
        self.schedule
            .get_or_init(|| match (self.symbolic.raw(), &self.values) {
                (SymbolicCholeskyRaw::Supernodal(s), Values::F64(v)) => {
                    supernodal::tree::schedule(&supernodal::Supernodal::new(s, v))
                }
                (SymbolicCholeskyRaw::Supernodal(s), Values::F32(v)) => {
                    supernodal::tree::schedule(&supernodal::Supernodal::new(s, v))
                }
                _ => None,
            })
            .as_ref()
    }

    fn solve_with(&self, rhs: MatMut<'_, f64>, par: Par, split: Option<&supernodal::Schedule>) {
        if let SymbolicCholeskyRaw::Supernodal(s) = self.symbolic.raw() {
            let perm = self.symbolic.perm().map(|p| p.arrays().0);
            match &self.values {
                Values::F64(v) => {
                    let f = supernodal::Supernodal::new(s, v);
                    for_chunks(rhs, |x| supernodal::solve_in_place(&f, perm, x, split))
                }
                Values::F32(v) => {
                    let f = supernodal::Supernodal::new(s, v);
                    for_chunks(rhs, |x| {
                        supernodal::solve_in_place_single(&f, perm, x, split)
                    })
                }
            }
            return;
        }
        self.solve_with_faer(rhs, par);
    }

    /// faer's own multi-RHS solve (column by column of B): the reference the row-wise supernodal
    /// kernel is tested and benchmarked against.
    pub fn solve_in_place_faer(&self, rhs: MatMut<'_, f64>) {
        self.solve_with_faer(rhs, self.par);
    }

    fn solve_with_faer(&self, rhs: MatMut<'_, f64>, par: Par) {
        let Values::F64(values) = &self.values else {
            // faer's solve is for f64 factors; an f32 one (always supernodal) takes the row
            // kernels
            return self.solve_with(rhs, par, None);
        };
        let llt = LltRef::new(&self.symbolic, values);
        let req = self
            .symbolic
            .solve_in_place_scratch::<f64>(rhs.ncols(), par);
        let mut buf = MemBuffer::new(req);
        llt.solve_in_place_with_conj(Conj::No, rhs, par, MemStack::new(&mut buf));
    }

    /// Solves A X = B for a factor of A itself: one solve for an f64 factor; for a mixed (f32)
    /// factor, iterative refinement X ← X + (L̃L̃ᵀ)⁻¹(B − A X) with the residual in f64
    /// (Wilkinson's refinement; the error shrinks by ρ ≈ ‖I − (L̃L̃ᵀ)⁻¹A‖ per step), until the
    /// error left, estimated from the last two corrections (δₖ²/δₖ₋₁, relative to each column's
    /// size), is at most `target`, or the corrections stop shrinking at f64 rounding
    /// (≤ [`REFINE_FLOOR`]). Returns the refinement steps taken (solves beyond the first). A
    /// correction that shrinks by less than half per step above that floor means the f32 factor
    /// is too far from A (ill conditioning): [`SolveError::Refinement`], and the caller factors in
    /// f64.
    pub fn solve_refined_in_place(
        &self,
        a: SparseColMatRef<'_, usize, f64>,
        mut rhs: MatMut<'_, f64>,
        target: f64,
    ) -> Result<usize, SolveError> {
        if !self.is_mixed() {
            self.solve_in_place(rhs);
            return Ok(0);
        }
        let b = rhs.to_owned();
        self.solve_in_place(rhs.as_mut());
        let mut last = f64::INFINITY;
        for step in 1..=MAX_REFINE {
            let mut r = &b - sparse_ops::spmm(a, rhs.as_ref());
            self.solve_in_place(r.as_mut());
            let mut worst = 0.0f64;
            for c in 0..r.ncols() {
                let dx = r.col(c).norm_max();
                let x = rhs.as_ref().col(c).norm_max();
                worst = worst.max(if x > 0.0 { dx / x } else { dx });
            }
            for c in 0..r.ncols() {
                for (x, d) in rhs.as_mut().col_mut(c).iter_mut().zip(r.col(c).iter()) {
                    *x += d;
                }
            }
            if worst.is_nan() {
                return Err(SolveError::Refinement {
                    step,
                    correction: worst,
                });
            }
            // the error left after this step ≈ δₖ·(δₖ/δₖ₋₁) once two corrections are known
            let shrink = worst / last;
            if worst <= target || (last.is_finite() && worst * shrink <= target) {
                return Ok(step);
            }
            if shrink > 0.5 {
                if worst <= REFINE_FLOOR {
                    return Ok(step);
                }
                return Err(SolveError::Refinement {
                    step,
                    correction: worst,
                });
            }
            last = worst;
        }
        Err(SolveError::Refinement {
            step: MAX_REFINE,
            correction: last,
        })
    }

    /// Returns A⁻¹ B.
    pub fn solve(&self, rhs: MatRef<'_, f64>) -> Mat<f64> {
        let mut x = rhs.to_owned();
        self.solve_in_place(x.as_mut());
        x
    }
}

/// The numeric LLᵀ of `a` (lower triangle read) into `values`, in the precision of `T` (f64, or
/// f32 for a mixed factor); a non-positive pivot is [`SolveError::NonPositivePivot`] with its
/// original dof.
fn factor_numeric<T: faer::traits::ComplexField>(
    symbolic: &SymbolicCholesky<usize>,
    values: &mut [T],
    a: SparseColMatRef<'_, usize, T>,
    par: Par,
    flops: f64,
) -> Result<(), SolveError> {
    let req = symbolic.factorize_numeric_llt_scratch::<T>(par, Default::default());
    let mut buf = MemBuffer::new(req);
    let res = with_share_reported(flops, || {
        symbolic.factorize_numeric_llt(
            values,
            a,
            Side::Lower,
            LltRegularization::default(),
            par,
            MemStack::new(&mut buf),
            Default::default(),
        )
    });
    if let Err(faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index }) = res {
        // faer 0.24 reports the simplicial pivot 1-based and the supernodal one 0-based, both in
        // the permuted order
        let pos = match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(_) => index.saturating_sub(1),
            SymbolicCholeskyRaw::Supernodal(_) => index,
        };
        let dof = symbolic
            .perm()
            .map_or(pos, |p| p.arrays().0[pos.min(p.arrays().0.len() - 1)]);
        return Err(SolveError::NonPositivePivot { dof });
    }
    Ok(())
}

/// Runs the numeric factorization `factor` of `flops` floating-point operations (the analysis's
/// count) while, with a progress reporter installed, a watcher reports the share done four times
/// a second ([`Event::FactorProgress`](super::progress::Event::FactorProgress)): the flops the
/// dense kernels (faer's x86-64 gemm, which counts them) did since the start over `flops`,
/// capped at 0.99 — the supernodes' updates and dense factors, where a large factorization
/// spends its time, run through those kernels (issue 47: a log heard nothing for the 7.5 s of
/// a 128k-dof factorization).
fn with_share_reported<R>(flops: f64, factor: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if super::progress::active() && flops > 0.0 {
        use std::sync::atomic::{AtomicBool, Ordering};
        let counter = &private_gemm_x86::FLOPS;
        let start = counter.load(Ordering::Relaxed);
        let done = AtomicBool::new(false);
        return std::thread::scope(|scope| {
            let watcher = scope.spawn(|| {
                while !done.load(Ordering::Acquire) {
                    std::thread::park_timeout(std::time::Duration::from_millis(250));
                    if done.load(Ordering::Acquire) {
                        break;
                    }
                    let counted = counter.load(Ordering::Relaxed).saturating_sub(start);
                    super::progress::report(super::progress::Event::FactorProgress {
                        share: (counted as f64 / flops).min(0.99),
                    });
                }
            });
            let out = factor();
            done.store(true, Ordering::Release);
            watcher.thread().unpark();
            out
        });
    }
    factor()
}

/// `solve` (the row kernels) on blocks of at most [`supernodal::MAX_LANES`] columns of `rhs`.
fn for_chunks(mut rhs: MatMut<'_, f64>, solve: impl Fn(MatMut<'_, f64>)) {
    let mut rest = rhs.as_mut();
    while rest.ncols() > 0 {
        let w = rest.ncols().min(supernodal::MAX_LANES);
        let (a, b) = rest.split_at_col_mut(w);
        solve(a);
        rest = b;
    }
}
