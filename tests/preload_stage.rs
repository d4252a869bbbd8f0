//! The preload stage's static solve and its errors (issue 35):
//!
//! * a free beam spinning about its midpoint: inertia relief against its six rigid-body modes,
//!   the axial force against the closed form N(s) = ½ρAΩ²(L²/4 − s²) (element means);
//! * gravity on a free body is balanced by its inertia: no stress;
//! * `Support::Held` on a free body, a mechanism and a load the importer could not use are
//!   errors naming what is wrong;
//! * the file's unit inertia terms: Σ_{i≤j} ω_iω_j K̂_G,ij equals K̂_G of the spin ω on a free
//!   body (linearity of the preload, the fields' decomposition).

use crate::common::steel;
use crate::preload_support::{hold, lowest, nodal_load, straight_line, Built};
use faer::Mat;
use flexbody::fe::geometric::{element_stresses, ElementStress};
use flexbody::fe::preload::{
    modal_geometric_stiffness, preload, unit_inertia_fields, InertiaLoad, PreloadCase,
    PreloadError, PreloadSpec, Spin, Support,
};
use flexbody::fe::{AssemblySpec, MassKind};
use flexbody::model::{BeamSection, ElementKind, Load, LoadPart, Model, Section};

const L: f64 = 2.0;
const NE: usize = 40;
const AREA: f64 = 8e-4;

/// A free beam along x centred at the origin (rod: `rod` elements instead of beams).
fn free_beam(rod: bool) -> Model {
    let (kind, section) = if rod {
        (
            ElementKind::Rod2,
            Section::Rod {
                area: AREA,
                j: 1e-8,
                nsm: 0.0,
            },
        )
    } else {
        (
            ElementKind::Beam2,
            Section::Beam(BeamSection {
                area: AREA,
                i1: 1e-8,
                i2: 2e-8,
                i12: 0.0,
                j: 2e-8,
                shear_factors: None,
                nsm: 0.0,
                shape: None,
                taper: None,
            }),
        )
    };
    straight_line(
        NE,
        [-0.5 * L, 0.0, 0.0],
        [0.5 * L, 0.0, 0.0],
        kind,
        section,
        steel(),
        [0.0, 1.0, 0.0],
    )
}

fn consistent() -> AssemblySpec {
    AssemblySpec {
        mass: MassKind::Consistent,
        ..Default::default()
    }
}

fn spin_z(omega: f64) -> Spin {
    Spin {
        point: [0.0; 3],
        axis: [0.0, 0.0, 1.0],
        omega,
    }
}

#[test]
fn free_spinning_beam_axial_force_matches_closed_form_with_inertia_relief() {
    let b = Built::new(free_beam(false), consistent());
    let omega = 100.0;
    let pre = preload(
        &b.system(),
        &PreloadCase::spin(&spin_z(omega)),
        &PreloadSpec::default(),
    )
    .unwrap();
    assert_eq!(pre.rigid_modes, 6);
    let stresses = element_stresses(&b.model, &b.asm.dofs, &b.spec, &pre.u, None).unwrap();
    let (rho, h) = (steel().rho, L / NE as f64);
    let n_max = 0.5 * rho * AREA * omega * omega * L * L / 4.0;
    let mut worst = 0.0f64;
    for (e, s) in &stresses {
        let ElementStress::Axial(n) = s else {
            panic!("{s:?}")
        };
        let mid = L * ((*e as f64 + 0.5) / NE as f64 - 0.5);
        // the element's mean of the parabola (linear elements carry the mean force)
        let want = 0.5 * rho * AREA * omega * omega * (L * L / 4.0 - mid * mid - h * h / 12.0);
        worst = worst.max((n - want).abs() / n_max);
    }
    eprintln!("free spinning beam: largest axial-force error {worst:.2e} of N_max = {n_max:.4e}");
    assert!(worst < 1e-9, "{worst}");
}

#[test]
fn gravity_on_a_free_body_is_balanced_by_its_inertia() {
    let b = Built::new(free_beam(false), consistent());
    let g = Load {
        name: "GRAVITY".into(),
        source: "test".into(),
        selected: true,
        parts: vec![LoadPart::Gravity {
            accel: [0.0, -9.81, 3.0],
        }],
        problem: None,
    };
    let case = PreloadCase {
        loads: vec![g],
        ..Default::default()
    };
    let pre = preload(&b.system(), &case, &PreloadSpec::default()).unwrap();
    let umax = pre.u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    assert!(umax < 1e-15, "{umax}");
}

#[test]
fn held_support_on_a_free_body_is_an_error() {
    let b = Built::new(free_beam(false), consistent());
    let spec = PreloadSpec {
        support: Support::Held,
        ..Default::default()
    };
    let err = preload(&b.system(), &PreloadCase::spin(&spin_z(10.0)), &spec).unwrap_err();
    eprintln!("{err}");
    assert!(
        matches!(err, PreloadError::NotHeld { rigid: 6, .. }),
        "{err}"
    );
}

/// Two collinear rods pinned at their far ends: the middle node's lateral motion has no
/// stiffness (a string without its tension) and is not a rigid-body motion.
#[test]
fn a_mechanism_is_an_error_naming_its_node() {
    let mut model = free_beam(true);
    model.nodes.truncate(3);
    model.elements.truncate(2);
    hold(&mut model, 0, "123456");
    hold(&mut model, 2, "123456");
    let b = Built::new(model, consistent());
    let case = PreloadCase {
        loads: vec![nodal_load(1, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0])],
        ..Default::default()
    };
    let err = preload(&b.system(), &case, &PreloadSpec::default()).unwrap_err();
    eprintln!("{err}");
    assert!(
        matches!(err, PreloadError::Singular { node: 2, .. }),
        "{err}"
    );
}

/// On a free body (inertia relief), the six unit angular-velocity terms combine into the spin's:
/// Σ_{i≤j} ω_iω_j K̂_G,ij = K̂_G(ω) for an oblique ω.
#[test]
fn unit_angular_velocity_terms_combine_into_the_spin_term_on_a_free_body() {
    let b = Built::new(free_beam(false), consistent());
    let (_, phi) = lowest(&b.red.k, &b.red.m, 14);
    let fields = unit_inertia_fields([0.0; 3]);
    let cases: Vec<PreloadCase> = (fields.iter())
        .map(|(_, f)| PreloadCase {
            inertia: vec![f.clone()],
            ..Default::default()
        })
        .collect();
    let w = [0.4, -1.1, 2.3];
    let norm = w.iter().map(|v: &f64| v * v).sum::<f64>().sqrt();
    let spin = Spin {
        point: [0.0; 3],
        axis: w,
        omega: norm,
    };
    let mut all = cases.clone();
    all.push(PreloadCase::spin(&spin));
    let terms = modal_geometric_stiffness(&b.system(), phi.as_ref(), &all, &PreloadSpec::default())
        .unwrap();
    let q = phi.ncols();
    let mut sum = Mat::<f64>::zeros(q, q);
    for ((label, _), t) in fields.iter().zip(&terms) {
        if let InertiaLoad::AngularVelocity(i, j) = label {
            sum += t * (w[*i] * w[*j]);
        }
    }
    let want = &terms[fields.len()];
    let scale = want.norm_max();
    let diff = (&sum - want).norm_max();
    eprintln!(
        "Σ ω_iω_j K̂_G,ij vs K̂_G(ω): {:.2e} of {scale:.3e}",
        diff / scale
    );
    assert!(scale > 0.0 && diff < 1e-10 * scale);
}

#[test]
fn a_load_the_importer_could_not_use_is_refused_not_dropped() {
    let b = Built::new(free_beam(false), consistent());
    let mut load = nodal_load(3, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    load.problem = Some("deck.bdf:12 PLOAD4 with a non-uniform pressure".into());
    let case = PreloadCase {
        loads: vec![load],
        ..Default::default()
    };
    let err = preload(&b.system(), &case, &PreloadSpec::default()).unwrap_err();
    eprintln!("{err}");
    assert!(matches!(err, PreloadError::Load { .. }), "{err}");
    assert!(err.to_string().contains("deck.bdf:12"));
}
