//! Consistency rules of a decoded body (SPEC.md §6): counts, finiteness, index ranges,
//! symmetry, cross-entry agreement. The writer runs the same function before writing.
use crate::codec::{
    DAMPING, EIGEN_RESIDUALS, FACES, GEOMETRIC_STIFFNESS, HEADER, INVARIANTS, LABEL_SHARES, LINES,
    MANIFEST, METHOD, MODAL_LOADS, MODES, NODAL_MASS, NODES, RECIPE, STRAIN_SHAPES,
    STRAIN_SHAPES_BOTTOM, STRESS_SHAPES, STRESS_SHAPES_BOTTOM,
};
use crate::error::ReadError;
use crate::limits::ReadLimits;
use crate::types::{Face, FieldShapes, ReducedBody};

mod entries;
mod recipe;
use entries::{eigen_residuals, geometric_stiffness, label_shares, modal_loads};
use recipe::recipe;

/// Relative tolerance of the symmetry and frequency rules.
pub const REL_TOL: f64 = 1e-9;
/// Tolerance of the frame orthonormality rule.
pub const FRAME_TOL: f64 = 1e-6;

/// Product of array dimensions, saturating (a saturated product never equals a real length).
fn dims(d: &[usize]) -> usize {
    d.iter().fold(1usize, |a, &b| a.saturating_mul(b))
}

fn count(
    entry: &str,
    field: &str,
    found: usize,
    expected: usize,
    rule: &str,
) -> Result<(), ReadError> {
    if found == expected {
        return Ok(());
    }
    Err(ReadError::CountMismatch {
        entry: entry.into(),
        field: field.into(),
        expected: expected as u64,
        found: found as u64,
        rule: rule.into(),
    })
}

fn finite<'a>(
    entry: &str,
    field: &str,
    values: impl IntoIterator<Item = &'a f64>,
) -> Result<(), ReadError> {
    for (i, v) in values.into_iter().enumerate() {
        if !v.is_finite() {
            return Err(ReadError::NonFinite {
                entry: entry.into(),
                field: field.into(),
                index: i as u64,
                value: *v,
            });
        }
    }
    Ok(())
}

fn limit(entry: &str, what: &str, value: usize, max: u64) -> Result<(), ReadError> {
    if value as u64 > max {
        return Err(ReadError::LimitExceeded {
            entry: entry.into(),
            what: what.into(),
            value: value as u64,
            limit: max,
        });
    }
    Ok(())
}

fn index(entry: &str, field: String, value: u32, n: usize) -> Result<(), ReadError> {
    if (value as usize) < n {
        return Ok(());
    }
    Err(ReadError::IndexOutOfRange {
        entry: entry.into(),
        field,
        value: value as u64,
        bound: n as u64,
    })
}

fn inconsistent(entry: &str, rule: String) -> ReadError {
    ReadError::Inconsistent {
        entry: entry.into(),
        rule,
    }
}

/// Symmetry of an n×n row-major matrix: |a_ij − a_ji| ≤ REL_TOL · max|a|.
fn symmetric(entry: &str, field: &str, a: &[f64], n: usize) -> Result<(), ReadError> {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for i in 0..n {
        for j in (i + 1)..n {
            let (x, y) = (a[i * n + j], a[j * n + i]);
            if (x - y).abs() > REL_TOL * scale {
                return Err(ReadError::NotSymmetric {
                    entry: entry.into(),
                    field: field.into(),
                    row: i as u64,
                    col: j as u64,
                    a: x,
                    b: y,
                });
            }
        }
    }
    Ok(())
}

fn field_shapes(entry: &str, s: &FieldShapes, n: usize, m: usize) -> Result<(), ReadError> {
    for (q, &p) in s.nodes.iter().enumerate() {
        index(entry, format!("nodes[{q}]"), p, n)?;
        if q > 0 && p <= s.nodes[q - 1] {
            return Err(inconsistent(
                entry,
                format!("nodes must be strictly ascending (nodes[{q}] = {p})"),
            ));
        }
    }
    count(
        entry,
        "values",
        s.values.len(),
        dims(&[m, s.nodes.len(), 6]),
        "modes × listed nodes × 6",
    )?;
    finite(entry, "values", &s.values)
}

/// Checks every v1 consistency rule; the first broken rule is returned.
pub fn validate(body: &ReducedBody, limits: &ReadLimits) -> Result<(), ReadError> {
    let n = body.nodes.len();
    let m = body.modes.omega2.len();
    limit(NODES, "node count", n, limits.max_nodes)?;
    limit(FACES, "face count", body.faces.len(), limits.max_faces)?;
    limit(MODES, "mode count", m, limits.max_modes)?;

    for (what, u) in [
        ("mass", &body.units.mass),
        ("length", &body.units.length),
        ("time", &body.units.time),
        ("force", &body.units.force),
    ] {
        if !(u.si.is_finite() && u.si > 0.0) {
            return Err(inconsistent(
                MANIFEST,
                format!("units.{what}.si must be finite and > 0, got {}", u.si),
            ));
        }
    }
    let req = &body.header.request;
    if let Some(f) = req.fmax_hz {
        if !(f.is_finite() && f > 0.0) {
            return Err(inconsistent(
                HEADER,
                format!("request.fmax_hz must be finite and > 0, got {f}"),
            ));
        }
    }

    let mut ids = std::collections::HashSet::with_capacity(n);
    for (p, node) in body.nodes.iter().enumerate() {
        finite(NODES, &format!("nodes[{p}].xyz"), &node.xyz)?;
        if !ids.insert(node.id) {
            return Err(inconsistent(
                NODES,
                format!("node id {} occurs twice (nodes[{p}])", node.id),
            ));
        }
    }
    for (f, face) in body.faces.iter().enumerate() {
        let idx: &[u32] = match face {
            Face::Tri(v) => v,
            Face::Quad(v) => v,
        };
        for (k, &v) in idx.iter().enumerate() {
            index(FACES, format!("faces[{f}][{k}]"), v, n)?;
        }
    }

    if let Some(lines) = &body.lines {
        limit(LINES, "line count", lines.len(), limits.max_faces)?;
        for (l, line) in lines.iter().enumerate() {
            for (k, &v) in line.iter().enumerate() {
                index(LINES, format!("lines[{l}][{k}]"), v, n)?;
            }
        }
    }

    count(
        NODAL_MASS,
        "nodal masses",
        body.nodal_mass.len(),
        n,
        "one per stored node in nodes.bin",
    )?;
    for (p, nm) in body.nodal_mass.iter().enumerate() {
        let field = format!("nodal_mass[{p}]");
        finite(
            NODAL_MASS,
            &field,
            std::iter::once(&nm.mass).chain(nm.inertia.iter().flatten()),
        )?;
        if nm.mass < 0.0 {
            return Err(inconsistent(
                NODAL_MASS,
                format!("{field}.mass is negative ({})", nm.mass),
            ));
        }
        symmetric(
            NODAL_MASS,
            &format!("{field}.inertia"),
            nm.inertia.as_flattened(),
            3,
        )?;
    }

    let md = &body.modes;
    count(
        MODES,
        "frequency_hz",
        md.frequency_hz.len(),
        m,
        "one per mode (length of omega2)",
    )?;
    count(
        MODES,
        "labels",
        md.labels.len(),
        m,
        "one per mode (length of omega2)",
    )?;
    count(
        MODES,
        "generalized_mass",
        md.generalized_mass.len(),
        dims(&[m, m]),
        "modes × modes",
    )?;
    count(
        MODES,
        "generalized_stiffness",
        md.generalized_stiffness.len(),
        dims(&[m, m]),
        "modes × modes",
    )?;
    count(
        MODES,
        "shapes",
        md.shapes.len(),
        dims(&[m, n, 6]),
        "modes × stored nodes (nodes.bin) × 6",
    )?;
    finite(MODES, "omega2", &md.omega2)?;
    finite(MODES, "frequency_hz", &md.frequency_hz)?;
    finite(MODES, "generalized_mass", &md.generalized_mass)?;
    finite(MODES, "generalized_stiffness", &md.generalized_stiffness)?;
    finite(MODES, "shapes", &md.shapes)?;
    symmetric(MODES, "generalized_mass", &md.generalized_mass, m)?;
    symmetric(MODES, "generalized_stiffness", &md.generalized_stiffness, m)?;
    for (j, (&w2, &f)) in md.omega2.iter().zip(&md.frequency_hz).enumerate() {
        let expect = w2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI);
        if (f - expect).abs() > REL_TOL * expect.max(1.0) {
            return Err(inconsistent(
                MODES,
                format!("frequency_hz[{j}] = {f} but sqrt(max(omega2, 0))/(2 pi) = {expect}"),
            ));
        }
    }

    let inv = &body.invariants;
    let want = req.invariant_set.mask();
    if inv.mask != want {
        return Err(inconsistent(
            INVARIANTS,
            format!(
                "mask {:?} differs from the mask of header invariant_set {:?}",
                inv.mask, req.invariant_set
            ),
        ));
    }
    let shapes = [
        1,
        3,
        dims(&[3, m]),
        dims(&[3, m]),
        dims(&[m, 3, m]),
        dims(&[m, m]),
        9,
        dims(&[m, 9]),
        dims(&[m, m, 9]),
    ];
    let fields = [
        &inv.i1, &inv.i2, &inv.i3, &inv.i4, &inv.i5, &inv.i6, &inv.i7, &inv.i8, &inv.i9,
    ];
    for k in 0..9 {
        let name = format!("i{}", k + 1);
        let expected = if inv.mask[k] { shapes[k] } else { 0 };
        count(
            INVARIANTS,
            &name,
            fields[k].len(),
            expected,
            if inv.mask[k] {
                "selected: full shape"
            } else {
                "not selected: empty"
            },
        )?;
        finite(INVARIANTS, &name, fields[k])?;
    }
    if inv.mask[5] {
        symmetric(INVARIANTS, "i6", &inv.i6, m)?;
    }
    if inv.mask[6] {
        symmetric(INVARIANTS, "i7", &inv.i7, 3)?;
    }
    if inv.mask[0] && inv.i1[0] < 0.0 {
        return Err(inconsistent(
            INVARIANTS,
            format!("i1 (total mass) is negative ({})", inv.i1[0]),
        ));
    }

    let me = &body.method;
    if me.method != req.method || me.mass_kind != req.mass_kind {
        return Err(inconsistent(
            METHOD,
            format!(
                "method {:?}/{:?} differs from header request {:?}/{:?}",
                me.method, me.mass_kind, req.method, req.mass_kind
            ),
        ));
    }
    for (q, itf) in me.interface.iter().enumerate() {
        index(METHOD, format!("interface[{q}].node"), itf.node, n)?;
        if !body.nodes[itf.node as usize].interface {
            return Err(inconsistent(
                METHOD,
                format!(
                    "interface[{q}] names node {} whose interface flag is false",
                    itf.node
                ),
            ));
        }
        let a = &itf.frame;
        finite(METHOD, &format!("interface[{q}].frame"), a.iter().flatten())?;
        for i in 0..3 {
            for j in 0..3 {
                let dot: f64 = (0..3).map(|k| a[i][k] * a[j][k]).sum();
                let target = if i == j { 1.0 } else { 0.0 };
                if (dot - target).abs() > FRAME_TOL {
                    return Err(inconsistent(
                        METHOD,
                        format!(
                            "interface[{q}].frame is not orthonormal (row {i} · row {j} = {dot})"
                        ),
                    ));
                }
            }
        }
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        if det <= 0.0 {
            return Err(inconsistent(
                METHOD,
                format!("interface[{q}].frame is left-handed (det = {det})"),
            ));
        }
    }
    for (q, rc) in me.reference_conditions.iter().enumerate() {
        index(
            METHOD,
            format!("reference_conditions[{q}].node"),
            rc.node,
            n,
        )?;
    }
    for (name, v) in [
        ("fmax_hz", me.cutoffs.fmax_hz),
        ("shift_fraction", me.cutoffs.shift_fraction),
        ("dependency_tolerance", me.cutoffs.dependency_tolerance),
    ] {
        if let Some(x) = v {
            if !x.is_finite() {
                return Err(ReadError::NonFinite {
                    entry: METHOD.into(),
                    field: format!("cutoffs.{name}"),
                    index: 0,
                    value: x,
                });
            }
        }
    }
    counts_and_cutoffs(body)?;

    if let Some(s) = &body.stress_shapes {
        field_shapes(STRESS_SHAPES, s, n, m)?;
    }
    if let Some(s) = &body.strain_shapes {
        field_shapes(STRAIN_SHAPES, s, n, m)?;
    }
    for (entry, bottom, top, top_entry) in [
        (
            STRESS_SHAPES_BOTTOM,
            &body.stress_shapes_bottom,
            &body.stress_shapes,
            STRESS_SHAPES,
        ),
        (
            STRAIN_SHAPES_BOTTOM,
            &body.strain_shapes_bottom,
            &body.strain_shapes,
            STRAIN_SHAPES,
        ),
    ] {
        let Some(b) = bottom else { continue };
        field_shapes(entry, b, n, m)?;
        // the bottom fibre's nodes are shell nodes whose top fibre is in the top entry
        let Some(t) = top else {
            return Err(inconsistent(entry, format!("present without {top_entry}")));
        };
        if let Some(p) = b.nodes.iter().find(|p| t.nodes.binary_search(p).is_err()) {
            return Err(inconsistent(
                entry,
                format!("node {p} has a bottom fibre but no value in {top_entry}"),
            ));
        }
    }
    if let Some(d) = &body.damping {
        count(DAMPING, "ratio", d.ratio.len(), m, "one per mode")?;
        finite(DAMPING, "ratio", &d.ratio)?;
        if let Some((j, r)) = d.ratio.iter().enumerate().find(|(_, r)| **r < 0.0) {
            return Err(inconsistent(
                DAMPING,
                format!("ratio[{j}] is negative ({r})"),
            ));
        }
    }
    if let Some(s) = &body.label_shares {
        label_shares(s, body)?;
    }
    if let Some(ml) = &body.modal_loads {
        modal_loads(ml, &body.modes.labels)?;
    }
    if let Some(r) = &body.recipe {
        recipe(r, body)?;
    }
    if let Some(i) = &body.interfaces {
        crate::interfaces::validate_interfaces(i, body)?;
    }
    if let Some(g) = &body.geometric_stiffness {
        geometric_stiffness(g, body)?;
    }
    if let Some(e) = &body.eigen_residuals {
        eigen_residuals(e, body)?;
    }
    Ok(())
}

/// Rule 8, second part (SPEC.md §5.7): the counts add up and the cutoffs are the method's.
fn counts_and_cutoffs(body: &ReducedBody) -> Result<(), ReadError> {
    use crate::types::{Method, ModeLabel};
    let me = &body.method;
    let c = &me.counts;
    let m = body.modes.omega2.len() as u64;
    let rigid = body
        .modes
        .labels
        .iter()
        .filter(|l| **l == ModeLabel::Rigid)
        .count() as u64;
    let bad = |rule: String| Err(inconsistent(METHOD, rule));
    if c.rigid != rigid {
        return bad(format!(
            "counts.rigid = {} but {rigid} modes are labelled Rigid",
            c.rigid
        ));
    }
    // Exact sums (u128: three u64 cannot overflow it), so every reader computes the same.
    let sum = |v: &[u64]| v.iter().map(|&x| u128::from(x)).sum::<u128>();
    let (zero, basis): (&[(&str, u64)], u128) = match me.method {
        Method::NormalModes => (
            &[
                ("constraint", c.constraint),
                ("fixed_interface", c.fixed_interface),
                ("attachment", c.attachment),
            ],
            sum(&[c.rigid, c.normal]),
        ),
        Method::CraigBampton => (
            &[("normal", c.normal), ("attachment", c.attachment)],
            sum(&[c.constraint, c.fixed_interface]),
        ),
        Method::CraigChang | Method::Dietz => (
            &[
                ("constraint", c.constraint),
                ("fixed_interface", c.fixed_interface),
            ],
            sum(&[c.rigid, c.normal, c.attachment]),
        ),
    };
    if let Some((name, v)) = zero.iter().find(|(_, v)| *v != 0) {
        return bad(format!("counts.{name} = {v} must be 0 for {:?}", me.method));
    }
    // Normal modes count residual vectors removed as dependent since 1.6 (0 before).
    let v = body.version;
    if me.method == Method::NormalModes && c.removed_dependent > 0 && (v.major, v.minor) < (1, 6) {
        return bad(format!(
            "counts.removed_dependent = {} must be 0 for NormalModes in a {}.{} file (counted since 1.6)",
            c.removed_dependent, v.major, v.minor
        ));
    }
    let (removed, m) = (u128::from(c.removed_dependent), u128::from(m));
    let ok = if me.method == Method::NormalModes {
        basis == m + removed
    } else {
        basis >= m + removed
    };
    if !ok {
        return bad(format!(
            "counts give {} basis vectors (after {removed} removed) for {m} modes",
            basis as i128 - removed as i128
        ));
    }
    let cut = &me.cutoffs;
    if cut.fmax_hz != body.header.request.fmax_hz {
        return bad(format!(
            "cutoffs.fmax_hz {:?} differs from the requested fmax {:?}",
            cut.fmax_hz, body.header.request.fmax_hz
        ));
    }
    for (name, value, wanted) in [
        (
            "shift_fraction",
            cut.shift_fraction,
            me.method == Method::Dietz,
        ),
        (
            "dependency_tolerance",
            cut.dependency_tolerance,
            me.method != Method::NormalModes,
        ),
    ] {
        match value {
            None if wanted => return bad(format!("cutoffs.{name} missing for {:?}", me.method)),
            Some(_) if !wanted => {
                return bad(format!("cutoffs.{name} present for {:?}", me.method))
            }
            Some(v) if !(v > 0.0 && v < 1.0) => {
                return bad(format!("cutoffs.{name} = {v} must lie in (0, 1)"))
            }
            _ => {}
        }
    }
    Ok(())
}
