//! Sparse factorizations (METIS-ordered Cholesky) and the block shift-invert eigensolver.
//!
//! [`lowest_modes`] returns the lowest eigenpairs of K φ = ω² M φ for full symmetric sparse K, M
//! (M positive semi-definite: lumped, consistent, massless dofs allowed), M-orthonormal, each
//! result checked (ΦᵀMΦ, ΦᵀKΦ, residuals) before it is returned. Problems with n ≤
//! [`DENSE_MAX`] go to a dense solver. [`buckling`] gives the lowest buckling factor of a
//! preload (K φ = −λ K_G φ).

pub mod amls;
pub mod buckling;
pub mod cholesky;
pub mod dense;
pub mod eigen;
mod gram_schmidt;
pub mod inertia;
pub mod inertia_relief;
pub mod memory;
pub mod ordering;
pub mod progress;
pub mod residual;
mod rows;
pub mod slepc;
pub mod sparse_ops;
mod supernodal;
pub mod thin_ops;

pub use cholesky::{FactorStats, SparseLlt};
pub use faer;
pub use faer::sparse::{SparseColMat, Triplet};
pub use faer::Mat;
use faer::{MatRef, Par};
use thiserror::Error;

/// Default block size of the eigensolver. Block Krylov–Schur needs about 55 + 21·b solved
/// vectors for 30 modes (20k-dof tet10 block: 108/144/180/208 with b = 2/4/6/8), while a block
/// solve costs the same for every b that pads to the same lanes (`solve::supernodal`: 4, 8, 12
/// or 16): 6 and 8 both take 30 block solves at 69k dofs (180 and 240 vectors), and 6 orthogonalizes
/// fewer vectors. 4 would solve ~9 % faster but cannot hold the six-fold zero eigenvalue of a free
/// body in one block.
pub const DEFAULT_BLOCK: usize = 6;

/// Problems up to this size are solved densely.
pub const DENSE_MAX: usize = 300;

/// Errors of the factorizations and eigensolvers.
#[derive(Debug, Error)]
pub enum SolveError {
    /// Shapes do not fit.
    #[error("dimension mismatch: {0}")]
    Dimension(String),
    /// NaN or infinity in an input.
    #[error("non-finite value in {0}")]
    NonFinite(&'static str),
    /// The Cholesky factorization met a non-positive pivot.
    #[error("matrix not positive definite: non-positive pivot at dof {dof}")]
    NonPositivePivot { dof: usize },
    /// A dense K − σM was not positive definite.
    #[error("K - sigma*M is not positive definite for sigma = {shift:e}")]
    NotPositiveDefinite { shift: f64 },
    /// METIS failed.
    #[error("ordering failed: {0}")]
    Ordering(String),
    /// faer's symbolic analysis failed.
    #[error("factorization failed: {0}")]
    Factor(String),
    /// More modes than finite eigenvalues.
    #[error("{requested} modes requested but the problem has only {available} finite eigenvalues")]
    TooManyModes { requested: usize, available: usize },
    /// The iteration did not converge.
    #[error("eigensolver did not converge to {requested} modes in {steps} block steps")]
    NotConverged { requested: usize, steps: usize },
    /// The inertia count of K − σM holds more eigenvalues below σ than the solver returned.
    #[error(
        "band check failed: the eigensolver returned {found} modes below omega^2 = {sigma:e} but \
         K - sigma*M has {missing} more negative pivots (Sylvester's law of inertia): a mode was \
         missed inside the band, or a repeated eigenvalue was cut at the last mode (ask for one \
         more mode)"
    )]
    MissedModes {
        found: usize,
        missing: usize,
        sigma: f64,
    },
    /// A dense eigen-decomposition failed.
    #[error("dense eigensolver: {0}")]
    DenseEigen(String),
    /// A basis was not of full M-rank where it must be.
    #[error("basis is not of full rank in the mass metric")]
    DependentBasis,
    /// A result failed its check.
    #[error(
        "result check failed: {what} = {value:e} > {limit:e} (an ill-conditioned model, e.g. a \
         large stiffness contrast between materials, or an inaccurate solve: see docs/stability.md)"
    )]
    CheckFailed {
        what: &'static str,
        value: f64,
        limit: f64,
    },
    /// Iterative refinement on a mixed-precision (f32) factor did not converge: the matrix is too
    /// ill-conditioned for f32 (the caller factors in f64).
    #[error(
        "iterative refinement on the single-precision factor stalled at step {step} (relative \
         correction {correction:e}): the matrix is too ill-conditioned for mixed precision"
    )]
    Refinement { step: usize, correction: f64 },
    /// Bad input.
    #[error("invalid input: {0}")]
    Invalid(String),
    /// The rigid modes are independent at no dof set: no statically determinate support
    /// ([`dense::determinate_support`]) for an inertia-relief solve.
    #[error("rigid-body modes: rigid modes are not independent at any dof set")]
    NoDeterminateSupport,
    /// The factor of an n × n matrix would not fit in memory (estimated before factoring).
    #[error(
        "factoring a {n} x {n} matrix needs about {} but only {} are available ({from}): \
         stopped before factoring; use a coarser mesh or free memory (the limit can be set with \
         `flexbody build --max-memory` or FLEXBODY_MAX_MEMORY)",
        cholesky::format_bytes(*needed), cholesky::format_bytes(*available)
    )]
    OutOfMemory {
        /// Dimension.
        n: usize,
        /// Estimated bytes of the factor and its scratch.
        needed: u64,
        /// Bytes available.
        available: u64,
        /// Where `available` came from.
        from: &'static str,
    },
}

/// Arithmetic of the Craig–Bampton interior's factorization (K_ii), `build --precision`.
///
/// Measured (docs/benchmarks.md, "Mixed precision", 69k/178k/519k dofs, one thread): an f32
/// factor takes half the memory of L and about half the f64 factorization time, but every solve
/// then needs iterative refinement against K_ii (about 4 triangular solves where f64 needs one;
/// in f32 arithmetic each takes 0.55× an f64 solve), so the eigen phase takes 1.9–2.5× longer
/// and the whole build 1.1–1.45×. With an f32 factor the Krylov basis also keeps no M·V beside
/// V ([`eigen::BlockParams::keep_mv`]: two more products with M per step). The 519k build then
/// peaks at 5,508 MiB against CHOLMOD's 7,701 MiB for the factorization alone
/// (docs/memory.md). Hence f64 by default, f32 where the f64 factor does not fit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Precision {
    /// f64, unless the f64 factor would exceed the memory limit and the f32 one fits.
    #[default]
    Auto,
    /// Always f64.
    F64,
    /// An f32 factor with refined solves; f64 again where refinement stalls (ill conditioning).
    Mixed,
}

impl std::str::FromStr for Precision {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => Ok(Self::Auto),
            "f64" => Ok(Self::F64),
            "mixed" => Ok(Self::Mixed),
            other => Err(format!("{other}: expected auto, f64 or mixed")),
        }
    }
}

/// Which eigensolver computes the lowest modes, `build --eigensolver`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum EigenMethod {
    /// [`EigenMethod::resolved`]: Lanczos until a crossover is measured.
    #[default]
    Auto,
    /// Block shift-invert Lanczos ([`eigen`]): exact to its tolerance.
    Lanczos,
    /// AMLS ([`amls`]) with these settings: approximate modes with a Rayleigh–Ritz contract,
    /// per-mode residuals and an inertia count.
    Amls(amls::AmlsParams),
}

impl EigenMethod {
    /// The solver that runs. `Auto` is Lanczos at every size: in the `amls` bench suite
    /// (docs/amls.md) our AMLS was slower than Lanczos at every measured size and mode count
    /// (20k dofs, 100 modes: 22 s against 4.1 s), so there is no crossover for `auto` to pick
    /// by yet (a rule by size and mode count goes here once one is measured).
    pub fn resolved(self) -> EigenMethod {
        match self {
            EigenMethod::Auto => EigenMethod::Lanczos,
            other => other,
        }
    }

    /// The name `--eigensolver` takes (`amls:F` with a cutoff factor other than the default).
    pub fn name(&self) -> String {
        match self {
            EigenMethod::Auto => "auto".into(),
            EigenMethod::Lanczos => "lanczos".into(),
            EigenMethod::Amls(p) if p.cutoff_factor == amls::DEFAULT_CUTOFF_FACTOR => "amls".into(),
            EigenMethod::Amls(p) => format!("amls:{}", p.cutoff_factor),
        }
    }
}

impl std::str::FromStr for EigenMethod {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => Ok(Self::Auto),
            "lanczos" => Ok(Self::Lanczos),
            "amls" => Ok(Self::Amls(Default::default())),
            other => match other.strip_prefix("amls:").map(str::parse::<f64>) {
                Some(Ok(f)) if f.is_finite() && f >= 1.0 => Ok(Self::Amls(amls::AmlsParams {
                    cutoff_factor: f,
                    ..Default::default()
                })),
                Some(_) => Err(format!(
                    "{other}: the AMLS cutoff factor must be a number >= 1 (amls:10 keeps \
                     substructure modes up to 10 times the band's top eigenvalue)"
                )),
                None => Err(format!(
                    "{other}: expected auto, lanczos, amls or amls:FACTOR"
                )),
            },
        }
    }
}

/// What to compute.
#[derive(Clone, Debug)]
pub struct EigenSpec {
    /// How many lowest modes.
    pub count: usize,
    /// σ with K − σM positive definite; `None` = automatic: σ = −10⁻⁶·tr K/tr M (negative so that
    /// free bodies factor; negligible against the first flexible eigenvalue), then −10⁻³·, −1·.
    pub shift: Option<f64>,
    /// Relative residual tolerance (default 1e-10).
    pub tol: f64,
    /// Vectors per block solve (`None`: min(count, DEFAULT_BLOCK)).
    pub block: Option<usize>,
    /// Largest Krylov basis before a thick restart (`None`: [`default_basis`]).
    pub max_basis: Option<usize>,
    /// Dofs per node for the METIS node graph (`None`: order the dof graph).
    pub dofs_per_node: Option<usize>,
    /// Parallelism of the dense kernels inside the factorization and solves.
    pub par: Par,
    /// Arithmetic of a Craig–Bampton interior's factorization (other factorizations are f64).
    pub precision: Precision,
    /// Band mode (an eigenvalue ω², e.g. from `--fmax`): every eigenvalue ≤ `upper` plus the
    /// first one above it, from one iteration whose count starts at `count` and grows as needed
    /// (see [`eigen::BlockParams::upper`]). The dense path, and a band that outgrows the sparse
    /// path's limit, return `count` values all ≤ `upper`: ask again with more.
    pub upper: Option<f64>,
    /// After the solve, prove with Sylvester's inertia count of K − σM (σ just above the
    /// highest returned eigenvalue; one extra LDLᵀ factorization, [`inertia`]) that the returned
    /// modes are all the eigenvalues below σ; a missed mode is [`SolveError::MissedModes`].
    pub verify_band: bool,
    /// `--engine slepc --mpi N`: the eigenpairs of [`crate::reduce::select::solve_count`] from
    /// PETSc/SLEPc under MPI ([`slepc::lowest_modes`]); `None`: ours.
    pub engine: Option<slepc::SlepcEngine>,
    /// Which eigensolver ([`EigenMethod::resolved`] resolves `Auto` per solve).
    pub method: EigenMethod,
}

impl Default for EigenSpec {
    fn default() -> Self {
        Self {
            count: 10,
            shift: None,
            tol: 1e-10,
            block: None,
            max_basis: None,
            dofs_per_node: None,
            par: Par::Seq,
            precision: Precision::Auto,
            upper: None,
            verify_band: false,
            engine: None,
            method: EigenMethod::Auto,
        }
    }
}

/// Which eigensolver produced a solution (recorded per eigenproblem in the file, format 1.9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Solver {
    /// The block shift-invert iteration ([`eigen`]).
    #[default]
    Lanczos,
    /// AMLS ([`amls`]).
    Amls,
    /// A dense eigen-decomposition ([`dense`]).
    Dense,
    /// PETSc/SLEPc under MPI ([`slepc`]).
    Slepc,
}

/// How a solution was obtained and how good it is.
#[derive(Clone, Debug, Default)]
pub struct EigenInfo {
    /// Which solver produced the eigenpairs.
    pub solver: Solver,
    /// The shift σ of the factorization.
    pub shift: f64,
    /// Whether the dense path was used.
    pub dense: bool,
    /// Vectors solved with the factorization.
    pub solves: usize,
    /// Extra triangular solves spent refining with a mixed-precision factor (vectors × steps).
    pub refinement_solves: usize,
    /// Block steps and thick restarts.
    pub steps: usize,
    /// Thick restarts.
    pub restarts: usize,
    /// Dense eigensolves of the projected matrix T (the Ritz pairs computed during the run).
    pub ritz_solves: usize,
    /// ‖ΦᵀMΦ − I‖_max.
    pub orthonormality: f64,
    /// ‖ΦᵀKΦ − diag(ω²)‖_max / max|ω²|.
    pub stiffness_diag: f64,
    /// Factorization size (sparse path).
    pub factor: Option<FactorStats>,
    /// Wall time of the factorization and of the iteration (s).
    pub seconds_factor: f64,
    /// Wall time of the iteration (s).
    pub seconds_eigen: f64,
    /// Part of `seconds_eigen` spent in the triangular solves (s).
    pub seconds_solve: f64,
    /// Part of `seconds_eigen` spent orthogonalizing (Gram–Schmidt, M-QR with its M products).
    pub seconds_orth: f64,
    /// Part of `seconds_eigen` spent in the thick restarts (s).
    pub seconds_restart: f64,
    /// How the Krylov basis's Gram–Schmidt passes went.
    pub gram_schmidt: eigen::GsTally,
    /// With [`EigenSpec::verify_band`]: (modes proven complete, the shift σ of the count).
    pub band_proof: Option<(usize, f64)>,
    /// The solver's own report line for the build: `--engine slepc` ("engine slepc, N MPI
    /// ranks: " and the engine's timings) or `--eigensolver amls` (its tree and the largest
    /// Rayleigh–Ritz residual).
    pub engine_report: Option<String>,
}

/// Lowest eigenpairs.
#[derive(Clone, Debug)]
pub struct EigenSolution {
    /// ω², ascending.
    pub eigenvalues: Vec<f64>,
    /// n × count, ΦᵀMΦ = I.
    pub vectors: Mat<f64>,
    /// ‖Kφ − λMφ‖ / ‖Kφ‖ per mode (large for rigid modes, where ‖Kφ‖ is rounding noise).
    pub residuals: Vec<f64>,
    /// Diagnostics.
    pub info: EigenInfo,
}

/// Sets faer's global parallelism (used by its dense operators) for a scope and restores it on
/// drop. The solvers run their dense kernels under `EigenSpec::par`: faer's default (rayon on all
/// cores) was measured 2.4× slower in the eigen phase on this shared 2-core machine (36k dofs:
/// 8.0 s vs 3.3 s). Process-global: concurrent faer users in other threads see the setting too.
pub struct ParGuard(Par);

/// Rows from which the row-wise products (K·X, the Gram–Schmidt products of
/// [`thin_ops`]) split their rows between two threads, under faer's global parallelism.
pub(crate) const SPLIT_ROWS: usize = 8192;

/// Whether a row-wise product over `n` rows runs on two threads: n ≥ [`SPLIT_ROWS`] and
/// faer's global parallelism of degree ≥ 2 (`--threads`, set by [`ParGuard`]).
pub(crate) fn rows_on_two_threads(n: usize) -> bool {
    n >= SPLIT_ROWS && faer::get_global_parallelism().degree() >= 2
}

impl ParGuard {
    /// Switches to `par` until the guard is dropped.
    pub fn new(par: Par) -> Self {
        let old = faer::get_global_parallelism();
        faer::set_global_parallelism(par);
        Self(old)
    }
}

impl Drop for ParGuard {
    fn drop(&mut self) {
        faer::set_global_parallelism(self.0);
    }
}

/// A stiffness-over-mass scale of the model: the median of K_ii / M_ii over the dofs with
/// The frequency of an eigenvalue ω²: √max(ω², 0) / (2π) (SPEC.md's `frequency_hz` rule).
pub fn hz(omega2: f64) -> f64 {
    omega2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// The automatic shift σ of a factorization of K − σM: just below zero (−1e-6 of the
/// stiffness-over-mass `scale`, [`trace_ratio`]), so that a free body's K − σM is positive
/// definite and its rigid modes come out at λ ≈ 0.
pub(crate) fn automatic_shift(scale: f64) -> f64 {
    -1e-6 * scale
}

/// The shifts a factorization of K − σM tries in turn when none is given: the
/// [`automatic_shift`], then further below zero where it is not positive definite.
pub(crate) fn automatic_shifts(scale: f64) -> Vec<f64> {
    vec![automatic_shift(scale), -1e-3 * scale, -scale]
}

/// The σ of an inertia count that takes in every returned eigenvalue: just above the highest,
/// `top`, when it stands above rounding ([`above_rounding`] of its M-orthonormal vector); for
/// rigid modes only, above their rounding ceiling ROUNDING_FACTOR·ε·max_j (|φ_j|ᵀ|K||φ_j|). Not
/// a fraction of the stiffness-over-mass scale: a free satellite with deployed booms has 47
/// flexible modes below 10⁻⁶ of it (pyNastran's `ISat_Dploy_Sm.dat`: 0.92 Hz against a median
/// K_ii/M_ii of 2.8e11). `vectors`: one column per value.
pub(crate) fn count_shift_above(
    k: &SparseColMat<usize, f64>,
    vectors: MatRef<'_, f64>,
    values: &[f64],
) -> f64 {
    debug_assert_eq!(vectors.ncols(), values.len());
    let top = values.iter().copied().fold(0.0f64, f64::max);
    let (abs_e, _) = sparse_ops::abs_products(k.as_ref(), vectors);
    let ceiling = (abs_e.iter()).fold(0.0f64, |c, &e| c.max(e));
    if above_rounding(top, ceiling) {
        top * (1.0 + 1e-8)
    } else {
        sparse_ops::ROUNDING_FACTOR * f64::EPSILON * ceiling
    }
}

/// Whether the eigenvalue `lambda` of an M-normalized φ stands above the rounding that forming
/// φᵀKφ leaves, ROUNDING_FACTOR·ε·(|φ|ᵀ|K||φ|) (`abs_energy`): below it λ cannot be told from a
/// rigid mode's 0. Measured on `ISat_Dploy_Sm.dat`: its six rigid modes at 2e-2 of ε|φ|ᵀ|K||φ|
/// or less, its flexible ones at 6e6 and more.
fn above_rounding(lambda: f64, abs_energy: f64) -> bool {
    lambda > sparse_ops::ROUNDING_FACTOR * f64::EPSILON * abs_energy
}

/// Whether eigenvalue `lambda` is a flexible mode's: above [`residual::RIGID_FRACTION`] (1e-8)
/// of the model's stiffness-over-mass `scale` ([`trace_ratio`]); at or below it the mode is rigid.
pub fn is_flexible(lambda: f64, scale: f64) -> bool {
    lambda > residual::RIGID_FRACTION * scale
}

/// positive K_ii and M_ii (tr K / tr M when there are none). Used for the automatic shift and
/// the rigid-mode threshold. The median, not tr K / tr M: a near-rigid insert (stiffness
/// contrast 1e10) dominates the trace and pushed the shift and the rigid threshold above the
/// body's flexible modes (docs/stability.md, row 7).
pub fn trace_ratio(k: &SparseColMat<usize, f64>, m: &SparseColMat<usize, f64>) -> f64 {
    let diag = |a: &SparseColMat<usize, f64>| -> Vec<f64> {
        (0..a.ncols())
            .map(|j| {
                a.row_idx_of_col_raw(j)
                    .iter()
                    .zip(a.val_of_col(j))
                    .filter(|(&i, _)| i == j)
                    .map(|(_, &v)| v)
                    .sum()
            })
            .collect()
    };
    let (dk, dm) = (diag(k), diag(m));
    scale_of(&dk, &dm)
}

pub(crate) fn trace_ratio_dense(k: MatRef<'_, f64>, m: MatRef<'_, f64>) -> f64 {
    let dk: Vec<f64> = (0..k.nrows()).map(|i| k[(i, i)]).collect();
    let dm: Vec<f64> = (0..m.nrows()).map(|i| m[(i, i)]).collect();
    scale_of(&dk, &dm)
}

fn scale_of(dk: &[f64], dm: &[f64]) -> f64 {
    let mut r: Vec<f64> = dk
        .iter()
        .zip(dm)
        .filter(|(&a, &b)| a > 0.0 && b > 0.0)
        .map(|(&a, &b)| a / b)
        .filter(|v| v.is_finite())
        .collect();
    if r.is_empty() {
        return ratio(dk.iter().sum(), dm.iter().sum());
    }
    let mid = r.len() / 2;
    *r.select_nth_unstable_by(mid, f64::total_cmp).1
}

fn ratio(tk: f64, tm: f64) -> f64 {
    if tm > 0.0 && tk > 0.0 {
        tk / tm
    } else {
        tk.abs().max(1.0)
    }
}

/// K and M square and of one size, else an error naming both shapes (after `context`).
pub(crate) fn check_pair(
    k: faer::sparse::SparseColMatRef<'_, usize, f64>,
    m: faer::sparse::SparseColMatRef<'_, usize, f64>,
    context: &str,
) -> Result<(), SolveError> {
    let n = k.nrows();
    if k.ncols() != n || m.nrows() != n || m.ncols() != n {
        return Err(SolveError::Dimension(format!(
            "{context}K is {}x{}, M is {}x{}",
            k.nrows(),
            k.ncols(),
            m.nrows(),
            m.ncols()
        )));
    }
    Ok(())
}

fn validate(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    count: usize,
) -> Result<(), SolveError> {
    let n = k.nrows();
    check_pair(k.as_ref(), m.as_ref(), "")?;
    if k.val().iter().any(|v| !v.is_finite()) {
        return Err(SolveError::NonFinite("K"));
    }
    if m.val().iter().any(|v| !v.is_finite()) {
        return Err(SolveError::NonFinite("M"));
    }
    if count == 0 || count > n {
        return Err(SolveError::TooManyModes {
            requested: count,
            available: n,
        });
    }
    Ok(())
}

/// The lowest `spec.count` eigenpairs of K φ = ω² M φ (K, M full symmetric, same size), or with
/// `spec.upper` the band below it.
pub fn lowest_modes(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    spec: &EigenSpec,
) -> Result<EigenSolution, SolveError> {
    let _par = ParGuard::new(spec.par);
    validate(k, m, spec.count)?;
    let n = k.nrows();
    let count = spec.count;
    if let (EigenMethod::Amls(p), true) = (spec.method.resolved(), n > DENSE_MAX) {
        return lowest_modes_amls(k, m, spec, &p);
    }
    let b = spec.block.unwrap_or(count.min(DEFAULT_BLOCK)).max(1);
    let max_basis = spec.max_basis.unwrap_or_else(|| default_basis(count, b));
    if n <= DENSE_MAX || (2 * max_basis > n && n <= 3000) {
        let t = std::time::Instant::now();
        let kd = sparse_ops::to_dense(k.as_ref());
        let md = sparse_ops::to_dense(m.as_ref());
        let (_, mut vecs) = dense::lowest(kd.as_ref(), md.as_ref(), count, spec.shift)?;
        let info = EigenInfo {
            solver: Solver::Dense,
            dense: true,
            seconds_eigen: t.elapsed().as_secs_f64(),
            ..Default::default()
        };
        return finish(k, m, &mut vecs, info, spec.tol).and_then(|s| verify_band(k, m, s, spec));
    }
    lowest_modes_iterative(k, m, spec)
}

/// [`amls::amls`] as the other solvers answer: a band the inertia count proves incomplete is
/// [`SolveError::MissedModes`].
fn lowest_modes_amls(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    spec: &EigenSpec,
    params: &amls::AmlsParams,
) -> Result<EigenSolution, SolveError> {
    let s = amls::amls(k, m, spec, params)?;
    match s.missing() {
        0 => Ok(s.solution),
        missing => Err(SolveError::MissedModes {
            found: s.report.returned_below_top,
            missing,
            sigma: s.report.band_top,
        }),
    }
}

/// [`lowest_modes`] always on the sparse path (factorization + block shift-invert iteration),
/// whatever the size.
pub fn lowest_modes_iterative(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    spec: &EigenSpec,
) -> Result<EigenSolution, SolveError> {
    let _par = ParGuard::new(spec.par);
    validate(k, m, spec.count)?;
    let n = k.nrows();
    let count = spec.count;
    let b = spec.block.unwrap_or(count.min(DEFAULT_BLOCK)).max(1);
    if count + 2 * b > n {
        return Err(SolveError::TooManyModes {
            requested: count + 2 * b,
            available: n,
        });
    }
    let scale = trace_ratio(k, m);
    let shifts = match spec.shift {
        Some(s) => vec![s],
        None => automatic_shifts(scale),
    };
    let t0 = std::time::Instant::now();
    let mut last = None;
    for sigma in shifts {
        let a = sparse_ops::add_scaled(k.as_ref(), m.as_ref(), -sigma)?;
        let llt = match SparseLlt::factor(a.as_ref(), spec.dofs_per_node, spec.par) {
            Ok(l) => l,
            Err(e @ SolveError::NonPositivePivot { .. }) => {
                last = Some(e);
                continue;
            }
            Err(e) => return Err(e),
        };
        let seconds_factor = t0.elapsed().as_secs_f64();
        let mut sol = lowest_modes_factored(k, m, &llt, sigma, spec)?;
        sol.info.seconds_factor = seconds_factor;
        return Ok(sol);
    }
    Err(last.unwrap_or(SolveError::NotPositiveDefinite { shift: 0.0 }))
}

/// The block iteration with an existing factorization `llt` of K − σM (e.g. K_ii reused by
/// Craig–Bampton with σ = 0).
pub fn lowest_modes_factored(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    llt: &SparseLlt,
    sigma: f64,
    spec: &EigenSpec,
) -> Result<EigenSolution, SolveError> {
    let _par = ParGuard::new(spec.par);
    validate(k, m, spec.count)?;
    let n = k.nrows();
    let count = spec.count;
    if let EigenMethod::Amls(p) = spec.method.resolved() {
        // AMLS factors its own substructures: `llt` is not used
        return lowest_modes_amls(k, m, spec, &p);
    }
    let b = spec.block.unwrap_or(count.min(DEFAULT_BLOCK)).max(1);
    if count + 2 * b > n || llt.n() != n {
        return Err(SolveError::TooManyModes {
            requested: count + 2 * b,
            available: n,
        });
    }
    let t1 = std::time::Instant::now();
    let prm = eigen::BlockParams {
        count,
        block: b,
        max_basis: spec
            .max_basis
            .unwrap_or_else(|| default_basis(count, b))
            .min(n),
        tol: spec.tol,
        max_steps: 200 + 20 * count.div_ceil(b),
        upper: spec.upper,
        // the basis (3 × count) stays within half the problem; beyond, the dense path
        max_count: count.max(n / 6),
        // an f32 factor is chosen to save memory (issue 22): so is the lean basis, whose M·V
        // is 0.37 GB at 519k dofs and 30 modes (docs/memory.md)
        keep_mv: !llt.is_mixed(),
    };
    // A small basis can stall (measured: a free 1000-element lumped CBAR line, whose rotations
    // are all massless, did not converge to 6 or 12 modes in 240 steps but did to 20): retry
    // with twice the count, up to the band mode's own limit n/6, and keep the lowest `count`.
    let mut r = eigen::block_shift_invert(k.as_ref(), m.as_ref(), llt, sigma, &prm);
    let mut wider = count;
    while matches!(r, Err(SolveError::NotConverged { .. }))
        && spec.upper.is_none()
        && 2 * wider <= prm.max_count
        && 2 * wider + 2 * b <= n
    {
        wider *= 2;
        let p2 = eigen::BlockParams {
            count: wider,
            max_basis: default_basis(wider, b).min(n),
            max_steps: 200 + 20 * wider.div_ceil(b),
            max_count: wider,
            ..prm.clone()
        };
        r = eigen::block_shift_invert(k.as_ref(), m.as_ref(), llt, sigma, &p2).map(|mut r| {
            r.values.truncate(count);
            r.vectors = r.vectors.as_ref().subcols(0, count).to_owned();
            r
        });
    }
    let r = r?;
    let mut info = EigenInfo {
        shift: sigma,
        dense: false,
        solves: r.solves,
        refinement_solves: r.refinement_solves,
        steps: r.steps,
        restarts: r.restarts,
        ritz_solves: r.ritz_solves,
        factor: Some(llt.stats.clone()),
        seconds_eigen: t1.elapsed().as_secs_f64(),
        seconds_solve: r.seconds_solve,
        seconds_orth: r.seconds_orth,
        seconds_restart: r.seconds_restart,
        gram_schmidt: r.gram_schmidt,
        ..Default::default()
    };
    // When the Krylov basis met its own test but the true residual misses the bound (stiffness
    // contrasts: the shift-invert operator's Ritz estimate understates it), refine by subspace
    // iteration X ← (K − σM)⁻¹ M X, at most REFINE_STEPS block solves; `finish` re-does the
    // Rayleigh–Ritz step each time.
    let mut x = r.vectors;
    let mut step = 0;
    loop {
        match finish(k, m, &mut x, info.clone(), spec.tol) {
            Err(SolveError::CheckFailed {
                what: "relative residual",
                ..
            }) if step < REFINE_STEPS => {
                x = sparse_ops::spmm(m.as_ref(), x.as_ref());
                info.refinement_solves +=
                    eigen::shift_inverse_solve(llt, k.as_ref(), sigma, x.as_mut(), spec.tol)?
                        * x.ncols();
                info.solves += x.ncols();
                step += 1;
            }
            other => return other.and_then(|s| verify_band(k, m, s, spec)),
        }
    }
}

/// With `spec.verify_band`: Sylvester's law of inertia on K − σM, σ = (1 + 10⁻⁸)·λ_max of
/// the solution (or a tiny positive σ when every returned λ is ~0), must count exactly the
/// returned modes; more is [`SolveError::MissedModes`] (a mode skipped inside the band, or a
/// repeated eigenvalue cut at the last returned mode).
pub(crate) fn verify_band(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    mut sol: EigenSolution,
    spec: &EigenSpec,
) -> Result<EigenSolution, SolveError> {
    if !spec.verify_band || sol.eigenvalues.is_empty() {
        return Ok(sol);
    }
    let sigma = count_shift_above(k, sol.vectors.as_ref(), &sol.eigenvalues);
    let found = sol.eigenvalues.len();
    match inertia::check_band(
        k,
        m,
        &sol.eigenvalues,
        f64::NEG_INFINITY,
        sigma,
        spec.dofs_per_node,
        spec.par,
    )? {
        Ok(_) => {
            sol.info.band_proof = Some((found, sigma));
            Ok(sol)
        }
        Err(missing) => Err(SolveError::MissedModes {
            found,
            missing,
            sigma,
        }),
    }
}

/// Largest Krylov basis of the block iteration for `count` modes with blocks of `b`. Measured on
/// the 20k-dof tet10 block, 30 modes, blocks of 6: a basis of 90 (the default) took 198 solved
/// vectors and 3 restarts, 120 and 150 took 180 and one restart, 200 took 180 and none, for
/// about the same eigen-phase time (Gram–Schmidt grows with the basis; its memory is 16·n·basis
/// bytes); [`EigenSpec::max_basis`] overrides it.
pub fn default_basis(count: usize, b: usize) -> usize {
    (3 * count).max(count + 4 * b)
}

/// Subspace-iteration steps allowed after the block iteration when residuals miss the bound.
const REFINE_STEPS: usize = 3;

/// Final Rayleigh–Ritz cleanup (exact ΦᵀMΦ = I, ΦᵀKΦ = diag to rounding) and the checks.
///
/// `x` is rotated to the Ritz vectors in place (x ← xY, the same span), so that a caller can go
/// on from it when a check fails; x, Kx and Mx are the only n × c blocks held (issue 22: copies
/// of them were the 519k build's peak).
fn finish(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    x: &mut Mat<f64>,
    mut info: EigenInfo,
    tol: f64,
) -> Result<EigenSolution, SolveError> {
    let ritz = ritz_in_place(k, m, x)?;
    let (vals, orth, kd) = (&ritz.values, ritz.orthonormality, ritz.stiffness_diag);
    let lmax = vals
        .iter()
        .fold(0.0f64, |a, &b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE);
    let scale = trace_ratio(k, m);
    // rounding scales of Kφ and φᵀKφ: the checks never ask for less than rounding leaves
    // (stiffness contrasts, docs/stability.md row 7)
    let (abs_e, abs_n) = sparse_ops::abs_products(k.as_ref(), x.as_ref());
    for (j, (&res, &kn)) in ritz.residuals.iter().zip(&ritz.k_norms).enumerate() {
        // every mode against the file's residual (SPEC §5.17): ‖Kφ − λMφ‖ over
        // max(‖Kφ‖, 10⁻⁸ s ‖Mφ‖) — ‖Kφ‖ for a flexible mode, the rigid threshold's scale for a
        // rigid one (whose ‖Kφ‖ is rounding). No mode is exempt: a flexible mode below 10⁻⁸ of
        // the scale (a soft mechanism of a stiff body) must converge too.
        let rn = if kn > 0.0 { res * kn } else { res };
        let denominator = kn
            .max(residual::RIGID_FRACTION * scale * ritz.m_norms[j])
            .max(f64::MIN_POSITIVE);
        let res = rn / denominator;
        let floor = sparse_ops::ROUNDING_FACTOR * f64::EPSILON * abs_n[j] / denominator;
        let limit = (1e3 * tol).max(1e-8).max(floor);
        if res.is_nan() || res > limit {
            return Err(SolveError::CheckFailed {
                what: "relative residual",
                value: res,
                limit,
            });
        }
    }
    if orth.is_nan() || orth > 1e-9 {
        return Err(SolveError::CheckFailed {
            what: "|PhiT M Phi - I|max",
            value: orth,
            limit: 1e-9,
        });
    }
    // raised to the rounding floor of ΦᵀKΦ for stiffness contrasts (docs/stability.md, row 7)
    let k_limit = 1e-9f64.max(
        sparse_ops::ROUNDING_FACTOR * f64::EPSILON * abs_e.iter().fold(0.0f64, |a, &b| a.max(b))
            / lmax,
    );
    if kd.is_nan() || kd > k_limit {
        return Err(SolveError::CheckFailed {
            what: "|PhiT K Phi - diag|max/max w2",
            value: kd,
            limit: k_limit,
        });
    }
    info.orthonormality = orth;
    info.stiffness_diag = kd;
    Ok(EigenSolution {
        eigenvalues: ritz.values,
        vectors: std::mem::replace(x, Mat::zeros(0, 0)),
        residuals: ritz.residuals,
        info,
    })
}

/// A Rayleigh–Ritz step and what it measured ([`ritz_in_place`]).
pub(crate) struct Ritz {
    /// Ritz values, ascending.
    pub values: Vec<f64>,
    /// ‖Kφ − λMφ‖ / ‖Kφ‖ per vector (‖Kφ − λMφ‖ where Kφ = 0).
    pub residuals: Vec<f64>,
    /// ‖Kφ‖ per vector.
    pub k_norms: Vec<f64>,
    /// ‖Mφ‖ per vector.
    pub m_norms: Vec<f64>,
    /// ‖ΦᵀMΦ − I‖_max after the step.
    pub orthonormality: f64,
    /// ‖ΦᵀKΦ − diag(λ)‖_max / max|λ| after the step.
    pub stiffness_diag: f64,
}

/// Rayleigh–Ritz on the full K and M: x ← xY with (xᵀKx)Y = (xᵀMx)YΛ, YᵀxᵀMxY = I (the same
/// span), then the residual of every vector and the measured ΦᵀMΦ − I and ΦᵀKΦ − Λ. x, Kx and
/// Mx are the only n × c blocks held (issue 22: copies of them were the 519k build's peak).
pub(crate) fn ritz_in_place(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    x: &mut Mat<f64>,
) -> Result<Ritz, SolveError> {
    let mut kx = sparse_ops::spmm(k.as_ref(), x.as_ref());
    let mut mx = sparse_ops::spmm(m.as_ref(), x.as_ref());
    let kp = x.transpose() * &kx;
    let mp = x.transpose() * &mx;
    let (vals, y) = dense::projected(kp.as_ref(), mp.as_ref())?;
    // y is c × c (c = the columns of x)
    let c = vals.len();
    for v in [&mut *x, &mut kx, &mut mx] {
        thin_ops::mul_in_place(v.as_mut(), y.as_ref());
    }
    let mut orth = 0.0f64;
    let mut kd = 0.0f64;
    let mp = x.transpose() * &mx;
    let kp = x.transpose() * &kx;
    let lmax = vals
        .iter()
        .fold(0.0f64, |a, &b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE);
    for j in 0..c {
        for i in 0..c {
            let id = if i == j { 1.0 } else { 0.0 };
            orth = orth.max((mp[(i, j)] - id).abs());
            kd = kd.max((kp[(i, j)] - id * vals[j]).abs() / lmax);
        }
    }
    let mut residuals = Vec::with_capacity(c);
    let mut k_norms = Vec::with_capacity(c);
    let mut m_norms = Vec::with_capacity(c);
    for j in 0..c {
        let (mut rn, mut kn, mut mn) = (0.0, 0.0, 0.0);
        for i in 0..x.nrows() {
            let r = kx[(i, j)] - vals[j] * mx[(i, j)];
            rn += r * r;
            kn += kx[(i, j)] * kx[(i, j)];
            mn += mx[(i, j)] * mx[(i, j)];
        }
        residuals.push(if kn > 0.0 {
            (rn / kn).sqrt()
        } else {
            rn.sqrt()
        });
        k_norms.push(kn.sqrt());
        m_norms.push(mn.sqrt());
    }
    Ok(Ritz {
        values: vals,
        residuals,
        k_norms,
        m_norms,
        orthonormality: orth,
        stiffness_diag: kd,
    })
}
