//! Small sparse kernels the solvers need: Y = A·X for a full symmetric CSC matrix, the combination
//! K − σM on the union pattern, sub-matrices by index lists, and dense conversions.

use super::rows::{self, Row};
use super::SolveError;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Mat, MatMut, MatRef};

/// Y = A X for a symmetric A stored in full (both triangles), as K and M always are here.
pub fn spmm(a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let mut y = Mat::<f64>::zeros(a.nrows(), x.ncols());
    spmm_into(a, x, y.as_mut());
    y
}

/// Y = A X into an existing matrix (overwritten), A symmetric and stored in full.
///
/// Up to [`SPMM_CHUNK`] columns of X per pass over A, copied to aligned rows of 4, 8, 12 or 16
/// lanes. By symmetry column j of A is row j, so y_j = Σ_i a_ij x_i is gathered in registers and
/// stored once: no scattered read-modify-write of Y (for 6 columns of a 69k-dof tet10 matrix
/// with 5.4M entries the scatter form, y_i += a_ij x_j, took 33 ms here, the gather form 21 ms).
/// A single column goes to faer's product.
pub fn spmm_into(a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
    debug_assert_eq!(
        a.nrows(),
        a.ncols(),
        "spmm needs a square (symmetric) matrix"
    );
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

/// The gather product for the lane count `x` needs (or |A| |X| when `ABS`).
fn lanes_dispatch<const ABS: bool>(
    a: SparseColMatRef<'_, usize, f64>,
    x: MatRef<'_, f64>,
    y: MatMut<'_, f64>,
) {
    match x.ncols() {
        0..=4 => gather_lanes::<4, 1, ABS>(a, x, y),
        5..=8 => gather_lanes::<8, 2, ABS>(a, x, y),
        9..=12 => gather_lanes::<12, 3, ABS>(a, x, y),
        _ => gather_lanes::<16, 4, ABS>(a, x, y),
    }
}

/// `W = 4·Q` lanes: rows of X in, rows of Y out.
fn gather_lanes<const W: usize, const Q: usize, const ABS: bool>(
    a: SparseColMatRef<'_, usize, f64>,
    x: MatRef<'_, f64>,
    y: MatMut<'_, f64>,
) {
    let mut xr = rows::to_rows::<W, f64>(x, None);
    if ABS {
        for r in xr.iter_mut() {
            r.0 = r.0.map(f64::abs);
        }
    }
    let mut yr = vec![Row::<W>::ZERO; a.ncols()];
    #[cfg(target_arch = "x86_64")]
    {
        if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
            let n = yr.len();
            // the output rows are independent: two halves on two threads under faer's global
            // parallelism (the products with M and K of the eigen phase and the refinement)
            if super::rows_on_two_threads(n) {
                let (y1, y2) = yr.split_at_mut(n / 2);
                let xr = &xr;
                rayon::join(
                    // SAFETY: as below, for the columns 0..n/2 and n/2..n.
                    || unsafe { gather_avx2::<W, Q, ABS>(a, xr, y1, 0) },
                    || unsafe { gather_avx2::<W, Q, ABS>(a, xr, y2, n / 2) },
                );
            } else {
                // SAFETY: the CPU has AVX2 and FMA (checked just above); `xr` has one row per
                // row of A and `yr` one per column, which is what the kernel indexes.
                unsafe { gather_avx2::<W, Q, ABS>(a, &xr, &mut yr, 0) };
            }
            rows::from_rows(&yr, y, None);
            return;
        }
    }
    for (j, yj) in yr.iter_mut().enumerate() {
        for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
            let v = if ABS { v.abs() } else { v };
            for t in 0..W {
                yj.0[t] += v * xr[i].0[t];
            }
        }
    }
    rows::from_rows(&yr, y, None);
}

/// y_j = Σ_i a_ij x_i over the stored entries of column j (for the columns `j0..j0 + yr.len()`,
/// `yr[0]` holding column j0), two independent accumulators (the FMA latency, not the loads,
/// bounded a single chain).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[allow(clippy::needless_range_loop)] // lanes of two accumulators indexed in lockstep
unsafe fn gather_avx2<const W: usize, const Q: usize, const ABS: bool>(
    a: SparseColMatRef<'_, usize, f64>,
    xr: &[Row<W>],
    yr: &mut [Row<W>],
    j0: usize,
) {
    use std::arch::x86_64::*;
    assert!(xr.len() == a.nrows() && j0 + yr.len() <= a.ncols());
    let sign = _mm256_set1_pd(-0.0);
    let xp = xr.as_ptr() as *const f64;
    for (jj, yj) in yr.iter_mut().enumerate() {
        let j = j0 + jj;
        let rows = a.row_idx_of_col_raw(j);
        let vals = a.val_of_col(j);
        let nz = rows.len().min(vals.len());
        assert!(rows.iter().all(|&i| i < xr.len()));
        let mut acc0 = [_mm256_setzero_pd(); Q];
        let mut acc1 = [_mm256_setzero_pd(); Q];
        let mut t = 0;
        while t + 2 <= nz {
            let (i0, i1) = (*rows.get_unchecked(t), *rows.get_unchecked(t + 1));
            let mut v0 = _mm256_broadcast_sd(vals.get_unchecked(t));
            let mut v1 = _mm256_broadcast_sd(vals.get_unchecked(t + 1));
            if ABS {
                v0 = _mm256_andnot_pd(sign, v0);
                v1 = _mm256_andnot_pd(sign, v1);
            }
            for q in 0..Q {
                acc0[q] = _mm256_fmadd_pd(v0, _mm256_load_pd(xp.add(W * i0 + 4 * q)), acc0[q]);
                acc1[q] = _mm256_fmadd_pd(v1, _mm256_load_pd(xp.add(W * i1 + 4 * q)), acc1[q]);
            }
            t += 2;
        }
        if t < nz {
            let i0 = *rows.get_unchecked(t);
            let mut v0 = _mm256_broadcast_sd(vals.get_unchecked(t));
            if ABS {
                v0 = _mm256_andnot_pd(sign, v0);
            }
            for q in 0..Q {
                acc0[q] = _mm256_fmadd_pd(v0, _mm256_load_pd(xp.add(W * i0 + 4 * q)), acc0[q]);
            }
        }
        let out = yj.0.as_mut_ptr();
        for q in 0..Q {
            _mm256_store_pd(out.add(4 * q), _mm256_add_pd(acc0[q], acc1[q]));
        }
    }
}

/// Columns of X per pass of [`spmm_into`] (row-major copies of n × 16 stay small).
pub const SPMM_CHUNK: usize = 16;

/// A = K + s·M on the union of both patterns (K itself for s = 0).
///
/// Each column is a merge of the two sorted row lists (faer keeps rows sorted); building through
/// triplets instead sorted every entry again and took longer than METIS and the symbolic analysis
/// together on a 69k-dof tet10 model (5.4M entries).
pub fn add_scaled(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    s: f64,
) -> Result<SparseColMat<usize, f64>, SolveError> {
    let n = k.nrows();
    super::check_pair(k, m, "K + sM: ")?;
    let sorted = |a: SparseColMatRef<'_, usize, f64>| {
        (0..n).all(|j| a.row_idx_of_col_raw(j).windows(2).all(|w| w[0] < w[1]))
    };
    if !sorted(k) || !sorted(m) {
        return add_scaled_triplets(k, m, s);
    }
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::with_capacity(k.compute_nnz().max(m.compute_nnz()));
    let mut val = Vec::with_capacity(row_idx.capacity());
    col_ptr.push(0usize);
    for j in 0..n {
        let (kr, kv) = (k.row_idx_of_col_raw(j), k.val_of_col(j));
        let (mr, mv) = if s == 0.0 {
            (&[][..], &[][..])
        } else {
            (m.row_idx_of_col_raw(j), m.val_of_col(j))
        };
        let (mut a, mut b) = (0, 0);
        while a < kr.len() || b < mr.len() {
            let ra = kr.get(a).copied().unwrap_or(usize::MAX);
            let rb = mr.get(b).copied().unwrap_or(usize::MAX);
            let (r, v) = match ra.cmp(&rb) {
                std::cmp::Ordering::Less => {
                    a += 1;
                    (ra, kv[a - 1])
                }
                std::cmp::Ordering::Greater => {
                    b += 1;
                    (rb, s * mv[b - 1])
                }
                std::cmp::Ordering::Equal => {
                    a += 1;
                    b += 1;
                    (ra, kv[a - 1] + s * mv[b - 1])
                }
            };
            row_idx.push(r);
            val.push(v);
        }
        col_ptr.push(row_idx.len());
    }
    let symbolic = faer::sparse::SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    Ok(SparseColMat::new(symbolic, val))
}

/// [`add_scaled`] for matrices whose columns are not sorted: through triplets.
fn add_scaled_triplets(
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

/// The congruence Tᵀ A T of a symmetric A (n × n) with a rectangular T (n × r), e.g. a
/// matrix of the physical dofs on the independent dofs of an elimination u = T u_r (faer's
/// sparse products; rows sorted).
pub fn congruence(
    t: SparseColMatRef<'_, usize, f64>,
    a: SparseColMatRef<'_, usize, f64>,
    par: faer::Par,
) -> Result<SparseColMat<usize, f64>, SolveError> {
    use faer::sparse::linalg::matmul::sparse_sparse_matmul;
    if a.nrows() != t.nrows() || a.ncols() != t.nrows() {
        return Err(SolveError::Dimension(format!(
            "TᵀAT: A is {}x{}, T is {}x{}",
            a.nrows(),
            a.ncols(),
            t.nrows(),
            t.ncols()
        )));
    }
    let oom = |e| SolveError::Invalid(format!("TᵀAT: {e:?}"));
    let at = sparse_sparse_matmul(a, t, 1.0, par).map_err(oom)?;
    // Tᵀ as a column-major matrix: the row-major T read transposed
    let t_rows = t.to_row_major().map_err(oom)?;
    sparse_sparse_matmul(t_rows.as_ref().transpose(), at.as_ref(), 1.0, par).map_err(oom)
}

/// The symmetric sub-matrix A[rows, cols] as a sparse matrix (`rows`, `cols` are index lists;
/// a row listed twice keeps its last position).
///
/// Built column by column (each column's entries sorted by their new row, which is a no-op for
/// increasing `rows` such as an interior complement); through triplets it sorted every entry
/// again, over a second on a 69k-dof model for K_ii, M_ii and K_ib.
pub fn submatrix(
    a: SparseColMatRef<'_, usize, f64>,
    rows: &[usize],
    cols: &[usize],
) -> Result<SparseColMat<usize, f64>, SolveError> {
    let mut pos = vec![usize::MAX; a.nrows()];
    for (r, &i) in rows.iter().enumerate() {
        *pos.get_mut(i).ok_or_else(|| {
            SolveError::Dimension(format!("sub-matrix: row {i} of a {}-row matrix", a.nrows()))
        })? = r;
    }
    let mut col_ptr = Vec::with_capacity(cols.len() + 1);
    let mut row_idx = Vec::new();
    let mut val = Vec::new();
    let mut col: Vec<(usize, f64)> = Vec::new();
    col_ptr.push(0usize);
    for &j in cols {
        if j >= a.ncols() {
            return Err(SolveError::Dimension(format!(
                "sub-matrix: column {j} of a {}-column matrix",
                a.ncols()
            )));
        }
        col.clear();
        col.extend(
            a.row_idx_of_col_raw(j)
                .iter()
                .zip(a.val_of_col(j))
                .filter(|(&i, _)| pos[i] != usize::MAX)
                .map(|(&i, &v)| (pos[i], v)),
        );
        sort_and_sum(&mut col);
        row_idx.extend(col.iter().map(|e| e.0));
        val.extend(col.iter().map(|e| e.1));
        col_ptr.push(row_idx.len());
    }
    let symbolic = faer::sparse::SymbolicSparseColMat::new_checked(
        rows.len(),
        cols.len(),
        col_ptr,
        None,
        row_idx,
    );
    Ok(SparseColMat::new(symbolic, val))
}

/// A column's (row, value) entries sorted by row, duplicates summed as a triplet build would
/// (a no-op for the usual strictly increasing column).
fn sort_and_sum(col: &mut Vec<(usize, f64)>) {
    if col.windows(2).all(|w| w[0].0 < w[1].0) {
        return;
    }
    col.sort_by_key(|e| e.0);
    col.dedup_by(|next, kept| {
        let same = next.0 == kept.0;
        if same {
            kept.1 += next.1;
        }
        same
    });
}

/// A square matrix split at its interior dofs: A_ii, and the border, every entry of A in a row
/// or a column outside the interior (in A's own indexing). The two hold A's entries once, so A
/// itself need not stay resident while A_ii is in use; [`join_interior`] puts it back.
#[derive(Clone, Debug)]
pub struct InteriorSplit {
    /// A[inner, inner], in `inner` order.
    pub interior: SparseColMat<usize, f64>,
    /// The entries of A with a row or a column outside `inner`, n × n.
    pub border: SparseColMat<usize, f64>,
}

/// Splits the square `a` at the strictly increasing interior dofs `inner` (consumed: A is dropped
/// once split). Each column's entries are sorted and duplicates summed, as [`submatrix`] does.
pub fn split_interior(
    a: SparseColMat<usize, f64>,
    inner: &[usize],
) -> Result<InteriorSplit, SolveError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(SolveError::Dimension(format!(
            "interior split of a {n} × {} matrix: not square",
            a.ncols()
        )));
    }
    let mut pos = vec![usize::MAX; n];
    for (r, &i) in inner.iter().enumerate() {
        if i >= n || (r > 0 && inner[r - 1] >= i) {
            return Err(SolveError::Dimension(format!(
                "interior split: interior dof {i} (position {r}) is out of range {n} or not increasing"
            )));
        }
        pos[i] = r;
    }
    let (mut in_ptr, mut in_idx, mut in_val) = (vec![0usize], Vec::new(), Vec::new());
    let (mut b_ptr, mut b_idx, mut b_val) = (vec![0usize], Vec::new(), Vec::new());
    let mut col: Vec<(usize, f64)> = Vec::new();
    for j in 0..n {
        col.clear();
        col.extend(
            a.row_idx_of_col_raw(j)
                .iter()
                .copied()
                .zip(a.val_of_col(j).iter().copied()),
        );
        sort_and_sum(&mut col);
        for &(i, v) in &col {
            if pos[j] != usize::MAX && pos[i] != usize::MAX {
                in_idx.push(pos[i]);
                in_val.push(v);
            } else {
                b_idx.push(i);
                b_val.push(v);
            }
        }
        if pos[j] != usize::MAX {
            in_ptr.push(in_idx.len());
        }
        b_ptr.push(b_idx.len());
    }
    drop(a);
    let ni = inner.len();
    let interior = SparseColMat::new(
        faer::sparse::SymbolicSparseColMat::new_checked(ni, ni, in_ptr, None, in_idx),
        in_val,
    );
    let border = SparseColMat::new(
        faer::sparse::SymbolicSparseColMat::new_checked(n, n, b_ptr, None, b_idx),
        b_val,
    );
    Ok(InteriorSplit { interior, border })
}

/// The matrix [`split_interior`] split at `inner` (the same list), entry for entry.
pub fn join_interior(
    split: InteriorSplit,
    inner: &[usize],
) -> Result<SparseColMat<usize, f64>, SolveError> {
    let InteriorSplit { interior, border } = split;
    let n = border.nrows();
    if interior.nrows() != inner.len() || interior.ncols() != inner.len() || border.ncols() != n {
        return Err(SolveError::Dimension(format!(
            "interior join: interior {} × {}, border {n} × {}, {} interior dofs",
            interior.nrows(),
            interior.ncols(),
            border.ncols(),
            inner.len()
        )));
    }
    let nnz = interior.compute_nnz() + border.compute_nnz();
    let (mut ptr, mut idx, mut val) = (
        Vec::with_capacity(n + 1),
        Vec::with_capacity(nnz),
        Vec::with_capacity(nnz),
    );
    ptr.push(0usize);
    let mut c = 0;
    for j in 0..n {
        let (bi, bv) = (border.row_idx_of_col_raw(j), border.val_of_col(j));
        if c < inner.len() && inner[c] == j {
            // merge the two sorted columns: interior rows map to increasing original rows
            let (ii, iv) = (interior.row_idx_of_col_raw(c), interior.val_of_col(c));
            let (mut p, mut q) = (0, 0);
            while p < ii.len() || q < bi.len() {
                let from_interior = q == bi.len() || (p < ii.len() && inner[ii[p]] < bi[q]);
                if from_interior {
                    idx.push(inner[ii[p]]);
                    val.push(iv[p]);
                    p += 1;
                } else {
                    idx.push(bi[q]);
                    val.push(bv[q]);
                    q += 1;
                }
            }
            c += 1;
        } else {
            idx.extend_from_slice(bi);
            val.extend_from_slice(bv);
        }
        ptr.push(idx.len());
    }
    drop((interior, border));
    Ok(SparseColMat::new(
        faer::sparse::SymbolicSparseColMat::new_checked(n, n, ptr, None, idx),
        val,
    ))
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

/// The indices of 0..n not in `dofs`, in order.
pub fn complement(dofs: &[usize], n: usize) -> Vec<usize> {
    let mut mark = vec![false; n];
    for &d in dofs {
        mark[d] = true;
    }
    (0..n).filter(|&i| !mark[i]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 7 × 7 symmetric matrix with a duplicate stored entry and an explicit zero.
    fn sample() -> SparseColMat<usize, f64> {
        let mut t = vec![];
        for i in 0..7usize {
            t.push(Triplet::new(i, i, 4.0 + i as f64));
            if i + 1 < 7 {
                t.push(Triplet::new(i, i + 1, -1.0 - 0.1 * i as f64));
                t.push(Triplet::new(i + 1, i, -1.0 - 0.1 * i as f64));
            }
        }
        t.push(Triplet::new(0, 6, 0.0));
        t.push(Triplet::new(6, 0, 0.0));
        t.push(Triplet::new(2, 5, 0.5));
        t.push(Triplet::new(5, 2, 0.5));
        SparseColMat::try_new_from_triplets(7, 7, &t).unwrap()
    }

    /// K·X with the output rows split between two threads (n ≥ SPLIT_ROWS) equals the one-thread
    /// product exactly (each row is one column's sum either way) and faer's product to rounding.
    #[test]
    fn spmm_on_two_threads_equals_one_thread() {
        let n = 9001;
        let mut t = vec![];
        for i in 0..n {
            t.push(Triplet::new(i, i, 4.0 + (i % 7) as f64));
            for d in [1, 97] {
                if i + d < n {
                    t.push(Triplet::new(i, i + d, -1.0));
                    t.push(Triplet::new(i + d, i, -1.0));
                }
            }
        }
        let a = SparseColMat::try_new_from_triplets(n, n, &t).unwrap();
        let x = crate::solve::eigen::random_block(n, 6, &mut 11);
        let run = |par| {
            let _g = crate::solve::ParGuard::new(par);
            spmm(a.as_ref(), x.as_ref())
        };
        let (y1, y2) = (run(faer::Par::Seq), run(faer::Par::rayon(2)));
        assert_eq!(y1, y2);
        let yref = &a * &x;
        assert!((&y2 - &yref).norm_max() <= 1e-13);
    }

    #[test]
    fn split_and_join_give_back_the_matrix_and_its_interior_block() {
        let a = sample();
        let inner = [1usize, 2, 4, 5];
        let split = split_interior(a.clone(), &inner).unwrap();
        let want = submatrix(a.as_ref(), &inner, &inner).unwrap();
        assert_eq!(to_dense(split.interior.as_ref()), to_dense(want.as_ref()));
        assert_eq!(
            split.interior.compute_nnz() + split.border.compute_nnz(),
            a.compute_nnz()
        );
        // the border holds no entry of the interior block
        for j in inner {
            for &i in split.border.row_idx_of_col_raw(j) {
                assert!(!inner.contains(&i), "({i}, {j}) in the border");
            }
        }
        let back = join_interior(split, &inner).unwrap();
        for j in 0..7 {
            assert_eq!(back.row_idx_of_col_raw(j), a.row_idx_of_col_raw(j));
            assert_eq!(back.val_of_col(j), a.val_of_col(j));
        }
    }

    /// A column stored unsorted and with a duplicate entry: both the sub-matrix and the split
    /// sort it and sum the duplicate.
    #[test]
    fn unsorted_duplicate_entries_are_sorted_and_summed() {
        // 3 × 3, column 1 stored as rows [2, 1, 1, 0] (row 1 twice: 1.5 + 0.5)
        let sym = faer::sparse::SymbolicSparseColMat::new_unsorted_checked(
            3,
            3,
            vec![0, 1, 5, 6],
            None,
            vec![0, 2, 1, 1, 0, 2],
        );
        let a = SparseColMat::new(sym, vec![4.0, -1.0, 1.5, 0.5, -2.0, 5.0]);
        let sub = submatrix(a.as_ref(), &[0, 1, 2], &[1]).unwrap();
        assert_eq!(sub.row_idx_of_col_raw(0), &[0, 1, 2]);
        assert_eq!(sub.val_of_col(0), &[-2.0, 2.0, -1.0]);
        let split = split_interior(a, &[1, 2]).unwrap();
        assert_eq!(split.interior.row_idx_of_col_raw(0), &[0, 1]);
        assert_eq!(split.interior.val_of_col(0), &[2.0, -1.0]);
        assert_eq!(split.border.row_idx_of_col_raw(1), &[0]);
        assert_eq!(split.border.val_of_col(1), &[-2.0]);
    }

    #[test]
    fn split_refuses_an_unordered_interior() {
        let e = split_interior(sample(), &[2, 1]).unwrap_err();
        assert!(e.to_string().contains("not increasing"), "{e}");
        let e = split_interior(sample(), &[1, 9]).unwrap_err();
        assert!(e.to_string().contains("out of range"), "{e}");
    }
}
