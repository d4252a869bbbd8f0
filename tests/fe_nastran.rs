//! A real Nastran deck through the Nastran importer and the assembler:
//! `nastran/beam_modes` of the external reference data (`FLEXBODY_REFERENCE`) (Simcenter Nastran 2019.2 SOL SEMODES; 9 CBAR + 1
//! CBEAM on PBARL/PBEAML ROD r = 1, a CONM2 tip mass, GRID 1 clamped, lumped mass).
//!
//! What Nastran does, as reproduced here: transverse shear flexibility with shear factor
//! K = 0.9 for the ROD section (the importer derives it as Nastran does; the model is not
//! patched, and the assembly's default beam theory follows the sections), and
//! lumped mass per element card (`BeamLumping::Nastran`): a CBAR lumps translations only, a
//! CBEAM also its torsional inertia ρI_pL/2 at its two nodes. With these all ten frequencies
//! agree to < 1e-6. With CBAR-type lumping everywhere the one torsion mode is 19% high.

use crate::common::{external_reference, hz, lowest_eigenvalues};
use flexbody::fe::{AssemblySpec, BeamLumping, ConstraintSpec, MassKind};
use flexbody::import::{read_model, Format, ImportOptions};
use flexbody::model::{Model, Section};
use flexbody::solve::EigenSpec;
use std::path::Path;

const CASE: &str = "nastran/beam_modes";

fn f06_freqs(dir: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(dir.join("case.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["freq_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn deck(dir: &Path) -> Model {
    let path = dir.join("beam_modes.dat");
    let model = read_model(
        &path,
        &ImportOptions {
            format: Some(Format::Nastran),
            ..Default::default()
        },
    )
    .unwrap();
    // As Nastran derives them for PBARL/PBEAML ROD (the f06's equivalent PBAR/PBEAM: 0.9).
    for p in &model.properties {
        if let Section::Beam(b) = &p.section {
            assert_eq!(b.shear_factors, Some([0.9, 0.9]), "{}", p.name);
        }
    }
    model
}

fn freqs(model: &Model, beam_lumping: BeamLumping) -> Vec<f64> {
    let spec = AssemblySpec {
        mass: MassKind::Lumped,
        beam_lumping,
        ..Default::default()
    };
    // GRID 12 is unconnected (Nastran AUTOSPC): it has no dofs here.
    let eigen = EigenSpec {
        count: 10,
        ..Default::default()
    };
    let lambda = lowest_eigenvalues(model, &spec, &ConstraintSpec::default(), &eigen);
    lambda.iter().map(|&l| hz(l)).collect()
}

#[test]
fn nastran_beam_modes_lumped_per_element_card_match_f06() {
    let Some(dir) =
        external_reference("nastran_beam_modes_lumped_per_element_card_match_f06", CASE)
    else {
        return;
    };
    let want = f06_freqs(&dir);
    let model = deck(&dir);
    let ours = freqs(&model, BeamLumping::Nastran);
    for (i, (f, w)) in ours.iter().zip(&want).enumerate() {
        let err = (f - w) / w;
        eprintln!(
            "beam_modes mode {}: ours {f:.4} Hz, Nastran {w} Hz, rel {err:+.2e}",
            i + 1
        );
        assert!(err.abs() < 1e-6, "mode {}: {f} vs {w}", i + 1);
    }
}

/// With CBAR-type lumping (no rotary inertia) on every element, bending and axial modes are
/// unchanged and the torsion mode is the CONM2 inertia on the shaft's torsional spring,
/// f = √(GJ/(L I_xx))/2π = 4226.5 Hz, 19% above Nastran's 3554.9 Hz.
#[test]
fn nastran_beam_modes_with_cbar_lumping_everywhere_give_the_closed_form_torsion() {
    let Some(dir) = external_reference(
        "nastran_beam_modes_with_cbar_lumping_everywhere_give_the_closed_form_torsion",
        CASE,
    ) else {
        return;
    };
    let want = f06_freqs(&dir);
    let model = deck(&dir);
    let ours = freqs(&model, BeamLumping::TranslationsOnly);
    for i in [0, 1, 2, 3, 5, 6, 7, 8, 9] {
        let err = (ours[i] - want[i]) / want[i];
        assert!(
            err.abs() < 1e-6,
            "mode {}: {} vs {}",
            i + 1,
            ours[i],
            want[i]
        );
    }
    let mat = &model.materials[0];
    let j = std::f64::consts::PI / 2.0;
    let closed = (mat.g * j / (10.0 * 2.59e-3)).sqrt() / (2.0 * std::f64::consts::PI);
    assert!(
        (ours[4] - closed).abs() < 1e-9 * closed,
        "torsion {} vs {closed}",
        ours[4]
    );
}
