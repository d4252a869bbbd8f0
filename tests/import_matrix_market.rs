//! Matrix Market import: CalculiX's own K and M of `hex8_single` (from the `.sti/.mas/.dof` dump)
//! written as Matrix Market, read back with a node table from the mesh, must give the dump's
//! entries exactly.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexbody::import::ccx_matrices::{read_ccx_matrices, SymmetricTriplets};
use flexbody::import::{abaqus, matrix_market};

fn reference(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/reference")
        .join(rel)
}

/// Matrix Market text of `t`: lower triangle (symmetric) or both triangles (general).
fn to_mm(t: &SymmetricTriplets, general: bool) -> String {
    let full = t.full();
    let list: Vec<_> = if general {
        full
    } else {
        t.upper.iter().map(|&(r, c, v)| (c, r, v)).collect()
    };
    let mut s = format!(
        "%%MatrixMarket matrix coordinate real {}\n% written by the test\n{} {} {}\n",
        if general { "general" } else { "symmetric" },
        t.n,
        t.n,
        list.len()
    );
    for (r, c, v) in list {
        writeln!(s, "{} {} {:?}", r + 1, c + 1, v).unwrap();
    }
    s
}

fn sorted(t: &SymmetricTriplets) -> Vec<(usize, usize, u64)> {
    let mut v: Vec<_> = t
        .upper
        .iter()
        .map(|&(r, c, x)| (r, c, x.to_bits()))
        .collect();
    v.sort_unstable();
    v
}

#[test]
fn ccx_hex8_single_round_trip_through_matrix_market() {
    let dump = read_ccx_matrices(&reference("e_matrices/hex8_single/ccx_matrix_free")).unwrap();
    let mesh = abaqus::read(&reference("e_matrices/hex8_single/mesh.inp")).unwrap();
    let dir = std::env::temp_dir().join(format!("flexbody_mm_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Node table in the dump's node order (3 dofs each, consecutive in the .dof file).
    let mut table = String::from("# id x y z ndof\n");
    for eq in dump.dofs.iter().step_by(3) {
        let n = mesh.nodes.iter().find(|n| n.id == eq.node).unwrap();
        writeln!(
            table,
            "{}, {:?}, {:?}, {:?}, 3",
            n.id, n.x[0], n.x[1], n.x[2]
        )
        .unwrap();
    }
    std::fs::write(dir.join("nodes.txt"), table).unwrap();
    let m_dump = dump.m.clone().unwrap();
    std::fs::write(dir.join("k.mtx"), to_mm(&dump.k, false)).unwrap();
    std::fs::write(dir.join("m.mtx"), to_mm(&m_dump, true)).unwrap();
    let mm = matrix_market::read(
        &dir.join("k.mtx"),
        &dir.join("m.mtx"),
        &dir.join("nodes.txt"),
    )
    .unwrap();
    assert_eq!(mm.dofs, dump.dofs);
    assert_eq!(mm.nodes.len(), 8);
    assert_eq!((mm.k.n, mm.m.n), (24, 24));
    assert_eq!(sorted(&mm.k), sorted(&dump.k));
    assert_eq!(sorted(&mm.m), sorted(&m_dump));
    // Total mass from M (sum of all entries / 3) = ρV = 5.40161012 kg (case.json).
    let total: f64 = mm.m.full().iter().map(|e| e.2).sum::<f64>() / 3.0;
    assert!((total - 5.401610119999975).abs() < 1e-9);
}

#[test]
fn ccx_dump_with_mesh_nodes() {
    let mesh = abaqus::read(&reference("e_matrices/hex8_block_coarse/mesh.inp")).unwrap();
    let mm = matrix_market::from_ccx_dump(
        &reference("e_matrices/hex8_block_coarse/ccx_matrix_fixed"),
        &mesh,
    )
    .unwrap();
    // Fixed run: END_X0 (9 nodes) constrained, so 90 of the 99 nodes carry equations.
    assert_eq!(mm.nodes.len(), 90);
    assert_eq!(mm.dofs.len(), 270);
    assert_eq!((mm.k.n, mm.m.n), (270, 270));
    let end = &mesh.node_sets["END_X0"];
    assert!(mm
        .nodes
        .iter()
        .all(|n| !end.iter().any(|&i| mesh.nodes[i].id == n.id)));
}
