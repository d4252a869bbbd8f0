//! Blocks of a few columns held row by row: the layout of the SIMD kernels (sparse products,
//! supernodal solves), where every row of an n × k block is one aligned array of `W ≥ k` lanes.

use faer::{MatMut, MatRef};

/// A row of `W` lanes (zero-padded past the block's columns), aligned so that AVX2 loads of its
/// 4-lane groups never split a cache line (unaligned rows measured up to 1.6× slower).
#[derive(Clone, Copy)]
#[repr(C, align(32))]
pub(crate) struct Row<const W: usize>(pub(crate) [f64; W]);

impl<const W: usize> Row<W> {
    pub(crate) const ZERO: Self = Row([0.0; W]);
}

/// Rows of `x` (k ≤ W columns): `rows[i] = x[perm[i], ..]` with a permutation `perm[new] = old`,
/// else `rows[i] = x[i, ..]`.
pub(crate) fn to_rows<const W: usize>(x: MatRef<'_, f64>, perm: Option<&[usize]>) -> Vec<Row<W>> {
    assert!(x.ncols() <= W);
    let mut rows = vec![Row::<W>::ZERO; x.nrows()];
    for c in 0..x.ncols() {
        let col = x.col(c);
        match perm {
            Some(p) => {
                for (row, &old) in rows.iter_mut().zip(p) {
                    row.0[c] = col[old];
                }
            }
            None => {
                for (row, v) in rows.iter_mut().zip(col.iter()) {
                    row.0[c] = *v;
                }
            }
        }
    }
    rows
}

/// The inverse of [`to_rows`]: `x[perm[i], ..] = rows[i]` (or `x[i, ..] = rows[i]`), the first
/// `x.ncols()` lanes.
pub(crate) fn from_rows<const W: usize>(
    rows: &[Row<W>],
    mut x: MatMut<'_, f64>,
    perm: Option<&[usize]>,
) {
    assert!(x.ncols() <= W && rows.len() == x.nrows());
    for c in 0..x.ncols() {
        let mut col = x.as_mut().col_mut(c);
        match perm {
            Some(p) => {
                for (row, &old) in rows.iter().zip(p) {
                    col[old] = row.0[c];
                }
            }
            None => {
                for (row, v) in rows.iter().zip(col.iter_mut()) {
                    *v = row.0[c];
                }
            }
        }
    }
}
