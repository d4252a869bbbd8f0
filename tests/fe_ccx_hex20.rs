//! C3D20R (hex20, reduced 2×2×2 stiffness) against the CalculiX test-suite case `beamf`
//! (`../shared/reference/ccx_tests/beamf.inp`, cantilever, `*FREQUENCY`, consistent mass;
//! reference frequencies in `beamf.dat.ref`, identical in ccx 2.11 and 2.20).

mod common;

use common::{hz, reference};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody::solve::{lowest_modes, EigenSpec};

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
    let model = read_model(&reference("ccx_tests/beamf.inp"), &ImportOptions::default()).unwrap();
    let asm = assemble(
        &model,
        &AssemblySpec {
            mass: MassKind::Consistent,
            ..Default::default()
        },
    )
    .unwrap();
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec::default(),
    )
    .unwrap();
    let want = dat_freqs(&std::fs::read_to_string(reference("ccx_tests/beamf.dat.ref")).unwrap());
    assert_eq!(want.len(), 10);
    let sol = lowest_modes(
        &red.k,
        &red.m,
        &EigenSpec {
            count: want.len(),
            ..Default::default()
        },
    )
    .unwrap();
    for (i, (l, w)) in sol.eigenvalues.iter().zip(&want).enumerate() {
        let f = hz(*l);
        let err = (f - w) / w;
        eprintln!("beamf mode {}: ours {f:.2} ccx {w} rel {err:+.2e}", i + 1);
        assert!(err.abs() < 1e-6, "mode {}: {f} vs {w}", i + 1);
    }
}
