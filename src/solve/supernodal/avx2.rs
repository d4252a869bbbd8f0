//! The AVX2/FMA kernels of [`super`]. Every function here requires AVX2 and FMA (callers check
//! `is_x86_feature_detected!`) and rows of `W = N·Q` lanes (N per vector, [`Lanes`]); the index
//! arithmetic stays inside the slices, which each function asserts once before its loops.

use super::tree::Schedule;
use super::{Entry, Node, Row, Supernodal, PANEL};
use crate::solve::rows::Lane;
use std::arch::x86_64::*;

/// The arithmetic of the right-hand sides' rows in 256-bit vectors of `N` lanes: f64 (4
/// lanes) with L read in f64 or f32, or f32 (8 lanes) with an f32 L.
pub(super) trait Lanes<T: Entry>: Lane {
    const N: usize;
    type V: Copy;
    unsafe fn zero() -> Self::V;
    unsafe fn load(p: *const Self) -> Self::V;
    unsafe fn store(p: *mut Self, v: Self::V);
    /// The entry of L at `p` in all lanes.
    unsafe fn splat(p: *const T) -> Self::V;
    /// 1 / (the entry of L at `p`) in all lanes.
    unsafe fn inv(p: *const T) -> Self::V;
    unsafe fn fmadd(a: Self::V, b: Self::V, c: Self::V) -> Self::V;
    unsafe fn fnmadd(a: Self::V, b: Self::V, c: Self::V) -> Self::V;
    unsafe fn mul(a: Self::V, b: Self::V) -> Self::V;
    unsafe fn sub(a: Self::V, b: Self::V) -> Self::V;
}

// SAFETY (both impls): the callers are the AVX2/FMA kernels below, which hold the target
// features, and pass pointers valid for the loads and stores (rows 32-byte aligned).
impl<T: Entry> Lanes<T> for f64 {
    const N: usize = 4;
    type V = __m256d;
    #[inline(always)]
    unsafe fn zero() -> __m256d {
        _mm256_setzero_pd()
    }
    #[inline(always)]
    unsafe fn load(p: *const f64) -> __m256d {
        _mm256_load_pd(p)
    }
    #[inline(always)]
    unsafe fn store(p: *mut f64, v: __m256d) {
        _mm256_store_pd(p, v)
    }
    #[inline(always)]
    unsafe fn splat(p: *const T) -> __m256d {
        T::splat(p)
    }
    #[inline(always)]
    unsafe fn inv(p: *const T) -> __m256d {
        _mm256_set1_pd(1.0 / (*p).to_f64())
    }
    #[inline(always)]
    unsafe fn fmadd(a: __m256d, b: __m256d, c: __m256d) -> __m256d {
        _mm256_fmadd_pd(a, b, c)
    }
    #[inline(always)]
    unsafe fn fnmadd(a: __m256d, b: __m256d, c: __m256d) -> __m256d {
        _mm256_fnmadd_pd(a, b, c)
    }
    #[inline(always)]
    unsafe fn mul(a: __m256d, b: __m256d) -> __m256d {
        _mm256_mul_pd(a, b)
    }
    #[inline(always)]
    unsafe fn sub(a: __m256d, b: __m256d) -> __m256d {
        _mm256_sub_pd(a, b)
    }
}

impl Lanes<f32> for f32 {
    const N: usize = 8;
    type V = __m256;
    #[inline(always)]
    unsafe fn zero() -> __m256 {
        _mm256_setzero_ps()
    }
    #[inline(always)]
    unsafe fn load(p: *const f32) -> __m256 {
        _mm256_load_ps(p)
    }
    #[inline(always)]
    unsafe fn store(p: *mut f32, v: __m256) {
        _mm256_store_ps(p, v)
    }
    #[inline(always)]
    unsafe fn splat(p: *const f32) -> __m256 {
        _mm256_broadcast_ss(&*p)
    }
    #[inline(always)]
    unsafe fn inv(p: *const f32) -> __m256 {
        _mm256_set1_ps(1.0 / *p)
    }
    #[inline(always)]
    unsafe fn fmadd(a: __m256, b: __m256, c: __m256) -> __m256 {
        _mm256_fmadd_ps(a, b, c)
    }
    #[inline(always)]
    unsafe fn fnmadd(a: __m256, b: __m256, c: __m256) -> __m256 {
        _mm256_fnmadd_ps(a, b, c)
    }
    #[inline(always)]
    unsafe fn mul(a: __m256, b: __m256) -> __m256 {
        _mm256_mul_ps(a, b)
    }
    #[inline(always)]
    unsafe fn sub(a: __m256, b: __m256) -> __m256 {
        _mm256_sub_ps(a, b)
    }
}

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

/// Forward then backward substitution on the permuted rows `x` (one per column of L); with a
/// [`Schedule`], on two threads ([`super::tree`]).
#[target_feature(enable = "avx2,fma")]
pub(super) unsafe fn solve<T: Entry, X: Lanes<T>, const W: usize, const Q: usize>(
    f: &Supernodal<'_, T>,
    x: &mut [Row<W, X>],
    split: Option<&Schedule>,
) {
    assert_eq!(x.len(), f.n);
    let Some(sch) = split else {
        let xp = x.as_mut_ptr() as *mut X;
        forward::<T, X, W, Q>(f, 0..f.n_supernodes(), xp);
        backward::<T, X, W, Q>(f, (0..f.n_supernodes()).rev(), xp);
        return;
    };
    // forward: group b on a copy whose rows of the rest are zero, then its rows and its
    // contributions to the rest's rows added back
    let mut xb = x.to_vec();
    let rows_of = |list: &[usize]| {
        list.iter()
            .flat_map(|&s| f.begin[s]..f.end[s])
            .collect::<Vec<_>>()
    };
    let (rows_b, rows_rest) = (rows_of(&sch.b), rows_of(&sch.rest));
    for &r in &rows_rest {
        xb[r] = Row::ZERO;
    }
    let (pa, pb) = (
        Shared(x.as_mut_ptr() as *mut X),
        Shared(xb.as_mut_ptr() as *mut X),
    );
    // SAFETY (both joins): the two groups' subtrees have no supernode in common, so their
    // updates write disjoint rows (a on x, b on xb in the forward pass; both on x in the
    // backward pass, where each writes only its own rows and reads rows of the rest, which no
    // one writes then); the CPU has AVX2/FMA (checked by the caller of `solve`).
    rayon::join(
        || unsafe { forward::<T, X, W, Q>(f, sch.a.iter().copied(), pa.get()) },
        || unsafe { forward::<T, X, W, Q>(f, sch.b.iter().copied(), pb.get()) },
    );
    for &r in &rows_b {
        x[r] = xb[r];
    }
    for &r in &rows_rest {
        for (v, d) in x[r].0.iter_mut().zip(xb[r].0) {
            *v = X::from_f64(v.to_f64() + d.to_f64());
        }
    }
    let xp = x.as_mut_ptr() as *mut X;
    forward::<T, X, W, Q>(f, sch.rest.iter().copied(), xp);
    backward::<T, X, W, Q>(f, sch.rest.iter().rev().copied(), xp);
    let p = Shared(xp);
    rayon::join(
        || unsafe { backward::<T, X, W, Q>(f, sch.a.iter().rev().copied(), p.get()) },
        || unsafe { backward::<T, X, W, Q>(f, sch.b.iter().rev().copied(), p.get()) },
    );
}

/// A pointer to the rows handed to the two threads of a split solve.
#[derive(Clone, Copy)]
struct Shared<X>(*mut X);
// SAFETY: the threads of a split solve write disjoint rows through it (see `solve`).
unsafe impl<X> Send for Shared<X> {}
unsafe impl<X> Sync for Shared<X> {}
impl<X> Shared<X> {
    /// The pointer (a method, so that closures capture the whole `Shared`, which is `Send`).
    fn get(self) -> *mut X {
        self.0
    }
}

/// The forward substitution of the supernodes `order` (children before parents).
#[target_feature(enable = "avx2,fma")]
unsafe fn forward<T: Entry, X: Lanes<T>, const W: usize, const Q: usize>(
    f: &Supernodal<'_, T>,
    order: impl Iterator<Item = usize>,
    xp: *mut X,
) {
    for s in order {
        let nd = f.node(s);
        forward_triangle::<T, X, W, Q>(&nd, xp);
        forward_update::<T, X, W, Q, _>(&nd, nd.w, 0, nd.w, Pattern(nd.pattern), xp);
    }
}

/// The backward substitution of the supernodes `order` (parents before children).
#[target_feature(enable = "avx2,fma")]
unsafe fn backward<T: Entry, X: Lanes<T>, const W: usize, const Q: usize>(
    f: &Supernodal<'_, T>,
    order: impl Iterator<Item = usize>,
    xp: *mut X,
) {
    for s in order {
        let nd = f.node(s);
        backward_update::<T, X, W, Q, _>(&nd, nd.w, 0, nd.w, Pattern(nd.pattern), xp);
        backward_triangle::<T, X, W, Q>(&nd, xp);
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
unsafe fn forward_update<T: Entry, X: Lanes<T>, const W: usize, const Q: usize, R: Rows>(
    nd: &Node<'_, T>,
    row0: usize,
    col0: usize,
    k: usize,
    rows: R,
    xp: *mut X,
) {
    let (kt, _) = tiles(Q);
    let mut t = 0;
    while t < k {
        let take = (k - t).min(kt);
        let c = col0 + t;
        match take {
            8 => fwd_tile::<T, X, W, Q, 8, R>(nd, row0, c, rows, xp),
            7 => fwd_tile::<T, X, W, Q, 7, R>(nd, row0, c, rows, xp),
            6 => fwd_tile::<T, X, W, Q, 6, R>(nd, row0, c, rows, xp),
            5 => fwd_tile::<T, X, W, Q, 5, R>(nd, row0, c, rows, xp),
            4 => fwd_tile::<T, X, W, Q, 4, R>(nd, row0, c, rows, xp),
            3 => fwd_tile::<T, X, W, Q, 3, R>(nd, row0, c, rows, xp),
            2 => fwd_tile::<T, X, W, Q, 2, R>(nd, row0, c, rows, xp),
            _ => fwd_tile::<T, X, W, Q, 1, R>(nd, row0, c, rows, xp),
        }
        t += take;
    }
}

/// One pass of [`forward_update`] with KT columns `col0..col0+KT` of L.
#[inline(always)]
unsafe fn fwd_tile<
    T: Entry,
    X: Lanes<T>,
    const W: usize,
    const Q: usize,
    const KT: usize,
    R: Rows,
>(
    nd: &Node<'_, T>,
    row0: usize,
    col0: usize,
    rows: R,
    xp: *mut X,
) {
    let ld = nd.ld();
    let r = rows.len();
    assert!(row0 + r <= ld && (col0 + KT) * ld <= nd.l.len());
    let mut xk = [[X::zero(); Q]; KT];
    for (m, xm) in xk.iter_mut().enumerate() {
        let src = xp.add(W * (nd.c0 + col0 + m));
        for (q, v) in xm.iter_mut().enumerate() {
            *v = X::load(src.add(X::N * q));
        }
    }
    let base: [*const T; KT] = std::array::from_fn(|m| nd.l.as_ptr().add((col0 + m) * ld + row0));
    for i in 0..r {
        let p = xp.add(W * rows.at(i));
        let mut acc = [X::zero(); Q];
        for (q, a) in acc.iter_mut().enumerate() {
            *a = X::load(p.add(X::N * q));
        }
        for m in 0..KT {
            let v = X::splat(base[m].add(i));
            for q in 0..Q {
                acc[q] = X::fnmadd(v, xk[m][q], acc[q]);
            }
        }
        for (q, a) in acc.iter().enumerate() {
            X::store(p.add(X::N * q), *a);
        }
    }
}

/// X[c0 + col0 + t] -= Σ_i L[row0 + i, col0 + t] · X[rows[i]] for t < k: the backward
/// (transposed) product, MR columns of L at a time.
#[target_feature(enable = "avx2,fma")]
unsafe fn backward_update<T: Entry, X: Lanes<T>, const W: usize, const Q: usize, R: Rows>(
    nd: &Node<'_, T>,
    row0: usize,
    col0: usize,
    k: usize,
    rows: R,
    xp: *mut X,
) {
    let (_, mr) = tiles(Q);
    let mut t = 0;
    while t < k {
        let take = (k - t).min(mr);
        let c = col0 + t;
        match take {
            8 => bwd_tile::<T, X, W, Q, 8, R>(nd, row0, c, rows, xp),
            7 => bwd_tile::<T, X, W, Q, 7, R>(nd, row0, c, rows, xp),
            6 => bwd_tile::<T, X, W, Q, 6, R>(nd, row0, c, rows, xp),
            5 => bwd_tile::<T, X, W, Q, 5, R>(nd, row0, c, rows, xp),
            4 => bwd_tile::<T, X, W, Q, 4, R>(nd, row0, c, rows, xp),
            3 => bwd_tile::<T, X, W, Q, 3, R>(nd, row0, c, rows, xp),
            2 => bwd_tile::<T, X, W, Q, 2, R>(nd, row0, c, rows, xp),
            _ => bwd_tile::<T, X, W, Q, 1, R>(nd, row0, c, rows, xp),
        }
        t += take;
    }
}

/// One tile of [`backward_update`]: MR columns `col0..col0+MR` of L.
#[inline(always)]
unsafe fn bwd_tile<
    T: Entry,
    X: Lanes<T>,
    const W: usize,
    const Q: usize,
    const MR: usize,
    R: Rows,
>(
    nd: &Node<'_, T>,
    row0: usize,
    col0: usize,
    rows: R,
    xp: *mut X,
) {
    let ld = nd.ld();
    let r = rows.len();
    assert!(row0 + r <= ld && (col0 + MR) * ld <= nd.l.len());
    let mut acc = [[X::zero(); Q]; MR];
    let base: [*const T; MR] = std::array::from_fn(|m| nd.l.as_ptr().add((col0 + m) * ld + row0));
    for i in 0..r {
        let g = xp.add(W * rows.at(i));
        let mut gi = [X::zero(); Q];
        for (q, v) in gi.iter_mut().enumerate() {
            *v = X::load(g.add(X::N * q));
        }
        for m in 0..MR {
            let v = X::splat(base[m].add(i));
            for q in 0..Q {
                acc[m][q] = X::fmadd(v, gi[q], acc[m][q]);
            }
        }
    }
    for (m, am) in acc.iter().enumerate() {
        let p = xp.add(W * (nd.c0 + col0 + m));
        for (q, a) in am.iter().enumerate() {
            X::store(p.add(X::N * q), X::sub(X::load(p.add(X::N * q)), *a));
        }
    }
}

/// L₁₁ Y = X₁ for a supernode's triangle: panels of [`PANEL`] columns, each solved column by
/// column, then the rows below it in the triangle updated by [`forward_update`].
#[target_feature(enable = "avx2,fma")]
unsafe fn forward_triangle<T: Entry, X: Lanes<T>, const W: usize, const Q: usize>(
    nd: &Node<'_, T>,
    xp: *mut X,
) {
    let (w, ld) = (nd.w, nd.ld());
    assert!(w * ld <= nd.l.len());
    let mut p0 = 0;
    while p0 < w {
        let p1 = (p0 + PANEL).min(w);
        for t in p0..p1 {
            let col = nd.l.as_ptr().add(t * ld);
            let d = X::inv(col.add(t));
            let pt = xp.add(W * (nd.c0 + t));
            let mut xt = [X::zero(); Q];
            for (q, v) in xt.iter_mut().enumerate() {
                *v = X::mul(X::load(pt.add(X::N * q)), d);
                X::store(pt.add(X::N * q), *v);
            }
            for i in t + 1..p1 {
                let v = X::splat(col.add(i));
                let pi = xp.add(W * (nd.c0 + i));
                for (q, x) in xt.iter().enumerate() {
                    let y = X::fnmadd(v, *x, X::load(pi.add(X::N * q)));
                    X::store(pi.add(X::N * q), y);
                }
            }
        }
        if p1 < w {
            forward_update::<T, X, W, Q, _>(nd, p1, p0, p1 - p0, Run(nd.c0 + p1, w - p1), xp);
        }
        p0 = p1;
    }
}

/// L₁₁ᵀ Z = Y for a supernode's triangle, panels from the bottom: each panel first takes the
/// product with the rows already solved below it ([`backward_update`]), then is solved
/// column by column.
#[target_feature(enable = "avx2,fma")]
unsafe fn backward_triangle<T: Entry, X: Lanes<T>, const W: usize, const Q: usize>(
    nd: &Node<'_, T>,
    xp: *mut X,
) {
    let (w, ld) = (nd.w, nd.ld());
    assert!(w * ld <= nd.l.len());
    let mut p1 = w;
    while p1 > 0 {
        let p0 = p1.saturating_sub(PANEL);
        if p1 < w {
            backward_update::<T, X, W, Q, _>(nd, p1, p0, p1 - p0, Run(nd.c0 + p1, w - p1), xp);
        }
        for t in (p0..p1).rev() {
            let col = nd.l.as_ptr().add(t * ld);
            let pt = xp.add(W * (nd.c0 + t));
            let mut acc = [X::zero(); Q];
            for (q, a) in acc.iter_mut().enumerate() {
                *a = X::load(pt.add(X::N * q));
            }
            for i in t + 1..p1 {
                let v = X::splat(col.add(i));
                let pi = xp.add(W * (nd.c0 + i));
                for (q, a) in acc.iter_mut().enumerate() {
                    *a = X::fnmadd(v, X::load(pi.add(X::N * q)), *a);
                }
            }
            let d = X::inv(col.add(t));
            for (q, a) in acc.iter().enumerate() {
                X::store(pt.add(X::N * q), X::mul(*a, d));
            }
        }
        p1 = p0;
    }
}
