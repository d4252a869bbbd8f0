//! Block classical Gram–Schmidt in the M inner product, as the block eigensolver
//! ([`super::eigen`]) orthogonalizes each new block W = A Q against its M-orthonormal basis V.
//!
//! One pass is w ← w − V (MV)ᵀw (with M·V kept) or w ← w − V Vᵀ(Mw) (the lean basis). A second
//! pass is made only when the first lost too much of the block: the DGKS test (Daniel, Gragg,
//! Kaufman & Stewart 1976; Kahan–Parlett's "twice is enough", Parlett 1998 §6.9) on the block,
//! which ARPACK and SLEPc apply column by column with η = 1/√2. The pass's remainder F, its
//! image M·F and its Gram matrix FᵀMF (which the test needs) are handed on to the block's M-QR,
//! which used to form M·F itself.

use super::dense;
use super::sparse_ops::spmm;
use super::thin_ops;
use super::SolveError;
use faer::sparse::SparseColMatRef;
use faer::{Mat, MatRef};

/// η of the test: one pass is enough when every combination y of the block keeps at least η of
/// its M-norm, ‖F y‖_M ≥ η ‖W y‖_M (η = 1/√2 as ARPACK's `dsaitr` (0.717) and SLEPc's
/// `BV_ORTHOG_REFINE_IFNEEDED`).
pub(crate) const KEEP_FRACTION: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Largest |VᵀMQ| a block may keep when its second pass's update is left out: the entries of
/// the basis's ‖VᵀMV − I‖_max the new columns would bring (the eigen phase's Krylov bases reach
/// 1e-15 with two passes; the final Rayleigh–Ritz step restores ΦᵀMΦ = I to rounding anyway).
pub(crate) const LOSS_LIMIT: f64 = 1e-14;

/// A block M-orthogonalized against a basis: W = V C + F.
pub(crate) struct Orthogonalized {
    /// Coefficients C (basis columns × block columns).
    pub coef: Mat<f64>,
    /// The remainder F, M-orthogonal to V.
    pub rest: Mat<f64>,
    /// M·F.
    pub m_rest: Mat<f64>,
    /// FᵀMF.
    pub gram: Mat<f64>,
    /// Updates w ← w − V D made: 1, or 2 when the second pass's was needed (0 against an empty
    /// basis).
    pub passes: usize,
    /// Whether the second pass's coefficients D = (MV)ᵀF were formed (the first pass failed the
    /// DGKS test) — with `passes` = 1 they showed a loss within [`LOSS_LIMIT`].
    pub measured: bool,
}

/// U S^{-½} with G = USUᵀ (Q = F U S^{-½} is the M-orthonormal block of F), or `None` when G is
/// not positive definite to rounding (the block lost a direction).
fn whitening(g: MatRef<'_, f64>) -> Result<Option<Mat<f64>>, SolveError> {
    let b = g.nrows();
    let (s, u) = dense::eigh(g)?;
    // ascending: s[0] is the smallest; a direction below rounding of the largest is lost
    if b > 0 && (s[0].is_nan() || s[0] <= 1e-24 * s[b - 1]) {
        return Ok(None);
    }
    Ok(Some(Mat::from_fn(b, b, |i, j| u[(i, j)] / s[j].sqrt())))
}

/// The DGKS test of one classical Gram–Schmidt pass on a block, W = V C + F with V
/// M-orthonormal and `t` = U S^{-½} from G = FᵀMF = USUᵀ: ‖W y‖²_M = ‖C y‖² + ‖F y‖²_M, so
/// ‖F y‖_M ≥ η‖W y‖_M for every y ⟺ ‖C y‖² ≤ ((1 − η²)/η²)·yᵀGy ⟺
/// λ_max((CT)ᵀ(CT)) ≤ (1 − η²)/η² (Daniel et al. 1976, eq. 2.4, for a block).
pub(crate) fn one_pass_suffices(
    c: MatRef<'_, f64>,
    t: MatRef<'_, f64>,
) -> Result<bool, SolveError> {
    let b = t.ncols();
    if b == 0 {
        return Ok(true);
    }
    let x = c * t;
    let (xs, _) = dense::eigh((x.transpose() * &x).as_ref())?;
    let bound = (1.0 - KEEP_FRACTION * KEEP_FRACTION) / (KEEP_FRACTION * KEEP_FRACTION);
    Ok(xs[b - 1] <= bound)
}

/// M-orthogonalizes `w` against the M-orthonormal `v` (`mv` = M·V, if kept): one classical
/// Gram–Schmidt pass; when it fails [`one_pass_suffices`], the second pass's coefficients
/// D = (MV)ᵀF, and its update F ← F − V D only when the loss they measure, max |D U S^{-½}| =
/// max |VᵀMQ| for the block Q the M-QR will make of F, exceeds [`LOSS_LIMIT`].
pub(crate) fn orthogonalize(
    v: MatRef<'_, f64>,
    mv: Option<MatRef<'_, f64>>,
    m: SparseColMatRef<'_, usize, f64>,
    mut w: Mat<f64>,
) -> Result<Orthogonalized, SolveError> {
    let mut coef = Mat::<f64>::zeros(v.ncols(), w.ncols());
    // (MV)ᵀw, or Vᵀ(Mw) on the lean basis with M·w from `mw` when already formed
    let project = |w: &Mat<f64>, mw: Option<&Mat<f64>>| match mv {
        Some(mv) => thin_ops::at_b(mv, w.as_ref()),
        None => match mw {
            Some(mw) => thin_ops::at_b(v, mw.as_ref()),
            None => thin_ops::at_b(v, spmm(m, w.as_ref()).as_ref()),
        },
    };
    let mut passes = 0;
    if v.ncols() > 0 {
        let d = project(&w, None);
        thin_ops::add_a_d(w.as_mut(), v, d.as_ref(), -1.0);
        coef += &d;
        passes = 1;
    }
    let m_rest = spmm(m, w.as_ref());
    let gram = thin_ops::at_b(w.as_ref(), m_rest.as_ref());
    let done = |coef, rest, m_rest, gram, passes, measured| Orthogonalized {
        coef,
        rest,
        m_rest,
        gram,
        passes,
        measured,
    };
    if passes == 0 {
        return Ok(done(coef, w, m_rest, gram, 0, false));
    }
    let t = whitening(gram.as_ref())?;
    if let Some(t) = &t {
        if one_pass_suffices(coef.as_ref(), t.as_ref())? {
            return Ok(done(coef, w, m_rest, gram, 1, false));
        }
    }
    let d = project(&w, Some(&m_rest));
    if let Some(t) = &t {
        let loss = (&d * t).norm_max();
        if loss <= LOSS_LIMIT {
            return Ok(done(coef, w, m_rest, gram, 1, true));
        }
    }
    thin_ops::add_a_d(w.as_mut(), v, d.as_ref(), -1.0);
    coef += &d;
    let m_rest = spmm(m, w.as_ref());
    let gram = thin_ops::at_b(w.as_ref(), m_rest.as_ref());
    Ok(done(coef, w, m_rest, gram, 2, true))
}

/// M-orthogonalization of `w` against the M-orthonormal `v` by two classical Gram–Schmidt passes
/// whatever the first left (the M-QR's padding directions). Returns the remainder.
pub(crate) fn twice(
    v: MatRef<'_, f64>,
    mv: Option<MatRef<'_, f64>>,
    m: SparseColMatRef<'_, usize, f64>,
    mut w: Mat<f64>,
) -> Mat<f64> {
    if v.ncols() == 0 {
        return w;
    }
    for _ in 0..2 {
        let d = match mv {
            Some(mv) => thin_ops::at_b(mv, w.as_ref()),
            None => thin_ops::at_b(v, spmm(m, w.as_ref()).as_ref()),
        };
        thin_ops::add_a_d(w.as_mut(), v, d.as_ref(), -1.0);
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::cholesky::SparseLlt;
    use crate::solve::eigen::random_block;
    use faer::sparse::{SparseColMat, Triplet};

    /// The fixed chain of n linear rod elements, h = 1/(n+1): K = tridiag(−1, 2, −1)/h and the
    /// consistent M = tridiag(1, 4, 1)·h/6, whose pencil has the closed-form spectrum
    /// λ_j = (6/h²)(1 − cos jπh)/(2 + cos jπh).
    fn chain(n: usize) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>, f64) {
        let h = 1.0 / (n + 1) as f64;
        let (mut k, mut m) = (vec![], vec![]);
        for i in 0..n {
            k.push(Triplet::new(i, i, 2.0 / h));
            m.push(Triplet::new(i, i, 4.0 * h / 6.0));
            if i + 1 < n {
                for (r, c) in [(i, i + 1), (i + 1, i)] {
                    k.push(Triplet::new(r, c, -1.0 / h));
                    m.push(Triplet::new(r, c, h / 6.0));
                }
            }
        }
        let k = SparseColMat::try_new_from_triplets(n, n, &k).unwrap();
        let m = SparseColMat::try_new_from_triplets(n, n, &m).unwrap();
        (k, m, h)
    }

    /// Whether one pass kept η of every combination of the block, from the block itself: the
    /// smallest generalized eigenvalue of (FᵀMF, WᵀMW) against η² (WᵀMW = USUᵀ-whitened, no use
    /// of the coefficients or of ‖W y‖² = ‖C y‖² + ‖F y‖²).
    fn kept_fraction2(
        m: SparseColMatRef<'_, usize, f64>,
        w: MatRef<'_, f64>,
        f: MatRef<'_, f64>,
    ) -> f64 {
        let gw = w.transpose() * spmm(m, w);
        let gf = f.transpose() * spmm(m, f);
        let (sw, uw) = dense::eigh(gw.as_ref()).unwrap();
        assert!(sw[0] > 0.0, "W has full rank");
        let li = Mat::from_fn(sw.len(), sw.len(), |i, j| uw[(i, j)] / sw[j].sqrt())
            .transpose()
            .to_owned();
        let (s, _) = dense::eigh((&li * &gf * li.transpose()).as_ref()).unwrap();
        s[0]
    }

    /// A block Krylov sequence of the chain's shift-invert operator A = K⁻¹M, blocks of 4 to a
    /// basis of 96 (n = 400), each new block W = A Q orthogonalized by [`orthogonalize`] with
    /// M·V kept and with the lean basis: the basis stays M-orthonormal to 1e-14 and every
    /// remainder M-orthogonal to it to 1e-14 of its norm; a block got one pass exactly when
    /// the kept fraction of its first pass, measured from the blocks themselves, is ≥ η (both
    /// cases occur); the Ritz values of the last basis give the chain's three lowest
    /// eigenvalues to 1e-10. Then a block built to lose most of itself (W = V C + 1e-6·F)
    /// takes the second pass and one that keeps it (W = F + 0.05·V C) does not.
    #[test]
    fn second_pass_only_where_the_test_asks_and_the_basis_stays_orthonormal() {
        let (n, b, blocks) = (400, 4, 24);
        let (k, m, h) = chain(n);
        let llt = SparseLlt::factor(k.as_ref(), None, faer::Par::Seq).unwrap();
        let eta2 = KEEP_FRACTION * KEEP_FRACTION;
        // M-QR by whitening twice (Cholesky-QR2: once leaves ε·κ(F)² within the block)
        let m_qr = |f: &Orthogonalized| {
            let whiten = |x: &Mat<f64>, mx: &Mat<f64>| {
                let (s, u) = dense::eigh((x.transpose() * mx).as_ref()).unwrap();
                let t = Mat::from_fn(b, b, |i, j| u[(i, j)] / s[j].sqrt());
                (x * &t, mx * &t)
            };
            let (q, mq) = whiten(&f.rest, &f.m_rest);
            whiten(&q, &mq)
        };
        for keep_mv in [true, false] {
            let mut v = Mat::<f64>::zeros(n, b * blocks);
            let mut mv = Mat::<f64>::zeros(n, b * blocks);
            let start = orthogonalize(
                v.as_ref().subcols(0, 0),
                None,
                m.as_ref(),
                random_block(n, b, &mut 7u64),
            )
            .unwrap();
            assert_eq!(start.passes, 0);
            let (q, mq) = m_qr(&start);
            v.as_mut().subcols_mut(0, b).copy_from(&q);
            mv.as_mut().subcols_mut(0, b).copy_from(&mq);
            // one pass by DGKS, one pass by the measured loss, two passes
            let mut tally = [0usize; 3];
            for j in 1..blocks {
                let p = j * b;
                let (vp, mvp) = (v.as_ref().subcols(0, p), mv.as_ref().subcols(0, p));
                let mut w = mvp.subcols(p - b, b).to_owned();
                llt.solve_in_place(w.as_mut());
                let first_pass = {
                    let d = thin_ops::at_b(mvp, w.as_ref());
                    let mut f = w.clone();
                    thin_ops::add_a_d(f.as_mut(), vp, d.as_ref(), -1.0);
                    f
                };
                let kept = kept_fraction2(m.as_ref(), w.as_ref(), first_pass.as_ref());
                let loss = {
                    // |VᵀMQ| of the first pass's M-orthonormal block, by faer's dense products
                    let mf = spmm(m.as_ref(), first_pass.as_ref());
                    let (s, u) = dense::eigh((first_pass.transpose() * &mf).as_ref()).unwrap();
                    let q = &first_pass * Mat::from_fn(b, b, |i, j| u[(i, j)] / s[j].sqrt());
                    (vp.transpose() * spmm(m.as_ref(), q.as_ref())).norm_max()
                };
                let o = orthogonalize(vp, keep_mv.then_some(mvp), m.as_ref(), w.clone()).unwrap();
                // away from the thresholds' rounding: no second look ⟺ the kept fraction ≥ η,
                // and then no update ⟺ the loss ≤ LOSS_LIMIT
                if (kept - eta2).abs() > 1e-8 {
                    assert_eq!(o.measured, kept < eta2, "block {j}: kept {kept:.3e}");
                }
                if o.measured && (loss / LOSS_LIMIT - 1.0).abs() > 0.1 {
                    assert_eq!(
                        o.passes == 1,
                        loss <= LOSS_LIMIT,
                        "block {j}: loss {loss:.3e}"
                    );
                }
                tally[usize::from(o.measured) + usize::from(o.passes == 2)] += 1;
                let leak = (vp.transpose() * &o.m_rest).norm_max() / o.gram.norm_max().sqrt();
                assert!(leak <= 1e-14, "block {j}: VᵀMF {leak:.1e} of ‖F‖_M");
                let (q, mq) = m_qr(&o);
                v.as_mut().subcols_mut(p, b).copy_from(&q);
                mv.as_mut().subcols_mut(p, b).copy_from(&mq);
            }
            eprintln!("keep_mv {keep_mv}: one pass (DGKS, loss measured), two: {tally:?}");
            assert!(tally.iter().all(|&t| t > 0), "{tally:?}");
            let g = v.transpose() * spmm(m.as_ref(), v.as_ref());
            let off = (&g - Mat::<f64>::identity(b * blocks, b * blocks)).norm_max();
            assert!(off <= 1e-14, "keep_mv {keep_mv}: ‖VᵀMV − I‖ {off:.1e}");
            // Rayleigh–Ritz on the basis: the chain's lowest eigenvalues in closed form
            let kp = v.transpose() * spmm(k.as_ref(), v.as_ref());
            let (vals, _) = dense::eigh(kp.as_ref()).unwrap();
            for (j, &l) in vals.iter().take(3).enumerate() {
                let c = ((j + 1) as f64 * std::f64::consts::PI * h).cos();
                let exact = 6.0 / (h * h) * (1.0 - c) / (2.0 + c);
                assert!((l - exact).abs() <= 1e-10 * exact, "λ{j} {l} vs {exact}");
            }
        }
        // constructed blocks on the last basis of 16 columns
        let mut v = random_block(n, 16, &mut 11u64);
        let mv0 = spmm(m.as_ref(), v.as_ref());
        let (s, u) = dense::eigh((v.transpose() * &mv0).as_ref()).unwrap();
        v = &v * Mat::from_fn(16, 16, |i, j| u[(i, j)] / s[j].sqrt());
        let mv = spmm(m.as_ref(), v.as_ref());
        let c = random_block(16, b, &mut 13u64);
        let f = {
            let o = orthogonalize(
                v.as_ref(),
                Some(mv.as_ref()),
                m.as_ref(),
                random_block(n, b, &mut 17u64),
            )
            .unwrap();
            o.rest
        };
        let lost = &v * &c + &f * faer::Scale(1e-6);
        let o = orthogonalize(v.as_ref(), Some(mv.as_ref()), m.as_ref(), lost).unwrap();
        assert!(o.measured && o.passes == 2);
        let kept = &f + &v * &c * faer::Scale(0.05);
        let o = orthogonalize(v.as_ref(), Some(mv.as_ref()), m.as_ref(), kept).unwrap();
        assert!(!o.measured && o.passes == 1);
        assert!((&o.coef - &c * faer::Scale(0.05)).norm_max() <= 1e-13);
    }
}
