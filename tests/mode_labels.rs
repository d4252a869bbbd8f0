//! Issue 16, labels that are true (and counts and cutoffs with one definition each): `Rigid` only for zero-frequency rigid-body modes by one test
//! for every method, and an orthonormalized multi-stage basis labels each mode by the origin
//! with the largest participation share, the share stored in `label_shares.bin` (SPEC §5.5).

use std::path::Path;

use faer::Mat;
use flexbody::build::{build, BuildMethod, BuildSpec};
use flexbody::reduce::orthonormalize::origin_labels;
use flexbody::reduce::ModeLabel;
use flexbody_reader as file;

/// The share rule by hand: w = [[3, 0], [4, 1], [0, 2]] over basis (Normal, Attachment,
/// Rigid). Mode 0: w² = 9, 16, 0 → Attachment with 16/25. Mode 1: w² = 0, 1, 4 → the rigid
/// column dominates but the mode is elastic, so it is the largest non-rigid kind, Attachment,
/// with share 1/5. A mode flagged rigid is `Rigid` with share 1.
#[test]
fn origin_label_is_the_largest_non_rigid_share() {
    let w = Mat::from_fn(3, 2, |r, c| [[3.0, 0.0], [4.0, 1.0], [0.0, 2.0]][r][c]);
    let basis = [
        ModeLabel::Normal,
        ModeLabel::Attachment { dof: 7 },
        ModeLabel::Rigid,
    ];
    let (labels, shares) = origin_labels(&[false, false], &w, &basis);
    assert_eq!(
        labels,
        [
            ModeLabel::Attachment { dof: 7 },
            ModeLabel::Attachment { dof: 7 }
        ]
    );
    assert!((shares[0] - 0.64).abs() < 1e-15 && (shares[1] - 0.2).abs() < 1e-15);
    let (labels, shares) = origin_labels(&[true, false], &w, &basis);
    assert_eq!(labels[0], ModeLabel::Rigid);
    assert_eq!(shares[0], 1.0);
}

/// Dietz, Craig–Chang, CB and normal-mode builds of the connecting rod (free body, spiders on
/// both bores, 20 modes): exactly the 6 zero-frequency modes are `Rigid`, none above
/// 1e-4·f_max; labels and shares agree with the file; normal modes are pure (share 1);
/// the multi-stage bases record mixtures (some share < 1). Before this rule the Dietz file
/// labelled elastic modes at 82.9, 92.6 and 119.2 kHz `Rigid`.
#[test]
fn only_zero_frequency_modes_are_rigid_for_every_method() {
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp");
    let mut bands = Vec::new();
    for method in [
        BuildMethod::Dietz,
        BuildMethod::CraigChang,
        BuildMethod::CraigBampton,
        BuildMethod::Normal,
    ] {
        // The same spiders for every method (normal modes too), so all see one model.
        let interface = ["BIG_END", "SMALL_END"];
        let mut spec = BuildSpec::new(model.clone(), file::Units::si(), &interface);
        spec.method = method;
        spec.modes = Some(20);
        let body = build(&spec, &mut |_| {}).unwrap().body;
        let f = &body.modes.frequency_hz;
        let f_max = f.iter().copied().fold(0.0, f64::max);
        let labels = &body.modes.labels;
        let shares = body.label_shares.as_ref().expect("build writes shares");
        for j in 0..f.len() {
            let rigid = labels[j] == file::ModeLabel::Rigid;
            assert_eq!(
                rigid,
                f[j] <= 1e-4 * f_max,
                "{method:?} mode {j}: {} Hz labelled {:?}",
                f[j],
                labels[j]
            );
            assert!(shares[j] > 0.0 && shares[j] <= 1.0);
            if rigid {
                assert_eq!(shares[j], 1.0);
            }
        }
        assert_eq!(
            labels
                .iter()
                .filter(|l| **l == file::ModeLabel::Rigid)
                .count(),
            6
        );
        // method.bin counts (SPEC §5.7): rigid = modes labelled Rigid, the rest basis vectors by
        // origin; 2 spiders × 6 dofs = 12 interface dofs; 20 free-free modes = 6 rigid + 14.
        let c = body.method.counts;
        let cut = body.method.cutoffs;
        let want = match method {
            BuildMethod::Normal => (6, 14, 0, 0, 0),
            BuildMethod::CraigBampton => (6, 0, 12, 20, 0),
            _ => (6, 14, 0, 0, 12),
        };
        assert_eq!(
            (
                c.rigid,
                c.normal,
                c.constraint,
                c.fixed_interface,
                c.attachment
            ),
            want,
            "{method:?}"
        );
        assert_eq!(c.removed_dependent, 0, "{method:?}");
        assert_eq!(cut.fmax_hz, None, "no --fmax given");
        assert_eq!(
            cut.shift_fraction,
            (method == BuildMethod::Dietz).then_some(0.25)
        );
        assert_eq!(
            cut.dependency_tolerance,
            (method != BuildMethod::Normal).then_some(1e-8)
        );
        let band = body.recipe.as_ref().unwrap().accuracy_band.clone();
        bands.push((method, band.rule, band.fmax_hz, f_max));
        let mixed = shares.iter().filter(|&&s| s < 0.99).count();
        if method == BuildMethod::Normal {
            assert_eq!(mixed, 0, "normal modes are pure");
        } else {
            assert!(
                mixed > 0,
                "{method:?}: an orthonormalized basis mixes its origins"
            );
        }
    }
    // Accuracy bands of these `--modes 20` builds (SPEC §5.11): normal modes up to their highest
    // mode; Craig–Chang and Dietz up to their highest free-free mode — the same 20 free-free
    // modes, so the same frequency; CB a third of its highest fixed-interface frequency.
    let normal = bands.iter().find(|b| b.0 == BuildMethod::Normal).unwrap();
    assert_eq!(normal.1, "normal-modes");
    assert!((normal.2 / normal.3 - 1.0).abs() < 1e-12);
    for b in &bands {
        match b.0 {
            BuildMethod::CraigChang | BuildMethod::Dietz => {
                assert_eq!(b.1, "free-free");
                assert!((b.2 / normal.2 - 1.0).abs() < 1e-9, "{b:?} vs {normal:?}");
            }
            BuildMethod::CraigBampton => assert_eq!(b.1, "fixed-interface"),
            BuildMethod::Normal => {}
        }
    }
}

/// SPEC §5.5 with residual vectors: the labels and shares of a two-stage build (Craig–Bampton,
/// then residual vectors) refer to the original basis vectors — the CB basis T and the static
/// responses r themselves. Checked against the final Φ expressed on [T | r] by the M-inner
/// least squares N = (BᵀMB)⁻¹BᵀMΦ, w_cj = N_cj·√(B_cᵀMB_c): a free chain of 40 unequal masses
/// and springs, interface at both ends, 4 fixed-interface modes, loads at dofs 13 and 29.
#[test]
fn residual_vector_shares_refer_to_the_original_basis_vectors() {
    use faer::linalg::solvers::Solve;
    use faer::sparse::{SparseColMat, Triplet};
    use flexbody::reduce::craig_bampton::{craig_bampton, craig_bampton_basis};
    use flexbody::reduce::residual::{add_residual_vectors, static_responses};
    use flexbody::reduce::select::ModeCount;
    use flexbody::solve::EigenSpec;
    let n = 40;
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    for i in 0..n {
        mt.push(Triplet::new(i, i, 1.0 + 0.37 * ((i * 7) % 5) as f64));
    }
    for i in 0..n - 1 {
        let s = 1000.0 * (1.0 + 0.5 * ((i * 3) % 4) as f64);
        kt.extend([
            Triplet::new(i, i, s),
            Triplet::new(i + 1, i + 1, s),
            Triplet::new(i, i + 1, -s),
            Triplet::new(i + 1, i, -s),
        ]);
    }
    let k = SparseColMat::try_new_from_triplets(n, n, &kt).unwrap();
    let m = SparseColMat::try_new_from_triplets(n, n, &mt).unwrap();
    let eig = EigenSpec::default();
    let ends = [0, n - 1];
    let cb = craig_bampton(&k, &m, &ends, ModeCount::Count(4), &eig).unwrap();
    let t = craig_bampton_basis(&k, &m, &ends, ModeCount::Count(4), &eig).unwrap();
    let f = Mat::from_fn(n, 2, |i, j| f64::from(u8::from(i == [13, 29][j])));
    let r = static_responses(&k, &m, &cb, &f, &eig).unwrap();
    let (set, report) = add_residual_vectors(&k, &m, cb, &f, &eig).unwrap();
    assert_eq!(report.kept, 2, "both responses add to the CB basis");
    // B = [T | r], N = (BᵀMB)⁻¹ BᵀMΦ
    let nb = t.t.ncols() + 2;
    let b = Mat::from_fn(n, nb, |i, c| {
        if c < t.t.ncols() {
            t.t[(i, c)]
        } else {
            r[(i, c - t.t.ncols())]
        }
    });
    let md = Mat::from_fn(n, n, |i, j| f64::from(u8::from(i == j)) * mt[i].val);
    let g = b.transpose() * &md * &b;
    let rhs = b.transpose() * &md * &set.phi;
    let coeffs = g.partial_piv_lu().solve(&rhs);
    // the final modes lie in span[T | r]
    let back = &b * &coeffs - &set.phi;
    let miss = (0..n)
        .flat_map(|i| (0..set.len()).map(move |j| (i, j)))
        .fold(0.0f64, |a, (i, j)| a.max(back[(i, j)].abs()));
    assert!(miss < 1e-9, "Φ outside span[T | r]: {miss:e}");
    let mut basis = t.labels.clone();
    basis.extend([
        ModeLabel::Residual { load: 0 },
        ModeLabel::Residual { load: 1 },
    ]);
    let w = Mat::from_fn(nb, set.len(), |c, j| coeffs[(c, j)] * g[(c, c)].sqrt());
    let rigid: Vec<bool> = set.labels.iter().map(|l| *l == ModeLabel::Rigid).collect();
    let (labels, shares) = origin_labels(&rigid, &w, &basis);
    let kinds = |l: &ModeLabel| std::mem::discriminant(l);
    let mut residual_modes = 0;
    for j in 0..set.len() {
        assert_eq!(
            kinds(&labels[j]),
            kinds(&set.labels[j]),
            "mode {j}: {:?} vs {:?}",
            labels[j],
            set.labels[j]
        );
        let d = (shares[j] - set.diagnostics.label_shares[j]).abs();
        assert!(
            d < 1e-8,
            "mode {j}: share {} vs least squares {}",
            set.diagnostics.label_shares[j],
            shares[j]
        );
        residual_modes += usize::from(matches!(set.labels[j], ModeLabel::Residual { .. }));
    }
    assert!(residual_modes >= 1, "{:?}", set.labels);
    // some mode mixes its origins (the test is not of pure modes only)
    assert!(
        set.diagnostics.label_shares.iter().any(|&s| s < 0.99),
        "{:?}",
        set.diagnostics.label_shares
    );
    // issue 37 item 1: a residual vector already in the basis is removed, and the labels and
    // shares are those of the build without it (they were all written as 1.0). The chain
    // grounded at dof 0, interface at the free end: the response to a load there is
    // K⁻¹e_b = ψ (K_bb − K_bi K_ii⁻¹ K_ib)⁻¹, the constraint mode ψ itself.
    kt.push(Triplet::new(0, 0, 5000.0));
    let k = SparseColMat::try_new_from_triplets(n, n, &kt).unwrap();
    let cb = craig_bampton(&k, &m, &[n - 1], ModeCount::Count(4), &eig).unwrap();
    let at_interface = Mat::from_fn(n, 1, |i, _| f64::from(u8::from(i == n - 1)));
    let (same, report) = add_residual_vectors(&k, &m, cb.clone(), &at_interface, &eig).unwrap();
    assert_eq!((report.kept, report.removed.len()), (0, 1), "{report:?}");
    assert_eq!(same.labels, cb.labels);
    for (a, b) in same
        .diagnostics
        .label_shares
        .iter()
        .zip(&cb.diagnostics.label_shares)
    {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
    assert!(cb.diagnostics.label_shares.iter().any(|&s| s < 0.99));
}
