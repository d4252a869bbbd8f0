//! Our block shift-invert eigensolver for the lowest eigenpairs of K x = λ M x (M ⪰ 0): a block
//! Krylov–Schur (thick-restart block Lanczos) iteration on A = (K − σM)⁻¹M, self-adjoint in the
//! M inner product, with full reorthogonalization.
//!
//! It maintains A V = V T + F Eᵀ with V M-orthonormal (n × p), T = VᵀMAV (p × p), F M-orthogonal
//! to V (n × b) and E (p × b). A step M-orthonormalizes F = QR, computes W = A Q with one
//! multi-RHS solve, Gram–Schmidt's it against [V Q] (a second pass only when the first lost too
//! much of the block: [`gram_schmidt`]) and appends the block to T. When the
//! basis is full, T = YΘYᵀ is truncated to its largest Ritz values (lowest λ = σ + 1/θ):
//! V ← VY_k, T ← Θ_k, E ← Y_kᵀE. Ritz pair i is converged when its estimate ‖R_F Eᵀy_i‖ ≤
//! tol·|θ_i| (relative). Vectors in the range of A have positive M-norm, so massless dofs need no
//! special treatment; every start and padding vector is A applied to a random block.

use super::cholesky::SparseLlt;
use super::dense;
use super::gram_schmidt::{self, Orthogonalized};
use super::sparse_ops::spmm;
use super::thin_ops;
use super::SolveError;
use faer::sparse::SparseColMatRef;
use faer::{Mat, MatRef};

/// Settings of one run.
#[derive(Clone, Debug)]
pub struct BlockParams {
    /// Number of wanted eigenpairs.
    pub count: usize,
    /// Block size (vectors per multi-RHS solve).
    pub block: usize,
    /// Largest basis before a thick restart.
    pub max_basis: usize,
    /// Relative residual tolerance.
    pub tol: f64,
    /// Maximal number of block steps (for `count`; grown with it).
    pub max_steps: usize,
    /// Band mode: every eigenvalue ≤ `upper` is wanted, `count` is only the first guess. When
    /// the converged Ritz values fill `count` and all lie at or below `upper`, the iteration
    /// goes on with twice the count (up to `max_count`) on a larger basis instead of stopping;
    /// it returns the converged values up to the first one above `upper` (or `max_count` values
    /// all below it, for the caller to go on another way).
    pub upper: Option<f64>,
    /// Largest count band mode may grow to.
    pub max_count: usize,
    /// Keep M·V beside V (one product with M per step, M·F; two when the second Gram–Schmidt
    /// update is made). Without it, the lean basis: half the basis memory (8·n·basis bytes less)
    /// for one more product with M per step (M·W before the first pass).
    pub keep_mv: bool,
}

/// Result of one run, before the final checks.
#[derive(Debug)]
pub struct BlockResult {
    /// Ascending Ritz values.
    pub values: Vec<f64>,
    /// M-orthonormal Ritz vectors (n × count).
    pub vectors: Mat<f64>,
    /// Number of vectors solved with the factorization.
    pub solves: usize,
    /// Triangular solves spent refining solves with a mixed-precision factor (vectors × steps).
    pub refinement_solves: usize,
    /// Number of block steps.
    pub steps: usize,
    /// Number of thick restarts.
    pub restarts: usize,
    /// Dense eigensolves of T (Ritz pairs computed; see [`ritz_due`]).
    pub ritz_solves: usize,
    /// Wall time in the triangular solves (s).
    pub seconds_solve: f64,
    /// Wall time in the Gram–Schmidt passes and M-QRs, M products included (s).
    pub seconds_orth: f64,
    /// Wall time of the thick restarts (V ← V·Y_k, M·V likewise) (s).
    pub seconds_restart: f64,
    /// How the Gram–Schmidt passes went.
    pub gram_schmidt: GsTally,
}

/// The Gram–Schmidt passes of one run ([`gram_schmidt::orthogonalize`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GsTally {
    /// Blocks orthogonalized against the basis.
    pub blocks: usize,
    /// Blocks whose first pass failed the DGKS test, so that the second pass's coefficients
    /// were formed.
    pub measured: usize,
    /// Blocks that took the second pass's update (their measured loss was above the limit).
    pub second_passes: usize,
}

impl GsTally {
    fn add(&mut self, o: &Orthogonalized) {
        self.blocks += 1;
        self.measured += usize::from(o.measured);
        self.second_passes += usize::from(o.passes == 2);
    }
}

/// A ← (K − σM)⁻¹ X with the factorization of K − σM: one solve with an f64 factor; with a
/// mixed-precision (f32) one, refined against K (σ must be 0: the factor is of K itself) until
/// the error left is below `target`. Returns the refinement solves beyond the first.
pub(crate) fn shift_inverse_solve(
    llt: &SparseLlt,
    k: SparseColMatRef<'_, usize, f64>,
    sigma: f64,
    x: faer::MatMut<'_, f64>,
    target: f64,
) -> Result<usize, SolveError> {
    if !llt.is_mixed() {
        llt.solve_in_place(x);
        return Ok(0);
    }
    if sigma != 0.0 {
        return Err(SolveError::Invalid(
            "a mixed-precision factorization is of K itself (shift 0)".into(),
        ));
    }
    llt.solve_refined_in_place(k, x, target)
}

/// The operator of one run: the factor, the matrix it refines against, σ and the target.
struct Operator<'a> {
    llt: &'a SparseLlt,
    k: SparseColMatRef<'a, usize, f64>,
    sigma: f64,
    target: f64,
    /// Triangular solves spent on refinement (vectors × steps).
    refinement: std::cell::Cell<usize>,
}

impl Operator<'_> {
    fn solve(&self, mut x: faer::MatMut<'_, f64>) -> Result<(), SolveError> {
        let cols = x.ncols();
        let steps = shift_inverse_solve(self.llt, self.k, self.sigma, x.as_mut(), self.target)?;
        self.refinement.set(self.refinement.get() + steps * cols);
        Ok(())
    }
}

/// (Q, M Q, R) of an M-QR.
type Mqr = (Mat<f64>, Mat<f64>, Mat<f64>);

/// M-QR of a block already M-orthogonal to `v` (`mv` = M v, if kept), from its remainder F, M·F
/// and FᵀMF as [`gram_schmidt::orthogonalize`] left them: F ≈ Q R with Q M-orthonormal; returns
/// (Q, M Q, R). Directions of relative M-norm² below 1e-24 are replaced by fresh random
/// directions (rows of R zero).
#[allow(clippy::too_many_arguments)]
fn mqr(
    m: SparseColMatRef<'_, usize, f64>,
    op: &Operator<'_>,
    v: MatRef<'_, f64>,
    mv: Option<MatRef<'_, f64>>,
    block: Orthogonalized,
    scale2: f64,
    seed: &mut u64,
    solves: &mut usize,
) -> Result<Mqr, SolveError> {
    let Orthogonalized {
        rest: w,
        m_rest: mw,
        gram: g,
        ..
    } = block;
    let (n, b) = (w.nrows(), w.ncols());
    let (s, u) = dense::eigh(g.as_ref())?;
    let keep: Vec<usize> = (0..b)
        .filter(|&i| s[i] > 1e-24 * scale2.max(f64::MIN_POSITIVE))
        .collect();
    let mut q = Mat::<f64>::zeros(n, b);
    let mut mq = Mat::<f64>::zeros(n, b);
    let mut r = Mat::<f64>::zeros(b, b);
    let tk = Mat::from_fn(b, keep.len(), |t, c| u[(t, keep[c])] / s[keep[c]].sqrt());
    thin_ops::add_a_d(
        q.as_mut().subcols_mut(0, keep.len()),
        w.as_ref(),
        tk.as_ref(),
        1.0,
    );
    thin_ops::add_a_d(
        mq.as_mut().subcols_mut(0, keep.len()),
        mw.as_ref(),
        tk.as_ref(),
        1.0,
    );
    for (c, &i) in keep.iter().enumerate() {
        let sq = s[i].sqrt();
        for t in 0..b {
            r[(c, t)] = sq * u[(t, i)];
        }
    }
    let kq = keep.len();
    rewhiten(
        q.as_mut().subcols_mut(0, kq),
        mq.as_mut().subcols_mut(0, kq),
        r.as_mut().subrows_mut(0, kq),
    )?;
    if kq < b {
        // pad with A·random, orthogonal to v and to the kept part of q
        let z = random_block(n, b - kq, seed);
        let mut pz = spmm(m, z.as_ref());
        op.solve(pz.as_mut())?;
        *solves += b - kq;
        // against v, then against the kept part of q (M-orthogonal to v)
        let pz = gram_schmidt::twice(v, mv, m, pz);
        let pz = gram_schmidt::twice(
            q.as_ref().subcols(0, kq),
            Some(mq.as_ref().subcols(0, kq)),
            m,
            pz,
        );
        let mpz = spmm(m, pz.as_ref());
        let g = pz.transpose() * &mpz;
        let (s2, u2) = dense::eigh(g.as_ref())?;
        if s2.iter().any(|&x| x.is_nan() || x <= 0.0) {
            return Err(SolveError::NotConverged {
                requested: 0,
                steps: 0,
            });
        }
        let t = Mat::from_fn(b - kq, b - kq, |i, j| u2[(i, j)] / s2[j].sqrt());
        q.as_mut()
            .subcols_mut(kq, b - kq)
            .copy_from((&pz * &t).as_ref());
        mq.as_mut()
            .subcols_mut(kq, b - kq)
            .copy_from((&mpz * &t).as_ref());
    }
    Ok((q, mq, r))
}

/// Largest |QᵀMQ − I| a whitening may leave before [`rewhiten`] whitens the block again.
const WHITE_TOL: f64 = 1e-15;

/// The second whitening of an M-QR (SVQB twice; Stathopoulos & Wu 2002, eq. 4.1): one whitening
/// Q = W·U·S^{-1/2} leaves |QᵀMQ − I| of order ε·cond(WᵀMW) (traced up to 1.4e-14 on the cb
/// suite's 68.5k blocks, 1.4e-12 on the eigen suite's 20k); when it exceeds [`WHITE_TOL`], G = QᵀMQ = U₂S₂U₂ᵀ whitens it again, Q ← Q·U₂S₂^{-1/2},
/// M·Q likewise, and R ← S₂^{1/2}U₂ᵀR keeps W = Q·R. Costs three n × b × b products. Only a
/// rounding-level correction: a block whose QᵀMQ has an eigenvalue outside (1/2, 2) is left as it
/// is.
fn rewhiten(
    mut q: faer::MatMut<'_, f64>,
    mut mq: faer::MatMut<'_, f64>,
    mut r: faer::MatMut<'_, f64>,
) -> Result<(), SolveError> {
    let k = q.ncols();
    if k == 0 {
        return Ok(());
    }
    let g = q.as_ref().transpose() * mq.as_ref();
    if off_identity(g.as_ref()) <= WHITE_TOL {
        return Ok(());
    }
    let (s, u) = dense::eigh(g.as_ref())?;
    if s.iter().any(|x| !(0.5..2.0).contains(x)) {
        // Not a rounding matter: the block holds directions near the M-QR's relative-norm limit
        // (a Krylov space nearly exhausted), which one whitening leaves far from M-orthonormal;
        // whitening them again would magnify what the Gram–Schmidt pass left of V in them. The
        // block stays as the one whitening made it, as before this second whitening existed.
        return Ok(());
    }
    let t = Mat::from_fn(k, k, |i, j| u[(i, j)] / s[j].sqrt());
    let q2 = q.as_ref() * &t;
    let mq2 = mq.as_ref() * &t;
    q.copy_from(q2.as_ref());
    mq.copy_from(mq2.as_ref());
    let tinv = Mat::from_fn(k, k, |i, j| s[i].sqrt() * u[(j, i)]);
    let r2 = &tinv * r.as_ref();
    r.copy_from(r2.as_ref());
    Ok(())
}

/// The largest |G − I| entry of a square Gram matrix G (how far a block is from orthonormal).
fn off_identity(g: MatRef<'_, f64>) -> f64 {
    let k = g.nrows();
    (0..k)
        .flat_map(|i| (0..k).map(move |j| (i, j)))
        .map(|(i, j)| (g[(i, j)] - f64::from(u8::from(i == j))).abs())
        .fold(0.0, f64::max)
}

/// The first `p` columns of the kept M·V, if it is kept.
fn mv_of(mvbuf: Option<&Mat<f64>>, p: usize) -> Option<MatRef<'_, f64>> {
    mvbuf.map(|x| x.as_ref().subcols(0, p))
}

/// Deterministic pseudo-random block (xorshift; `seed` must be non-zero and is advanced),
/// entries in (−1, 1).
pub fn random_block(n: usize, b: usize, seed: &mut u64) -> Mat<f64> {
    Mat::from_fn(n, b, |_, _| {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    })
}

/// Whether a step at basis size `p` computes the Ritz pairs of T although no restart needs
/// them. T's dense eigensolve costs ~9p³ flops against ~4npb for the step's Gram–Schmidt: every
/// step while it costs no more than that, else once the basis has grown by a tenth since the
/// last one (`last_p`), so a run of hundreds of modes makes tens of eigensolves, not hundreds,
/// and stops at most a tenth of its basis later than it could have.
fn ritz_due(n: usize, b: usize, p: usize, last_p: usize) -> bool {
    9 * p * p <= 4 * n * b || p >= last_p + b.max(last_p / 10)
}

/// Lowest `count` eigenpairs of (K, M) with the factorization `llt` of K − σM.
pub fn block_shift_invert(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    llt: &SparseLlt,
    sigma: f64,
    prm: &BlockParams,
) -> Result<BlockResult, SolveError> {
    let n = m.nrows();
    let b = prm.block.max(1);
    let mut count = prm.count;
    let mut max_basis = prm.max_basis.max(count + 3 * b).min(n);
    let mut keep = (count + b).max(max_basis / 2).min(max_basis - b);
    let mut max_steps = prm.max_steps;
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut solves = 0usize;
    let mut restarts = 0usize;
    // A x from M x: with `keep_mv` every block's M-image is kept (MV beside V), so a step costs
    // one product with M (M·F, which the Gram–Schmidt test and the M-QR share) instead of two.
    let seconds_solve = std::cell::Cell::new(0.0);
    let mut seconds_orth = 0.0;
    let mut seconds_restart = 0.0;
    let op = Operator {
        llt,
        k,
        sigma,
        target: prm.tol,
        refinement: std::cell::Cell::new(0),
    };
    let apply = |mx: &Mat<f64>, solves: &mut usize| -> Result<Mat<f64>, SolveError> {
        let t = std::time::Instant::now();
        let mut w = mx.clone();
        op.solve(w.as_mut())?;
        *solves += mx.ncols();
        seconds_solve.set(seconds_solve.get() + t.elapsed().as_secs_f64());
        Ok(w)
    };
    // V and M·V live in preallocated n × max_basis buffers: the basis grows by writing b columns
    // and shrinks at a restart, never by copying the whole basis into a new matrix (that copy
    // cost as much as the Gram–Schmidt passes).
    let mut vbuf = Mat::<f64>::zeros(n, max_basis);
    let mut mvbuf = prm.keep_mv.then(|| Mat::<f64>::zeros(n, max_basis));
    // start: V = MQR(A Z), then A V = V T + F Eᵀ
    let z = random_block(n, b, &mut seed);
    let w0 = apply(&spmm(m, z.as_ref()), &mut solves)?;
    let empty = Mat::<f64>::zeros(n, 0);
    let s0 = w0.norm_max().powi(2);
    let w0 = gram_schmidt::orthogonalize(empty.as_ref(), None, m, w0)?;
    let (q0, mq0, _) = mqr(m, &op, empty.as_ref(), None, w0, s0, &mut seed, &mut solves)?;
    vbuf.as_mut().subcols_mut(0, b).copy_from(&q0);
    if let Some(mvbuf) = &mut mvbuf {
        mvbuf.as_mut().subcols_mut(0, b).copy_from(&mq0);
    }
    let mut p = b;
    let w = apply(&mq0, &mut solves)?;
    let mut f =
        gram_schmidt::orthogonalize(vbuf.as_ref().subcols(0, p), mv_of(mvbuf.as_ref(), p), m, w)?;
    let mut t = f.coef.clone();
    let mut tally = GsTally::default();
    tally.add(&f);
    let mut e = Mat::<f64>::identity(b, b);
    let mut step = 0;
    let (mut last_ritz_p, mut ritz_solves) = (0, 0);
    while step < max_steps {
        step += 1;
        // M-QR of the residual block (already M-orthogonal to V: Gram–Schmidt'd when it
        // was formed, and V only shrinks to V·Y_k at a restart)
        let fscale = t.norm_max().powi(2);
        let clock = std::time::Instant::now();
        let (q, mq, rf) = mqr(
            m,
            &op,
            vbuf.as_ref().subcols(0, p),
            mv_of(mvbuf.as_ref(), p),
            f,
            fscale,
            &mut seed,
            &mut solves,
        )?;
        seconds_orth += clock.elapsed().as_secs_f64();
        // The Ritz pairs (a dense eigensolve of the p × p T) where they can end the run or a
        // restart needs them: every step while that is cheap, then at growing intervals.
        if p + b > max_basis || ritz_due(n, b, p, last_ritz_p) {
            last_ritz_p = p;
            ritz_solves += 1;
            let ts = dense::sym(t.as_ref());
            let (theta_asc, y_asc) = dense::eigh(ts.as_ref())?;
            // descending θ = ascending λ
            let order: Vec<usize> = (0..p).rev().collect();
            let theta: Vec<f64> = order.iter().map(|&i| theta_asc[i]).collect();
            let y = Mat::from_fn(p, p, |r, c| y_asc[(r, order[c])]);
            let ey = e.transpose() * &y; // b × p
            let est = &rf * &ey;
            let nconv = (0..count.min(p))
                .take_while(|&j| {
                    let r = est.col(j).norm_l2();
                    theta[j] > 0.0 && r <= prm.tol * theta[j].abs()
                })
                .count();
            super::progress::report(super::progress::Event::Eigen {
                converged: nconv,
                wanted: count,
            });
            // band mode: done at the first converged value above `upper`, or grow the count
            let lambda = |j: usize| sigma + 1.0 / theta[j];
            let done = match prm.upper {
                None => (p >= count && nconv == count).then_some(count),
                Some(u) => match (0..nconv).find(|&j| lambda(j) > u) {
                    Some(j) => Some(j + 1),
                    None if p >= count && nconv == count && count >= prm.max_count => Some(count),
                    None if p >= count && nconv == count => {
                        let grown = (2 * count).min(prm.max_count);
                        max_steps += 20 * (grown - count).div_ceil(b);
                        count = grown;
                        let basis = max_basis.max(super::default_basis(count, b)).min(n);
                        if basis > max_basis {
                            let wider = |old: MatRef<'_, f64>| {
                                let mut v = Mat::<f64>::zeros(n, basis);
                                v.as_mut().subcols_mut(0, p).copy_from(old.subcols(0, p));
                                v
                            };
                            vbuf = wider(vbuf.as_ref());
                            mvbuf = mvbuf.as_ref().map(|x| wider(x.as_ref()));
                            max_basis = basis;
                        }
                        keep = (count + b).max(max_basis / 2).min(max_basis - b);
                        None
                    }
                    None => None,
                },
            };
            if let Some(c) = done {
                let x = vbuf.as_ref().subcols(0, p) * y.as_ref().subcols(0, c);
                let values = theta[..c].iter().map(|&th| sigma + 1.0 / th).collect();
                return Ok(BlockResult {
                    values,
                    vectors: x,
                    solves,
                    refinement_solves: op.refinement.get(),
                    steps: step - 1,
                    restarts,
                    ritz_solves,
                    seconds_solve: seconds_solve.get(),
                    seconds_orth,
                    seconds_restart,
                    gram_schmidt: tally,
                });
            }
            if p + b > max_basis {
                let clock = std::time::Instant::now();
                let yk = y.as_ref().subcols(0, keep);
                thin_ops::mul_in_place(vbuf.as_mut(), yk);
                if let Some(mvbuf) = &mut mvbuf {
                    thin_ops::mul_in_place(mvbuf.as_mut(), yk);
                }
                t = Mat::from_fn(keep, keep, |i, j| if i == j { theta[i] } else { 0.0 });
                e = yk.transpose() * &e;
                p = keep;
                restarts += 1;
                seconds_restart += clock.elapsed().as_secs_f64();
            }
        }
        // expand with Q: A Q = [V Q] C + F'
        let aq = apply(&mq, &mut solves)?;
        vbuf.as_mut().subcols_mut(p, b).copy_from(&q);
        if let Some(mvbuf) = &mut mvbuf {
            mvbuf.as_mut().subcols_mut(p, b).copy_from(&mq);
        }
        let clock = std::time::Instant::now();
        let fnew = gram_schmidt::orthogonalize(
            vbuf.as_ref().subcols(0, p + b),
            mv_of(mvbuf.as_ref(), p + b),
            m,
            aq,
        )?;
        seconds_orth += clock.elapsed().as_secs_f64();
        tally.add(&fnew);
        let mut tn = Mat::<f64>::zeros(p + b, p + b);
        tn.as_mut().submatrix_mut(0, 0, p, p).copy_from(t.as_ref());
        tn.as_mut()
            .submatrix_mut(0, p, p + b, b)
            .copy_from(fnew.coef.as_ref());
        let re = &rf * e.transpose(); // b × p
        tn.as_mut().submatrix_mut(p, 0, b, p).copy_from(re.as_ref());
        t = tn;
        e = Mat::from_fn(p + b, b, |i, j| if i == p + j { 1.0 } else { 0.0 });
        p += b;
        f = fnew;
    }
    Err(SolveError::NotConverged {
        requested: count,
        steps: max_steps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::{SparseColMat, Triplet};

    fn params(count: usize, block: usize, keep_mv: bool) -> BlockParams {
        BlockParams {
            count,
            block,
            max_basis: 3 * count,
            tol: 1e-10,
            max_steps: 400,
            upper: None,
            max_count: count,
            keep_mv,
        }
    }

    fn sparse(n: usize, entries: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
        let t: Vec<_> = entries
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
    }

    /// A fixed chain of `n` dofs: K tridiagonal (2, −1), M = h·I; λ_j = (2 − 2 cos(jπ/(n+1)))/h.
    fn fixed_chain(n: usize, h: f64) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
        let mut k = vec![];
        for i in 0..n {
            k.push((i, i, 2.0));
            if i + 1 < n {
                k.push((i, i + 1, -1.0));
                k.push((i + 1, i, -1.0));
            }
        }
        let m = sparse(n, &(0..n).map(|i| (i, i, h)).collect::<Vec<_>>());
        (sparse(n, &k), m)
    }

    /// The largest |QᵀMQ − I| of a block, M diagonal (`d`), M·Q formed afresh.
    fn whiteness(q: MatRef<'_, f64>, d: &[f64]) -> f64 {
        let mq = Mat::from_fn(q.nrows(), q.ncols(), |r, c| d[r] * q[(r, c)]);
        off_identity((q.transpose() * &mq).as_ref())
    }

    #[test]
    fn rewhiten_brings_an_ill_conditioned_block_to_rounding_and_keeps_w_equal_q_r() {
        // W: five nearly parallel columns (cond(WᵀMW) ≈ 1e6…1e7: one whitening leaves 2.7e-10,
        // more than the 1.4e-12 traced on the 20k eigen suite), M = diag(d) over 1e-2…1e2.
        let (n, k) = (300, 5);
        let d: Vec<f64> = (0..n)
            .map(|i| 10f64.powf(-2.0 + 4.0 * i as f64 / n as f64))
            .collect();
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let base = random_block(n, 1, &mut seed);
        let noise = random_block(n, k, &mut seed);
        let w = Mat::from_fn(n, k, |r, c| base[(r, 0)] + 1e-3 * noise[(r, c)]);
        let mw = Mat::from_fn(n, k, |r, c| d[r] * w[(r, c)]);
        // one whitening (SVQB): Q = W·U·S^{-1/2}, R = S^{1/2}·Uᵀ
        let g = w.transpose() * &mw;
        let (s, u) = dense::eigh(g.as_ref()).unwrap(); // 5 × 5 symmetric: eigh cannot fail
        let t = Mat::from_fn(k, k, |i, j| u[(i, j)] / s[j].sqrt());
        let mut q = &w * &t;
        let mut mq = &mw * &t;
        let mut r = Mat::from_fn(k, k, |i, j| s[i].sqrt() * u[(j, i)]);
        let once = whiteness(q.as_ref(), &d);
        assert!(
            once > 1e-12,
            "the case must need a second whitening: {once:.1e}"
        );
        rewhiten(q.as_mut(), mq.as_mut(), r.as_mut()).unwrap();
        // What rewhiten sees is Qᵀ(M·Q) with the M·Q carried along (as the eigensolver keeps it):
        // that is whitened to rounding. Q's and M·Q's own rounding (ε·√cond(WᵀMW) of them, formed
        // from nearly parallel columns) bounds QᵀMQ formed afresh.
        let carried = off_identity((q.transpose() * &mq).as_ref());
        // (rounding level here: n = 300 terms of a Gram whose M spans four decades)
        assert!(
            carried <= 5e-14,
            "|Qᵀ(MQ) − I| after the second whitening: {carried:.1e}"
        );
        let twice = whiteness(q.as_ref(), &d);
        assert!(
            twice <= 1e-3 * once && twice <= 1e-13,
            "|QᵀMQ − I| once {once:.1e}, twice {twice:.1e}"
        );
        // M·Q follows Q, and Q·R is still W (to the rounding of W's own conditioning)
        let mq_err = (0..n)
            .flat_map(|r| (0..k).map(move |c| (r, c)))
            .map(|(r, c)| (mq[(r, c)] - d[r] * q[(r, c)]).abs())
            .fold(0.0, f64::max);
        assert!(mq_err <= 1e-12 * mq.norm_max(), "M·Q off by {mq_err:.1e}");
        let back = (&q * &r - &w).norm_max() / w.norm_max();
        assert!(back <= 1e-9, "Q·R − W: {back:.1e}");
    }

    #[test]
    fn rewhiten_leaves_a_block_far_from_m_orthonormal_as_it_is() {
        // QᵀMQ with an eigenvalue 4 (outside (1/2, 2)): not a rounding matter, left unchanged.
        let (n, k) = (50, 3);
        let d = vec![1.0; n];
        let mut q = Mat::from_fn(n, k, |r, c| f64::from(u8::from(r == c)));
        q[(0, 0)] = 2.0;
        let mut mq = q.clone();
        let mut r = Mat::from_fn(k, k, |i, j| f64::from(u8::from(i == j)));
        let before = (q.clone(), r.clone());
        rewhiten(q.as_mut(), mq.as_mut(), r.as_mut()).unwrap();
        assert!(whiteness(q.as_ref(), &d) > 2.9);
        assert_eq!((q, r), before);
    }

    /// The lean basis (no M·V) and the kept one both find the closed-form spectrum of a fixed
    /// chain, λ_j = (2 − 2 cos(jπ/(n+1)))/h with M = h·I, with M-orthonormal vectors; and on a
    /// spectrum of five distinct values (the Krylov space is exhausted after five blocks, so the
    /// M-QR pads with random directions) both give the lowest value, 40-fold, 8 times.
    #[test]
    fn lean_and_kept_basis_agree_with_closed_form() {
        let (n, h) = (400usize, 0.25);
        let (k, m) = fixed_chain(n, h);
        let llt = SparseLlt::factor(k.as_ref(), None, faer::Par::Seq).unwrap();
        for keep_mv in [true, false] {
            let r = block_shift_invert(k.as_ref(), m.as_ref(), &llt, 0.0, &params(12, 4, keep_mv))
                .unwrap();
            for (j, &l) in r.values.iter().enumerate() {
                let exact = (2.0
                    - 2.0 * ((j + 1) as f64 * std::f64::consts::PI / (n + 1) as f64).cos())
                    / h;
                assert!(
                    (l - exact).abs() <= 1e-10 * exact,
                    "keep_mv {keep_mv} λ{j} {l} vs {exact}"
                );
            }
            let g = r.vectors.transpose() * spmm(m.as_ref(), r.vectors.as_ref());
            let off = (&g - Mat::<f64>::identity(12, 12)).norm_max();
            assert!(off <= 1e-12, "keep_mv {keep_mv}: ‖XᵀMX − I‖ {off:.1e}");
        }
        // λ = 1 and 2 three-fold (within a block of 4), 3, 4, 5 many-fold: the Krylov space holds
        // at most 3 + 3 + 3·4 = 18 directions
        let value = |i: usize| match i {
            0..3 => 1.0,
            3..6 => 2.0,
            _ => 3.0 + (i % 3) as f64,
        };
        let kd = sparse(n, &(0..n).map(|i| (i, i, value(i))).collect::<Vec<_>>());
        let id = sparse(n, &(0..n).map(|i| (i, i, 1.0)).collect::<Vec<_>>());
        let llt = SparseLlt::factor(kd.as_ref(), None, faer::Par::Seq).unwrap();
        for keep_mv in [true, false] {
            let r = block_shift_invert(kd.as_ref(), id.as_ref(), &llt, 0.0, &params(8, 4, keep_mv))
                .unwrap();
            eprintln!(
                "keep {keep_mv} solves {} steps {} restarts {}",
                r.solves, r.steps, r.restarts
            );
            let want = [1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 3.0, 3.0];
            assert_eq!(r.values.len(), 8);
            for (&l, w) in r.values.iter().zip(want) {
                assert!(
                    (l - w).abs() <= 1e-10 * w,
                    "keep_mv {keep_mv}: {:?}",
                    r.values
                );
            }
        }
    }

    /// A run of 100 modes on a 1500-dof chain, where T's eigensolve costs more than a step's
    /// Gram–Schmidt past p = 51 (`ritz_due`): the Ritz pairs are computed at intervals (fewer
    /// eigensolves than steps) and the 100 values are the closed form's to 1e-10, the vectors
    /// M-orthonormal — the same accuracy as a run checking every step.
    #[test]
    fn ritz_pairs_at_intervals_keep_the_closed_form() {
        let (n, h) = (1500usize, 0.25);
        let (k, m) = fixed_chain(n, h);
        let llt = SparseLlt::factor(k.as_ref(), None, faer::Par::Seq).unwrap();
        let r =
            block_shift_invert(k.as_ref(), m.as_ref(), &llt, 0.0, &params(100, 4, true)).unwrap();
        eprintln!(
            "solves {} steps {} eigensolves {}",
            r.solves, r.steps, r.ritz_solves
        );
        assert!(
            r.ritz_solves * 2 < r.steps,
            "{} eigensolves in {} steps",
            r.ritz_solves,
            r.steps
        );
        for (j, &l) in r.values.iter().enumerate() {
            let exact =
                (2.0 - 2.0 * ((j + 1) as f64 * std::f64::consts::PI / (n + 1) as f64).cos()) / h;
            assert!((l - exact).abs() <= 1e-10 * exact, "λ{j} {l} vs {exact}");
        }
        let g = r.vectors.transpose() * spmm(m.as_ref(), r.vectors.as_ref());
        let off = (&g - Mat::<f64>::identity(100, 100)).norm_max();
        assert!(off <= 1e-12, "‖XᵀMX − I‖ {off:.1e}");
    }
}
