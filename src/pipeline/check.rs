//! `flexbody check` as a pipeline function: a verification report on a reduced-body file, in the
//! spirit of pyyeti's `cbcheck` (the command line only prints it, `cli/check.rs`). Each check measures one figure against a stated limit; the file passes only when
//! every check passes.
//!
//! From the file alone: the checks of [`file_checks`] (generalized mass and stiffness, rigid-body
//! properties, rigid-body modes, invariants recomputed from the stored nodes) — the same ones the
//! build runs on its own result before writing.
//!
//! A file that stores only some nodes (`build --keep-nodes interface|surface|SET`) cannot
//! support the centre-of-mass bounding-box test, the invariants recomputed from nodal masses or
//! the checks against the model's matrices: they are skipped and listed in
//! [`CheckReport::skipped`] (printed as `skip …` lines).
//!
//! With the FE model (`--model`, rebuilt through `build`'s own stages from the file's recipe —
//! interface spiders, beam lumping, format, material — unless given explicitly):
//! * the model files are the ones the body was built from (SHA-256 of the recipe); a changed
//!   file fails the check and stops the model checks;
//! * ΦᵀMΦ = I and ΦᵀKΦ = diag(ω²) against the model's own K and M (all nodes stored);
//! * eigen residuals ‖Kφ − ω²Mφ‖/‖Kφ‖ (normal modes: must be small; reduced bases: reported);
//! * frequencies against a full normal-mode solve: Rayleigh–Ritz bound (reduced ≥ full) and
//!   relative error ≤ 1% for the flexible modes inside the recipe's accuracy band (files
//!   without a recipe: below the requested fmax, else the lower half of the modes).

use faer::{Mat, Par};
use flexbody_reader as file;

use crate::fe::{self, AssemblySpec};
use crate::model::Model;
use crate::model::{DofMask, NodeIndex};
use crate::pipeline::file_checks::{partial_nodes, rigid_modes, RigidRule, RIGID_MODES};
use crate::pipeline::matrices::{constrained_stages, spec_of_input, ConstrainedStages};
use crate::pipeline::precheck::expected_rigid_motions;
use crate::pipeline::stages::import::import;
use crate::reduce::select::ModeCount;
use crate::solve::EigenSpec;

pub use crate::pipeline::file_checks::{
    file_checks, zero_inertia_axes, CheckItem, CheckReport, ORTHO_LIMIT, ZERO_INERTIA,
};
pub use crate::pipeline::recipe::ModelInput;

/// Errors that stop the check from running at all (a failed check is not an error).
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    /// The model could not be rebuilt.
    #[error(transparent)]
    Build(#[from] crate::pipeline::BuildError),
}

/// Limit on the relative frequency error of modes in the scene's band.
pub const FREQ_LIMIT: f64 = 0.01;

/// Run every check that the inputs allow: the file's own ([`file_checks`]), then with `model`
/// the checks against the rebuilt FE model.
pub fn check(
    body: &file::ReducedBody,
    model: Option<&ModelInput>,
) -> Result<CheckReport, CheckError> {
    let mut r = file_checks(body);
    if let Some(input) = model {
        model_checks(body, input, &mut r)?;
    }
    Ok(r)
}

/// The checks against the FE model: its files as built, then the model rebuilt as `build` did
/// and the body's frequencies and identities against it.
fn model_checks(
    body: &file::ReducedBody,
    input: &ModelInput,
    r: &mut CheckReport,
) -> Result<(), CheckError> {
    if !model_files_as_built(body, input, r) {
        return Ok(());
    }
    let rebuilt = rebuild(body, input)?;
    rigid_modes_of_the_model(body, &rebuilt, r);
    preload_as_built(body, &rebuilt, r);
    frequencies_against_full_solve(body, &rebuilt, r)?;
    identities_against_model(body, &rebuilt, r);
    eigen_residuals_against_model(body, &rebuilt, r)?;
    geometric_stiffness_against_model(body, &rebuilt, r)?;
    lumped_inertia_against_consistent(&rebuilt, r);
    Ok(())
}

/// A lumped-mass file: its rigid-body inertia against the consistent mass of the same mesh, for
/// information (the build warned beyond 1 %; `--mass consistent` is exact; issue 47).
fn lumped_inertia_against_consistent(rebuilt: &Rebuilt, r: &mut CheckReport) {
    if rebuilt.assembly.mass != fe::MassKind::Lumped {
        return;
    }
    let Ok(cmp) = fe::rigid_mass::compare(&rebuilt.model, &rebuilt.assembly) else {
        return;
    };
    let (l, c) = (&cmp.lumped, &cmp.consistent);
    r.push(
        "rigid-body inertia: lumped vs consistent mass",
        cmp.worst(),
        f64::INFINITY,
        format!(
            "mass {:.4e} vs {:.4e}, principal inertia ({:.4e}, {:.4e}, {:.4e}) vs ({:.4e}, {:.4e}, {:.4e}); --mass consistent is exact",
            l.mass, c.mass, l.principal[0], l.principal[1], l.principal[2],
            c.principal[0], c.principal[1], c.principal[2]
        ),
    );
}

/// A model of several connected parts: the rigid-body modes counted from its parts (as `build`
/// verified them) replace the file-alone count.
fn rigid_modes_of_the_model(body: &file::ReducedBody, rebuilt: &Rebuilt, r: &mut CheckReport) {
    let by_id = rebuilt.model.node_index_by_id();
    let reference: Vec<(NodeIndex, DofMask)> = (body.method.reference_conditions.iter())
        .filter_map(|rc| {
            let node = *by_id.get(&body.nodes.get(rc.node as usize)?.id)?;
            let mask = (0..6).filter(|&c| rc.dofs[c]).fold(0u8, |m, c| m | 1 << c);
            Some((node, DofMask(mask)))
        })
        .collect();
    let expected = expected_rigid_motions(&rebuilt.model, &rebuilt.assembled.dofs, &reference);
    if let Some(e) = &expected {
        let item = rigid_modes(body, RigidRule::Model(e));
        match r.items.iter_mut().find(|i| i.name == RIGID_MODES) {
            Some(old) => *old = item,
            None => r.items.push(item),
        }
    }
}

/// The preload rebuilt from the model and the recipe against the one the recipe records: the
/// same loads and the same static solution (max |u0|, relative difference ≤ 1e-9).
fn preload_as_built(body: &file::ReducedBody, rebuilt: &Rebuilt, r: &mut CheckReport) {
    let recorded = body.recipe.as_ref().and_then(|x| x.preload.as_ref());
    match (recorded, &rebuilt.preload) {
        (None, None) => {}
        (Some(p), Some(q)) => {
            let scale = p.max_displacement.abs().max(f64::MIN_POSITIVE);
            let mut diff = (p.max_displacement - q.max_displacement).abs() / scale;
            if p.loads != q.loads || p.max_displacement_node != q.max_displacement_node {
                diff = f64::INFINITY;
            }
            r.push(
                "preload as built",
                diff,
                1e-9,
                format!(
                    "{}: max |u0| {:.6e} at node {} (recorded {:.6e} at node {}, loads {})",
                    q.source,
                    q.max_displacement,
                    q.max_displacement_node,
                    p.max_displacement,
                    p.max_displacement_node,
                    p.loads.join(", ")
                ),
            );
        }
        (p, q) => r.push(
            "preload as built",
            f64::INFINITY,
            1e-9,
            format!(
                "the recipe records {} but the rebuilt model has {}",
                p.map_or("no preload".into(), |p| format!("the preload {}", p.source)),
                q.as_ref()
                    .map_or("none".into(), |q| format!("the preload {}", q.source))
            ),
        ),
    }
}

/// The model files against the recipe's SHA-256; false when one changed (the model checks stop).
fn model_files_as_built(body: &file::ReducedBody, input: &ModelInput, r: &mut CheckReport) -> bool {
    if let Some(recipe) = &body.recipe {
        let changed = crate::pipeline::recipe::changed_model_files(recipe, &input.path);
        r.push(
            "model files as built (recipe SHA-256)",
            changed.len() as f64,
            0.0,
            if changed.is_empty() {
                format!(
                    "{} file(s) unchanged since the build",
                    recipe.model_files.len()
                )
            } else {
                changed.join("; ")
            },
        );
        return changed.is_empty();
    }
    true
}

/// The model as `build` constrained it, and the body's reference-condition dofs in it.
struct Rebuilt {
    model: Model,
    assembled: fe::Assembled,
    reduced: fe::Reduced,
    /// Reference-condition dofs in the independent numbering.
    fixed: Vec<usize>,
    /// The preload applied to K_r as `build` did (stages::preload).
    preload: Option<crate::pipeline::stages::PreloadSummary>,
    /// The assembly options `build` used (mass, beam lumping).
    assembly: AssemblySpec,
}

/// The model rebuilt through `build`'s own stages up to the reduction (import, plan, interfaces,
/// assembly, elimination, preload: [`constrained_stages`]) with the file's recipe and mass.
fn rebuild(body: &file::ReducedBody, input: &ModelInput) -> Result<Rebuilt, CheckError> {
    let spec = spec_of_input(body, input.clone()).with_beam_lumping_resolved();
    let model = import(&spec)?;
    let ConstrainedStages {
        plan,
        interfaced,
        assembled: a,
        reduced: red,
        preload,
    } = constrained_stages(&spec, model)?;
    let assembly = plan.assembly;
    let model = interfaced.model;
    let by_id = model.node_index_by_id();
    // Reference-condition dofs in the reduced numbering.
    let mut reduced_index = vec![usize::MAX; a.dofs.n_dofs];
    for (i, &p) in red.retained.iter().enumerate() {
        reduced_index[p] = i;
    }
    let mut fixed = Vec::new();
    for rc in &body.method.reference_conditions {
        let node = body
            .nodes
            .get(rc.node as usize)
            .and_then(|p| by_id.get(&p.id))
            .copied();
        if let Some(node) = node {
            for c in (0..usize::from(a.dofs.count[node])).filter(|&c| rc.dofs[c]) {
                let d = reduced_index[a.dofs.first[node] + c];
                if d != usize::MAX {
                    fixed.push(d);
                }
            }
        }
    }
    Ok(Rebuilt {
        model,
        assembled: a,
        reduced: red,
        fixed,
        preload,
        assembly,
    })
}

/// The flexible frequencies against a full normal-mode solve of the model: the Rayleigh–Ritz
/// bound (reduced ≥ full) and the relative error inside the accuracy band.
fn frequencies_against_full_solve(
    body: &file::ReducedBody,
    rebuilt: &Rebuilt,
    r: &mut CheckReport,
) -> Result<(), CheckError> {
    use crate::pipeline::BuildError;
    let (red, fixed) = (&rebuilt.reduced, &rebuilt.fixed);
    let n_r = red.retained.len();
    let flexible: Vec<(usize, f64)> = body
        .modes
        .frequency_hz
        .iter()
        .copied()
        .enumerate()
        .filter(|&(j, _)| body.modes.labels[j] != file::ModeLabel::Rigid)
        .collect();
    let wanted = (body
        .modes
        .labels
        .iter()
        .filter(|l| **l == file::ModeLabel::Rigid)
        .count()
        + flexible.len())
    .min(n_r.saturating_sub(fixed.len()))
    .max(1);
    let eig = EigenSpec {
        dofs_per_node: Some(3),
        ..Default::default()
    };
    let massless = crate::reduce::massless::analyse(&red.k, &red.m, fixed, &[], Par::Seq)
        .map_err(BuildError::from)?;
    let full = crate::reduce::massless::on_held(&red.k, &red.m, &massless, |k, m, map| {
        let fixed = crate::reduce::massless::map_dofs(map, fixed, "reference dofs")?;
        crate::reduce::normal::normal_modes(k, m, ModeCount::Count(wanted), &fixed, &eig)
    })
    .map_err(BuildError::from)?;
    let full_flex: Vec<f64> = full
        .frequencies_hz()
        .into_iter()
        .zip(&full.labels)
        .filter(|(_, l)| **l != crate::reduce::ModeLabel::Rigid)
        .map(|(f, _)| f)
        .collect();
    let (band, band_rule) = match &body.recipe {
        Some(rc) => (rc.accuracy_band.fmax_hz, rc.accuracy_band.rule.clone()),
        None => (
            body.header.request.fmax_hz.unwrap_or(f64::INFINITY),
            "fmax".to_string(),
        ),
    };
    let selected = (body.recipe.as_ref()).is_some_and(|rc| rc.options.select.is_some());
    let mut worst_err: f64 = 0.0;
    let mut worst_bound: f64 = 0.0;
    let mut compared = 0;
    for (q, (_, f)) in flexible.iter().enumerate() {
        let Some(&f_full) = full_flex.get(q) else {
            break;
        };
        worst_bound = worst_bound.max((f_full - f) / f_full);
        let in_band = if band.is_finite() {
            f_full <= band
        } else {
            q < full_flex.len().div_ceil(2)
        };
        if selected {
            // `--select participation`: modes inside the band the scene does not excite were
            // dropped; each kept one is compared with the nearest full frequency.
            if band.is_finite() && *f <= band {
                let nearest = (full_flex.iter())
                    .map(|&ff| (f - ff).abs() / ff)
                    .fold(f64::INFINITY, f64::min);
                worst_err = worst_err.max(nearest);
                compared += 1;
            }
        } else if in_band {
            worst_err = worst_err.max((f - f_full).abs() / f_full);
            compared += 1;
        }
    }
    r.push(
        "Rayleigh–Ritz bound: reduced ≥ full frequencies",
        worst_bound,
        1e-8,
        format!(
            "max (f_full − f)/f_full over {} flexible modes",
            flexible.len().min(full_flex.len())
        ),
    );
    r.push(
        "frequencies vs full normal-mode solve",
        worst_err,
        FREQ_LIMIT,
        format!(
            "max relative error over the {compared} flexible modes {}",
            if band.is_finite() {
                format!("below fmax = {band} Hz (accuracy band, rule {band_rule})")
            } else {
                "in the lower half".into()
            }
        ),
    );
    Ok(())
}

/// ΦᵀMΦ, ΦᵀKΦ and residuals against the model's matrices (needs every node's shape).
fn identities_against_model(body: &file::ReducedBody, rebuilt: &Rebuilt, r: &mut CheckReport) {
    let (red, fixed) = (&rebuilt.reduced, &rebuilt.fixed);
    let n_r = red.retained.len();
    if let Some(stored) = partial_nodes(body) {
        r.skipped.push(format!(
            "Φᵀ M Φ, Φᵀ K Φ and eigen residuals against the model: the file stores {stored}, \
             not every node's shape"
        ));
    }
    let interior = &rebuilt.assembled.dofs.interior;
    if !interior.is_empty() && body.method.method != file::Method::NormalModes {
        r.skipped.push(format!(
            "Φᵀ M Φ, Φᵀ K Φ and residuals against the model: the model keeps the incompatible \
             modes of {} C3D8I elements as interior dofs, which the file does not store, and \
             the modes of a reduced basis are not eigenvectors of the model, from which they \
             could be recovered (the build checked these identities on the full vectors)",
            interior.len()
        ));
        return;
    }
    if let Some(phi) = file_modes_on_model(body, rebuilt) {
        let f =
            crate::pipeline::verify::identities(&red.k, &red.m, &phi, &body.modes.omega2, fixed);
        crate::pipeline::verify::push_identities(
            r,
            &f,
            &body.modes.labels,
            crate::pipeline::verify::exact_eigenvectors(body),
            n_r,
        );
    }
}

/// Agreement of a recomputed residual with the stored one: |r − r_stored| ≤ this ×
/// max(r, r_stored) plus what rounding alone leaves in r ([`crate::solve::residual::rounding_floors`]:
/// the file's φ is the solver's rounded into the stored frame, or recovered at C3D8I's interior
/// dofs). Measured on the conrod: 0 (tests/eigen_residuals.rs).
pub const RESIDUAL_AGREEMENT: f64 = 1e-2;

/// The stored residuals of the normal-modes eigenproblem (`eigen_residuals.bin`, SPEC §5.17)
/// recomputed from the file's modes on the rebuilt model's K and M (the free dofs when the body
/// has reference conditions), and its scale s; the other problems' vectors (fixed-interface,
/// free-free) are not in the file: skipped with that reason.
fn eigen_residuals_against_model(
    body: &file::ReducedBody,
    rebuilt: &Rebuilt,
    r: &mut CheckReport,
) -> Result<(), CheckError> {
    use crate::pipeline::BuildError;
    use crate::solve::residual::{relative_residuals, rounding_floors};
    use crate::solve::{sparse_ops, trace_ratio};
    const NAME: &str = "eigen residuals against the model";
    let Some(e) = &body.eigen_residuals else {
        return Ok(());
    };
    for p in &e.problems {
        if p.kind != file::EigenProblemKind::NormalModes {
            r.skipped.push(format!(
                "{NAME}: the {:?} modes are basis vectors the file does not store (its modes \
                 are the orthonormalized basis); the stored residuals are the build's",
                p.kind
            ));
            continue;
        }
        if p.omega2.len() != body.mode_count() {
            r.skipped.push(format!(
                "{NAME}: the file's modes hold residual vectors, not only the {} eigenvectors",
                p.omega2.len()
            ));
            continue;
        }
        let interior = rebuilt.assembled.dofs.interior.len();
        if interior > 0 {
            r.skipped.push(format!(
                "{NAME}: the model keeps the incompatible modes of {interior} C3D8I elements as \
                 interior dofs, which the file does not store; recovered element by element \
                 they are not the solver's vectors (their residuals are checked above)"
            ));
            continue;
        }
        let Some(phi) = file_modes_on_model(body, rebuilt) else {
            r.skipped.push(format!(
                "{NAME}: the file stores {}, not every node's shape",
                partial_nodes(body).unwrap_or_else(|| "some nodes".into())
            ));
            continue;
        };
        // the problem of the free dofs (reference conditions held)
        let red = &rebuilt.reduced;
        let free = sparse_ops::complement(&rebuilt.fixed, red.k.nrows());
        let sub = |a: &crate::solve::SparseColMat<usize, f64>| {
            sparse_ops::submatrix(a.as_ref(), &free, &free)
        };
        let (k, m) = (
            sub(&red.k).map_err(|e| BuildError::from(crate::reduce::ReduceError::from(e)))?,
            sub(&red.m).map_err(|e| BuildError::from(crate::reduce::ReduceError::from(e)))?,
        );
        let phi_free = Mat::from_fn(free.len(), phi.ncols(), |i, j| phi[(free[i], j)]);
        let scale = trace_ratio(&k, &m);
        let again = relative_residuals(&k, &m, phi_free.as_ref(), &p.omega2, scale);
        let floors = rounding_floors(&k, &m, phi_free.as_ref(), scale);
        let (mut worst, mut at) = (0.0f64, 0);
        for (j, ((&a, &b), &f)) in again.iter().zip(&p.residual).zip(&floors).enumerate() {
            let d = (a - b).abs() / (RESIDUAL_AGREEMENT * a.max(b) + f);
            if d.is_nan() || d > worst {
                (worst, at) = (d, j);
            }
        }
        r.push(
            NAME,
            worst,
            1.0,
            format!(
                "max |r − r_stored| / ({RESIDUAL_AGREEMENT:e}·max(r, r_stored) + rounding of \
                 Kφ) over {} modes (mode {}: {:.3e} recomputed, {:.3e} stored; \
                 scale s {:.6e} recomputed, {:.6e} stored; {:?})",
                again.len(),
                at + 1,
                again.get(at).copied().unwrap_or(0.0),
                p.residual.get(at).copied().unwrap_or(0.0),
                scale,
                p.scale,
                p.solver
            ),
        );
        let largest = p.largest_flexible_residual().map_or(0.0, |(_, v)| v);
        r.push(
            "largest stored residual of a flexible mode",
            largest,
            f64::INFINITY,
            format!("{:?} eigenproblem, {:?}", p.kind, p.solver),
        );
    }
    Ok(())
}

/// The file's modes on the rebuilt model's independent dofs (local frames), or `None` when the
/// file does not store every node's shape.
fn file_modes_on_model(body: &file::ReducedBody, rebuilt: &Rebuilt) -> Option<Mat<f64>> {
    let (model, a, red) = (&rebuilt.model, &rebuilt.assembled, &rebuilt.reduced);
    let (m, n_r) = (body.mode_count(), red.retained.len());
    if body.header.request.keep_nodes != file::KeepNodes::All {
        return None;
    }
    let pos: std::collections::HashMap<u64, usize> = body
        .nodes
        .iter()
        .enumerate()
        .map(|(i, p)| (p.id, i))
        .collect();
    let ns = body.node_count();
    let mut phi = Mat::<f64>::zeros(n_r, m);
    let mut missing = 0usize;
    for (i, &p) in red.retained.iter().enumerate() {
        let Some((node, c)) = a.dofs.node_of(p) else {
            continue;
        };
        let Some(&q) = pos.get(&model.nodes[node].id) else {
            missing += 1;
            continue;
        };
        for j in 0..m {
            let s = &body.modes.shapes[(j * ns + q) * 6..(j * ns + q) * 6 + 6];
            let (base, v) = if c < 3 {
                (0, [s[0], s[1], s[2]])
            } else {
                (3, [s[3], s[4], s[5]])
            };
            // local = A · basic
            phi[(i, j)] = match a.dofs.frames[node] {
                None => v[c - base],
                Some(ax) => (0..3).map(|k| ax[c - base][k] * v[k]).sum(),
            };
        }
    }
    // the interior dofs (ccx's C3D8I modes) the file does not store: recovered per element
    if missing == 0 && !a.dofs.interior.is_empty() {
        let unrecovered = fe::interior::recover_interior(
            &a.dofs,
            &red.retained,
            &red.k,
            &red.m,
            &body.modes.omega2,
            &mut phi,
        );
        missing += unrecovered;
    }
    (missing == 0).then_some(phi)
}

/// The file's geometric-stiffness terms (`geometric_stiffness.bin`, SPEC §5.16) recomputed on
/// the rebuilt model: the twelve unit inertia loads' static stress, K_G and Φᵀ K_G Φ with the
/// file's modes, as `build` made them; the largest difference over the largest term ≤ 1e-9.
fn geometric_stiffness_against_model(
    body: &file::ReducedBody,
    rebuilt: &Rebuilt,
    r: &mut CheckReport,
) -> Result<(), CheckError> {
    const NAME: &str = "geometric stiffness against the model";
    let Some(g) = &body.geometric_stiffness else {
        return Ok(());
    };
    let Some(phi) = file_modes_on_model(body, rebuilt) else {
        r.skipped.push(format!(
            "{NAME}: the file stores {}, not every node's shape",
            partial_nodes(body).unwrap_or_else(|| "some nodes".into())
        ));
        return Ok(());
    };
    let constrained_like = crate::fe::preload::System {
        model: &rebuilt.model,
        assembled: &rebuilt.assembled,
        reduced: &rebuilt.reduced,
        assembly: &rebuilt.assembly,
    };
    let fields = crate::fe::preload::unit_inertia_fields([0.0; 3]);
    let cases: Vec<crate::fe::preload::PreloadCase> = (fields.iter())
        .map(|(_, f)| crate::fe::preload::PreloadCase {
            inertia: vec![f.clone()],
            ..Default::default()
        })
        .collect();
    let kg = crate::fe::preload::modal_geometric_stiffness(
        &constrained_like,
        phi.as_ref(),
        &cases,
        &Default::default(),
    )
    .map_err(crate::pipeline::BuildError::from)?;
    let m = body.mode_count();
    let (mut diff, mut scale, mut unknown) = (0.0f64, 0.0f64, 0usize);
    for f in &g.fields {
        let Some(q) = (fields.iter())
            .position(|(l, _)| crate::pipeline::stages::geometric::unit_load(*l) == f.load)
        else {
            unknown += 1;
            continue;
        };
        for (i, v) in f.matrix.iter().enumerate() {
            let want = kg[q][(i / m, i % m)];
            diff = diff.max((v - want).abs());
            scale = scale.max(want.abs());
        }
    }
    let rel = if unknown > 0 {
        f64::INFINITY
    } else {
        diff / scale.max(f64::MIN_POSITIVE)
    };
    r.push(
        NAME,
        rel,
        1e-9,
        format!(
            "{} unit loads recomputed ({:?}): largest difference {diff:.3e}, largest term \
             {scale:.6e}",
            g.fields.len(),
            g.support
        ),
    );
    Ok(())
}
