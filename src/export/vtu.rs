//! VTU export: the body as a VTK XML unstructured grid (`.vtu`, "VTK File Formats", XML
//! `UnstructuredGrid`) for ParaView and every VTK reader.
//!
//! * points: every stored node (body frame, the file's length unit);
//! * cells: the file's graphics faces (triangles, quadrilaterals), its lines (beams, rods), and
//!   a vertex for each interface node no face or line uses (spider centres) — for every node
//!   when the file has neither faces nor lines (`--keep-nodes interface`);
//! * point data: `node id` (the model's ids), `interface` (1 at interface nodes), and per
//!   flexible mode j (the file's 1-based mode number) `mode j, F Hz, LABEL` (translations, 3
//!   components) and `mode j rotation`; where the file stores them `mode j stress`,
//!   `mode j strain` (and `… bottom` for shell bottom fibres) as 6-component symmetric tensors
//!   in VTK's order xx yy zz xy yz xz — the file's order — NaN at nodes without a value;
//! * field data: `mode number`, `frequency_hz` (and `damping ratio` when stored) of the modes
//!   written.
//!
//! Arrays are inline base64 binary, little-endian, each a UInt64 byte count then the data,
//! each base64-encoded separately as VTK's own writer does: the values are the file's bits.
//! Written through a temp file and a rename.
use std::fmt::Write as _;
use std::path::Path;

use flexbody_reader::{Face, FieldShapes, ReducedBody};

use super::{flexible_modes, mode_label_name, write_atomic, ExportError, ExportSummary};

/// VTK cell types (vtkCellType.h).
const VTK_VERTEX: u8 = 1;
const VTK_LINE: u8 = 3;
const VTK_TRIANGLE: u8 = 5;
const VTK_QUAD: u8 = 9;

/// Writes the `.vtu` of `body` to `path` (temp file + rename).
pub fn export_vtu(body: &ReducedBody, path: &Path) -> Result<ExportSummary, ExportError> {
    let (text, summary) = vtu_xml(body)?;
    write_atomic(path, text.as_bytes())?;
    Ok(summary)
}

/// The name of mode `j`'s translation array: `mode 7, 2469.1 Hz, fixed-interface`.
pub fn mode_array_name(body: &ReducedBody, j: usize) -> String {
    format!(
        "mode {}, {} Hz, {}",
        j + 1,
        significant(body.modes.frequency_hz[j], 5),
        mode_label_name(body.modes.labels[j])
    )
}

/// `x` with `digits` significant digits: plain decimals from 1e-3 to 1e9, else an exponent.
pub fn significant(x: f64, digits: i32) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let magnitude = x.abs().log10().floor() as i32;
    if !(-3..9).contains(&magnitude) {
        let decimals = (digits - 1).max(0) as usize;
        return format!("{x:.decimals$e}");
    }
    let decimals = (digits - 1 - magnitude).clamp(0, 17) as usize;
    format!("{x:.decimals$}")
}

/// The cells: faces, lines, then a vertex per interface node no face or line uses (per node
/// when there are neither faces nor lines); (connectivity, offsets, types).
fn cells(body: &ReducedBody) -> (Vec<i64>, Vec<i64>, Vec<u8>) {
    let mut connectivity = Vec::new();
    let mut offsets = Vec::new();
    let mut types = Vec::new();
    let mut used = vec![false; body.node_count()];
    let mut push = |nodes: &[u32], kind: u8| {
        for &p in nodes {
            connectivity.push(i64::from(p));
            used[p as usize] = true;
        }
        offsets.push(connectivity.len() as i64);
        types.push(kind);
    };
    for face in &body.faces {
        match face {
            Face::Tri(n) => push(n, VTK_TRIANGLE),
            Face::Quad(n) => push(n, VTK_QUAD),
        }
    }
    for line in body.lines.iter().flatten() {
        push(line, VTK_LINE);
    }
    let no_mesh = types.is_empty();
    let free: Vec<u32> = (0..body.node_count() as u32)
        .filter(|&p| no_mesh || (!used[p as usize] && body.nodes[p as usize].interface))
        .collect();
    for p in free {
        connectivity.push(i64::from(p));
        offsets.push(connectivity.len() as i64);
        types.push(VTK_VERTEX);
    }
    (connectivity, offsets, types)
}

/// Tensor fields the file stores, with their array-name suffixes.
fn tensor_fields(body: &ReducedBody) -> Vec<(&'static str, &FieldShapes)> {
    [
        ("stress", &body.stress_shapes),
        ("strain", &body.strain_shapes),
        ("stress bottom", &body.stress_shapes_bottom),
        ("strain bottom", &body.strain_shapes_bottom),
    ]
    .into_iter()
    .filter_map(|(name, f)| f.as_ref().map(|f| (name, f)))
    .collect()
}

/// The `.vtu` text and the summary (no file written).
pub fn vtu_xml(body: &ReducedBody) -> Result<(String, ExportSummary), ExportError> {
    let n = body.node_count();
    if n == 0 {
        return Err(ExportError::Unsupported {
            target: "vtu",
            reason: "the file stores no nodes".into(),
        });
    }
    let flex = flexible_modes(body);
    let (connectivity, offsets, types) = cells(body);
    let mut s = String::new();
    // `write!` into a String cannot fail; the results are ignored on purpose.
    let _ = writeln!(s, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        s,
        "<!-- {} {} from a .flexbody file: {}; units {} {} {} {} -->",
        body.generator.name,
        body.generator.version,
        xml_escape(&body.header.title).replace("--", "- -"),
        body.units.mass.name,
        body.units.length.name,
        body.units.time.name,
        body.units.force.name
    );
    let _ = writeln!(
        s,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">"
    );
    let _ = writeln!(s, "<UnstructuredGrid>");
    field_data(&mut s, body, &flex);
    let _ = writeln!(
        s,
        "<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{}\">",
        types.len()
    );
    let _ = writeln!(s, "<Points>");
    let xyz: Vec<f64> = body.nodes.iter().flat_map(|nd| nd.xyz).collect();
    data_array(&mut s, "Points", "Float64", 3, &f64_bytes(&xyz));
    let _ = writeln!(s, "</Points>");
    let _ = writeln!(s, "<Cells>");
    data_array(
        &mut s,
        "connectivity",
        "Int64",
        1,
        &i64_bytes(&connectivity),
    );
    data_array(&mut s, "offsets", "Int64", 1, &i64_bytes(&offsets));
    data_array(&mut s, "types", "UInt8", 1, &types);
    let _ = writeln!(s, "</Cells>");
    point_data(&mut s, body, &flex);
    let _ = writeln!(s, "</Piece>");
    let _ = writeln!(s, "</UnstructuredGrid>");
    let _ = writeln!(s, "</VTKFile>");
    let fields = tensor_fields(body);
    let mut notes = Vec::new();
    for (name, f) in &fields {
        if f.nodes.len() < n {
            notes.push(format!(
                "{name} shapes are stored at {} of the {n} nodes; the others hold NaN",
                f.nodes.len()
            ));
        }
    }
    Ok((
        s,
        ExportSummary {
            modes: flex.len(),
            nodes: n,
            notes,
        },
    ))
}

/// Mode numbers, frequencies and damping ratios of the modes written, as field data.
fn field_data(s: &mut String, body: &ReducedBody, flex: &[usize]) {
    let _ = writeln!(s, "<FieldData>");
    let numbers: Vec<i64> = flex.iter().map(|&j| j as i64 + 1).collect();
    let hz: Vec<f64> = flex.iter().map(|&j| body.modes.frequency_hz[j]).collect();
    field_array(
        s,
        "mode number",
        "Int64",
        numbers.len(),
        &i64_bytes(&numbers),
    );
    field_array(s, "frequency_hz", "Float64", hz.len(), &f64_bytes(&hz));
    if let Some(d) = &body.damping {
        let ratio: Vec<f64> = flex.iter().map(|&j| d.ratio[j]).collect();
        field_array(
            s,
            "damping ratio",
            "Float64",
            ratio.len(),
            &f64_bytes(&ratio),
        );
    }
    let _ = writeln!(s, "</FieldData>");
}

/// Node ids, the interface flag, the mode shapes and the tensor fields as point data.
fn point_data(s: &mut String, body: &ReducedBody, flex: &[usize]) {
    let n = body.node_count();
    let _ = writeln!(s, "<PointData>");
    let ids: Vec<u8> = body
        .nodes
        .iter()
        .flat_map(|nd| nd.id.to_le_bytes())
        .collect();
    data_array(s, "node id", "UInt64", 1, &ids);
    let interface: Vec<u8> = body.nodes.iter().map(|nd| u8::from(nd.interface)).collect();
    data_array(s, "interface", "UInt8", 1, &interface);
    let shapes = &body.modes.shapes;
    for &j in flex {
        let block = &shapes[j * n * 6..(j + 1) * n * 6];
        let part = |from: usize| -> Vec<f64> {
            block
                .chunks_exact(6)
                .flat_map(|v| [v[from], v[from + 1], v[from + 2]])
                .collect()
        };
        let name = mode_array_name(body, j);
        data_array(s, &name, "Float64", 3, &f64_bytes(&part(0)));
        let name = format!("mode {} rotation", j + 1);
        data_array(s, &name, "Float64", 3, &f64_bytes(&part(3)));
    }
    for (suffix, field) in tensor_fields(body) {
        let k = field.nodes.len();
        for &j in flex {
            let mut values = vec![f64::NAN; n * 6];
            for (q, &p) in field.nodes.iter().enumerate() {
                let from = (j * k + q) * 6;
                values[p as usize * 6..p as usize * 6 + 6]
                    .copy_from_slice(&field.values[from..from + 6]);
            }
            let name = format!("mode {} {suffix}", j + 1);
            data_array(s, &name, "Float64", 6, &f64_bytes(&values));
        }
    }
    let _ = writeln!(s, "</PointData>");
}

fn f64_bytes(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn i64_bytes(v: &[i64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// One `<DataArray>` with inline binary data: base64 of the UInt64 byte count, then base64 of
/// the bytes (two separately padded blocks, VTK's layout for uncompressed inline binary).
fn data_array(s: &mut String, name: &str, kind: &str, components: usize, bytes: &[u8]) {
    let _ = write!(
        s,
        "<DataArray type=\"{kind}\" Name=\"{}\" NumberOfComponents=\"{components}\" format=\"binary\">",
        xml_escape(name)
    );
    base64_into(s, &(bytes.len() as u64).to_le_bytes());
    base64_into(s, bytes);
    let _ = writeln!(s, "</DataArray>");
}

/// A field-data array (`NumberOfTuples` instead of points).
fn field_array(s: &mut String, name: &str, kind: &str, tuples: usize, bytes: &[u8]) {
    let _ = write!(
        s,
        "<DataArray type=\"{kind}\" Name=\"{}\" NumberOfTuples=\"{tuples}\" format=\"binary\">",
        xml_escape(name)
    );
    base64_into(s, &(bytes.len() as u64).to_le_bytes());
    base64_into(s, bytes);
    let _ = writeln!(s, "</DataArray>");
}

/// Base64 (RFC 4648 §4, standard alphabet, `=` padding) of `bytes`, appended to `s`.
pub fn base64_into(s: &mut String, bytes: &[u8]) {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    s.reserve(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let triple = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= chunk.len() {
                s.push(char::from(ALPHABET[(triple >> shift) as usize & 63]));
            } else {
                s.push('=');
            }
        }
    }
}

/// `text` with XML's five special characters escaped (attribute values and comments).
pub fn xml_escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_test_vectors() {
        // RFC 4648 §10.
        for (plain, encoded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            let mut s = String::new();
            base64_into(&mut s, plain.as_bytes());
            assert_eq!(s, encoded, "{plain}");
        }
    }

    #[test]
    fn significant_digits() {
        assert_eq!(significant(2469.1234, 5), "2469.1");
        assert_eq!(significant(0.00123456, 3), "0.00123");
        assert_eq!(significant(123456.7, 5), "123457");
        assert_eq!(significant(0.0, 5), "0");
        assert_eq!(significant(-9.9341e-10, 5), "-9.9341e-10");
    }
}
