//! `flexbody view`: one self-contained HTML page of a body (no network, no CDN: the page's
//! script and data are inline; canvas 2D, no WebGL) that animates each mode with its frequency
//! and label and a scale slider, marks the interface nodes by name, and lists the body's key
//! figures (mass, centre of mass, inertia, modes, frequencies, damping).
//!
//! The page shows the graphics faces (quads split in two triangles), the lines and the
//! interface nodes; only the nodes they use are embedded (every node, as points, when the file
//! has neither faces nor lines). Coordinates and mode shapes are embedded as base64 float32
//! (display precision), the figures as text from the file's float64 values. The URL fragment
//! selects the mode and can freeze the animation: `body.html#mode=7&t=0.25` shows mode 7 (the
//! file's 1-based mode number) at a quarter period, the largest deflection. After drawing, the
//! page records `data-status="ok"`, the mode shown and a hash of the canvas pixels on its
//! `<body>` element (for headless browser tests); script errors go to `data-errors`.
use std::fmt::Write as _;
use std::path::Path;

use flexbody_reader::{Face, ReducedBody};

use super::vtu::{base64_into, significant, xml_escape};
use super::{flexible_modes, mode_label_name, write_atomic, ExportError, ExportSummary};

/// The page around the data: `{{TITLE}}`, `{{FIGURES}}`, `{{DATA}}` are filled in.
const TEMPLATE: &str = include_str!("view.html");

/// Writes the viewer page of `body` to `path` (temp file + rename).
pub fn export_view(body: &ReducedBody, path: &Path) -> Result<ExportSummary, ExportError> {
    let (html, summary) = view_html(body)?;
    write_atomic(path, html.as_bytes())?;
    Ok(summary)
}

fn base64_f32(values: impl Iterator<Item = f64>) -> String {
    let bytes: Vec<u8> = values.flat_map(|v| (v as f32).to_le_bytes()).collect();
    let mut s = String::new();
    base64_into(&mut s, &bytes);
    s
}

fn base64_u32(values: impl Iterator<Item = u32>) -> String {
    let bytes: Vec<u8> = values.flat_map(u32::to_le_bytes).collect();
    let mut s = String::new();
    base64_into(&mut s, &bytes);
    s
}

/// The stored nodes the page draws: those of faces, lines and interfaces (all when the file has
/// neither faces nor lines), as (page index of each stored node, stored index of each page node).
fn shown_nodes(body: &ReducedBody) -> (Vec<Option<u32>>, Vec<usize>) {
    let n = body.node_count();
    let mut used = vec![false; n];
    for face in &body.faces {
        let nodes: &[u32] = match face {
            Face::Tri(v) => v,
            Face::Quad(v) => v,
        };
        for &p in nodes {
            used[p as usize] = true;
        }
    }
    for line in body.lines.iter().flatten() {
        used[line[0] as usize] = true;
        used[line[1] as usize] = true;
    }
    let no_mesh = !used.iter().any(|&u| u);
    let mut page_index = vec![None; n];
    let mut stored = Vec::new();
    for p in 0..n {
        if no_mesh || used[p] || body.nodes[p].interface {
            page_index[p] = Some(stored.len() as u32);
            stored.push(p);
        }
    }
    (page_index, stored)
}

/// The page's data as JSON: nodes, triangles, lines, interfaces, modes.
fn page_data(body: &ReducedBody) -> serde_json::Value {
    let n = body.node_count();
    let (page_index, stored) = shown_nodes(body);
    // Every node of a face, line or interface is in `stored`, so `page_index` is Some for it.
    let at = |p: u32| page_index[p as usize].unwrap_or(0);
    let triangles = body.faces.iter().flat_map(|f| match f {
        Face::Tri(v) => vec![at(v[0]), at(v[1]), at(v[2])],
        Face::Quad(v) => vec![at(v[0]), at(v[1]), at(v[2]), at(v[0]), at(v[2]), at(v[3])],
    });
    let lines = body
        .lines
        .iter()
        .flatten()
        .flat_map(|l| [at(l[0]), at(l[1])]);
    let interfaces: Vec<serde_json::Value> = match &body.interfaces {
        Some(list) => list
            .iter()
            .map(|i| {
                serde_json::json!({
                    "name": i.name,
                    "node": at(i.node),
                    "kind": format!("{:?}", i.kind),
                })
            })
            .collect(),
        None => (0..n)
            .filter(|&p| body.nodes[p].interface)
            .map(|p| {
                serde_json::json!({
                    "name": format!("NODE{}", body.nodes[p].id),
                    "node": at(p as u32),
                    "kind": "Node",
                })
            })
            .collect(),
    };
    let shapes = &body.modes.shapes;
    let modes: Vec<serde_json::Value> = (0..body.mode_count())
        .map(|j| {
            let shape = stored
                .iter()
                .flat_map(|&p| shapes[(j * n + p) * 6..(j * n + p) * 6 + 3].iter().copied());
            serde_json::json!({
                "number": j + 1,
                "hz": body.modes.frequency_hz[j],
                "label": mode_label_name(body.modes.labels[j]),
                "shape": base64_f32(shape),
            })
        })
        .collect();
    serde_json::json!({
        "xyz": base64_f32(stored.iter().flat_map(|&p| body.nodes[p].xyz)),
        "triangles": base64_u32(triangles),
        "lines": base64_u32(lines),
        "interfaces": interfaces,
        "modes": modes,
        "firstFlexible": flexible_modes(body).first().map_or(1, |&j| j + 1),
        "length": body.units.length.name,
    })
}

/// The key figures as an HTML table body and a frequency list.
fn figures(body: &ReducedBody) -> String {
    let u = &body.units;
    let inv = &body.invariants;
    let mut s = String::new();
    // `write!` into a String cannot fail; the results are ignored on purpose.
    let row = |s: &mut String, key: &str, value: String| {
        let _ = writeln!(
            s,
            "<tr><th>{}</th><td>{}</td></tr>",
            xml_escape(key),
            xml_escape(&value)
        );
    };
    if inv.mask[0] {
        let mass = inv.i1[0];
        row(
            &mut s,
            "mass",
            format!("{} {}", significant(mass, 6), u.mass.name),
        );
        if inv.mask[1] && mass > 0.0 {
            let c: Vec<String> = inv.i2.iter().map(|v| significant(v / mass, 5)).collect();
            row(
                &mut s,
                "centre of mass",
                format!("({}) {}", c.join(", "), u.length.name),
            );
        }
    }
    if inv.mask[6] {
        row(
            &mut s,
            "inertia about the origin Ixx, Iyy, Izz",
            format!(
                "{}, {}, {} {}·{}²",
                significant(inv.i7[0], 5),
                significant(inv.i7[4], 5),
                significant(inv.i7[8], 5),
                u.mass.name,
                u.length.name
            ),
        );
    }
    let flex = flexible_modes(body);
    row(
        &mut s,
        "modes",
        format!(
            "{} ({} flexible, {} rigid); method {:?}",
            body.mode_count(),
            flex.len(),
            body.mode_count() - flex.len(),
            body.header.request.method
        ),
    );
    row(&mut s, "nodes stored", body.node_count().to_string());
    row(
        &mut s,
        "interfaces",
        match &body.interfaces {
            Some(list) => list
                .iter()
                .map(|i| i.name.clone())
                .collect::<Vec<_>>()
                .join(", "),
            None => body
                .nodes
                .iter()
                .filter(|nd| nd.interface)
                .count()
                .to_string(),
        },
    );
    row(
        &mut s,
        "units",
        format!(
            "{} {} {} {}",
            u.mass.name, u.length.name, u.time.name, u.force.name
        ),
    );
    let _ = writeln!(
        s,
        "</table><table class=\"freq\"><tr><th>mode</th><th>Hz</th><th>label</th><th>ζ</th></tr>"
    );
    for j in 0..body.mode_count() {
        let zeta = body
            .damping
            .as_ref()
            .map_or(String::from("–"), |d| significant(d.ratio[j], 3));
        let _ = writeln!(
            s,
            "<tr data-mode=\"{}\"><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            j + 1,
            j + 1,
            significant(body.modes.frequency_hz[j], 6),
            mode_label_name(body.modes.labels[j]),
            zeta
        );
    }
    s
}

/// `template` with each placeholder replaced once, in one pass over the template (a value that
/// itself contains a placeholder's text stays as it is).
fn fill(template: &str, values: &[(&str, &str)]) -> String {
    let mut out =
        String::with_capacity(template.len() + values.iter().map(|v| v.1.len()).sum::<usize>());
    let mut rest = template;
    while let Some(at) = rest.find("{{") {
        out.push_str(&rest[..at]);
        rest = &rest[at..];
        match values.iter().find(|(key, _)| rest.starts_with(key)) {
            Some((key, value)) => {
                out.push_str(value);
                rest = &rest[key.len()..];
            }
            None => {
                out.push_str("{{");
                rest = &rest[2..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// The page and the summary (no file written).
pub fn view_html(body: &ReducedBody) -> Result<(String, ExportSummary), ExportError> {
    if body.node_count() == 0 || body.mode_count() == 0 {
        return Err(ExportError::Unsupported {
            target: "view",
            reason: "the file stores no nodes or no modes".into(),
        });
    }
    // `</` inside the JSON would end the script element; `<\/` is the same JSON string.
    let data = page_data(body).to_string().replace("</", "<\\/");
    let title = if body.header.title.is_empty() {
        "flexbody".to_string()
    } else {
        body.header.title.clone()
    };
    let html = fill(
        TEMPLATE,
        &[
            ("{{TITLE}}", &xml_escape(&title)),
            ("{{FIGURES}}", &figures(body)),
            ("{{DATA}}", &data),
        ],
    );
    let (_, stored) = shown_nodes(body);
    Ok((
        html,
        ExportSummary {
            modes: body.mode_count(),
            nodes: stored.len(),
            notes: Vec::new(),
        },
    ))
}
