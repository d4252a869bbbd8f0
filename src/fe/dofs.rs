//! `DofMap`: node ↔ global dof index, node-major, 3 dofs per solid-only node and 6 where beams,
//! rods, shells (with a property), rigid elements or point masses with inertia attach; nodes
//! that nothing uses get none. Springs, scalar masses, MPCs and rigid bodies ask for the
//! components they name (3 for a translation, 6 for a rotation; a bush with rotational
//! stiffness or an offset spring point 6). A scalar point (Nastran SPOINT) has 1 dof when
//! something attaches to it; a scalar point named as a grid (by an element, a rigid element,
//! a component other than 0) is an error.
//!
//! Dofs are expressed in each node's displacement frame (Nastran GRID CD): for a node with a
//! frame, `frames[node]` holds R whose rows are the local unit axes at the node in the basic
//! frame, so u_local = R u_basic for translations and rotations alike. Cylindrical frames use
//! (e_r, e_θ, e_z) and spherical ones (e_R, e_θ, e_φ) evaluated at the node (MSC Nastran QRG,
//! CORD2C/CORD2S).
//!
//! After the nodes' dofs (`0..n_physical`) come the interior dofs of elements that keep
//! internal unknowns in the system (ccx 2.20's C3D8I: its nine incompatible-mode amplitudes,
//! as ccx keeps them): no node owns them, `node_of` gives `None`, and they are expressed in the
//! basic frame. The assembly appends them ([`DofMap::append_interior`]).

use super::mass::point_mass_has_rotary;
use super::FeError;
use crate::model::geometry::{cross, dot, norm, scale, sub};
use crate::model::{CoordKind, ElementKind, Model, NodeDof, RigidElement};

/// Node ↔ dof numbering of a model.
#[derive(Debug, Clone, PartialEq)]
pub struct DofMap {
    /// First global dof of each node (meaningful when `count[node] > 0`).
    pub first: Vec<usize>,
    /// Dofs per node: 0, 3 or 6 (`[ux uy uz]` or `[ux uy uz rx ry rz]`); 1 for a scalar point.
    pub count: Vec<u8>,
    /// Displacement-frame rotation per node (rows = local axes in the basic frame).
    pub frames: Vec<Option<[[f64; 3]; 3]>>,
    /// Total number of dofs: the nodes' then the elements' interior dofs.
    pub n_dofs: usize,
    /// Number of the nodes' dofs (`0..n_physical`); the interior dofs follow.
    pub n_physical: usize,
    /// Interior dof blocks, ascending by element and by first dof.
    pub interior: Vec<InteriorDofs>,
}

/// The interior dofs of one element: `first .. first + count`, no node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InteriorDofs {
    /// Element index in the model.
    pub element: usize,
    /// First global dof.
    pub first: usize,
    /// Number of dofs.
    pub count: usize,
}

impl DofMap {
    /// Number the dofs of `model` (rules in the module doc).
    pub fn from_model(model: &Model) -> Result<DofMap, FeError> {
        let nn = model.nodes.len();
        let mut count = vec![0u8; nn];
        let bad_node = |node: usize, what: String| FeError::BadReference {
            source_file: model.source.clone(),
            message: format!("{what} refers to node index {node}, but the model has {nn} nodes"),
        };
        let mut raise = |node: usize, n: u8, what: &dyn Fn() -> String| -> Result<(), FeError> {
            let c = count.get_mut(node).ok_or_else(|| bad_node(node, what()))?;
            if (n == 1) != model.is_scalar_point(node) {
                return Err(FeError::BadReference {
                    source_file: model.source.clone(),
                    message: format!(
                        "{} names {} {} as {}",
                        what(),
                        if n == 1 { "grid" } else { "scalar point" },
                        model.nodes[node].id,
                        if n == 1 {
                            "a scalar point (component 0)"
                        } else {
                            "a grid (a scalar point has one dof, component 0)"
                        }
                    ),
                });
            }
            *c = (*c).max(n);
            Ok(())
        };
        for e in &model.elements {
            let n = match e.kind {
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
                | ElementKind::Pyram13Ansys => 3,
                ElementKind::Beam2
                | ElementKind::Bar2
                | ElementKind::Beam2Linear
                | ElementKind::Beam3Quadratic
                | ElementKind::Beam4Cubic
                | ElementKind::Rod2
                | ElementKind::Quad4
                | ElementKind::Tri3
                | ElementKind::Quad8
                | ElementKind::Tri6 => 6,
                // expanded into bricks on import: never assembled
                ElementKind::Beam3 => continue,
            };
            if e.property.is_none() {
                continue;
            }
            for &node in &e.nodes {
                raise(node, n, &|| format!("element {}", e.id))?;
            }
        }
        for p in &model.point_masses {
            let n = if point_mass_has_rotary(p) { 6 } else { 3 };
            raise(p.node, n, &|| format!("point mass {}", p.id))?;
        }
        for r in &model.rigid_elements {
            match r {
                RigidElement::Rbe2 {
                    id,
                    independent,
                    dependent,
                    ..
                } => {
                    raise(*independent, 6, &|| format!("RBE2 {id}"))?;
                    for &d in dependent {
                        raise(d, 3, &|| format!("RBE2 {id}"))?;
                    }
                }
                RigidElement::Rbe3 {
                    id,
                    reference,
                    ref_dofs,
                    independent,
                } => {
                    let n = if ref_dofs.dofs().any(|k| k >= 3) {
                        6
                    } else {
                        3
                    };
                    raise(*reference, n, &|| format!("RBE3 {id}"))?;
                    for &(node, _, _) in independent {
                        raise(node, 3, &|| format!("RBE3 {id}"))?;
                    }
                }
            }
        }
        // The dofs a component needs: 1 on a scalar point (component 0), else 3 or 6.
        let need = |d: NodeDof| -> u8 {
            match d.component {
                _ if model.is_scalar_point(d.node) && d.component == 0 => 1,
                0..=2 => 3,
                _ => 6,
            }
        };
        let check = |d: NodeDof, what: &dyn Fn() -> String| -> Result<(), FeError> {
            if d.component > 5 {
                return Err(FeError::BadReference {
                    source_file: model.source.clone(),
                    message: format!(
                        "{} names component {} (0-based, at most 5)",
                        what(),
                        d.component
                    ),
                });
            }
            Ok(())
        };
        let ends = |a: NodeDof, b: Option<NodeDof>| std::iter::once(a).chain(b);
        for s in &model.springs {
            for d in ends(s.a, s.b) {
                check(d, &|| format!("spring {}", s.id))?;
                raise(d.node, need(d), &|| format!("spring {}", s.id))?;
            }
        }
        for s in &model.scalar_masses {
            for d in ends(s.a, s.b) {
                check(d, &|| format!("scalar mass {}", s.id))?;
                raise(d.node, need(d), &|| format!("scalar mass {}", s.id))?;
            }
        }
        for matrix in &model.dof_matrices {
            for &(a, b, _) in matrix.stiffness.iter().chain(&matrix.mass) {
                for d in [a, b] {
                    check(d, &|| matrix.what.clone())?;
                    raise(d.node, need(d), &|| matrix.what.clone())?;
                }
            }
        }
        for m in &model.mpcs {
            for (d, _) in &m.terms {
                check(*d, &|| format!("MPC {}", m.id))?;
                raise(d.node, need(*d), &|| format!("MPC {}", m.id))?;
            }
        }
        for r in &model.rigid_bodies {
            for &(node, mask) in r.independent.iter().chain(&r.dependent) {
                let n = if mask.dofs().any(|c| c >= 3) { 6 } else { 3 };
                raise(node, n, &|| format!("rigid element {}", r.id))?;
            }
        }
        for bush in &model.bushes {
            let rotational = bush.k[3..].iter().any(|&k| k != 0.0);
            for node in std::iter::once(bush.a).chain(bush.b) {
                let x = model.nodes.get(node).map_or([0.0; 3], |n| n.x);
                let offset = (0..3).any(|i| bush.location[i] != x[i]);
                let n = if rotational || offset { 6 } else { 3 };
                raise(node, n, &|| format!("bush {}", bush.id))?;
            }
        }
        let mut first = vec![0usize; nn];
        let mut next = 0usize;
        for (f, &c) in first.iter_mut().zip(&count) {
            *f = next;
            next += usize::from(c);
        }
        let mut frames = vec![None; nn];
        for (i, node) in model.nodes.iter().enumerate() {
            if let Some(cs) = node.displacement_frame {
                let sys = model
                    .coord_systems
                    .get(cs)
                    .ok_or_else(|| FeError::BadReference {
                        source_file: model.source.clone(),
                        message: format!(
                            "node {} uses coordinate system index {cs}, which does not exist",
                            node.id
                        ),
                    })?;
                frames[i] = Some(frame_at(sys.kind, sys.origin, &sys.axes, node.x));
            }
        }
        Ok(DofMap {
            first,
            count,
            frames,
            n_dofs: next,
            n_physical: next,
            interior: Vec::new(),
        })
    }

    /// Append `count` interior dofs of element `element` (after every dof so far; elements in
    /// ascending order) and return the first.
    pub fn append_interior(&mut self, element: usize, count: usize) -> usize {
        let first = self.n_dofs;
        self.interior.push(InteriorDofs {
            element,
            first,
            count,
        });
        self.n_dofs += count;
        first
    }

    /// The interior dofs of element `element`, if it has any.
    pub fn interior_of(&self, element: usize) -> Option<std::ops::Range<usize>> {
        let i = self
            .interior
            .binary_search_by_key(&element, |b| b.element)
            .ok()?;
        let b = self.interior[i];
        Some(b.first..b.first + b.count)
    }

    /// Global dof of component `comp` (0 = ux … 5 = rz) of `node`, if it exists.
    pub fn dof(&self, node: usize, comp: usize) -> Option<usize> {
        let c = usize::from(*self.count.get(node)?);
        (comp < c).then(|| self.first[node] + comp)
    }

    /// (node, component) of a global dof; `None` for an interior dof.
    pub fn node_of(&self, dof: usize) -> Option<(usize, usize)> {
        if dof >= self.n_physical {
            return None;
        }
        // Last node whose first dof is ≤ dof and that owns dofs.
        let mut node = self.first.partition_point(|&f| f <= dof).checked_sub(1)?;
        while self.count[node] == 0 || self.first[node] > dof {
            node = node.checked_sub(1)?;
        }
        Some((node, dof - self.first[node]))
    }
}

/// Local axes (rows, basic components) of a displacement frame at point `x`.
pub fn frame_at(
    kind: CoordKind,
    origin: [f64; 3],
    axes: &[[f64; 3]; 3],
    x: [f64; 3],
) -> [[f64; 3]; 3] {
    let d = sub(x, origin);
    let p = [dot(axes[0], d), dot(axes[1], d), dot(axes[2], d)];
    let to_basic = |v: [f64; 3]| -> [f64; 3] {
        std::array::from_fn(|i| axes[0][i] * v[0] + axes[1][i] * v[1] + axes[2][i] * v[2])
    };
    match kind {
        CoordKind::Rectangular => *axes,
        CoordKind::Cylindrical => {
            let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
            let (c, s) = if r > 0.0 {
                (p[0] / r, p[1] / r)
            } else {
                (1.0, 0.0)
            };
            [to_basic([c, s, 0.0]), to_basic([-s, c, 0.0]), axes[2]]
        }
        CoordKind::Spherical => {
            let rr = norm(p);
            let er = if rr > 0.0 {
                scale(p, 1.0 / rr)
            } else {
                [0.0, 0.0, 1.0]
            };
            let rxy = (p[0] * p[0] + p[1] * p[1]).sqrt();
            let ephi = if rxy > 0.0 {
                [-p[1] / rxy, p[0] / rxy, 0.0]
            } else {
                [0.0, 1.0, 0.0]
            };
            let eth = cross(ephi, er);
            [to_basic(er), to_basic(eth), to_basic(ephi)]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{DofMask, Element, Node, PointMass};

    /// Tet4 on nodes 0–3, a beam 3–4, a translational point mass on 5, an RBE2 from 6 to 0,
    /// node 7 unused: counts 3,3,3,6,6,3,6,0 and node-major numbering.
    #[test]
    fn dof_counts_follow_what_attaches_and_numbering_is_node_major() {
        let mut m = Model::default();
        for i in 0..8 {
            m.nodes.push(Node {
                id: 100 + i as u64,
                x: [i as f64, 0.0, 0.0],
                displacement_frame: None,
            });
        }
        let el = |kind, nodes| Element {
            id: 1,
            kind,
            nodes,
            property: Some(0),
            orientation: None,
        };
        m.elements.push(el(ElementKind::Tet4, vec![0, 1, 2, 3]));
        m.elements.push(el(ElementKind::Beam2, vec![3, 4]));
        m.point_masses.push(PointMass {
            id: 2,
            node: 5,
            mass: 1.0,
            offset: [0.0; 3],
            inertia: [[0.0; 3]; 3],
        });
        m.rigid_elements.push(RigidElement::Rbe2 {
            id: 3,
            independent: 6,
            dependent: vec![0],
            dofs: DofMask::ALL,
        });
        let d = DofMap::from_model(&m).unwrap();
        assert_eq!(d.count, vec![3, 3, 3, 6, 6, 3, 6, 0]);
        assert_eq!(d.n_dofs, 30);
        assert_eq!(d.dof(3, 5), Some(14));
        assert_eq!(d.dof(0, 3), None);
        assert_eq!(d.node_of(14), Some((3, 5)));
        assert_eq!(d.node_of(29), Some((6, 5)));
        assert_eq!(d.node_of(30), None);
    }

    /// A spring from a grid's rotation to a scalar point: 6 dofs at the grid, 1 at the point;
    /// a scalar mass on a translation: 3; a scalar point named with component 3 is an error.
    #[test]
    fn connectors_ask_for_their_components_and_scalar_points_have_one_dof() {
        use crate::model::{NodeDof, ScalarMass, ScalarSpring};
        let mut m = Model::default();
        for i in 0..3 {
            m.nodes.push(Node {
                id: 10 + i as u64,
                x: [0.0; 3],
                displacement_frame: None,
            });
        }
        m.scalar_points = vec![1];
        let dof = |node, component| NodeDof { node, component };
        m.springs.push(ScalarSpring {
            id: 1,
            a: dof(0, 4),
            b: Some(dof(1, 0)),
            k: 1.0,
        });
        m.scalar_masses.push(ScalarMass {
            id: 2,
            a: dof(2, 1),
            b: None,
            m: 1.0,
        });
        let d = DofMap::from_model(&m).unwrap();
        assert_eq!((d.count.clone(), d.n_dofs), (vec![6, 1, 3], 10));
        assert_eq!(d.node_of(6), Some((1, 0)));
        m.springs[0].b = Some(dof(1, 3));
        let e = DofMap::from_model(&m).unwrap_err().to_string();
        assert!(
            e.contains("spring 1 names scalar point 11 as a grid"),
            "{e}"
        );
    }

    #[test]
    fn cylindrical_frame_at_node_is_radial_tangential_axial() {
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let r = frame_at(
            CoordKind::Cylindrical,
            [1.0, 0.0, 0.0],
            &axes,
            [1.0, 2.0, 5.0],
        );
        assert_eq!(r, [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
        let s = frame_at(CoordKind::Spherical, [0.0; 3], &axes, [3.0, 0.0, 0.0]);
        // e_R = x, e_θ (towards −z from the equator… θ measured from z) = −z, e_φ = y
        assert_eq!(s, [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]);
    }

    /// Two ccx C3D8I in a row: each keeps nine interior dofs after the 36 nodes' dofs
    /// (`node_of` has none for them), and the assembled K and M rows and columns of one
    /// element's interior dofs are its own 33 × 33's; under lumped mass there are none.
    #[test]
    fn ccx_c3d8i_modes_are_interior_dofs_after_the_nodes() {
        use crate::fe::elements::{solid_incompatible, Isotropic, Xyz};
        use crate::fe::{assemble, AssemblySpec, MassKind};
        use crate::model::generate::{block, BlockElement, BlockSpec};
        let mut model = block(&BlockSpec {
            n: [2, 1, 1],
            size: [0.4, 0.1, 0.1],
            element: BlockElement::Hex8,
            material: crate::model::Material::steel(),
        });
        model.params.solid_bubbles = true;
        model.params.ccx_solid_rules = true;
        let spec = AssemblySpec {
            mass: MassKind::Consistent,
            ..Default::default()
        };
        let a = assemble(&model, &spec).unwrap();
        let d = &a.dofs;
        assert_eq!((d.n_physical, d.n_dofs, d.interior.len()), (36, 54, 2));
        assert_eq!(d.interior_of(1), Some(45..54));
        assert_eq!(d.node_of(36), None);
        let el = &model.elements[0];
        let x: [Xyz; 8] = std::array::from_fn(|i| model.nodes[el.nodes[i]].x);
        let mat = &model.materials[0];
        let (k, m) =
            solid_incompatible::hex8_ccx_matrices(&x, &Isotropic::new(mat.e, mat.nu, mat.rho))
                .unwrap();
        let global = |l: usize| -> usize {
            if l < 24 {
                d.dof(el.nodes[l / 3], l % 3).unwrap()
            } else {
                36 + l - 24
            }
        };
        let at = |s: &faer::sparse::SparseColMat<usize, f64>, r: usize, c: usize| -> f64 {
            let s = s.as_ref();
            (s.row_idx_of_col(c).zip(s.val_of_col(c)))
                .find(|(i, _)| *i == r)
                .map_or(0.0, |(_, v)| *v)
        };
        let scale = k.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let mscale = m.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        // the interior dofs' rows and columns are the element's alone
        for i in 24..33 {
            for j in 0..33 {
                let (gi, gj) = (global(i), global(j));
                assert!((at(&a.k, gi, gj) - k[i * 33 + j]).abs() <= 1e-12 * scale);
                assert!((at(&a.k, gj, gi) - k[j * 33 + i]).abs() <= 1e-12 * scale);
                assert!((at(&a.m, gi, gj) - m[i * 33 + j]).abs() <= 1e-12 * mscale);
            }
        }
        let lumped = assemble(&model, &AssemblySpec::default()).unwrap();
        assert_eq!((lumped.dofs.n_dofs, lumped.dofs.interior.len()), (36, 0));
    }
}
