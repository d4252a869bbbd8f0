//! Preloaded beams against closed forms (issue 35): a pinned-pinned beam-column under axial
//! compression and tension (Euler: f(P)/f(0) = √(1 − P/P_cr), P_cr = π²EI/L²), refused past
//! P_cr with the buckling factor; the Timoshenko beam-column against the shear-corrected P_cr;
//! a thermally preloaded clamped–clamped bar (N = −EAαΔT) against the beam-column's frequency
//! equation; a pinned beam with a cooled rod alongside (a pretensioned tie: the rods' string
//! stiffness N/L (I − e eᵀ)) against f(T)/f(0) = √(1 + T/P_cr).

use crate::common::steel;
use crate::preload_support::{
    check_ratio, eigenvalues, frequency_ratio, heated, hold, nodal_load, straight_line, Built,
};
use flexbody::fe::geometric::{ElementStress, Temperature, Thermal};
use flexbody::fe::preload::{preload, PreloadCase, PreloadError, PreloadSpec};
use flexbody::fe::{AssemblySpec, BeamTheory, MassKind};
use flexbody::model::{BeamSection, Element, ElementKind, Model, Property, Section};
use std::f64::consts::PI;

const W: f64 = 0.03; // local y
const H: f64 = 0.02; // local z: the weak plane is x–z (I₂ = W H³/12)

fn section(shear: bool) -> BeamSection {
    BeamSection {
        area: W * H,
        i1: H * W.powi(3) / 12.0,
        i2: W * H.powi(3) / 12.0,
        i12: 0.0,
        j: 0.1406 * W * H.powi(3) * 1.2,
        shear_factors: shear.then_some([5.0 / 6.0, 5.0 / 6.0]),
        nsm: 0.0,
        shape: None,
        taper: None,
    }
}

/// A straight beam along x of length `l` with `ne` elements.
fn beam(ne: usize, l: f64, shear: bool) -> Model {
    straight_line(
        ne,
        [0.0; 3],
        [l, 0.0, 0.0],
        ElementKind::Beam2,
        Section::Beam(section(shear)),
        steel(),
        [0.0, 1.0, 0.0],
    )
}

fn spec(theory: BeamTheory) -> AssemblySpec {
    AssemblySpec {
        mass: MassKind::Consistent,
        beam: theory,
        ..Default::default()
    }
}

/// Pinned-pinned: node 1 holds u, v, w and the twist, the last node v and w.
fn pinned_pinned(ne: usize, l: f64, shear: bool) -> Model {
    let mut m = beam(ne, l, shear);
    hold(&mut m, 0, "1234");
    hold(&mut m, ne, "23");
    m
}

/// The case of an axial end force −`p` at node `ne` (compression for p > 0).
fn axial(ne: usize, p: f64) -> PreloadCase {
    PreloadCase {
        loads: vec![nodal_load(ne, [-p, 0.0, 0.0, 0.0, 0.0, 0.0])],
        ..Default::default()
    }
}

#[test]
fn pinned_pinned_beam_column_frequency_ratio_matches_euler_within_1e3() {
    let (ne, l) = (40, 1.2);
    let b = Built::new(
        pinned_pinned(ne, l, false),
        spec(BeamTheory::EulerBernoulli),
    );
    let mat = steel();
    let p_cr = PI * PI * mat.e * section(false).i2 / (l * l);
    let w0 = eigenvalues(&b.red.k, &b.red.m)[0];
    for ratio in [0.25, 0.5, 0.9, -0.5, -2.0] {
        let got = frequency_ratio(&b, &axial(ne, ratio * p_cr), w0).unwrap();
        check_ratio(
            &format!("Euler beam P/P_cr = {ratio:+}"),
            got,
            (1.0 - ratio).sqrt(),
            1e-3,
        );
    }
}

/// Timoshenko (shear-flexible, L/h = 10): the pinned-pinned mode stays sin(πx/L) and
/// P_cr = P_E/(1 + P_E/(kGA)) (Timoshenko & Gere, *Theory of Elastic Stability* (1961) §2.17),
/// so f(P)/f(0) = √(1 − P/P_cr) with that P_cr.
#[test]
fn timoshenko_beam_column_frequency_ratio_matches_shear_corrected_euler() {
    let (ne, l) = (40, 0.2);
    let b = Built::new(pinned_pinned(ne, l, true), spec(BeamTheory::Timoshenko));
    let mat = steel();
    let s = section(true);
    let p_e = PI * PI * mat.e * s.i2 / (l * l);
    let p_cr = p_e / (1.0 + p_e / (5.0 / 6.0 * mat.g * s.area));
    eprintln!("Timoshenko: P_cr / P_E = {:.5}", p_cr / p_e);
    let w0 = eigenvalues(&b.red.k, &b.red.m)[0];
    for ratio in [0.5, 0.9, -1.0] {
        let got = frequency_ratio(&b, &axial(ne, ratio * p_cr), w0).unwrap();
        check_ratio(
            &format!("Timoshenko beam P/P_cr = {ratio:+}"),
            got,
            (1.0 - ratio).sqrt(),
            1e-3,
        );
    }
}

#[test]
fn compression_beyond_euler_load_is_refused_with_the_buckling_factor() {
    let (ne, l) = (40, 1.2);
    let b = Built::new(
        pinned_pinned(ne, l, false),
        spec(BeamTheory::EulerBernoulli),
    );
    let p_cr = PI * PI * steel().e * section(false).i2 / (l * l);
    let err = preload(
        &b.system(),
        &axial(ne, 1.25 * p_cr),
        &PreloadSpec::default(),
    )
    .unwrap_err();
    let msg = err.to_string();
    eprintln!("{msg}");
    let PreloadError::Buckling {
        factor: Some(factor),
        ..
    } = err
    else {
        panic!("expected a buckling error, got {msg}");
    };
    assert!(
        (factor - 0.8).abs() < 1e-4,
        "λ₁ = {factor}, closed form 1/1.25"
    );
    assert!(msg.contains("indefinite") && msg.contains("buckl"), "{msg}");
}

/// Clamped–clamped beam-column under compression P (p = P/EI, k = ρAω²/EI):
/// w = A cosh αx + B sinh αx + C cos βx + D sin βx with α² = (−p + √(p² + 4k))/2,
/// β² = (p + √(p² + 4k))/2; the four clamped conditions give
/// 2αβ (1 − cosh αL cos βL) + (α² − β²) sinh αL sin βL = 0 (derived from the beam-column
/// equation EI w'''' + P w'' = ρAω² w; at P = 0 the classical cosh βL cos βL = 1).
fn clamped_clamped_omega2(p: f64, ei: f64, rho_a: f64, l: f64) -> f64 {
    let f = |w2: f64| {
        let (pp, k) = (p / ei, rho_a * w2 / ei);
        let r = (pp * pp + 4.0 * k).sqrt();
        let (a, b) = (((r - pp) / 2.0).sqrt(), ((r + pp) / 2.0).sqrt());
        2.0 * a * b * (1.0 - (a * l).cosh() * (b * l).cos())
            + (a * a - b * b) * (a * l).sinh() * (b * l).sin()
    };
    // the first root: bracket from ω² → 0⁺ upward, then bisect
    let w2_0 = (4.730_040_744_862_704f64.powi(4)) * ei / (rho_a * l.powi(4));
    let (mut lo, mut hi) = (1e-6 * w2_0, 1e-6 * w2_0);
    while f(lo).signum() == f(hi).signum() {
        lo = hi;
        hi *= 1.05;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid).signum() == f(lo).signum() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn thermally_preloaded_clamped_clamped_bar_matches_beam_column_frequency_equation() {
    let (ne, l) = (60, 1.2);
    let mut model = beam(ne, l, false);
    hold(&mut model, 0, "123456");
    hold(&mut model, ne, "123456");
    let b = Built::new(model, spec(BeamTheory::EulerBernoulli));
    let (mat, s) = (steel(), section(false));
    let alpha = 1.2e-5;
    let ei = mat.e * s.i2;
    // half the clamped–clamped buckling load 4π²EI/L²
    let p = 0.5 * 4.0 * PI * PI * ei / (l * l);
    let dt = p / (mat.e * s.area * alpha);
    let (pre, stresses) = heated(&b, vec![alpha], dt);
    // held ends: no axial strain, N = −EAαΔT in every element
    for (_, st) in &stresses {
        let ElementStress::Axial(n) = st else {
            panic!("beam stress {st:?}")
        };
        assert!((n + p).abs() < 1e-9 * p, "N = {n}, want {}", -p);
    }
    let w0 = eigenvalues(&b.red.k, &b.red.m)[0];
    let w = eigenvalues(&pre.k_t, &b.red.m)[0];
    let rho_a = mat.rho * s.area;
    let want0 = clamped_clamped_omega2(0.0, ei, rho_a, l);
    let want = clamped_clamped_omega2(p, ei, rho_a, l);
    let got = (w / w0).sqrt();
    let exact = (want / want0).sqrt();
    let err = (got - exact) / exact;
    eprintln!(
        "thermal clamped-clamped (P = 0.5 P_cr, ΔT = {dt:.2} K): f/f0 = {got:.8}, frequency \
         equation {exact:.8}, rel. error {err:+.2e}; f0 FE vs exact {:+.2e}",
        (w0 / want0).sqrt() - 1.0
    );
    assert!(err.abs() < 1e-3, "{got} vs {exact}");
    assert!(((w / want).sqrt() - 1.0).abs() < 1e-3);
}

/// A pinned-pinned beam with a rod along the same nodes, both ends held axially; the rod is
/// cooled (its α alone is non-zero), so it carries the tension T = E A_rod α |ΔT| and the beam
/// none. The transverse mode stays sin(πx/L): ω² ∝ EI k⁴ + T k², f(T)/f(0) = √(1 + T/P_cr).
#[test]
fn beam_with_a_pretensioned_rod_alongside_matches_string_plus_beam_closed_form() {
    let (ne, l) = (40, 1.2);
    let mut model = pinned_pinned(ne, l, false);
    hold(&mut model, ne, "1");
    let rod_area = 2e-5;
    model.materials.push(steel());
    model.properties.push(Property {
        id: 2,
        name: "TIE".into(),
        material: 1,
        section: Section::Rod {
            area: rod_area,
            j: 0.0,
            nsm: 0.0,
        },
    });
    for e in 0..ne {
        model.elements.push(Element {
            id: (ne + e) as u64 + 1,
            kind: ElementKind::Rod2,
            nodes: vec![e, e + 1],
            property: Some(1),
            orientation: None,
        });
    }
    let b = Built::new(model, spec(BeamTheory::EulerBernoulli));
    let mat = steel();
    let p_cr = PI * PI * mat.e * section(false).i2 / (l * l);
    let alpha = 1.2e-5;
    let w0 = eigenvalues(&b.red.k, &b.red.m)[0];
    for ratio in [0.5, 2.0] {
        let tension = ratio * p_cr;
        let thermal = Thermal {
            delta_t: Temperature::Uniform(-tension / (mat.e * rod_area * alpha)),
            // the beam's material does not expand, the rod's does
            alpha: vec![0.0, alpha],
        };
        let case = PreloadCase {
            thermal: Some(thermal),
            ..Default::default()
        };
        let got = frequency_ratio(&b, &case, w0).unwrap();
        check_ratio(
            &format!("beam + tie, T/P_cr = {ratio}"),
            got,
            (1.0 + ratio).sqrt(),
            1e-3,
        );
    }
}
