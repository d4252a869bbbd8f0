//! Each term of the beam-column geometric stiffness (SPEC §5.16, format 1.8; issue 49 item 6)
//! against a closed form, on a straight column along x of Euler–Bernoulli beams, clamped at
//! node 0 and loaded by an end force P along its axis (N = P in every element):
//!
//! * **axial** term N/L [1 −1; −1 1] on u: with bending and twist held the column's axial
//!   stiffness EA/L per element becomes (EA + N)/L, so every axial eigenvalue is multiplied by
//!   exactly 1 + N/(EA) (any mesh, any mass);
//! * **torsional** (Wagner) term N I_p/(A L) [1 −1; −1 1] on the twist: with bending held the
//!   torsion stiffness GJ/L becomes (GJ + N I_p/A)/L, so the torsional eigenvalues are
//!   multiplied by 1 + N I_p/(A G J), and a compressed column buckles in pure torsion at
//!   P_T = G J A/I_p (Timoshenko & Gere, *Theory of Elastic Stability* (1961) §5.3, no
//!   warping), below its axial limit EA;
//! * **flexural** terms: the Euler and Southwell tests of `tests/preload_beams.rs` and
//!   `tests/geometric_stiffness_file.rs` (unchanged by the two terms above).

use crate::common::steel;
use crate::preload_support::{eigenvalues, hold, nodal_load, straight_line, Built};
use flexbody::fe::preload::{buckling_factor, preload, PreloadCase, PreloadSpec};
use flexbody::fe::{AssemblySpec, BeamTheory, MassKind};
use flexbody::model::{BeamSection, ElementKind, Section};

const W: f64 = 0.03;
const H: f64 = 0.02;
const L: f64 = 1.2;
const NE: usize = 30;

fn section() -> BeamSection {
    BeamSection {
        area: W * H,
        i1: H * W.powi(3) / 12.0,
        i2: W * H.powi(3) / 12.0,
        i12: 0.0,
        j: 0.1406 * W * H.powi(3) * 1.2,
        shear_factors: None,
        nsm: 0.0,
        shape: None,
        taper: None,
    }
}

/// The column clamped at node 0 with `held` digits held at every other node.
fn column(held: &str) -> Built {
    let mut m = straight_line(
        NE,
        [0.0; 3],
        [L, 0.0, 0.0],
        ElementKind::Beam2,
        Section::Beam(section()),
        steel(),
        [0.0, 1.0, 0.0],
    );
    hold(&mut m, 0, "123456");
    for p in 1..=NE {
        hold(&mut m, p, held);
    }
    Built::new(
        m,
        AssemblySpec {
            mass: MassKind::Consistent,
            beam: BeamTheory::EulerBernoulli,
            ..Default::default()
        },
    )
}

/// The end force P along x (tension for P > 0).
fn end_force(p: f64) -> PreloadCase {
    PreloadCase {
        loads: vec![nodal_load(NE, [p, 0.0, 0.0, 0.0, 0.0, 0.0])],
        ..Default::default()
    }
}

/// The lowest eigenvalues of K + K_G(P) over those of K, mode by mode.
fn eigenvalue_ratios(b: &Built, p: f64) -> Vec<f64> {
    let w0 = eigenvalues(&b.red.k, &b.red.m);
    let pre = preload(&b.system(), &end_force(p), &PreloadSpec::default()).unwrap();
    let w = eigenvalues(&pre.k_t, &b.red.m);
    w.iter().zip(&w0).map(|(a, b)| a / b).collect()
}

#[test]
fn axial_term_stiffens_the_axial_modes_by_one_plus_n_over_ea() {
    // bending and twist held: only the axial displacements move
    let b = column("23456");
    let ea = steel().e * section().area;
    for p in [0.01 * ea, -0.02 * ea] {
        for (k, r) in eigenvalue_ratios(&b, p).iter().enumerate() {
            let want = 1.0 + p / ea;
            eprintln!(
                "axial mode {k}, N/EA = {:+}: ω²/ω²₀ = {r:.12}, closed form {want:.12}",
                p / ea
            );
            // measured 2e-15 (without the axial term the ratio is 1: an error of 1e-2)
            assert!((r - want).abs() < 1e-10, "mode {k}: {r} vs {want}");
        }
    }
}

#[test]
fn torsional_term_gives_the_torsional_buckling_load_g_j_a_over_ip() {
    // bending held: axial displacements and twists move; torsion is the lowest family
    let b = column("2356");
    let (s, mat) = (section(), steel());
    let ip = s.i1 + s.i2;
    let p_t = mat.g * s.j * s.area / ip;
    assert!(
        p_t < mat.e * s.area,
        "torsion buckles before the axial limit"
    );
    for ratio in [0.5, -1.0] {
        let p = -ratio * p_t; // compression for ratio > 0
        let r = eigenvalue_ratios(&b, p);
        let want = 1.0 - ratio;
        eprintln!(
            "torsion, P/P_T = {ratio:+}: ω²/ω²₀ = {:.12}, closed form {want:.12}",
            r[0]
        );
        // measured 1e-14 (without the torsional term: 1, an error of 0.5 or 1)
        assert!((r[0] - want).abs() < 1e-9, "{} vs {want}", r[0]);
    }
    // half the torsional buckling load: the lowest buckling factor is 2
    let pre = preload(&b.system(), &end_force(-0.5 * p_t), &PreloadSpec::default()).unwrap();
    let l1 = buckling_factor(&b.system(), &pre, faer::Par::Seq)
        .unwrap()
        .expect("compressed: a buckling factor");
    eprintln!("λ₁ = {l1:.12} at P = P_T/2 (closed form 2)");
    assert!((l1 - 2.0).abs() < 1e-8, "λ₁ = {l1}");
    // in tension nothing is compressed: no buckling factor (the rounding zero is not one)
    let pre = preload(&b.system(), &end_force(0.5 * p_t), &PreloadSpec::default()).unwrap();
    let none = buckling_factor(&b.system(), &pre, faer::Par::Seq).unwrap();
    assert_eq!(none, None);
}
