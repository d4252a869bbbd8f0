//! What joins dofs besides elements and RBE2/RBE3: scalar springs and masses, bushes, linear
//! multipoint constraints and rigid bodies with chosen independent dofs. Importers fill them
//! (Nastran CELAS1–4, CMASS1–4, CBUSH, MPC, RBAR, RBAR1, RBE1; Abaqus `*SPRING`, `*MASS`,
//! `*EQUATION` alike); `fe` assembles and eliminates them.
//!
//! A component is 0 … 5 = `[ux uy uz rx ry rz]` of a grid in its displacement frame (Nastran
//! CD), or 0 for the one dof of a scalar point ([`super::Model::scalar_points`]).

use super::{DofMask, NodeIndex};

/// One dof: a node and a component (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct NodeDof {
    /// The node (a grid or a scalar point).
    pub node: NodeIndex,
    /// 0 … 5 for a grid, 0 for a scalar point.
    pub component: u8,
}

/// A scalar spring between two dofs, or from one dof to ground: strain energy
/// ½ k (u_a − u_b)², u_b = 0 when grounded (MSC QRG "CELAS1": the components are those of the
/// grids' displacement frames).
#[derive(Debug, Clone, PartialEq)]
pub struct ScalarSpring {
    /// External element id.
    pub id: u64,
    /// First end.
    pub a: NodeDof,
    /// Second end; `None` = grounded.
    pub b: Option<NodeDof>,
    /// Stiffness k (force/length or moment/radian).
    pub k: f64,
}

/// A scalar mass between two dofs, or on one dof: kinetic energy ½ m (u̇_a − u̇_b)² (MSC QRG
/// "CMASS1"; grounded, the common case, it is a mass on one component).
#[derive(Debug, Clone, PartialEq)]
pub struct ScalarMass {
    /// External element id.
    pub id: u64,
    /// First end.
    pub a: NodeDof,
    /// Second end; `None` = grounded.
    pub b: Option<NodeDof>,
    /// Mass m (already scaled by WTMASS).
    pub m: f64,
}

/// A bush: six stiffnesses along and about the axes of an element frame, acting at a spring
/// point rigidly attached to both ends (Nastran CBUSH/PBUSH, MSC QRG "CBUSH").
///
/// With d_n = x_s − x_n and H_n = [I, −d̃_n; 0, I] (the motion of the spring point carried by
/// node n), E = diag(R, R) (R's rows the element axes in basic), the deformation is
/// δ = E (H_b q_b − H_a q_a) and the strain energy ½ δᵀ diag(k) δ (q_b = 0 when grounded).
#[derive(Debug, Clone, PartialEq)]
pub struct Bush {
    /// External element id.
    pub id: u64,
    /// End A (GA).
    pub a: NodeIndex,
    /// End B (GB); `None` = grounded.
    pub b: Option<NodeIndex>,
    /// Rows: the element's x, y and z axes, unit vectors in basic.
    pub axes: [[f64; 3]; 3],
    /// K1 … K6: along x, y, z (force/length) and about x, y, z (moment/radian).
    pub k: [f64; 6],
    /// The spring point x_s, basic.
    pub location: [f64; 3],
}

impl Bush {
    /// An axial spring between nodes a and b at xa and xb: strain energy ½ k (e·(u_b − u_a))²,
    /// e the unit vector from a to b (CalculiX SPRINGA, ANSYS COMBIN14 KEYOPT(2)=0): k along e
    /// alone, the spring point at node a on the axis, so the rotations do not enter. `None`
    /// when the nodes coincide (no direction).
    pub fn axial(
        id: u64,
        (a, xa): (NodeIndex, [f64; 3]),
        (b, xb): (NodeIndex, [f64; 3]),
        k: f64,
    ) -> Option<Bush> {
        let d = [xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if a == b || !(len > 0.0 && len.is_finite()) {
            return None;
        }
        Some(Bush {
            id,
            a,
            b: Some(b),
            axes: orthonormal_frame(d.map(|c| c / len)),
            k: [k, 0.0, 0.0, 0.0, 0.0, 0.0],
            location: xa,
        })
    }
}

/// A right-handed orthonormal frame whose first axis is the unit vector `e1`.
fn orthonormal_frame(e1: [f64; 3]) -> [[f64; 3]; 3] {
    let cross = |p: [f64; 3], q: [f64; 3]| {
        [
            p[1] * q[2] - p[2] * q[1],
            p[2] * q[0] - p[0] * q[2],
            p[0] * q[1] - p[1] * q[0],
        ]
    };
    // the basic axis least aligned with e1
    let k = (0..3)
        .min_by(|&i, &j| e1[i].abs().total_cmp(&e1[j].abs()))
        .unwrap_or(0);
    let mut t = [0.0; 3];
    t[k] = 1.0;
    let e2 = cross(e1, t);
    let n = (e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]).sqrt();
    let e2 = e2.map(|c| c / n);
    [e1, e2, cross(e1, e2)]
}

/// A symmetric stiffness and mass matrix given term by term on dofs (Nastran GENEL, DMIG
/// matrices selected by K2GG/M2GG, CBUSH1D): on the nodes' own (displacement-frame) dofs, or
/// on the basic frame's components, added to K and M as written. A term (a, b, v) adds v at
/// row a, column b; both triangles are listed.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DofMatrix {
    /// What it is, for messages (`GENEL 12`, `DMIG KAX (K2GG)`).
    pub what: String,
    /// Stiffness terms.
    pub stiffness: Vec<(NodeDof, NodeDof, f64)>,
    /// Mass terms (already scaled by WTMASS where the format says so).
    pub mass: Vec<(NodeDof, NodeDof, f64)>,
    /// The components are the basic frame's (rotated into the nodes' displacement frames by
    /// the assembler); else the nodes' own.
    pub basic: bool,
}

impl DofMatrix {
    /// The matrix with its mass lumped to node blocks, for what needs a mass per node (the
    /// file's nodal masses): unchanged when no mass term couples two nodes; else diagonal, each
    /// translation's diagonal terms scaled so that they hold the matrix's mass in that direction
    /// (HRZ lumping, Hinton, Rock & Zienkiewicz 1976: m_ii' = m_ii · Σ_jk m_jk / Σ_j m_jj over
    /// the terms of one direction), rotations' diagonal terms kept.
    pub fn lumped(&self) -> DofMatrix {
        if self.mass.iter().all(|(a, b, _)| a.node == b.node) {
            return self.clone();
        }
        let (mut total, mut diagonal) = ([0.0; 6], [0.0; 6]);
        for &(a, b, v) in &self.mass {
            if a.component == b.component {
                total[usize::from(a.component)] += v;
                if a.node == b.node {
                    diagonal[usize::from(a.component)] += v;
                }
            }
        }
        let scale = |c: usize| match c {
            0..=2 if diagonal[c] != 0.0 => total[c] / diagonal[c],
            _ => 1.0,
        };
        let mass = (self.mass.iter())
            .filter(|(a, b, _)| a == b)
            .map(|&(a, b, v)| (a, b, v * scale(usize::from(a.component))))
            .collect();
        DofMatrix {
            mass,
            ..self.clone()
        }
    }

    /// Every node a term of the matrix names, ascending, once.
    pub fn nodes(&self) -> Vec<NodeIndex> {
        let mut nodes: Vec<NodeIndex> = (self.stiffness.iter().chain(&self.mass))
            .flat_map(|(a, b, _)| [a.node, b.node])
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}

/// A linear multipoint constraint Σ cᵢ uᵢ = 0; the first term's dof is the dependent one
/// (Nastran MPC, MSC QRG "MPC": u₁ = −Σᵢ₌₂ (cᵢ/c₁) uᵢ).
#[derive(Debug, Clone, PartialEq)]
pub struct Mpc {
    /// The set id (Nastran SID), for messages.
    pub id: u64,
    /// (dof, coefficient); at least one, the first coefficient non-zero.
    pub terms: Vec<(NodeDof, f64)>,
}

/// A rigid body whose independent dofs are chosen among its nodes (Nastran RBAR, RBAR1, RBE1):
/// the six independent dofs fix its rigid motion; every dependent dof follows that motion.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBody {
    /// External element id.
    pub id: u64,
    /// Independent components per node (six in all, determining the rigid motion).
    pub independent: Vec<(NodeIndex, DofMask)>,
    /// Dependent components per node.
    pub dependent: Vec<(NodeIndex, DofMask)>,
}

impl RigidBody {
    /// Every node of the body, independent ones first.
    pub fn nodes(&self) -> impl Iterator<Item = NodeIndex> + '_ {
        self.independent
            .iter()
            .chain(&self.dependent)
            .map(|&(n, _)| n)
    }
}
