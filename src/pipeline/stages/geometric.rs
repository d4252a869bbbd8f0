//! Geometric stiffness (format 1.8 `geometric_stiffness.bin`, SPEC §5.16; issue 35): when the
//! build asks (`--geometric-stiffness inertia`), the modal geometric stiffness of the body's
//! stress under each of the twelve unit inertia loads — K̂_G,j = Φᵀ K_G(σ(load j)) Φ in the
//! file's modes, from `fe::preload::modal_geometric_stiffness` — so that a multibody solver
//! stiffens the body by K̂ + Σ_j s_j K̂_G,j. Takes the constrained system and the reduced basis
//! (after the invariants stage, which restores the physical M a native Craig–Bampton run
//! released), fills [`ReducedBasis::geometric_stiffness`].
//!
//! The static solve is the preload stage's `Support::Auto`: held when the model's constraints
//! leave no rigid-body motion free, inertia relief otherwise. The angular loads act about the
//! origin of the body frame (the model's basic frame, in which the file's nodes are). Under
//! inertia relief the acceleration and angular-acceleration fields are written as exact zeros
//! (SPEC §5.16, rule 15 since 1.8).
//! Refused, never approximated: a build with a preload (its K_r is K + K_G(σ₀), so the unit
//! loads' stress would be that of another stiffness than the linear one the terms assume).

use flexbody_reader as file;

use crate::fe::preload::{
    self, statics, unit_inertia_fields, InertiaLoad, PreloadCase, PreloadSpec, System,
};
use crate::model::Model;
use crate::pipeline::plan::Plan;
use crate::pipeline::stages::Constrained;
use crate::pipeline::stages::ReducedBasis;
use crate::pipeline::{BuildError, GeometricLoads};

/// The unit load of the file for a unit inertia field of `fe::preload`.
pub(crate) fn unit_load(load: InertiaLoad) -> file::UnitLoad {
    // axes are 0, 1, 2 (unit_inertia_fields): the casts cannot truncate
    let axis = |a: usize| a as u8;
    match load {
        InertiaLoad::Acceleration(a) => file::UnitLoad::Acceleration(axis(a)),
        InertiaLoad::AngularVelocity(i, j) => file::UnitLoad::AngularVelocity([axis(i), axis(j)]),
        InertiaLoad::AngularAcceleration(a) => file::UnitLoad::AngularAcceleration(axis(a)),
    }
}

/// The geometric-stiffness stage (module doc): `basis.geometric_stiffness` when asked.
pub fn geometric_stiffness(
    plan: &Plan,
    model: &Model,
    constrained: &Constrained,
    basis: &mut ReducedBasis,
) -> Result<(), BuildError> {
    let Some(loads) = plan.spec.geometric_stiffness else {
        return Ok(());
    };
    if let Some(p) = &basis.preload {
        return Err(plan.request_error(format!(
            "--geometric-stiffness with a preload ({}): the modes are those of K + K_G(σ₀), and \
             the unit loads' stress for the file's terms must come from the linear K; build \
             the geometric-stiffness terms without the preload (the terms then give the \
             stiffening of any load level, K̂ + Σ s_j K̂_G,j)",
            p.source
        )));
    }
    basis.geometric_stiffness = Some(modal_terms(
        model,
        constrained,
        &basis.set.phi,
        loads,
        plan,
    )?);
    Ok(())
}

/// K̂_G,j of each unit load of `loads` for the modes `phi_r` (independent dofs), and the
/// static support the stress was solved on.
pub fn modal_terms(
    model: &Model,
    constrained: &Constrained,
    phi_r: &faer::Mat<f64>,
    loads: GeometricLoads,
    plan: &Plan,
) -> Result<file::GeometricStiffness, BuildError> {
    let GeometricLoads::Inertia = loads;
    let sys = System {
        model,
        assembled: &constrained.assembled,
        reduced: &constrained.reduced,
        assembly: &plan.assembly,
    };
    let fields = unit_inertia_fields([0.0; 3]);
    let cases: Vec<PreloadCase> = (fields.iter())
        .map(|(_, f)| PreloadCase {
            inertia: vec![f.clone()],
            ..Default::default()
        })
        .collect();
    let spec = PreloadSpec {
        par: plan.spec.par(),
        ..Default::default()
    };
    let rigid = statics::free_rigid_modes(model, &constrained.assembled.dofs, sys.reduced)?;
    let matrices = preload::modal_geometric_stiffness(&sys, phi_r.as_ref(), &cases, &spec)?;
    let q = phi_r.ncols();
    let held = rigid.ncols() == 0;
    Ok(file::GeometricStiffness {
        support: if held {
            file::StaticSupport::Held
        } else {
            file::StaticSupport::InertiaRelief
        },
        fields: (fields.iter().zip(&matrices))
            .map(|((load, _), g)| file::GeometricField {
                load: unit_load(*load),
                matrix: if held || !is_rigid_acceleration(*load) {
                    (0..q * q).map(|k| g[(k / q, k % q)]).collect()
                } else {
                    vec![0.0; q * q]
                },
            })
            .collect(),
    })
}

/// A rigid-body acceleration field (SPEC §5.16, format 1.8): under inertia relief the body's
/// inertia balances it everywhere, it leaves no stress, and the file holds its K̂_G as exact
/// zeros (the solve's rounding, ~1e-14 of the centrifugal terms, is not written).
fn is_rigid_acceleration(load: InertiaLoad) -> bool {
    match load {
        InertiaLoad::Acceleration(_) | InertiaLoad::AngularAcceleration(_) => true,
        InertiaLoad::AngularVelocity(..) => false,
    }
}
