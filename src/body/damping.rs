//! Modal damping from `--damping` (entry `damping.bin`, SPEC.md §5.9): one ratio for every
//! mode (`2%` or `0.02`), ratios by frequency band (`0-1000:1%,1000-:3%`, bands [lo, hi) in Hz,
//! an empty upper end is open), or Rayleigh damping C = αM + βK (`rayleigh:α,β`), whose modal
//! ratio is ζ_j = α/(2ω_j) + βω_j/2 (Clough & Penzien eq. 12-42). Rigid-body modes get 0.

use flexbody_reader as file;

/// A parsed `--damping` value.
#[derive(Debug, Clone, PartialEq)]
pub enum DampingSpec {
    /// One ratio for every flexible mode.
    Constant(f64),
    /// (lower Hz, upper Hz or ∞, ratio): a mode at f takes the first band with lo ≤ f < hi.
    Bands(Vec<(f64, f64, f64)>),
    /// Rayleigh C = αM + βK.
    Rayleigh {
        /// Mass-proportional coefficient α (1/time).
        alpha: f64,
        /// Stiffness-proportional coefficient β (time).
        beta: f64,
    },
}

/// A `--damping` value that cannot be read or applied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("--damping {value}: {message}")]
pub struct DampingError {
    /// The option value.
    pub value: String,
    /// What is wrong.
    pub message: String,
}

fn ratio(s: &str) -> Option<f64> {
    let s = s.trim();
    let v = match s.strip_suffix('%') {
        Some(p) => p.trim().parse::<f64>().ok()? / 100.0,
        None => s.parse::<f64>().ok()?,
    };
    (v.is_finite() && v >= 0.0).then_some(v)
}

/// A modal damping ratio ζ ≥ 1 is critical or overdamped: the mode does not oscillate, and
/// a modal-damping solver's ζ·2ω term is meant for ζ well below 1 (2% is typical of steel).
fn underdamped(v: f64) -> bool {
    v < 1.0
}

const OVERDAMPED: &str = "a modal damping ratio must be below 1 (100%): ζ ≥ 1 is critical or \
                          overdamped, no vibration mode (typical ratios are 0.5%–5%)";

/// Parses `2%`, `0.02`, `0-1000:1%,1000-:3%` or `rayleigh:α,β`.
pub fn parse_damping(value: &str) -> Result<DampingSpec, DampingError> {
    let err = |message: &str| DampingError {
        value: value.to_string(),
        message: message.to_string(),
    };
    let v = value.trim();
    if let Some(rest) = v.strip_prefix("rayleigh:") {
        let (a, b) = rest
            .split_once(',')
            .ok_or_else(|| err("expected rayleigh:ALPHA,BETA"))?;
        let (alpha, beta) = (a.trim().parse::<f64>(), b.trim().parse::<f64>());
        return match (alpha, beta) {
            (Ok(alpha), Ok(beta))
                if alpha.is_finite() && beta.is_finite() && alpha >= 0.0 && beta >= 0.0 =>
            {
                Ok(DampingSpec::Rayleigh { alpha, beta })
            }
            _ => Err(err("ALPHA and BETA must be finite numbers ≥ 0")),
        };
    }
    if !v.contains(':') {
        let r = ratio(v).ok_or_else(|| err("expected a ratio ≥ 0 such as 2% or 0.02"))?;
        return if underdamped(r) {
            Ok(DampingSpec::Constant(r))
        } else {
            Err(err(OVERDAMPED))
        };
    }
    let mut bands = Vec::new();
    for part in v.split(',') {
        let (range, r) = part
            .split_once(':')
            .ok_or_else(|| err("expected bands LO-HI:RATIO separated by commas"))?;
        let (lo, hi) = range
            .split_once('-')
            .ok_or_else(|| err("a band is LO-HI (Hz; HI may be empty)"))?;
        let lo: f64 = lo
            .trim()
            .parse()
            .map_err(|_| err("a band's lower end must be a number (Hz)"))?;
        let hi: f64 = if hi.trim().is_empty() {
            f64::INFINITY
        } else {
            hi.trim()
                .parse()
                .map_err(|_| err("a band's upper end must be a number (Hz) or empty"))?
        };
        let r = ratio(r).ok_or_else(|| err("a band's ratio must be ≥ 0, e.g. 1% or 0.01"))?;
        if !(lo >= 0.0 && hi > lo) {
            return Err(err("each band needs 0 ≤ LO < HI"));
        }
        if !underdamped(r) {
            return Err(err(OVERDAMPED));
        }
        bands.push((lo, hi, r));
    }
    Ok(DampingSpec::Bands(bands))
}

/// The ratio of every mode of `modes` (ω², frequencies, labels): 0 for rigid-body modes; an error
/// names a flexible mode no band covers.
pub fn modal_ratios(spec: &DampingSpec, modes: &file::Modes) -> Result<Vec<f64>, DampingError> {
    modes
        .omega2
        .iter()
        .zip(&modes.frequency_hz)
        .zip(&modes.labels)
        .enumerate()
        .map(|(j, ((&w2, &f), label))| {
            if *label == file::ModeLabel::Rigid {
                return Ok(0.0);
            }
            match spec {
                DampingSpec::Constant(r) => Ok(*r),
                DampingSpec::Bands(bands) => bands
                    .iter()
                    .find(|(lo, hi, _)| *lo <= f && f < *hi)
                    .map(|b| b.2)
                    .ok_or_else(|| DampingError {
                        value: format!("{bands:?}"),
                        message: format!("mode {} at {f:.6} Hz lies in no band", j + 1),
                    }),
                DampingSpec::Rayleigh { alpha, beta } => {
                    let w = w2.max(0.0).sqrt();
                    Ok(if w > 0.0 {
                        alpha / (2.0 * w) + beta * w / 2.0
                    } else {
                        0.0
                    })
                }
            }
        })
        .collect()
}

/// Fills `body.damping` from `value` (the option text) and records the text in the recipe.
pub fn apply(body: &mut file::ReducedBody, value: &str) -> Result<(), DampingError> {
    let spec = parse_damping(value)?;
    let ratio = modal_ratios(&spec, &body.modes).map_err(|e| DampingError {
        value: value.to_string(),
        message: e.message,
    })?;
    // Rayleigh's ζ grows without bound at both ends of the spectrum
    if let Some((j, &z)) = ratio.iter().enumerate().find(|(_, &z)| !underdamped(z)) {
        return Err(DampingError {
            value: value.to_string(),
            message: format!(
                "mode {} at {:.6} Hz gets ζ = {z:.4}; {OVERDAMPED}",
                j + 1,
                body.modes.frequency_hz[j]
            ),
        });
    }
    body.damping = Some(file::Damping { ratio });
    if let Some(r) = body.recipe.as_mut() {
        r.options.damping = Some(value.to_string());
    }
    Ok(())
}
