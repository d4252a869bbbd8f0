//! Shells whose reference plane is off their grid points (Nastran CQUAD4/CTRIA3 `ZOFFS`): the
//! element is formed on nodes at the reference plane, each rigidly linked to its grid point.
//!
//! MSC Nastran's QRG (CQUAD4 remark on ZOFFS): the element's reference plane lies ZOFFS along
//! the element normal from the plane of its grid points (positive: above), and the offset is a
//! rigid link. So each element corner gets a node at x + ZOFFS·n, where n is the element
//! normal (CQUAD4: the cross product of the diagonals G1→G3 × G2→G4; CTRIA3: G1→G2 × G1→G3;
//! the same diagonals for a flat 8-node shell, ANSYS's SHELL281 on a TOP or BOT section),
//! and an RBE2 on all six dofs ties it to the grid point: u_ref = u + θ × (ZOFFS·n),
//! θ_ref = θ. The element's stiffness and mass are those of the offset plane, so the body's
//! M, K and its lumped mass points (at the reference plane, where the material is) are the
//! offset shell's. Elements that share a grid point and the same offset vector share the node
//! (a flat offset panel stays one connected surface at its reference plane).

use std::collections::BTreeMap;

use super::geometry::{cross, dot, norm, sub, unit};
use super::{DofMask, ElementKind, Model, Node, NodeIndex, RigidElement};

/// One shell element's offset, as read from its card.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellOffset {
    /// Index of the element in `Model::elements`.
    pub elem: usize,
    /// Signed distance from the grid points' plane to the reference plane along the normal.
    pub zoffs: f64,
}

/// What [`offset_shells`] made, for the build report.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OffsetNodes {
    /// Elements moved to their reference plane.
    pub elements: usize,
    /// The nodes made at reference planes, in creation order.
    pub nodes: Vec<NodeIndex>,
    /// The rigid links made (one RBE2 per grid point), by id.
    pub links: Vec<u64>,
}

/// The unit normal of a flat shell element (module doc); `None` for other kinds, a degenerate
/// element, an 8-node shell unless `quad8` and it is flat.
fn element_normal(model: &Model, elem: usize, quad8: bool) -> Option<[f64; 3]> {
    let e = &model.elements[elem];
    let x = |k: usize| model.nodes[e.nodes[k]].x;
    let (p, q) = match e.kind {
        // a flat 8-node shell: the corners' diagonals (below)
        ElementKind::Quad4 | ElementKind::Quad8 => (sub(x(2), x(0)), sub(x(3), x(1))),
        ElementKind::Tri3 => (sub(x(1), x(0)), sub(x(2), x(0))),
        ElementKind::Tet4
        | ElementKind::Tet10
        | ElementKind::Hex8
        | ElementKind::Hex8R
        | ElementKind::Hex8Bbar
        | ElementKind::Hex20
        | ElementKind::Hex20R
        | ElementKind::Prism6
        | ElementKind::Prism15
        | ElementKind::Pyram5
        | ElementKind::Pyram13
        | ElementKind::Pyram13Ansys
        | ElementKind::Beam2
        | ElementKind::Bar2
        | ElementKind::Beam2Linear
        | ElementKind::Beam3Quadratic
        | ElementKind::Beam4Cubic
        | ElementKind::Rod2
        | ElementKind::Beam3
        | ElementKind::Tri6 => return None,
    };
    let n = unit(cross(p, q))?;
    // an 8-node shell has one normal only when flat (its nodes within 1e-9 of its size of the
    // plane through its first corner)
    let size = (0..e.nodes.len())
        .map(|k| norm(sub(x(k), x(0))))
        .fold(0.0, f64::max);
    let flat = (0..e.nodes.len()).all(|k| dot(sub(x(k), x(0)), n).abs() <= 1e-9 * size);
    (e.kind != ElementKind::Quad8 || (quad8 && flat)).then_some(n)
}

/// Moves every offset shell onto nodes at its reference plane, rigidly linked to its grid
/// points (module doc). An error gives the position in `offsets` and names the element: not a
/// flat shell, or degenerate.
pub fn offset_shells(
    model: &mut Model,
    offsets: &[ShellOffset],
) -> Result<OffsetNodes, (usize, String)> {
    offset_elements(model, offsets, false)
}

/// [`offset_shells`] that also offsets flat 8-node shells (ANSYS's SHELL281 on a TOP or BOT
/// section, whose element forces show this offset; Nastran's and Abaqus's quadratic shells
/// keep refusing theirs).
pub fn offset_shells_and_flat_quad8(
    model: &mut Model,
    offsets: &[ShellOffset],
) -> Result<OffsetNodes, (usize, String)> {
    offset_elements(model, offsets, true)
}

/// The offsets of [`offset_shells`], flat 8-node shells with them when `quad8`.
fn offset_elements(
    model: &mut Model,
    offsets: &[ShellOffset],
    quad8: bool,
) -> Result<OffsetNodes, (usize, String)> {
    let mut made = OffsetNodes::default();
    // per grid point: the offset vectors made so far and their nodes
    let mut at_grid: BTreeMap<NodeIndex, Vec<([f64; 3], NodeIndex)>> = BTreeMap::new();
    let mut next_id = model.max_node_id() + 1;
    for (at, o) in offsets.iter().enumerate().filter(|(_, o)| o.zoffs != 0.0) {
        let eid = model.elements[o.elem].id;
        if !o.zoffs.is_finite() {
            return Err((
                at,
                format!("element {eid}: ZOFFS = {} is not a number", o.zoffs),
            ));
        }
        let n = element_normal(model, o.elem, quad8).ok_or_else(|| {
            let why = format!(
                "element {eid} ({:?}): an offset needs a flat shell (CQUAD4/CTRIA3, a flat \
                 SHELL281) with a normal; this one has none (degenerate corners?)",
                model.elements[o.elem].kind
            );
            (at, why)
        })?;
        let d = n.map(|c| o.zoffs * c);
        let tol = 1e-9 * o.zoffs.abs();
        for k in 0..model.elements[o.elem].nodes.len() {
            let grid = model.elements[o.elem].nodes[k];
            let made_here = at_grid.entry(grid).or_default();
            let same = |v: &[f64; 3]| (0..3).all(|i| (v[i] - d[i]).abs() <= tol);
            let node = match made_here.iter().find(|(v, _)| same(v)) {
                Some(&(_, node)) => node,
                None => {
                    let x = model.nodes[grid].x;
                    let node = model.nodes.len();
                    model.nodes.push(Node {
                        id: next_id,
                        x: std::array::from_fn(|i| x[i] + d[i]),
                        displacement_frame: None,
                    });
                    next_id += 1;
                    made_here.push((d, node));
                    made.nodes.push(node);
                    node
                }
            };
            model.elements[o.elem].nodes[k] = node;
        }
        made.elements += 1;
    }
    let first_link = model.max_element_id() + 1;
    for (link_id, (grid, nodes)) in (first_link..).zip(at_grid) {
        model.rigid_elements.push(RigidElement::Rbe2 {
            id: link_id,
            independent: grid,
            dependent: nodes.iter().map(|&(_, n)| n).collect(),
            dofs: DofMask::ALL,
        });
        made.links.push(link_id);
    }
    Ok(made)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Element;

    fn node(id: u64, x: [f64; 3]) -> Node {
        Node {
            id,
            x,
            displacement_frame: None,
        }
    }

    fn quad(id: u64, nodes: [usize; 4]) -> Element {
        Element {
            id,
            kind: ElementKind::Quad4,
            nodes: nodes.to_vec(),
            property: None,
            orientation: None,
        }
    }

    /// Two quads sharing an edge, offset the same: the shared grids get one reference node each
    /// (6 nodes, at z = ZOFFS along the diagonal-product normal), one RBE2 per grid; a third
    /// quad on the same grids offset the other way gets nodes of its own.
    #[test]
    fn shared_grids_share_their_reference_node() {
        let mut m = Model {
            nodes: vec![
                node(1, [0.0, 0.0, 0.0]),
                node(2, [1.0, 0.0, 0.0]),
                node(3, [2.0, 0.0, 0.0]),
                node(4, [0.0, 1.0, 0.0]),
                node(5, [1.0, 1.0, 0.0]),
                node(6, [2.0, 1.0, 0.0]),
            ],
            elements: vec![
                quad(10, [0, 1, 4, 3]),
                quad(11, [1, 2, 5, 4]),
                quad(12, [0, 1, 4, 3]),
            ],
            ..Default::default()
        };
        let offsets = [
            ShellOffset {
                elem: 0,
                zoffs: 0.25,
            },
            ShellOffset {
                elem: 1,
                zoffs: 0.25,
            },
            ShellOffset {
                elem: 2,
                zoffs: -0.5,
            },
        ];
        let made = offset_shells(&mut m, &offsets).unwrap();
        assert_eq!(
            (made.elements, made.nodes.len(), made.links.len()),
            (3, 10, 6)
        );
        for &n in &made.nodes[..6] {
            assert_eq!(m.nodes[n].x[2], 0.25);
            assert!(m.nodes[n].id > 6);
        }
        assert_eq!(m.elements[0].nodes[1], m.elements[1].nodes[0]);
        assert_eq!(m.nodes[m.elements[2].nodes[0]].x, [0.0, 0.0, -0.5]);
        assert!(made.links.iter().all(|&l| l > 12));
        let RigidElement::Rbe2 {
            independent,
            dependent,
            dofs,
            ..
        } = &m.rigid_elements[0]
        else {
            panic!("an RBE2")
        };
        assert_eq!((*independent, dependent.len(), *dofs), (0, 2, DofMask::ALL));
    }

    /// A beam cannot be offset this way: the error names the element.
    #[test]
    fn non_shell_offset_is_an_error_naming_the_element() {
        let mut m = Model {
            nodes: vec![node(1, [0.0; 3]), node(2, [1.0, 0.0, 0.0])],
            elements: vec![Element {
                id: 7,
                kind: ElementKind::Beam2,
                nodes: vec![0, 1],
                property: None,
                orientation: None,
            }],
            ..Default::default()
        };
        let (at, e) = offset_shells(
            &mut m,
            &[ShellOffset {
                elem: 0,
                zoffs: 1.0,
            }],
        )
        .unwrap_err();
        assert!(at == 0 && e.contains("element 7"), "{e}");
    }
}
