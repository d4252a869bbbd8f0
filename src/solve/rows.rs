//! Blocks of a few columns held row by row: the layout of the SIMD kernels (sparse products,
//! supernodal solves), where every row of an n × k block is one aligned array of `W ≥ k` lanes.

use faer::{MatMut, MatRef};

/// The element of a row: f64, or f32 for the single-precision solves of a mixed factor.
pub(crate) trait Lane: Copy + Send + Sync + 'static {
    const ZERO: Self;
    fn from_f64(v: f64) -> Self;
    fn to_f64(self) -> f64;
}

impl Lane for f64 {
    const ZERO: Self = 0.0;
    #[inline(always)]
    fn from_f64(v: f64) -> Self {
        v
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
}

impl Lane for f32 {
    const ZERO: Self = 0.0;
    #[inline(always)]
    fn from_f64(v: f64) -> Self {
        v as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
}

/// A row of `W` lanes (zero-padded past the block's columns), aligned so that AVX2 loads of its
/// 32-byte groups never split a cache line (unaligned rows measured up to 1.6× slower).
#[derive(Clone, Copy)]
#[repr(C, align(32))]
pub(crate) struct Row<const W: usize, E = f64>(pub(crate) [E; W]);

impl<const W: usize, E: Lane> Row<W, E> {
    pub(crate) const ZERO: Self = Row([E::ZERO; W]);
}

/// Rows of `x` (k ≤ W columns): `rows[i] = x[perm[i], ..]` with a permutation `perm[new] = old`,
/// else `rows[i] = x[i, ..]`, rounded to `E`.
pub(crate) fn to_rows<const W: usize, E: Lane>(
    x: MatRef<'_, f64>,
    perm: Option<&[usize]>,
) -> Vec<Row<W, E>> {
    assert!(x.ncols() <= W);
    let mut rows = vec![Row::<W, E>::ZERO; x.nrows()];
    for c in 0..x.ncols() {
        let col = x.col(c);
        match perm {
            Some(p) => {
                for (row, &old) in rows.iter_mut().zip(p) {
                    row.0[c] = E::from_f64(col[old]);
                }
            }
            None => {
                for (row, v) in rows.iter_mut().zip(col.iter()) {
                    row.0[c] = E::from_f64(*v);
                }
            }
        }
    }
    rows
}

/// The inverse of [`to_rows`]: `x[perm[i], ..] = rows[i]` (or `x[i, ..] = rows[i]`), the first
/// `x.ncols()` lanes.
pub(crate) fn from_rows<const W: usize, E: Lane>(
    rows: &[Row<W, E>],
    mut x: MatMut<'_, f64>,
    perm: Option<&[usize]>,
) {
    assert!(x.ncols() <= W && rows.len() == x.nrows());
    for c in 0..x.ncols() {
        let mut col = x.as_mut().col_mut(c);
        match perm {
            Some(p) => {
                for (row, &old) in rows.iter().zip(p) {
                    col[old] = row.0[c].to_f64();
                }
            }
            None => {
                for (row, v) in rows.iter().zip(col.iter_mut()) {
                    *v = row.0[c].to_f64();
                }
            }
        }
    }
}
