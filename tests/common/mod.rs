//! Test support for the fe tests: the reference-data paths, a minimal reader of the gmsh-written
//! `mesh.inp` files in `../shared/reference` (*NODE, *ELEMENT C3D8/C3D10, *NSET only — a stand-in
//! until the `.inp` importer is merged), dense copies of sparse matrices, and a dense generalized
//! symmetric eigen-solve for small systems.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use faer::sparse::SparseColMat;
use faer::Mat;
use flexbody::model::{Element, ElementKind, Material, Model, Node, Property, Section};

pub fn reference(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/reference").join(rel)
}

pub fn steel() -> Material {
    Material { id: 1, name: "STEEL".into(), e: 210e9, nu: 0.3, g: 210e9 / 2.6, rho: 7850.0 }
}

/// Read nodes, C3D4/C3D8/C3D10/C3D20 elements and node sets of a reference mesh.inp; all elements
/// get one solid property of steel.
pub fn read_mesh_inp(path: &Path) -> Model {
    let text = std::fs::read_to_string(path).expect("reference mesh.inp is readable");
    let mut model = Model { source: path.display().to_string(), ..Model::default() };
    model.materials.push(steel());
    model.properties.push(Property { id: 1, name: "SOLID".into(), material: 0, section: Section::Solid });
    enum Block {
        None,
        Node,
        Element(ElementKind),
        Nset(String),
    }
    let mut block = Block::None;
    let mut raw_elems: Vec<(u64, ElementKind, Vec<u64>)> = Vec::new();
    let mut raw_sets: BTreeMap<String, Vec<u64>> = BTreeMap::new();
    for line in text.lines() {
        let l = line.trim();
        if l.starts_with("**") || l.is_empty() {
            continue;
        }
        if l.starts_with('*') {
            let up = l.to_uppercase();
            block = if up.starts_with("*NODE") {
                Block::Node
            } else if up.starts_with("*ELEMENT") {
                let kind = match up.split("TYPE=").nth(1).and_then(|s| s.split(',').next()).map(str::trim) {
                    Some("C3D4") => ElementKind::Tet4,
                    Some("C3D8") => ElementKind::Hex8,
                    Some("C3D10") => ElementKind::Tet10,
                    Some("C3D20") => ElementKind::Hex20,
                    other => panic!("unexpected element type {other:?}"),
                };
                Block::Element(kind)
            } else if up.starts_with("*NSET") {
                let name = up.split("NSET=").nth(1).unwrap().split(',').next().unwrap().trim().to_string();
                Block::Nset(name)
            } else {
                Block::None
            };
            continue;
        }
        let f: Vec<&str> = l.split(',').map(str::trim).filter(|s| !s.is_empty()).collect();
        match &block {
            Block::Node => model.nodes.push(Node {
                id: f[0].parse().unwrap(),
                x: [f[1].parse().unwrap(), f[2].parse().unwrap(), f[3].parse().unwrap()],
                displacement_frame: None,
            }),
            Block::Element(kind) => {
                let ids: Vec<u64> = f.iter().map(|s| s.parse().unwrap()).collect();
                raw_elems.push((ids[0], *kind, ids[1..].to_vec()));
            }
            Block::Nset(name) => raw_sets.entry(name.clone()).or_default().extend(f.iter().map(|s| s.parse::<u64>().unwrap())),
            Block::None => {}
        }
    }
    let idx = model.node_index_by_id();
    for (id, kind, nodes) in raw_elems {
        model.elements.push(Element {
            id,
            kind,
            nodes: nodes.iter().map(|n| idx[n]).collect(),
            property: Some(0),
            orientation: None,
        });
    }
    for (name, ids) in raw_sets {
        let mut v: Vec<usize> = ids.iter().map(|n| idx[n]).collect();
        v.sort_unstable();
        v.dedup();
        model.node_sets.insert(name, v);
    }
    model
}

pub fn dense(a: &SparseColMat<usize, f64>) -> Mat<f64> {
    let a = a.as_ref();
    let mut d = Mat::zeros(a.nrows(), a.ncols());
    for j in 0..a.ncols() {
        for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            d[(i, j)] += v;
        }
    }
    d
}

/// Eigenvalues λ of K x = λ M x (M positive definite), ascending, via M = LLᵀ and
/// L⁻¹ K L⁻ᵀ (dense; for n up to a few thousand).
pub fn generalized_eigenvalues(k: &Mat<f64>, m: &Mat<f64>) -> Vec<f64> {
    let n = k.nrows();
    let llt = m.llt(faer::Side::Lower).expect("M positive definite");
    let l = llt.L();
    // A = L⁻¹ K L⁻ᵀ
    let mut a = k.clone();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, a.as_mut(), faer::Par::Seq);
    let mut at = a.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, at.as_mut(), faer::Par::Seq);
    let sym = Mat::from_fn(n, n, |i, j| 0.5 * (at[(i, j)] + at[(j, i)]));
    let mut ev = sym.self_adjoint_eigenvalues(faer::Side::Lower).expect("eigenvalues converge");
    ev.sort_by(f64::total_cmp);
    ev
}

/// Hz from ω².
pub fn hz(lambda: f64) -> f64 {
    lambda.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}
