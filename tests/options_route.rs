//! An option has one route (issue 48): the modes asked are resolved once into the plan's
//! `ModeRequest` (the deck's EIGRL included), and `--damping` is applied by the pipeline, so a
//! program calling `flexbody::build::build` gets the same file as the command line.

use std::path::{Path, PathBuf};

use flexbody::build::plan::Plan;
use flexbody::build::{build, BuildMethod, BuildSpec};
use flexbody::import::{read_model, ImportOptions};
use flexbody::reduce::select::{ModeCount, FMAX_FACTOR};
use flexbody_reader as file;

fn fixture(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

fn normal_modes(model: PathBuf) -> BuildSpec {
    BuildSpec {
        method: BuildMethod::Normal,
        ..BuildSpec::new(model, file::Units::si(), &[])
    }
}

#[test]
fn mode_request_takes_the_decks_eigrl_unless_modes_or_fmax_are_given() {
    // planar_beam.bdf: METHOD = 1, EIGRL,1,,,20 (ND = 20, no V2)
    let path = fixture("fixtures/models/planar_beam/planar_beam.bdf");
    let model = read_model(&path, &ImportOptions::default()).unwrap();
    let deck = Plan::resolve(&normal_modes(path.clone()), &model).unwrap();
    assert_eq!(deck.modes.solve, ModeCount::Count(20));
    assert_eq!(deck.modes.count, Some(20));
    assert_eq!(deck.modes.cap, None);
    assert!(deck
        .deck_notes
        .iter()
        .any(|n| n.contains("mode count: 20 modes")));
    // the stages cannot read the spec's own request: the plan's spec has it cleared
    assert_eq!((deck.spec.modes, deck.spec.fmax_hz), (None, None));

    // --fmax 100 --modes 2: the band 3 × 100 Hz, capped at 2; the deck's EIGRL not used
    let mut both = normal_modes(path.clone());
    (both.modes, both.fmax_hz) = (Some(2), Some(100.0));
    let plan = Plan::resolve(&both, &model).unwrap();
    assert_eq!(plan.modes.solve, ModeCount::BelowHz(FMAX_FACTOR * 100.0));
    assert_eq!((plan.modes.count, plan.modes.cap), (Some(2), Some(2)));
    assert_eq!(plan.modes.fmax_hz, Some(100.0));
    assert!(plan.deck_notes.iter().any(|n| n.contains("is not used")));

    // an --fmax that is no frequency is refused before the first stage
    let mut bad = normal_modes(path);
    bad.fmax_hz = Some(-3.0);
    let err = Plan::resolve(&bad, &model).unwrap_err().to_string();
    assert!(
        err.contains("--fmax -3 must be a positive frequency"),
        "{err}"
    );
}

#[test]
fn a_program_gets_the_damping_of_its_spec() {
    // Rayleigh ζ = α/(2ω) + βω/2 per flexible mode, 0 for the rigid ones (closed form)
    let (alpha, beta) = (1.0, 1.0e-6);
    let mut spec = normal_modes(fixture("fixtures/models/conrod/conrod.inp"));
    spec.modes = Some(12);
    spec.damping = Some(format!("rayleigh:{alpha},{beta}"));
    let out = build(&spec, &mut |_| {}).unwrap();
    let body = out.body;
    let ratio = &body
        .damping
        .as_ref()
        .expect("damping.bin from the spec")
        .ratio;
    assert_eq!(ratio.len(), body.modes.omega2.len());
    let mut flexible = 0;
    for ((z, &w2), label) in ratio.iter().zip(&body.modes.omega2).zip(&body.modes.labels) {
        if *label == file::ModeLabel::Rigid {
            assert_eq!(*z, 0.0);
            continue;
        }
        flexible += 1;
        let w = w2.sqrt();
        let exact = alpha / (2.0 * w) + beta * w / 2.0;
        // measured: equal to the last bit or two (the same formula, evaluated in f64)
        assert!((z - exact).abs() <= 1e-12 * exact, "ζ {z} vs {exact}");
    }
    assert_eq!(flexible, 6, "the conrod's 12 modes hold 6 rigid ones");
    let recorded = body.recipe.as_ref().and_then(|r| r.options.damping.clone());
    assert_eq!(recorded.as_deref(), Some("rayleigh:1,0.000001"));
}
