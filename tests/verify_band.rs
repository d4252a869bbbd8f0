//! `--verify-band` (issue 22, the missed-mode proof): every eigenproblem of the build is proven
//! complete by Sylvester's inertia count of K − σM, σ just above the highest returned mode, and
//! a build whose mode count cuts a repeated eigenvalue fails loudly instead of writing half a
//! degenerate pair.

use std::path::{Path, PathBuf};

use flexbody::build::{build, build_model, BuildMethod, BuildSpec};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::Material;
use flexbody_reader as file;

fn conrod() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp")
}

/// (modes, Hz) of the report's band-check note of `problem`.
fn band_note(notes: &[String], problem: &str) -> Option<(usize, f64)> {
    let n = notes
        .iter()
        .find(|n| n.starts_with("band check:") && n.contains(&format!("lowest {problem} modes")))?;
    let words: Vec<&str> = n.split_whitespace().collect();
    let modes = words.iter().find_map(|w| w.parse::<usize>().ok())?;
    let at = words.iter().position(|w| *w == "below")?;
    Some((modes, words[at + 1].parse().ok()?))
}

fn conrod_spec(method: BuildMethod, modes: usize, verify: bool) -> BuildSpec {
    BuildSpec {
        method,
        modes: Some(modes),
        verify_band: verify,
        ..BuildSpec::new(conrod(), file::Units::si(), &["BIG_END", "SMALL_END"])
    }
}

/// Normal modes, Craig–Bampton and Craig–Chang on the conrod (sparse path): each proven band
/// ends at the highest mode of the method's own eigenproblem. Normal modes: the same solve asked
/// for 4 more modes without the proof has exactly the proven count at or below the band's top.
#[test]
fn conrod_bands_are_proven_complete_for_each_method() {
    for (method, problem) in [
        (BuildMethod::Normal, "normal"),
        (BuildMethod::CraigBampton, "fixed-interface"),
        (BuildMethod::CraigChang, "free-free"),
    ] {
        let out = build(&conrod_spec(method, 8, true), &mut |_| {}).unwrap();
        let notes = &out.report.diagnostics.notes;
        let (modes, top_hz) = band_note(notes, problem)
            .unwrap_or_else(|| panic!("{method:?}: no band note in {notes:?}"));
        println!("{method:?}: {modes} {problem} modes proven below {top_hz:.6e} Hz");
        let basis_top = match method {
            BuildMethod::Normal => *out.body.modes.frequency_hz.last().unwrap(),
            _ => hz(out.report.diagnostics.basis_top_omega2.unwrap()),
        };
        assert!(
            (top_hz - basis_top).abs() <= 1e-6 * basis_top,
            "{method:?}: proven top {top_hz} Hz vs the eigenproblem's highest mode {basis_top} Hz"
        );
        if method == BuildMethod::Normal {
            assert_eq!(modes, 8);
            let more = build(&conrod_spec(method, 12, false), &mut |_| {}).unwrap();
            let f = &more.body.modes.frequency_hz;
            let below = f.iter().filter(|&&x| x <= top_hz * (1.0 + 1e-7)).count();
            assert_eq!(below, modes, "{f:?} vs proven top {top_hz} Hz");
        }
    }
}

fn hz(omega2: f64) -> f64 {
    omega2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// A free square-section bar (hex8, symmetric under y ↔ z): its first flexible mode is a
/// bending pair with equal frequencies. Seven modes (6 rigid + 1) cut the pair: the band check
/// fails naming the cut; eight pass with the pair inside the proven band.
#[test]
fn a_mode_count_that_cuts_a_repeated_eigenvalue_fails_loudly() {
    let bar = || {
        block(&BlockSpec {
            n: [12, 2, 2],
            size: [1.2, 0.1, 0.1],
            element: BlockElement::Hex8,
            material: Material::steel(),
        })
    };
    let spec = |modes: usize| BuildSpec {
        method: BuildMethod::Normal,
        modes: Some(modes),
        verify_band: true,
        ..BuildSpec::new(
            PathBuf::from("square bar (generated)"),
            file::Units::si(),
            &[],
        )
    };
    let err = match build_model(&spec(7), bar(), &mut |_| {}) {
        Err(e) => e,
        Ok(out) => panic!(
            "7 modes cut the bending pair but the build passed: {:?}",
            out.body.modes.frequency_hz
        ),
    };
    let text = format!("{err}");
    assert!(
        text.contains("band check failed")
            && text.contains("returned 7 modes")
            && text.contains("1 more negative pivots")
            && text.contains("ask for one more mode"),
        "{text}"
    );
    let out = build_model(&spec(8), bar(), &mut |_| {}).unwrap();
    let (modes, top_hz) = band_note(&out.report.diagnostics.notes, "normal").unwrap();
    let f = &out.body.modes.frequency_hz;
    assert_eq!(modes, 8);
    // the pair: equal to rounding, and the proven top is its frequency
    assert!((f[6] - f[7]).abs() <= 1e-9 * f[7], "{f:?}");
    assert!((top_hz - f[7]).abs() <= 1e-6 * f[7], "{top_hz} vs {f:?}");
}
