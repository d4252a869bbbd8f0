//! Where AMLS spends its time: counts and seconds per phase, gathered while it runs (the
//! measurement behind docs/amls.md's speed tables and the `harness amls` JSON).

use std::cell::Cell;
use std::time::Instant;

/// Counts and seconds of one AMLS run, phase by phase.
#[derive(Clone, Debug, Default)]
pub struct Profile {
    /// Dense leaf eigenproblems solved (the cutoff estimate's and the bases'), their seconds.
    pub leaf_pencils: Cell<usize>,
    /// Seconds of the leaf eigenproblems.
    pub leaf_seconds: Cell<f64>,
    /// Sparse factorizations of subtrees (A_TT), their flops (the analysis's count), seconds.
    pub factorizations: Cell<usize>,
    /// Flops of the subtree factorizations.
    pub factor_flops: Cell<f64>,
    /// Seconds of the subtree factorizations (ordering, analysis and numeric).
    pub factor_seconds: Cell<f64>,
    /// Right-hand-side columns solved with a subtree factor (a half solve, L⁻¹ or L⁻ᵀ alone,
    /// counts one half), and their seconds.
    pub solved_columns: Cell<f64>,
    /// Seconds of those solves.
    pub solve_seconds: Cell<f64>,
    /// Dense products with the subtree bases (couplings Φᵀ W, expansions Φ Y): flops, seconds.
    pub basis_flops: Cell<f64>,
    /// Seconds of the dense basis products.
    pub basis_seconds: Cell<f64>,
    /// Separator pencils solved densely, the largest one's order, their seconds.
    pub split_pencils: Cell<usize>,
    /// Order of the largest separator pencil.
    pub largest_pencil: Cell<usize>,
    /// Σ order³ of the separator pencils (their dense eigensolver's work ∝ this).
    pub pencil_cubes: Cell<f64>,
    /// Seconds of the separator pencils.
    pub pencil_seconds: Cell<f64>,
    /// Seconds of the refinement's factorization of the full K − σM.
    pub refine_factor_seconds: Cell<f64>,
    /// Columns solved by the refinement.
    pub refine_columns: Cell<usize>,
    /// Seconds of the refinement's solves.
    pub refine_solve_seconds: Cell<f64>,
    /// Seconds of the Rayleigh–Ritz steps (each K·X, M·X, the projected problem, X·Q).
    pub ritz_seconds: Cell<f64>,
}

impl Profile {
    /// Adds `secs` to a seconds cell.
    pub fn add(cell: &Cell<f64>, secs: f64) {
        cell.set(cell.get() + secs);
    }

    /// Adds `n` to a count cell.
    pub fn count(cell: &Cell<usize>, n: usize) {
        cell.set(cell.get() + n);
    }

    /// Runs `f`, adding its seconds to `cell`.
    pub fn time<R>(cell: &Cell<f64>, f: impl FnOnce() -> R) -> R {
        let t = Instant::now();
        let r = f();
        Self::add(cell, t.elapsed().as_secs_f64());
        r
    }
}
