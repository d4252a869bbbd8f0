//! Issue 36, `flexbody export --to vtu`: the VTK XML unstructured grid read back two ways.
//!
//! * Here, without Python: the XML's arrays decoded by a base64 decoder written in this test
//!   (VTK's inline-binary layout: a separately padded UInt64 byte count, then the data) give the
//!   file's node coordinates and every flexible mode's translations bit for bit.
//! * meshio (a third-party VTK reader, `tests/python/vtu_export_check.py`) against the file as
//!   this repository's numpy package reads it: points, cells (faces, lines, interface vertices),
//!   node ids, every mode's translations and rotations, stress/strain shapes (NaN where the file
//!   has none), frequencies and damping to 1e-15. Skipped visibly without meshio (CI installs
//!   it).
//!
//! Models: the conrod (tet10 surface triangles, two spider centres, stress and strain shapes,
//! damping), the planar beam (lines, rotations) and a free S4 shell plate written here (quads,
//! top and bottom fibre shapes).

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{base64_block, exe, python_has, scratch, skipped_install};
use flexbody_reader as file;

fn run(args: &[&str]) {
    let o = exe().args(args).output().unwrap();
    assert!(
        o.status.success(),
        "flexbody {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The f64 values of the `<DataArray>` named `name`: the byte count block, then the data.
fn float_array(xml: &str, name: &str) -> Vec<f64> {
    let at = xml
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no array {name}"));
    let start = at + xml[at..].find('>').unwrap() + 1;
    let end = start + xml[start..].find('<').unwrap();
    let text = &xml[start..end];
    let (header, used) = base64_block(text);
    let count = u64::from_le_bytes(header.try_into().unwrap()) as usize;
    let (data, _) = base64_block(&text[used..]);
    assert_eq!(data.len(), count, "{name}: byte count");
    data.chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
        .collect()
}

/// Builds `model`, exports it to VTU, checks the arrays here and with meshio.
fn check(name: &str, model: &Path, build_args: &[&str]) -> file::ReducedBody {
    let dir = scratch(&format!("vtu-{name}"));
    let body_path = dir.join("body.flexbody");
    let vtu_path = dir.join("body.vtu");
    let mut args = vec!["build", model.to_str().unwrap()];
    args.extend_from_slice(build_args);
    args.extend_from_slice(&["--units", "si", "-q", "-o", body_path.to_str().unwrap()]);
    run(&args);
    run(&[
        "export",
        body_path.to_str().unwrap(),
        "--to",
        "vtu",
        "-o",
        vtu_path.to_str().unwrap(),
    ]);
    let body = file::read(&body_path).unwrap();
    let xml = std::fs::read_to_string(&vtu_path).unwrap();
    let n = body.node_count();
    let xyz: Vec<f64> = body.nodes.iter().flat_map(|nd| nd.xyz).collect();
    assert_eq!(float_array(&xml, "Points"), xyz);
    let flex: Vec<usize> = (0..body.mode_count())
        .filter(|&j| body.modes.labels[j] != file::ModeLabel::Rigid)
        .collect();
    for &j in &flex {
        let array_name = flexbody::export::vtu::mode_array_name(&body, j);
        let expected: Vec<f64> = body.modes.shapes[j * n * 6..(j + 1) * n * 6]
            .chunks_exact(6)
            .flat_map(|v| [v[0], v[1], v[2]])
            .collect();
        assert_eq!(float_array(&xml, &array_name), expected, "{array_name}");
    }
    println!(
        "{name}: {} bytes of VTU, {n} points, {} modes equal to the file bit for bit",
        xml.len(),
        flex.len()
    );
    if !python_has("meshio") || !python_has("numpy") {
        skipped_install(
            &format!(
                "the meshio check of export_vtu ({name}): python3 cannot import meshio and numpy"
            ),
            "pip install meshio numpy",
        );
    } else {
        let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
        let o = Command::new("python3")
            .arg(root.join("tests/python/vtu_export_check.py"))
            .arg(&vtu_path)
            .arg(&body_path)
            .env("PYTHONPATH", root.join("python"))
            .output()
            .unwrap();
        let out = String::from_utf8_lossy(&o.stdout);
        println!("{name}:\n{out}");
        assert!(
            o.status.success(),
            "{out}\n{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    body
}

fn fixture(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

#[test]
fn conrod_vtu_holds_the_surface_modes_and_stress_shapes() {
    let body = check(
        "conrod",
        &fixture("fixtures/models/conrod/conrod.inp"),
        &[
            "--interface",
            "BIG_END,SMALL_END",
            "--fmax",
            "3000",
            "--stress-modes",
            "--damping",
            "2%",
        ],
    );
    assert!(body.stress_shapes.is_some() && body.strain_shapes.is_some());
}

#[test]
fn beam_vtu_holds_lines_and_rotations() {
    let body = check(
        "beam",
        &fixture("fixtures/models/planar_beam/planar_beam.bdf"),
        &["--method", "normal", "--modes", "6"],
    );
    assert!(body.lines.as_ref().is_some_and(|l| !l.is_empty()));
}

/// A free 0.4 × 0.2 × 0.002 m steel plate of 4 × 2 S4 shells (Abaqus deck).
fn shell_plate_deck() -> String {
    let mut s = String::from("*NODE\n");
    for j in 0..3 {
        for i in 0..5 {
            s.push_str(&format!(
                "{}, {}, {}, 0.0\n",
                j * 5 + i + 1,
                0.1 * i as f64,
                0.1 * j as f64
            ));
        }
    }
    s.push_str("*ELEMENT, TYPE=S4, ELSET=PLATE\n");
    for j in 0..2 {
        for i in 0..4 {
            let a = j * 5 + i + 1;
            s.push_str(&format!(
                "{}, {}, {}, {}, {}\n",
                j * 4 + i + 1,
                a,
                a + 1,
                a + 6,
                a + 5
            ));
        }
    }
    s.push_str(
        "*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL\n0.002\n*MATERIAL, NAME=STEEL\n\
         *ELASTIC\n210e9, 0.3\n*DENSITY\n7850.\n",
    );
    s
}

#[test]
fn shell_vtu_holds_quads_and_both_fibres() {
    let dir = scratch("vtu-shell-deck");
    let deck = dir.join("plate.inp");
    std::fs::write(&deck, shell_plate_deck()).unwrap();
    let body = check(
        "shell",
        &deck,
        // flexbody's shells (their fibres); by default the S4 would be ccx's C3D8I bricks
        &[
            "--method",
            "normal",
            "--modes",
            "10",
            "--stress-modes",
            "--inp-shells",
            "native",
        ],
    );
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(body.faces.len(), 8);
    assert!(body.stress_shapes_bottom.is_some() && body.strain_shapes_bottom.is_some());
}

#[test]
fn a_vtu_export_that_cannot_be_written_names_the_path_and_leaves_nothing() {
    let dir = scratch("vtu-unwritable");
    let body_path = dir.join("body.flexbody");
    run(&[
        "build",
        fixture("fixtures/models/planar_beam/planar_beam.bdf")
            .to_str()
            .unwrap(),
        "--method",
        "normal",
        "--modes",
        "4",
        "--units",
        "si",
        "-q",
        "-o",
        body_path.to_str().unwrap(),
    ]);
    let target = dir.join("no-such-folder/body.vtu");
    let o = exe()
        .args(["export", body_path.to_str().unwrap(), "--to", "vtu", "-o"])
        .arg(&target)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("no-such-folder/body.vtu"), "{err}");
    assert!(!target.exists());
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "only the .flexbody file: {left:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
