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
    fn describe(&self, number: usize) -> String {
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
    pub(super) fn begin(&mut self, loc: Loc, name: Option<String>) {
        self.finish_current();
        self.current = Some(Step {
            loc,
            name,
            procedure: None,
            eigenvalues: None,
            boundaries: Vec::new(),
            op_new: false,
        });
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

    /// Split the step conditions into applied (first `*FREQUENCY` step, with what propagates
    /// into it) and ignored (warnings `file:line`-located by `at`).
    pub(super) fn applied(&self, at: &dyn Fn(Loc) -> String) -> Applied<'_> {
        let freq = self
            .done
            .iter()
            .position(|s| s.procedure.as_ref().is_some_and(|p| p.0 == "FREQUENCY"));
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
