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
//! kernels use AVX2/FMA when the CPU has them (checked at run time) and portable Rust otherwise.
//! Simplicial factors (small problems) are left to faer.

use super::rows::{self, Row};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::MatMut;

/// Columns of a supernode's diagonal triangle solved per panel: the rows below a panel are
/// updated by the tiled product of depth `PANEL`, the panel itself column by column.
const PANEL: usize = 32;

/// Widest block solved in one pass; wider right-hand sides are split into chunks of this many.
pub(crate) const MAX_LANES: usize = 16;

/// A stored value of L: f64, or f32 for a mixed-precision factor (read into f64 registers, so
/// that the solves run in f64 arithmetic on a factor of half the bytes).
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

/// Solves L Lᵀ X = B in place for the columns of `rhs` (at most [`MAX_LANES`]), `perm[new] =
/// old` being the factor's fill-reducing permutation.
pub(crate) fn solve_in_place<T: Entry>(
    f: &Supernodal<'_, T>,
    perm: Option<&[usize]>,
    rhs: MatMut<'_, f64>,
) {
    solve_dispatch(f, perm, rhs, true);
}

fn solve_dispatch<T: Entry>(
    f: &Supernodal<'_, T>,
    perm: Option<&[usize]>,
    rhs: MatMut<'_, f64>,
    simd: bool,
) {
    assert!(rhs.ncols() <= MAX_LANES && rhs.nrows() == f.n);
    match rhs.ncols() {
        0 => {}
        1..=4 => solve_lanes::<T, 4, 1>(f, perm, rhs, simd),
        5..=8 => solve_lanes::<T, 8, 2>(f, perm, rhs, simd),
        9..=12 => solve_lanes::<T, 12, 3>(f, perm, rhs, simd),
        _ => solve_lanes::<T, 16, 4>(f, perm, rhs, simd),
    }
}

/// `W = 4·Q` lanes.
fn solve_lanes<T: Entry, const W: usize, const Q: usize>(
    f: &Supernodal<'_, T>,
    perm: Option<&[usize]>,
    mut rhs: MatMut<'_, f64>,
    simd: bool,
) {
    debug_assert_eq!(W, 4 * Q);
    let mut x = rows::to_rows::<W>(rhs.as_ref(), perm);
    let mut done = false;
    #[cfg(target_arch = "x86_64")]
    {
        if simd && is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
            // SAFETY: the CPU has AVX2 and FMA (checked just above), and `x` holds one row per
            // column of the factor, which is what the kernels index.
            unsafe { avx2::solve::<T, W, Q>(f, &mut x) };
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
mod avx2 {
    //! The AVX2/FMA kernels. Every function here requires AVX2 and FMA (callers check
    //! `is_x86_feature_detected!`) and rows of `W = 4·Q` lanes; the index arithmetic stays inside
    //! the slices, which each function asserts once before its loops.

    use super::{Entry, Node, Row, Supernodal, PANEL};
    use std::arch::x86_64::*;

    /// Where the rows of a product live: a contiguous run of X (rows inside a supernode's
    /// triangle) or the rows of a supernode's pattern.
    trait Rows: Copy {
        /// Row number of the i-th row.
        fn at(self, i: usize) -> usize;
        fn len(self) -> usize;
    }

    #[derive(Clone, Copy)]
    struct Run(usize, usize);
    impl Rows for Run {
        #[inline(always)]
        fn at(self, i: usize) -> usize {
            self.0 + i
        }
        #[inline(always)]
        fn len(self) -> usize {
            self.1
        }
    }

    #[derive(Clone, Copy)]
    struct Pattern<'a>(&'a [usize]);
    impl Rows for Pattern<'_> {
        #[inline(always)]
        fn at(self, i: usize) -> usize {
            // SAFETY: callers only ask for i < len().
            unsafe { *self.0.get_unchecked(i) }
        }
        #[inline(always)]
        fn len(self) -> usize {
            self.0.len()
        }
    }

    /// Forward then backward substitution on the permuted rows `x` (one per column of L).
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn solve<T: Entry, const W: usize, const Q: usize>(
        f: &Supernodal<'_, T>,
        x: &mut [Row<W>],
    ) {
        assert_eq!(x.len(), f.n);
        let xp = x.as_mut_ptr() as *mut f64;
        for s in 0..f.n_supernodes() {
            let nd = f.node(s);
            forward_triangle::<T, W, Q>(&nd, xp);
            forward_update::<T, W, Q, _>(&nd, nd.w, 0, nd.w, Pattern(nd.pattern), xp);
        }
        for s in (0..f.n_supernodes()).rev() {
            let nd = f.node(s);
            backward_update::<T, W, Q, _>(&nd, nd.w, 0, nd.w, Pattern(nd.pattern), xp);
            backward_triangle::<T, W, Q>(&nd, xp);
        }
    }

    /// Registers-wide tiles per lane count: forward KT (columns of L per pass), backward MR
    /// (columns of L accumulated side by side). Measured in-cache on this project's Zen machine.
    const fn tiles(q: usize) -> (usize, usize) {
        match q {
            1 => (8, 8),
            2 => (6, 6),
            3 => (4, 3),
            _ => (3, 2),
        }
    }

    /// X[rows[i]] -= Σ_{t<k} L[row0 + i, col0 + t] · X[c0 + col0 + t] for all rows: the forward
    /// product, KT columns of L at a time.
    #[target_feature(enable = "avx2,fma")]
    unsafe fn forward_update<T: Entry, const W: usize, const Q: usize, R: Rows>(
        nd: &Node<'_, T>,
        row0: usize,
        col0: usize,
        k: usize,
        rows: R,
        xp: *mut f64,
    ) {
        let (kt, _) = tiles(Q);
        let mut t = 0;
        while t < k {
            let take = (k - t).min(kt);
            let c = col0 + t;
            match take {
                8 => fwd_tile::<T, W, Q, 8, R>(nd, row0, c, rows, xp),
                7 => fwd_tile::<T, W, Q, 7, R>(nd, row0, c, rows, xp),
                6 => fwd_tile::<T, W, Q, 6, R>(nd, row0, c, rows, xp),
                5 => fwd_tile::<T, W, Q, 5, R>(nd, row0, c, rows, xp),
                4 => fwd_tile::<T, W, Q, 4, R>(nd, row0, c, rows, xp),
                3 => fwd_tile::<T, W, Q, 3, R>(nd, row0, c, rows, xp),
                2 => fwd_tile::<T, W, Q, 2, R>(nd, row0, c, rows, xp),
                _ => fwd_tile::<T, W, Q, 1, R>(nd, row0, c, rows, xp),
            }
            t += take;
        }
    }

    /// One pass of [`forward_update`] with KT columns `col0..col0+KT` of L.
    #[inline(always)]
    unsafe fn fwd_tile<T: Entry, const W: usize, const Q: usize, const KT: usize, R: Rows>(
        nd: &Node<'_, T>,
        row0: usize,
        col0: usize,
        rows: R,
        xp: *mut f64,
    ) {
        let ld = nd.ld();
        let r = rows.len();
        assert!(row0 + r <= ld && (col0 + KT) * ld <= nd.l.len());
        let mut xk = [[_mm256_setzero_pd(); Q]; KT];
        for (m, xm) in xk.iter_mut().enumerate() {
            let src = xp.add(W * (nd.c0 + col0 + m));
            for (q, v) in xm.iter_mut().enumerate() {
                *v = _mm256_load_pd(src.add(4 * q));
            }
        }
        let base: [*const T; KT] =
            std::array::from_fn(|m| nd.l.as_ptr().add((col0 + m) * ld + row0));
        for i in 0..r {
            let p = xp.add(W * rows.at(i));
            let mut acc = [_mm256_setzero_pd(); Q];
            for (q, a) in acc.iter_mut().enumerate() {
                *a = _mm256_load_pd(p.add(4 * q));
            }
            for m in 0..KT {
                let v = T::splat(base[m].add(i));
                for q in 0..Q {
                    acc[q] = _mm256_fnmadd_pd(v, xk[m][q], acc[q]);
                }
            }
            for (q, a) in acc.iter().enumerate() {
                _mm256_store_pd(p.add(4 * q), *a);
            }
        }
    }

    /// X[c0 + col0 + t] -= Σ_i L[row0 + i, col0 + t] · X[rows[i]] for t < k: the backward
    /// (transposed) product, MR columns of L at a time.
    #[target_feature(enable = "avx2,fma")]
    unsafe fn backward_update<T: Entry, const W: usize, const Q: usize, R: Rows>(
        nd: &Node<'_, T>,
        row0: usize,
        col0: usize,
        k: usize,
        rows: R,
        xp: *mut f64,
    ) {
        let (_, mr) = tiles(Q);
        let mut t = 0;
        while t < k {
            let take = (k - t).min(mr);
            let c = col0 + t;
            match take {
                8 => bwd_tile::<T, W, Q, 8, R>(nd, row0, c, rows, xp),
                7 => bwd_tile::<T, W, Q, 7, R>(nd, row0, c, rows, xp),
                6 => bwd_tile::<T, W, Q, 6, R>(nd, row0, c, rows, xp),
                5 => bwd_tile::<T, W, Q, 5, R>(nd, row0, c, rows, xp),
                4 => bwd_tile::<T, W, Q, 4, R>(nd, row0, c, rows, xp),
                3 => bwd_tile::<T, W, Q, 3, R>(nd, row0, c, rows, xp),
                2 => bwd_tile::<T, W, Q, 2, R>(nd, row0, c, rows, xp),
                _ => bwd_tile::<T, W, Q, 1, R>(nd, row0, c, rows, xp),
            }
            t += take;
        }
    }

    /// One tile of [`backward_update`]: MR columns `col0..col0+MR` of L.
    #[inline(always)]
    unsafe fn bwd_tile<T: Entry, const W: usize, const Q: usize, const MR: usize, R: Rows>(
        nd: &Node<'_, T>,
        row0: usize,
        col0: usize,
        rows: R,
        xp: *mut f64,
    ) {
        let ld = nd.ld();
        let r = rows.len();
        assert!(row0 + r <= ld && (col0 + MR) * ld <= nd.l.len());
        let mut acc = [[_mm256_setzero_pd(); Q]; MR];
        let base: [*const T; MR] =
            std::array::from_fn(|m| nd.l.as_ptr().add((col0 + m) * ld + row0));
        for i in 0..r {
            let g = xp.add(W * rows.at(i));
            let mut gi = [_mm256_setzero_pd(); Q];
            for (q, v) in gi.iter_mut().enumerate() {
                *v = _mm256_load_pd(g.add(4 * q));
            }
            for m in 0..MR {
                let v = T::splat(base[m].add(i));
                for q in 0..Q {
                    acc[m][q] = _mm256_fmadd_pd(v, gi[q], acc[m][q]);
                }
            }
        }
        for (m, am) in acc.iter().enumerate() {
            let p = xp.add(W * (nd.c0 + col0 + m));
            for (q, a) in am.iter().enumerate() {
                _mm256_store_pd(
                    p.add(4 * q),
                    _mm256_sub_pd(_mm256_load_pd(p.add(4 * q)), *a),
                );
            }
        }
    }

    /// L₁₁ Y = X₁ for a supernode's triangle: panels of [`PANEL`] columns, each solved column by
    /// column, then the rows below it in the triangle updated by [`forward_update`].
    #[target_feature(enable = "avx2,fma")]
    unsafe fn forward_triangle<T: Entry, const W: usize, const Q: usize>(
        nd: &Node<'_, T>,
        xp: *mut f64,
    ) {
        let (w, ld) = (nd.w, nd.ld());
        assert!(w * ld <= nd.l.len());
        let mut p0 = 0;
        while p0 < w {
            let p1 = (p0 + PANEL).min(w);
            for t in p0..p1 {
                let col = nd.l.as_ptr().add(t * ld);
                let d = _mm256_set1_pd(1.0 / (*col.add(t)).to_f64());
                let pt = xp.add(W * (nd.c0 + t));
                let mut xt = [_mm256_setzero_pd(); Q];
                for (q, v) in xt.iter_mut().enumerate() {
                    *v = _mm256_mul_pd(_mm256_load_pd(pt.add(4 * q)), d);
                    _mm256_store_pd(pt.add(4 * q), *v);
                }
                for i in t + 1..p1 {
                    let v = T::splat(col.add(i));
                    let pi = xp.add(W * (nd.c0 + i));
                    for (q, x) in xt.iter().enumerate() {
                        let y = _mm256_fnmadd_pd(v, *x, _mm256_load_pd(pi.add(4 * q)));
                        _mm256_store_pd(pi.add(4 * q), y);
                    }
                }
            }
            if p1 < w {
                forward_update::<T, W, Q, _>(nd, p1, p0, p1 - p0, Run(nd.c0 + p1, w - p1), xp);
            }
            p0 = p1;
        }
    }

    /// L₁₁ᵀ Z = Y for a supernode's triangle, panels from the bottom: each panel first takes the
    /// product with the rows already solved below it ([`backward_update`]), then is solved
    /// column by column.
    #[target_feature(enable = "avx2,fma")]
    unsafe fn backward_triangle<T: Entry, const W: usize, const Q: usize>(
        nd: &Node<'_, T>,
        xp: *mut f64,
    ) {
        let (w, ld) = (nd.w, nd.ld());
        assert!(w * ld <= nd.l.len());
        let mut p1 = w;
        while p1 > 0 {
            let p0 = p1.saturating_sub(PANEL);
            if p1 < w {
                backward_update::<T, W, Q, _>(nd, p1, p0, p1 - p0, Run(nd.c0 + p1, w - p1), xp);
            }
            for t in (p0..p1).rev() {
                let col = nd.l.as_ptr().add(t * ld);
                let pt = xp.add(W * (nd.c0 + t));
                let mut acc = [_mm256_setzero_pd(); Q];
                for (q, a) in acc.iter_mut().enumerate() {
                    *a = _mm256_load_pd(pt.add(4 * q));
                }
                for i in t + 1..p1 {
                    let v = T::splat(col.add(i));
                    let pi = xp.add(W * (nd.c0 + i));
                    for (q, a) in acc.iter_mut().enumerate() {
                        *a = _mm256_fnmadd_pd(v, _mm256_load_pd(pi.add(4 * q)), *a);
                    }
                }
                let d = _mm256_set1_pd(1.0 / (*col.add(t)).to_f64());
                for (q, a) in acc.iter().enumerate() {
                    _mm256_store_pd(pt.add(4 * q), _mm256_mul_pd(*a, d));
                }
            }
            p1 = p0;
        }
    }
}

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
                solve_dispatch(&f, perm, x.as_mut(), simd);
                let d = (&x - &reference).norm_max() / reference.norm_max();
                assert!(d < 1e-12, "b = {b}, simd = {simd}: {d:e}");
                let r = sparse_ops::spmm(a.as_ref(), x.as_ref()) - &bm;
                let rel = r.norm_max() / bm.norm_max();
                assert!(rel < 1e-12, "b = {b}, simd = {simd}: residual {rel:e}");
            }
        }
    }

    /// An f32 factor: the SIMD and portable kernels agree (both read L into f64 arithmetic); one
    /// solve is off by what f32 leaves (> 1e-9), and refinement against A brings it to the f64
    /// solve's accuracy.
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
            solve_dispatch(&f, perm, portable.as_mut(), false);
            let dk = (&portable - &one).norm_max() / scale;
            assert!(dk < 1e-13, "b = {b}: SIMD vs portable on f32 L {dk:e}");
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
