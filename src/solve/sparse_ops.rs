//! Small sparse kernels the solvers need: Y = A·X for a full symmetric CSC matrix, the combination
//! K − σM on the union pattern, sub-matrices by index lists, and dense conversions.

use super::SolveError;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Mat, MatMut, MatRef};

/// Y = A X (A stored in full, column by column).
pub fn spmm(a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let mut y = Mat::<f64>::zeros(a.nrows(), x.ncols());
    spmm_into(a, x, y.as_mut());
    y
}

/// Y = A X into an existing matrix (overwritten). One pass over A for up to [`SPMM_CHUNK`]
/// columns of X: they are copied to row-major rows zero-padded to a width of 4, 8, 12 or 16, so
/// that every stored a_ij updates one contiguous, SIMD-friendly row of Y (faer's kernel passes
/// over A once per column of X: 2.5× slower on a 20k-dof tet10 mass matrix with 6 columns; the
/// vectorized rows took the kernel's share of a 20k-dof eigen run from 8.4 % to 4.6 %).
pub fn spmm_into(a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
    let b = x.ncols();
    if b == 1 {
        faer::sparse::linalg::matmul::sparse_dense_matmul(
            y,
            faer::Accum::Replace,
            a,
            x,
            1.0,
            faer::Par::Seq,
        );
        return;
    }
    let mut c0 = 0;
    while c0 < b {
        let w = (b - c0).min(SPMM_CHUNK);
        let xs = x.subcols(c0, w);
        let ys = y.as_mut().subcols_mut(c0, w);
        lanes_dispatch::<false>(a, xs, ys);
        c0 += w;
    }
}

/// [`spmm_lanes`] for the lane count `x` needs, compiled for AVX2+FMA when the CPU has them
/// (the default x86-64 target only allows SSE2, which left the lanes scalar).
fn lanes_dispatch<const ABS: bool>(
    a: SparseColMatRef<'_, usize, f64>,
    x: MatRef<'_, f64>,
    y: MatMut<'_, f64>,
) {
    #[cfg(target_arch = "x86_64")]
    {
        if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
            // SAFETY: the CPU supports the features `spmm_lanes_avx2` is compiled for (checked
            // just above); the function is otherwise plain safe Rust.
            unsafe {
                match x.ncols().div_ceil(4) {
                    1 => spmm_lanes_avx2::<4, ABS>(a, x, y),
                    2 => spmm_lanes_avx2::<8, ABS>(a, x, y),
                    3 => spmm_lanes_avx2::<12, ABS>(a, x, y),
                    _ => spmm_lanes_avx2::<16, ABS>(a, x, y),
                }
            }
            return;
        }
    }
    match x.ncols().div_ceil(4) {
        1 => spmm_lanes::<4, ABS>(a, x, y),
        2 => spmm_lanes::<8, ABS>(a, x, y),
        3 => spmm_lanes::<12, ABS>(a, x, y),
        _ => spmm_lanes::<16, ABS>(a, x, y),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn spmm_lanes_avx2<const W: usize, const ABS: bool>(
    a: SparseColMatRef<'_, usize, f64>,
    x: MatRef<'_, f64>,
    y: MatMut<'_, f64>,
) {
    spmm_lanes::<W, ABS>(a, x, y)
}

/// Y = A X (or |A| |X| when `ABS`) for at most W columns, rows of X and Y held as zero-padded
/// arrays of W (flat arrays: LLVM vectorizes them, nested lanes it left scalar).
#[inline(always)]
fn spmm_lanes<const W: usize, const ABS: bool>(
    a: SparseColMatRef<'_, usize, f64>,
    x: MatRef<'_, f64>,
    mut y: MatMut<'_, f64>,
) {
    let w = x.ncols();
    let mut xr = vec![[0.0f64; W]; a.ncols()];
    for c in 0..w {
        for (row, &v) in xr.iter_mut().zip(x.col(c).iter()) {
            row[c] = if ABS { v.abs() } else { v };
        }
    }
    let mut yr = vec![[0.0f64; W]; a.nrows()];
    for (j, xj) in xr.iter().enumerate() {
        if xj.iter().all(|&v| v == 0.0) {
            continue;
        }
        column_update::<W, ABS>(a.row_idx_of_col_raw(j), a.val_of_col(j), xj, &mut yr);
    }
    for c in 0..w {
        for (yv, row) in y.as_mut().col_mut(c).iter_mut().zip(&yr) {
            *yv = row[c];
        }
    }
}

/// y_i += a_ij x_j over the stored entries of one column (separate arguments, so that LLVM knows
/// `xj` and `yr` do not alias and vectorizes the row update).
#[inline(always)]
fn column_update<const W: usize, const ABS: bool>(
    rows: &[usize],
    vals: &[f64],
    xj: &[f64; W],
    yr: &mut [[f64; W]],
) {
    for (&i, &v) in rows.iter().zip(vals) {
        let v = if ABS { v.abs() } else { v };
        let yi = &mut yr[i];
        for t in 0..W {
            yi[t] += v * xj[t];
        }
    }
}

/// Columns of X per pass of [`spmm_into`] (row-major copies of n × 16 stay small).
pub const SPMM_CHUNK: usize = 16;

/// A = K + s·M on the union of both patterns.
pub fn add_scaled(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    s: f64,
) -> Result<SparseColMat<usize, f64>, SolveError> {
    let n = k.nrows();
    let mut trips = Vec::with_capacity(k.compute_nnz() + m.compute_nnz());
    for j in 0..n {
        for (&i, &v) in k.row_idx_of_col_raw(j).iter().zip(k.val_of_col(j)) {
            trips.push(Triplet::new(i, j, v));
        }
        if s != 0.0 {
            for (&i, &v) in m.row_idx_of_col_raw(j).iter().zip(m.val_of_col(j)) {
                trips.push(Triplet::new(i, j, s * v));
            }
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &trips)
        .map_err(|e| SolveError::Dimension(format!("K + sM: {e:?}")))
}

/// The symmetric sub-matrix A[rows, cols] as a sparse matrix (`rows`, `cols` are index lists).
pub fn submatrix(
    a: SparseColMatRef<'_, usize, f64>,
    rows: &[usize],
    cols: &[usize],
) -> Result<SparseColMat<usize, f64>, SolveError> {
    let mut pos = vec![usize::MAX; a.nrows()];
    for (r, &i) in rows.iter().enumerate() {
        pos[i] = r;
    }
    let mut trips = Vec::new();
    for (c, &j) in cols.iter().enumerate() {
        for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
            if pos[i] != usize::MAX {
                trips.push(Triplet::new(pos[i], c, v));
            }
        }
    }
    SparseColMat::try_new_from_triplets(rows.len(), cols.len(), &trips)
        .map_err(|e| SolveError::Dimension(format!("sub-matrix: {e:?}")))
}

/// Dense copy of a sparse matrix.
pub fn to_dense(a: SparseColMatRef<'_, usize, f64>) -> Mat<f64> {
    let mut d = Mat::<f64>::zeros(a.nrows(), a.ncols());
    for j in 0..a.ncols() {
        for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
            d[(i, j)] += v;
        }
    }
    d
}

/// Sparse matrix from a dense one (entries that are exactly zero are dropped).
pub fn from_dense(d: MatRef<'_, f64>) -> SparseColMat<usize, f64> {
    let mut trips = Vec::new();
    for j in 0..d.ncols() {
        for i in 0..d.nrows() {
            if d[(i, j)] != 0.0 {
                trips.push(Triplet::new(i, j, d[(i, j)]));
            }
        }
    }
    // Cannot fail: every index is inside the declared shape.
    SparseColMat::try_new_from_triplets(d.nrows(), d.ncols(), &trips).expect("indices in range")
}

/// Multiple of ε·max_j (|Φ|ᵀ|K||Φ|)_jj / max ω² that rounding alone may leave in ΦᵀKΦ (the
/// floating-point bound is γ_n·(|Φ|ᵀ|K||Φ|); 1e3 stands for the usual √n growth). Checks of
/// ‖ΦᵀKΦ − diag‖/max ω² are raised to this floor when it exceeds their fixed limit.
pub const ROUNDING_FACTOR: f64 = 1e3;

/// max_j (|Φ|ᵀ|K||Φ|)_jj: the strain energy of each vector summed without cancellation. Equal to
/// φᵀKφ up to a modest factor for a homogeneous body, but up to the stiffness contrast larger
/// when a near-rigid part moves rigidly (its large entries cancel in Kφ) — the scale of the
/// rounding error of ΦᵀKΦ (docs/stability.md, row 7).
pub fn abs_energy(k: SparseColMatRef<'_, usize, f64>, phi: MatRef<'_, f64>) -> f64 {
    abs_products(k, phi).0.into_iter().fold(0.0, f64::max)
}

/// Per column j of Φ: ((|Φ|ᵀ|K||Φ|)_jj, ‖|K||φ_j|‖₂) — the rounding scales of φᵀKφ and of Kφ.
pub fn abs_products(
    k: SparseColMatRef<'_, usize, f64>,
    phi: MatRef<'_, f64>,
) -> (Vec<f64>, Vec<f64>) {
    let (n, c) = (phi.nrows(), phi.ncols());
    let mut energy = vec![0.0; c];
    let mut norm = vec![0.0; c];
    let mut y = Mat::<f64>::zeros(k.nrows(), c.min(SPMM_CHUNK));
    let mut c0 = 0;
    while c0 < c {
        let w = (c - c0).min(SPMM_CHUNK);
        let ys = y.as_mut().subcols_mut(0, w);
        lanes_dispatch::<true>(k, phi.subcols(c0, w), ys);
        for t in 0..w {
            let yc = y.col(t);
            energy[c0 + t] = (0..n).map(|r| yc[r] * phi[(r, c0 + t)].abs()).sum();
            norm[c0 + t] = yc.iter().map(|v| v * v).sum::<f64>().sqrt();
        }
        c0 += w;
    }
    (energy, norm)
}
