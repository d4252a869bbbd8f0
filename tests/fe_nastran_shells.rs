//! `../shared/reference/nastran/mode_solid_shell_bar` (MSC Nastran 2005.1 SOL 103: CHEXA,
//! CPENTA, CTETRA, CQUAD4/CTRIA3 on PSHELL and on PCOMP, CBEAM, CBAR, CROD in one model,
//! lumped mass) through the Nastran importer, the assembler and the eigensolver.

mod common;

use common::{hz, reference};
use flexbody::fe::{
    assemble, eliminate, AssemblySpec, BeamLumping, BeamTheory, ConstraintSpec, MassKind,
};
use flexbody::import::{read_model, Format, ImportOptions};
use flexbody::solve::{lowest_modes, EigenSpec};

fn f06_freqs() -> Vec<f64> {
    let text =
        std::fs::read_to_string(reference("nastran/mode_solid_shell_bar/case.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["freq_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn freqs(beam: BeamTheory) -> Vec<f64> {
    let path = reference("nastran/mode_solid_shell_bar/mode_solid_shell_bar.bdf");
    let model = read_model(
        &path,
        &ImportOptions {
            format: Some(Format::Nastran),
            ..Default::default()
        },
    )
    .unwrap();
    for w in &model.warnings {
        eprintln!("warning: {}", w.message);
    }
    let spec = AssemblySpec {
        mass: MassKind::Lumped,
        beam,
        beam_lumping: BeamLumping::Nastran,
        ..Default::default()
    };
    let asm = assemble(&model, &spec).unwrap();
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec {
            auto_spc: true,
            ..Default::default()
        },
    )
    .unwrap();
    let sol = lowest_modes(
        &red.k,
        &red.m,
        &EigenSpec {
            count: 3,
            ..Default::default()
        },
    )
    .unwrap();
    sol.eigenvalues.iter().map(|&l| hz(l)).collect()
}

/// Timoshenko beams (the PBEAM gives K1 = K2 = 0.85; the PBAR none, so Euler–Bernoulli as in
/// Nastran), Nastran lumping: modes 1 and 2 within 1 % (measured +0.64 %, +0.74 %), mode 3
/// −2.79 %. What differs from MSC Nastran here:
/// * rotary inertia ρt³/12 of our lumped shells' bending rotations (Nastran's lumped mass has
///   none): the PCOMP
///   walls are 1.0 and 1.5 thick on 1×1 elements, so it is not small — without it the three
///   modes are +1.32 %, +0.97 %, +2.21 % (this inertia alone moves mode 3 by 5 %);
/// * the DKT triangles are shear-rigid (Kirchhoff) on those very thick walls (t/L = 1–1.5),
///   the CHEXA is our fully integrated Hex8 (MSC's CHEXA has bubble modes), both stiffer;
/// * the PCOMP laminates of one isotropic material are read as homogeneous PSHELLs (TS/T = 5/6).
///
/// Euler–Bernoulli beams everywhere: +4.2 %, +2.2 %, +1.8 %.
#[test]
fn nastran_mode_solid_shell_bar_matches_f06() {
    let want = f06_freqs();
    let eb = freqs(BeamTheory::EulerBernoulli);
    let got = freqs(BeamTheory::Timoshenko);
    for ((g, e), w) in got.iter().zip(&eb).zip(&want) {
        eprintln!(
            "Timoshenko {g:.4} (EB {e:.4}) vs {w:.4} Hz ({:+.3} %)",
            100.0 * (g - w) / w
        );
    }
    for (k, tol) in [(0, 0.01), (1, 0.01), (2, 0.035)] {
        let err = (got[k] - want[k]) / want[k];
        assert!(
            err.abs() < tol,
            "mode {}: {} vs {} Hz",
            k + 1,
            got[k],
            want[k]
        );
    }
}
