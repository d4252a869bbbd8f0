//! Rules of the optional entries (SPEC.md §6): label shares, modal loads, geometric stiffness,
//! eigen residuals.

use super::*;

/// Rule 16 (SPEC §5.17): each problem the method's own and at most once; as many eigenvalues
/// as residuals, as many as the counts of `method.bin` say (exactly, without residual
/// vectors); finite; residuals ≥ 0; an inertia count's shift finite and its count at least the
/// stored eigenvalues below it.
pub(super) fn eigen_residuals(
    e: &crate::types::EigenResiduals,
    body: &ReducedBody,
) -> Result<(), ReadError> {
    use crate::types::{EigenProblemKind, Method};
    let c = &body.method.counts;
    let m = body.modes.omega2.len() as u64;
    // with residual vectors in the basis (their flags), they share the method's count
    let residual_vectors = body
        .modal_loads
        .as_ref()
        .is_some_and(|ml| !ml.residual.is_empty());
    for (q, p) in e.problems.iter().enumerate() {
        // the problem's vectors are basis vectors: as many as the counts say — fewer only when
        // residual vectors share the count (§5.7), more only for an extended free-free set
        let (own, bound, what) = match body.method.method {
            Method::NormalModes => (EigenProblemKind::NormalModes, m, "the modes M"),
            Method::CraigBampton => (
                EigenProblemKind::FixedInterface,
                c.fixed_interface,
                "counts.fixed_interface",
            ),
            Method::CraigChang | Method::Dietz => (
                EigenProblemKind::FreeFree,
                c.rigid.saturating_add(c.normal),
                "counts.rigid + counts.normal",
            ),
        };
        if p.kind != own {
            return Err(inconsistent(
                EIGEN_RESIDUALS,
                format!(
                    "problems[{q}] is {:?}, not the {:?} problem of {:?}",
                    p.kind, own, body.method.method
                ),
            ));
        }
        if e.problems[..q].iter().any(|o| o.kind == p.kind) {
            return Err(inconsistent(
                EIGEN_RESIDUALS,
                format!("problems[{q}]: {:?} appears twice", p.kind),
            ));
        }
        finite(EIGEN_RESIDUALS, &format!("problems[{q}].scale"), [&p.scale])?;
        if p.scale <= 0.0 {
            return Err(inconsistent(
                EIGEN_RESIDUALS,
                format!("problems[{q}].scale = {} is not > 0", p.scale),
            ));
        }
        let n = p.omega2.len();
        let field = format!("problems[{q}].residual");
        count(
            EIGEN_RESIDUALS,
            &field,
            p.residual.len(),
            n,
            "one per eigenvalue",
        )?;
        let (fits, relation) = match own {
            EigenProblemKind::FreeFree => (n as u64 >= bound, " at least"),
            EigenProblemKind::NormalModes | EigenProblemKind::FixedInterface
                if residual_vectors =>
            {
                (n as u64 <= bound, " at most")
            }
            EigenProblemKind::NormalModes | EigenProblemKind::FixedInterface => {
                (n as u64 == bound, "")
            }
        };
        if !fits {
            return Err(ReadError::CountMismatch {
                entry: EIGEN_RESIDUALS.into(),
                field: format!("problems[{q}].omega2"),
                expected: bound,
                found: n as u64,
                rule: format!("{what}{relation}"),
            });
        }
        finite(EIGEN_RESIDUALS, &format!("problems[{q}].omega2"), &p.omega2)?;
        finite(EIGEN_RESIDUALS, &field, &p.residual)?;
        if let Some((j, r)) = p.residual.iter().enumerate().find(|(_, r)| **r < 0.0) {
            return Err(inconsistent(
                EIGEN_RESIDUALS,
                format!("{field}[{j}] is negative ({r})"),
            ));
        }
        if let Some(i) = &p.inertia {
            let field = format!("problems[{q}].inertia.shift");
            finite(EIGEN_RESIDUALS, &field, [&i.shift])?;
            let below = p.omega2.iter().filter(|&&l| l < i.shift).count() as u64;
            if i.below < below {
                return Err(inconsistent(
                    EIGEN_RESIDUALS,
                    format!(
                        "problems[{q}]: {below} stored eigenvalues lie below the shift {:e}, but \
                         the inertia count says {}",
                        i.shift, i.below
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Rule 15 (SPEC §5.16): a `Held` body has no `Rigid` mode; each field's load valid and not
/// repeated, its matrix M×M, finite and symmetric, and (since 1.8) zero for an acceleration
/// field under inertia relief.
pub(super) fn geometric_stiffness(
    g: &crate::types::GeometricStiffness,
    body: &ReducedBody,
) -> Result<(), ReadError> {
    use crate::types::{ModeLabel, StaticSupport, UnitLoad};
    let m = body.modes.omega2.len();
    if g.support == StaticSupport::Held {
        if let Some(j) = body
            .modes
            .labels
            .iter()
            .position(|l| *l == ModeLabel::Rigid)
        {
            return Err(inconsistent(
                GEOMETRIC_STIFFNESS,
                format!("support is Held, but mode {j} is labelled Rigid"),
            ));
        }
    }
    let v = body.version;
    let zero_accelerations =
        g.support == StaticSupport::InertiaRelief && (v.major, v.minor) >= (1, 8);
    for (q, f) in g.fields.iter().enumerate() {
        if !f.load.is_valid() {
            return Err(inconsistent(
                GEOMETRIC_STIFFNESS,
                format!("fields[{q}]: load {:?} has an axis out of range", f.load),
            ));
        }
        if g.fields[..q].iter().any(|o| o.load == f.load) {
            return Err(inconsistent(
                GEOMETRIC_STIFFNESS,
                format!("fields[{q}]: load {:?} appears twice", f.load),
            ));
        }
        let field = format!("fields[{q}].matrix");
        count(
            GEOMETRIC_STIFFNESS,
            &field,
            f.matrix.len(),
            dims(&[m, m]),
            "modes × modes",
        )?;
        finite(GEOMETRIC_STIFFNESS, &field, &f.matrix)?;
        symmetric(GEOMETRIC_STIFFNESS, &field, &f.matrix, m)?;
        let rigid_acceleration = matches!(
            f.load,
            UnitLoad::Acceleration(_) | UnitLoad::AngularAcceleration(_)
        );
        if zero_accelerations && rigid_acceleration {
            if let Some(k) = f.matrix.iter().position(|a| *a != 0.0) {
                return Err(inconsistent(
                    GEOMETRIC_STIFFNESS,
                    format!(
                        "{field}[{k}] = {}: an acceleration field under InertiaRelief is zero",
                        f.matrix[k]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Rule 11 (SPEC §5.12): one share per mode in 0…1; 1 for a `Rigid` mode and for every mode of
/// a single-stage basis (normal modes without residual vectors: `modal_loads.residual` empty).
pub(super) fn label_shares(s: &[f64], body: &ReducedBody) -> Result<(), ReadError> {
    use crate::types::{Method, ModeLabel};
    let labels = &body.modes.labels;
    count(
        LABEL_SHARES,
        "shares",
        s.len(),
        labels.len(),
        "one per mode",
    )?;
    finite(LABEL_SHARES, "shares", s)?;
    // before 1.6: no mode flagged residual; since 1.6: no residual vectors in the basis
    let v = body.version;
    let no_residual = |ml: &crate::ModalLoads| {
        if (v.major, v.minor) < (1, 6) {
            ml.residual.iter().all(|&r| r == 0)
        } else {
            ml.residual.is_empty()
        }
    };
    let single_stage = body.method.method == Method::NormalModes
        && body.modal_loads.as_ref().is_none_or(no_residual);
    for (j, (&v, &label)) in s.iter().zip(labels).enumerate() {
        if !(0.0..=1.0).contains(&v) {
            return Err(inconsistent(
                LABEL_SHARES,
                format!("share[{j}] = {v} is outside 0…1"),
            ));
        }
        if v != 1.0 && (label == ModeLabel::Rigid || single_stage) {
            return Err(inconsistent(
                LABEL_SHARES,
                format!(
                    "share[{j}] = {v} must be 1 ({})",
                    if label == ModeLabel::Rigid {
                        "a Rigid mode"
                    } else {
                        "normal modes without residual vectors"
                    }
                ),
            ));
        }
    }
    Ok(())
}

/// Rule 12 (SPEC §5.14): one value per mode per load, finite; names non-empty and unique;
/// `residual` empty or one 0/1 per mode, 1 only for a mode labelled `Attachment`.
pub(super) fn modal_loads(
    ml: &crate::types::ModalLoads,
    labels: &[crate::types::ModeLabel],
) -> Result<(), ReadError> {
    let m = labels.len();
    for (q, l) in ml.loads.iter().enumerate() {
        if l.name.is_empty() {
            return Err(inconsistent(
                MODAL_LOADS,
                format!("loads[{q}] has an empty name"),
            ));
        }
        if ml.loads[..q].iter().any(|o| o.name == l.name) {
            return Err(inconsistent(
                MODAL_LOADS,
                format!("load name {} appears twice", l.name),
            ));
        }
        count(MODAL_LOADS, "values", l.values.len(), m, "one per mode")?;
        finite(MODAL_LOADS, "values", &l.values)?;
    }
    if ml.residual.is_empty() {
        return Ok(());
    }
    count(
        MODAL_LOADS,
        "residual",
        ml.residual.len(),
        m,
        "one per mode or none",
    )?;
    for (j, (&v, &label)) in ml.residual.iter().zip(labels).enumerate() {
        if v > 1 {
            return Err(inconsistent(
                MODAL_LOADS,
                format!("residual[{j}] = {v} is not 0 or 1"),
            ));
        }
        if v == 1 && label != crate::types::ModeLabel::Attachment {
            return Err(inconsistent(
                MODAL_LOADS,
                format!("residual[{j}] = 1 but mode {j} is labelled {label:?}, not Attachment"),
            ));
        }
    }
    Ok(())
}
