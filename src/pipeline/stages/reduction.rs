//! Reduction: the constrained system → a mode set by the method asked for ([`crate::reduce`]),
//! fitted to the scene (a mode cap, `--select participation`, residual vectors), then expanded
//! to the physical dofs, Φ = T Φ_r.

use faer::Mat;

use crate::fe::MassKind;
use crate::model::Model;
use crate::pipeline::plan::Plan;
use crate::pipeline::scene::{
    reduced_loads, removed_note, residual_loads, select_by_scene, SceneLoads,
};
use crate::pipeline::stages::empty_matrix;
use crate::pipeline::stages::ReducedBasis;
use crate::pipeline::stages::{Constrained, PreloadSummary};
use crate::pipeline::{BuildError, BuildMethod, BuildReport};
use crate::reduce::massless::{self, MasslessDofs};
use crate::reduce::participation::{self, Participation};
use crate::reduce::select::{self, ModeCount};
use crate::reduce::{self, ModeSet, ReduceError};
use crate::solve::{Precision, SparseColMat};

/// A Craig–Bampton set with no fixed-interface mode below the cutoff is a Guyan (static)
/// reduction: worth a warning, since the user asked for a frequency band (issue 31).
fn guyan_only(set: &ModeSet, fmax_hz: Option<f64>) -> Option<String> {
    use crate::reduce::Method;
    let fixed = match &set.method {
        Method::CraigBampton {
            fixed_interface_modes,
            ..
        }
        | Method::ImprovedCraigBampton1 {
            fixed_interface_modes,
            ..
        }
        | Method::ImprovedCraigBampton2 {
            fixed_interface_modes,
            ..
        } => *fixed_interface_modes,
        _ => return None,
    };
    let f = fmax_hz?;
    (fixed == 0).then(|| {
        format!(
            "no fixed-interface mode lies below the basis cutoff {:.6} Hz (3 × --fmax {f}): the \
             body holds the constraint (static) modes only, a Guyan reduction with no dynamic \
             content of its own; raise --fmax or give --modes N",
            crate::reduce::select::FMAX_FACTOR * f
        )
    })
}

/// The reduction stage; `hook` sees the mode set last, before it is expanded.
pub fn reduction(
    plan: &Plan,
    model: &Model,
    constrained: &mut Constrained,
    preload: Option<PreloadSummary>,
    hook: &mut dyn FnMut(&mut ModeSet),
    report: &mut BuildReport,
) -> Result<ReducedBasis, BuildError> {
    let spec = &plan.spec;
    let count = plan.modes.solve;
    let massless = massless_dofs(plan, constrained)?;
    check_engine_request(plan, constrained)?;
    // The scene's loads on the independent dofs (f_r = Tᵀf; gravity is M·g with the physical M).
    let scene = reduced_loads(
        &spec.scene,
        model,
        &constrained.assembled,
        &constrained.reduced,
    )
    .map_err(|e| plan.request_error(e.to_string()))??;
    // A consistent physical M is as large as K: not held through the native Craig–Bampton
    // reduction either (issue 22: +0.69 GB at 519k dofs), but assembled again for the invariants
    // after it (the assembly's time, ~1.5 % of such a build). A lumped M is node-block diagonal.
    let mass_released = spec.mass == MassKind::Consistent && native_cb(plan, constrained);
    if mass_released {
        constrained.assembled.m = empty_matrix();
    }
    let mut set = reduce_by_method(plan, constrained, count, &massless)?;
    if let Some(w) = guyan_only(&set, plan.modes.fmax_hz) {
        // a warning with the cutoff, in place of the library's note
        (set.diagnostics.notes).retain(|n| n != crate::reduce::craig_bampton::GUYAN_NOTE);
        report.warnings.push(w);
    }
    let mut set = fit_to_scene(plan, constrained, set, &massless, &scene, report)?;
    hook(&mut set);
    report.diagnostics = set.diagnostics.clone();
    let phi = constrained.reduced.expand(set.phi.as_ref());
    Ok(ReducedBasis {
        set,
        phi,
        scene,
        mass_released,
        preload,
        geometric_stiffness: None,
    })
}

/// The native Craig–Bampton reduction (no reference conditions, our own engine), which takes K
/// and M over.
fn native_cb(plan: &Plan, constrained: &Constrained) -> bool {
    plan.spec.method == BuildMethod::CraigBampton
        && constrained.reference_dofs.is_empty()
        && plan.spec.engine.is_none()
}

/// Massless dofs: motions with neither mass nor stiffness are held ([`massless`]).
fn massless_dofs(plan: &Plan, constrained: &Constrained) -> Result<MasslessDofs, BuildError> {
    let (k_r, m_r) = (&constrained.reduced.k, &constrained.reduced.m);
    let par = plan.eigen.par;
    Ok(match plan.spec.method {
        BuildMethod::CraigBampton => MasslessDofs {
            massless: massless::massless_dofs(m_r),
            held: vec![],
        },
        BuildMethod::Normal => massless::analyse(k_r, m_r, &constrained.reference_dofs, &[], par)?,
        _ => massless::analyse(k_r, m_r, &[], &constrained.interface_dofs, par)?,
    })
}

/// An explicit `--precision mixed`, `--engine slepc` or `--eigensolver amls` that the build
/// would not use is refused, not ignored.
fn check_engine_request(plan: &Plan, constrained: &Constrained) -> Result<(), BuildError> {
    let spec = &plan.spec;
    if spec.precision == Precision::Mixed
        && (spec.method != BuildMethod::CraigBampton || spec.engine.is_some())
    {
        return Err(plan.request_error(
            "--precision mixed applies to the Craig-Bampton interior of the native engine: use \
             --method cb without --engine slepc (the other methods factor in f64)"
                .into(),
        ));
    }
    let engine_runs_it = match spec.method {
        BuildMethod::CraigBampton => constrained.reference_dofs.is_empty(),
        BuildMethod::Normal | BuildMethod::CraigChang => true,
        BuildMethod::Dietz => false,
    };
    if spec.engine.is_some() && matches!(spec.eigensolver, crate::solve::EigenMethod::Amls(_)) {
        return Err(plan.request_error(
            "--engine slepc computes the modes with SLEPc's Krylov-Schur: --eigensolver amls \
             applies to the native engine only (use one or the other)"
                .into(),
        ));
    }
    if spec.engine.is_some() && !engine_runs_it {
        return Err(plan.request_error(
            "--engine slepc runs normal modes, Craig-Chang and the Craig-Bampton interior \
             (without --reference-conditions): use one of these methods, or the default engine"
                .into(),
        ));
    }
    Ok(())
}

/// Unit loads at the interface dofs, over the dofs that `map` keeps (`usize::MAX`: held).
fn unit_loads_at(
    interface_dofs: &[usize],
    map: &[usize],
    k: &SparseColMat<usize, f64>,
) -> Result<Mat<f64>, ReduceError> {
    let dofs: Vec<usize> = interface_dofs
        .iter()
        .filter_map(|&d| Some(map[d]).filter(|&r| r != usize::MAX))
        .collect();
    reduce::craig_chang::unit_loads(k.nrows(), &dofs)
}

/// The mode set of the method asked for.
fn reduce_by_method(
    plan: &Plan,
    constrained: &mut Constrained,
    count: ModeCount,
    massless: &MasslessDofs,
) -> Result<ModeSet, BuildError> {
    let (spec, eig) = (&plan.spec, &plan.eigen);
    let reference = &constrained.reference_dofs;
    let interface_dofs = &constrained.interface_dofs;
    let reduced = &mut constrained.reduced;
    Ok(match spec.method {
        BuildMethod::CraigBampton if reference.is_empty() && spec.engine.is_some() => {
            let engine = spec
                .engine
                .as_ref()
                .ok_or_else(|| plan.request_error("engine".into()))?;
            reduce::craig_bampton::craig_bampton_slepc(
                &reduced.k,
                &reduced.m,
                interface_dofs,
                count,
                eig,
                engine,
            )?
        }
        BuildMethod::Normal => massless::on_held(&reduced.k, &reduced.m, massless, |k, m, map| {
            let fixed = massless::map_dofs(map, reference, "reference dofs")?;
            reduce::normal::normal_modes(k, m, count, &fixed, eig)
        })?,
        BuildMethod::CraigBampton if reference.is_empty() && spec.engine.is_none() => {
            // K and M handed over: not resident beside K_ii, M_ii and L (issue 22)
            let k = std::mem::replace(&mut reduced.k, empty_matrix());
            let m = std::mem::replace(&mut reduced.m, empty_matrix());
            let (set, k, m) =
                reduce::craig_bampton::craig_bampton_owned(k, m, interface_dofs, count, eig)?;
            (reduced.k, reduced.m) = (k, m);
            set
        }
        BuildMethod::CraigBampton => match spec.reference_method {
            1 => reduce::reference::improved_cb_method1(
                &reduced.k,
                &reduced.m,
                interface_dofs,
                reference,
                count,
                eig,
            )?,
            2 => reduce::reference::improved_cb_method2(
                &reduced.k,
                &reduced.m,
                interface_dofs,
                reference,
                count,
                eig,
            )?,
            other => {
                return Err(
                    plan.request_error(format!("--reference-method {other}: must be 1 or 2"))
                )
            }
        },
        BuildMethod::CraigChang => {
            massless::on_held(&reduced.k, &reduced.m, massless, |k, m, map| {
                let fa = unit_loads_at(interface_dofs, map, k)?;
                reduce::craig_chang::craig_chang(k, m, &fa, count, eig)
            })?
        }
        BuildMethod::Dietz => massless::on_held(&reduced.k, &reduced.m, massless, |k, m, map| {
            let fa = unit_loads_at(interface_dofs, map, k)?;
            reduce::dietz::dietz(k, m, &fa, count, None, eig)
        })?,
    })
}

/// The set fitted to what was asked beyond the method: the massless dofs noted (CB), `--modes`
/// capping a band, the scene's mode selection and its residual vectors.
fn fit_to_scene(
    plan: &Plan,
    constrained: &Constrained,
    mut set: ModeSet,
    massless: &MasslessDofs,
    scene: &SceneLoads,
    report: &mut BuildReport,
) -> Result<ModeSet, BuildError> {
    let (spec, eig) = (&plan.spec, &plan.eigen);
    let (k_r, m_r) = (&constrained.reduced.k, &constrained.reduced.m);
    let interface_dofs = &constrained.interface_dofs;
    if spec.method == BuildMethod::CraigBampton {
        set.diagnostics.massless_dofs = massless.massless.len();
        if !massless.massless.is_empty() {
            set.diagnostics.notes.push(format!(
                "{} massless dofs (zero mass row and column): condensed statically by the \
                 constraint-mode and fixed-interface solves",
                massless.massless.len()
            ));
        }
    }
    if let Some(n) = plan.modes.cap {
        // Both given: the count caps the band (CB keeps its constraint-derived modes on top).
        let extra = if spec.method == BuildMethod::Normal {
            0
        } else {
            interface_dofs.len()
        };
        set = select::by_count(set, n + extra);
    }
    if let Some(eps) = spec.scene.select {
        // the band: --fmax, else the candidates' top read back through FMAX_FACTOR
        let top = set.frequencies_hz().into_iter().fold(0.0f64, f64::max);
        let band = plan.modes.fmax_hz.unwrap_or(top / select::FMAX_FACTOR);
        let (s, rep) = select_by_scene(
            k_r,
            m_r,
            set,
            scene,
            interface_dofs,
            spec.scene.residual_vectors,
            eps,
            band,
            eig,
        )?;
        set = s;
        if rep.estimate_all > eps {
            report.warnings.push(participation::note(
                &rep,
                &Participation {
                    epsilon: eps,
                    band_hz: band,
                    damping: participation::DEFAULT_DAMPING,
                },
            ));
        }
    }
    if let Some(kind) = spec.scene.residual_vectors {
        let f = residual_loads(kind, scene, interface_dofs, k_r.nrows())
            .map_err(|e| plan.request_error(e))?;
        let (s, rep) = reduce::residual::add_residual_vectors(k_r, m_r, set, &f, eig)?;
        set = s;
        if !rep.removed.is_empty() || !rep.no_response.is_empty() {
            report.notes.push(removed_note(&rep, scene));
        }
    }
    Ok(set)
}
