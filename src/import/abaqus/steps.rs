//! Abaqus/CalculiX history data: which `*BOUNDARY` conditions hold the body.
//!
//! `*BOUNDARY` in the model data (before the first `*STEP`) holds in every step. Inside a
//! `*STEP` it belongs to that step and, as Abaqus propagates boundary conditions, to the steps
//! after it (until an `*BOUNDARY, OP=NEW` removes the earlier steps' ones). The body's modes are
//! those of the first `*FREQUENCY` step, so its conditions (with those propagated into it) are
//! applied; the conditions of every other step — a `*STATIC` load case after it, or any step of
//! a deck with no `*FREQUENCY` step — are ignored with a warning naming the step and line.
//! `*FREQUENCY`'s first data value (the number of eigenvalues) is recorded as the deck's mode
//! count request.

use super::Target;
use crate::import::text::Loc;
use crate::model::deck::PreloadRequest;
use crate::model::DofMask;

/// One `*BOUNDARY` data line: where, which dofs, the line.
pub(super) type Boundary = (Target, DofMask, Loc);

/// One `*STEP … *END STEP`.
#[derive(Debug)]
pub(super) struct Step {
    pub loc: Loc,
    pub name: Option<String>,
    /// The procedure keyword (`FREQUENCY`, `STATIC`, …) and its line.
    pub procedure: Option<(String, Loc)>,
    /// Number of eigenvalues asked for by `*FREQUENCY`.
    pub eigenvalues: Option<usize>,
    pub boundaries: Vec<Boundary>,
    /// `*BOUNDARY, OP=NEW` in this step: earlier steps' conditions are removed.
    pub op_new: bool,
    /// `*STEP, PERTURBATION` (or `*FREQUENCY, PERTURBATION`): the step works on the loaded
    /// state of the static step before it.
    pub perturbation: bool,
    /// `*STEP, NLGEOM` (not `NLGEOM=NO`).
    pub nlgeom: bool,
    /// The step's load keywords (`*CLOAD`, `*DLOAD`, `*TEMPERATURE`) and their lines.
    pub loads: Vec<(String, Loc)>,
}

/// Procedure keywords that open an analysis inside a step.
pub(super) const PROCEDURES: [&str; 12] = [
    "FREQUENCY",
    "STATIC",
    "BUCKLE",
    "DYNAMIC",
    "MODAL DYNAMIC",
    "STEADY STATE DYNAMICS",
    "HEAT TRANSFER",
    "COUPLED TEMPERATURE-DISPLACEMENT",
    "VISCO",
    "COMPLEX FREQUENCY",
    "SUBSTRUCTURE GENERATE",
    "MATRIX GENERATE",
];

/// The steps read so far.
#[derive(Debug, Default)]
pub(super) struct Steps {
    pub current: Option<Step>,
    pub done: Vec<Step>,
}

/// The conditions that hold the body, and what was left out.
pub(super) struct Applied<'a> {
    /// Step conditions applied (with the step's description for the report).
    pub boundaries: Vec<(&'a Boundary, String)>,
    /// Warnings: the steps whose conditions were ignored (first *BOUNDARY line, message).
    pub ignored: Vec<(Loc, String)>,
    /// The `*FREQUENCY` step used: its description and eigenvalue count.
    pub frequency: Option<(String, Option<usize>)>,
}

impl Step {
    pub(super) fn describe(&self, number: usize) -> String {
        let proc = self
            .procedure
            .as_ref()
            .map_or("no procedure".to_owned(), |p| format!("*{}", p.0));
        match &self.name {
            Some(n) => format!("step {number} ({n}, {proc})"),
            None => format!("step {number} ({proc})"),
        }
    }
}

impl Steps {
    pub(super) fn begin(
        &mut self,
        loc: Loc,
        name: Option<String>,
        perturbation: bool,
        nlgeom: bool,
    ) {
        self.finish_current();
        self.current = Some(Step {
            loc,
            name,
            procedure: None,
            eigenvalues: None,
            boundaries: Vec::new(),
            op_new: false,
            perturbation,
            nlgeom,
            loads: Vec::new(),
        });
    }

    /// The index of the first `*FREQUENCY` step (the one whose modes the body uses).
    pub(super) fn frequency_step(&self) -> Option<usize> {
        self.done
            .iter()
            .position(|s| s.procedure.as_ref().is_some_and(|p| p.0 == "FREQUENCY"))
    }

    /// The static step that preloads the body's modes (module doc): `Ok(None)` when the
    /// `*FREQUENCY` step is not a perturbation of a loaded state; an error (line, keyword,
    /// message) for a preload that cannot be honoured — an NLGEOM step (the preload is linear),
    /// loads in several steps, or loads in a step that is not `*STATIC`.
    pub(super) fn preload(
        &self,
        at: &dyn Fn(Loc) -> String,
    ) -> Result<Option<usize>, (Loc, String, String)> {
        let Some(f) = self.frequency_step() else {
            return Ok(None);
        };
        let freq = &self.done[f];
        if !freq.perturbation {
            return Ok(None);
        }
        let proc_loc = freq.procedure.as_ref().map_or(freq.loc, |p| p.1);
        let what = format!(
            "the *FREQUENCY, PERTURBATION {} at {}",
            freq.describe(f + 1),
            at(proc_loc)
        );
        let loaded: Vec<usize> = (0..f).filter(|&k| !self.done[k].loads.is_empty()).collect();
        let Some(&k) = loaded.first() else {
            return Ok(None);
        };
        let step = &self.done[k];
        if step.nlgeom {
            return Err((
                step.loc,
                "*STEP, NLGEOM".to_owned(),
                format!(
                    "{} is geometrically nonlinear (NLGEOM) and preloads {what}: flexbody's preload is linear (K + K_G of the linear static state), it cannot reproduce an NLGEOM base state; remove NLGEOM to use the linear preload",
                    step.describe(k + 1)
                ),
            ));
        }
        if let Some(&other) = loaded.get(1) {
            let (kw, loc) = &self.done[other].loads[0];
            return Err((
                *loc,
                kw.clone(),
                format!(
                    "{} loads the body too: a preload of {what} made of several steps' loads is not supported (give them in one *STATIC step)",
                    self.done[other].describe(other + 1)
                ),
            ));
        }
        if step.procedure.as_ref().is_none_or(|p| p.0 != "STATIC") {
            let (kw, loc) = &step.loads[0];
            return Err((
                *loc,
                kw.clone(),
                format!(
                    "{} preloads {what} but is not a *STATIC step: only a linear static preload is supported",
                    step.describe(k + 1)
                ),
            ));
        }
        Ok(Some(k))
    }

    /// Whether the first `*FREQUENCY` step is over: every keyword after it is ignored (only
    /// that step and what precedes it define the body).
    pub(super) fn after_frequency(&self) -> bool {
        (self.done.iter()).any(|s| s.procedure.as_ref().is_some_and(|p| p.0 == "FREQUENCY"))
    }

    pub(super) fn finish_current(&mut self) {
        if let Some(s) = self.current.take() {
            self.done.push(s);
        }
    }

    /// The deck's preload request of step `k` (the one [`Steps::preload`] found): its
    /// `*CLOAD` / `*DLOAD` lines are the scene load named after the step (loads.rs); its
    /// `*TEMPERATURE`'s thermal strain is added when the deck is resolved (temperature.rs).
    pub(super) fn preload_request(&self, k: usize, at: &dyn Fn(Loc) -> String) -> PreloadRequest {
        let step = &self.done[k];
        let (kw, loc) = &step.loads[0];
        let mut request = PreloadRequest {
            source: format!("{} at {}", step.describe(k + 1), at(step.loc)),
            first_load: format!("{}: {kw}", at(*loc)),
            // ccx's perturbation step: K + K_G + the large-displacement stiffness (e_c3d)
            initial_displacement: true,
            // … and the stiffness of its centrifugal forces (CENTRIF)
            spin_softening: true,
            ..Default::default()
        };
        if step.loads.iter().any(|(kw, _)| kw != "*TEMPERATURE") {
            request
                .loads
                .push(super::loads::step_load_name(k, &step.name));
        }
        // a *TEMPERATURE's thermal strain: resolve.rs (thermal_strain, temperature.rs)
        request
    }

    /// Split the step conditions into applied (first `*FREQUENCY` step, with what propagates
    /// into it) and ignored (warnings `file:line`-located by `at`).
    pub(super) fn applied(&self, at: &dyn Fn(Loc) -> String) -> Applied<'_> {
        let freq = self.frequency_step();
        let mut out = Applied {
            boundaries: Vec::new(),
            ignored: Vec::new(),
            frequency: None,
        };
        // Steps whose conditions are in force in the frequency step.
        let mut live = vec![false; self.done.len()];
        if let Some(f) = freq {
            let start = (0..=f).rev().find(|&k| self.done[k].op_new).unwrap_or(0);
            for l in live.iter_mut().take(f + 1).skip(start) {
                *l = true;
            }
            let s = &self.done[f];
            out.frequency = Some((
                format!("{} at {}", s.describe(f + 1), at(s.loc)),
                s.eigenvalues,
            ));
        }
        for (k, s) in self.done.iter().enumerate() {
            if s.boundaries.is_empty() {
                continue;
            }
            let what = s.describe(k + 1);
            if live[k] {
                out.boundaries
                    .extend(s.boundaries.iter().map(|b| (b, what.clone())));
            } else {
                let reason = match freq {
                    None => "the deck has no *FREQUENCY step".to_owned(),
                    Some(f) if k > f => format!(
                        "it comes after the *FREQUENCY step {} whose modes the body uses",
                        f + 1
                    ),
                    Some(f) => format!(
                        "the *FREQUENCY step {} removes it with *BOUNDARY, OP=NEW",
                        f + 1
                    ),
                };
                out.ignored.push((
                    s.boundaries[0].2,
                    format!(
                        "line {}: *BOUNDARY of {what} ({} lines) ignored: {reason}; the body's supports are the model data's *BOUNDARY and those of the *FREQUENCY step",
                        s.boundaries[0].2.line,
                        s.boundaries.len()
                    ),
                ));
            }
        }
        out
    }
}
