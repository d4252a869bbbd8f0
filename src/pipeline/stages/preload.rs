//! Preload (issue 35): when the deck asks its modes on a loaded state (CalculiX `*STATIC` with
//! loads before a `*STEP, PERTURBATION` / `*FREQUENCY`) or the user names scene loads with
//! `--preload LOAD[,LOAD…]`, the linear static solve of that case on the constrained system,
//! the geometric stiffness of its stress and K_T,r = K_r + Tᵀ K_G T (+ Tᵀ K_L(u₀) T, the
//! initial-displacement stiffness, for a CalculiX perturbation step), which replaces K_r for the
//! reduction (every method unchanged; `fe::preload`, whose module doc is the design note).
//! Takes the constrained system, puts K_T,r in it and returns a [`PreloadSummary`] for the
//! report and the recipe. `flexbody check --model` rebuilds the same K_T with [`apply`].
//!
//! Refused, never dropped: a deck preload the importer could not read (its request's
//! problem, a load with a problem), a pressure in a deck's preload (its solver adds the
//! pressure's follower stiffness, not formed here), a name that is no scene load, a free body (the preload of
//! a body held only by inertia relief is not supported through the build), and a preload
//! beyond the first buckling load ([`PreloadError::Buckling`] with the buckling factor).

use faer::Par;

use crate::fe::geometric::{Temperature, Thermal};
use crate::fe::preload::{self, PreloadCase, PreloadError, PreloadSpec, System};
use crate::fe::{Assembled, AssemblySpec, Reduced};
use crate::model::load::LoadPart;
use crate::model::{Load, Model};
use crate::pipeline::plan::Plan;
use crate::pipeline::scene::{scene_loads, SceneSpec};
use crate::pipeline::stages::Constrained;
use crate::pipeline::stages::PreloadSummary;
use crate::pipeline::stages::WithInterfaces;
use crate::pipeline::{BuildError, BuildReport};

/// The share of the part's size (bounding-box diagonal) above which a preload's displacement is
/// no longer small: the linear preload then misses the initial-displacement stiffness.
const LARGE_PRELOAD_DISPLACEMENT: f64 = 0.01;

/// A warning when the preload moves the part by more than [`LARGE_PRELOAD_DISPLACEMENT`] of its
/// size: K + K_G(σ₀) is the linear-preload tangent; a solver that perturbs the static state
/// (ccx `*STEP, PERTURBATION`, Nastran SOL 106) also includes the stiffness of the displaced
/// geometry. (CalculiX beampsensfreq, strain ≈ 0.48, as a linear preload: its bending pair
/// within 2.3e-3 of ccx's, other modes up to 25 % off; a CalculiX deck's own perturbation
/// step is built with K_L(u₀) and has no such warning.)
fn large_displacement_warning(model: &Model, s: &PreloadSummary) -> Option<String> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for n in &model.nodes {
        for k in 0..3 {
            lo[k] = lo[k].min(n.x[k]);
            hi[k] = hi[k].max(n.x[k]);
        }
    }
    let size = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    let share = s.max_displacement / size;
    (size > 0.0 && share > LARGE_PRELOAD_DISPLACEMENT).then(|| {
        format!(
            "the preload displaces node {} by {:.3e}, {:.1} % of the part's size: the linear \
             preload (K + K_G of the undeformed geometry) misses the large-displacement \
             stiffness a nonlinear perturbation (ccx *STEP, PERTURBATION after a large static \
             step; Nastran SOL 106) includes, so the modes may differ from such a solver's",
            s.max_displacement_node,
            s.max_displacement,
            100.0 * share
        )
    })
}

/// Whether the build has a preload (`--preload` or the deck's).
pub fn has_preload(plan: &Plan, interfaced: &WithInterfaces) -> bool {
    !plan.spec.scene.preload.is_empty() || interfaced.model.deck.preload.is_some()
}

/// The preload stage (module doc): K_T,r in place of `constrained.reduced.k` when the build
/// has a preload; returns its summary (also noted in the report).
pub fn preload(
    plan: &Plan,
    interfaced: &WithInterfaces,
    constrained: &mut Constrained,
    report: &mut BuildReport,
) -> Result<Option<PreloadSummary>, BuildError> {
    let summary = apply(
        &interfaced.model,
        &constrained.assembled,
        &mut constrained.reduced,
        &plan.assembly,
        &plan.spec.scene,
        plan.spec.par(),
    )?;
    if let Some(s) = &summary {
        report.notes.push(s.note());
        if s.spin_softening {
            report.warnings.push(format!(
                "{}: the modes include the spin softening −Ω²M⊥ of the preload's centrifugal \
                 loads (the modes in the rotating frame, as the deck's solver forms them); a \
                 multibody solver that spins the body adds that softening itself: for such a \
                 body build with --preload naming the step's load (K + K_G, no softening)",
                s.source
            ));
        }
        if let Some(w) = (!s.initial_displacement)
            .then(|| large_displacement_warning(&interfaced.model, s))
            .flatten()
        {
            report.warnings.push(w);
        }
    }
    Ok(summary)
}

/// The preload of `model` (the `--preload` names of `scene`, else the deck's request) applied
/// to `reduced` (K_r → K_T,r); `Ok(None)` when there is none.
pub fn apply(
    model: &Model,
    assembled: &Assembled,
    reduced: &mut Reduced,
    assembly: &AssemblySpec,
    scene: &SceneSpec,
    par: Par,
) -> Result<Option<PreloadSummary>, BuildError> {
    let Some((source, names, case)) = preload_case(model, scene)? else {
        return Ok(None);
    };
    let sys = System {
        model,
        assembled,
        reduced,
        assembly,
    };
    let spec = PreloadSpec {
        par,
        ..Default::default()
    };
    let pl = preload::preload(&sys, &case, &spec)?;
    if pl.rigid_modes > 0 {
        return Err(BuildError::Request {
            file: model.source.clone(),
            message: format!(
                "{source}: the body is free ({} rigid-body motion(s) balanced by inertia relief): a preload of a free body is not supported through the build; hold the body (*BOUNDARY / SPC) or drop the preload",
                pl.rigid_modes
            ),
        });
    }
    let buckling_factor = preload::buckling_factor(&sys, &pl, par)?;
    let (max_displacement, node) = max_translation(model, assembled, &pl.u);
    reduced.k = pl.k_t;
    Ok(Some(PreloadSummary {
        source,
        loads: names,
        max_displacement,
        max_displacement_node: model.nodes[node].id,
        buckling_factor,
        initial_displacement: case.initial_displacement,
        spin_softening: case.spin_softening
            && (case.loads.iter().flat_map(|l| &l.parts))
                .any(|p| matches!(p, crate::model::LoadPart::Centrifugal { .. })),
    }))
}

/// The largest nodal translation |u| of `u` (physical dofs) and its node.
fn max_translation(model: &Model, assembled: &Assembled, u: &[f64]) -> (f64, usize) {
    let d = &assembled.dofs;
    (0..model.nodes.len())
        .map(|p| {
            let n = usize::from(d.count[p]).min(3);
            let s: f64 = (0..n).map(|c| u[d.first[p] + c].powi(2)).sum();
            (s.sqrt(), p)
        })
        .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a })
}

/// The preload case: `--preload` names (scene loads and the deck's load sets by name), else
/// the deck's request; with its source and the names of its parts.
fn preload_case(
    model: &Model,
    scene: &SceneSpec,
) -> Result<Option<(String, Vec<String>, PreloadCase)>, BuildError> {
    let request_error = |message: String| BuildError::Request {
        file: model.source.clone(),
        message,
    };
    if !scene.preload.is_empty() {
        let available = scene_loads(model, scene).map_err(|e| request_error(e.to_string()))?;
        let mut loads: Vec<Load> = Vec::new();
        for name in &scene.preload {
            let found = (available.iter())
                .chain(&model.loads)
                .find(|l| l.name.eq_ignore_ascii_case(name.trim()));
            let Some(l) = found else {
                let known: Vec<&str> = (available.iter().chain(&model.loads))
                    .map(|l| l.name.as_str())
                    .collect();
                return Err(request_error(format!(
                    "--preload {name}: no scene load of that name (the scene has: {}; give --gravity or --load for more)",
                    if known.is_empty() { "none".into() } else { known.join(", ") }
                )));
            };
            loads.push(l.clone());
        }
        let names = loads.iter().map(|l| l.name.clone()).collect();
        let source = format!("--preload {}", scene.preload.join(","));
        let case = PreloadCase {
            loads,
            ..Default::default()
        };
        return Ok(Some((source, names, case)));
    }
    let Some(request) = &model.deck.preload else {
        return Ok(None);
    };
    if let Some(problem) = &request.problem {
        return Err(request_error(format!(
            "{problem} ({} preloads the deck's modes; a preload the tool cannot apply is refused, never dropped)",
            request.source
        )));
    }
    let mut case = PreloadCase {
        initial_displacement: request.initial_displacement,
        spin_softening: request.spin_softening,
        ..Default::default()
    };
    let mut names = Vec::new();
    for name in &request.loads {
        let l = (model.loads.iter())
            .find(|l| &l.name == name)
            .ok_or_else(|| {
                request_error(format!(
                    "{}: the preload's load {name} was not read",
                    request.first_load
                ))
            })?;
        if l.parts
            .iter()
            .any(|p| matches!(p, LoadPart::Surface { .. }))
        {
            return Err(request_error(follower_pressure_refusal(request, l)));
        }
        case.loads.push(l.clone());
        names.push(name.clone());
    }
    if let Some((delta_t, alpha)) = &request.thermal {
        case.thermal = Some(Thermal {
            delta_t: Temperature::Nodal(delta_t.clone()),
            alpha: alpha.clone(),
        });
        names.push(format!("thermal strain of {}", request.source));
    }
    Ok(Some((request.source.clone(), names, case)))
}

/// Why a deck's pressure preload is refused: its solver's tangent carries the pressure's
/// follower (load) stiffness, which is not formed here.
fn follower_pressure_refusal(request: &crate::model::deck::PreloadRequest, load: &Load) -> String {
    let solver = if request.initial_displacement {
        "CalculiX's perturbation step adds the follower (load) stiffness of a pressure on the \
         deformed faces (measured: a C3D8 bar under end pressure 46.93 Hz against ccx's 62.22; \
         an S3 panel under 1 MPa 0.5 % off)"
    } else {
        "MSC Nastran's SOL 103 with STATSUB adds the follower stiffness of pressure loads \
         (PARAM,FOLLOWK)"
    };
    format!(
        "{}: the preload's load {} ({}) has a pressure; {solver}, which flexbody does not form, \
         so the modes would be wrong. `--preload {}` builds it as a dead load (K + K_G) if that \
         is the meaning wanted",
        request.first_load, load.name, load.source, load.name
    )
}

impl From<PreloadError> for BuildError {
    fn from(e: PreloadError) -> Self {
        BuildError::Preload(e)
    }
}
