//! Beam and rod elements against closed-form frequencies (Euler–Bernoulli bending, axial and
//! torsional rods; Blevins, *Formulas for Natural Frequency and Mode Shape* (1979) Tables 8-1,
//! 12-1): 40 elements, within 0.1%. Dense generalized eigen-solve on the reduced system.

use crate::common::{dense, generalized_eigenvalues, hz, steel};
use flexbody::fe::{assemble, eliminate, AssemblySpec, BeamTheory, ConstraintSpec, MassKind};
use flexbody::model::{
    BeamSection, DofMask, Element, ElementKind, Model, Node, Property, Section, Spc,
};

const L: f64 = 1.2;
const W: f64 = 0.03; // local y (width)
const H: f64 = 0.02; // local z (height)

fn section() -> BeamSection {
    BeamSection {
        area: W * H,
        i1: H * W.powi(3) / 12.0, // about local z: bending in x–y, width along y
        i2: W * H.powi(3) / 12.0,
        i12: 0.0,
        j: 0.1406 * W * H.powi(3) * 1.2, // any J: torsion checked with its own value
        shear_factors: Some([5.0 / 6.0, 5.0 / 6.0]),
        nsm: 0.0,
        shape: None,
        taper: None,
    }
}

/// A straight beam (or rod) along the direction `dir`, `ne` elements, orientation vector `v`.
fn beam_model(ne: usize, kind: ElementKind, dir: [f64; 3], v: [f64; 3]) -> Model {
    let mut model = Model {
        source: "beam".into(),
        ..Model::default()
    };
    model.materials.push(steel());
    let s = section();
    model.properties.push(Property {
        id: 1,
        name: "B".into(),
        material: 0,
        section: match kind {
            ElementKind::Rod2 => Section::Rod {
                area: s.area,
                j: s.j,
                nsm: 0.0,
            },
            _ => Section::Beam(s),
        },
    });
    for i in 0..=ne {
        let t = L * i as f64 / ne as f64;
        model.nodes.push(Node {
            id: i as u64 + 1,
            x: [0.2 + dir[0] * t, -0.1 + dir[1] * t, dir[2] * t],
            displacement_frame: None,
        });
    }
    for e in 0..ne {
        model.elements.push(Element {
            id: e as u64 + 1,
            kind,
            nodes: vec![e, e + 1],
            property: Some(0),
            orientation: Some(v),
        });
    }
    model
}

fn frequencies(model: &Model, mass: MassKind, beam: BeamTheory) -> Vec<f64> {
    let asm = assemble(
        model,
        &AssemblySpec {
            mass,
            beam,
            ..Default::default()
        },
    )
    .unwrap();
    let red = eliminate(model, &asm.dofs, &asm.k, &asm.m, &ConstraintSpec::default()).unwrap();
    generalized_eigenvalues(&dense(&red.k), &dense(&red.m))
        .into_iter()
        .map(hz)
        .collect()
}

fn bending_hz(beta_l: f64, i: f64) -> f64 {
    let m = steel();
    beta_l * beta_l / (2.0 * std::f64::consts::PI) * (m.e * i / (m.rho * W * H * L.powi(4))).sqrt()
}

/// The computed frequency nearest to `want`, and its relative error.
fn nearest(f: &[f64], want: f64) -> f64 {
    f.iter()
        .map(|&x| (x - want) / want)
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap()
}

/// Consistent mass: 0.1% for every mode (the acceptance bound). Lumped translational mass plus
/// section rotary inertia converges as O((n/N)²) from below and is not held to 0.1%: measured
/// at 40 elements −4e-4 (cantilever mode 1) to −6e-3 (cantilever mode 4), −3.2e-3 (free-free
/// mode 1) to −1.3e-2 (free-free mode 4; section rotary inertia, absent from the closed form,
/// is about −0.5% of that); printed by the tests. Bounds: 0.5% for the first mode, 2% above.
fn tolerance(mass: MassKind, n: usize) -> f64 {
    match (mass, n) {
        (MassKind::Consistent, _) => 1e-3,
        (MassKind::Lumped, 0) => 5e-3,
        (MassKind::Lumped, _) => 2e-2,
    }
}

/// Exact frequency (Hz) of mode n of a free-free chain of `ne` equal linear 2-node elements of
/// length h with wave speed c: ω = 2c/h·sin(θ/2) lumped, ω² = 6c²/h²·(1 − cos θ)/(2 + cos θ)
/// consistent, θ = nπ/ne (the dispersion relation of the discrete chain; tends to nπc/L).
fn chain_hz(n: usize, ne: usize, c: f64, mass: MassKind) -> f64 {
    let h = L / ne as f64;
    let th = n as f64 * std::f64::consts::PI / ne as f64;
    let w = match mass {
        MassKind::Lumped => 2.0 * c / h * (th / 2.0).sin(),
        MassKind::Consistent => {
            (6.0 * c * c / (h * h) * (1.0 - th.cos()) / (2.0 + th.cos())).sqrt()
        }
    };
    w / (2.0 * std::f64::consts::PI)
}

const CANTILEVER: [f64; 4] = [1.875_104_07, 4.694_091_13, 7.854_757_44, 10.995_540_73];
const FREE_FREE: [f64; 4] = [4.730_040_74, 7.853_204_62, 10.995_607_84, 14.137_165_49];

#[test]
fn euler_bernoulli_cantilever_matches_closed_form_within_0_1_percent_at_40_elements() {
    let s = section();
    // Skewed axis and orientation: the element frame must handle any direction.
    let dir = [0.6, 0.0, 0.8];
    let mut model = beam_model(40, ElementKind::Beam2, dir, [0.0, 1.0, 0.0]);
    model.spcs.push(Spc {
        node: 0,
        dofs: DofMask::ALL,
        set_id: 0,
    });
    for mass in [MassKind::Consistent, MassKind::Lumped] {
        let f = frequencies(&model, mass, BeamTheory::EulerBernoulli);
        for (n, &bl) in CANTILEVER.iter().enumerate() {
            for i in [s.i1, s.i2] {
                let want = bending_hz(bl, i);
                let err = nearest(&f, want);
                eprintln!(
                    "cantilever {mass:?} mode {} I={i:.3e}: {want:.3} Hz, rel. error {err:+.2e}",
                    n + 1
                );
                assert!(
                    err.abs() < tolerance(mass, n),
                    "{mass:?}: mode {} error {err:e}",
                    n + 1
                );
            }
        }
    }
}

#[test]
fn euler_bernoulli_free_free_beam_matches_closed_form_and_has_six_rigid_modes() {
    let s = section();
    let model = beam_model(40, ElementKind::Beam2, [0.0, 1.0, 0.0], [1.0, 0.0, 1.0]);
    for mass in [MassKind::Consistent, MassKind::Lumped] {
        let f = frequencies(&model, mass, BeamTheory::EulerBernoulli);
        let first_elastic = bending_hz(FREE_FREE[0], s.i2.min(s.i1));
        assert_eq!(
            f.iter().filter(|&&x| x < 1e-3 * first_elastic).count(),
            6,
            "{mass:?}: {:?}",
            &f[..8]
        );
        for (n, &bl) in FREE_FREE.iter().enumerate() {
            for i in [s.i1, s.i2] {
                let want = bending_hz(bl, i);
                let err = nearest(&f, want);
                eprintln!(
                    "free-free {mass:?} mode {} I={i:.3e}: {want:.3} Hz, rel. error {err:+.2e}",
                    n + 1
                );
                assert!(
                    err.abs() < tolerance(mass, n),
                    "{mass:?}: mode {} error {err:e}",
                    n + 1
                );
            }
        }
        // Axial and torsional free-free modes: the discrete chain's exact frequencies with
        // c = √(E/ρ) and √(GJ/(ρ I_p)) (continuum limit n/(2L)·c, within 0.1% for n = 1).
        let m = steel();
        for n in 1..=3 {
            let ax = chain_hz(n, 40, (m.e / m.rho).sqrt(), mass);
            let tor = chain_hz(n, 40, (m.g * s.j / (m.rho * (s.i1 + s.i2))).sqrt(), mass);
            for want in [ax, tor] {
                let err = nearest(&f, want);
                assert!(
                    err.abs() < 1e-9,
                    "{mass:?}: axial/torsion mode {n} ({want} Hz) error {err:e}"
                );
            }
        }
        let continuum = (m.e / m.rho).sqrt() / (2.0 * L);
        assert!((nearest(&f, continuum)).abs() < 1e-3);
    }
}

#[test]
fn timoshenko_beam_is_softer_than_euler_bernoulli_by_the_shear_correction() {
    // Deep beam: shear lowers the first cantilever frequency; the Timoshenko result lies within
    // 2% of Rayleigh–Timoshenko's first-order correction f_T ≈ f_EB / √(1 + (β²)(1 + E/(kG)) r²/L²)…
    // checked here only as ordering plus agreement with EB for the slender beam above.
    let mut model = beam_model(40, ElementKind::Beam2, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    model.spcs.push(Spc {
        node: 0,
        dofs: DofMask::ALL,
        set_id: 0,
    });
    let eb = frequencies(&model, MassKind::Consistent, BeamTheory::EulerBernoulli);
    let ti = frequencies(&model, MassKind::Consistent, BeamTheory::Timoshenko);
    let s = section();
    let want = bending_hz(CANTILEVER[0], s.i2);
    let (e_eb, e_ti) = (nearest(&eb, want), nearest(&ti, want));
    // Slender (L/h = 60): shear effect ~ (h/L)² ≈ 3e-4, below 0.1% but strictly softer.
    assert!(
        e_ti < e_eb && e_ti.abs() < 1e-3,
        "EB {e_eb:e}, Timoshenko {e_ti:e}"
    );
}

#[test]
fn rod_chain_axial_and_torsion_modes_match_closed_form() {
    let s = section();
    let model = beam_model(40, ElementKind::Rod2, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let m = steel();
    for mass in [MassKind::Consistent, MassKind::Lumped] {
        let f = frequencies(&model, mass, BeamTheory::EulerBernoulli);
        for n in 1..=3 {
            let ax = chain_hz(n, 40, (m.e / m.rho).sqrt(), mass);
            // Rod torsional inertia uses ρJ (module doc of rod.rs): c = √(G/ρ).
            let tor = chain_hz(n, 40, (m.g / m.rho).sqrt(), mass);
            for want in [ax, tor] {
                let err = nearest(&f, want);
                assert!(
                    err.abs() < 1e-9,
                    "{mass:?}: mode {n} ({want} Hz) error {err:e}"
                );
            }
        }
        assert!(s.area > 0.0);
    }
}
