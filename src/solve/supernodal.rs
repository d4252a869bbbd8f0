//! Multi-right-hand-side triangular solves L Lᵀ X = B with a supernodal Cholesky factor, on
//! right-hand sides held row by row.
//!
//! faer's supernodal solve works on B column by column: per supernode a triangular solve and a
//! matrix product into a temporary, then a scatter of that temporary one column at a time; with
//! the 4–16 columns of an eigensolver block its products are too thin to run near the machine's
//! speed (20k-dof tet10 factor, 8 columns: 4.7 GFlop/s). Here the columns are copied once into
//! 32-byte aligned rows of `W` lanes in the factor's permuted order, so that every stored entry of
//! L updates (or reads) one contiguous, SIMD-wide row of X, and every product streams its columns
//! of L from memory in storage order against a register-resident tile:
//!
//! * forward, L₂₁X₁ (rows of L below a supernode's triangle): KT columns of L walked down side by
//!   side, KT rows of X₁ held in registers, each target row of X loaded, updated, stored once;
//! * backward, L₂₁ᵀX₂: MR columns of L walked down side by side into MR × W accumulators.
//!
//! Rows below a supernode are reached through its row pattern directly: no gathered copies. The
//! kernels use AVX2/FMA when the CPU has them (checked at run time) and portable Rust otherwise;
//! they are generic over the arithmetic of X's rows (f64 in 4-lane vectors, or f32 in 8-lane
//! vectors for an f32 factor). Simplicial factors (small problems) are left to faer.

use super::rows::{self, Row};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::MatMut;

/// Columns of a supernode's diagonal triangle solved per panel: the rows below a panel are
/// updated by the tiled product of depth `PANEL`, the panel itself column by column.
const PANEL: usize = 32;

/// Widest block solved in one pass; wider right-hand sides are split into chunks of this many.
pub(crate) const MAX_LANES: usize = 16;

/// A stored value of L: f64, or f32 for a mixed-precision factor. An f32 factor is solved in f32
/// arithmetic ([`solve_in_place_single`]) where the CPU has AVX2/FMA, else read into f64
/// registers by the f64-arithmetic kernels.
pub(crate) trait Entry: Copy + Send + Sync + 'static {
    fn to_f64(self) -> f64;
    /// The value at `p` in all four f64 lanes (one load; for f32 one conversion).
    ///
    /// # Safety
    /// `p` is valid for a read, and the CPU has AVX (the callers are the AVX2 kernels).
    #[cfg(target_arch = "x86_64")]
    unsafe fn splat(p: *const Self) -> std::arch::x86_64::__m256d;
}

impl Entry for f64 {
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn splat(p: *const Self) -> std::arch::x86_64::__m256d {
        std::arch::x86_64::_mm256_broadcast_sd(&*p)
    }
}

impl Entry for f32 {
    #[inline(always)]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn splat(p: *const Self) -> std::arch::x86_64::__m256d {
        use std::arch::x86_64::*;
        _mm256_cvtps_pd(_mm_broadcast_ss(&*p))
    }
}

/// The parts of a supernodal factor the solves read.
pub(crate) struct Supernodal<'a, T: Entry> {
    /// First column of each supernode.
    begin: &'a [usize],
    /// Past-the-end column of each supernode.
    end: &'a [usize],
    /// Start of each supernode's off-diagonal row pattern in `rows`.
    row_ptr: &'a [usize],
    /// Off-diagonal rows of the supernodes (permuted order).
    rows: &'a [usize],
    /// Start of each supernode's values: a column-major (w + r) × w block, lower triangle on top.
    val_ptr: &'a [usize],
    values: &'a [T],
    n: usize,
}

/// One supernode: first column, width, rows below it, and its column-major (w + r) × w values.
struct Node<'a, T> {
    c0: usize,
    w: usize,
    pattern: &'a [usize],
    l: &'a [T],
}

impl<T> Node<'_, T> {
    /// Leading dimension of the value block.
    fn ld(&self) -> usize {
        self.w + self.pattern.len()
    }
}

impl<'a, T: Entry> Supernodal<'a, T> {
    pub(crate) fn new(s: &'a SymbolicSupernodalCholesky<usize>, values: &'a [T]) -> Self {
        Self {
            begin: s.supernode_begin(),
            end: s.supernode_end(),
            row_ptr: s.col_ptr_for_row_idx(),
            rows: s.row_idx(),
            val_ptr: s.col_ptr_for_val(),
            values,
            n: s.nrows(),
        }
    }

    fn n_supernodes(&self) -> usize {
        self.begin.len()
    }

    fn node(&self, s: usize) -> Node<'a, T> {
        let c0 = self.begin[s];
        let w = self.end[s] - c0;
        let l = &self.values[self.val_ptr[s]..self.val_ptr[s + 1]];
        // the pattern's length from the value block ((w + r) × w): faer's row pointers may leave
        // slack between supernodes
        let r = l.len() / w - w;
        let pattern = &self.rows[self.row_ptr[s]..][..r];
        debug_assert!(pattern.iter().all(|&p| p >= c0 + w && p < self.n));
        Node { c0, w, pattern, l }
    }
}

/// Whether the AVX2/FMA kernels run on this CPU (the only ones a [`Schedule`] splits).
pub(crate) fn simd_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Solves L Lᵀ X = B in place for the columns of `rhs` (at most [`MAX_LANES`]), `perm[new] =
/// old` being the factor's fill-reducing permutation.
pub(crate) fn solve_in_place<T: Entry>(
    f: &Supernodal<'_, T>,
    perm: Option<&[usize]>,
    rhs: MatMut<'_, f64>,
    split: Option<&Schedule>,
) {
    solve_dispatch(f, perm, rhs, true, split);
}

/// Solves L Lᵀ X = B for an f32 factor in f32 arithmetic, rows of 8 or 16 f32 lanes (at most
/// [`MAX_LANES`] columns): twice the lanes of an instruction and half the bytes of X, so 0.55×
/// the time of the f64-arithmetic solve of the same factor (the 180k tet10 factor, 6 columns),
/// whose error it matches (one solve: 6.2e-2 either way, the factor's own). Each
/// column is scaled by a power of two to max |b| ∈ [1, 2) first, so f32's range holds it. For
/// refined solves ([`super::cholesky::SparseLlt::solve_refined_in_place`]); machines without
/// AVX2/FMA take the f64-arithmetic kernels.
pub(crate) fn solve_in_place_single(
    f: &Supernodal<'_, f32>,
    perm: Option<&[usize]>,
    mut rhs: MatMut<'_, f64>,
    split: Option<&Schedule>,
) {
    assert!(rhs.ncols() <= MAX_LANES && rhs.nrows() == f.n);
    #[cfg(target_arch = "x86_64")]
    {
        if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
            let scales: Vec<f64> = (0..rhs.ncols())
                .map(|c| {
                    let top = rhs.as_ref().col(c).norm_max();
                    if top > 0.0 && top.is_finite() {
                        (-top.log2().floor()).exp2()
                    } else {
                        1.0
                    }
                })
                .collect();
            for (c, &sc) in scales.iter().enumerate() {
                rhs.as_mut().col_mut(c).iter_mut().for_each(|v| *v *= sc);
            }
            match rhs.ncols() {
                0 => {}
                1..=8 => single_lanes::<8, 1>(f, perm, rhs.as_mut(), split),
                _ => single_lanes::<16, 2>(f, perm, rhs.as_mut(), split),
            }
            for (c, &sc) in scales.iter().enumerate() {
                rhs.as_mut().col_mut(c).iter_mut().for_each(|v| *v /= sc);
            }
            return;
        }
    }
    solve_dispatch(f, perm, rhs, true, split);
}

/// [`solve_in_place_single`] on rows of `W = 8·Q` f32 lanes.
#[cfg(target_arch = "x86_64")]
fn single_lanes<const W: usize, const Q: usize>(
    f: &Supernodal<'_, f32>,
    perm: Option<&[usize]>,
    mut rhs: MatMut<'_, f64>,
    split: Option<&Schedule>,
) {
    debug_assert_eq!(W, 8 * Q);
    let mut x = rows::to_rows::<W, f32>(rhs.as_ref(), perm);
    // SAFETY: the caller checked AVX2 and FMA, and `x` holds one row per column of the factor.
    unsafe { avx2::solve::<f32, f32, W, Q>(f, &mut x, split) };
    rows::from_rows(&x, rhs.as_mut(), perm);
}

/// The f64-arithmetic kernels (AVX2 with `simd` where the CPU has it, else portable; `split`
/// only with AVX2: the portable kernels run on one thread).
fn solve_dispatch<T: Entry>(
    f: &Supernodal<'_, T>,
    perm: Option<&[usize]>,
    rhs: MatMut<'_, f64>,
    simd: bool,
    split: Option<&Schedule>,
) {
    assert!(rhs.ncols() <= MAX_LANES && rhs.nrows() == f.n);
    match rhs.ncols() {
        0 => {}
        1..=4 => solve_lanes::<T, 4, 1>(f, perm, rhs, simd, split),
        5..=8 => solve_lanes::<T, 8, 2>(f, perm, rhs, simd, split),
        9..=12 => solve_lanes::<T, 12, 3>(f, perm, rhs, simd, split),
        _ => solve_lanes::<T, 16, 4>(f, perm, rhs, simd, split),
    }
}

/// `W = 4·Q` lanes.
fn solve_lanes<T: Entry, const W: usize, const Q: usize>(
    f: &Supernodal<'_, T>,
    perm: Option<&[usize]>,
    mut rhs: MatMut<'_, f64>,
    simd: bool,
    split: Option<&Schedule>,
) {
    debug_assert_eq!(W, 4 * Q);
    let mut x = rows::to_rows::<W, f64>(rhs.as_ref(), perm);
    let mut done = false;
    #[cfg(target_arch = "x86_64")]
    {
        if simd && is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
            // SAFETY: the CPU has AVX2 and FMA (checked just above), and `x` holds one row per
            // column of the factor, which is what the kernels index.
            unsafe { avx2::solve::<T, f64, W, Q>(f, &mut x, split) };
            done = true;
        }
    }
    if !done {
        portable::solve::<T, W>(f, &mut x);
    }
    rows::from_rows(&x, rhs.as_mut(), perm);
}

// the lane loops index several arrays of the same const length in lockstep
#[allow(clippy::needless_range_loop)]
/// The same substitutions in plain Rust, column of L by column of L (machines without AVX2/FMA).
mod portable {
    use super::{Entry, Row, Supernodal};

    pub(super) fn solve<T: Entry, const W: usize>(f: &Supernodal<'_, T>, x: &mut [Row<W>]) {
        for s in 0..f.n_supernodes() {
            let nd = f.node(s);
            let ld = nd.ld();
            for t in 0..nd.w {
                let col = &nd.l[t * ld..(t + 1) * ld];
                let d = 1.0 / col[t].to_f64();
                let xt = x[nd.c0 + t].0.map(|v| v * d);
                x[nd.c0 + t].0 = xt;
                let below = (t + 1..nd.w).map(|i| (nd.c0 + i, col[i].to_f64()));
                let outer = nd
                    .pattern
                    .iter()
                    .zip(&col[nd.w..])
                    .map(|(&p, &v)| (p, v.to_f64()));
                for (row, v) in below.chain(outer) {
                    for c in 0..W {
                        x[row].0[c] -= v * xt[c];
                    }
                }
            }
        }
        for s in (0..f.n_supernodes()).rev() {
            let nd = f.node(s);
            let ld = nd.ld();
            for t in (0..nd.w).rev() {
                let col = &nd.l[t * ld..(t + 1) * ld];
                let mut acc = x[nd.c0 + t].0;
                let below = (t + 1..nd.w).map(|i| (nd.c0 + i, col[i].to_f64()));
                let outer = nd
                    .pattern
                    .iter()
                    .zip(&col[nd.w..])
                    .map(|(&p, &v)| (p, v.to_f64()));
                for (row, v) in below.chain(outer) {
                    for c in 0..W {
                        acc[c] -= v * x[row].0[c];
                    }
                }
                let d = 1.0 / col[t].to_f64();
                x[nd.c0 + t].0 = acc.map(|v| v * d);
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
mod avx2;
pub(crate) mod tree;
pub(crate) use tree::Schedule;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::sparse_ops;
    use crate::solve::SparseLlt;
    use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
    use faer::Par;

    /// A 3D Laplacian-like SPD matrix on an nx × ny × nz grid with 3 dofs per node (coupled),
    /// big enough for faer to choose the supernodal factor with wide supernodes.
    fn grid_matrix(nx: usize, ny: usize, nz: usize) -> faer::sparse::SparseColMat<usize, f64> {
        let id = |i: usize, j: usize, k: usize| (i * ny + j) * nz + k;
        let nn = nx * ny * nz;
        let mut trips = Vec::new();
        for i in 0..nx {
            for j in 0..ny {
                for k in 0..nz {
                    let a = id(i, j, k);
                    for c in 0..3 {
                        trips.push(faer::sparse::Triplet::new(3 * a + c, 3 * a + c, 13.0));
                        if c > 0 {
                            trips.push(faer::sparse::Triplet::new(3 * a + c, 3 * a, 0.5));
                            trips.push(faer::sparse::Triplet::new(3 * a, 3 * a + c, 0.5));
                        }
                    }
                    let mut link = |b: usize| {
                        for c in 0..3 {
                            for e in 0..3 {
                                let v = if c == e { -1.0 } else { -0.1 };
                                trips.push(faer::sparse::Triplet::new(3 * a + c, 3 * b + e, v));
                                trips.push(faer::sparse::Triplet::new(3 * b + e, 3 * a + c, v));
                            }
                        }
                    };
                    if i + 1 < nx {
                        link(id(i + 1, j, k));
                    }
                    if j + 1 < ny {
                        link(id(i, j + 1, k));
                    }
                    if k + 1 < nz {
                        link(id(i, j, k + 1));
                    }
                }
            }
        }
        faer::sparse::SparseColMat::try_new_from_triplets(3 * nn, 3 * nn, &trips).unwrap()
    }

    /// Every lane width, the SIMD and the portable kernels, against faer's solve and by the
    /// residual ‖A X − B‖ (supernodes wider than a panel included).
    #[test]
    fn row_solves_equal_faer_and_satisfy_the_system() {
        let a = grid_matrix(14, 12, 12);
        let llt = SparseLlt::factor(a.as_ref(), Some(3), Par::Seq).unwrap();
        let SymbolicCholeskyRaw::Supernodal(s) = llt.symbolic().raw() else {
            panic!("expected a supernodal factor");
        };
        let f = Supernodal::new(s, llt.values());
        let widest = (0..f.n_supernodes()).map(|s| f.node(s).w).max().unwrap();
        assert!(widest > 2 * PANEL, "widest supernode {widest}");
        let perm = llt.symbolic().perm().map(|p| p.arrays().0);
        let n = a.nrows();
        for b in [1, 3, 4, 6, 8, 11, 12, 16] {
            let bm = crate::solve::eigen::random_block(n, b, &mut 0x9E37_79B9_7F4A_7C15u64);
            let mut reference = bm.clone();
            llt.solve_in_place_faer(reference.as_mut());
            for simd in [true, false] {
                let mut x = bm.clone();
                solve_dispatch(&f, perm, x.as_mut(), simd, None);
                let d = (&x - &reference).norm_max() / reference.norm_max();
                assert!(d < 1e-12, "b = {b}, simd = {simd}: {d:e}");
                let r = sparse_ops::spmm(a.as_ref(), x.as_ref()) - &bm;
                let rel = r.norm_max() / bm.norm_max();
                assert!(rel < 1e-12, "b = {b}, simd = {simd}: residual {rel:e}");
            }
        }
    }

    /// The half solves of an in-order factor (AMLS's, faer's kernels): L⁻ᵀ(L⁻¹B) equals the
    /// full solve of the same factor (our row kernels) and satisfies A X = B, for 130 columns.
    #[test]
    fn half_solves_compose_to_the_solve() {
        let a = grid_matrix(10, 9, 8);
        let (symbolic, stats) = crate::solve::cholesky::analyze_in_order(a.as_ref()).unwrap();
        let llt = SparseLlt::factor_with(symbolic, stats, a.as_ref(), Par::Seq).unwrap();
        assert!(llt.symbolic().perm().is_none());
        assert!(matches!(
            llt.symbolic().raw(),
            SymbolicCholeskyRaw::Supernodal(_)
        ));
        let n = a.nrows();
        let bm = crate::solve::eigen::random_block(n, 130, &mut 0x9E37_79B9_7F4A_7C15u64);
        let mut x = bm.clone();
        llt.l_solve_in_place(x.as_mut()).unwrap();
        llt.lt_solve_in_place(x.as_mut()).unwrap();
        let mut full = bm.clone();
        llt.solve_in_place(full.as_mut());
        let d = (&x - &full).norm_max() / full.norm_max();
        let r = sparse_ops::spmm(a.as_ref(), x.as_ref()) - &bm;
        let rel = r.norm_max() / bm.norm_max();
        eprintln!("half solves vs the solve {d:.1e}, residual {rel:.1e}");
        // measured 2.5e-15 and 1.6e-15
        assert!(d < 2.5e-14, "{d:e}");
        assert!(rel < 1.6e-14, "residual {rel:e}");
    }

    /// Two threads on one solve: the elimination tree of the grid splits into two groups of
    /// subtrees holding most of L, and the split solve gives the one-thread solve's X (to
    /// rounding: the rows above both groups are summed in another order) for f64 and f32
    /// factors and every lane width.
    #[test]
    fn two_thread_tree_split_solves_equal_one_thread() {
        let a = grid_matrix(14, 12, 12);
        let n = a.nrows();
        for mixed in [false, true] {
            let (sym, st) = crate::solve::cholesky::analyze(a.as_ref(), Some(3)).unwrap();
            let (sym2, st2) = crate::solve::cholesky::analyze(a.as_ref(), Some(3)).unwrap();
            let factor = |sym, st, par| {
                if mixed {
                    SparseLlt::factor_mixed_with(sym, st, a.as_ref(), par).unwrap()
                } else {
                    SparseLlt::factor_with(sym, st, a.as_ref(), par).unwrap()
                }
            };
            let one = factor(sym, st, Par::Seq);
            let two = factor(sym2, st2, Par::rayon(2));
            let SymbolicCholeskyRaw::Supernodal(s) = two.symbolic().raw() else {
                panic!("expected a supernodal factor");
            };
            let sch = if mixed {
                tree::schedule(&Supernodal::new(s, two.values_f32()))
            } else {
                tree::schedule(&Supernodal::new(s, two.values()))
            }
            .expect("the grid's tree splits");
            let ptr = s.col_ptr_for_val();
            let share = |l: &[usize]| {
                l.iter().map(|&k| ptr[k + 1] - ptr[k]).sum::<usize>() as f64
                    / ptr[ptr.len() - 1] as f64
            };
            let (wa, wb, wr) = (share(&sch.a), share(&sch.b), share(&sch.rest));
            assert!(
                wa > 0.2 && wb > 0.2 && wr < 0.5,
                "shares of L: {wa:.2} / {wb:.2} / rest {wr:.2}"
            );
            for b in [1, 6, 8, 12, 16] {
                let bm = crate::solve::eigen::random_block(n, b, &mut 0x9E37_79B9_7F4A_7C15u64);
                let x1 = one.solve(bm.as_ref());
                let x2 = two.solve(bm.as_ref());
                let d = (&x1 - &x2).norm_max() / x1.norm_max();
                let limit = if mixed { 1e-5 } else { 1e-13 };
                assert!(d <= limit, "mixed {mixed}, b = {b}: {d:e}");
            }
        }
    }

    /// An f32 factor: the f64-arithmetic SIMD and portable kernels agree; one solve (in f32
    /// arithmetic) is off by what f32 leaves (> 1e-9), within 10× the f64-arithmetic solve's
    /// error on the same factor (this well-conditioned matrix's factor is accurate enough for
    /// f32 rounding in the solve to show: 1.6e-6 against 4.4e-7; on the 180k tet10 K both are the
    /// factor's 6.2e-2), also for right-hand sides scaled by 1e-42 and 1e40 (subnormal
    /// and overflowing in f32 without the column scaling); and refinement against A brings it to the f64 solve's
    /// accuracy.
    #[test]
    fn mixed_factor_solves_refine_to_the_f64_solution() {
        let a = grid_matrix(14, 12, 12);
        let (s64, st64) = crate::solve::cholesky::analyze(a.as_ref(), Some(3)).unwrap();
        let f64_llt = SparseLlt::factor_with(s64, st64, a.as_ref(), Par::Seq).unwrap();
        let (s32, st32) = crate::solve::cholesky::analyze(a.as_ref(), Some(3)).unwrap();
        let mixed = SparseLlt::factor_mixed_with(s32, st32, a.as_ref(), Par::Seq).unwrap();
        assert!(mixed.is_mixed());
        assert_eq!(mixed.stats.factor_bytes, 4 * mixed.symbolic().len_val());
        let n = a.nrows();
        for b in [1, 6, 8, 16] {
            let bm = crate::solve::eigen::random_block(n, b, &mut 0x2545_F491_4F6C_DD1Du64);
            let exact = f64_llt.solve(bm.as_ref());
            let scale = exact.norm_max();
            let one = mixed.solve(bm.as_ref());
            let d1 = (&one - &exact).norm_max() / scale;
            assert!(d1 > 1e-9 && d1 < 1e-4, "b = {b}: one f32 solve {d1:e}");
            // the two kernels on the f32 factor
            let SymbolicCholeskyRaw::Supernodal(sym) = mixed.symbolic().raw() else {
                panic!("expected a supernodal factor");
            };
            let f = Supernodal::new(sym, mixed.values_f32());
            let perm = mixed.symbolic().perm().map(|p| p.arrays().0);
            let mut portable = bm.clone();
            solve_dispatch(&f, perm, portable.as_mut(), false, None);
            let mut simd = bm.clone();
            solve_dispatch(&f, perm, simd.as_mut(), true, None);
            let dk = (&portable - &simd).norm_max() / scale;
            assert!(dk < 1e-13, "b = {b}: SIMD vs portable on f32 L {dk:e}");
            let d64 = (&simd - &exact).norm_max() / scale;
            assert!(
                d1 <= 10.0 * d64,
                "b = {b}: f32 arithmetic {d1:e}, f64 {d64:e}"
            );
            for size in [1e-42, 1e40] {
                let x = mixed.solve((&bm * faer::Scale(size)).as_ref());
                let dt = (&x * faer::Scale(1.0 / size) - &exact).norm_max() / scale;
                assert!(dt <= 10.0 * d64, "b = {b}: scaled by {size:e}: {dt:e}");
            }
            let mut x = bm.clone();
            let steps = mixed
                .solve_refined_in_place(a.as_ref(), x.as_mut(), crate::solve::cholesky::REFINE_F64)
                .unwrap();
            let d = (&x - &exact).norm_max() / scale;
            assert!(
                steps >= 1 && d < 1e-13,
                "b = {b}: refined in {steps} steps: {d:e}"
            );
        }
        // the f32 factor's analysis factors A again in f64: the same L as a fresh analysis
        let (symbolic, stats) = mixed.into_analysis();
        assert_eq!(stats.factor_bytes, f64_llt.stats.factor_bytes);
        let again = SparseLlt::factor_with(symbolic, stats, a.as_ref(), Par::Seq).unwrap();
        assert!(!again.is_mixed());
        assert_eq!(again.values(), f64_llt.values());
    }

    /// A matrix too ill-conditioned for f32 (a grid Laplacian, singular, shifted by 1e-9 of its
    /// largest diagonal: κ ≈ 1e10) is refused loudly, by a non-positive f32 pivot or a stalled
    /// refinement, never answered with an f32-accurate solution.
    #[test]
    fn mixed_factor_of_an_ill_conditioned_matrix_fails_loudly() {
        let (nx, ny, nz) = (14, 12, 12);
        let id = |i: usize, j: usize, k: usize| (i * ny + j) * nz + k;
        let n = 3 * nx * ny * nz;
        let mut diag = vec![6e-9; n];
        let mut trips = Vec::new();
        for i in 0..nx {
            for j in 0..ny {
                for k in 0..nz {
                    let a = id(i, j, k);
                    let mut links = vec![];
                    if i + 1 < nx {
                        links.push(id(i + 1, j, k));
                    }
                    if j + 1 < ny {
                        links.push(id(i, j + 1, k));
                    }
                    if k + 1 < nz {
                        links.push(id(i, j, k + 1));
                    }
                    for b in links {
                        for c in 0..3 {
                            trips.push(faer::sparse::Triplet::new(3 * a + c, 3 * b + c, -1.0));
                            trips.push(faer::sparse::Triplet::new(3 * b + c, 3 * a + c, -1.0));
                            diag[3 * a + c] += 1.0;
                            diag[3 * b + c] += 1.0;
                        }
                    }
                }
            }
        }
        trips.extend(
            diag.iter()
                .enumerate()
                .map(|(i, &d)| faer::sparse::Triplet::new(i, i, d)),
        );
        let a = faer::sparse::SparseColMat::try_new_from_triplets(n, n, &trips).unwrap();
        let (s32, st32) = crate::solve::cholesky::analyze(a.as_ref(), Some(3)).unwrap();
        assert!(matches!(s32.raw(), SymbolicCholeskyRaw::Supernodal(_)));
        let outcome = SparseLlt::factor_mixed_with(s32, st32, a.as_ref(), Par::Seq).and_then(|l| {
            let mut x = crate::solve::eigen::random_block(n, 4, &mut 0x9E37_79B9u64);
            l.solve_refined_in_place(a.as_ref(), x.as_mut(), crate::solve::cholesky::REFINE_F64)
        });
        assert!(
            matches!(
                outcome,
                Err(crate::solve::SolveError::Refinement { .. })
                    | Err(crate::solve::SolveError::NonPositivePivot { .. })
            ),
            "{outcome:?}"
        );
    }
}
