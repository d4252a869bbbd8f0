//! The pipeline behind `flexbody build`: FE model file → reduced flexible body
//! ([`ReducedBody`](flexbody_reader::ReducedBody)), as a list of named stages.
//!
//! ```text
//! import ─► interfaces ─► assembly ─► constraints ─► preload ─► reduction ─► invariants ─► geometric stiffness ─► stress shapes
//! Model     spiders       K, M        K_r, M_r, T    K_T,r       ModeSet, Φ   masses, I1…I9  Φᵀ K_G Φ per unit load  (when asked)
//!                                                    (when asked)                            (when asked)
//!        ─► assemble file ─► verify
//!           ReducedBody      checked against the file rules and K_r, M_r
//! ```
//!
//! [`build_model_with_hook`] reads as that list: one call per stage ([`stages`]), each taking
//! the previous stage's data and returning its own; progress and timing around them in one
//! place; the options resolved once before the first stage ([`plan::Plan`]). The pipeline never
//! prints: progress goes to a callback, findings into the [`BuildReport`].
//!
//! Beside the stages, what they use: the deck's own requests ([`deck`]), interface spiders
//! ([`interface`], [`interface_entry`]), the scene's loads ([`scene`]), the checks before the
//! reduction ([`precheck`]) and of the result ([`file_checks`], [`verify`]), the recipe
//! ([`recipe`]), option values as text ([`options`]), solver failures in the model's terms
//! ([`diagnose`]), and the constrained matrices for `--write-matrices` ([`matrices`]).

use std::time::Instant;

use crate::model::Model;
use crate::reduce::ModeSet;

pub mod check;
pub mod deck;
pub mod diagnose;
pub mod file_checks;
pub mod interface;
pub mod interface_entry;
pub mod matrices;
pub mod options;
pub mod plan;
pub mod precheck;
pub mod recipe;
mod report;
pub mod scene;
mod spec;
pub mod stages;
pub mod verify;

pub use report::{BuildError, BuildOutput, BuildReport, Stage, STAGES};
pub use spec::{BuildMethod, BuildSpec, GeometricLoads, KeepNodes, SceneSpec, DEFAULT_MODES};

use plan::Plan;
use stages::{assembly, constraints, fields, file, import, interfaces, invariants, reduction};

/// Run the pipeline. `progress(stage)` is called as each stage starts.
pub fn build(spec: &BuildSpec, progress: &mut dyn FnMut(&str)) -> Result<BuildOutput, BuildError> {
    build_reporting(spec, progress).map_err(|f| f.error)
}

/// [`build`], and when it fails, the warnings and notes the stages run had gathered (issue 32:
/// a failing build prints them too — an ignored card is often the cause of the failure).
pub fn build_reporting(
    spec: &BuildSpec,
    progress: &mut dyn FnMut(&str),
) -> Result<BuildOutput, Box<BuildFailure>> {
    let mut clock = StageClock::new(progress);
    let model = clock
        .run(Stage::Import, || import::import(spec))
        .map_err(|e| Box::new(BuildFailure::from(e)))?;
    let ctx = diagnose::SolverContext::of(&model);
    let mut report = BuildReport::default();
    let spec = spec.with_beam_lumping_resolved();
    match run_stages(&spec, model, clock.progress, &mut |_| {}, &mut report) {
        Ok(mut out) => {
            out.report.stages.splice(0..0, clock.times);
            Ok(out)
        }
        Err(e) => Err(Box::new(BuildFailure {
            error: ctx.explain(e),
            warnings: report.warnings,
            notes: report.notes,
        })),
    }
}

/// A failed build: the error, and the warnings and notes gathered before it.
#[derive(Debug)]
pub struct BuildFailure {
    /// Why the build stopped.
    pub error: BuildError,
    /// The model's and the stages' warnings up to the failure.
    pub warnings: Vec<String>,
    /// The deck's and the stages' notes up to the failure.
    pub notes: Vec<String>,
}

impl From<BuildError> for BuildFailure {
    fn from(error: BuildError) -> Self {
        BuildFailure {
            error,
            warnings: Vec::new(),
            notes: Vec::new(),
        }
    }
}

/// The pipeline after import, for a model already in memory (generated meshes, models edited
/// by a program); `spec.model` only names it in messages and the header. `progress(stage)` is
/// called as each stage starts.
pub fn build_model(
    spec: &BuildSpec,
    model: Model,
    progress: &mut dyn FnMut(&str),
) -> Result<BuildOutput, BuildError> {
    // Solver failures in the model's terms (diagnose).
    let ctx = diagnose::SolverContext::of(&model);
    build_model_with_hook(spec, model, progress, &mut |_| {}).map_err(|e| ctx.explain(e))
}

/// [`build_model`] with `hook` applied to the mode set (over the independent dofs) right after
/// the reduction, before the body is assembled and verified: for tests of the verification
/// (a corrupted basis must be refused) and for programs that post-process a set.
pub fn build_model_with_hook(
    spec: &BuildSpec,
    model: Model,
    progress: &mut dyn FnMut(&str),
    hook: &mut dyn FnMut(&mut ModeSet),
) -> Result<BuildOutput, BuildError> {
    run_stages(spec, model, progress, hook, &mut BuildReport::default())
}

/// The stages after import, `report` filled as they go (kept by the caller on failure).
fn run_stages(
    spec: &BuildSpec,
    model: Model,
    progress: &mut dyn FnMut(&str),
    hook: &mut dyn FnMut(&mut ModeSet),
    report: &mut BuildReport,
) -> Result<BuildOutput, BuildError> {
    // The deck's own requests (COUPMASS, METHOD, ASET, TITLE) fill the choices left open.
    let plan = Plan::resolve(spec, &model)?;
    report.notes = plan.deck_notes.clone();
    report.warnings = (model.warnings.iter())
        .map(|w| format!("{}: {}", w.file, w.message))
        .collect();
    report.warnings.extend(unit_warnings(spec, &model));
    let mut clock = StageClock::new(progress);
    let interfaced = clock.run(Stage::Interfaces, || interfaces::interfaces(&plan, model))?;
    report.notes.extend(interfaced.mass_nodes.iter().map(|m| {
        let model = &interfaced.model;
        format!(
            "{}: point mass {}: its centre of gravity, off node {}, is node {} of the body, \
             rigidly linked to it (element {}): the file holds one mass per node",
            model.element_origin(m.mass_id),
            m.mass_id,
            model.nodes[m.attached_to].id,
            model.nodes[m.node].id,
            m.link_id
        )
    }));
    let assembled = clock.run(Stage::Assembly, || {
        assembly::assembly(&plan, &interfaced, report)
    })?;
    let mut constrained = clock.run(Stage::Constraints, || {
        constraints::constraints(&plan, &interfaced, assembled, report)
    })?;
    report
        .warnings
        .extend(stages::lumping_check::quadratic_lumping_warning(
            &plan,
            &interfaced,
            &constrained,
        ));
    let preload = if stages::preload::has_preload(&plan, &interfaced) {
        clock.run(Stage::Preload, || {
            stages::preload::preload(&plan, &interfaced, &mut constrained, report)
        })?
    } else {
        None
    };
    // `--write-matrices`: K_r, M_r as the reduction gets them (it may take them over)
    let constrained_system = plan.spec.constrained_system.then(|| {
        let (model, reduced) = (&interfaced.model, &constrained.reduced);
        let dofs = &constrained.assembled.dofs;
        let (k, m) = (reduced.k.clone(), reduced.m.clone());
        matrices::system_of(&plan, model, dofs, &reduced.retained, k, m)
    });
    let mut basis = clock.run(Stage::Reduction, || {
        reduction::reduction(
            &plan,
            &interfaced.model,
            &mut constrained,
            preload,
            hook,
            report,
        )
    })?;
    let mass = clock.run(Stage::Invariants, || {
        invariants::invariants(&plan, &interfaced.model, &mut constrained, &basis)
    })?;
    if plan.spec.geometric_stiffness.is_some() {
        clock.run(Stage::GeometricStiffness, || {
            stages::geometric::geometric_stiffness(
                &plan,
                &interfaced.model,
                &constrained,
                &mut basis,
            )
        })?;
    }
    let stored = file::stored_nodes(&plan, &interfaced, &constrained)?;
    let fields = if plan.spec.fields.is_empty() {
        stages::FieldShapes::default()
    } else {
        clock.run(Stage::StressShapes, || {
            fields::fields(
                &plan,
                &interfaced.model,
                &constrained,
                &basis,
                &stored,
                report,
            )
        })?
    };
    let body = clock.run(Stage::AssembleFile, || {
        file::assemble_file(
            &plan,
            &interfaced,
            &constrained,
            &basis,
            &mass,
            &stored,
            &fields,
        )
    })?;
    let body = clock.run(Stage::Verify, || {
        stages::verify::verify(&plan, body, &constrained, &basis)
    })?;
    report.stages = clock.times;
    report.interfaces = interfaced.interfaces;
    Ok(BuildOutput {
        body,
        report: std::mem::take(report),
        constrained_system,
    })
}

/// A declared unit system in which the model's materials are no real solid's (issue 31:
/// `--units mm-t-s` on the SI conrod went through without a word), with the presets in which
/// they are.
fn unit_warnings(spec: &BuildSpec, model: &Model) -> Vec<String> {
    let name = options::unit_preset_name(&spec.units).unwrap_or("the declared units");
    let presets = options::unit_presets();
    crate::import::plausibility::unit_system_warnings(model, &spec.units, name, &presets)
}

/// Progress and timing of the stages, in one place: `progress(name)` as a stage starts, its
/// duration in `times` when it ends.
struct StageClock<'a> {
    progress: &'a mut dyn FnMut(&str),
    /// (stage, seconds) of the stages run, in order.
    times: Vec<(String, f64)>,
}

impl<'a> StageClock<'a> {
    fn new(progress: &'a mut dyn FnMut(&str)) -> Self {
        StageClock {
            progress,
            times: Vec::new(),
        }
    }

    /// Runs `work` as `stage`.
    fn run<T>(
        &mut self,
        stage: Stage,
        work: impl FnOnce() -> Result<T, BuildError>,
    ) -> Result<T, BuildError> {
        (self.progress)(stage.name());
        let start = Instant::now();
        let out = work()?;
        self.times
            .push((stage.name().to_string(), start.elapsed().as_secs_f64()));
        Ok(out)
    }
}
