//! Acceptance: the a/b/d reference cases read from `.inp`, `.bdf` and `.msh` give the same model
//! (ids, coordinates to the file's precision, connectivity in one node order, node sets), and a
//! binary `.msh` reads to exactly the model of its ASCII original.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use flexbody::import::{gmsh, read_model, ImportOptions};
use flexbody::model::Model;

fn reference(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/reference")
        .join(rel)
}

fn read(rel: &str) -> Model {
    read_model(&reference(rel), &ImportOptions::default()).unwrap()
}

fn coords(m: &Model) -> HashMap<u64, [f64; 3]> {
    m.nodes.iter().map(|n| (n.id, n.x)).collect()
}

/// Element id → (kind, node ids).
fn conn(m: &Model) -> Vec<(u64, String, Vec<u64>)> {
    let mut v: Vec<_> = m
        .elements
        .iter()
        .map(|e| {
            (
                e.id,
                format!("{:?}", e.kind),
                e.nodes.iter().map(|&i| m.nodes[i].id).collect(),
            )
        })
        .collect();
    v.sort();
    v
}

fn set_ids(m: &Model, name: &str) -> Vec<u64> {
    let mut v: Vec<u64> = m.node_sets[name].iter().map(|&i| m.nodes[i].id).collect();
    v.sort_unstable();
    v
}

/// Max |Δx| over all nodes, relative to the model size.
fn max_rel_diff(a: &Model, b: &Model) -> f64 {
    let (ca, cb) = (coords(a), coords(b));
    assert_eq!(ca.len(), cb.len());
    let size = a
        .nodes
        .iter()
        .flat_map(|n| n.x)
        .fold(0.0f64, |m, x| m.max(x.abs()));
    ca.iter()
        .map(|(id, x)| {
            let y = cb[id];
            (0..3).map(|d| (x[d] - y[d]).abs()).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
        / size
}

fn check_case(case: &str, sets: [&str; 2]) {
    let inp = read(&format!("{case}/mesh.inp"));
    let bdf = read(&format!("{case}/mesh.bdf"));
    let msh = read(&format!("{case}/mesh.msh"));
    // Coordinates: .inp holds full double precision, .bdf 10 significant digits (GRID*).
    let d_inp = max_rel_diff(&inp, &msh);
    let d_bdf = max_rel_diff(&bdf, &msh);
    assert!(d_inp <= 2.5e-16, "{case}: inp vs msh {d_inp:e}");
    assert!(d_bdf <= 1e-9, "{case}: bdf vs msh {d_bdf:e}");
    assert_eq!(conn(&inp), conn(&msh), "{case}: connectivity inp vs msh");
    assert_eq!(conn(&bdf), conn(&msh), "{case}: connectivity bdf vs msh");
    for (k, s) in sets.iter().enumerate() {
        let i = set_ids(&inp, s);
        assert!(!i.is_empty());
        assert_eq!(i, set_ids(&msh, s), "{case}: set {s} inp vs msh");
        assert_eq!(
            i,
            set_ids(&bdf, &format!("SPC_{}", k + 1)),
            "{case}: set {s} inp vs bdf"
        );
    }
    assert_eq!(msh.element_sets["SOLID"].len(), msh.elements.len());
    assert_eq!(inp.element_sets["SOLID"].len(), inp.elements.len());
}

#[test]
fn a_block_hex8_same_model_in_three_formats() {
    check_case("a_block_hex8", ["FIXED", "TIP"]);
}

#[test]
fn b_block_tet10_same_model_in_three_formats() {
    check_case("b_block_tet10", ["FIXED", "TIP"]);
}

#[test]
fn d_plate_hex8_same_model_in_three_formats() {
    check_case("d_plate_hex8", ["CLAMPED_EDGE", "FREE_EDGE_X"]);
}

#[test]
fn binary_msh_equals_ascii_msh() {
    for case in ["tet10_block_coarse", "hex8_block_coarse"] {
        let ascii = gmsh::read(&reference(&format!("e_matrices/{case}/mesh.msh")), None).unwrap();
        let bin_path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("fixtures/import/{case}_bin.msh"));
        let bin = gmsh::read(&bin_path, None).unwrap();
        assert_eq!(ascii.nodes, bin.nodes, "{case}");
        assert_eq!(ascii.elements, bin.elements, "{case}");
        assert_eq!(ascii.node_sets, bin.node_sets, "{case}");
        assert_eq!(ascii.element_sets, bin.element_sets, "{case}");
        assert!(!bin.elements.is_empty());
        // And the mesh matches the .inp of the same case (these meshes carry no surface groups).
        let inp = read(&format!("e_matrices/{case}/mesh.inp"));
        assert_eq!(conn(&inp), conn(&bin), "{case}");
        assert!(max_rel_diff(&inp, &bin) <= 2.5e-16, "{case}");
    }
}

/// A binary mesh with physical surfaces equals its ASCII twin, and the tet10 permutation puts
/// every mid-side node at the midpoint of the Abaqus edge it belongs to (5:(1,2) 6:(2,3) 7:(1,3)
/// 8:(1,4) 9:(2,4) 10:(3,4)).
#[test]
fn binary_msh_with_surface_groups_and_tet10_mid_nodes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/import");
    let a = gmsh::read(&dir.join("small_tet10_ascii.msh"), None).unwrap();
    let b = gmsh::read(&dir.join("small_tet10_bin.msh"), None).unwrap();
    // The ASCII file prints 16 significant digits; the binary one holds the exact doubles.
    assert!(a.nodes.iter().zip(&b.nodes).all(|(p, q)| p.id == q.id));
    assert!(max_rel_diff(&a, &b) <= 1e-15);
    assert!(a.elements == b.elements, "elements differ");
    assert_eq!(a.node_sets, b.node_sets);
    assert!(
        a.node_sets["X0"].len() >= 3
            && a.node_sets["X0"]
                .iter()
                .all(|&i| b.nodes[i].x[0].abs() < 1e-12)
    );
    assert!(a.node_sets["XL"]
        .iter()
        .all(|&i| (b.nodes[i].x[0] - 0.1).abs() < 1e-12));
    let edges = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)];
    for e in &b.elements {
        let x = |k: usize| b.nodes[e.nodes[k]].x;
        for (k, (p, q)) in edges.iter().enumerate() {
            for d in 0..3 {
                assert!(
                    (x(4 + k)[d] - 0.5 * (x(*p)[d] + x(*q)[d])).abs() < 1e-12,
                    "element {}",
                    e.id
                );
            }
        }
    }
    // With a material from the options every solid element gets a property.
    let opts = ImportOptions {
        material: Some(flexbody::model::Material::steel()),
        ..Default::default()
    };
    let m = read_model(&dir.join("small_tet10_bin.msh"), &opts).unwrap();
    assert!(m.elements.iter().all(|e| e.property == Some(0)));
    assert_eq!(m.materials[0].e, 210e9);
}
