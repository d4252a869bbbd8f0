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
