//! Craig–Bampton, Craig–Chang and Dietz on the CalculiX e_matrices hex8/tet10 blocks: spectra
//! against the full model (CB with all modes), CalculiX fixed-interface frequencies, span
//! properties, and dependent attachment vectors removed and reported.

use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;
use flexbody::import::ccx_matrices::read_ccx_matrices;
use flexbody::reduce::craig_bampton::{
    craig_bampton, craig_bampton_basis, craig_bampton_owned, orthonormalize_basis, projection,
};
use flexbody::reduce::craig_chang::{craig_chang, unit_loads};
use flexbody::reduce::dietz::{dietz, dietz_modified};
use flexbody::reduce::normal::normal_modes;
use flexbody::reduce::orthonormalize::orthonormalize;
use flexbody::reduce::select::{by_fmax, ModeCount, FMAX_FACTOR};
use flexbody::reduce::{ModeLabel, ModeSet};
use flexbody::solve::{sparse_ops, EigenSpec};
use std::path::{Path, PathBuf};

type Sparse = SparseColMat<usize, f64>;

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/reference/e_matrices")
        .join(name)
}

fn to_sparse(n: usize, t: &[(usize, usize, f64)]) -> Sparse {
    let trips: Vec<_> = t.iter().map(|&(i, j, v)| Triplet::new(i, j, v)).collect();
    SparseColMat::try_new_from_triplets(n, n, &trips).unwrap()
}

/// K, M of the free dump and the equation indices of the nodes of node set `set`.
fn load(name: &str, set: &str) -> (Sparse, Sparse, Vec<usize>) {
    let dir = case(name);
    let c = read_ccx_matrices(&dir.join("ccx_matrix_free")).unwrap();
    let mm = c.m.as_ref().unwrap();
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("case.json")).unwrap()).unwrap();
    let nodes: Vec<u64> = j["node_sets"][set]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    let dofs = (0..c.dofs.len())
        .filter(|&i| nodes.contains(&c.dofs[i].node))
        .collect();
    (
        to_sparse(c.k.n, &c.k.full()),
        to_sparse(mm.n, &mm.full()),
        dofs,
    )
}

fn ccx_freqs(path: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut out = Vec::new();
    let mut on = false;
    for line in text.lines() {
        if line.contains("E I G E N V A L U E   O U T P U T") {
            on = true;
            continue;
        }
        if line.contains("P A R T I C I P A T I O N") {
            break;
        }
        let f: Vec<&str> = line.split_whitespace().collect();
        if on && f.len() == 5 && f[0].parse::<usize>().is_ok() {
            out.push(f[1].parse::<f64>().unwrap().max(0.0).sqrt() / (2.0 * std::f64::consts::PI));
        }
    }
    out
}

fn eig() -> EigenSpec {
    EigenSpec {
        dofs_per_node: Some(3),
        ..Default::default()
    }
}

fn checks(s: &ModeSet) {
    assert!(
        s.diagnostics.orthonormality <= 1e-10,
        "orth {}",
        s.diagnostics.orthonormality
    );
    assert!(
        s.diagnostics.stiffness_diag <= 1e-10,
        "kdiag {}",
        s.diagnostics.stiffness_diag
    );
    assert!(s.omega2.iter().all(|v| v.is_finite()));
}

/// ‖x − ΦΦᵀMx‖_M / ‖x‖_M, the part of x outside span Φ.
fn outside(set: &ModeSet, m: &Sparse, x: &Mat<f64>) -> f64 {
    let mx = sparse_ops::spmm(m.as_ref(), x.as_ref());
    let c = set.phi.transpose() * &mx;
    let r = x - &set.phi * &c;
    let mr = sparse_ops::spmm(m.as_ref(), r.as_ref());
    let mut worst = 0.0f64;
    for j in 0..x.ncols() {
        let a = r.col(j).transpose() * mr.col(j);
        let b = x.col(j).transpose() * mx.col(j);
        worst = worst.max((a.max(0.0) / b).sqrt());
    }
    worst
}

#[test]
fn cb_all_fixed_interface_modes_is_the_full_spectrum_hex8() {
    let (k, m, ends) = load("hex8_block_coarse", "ENDS");
    let n = k.nrows();
    let full = normal_modes(&k, &m, ModeCount::Count(n), &[], &eig()).unwrap();
    let cb = craig_bampton(&k, &m, &ends, ModeCount::All, &eig()).unwrap();
    checks(&cb);
    assert_eq!(cb.len(), n);
    let lmax = full.omega2[n - 1];
    // rigid modes compared in absolute terms (their ω² is rounding noise of the dumped K)
    for j in 0..n {
        let tol = 1e-9 * full.omega2[j].abs().max(full.omega2[6]);
        assert!(
            (cb.omega2[j] - full.omega2[j]).abs() <= tol,
            "mode {j}: {} vs {}",
            cb.omega2[j],
            full.omega2[j]
        );
    }
    assert!(lmax > 0.0);
}

#[test]
fn cb_truncated_is_rayleigh_ritz_bound_tet10() {
    let (k, m, ends) = load("tet10_block_coarse", "ENDS");
    let full = normal_modes(&k, &m, ModeCount::Count(60), &[], &eig()).unwrap();
    for nq in [5, 20] {
        let cb = craig_bampton(&k, &m, &ends, ModeCount::Count(nq), &eig()).unwrap();
        checks(&cb);
        assert_eq!(
            cb.labels.iter().filter(|l| **l == ModeLabel::Rigid).count(),
            6
        );
        for j in 6..cb.len().min(60) {
            assert!(
                cb.omega2[j] >= full.omega2[j] * (1.0 - 1e-10),
                "nq {nq} mode {j}"
            );
        }
        // the lowest flexible modes are well represented
        let rel = cb.omega2[6] / full.omega2[6] - 1.0;
        assert!(
            rel < if nq == 20 { 1e-3 } else { 5e-2 },
            "nq {nq}: first flexible off by {rel}"
        );
    }
}

/// The Craig–Bampton projection from the constraint columns alone (T_qᵀKT_q = diag(ω²) and
/// T_qᵀMT_q = I taken from the eigensolver) equals TᵀKT and TᵀMT formed with every column, and
/// the set orthonormalized with it equals the generic orthonormalization of the same basis.
#[test]
fn cb_projection_from_the_constraint_columns_equals_the_full_products() {
    let (k, m, ends) = load("tet10_block_coarse", "ENDS");
    let basis = craig_bampton_basis(&k, &m, &ends, ModeCount::Count(20), &eig()).unwrap();
    let known = projection(&k, &m, &basis.t, &basis.fixed_omega2);
    let kh = basis.t.transpose() * sparse_ops::spmm(k.as_ref(), basis.t.as_ref());
    let mh = basis.t.transpose() * sparse_ops::spmm(m.as_ref(), basis.t.as_ref());
    let rel = |a: &Mat<f64>, b: &Mat<f64>| (a - b).norm_max() / b.norm_max();
    let (ek, em) = (rel(&known.kh, &kh), rel(&known.mh, &mh));
    eprintln!("projection: K {ek:.1e}, M {em:.1e}");
    // measured 2.3e-15 (K) and 1.5e-15 (M)
    assert!(ek <= 2e-14 && em <= 2e-14, "K {ek:.1e}, M {em:.1e}");
    let fused = orthonormalize_basis(&k, &m, &basis).unwrap();
    let generic = orthonormalize(&k, &m, &basis.t, &basis.labels).unwrap();
    assert_eq!(fused.omega2.len(), generic.omega2.len());
    // flexible modes relative to themselves, the six rigid ones (ω² of rounding size) to the top
    let top = generic.omega2.last().copied().unwrap();
    let (mut flexible, mut rigid) = (0.0f64, 0.0f64);
    for ((a, b), label) in fused
        .omega2
        .iter()
        .zip(&generic.omega2)
        .zip(&generic.labels)
    {
        if *label == ModeLabel::Rigid {
            rigid = rigid.max((a - b).abs() / top);
        } else {
            flexible = flexible.max((a - b).abs() / b);
        }
    }
    let orth = fused.diagnostics.orthonormality;
    eprintln!("eigenvalues: flexible {flexible:.1e}, rigid {rigid:.1e}; orthonormality {orth:.1e}");
    // measured 1.8e-11 (rounding of the top ω², ~eps·ω²_max, on the lowest flexible one) and 9.3e-17
    assert!(
        flexible <= 1e-10 && rigid <= 1e-15,
        "{flexible:.1e}, {rigid:.1e}"
    );
    assert_eq!(fused.labels, generic.labels);
    assert!(orth <= 5e-14, "{orth:.1e}"); // measured 5.3e-15
}

#[test]
fn cb_fixed_interface_modes_equal_ccx_fixed_run() {
    for name in ["hex8_block_coarse", "tet10_block_coarse"] {
        let (k, m, x0) = load(name, "END_X0");
        let basis = craig_bampton_basis(&k, &m, &x0, ModeCount::Count(10), &eig()).unwrap();
        let ccx = ccx_freqs(&case(name).join("ccx_fixed.dat"));
        for (i, &l) in basis.fixed_omega2.iter().enumerate() {
            let f = l.sqrt() / (2.0 * std::f64::consts::PI);
            assert!(
                (f - ccx[i]).abs() <= 2e-6 * ccx[i],
                "{name} {i}: {f} vs ccx {}",
                ccx[i]
            );
        }
    }
}

/// K and M handed over by value (the build's path: split into interior blocks and borders, then
/// joined) give the same mode set, bit for bit, as the borrowed path, and come back unchanged.
#[test]
fn cb_owned_matrices_give_the_borrowed_result_and_come_back_unchanged() {
    for (name, set) in [
        ("hex8_block_coarse", "ENDS"),
        ("tet10_block_coarse", "END_X0"),
    ] {
        let (k, m, iface) = load(name, set);
        let borrowed = craig_bampton(&k, &m, &iface, ModeCount::Count(10), &eig()).unwrap();
        let (owned, k2, m2) =
            craig_bampton_owned(k.clone(), m.clone(), &iface, ModeCount::Count(10), &eig())
                .unwrap();
        assert_eq!(owned.omega2, borrowed.omega2, "{name}");
        assert_eq!(owned.phi, borrowed.phi, "{name}");
        for (a, b) in [(&k, &k2), (&m, &m2)] {
            assert_eq!(a.symbolic().col_ptr(), b.symbolic().col_ptr(), "{name}");
            assert_eq!(a.symbolic().row_idx(), b.symbolic().row_idx(), "{name}");
            assert_eq!(a.val(), b.val(), "{name}");
        }
    }
}

#[test]
fn cb_fmax_selection_keeps_rigid_and_modes_below_cutoff() {
    let (k, m, ends) = load("hex8_block_coarse", "ENDS");
    let cb = craig_bampton(&k, &m, &ends, ModeCount::Count(10), &eig()).unwrap();
    let scene = 1500.0;
    let sel = by_fmax(cb, scene);
    let f = sel.frequencies_hz();
    assert!(f.iter().all(|&x| x <= FMAX_FACTOR * scene));
    // rigid (6) + 1241, 1241, 3221, 3337, 3337 Hz flexible modes are below 4500 Hz
    assert_eq!(sel.len(), 11, "{f:?}");
}

#[test]
fn craig_chang_span_contains_free_modes_and_static_solutions() {
    let (k, m, ends) = load("hex8_block_coarse", "ENDS");
    let fa = unit_loads(k.nrows(), &ends).unwrap();
    let nn = 16;
    let cc = craig_chang(&k, &m, &fa, ModeCount::Count(nn), &eig()).unwrap();
    checks(&cc);
    let ff = normal_modes(&k, &m, ModeCount::Count(nn), &[], &eig()).unwrap();
    let out = outside(&cc, &m, &ff.phi);
    assert!(
        out < 1e-9,
        "free-free modes outside the Craig–Chang span: {out}"
    );
    for j in 6..nn {
        assert!(
            (cc.omega2[j] - ff.omega2[j]).abs() <= 1e-9 * ff.omega2[j],
            "{j}"
        );
    }
    // inertia-relief static response to an interface load, solved densely from the bordered
    // system [K MXr; XrᵀM 0][y; μ] = [Pf; 0]: it lies in the span (attachment completeness)
    let n = k.nrows();
    let kd = sparse_ops::to_dense(k.as_ref());
    let md = sparse_ops::to_dense(m.as_ref());
    let xr = ff.phi.as_ref().subcols(0, 6).to_owned();
    let mxr = &md * &xr;
    let mut f = Mat::<f64>::zeros(n, 1);
    f[(ends[4], 0)] = 1.0;
    let pf = &f - &mxr * (xr.transpose() * &f);
    let mut a = Mat::<f64>::zeros(n + 6, n + 6);
    a.as_mut().submatrix_mut(0, 0, n, n).copy_from(kd.as_ref());
    a.as_mut().submatrix_mut(0, n, n, 6).copy_from(mxr.as_ref());
    a.as_mut()
        .submatrix_mut(n, 0, 6, n)
        .copy_from(mxr.transpose());
    let mut rhs = Mat::<f64>::zeros(n + 6, 1);
    rhs.as_mut()
        .submatrix_mut(0, 0, n, 1)
        .copy_from(pf.as_ref());
    let sol = a.as_ref().partial_piv_lu().solve(&rhs);
    let y = sol.as_ref().submatrix(0, 0, n, 1).to_owned();
    let out = outside(&cc, &m, &y);
    assert!(
        out < 1e-8,
        "inertia-relief response outside the Craig–Chang span: {out}"
    );
    assert!(cc.diagnostics.notes.iter().any(|n| n.contains("support")));
}

#[test]
fn craig_chang_dependent_attachments_are_removed_and_reported() {
    let (k, m, ends) = load("hex8_block_coarse", "ENDS");
    let mut dofs = ends.clone();
    dofs.extend_from_slice(&ends[..5]); // 5 duplicated attachment loads
    let fa = unit_loads(k.nrows(), &dofs).unwrap();
    let cc = craig_chang(&k, &m, &fa, ModeCount::Count(12), &eig()).unwrap();
    checks(&cc);
    assert!(
        cc.diagnostics.removed.len() >= 5,
        "removed {:?}",
        cc.diagnostics.removed.len()
    );
    assert!(cc
        .diagnostics
        .removed
        .iter()
        .all(|r| matches!(r.label, ModeLabel::Attachment { .. })));
    assert!(cc.len() <= 12 + ends.len());
}

#[test]
fn dietz_static_and_modified_agree_and_contain_the_response() {
    let (k, m, ends) = load("hex8_block_coarse", "ENDS");
    let n = k.nrows();
    let fa = unit_loads(n, &ends[..6]).unwrap();
    let st = dietz(&k, &m, &fa, ModeCount::Count(12), None, &eig()).unwrap();
    let md = dietz_modified(&k, &m, &fa, 12, n, None, &eig()).unwrap();
    checks(&st);
    checks(&md);
    assert_eq!(st.len(), md.len());
    for j in 6..st.len() {
        assert!(
            (st.omega2[j] - md.omega2[j]).abs() <= 1e-8 * st.omega2[j],
            "{j}: {} vs {}",
            st.omega2[j],
            md.omega2[j]
        );
    }
    // (K − ℓM) x = Fa solved densely lies in the span
    let ell = match st.method {
        flexbody::reduce::Method::Dietz { shift, .. } => shift,
        _ => unreachable!(),
    };
    let ff = normal_modes(&k, &m, ModeCount::Count(7), &[], &eig()).unwrap();
    assert!((ell - 0.25 * ff.omega2[6]).abs() <= 1e-9 * ell);
    let kd = sparse_ops::to_dense(k.as_ref());
    let md_ = sparse_ops::to_dense(m.as_ref());
    let a = Mat::from_fn(n, n, |i, j| kd[(i, j)] - ell * md_[(i, j)]);
    let x = a.as_ref().partial_piv_lu().solve(&fa);
    let out = outside(&st, &m, &x);
    assert!(
        out < 1e-7,
        "frequency response outside the Dietz span: {out}"
    );
}

#[test]
fn bad_dof_lists_are_errors() {
    use flexbody::reduce::reference::improved_cb_method1;
    use flexbody::reduce::ReduceError;
    let (k, m, ends) = load("hex8_block_coarse", "ENDS");
    let n = k.nrows();
    let r = craig_bampton(&k, &m, &[0, n], ModeCount::Count(4), &eig());
    assert!(matches!(r, Err(ReduceError::Dofs { .. })), "{r:?}");
    let r = craig_bampton(&k, &m, &[3, 3], ModeCount::Count(4), &eig());
    assert!(matches!(r, Err(ReduceError::Dofs { .. })), "{r:?}");
    // a reference dof that is not an interface dof
    let inner = (0..n).find(|d| !ends.contains(d)).unwrap();
    let r = improved_cb_method1(&k, &m, &ends, &[inner], ModeCount::Count(4), &eig());
    assert!(matches!(r, Err(ReduceError::Dofs { .. })), "{r:?}");
    assert!(matches!(
        unit_loads(n, &[n + 1]),
        Err(ReduceError::Dofs { .. })
    ));
}

#[test]
fn normal_modes_with_fixed_end_equal_ccx_fixed_and_count_selection() {
    use flexbody::reduce::select::by_count;
    let (k, m, x0) = load("tet10_block_coarse", "END_X0");
    let s = normal_modes(&k, &m, ModeCount::Count(10), &x0, &eig()).unwrap();
    checks(&s);
    assert_eq!(s.reference_dofs, x0);
    assert!(x0
        .iter()
        .all(|&d| (0..s.len()).all(|j| s.phi[(d, j)] == 0.0)));
    let ccx = ccx_freqs(&case("tet10_block_coarse").join("ccx_fixed.dat"));
    for (j, f) in s.frequencies_hz().iter().enumerate() {
        assert!(
            (f - ccx[j]).abs() <= 2e-6 * ccx[j],
            "{j}: {f} vs {}",
            ccx[j]
        );
        assert!(
            s.diagnostics.residuals[j] <= 1e-8,
            "{j}: {}",
            s.diagnostics.residuals[j]
        );
    }
    let s4 = by_count(s, 4);
    assert_eq!(s4.len(), 4);
    assert_eq!(
        s4.selection,
        Some(flexbody::reduce::select::Selection::Count(4))
    );
}
