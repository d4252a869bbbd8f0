//! The build's own verification before anything is written: the assembled body must pass the
//! checks `flexbody check` runs on the file (same items, same limits, [`file_checks`]) plus the
//! identities against the assembled, constrained model it was reduced from:
//!
//! * ΦᵀMΦ = I and ΦᵀKΦ = diag(ω²) against that model's K and M ([`identities`]); together they
//!   also guarantee the Rayleigh–Ritz bound ω²_j ≥ λ_j(full) of a reduced basis (Courant–Fischer:
//!   each ω²_j is a max–min of Rayleigh quotients over M-orthonormal vectors of the model space),
//!   so a reduced basis that passes cannot undercut the full model's frequencies;
//! * eigen residuals ‖Kφ − ω²Mφ‖/‖Kφ‖ of normal modes;
//! * the rigid-mode count and the stored-data identities of the file (generalized mass and
//!   stiffness, invariants recomputed from the stored shapes), by [`file_checks`].
//!
//! A violation is [`VerifyError`], naming every failed item; `flexbody build` then writes nothing.
//! The cost is a few sparse products per mode (timed as the build's "verify" stage).

use faer::Mat;
use flexbody_reader as file;

use super::file_checks::{file_checks_with, CheckItem, CheckReport, RigidRule, ORTHO_LIMIT};
use super::precheck::RigidExpectation;
use crate::solve::{sparse_ops, SparseColMat};

/// Limit on the eigen residual of a normal mode against the model (as `check`).
pub const RESIDUAL_LIMIT: f64 = 1e-6;

/// Quality figures of Φ against a model.
#[derive(Clone, Debug, PartialEq)]
pub struct Identities {
    /// max |ΦᵀMΦ − I|.
    pub orthonormality: f64,
    /// max |ΦᵀKΦ − diag(ω²)| / max ω².
    pub stiffness: f64,
    /// Its limit: max([`ORTHO_LIMIT`], the rounding floor ROUNDING_FACTOR·ε·|Φ|ᵀ|K||Φ| / max ω²
    /// of forming ΦᵀKΦ, as the reduction's own check uses).
    pub stiffness_limit: f64,
    /// ‖Kφ − ω²Mφ‖/‖Kφ‖ per mode.
    pub residuals: Vec<f64>,
    /// The limit per mode: max([`RESIDUAL_LIMIT`], the rounding floor
    /// ROUNDING_FACTOR·ε·‖|K||φ|‖/‖Kφ‖ that forming Kφ alone leaves; on a 1000-element slender
    /// beam it is 3e-5, measured).
    pub residual_limits: Vec<f64>,
}

/// ΦᵀMΦ − I, ΦᵀKΦ − diag(ω²) and the eigen residuals of Φ (n × modes) against (K, M). The
/// rows `held` (reference-condition dofs: Φ is zero there and Kφ − ω²Mφ is the reaction force
/// that holds them) are left out of the residuals.
pub fn identities(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    phi: &Mat<f64>,
    omega2: &[f64],
    held: &[usize],
) -> Identities {
    let mut is_held = vec![false; phi.nrows()];
    for &d in held {
        if let Some(h) = is_held.get_mut(d) {
            *h = true;
        }
    }
    let nm = phi.ncols();
    let mphi = sparse_ops::spmm(m.as_ref(), phi.as_ref());
    let kphi = sparse_ops::spmm(k.as_ref(), phi.as_ref());
    let g = phi.transpose() * &mphi;
    let h = phi.transpose() * &kphi;
    let max_w2 = omega2
        .iter()
        .fold(0.0f64, |x, &y| x.max(y.abs()))
        .max(f64::MIN_POSITIVE);
    let mut orthonormality: f64 = 0.0;
    let mut stiffness: f64 = 0.0;
    for j in 0..nm {
        for i in 0..nm {
            let id = if i == j { 1.0 } else { 0.0 };
            orthonormality = orthonormality.max((g[(i, j)] - id).abs());
            stiffness = stiffness.max((h[(i, j)] - id * omega2[j]).abs() / max_w2);
        }
    }
    let (_, abs_norm) = sparse_ops::abs_products(k.as_ref(), phi.as_ref());
    let stiffness_limit = ORTHO_LIMIT.max(
        sparse_ops::ROUNDING_FACTOR
            * f64::EPSILON
            * sparse_ops::abs_energy(k.as_ref(), phi.as_ref())
            / max_w2,
    );
    let mut residuals = Vec::with_capacity(nm);
    let mut residual_limits = Vec::with_capacity(nm);
    for j in 0..nm {
        let (mut rn, mut kn) = (0.0, 0.0);
        for i in (0..phi.nrows()).filter(|&i| !is_held[i]) {
            rn += (kphi[(i, j)] - omega2[j] * mphi[(i, j)]).powi(2);
            kn += kphi[(i, j)].powi(2);
        }
        let kn = kn.sqrt().max(f64::MIN_POSITIVE);
        residuals.push(rn.sqrt() / kn);
        residual_limits.push(
            RESIDUAL_LIMIT.max(sparse_ops::ROUNDING_FACTOR * f64::EPSILON * abs_norm[j] / kn),
        );
    }
    Identities {
        orthonormality,
        stiffness,
        stiffness_limit,
        residuals,
        residual_limits,
    }
}

/// The build refused its own result.
#[derive(Debug, thiserror::Error)]
#[error(
    "the built body fails its own verification, so no file was written: {}",
    failed.iter().map(|i| format!("{} = {:.3e} > {:.1e} ({})", i.name, i.value, i.limit, i.detail)).collect::<Vec<_>>().join("; ")
)]
pub struct VerifyError {
    /// The failed items.
    pub failed: Vec<CheckItem>,
}

/// (K, M, Φ, held dofs) over the independent dofs of the model a body was reduced from; the
/// held dofs are the reference conditions' (left out of the eigen residuals, [`identities`]).
pub type ModelPhi<'a> = (
    &'a SparseColMat<usize, f64>,
    &'a SparseColMat<usize, f64>,
    &'a Mat<f64>,
    &'a [usize],
);

/// Verifies `body` (as it will be written) and Φ over the independent dofs of the model (K, M)
/// it was reduced from; `None` for Φ skips the model identities. `rigid`: the rigid-body modes
/// a model of several parts must have (`None`: the file's reference conditions say).
/// Returns the full report.
pub fn verify_body(
    body: &file::ReducedBody,
    model: Option<ModelPhi<'_>>,
    rigid: Option<&RigidExpectation>,
) -> Result<CheckReport, VerifyError> {
    let mut report = file_checks_with(body, RigidRule::from_model(rigid));
    if let Some((k, m, phi, held)) = model {
        push_identities(
            &mut report,
            &identities(k, m, phi, &body.modes.omega2, held),
            &body.modes.labels,
            crate::pipeline::verify::exact_eigenvectors(body),
            k.nrows(),
        );
    }
    let failed: Vec<CheckItem> = report.items.iter().filter(|i| !i.pass).cloned().collect();
    if failed.is_empty() {
        Ok(report)
    } else {
        Err(VerifyError { failed })
    }
}

/// Whether the body's modes must be eigenvectors of the model to [`RESIDUAL_LIMIT`]: normal
/// modes without residual vectors, computed by Lanczos. AMLS modes (the recipe's
/// `--eigensolver amls`) are Rayleigh–Ritz pairs whose residuals measure the cutoff's
/// truncation, reported for information; their completeness was proven by the build's inertia
/// count.
pub fn exact_eigenvectors(body: &file::ReducedBody) -> bool {
    let amls = (body.recipe.as_ref())
        .and_then(|r| r.options.eigensolver.as_deref())
        .is_some_and(|e| e.starts_with("amls"));
    body.method.method == file::Method::NormalModes
        && !crate::pipeline::scene::has_residual_vectors(body)
        && !amls
}

/// The model-identity rows of a report (shared by `check --model` and the build).
pub fn push_identities(
    report: &mut CheckReport,
    f: &Identities,
    labels: &[file::ModeLabel],
    normal_modes: bool,
    dofs: usize,
) {
    let m = labels.len();
    report.push(
        "Φᵀ M Φ = I against the model",
        f.orthonormality,
        ORTHO_LIMIT,
        format!("{m} modes, {dofs} independent dofs"),
    );
    report.push(
        "Φᵀ K Φ = diag(ω²) against the model",
        f.stiffness,
        f.stiffness_limit,
        "relative to max ω² (limit: 1e-8 or the rounding floor of Φᵀ K Φ, whichever is higher)"
            .into(),
    );
    let flexible = || {
        (0..f.residuals.len())
            .filter(|&j| labels.get(j).is_some_and(|l| *l != file::ModeLabel::Rigid))
    };
    let worst = flexible().fold(0.0f64, |a, j| a.max(f.residuals[j]));
    if normal_modes {
        // the limit where the residual is nearest to its own limit
        let (value, limit) = flexible()
            .map(|j| (f.residuals[j], f.residual_limits[j]))
            .fold((0.0, RESIDUAL_LIMIT), |b, (r, l)| {
                if r / l > b.0 / b.1 {
                    (r, l)
                } else {
                    b
                }
            });
        report.push(
            "eigen residuals ‖Kφ − ω²Mφ‖/‖Kφ‖",
            value,
            limit,
            format!(
                "normal modes are eigenvectors of the model (limit: {RESIDUAL_LIMIT:e} or the \
                 rounding floor of Kφ, whichever is higher; worst residual {worst:.3e})"
            ),
        );
    } else {
        report.push(
            "eigen residuals (reduced basis, for information)",
            worst,
            f64::INFINITY,
            "a reduced basis (or AMLS's Rayleigh–Ritz modes) is not an eigenbasis of the full \
             model: this measures truncation"
                .into(),
        );
    }
}
