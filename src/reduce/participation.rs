//! Mode selection by the scene (`--select participation:ε`): the candidate modes are ranked by
//! what the scene's loads (and unit loads at the interface dofs) make them do over the band
//! [0, fmax], and the fewest are kept whose estimated frequency-response error stays ≤ ε.
//!
//! For a load f_k with static (elastic, inertia-relief balanced) compliance c_k = f_kᵀr_k and a
//! set with modal loads g_jk = φ_jᵀf_k, the work-conjugate ("driving-point") frequency response
//! is H_k(ω) = Σ_j g_jk² / (ω_j² − ω² + 2iζω_jω) (modal superposition, rigid modes excluded).
//! Dropping a set D of candidate modes changes it by their terms, bounded by
//! Σ_{j∈D} g_jk² w_j(ω) with w_j = 1/|ω_j² − ω² + 2iζω_jω| (the modes' FRF amplitude) or, when
//! the load's residual vector is added afterwards (it carries the dropped modes' static part,
//! the mode-acceleration argument), w_j = |1/(ω_j² − ω² + 2iζω_jω) − 1/ω_j²|. The modes beyond
//! the candidates hold the static compliance the candidates miss, T_k = c_k − Σ g_jk²/ω_j²;
//! with every one above the highest candidate ω_c, their terms are bounded by T_k·ω_c²/(ω_c² − ω²)
//! (T_k·ω²/(ω_c² − ω²) with the residual vector). The estimate is the worst over loads and band
//! of that bound relative to c_k: the FRF error relative to the load's static response.
//!
//! Ranking: each candidate's score is its largest term over loads and band (relative to c_k);
//! candidates are dropped lowest score first while the estimate stays ≤ ε. Rigid-body modes are
//! always kept. ζ is the build's damping ratio, or [`DEFAULT_DAMPING`] (it only bounds the
//! resonance peak of a dropped mode inside the band).

use super::select::{pick, Selection};
use super::{ModeLabel, ModeSet, ReduceError};
use faer::Mat;

/// Damping ratio of the band's FRF amplitude when the build gives none (2 %, a common structural
/// value); only the peak of a dropped mode that resonates inside the band depends on it.
pub const DEFAULT_DAMPING: f64 = 0.02;

/// Evenly spaced frequencies of the band at which the estimate is evaluated (plus the
/// candidates' own frequencies inside the band, where their peaks are).
pub const BAND_SAMPLES: usize = 400;

/// A load whose static compliance is below this fraction of the largest one deforms the body
/// negligibly (e.g. gravity on a free body, balanced by its inertia): it does not rank modes.
pub const NEGLIGIBLE_COMPLIANCE: f64 = 1e-12;

/// What the selection is asked for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Participation {
    /// Largest estimated FRF error (relative to each load's static response) accepted.
    pub epsilon: f64,
    /// Upper end of the band (Hz).
    pub band_hz: f64,
    /// Damping ratio ζ of the FRF amplitude.
    pub damping: f64,
}

/// What the selection did.
#[derive(Debug, Clone, PartialEq)]
pub struct SelectionReport {
    /// Flexible candidate modes.
    pub candidates: usize,
    /// Flexible modes kept.
    pub kept: usize,
    /// Frequencies (Hz) of the dropped modes, ascending.
    pub dropped_hz: Vec<f64>,
    /// The estimated worst FRF error with the kept modes (relative to static response).
    pub estimate: f64,
    /// The same with every candidate kept (the truncation beyond the candidates alone).
    pub estimate_all: f64,
    /// Per load (column of `f`): its estimated worst error with the kept modes (`None` for a load
    /// with negligible compliance).
    pub per_load: Vec<Option<f64>>,
}

/// |1/(a − ω² + 2iζ√a ω)| with a = ω_j², or with `corrected` the same minus its static value.
fn weight(a: f64, w: f64, zeta: f64, corrected: bool) -> f64 {
    let re = a - w * w;
    let im = 2.0 * zeta * a.sqrt() * w;
    let d = (re * re + im * im).sqrt();
    if corrected {
        // |1/(re + i im) − 1/a| = |a − re − i im| / (a d) = |ω² − i im| / (a d)
        (w * w).hypot(im) / (a * d)
    } else {
        1.0 / d
    }
}

/// Selects modes of `set` by the participation of the loads `f` (n × L, over the set's dofs)
/// with static compliances `compliance` (length L, c_k = f_kᵀr_k); `corrected[k]` says whether
/// load k's residual vector will be added (module doc).
pub fn select_by_participation(
    set: ModeSet,
    f: &Mat<f64>,
    compliance: &[f64],
    corrected: &[bool],
    p: &Participation,
) -> Result<(ModeSet, SelectionReport), ReduceError> {
    let nl = f.ncols();
    if compliance.len() != nl || corrected.len() != nl || f.nrows() != set.phi.nrows() {
        return Err(ReduceError::Dofs {
            what: "participation selection",
            detail: format!(
                "{nl} loads over {} rows, {} compliances, {} flags, {} dofs",
                f.nrows(),
                compliance.len(),
                corrected.len(),
                set.phi.nrows()
            ),
        });
    }
    if !(p.epsilon.is_finite() && p.epsilon > 0.0 && p.band_hz > 0.0 && p.damping >= 0.0) {
        return Err(ReduceError::Dofs {
            what: "participation selection",
            detail: format!(
                "ε = {}, band {} Hz, ζ = {}: need ε > 0 and a positive band",
                p.epsilon, p.band_hz, p.damping
            ),
        });
    }
    let two_pi = 2.0 * std::f64::consts::PI;
    let w_max = two_pi * p.band_hz;
    let flex: Vec<usize> = (0..set.len())
        .filter(|&j| set.labels[j] != ModeLabel::Rigid)
        .collect();
    let w_c2 = flex.iter().map(|&j| set.omega2[j]).fold(0.0f64, f64::max);
    if w_c2 <= (1.01 * w_max).powi(2) {
        return Err(ReduceError::Dofs {
            what: "participation selection",
            detail: format!(
                "the candidate modes reach only {:.4} Hz, not above the band's {:.4} Hz: compute \
                 more candidates (a higher --fmax basis or more --modes)",
                w_c2.max(0.0).sqrt() / two_pi,
                p.band_hz
            ),
        });
    }
    // g = Φᵀf over the flexible candidates
    let g = set.phi.transpose() * f;
    let c_top = compliance.iter().copied().fold(0.0f64, f64::max);
    let live: Vec<usize> = (0..nl)
        .filter(|&k| compliance[k] > NEGLIGIBLE_COMPLIANCE * c_top && c_top > 0.0)
        .collect();
    if live.is_empty() {
        return Err(ReduceError::Dofs {
            what: "participation selection",
            detail: "no scene load or interface unit load deforms the body (all are balanced by \
                     its rigid-body inertia or held): nothing ranks the modes"
                .into(),
        });
    }
    let mut omegas: Vec<f64> = (0..=BAND_SAMPLES)
        .map(|s| w_max * s as f64 / BAND_SAMPLES as f64)
        .collect();
    omegas.extend(
        flex.iter()
            .map(|&j| set.omega2[j].max(0.0).sqrt())
            .filter(|&w| w <= w_max),
    );
    let ns = omegas.len();
    // acc[k][s]: the tail bound, then plus the dropped modes' terms, relative to c_k
    let mut acc: Vec<Vec<f64>> = live
        .iter()
        .map(|&k| {
            let captured: f64 = flex
                .iter()
                .map(|&j| g[(j, k)].powi(2) / set.omega2[j])
                .sum();
            let tail = (compliance[k] - captured).max(0.0);
            omegas
                .iter()
                .map(|&w| {
                    let amp = if corrected[k] { w * w } else { w_c2 };
                    tail * amp / (w_c2 - w * w) / compliance[k]
                })
                .collect()
        })
        .collect();
    let worst = |acc: &Vec<Vec<f64>>| -> f64 {
        acc.iter()
            .flat_map(|r| r.iter().copied())
            .fold(0.0f64, f64::max)
    };
    let estimate_all = worst(&acc);
    // term[j][k][s]
    let term = |j: usize, a: usize, s: usize| -> f64 {
        let k = live[a];
        let g2 = g[(j, k)].powi(2);
        if g2 == 0.0 {
            return 0.0;
        }
        g2 * weight(set.omega2[j], omegas[s], p.damping, corrected[k]) / compliance[k]
    };
    let mut ranked: Vec<(f64, usize)> = flex
        .iter()
        .map(|&j| {
            let score = (0..live.len())
                .flat_map(|a| (0..ns).map(move |s| (a, s)))
                .map(|(a, s)| term(j, a, s))
                .fold(0.0f64, f64::max);
            (score, j)
        })
        .collect();
    ranked.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let mut dropped: Vec<usize> = Vec::new();
    let mut estimate = estimate_all;
    if estimate_all <= p.epsilon {
        for &(_, j) in &ranked {
            let mut next = acc.clone();
            for (a, row) in next.iter_mut().enumerate() {
                for (s, v) in row.iter_mut().enumerate() {
                    *v += term(j, a, s);
                }
            }
            let e = worst(&next);
            if e > p.epsilon {
                break;
            }
            acc = next;
            estimate = e;
            dropped.push(j);
        }
    }
    let mut per_load = vec![None; nl];
    for (a, &k) in live.iter().enumerate() {
        per_load[k] = Some(acc[a].iter().copied().fold(0.0f64, f64::max));
    }
    let mut is_dropped = vec![false; set.len()];
    for &j in &dropped {
        is_dropped[j] = true;
    }
    let keep: Vec<usize> = (0..set.len()).filter(|&j| !is_dropped[j]).collect();
    let mut dropped_hz: Vec<f64> = dropped
        .iter()
        .map(|&j| set.omega2[j].max(0.0).sqrt() / two_pi)
        .collect();
    dropped_hz.sort_by(f64::total_cmp);
    let report = SelectionReport {
        candidates: flex.len(),
        kept: flex.len() - dropped.len(),
        dropped_hz,
        estimate,
        estimate_all,
        per_load,
    };
    let mut out = pick(
        set,
        &keep,
        Selection::Participation {
            epsilon: p.epsilon,
            estimate,
            band_hz: p.band_hz,
        },
    );
    out.diagnostics.notes.push(note(&report, p));
    Ok((out, report))
}

/// The build-report line of a selection.
pub fn note(r: &SelectionReport, p: &Participation) -> String {
    let list: Vec<String> = r.dropped_hz.iter().map(|f| format!("{f:.4}")).collect();
    let mut s = format!(
        "scene selection (participation, ε = {:.3e}, band 0–{:.4} Hz, ζ = {}): {} of {} flexible \
         candidate modes kept, estimated worst FRF error {:.3e} of the static response (all \
         candidates: {:.3e})",
        p.epsilon, p.band_hz, p.damping, r.kept, r.candidates, r.estimate, r.estimate_all
    );
    if r.estimate_all > p.epsilon {
        s += "; the candidates alone miss ε: all kept (raise --fmax/--modes or add residual vectors)";
    }
    if !list.is_empty() {
        s += &format!("; dropped (Hz): {}", list.join(", "));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corrected weight is the uncorrected response minus its static value (closed form).
    #[test]
    fn corrected_weight_is_the_dynamic_part() {
        let (a, w, z) = (100.0f64, 4.0f64, 0.05f64);
        let re = a - w * w;
        let im = 2.0 * z * a.sqrt() * w;
        let d2 = re * re + im * im;
        // 1/(re + i im) = (re − i im)/d2
        let (hr, hi) = (re / d2 - 1.0 / a, -im / d2);
        assert!((weight(a, w, z, true) - hr.hypot(hi)).abs() < 1e-15);
        assert!((weight(a, w, z, false) - 1.0 / d2.sqrt()).abs() < 1e-15);
        assert_eq!(weight(a, 0.0, z, true), 0.0);
    }
}
