//! What a mode set records of the eigenproblem behind it: which problem and solver, each
//! mode's eigenvalue and relative residual on the problem's own K and M, and the inertia count
//! when the band was verified — the file's `eigen_residuals.bin` (format 1.9, SPEC §5.17).

use faer::MatRef;

use crate::solve::{
    residual::relative_residuals, trace_ratio, EigenSolution, Solver, SparseColMat,
};

/// Which eigenproblem of a method reaches its basis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EigenProblem {
    /// Normal modes of the (constrained) model: the set's modes.
    NormalModes,
    /// Craig–Bampton's fixed-interface modes (K_ii, M_ii).
    FixedInterface,
    /// Craig–Chang's and Dietz's free-free modes.
    FreeFree,
}

/// The eigenpairs of one problem as the basis took them, with their residuals.
#[derive(Clone, Debug, PartialEq)]
pub struct EigenRecord {
    /// Which problem.
    pub problem: EigenProblem,
    /// Which solver produced the pairs.
    pub solver: Solver,
    /// s, the median of K_ii/M_ii of the problem ([`trace_ratio`]).
    pub scale: f64,
    /// ω² per mode, as returned.
    pub omega2: Vec<f64>,
    /// ‖Kφ − λMφ‖₂ / max(‖Kφ‖₂, 10⁻⁸ s ‖Mφ‖₂) per mode ([`relative_residuals`]).
    pub residuals: Vec<f64>,
    /// Sylvester's count when the band was verified: (eigenvalues below σ, σ).
    pub inertia: Option<(usize, f64)>,
}

impl EigenRecord {
    /// The record of `s`, a solution of K φ = λ M φ with these `k`, `m`: the residuals are
    /// computed here from the vectors (one K·φ and M·φ per mode), not taken from the solver.
    pub fn of(
        problem: EigenProblem,
        k: &SparseColMat<usize, f64>,
        m: &SparseColMat<usize, f64>,
        s: &EigenSolution,
    ) -> Self {
        Self::from_pairs(
            problem,
            s.info.solver,
            (k, m),
            (s.vectors.as_ref(), &s.eigenvalues),
            s.info.band_proof,
        )
    }

    /// [`EigenRecord::of`] for pairs that come without an [`EigenSolution`] (the SLEPc
    /// engine's fixed-interface modes): `vectors` n × modes, `omega2` per mode.
    pub fn from_pairs(
        problem: EigenProblem,
        solver: Solver,
        (k, m): (&SparseColMat<usize, f64>, &SparseColMat<usize, f64>),
        (vectors, omega2): (MatRef<'_, f64>, &[f64]),
        inertia: Option<(usize, f64)>,
    ) -> Self {
        let scale = trace_ratio(k, m);
        EigenRecord {
            problem,
            solver,
            scale,
            residuals: relative_residuals(k, m, vectors, omega2, scale),
            omega2: omega2.to_vec(),
            inertia,
        }
    }

    /// The entries `keep` (indices into the record), in that order.
    pub fn pick(&self, keep: &[usize]) -> Self {
        EigenRecord {
            omega2: keep.iter().map(|&j| self.omega2[j]).collect(),
            residuals: keep.iter().map(|&j| self.residuals[j]).collect(),
            ..self.clone()
        }
    }
}
