//! Where CalculiX 2.20 finds a tie's slave node on the master surface (its sources
//! `triangucont.f`, `trianeighbor.f`, `straighteq3d.f` and `gentiedmpc.f`, read, not copied):
//!
//! * every master face of every tie is cut into triangles (a 3-node face: itself; 4 nodes: two
//!   over the diagonal 2-4 of ccx's face order; 6 nodes: four; 8 nodes: six through the mid-side
//!   nodes), each with its centroid, its plane and the three planes through its edges
//!   perpendicular to it (normals outward);
//! * the in-face tolerance is 2.5 % of the mean distance from a triangle's centroid to its edge
//!   2-3 over the triangles of **all** ties; a tie's position tolerance is POSITION TOLERANCE,
//!   or that in-face tolerance when absent or below 1e-10;
//! * a slave node starts at the triangle of the tie whose centroid is nearest and walks across
//!   the edge it lies beyond by more than the in-face tolerance until it is within all three
//!   edges (found), steps back across the edge it came over (found, between two triangles), or
//!   reaches the border, returns to a triangle it walked over or takes more than 100 steps (no
//!   master face); a found node farther from the triangle's plane than the position tolerance
//!   is not tied either.
//!
//! The faces' node order is ccx's (`ifaceq`, `ifacet`, `ifacew1/2`): the same orientation as
//! [`face_nodes`], started at ccx's first corner, which decides the quadrilaterals' diagonal.

use crate::model::geometry::cross;
use crate::model::load::{face_nodes, solid_faces};
use crate::model::{ElementKind, NodeIndex};

/// The nodes of face `face` (1-based) of an element in ccx's order (module doc): corners,
/// then the mid-side node of each edge from corner k to k + 1. `None`: no such solid face.
pub(super) fn ccx_face_nodes(
    kind: ElementKind,
    nodes: &[NodeIndex],
    face: usize,
) -> Option<Vec<NodeIndex>> {
    let (faces, edges) =
        solid_faces(kind).filter(|(faces, _)| (1..=faces.len()).contains(&face))?;
    let ours = face_nodes(nodes, faces[face - 1], edges)?;
    // ccx's first corner of each face (0-based element-local index): hex `ifaceq`, tet
    // `ifacet`, wedge `ifacew1`; pyramids have no ccx face order (kept as they are)
    let first = match kind {
        ElementKind::Hex8
        | ElementKind::Hex8R
        | ElementKind::Hex8Bbar
        | ElementKind::Hex20
        | ElementKind::Hex20R => [3, 4, 0, 1, 2, 3][face - 1],
        ElementKind::Tet4 | ElementKind::Tet10 => [0, 0, 1, 0][face - 1],
        ElementKind::Prism6 | ElementKind::Prism15 => [0, 3, 0, 1, 2][face - 1],
        ElementKind::Pyram5 | ElementKind::Pyram13 | ElementKind::Pyram13Ansys => {
            faces[face - 1][0]
        }
        ElementKind::Beam2
        | ElementKind::Bar2
        | ElementKind::Beam2Linear
        | ElementKind::Beam3Quadratic
        | ElementKind::Beam4Cubic
        | ElementKind::Rod2
        | ElementKind::Tri3
        | ElementKind::Quad4
        | ElementKind::Tri6
        | ElementKind::Quad8
        | ElementKind::Beam3 => return None,
    };
    let corners = faces[face - 1].len();
    let at = ours[..corners].iter().position(|&n| n == nodes[first])?;
    let turn = |part: &[NodeIndex]| -> Vec<NodeIndex> {
        (0..part.len())
            .map(|k| part[(k + at) % part.len()])
            .collect()
    };
    let mut out = turn(&ours[..corners]);
    if ours.len() > corners {
        out.extend(turn(&ours[corners..]));
    }
    Some(out)
}

/// ccx's triangles of a face of `n` nodes (`itrifac3/4/6/8`, 0-based positions in the face).
fn face_triangles(n: usize) -> &'static [[usize; 3]] {
    match n {
        3 => &[[0, 1, 2]],
        4 => &[[0, 1, 3], [1, 2, 3]],
        6 => &[[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]],
        8 => &[
            [0, 4, 7],
            [4, 1, 5],
            [6, 5, 2],
            [7, 6, 3],
            [7, 4, 6],
            [4, 5, 6],
        ],
        _ => &[],
    }
}

/// One master triangle: its corners, the face it belongs to, its centroid and four planes
/// (normal, offset): through edges 2-3, 3-1, 1-2 (outward), then its own.
struct Triangle {
    corners: [NodeIndex; 3],
    face: usize,
    centroid: [f64; 3],
    planes: [[f64; 4]; 4],
}

/// Where a slave node was found (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Found {
    /// On this face (index into the faces the triangulation was built from).
    Face(usize),
    /// Opposite a master face, farther from it than the position tolerance: the distance.
    TooFar(f64),
    /// No master face opposite.
    NoFace,
}

/// The triangulated master surfaces of all ties (module doc).
pub(super) struct MasterTriangles {
    triangles: Vec<Triangle>,
    /// The triangle across edge 2-3, 3-1, 1-2 of each triangle.
    across: Vec<[Option<usize>; 3]>,
    /// The triangles of each tie.
    ranges: Vec<std::ops::Range<usize>>,
    /// ccx's in-face tolerance (`tolloc`).
    pub in_face_tolerance: f64,
}

impl MasterTriangles {
    /// The triangles of `faces_per_tie` (each face: its nodes in ccx's order, the global face
    /// index returned by [`Self::find`]) at the node positions `x`.
    pub fn new(
        faces_per_tie: &[Vec<(usize, Vec<NodeIndex>)>],
        x: impl Fn(NodeIndex) -> [f64; 3],
    ) -> Self {
        let mut triangles = Vec::new();
        let mut ranges = Vec::new();
        for faces in faces_per_tie {
            let start = triangles.len();
            for (face, nodes) in faces {
                for t in face_triangles(nodes.len()) {
                    let corners = t.map(|k| nodes[k]);
                    let c = corners.map(&x);
                    triangles.push(Triangle {
                        corners,
                        face: *face,
                        centroid: [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0),
                        planes: planes(c),
                    });
                }
            }
            ranges.push(start..triangles.len());
        }
        let across = neighbours(&triangles);
        let sum: f64 = (triangles.iter())
            .map(|t| plane_distance(t.planes[0], t.centroid).abs())
            .sum();
        let in_face_tolerance = 0.025 * sum / triangles.len().max(1) as f64;
        MasterTriangles {
            triangles,
            across,
            ranges,
            in_face_tolerance,
        }
    }

    /// The master face of tie `tie` holding the point `p` within the position `tolerance`
    /// (module doc).
    pub fn find(&self, tie: usize, p: [f64; 3], tolerance: f64) -> Found {
        let Some(start) = (self.ranges[tie].clone()).min_by(|&a, &b| {
            let d = |t: usize| dist2(self.triangles[t].centroid, p);
            d(a).total_cmp(&d(b))
        }) else {
            return Found::NoFace;
        };
        let (mut at, mut came_from) = (start, None);
        let mut walked: Vec<usize> = Vec::new();
        'walk: loop {
            for l in 0..3 {
                if plane_distance(self.triangles[at].planes[l], p) <= self.in_face_tolerance {
                    continue;
                }
                match self.across[at][l] {
                    None => return Found::NoFace,
                    Some(next) if Some(next) == came_from => break 'walk,
                    Some(next) => {
                        if walked.contains(&next) || walked.len() >= 100 {
                            return Found::NoFace;
                        }
                        walked.push(next);
                        (came_from, at) = (Some(at), next);
                        continue 'walk;
                    }
                }
            }
            break;
        }
        let t = &self.triangles[at];
        let off = plane_distance(t.planes[3], p).abs();
        if off > tolerance {
            Found::TooFar(off)
        } else {
            Found::Face(t.face)
        }
    }
}

/// ccx's `straighteq3d`: the planes through edges 2-3, 3-1, 1-2 of triangle `c` perpendicular
/// to it with outward unit normals, and its own plane (normal (2−1) × (3−2), unit).
fn planes(c: [[f64; 3]; 3]) -> [[f64; 4]; 4] {
    let sub = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|k| a[k] - b[k]);
    let (p12, p23, p31) = (sub(c[1], c[0]), sub(c[2], c[1]), sub(c[0], c[2]));
    let unit = |v: [f64; 3]| {
        let n = dist2(v, [0.0; 3]).sqrt().max(f64::MIN_POSITIVE);
        v.map(|x| x / n)
    };
    let n = unit(cross(p12, p23));
    let plane = |normal: [f64; 3], through: [f64; 3]| {
        [
            normal[0],
            normal[1],
            normal[2],
            -(normal[0] * through[0] + normal[1] * through[1] + normal[2] * through[2]),
        ]
    };
    [
        plane(unit(cross(p23, n)), c[1]),
        plane(unit(cross(p31, n)), c[2]),
        plane(unit(cross(p12, n)), c[0]),
        plane(n, c[0]),
    ]
}

/// ccx's `trianeighbor`: for each triangle, the triangle sharing its edge 2-3, 3-1, 1-2.
fn neighbours(triangles: &[Triangle]) -> Vec<[Option<usize>; 3]> {
    let mut across = vec![[None; 3]; triangles.len()];
    let mut open: std::collections::HashMap<(NodeIndex, NodeIndex), (usize, usize)> =
        std::collections::HashMap::new();
    for (j, t) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t.corners[k], t.corners[(k + 1) % 3]);
            // the edge from corner k to k + 1 is opposite corner k + 2: plane (k + 2) mod 3
            let side = (k + 2) % 3;
            let key = (a.min(b), a.max(b));
            if let Some((other, other_side)) = open.remove(&key) {
                across[j][side] = Some(other);
                across[other][other_side] = Some(j);
            } else {
                open.insert(key, (j, side));
            }
        }
    }
    across
}

fn plane_distance(plane: [f64; 4], p: [f64; 3]) -> f64 {
    plane[0] * p[0] + plane[1] * p[1] + plane[2] * p[2] + plane[3]
}

fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}
