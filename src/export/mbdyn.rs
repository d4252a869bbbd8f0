//! MBDyn export: the modal element's FEM file (`.fem`, MBDyn input manual, "Modal Element
//! Data — FEM File Format"): record groups 1–12, and 13 (modal damping) when the file has
//! damping. Flexible modes only (the modal node carries the rigid-body motion), every stored
//! node exposed, numbers in Rust's shortest round-trip notation. Laid out as MBDyn's `femgen`
//! writes it (the manual's example): a bare `**` line before each record group's title, no
//! trailing blanks — readers that count lines (Blender's Blendyn) need exactly that.
//!
//! * 8: mode shapes, 6 components per node (x y z rx ry rz, linearized rotations);
//! * 9, 10: generalized mass Φᵀ M Φ and stiffness Φᵀ K Φ of the flexible modes;
//! * 11: diagonal of the lumped mass per node (m m m Ixx Iyy Izz) — off-diagonal nodal inertia
//!   cannot be expressed there (a note says so);
//! * 12: mass I1, centre of mass I2/I1, and the inertia tensor about the centre of mass,
//!   J = I7 − m (|c|² 1 − c cᵀ) (exact, from the invariants, which MBDyn prefers over 11);
//! * 13: modal damping c_jj = 2 ζ_j ω_j m_jj.
use std::fmt::Write as _;
use std::path::Path;

use flexbody_reader::ReducedBody;

use super::{flexible_modes, write_atomic, ExportError, ExportSummary};

/// Writes the MBDyn `.fem` file of `body` to `path` (temp file + rename).
pub fn export_mbdyn(body: &ReducedBody, path: &Path) -> Result<ExportSummary, ExportError> {
    let (text, summary) = mbdyn_fem(body)?;
    write_atomic(path, text.as_bytes())?;
    Ok(summary)
}

fn unsupported(reason: impl Into<String>) -> ExportError {
    ExportError::Unsupported {
        target: "mbdyn",
        reason: reason.into(),
    }
}

/// The `.fem` text and the summary (no file written).
pub fn mbdyn_fem(body: &ReducedBody) -> Result<(String, ExportSummary), ExportError> {
    let inv = &body.invariants;
    for k in [0, 1, 6] {
        if !inv.mask[k] {
            return Err(unsupported(format!(
                "record group 12 needs invariant I{}; the file lacks it",
                k + 1
            )));
        }
    }
    let n = body.node_count();
    let big_m = body.mode_count();
    let flex = flexible_modes(body);
    let m = flex.len();
    if m == 0 {
        return Err(unsupported("the file has no flexible modes"));
    }
    if n == 0 {
        return Err(unsupported("the file stores no nodes"));
    }
    let mut notes = Vec::new();
    let mut s = String::new();
    // femgen's layout: a bare `**` line closes each record group, before the next title.
    // Readers that step over fixed line counts (Blender's Blendyn: "title, then values") need
    // it; MBDyn itself skips every `**` line that is not a title.
    let sep = |s: &mut String| {
        let _ = writeln!(s, "**");
    };
    // `write!` into a String cannot fail; the results are ignored on purpose.
    let u = &body.units;
    let _ = writeln!(s, "** MBDyn MODAL DATA FILE");
    let _ = writeln!(
        s,
        "** written by {} {} from a .flexbody file ({}); units: {} {} {} {}",
        body.generator.name,
        body.generator.version,
        body.header.title.replace('\n', " "),
        u.mass.name,
        u.length.name,
        u.time.name,
        u.force.name
    );
    let _ = writeln!(
        s,
        "** {m} flexible modes of the file's {big_m} (rigid-body modes are the modal node's motion)"
    );
    sep(&mut s);
    let _ = writeln!(s, "** RECORD GROUP 1, HEADER");
    let _ = writeln!(
        s,
        "**   REVISION,  NODE,  NORMAL, ATTACHMENT, CONSTRAINT, REJECTED MODES."
    );
    let _ = writeln!(s, "REV0 {n} {m} 0 0 0");
    sep(&mut s);
    let _ = writeln!(s, "** RECORD GROUP 2, FINITE ELEMENT NODE LIST");
    for chunk in body.nodes.chunks(6) {
        let ids: Vec<String> = chunk.iter().map(|nd| nd.id.to_string()).collect();
        let _ = writeln!(s, "{}", ids.join(" "));
    }
    sep(&mut s);
    let _ = writeln!(s, "** RECORD GROUP 3, INITIAL MODAL DISPLACEMENTS");
    let zeros = vec!["0"; m].join(" ");
    let _ = writeln!(s, "{zeros}");
    sep(&mut s);
    let _ = writeln!(s, "** RECORD GROUP 4, INITIAL MODAL VELOCITIES");
    let _ = writeln!(s, "{zeros}");
    for (c, axis) in ["X", "Y", "Z"].iter().enumerate() {
        sep(&mut s);
        let _ = writeln!(s, "** RECORD GROUP {}, NODAL {axis} COORDINATES", 5 + c);
        for nd in &body.nodes {
            let _ = writeln!(s, "{:e}", nd.xyz[c]);
        }
    }
    sep(&mut s);
    let _ = writeln!(s, "** RECORD GROUP 8, NON-ORTHOGONALIZED MODE SHAPES");
    let shapes = &body.modes.shapes;
    for (i, &j) in flex.iter().enumerate() {
        let _ = writeln!(s, "**    NORMAL MODE SHAPE #  {}", i + 1);
        for p in 0..n {
            let v = &shapes[(j * n + p) * 6..(j * n + p) * 6 + 6];
            let _ = writeln!(
                s,
                "{:e} {:e} {:e} {:e} {:e} {:e}",
                v[0], v[1], v[2], v[3], v[4], v[5]
            );
        }
    }
    let matrix = |s: &mut String, title: &str, value: &dyn Fn(usize, usize) -> f64| {
        sep(s);
        let _ = writeln!(s, "{title}");
        // Column-major: line c holds column c (rows 1…m).
        for c in 0..m {
            let col: Vec<String> = (0..m).map(|r| format!("{:e}", value(r, c))).collect();
            let _ = writeln!(s, "{}", col.join(" "));
        }
    };
    let gm = &body.modes.generalized_mass;
    let gk = &body.modes.generalized_stiffness;
    matrix(
        &mut s,
        "** RECORD GROUP 9, MODAL MASS MATRIX. COLUMN-MAJOR FORM",
        &|r, c| gm[flex[r] * big_m + flex[c]],
    );
    matrix(
        &mut s,
        "** RECORD GROUP 10, MODAL STIFFNESS MATRIX. COLUMN-MAJOR FORM",
        &|r, c| gk[flex[r] * big_m + flex[c]],
    );
    sep(&mut s);
    let _ = writeln!(s, "** RECORD GROUP 11, DIAGONAL OF LUMPED MASS MATRIX");
    let mut off_diagonal = 0.0f64;
    let mut diagonal = 0.0f64;
    for nm in &body.nodal_mass {
        let i = nm.inertia;
        let _ = writeln!(
            s,
            "{:e} {:e} {:e} {:e} {:e} {:e}",
            nm.mass, nm.mass, nm.mass, i[0][0], i[1][1], i[2][2]
        );
        off_diagonal = off_diagonal.max(i[0][1].abs().max(i[0][2].abs()).max(i[1][2].abs()));
        diagonal = diagonal.max(i[0][0].abs().max(i[1][1].abs()).max(i[2][2].abs()));
    }
    if off_diagonal > 1e-12 * diagonal {
        notes.push(format!(
            "record group 11 holds the diagonal of each nodal inertia only (largest off-diagonal dropped: {off_diagonal:e}); record group 12 has the exact body inertia"
        ));
    }
    if body.header.request.mass_kind == flexbody_reader::MassKind::Consistent {
        notes.push(
            "the file was built with consistent mass: record group 11 (lumped nodal masses) is not the mass matrix the modes are orthonormal in".into(),
        );
    }
    let mass = inv.i1[0];
    if mass.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(unsupported(format!(
            "the body's mass I1 = {mass} is not positive"
        )));
    }
    let c = [inv.i2[0] / mass, inv.i2[1] / mass, inv.i2[2] / mass];
    let c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    sep(&mut s);
    let _ = writeln!(s, "** RECORD GROUP 12, GLOBAL INERTIA PROPERTIES");
    let _ = writeln!(s, "{mass:e}");
    let _ = writeln!(s, "{:e} {:e} {:e}", c[0], c[1], c[2]);
    for a in 0..3 {
        let row: Vec<String> = (0..3)
            .map(|b| {
                let delta = if a == b { 1.0 } else { 0.0 };
                format!(
                    "{:e}",
                    inv.i7[a * 3 + b] - mass * (c2 * delta - c[a] * c[b])
                )
            })
            .collect();
        let _ = writeln!(s, "{}", row.join(" "));
    }
    if let Some(d) = &body.damping {
        let omega2 = &body.modes.omega2;
        matrix(
            &mut s,
            "** RECORD GROUP 13, MODAL DAMPING MATRIX. COLUMN-MAJOR FORM",
            &|r, c| {
                if r == c {
                    let j = flex[r];
                    2.0 * d.ratio[j] * omega2[j].max(0.0).sqrt() * gm[j * big_m + j]
                } else {
                    0.0
                }
            },
        );
    }
    sep(&mut s);
    let _ = writeln!(s, "** END OF FILE");
    Ok((
        s,
        ExportSummary {
            modes: m,
            nodes: n,
            notes,
        },
    ))
}
