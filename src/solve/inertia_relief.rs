//! Inertia-relief static solves: y with K y = P f, P = I − M Xr Xrᵀ, Xrᵀ M y = 0, on an
//! automatically chosen statically determinate support (MotionView flexbody theory, "Craig-Chang
//! modes"). Used by Craig–Chang's and Dietz's attachment vectors, the residual vectors and the
//! preload's static solve of a free body.

use super::dense::determinate_support;
use super::{sparse_ops, EigenSpec, SolveError, SparseColMat, SparseLlt};
use faer::Mat;

/// Inertia-relief static solver: y with K y = P f, Xrᵀ M y = 0 (f → P f → support solve → purify).
pub struct InertiaRelief<'a> {
    m: &'a SparseColMat<usize, f64>,
    xr: Mat<f64>,
    free: Vec<usize>,
    llt: SparseLlt,
    /// The support dofs (sorted; empty without rigid modes).
    pub support: Vec<usize>,
}

impl<'a> InertiaRelief<'a> {
    /// Factors K on the dofs outside the support [`support_of`] picks for the rigid modes `xr`
    /// (n × r, M-orthonormal; none: K itself), or [`SolveError::NoDeterminateSupport`].
    pub fn new(
        k: &SparseColMat<usize, f64>,
        m: &'a SparseColMat<usize, f64>,
        xr: Mat<f64>,
        eig: &EigenSpec,
    ) -> Result<Self, SolveError> {
        let support = support_of(&xr)?;
        Self::on_support(k, m, xr, support, eig)
    }

    /// [`InertiaRelief::new`] on a `support` already found by [`support_of`]: the pivot `dof` of
    /// a [`SolveError::NonPositivePivot`] indexes `sparse_ops::complement(&support, n)`.
    pub fn on_support(
        k: &SparseColMat<usize, f64>,
        m: &'a SparseColMat<usize, f64>,
        xr: Mat<f64>,
        support: Vec<usize>,
        eig: &EigenSpec,
    ) -> Result<Self, SolveError> {
        let free = sparse_ops::complement(&support, k.nrows());
        let kff = sparse_ops::submatrix(k.as_ref(), &free, &free)?;
        let llt = SparseLlt::factor(kff.as_ref(), None, eig.par)?;
        Ok(Self {
            m,
            xr,
            free,
            llt,
            support,
        })
    }

    /// P f = f − M Xr Xrᵀ f.
    pub fn equilibrate(&self, f: &Mat<f64>) -> Mat<f64> {
        if self.xr.ncols() == 0 {
            return f.clone();
        }
        let c = self.xr.transpose() * f;
        let mxr = sparse_ops::spmm(self.m.as_ref(), self.xr.as_ref());
        f - &mxr * &c
    }

    /// y = purify(K_ff⁻¹ f_f) for an already equilibrated f.
    pub fn solve_equilibrated(&self, f: &Mat<f64>) -> Mat<f64> {
        let n = f.nrows();
        let mut rhs = Mat::from_fn(self.free.len(), f.ncols(), |r, j| f[(self.free[r], j)]);
        self.llt.solve_in_place(rhs.as_mut());
        let mut y = Mat::<f64>::zeros(n, f.ncols());
        for j in 0..f.ncols() {
            for (r, &i) in self.free.iter().enumerate() {
                y[(i, j)] = rhs[(r, j)];
            }
        }
        self.purify(y)
    }

    /// y − Xr Xrᵀ M y.
    pub fn purify(&self, y: Mat<f64>) -> Mat<f64> {
        if self.xr.ncols() == 0 {
            return y;
        }
        let my = sparse_ops::spmm(self.m.as_ref(), y.as_ref());
        let c = self.xr.transpose() * &my;
        &y - &self.xr * &c
    }
}

/// The support [`InertiaRelief::new`] holds for the rigid modes `xr`: empty without rigid modes.
pub fn support_of(xr: &Mat<f64>) -> Result<Vec<usize>, SolveError> {
    if xr.ncols() == 0 {
        return Ok(Vec::new());
    }
    determinate_support(xr).ok_or(SolveError::NoDeterminateSupport)
}
