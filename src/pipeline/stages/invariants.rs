//! Invariants: the mass points of the body — every node with its lumped structural mass, every
//! point mass at its centre of gravity — and the nine inertia invariants from them
//! ([`compute_invariants`]), or from the consistent M when the modes are orthonormal in it
//! ([`consistent_invariants`], SPEC §5.6).

use faer::Mat;

use crate::body::invariants::{compute_invariants, MassPoint};
use crate::body::invariants_consistent::consistent_invariants;
use crate::fe::{self, assemble, Assembled, AssemblySpec, BeamLumping, DofMap, MassKind};
use crate::model::{DofMatrix, Model, NodeIndex};
use crate::pipeline::plan::Plan;
use crate::pipeline::stages::node_shape;
use crate::pipeline::stages::Constrained;
use crate::pipeline::stages::ReducedBasis;
use crate::pipeline::stages::{MassProperties, NodalMass};
use crate::pipeline::BuildError;

/// The invariants stage.
pub fn invariants(
    plan: &Plan,
    model: &Model,
    constrained: &mut Constrained,
    basis: &ReducedBasis,
) -> Result<MassProperties, BuildError> {
    let spec = &plan.spec;
    let assembled = &mut constrained.assembled;
    if basis.mass_released {
        assembled.m = assemble(model, &plan.assembly)?.m;
    }
    let dofs = &assembled.dofs;
    let phi = &basis.phi;
    // The lumped M of the reduction already holds the nodal masses unless point masses were
    // added to it (they are separate mass points) or the reduction used consistent mass.
    let reusable =
        (spec.mass == MassKind::Lumped && model.point_masses.is_empty()).then_some(&*assembled);
    let (points, point_shapes, nodal) =
        mass_points(model, dofs, phi, reusable, plan.assembly.beam_lumping)?;
    let invariants = if spec.mass == MassKind::Consistent {
        // SPEC §5.6: the invariants use the mass the modes are orthonormal in.
        let x: Vec<[f64; 3]> = model.nodes.iter().map(|n| n.x).collect();
        let shape = |p: NodeIndex, j: usize| -> [f64; 3] {
            let s = node_shape(dofs, phi, p, j);
            [s[0], s[1], s[2]]
        };
        consistent_invariants(&assembled.m, dofs, &x, phi, &shape, spec.invariants)
    } else {
        compute_invariants(&points, point_shapes.as_ref(), spec.invariants, spec.par())?
    };
    Ok(MassProperties { nodal, invariants })
}

/// Mass points for the invariants: every node with its lumped structural mass (a lumped assembly
/// of the model without point masses, or `lumped` when that is already it), plus one point per point mass at its centre of gravity,
/// moving rigidly with its node (u + θ × d). Returns the points, their 6-row shapes, and the
/// per-node mass (structure + point masses lumped to the node, inertia shifted to the node) that
/// the file stores.
fn mass_points(
    model: &Model,
    dofs: &DofMap,
    phi: &Mat<f64>,
    lumped: Option<&Assembled>,
    beam_lumping: BeamLumping,
) -> Result<(Vec<MassPoint>, Mat<f64>, NodalMass), BuildError> {
    let own;
    let lumped = match lumped {
        Some(l) => l,
        None => {
            let mut bare = model.clone();
            bare.point_masses.clear();
            // a matrix's mass coupling nodes (an ANSYS full file's M) lumped per node
            bare.dof_matrices = model.dof_matrices.iter().map(DofMatrix::lumped).collect();
            own = assemble(
                &bare,
                &AssemblySpec {
                    mass: fe::MassKind::Lumped,
                    beam_lumping,
                    ..Default::default()
                },
            )?;
            &own
        }
    };
    let mut nodal = nodal_masses(model, lumped);
    let nn = model.nodes.len();
    let nm = phi.ncols();
    let np = nn + model.point_masses.len();
    let mut points = Vec::with_capacity(np);
    let mut shapes = Mat::<f64>::zeros(6 * np, nm);
    for (p, node) in model.nodes.iter().enumerate() {
        points.push(MassPoint {
            position: node.x,
            mass: nodal[p].0,
            inertia: nodal[p].1,
        });
        for j in 0..nm {
            let s = node_shape(dofs, phi, p, j);
            for (c, v) in s.iter().enumerate() {
                shapes[(6 * p + c, j)] = *v;
            }
        }
    }
    for (q, pm) in model.point_masses.iter().enumerate() {
        let row = 6 * (nn + q);
        let d = pm.offset;
        let x = model.nodes[pm.node].x;
        points.push(MassPoint {
            position: std::array::from_fn(|k| x[k] + d[k]),
            mass: pm.mass,
            inertia: pm.inertia,
        });
        for j in 0..nm {
            let s = node_shape(dofs, phi, pm.node, j);
            let cross = [
                s[4] * d[2] - s[5] * d[1],
                s[5] * d[0] - s[3] * d[2],
                s[3] * d[1] - s[4] * d[0],
            ];
            for c in 0..3 {
                shapes[(row + c, j)] = s[c] + cross[c];
                shapes[(row + 3 + c, j)] = s[3 + c];
            }
        }
        // Lumped to the node for the stored nodal mass: inertia about the node = J + m(d·d E − d dᵀ).
        let dd = d.iter().map(|v| v * v).sum::<f64>();
        let (m0, i0) = &mut nodal[pm.node];
        *m0 += pm.mass;
        for r in 0..3 {
            for c in 0..3 {
                i0[r][c] +=
                    pm.inertia[r][c] + pm.mass * (if r == c { dd } else { 0.0 } - d[r] * d[c]);
            }
        }
    }
    Ok((points, shapes, nodal))
}

/// Per node: the lumped mass (the mean of its three translational diagonal entries) and the
/// rotary inertia block of a 6-dof node in the basic frame, I_basic = Aᵀ I_local A.
fn nodal_masses(model: &Model, lumped: &Assembled) -> NodalMass {
    let (ld, lm) = (&lumped.dofs, lumped.m.as_ref());
    let entry = |row: usize, col: usize| -> f64 {
        lm.row_idx_of_col(col)
            .zip(lm.val_of_col(col))
            .find(|(r, _)| *r == row)
            .map_or(0.0, |(_, v)| *v)
    };
    let nn = model.nodes.len();
    let mut nodal: NodalMass = Vec::with_capacity(nn);
    for p in 0..nn {
        let count = usize::from(ld.count[p]);
        if count == 0 {
            nodal.push((0.0, [[0.0; 3]; 3]));
            continue;
        }
        let f = ld.first[p];
        let mass = (0..3).map(|c| entry(f + c, f + c)).sum::<f64>() / 3.0;
        let mut inertia = [[0.0; 3]; 3];
        if count == 6 {
            let local: [[f64; 3]; 3] =
                std::array::from_fn(|r| std::array::from_fn(|c| entry(f + 3 + r, f + 3 + c)));
            // I_basic = Aᵀ I_local A.
            inertia = match ld.frames[p] {
                None => local,
                Some(a) => std::array::from_fn(|r| {
                    std::array::from_fn(|c| {
                        (0..3)
                            .map(|i| (0..3).map(|k| a[i][r] * local[i][k] * a[k][c]).sum::<f64>())
                            .sum()
                    })
                }),
            };
        }
        nodal.push((mass, inertia));
    }
    nodal
}
