//! Element and assembled K, M against CalculiX 2.20's dumped matrices
//! (`fixtures/reference/e_matrices/`, `*FREQUENCY, SOLVER=MATRIXSTORAGE`), entry-wise, relative
//! to the largest entry; ccx equations are mapped to our dofs through its `.dof` table.

use crate::common::{dense, read_mesh_inp, reference};
use flexbody::fe::{assemble, AssemblySpec, MassKind, Tet10MassRule};
use flexbody::import::ccx_matrices::read_ccx_matrices;

/// Max |ours − ccx| / max |ccx| for K and M; also checks that ours has nothing outside ccx's dofs.
fn compare(case: &str, stem: &str) -> (f64, f64) {
    let model = read_mesh_inp(&reference(&format!("e_matrices/{case}/mesh.inp")));
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        tet10_mass: Tet10MassRule::CalculixFourPoint,
        ..Default::default()
    };
    let asm = assemble(&model, &spec).unwrap();
    let ccx = read_ccx_matrices(&reference(&format!("e_matrices/{case}/{stem}"))).unwrap();
    assert_eq!(
        ccx.dofs.len(),
        asm.dofs.n_dofs,
        "{case}: same number of equations (free run)"
    );
    let idx = model.node_index_by_id();
    let map: Vec<usize> = ccx
        .dofs
        .iter()
        .map(|d| asm.dofs.dof(idx[&d.node], d.dir as usize).unwrap())
        .collect();
    let (k, m) = (dense(&asm.k), dense(&asm.m));
    let rel = |ours: &faer::Mat<f64>,
               theirs: &flexbody::import::ccx_matrices::SymmetricTriplets| {
        let n = theirs.n;
        let mut t = faer::Mat::<f64>::zeros(n, n);
        for (r, c, v) in theirs.full() {
            t[(map[r], map[c])] = v;
        }
        let scale = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .fold(0.0f64, |a, (i, j)| a.max(t[(i, j)].abs()));
        let diff = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .fold(0.0f64, |a, (i, j)| a.max((ours[(i, j)] - t[(i, j)]).abs()));
        diff / scale
    };
    let ek = rel(&k, &ccx.k);
    let em = rel(&m, ccx.m.as_ref().unwrap());
    eprintln!("{case}: max rel. difference K {ek:.2e}, M {em:.2e}");
    (ek, em)
}

#[test]
fn hex8_single_k_and_m_match_ccx_1e10() {
    let (ek, em) = compare("hex8_single", "ccx_matrix_free");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}

#[test]
fn tet10_single_k_and_four_point_m_match_ccx_1e10() {
    let (ek, em) = compare("tet10_single", "ccx_matrix_free");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}

#[test]
fn hex8_block_coarse_assembled_k_and_m_match_ccx_1e10() {
    let (ek, em) = compare("hex8_block_coarse", "ccx_matrix_free");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}

#[test]
fn tet10_block_coarse_assembled_k_and_m_match_ccx_1e10() {
    let (ek, em) = compare("tet10_block_coarse", "ccx_matrix_free");
    assert!(ek < 1e-10 && em < 1e-10, "K {ek:e}, M {em:e}");
}
