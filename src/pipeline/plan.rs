//! The build's options, resolved once before the first stage: the spec with the deck's own
//! requests filled in (mass, interface, title: [`Plan::resolve`]), the modes asked
//! ([`ModeRequest`]: `--modes`, `--fmax` and the deck's eigenvalue request in one place), and
//! the settings every stage shares (assembly, eigen solves, the file named in messages). The
//! stages read the plan, never the spec as given.
//!
//! What a deck asks, as its own solver applies it: `PARAM,COUPMASS > 0` → consistent mass unless
//! the user chose `--mass`; the case control's `METHOD` → `EIGRL`/`EIGR` (ND, V1, V2), or a
//! CalculiX `*FREQUENCY` → the mode count or band unless `--modes`/`--fmax` are given;
//! QSET/QSET1 → the mode count when nothing else gives one; bulk-data ASET/ASET1/BSET/BSET1 →
//! the interface unless `--interface` is given; TITLE → the header title. Each choice is a note
//! in the build report.

use std::collections::BTreeMap;

use crate::fe::{AssemblySpec, MassKind};
use crate::model::{DofMask, Model, NodeIndex};
use crate::pipeline::{BuildError, BuildSpec, DEFAULT_MODES};
use crate::reduce::select::{self, ModeCount};
use crate::solve::EigenSpec;

/// What this build does, resolved from its [`BuildSpec`] and the model's deck.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The spec with the deck's defaults filled in (mass, interface, title). Its `modes` and
    /// `fmax_hz` are cleared: the modes asked are [`Plan::modes`].
    pub spec: BuildSpec,
    /// The modes asked: what the eigensolvers compute, the cap, the scene's band.
    pub modes: ModeRequest,
    /// What was taken from the deck, for the report.
    pub deck_notes: Vec<String>,
    /// Assembly of K and M: mass kind and beam lumping.
    pub assembly: AssemblySpec,
    /// Every eigen solve and the parallel kernels: threads, band proof, precision.
    pub eigen: EigenSpec,
    /// The model file, as messages name it.
    pub file_name: String,
}

/// The modes a build asks for, resolved once from `--modes`, `--fmax` and the deck's eigenvalue
/// request (EIGRL/EIGR ND and V2, `*FREQUENCY`) or q-set size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeRequest {
    /// What the eigensolvers compute: `--fmax` (to [`select::FMAX_FACTOR`] times it), else the
    /// deck's band, else the count (or [`DEFAULT_MODES`]).
    pub solve: ModeCount,
    /// The count asked: `--modes`, else the deck's ND or q-set size (the file's request and
    /// recipe record it).
    pub count: Option<usize>,
    /// The count that caps a band (`count`, when `--fmax` or the deck's band is asked too;
    /// Craig–Bampton keeps its constraint modes on top).
    pub cap: Option<usize>,
    /// `--fmax`: the scene's highest frequency (the accuracy band, the participation band).
    pub fmax_hz: Option<f64>,
}

impl Plan {
    /// `spec` with the deck's requests (COUPMASS, METHOD, ASET, TITLE) filling the choices it
    /// leaves open (module doc); an `--fmax` that is no positive frequency is refused.
    pub fn resolve(spec: &BuildSpec, model: &Model) -> Result<Plan, BuildError> {
        let mut spec = spec.clone();
        let mut notes: Vec<String> = model.deck.notes.clone();
        if let Some(s) = model.deck.subcase {
            notes.push(format!("case control: subcase {s} used"));
        }
        spec.mass = deck_mass(&spec, model, &mut notes);
        let modes = ModeRequest::resolve(&spec, model, &mut notes)?;
        (spec.modes, spec.fmax_hz) = (None, None);
        if let Some(interface) = deck_interface(&spec, model, &mut notes) {
            spec.interface = interface;
        }
        if spec.title.is_none() {
            spec.title = model.deck.title.clone().filter(|t| !t.is_empty());
        }
        Ok(Plan {
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
                engine: spec.engine.clone(),
                method: spec.eigensolver,
                ..Default::default()
            },
            file_name: spec.model.display().to_string(),
            modes,
            deck_notes: notes,
            spec,
        })
    }

    /// A request that does not fit the model: `message` says what is wrong and what to do.
    pub fn request_error(&self, message: String) -> BuildError {
        BuildError::Request {
            file: self.file_name.clone(),
            message,
        }
    }
}

impl ModeRequest {
    /// The modes `spec` asks, the deck's eigenvalue request or q-set filling a spec that gives
    /// neither `--modes` nor `--fmax`; `notes` say what was taken from the deck.
    fn resolve(
        spec: &BuildSpec,
        model: &Model,
        notes: &mut Vec<String>,
    ) -> Result<ModeRequest, BuildError> {
        let mut count = spec.modes;
        let mut band = None;
        if spec.modes.is_none() && spec.fmax_hz.is_none() {
            if let Some(e) = &model.deck.eigen {
                count = e.count;
                if let Some(hi) = e.upper_hz.filter(|h| *h > 0.0) {
                    band = Some(ModeCount::BelowHz(hi));
                }
                let what = match (e.count, band) {
                    (Some(n), Some(_)) => format!(
                        "the modes below {} Hz, at most {n}",
                        e.upper_hz.unwrap_or(0.0)
                    ),
                    (Some(n), None) => format!("{n} modes"),
                    (None, _) => format!("the modes below {} Hz", e.upper_hz.unwrap_or(0.0)),
                };
                notes.push(format!(
                    "mode count: {what}, from the deck's {} (give --modes or --fmax to override)",
                    e.source
                ));
                if let Some(lo) = e.lower_hz.filter(|l| *l > 0.0) {
                    notes.push(format!(
                        "the eigenvalue request's lower bound V1 = {lo} Hz is not used: a reduction keeps every mode from 0 Hz"
                    ));
                }
            } else if let Some((q, cards)) = &model.deck.qset_modes {
                count = Some(*q);
                notes.push(format!(
                    "mode count: {q}, the number of q-set dofs of the deck's {cards} (give --modes or --fmax to override)"
                ));
            }
        } else if let Some(e) = &model.deck.eigen {
            notes.push(format!(
                "the deck's {} is not used: --modes/--fmax given",
                e.source
            ));
        }
        if let (Some((q, cards)), true) = (&model.deck.qset_modes, model.deck.eigen.is_some()) {
            notes.push(format!(
                "the deck's {cards} ({q} q-set dofs) do not set the mode count: the eigenvalue request does"
            ));
        }
        let solve = match (spec.fmax_hz, band, count) {
            (Some(f), _, _) if !(f.is_finite() && f > 0.0) => {
                return Err(BuildError::Request {
                    file: spec.model.display().to_string(),
                    message: format!("--fmax {f} must be a positive frequency in Hz"),
                })
            }
            (Some(f), _, _) => ModeCount::BelowHz(select::FMAX_FACTOR * f),
            (None, Some(band), _) => band,
            (None, None, Some(n)) => ModeCount::Count(n),
            (None, None, None) => ModeCount::Count(DEFAULT_MODES),
        };
        let banded = spec.fmax_hz.is_some() || band.is_some();
        Ok(ModeRequest {
            solve,
            count,
            cap: count.filter(|_| banded),
            fmax_hz: spec.fmax_hz,
        })
    }
}

/// The mass of the build: `--mass`, else the deck's PARAM,COUPMASS / LUMPM; `notes` say which.
fn deck_mass(spec: &BuildSpec, model: &Model, notes: &mut Vec<String>) -> MassKind {
    let Some(asked) = &model.params.coupled_mass else {
        return spec.mass;
    };
    let kind = |c: bool| if c { "consistent" } else { "lumped" };
    if !spec.mass_explicit {
        notes.push(format!(
            "mass: {}, because the deck asks for it ({}) (--mass {} overrides)",
            kind(asked.consistent),
            asked.asked_by,
            kind(!asked.consistent)
        ));
        if asked.consistent {
            return MassKind::Consistent;
        }
    } else if (spec.mass == MassKind::Consistent) != asked.consistent {
        notes.push(format!(
            "mass: {} as --mass asks, although the deck asks for {} mass ({})",
            kind(spec.mass == MassKind::Consistent),
            kind(asked.consistent),
            asked.asked_by
        ));
    }
    spec.mass
}

/// The deck's a-set / b-set as interface entries (`NODE:DOFS`) when `--interface` gives none;
/// `notes` say which is used.
fn deck_interface(spec: &BuildSpec, model: &Model, notes: &mut Vec<String>) -> Option<Vec<String>> {
    let source = model.deck.interface_source.as_deref().unwrap_or("ASET");
    if model.interface.is_empty() {
        return None;
    }
    if !spec.interface.is_empty() {
        notes.push(format!(
            "the deck's {source} is not used: --interface given"
        ));
        return None;
    }
    let mut per_node: BTreeMap<NodeIndex, u8> = BTreeMap::new();
    for i in &model.interface {
        *per_node.entry(i.node).or_default() |= i.dofs.0;
    }
    notes.push(format!(
        "interface: the deck's {source} (--interface overrides)"
    ));
    Some(
        per_node
            .iter()
            .map(|(&n, &m)| format!("{}:{}", model.nodes[n].id, DofMask(m).digits()))
            .collect(),
    )
}
