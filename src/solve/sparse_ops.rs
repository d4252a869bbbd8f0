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

/// Y = A X into an existing matrix (overwritten). One pass over A for all columns of X: X is
/// copied to row-major blocks of up to [`SPMM_CHUNK`] columns so that every stored a_ij updates a
/// contiguous row of Y (faer's kernel passes over A once per column of X: 2.5× slower on a 20k-dof
/// tet10 mass matrix with 6 columns).
pub fn spmm_into(a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
    let (n, b) = (a.nrows(), x.ncols());
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
        let mut xr = vec![0.0; a.ncols() * w];
        for c in 0..w {
            for (j, &v) in x.col(c0 + c).iter().enumerate() {
                xr[j * w + c] = v;
            }
        }
        let mut yr = vec![0.0; n * w];
        for j in 0..a.ncols() {
            let xj = &xr[j * w..j * w + w];
            if xj.iter().all(|&v| v == 0.0) {
                continue;
            }
            for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
                for (yi, &xv) in yr[i * w..i * w + w].iter_mut().zip(xj) {
                    *yi += v * xv;
                }
            }
        }
        for c in 0..w {
            for (i, yv) in y.as_mut().col_mut(c0 + c).iter_mut().enumerate() {
                *yv = yr[i * w + c];
            }
        }
        c0 += w;
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
    let mut energy = vec![0.0; phi.ncols()];
    let mut norm = vec![0.0; phi.ncols()];
    let mut y = vec![0.0; k.nrows()];
    for j in 0..phi.ncols() {
        y.iter_mut().for_each(|v| *v = 0.0);
        for c in 0..k.ncols() {
            let pc = phi[(c, j)].abs();
            if pc == 0.0 {
                continue;
            }
            for (r, v) in k.row_idx_of_col(c).zip(k.val_of_col(c)) {
                y[r] += v.abs() * pc;
            }
        }
        energy[j] = (0..k.nrows()).map(|r| y[r] * phi[(r, j)].abs()).sum();
        norm[j] = y.iter().map(|v| v * v).sum::<f64>().sqrt();
    }
    (energy, norm)
}
