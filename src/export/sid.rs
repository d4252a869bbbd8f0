//! SID export: Wallrapp's *Standard Input Data* of a flexible body (`.SID_FEM` text;
//! Wallrapp 1993, Schwertassek & Wallrapp, *Dynamik flexibler Mehrkörpersysteme*, Table 6.9),
//! as EMBSlib reads it. Every body term is a Taylor expansion in the modal coordinates q,
//! T(q) = T⁰ + Σ_k T¹_k q_k, computed from the file's inertia invariants (which sum over every
//! mass node of the model, not only the stored ones). Flexible modes only (the reference frame
//! carries the rigid-body motion), indices r, s over them, j = F(r) the file's mode:
//!
//! | term | size, order | T⁰ | T¹_k |
//! |---|---|---|---|
//! | `mdCM` | 3×1, 1 | I2 | I3 column k |
//! | `J` | 6×1, 1 | I7 (xx yy zz xy xz yz) | −(I8_k + I8_kᵀ) |
//! | `Ct` | q×3, 0 (1 with K̂_G) | I3ᵀ | (r, k, a): K̂_G of `Acceleration(a)` (r, k) |
//! | `Cr` | q×3, 1 | I4ᵀ | row r: I5_k column j (Σ m φ̃_k φ_j), + K̂_G of `AngularAcceleration(a)` |
//! | `Me`, `Ke` | q×q, 0 | I6, Φᵀ K Φ | — |
//! | `Gr` | 3×3q, 0 | block s: −2 I8_s | — |
//! | `Ge` | q×3q, 0 | (r, 3s+a): 2 Cr¹(r, s, a) | — |
//! | `Oe` | q×6, 1 | row r: sym(I8_j) as xx yy zz 2xy 2yz 2xz | sym(I9_kj), same order, + K̂_G of `AngularVelocity` |
//! | `De` | q×q, 0 | diag 2 ζ ω m | — |
//! | `ksigma` | q×1, 0 | 0 (no preload) | — |
//!
//! Geometric stiffening (format 1.7 `geometric_stiffness.bin`, SPEC §5.16; when the file has
//! it): SID carries the stiffness of the stress of the body's inertia loads as the first-order
//! terms of the inertia coefficients that multiply those loads (Schwertassek & Wallrapp §6.6;
//! welib's FEM-to-SID writer puts the stiffening of the ω products into `Oe`¹ and of the
//! frame's acceleration into `Ct`¹ the same way): the equations hold `Ct a + Cr α + Oe ω̄` on
//! the side of `Ke q`, so the part of `Ct`¹, `Cr`¹, `Oe`¹ linear in q adds Σ_j s_j K̂_G,j q to
//! `Ke q` — with s_j the frame's acceleration a_a, angular acceleration α_a and the product
//! ω_iω_j of the column. `ksigma` stays 0: the preload of a preloaded build is already in `Ke`
//! (its modes are those of K + K_G(σ₀)).
//!
//! Conventions (those of EMBSlib's reader and flexible body, `EMBSlib/Components.mo`): first-order
//! entries are written `m1(row, mode, column)`; `J` is the 6-vector xx yy zz xy xz yz of the
//! inertia tensor (true tensor: negative products); `Oe` multiplies (ωx², ωy², ωz², ωxωy, ωyωz,
//! ωxωz); `Gr` and `Ge` hold one 3-column block per mode. Numbers in Fortran `D` notation with 17
//! significant digits (round-trip exact); zero entries are omitted (SID's default is zero).
//! Frames (`new node`): the interface nodes, or every stored node when the file flags none, each
//! with `origin` (order 1: position, translational shape), `phi`, `psi` and `AP` (order 1:
//! identity, skew of the rotational shape).
use std::fmt::Write as _;
use std::path::Path;

use flexbody_reader::{ReducedBody, UnitLoad};

use super::{flexible_modes, write_atomic, ExportError, ExportSummary};

/// Writes the `.SID_FEM` text of `body` to `path` (temp file + rename).
pub fn export_sid(body: &ReducedBody, path: &Path) -> Result<ExportSummary, ExportError> {
    let (text, summary) = sid_fem(body)?;
    write_atomic(path, text.as_bytes())?;
    Ok(summary)
}

fn unsupported(reason: impl Into<String>) -> ExportError {
    ExportError::Unsupported {
        target: "sid",
        reason: reason.into(),
    }
}

/// A number in Fortran `D` notation with 17 significant digits: ` 1.2345678901234567D-05`
/// (a leading blank for non-negative values, as SID files are written).
fn fortran(x: f64) -> String {
    let s = format!("{x:.16e}");
    // `{:e}` writes one 'e' for every finite value (the reader refuses non-finite ones).
    let (mantissa, exponent) = s.split_once('e').unwrap_or((s.as_str(), "0"));
    let e: i32 = exponent.parse().unwrap_or(0);
    let sign = if e < 0 { '-' } else { '+' };
    let lead = if mantissa.starts_with('-') { "" } else { " " };
    format!("{lead}{mantissa}D{sign}{:02}", e.abs())
}

/// One Taylor block being written: the header, then entries.
struct Taylor<'a> {
    s: &'a mut String,
    indent: &'static str,
}

impl<'a> Taylor<'a> {
    #[allow(clippy::too_many_arguments)]
    fn open(
        s: &'a mut String,
        indent: &'static str,
        name: &str,
        order: usize,
        nrow: usize,
        ncol: usize,
        nq: usize,
        structure: usize,
    ) -> Self {
        // `write!` into a String cannot fail; the results are ignored on purpose.
        let _ = writeln!(s, "{indent}{name}");
        for (key, v) in [
            ("order", order),
            ("nrow", nrow),
            ("ncol", ncol),
            ("nq", nq),
            ("nqn", 0),
            ("structure", structure),
        ] {
            let _ = writeln!(s, "{indent}     {key:<22}= {v:4}");
        }
        Taylor { s, indent }
    }

    fn m0(&mut self, r: usize, c: usize, v: f64) {
        if v != 0.0 {
            let key = format!("m0( {}, {})", r + 1, c + 1);
            let _ = writeln!(self.s, "{}     {key:<22}={}", self.indent, fortran(v));
        }
    }

    fn m1(&mut self, r: usize, k: usize, c: usize, v: f64) {
        if v != 0.0 {
            let key = format!("m1( {}, {}, {})", r + 1, k + 1, c + 1);
            let _ = writeln!(self.s, "{}     {key:<22}={}", self.indent, fortran(v));
        }
    }

    fn close(self, name: &str) {
        let _ = writeln!(self.s, "{}end {name}", self.indent);
    }
}

/// The six components of a symmetric 3×3 tensor in the order of `J`: xx yy zz xy xz yz.
fn j_order(t: &[f64]) -> [f64; 6] {
    [t[0], t[4], t[8], t[1], t[2], t[5]]
}

/// The six coefficients of ωᵀ S ω for the products of `Oe` (ωx², ωy², ωz², ωxωy, ωyωz, ωxωz)
/// of the symmetric part S of `t`.
fn oe_order(t: &[f64]) -> [f64; 6] {
    [t[0], t[4], t[8], t[1] + t[3], t[5] + t[7], t[2] + t[6]]
}

/// The `.SID_FEM` text and the summary (no file written).
pub fn sid_fem(body: &ReducedBody) -> Result<(String, ExportSummary), ExportError> {
    let inv = &body.invariants;
    if let Some(k) = inv.mask.iter().position(|&m| !m) {
        return Err(unsupported(format!(
            "SID's first-order terms need all nine inertia invariants; the file lacks I{} \
             (rebuild with --invariants full)",
            k + 1
        )));
    }
    let flex = flexible_modes(body);
    if flex.is_empty() {
        return Err(unsupported("the file has no flexible modes"));
    }
    let (frames, notes) = frames(body);
    let mut s = String::new();
    write_refmod(&mut s, body, &flex, frames.len());
    write_frames(&mut s, body, &flex, &frames);
    let terms = Terms {
        inv,
        m: body.mode_count(),
        geometric: body.geometric_stiffness.as_ref(),
    };
    write_inertia_terms(&mut s, &terms, &flex);
    write_stiffness_and_damping(&mut s, body, &flex);
    let _ = writeln!(s, "      end modal");
    let _ = writeln!(s, " end part");
    Ok((
        s,
        ExportSummary {
            modes: flex.len(),
            nodes: frames.len(),
            notes,
        },
    ))
}

/// The stored nodes written as SID frames — the interface nodes, or every node when the file
/// flags none — and the notes about them.
fn frames(body: &ReducedBody) -> (Vec<usize>, Vec<String>) {
    let n = body.node_count();
    let mut notes = Vec::new();
    let mut frames: Vec<usize> = (0..n).filter(|&p| body.nodes[p].interface).collect();
    if frames.is_empty() {
        frames = (0..n).collect();
        notes.push(format!(
            "the file flags no interface node: all {n} stored nodes are written as SID frames"
        ));
    }
    if let Some(nd) = frames
        .iter()
        .map(|&p| &body.nodes[p])
        .find(|nd| nd.id > 99_999)
    {
        notes.push(format!(
            "node id {} has more than 5 digits: EMBSlib's reader reads at most 5 (renumber the \
             model if you load the file there)",
            nd.id
        ));
    }
    (frames, notes)
}

/// The header and `refmod`: mass, the flexible modes with their frequencies.
fn write_refmod(s: &mut String, body: &ReducedBody, flex: &[usize], frames: usize) {
    let nq = flex.len();
    let _ = writeln!(
        s,
        "{:6} {:4}    :No. nodes, No. modes: written by {} {}",
        frames, nq, body.generator.name, body.generator.version
    );
    let _ = writeln!(s, " part");
    let _ = writeln!(s, "      new modal                                 =");
    let _ = writeln!(s, "           refmod");
    let _ = writeln!(
        s,
        "                mass                            ={}",
        fortran(body.invariants.i1[0])
    );
    let _ = writeln!(
        s,
        "                nelastq                         = {nq:5}"
    );
    for (r, &j) in flex.iter().enumerate() {
        let _ = writeln!(
            s,
            "                ielastq ({:4})                  = Eigen Mode {:4} : {:14.6} Hz",
            r + 1,
            j + 1,
            body.modes.frequency_hz[j]
        );
    }
    let _ = writeln!(s, "           end refmod");
}

/// `frame`: per frame node its `origin`, `phi`, `psi` and `AP`.
fn write_frames(s: &mut String, body: &ReducedBody, flex: &[usize], frames: &[usize]) {
    let (n, nq) = (body.node_count(), flex.len());
    let shapes = &body.modes.shapes;
    let shape = |j: usize, p: usize, c: usize| shapes[(j * n + p) * 6 + c];
    let _ = writeln!(s, "           frame");
    const NODE: &str = "                     ";
    for &p in frames {
        let nd = &body.nodes[p];
        let _ = writeln!(
            s,
            "                new node                        = {:7}",
            nd.id
        );
        let _ = writeln!(s, "{NODE}rframe                     =    body ref");
        let mut t = Taylor::open(s, NODE, "origin", 1, 3, 1, nq, 3);
        for a in 0..3 {
            t.m0(a, 0, nd.xyz[a]);
        }
        for a in 0..3 {
            for (r, &j) in flex.iter().enumerate() {
                t.m1(a, r, 0, shape(j, p, a));
            }
        }
        t.close("origin");
        for (name, c0) in [("phi", 0), ("psi", 3)] {
            let mut t = Taylor::open(s, NODE, name, 0, 3, nq, nq, 3);
            for a in 0..3 {
                for (r, &j) in flex.iter().enumerate() {
                    t.m0(a, r, shape(j, p, c0 + a));
                }
            }
            t.close(name);
        }
        let mut t = Taylor::open(s, NODE, "AP", 1, 3, 3, nq, 3);
        for a in 0..3 {
            t.m0(a, a, 1.0);
        }
        for a in 0..3 {
            for (r, &j) in flex.iter().enumerate() {
                let w = [shape(j, p, 3), shape(j, p, 4), shape(j, p, 5)];
                let skew = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
                for (b, &v) in skew[a].iter().enumerate() {
                    t.m1(a, r, b, v);
                }
            }
        }
        t.close("AP");
        let _ = writeln!(s, "                end node");
    }
    let _ = writeln!(s, "           end frame");
}

/// The invariants of the file by index (m modes), as the SID terms read them, and its modal
/// geometric stiffness when it has one.
struct Terms<'a> {
    inv: &'a flexbody_reader::Invariants,
    m: usize,
    geometric: Option<&'a flexbody_reader::GeometricStiffness>,
}

/// The angular-velocity products of `Oe`'s columns (ωx², ωy², ωz², ωxωy, ωyωz, ωxωz) as the
/// file's unit loads.
const OE_PRODUCTS: [[u8; 2]; 6] = [[0, 0], [1, 1], [2, 2], [0, 1], [1, 2], [0, 2]];

impl Terms<'_> {
    fn i3(&self, a: usize, j: usize) -> f64 {
        self.inv.i3[a * self.m + j]
    }
    fn i4(&self, a: usize, j: usize) -> f64 {
        self.inv.i4[a * self.m + j]
    }
    fn i5(&self, j: usize, a: usize, k: usize) -> f64 {
        self.inv.i5[(j * 3 + a) * self.m + k]
    }
    fn i8(&self, j: usize) -> &[f64] {
        &self.inv.i8[j * 9..j * 9 + 9]
    }
    fn i9(&self, j: usize, k: usize) -> &[f64] {
        let at = (j * self.m + k) * 9;
        &self.inv.i9[at..at + 9]
    }
    /// K̂_G(j, k) of `load` (file modes j, k); 0 when the file has no such field.
    fn kg(&self, load: UnitLoad, j: usize, k: usize) -> f64 {
        self.field(load).map_or(0.0, |f| f.matrix[j * self.m + k])
    }
    fn field(&self, load: UnitLoad) -> Option<&flexbody_reader::GeometricField> {
        self.geometric?.fields.iter().find(|f| f.load == load)
    }
}

/// The inertia terms from the invariants: `mdCM`, `J`, `Ct`, `Cr`, `Me`, `Gr`, `Ge`, `Oe`.
fn write_inertia_terms(s: &mut String, terms: &Terms, flex: &[usize]) {
    let (inv, m, nq) = (terms.inv, terms.m, flex.len());
    const BODY: &str = "           ";
    let mut t = Taylor::open(s, BODY, "mdCM", 1, 3, 1, nq, 3);
    for a in 0..3 {
        t.m0(a, 0, inv.i2[a]);
    }
    for a in 0..3 {
        for (r, &j) in flex.iter().enumerate() {
            t.m1(a, r, 0, terms.i3(a, j));
        }
    }
    t.close("mdCM");

    let mut t = Taylor::open(s, BODY, "J", 1, 6, 1, nq, 3);
    for (c, v) in j_order(&inv.i7).into_iter().enumerate() {
        t.m0(c, 0, v);
    }
    let j1: Vec<[f64; 6]> = flex
        .iter()
        .map(|&j| {
            let c = terms.i8(j);
            let mut sym = [0.0; 9];
            for a in 0..3 {
                for b in 0..3 {
                    sym[a * 3 + b] = -(c[a * 3 + b] + c[b * 3 + a]);
                }
            }
            j_order(&sym)
        })
        .collect();
    for c in 0..6 {
        for (r, v) in j1.iter().enumerate() {
            t.m1(c, r, 0, v[c]);
        }
    }
    t.close("J");

    let acceleration = (0..3).any(|a| terms.field(UnitLoad::Acceleration(a)).is_some());
    let mut t = Taylor::open(s, BODY, "Ct", usize::from(acceleration), nq, 3, nq, 3);
    for (r, &j) in flex.iter().enumerate() {
        for a in 0..3 {
            t.m0(r, a, terms.i3(a, j));
        }
    }
    // geometric stiffening of the frame's acceleration (module doc)
    for (r, &j) in flex.iter().enumerate() {
        for (s_, &k) in flex.iter().enumerate() {
            for a in 0..3u8 {
                t.m1(r, s_, a.into(), terms.kg(UnitLoad::Acceleration(a), j, k));
            }
        }
    }
    t.close("Ct");

    // Cr¹(r, s, a) = (Σ m φ̃_k φ_j)_a with k = F(s), j = F(r).
    let cr1 = |r: usize, s_: usize, a: usize| terms.i5(flex[s_], a, flex[r]);
    let mut t = Taylor::open(s, BODY, "Cr", 1, nq, 3, nq, 3);
    for (r, &j) in flex.iter().enumerate() {
        for a in 0..3 {
            t.m0(r, a, terms.i4(a, j));
        }
    }
    for r in 0..nq {
        for s_ in 0..nq {
            for a in 0..3u8 {
                let stiffening = terms.kg(UnitLoad::AngularAcceleration(a), flex[r], flex[s_]);
                let a = usize::from(a);
                t.m1(r, s_, a, cr1(r, s_, a) + stiffening);
            }
        }
    }
    t.close("Cr");

    let mut t = Taylor::open(s, BODY, "Me", 0, nq, nq, nq, 3);
    for (r, &j) in flex.iter().enumerate() {
        for (c, &k) in flex.iter().enumerate() {
            t.m0(r, c, inv.i6[j * m + k]);
        }
    }
    t.close("Me");

    let mut t = Taylor::open(s, BODY, "Gr", 0, 3, 3 * nq, nq, 3);
    for (r, &j) in flex.iter().enumerate() {
        let c = terms.i8(j);
        for a in 0..3 {
            for b in 0..3 {
                t.m0(a, 3 * r + b, -2.0 * c[a * 3 + b]);
            }
        }
    }
    t.close("Gr");

    let mut t = Taylor::open(s, BODY, "Ge", 0, nq, 3 * nq, nq, 3);
    for r in 0..nq {
        for s_ in 0..nq {
            for a in 0..3 {
                t.m0(r, 3 * s_ + a, 2.0 * cr1(r, s_, a));
            }
        }
    }
    t.close("Ge");

    let mut t = Taylor::open(s, BODY, "Oe", 1, nq, 6, nq, 3);
    for (r, &j) in flex.iter().enumerate() {
        for (c, v) in oe_order(terms.i8(j)).into_iter().enumerate() {
            t.m0(r, c, v);
        }
    }
    for (r, &j) in flex.iter().enumerate() {
        for (s_, &k) in flex.iter().enumerate() {
            for (c, v) in oe_order(terms.i9(k, j)).into_iter().enumerate() {
                let stiffening = terms.kg(UnitLoad::AngularVelocity(OE_PRODUCTS[c]), j, k);
                t.m1(r, s_, c, v + stiffening);
            }
        }
    }
    t.close("Oe");
}

/// `ksigma` (no preload), `Ke` = Φᵀ K Φ and `De` (diag 2 ζ ω m, when the file has damping).
fn write_stiffness_and_damping(s: &mut String, body: &ReducedBody, flex: &[usize]) {
    let (m, nq) = (body.mode_count(), flex.len());
    let gm = &body.modes.generalized_mass;
    let gk = &body.modes.generalized_stiffness;
    const BODY: &str = "           ";
    let t = Taylor::open(s, BODY, "ksigma", 0, nq, 1, nq, 0);
    t.close("ksigma");

    let mut t = Taylor::open(s, BODY, "Ke", 0, nq, nq, nq, 3);
    for (r, &j) in flex.iter().enumerate() {
        for (c, &k) in flex.iter().enumerate() {
            t.m0(r, c, gk[j * m + k]);
        }
    }
    t.close("Ke");

    match &body.damping {
        Some(d) => {
            let mut t = Taylor::open(s, BODY, "De", 0, nq, nq, nq, 3);
            for (r, &j) in flex.iter().enumerate() {
                let omega = body.modes.omega2[j].max(0.0).sqrt();
                t.m0(r, r, 2.0 * d.ratio[j] * omega * gm[j * m + j]);
            }
            t.close("De");
        }
        None => {
            let t = Taylor::open(s, BODY, "De", 0, nq, nq, nq, 0);
            t.close("De");
        }
    }
}
