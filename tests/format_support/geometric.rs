//! The golden bodies of formats 1.7 and 1.8: the 3-node chain with `geometric_stiffness.bin`
//! (SPEC §5.16) for the twelve unit inertia loads.
use flexbody_reader::*;

use super::body_3node_recipe;

/// The 3-node chain of format 1.8 (SPEC §5.16, rule 15): [`body_3node_geometric_stiffness_1_7`]
/// with the acceleration and angular-acceleration fields written as the exact zeros a free
/// body's inertia relief leaves (the angular-velocity fields keep their synthetic numbers).
pub fn body_3node_geometric_stiffness() -> ReducedBody {
    let mut b = body_3node_geometric_stiffness_1_7();
    b.header.title = "3-node chain with modal geometric stiffness (format 1.8)".into();
    if let Some(g) = &mut b.geometric_stiffness {
        for f in &mut g.fields {
            if !matches!(f.load, UnitLoad::AngularVelocity(_)) {
                f.matrix.iter_mut().for_each(|a| *a = 0.0);
            }
        }
    }
    b.version = FORMAT_VERSION;
    b.version = version_for(&b);
    b
}

/// The 3-node chain with the modal geometric stiffness of the twelve unit inertia loads, as
/// `build --geometric-stiffness inertia` writes them (free-free: inertia relief). The chain's
/// modes are axial, and an axial spring's geometric stiffness acts only across it, so its true
/// terms are zero; the matrices here are synthetic symmetric numbers, distinct per load and
/// entry ((k + 1)/8 + (r + c)/4, diagonal + 1), so that a reader that mixes up loads, rows or
/// columns fails the summary. The physics of the terms is tested on real builds
/// (`tests/geometric_stiffness_file.rs`).
/// The golden file of 1.7 keeps its stamp and bytes (a 1.7 file's inertia-relief acceleration
/// fields need not be zero).
pub fn body_3node_geometric_stiffness_1_7() -> ReducedBody {
    let mut b = body_3node_recipe();
    b.header.title = "3-node chain with modal geometric stiffness (synthetic terms)".into();
    let m = b.modes.omega2.len();
    let fields = UnitLoad::inertia()
        .into_iter()
        .enumerate()
        .map(|(k, load)| GeometricField {
            load,
            matrix: (0..m * m)
                .map(|i| {
                    let (r, c) = (i / m, i % m);
                    (k + 1) as f64 / 8.0 + (r + c) as f64 / 4.0 + if r == c { 1.0 } else { 0.0 }
                })
                .collect(),
        })
        .collect();
    b.geometric_stiffness = Some(GeometricStiffness {
        support: StaticSupport::InertiaRelief,
        fields,
    });
    if let Some(r) = &mut b.recipe {
        r.options.geometric_stiffness = Some("inertia".into());
    }
    b.version = Version { major: 1, minor: 7 };
    b
}
