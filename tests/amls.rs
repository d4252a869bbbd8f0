//! AMLS (`solve::amls`) against our block shift-invert Lanczos on the bench's clamped tet10
//! block: eigenvalues of the modes well below the cutoff, the Rayleigh–Ritz contract
//! (ΦᵀMΦ = I, ΦᵀKΦ = diag to round-off), per-mode residuals, the Sylvester count; and a cutoff
//! too low to hold the band, which must say how many modes are missing.

use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec, MassKind};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::{DofMask, Elasticity, Material};
use flexbody::solve::amls::{amls, AmlsParams};
use flexbody::solve::{lowest_modes, EigenMethod, EigenSpec, SolveError, SparseColMat};

/// The bench's 0.5 × 0.1 × 0.1 m steel tet10 block of n bricks, x = 0 clamped, consistent mass.
fn clamped_block(n: [usize; 3]) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    let model = block(&BlockSpec {
        n,
        size: [0.5, 0.1, 0.1],
        element: BlockElement::Tet10Six,
        material: Material {
            id: 1,
            name: "STEEL".into(),
            e: 210e9,
            nu: 0.3,
            g: 210e9 / 2.6,
            rho: 7850.0,
            elasticity: Elasticity::Isotropic,
        },
    });
    let asm = assemble(
        &model,
        &AssemblySpec {
            mass: MassKind::Consistent,
            ..Default::default()
        },
    )
    .unwrap();
    let fixed = model.node_sets["X0"].clone();
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec {
            fixed: fixed.iter().map(|&i| (i, DofMask::ALL)).collect(),
            ..Default::default()
        },
    )
    .unwrap();
    (red.k, red.m)
}

fn spec(count: usize, method: EigenMethod) -> EigenSpec {
    EigenSpec {
        count,
        dofs_per_node: Some(3),
        method,
        ..Default::default()
    }
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / y.abs())
        .fold(0.0, f64::max)
}

#[test]
fn amls_agrees_with_lanczos_and_proves_its_band() {
    let (k, m) = clamped_block([20, 4, 4]);
    assert_eq!(k.nrows(), 9720);
    let count = 40;
    // The reference is a Rayleigh quotient too: its error is of the order of the high-frequency
    // content of its vector squared (λ_max(mesh)·‖δ‖²_M, ~1e-12 of λ on the highest of these 40
    // modes at the default tolerance 1e-10: two runs differing only in rounding were 1e-12
    // apart). At 1e-13 that is far below the 1e-12 the check below allows.
    let exact = lowest_modes(
        &k,
        &m,
        &EigenSpec {
            tol: 1e-13,
            ..spec(count, EigenMethod::Lanczos)
        },
    )
    .unwrap();
    // the defaults (cutoff 4x, two refinement steps) with leaves of 600 dofs: 17 leaves
    let params = AmlsParams {
        leaf_dofs: 600,
        ..Default::default()
    };
    let s = amls(&k, &m, &spec(count, EigenMethod::Lanczos), &params).unwrap();
    let (vals, r) = (&s.solution.eigenvalues, &s.report);
    println!(
        "leaves {} (largest {}), separators {} dofs, depth {}, root modes {}",
        r.leaves, r.largest_leaf, r.separator_dofs, r.depth, r.root_modes
    );
    let low = max_rel(&vals[..10], &exact.eigenvalues[..10]);
    let all = max_rel(vals, &exact.eigenvalues);
    let res = s.solution.residuals.iter().fold(0.0f64, |a, &b| a.max(b));
    let (orth, kd) = (
        s.solution.info.orthonormality,
        s.solution.info.stiffness_diag,
    );
    println!("lowest 10 {low:.2e}, all 40 {all:.2e}, residual {res:.2e}, orth {orth:.1e}, kdiag {kd:.1e}");
    // measured 7.3e-11 (lowest 10), 1.2e-5 (all 40), 3.2e-3 (largest residual)
    assert!(low < 7e-10, "{low:e}");
    assert!(all < 1e-4, "{all:e}");
    assert_eq!(s.solution.residuals.len(), count);
    assert!(res < 3e-2 && res > 0.0, "{res:e}");
    // round-off: measured 4.0e-15 and 2.3e-15
    assert!(orth < 3e-14 && kd < 3e-14, "{orth:e} {kd:e}");
    // AMLS eigenvalues are Rayleigh quotients: never below the exact ones (to round-off)
    for (a, e) in vals.iter().zip(&exact.eigenvalues) {
        assert!(*a >= e * (1.0 - 1e-12), "{a} below the exact {e}");
    }
    // Sylvester: 40 eigenvalues below the band top, 40 returned
    assert_eq!(
        (r.below_top, r.returned_below_top, s.missing()),
        (40, 40, 0)
    );
    assert!(s.solution.info.band_proof.is_some());

    // without refinement the contract still holds; only the accuracy is the cutoff's
    let plain = AmlsParams {
        refine: 0,
        ..params
    };
    let s0 = amls(&k, &m, &spec(count, EigenMethod::Lanczos), &plain).unwrap();
    let low0 = max_rel(&s0.solution.eigenvalues[..10], &exact.eigenvalues[..10]);
    println!("no refinement: lowest 10 {low0:.2e}");
    // measured 1.1e-3: refinement is what buys the 1e-9
    assert!(low0 < 1e-2 && low0 > 1e-6, "{low0:e}");
    assert!(s0.solution.info.orthonormality < 3e-14);
}

#[test]
fn a_cutoff_at_the_band_top_reports_the_missing_modes() {
    let (k, m) = clamped_block([20, 4, 4]);
    let exact = lowest_modes(&k, &m, &spec(41, EigenMethod::Lanczos)).unwrap();
    let e = &exact.eigenvalues;
    // the band: the lowest 40 (its top halfway to the 41st)
    let upper = 0.5 * (e[39] + e[40]);
    let band = EigenSpec {
        upper: Some(upper),
        ..spec(10, EigenMethod::Lanczos)
    };
    let params = AmlsParams {
        cutoff_factor: 1.0,
        leaf_dofs: 600,
        refine: 0,
    };
    let s = amls(&k, &m, &band, &params).unwrap();
    let r = &s.report;
    println!(
        "cutoff 1x: {} below the top by inertia, {} returned below it",
        r.below_top, r.returned_below_top
    );
    assert_eq!(r.below_top, 40);
    assert!(s.missing() > 0, "a cutoff at the band top lost no mode?");
    assert!(s.solution.info.band_proof.is_none());
    // through lowest_modes the same request is an error naming the count
    let method = EigenMethod::Amls(params);
    let err = lowest_modes(
        &k,
        &m,
        &EigenSpec {
            method,
            ..band.clone()
        },
    )
    .unwrap_err();
    match err {
        SolveError::MissedModes { missing, found, .. } => {
            assert_eq!((missing, found), (s.missing(), r.returned_below_top));
        }
        other => panic!("expected MissedModes, got {other}"),
    }
    // a generous cutoff finds the whole band
    let ok = EigenMethod::Amls(AmlsParams {
        leaf_dofs: 600,
        ..Default::default()
    });
    let s = lowest_modes(&k, &m, &EigenSpec { method: ok, ..band }).unwrap();
    let below = s.eigenvalues.iter().filter(|&&l| l <= upper).count();
    assert_eq!(below, 40);
}

fn conrod() -> String {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/models/conrod/conrod.inp")
        .display()
        .to_string()
}

/// Builds the conrod with `extra` options; the flexible frequencies and the recipe's
/// `options.eigensolver`.
fn build_conrod(out: &std::path::Path, extra: &[&str]) -> (Vec<f64>, Option<String>) {
    let o = crate::common::exe()
        .args(["build", &conrod(), "--interface", "BIG_END,SMALL_END"])
        .args(["--units", "si", "--threads", "1"])
        .args(extra)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{extra:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    // an AMLS build says what its modes are: Rayleigh–Ritz pairs and their largest residual
    let stderr = String::from_utf8_lossy(&o.stderr);
    let amls = extra
        .windows(2)
        .any(|w| w[0] == "--eigensolver" && w[1].starts_with("amls"));
    assert_eq!(
        stderr.contains("note: eigensolver amls:")
            && stderr.contains("Rayleigh-Ritz pairs")
            && stderr.contains("largest relative residual"),
        amls,
        "{extra:?}: {stderr}"
    );
    let body = flexbody_reader::read(out).unwrap();
    let f = (body.modes.frequency_hz.iter().zip(&body.modes.labels))
        .filter(|(_, l)| **l != flexbody_reader::ModeLabel::Rigid)
        .map(|(f, _)| *f)
        .collect();
    (f, body.recipe.and_then(|r| r.options.eigensolver))
}

#[test]
fn eigensolver_option_gives_lanczos_frequencies_through_the_cli() {
    let dir = crate::common::scratch("amls-cli");
    for (method, modes, limit_low, limit_all) in [
        // measured: normal 2.0e-10 / 1.7e-7, cb 6.3e-6 / 6.9e-5 (its fixed-interface modes'
        // errors reach the body), craig-chang 2.4e-8 / 2.6e-6 (lower half / all)
        ("normal", "30", 2e-9, 1e-6),
        ("cb", "12", 5e-5, 5e-4),
        ("craig-chang", "12", 2e-7, 2e-5),
    ] {
        let mut runs = vec![];
        for solver in ["lanczos", "amls"] {
            let out = dir.join(format!("{method}-{solver}.flexbody"));
            runs.push(build_conrod(
                &out,
                &[
                    "--method",
                    method,
                    "--modes",
                    modes,
                    "--eigensolver",
                    solver,
                ],
            ));
        }
        let (a, b) = (&runs[0], &runs[1]);
        assert_eq!(a.0.len(), b.0.len());
        let worst = max_rel(&b.0, &a.0);
        let half = a.0.len() / 2;
        let low = max_rel(&b.0[..half], &a.0[..half]);
        println!(
            "conrod {method} {modes} modes: AMLS vs Lanczos frequencies, lower half {low:.2e}, \
             all {worst:.2e}"
        );
        assert!(
            low < limit_low && worst < limit_all,
            "{method}: {low:e} {worst:e}"
        );
        assert_eq!(a.1.as_deref(), Some("lanczos"));
        assert_eq!(b.1.as_deref(), Some("amls"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bad_eigensolver_is_refused_by_name() {
    for (bad, says) in [
        ("arnoldi", "expected auto, lanczos, amls or amls:FACTOR"),
        ("amls:0.5", "cutoff factor must be a number >= 1"),
    ] {
        let o = crate::common::exe()
            .args([
                "build",
                &conrod(),
                "--units",
                "si",
                "--eigensolver",
                bad,
                "-o",
            ])
            .arg(crate::common::scratch("amls-bad").join("x.flexbody"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{bad} accepted");
        assert!(err.contains("--eigensolver") && err.contains(says), "{err}");
    }
}

/// `--eigensolver` has one route: `Plan::resolve` puts it into the eigen settings every solve
/// reads.
#[test]
fn the_plan_carries_the_eigensolver() {
    use flexbody::build::plan::Plan;
    use flexbody::build::BuildSpec;
    let path = std::path::PathBuf::from(conrod());
    let model = flexbody::import::read_model(&path, &Default::default()).unwrap();
    for text in ["auto", "lanczos", "amls", "amls:8"] {
        let method: EigenMethod = text.parse().unwrap();
        let spec = BuildSpec {
            eigensolver: method,
            ..BuildSpec::new(path.clone(), flexbody_reader::Units::si(), &[])
        };
        let plan = Plan::resolve(&spec, &model).unwrap();
        assert_eq!(plan.eigen.method, method);
        assert_eq!(plan.eigen.method.name(), text);
    }
    // auto is Lanczos at every size (docs/amls.md: AMLS was never measured faster)
    assert_eq!(EigenMethod::Auto.resolved(), EigenMethod::Lanczos);
}
