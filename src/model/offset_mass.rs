//! Point masses whose centre of gravity is off their node (Nastran CONM2 X1–X3, CONM1's
//! coupling block) become a mass node at the centre of gravity, rigidly linked to the node.
//!
//! The file stores one mass and one inertia per node, so a mass lumped to its node loses the
//! coupling of its offset (the first moment m·e): the stored invariants would not be the
//! body's. A rigid link is exact instead: the point mass's 6×6 matrix [m I, −m ẽ; m ẽ,
//! I_cg − m ẽ ẽ] is Hᵀ diag(m I, I_cg) H with H the rigid transfer u_cg = u + θ × e, θ_cg = θ
//! (the RBE2 row of `fe::constraints`), so the model's M and every frequency are unchanged and
//! the new node holds m and I_cg as the file stores them.

use super::{DofMask, Model, Node, NodeIndex, RigidElement};

/// A mass node made for a point mass with an offset centre of gravity.
#[derive(Debug, Clone, PartialEq)]
pub struct MassNode {
    /// The new node (at the centre of gravity).
    pub node: NodeIndex,
    /// The point mass's element id.
    pub mass_id: u64,
    /// The node the point mass was attached to.
    pub attached_to: NodeIndex,
    /// The rigid element linking them.
    pub link_id: u64,
}

/// Moves every point mass with a non-zero offset onto a new node at its centre of gravity,
/// linked to its node by an RBE2 on all six dofs; returns the nodes made, in point-mass order.
pub fn place_offset_masses(model: &mut Model) -> Vec<MassNode> {
    let mut made = Vec::new();
    for q in 0..model.point_masses.len() {
        let pm = &model.point_masses[q];
        if pm.offset.iter().all(|&v| v == 0.0) {
            continue;
        }
        let (attached_to, mass_id, offset) = (pm.node, pm.id, pm.offset);
        let x = model.nodes[attached_to].x;
        let node = model.nodes.len();
        model.nodes.push(Node {
            id: model.max_node_id() + 1,
            x: std::array::from_fn(|k| x[k] + offset[k]),
            displacement_frame: None,
        });
        let link_id = model.max_element_id() + 1;
        model.rigid_elements.push(RigidElement::Rbe2 {
            id: link_id,
            independent: attached_to,
            dependent: vec![node],
            dofs: DofMask::ALL,
        });
        let pm = &mut model.point_masses[q];
        pm.node = node;
        pm.offset = [0.0; 3];
        made.push(MassNode {
            node,
            mass_id,
            attached_to,
            link_id,
        });
    }
    made
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Bush, NodeDof, PointMass, RigidBody, ScalarSpring};

    fn node(id: u64, x: [f64; 3]) -> Node {
        Node {
            id,
            x,
            displacement_frame: None,
        }
    }

    /// The new node and link take ids above every node and element-like id of the model —
    /// springs, bushes and rigid bodies included (a spider took an RBAR's or a spring's id).
    #[test]
    fn mass_node_at_the_centre_of_gravity_with_fresh_ids() {
        let mut m = Model {
            nodes: vec![node(1, [0.0; 3]), node(40, [1.0, 0.0, 0.0])],
            ..Default::default()
        };
        m.springs.push(ScalarSpring {
            id: 700,
            a: NodeDof {
                node: 0,
                component: 0,
            },
            b: None,
            k: 1.0,
        });
        m.bushes.push(Bush {
            id: 650,
            a: 0,
            b: Some(1),
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            k: [1.0; 6],
            location: [0.0; 3],
        });
        m.rigid_bodies.push(RigidBody {
            id: 900,
            independent: vec![(0, DofMask::ALL)],
            dependent: vec![(1, DofMask::ALL)],
        });
        assert_eq!(m.max_element_id(), 900);
        let inertia = [[0.1, 0.0, 0.0], [0.0, 0.2, 0.0], [0.0, 0.0, 0.3]];
        for (id, offset) in [(5, [0.0; 3]), (6, [0.0, 0.5, -0.25])] {
            m.point_masses.push(PointMass {
                id,
                node: 1,
                mass: 3.0,
                offset,
                inertia,
            });
        }
        let made = place_offset_masses(&mut m);
        assert_eq!(
            made,
            vec![MassNode {
                node: 2,
                mass_id: 6,
                attached_to: 1,
                link_id: 901
            }]
        );
        assert_eq!(m.nodes[2].id, 41);
        assert_eq!(m.nodes[2].x, [1.0, 0.5, -0.25]);
        // the mass without an offset stays on its node; the other moved, offset cleared
        assert_eq!((m.point_masses[0].node, m.point_masses[1].node), (1, 2));
        assert_eq!(m.point_masses[1].offset, [0.0; 3]);
        assert_eq!(m.point_masses[1].inertia, inertia);
        assert_eq!(
            m.rigid_elements,
            vec![RigidElement::Rbe2 {
                id: 901,
                independent: 1,
                dependent: vec![2],
                dofs: DofMask::ALL
            }]
        );
    }
}
