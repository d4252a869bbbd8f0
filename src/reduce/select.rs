//! Mode selection: an explicit count, or every mode up to a cutoff derived from the highest
//! frequency of the scene, `cutoff = FMAX_FACTOR · f_scene`. Rigid-body modes are always kept.

use super::{ModeLabel, ModeSet, ReduceError};
use crate::solve::{hz, lowest_modes, EigenSolution, EigenSpec, SparseColMat};

/// Cutoff factor on the scene's highest frequency. A mode well above the excitation responds
/// quasi-statically; keeping modes to 3× the highest frequency of interest (the common rule of
/// thumb for multibody flexible bodies, 2–3×) keeps the dynamic amplification of the last
/// retained mode within ~12 % (1/(1 − (1/3)²)) while the static part is carried by the
/// constraint/attachment modes.
pub const FMAX_FACTOR: f64 = 3.0;

/// How many modes a method computes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ModeCount {
    /// The lowest `n`.
    Count(usize),
    /// All modes up to this frequency (Hz).
    BelowHz(f64),
    /// Every mode of the (sub)problem (dense; for verification on small models).
    All,
}

/// The selection recorded on a mode set.
#[derive(Clone, Debug, PartialEq)]
pub enum Selection {
    /// The lowest `n` modes were kept.
    Count(usize),
    /// Modes up to `cutoff_hz = factor · scene_hz` were kept.
    Fmax {
        scene_hz: f64,
        factor: f64,
        cutoff_hz: f64,
    },
    /// The fewest candidates whose estimated FRF error over [0, `band_hz`] is ≤ `epsilon`
    /// (see [`super::participation`]); `estimate` is that error with the kept modes.
    Participation {
        epsilon: f64,
        estimate: f64,
        band_hz: f64,
    },
}

/// Lowest eigenpairs by [`ModeCount`]; `BelowHz` runs the solver in band mode (one iteration
/// that grows its count until a converged mode lies above the limit), doubles the count and asks
/// again only when a run came back with every mode below the limit (the dense path, or a band
/// past the sparse path's size limit), then truncates.
pub fn solve_count(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    count: ModeCount,
    eig: &EigenSpec,
) -> Result<EigenSolution, ReduceError> {
    let run = |c: usize, upper: Option<f64>| -> Result<EigenSolution, ReduceError> {
        let spec = EigenSpec {
            count: c,
            upper,
            ..eig.clone()
        };
        Ok(match &eig.engine {
            Some(engine) => crate::solve::slepc::lowest_modes(k, m, &spec, engine)?,
            None => lowest_modes(k, m, &spec)?,
        })
    };
    solve_count_with(k, m, count, eig.shift, &run)
}

/// [`solve_count`] with the solver supplied by the caller (e.g. one reusing an existing
/// factorization): `run(count, upper)` returns the lowest `count` eigenpairs, or with `upper`
/// given may return more, up to the first eigenvalue above `upper`; `shift` is used for the
/// dense `All` path.
pub fn solve_count_with(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    count: ModeCount,
    shift: Option<f64>,
    run: &dyn Fn(usize, Option<f64>) -> Result<EigenSolution, ReduceError>,
) -> Result<EigenSolution, ReduceError> {
    let n = k.nrows();
    match count {
        ModeCount::Count(c) => run(c.min(n), None),
        ModeCount::All => {
            let kd = crate::solve::sparse_ops::to_dense(k.as_ref());
            let md = crate::solve::sparse_ops::to_dense(m.as_ref());
            // all finite eigenvalues: the dense solver reports how many there are
            let (vals, vecs) = match crate::solve::dense::lowest(kd.as_ref(), md.as_ref(), n, shift)
            {
                Ok(r) => r,
                Err(crate::solve::SolveError::TooManyModes { available, .. }) => {
                    crate::solve::dense::lowest(kd.as_ref(), md.as_ref(), available, shift)?
                }
                Err(e) => return Err(e.into()),
            };
            Ok(EigenSolution {
                residuals: vec![0.0; vals.len()],
                eigenvalues: vals,
                vectors: vecs,
                info: crate::solve::EigenInfo {
                    solver: crate::solve::Solver::Dense,
                    ..Default::default()
                },
            })
        }
        ModeCount::BelowHz(f) => {
            let upper = (2.0 * std::f64::consts::PI * f).powi(2);
            let mut c = 12usize.min(n);
            loop {
                let s = run(c, Some(upper))?;
                let last = *s.eigenvalues.last().unwrap_or(&0.0);
                let got = s.eigenvalues.len();
                if hz(last) > f || got >= n {
                    let keep = s.eigenvalues.iter().filter(|&&l| hz(l) <= f).count();
                    return Ok(truncate(s, keep));
                }
                c = (2 * c.max(got)).min(n);
            }
        }
    }
}

/// Rejects a mode request a problem of `n` dofs cannot satisfy: an explicit count of 0 or above
/// `n` (`what` names the problem, e.g. "the interior"), with what to do instead.
pub(crate) fn check_count(count: ModeCount, n: usize, what: &str) -> Result<(), ReduceError> {
    match count {
        ModeCount::Count(0) => Err(ReduceError::Dofs {
            what: "mode count",
            detail: format!("0 modes requested for {what}: ask for at least one (--modes) or give --fmax"),
        }),
        ModeCount::Count(c) if c > n => Err(ReduceError::Dofs {
            what: "mode count",
            detail: format!(
                "{c} modes requested but {what} has only {n} dofs: ask for fewer (--modes) or give --fmax"
            ),
        }),
        _ => Ok(()),
    }
}

/// The error for a frequency cutoff with no flexible mode below it: `first_hz` is the first
/// flexible mode found above it.
pub(crate) fn cutoff_below_first(cutoff_hz: f64, first_hz: f64) -> ReduceError {
    ReduceError::Dofs {
        what: "mode cutoff",
        detail: format!(
            "no flexible mode below the cutoff {cutoff_hz:.6} Hz (3 x --fmax): the first one is at \
             {first_hz:.6} Hz; raise --fmax above {:.6} Hz or give --modes",
            first_hz / FMAX_FACTOR
        ),
    }
}

/// The first `keep` pairs of a solution.
pub fn truncate(mut s: EigenSolution, keep: usize) -> EigenSolution {
    s.eigenvalues.truncate(keep);
    s.residuals.truncate(keep);
    s.vectors = s.vectors.as_ref().subcols(0, keep).to_owned();
    s
}

/// Keeps the rigid modes and the lowest flexible ones: all up to `FMAX_FACTOR · scene_hz`.
pub fn by_fmax(set: ModeSet, scene_hz: f64) -> ModeSet {
    let cutoff = FMAX_FACTOR * scene_hz;
    let f = set.frequencies_hz();
    let keep: Vec<usize> = (0..set.len())
        .filter(|&j| set.labels[j] == ModeLabel::Rigid || f[j] <= cutoff)
        .collect();
    let sel = Selection::Fmax {
        scene_hz,
        factor: FMAX_FACTOR,
        cutoff_hz: cutoff,
    };
    pick(set, &keep, sel)
}

/// Keeps the lowest `count` modes.
pub fn by_count(set: ModeSet, count: usize) -> ModeSet {
    let keep: Vec<usize> = (0..set.len().min(count)).collect();
    pick(set, &keep, Selection::Count(count))
}

pub(crate) fn pick(mut set: ModeSet, keep: &[usize], sel: Selection) -> ModeSet {
    // normal modes: each mode is its own eigenvector, kept or not with it
    if let Some(r) = set.diagnostics.eigenproblem.as_mut() {
        if set.method == super::Method::NormalModes && r.omega2.len() == set.omega2.len() {
            *r = r.pick(keep);
        }
    }
    let phi = faer::Mat::from_fn(set.phi.nrows(), keep.len(), |i, j| set.phi[(i, keep[j])]);
    set.phi = phi;
    set.omega2 = keep.iter().map(|&j| set.omega2[j]).collect();
    set.labels = keep.iter().map(|&j| set.labels[j].clone()).collect();
    let r = &set.diagnostics.residuals;
    if r.len() >= keep.iter().max().map_or(0, |&x| x + 1) {
        set.diagnostics.residuals = keep.iter().map(|&j| r[j]).collect();
    }
    let s = &set.diagnostics.label_shares;
    if s.len() >= keep.iter().max().map_or(0, |&x| x + 1) {
        set.diagnostics.label_shares = keep.iter().map(|&j| s[j]).collect();
    }
    if let Some(o) = set.diagnostics.origin.as_mut() {
        if o.weights.ncols() >= keep.iter().max().map_or(0, |&x| x + 1) {
            o.weights = faer::Mat::from_fn(o.weights.nrows(), keep.len(), |c, j| {
                o.weights[(c, keep[j])]
            });
        } else {
            set.diagnostics.origin = None;
        }
    }
    set.selection = Some(sel);
    set
}
