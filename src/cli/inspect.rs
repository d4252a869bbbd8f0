//! `flexbody inspect`: a plain summary of a reduced-body file — header, units, counts, mass
//! properties, modes, invariant set, entry sizes. Computed here, printed by `command` (`flexbody inspect`).
//!
//! The JSON form of [`Summary`] is also the expected-content file of each golden fixture
//! (`fixtures/golden/v1.0/*.json`) that `format-spec/reference_reader.py` reproduces.
use flexbody_reader::{codec::Manifest, ReducedBody};
use serde::Serialize;

/// Counts of the main arrays.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Counts {
    /// Stored nodes.
    pub nodes: usize,
    /// Stored nodes flagged as interface.
    pub interface_nodes: usize,
    /// Graphics faces.
    pub faces: usize,
    /// Graphics lines (format 1.1; 0 when absent).
    pub lines: usize,
    /// Modes.
    pub modes: usize,
}

/// One line of the modes table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModeLine {
    /// 1-based mode number.
    pub number: usize,
    /// Frequency, Hz.
    pub frequency_hz: f64,
    /// ω², rad²/s².
    pub omega2: f64,
    /// Label (`Rigid`, `Normal`, …).
    pub label: String,
    /// Share of the labelled origin in the mode (`label_shares.bin`, format 1.2), or null.
    pub label_share: Option<f64>,
    /// Modal damping ratio (`damping.bin`), or null.
    pub damping_ratio: Option<f64>,
}

/// One container entry.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EntryLine {
    /// Entry name.
    pub name: String,
    /// Uncompressed bytes.
    pub size: u64,
    /// SHA-256 hex.
    pub sha256: String,
    /// Required flag.
    pub required: bool,
}

/// Mass properties: I1, I2/I1 and the inertia tensors (true tensors: negative products).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MassProperties {
    /// `invariants` (I1, I2, I7) or `nodal_mass` (stored nodes only).
    pub source: String,
    /// Total mass.
    pub total_mass: f64,
    /// Centre of mass (I2 / I1); zeros when the mass is zero.
    pub center_of_mass: [f64; 3],
    /// Inertia tensor about the body origin (I7), row-major.
    pub inertia_origin: [[f64; 3]; 3],
    /// Inertia tensor about the centre of mass: I7 − m((c·c)E − c cᵀ) (parallel axis).
    pub inertia_center_of_mass: [[f64; 3]; 3],
}

/// Everything `flexbody inspect` reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// `major.minor`.
    pub format_version: String,
    /// Writer program and version.
    pub generator: String,
    /// Header title.
    pub title: String,
    /// Creation time if recorded.
    pub created_utc: Option<String>,
    /// Unit system.
    pub units: flexbody_reader::Units,
    /// Method, e.g. `CraigBampton`.
    pub method: String,
    /// `Lumped` / `Consistent`.
    pub mass_kind: String,
    /// Invariant set name.
    pub invariant_set: String,
    /// Selected invariants, 1-based.
    pub invariants_present: Vec<usize>,
    /// Counts.
    pub counts: Counts,
    /// Mass properties.
    pub mass: MassProperties,
    /// Modes table.
    pub modes: Vec<ModeLine>,
    /// Optional entries present: stress, strain, damping, lines.
    pub optional: [bool; 4],
    /// Entries in container order.
    pub entries: Vec<EntryLine>,
    /// The build recipe (`recipe.json`, format 1.2), `null` when the file has none.
    pub recipe: Option<flexbody_reader::Recipe>,
    /// Interface metadata (`interfaces.bin`, format 1.3), `null` when the file has none.
    pub interfaces: Option<Vec<flexbody_reader::InterfaceInfo>>,
    /// The modal loads and residual-vector origins (`modal_loads.bin`, format 1.4); absent
    /// when the file has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modal_loads: Option<flexbody_reader::ModalLoads>,
    /// The modal geometric stiffness per unit inertia load (`geometric_stiffness.bin`, format
    /// 1.7); absent when the file has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub geometric_stiffness: Option<GeometricSummary>,
    /// The eigenproblems behind the basis with each mode's residual (`eigen_residuals.bin`,
    /// format 1.9); absent when the file has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eigen_residuals: Option<Vec<EigenSummary>>,
}

/// One problem of `eigen_residuals.bin` in the summary (SPEC §9): as decoded, with its largest
/// residual of a flexible mode.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EigenSummary {
    /// Which problem.
    pub kind: flexbody_reader::EigenProblemKind,
    /// Which solver.
    pub solver: flexbody_reader::EigenSolverKind,
    /// s (the rigid threshold is 10⁻⁸ s).
    pub scale: f64,
    /// ω² per mode.
    pub omega2: Vec<f64>,
    /// Relative residual per mode (SPEC §5.17).
    pub residual: Vec<f64>,
    /// Sylvester's count, when the band was verified.
    pub inertia: Option<flexbody_reader::InertiaCount>,
    /// The largest residual of a mode with ω² > 10⁻⁸ s; `null` when there is none.
    pub largest_flexible_residual: Option<f64>,
}

fn eigen_summary(p: &flexbody_reader::EigenProblem) -> EigenSummary {
    EigenSummary {
        kind: p.kind,
        solver: p.solver,
        scale: p.scale,
        omega2: p.omega2.clone(),
        residual: p.residual.clone(),
        inertia: p.inertia,
        largest_flexible_residual: p.largest_flexible_residual().map(|(_, r)| r),
    }
}

/// `geometric_stiffness.bin` in the summary (SPEC §9): the support and each load by name.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GeometricSummary {
    /// `Held` or `InertiaRelief`.
    pub support: flexbody_reader::StaticSupport,
    /// One per field, in the file's order.
    pub fields: Vec<GeometricFieldSummary>,
}

/// One field of [`GeometricSummary`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GeometricFieldSummary {
    /// The load's name (SPEC §5.16: `a_x`, `omega_x*omega_y`, `alpha_z`).
    pub load: String,
    /// K̂_G, row-major M·M.
    pub matrix: Vec<f64>,
}

fn geometric_summary(g: &flexbody_reader::GeometricStiffness) -> GeometricSummary {
    GeometricSummary {
        support: g.support,
        fields: (g.fields.iter())
            .map(|f| GeometricFieldSummary {
                // a validated file's loads have valid axes (rule 15)
                load: f.load.name().unwrap_or_else(|| format!("{:?}", f.load)),
                matrix: f.matrix.clone(),
            })
            .collect(),
    }
}

/// Mass properties from I1, I2, I7 when present, else from the stored nodal masses.
/// Parallel-axis theorem: J_c = J_o − m((c·c)E − c cᵀ).
pub fn mass_properties(body: &ReducedBody) -> MassProperties {
    let inv = &body.invariants;
    let (source, m, first, io) = if inv.mask[0] && inv.mask[1] && inv.mask[6] {
        let io = [
            [inv.i7[0], inv.i7[1], inv.i7[2]],
            [inv.i7[3], inv.i7[4], inv.i7[5]],
            [inv.i7[6], inv.i7[7], inv.i7[8]],
        ];
        (
            "invariants",
            inv.i1[0],
            [inv.i2[0], inv.i2[1], inv.i2[2]],
            io,
        )
    } else {
        let (mut m, mut s, mut io) = (0.0, [0.0; 3], [[0.0; 3]; 3]);
        for (node, nm) in body.nodes.iter().zip(&body.nodal_mass) {
            let x = node.xyz;
            m += nm.mass;
            let xx = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
            for i in 0..3 {
                s[i] += nm.mass * x[i];
                for j in 0..3 {
                    let delta = if i == j { xx } else { 0.0 };
                    io[i][j] += nm.mass * (delta - x[i] * x[j]) + nm.inertia[i][j];
                }
            }
        }
        ("nodal_mass", m, s, io)
    };
    let c = if m > 0.0 {
        [first[0] / m, first[1] / m, first[2] / m]
    } else {
        [0.0; 3]
    };
    let cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    let mut ic = io;
    for i in 0..3 {
        for j in 0..3 {
            let delta = if i == j { cc } else { 0.0 };
            ic[i][j] = io[i][j] - m * (delta - c[i] * c[j]);
        }
    }
    MassProperties {
        source: source.into(),
        total_mass: m,
        center_of_mass: c,
        inertia_origin: io,
        inertia_center_of_mass: ic,
    }
}

/// Builds the summary of a read body and its manifest.
pub fn summarize(body: &ReducedBody, manifest: &Manifest) -> Summary {
    let req = &body.header.request;
    Summary {
        format_version: format!("{}.{}", body.version.major, body.version.minor),
        generator: format!("{} {}", body.generator.name, body.generator.version),
        title: body.header.title.clone(),
        created_utc: body.header.created_utc.clone(),
        units: body.units.clone(),
        method: format!("{:?}", body.method.method),
        mass_kind: format!("{:?}", body.method.mass_kind),
        invariant_set: format!("{:?}", req.invariant_set),
        invariants_present: (1..=9).filter(|k| body.invariants.mask[k - 1]).collect(),
        counts: Counts {
            nodes: body.nodes.len(),
            interface_nodes: body.nodes.iter().filter(|n| n.interface).count(),
            faces: body.faces.len(),
            lines: body.lines.as_ref().map_or(0, Vec::len),
            modes: body.mode_count(),
        },
        mass: mass_properties(body),
        modes: (0..body.mode_count())
            .map(|j| ModeLine {
                number: j + 1,
                frequency_hz: body.modes.frequency_hz[j],
                omega2: body.modes.omega2[j],
                label: format!("{:?}", body.modes.labels[j]),
                label_share: body.label_shares.as_ref().map(|s| s[j]),
                damping_ratio: body.damping.as_ref().map(|d| d.ratio[j]),
            })
            .collect(),
        optional: [
            body.stress_shapes.is_some(),
            body.strain_shapes.is_some(),
            body.damping.is_some(),
            body.lines.is_some(),
        ],
        entries: manifest
            .entries
            .iter()
            .map(|e| EntryLine {
                name: e.name.clone(),
                size: e.size,
                sha256: e.sha256.clone(),
                required: e.required,
            })
            .collect(),
        recipe: body.recipe.clone(),
        interfaces: body.interfaces.clone(),
        modal_loads: body.modal_loads.clone(),
        geometric_stiffness: body.geometric_stiffness.as_ref().map(geometric_summary),
        eigen_residuals: (body.eigen_residuals.as_ref())
            .map(|e| e.problems.iter().map(eigen_summary).collect()),
    }
}

/// Human-readable text of a summary.
pub fn render_text(s: &Summary) -> String {
    use std::fmt::Write;
    let mut o = String::new();
    // Writing into a String cannot fail; the results are ignored on purpose.
    let _ = writeln!(
        o,
        "{}  (flexbody format {}, written by {})",
        s.title, s.format_version, s.generator
    );
    if let Some(t) = &s.created_utc {
        let _ = writeln!(o, "created      {t}");
    }
    let u = |x: &flexbody_reader::Unit| format!("{} (= {} SI)", x.name, x.si);
    let us = &s.units;
    let _ = writeln!(
        o,
        "units        mass {}, length {}, time {}, force {}",
        u(&us.mass),
        u(&us.length),
        u(&us.time),
        u(&us.force)
    );
    let _ = writeln!(
        o,
        "method       {} ({} mass), invariants {} {:?}",
        s.method, s.mass_kind, s.invariant_set, s.invariants_present
    );
    let c = &s.counts;
    let _ = writeln!(
        o,
        "counts       {} nodes ({} interface), {} faces, {} lines, {} modes",
        c.nodes, c.interface_nodes, c.faces, c.lines, c.modes
    );
    let mp = &s.mass;
    let _ = writeln!(
        o,
        "mass         {:.6e}  (from {})",
        mp.total_mass, mp.source
    );
    let _ = writeln!(
        o,
        "centre       [{:.6e}, {:.6e}, {:.6e}]",
        mp.center_of_mass[0], mp.center_of_mass[1], mp.center_of_mass[2]
    );
    if s.mass_kind == "Lumped" {
        // the file alone cannot tell how far a lumped mass's inertia is from the exact one
        let _ = writeln!(
            o,
            "             (lumped mass: `flexbody check FILE --model MODEL` compares this inertia with the consistent mass's)"
        );
    }
    let _ = writeln!(o, "inertia about centre of mass:");
    for row in &mp.inertia_center_of_mass {
        let _ = writeln!(
            o,
            "             [{:>14.6e} {:>14.6e} {:>14.6e}]",
            row[0], row[1], row[2]
        );
    }
    let _ = writeln!(o, "modes        #      frequency [Hz]   label");
    for m in &s.modes {
        let share = match m.label_share {
            Some(v) if v < 0.995 => format!(" ({:.0} %)", 100.0 * v),
            _ => String::new(),
        };
        let damping = m
            .damping_ratio
            .map_or(String::new(), |z| format!("  ζ = {:.4} %", 100.0 * z));
        let _ = writeln!(
            o,
            "             {:<6} {:>15.6}   {}{share}{damping}",
            m.number, m.frequency_hz, m.label
        );
    }
    let opt: Vec<&str> = ["stress shapes", "strain shapes", "damping", "lines"]
        .iter()
        .zip(s.optional)
        .filter(|(_, p)| *p)
        .map(|(n, _)| *n)
        .collect();
    let _ = writeln!(
        o,
        "optional     {}",
        if opt.is_empty() {
            "none".to_string()
        } else {
            opt.join(", ")
        }
    );
    let _ = writeln!(o, "entries      {:<20} {:>12}  required", "name", "bytes");
    for e in &s.entries {
        let _ = writeln!(
            o,
            "             {:<20} {:>12}  {}",
            e.name,
            e.size,
            if e.required { "yes" } else { "no" }
        );
    }
    if let Some(r) = &s.recipe {
        render_recipe(&mut o, r);
    }
    if let Some(list) = &s.interfaces {
        render_interfaces(&mut o, list);
    }
    if let Some(g) = &s.geometric_stiffness {
        render_geometric(&mut o, g, s.counts.modes);
    }
    for p in s.eigen_residuals.iter().flatten() {
        render_eigen(&mut o, p);
    }
    o
}

/// One eigenproblem of the text summary: its solver, mode count, largest residual of a
/// flexible mode and of a rigid one, and the inertia count.
fn render_eigen(o: &mut String, p: &EigenSummary) {
    use std::fmt::Write;
    let rigid = (p.omega2.iter().zip(&p.residual))
        .filter(|(&l, _)| !crate::solve::is_flexible(l, p.scale))
        .map(|(_, &r)| r)
        .fold(None, |a: Option<f64>, r| Some(a.map_or(r, |a| a.max(r))));
    let _ = writeln!(
        o,
        "eigenproblem {:?} ({:?}): {} modes, largest relative residual |K phi - w2 M phi| / |K \
         phi| {}{}",
        p.kind,
        p.solver,
        p.omega2.len(),
        p.largest_flexible_residual
            .map_or("(no flexible mode)".into(), |r| format!("{r:.3e}")),
        rigid.map_or(String::new(), |r| format!(
            "; rigid modes {r:.3e} (against 1e-8 s |M phi|)"
        ))
    );
    if let Some(i) = &p.inertia {
        let _ = writeln!(
            o,
            "             Sylvester inertia count: {} eigenvalues below {:.6e} Hz",
            i.below,
            crate::solve::hz(i.shift)
        );
    }
}

/// The geometric-stiffness block of the text summary: per load its largest diagonal term
/// (mode and value: for a spin product, the largest Southwell coefficient).
fn render_geometric(o: &mut String, g: &GeometricSummary, m: usize) {
    use std::fmt::Write;
    let _ = writeln!(
        o,
        "geometric stiffness  {} unit loads ({:?} static support): K = K̂ + Σ s_j K̂_G,j",
        g.fields.len(),
        g.support
    );
    for f in &g.fields {
        let (j, v) = (0..m)
            .map(|j| (j, f.matrix[j * m + j]))
            .fold(
                (0, 0.0f64),
                |a, b| if b.1.abs() > a.1.abs() { b } else { a },
            );
        let _ = writeln!(
            o,
            "             {:<18} largest diagonal term {:>14.6e} (mode {})",
            f.load,
            v,
            j + 1
        );
    }
}

/// The interface block of the text summary (`interfaces.bin`).
fn render_interfaces(o: &mut String, list: &[flexbody_reader::InterfaceInfo]) {
    use std::fmt::Write;
    let _ = writeln!(
        o,
        "interfaces   {:<20} {:>6} {:>5} {:>10}  centre fit   (index: 0-based, nodes.bin order)",
        "name", "index", "kind", "dependent"
    );
    for i in list {
        let _ = write!(
            o,
            "             {:<20} {:>6} {:>5} {:>10}",
            i.name,
            i.node,
            format!("{:?}", i.kind).to_uppercase(),
            i.dependent.len()
        );
        if let Some(f) = &i.fit {
            let _ = write!(
                o,
                "  {:?} ({:.6e}, {:.6e}, {:.6e})",
                f.method, f.centre[0], f.centre[1], f.centre[2]
            );
            if let (Some(a), Some(r)) = (f.axis, f.radius) {
                let _ = write!(
                    o,
                    " axis ({:.6}, {:.6}, {:.6}) radius {:.6e}",
                    a[0], a[1], a[2], r
                );
            }
        }
        let _ = writeln!(o);
    }
}

/// The recipe block of the text summary.
fn render_recipe(o: &mut String, r: &flexbody_reader::Recipe) {
    use std::fmt::Write;
    let p = &r.options;
    let _ = writeln!(
        o,
        "recipe       built by {} {}",
        r.tool.name, r.tool.version
    );
    for f in &r.model_files {
        let _ = writeln!(
            o,
            "  model file {} ({}, {} bytes, SHA-256 {})",
            f.path, f.role, f.size, f.sha256
        );
    }
    let opt = |v: &Option<String>| v.clone().unwrap_or_else(|| "-".into());
    let _ = writeln!(
        o,
        "  options    (as the build resolved them: defaults and the deck's requests made explicit)\n             --method {} --modes {} --fmax {} --mass {} --beam-mass {} --units {}",
        p.method,
        p.modes.map_or("-".into(), |n| n.to_string()),
        p.fmax_hz.map_or("-".into(), |f| f.to_string()),
        p.mass,
        p.beam_mass,
        units_option(&p.units)
    );
    let _ = writeln!(
        o,
        "             --interface {} --spider {} --reference-conditions {} --reference-method {}",
        if p.interface.is_empty() {
            "-".into()
        } else {
            p.interface.join(",")
        },
        p.spider,
        if p.reference_conditions.is_empty() {
            "-".into()
        } else {
            p.reference_conditions.join(",")
        },
        p.reference_method
    );
    let _ = writeln!(
        o,
        "             --keep-nodes {} --invariants {} --stress-modes {} --format {} --material {}",
        p.keep_nodes,
        p.invariants,
        p.stress_fields,
        opt(&p.format),
        opt(&p.material)
    );
    if !p.ignore.is_empty() {
        let _ = writeln!(
            o,
            "             --ignore {} (dropped on purpose although they could change the body)",
            p.ignore.join(",")
        );
    }
    for i in &r.interfaces {
        let nodes: Vec<String> = i.nodes.iter().map(u64::to_string).collect();
        let _ = write!(o, "  interface  {} → node(s) {}", i.entry, nodes.join(","));
        if let Some(s) = &i.spider {
            let _ = write!(
                o,
                " ({} spider over {} nodes, centre ({:.6e}, {:.6e}, {:.6e}) by {}, {:.3e} {} from the node average)",
                s.kind,
                s.set_nodes.len(),
                s.centre[0],
                s.centre[1],
                s.centre[2],
                s.fit,
                s.offset_from_node_average,
                p.units.length.name
            );
        }
        let _ = writeln!(o);
    }
    let _ = writeln!(
        o,
        "  accurate   0 – {:.6} Hz (rule {})",
        r.accuracy_band.fmax_hz, r.accuracy_band.rule
    );
    if let Some(p) = &r.preload {
        let factor = p
            .buckling_factor
            .map_or("none (nothing in compression)".into(), |l| {
                format!("{l:.6}")
            });
        let _ = writeln!(
            o,
            "  preload    {} ({}): linear static, max |u0| {:.6e} at node {}, buckling factor {factor}",
            p.source,
            p.loads.join(", "),
            p.max_displacement,
            p.max_displacement_node
        );
    }
}

/// The `--units` value of a unit system: its preset name (`si`, `mm-t-s`, …), or the units
/// themselves when no preset matches.
fn units_option(u: &flexbody_reader::Units) -> String {
    crate::pipeline::options::unit_preset_name(u).map_or_else(
        || {
            format!(
                "{}/{}/{}/{} (no preset)",
                u.mass.name, u.length.name, u.time.name, u.force.name
            )
        },
        str::to_string,
    )
}

/// Runs `flexbody inspect`: the summary as text, or as JSON.
pub(crate) fn command(file: &std::path::Path, json: bool) -> anyhow::Result<()> {
    use anyhow::Context;
    let bytes = std::fs::read(file).with_context(|| format!("cannot read {}", file.display()))?;
    let limits = flexbody_reader::ReadLimits::default();
    let (body, manifest) = flexbody_reader::from_bytes_with_manifest(&bytes, &limits)
        .map_err(flexbody_reader::ReadError::named)
        .with_context(|| format!("{} is not a valid flexbody file", file.display()))?;
    let summary = summarize(&body, &manifest);
    if json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        print!("{}", render_text(&summary));
    }
    Ok(())
}
