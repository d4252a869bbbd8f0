//! METIS-ordered sparse LLᵀ: multi-RHS solve accuracy on the tet10 block's fixed K, fill against
//! the natural ordering, and the typed non-positive-pivot error naming the original dof.

use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;
use flexbody::import::ccx_matrices::read_ccx_matrices;
use flexbody::solve::{sparse_ops, SolveError, SparseLlt};
use std::path::Path;

fn tet10_free_k() -> SparseColMat<usize, f64> {
    let stem = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/reference/e_matrices/tet10_block_coarse/ccx_matrix_free");
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
