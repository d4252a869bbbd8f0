//! Products of a tall n × p basis with thin n × k blocks: D = AᵀB and W += α·A·D, the two halves
//! of a block Gram–Schmidt pass in the eigensolver (and the small basis changes of its M-QR).
//!
//! Both are bound by reading A once from memory; faer's general products reached 2.6–3.6 GB/s on
//! these shapes on this project's machine (n = 69k, p = 90, k = 6), a third of a plain streaming
//! read. These kernels walk A in row blocks small enough that the rows of the thin operand stay
//! in L1 while every column of A is streamed through it once. AVX2/FMA when the CPU has them
//! (checked at run time), faer's products otherwise or for strided views.

use faer::{Accum, Mat, MatMut, MatRef, Par};

/// Rows per block: the block's rows of the thin operand (≤ 16 columns × 512 rows × 8 bytes =
/// 64 KiB, 32 KiB for the usual 8) stay in L1/L2 while the columns of A stream past.
const ROW_BLOCK: usize = 512;

/// Columns of the thin operand per kernel pass.
const MAX_THIN: usize = 8;

/// Where to split n rows for two threads, if at all ([`super::rows_on_two_threads`]: the
/// Gram–Schmidt passes were the eigen phase's largest sequential part once the solves ran on two
/// threads): at a multiple of the row block, so that every row is computed as on one thread.
fn halves(n: usize) -> Option<usize> {
    super::rows_on_two_threads(n).then_some(n / 2 / ROW_BLOCK * ROW_BLOCK)
}

/// D = Aᵀ B (A n × p, B n × k).
pub fn at_b(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Mat<f64> {
    assert_eq!(a.nrows(), b.nrows());
    if let Some(h) = halves(a.nrows()) {
        let n = a.nrows();
        let (d1, d2) = rayon::join(
            || at_b_seq(a.subrows(0, h), b.subrows(0, h)),
            || at_b_seq(a.subrows(h, n - h), b.subrows(h, n - h)),
        );
        return d1 + d2;
    }
    at_b_seq(a, b)
}

/// [`at_b`] on one thread.
fn at_b_seq(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Mat<f64> {
    let mut d = Mat::<f64>::zeros(a.ncols(), b.ncols());
    #[cfg(target_arch = "x86_64")]
    {
        if simd_ok(&[a, b]) {
            let mut c0 = 0;
            while c0 < b.ncols() {
                let k = (b.ncols() - c0).min(MAX_THIN);
                let bs = b.subcols(c0, k);
                let ds = d.as_mut().subcols_mut(c0, k);
                // SAFETY: AVX2 and FMA are present and every column is contiguous (`simd_ok`);
                // the kernel stays inside the columns' n rows.
                unsafe { avx2::at_b_dispatch(a, bs, ds) };
                c0 += k;
            }
            return d;
        }
    }
    faer::linalg::matmul::matmul(d.as_mut(), Accum::Replace, a.transpose(), b, 1.0, Par::Seq);
    d
}

/// W += α A D (W n × k, A n × p, D p × k).
pub fn add_a_d(w: MatMut<'_, f64>, a: MatRef<'_, f64>, d: MatRef<'_, f64>, alpha: f64) {
    assert!(w.nrows() == a.nrows() && a.ncols() == d.nrows() && d.ncols() == w.ncols());
    if let Some(h) = halves(a.nrows()) {
        let n = a.nrows();
        let (w1, w2) = w.split_at_row_mut(h);
        rayon::join(
            || add_a_d_seq(w1, a.subrows(0, h), d, alpha),
            || add_a_d_seq(w2, a.subrows(h, n - h), d, alpha),
        );
        return;
    }
    add_a_d_seq(w, a, d, alpha);
}

/// [`add_a_d`] on one thread.
fn add_a_d_seq(mut w: MatMut<'_, f64>, a: MatRef<'_, f64>, d: MatRef<'_, f64>, alpha: f64) {
    #[cfg(target_arch = "x86_64")]
    {
        if simd_ok(&[a, w.as_ref()]) {
            let mut c0 = 0;
            while c0 < w.ncols() {
                let k = (w.ncols() - c0).min(MAX_THIN);
                let ws = w.as_mut().subcols_mut(c0, k);
                // SAFETY: as in `at_b`.
                unsafe { avx2::add_a_d_dispatch(ws, a, d.subcols(c0, k), alpha) };
                c0 += k;
            }
            return;
        }
    }
    faer::linalg::matmul::matmul(w, Accum::Add, a, d, alpha, Par::Seq);
}

/// Rows per block of [`mul_in_place`]: its scratch is this × k (0.7 MB for k = 22).
const IN_PLACE_ROWS: usize = 4096;

/// V[:, ..k] = V[:, ..p] · Y (Y p × k, k ≤ p ≤ V's columns) in place, by blocks of rows: a row
/// of the product needs only the same row of V, so no n × k temporary is made (the thick
/// restart's V·Y_k was the eigen phase's peak, issue 22). Columns k.. of V are left as they were.
pub fn mul_in_place(mut v: MatMut<'_, f64>, y: MatRef<'_, f64>) {
    let (n, p, k) = (v.nrows(), y.nrows(), y.ncols());
    assert!(k <= p && p <= v.ncols());
    let par = faer::get_global_parallelism();
    let mut tmp = Mat::<f64>::zeros(IN_PLACE_ROWS.min(n), k);
    let mut r0 = 0;
    while r0 < n {
        let h = (n - r0).min(IN_PLACE_ROWS);
        let mut t = tmp.as_mut().subrows_mut(0, h);
        faer::linalg::matmul::matmul(
            t.as_mut(),
            Accum::Replace,
            v.as_ref().submatrix(r0, 0, h, p),
            y,
            1.0,
            par,
        );
        v.as_mut().submatrix_mut(r0, 0, h, k).copy_from(t.as_ref());
        r0 += h;
    }
}

/// AVX2/FMA present and all matrices stored with contiguous columns.
#[cfg(target_arch = "x86_64")]
fn simd_ok(ms: &[MatRef<'_, f64>]) -> bool {
    is_x86_feature_detected!("avx2")
        && is_x86_feature_detected!("fma")
        && ms.iter().all(|m| m.nrows() == 0 || m.row_stride() == 1)
}

#[cfg(target_arch = "x86_64")]
// the tile loops index several arrays of the same const length in lockstep
#[allow(clippy::needless_range_loop)]
mod avx2 {
    //! Every function requires AVX2 and FMA and matrices whose columns are contiguous (row
    //! stride 1), which the callers check.

    use super::ROW_BLOCK;
    use faer::{MatMut, MatRef};
    use std::arch::x86_64::*;

    pub(super) unsafe fn at_b_dispatch(a: MatRef<'_, f64>, b: MatRef<'_, f64>, d: MatMut<'_, f64>) {
        match b.ncols() {
            1 => at_b::<1>(a, b, d),
            2 => at_b::<2>(a, b, d),
            3 => at_b::<3>(a, b, d),
            4 => at_b::<4>(a, b, d),
            5 => at_b::<5>(a, b, d),
            6 => at_b::<6>(a, b, d),
            7 => at_b::<7>(a, b, d),
            _ => at_b::<8>(a, b, d),
        }
    }

    pub(super) unsafe fn add_a_d_dispatch(
        w: MatMut<'_, f64>,
        a: MatRef<'_, f64>,
        d: MatRef<'_, f64>,
        alpha: f64,
    ) {
        match w.ncols() {
            1 => add_a_d::<1>(w, a, d, alpha),
            2 => add_a_d::<2>(w, a, d, alpha),
            3 => add_a_d::<3>(w, a, d, alpha),
            4 => add_a_d::<4>(w, a, d, alpha),
            5 => add_a_d::<5>(w, a, d, alpha),
            6 => add_a_d::<6>(w, a, d, alpha),
            7 => add_a_d::<7>(w, a, d, alpha),
            _ => add_a_d::<8>(w, a, d, alpha),
        }
    }

    #[inline(always)]
    unsafe fn hsum(v: __m256d) -> f64 {
        let lo = _mm256_castpd256_pd128(v);
        let hi = _mm256_extractf128_pd(v, 1);
        let s = _mm_add_pd(lo, hi);
        _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)))
    }

    /// D = AᵀB with K = b.ncols(): per row block, CA columns of A at a time against the K
    /// columns of B (CA·K accumulators of 4 rows; CA = 2 shares every load of B between two
    /// columns of A while the accumulators fit the 16 registers), reduced into D.
    #[target_feature(enable = "avx2,fma")]
    unsafe fn at_b<const K: usize>(a: MatRef<'_, f64>, b: MatRef<'_, f64>, mut d: MatMut<'_, f64>) {
        let (n, p) = (a.nrows(), a.ncols());
        if n == 0 {
            return;
        }
        let mut r0 = 0;
        while r0 < n {
            let r1 = (r0 + ROW_BLOCK).min(n);
            let mut c = 0;
            if K <= 6 {
                while c + 2 <= p {
                    at_b_tile::<K, 2>(a, b, d.as_mut(), c, r0, r1);
                    c += 2;
                }
            }
            while c < p {
                at_b_tile::<K, 1>(a, b, d.as_mut(), c, r0, r1);
                c += 1;
            }
            r0 = r1;
        }
    }

    #[inline(always)]
    unsafe fn at_b_tile<const K: usize, const CA: usize>(
        a: MatRef<'_, f64>,
        b: MatRef<'_, f64>,
        mut d: MatMut<'_, f64>,
        c: usize,
        r0: usize,
        r1: usize,
    ) {
        let bc: [*const f64; K] = std::array::from_fn(|j| b.col(j).as_ptr());
        let ac: [*const f64; CA] = std::array::from_fn(|m| a.col(c + m).as_ptr());
        let full = r0 + (r1 - r0) / 4 * 4;
        let mut acc = [[_mm256_setzero_pd(); K]; CA];
        let mut i = r0;
        while i < full {
            let av: [__m256d; CA] = std::array::from_fn(|m| _mm256_loadu_pd(ac[m].add(i)));
            for j in 0..K {
                let bv = _mm256_loadu_pd(bc[j].add(i));
                for m in 0..CA {
                    acc[m][j] = _mm256_fmadd_pd(av[m], bv, acc[m][j]);
                }
            }
            i += 4;
        }
        for m in 0..CA {
            for j in 0..K {
                let mut s = hsum(acc[m][j]);
                for t in full..r1 {
                    s += *ac[m].add(t) * *bc[j].add(t);
                }
                d[(c + m, j)] += s;
            }
        }
    }

    /// W += α A D with K = w.ncols(): per row block, CT = 4 columns of A at a time update the
    /// block's rows of W (which stay in L1; α D's entries are broadcast from memory).
    #[target_feature(enable = "avx2,fma")]
    unsafe fn add_a_d<const K: usize>(
        mut w: MatMut<'_, f64>,
        a: MatRef<'_, f64>,
        d: MatRef<'_, f64>,
        alpha: f64,
    ) {
        let (n, p) = (a.nrows(), a.ncols());
        if n == 0 || p == 0 {
            return;
        }
        // α D row by row (p × K, row-major) so that a column of A meets K consecutive entries
        let dr: Vec<f64> = (0..p)
            .flat_map(|c| (0..K).map(move |j| alpha * d[(c, j)]))
            .collect();
        let wc: [*mut f64; K] = std::array::from_fn(|j| w.as_mut().col_mut(j).as_ptr_mut());
        let mut r0 = 0;
        while r0 < n {
            let r1 = (r0 + ROW_BLOCK).min(n);
            let mut c = 0;
            while c + 4 <= p {
                add_a_d_tile::<K, 4>(a, &dr, wc, c, r0, r1);
                c += 4;
            }
            match p - c {
                3 => add_a_d_tile::<K, 3>(a, &dr, wc, c, r0, r1),
                2 => add_a_d_tile::<K, 2>(a, &dr, wc, c, r0, r1),
                1 => add_a_d_tile::<K, 1>(a, &dr, wc, c, r0, r1),
                _ => {}
            }
            r0 = r1;
        }
    }

    #[inline(always)]
    unsafe fn add_a_d_tile<const K: usize, const CT: usize>(
        a: MatRef<'_, f64>,
        dr: &[f64],
        wc: [*mut f64; K],
        c: usize,
        r0: usize,
        r1: usize,
    ) {
        let ac: [*const f64; CT] = std::array::from_fn(|m| a.col(c + m).as_ptr());
        let dc = dr.as_ptr().add(c * K);
        let full = r0 + (r1 - r0) / 4 * 4;
        let mut i = r0;
        while i < full {
            let av: [__m256d; CT] = std::array::from_fn(|m| _mm256_loadu_pd(ac[m].add(i)));
            for j in 0..K {
                let mut x = _mm256_loadu_pd(wc[j].add(i));
                for m in 0..CT {
                    let dv = _mm256_broadcast_sd(&*dc.add(m * K + j));
                    x = _mm256_fmadd_pd(av[m], dv, x);
                }
                _mm256_storeu_pd(wc[j].add(i), x);
            }
            i += 4;
        }
        for t in full..r1 {
            for j in 0..K {
                let mut x = *wc[j].add(t);
                for m in 0..CT {
                    x += *ac[m].add(t) * *dc.add(m * K + j);
                }
                *wc[j].add(t) = x;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mat(n: usize, k: usize, seed: u64) -> Mat<f64> {
        crate::solve::eigen::random_block(n, k, &mut { seed })
    }

    /// On two threads (rows split in halves, from SPLIT_ROWS rows) both kernels give faer's
    /// products, W += αAD exactly the one-thread result (rows are independent) and D = AᵀB the
    /// one-thread result to rounding (the halves are summed).
    #[test]
    fn thin_products_on_two_threads_equal_one_thread() {
        let (n, p, k) = (crate::solve::SPLIT_ROWS + 37, 9, 6);
        let (a, b, d) = (mat(n, p, 3), mat(n, k, 5), mat(p, k, 9));
        let run = |par| {
            let _g = crate::solve::ParGuard::new(par);
            let mut w = b.clone();
            add_a_d(w.as_mut(), a.as_ref(), d.as_ref(), -0.5);
            (at_b(a.as_ref(), b.as_ref()), w)
        };
        let (d1, w1) = run(Par::Seq);
        let (d2, w2) = run(Par::rayon(2));
        assert_eq!(w1, w2);
        let dref = a.transpose() * &b;
        assert!((&d2 - &dref).norm_max() <= 1e-12 * n as f64);
        assert!((&d1 - &d2).norm_max() <= 1e-13 * n as f64);
        let wref = &b - (&a * &d) * faer::Scale(0.5);
        assert!((&w2 - &wref).norm_max() <= 1e-13 * p as f64);
    }

    /// Both kernels against faer's products, for thin widths 1…13 (two passes above 8), row
    /// counts that are not multiples of 4 or of the row block, and column views of a wider matrix.
    #[test]
    fn thin_products_equal_faer() {
        for (n, p) in [(1, 1), (7, 3), (1029, 5), (2 * ROW_BLOCK + 3, 17)] {
            let wide = mat(n, p + 2, 1);
            let a = wide.as_ref().subcols(1, p);
            for k in [1, 2, 3, 4, 5, 6, 7, 8, 13] {
                let b = mat(n, k, 7 + k as u64);
                let d = at_b(a, b.as_ref());
                let dref = a.transpose() * &b;
                let scale = n as f64;
                assert!(
                    (&d - &dref).norm_max() <= 1e-13 * scale,
                    "AtB n={n} p={p} k={k}"
                );
                let dd = mat(p, k, 99);
                let mut w = b.clone();
                add_a_d(w.as_mut(), a, dd.as_ref(), -0.5);
                let wref = &b - a * &dd * faer::Scale(0.5);
                assert!(
                    (&w - &wref).norm_max() <= 1e-13 * p as f64,
                    "W+aAD n={n} p={p} k={k}"
                );
            }
        }
    }

    /// The in-place product equals faer's V·Y on row counts around the row block, leaves the
    /// columns past k alone, and handles k = p and k = 0.
    #[test]
    fn in_place_product_equals_faer() {
        for (n, p, k) in [
            (5, 3, 2),
            (IN_PLACE_ROWS + 17, 9, 4),
            (2 * IN_PLACE_ROWS, 6, 6),
            (10, 4, 0),
        ] {
            let v0 = mat(n, p + 2, 3);
            let y = mat(p, k, 11);
            let want = v0.as_ref().subcols(0, p) * &y;
            let mut v = v0.clone();
            mul_in_place(v.as_mut(), y.as_ref());
            let got = v.as_ref().subcols(0, k);
            assert!(
                (got - &want).norm_max() <= 1e-13 * p as f64,
                "n={n} p={p} k={k}"
            );
            assert_eq!(
                v.as_ref().subcols(k, p + 2 - k),
                v0.as_ref().subcols(k, p + 2 - k)
            );
        }
    }
}
