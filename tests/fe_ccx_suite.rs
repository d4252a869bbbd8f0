//! Cantilevers of the CalculiX test suite (`ccx_tests/` of the external reference data,
//! `FLEXBODY_REFERENCE`, else Debian's `calculix-ccx-test`: `crate::common::ccx_suite`; `*FREQUENCY`,
//! consistent mass; reference frequencies in the `.dat.ref` files, identical in ccx 2.11 and
//! 2.20): `beamf` (C3D20R, hex20 with reduced 2×2×2 integration) and `beam8f` (C3D8).

use crate::common::{ccx_suite, hz, lowest_eigenvalues};
use flexbody::fe::{AssemblySpec, ConstraintSpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody::solve::EigenSpec;

/// The (cycles/time) column of the EIGENVALUE OUTPUT table of a ccx .dat file.
fn dat_freqs(text: &str) -> Vec<f64> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if line.contains("E I G E N V A L U E   O U T P U T") {
            inside = true;
            continue;
        }
        if inside && line.contains("P A R T I C I P A T I O N") {
            break;
        }
        let f: Vec<&str> = line.split_whitespace().collect();
        if inside && f.len() == 5 && f[0].parse::<usize>().is_ok() {
            out.push(f[3].parse().unwrap());
        }
    }
    out
}

#[test]
fn hex20r_cantilever_beamf_matches_ccx_test_suite_1e6() {
    check(
        "hex20r_cantilever_beamf_matches_ccx_test_suite_1e6",
        "beamf",
    );
}

#[test]
fn hex8_cantilever_beam8f_matches_ccx_test_suite_1e6() {
    check(
        "hex8_cantilever_beam8f_matches_ccx_test_suite_1e6",
        "beam8f",
    );
}

fn check(test: &str, case: &str) {
    let (deck, dat) = (format!("{case}.inp"), format!("{case}.dat.ref"));
    let Some(dir) = ccx_suite(test, &[&deck, &dat]) else {
        return;
    };
    let dat = dir.join(dat);
    let model = read_model(&dir.join(deck), &ImportOptions::default()).unwrap();
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        ..Default::default()
    };
    let want = dat_freqs(&std::fs::read_to_string(dat).unwrap());
    assert!(want.len() >= 4, "{case}: {want:?}");
    let eigen = EigenSpec {
        count: want.len(),
        ..Default::default()
    };
    let lambda = lowest_eigenvalues(&model, &spec, &ConstraintSpec::default(), &eigen);
    let ours: Vec<f64> = lambda.iter().map(|l| hz(*l)).collect();
    // ccx prints 7 significant digits
    let worst = crate::common::assert_frequencies(case, &ours, &want, 0, 1e-6);
    eprintln!("{case}: worst relative difference {worst:.2e}");
}
