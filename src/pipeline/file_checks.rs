//! The checks a reduced-body file must pass from its own data — the same items and limits in
//! `flexbody check` and in the build's own verification before anything is written
//! ([`crate::pipeline::verify`]). Each check measures one figure against a stated limit; the file
//! passes only when every check passes.
//!
//! * generalized mass = I and generalized stiffness = diag(ω²), frequencies = √ω²/2π;
//! * rigid-body properties from the invariants: I1 > 0, centre of mass I2/I1 inside the nodes'
//!   bounding box, I7 symmetric positive definite;
//! * the number of rigid-body modes against the expectation (6 for a free body, 0 with
//!   reference conditions; for a model of several connected parts the sum of their free
//!   motions, which the build counts from the model and the file records, [`RigidRule`]);
//! * lumped mass, every node stored: invariants I1, I2, I6, I7 recomputed from the stored nodal
//!   masses and shapes equal the stored ones, and I6 equals the generalized mass — a corrupted
//!   mode shape breaks these; consistent mass: I6 equals the generalized mass (the invariants
//!   come from the consistent M, not from the lumped nodal masses).
//!
//! A file that stores only some nodes (`build --keep-nodes interface|surface|SET`) cannot
//! support the centre-of-mass bounding-box test or the invariants recomputed from nodal masses:
//! they are skipped and listed in [`CheckReport::skipped`] (printed as `skip …` lines).

use faer::{Mat, Par};
use flexbody_reader as file;

use crate::body::invariants::{compute_invariants, InvariantSet, MassPoint};
use crate::pipeline::precheck::RigidExpectation;

/// One check: a measured figure against its limit.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CheckItem {
    /// Short name.
    pub name: String,
    /// Measured value.
    pub value: f64,
    /// Limit the value must not exceed (or reach, see `detail`).
    pub limit: f64,
    /// Did it pass?
    pub pass: bool,
    /// One line explaining the figure.
    pub detail: String,
}

/// The whole report.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct CheckReport {
    /// Checks in the order run.
    pub items: Vec<CheckItem>,
    /// Checks not run because the file's stored data cannot support them (e.g. a file that
    /// stores only some nodes), each "name: reason".
    pub skipped: Vec<String>,
}

impl CheckReport {
    /// True when every check passed.
    pub fn passed(&self) -> bool {
        self.items.iter().all(|i| i.pass)
    }

    pub(crate) fn push(&mut self, name: &str, value: f64, limit: f64, detail: String) {
        let pass = value.is_finite() && value <= limit;
        self.items.push(CheckItem {
            name: name.into(),
            value,
            limit,
            pass,
            detail,
        });
    }
}

/// Limit on ‖ΦᵀMΦ − I‖, ‖ΦᵀKΦ − diag ω²‖/max ω² and the stored-data identities (relative):
/// the one limit of SPEC §5 (`modes.bin`), which the orthonormalization enforces before writing.
pub const ORTHO_LIMIT: f64 = crate::reduce::orthonormalize::CHECK_LIMIT;

/// Where the expected number of rigid-body modes comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RigidRule<'a> {
    /// The file's reference conditions (6 − their rank): the build of a one-part model.
    File,
    /// The file alone (`check` without `--model`): its reference conditions, or the count the
    /// build recorded (`method.bin` counts) when that is higher — a model of several parts, whose
    /// connectivity the file does not hold, has more (the sum over its parts is never below the
    /// whole body's count); `check --model` recomputes it from the model's parts.
    FileOrRecorded,
    /// Counted from the model's connected parts ([`crate::pipeline::precheck::expected_rigid_motions`]).
    Model(&'a RigidExpectation),
}

impl<'a> RigidRule<'a> {
    /// The model's count when it has several parts, else the file's reference conditions.
    pub fn from_model(expectation: Option<&'a RigidExpectation>) -> Self {
        expectation.map_or(RigidRule::File, RigidRule::Model)
    }
}

/// Every check the file's own data allows, in the order run (the rigid-body modes by
/// [`RigidRule::FileOrRecorded`]).
pub fn file_checks(body: &file::ReducedBody) -> CheckReport {
    file_checks_with(body, RigidRule::FileOrRecorded)
}

/// [`file_checks`] with the rigid-body modes expected by `rigid`.
pub fn file_checks_with(body: &file::ReducedBody, rigid: RigidRule<'_>) -> CheckReport {
    let mut r = CheckReport::default();
    generalized_matrices(body, &mut r);
    rigid_body_properties(body, &mut r);
    r.items.push(rigid_modes(body, rigid));
    stored_invariants(body, &mut r);
    r
}

/// Generalized mass = I and stiffness = diag(ω²) as stored, frequencies = √ω²/2π.
fn generalized_matrices(body: &file::ReducedBody, r: &mut CheckReport) {
    let m = body.mode_count();
    let md = &body.modes;
    let max_w2 = md
        .omega2
        .iter()
        .fold(0.0f64, |a, &b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE);
    let gm_err = (0..m * m)
        .map(|i| (md.generalized_mass[i] - if i / m == i % m { 1.0 } else { 0.0 }).abs())
        .fold(0.0, f64::max);
    r.push(
        "generalized mass = I",
        gm_err,
        ORTHO_LIMIT,
        format!("max |Φᵀ M Φ − I| as stored, {m} modes"),
    );
    let gk_err = (0..m * m)
        .map(|i| {
            (md.generalized_stiffness[i]
                - if i / m == i % m {
                    md.omega2[i / m]
                } else {
                    0.0
                })
            .abs()
        })
        .fold(0.0, f64::max)
        / max_w2;
    r.push(
        "generalized stiffness = diag(ω²)",
        gk_err,
        ORTHO_LIMIT,
        "max |Φᵀ K Φ − diag(ω²)| / max ω², as stored".into(),
    );
    let f_err = md
        .omega2
        .iter()
        .zip(&md.frequency_hz)
        .map(|(&w2, &f)| (crate::solve::hz(w2) - f).abs() / f.max(1e-300))
        .filter(|e| e.is_finite())
        .fold(0.0, f64::max);
    r.push("frequencies = √ω²/2π", f_err, 1e-12, "relative".into());
}

/// Rigid-body properties from the invariants: I1 > 0, the centre of mass I2/I1 inside the nodes'
/// bounding box (every node stored), I7 symmetric positive definite.
fn rigid_body_properties(body: &file::ReducedBody, r: &mut CheckReport) {
    let n = body.node_count();
    let inv = &body.invariants;
    let i1 = inv.i1.first().copied().unwrap_or(0.0);
    r.push(
        "total mass I1 > 0",
        if i1 > 0.0 { 0.0 } else { 1.0 },
        0.0,
        format!("I1 = {i1:.6e}"),
    );
    let partial = partial_nodes(body);
    if let Some(stored) = &partial {
        r.skipped.push(format!(
            "centre of mass inside the body's bounding box: the file stores {stored}, whose \
             bounding box need not hold the centre of mass"
        ));
    }
    if i1 > 0.0 && inv.i2.len() == 3 && n > 0 && partial.is_none() {
        let cm: Vec<f64> = inv.i2.iter().map(|v| v / i1).collect();
        let outside = (0..3)
            .map(|k| {
                let lo = body
                    .nodes
                    .iter()
                    .map(|p| p.xyz[k])
                    .fold(f64::INFINITY, f64::min);
                let hi = body
                    .nodes
                    .iter()
                    .map(|p| p.xyz[k])
                    .fold(f64::NEG_INFINITY, f64::max);
                // the mass-weighted mean of coordinates of size |x| carries rounding of order
                // ε·|x|: a line or a flat plate far from the origin has zero extent across it
                let tol = (1e-9 * (hi - lo).abs())
                    .max(1e-12 * lo.abs().max(hi.abs()))
                    .max(1e-300);
                ((lo - tol) - cm[k]).max(cm[k] - (hi + tol)).max(0.0)
            })
            .fold(0.0, f64::max);
        r.push(
            "centre of mass inside the body's bounding box",
            outside,
            0.0,
            format!("I2/I1 = ({:.6e}, {:.6e}, {:.6e})", cm[0], cm[1], cm[2]),
        );
    }
    if inv.i7.len() == 9 {
        let t = Mat::from_fn(3, 3, |a, b| inv.i7[3 * a + b]);
        let asym = (0..3)
            .flat_map(|a| (0..3).map(move |b| (a, b)))
            .map(|(a, b)| (t[(a, b)] - t[(b, a)]).abs())
            .fold(0.0, f64::max);
        let ev = t
            .self_adjoint_eigenvalues(faer::Side::Lower)
            .unwrap_or_default();
        let min_ev = ev.first().copied().unwrap_or(-1.0);
        let max_ev = ev.last().copied().unwrap_or(1.0);
        // a line of point masses without rotary inertia about it (beam-only models with lumped
        // mass, e.g. Nastran's CBAR) has no inertia about that line: physics, not an error
        let line = zero_inertia_axes(body) == 1 && min_ev.abs() <= ZERO_INERTIA * max_ev;
        r.push(
            "inertia tensor I7 symmetric positive definite",
            if min_ev > 0.0 || line {
                asym / max_ev
            } else {
                1.0
            },
            1e-12,
            if line {
                format!(
                    "principal values {}: singular, accepted: all mass lies on a line \
                     through the origin with no rotary inertia about it (beam-only or point \
                     masses on a line)",
                    fmt_values(&ev)
                )
            } else {
                format!(
                    "principal values about the centre of mass {} (as inspect shows), about \
                     the origin {}",
                    fmt_values(&centre_of_mass_principal(&t, inv)),
                    fmt_values(&ev)
                )
            },
        );
    }
}

/// `[a, b, c]` with 6 significant digits.
fn fmt_values(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| format!("{x:.6e}")).collect();
    format!("[{}]", parts.join(", "))
}

/// Principal values of the inertia about the centre of mass c = I2/I1: the parallel-axis
/// theorem I_c = I7 − I1((c·c)E − c cᵀ).
fn centre_of_mass_principal(i7: &Mat<f64>, inv: &file::Invariants) -> Vec<f64> {
    let (Some(&m), true) = (inv.i1.first(), inv.i2.len() >= 3) else {
        return Vec::new();
    };
    if m <= 0.0 {
        return Vec::new();
    }
    let c = [inv.i2[0] / m, inv.i2[1] / m, inv.i2[2] / m];
    let cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    let ic = Mat::from_fn(3, 3, |a, b| {
        i7[(a, b)] - m * (if a == b { cc } else { 0.0 } - c[a] * c[b])
    });
    ic.self_adjoint_eigenvalues(faer::Side::Lower)
        .unwrap_or_default()
}

/// The name of the rigid-body mode check (`check --model` replaces the item by name).
pub const RIGID_MODES: &str = "rigid-body modes as expected";

/// The rigid-body modes against the expectation of `rule`: the rigid motions the reference
/// conditions leave free (6 for a free body) that carry inertia — not the rotation about a line
/// of translation-only masses — or the sum over the model's parts.
pub fn rigid_modes(body: &file::ReducedBody, rule: RigidRule<'_>) -> CheckItem {
    let md = &body.modes;
    // rigid: below 1e-4 of the highest frequency, or labelled rigid and below 1e-2 of the first
    // flexible mode (on a slender model rounding leaves rigid modes at ~1e-3 Hz while the set
    // ends at a few hundred Hz)
    let fmax_stored = md.frequency_hz.iter().fold(0.0f64, |a, &b| a.max(b));
    let first_flexible = md
        .frequency_hz
        .iter()
        .zip(&md.labels)
        .filter(|(_, l)| **l != file::ModeLabel::Rigid)
        .map(|(f, _)| *f)
        .fold(f64::INFINITY, f64::min);
    let rigid = md
        .frequency_hz
        .iter()
        .zip(&md.labels)
        .filter(|&(&f, l)| {
            f < 1e-4 * fmax_stored || (*l == file::ModeLabel::Rigid && f < 1e-2 * first_flexible)
        })
        .count();
    let free = free_rigid_motions(body);
    let from_file = free_rigid_motions_with_inertia(body, &free);
    let labelled = md
        .labels
        .iter()
        .filter(|l| **l == file::ModeLabel::Rigid)
        .count();
    let without_inertia = free.len() - from_file;
    let file_why = match (body.method.reference_conditions.is_empty(), without_inertia) {
        (true, 0) => "free body".to_string(),
        (true, k) => format!(
            "free body; {k} of its rigid motions (the rotation about the line of its masses) carry no inertia and are no modes"
        ),
        (false, 0) => "rigid motions the reference conditions leave free".to_string(),
        (false, k) => format!(
            "rigid motions the reference conditions leave free, less {k} that carry no inertia (a rotation about the line of its masses)"
        ),
    };
    let recorded = body.method.counts.rigid as usize;
    let (expected, why) = match rule {
        RigidRule::Model(e) => (e.count, e.detail.clone()),
        RigidRule::FileOrRecorded if recorded > from_file && rigid == recorded => (
            recorded,
            format!(
                "the build's count in method.bin: its model has several connected parts, whose \
                 free motions add up, which the file cannot tell; from the file's reference \
                 conditions alone at least {from_file}; `check --model` recounts them from the model"
            ),
        ),
        _ => (from_file, file_why),
    };
    let value = (rigid as f64 - expected as f64).abs() + (labelled as f64 - rigid as f64).abs();
    CheckItem {
        name: RIGID_MODES.into(),
        value,
        limit: 0.0,
        pass: value == 0.0,
        detail: format!(
            "{rigid} modes below 1e-4·f_max (labelled rigid: {labelled}); expected {expected} ({why})"
        ),
    }
}

/// The stored invariants: I6 = the generalized mass for consistent mass; for lumped mass with
/// every node stored, I1, I2, I6, I7 recomputed from the stored nodal masses and shapes.
fn stored_invariants(body: &file::ReducedBody, r: &mut CheckReport) {
    let m = body.mode_count();
    let n = body.node_count();
    let md = &body.modes;
    let inv = &body.invariants;
    let i1 = inv.i1.first().copied().unwrap_or(0.0);
    let partial = partial_nodes(body);
    // Invariants recomputed from the stored nodes (only meaningful when every node is stored).
    let all_nodes = body.header.request.keep_nodes == file::KeepNodes::All;
    let consistent = body.method.mass_kind == file::MassKind::Consistent;
    if consistent && inv.i6.len() == m * m {
        // Consistent mass: the invariants come from the consistent M (SPEC §5.6), not from the
        // lumped nodal masses, so they cannot be recomputed from the file; I6 is Φᵀ M Φ itself.
        let e = (0..m * m)
            .map(|i| (inv.i6[i] - md.generalized_mass[i]).abs())
            .fold(0.0, f64::max);
        r.push(
            "I6 = generalized mass (consistent M)",
            e,
            1e-9,
            "the invariants use the mass the modes are orthonormal in".into(),
        );
    }
    if let (Some(stored), false) = (&partial, consistent) {
        r.skipped.push(format!(
            "invariants recomputed from the stored nodal masses and shapes: the file stores \
             {stored}, not the mass of the whole body"
        ));
    }
    if all_nodes && !consistent {
        let points: Vec<MassPoint> = body
            .nodes
            .iter()
            .zip(&body.nodal_mass)
            .map(|(p, nm)| MassPoint {
                position: p.xyz,
                mass: nm.mass,
                inertia: nm.inertia,
            })
            .collect();
        let shapes = Mat::from_fn(6 * n, m, |row, j| {
            md.shapes[(j * n + row / 6) * 6 + row % 6]
        });
        if let Ok(re) =
            compute_invariants(&points, shapes.as_ref(), InvariantSet::Constant, Par::Seq)
        {
            let rel = |a: f64, b: f64, scale: f64| (a - b).abs() / scale.max(f64::MIN_POSITIVE);
            let mut worst: f64 = rel(re.i1, i1, i1.abs());
            let len = (inv.i7.iter().map(|v| v.abs()).fold(0.0, f64::max)
                / i1.max(f64::MIN_POSITIVE))
            .sqrt();
            for k in 0..3 {
                worst = worst.max(rel(
                    re.i2[k],
                    inv.i2.get(k).copied().unwrap_or(f64::NAN),
                    i1 * len,
                ));
            }
            for k in 0..9 {
                worst = worst.max(rel(
                    re.i7[k / 3][k % 3],
                    inv.i7.get(k).copied().unwrap_or(f64::NAN),
                    i1 * len * len,
                ));
            }
            if inv.i6.len() == m * m {
                if let Some(i6) = &re.i6 {
                    for a in 0..m {
                        for b in 0..m {
                            worst = worst.max(rel(i6[(a, b)], inv.i6[a * m + b], 1.0));
                        }
                    }
                }
            }
            r.push(
                "stored invariants = recomputation from stored nodes",
                worst,
                1e-9,
                "I1, I2, I6, I7 relative".into(),
            );
            if body.method.mass_kind == file::MassKind::Lumped {
                if let Some(i6) = &re.i6 {
                    let e = (0..m * m)
                        .map(|i| (i6[(i / m, i % m)] - md.generalized_mass[i]).abs())
                        .fold(0.0, f64::max);
                    r.push(
                        "I6 from stored shapes = generalized mass",
                        e,
                        1e-6,
                        "lumped mass: Σ m ΦᵀΦ + Φ*ᵀ I Φ* must equal Φᵀ M Φ = I".into(),
                    );
                }
            }
        }
    }
}

/// Principal inertia ≤ ZERO_INERTIA · the largest one counts as zero (rounding of Σ m·0).
pub const ZERO_INERTIA: f64 = 1e-10;

/// The relative rounding of the invariants' sums over the nodes (about √n·ε for n nodes up to a
/// million, ε = 2.2e-16): a principal inertia through the centre of mass within this fraction of
/// I7's terms about the origin (m|c|², |I7|) counts as zero. The free CBAR line of
/// tests/massless_frames.rs moved 1e5 m from the origin (origin terms 2.8e11 kg·m², limit 6e-2)
/// leaves −9.2e-5 kg·m² of rounding in its zero inertia about the line; its other principal
/// inertias are 0.69.
const INVARIANT_ROUNDING: f64 = 1e3 * f64::EPSILON;

/// `Some("only the … nodes (k of the model's)")` when the file does not store every node.
pub fn partial_nodes(body: &file::ReducedBody) -> Option<String> {
    let what = match &body.header.request.keep_nodes {
        file::KeepNodes::All => return None,
        file::KeepNodes::InterfaceAndSurface => "the interface and surface nodes".to_owned(),
        file::KeepNodes::List(ids) if ids.is_empty() => "the interface nodes".to_owned(),
        file::KeepNodes::List(ids) => format!("the interface nodes and {} listed nodes", ids.len()),
    };
    Some(format!("only {what} ({} nodes)", body.node_count()))
}

/// Principal axes through the centre of mass without inertia (from I1, I2, I7): 1 when every
/// mass lies on a line and carries no rotary inertia about it, 0 for a body with volume.
pub fn zero_inertia_axes(body: &file::ReducedBody) -> usize {
    zero_inertia_rotations(body).map_or(0, |(_, axes)| axes.len())
}

/// The centre of mass and the unit principal axes through it without inertia (J_cm eigenvalue
/// ≤ [`ZERO_INERTIA`] · the largest); `None` without mass or invariants.
fn zero_inertia_rotations(body: &file::ReducedBody) -> Option<([f64; 3], Vec<[f64; 3]>)> {
    let inv = &body.invariants;
    let i1 = inv.i1.first().copied().unwrap_or(0.0);
    if i1.is_nan() || i1 <= 0.0 || inv.i2.len() != 3 || inv.i7.len() != 9 {
        return None;
    }
    let c: [f64; 3] = std::array::from_fn(|k| inv.i2[k] / i1);
    let cc = c.iter().map(|v| v * v).sum::<f64>();
    // J_cm = I7 − m (|c|² E − c cᵀ)
    let j = Mat::from_fn(3, 3, |a, b| {
        inv.i7[3 * a + b] - i1 * (if a == b { cc } else { 0.0 } - c[a] * c[b])
    });
    let (ev, vecs) = crate::solve::dense::eigh(j.as_ref()).ok()?;
    let top = ev.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    if top <= 0.0 {
        return None;
    }
    // J_cm is I7 less m(|c|² E − c cᵀ): far from the origin both are large and their rounding
    // (of the sums over the nodes) is left in J_cm
    let origin_terms = i1 * cc + inv.i7.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let zero = (ZERO_INERTIA * top).max(INVARIANT_ROUNDING * origin_terms);
    let axes = (0..3)
        .filter(|&k| ev[k].abs() <= zero)
        .map(|k| std::array::from_fn(|i| vecs[(i, k)]))
        .collect();
    Some((c, axes))
}

/// Rigid-body motions the reference conditions leave free: an orthonormal basis (6 − rank(R_c)
/// vectors (t, θ·size)) of the null space of R_c, which holds the rows of the rigid motion
/// u = t + θ × x at the held dofs (node frames from the interface records, else basic); θ is
/// scaled by the body size so the rank test is unit-free.
fn free_rigid_motions(body: &file::ReducedBody) -> Vec<[f64; 6]> {
    let size = rigid_scale(body);
    let eye = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut g = faer::Mat::<f64>::zeros(6, 6);
    for rc in &body.method.reference_conditions {
        let Some(node) = body.nodes.get(rc.node as usize) else {
            continue;
        };
        let x = node.xyz;
        let f = body
            .method
            .interface
            .iter()
            .find(|i| i.node == rc.node)
            .map_or(eye, |i| i.frame);
        for c in (0..6).filter(|&c| rc.dofs[c]) {
            let e = f[c % 3];
            let row: [f64; 6] = if c < 3 {
                // e · (θ × x) = θ · (x × e)
                [
                    e[0],
                    e[1],
                    e[2],
                    (x[1] * e[2] - x[2] * e[1]) / size,
                    (x[2] * e[0] - x[0] * e[2]) / size,
                    (x[0] * e[1] - x[1] * e[0]) / size,
                ]
            } else {
                // [0, e/size], scaled by `size` as a row (rank is unchanged).
                [0.0, 0.0, 0.0, e[0], e[1], e[2]]
            };
            for a in 0..6 {
                for b in 0..6 {
                    g[(a, b)] += row[a] * row[b];
                }
            }
        }
    }
    let Ok((vals, vecs)) = crate::solve::dense::eigh(g.as_ref()) else {
        return Vec::new();
    };
    let top = vals.iter().fold(0.0f64, |a, &b| a.max(b));
    (0..6)
        .filter(|&j| !(top > 0.0 && vals[j] > 1e-10 * top))
        .map(|j| std::array::from_fn(|i| vecs[(i, j)]))
        .collect()
}

/// How many of the `free` rigid motions (from [`free_rigid_motions`]) carry inertia: their
/// number less the dimension of their intersection with the rotations about the principal axes
/// without inertia through the centre of mass c (u = a × (x − c): t = c × a, θ = a). A motion
/// without inertia (the rotation about the line of translation-only masses) is no mode.
fn free_rigid_motions_with_inertia(body: &file::ReducedBody, free: &[[f64; 6]]) -> usize {
    let Some((c, axes)) = zero_inertia_rotations(body) else {
        return free.len();
    };
    let size = rigid_scale(body);
    // the rotations in the coordinates of `free` (t, θ·size), orthonormalized
    let mut z: Vec<[f64; 6]> = Vec::new();
    for a in &axes {
        let mut v = [
            c[1] * a[2] - c[2] * a[1],
            c[2] * a[0] - c[0] * a[2],
            c[0] * a[1] - c[1] * a[0],
            a[0] * size,
            a[1] * size,
            a[2] * size,
        ];
        for b in &z {
            let d: f64 = (0..6).map(|i| v[i] * b[i]).sum();
            (0..6).for_each(|i| v[i] -= d * b[i]);
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 0.0 {
            z.push(v.map(|x| x / norm));
        }
    }
    // Zᵀ F Fᵀ Z: eigenvalue 1 for a rotation inside the free space, 0 for one held
    let s = Mat::from_fn(z.len(), z.len(), |p, q| {
        (free.iter())
            .map(|f| {
                let dp: f64 = (0..6).map(|i| f[i] * z[p][i]).sum();
                let dq: f64 = (0..6).map(|i| f[i] * z[q][i]).sum();
                dp * dq
            })
            .sum::<f64>()
    });
    // an eigen failure (non-finite terms) counts every free motion, as without invariants
    let Ok(ev) = s.self_adjoint_eigenvalues(faer::Side::Lower) else {
        return free.len();
    };
    let inside = ev.iter().filter(|&&v| v > 0.5).count();
    free.len() - inside.min(free.len())
}

/// The body size rotations are scaled by in [`free_rigid_motions`]: the stored nodes' largest
/// distance from the origin, or the body's radius of gyration about it, √(tr I7 / (2 I1)),
/// when larger (a file may store few or no nodes: `--keep-nodes interface`).
fn rigid_scale(body: &file::ReducedBody) -> f64 {
    let nodes = (body.nodes.iter())
        .map(|n| n.xyz.iter().map(|v| v * v).sum::<f64>().sqrt())
        .fold(0.0f64, f64::max);
    let inv = &body.invariants;
    let gyration = match inv.i1.first() {
        Some(&m) if m > 0.0 && inv.i7.len() == 9 => ((inv.i7[0] + inv.i7[4] + inv.i7[8])
            / (2.0 * m))
            .max(0.0)
            .sqrt(),
        _ => 0.0,
    };
    nodes.max(gyration).max(f64::MIN_POSITIVE)
}
