//! A spinning cantilever (issue 35): a uniform Euler–Bernoulli beam along x, clamped at the
//! hub (hub radius 0), spinning at Ω about the z axis through its root; the centrifugal preload
//! is Ω² M r_⊥ (CalculiX CENTRIF, Nastran RFORCE).
//!
//! * Flap (bending out of the plane of rotation, along z): ω² = ω₀² + K Ω² to first order with
//!   the Southwell coefficient K₁ = 1.1933 of the first mode; the exact eigenvalues of the
//!   rotating-beam equation (EI w'''')' − (N w')' = ρAω² w with N = ½ρAΩ²(L² − x²) are
//!   tabulated by Wright, Smith, Thompson & Worley, *J. Appl. Mech.* 49 (1982) 197, Table 1
//!   (hub radius 0; the same values in Banerjee, *J. Sound Vib.* 233 (2000) 857, Table 1), in
//!   ω̄ = ω √(ρAL⁴/EI) against Ω̄ = Ω √(ρAL⁴/EI).
//! * Lead-lag (bending in the plane of rotation, along y): seen in the rotating frame the
//!   centrifugal force also softens the in-plane motion, −Ω² m v (the spin softening), so
//!   ω̄²_lag = ω̄²_flap − Ω̄² for the same EI: the coefficient of Ω² is K₁ − 1 there. The
//!   preloaded K_T alone gives the flap value in both planes; K_T + spin_softening gives the
//!   lead-lag one.
//! * The file's terms: K̂_G = Φᵀ K_G(σ(Ω = 1)) Φ from the unloaded modes; K̂ + Ω² K̂_G reproduces
//!   the preloaded build, and K̂_G,11 is the Southwell coefficient.
//! * K_T feeds the reductions unchanged: Craig–Bampton on K_T (interface at the tip, all
//!   fixed-interface modes) gives the preloaded frequencies.

use crate::common::steel;
use crate::preload_support::{eigenvalues, hold, lowest, straight_line, Built};
use faer::Mat;
use flexbody::fe::preload::{
    modal_geometric_stiffness, preload, spin_softening, PreloadCase, PreloadSpec, Spin,
};
use flexbody::fe::{AssemblySpec, BeamTheory, MassKind};
use flexbody::model::{BeamSection, ElementKind, Section};
use flexbody::solve::sparse_ops;

const L: f64 = 2.0;
const W: f64 = 0.04; // along y: in-plane (lead-lag) bending uses I₁ = H W³/12
const H: f64 = 0.02; // along z: flap bending uses I₂ = W H³/12
const NE: usize = 40;

/// Wright et al. (1982), Table 1, first flap mode, hub radius 0: (Ω̄, ω̄).
const WRIGHT_1982: [(f64, f64); 11] = [
    (0.0, 3.5160),
    (1.0, 3.6816),
    (2.0, 4.1373),
    (3.0, 4.7973),
    (4.0, 5.5850),
    (5.0, 6.4495),
    (6.0, 7.3604),
    (7.0, 8.2996),
    (8.0, 9.2568),
    (9.0, 10.2257),
    (10.0, 11.2023),
];

/// The published Southwell coefficient of the first flap mode of a cantilever with hub radius 0.
const SOUTHWELL_1: f64 = 1.1933;

#[derive(Clone, Copy, PartialEq)]
enum Plane {
    /// Bending along z only (u_y, θz held everywhere).
    Flap,
    /// Bending along y only (u_z, θy held everywhere).
    LeadLag,
}

fn cantilever(plane: Plane) -> Built {
    let section = Section::Beam(BeamSection {
        area: W * H,
        i1: H * W.powi(3) / 12.0,
        i2: W * H.powi(3) / 12.0,
        i12: 0.0,
        j: 0.229 * W * H.powi(3),
        shear_factors: None,
        nsm: 0.0,
        shape: None,
        taper: None,
    });
    let mut model = straight_line(
        NE,
        [0.0; 3],
        [L, 0.0, 0.0],
        ElementKind::Beam2,
        section,
        steel(),
        [0.0, 1.0, 0.0],
    );
    hold(&mut model, 0, "123456");
    for n in 1..=NE {
        hold(
            &mut model,
            n,
            match plane {
                Plane::Flap => "26",
                Plane::LeadLag => "35",
            },
        );
    }
    Built::new(
        model,
        AssemblySpec {
            mass: MassKind::Consistent,
            beam: BeamTheory::EulerBernoulli,
            ..Default::default()
        },
    )
}

/// √(EI/(ρA L⁴)): ω̄ = ω / this.
fn unit(plane: Plane) -> f64 {
    let m = steel();
    let i = match plane {
        Plane::Flap => W * H.powi(3) / 12.0,
        Plane::LeadLag => H * W.powi(3) / 12.0,
    };
    (m.e * i / (m.rho * W * H * L.powi(4))).sqrt()
}

fn spin(omega: f64) -> Spin {
    Spin {
        point: [0.0; 3],
        axis: [0.0, 0.0, 1.0],
        omega,
    }
}

/// Lowest ω² of the preloaded build at Ω (plus the spin softening when `soften`).
fn preloaded_lowest(b: &Built, omega: f64, soften: bool) -> f64 {
    let pre = preload(
        &b.system(),
        &PreloadCase::spin(&spin(omega)),
        &PreloadSpec::default(),
    )
    .unwrap();
    let k = if soften {
        let soft = spin_softening(&b.model, &b.asm.dofs, &b.asm.m, &spin(omega)).unwrap();
        let soft_r =
            sparse_ops::congruence(b.red.t.as_ref(), soft.as_ref(), faer::Par::Seq).unwrap();
        sparse_ops::add_scaled(pre.k_t.as_ref(), soft_r.as_ref(), 1.0).unwrap()
    } else {
        pre.k_t
    };
    eigenvalues(&k, &b.red.m)[0]
}

/// ∫₀¹ ½(1 − ξ²) φ′² dξ / ∫₀¹ φ² dξ with the exact first cantilever mode φ (Simpson, 2·10⁴
/// intervals): the first-order (Southwell) coefficient of the rotating-beam equation.
fn southwell_rayleigh_quotient() -> f64 {
    let b: f64 = 1.875_104_068_711_961;
    let s = (b.cosh() + b.cos()) / (b.sinh() + b.sin());
    let phi = |x: f64| (b * x).cosh() - (b * x).cos() - s * ((b * x).sinh() - (b * x).sin());
    let dphi = |x: f64| b * ((b * x).sinh() + (b * x).sin() - s * ((b * x).cosh() - (b * x).cos()));
    let n = 20_000;
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..=n {
        let x = i as f64 / n as f64;
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        num += w * 0.5 * (1.0 - x * x) * dphi(x).powi(2);
        den += w * phi(x).powi(2);
    }
    num / den
}

#[test]
fn spinning_cantilever_flap_frequencies_match_wright_1982_within_2e_4() {
    let b = cantilever(Plane::Flap);
    let u = unit(Plane::Flap);
    for &(om, want) in &WRIGHT_1982 {
        let got = preloaded_lowest(&b, om * u, false).sqrt() / u;
        let err = (got - want) / want;
        eprintln!(
            "flap Ω̄ = {om:4.1}: ω̄ = {got:.5}, Wright et al. {want:.4}, rel. error {err:+.2e}"
        );
        // measured ≤ 4.1e-5 (Ω̄ = 5; the table's 5 digits round to ≤ 1.4e-5)
        assert!(err.abs() < 2e-4, "Ω̄ = {om}: {got} vs {want}");
    }
}

#[test]
fn spinning_cantilever_lead_lag_needs_the_spin_softening() {
    let b = cantilever(Plane::LeadLag);
    let u = unit(Plane::LeadLag);
    for &(om, flap) in &WRIGHT_1982[1..] {
        let want = (flap * flap - om * om).sqrt();
        let got = preloaded_lowest(&b, om * u, true).sqrt() / u;
        let stiff_only = preloaded_lowest(&b, om * u, false).sqrt() / u;
        let err = (got - want) / want;
        eprintln!(
            "lead-lag Ω̄ = {om:4.1}: ω̄ = {got:.5} (K_T alone {stiff_only:.5}), \
             √(ω̄²_flap − Ω̄²) = {want:.4}, rel. error {err:+.2e}"
        );
        // measured ≤ 1.23e-4 (Ω̄ = 9, 10: √(ω̄² − Ω̄²) magnifies the table's rounding ~5×)
        assert!(err.abs() < 5e-4, "Ω̄ = {om}: {got} vs {want}");
        // the flap values: measured ≤ 4.1e-5
        assert!((stiff_only - flap).abs() < 2e-4 * flap);
    }
}

/// The Southwell coefficient three ways: the file's term K̂_G,11 (Ω = 1), the preloaded build's
/// slope (ω² − ω₀²)/Ω² extrapolated to Ω → 0 (Richardson on Ω̄ = 0.1, 0.2), the published
/// 1.1933 and the Rayleigh quotient of the exact mode; and the file's terms at speed,
/// eig(diag ω₀² + Ω² K̂_G) on the 40 lowest unloaded modes, against the preloaded build.
#[test]
fn spinning_cantilever_file_terms_equal_the_preloaded_build() {
    let b = cantilever(Plane::Flap);
    let u = unit(Plane::Flap);
    let q = 40;
    let (w0, phi) = lowest(&b.red.k, &b.red.m, q);
    let kg = modal_geometric_stiffness(
        &b.system(),
        phi.as_ref(),
        &[PreloadCase::spin(&spin(1.0))],
        &PreloadSpec::default(),
    )
    .unwrap()
    .remove(0);
    let k_file = kg[(0, 0)];
    // ω₀² by the same eigensolve as the loaded ones: the slope divides their difference by Ω²
    let w00 = preloaded_lowest(&b, 0.0, false);
    let slope = |om: f64| (preloaded_lowest(&b, om * u, false) - w00) / (om * u).powi(2);
    let k_build = (4.0 * slope(0.1) - slope(0.2)) / 3.0;
    let rq = southwell_rayleigh_quotient();
    eprintln!(
        "Southwell K₁: file term {k_file:.7}, preloaded build {k_build:.7}, exact mode's \
         Rayleigh quotient {rq:.7}, published {SOUTHWELL_1}"
    );
    assert!((rq - SOUTHWELL_1).abs() < 1e-4);
    // measured 1.1934891: +1.6e-4 (the published 1.1933 is rounded to 4e-5)
    assert!((k_file - SOUTHWELL_1).abs() < 1e-3 * SOUTHWELL_1);
    assert!(
        (k_file - k_build).abs() < 1e-6 * k_file,
        "{k_file} vs {k_build}"
    );
    for &(om, _) in &WRIGHT_1982[1..] {
        let omega = om * u;
        let a = Mat::from_fn(q, q, |i, j| {
            omega * omega * kg[(i, j)] + if i == j { w0[i] } else { 0.0 }
        });
        let file = a
            .self_adjoint_eigenvalues(faer::Side::Lower)
            .unwrap()
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let build = preloaded_lowest(&b, omega, false);
        let rel = (file.sqrt() - build.sqrt()) / build.sqrt();
        eprintln!(
            "Ω̄ = {om:4.1}: ω̄ from the file's terms ({q} modes) {:.8}, preloaded build {:.8}, \
             rel. {rel:+.2e}",
            file.sqrt() / u,
            build.sqrt() / u
        );
        // the modal basis truncates: 12 modes give 2e-5 at Ω̄ = 10, 40 modes 1.8e-7
        assert!(rel.abs() < 1e-6, "Ω̄ = {om}: {file} vs {build}");
    }
}

#[test]
fn craig_bampton_on_the_tangent_stiffness_gives_the_preloaded_frequencies() {
    let b = cantilever(Plane::Flap);
    let omega = 6.0 * unit(Plane::Flap);
    let pre = preload(
        &b.system(),
        &PreloadCase::spin(&spin(omega)),
        &PreloadSpec::default(),
    )
    .unwrap();
    let full = lowest(&pre.k_t, &b.red.m, 3).0;
    // the tip node's independent dofs as the interface
    let tip = b.asm.dofs.first[NE];
    let interface: Vec<usize> = (b.red.retained.iter().enumerate())
        .filter(|(_, &p)| (tip..tip + 6).contains(&p))
        .map(|(r, _)| r)
        .collect();
    let set = flexbody::reduce::craig_bampton::craig_bampton(
        &pre.k_t,
        &b.red.m,
        &interface,
        flexbody::reduce::select::ModeCount::All,
        &flexbody::solve::EigenSpec::default(),
    )
    .unwrap();
    for (c, f) in set.omega2.iter().zip(&full) {
        let rel = (c.sqrt() - f.sqrt()) / f.sqrt();
        eprintln!(
            "CB on K_T: ω = {:.6} rad/s, full preloaded {:.6}, rel. {rel:+.2e}",
            c.sqrt(),
            f.sqrt()
        );
        // every fixed-interface mode: CB spans the whole space (the two eigensolves agree to
        // their tolerance, ~1e-9)
        assert!(rel.abs() < 1e-8, "{c} vs {f}");
    }
}
