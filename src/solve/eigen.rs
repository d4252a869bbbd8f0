//! Our block shift-invert eigensolver for the lowest eigenpairs of K x = λ M x (M ⪰ 0).
//!
//! The search space grows by blocks W = (K − σM)⁻¹ R of the residuals R = KX − MXΛ of the lowest
//! unconverged Ritz vectors; since (K − σM)⁻¹r = x − (λ − σ)(K − σM)⁻¹Mx this is the block Krylov
//! space of the shift-invert operator (K − σM)⁻¹M, built without cancellation. The basis is kept
//! M-orthonormal by full reorthogonalization (block classical Gram–Schmidt, twice, then an
//! eigen-based orthonormalization of the block that drops dependent directions), the projection
//! H = VᵀKV is grown block by block, and when the basis is full it is thick-restarted onto its
//! lowest Ritz vectors (V ← VY, H ← diag(θ)). Vectors in the range of (K − σM)⁻¹M have positive
//! M-norm, so massless dofs need no special treatment. Convergence is relative:
//! ‖Kx − θMx‖ ≤ tol·(‖Kx‖ + (|θ| + |σ|)‖Mx‖), with a rounding floor.

use super::cholesky::SparseLlt;
use super::dense;
use super::sparse_ops::spmm;
use super::SolveError;
use faer::sparse::SparseColMatRef;
use faer::Mat;

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
    /// Maximal number of block steps.
    pub max_steps: usize,
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
    /// Number of block steps.
    pub steps: usize,
    /// Number of thick restarts.
    pub restarts: usize,
}

struct Space<'a> {
    k: SparseColMatRef<'a, usize, f64>,
    m: SparseColMatRef<'a, usize, f64>,
    v: Mat<f64>,
    h: Mat<f64>,
}

impl Space<'_> {
    /// Appends the M-orthonormalized part of `w` that is independent of the basis; returns how
    /// many vectors were added.
    fn add(&mut self, mut w: Mat<f64>) -> Result<usize, SolveError> {
        // unit M-norm columns, so that the drop threshold below is relative
        let mw = spmm(self.m, w.as_ref());
        let mut cols = Vec::new();
        for j in 0..w.ncols() {
            let nrm = w.col(j).transpose() * mw.col(j);
            if nrm.is_finite() && nrm > 0.0 {
                cols.push((j, 1.0 / nrm.sqrt()));
            }
        }
        let mut w2 = Mat::<f64>::zeros(w.nrows(), cols.len());
        for (c, &(j, s)) in cols.iter().enumerate() {
            for i in 0..w.nrows() {
                w2[(i, c)] = w[(i, j)] * s;
            }
        }
        w = w2;
        for _round in 0..2 {
            if w.ncols() == 0 {
                return Ok(0);
            }
            for _pass in 0..2 {
                if self.v.ncols() > 0 {
                    let mw = spmm(self.m, w.as_ref());
                    let c = self.v.transpose() * &mw;
                    w -= &self.v * &c;
                }
            }
            let mw = spmm(self.m, w.as_ref());
            let g = w.transpose() * &mw;
            let (s, u) = dense::eigh(g.as_ref())?;
            let smax = s.iter().fold(0.0f64, |a, &b| a.max(b));
            let keep: Vec<usize> = (0..s.len())
                .filter(|&i| s[i] > 1e-14f64.max(1e-14 * smax))
                .collect();
            let mut t = Mat::<f64>::zeros(u.nrows(), keep.len());
            for (c, &i) in keep.iter().enumerate() {
                let f = 1.0 / s[i].sqrt();
                for r in 0..u.nrows() {
                    t[(r, c)] = u[(r, i)] * f;
                }
            }
            w = &w * &t;
        }
        let q = w.ncols();
        if q == 0 {
            return Ok(0);
        }
        let kw = spmm(self.k, w.as_ref());
        let p = self.v.ncols();
        let vkw = self.v.transpose() * &kw;
        let wkw = w.transpose() * &kw;
        let mut h = Mat::<f64>::zeros(p + q, p + q);
        for j in 0..p {
            for i in 0..p {
                h[(i, j)] = self.h[(i, j)];
            }
        }
        for j in 0..q {
            for i in 0..p {
                h[(i, p + j)] = vkw[(i, j)];
                h[(p + j, i)] = vkw[(i, j)];
            }
            for i in 0..q {
                h[(p + i, p + j)] = 0.5 * (wkw[(i, j)] + wkw[(j, i)]);
            }
        }
        let n = self.v.nrows();
        let mut v = Mat::<f64>::zeros(n, p + q);
        v.as_mut().subcols_mut(0, p).copy_from(self.v.as_ref());
        v.as_mut().subcols_mut(p, q).copy_from(w.as_ref());
        self.v = v;
        self.h = h;
        Ok(q)
    }
}

/// Deterministic pseudo-random block (xorshift), entries in (−1, 1).
fn random_block(n: usize, b: usize, seed: &mut u64) -> Mat<f64> {
    Mat::from_fn(n, b, |_, _| {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    })
}

/// Lowest `count` eigenpairs of (K, M) with the factorization `llt` of K − σM.
pub fn block_shift_invert(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    llt: &SparseLlt,
    sigma: f64,
    prm: &BlockParams,
) -> Result<BlockResult, SolveError> {
    let n = k.nrows();
    let b = prm.block.max(1);
    let count = prm.count;
    let keep = count + b;
    let max_basis = prm.max_basis.max(keep + b).min(n);
    let knorm = (0..n)
        .map(|j| k.val_of_col(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mnorm = (0..n)
        .map(|j| m.val_of_col(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut space = Space {
        k,
        m,
        v: Mat::zeros(n, 0),
        h: Mat::zeros(0, 0),
    };
    let mut solves = 0usize;
    let mut restarts = 0usize;
    // start: (K − σM)⁻¹ M Z for a random block Z (purged of massless components)
    let z = random_block(n, b.max(count.min(2 * b)), &mut seed);
    let mut w = spmm(m, z.as_ref());
    llt.solve_in_place(w.as_mut());
    solves += w.ncols();
    space.add(w)?;
    for step in 0..prm.max_steps {
        let p = space.v.ncols();
        let (theta, y) = dense::eigh(space.h.as_ref())?;
        let ncheck = p.min(count + b);
        let x = &space.v * y.as_ref().subcols(0, ncheck);
        let kx = spmm(k, x.as_ref());
        let mx = spmm(m, x.as_ref());
        let mut r = kx.clone();
        let mut conv = vec![false; ncheck];
        for j in 0..ncheck {
            let mut rn = 0.0;
            let (mut kn, mut mn, mut xn) = (0.0, 0.0, 0.0);
            for i in 0..n {
                r[(i, j)] -= theta[j] * mx[(i, j)];
                rn += r[(i, j)] * r[(i, j)];
                kn += kx[(i, j)] * kx[(i, j)];
                mn += mx[(i, j)] * mx[(i, j)];
                xn += x[(i, j)] * x[(i, j)];
            }
            let scale = kn.sqrt() + (theta[j].abs() + sigma.abs()) * mn.sqrt();
            let floor = 64.0 * f64::EPSILON * (knorm + theta[j].abs() * mnorm) * xn.sqrt();
            conv[j] = rn.sqrt() <= (prm.tol * scale).max(floor);
        }
        if p >= count && conv[..count].iter().all(|&c| c) {
            let values = theta[..count].to_vec();
            let vectors = x.as_ref().subcols(0, count).to_owned();
            return Ok(BlockResult {
                values,
                vectors,
                solves,
                steps: step,
                restarts,
            });
        }
        let sel: Vec<usize> = (0..ncheck).filter(|&j| !conv[j]).take(b).collect();
        let mut w = Mat::<f64>::zeros(n, sel.len());
        for (c, &j) in sel.iter().enumerate() {
            w.col_mut(c).copy_from(r.col(j));
        }
        llt.solve_in_place(w.as_mut());
        solves += w.ncols();
        if p + w.ncols() > max_basis {
            let kk = keep.min(p);
            space.v = &space.v * y.as_ref().subcols(0, kk);
            space.h = Mat::from_fn(kk, kk, |i, j| if i == j { theta[i] } else { 0.0 });
            restarts += 1;
        }
        let added = space.add(w)?;
        if added == 0 {
            if space.v.ncols() >= n {
                return Err(SolveError::NotConverged {
                    requested: count,
                    steps: step,
                });
            }
            let z = random_block(n, b, &mut seed);
            let mut w = spmm(m, z.as_ref());
            llt.solve_in_place(w.as_mut());
            solves += w.ncols();
            space.add(w)?;
        }
    }
    Err(SolveError::NotConverged {
        requested: count,
        steps: prm.max_steps,
    })
}
