//! Interface metadata (`interfaces.bin`, format 1.3) through the real binary on the bundled
//! connecting rod: the bores' names, kinds, dependent nodes (against the deck's own `*NSET`
//! lists) and cylinder fits (against the drawing: Ø50 mm and Ø22 mm bores, axes along the
//! thickness); `--interface` and `--reference-conditions` take the names (`BIG_END:123456`,
//! `NODE<id>`) and give the same body as the node ids; `inspect` and the Python reference reader
//! show the same metadata.
use std::path::{Path, PathBuf};
use std::process::Command;

use flexbody_reader as file;

fn conrod_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod")
}

/// The ids of `*NSET,NSET=name` in the conrod mesh, read from the deck text.
fn nset(name: &str) -> Vec<u64> {
    let text = std::fs::read_to_string(conrod_dir().join("conrod_mesh.inp")).unwrap();
    let header = format!("*NSET,NSET={name}");
    let mut lines = text
        .lines()
        .skip_while(|l| !l.eq_ignore_ascii_case(&header));
    lines.next().expect("set exists");
    lines
        .take_while(|l| !l.starts_with('*'))
        .flat_map(|l| l.split(','))
        .filter_map(|t| t.trim().parse().ok())
        .collect()
}

fn build(out: &Path, interface: &str, reference: &str) -> file::ReducedBody {
    let status = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("build")
        .arg(conrod_dir().join("conrod.inp"))
        .args([
            "--interface",
            interface,
            "--reference-conditions",
            reference,
            "--modes",
            "8",
            "--units",
            "si",
            "-q",
            "-o",
        ])
        .arg(out)
        .status()
        .unwrap();
    assert!(status.success(), "build {interface} / {reference}");
    file::read(out).unwrap()
}

#[test]
fn conrod_interface_names_give_the_same_body_as_node_ids() {
    let dir = std::env::temp_dir().join(format!("flexbody-itf-names-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let small = nset("SMALL_END");
    let big = nset("BIG_END");
    let p = small[0];
    let by_name = build(
        &dir.join("names.flexbody"),
        &format!("BIG_END,NODE{p}"),
        "big_end:123456",
    );
    // 1.9 for the eigenproblem's record (every build), 1.3 for the interfaces without it
    assert_eq!(by_name.version, file::Version { major: 1, minor: 9 });
    let mut bare = by_name.clone();
    bare.eigen_residuals = None;
    assert_eq!(
        file::version_for(&bare),
        file::Version { major: 1, minor: 3 }
    );
    let itf = by_name
        .interfaces
        .as_ref()
        .expect("build writes interfaces.bin");
    assert_eq!(itf.len(), by_name.method.interface.len());
    assert_eq!(itf.len(), 2);

    // BIG_END: an RBE2 spider over every node of the deck's set, centred on the bore axis.
    let b = &itf[0];
    assert_eq!(b.name, "BIG_END");
    assert_eq!(b.kind, file::InterfaceKind::Rbe2);
    assert_eq!(b.dependent, big);
    let fit = b.fit.as_ref().unwrap();
    assert_eq!(fit.method, file::FitMethod::CylinderFit);
    let radius = fit.radius.unwrap();
    // Ø50 mm bore; the mesh nodes lie on the true cylinder (README) as far as gmsh placed and
    // printed them (measured |Δr| = 7.8e-12 m here, 1.9e-10 m at the Ø22 mm small end).
    assert!((radius - 0.025).abs() < 1e-10, "big-end radius {radius}");
    let axis = fit.axis.unwrap();
    let centre_node = &by_name.nodes[b.node as usize];
    assert_eq!(fit.centre, centre_node.xyz);
    assert!(centre_node.interface);
    // The bores' axes are parallel (both through the 20 mm thickness).
    let s = itf
        .iter()
        .position(|i| i.name == format!("NODE{p}"))
        .unwrap();
    assert_eq!(itf[s].kind, file::InterfaceKind::Node);
    assert!(itf[s].dependent.is_empty() && itf[s].fit.is_none());
    assert_eq!(by_name.nodes[itf[s].node as usize].id, p);
    // The reference condition named BIG_END landed on the spider centre, all six components.
    assert_eq!(
        by_name.method.reference_conditions,
        vec![file::ReferenceCondition {
            node: b.node,
            dofs: [true; 6]
        }]
    );

    // The same build with plain ids: the spider centre's id from the file, the node's id.
    let by_id = build(
        &dir.join("ids.flexbody"),
        &format!("BIG_END,{p}"),
        &format!("{}:123456", centre_node.id),
    );
    assert_eq!(by_id.nodes, by_name.nodes);
    assert_eq!(by_id.modes, by_name.modes);
    assert_eq!(by_id.invariants, by_name.invariants);
    assert_eq!(by_id.method, by_name.method);
    assert_eq!(by_id.interfaces, by_name.interfaces);

    // The small end's own cylinder: a second build with both bores as spiders.
    let both = build(
        &dir.join("both.flexbody"),
        "BIG_END,SMALL_END:123",
        "BIG_END",
    );
    let i2 = both.interfaces.as_ref().unwrap();
    assert_eq!(i2[1].name, "SMALL_END");
    assert_eq!(i2[1].dependent, small);
    let f2 = i2[1].fit.as_ref().unwrap();
    assert!((f2.radius.unwrap() - 0.011).abs() < 1e-9, "{:?}", f2.radius);
    // Both axes along z (the thickness). The axis is the weak eigenvector of the faces' normal
    // scatter, so the facetting of the curved tet10 faces tilts it: measured 2.3e-6 rad at
    // the big end, 1.8e-5 rad at the small end (1.8e-7 m over the 10 mm half-thickness).
    let a2 = f2.axis.unwrap();
    for a in [axis, a2] {
        let tilt = (a[0] * a[0] + a[1] * a[1]).sqrt();
        assert!(tilt < 1e-4, "axis {a:?} tilted {tilt:e} rad from z");
    }
    // 150 mm centre to centre.
    let d: f64 = (0..3)
        .map(|k| (f2.centre[k] - fit.centre[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!((d - 0.150).abs() < 1e-9, "centre distance {d}");
    // SMALL_END:123 — the spider centre carries translations only.
    assert_eq!(
        both.method.interface[1].dofs,
        [true, true, true, false, false, false]
    );
    assert_eq!(
        both.recipe.as_ref().unwrap().options.reference_conditions,
        vec!["BIG_END"]
    );

    // inspect shows the block; the Python reference reader decodes the same metadata.
    let text = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("inspect")
        .arg(dir.join("both.flexbody"))
        .output()
        .unwrap();
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(text.contains("interfaces"), "{text}");
    assert!(
        text.contains("SMALL_END") && text.contains("CylinderFit"),
        "{text}"
    );
    let py = Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("format-spec/reference_reader.py"))
        .arg(dir.join("both.flexbody"))
        .output()
        .unwrap();
    assert!(
        py.status.success(),
        "{}",
        String::from_utf8_lossy(&py.stderr)
    );
    let summary: serde_json::Value = serde_json::from_slice(&py.stdout).unwrap();
    assert_eq!(
        summary["interfaces"],
        serde_json::to_value(i2).unwrap(),
        "reference reader's interfaces"
    );
    std::fs::remove_dir_all(&dir).ok();
}
