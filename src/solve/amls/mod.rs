//! AMLS, automated multilevel substructuring (Bennighof & Lehoucq 2004; Kaplan 2001): the lowest
//! eigenpairs of K φ = λ M φ from substructure modes instead of a Krylov iteration over the
//! whole model, then a Rayleigh–Ritz step on the full K and M and a completeness proof.
//!
//! 1. [`tree`]: METIS vertex separators, applied recursively, split the node graph into leaf
//!    substructures of at most [`AmlsParams::leaf_dofs`] dofs and the separators between them
//!    (the top levels of a nested-dissection tree).
//! 2. [`reduce`], bottom-up on A = K − σM (σ < 0 so that free bodies factor): a leaf keeps its
//!    fixed-boundary eigenvectors with λ ≤ the cutoff; a separator condenses its two subtrees'
//!    bases and its own static extension into a projected pencil, whose eigenvectors with
//!    λ ≤ the cutoff become the subtree's basis. The cutoff is [`AmlsParams::cutoff_factor`]
//!    times the band top: `EigenSpec::upper` when given, else an upper bound of λ_count (the
//!    count-th lowest leaf eigenvalue: Cauchy interlacing).
//! 3. The root's lowest `count` vectors Φ (plus, in band mode, every one ≤ `upper` and the
//!    first above) get a Rayleigh–Ritz step on the full K and M, so ΦᵀMΦ = I and ΦᵀKΦ =
//!    diag(λ) to round-off whatever the cutoff, and every mode its relative residual
//!    ‖Kφ − λMφ‖/‖Kφ‖ (the accuracy the cutoff bought: not bounded by a tolerance here).
//! 4. Completeness: Sylvester's inertia of K − σ_top M (one LDLᵀ, [`super::inertia`]) counts
//!    the eigenvalues below the band top σ_top; fewer modes returned below it is
//!    [`AmlsSolution::missing`] > 0, which [`super::lowest_modes`] turns into
//!    [`SolveError::MissedModes`]: never silently incomplete.
//!
//! Memory: no n × (all substructure modes) basis is formed. At a separator the solver holds
//! the two children's sparse factors of A_cc, their bases (n_c × k_c, k_c their modes below the
//! cutoff), the dense s × s separator blocks and reduced pencil ((k_1 + k_2 + s)² twice) and one
//! n_T × 128 chunk of the static extension; the children's data are dropped once the subtree's
//! basis (n_T × k_T) is formed. The peak is at the root: the factors of its two halves, their
//! bases, the reduced pencil, then n × count three times in the Rayleigh–Ritz step (Φ, KΦ,
//! MΦ), then the LDLᵀ of the inertia count (one factor of the full size).

mod profile;
mod reduce;
mod tree;

pub use profile::Profile;

use super::{
    hz, inertia, is_flexible, sparse_ops, trace_ratio, EigenInfo, EigenSolution, EigenSpec,
    ParGuard, SolveError, SparseColMat,
};
use faer::Mat;

/// AMLS settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmlsParams {
    /// Substructure modes are kept up to this multiple of the band top (λ, not frequency).
    pub cutoff_factor: f64,
    /// Largest leaf substructure (dofs).
    pub leaf_dofs: usize,
    /// Subspace-iteration steps X ← (K − σM)⁻¹MX on the returned modes after AMLS, each
    /// followed by the Rayleigh–Ritz step (one more factorization of the full K − σM): AMLS
    /// alone leaves relative eigenvalue errors of 1e-4–1e-3 (docs/amls.md).
    pub refine: usize,
}

/// Default [`AmlsParams::cutoff_factor`]: see docs/amls.md for the measured error per factor.
pub const DEFAULT_CUTOFF_FACTOR: f64 = 4.0;

/// Default [`AmlsParams::refine`]: two steps took the lowest 10 of 40 modes from 1.1e-3 to
/// 9e-11 relative error on a 9.7k-dof tet10 block (tests/amls.rs).
pub const DEFAULT_REFINE: usize = 2;

/// Default [`AmlsParams::leaf_dofs`].
pub const DEFAULT_LEAF_DOFS: usize = 1200;

impl Default for AmlsParams {
    fn default() -> Self {
        Self {
            cutoff_factor: DEFAULT_CUTOFF_FACTOR,
            leaf_dofs: DEFAULT_LEAF_DOFS,
            refine: DEFAULT_REFINE,
        }
    }
}

/// What AMLS did, beside the eigenpairs.
#[derive(Clone, Debug, Default)]
pub struct AmlsReport {
    /// Leaf substructures, the largest leaf, total separator dofs, tree depth.
    pub leaves: usize,
    /// Largest leaf (dofs).
    pub largest_leaf: usize,
    /// Total separator dofs.
    pub separator_dofs: usize,
    /// Tree depth.
    pub depth: usize,
    /// The cutoff λ_c of the substructure modes.
    pub cutoff: f64,
    /// Vectors of the root's basis (the projected problem's modes below the cutoff).
    pub root_modes: usize,
    /// Band top σ_top of the inertia count.
    pub band_top: f64,
    /// Eigenvalues below σ_top by Sylvester's inertia.
    pub below_top: usize,
    /// Modes returned below σ_top.
    pub returned_below_top: usize,
    /// Seconds: the substructure reduction, the Rayleigh–Ritz step, the inertia count.
    pub seconds_reduce: f64,
    /// Seconds of the Rayleigh–Ritz step.
    pub seconds_ritz: f64,
    /// Seconds of the inertia count.
    pub seconds_inertia: f64,
    /// Counts and seconds per phase.
    pub profile: Profile,
}

/// Eigenpairs from AMLS and how complete they are.
#[derive(Clone, Debug)]
pub struct AmlsSolution {
    /// The eigenpairs (Rayleigh–Ritz on K and M; residuals per mode).
    pub solution: EigenSolution,
    /// The tree, cutoff and completeness count.
    pub report: AmlsReport,
}

impl AmlsSolution {
    /// Eigenvalues below the band top that were not returned (0: complete).
    pub fn missing(&self) -> usize {
        self.report
            .below_top
            .saturating_sub(self.report.returned_below_top)
    }
}

/// The lowest `spec.count` eigenpairs (or with `spec.upper` every one ≤ upper and the first
/// above) by AMLS, with the inertia count of the band top (module doc). `spec.shift`,
/// `dofs_per_node` and `par` are used; block, basis and tolerance settings are the Lanczos
/// solver's and ignored.
pub fn amls(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    spec: &EigenSpec,
    params: &AmlsParams,
) -> Result<AmlsSolution, SolveError> {
    let _par = ParGuard::new(spec.par);
    super::validate(k, m, spec.count)?;
    if params.cutoff_factor.is_nan() || params.cutoff_factor < 1.0 || params.leaf_dofs < 2 {
        return Err(SolveError::Invalid(format!(
            "AMLS cutoff factor {} (must be >= 1) or leaf size {} (must be >= 2)",
            params.cutoff_factor, params.leaf_dofs
        )));
    }
    let t0 = std::time::Instant::now();
    let n = k.nrows();
    let scale = trace_ratio(k, m);
    let sigma = spec.shift.unwrap_or(super::automatic_shift(scale));
    let a = sparse_ops::add_scaled(k.as_ref(), m.as_ref(), -sigma)?;
    let root = tree::build(&a, spec.dofs_per_node, params.leaf_dofs)?;
    let (leaves, largest_leaf, separator_dofs, depth) = root.shape();
    let profile = Profile::default();
    let mut ctx = reduce::Context {
        a: &a,
        m,
        mu_cut: f64::INFINITY,
        block: spec.dofs_per_node,
        par: spec.par,
        profile: &profile,
        leaf_modes: Default::default(),
    };
    let band_top_guess = match spec.upper {
        Some(u) => u - sigma,
        None => count_bound(&ctx, &root, spec.count, params.cutoff_factor)?,
    };
    ctx.mu_cut = params.cutoff_factor * band_top_guess.max(f64::MIN_POSITIVE);
    let (basis, root_factor) = reduce::basis(&ctx, &root, spec.count, params.refine > 0)?;
    let mu_cut = ctx.mu_cut;
    drop((root, ctx));
    let root_modes = basis.mu.len();
    // how many of the root's vectors are returned (before refinement)
    let keep = match spec.upper {
        Some(u) => {
            let below = basis.mu.iter().filter(|&&mu| mu + sigma <= u).count();
            (below + 1).max(spec.count).min(root_modes)
        }
        None => spec.count.min(root_modes),
    };
    if keep < spec.count {
        return Err(SolveError::TooManyModes {
            requested: spec.count,
            available: keep,
        });
    }
    // refinement converges mode j as (λ_j/λ_width)^step: guard vectors above the kept ones
    let width = if params.refine > 0 {
        (keep + (keep / 2).max(8)).min(root_modes)
    } else {
        keep
    };
    let mut x = Mat::<f64>::zeros(n, width);
    for (r, &d) in basis.dofs.iter().enumerate() {
        for c in 0..width {
            x[(d, c)] = basis.phi[(r, c)];
        }
    }
    let order = basis.dofs;
    drop((basis.phi, basis.mu));
    let seconds_reduce = t0.elapsed().as_secs_f64();
    let t1 = std::time::Instant::now();
    if params.refine > 0 {
        // the root split's factor of A in the basis's row order, else (a leaf root) A's own
        let (llt, in_basis_order) = match root_factor {
            Some(f) => (f, true),
            None => (
                Profile::time(&profile.refine_factor_seconds, || {
                    super::SparseLlt::factor(a.as_ref(), spec.dofs_per_node, spec.par)
                })?,
                false,
            ),
        };
        drop(a);
        for step in 0..params.refine {
            // the root's vectors are already Ritz vectors of its pencil: no Ritz step before the
            // first solve
            if step > 0 {
                Profile::time(&profile.ritz_seconds, || super::ritz_in_place(k, m, &mut x))?;
            }
            let mut y = sparse_ops::spmm(m.as_ref(), x.as_ref());
            Profile::count(&profile.refine_columns, y.ncols());
            Profile::time(&profile.refine_solve_seconds, || {
                if in_basis_order {
                    let mut yb = Mat::from_fn(n, y.ncols(), |r, c| y[(order[r], c)]);
                    llt.solve_in_place(yb.as_mut());
                    for (r, &d) in order.iter().enumerate() {
                        for c in 0..yb.ncols() {
                            y[(d, c)] = yb[(r, c)];
                        }
                    }
                } else {
                    llt.solve_in_place(y.as_mut());
                }
            });
            x = y;
        }
    } else {
        drop(a);
    }
    let mut ritz = Profile::time(&profile.ritz_seconds, || super::ritz_in_place(k, m, &mut x))?;
    let keep = match spec.upper {
        Some(u) => (ritz.values.iter().filter(|&&l| l <= u).count() + 1)
            .max(spec.count)
            .min(width),
        None => spec.count,
    };
    ritz.values.truncate(keep);
    ritz.residuals.truncate(keep);
    x.truncate(n, keep);
    let seconds_ritz = t1.elapsed().as_secs_f64();
    if ritz.orthonormality.is_nan() || ritz.orthonormality > 1e-9 {
        return Err(SolveError::CheckFailed {
            what: "|PhiT M Phi - I|max",
            value: ritz.orthonormality,
            limit: 1e-9,
        });
    }
    // the band top: `upper`, else just above the highest returned eigenvalue
    let band_top = match spec.upper {
        Some(u) => u,
        None => super::count_shift_above(k, x.as_ref(), &ritz.values),
    };
    let t2 = std::time::Instant::now();
    let below_top = inertia::count_below(k, m, band_top, spec.dofs_per_node, spec.par)?;
    let seconds_inertia = t2.elapsed().as_secs_f64();
    let returned_below_top = ritz.values.iter().filter(|&&l| l < band_top).count();
    // the largest residual of a flexible mode (a rigid mode's ‖Kφ‖ is rounding noise)
    let worst = (ritz.values.iter().zip(&ritz.residuals).enumerate())
        .filter(|(_, (&l, _))| is_flexible(l, scale))
        .fold(None, |w: Option<(usize, f64)>, (j, (_, &r))| match w {
            Some((_, wr)) if wr >= r => w,
            _ => Some((j, r)),
        });
    let cutoff = mu_cut + sigma;
    let report_line = format!(
        "eigensolver amls: {leaves} substructures, {root_modes} modes at the root (cutoff \
         {:.4e} Hz); Rayleigh-Ritz pairs, |PhiT M Phi - I| {:.1e}{}",
        hz(cutoff),
        ritz.orthonormality,
        worst.map_or(String::new(), |(j, r)| format!(
            ", largest relative residual {r:.1e} (mode {})",
            j + 1
        ))
    );
    let info = EigenInfo {
        solver: super::Solver::Amls,
        shift: sigma,
        orthonormality: ritz.orthonormality,
        stiffness_diag: ritz.stiffness_diag,
        seconds_eigen: t0.elapsed().as_secs_f64(),
        band_proof: (below_top <= returned_below_top).then_some((below_top, band_top)),
        engine_report: Some(report_line),
        ..Default::default()
    };
    Ok(AmlsSolution {
        solution: EigenSolution {
            eigenvalues: ritz.values,
            vectors: x,
            residuals: ritz.residuals,
            info,
        },
        report: AmlsReport {
            leaves,
            largest_leaf,
            separator_dofs,
            depth,
            cutoff,
            root_modes,
            band_top,
            below_top,
            returned_below_top,
            seconds_reduce,
            seconds_ritz,
            seconds_inertia,
            profile,
        },
    })
}

/// An upper bound of μ_count: the count-th lowest eigenvalue over all leaves (their union is a
/// principal sub-pencil of (A, M); Cauchy interlacing), or the largest one when the leaves have
/// fewer. Each leaf is solved once: its vectors up to `factor` × the bound known so far (a
/// running upper bound of the final one, so the final cutoff never needs more) are kept in
/// `ctx.leaf_modes` for the leaf's basis (all `count` lowest when the root is a leaf).
fn count_bound(
    ctx: &reduce::Context<'_>,
    root: &tree::Substructure,
    count: usize,
    factor: f64,
) -> Result<f64, SolveError> {
    let root_is_leaf = matches!(root, tree::Substructure::Leaf(_));
    let at_least = if root_is_leaf { count } else { 0 };
    let mut all: Vec<f64> = Vec::new();
    let mut bound = f64::INFINITY;
    let mut stack = vec![root];
    while let Some(node) = stack.pop() {
        match node {
            tree::Substructure::Leaf(dofs) => {
                if dofs.len() <= reduce::DENSE_LEAF {
                    let modes = reduce::leaf_eigenpairs(ctx, dofs, factor * bound, at_least)?;
                    all.extend_from_slice(&modes.mu);
                    if let Some(&first) = dofs.first() {
                        ctx.leaf_modes.borrow_mut().insert(first, modes);
                    }
                    if all.len() >= count.max(1) {
                        let c = count.max(1) - 1;
                        all.select_nth_unstable_by(c, f64::total_cmp);
                        bound = all[c];
                        all.truncate(count.max(1));
                    }
                }
            }
            tree::Substructure::Split { children, .. } => {
                stack.extend(children.iter());
            }
        }
    }
    all.sort_by(f64::total_cmp);
    Ok(match all.get(count.saturating_sub(1)) {
        Some(&mu) => mu,
        None => all.last().copied().unwrap_or(1.0),
    })
}
