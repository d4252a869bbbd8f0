//! Consistent-mass frequencies of the CalculiX reference blocks (`fixtures/reference/`,
//! ccx 2.20 `*FREQUENCY`): free-free modes 7–16 and the first 10 fixed modes agree with
//! `case.json` to 2e-6 relative (ccx prints 7 significant digits). The models are read with the
//! `.inp` importer from the very decks ccx ran; the eigen-solve is `solve::lowest_modes`.

use crate::common::{hz, lowest_eigenvalues, reference};
use flexbody::fe::{AssemblySpec, ConstraintSpec, MassKind, Tet10MassRule};
use flexbody::import::{read_model, ImportOptions};
use flexbody::solve::EigenSpec;

fn case_freqs(case: &str, key: &str, field: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(reference(&format!("{case}/case.json"))).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v[key][field]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Our lowest `count` frequencies (Hz) of the deck `case/deck`.
fn our_freqs(case: &str, deck: &str, count: usize) -> Vec<f64> {
    let model = read_model(
        &reference(&format!("{case}/{deck}")),
        &ImportOptions::default(),
    )
    .unwrap();
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        tet10_mass: Tet10MassRule::CalculixFourPoint,
        ..Default::default()
    };
    let eigen = EigenSpec {
        count,
        dofs_per_node: Some(3),
        ..Default::default()
    };
    let lambda = lowest_eigenvalues(&model, &spec, &ConstraintSpec::default(), &eigen);
    lambda.iter().map(|&l| hz(l)).collect()
}

fn check(case: &str) {
    let want_free = case_freqs(case, "free_free", "all_computed_freq_hz");
    let free = our_freqs(case, "ccx_free.inp", 16);
    for i in 6..16 {
        let err = (free[i] - want_free[i]) / want_free[i];
        eprintln!(
            "{case} free-free mode {}: ours {:.7} ccx {} rel {err:+.2e}",
            i + 1,
            free[i],
            want_free[i]
        );
        assert!(
            err.abs() < 2e-6,
            "{case}: free-free mode {} {} vs {}",
            i + 1,
            free[i],
            want_free[i]
        );
    }
    for f in &free[..6] {
        assert!(*f < 1e-3 * want_free[6], "{case}: rigid mode at {f} Hz");
    }
    let want_fixed = case_freqs(case, "fixed", "freq_hz");
    let fixed = our_freqs(case, "ccx_fixed.inp", want_fixed.len());
    for (i, (f, w)) in fixed.iter().zip(&want_fixed).enumerate() {
        let err = (f - w) / w;
        eprintln!(
            "{case} fixed mode {}: ours {f:.7} ccx {w} rel {err:+.2e}",
            i + 1
        );
        assert!(err.abs() < 2e-6, "{case}: fixed mode {} {f} vs {w}", i + 1);
    }
}

#[test]
fn a_block_hex8_consistent_frequencies_match_ccx_2e6() {
    check("a_block_hex8");
}

#[test]
fn b_block_tet10_consistent_frequencies_match_ccx_2e6() {
    check("b_block_tet10");
}

#[test]
fn d_plate_hex8_consistent_frequencies_match_ccx_2e6() {
    check("d_plate_hex8");
}
