//! Graphics faces: the free (outer) faces of the solid mesh, plus shell faces and beam/rod lines,
//! so a multibody solver can draw the body.
//!
//! A face of a solid element is *free* when no other element has a face with the same corner
//! nodes. Faces are reported by their corner nodes only (3 or 4; mid-side nodes of quadratic
//! elements are not needed to draw), oriented so that the right-hand normal points out of the
//! element that owns the face. Beams and rods give 2-node lines; shell elements with a property
//! give their own face.
//!
//! Corner faces per element kind, Abaqus/Nastran node order (1-based):
//!
//! ```text
//! tet   : 1-2-3  1-4-2  2-4-3  3-4-1
//! prism : 1-2-3  4-6-5  1-4-5-2  2-5-6-3  3-6-4-1
//! hex   : 1-2-3-4  5-8-7-6  1-5-6-2  2-6-7-3  3-7-8-4  4-8-5-1
//! pyram : 1-2-3-4  1-5-2  2-5-3  3-5-4  4-5-1
//!
//!        8-------7          6            4
//!       /|      /|         /|\          /|\
//!      5-------6 |        4---5        / | \
//!      | 4-----|-3        | 3 |       1--|--3
//!      |/      |/         |/ \|        \ | /
//!      1-------2          1---2          2
//! ```

use std::collections::HashMap;

use crate::model::load::{self, FaceTable};
use crate::model::{ElementKind, Model, NodeIndex};

/// A polygon to draw: 2 (line), 3 (triangle) or 4 (quadrilateral) node indices into
/// [`Model::nodes`].
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct GraphicsFace {
    /// Node indices, outward-oriented for solid faces.
    pub nodes: Vec<NodeIndex>,
}

/// Corner faces of a solid element kind (local 0-based corner indices), `None` for non-solids.
fn solid_faces(kind: ElementKind) -> Option<FaceTable> {
    load::solid_faces(kind).map(|(faces, _)| faces)
}

/// The faces and lines to draw for `model`, in a deterministic order (element order, then face
/// order within the element).
pub fn graphics_faces(model: &Model) -> Vec<GraphicsFace> {
    // Count every solid corner face by its sorted node set.
    let mut count: HashMap<Vec<NodeIndex>, u32> = HashMap::new();
    let key = |nodes: &[NodeIndex]| {
        let mut k = nodes.to_vec();
        k.sort_unstable();
        k
    };
    for e in &model.elements {
        if let Some(faces) = solid_faces(e.kind) {
            for f in faces {
                let corners: Vec<NodeIndex> = f.iter().map(|&i| e.nodes[i]).collect();
                *count.entry(key(&corners)).or_insert(0) += 1;
            }
        }
    }
    let mut out = Vec::new();
    for e in &model.elements {
        match e.kind {
            ElementKind::Beam2
            | ElementKind::Bar2
            | ElementKind::Beam2Linear
            | ElementKind::Rod2 => out.push(GraphicsFace {
                nodes: e.nodes.clone(),
            }),
            // nodes I, J, mid: two segments through the mid node
            ElementKind::Beam3Quadratic => {
                for pair in [[e.nodes[0], e.nodes[2]], [e.nodes[2], e.nodes[1]]] {
                    out.push(GraphicsFace {
                        nodes: pair.to_vec(),
                    });
                }
            }
            // nodes I, J, K (1/3), L (2/3): three segments I–K–L–J
            ElementKind::Beam4Cubic => {
                let [i, j, k, l] = [0, 1, 2, 3].map(|a| e.nodes[a]);
                for pair in [[i, k], [k, l], [l, j]] {
                    out.push(GraphicsFace {
                        nodes: pair.to_vec(),
                    });
                }
            }
            ElementKind::Tri3 | ElementKind::Tri6 | ElementKind::Quad4 | ElementKind::Quad8 => {
                if e.property.is_some() {
                    let corners = if matches!(e.kind, ElementKind::Tri3 | ElementKind::Tri6) {
                        3
                    } else {
                        4
                    };
                    out.push(GraphicsFace {
                        nodes: e.nodes[..corners].to_vec(),
                    });
                }
            }
            // never assembled (expanded into bricks on import): nothing to draw
            ElementKind::Beam3 => {}
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
            | ElementKind::Pyram13Ansys => {
                let Some(faces) = solid_faces(e.kind) else {
                    continue;
                };
                let corner_count = faces
                    .iter()
                    .flat_map(|f| f.iter())
                    .max()
                    .map_or(0, |m| m + 1);
                let centroid = mean(model, &e.nodes[..corner_count]);
                for f in faces {
                    let mut corners: Vec<NodeIndex> = f.iter().map(|&i| e.nodes[i]).collect();
                    if count.get(&key(&corners)) != Some(&1) {
                        continue;
                    }
                    // Orient outward: the right-hand normal must point away from the element centroid.
                    let n = polygon_normal(model, &corners);
                    let c = mean(model, &corners);
                    let outward: f64 = (0..3).map(|k| n[k] * (c[k] - centroid[k])).sum();
                    if outward < 0.0 {
                        corners[1..].reverse();
                    }
                    out.push(GraphicsFace { nodes: corners });
                }
            }
        }
    }
    out
}

fn mean(model: &Model, nodes: &[NodeIndex]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for &n in nodes {
        for (ck, xk) in c.iter_mut().zip(model.nodes[n].x) {
            *ck += xk / nodes.len() as f64;
        }
    }
    c
}

/// Newell's normal of a polygon (twice the vector area for a planar polygon).
fn polygon_normal(model: &Model, nodes: &[NodeIndex]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for i in 0..nodes.len() {
        let a = model.nodes[nodes[i]].x;
        let b = model.nodes[nodes[(i + 1) % nodes.len()]].x;
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Element, Node};

    /// nx×ny×nz unit hex8 cubes; optionally each cube split into 6 tets (Kuhn split, conforming).
    fn block(nx: usize, ny: usize, nz: usize, tets: bool) -> Model {
        let id = |i: usize, j: usize, k: usize| (k * (ny + 1) + j) * (nx + 1) + i;
        let mut m = Model::default();
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    m.nodes.push(Node {
                        id: id(i, j, k) as u64 + 1,
                        x: [i as f64, j as f64, k as f64],
                        displacement_frame: None,
                    });
                }
            }
        }
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let h = [
                        id(i, j, k),
                        id(i + 1, j, k),
                        id(i + 1, j + 1, k),
                        id(i, j + 1, k),
                        id(i, j, k + 1),
                        id(i + 1, j, k + 1),
                        id(i + 1, j + 1, k + 1),
                        id(i, j + 1, k + 1),
                    ];
                    let elems: Vec<(ElementKind, Vec<usize>)> = if tets {
                        // Kuhn: 6 tets around the 0–6 diagonal.
                        [
                            [0, 1, 2, 6],
                            [0, 2, 3, 6],
                            [0, 3, 7, 6],
                            [0, 7, 4, 6],
                            [0, 4, 5, 6],
                            [0, 5, 1, 6],
                        ]
                        .iter()
                        .map(|t| (ElementKind::Tet4, t.iter().map(|&a| h[a]).collect()))
                        .collect()
                    } else {
                        vec![(ElementKind::Hex8, h.to_vec())]
                    };
                    for (kind, nodes) in elems {
                        m.elements.push(Element {
                            id: m.elements.len() as u64 + 1,
                            kind,
                            nodes,
                            property: Some(0),
                            orientation: None,
                        });
                    }
                }
            }
        }
        m
    }

    /// Divergence theorem: Σ_faces (centroid · n_area) = 3·V for a closed, outward surface.
    fn divergence_volume(m: &Model, faces: &[GraphicsFace]) -> f64 {
        faces
            .iter()
            .map(|f| {
                let n = polygon_normal(m, &f.nodes);
                let c = mean(m, &f.nodes);
                0.5 * (0..3).map(|k| n[k] * c[k]).sum::<f64>() / 3.0
            })
            .sum()
    }

    #[test]
    fn hex_block_free_faces_are_the_outer_surface_outward() {
        let m = block(3, 2, 2, false);
        let faces = graphics_faces(&m);
        // Outer surface of a 3×2×2 block of unit cubes: 2(3·2 + 3·2 + 2·2) = 32 quads.
        assert_eq!(faces.len(), 32);
        assert!(faces.iter().all(|f| f.nodes.len() == 4));
        assert!((divergence_volume(&m, &faces) - 12.0).abs() < 1e-12);
    }

    #[test]
    fn tet_block_free_faces_close_the_volume_outward() {
        let m = block(2, 2, 1, true);
        let faces = graphics_faces(&m);
        // Each outer unit square is split into 2 triangles: 2(4 + 2 + 2) squares · 2.
        assert_eq!(faces.len(), 32);
        assert!((divergence_volume(&m, &faces) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn beams_give_lines_and_surface_elements_without_property_are_skipped() {
        let mut m = block(1, 1, 1, false);
        m.elements.push(Element {
            id: 90,
            kind: ElementKind::Beam2,
            nodes: vec![0, 7],
            property: Some(1),
            orientation: Some([0.0, 0.0, 1.0]),
        });
        m.elements.push(Element {
            id: 91,
            kind: ElementKind::Quad4,
            nodes: vec![0, 1, 2, 3],
            property: None,
            orientation: None,
        });
        let faces = graphics_faces(&m);
        assert_eq!(faces.len(), 7);
        assert_eq!(faces[6].nodes, vec![0, 7]);
    }
}
