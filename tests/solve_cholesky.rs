//! METIS-ordered sparse LLᵀ: multi-RHS solve accuracy on the tet10 block's fixed K, fill against
//! the natural ordering, and the typed non-positive-pivot error naming the original dof.

use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;
use flexbody::import::ccx_matrices::read_ccx_matrices;
use flexbody::solve::{sparse_ops, SolveError, SparseLlt};
use std::path::Path;

fn tet10_free_k() -> SparseColMat<usize, f64> {
    let stem = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/reference/e_matrices/tet10_block_coarse/ccx_matrix_free");
    let c = read_ccx_matrices(&stem).unwrap();
    let t: Vec<_> =
        c.k.full()
            .into_iter()
            .map(|(i, j, v)| Triplet::new(i, j, v))
            .collect();
    SparseColMat::try_new_from_triplets(c.k.n, c.k.n, &t).unwrap()
}

#[test]
fn multi_rhs_solve_and_metis_fill() {
    let k = tet10_free_k();
    // clamp the first 60 dofs (one end region) so K is positive definite
    let keep: Vec<usize> = (60..k.nrows()).collect();
    let kf = sparse_ops::submatrix(k.as_ref(), &keep, &keep).unwrap();
    let n = kf.nrows();
    let llt = SparseLlt::factor(kf.as_ref(), Some(3), faer::Par::Seq).unwrap();
    let b = Mat::from_fn(n, 12, |i, j| ((i * 7 + j * 13) % 17) as f64 - 8.0);
    let x = llt.solve(b.as_ref());
    let r = sparse_ops::spmm(kf.as_ref(), x.as_ref()) - &b;
    let rel = r.norm_max() / b.norm_max();
    assert!(rel < 1e-6, "relative residual {rel}");
    // backward error: ‖Kx − b‖ / (‖K‖‖x‖)
    let knorm = (0..n)
        .map(|j| kf.val_of_col(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    assert!(r.norm_max() / (knorm * x.norm_max()) < 1e-14);
    // nested dissection must not fill more than the natural ordering's band
    let st = &llt.stats;
    assert_eq!(st.n, n);
    assert!(
        st.nnz_l >= kf.compute_nnz() / 2,
        "L holds at least the lower triangle of K"
    );
    let ident = {
        let d = sparse_ops::to_dense(kf.as_ref());
        // natural-order profile fill: Σ_j (j − first nonzero row of column j in the lower part) + 1
        let mut fill = 0usize;
        for i in 0..n {
            let first = (0..=i).find(|&j| d[(i, j)] != 0.0).unwrap();
            fill += i - first + 1;
        }
        fill
    };
    assert!(
        st.nnz_l < ident,
        "METIS nnz(L) {} vs natural profile {ident}",
        st.nnz_l
    );
    assert!(st.flops > st.nnz_l as f64 && st.factor_bytes >= 8 * st.nnz_l);
}

#[test]
fn non_positive_pivot_names_the_dof() {
    let n = 40;
    let mut t = Vec::new();
    for i in 0..n {
        t.push(Triplet::new(i, i, if i == 23 { -1.0 } else { 4.0 }));
        if i + 1 < n {
            t.push(Triplet::new(i, i + 1, 1.0));
            t.push(Triplet::new(i + 1, i, 1.0));
        }
    }
    let a = SparseColMat::try_new_from_triplets(n, n, &t).unwrap();
    match SparseLlt::factor(a.as_ref(), None, faer::Par::Seq) {
        Err(SolveError::NonPositivePivot { dof }) => assert_eq!(dof, 23),
        other => panic!("expected a non-positive pivot at dof 23, got {other:?}"),
    }
}

/// The lane kernel of `spmm` (widths padded to 4/8/12/16, chunks of 16) and `abs_products`
/// against dense products, and column-split threaded solves against the sequential solve.
#[test]
fn spmm_lanes_abs_products_and_threaded_solve() {
    let k = tet10_free_k();
    let n = k.nrows();
    let kd = sparse_ops::to_dense(k.as_ref());
    let scale = kd.norm_max();
    for w in [1, 2, 3, 4, 5, 6, 9, 13, 16, 17, 30] {
        let x = Mat::from_fn(n, w, |i, j| ((i * 5 + j * 11) % 13) as f64 - 6.0);
        let y = sparse_ops::spmm(k.as_ref(), x.as_ref());
        let yd = &kd * &x;
        let err = (&y - &yd).norm_max() / (scale * 6.0 * 100.0);
        assert!(err < 1e-14, "width {w}: {err:e}");
        let (energy, norm) = sparse_ops::abs_products(k.as_ref(), x.as_ref());
        let ka = Mat::from_fn(n, n, |i, j| kd[(i, j)].abs());
        let xa = Mat::from_fn(n, w, |i, j| x[(i, j)].abs());
        let ya = &ka * &xa;
        for j in 0..w {
            let e: f64 = (0..n).map(|i| ya[(i, j)] * xa[(i, j)]).sum();
            let nn = ya.col(j).norm_l2();
            assert!((energy[j] - e).abs() <= 1e-12 * e, "width {w} col {j}");
            assert!((norm[j] - nn).abs() <= 1e-12 * nn, "width {w} col {j}");
        }
    }
    let keep: Vec<usize> = (60..n).collect();
    let kf = sparse_ops::submatrix(k.as_ref(), &keep, &keep).unwrap();
    let b = Mat::from_fn(kf.nrows(), 7, |i, j| ((i * 3 + j * 7) % 11) as f64 - 5.0);
    let seq = SparseLlt::factor(kf.as_ref(), Some(3), faer::Par::Seq).unwrap();
    let par = SparseLlt::factor(kf.as_ref(), Some(3), faer::Par::rayon(2)).unwrap();
    let (xs, xp) = (seq.solve(b.as_ref()), par.solve(b.as_ref()));
    let d = (&xs - &xp).norm_max() / xs.norm_max();
    assert!(d < 1e-12, "threaded solve differs by {d:e}");
    let r = sparse_ops::spmm(kf.as_ref(), xp.as_ref()) - &b;
    assert!(r.norm_max() < 1e-8 * b.norm_max(), "{:e}", r.norm_max());
}

/// K + s·M by merging sorted columns equals the dense sum, for M on a smaller pattern (lumped,
/// diagonal) and on the same pattern, for s = 0 (K itself) and when M's columns are unsorted
/// (the triplet path).
#[test]
fn add_scaled_merges_patterns() {
    let k = tet10_free_k();
    let n = k.nrows();
    let kd = sparse_ops::to_dense(k.as_ref());
    let diag: Vec<_> = (0..n)
        .map(|i| Triplet::new(i, i, 1.0 + (i % 7) as f64))
        .collect();
    let lumped = SparseColMat::try_new_from_triplets(n, n, &diag).unwrap();
    let same = SparseColMat::try_new_from_triplets(
        n,
        n,
        &(0..n)
            .flat_map(|j| {
                k.row_idx_of_col_raw(j)
                    .iter()
                    .map(move |&i| Triplet::new(i, j, ((i + 2 * j) % 5) as f64 - 2.0))
            })
            .collect::<Vec<_>>(),
    )
    .unwrap();
    for m in [&lumped, &same] {
        let md = sparse_ops::to_dense(m.as_ref());
        for s in [0.0, -3.5e4, 2.0] {
            let a = sparse_ops::add_scaled(k.as_ref(), m.as_ref(), s).unwrap();
            let want = &kd + &md * faer::Scale(s);
            let got = sparse_ops::to_dense(a.as_ref());
            assert!((&got - &want).norm_max() == 0.0, "s = {s}");
            let union = (0..n)
                .map(|j| {
                    let mut r: Vec<usize> = k.row_idx_of_col_raw(j).to_vec();
                    if s != 0.0 {
                        r.extend_from_slice(m.row_idx_of_col_raw(j));
                    }
                    r.sort_unstable();
                    r.dedup();
                    r.len()
                })
                .sum::<usize>();
            assert_eq!(a.compute_nnz(), union, "s = {s}: stored entries");
        }
    }
    // unsorted columns (reversed rows) go through triplets and give the same sum
    let col_ptr: Vec<usize> = (0..=n).collect();
    let rows: Vec<usize> = (0..n).collect();
    let mut cp = vec![0usize];
    let mut ri = Vec::new();
    let mut vals = Vec::new();
    for j in 0..n {
        for (&i, &v) in k.row_idx_of_col_raw(j).iter().zip(k.val_of_col(j)).rev() {
            ri.push(i);
            vals.push(v);
        }
        cp.push(ri.len());
    }
    let sym = faer::sparse::SymbolicSparseColMat::new_unsorted_checked(n, n, cp, None, ri);
    let unsorted = SparseColMat::new(sym, vals);
    let eye = SparseColMat::new(
        faer::sparse::SymbolicSparseColMat::new_checked(n, n, col_ptr, None, rows),
        vec![1.0; n],
    );
    let a = sparse_ops::add_scaled(unsorted.as_ref(), eye.as_ref(), 3.0).unwrap();
    let want = &kd + Mat::<f64>::identity(n, n) * faer::Scale(3.0);
    assert!((sparse_ops::to_dense(a.as_ref()) - want).norm_max() == 0.0);
}

/// Sub-matrices for increasing and for shuffled index lists equal the dense selection, and an
/// index out of range is an error, not a panic.
#[test]
fn submatrix_equals_dense_selection() {
    let k = tet10_free_k();
    let n = k.nrows();
    let kd = sparse_ops::to_dense(k.as_ref());
    let inner: Vec<usize> = (0..n).filter(|i| i % 5 != 2).collect();
    let iface: Vec<usize> = (0..n).filter(|i| i % 5 == 2).rev().collect();
    let shuffled: Vec<usize> = (0..n).map(|i| (i * 7919) % n).collect();
    for (rows, cols) in [
        (&inner, &inner),
        (&inner, &iface),
        (&shuffled, &inner),
        (&iface, &shuffled),
    ] {
        let s = sparse_ops::submatrix(k.as_ref(), rows, cols).unwrap();
        let want = Mat::from_fn(rows.len(), cols.len(), |r, c| kd[(rows[r], cols[c])]);
        assert_eq!(sparse_ops::to_dense(s.as_ref()), want);
        let stored = (0..cols.len())
            .map(|c| s.row_idx_of_col_raw(c).len())
            .sum::<usize>();
        let nonzero = (0..cols.len())
            .map(|c| {
                k.row_idx_of_col_raw(cols[c])
                    .iter()
                    .filter(|i| rows.contains(i))
                    .count()
            })
            .sum::<usize>();
        assert_eq!(stored, nonzero);
    }
    assert!(sparse_ops::submatrix(k.as_ref(), &[n], &[0]).is_err());
    assert!(sparse_ops::submatrix(k.as_ref(), &[0], &[n + 3]).is_err());
}
