//! The rigid-body mass properties of a mesh's lumped mass matrix against those of its consistent
//! one (issue 47: a coarse tet4 bar's lumped Ixx was 20 % above the exact value, and the build
//! said nothing, while a multibody solver takes the file's inertia as the truth).
//!
//! With R the six rigid-body vectors (translations e_a; rotations e_b × x on translational dofs,
//! e_b on rotational dofs; basic axes), Rᵀ M R = [[m E, −m c̃], [m c̃, J_o]]: the mass m, the
//! first moment m c and the inertia about the origin J_o (SPEC §5.6's I1, I2, I7). Both
//! matrices come from one pass over the elements (each element's lumped and consistent mass
//! matrix in the basic frame), plus the point masses, which both share. Scalar connectors
//! (CMASS) are left out of both.

use rayon::prelude::*;

use super::assembly::{element_matrices, is_structural, AssemblySpec};
use super::mass::{point_mass_matrix, MassKind};
use super::FeError;
use crate::model::Model;

/// Rᵀ M R of one mass matrix: rows and columns tx ty tz rx ry rz.
pub type RigidMassMatrix = [[f64; 6]; 6];

/// Mass, centre of mass and principal inertia about the centre (ascending) of a rigid-body mass
/// matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Total mass.
    pub mass: f64,
    /// Centre of mass, basic frame.
    pub centre: [f64; 3],
    /// Principal moments of inertia about the centre of mass, ascending.
    pub principal: [f64; 3],
}

/// The lumped mass's rigid-body properties against the consistent mass's, with the relative
/// differences the build's warning is judged on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InertiaComparison {
    /// From the lumped mass matrix (the one the build uses).
    pub lumped: MassProperties,
    /// From the consistent mass matrix of the same mesh.
    pub consistent: MassProperties,
    /// |m_l − m_c| / m_c.
    pub mass: f64,
    /// |c_l − c_c| over the consistent mass's largest radius of gyration √(J_max / m).
    pub centre: f64,
    /// |J_l,i − J_c,i| / J_c,i per principal moment (ascending), J_c,i floored at 1e-3 J_max
    /// (a slender part's moment about its axis, next to nothing, is judged against the others).
    pub principal: [f64; 3],
}

impl InertiaComparison {
    /// The largest of the relative differences.
    pub fn worst(&self) -> f64 {
        [self.mass, self.centre]
            .into_iter()
            .chain(self.principal)
            .fold(0.0, f64::max)
    }
}

/// Rᵀ M_e R of the element matrices `m` (row-major, `dpn` dofs per node) at the nodes `x`.
fn element_rigid_mass(m: &[f64], dpn: usize, x: &[[f64; 3]]) -> RigidMassMatrix {
    let nd = dpn * x.len();
    // R_e: nd × 6
    let mut r = vec![[0.0f64; 6]; nd];
    for (p, xp) in x.iter().enumerate() {
        for c in 0..dpn.min(6) {
            let row = &mut r[p * dpn + c];
            if c < 3 {
                row[c] = 1.0;
                // (e_b × x)_c for b = 0, 1, 2
                let (i, j) = ((c + 1) % 3, (c + 2) % 3);
                row[3 + i] = xp[j];
                row[3 + j] = -xp[i];
            } else {
                row[c] = 1.0;
            }
        }
    }
    let mut out = [[0.0; 6]; 6];
    for a in 0..nd {
        for b in 0..nd {
            let mab = m[a * nd + b];
            if mab == 0.0 {
                continue;
            }
            for (i, oi) in out.iter_mut().enumerate() {
                let ri = r[a][i] * mab;
                if ri == 0.0 {
                    continue;
                }
                for (j, o) in oi.iter_mut().enumerate() {
                    *o += ri * r[b][j];
                }
            }
        }
    }
    out
}

fn add(a: &mut RigidMassMatrix, b: &RigidMassMatrix) {
    for (ra, rb) in a.iter_mut().zip(b) {
        for (x, y) in ra.iter_mut().zip(rb) {
            *x += y;
        }
    }
}

/// Rᵀ M R of the lumped and of the consistent mass matrix of `model` (the rest of `spec` as
/// the build assembles), in one pass over the elements.
pub fn lumped_and_consistent(
    model: &Model,
    spec: &AssemblySpec,
) -> Result<(RigidMassMatrix, RigidMassMatrix), FeError> {
    let lumped_spec = AssemblySpec {
        mass: MassKind::Lumped,
        ..*spec
    };
    let consistent_spec = AssemblySpec {
        mass: MassKind::Consistent,
        ..*spec
    };
    let elements: Vec<usize> = (model.elements.iter().enumerate())
        .filter(|(_, e)| e.property.is_some() || is_structural(e.kind))
        .map(|(i, _)| i)
        .collect();
    let per_element = elements
        .par_iter()
        .map(|&e| {
            let x: Vec<[f64; 3]> = (model.elements[e].nodes.iter())
                .map(|&n| model.nodes[n].x)
                .collect();
            let l = element_matrices(model, e, &lumped_spec)?;
            let c = element_matrices(model, e, &consistent_spec)?;
            Ok((
                element_rigid_mass(&l.nodal_mass(), l.dpn, &x),
                // a rigid motion excites no interior dof (ccx's C3D8I modes): the nodal block
                element_rigid_mass(&c.nodal_mass(), c.dpn, &x),
            ))
        })
        .collect::<Result<Vec<_>, FeError>>()?;
    let (mut lumped, mut consistent) = ([[0.0; 6]; 6], [[0.0; 6]; 6]);
    for (l, c) in &per_element {
        add(&mut lumped, l);
        add(&mut consistent, c);
    }
    for pm in &model.point_masses {
        let m6 = point_mass_matrix(pm);
        let flat: Vec<f64> = m6.iter().flatten().copied().collect();
        let r = element_rigid_mass(&flat, 6, &[model.nodes[pm.node].x]);
        add(&mut lumped, &r);
        add(&mut consistent, &r);
    }
    Ok((lumped, consistent))
}

/// Mass, centre and principal inertia of Rᵀ M R (SPEC §5.6: c = I2/I1, J_c = J_o − m((c·c)E −
/// c cᵀ)).
pub fn properties(rr: &RigidMassMatrix) -> MassProperties {
    let mass = (rr[0][0] + rr[1][1] + rr[2][2]) / 3.0;
    // t_aᵀ M r_b = (e_a × e_b) · S with S the first moment
    let first = [rr[1][5], rr[2][3], rr[0][4]];
    let centre = if mass > 0.0 {
        first.map(|s| s / mass)
    } else {
        [0.0; 3]
    };
    let cc: f64 = centre.iter().map(|v| v * v).sum();
    let jc = faer::Mat::<f64>::from_fn(3, 3, |i, j| {
        let jo = 0.5 * (rr[3 + i][3 + j] + rr[3 + j][3 + i]);
        jo - mass * (if i == j { cc } else { 0.0 } - centre[i] * centre[j])
    });
    let mut principal = [0.0; 3];
    if let Ok(values) = jc.self_adjoint_eigenvalues(faer::Side::Lower) {
        for (p, v) in principal.iter_mut().zip(values) {
            *p = v;
        }
    }
    principal.sort_by(f64::total_cmp);
    MassProperties {
        mass,
        centre,
        principal,
    }
}

/// The lumped mass's rigid-body properties against the consistent mass's of the same mesh.
pub fn compare(model: &Model, spec: &AssemblySpec) -> Result<InertiaComparison, FeError> {
    let (l, c) = lumped_and_consistent(model, spec)?;
    let (lumped, consistent) = (properties(&l), properties(&c));
    let j_max = consistent.principal[2].max(f64::MIN_POSITIVE);
    let gyration = if consistent.mass > 0.0 {
        (j_max / consistent.mass).sqrt()
    } else {
        1.0
    };
    let distance = (0..3)
        .map(|k| (lumped.centre[k] - consistent.centre[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    Ok(InertiaComparison {
        lumped,
        consistent,
        mass: (lumped.mass - consistent.mass).abs() / consistent.mass.abs().max(f64::MIN_POSITIVE),
        centre: distance / gyration,
        principal: std::array::from_fn(|i| {
            (lumped.principal[i] - consistent.principal[i]).abs()
                / consistent.principal[i].abs().max(1e-3 * j_max)
        }),
    })
}

/// The build's warning when the lumped mass's rigid-body properties are more than `limit`
/// (relative) off the consistent mass's: both figures and the option that fixes it.
pub fn warning(cmp: &InertiaComparison, limit: f64) -> Option<String> {
    if cmp.worst() <= limit {
        return None;
    }
    let (l, c) = (&cmp.lumped, &cmp.consistent);
    let v3 = |v: &[f64; 3]| format!("({:.4e}, {:.4e}, {:.4e})", v[0], v[1], v[2]);
    Some(format!(
        "the lumped mass's rigid-body inertia is up to {:.1} % off the consistent mass of the same \
         mesh (mass {:.4e} vs {:.4e}; centre {} vs {}; principal inertia {} vs {}): a multibody \
         solver takes the file's inertia as the part's; build with --mass consistent for the \
         exact rigid-body inertia (the modes of a fine mesh are right with either)",
        100.0 * cmp.worst(),
        l.mass,
        c.mass,
        v3(&l.centre),
        v3(&c.centre),
        v3(&l.principal),
        v3(&c.principal)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit point mass at (1, 2, 3): m = 1, c = (1, 2, 3), J_c = 0; its Rᵀ M R has
    /// J_o = (c·c)E − c cᵀ (the parallel-axis term alone).
    #[test]
    fn a_point_mass_has_its_position_as_centre_and_no_inertia_about_it() {
        let mut m = vec![0.0; 9];
        for k in 0..3 {
            m[k * 3 + k] = 1.0;
        }
        let rr = element_rigid_mass(&m, 3, &[[1.0, 2.0, 3.0]]);
        let p = properties(&rr);
        assert!((p.mass - 1.0).abs() < 1e-15);
        assert!(
            (0..3).all(|k| (p.centre[k] - [1.0, 2.0, 3.0][k]).abs() < 1e-14),
            "{p:?}"
        );
        assert!(p.principal.iter().all(|v| v.abs() < 1e-13), "{p:?}");
        // J_o,xx = y² + z² = 13
        assert!((rr[3][3] - 13.0).abs() < 1e-13, "{rr:?}");
    }
}
