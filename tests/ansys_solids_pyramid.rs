//! SOLID186 collapsed into ANSYS's pyramid and wedge against ANSYS's own strain energies: a
//! part (271 pyramids, 20 wedges, 44 bricks of SOLID186, 15 SOLID187; 1555 nodes; its
//! elements joined over faces) of the Workbench mesh of
//! ansys/example-data's `hemisphere.rst` (ANSYS 2022 R2, static, converted by
//! `tests/data/ansys/make_hemisphere_pyramids.py`), whose ENG record holds each element's strain
//! energy SENE = ½ u_eᵀ K_e u_e at ANSYS's displacements u.
//!
//! - element by element, through the library (`fe::assembly::element_matrices` of the archive's
//!   model), ½ u_eᵀ K_e u_e equals ANSYS's SENE;
//! - through the CLI (`build --write-matrices`, free-free), ½ uᵀ K u of the assembled K equals
//!   the elements' summed SENE.

use std::collections::HashMap;

use crate::ansys_support::{build, data, multiply, read_dofs};
use crate::common::scratch;
use flexbody::fe::assembly::element_matrices;
use flexbody::fe::AssemblySpec;
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::ElementKind;

/// ANSYS's solution: node id → (x, u), element id → (volume, SENE).
struct Solution {
    nodes: HashMap<u64, [f64; 6]>,
    elements: HashMap<u64, [f64; 2]>,
}

fn solution() -> Solution {
    let text = std::fs::read_to_string(data("hemisphere_pyramids.csv")).unwrap();
    let (mut nodes, mut elements) = (HashMap::new(), HashMap::new());
    for line in text.lines() {
        let f: Vec<&str> = line.split(',').collect();
        let id: u64 = f[1].parse().unwrap();
        let v: Vec<f64> = f[2..].iter().map(|t| t.parse().unwrap()).collect();
        if f[0] == "node" {
            nodes.insert(id, std::array::from_fn(|i| v[i]));
        } else {
            elements.insert(id, [v[0], v[1]]);
        }
    }
    Solution { nodes, elements }
}

/// Each element's ½ u_eᵀ K_e u_e against ANSYS's SENE. Measured at most: pyramids 5.5e-8,
/// wedges 4.8e-8, bricks (C3D20R) 5.2e-8, SOLID187 (C3D10) 4.3e-8 (ANSYS writes ENG in single
/// precision: relative 6e-8). Once, in numpy
/// over all 684 pyramids of the mesh: ANSYS's functions on 2×2×2 points 5.9e-8, Bedrosian's
/// 13-node pyramid (flexbody's `Pyram13`, Nastran CPYRAM) on 4×4×4 points 5.8e-2 and on 2×2×2
/// 3.8e-2, the collapsed 20-node brick on 2×2×2 0.12.
#[test]
fn solid186_pyramid_and_wedge_equal_ansys_strain_energies() {
    let s = solution();
    let model = read_model(&data("hemisphere_pyramids.cdb"), &ImportOptions::default()).unwrap();
    let spec = AssemblySpec::default();
    let mut worst = HashMap::new();
    for (e, el) in model.elements.iter().enumerate() {
        let em = element_matrices(&model, e, &spec).unwrap();
        let u: Vec<f64> = (el.nodes.iter())
            .flat_map(|&n| {
                let x = s.nodes[&model.nodes[n].id];
                [x[3], x[4], x[5]]
            })
            .collect();
        let k = &em.k;
        let nd = u.len();
        let energy: f64 = (0..nd)
            .map(|i| u[i] * (0..nd).map(|j| k[i * nd + j] * u[j]).sum::<f64>())
            .sum::<f64>()
            / 2.0;
        let sene = s.elements[&el.id][1];
        let error = (energy / sene - 1.0).abs();
        let w: &mut f64 = worst.entry(el.kind).or_insert(0.0);
        *w = w.max(error);
    }
    println!("max |½ uᵀ K_e u / SENE − 1|: {worst:?}");
    assert_eq!(worst.len(), 4, "{worst:?}");
    // measured 5.5e-8 (pyramids), 4.8e-8 (wedges), 5.2e-8 (bricks), 4.3e-8 (SOLID187)
    assert!(worst[&ElementKind::Pyram13Ansys] < 5e-7, "{worst:?}");
    assert!(worst[&ElementKind::Prism15] < 4e-7, "{worst:?}");
    assert!(worst[&ElementKind::Hex20R] < 5e-7, "{worst:?}");
    assert!(worst[&ElementKind::Tet10] < 4e-7, "{worst:?}");
}

/// Through the CLI: ½ uᵀ K u of the archive's assembled K (`build --write-matrices`, free-free)
/// equals the 350 elements' summed SENE. Measured 3.7e-9.
#[test]
fn solid186_pyramid_archive_through_the_cli_stores_ansys_energy() {
    let s = solution();
    let dir = scratch("ansys-pyramid");
    let cdb = dir.join("hemisphere.cdb");
    std::fs::copy(data("hemisphere_pyramids.cdb"), &cdb).unwrap();
    let mats = dir.join("mats");
    let o = build(
        &cdb,
        "mm-t-s",
        8,
        &["--write-matrices", mats.to_str().unwrap()],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let dofs = read_dofs(&mats.join("dofs.txt"));
    assert_eq!(dofs.len(), 1555 * 3, "every node's three translations");
    let u: Vec<f64> = dofs.iter().map(|&(n, c)| s.nodes[&n][3 + c]).collect();
    let ku = multiply(&mats.join("K.mtx"), &u);
    let energy: f64 = u.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>() / 2.0;
    let sene: f64 = s.elements.values().map(|v| v[1]).sum();
    let error = (energy / sene - 1.0).abs();
    println!("½ uᵀ K u = {energy:.9e}, Σ SENE = {sene:.9e}: {error:.2e}");
    assert!(error < 3e-8, "{error:e}");
    let _ = std::fs::remove_dir_all(&dir);
}
