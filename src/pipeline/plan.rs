//! The build's options, resolved once before the first stage: the spec with the deck's own
//! requests filled in ([`deck_defaults`]), and the settings every stage shares (assembly, eigen
//! solves, the file named in messages).

use crate::fe::AssemblySpec;
use crate::model::Model;
use crate::pipeline::deck::deck_defaults;
use crate::pipeline::{BuildError, BuildSpec, DEFAULT_MODES};
use crate::reduce::select::{self, ModeCount};
use crate::solve::EigenSpec;

/// What this build does, resolved from its [`BuildSpec`] and the model's deck.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The spec with the deck's defaults filled in (mass, mode count, interface, title).
    pub spec: BuildSpec,
    /// The band of the deck's eigenvalue request, when the spec gives neither count nor fmax.
    pub deck_band: Option<ModeCount>,
    /// What was taken from the deck, for the report.
    pub deck_notes: Vec<String>,
    /// Assembly of K and M: mass kind and beam lumping.
    pub assembly: AssemblySpec,
    /// Every eigen solve and the parallel kernels: threads, band proof, precision.
    pub eigen: EigenSpec,
    /// The model file, as messages name it.
    pub file_name: String,
}

impl Plan {
    /// `spec` with the deck's requests (COUPMASS, METHOD, ASET, TITLE) filling the choices it
    /// leaves open.
    pub fn resolve(spec: &BuildSpec, model: &Model) -> Plan {
        let defaults = deck_defaults(spec, model);
        let spec = defaults.spec;
        Plan {
            assembly: AssemblySpec {
                mass: spec.mass,
                beam_lumping: spec.beam_mass.unwrap_or_default(),
                ..Default::default()
            },
            eigen: EigenSpec {
                dofs_per_node: Some(3),
                par: spec.par(),
                verify_band: spec.verify_band,
                precision: spec.precision,
                ..Default::default()
            },
            file_name: spec.model.display().to_string(),
            deck_band: defaults.band,
            deck_notes: defaults.notes,
            spec,
        }
    }

    /// A request that does not fit the model: `message` says what is wrong and what to do.
    pub fn request_error(&self, message: String) -> BuildError {
        BuildError::Request {
            file: self.file_name.clone(),
            message,
        }
    }

    /// The modes to compute: `--fmax` (to [`select::FMAX_FACTOR`] times it), else the deck's
    /// band, else `--modes` or [`DEFAULT_MODES`].
    pub fn mode_count(&self) -> Result<ModeCount, BuildError> {
        let spec = &self.spec;
        Ok(match (spec.modes, spec.fmax_hz, self.deck_band) {
            (_, Some(f), _) if !(f.is_finite() && f > 0.0) => {
                return Err(
                    self.request_error(format!("--fmax {f} must be a positive frequency in Hz"))
                )
            }
            (_, Some(f), _) => ModeCount::BelowHz(select::FMAX_FACTOR * f),
            (_, None, Some(band)) => band,
            (Some(n), None, None) => ModeCount::Count(n),
            (None, None, None) => ModeCount::Count(DEFAULT_MODES),
        })
    }
}
