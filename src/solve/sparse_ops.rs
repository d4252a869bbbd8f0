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

/// Y = A X into an existing matrix (overwritten), faer's sparse × dense kernel.
pub fn spmm_into(a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>, y: MatMut<'_, f64>) {
    faer::sparse::linalg::matmul::sparse_dense_matmul(
        y,
        faer::Accum::Replace,
        a,
        x,
        1.0,
        faer::Par::Seq,
    );
}

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
