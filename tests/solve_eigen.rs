//! `solve::lowest_modes` against CalculiX frequencies of the dumped e_matrices cases, the
//! numpy-derived spectra in their case.json, and the dense solver (repeated eigenvalues,
//! massless dofs).

use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;
use flexbody::import::ccx_matrices::read_ccx_matrices;
use flexbody::solve::{lowest_modes, lowest_modes_iterative, sparse_ops, EigenSpec, SolveError};
use std::path::{Path, PathBuf};

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/reference/e_matrices")
        .join(name)
}

type Sparse = SparseColMat<usize, f64>;

fn to_sparse(n: usize, t: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let trips: Vec<_> = t.iter().map(|&(i, j, v)| Triplet::new(i, j, v)).collect();
    SparseColMat::try_new_from_triplets(n, n, &trips).unwrap()
}

/// (K, M, equation dofs as (node, dir)) of a CalculiX dump.
fn load(stem: &Path) -> (Sparse, Sparse, Vec<(u64, u8)>) {
    let c = read_ccx_matrices(stem).unwrap();
    let m = c.m.as_ref().unwrap();
    let dofs = c.dofs.iter().map(|d| (d.node, d.dir)).collect();
    (
        to_sparse(c.k.n, &c.k.full()),
        to_sparse(m.n, &m.full()),
        dofs,
    )
}

/// Frequencies (Hz) printed by CalculiX in a .dat EIGENVALUE OUTPUT table.
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
            let lam: f64 = f[1].parse().unwrap();
            out.push(lam.max(0.0).sqrt() / (2.0 * std::f64::consts::PI));
        }
    }
    out
}

fn numpy_freqs(case_dir: &Path) -> Vec<f64> {
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(case_dir.join("case.json")).unwrap())
            .unwrap();
    let free = &j["checks"]["free"];
    let key = free
        .as_object()
        .unwrap()
        .keys()
        .find(|k| k.starts_with("numpy_eigh"))
        .unwrap()
        .clone();
    free[&key]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

fn hz(l: f64) -> f64 {
    l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

fn spec(count: usize) -> EigenSpec {
    EigenSpec {
        count,
        ..Default::default()
    }
}

/// Free-free check: exactly 6 rigid modes (below 2e-5·f7: the dumped K carries CalculiX's printed
/// digits, so its rigid modes sit at up to 0.0086 Hz = 8.4e-6·f7 also in numpy, see case.json), elastic ones equal ccx (2e-6) and the
/// numpy spectrum of the same matrices (1e-9).
fn check_free(name: &str, iterative: bool) {
    let dir = case(name);
    let (k, m, _) = load(&dir.join("ccx_matrix_free"));
    let s = if iterative {
        lowest_modes_iterative(&k, &m, &spec(20))
    } else {
        lowest_modes(&k, &m, &spec(20))
    };
    let s = s.unwrap();
    let f: Vec<f64> = s.eigenvalues.iter().map(|&l| hz(l)).collect();
    let rigid = f.iter().filter(|&&x| x < 2e-5 * f[6]).count();
    assert_eq!(rigid, 6, "{name}: {f:?}");
    let ccx = ccx_freqs(&dir.join("ccx_free.dat"));
    let np = numpy_freqs(&dir);
    for i in 6..20 {
        assert!(
            (f[i] - ccx[i]).abs() <= 2e-6 * ccx[i],
            "{name} mode {i}: {} vs ccx {}",
            f[i],
            ccx[i]
        );
        assert!(
            (f[i] - np[i]).abs() <= 1e-9 * np[i],
            "{name} mode {i}: {} vs numpy {}",
            f[i],
            np[i]
        );
        assert!(
            s.residuals[i] <= 1e-8,
            "{name} residual {i}: {}",
            s.residuals[i]
        );
    }
    assert!(s.info.orthonormality <= 1e-10, "{}", s.info.orthonormality);
    assert!(s.info.stiffness_diag <= 1e-10, "{}", s.info.stiffness_diag);
}

#[test]
fn hex8_free_dense_matches_ccx() {
    check_free("hex8_block_coarse", false);
}

#[test]
fn hex8_free_iterative_matches_ccx() {
    check_free("hex8_block_coarse", true);
}

#[test]
fn tet10_free_consistent_singular_mass_matches_ccx() {
    check_free("tet10_block_coarse", true);
}

/// Band mode (`--fmax`): starting from 6 modes, one iteration grows its count (6 → 12 → 24, capped
/// at n/6) until a converged mode lies above the limit, and returns exactly the modes below it
/// plus that one; they equal the numpy spectrum of the same matrices.
#[test]
fn band_mode_grows_to_every_mode_below_the_limit() {
    for name in ["hex8_block_coarse", "tet10_block_coarse"] {
        let dir = case(name);
        let (k, m, _) = load(&dir.join("ccx_matrix_free"));
        let np = numpy_freqs(&dir);
        assert!(k.nrows() / 6 >= 17, "{name}: n = {}", k.nrows());
        let band = |f_cut: f64| {
            let upper = (2.0 * std::f64::consts::PI * f_cut).powi(2);
            let banded = EigenSpec {
                upper: Some(upper),
                ..spec(6)
            };
            let s = lowest_modes_iterative(&k, &m, &banded).unwrap();
            let f: Vec<f64> = s.eigenvalues.iter().map(|&l| hz(l)).collect();
            (s, f)
        };
        // the limit halfway between numpy modes 15 and 16 (0-based): 16 modes lie below it
        let f_cut = 0.5 * (np[15] + np[16]);
        let (s, f) = band(f_cut);
        assert_eq!(f.len(), 17, "{name}: {f:?}");
        assert!(f[15] <= f_cut && f[16] > f_cut, "{name}: {f:?}");
        for i in 6..17 {
            assert!(
                (f[i] - np[i]).abs() <= 1e-9 * np[i],
                "{name} mode {i}: {} vs numpy {}",
                f[i],
                np[i]
            );
        }
        // one factorization, and fewer solved vectors than runs of 6, 12 and 24 modes would need
        let counted: usize = [6, 12, 24]
            .iter()
            .map(|&c| {
                lowest_modes_iterative(&k, &m, &spec(c))
                    .unwrap()
                    .info
                    .solves
            })
            .sum();
        assert!(
            s.info.solves < counted,
            "{name}: {} vs {counted}",
            s.info.solves
        );
        // a limit between the rigid modes and the first flexible one: the 6 rigid + that one
        let (_, f) = band(0.5 * np[6]);
        assert_eq!(f.len(), 7, "{name}: {f:?}");
        assert!((f[6] - np[6]).abs() <= 1e-9 * np[6], "{name}: {f:?}");
        // without a limit the same call returns just the 6 asked for
        let six = lowest_modes_iterative(&k, &m, &spec(6)).unwrap();
        assert_eq!(six.eigenvalues.len(), 6);
    }
}

/// Constrained run: K, M restricted to the equations of the fixed dump equal ccx_fixed.dat.
fn check_fixed(name: &str) {
    let dir = case(name);
    let (k, m, dofs) = load(&dir.join("ccx_matrix_free"));
    let fixed_dofs: Vec<(u64, u8)> = std::fs::read_to_string(dir.join("ccx_matrix_fixed.dof"))
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let (a, b) = l.trim().split_once('.').unwrap();
            (a.parse().unwrap(), b.parse::<u8>().unwrap() - 1)
        })
        .collect();
    let keep: Vec<usize> = fixed_dofs
        .iter()
        .map(|d| dofs.iter().position(|e| e == d).unwrap())
        .collect();
    let kf = sparse_ops::submatrix(k.as_ref(), &keep, &keep).unwrap();
    let mf = sparse_ops::submatrix(m.as_ref(), &keep, &keep).unwrap();
    let s = lowest_modes_iterative(&kf, &mf, &spec(12)).unwrap();
    let ccx = ccx_freqs(&dir.join("ccx_fixed.dat"));
    assert!(ccx.len() >= 10);
    for (i, &c) in ccx.iter().take(10).enumerate() {
        let f = hz(s.eigenvalues[i]);
        assert!(
            (f - c).abs() <= 2e-6 * c,
            "{name} fixed mode {i}: {f} vs ccx {c}"
        );
    }
}

#[test]
fn hex8_fixed_matches_ccx() {
    check_fixed("hex8_block_coarse");
}

#[test]
fn tet10_fixed_matches_ccx() {
    check_fixed("tet10_block_coarse");
}

/// max singular-value defect of Aᵀ M B for two M-orthonormal bases of the same subspace.
fn subspace_defect(a: &Mat<f64>, b: &Mat<f64>, m: &SparseColMat<usize, f64>) -> f64 {
    let mb = sparse_ops::spmm(m.as_ref(), b.as_ref());
    let p = a.transpose() * &mb;
    let ptp = p.transpose() * &p;
    let mut d = 0.0f64;
    for i in 0..ptp.nrows() {
        for j in 0..ptp.ncols() {
            let id = if i == j { 1.0 } else { 0.0 };
            d = d.max((ptp[(i, j)] - id).abs());
        }
    }
    d
}

fn cols(x: &Mat<f64>, r: std::ops::Range<usize>) -> Mat<f64> {
    x.as_ref().subcols(r.start, r.len()).to_owned()
}

#[test]
fn repeated_eigenvalues_span_the_dense_subspace() {
    let (k, m, _) = load(&case("hex8_block_coarse").join("ccx_matrix_free"));
    let d = lowest_modes(&k, &m, &spec(16)).unwrap();
    let it = lowest_modes_iterative(
        &k,
        &m,
        &EigenSpec {
            count: 16,
            block: Some(4),
            ..Default::default()
        },
    )
    .unwrap();
    // 0..6 rigid, (6,7), (9,10), (12,13) double pairs on the square section
    for r in [0..6, 6..8, 9..11, 12..14] {
        let e = subspace_defect(
            &cols(&d.vectors, r.clone()),
            &cols(&it.vectors, r.clone()),
            &m,
        );
        assert!(e < 1e-8, "subspace {r:?}: defect {e}");
    }
    for i in 0..16 {
        let (a, b) = (d.eigenvalues[i], it.eigenvalues[i]);
        assert!(
            (a - b).abs() <= 1e-9 * b.abs().max(d.eigenvalues[6]),
            "{i}: {a} vs {b}"
        );
    }
}

#[test]
fn massless_dofs_lumped_mass_agrees_with_dense() {
    let (k, m, dofs) = load(&case("hex8_block_coarse").join("ccx_matrix_free"));
    let n = k.nrows();
    // row-sum lumped mass, with every fifth node massless
    let md = sparse_ops::to_dense(m.as_ref());
    let mut trips = Vec::new();
    for i in 0..n {
        let node = dofs[i].0;
        let row: f64 = (0..n).map(|j| md[(i, j)]).sum();
        if node % 5 != 0 {
            trips.push(Triplet::new(i, i, row));
        }
    }
    let ml = SparseColMat::try_new_from_triplets(n, n, &trips).unwrap();
    let massless = n - trips.len();
    assert!(massless > 30);
    let d = lowest_modes(&k, &ml, &spec(14)).unwrap();
    let it = lowest_modes_iterative(&k, &ml, &spec(14)).unwrap();
    assert!(d.info.dense && !it.info.dense);
    for i in 6..14 {
        let (a, b) = (d.eigenvalues[i], it.eigenvalues[i]);
        assert!((a - b).abs() <= 1e-9 * b, "{i}: dense {a} vs iterative {b}");
    }
    assert!(it.info.orthonormality <= 1e-10);
}

#[test]
fn bad_input_is_an_error() {
    let (k, m, _) = load(&case("hex8_block_coarse").join("ccx_matrix_free"));
    let small = sparse_ops::submatrix(m.as_ref(), &[0, 1, 2], &[0, 1, 2]).unwrap();
    assert!(matches!(
        lowest_modes(&k, &small, &spec(3)),
        Err(SolveError::Dimension(_))
    ));
    assert!(matches!(
        lowest_modes(&k, &m, &spec(0)),
        Err(SolveError::TooManyModes { .. })
    ));
    assert!(matches!(
        lowest_modes(&k, &m, &spec(1000)),
        Err(SolveError::TooManyModes { .. })
    ));
    // a positive shift above the first flexible eigenvalue makes K − σM indefinite
    let r = lowest_modes_iterative(
        &k,
        &m,
        &EigenSpec {
            count: 8,
            shift: Some(1e9),
            ..Default::default()
        },
    );
    assert!(
        matches!(r, Err(SolveError::NonPositivePivot { .. })),
        "{r:?}"
    );
}
