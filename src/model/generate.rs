//! Reproducible structured block meshes `[0,Lx]×[0,Ly]×[0,Lz]` → [`Model`], for tests and
//! benchmarks that need a mesh of a given size without a mesh file.
//!
//! * Hex8: nx·ny·nz bricks, node id `1 + i + (nx+1)(j + (ny+1)k)`.
//! * Tet10: each brick split into 6 tetrahedra (Kuhn split along the main diagonal, the same in
//!   every brick) or 5 (a central tetrahedron plus four corners, mirrored in alternate bricks so
//!   faces match). Mid-side nodes are shared between neighbours; nodes live on the half-step
//!   lattice and are numbered from 1 in lattice order (x fastest), skipping unused points.
//!
//! Every element has positive volume in Abaqus/Nastran node order. Sets: node sets `X0` (x = 0
//! face), `XL` (x = Lx face) and `NALL`; element set `SOLID`; one solid property `SOLID` with
//! the given material.

use std::collections::BTreeMap;

use super::{Element, ElementKind, Material, Model, ModelParams, Node, Property, Section};

/// Element type and tet split of a generated block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockElement {
    /// 8-node bricks.
    Hex8,
    /// 10-node tetrahedra, 6 per brick.
    Tet10Six,
    /// 10-node tetrahedra, 5 per brick.
    Tet10Five,
}

/// A structured block mesh request.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockSpec {
    /// Bricks along x, y, z (each ≥ 1).
    pub n: [usize; 3],
    /// Box size Lx, Ly, Lz.
    pub size: [f64; 3],
    /// Element type.
    pub element: BlockElement,
    /// Material of the single solid section.
    pub material: Material,
}

/// Generate the block mesh. Panics only if a count in `spec.n` is zero (a programming error).
pub fn block(spec: &BlockSpec) -> Model {
    assert!(
        spec.n.iter().all(|&k| k >= 1),
        "block: every count must be >= 1"
    );
    let (nodes, elements, x0, xl) = match spec.element {
        BlockElement::Hex8 => hex_mesh(spec),
        BlockElement::Tet10Six | BlockElement::Tet10Five => tet_mesh(spec),
    };
    let n_nodes = nodes.len();
    let n_el = elements.len();
    let mut node_sets = BTreeMap::new();
    node_sets.insert("X0".to_owned(), x0);
    node_sets.insert("XL".to_owned(), xl);
    node_sets.insert("NALL".to_owned(), (0..n_nodes).collect());
    let mut element_sets = BTreeMap::new();
    element_sets.insert("SOLID".to_owned(), (0..n_el).collect());
    Model {
        source: format!(
            "generated {:?} block {:?} size {:?}",
            spec.element, spec.n, spec.size
        ),
        nodes,
        elements,
        properties: vec![Property {
            id: 1,
            name: "SOLID".into(),
            material: 0,
            section: Section::Solid,
        }],
        materials: vec![spec.material.clone()],
        node_sets,
        element_sets,
        params: ModelParams {
            wtmass: 1.0,
            coupled_mass: None,
            solid_bubbles: false,
            ccx_solid_rules: false,
            ansys_solid_rules: false,
            ansys_shell181: false,
            k6rot: None,
            nastran_deck: false,
        },
        ..Default::default()
    }
}

type Mesh = (Vec<Node>, Vec<Element>, Vec<usize>, Vec<usize>);

fn node(id: usize, x: [f64; 3]) -> Node {
    Node {
        id: id as u64,
        x,
        displacement_frame: None,
    }
}

fn hex_mesh(spec: &BlockSpec) -> Mesh {
    let [nx, ny, nz] = spec.n;
    let h = [0, 1, 2].map(|d| spec.size[d] / spec.n[d] as f64);
    let idx = |i: usize, j: usize, k: usize| i + (nx + 1) * (j + (ny + 1) * k);
    let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
    let (mut x0, mut xl) = (Vec::new(), Vec::new());
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let p = nodes.len();
                nodes.push(node(
                    p + 1,
                    [i as f64 * h[0], j as f64 * h[1], k as f64 * h[2]],
                ));
                if i == 0 {
                    x0.push(p);
                }
                if i == nx {
                    xl.push(p);
                }
            }
        }
    }
    let mut elements = Vec::with_capacity(nx * ny * nz);
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let c = [
                    idx(i, j, k),
                    idx(i + 1, j, k),
                    idx(i + 1, j + 1, k),
                    idx(i, j + 1, k),
                    idx(i, j, k + 1),
                    idx(i + 1, j, k + 1),
                    idx(i + 1, j + 1, k + 1),
                    idx(i, j + 1, k + 1),
                ];
                elements.push(Element {
                    id: elements.len() as u64 + 1,
                    kind: ElementKind::Hex8,
                    nodes: c.to_vec(),
                    property: Some(0),
                    orientation: None,
                });
            }
        }
    }
    (nodes, elements, x0, xl)
}

type P = [i64; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// 6 × signed volume: det[p1 − p0, p2 − p0, p3 − p0].
fn det6(p: &[P; 4]) -> i64 {
    let (a, b, c) = (sub(p[1], p[0]), sub(p[2], p[0]), sub(p[3], p[0]));
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// Corner tetrahedra of a unit brick (corner coordinates 0/1).
fn brick_tets(element: BlockElement, parity: bool) -> Vec<[P; 4]> {
    match element {
        BlockElement::Tet10Six => {
            let e = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
            let perms = [
                [0, 1, 2],
                [0, 2, 1],
                [1, 0, 2],
                [1, 2, 0],
                [2, 0, 1],
                [2, 1, 0],
            ];
            perms
                .iter()
                .map(|p| {
                    let p1 = e[p[0]];
                    let p2 = [p1[0] + e[p[1]][0], p1[1] + e[p[1]][1], p1[2] + e[p[1]][2]];
                    [[0, 0, 0], p1, p2, [1, 1, 1]]
                })
                .collect()
        }
        _ => {
            let t: [[P; 4]; 5] = [
                [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                [[1, 1, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]],
                [[1, 0, 1], [1, 0, 0], [0, 0, 1], [1, 1, 1]],
                [[0, 1, 1], [0, 0, 1], [0, 1, 0], [1, 1, 1]],
                [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]],
            ];
            t.iter()
                .map(|tet| tet.map(|p| if parity { [1 - p[0], p[1], p[2]] } else { p }))
                .collect()
        }
    }
}

fn tet_mesh(spec: &BlockSpec) -> Mesh {
    let [nx, ny, nz] = spec.n;
    let (fx, fy, fz) = (2 * nx + 1, 2 * ny + 1, 2 * nz + 1);
    let lin = |p: P| p[0] as usize + fx * (p[1] as usize + fy * p[2] as usize);
    // Pass 1: connectivity on the half-step lattice.
    let mut conn: Vec<[usize; 10]> = Vec::new();
    let mut used = vec![false; fx * fy * fz];
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let parity = (i + j + k) % 2 == 1;
                for tet in brick_tets(spec.element, parity) {
                    let mut c = tet.map(|p| {
                        [
                            2 * (i as i64 + p[0]),
                            2 * (j as i64 + p[1]),
                            2 * (k as i64 + p[2]),
                        ]
                    });
                    if det6(&c) < 0 {
                        c.swap(1, 2);
                    }
                    let mid = |a: usize, b: usize| [0, 1, 2].map(|d| (c[a][d] + c[b][d]) / 2);
                    let all = [
                        c[0],
                        c[1],
                        c[2],
                        c[3],
                        mid(0, 1),
                        mid(1, 2),
                        mid(0, 2),
                        mid(0, 3),
                        mid(1, 3),
                        mid(2, 3),
                    ];
                    let l = all.map(lin);
                    for &q in &l {
                        used[q] = true;
                    }
                    conn.push(l);
                }
            }
        }
    }
    // Pass 2: number used lattice points in lattice order.
    let h = [0, 1, 2].map(|d| spec.size[d] / (2 * spec.n[d]) as f64);
    let mut number = vec![usize::MAX; used.len()];
    let mut nodes = Vec::new();
    let (mut x0, mut xl) = (Vec::new(), Vec::new());
    for (q, &u) in used.iter().enumerate() {
        if !u {
            continue;
        }
        let (i, j, k) = (q % fx, (q / fx) % fy, q / (fx * fy));
        let p = nodes.len();
        number[q] = p;
        nodes.push(node(
            p + 1,
            [i as f64 * h[0], j as f64 * h[1], k as f64 * h[2]],
        ));
        if i == 0 {
            x0.push(p);
        }
        if i == fx - 1 {
            xl.push(p);
        }
    }
    let elements = conn
        .iter()
        .enumerate()
        .map(|(e, l)| Element {
            id: e as u64 + 1,
            kind: ElementKind::Tet10,
            nodes: l.iter().map(|&q| number[q]).collect(),
            property: Some(0),
            orientation: None,
        })
        .collect();
    (nodes, elements, x0, xl)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn spec(n: [usize; 3], element: BlockElement) -> BlockSpec {
        BlockSpec {
            n,
            size: [0.5, 0.05, 0.04],
            element,
            material: Material::steel(),
        }
    }

    fn tet_vol(m: &Model, e: &Element) -> f64 {
        let p = |k: usize| m.nodes[e.nodes[k]].x;
        let (a, b, c) = (
            [0, 1, 2].map(|d| p(1)[d] - p(0)[d]),
            [0, 1, 2].map(|d| p(2)[d] - p(0)[d]),
            [0, 1, 2].map(|d| p(3)[d] - p(0)[d]),
        );
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))
            / 6.0
    }

    /// Conforming: each interior triangle shared by exactly 2 tets, boundary triangles
    /// (2 per boundary brick face) by one; volumes positive and summing to Lx·Ly·Lz; mid-side
    /// nodes at edge midpoints.
    fn check_tet(element: BlockElement, per_brick: usize) {
        let n = [3, 2, 2];
        let m = block(&spec(n, element));
        assert_eq!(m.elements.len(), per_brick * 12);
        let mut vol = 0.0;
        let mut faces: HashMap<[usize; 3], usize> = HashMap::new();
        for e in &m.elements {
            let v = tet_vol(&m, e);
            assert!(v > 0.0);
            vol += v;
            for (k, (a, b)) in [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]
                .iter()
                .enumerate()
            {
                let (pa, pb, pm) = (
                    m.nodes[e.nodes[*a]].x,
                    m.nodes[e.nodes[*b]].x,
                    m.nodes[e.nodes[4 + k]].x,
                );
                for d in 0..3 {
                    assert!((pm[d] - 0.5 * (pa[d] + pb[d])).abs() < 1e-15);
                }
            }
            for f in [[0, 1, 2], [0, 1, 3], [1, 2, 3], [0, 2, 3]] {
                let mut key = f.map(|k| e.nodes[k]);
                key.sort_unstable();
                *faces.entry(key).or_default() += 1;
            }
        }
        assert!((vol - 0.5 * 0.05 * 0.04).abs() < 1e-15);
        let boundary = faces.values().filter(|&&c| c == 1).count();
        assert!(faces.values().all(|&c| c == 1 || c == 2));
        assert_eq!(boundary, 4 * (n[0] * n[1] + n[1] * n[2] + n[0] * n[2]));
        // Every node is used; x = 0 face holds (2ny+1)(2nz+1) lattice points minus unused ones.
        let mut seen = vec![false; m.nodes.len()];
        m.elements
            .iter()
            .flat_map(|e| &e.nodes)
            .for_each(|&q| seen[q] = true);
        assert!(seen.iter().all(|&s| s));
        for &q in &m.node_sets["X0"] {
            assert_eq!(m.nodes[q].x[0], 0.0);
        }
        for &q in &m.node_sets["XL"] {
            assert!((m.nodes[q].x[0] - 0.5).abs() < 1e-15);
        }
    }

    #[test]
    fn tet10_six_per_brick_is_conforming() {
        check_tet(BlockElement::Tet10Six, 6);
        // Kuhn split uses every half-step lattice point.
        let m = block(&spec([3, 2, 2], BlockElement::Tet10Six));
        assert_eq!(m.nodes.len(), 7 * 5 * 5);
        assert_eq!(m.node_sets["X0"].len(), 5 * 5);
    }

    #[test]
    fn tet10_five_per_brick_is_conforming() {
        check_tet(BlockElement::Tet10Five, 5);
        // Brick centres are unused: 7·5·5 − 12 nodes.
        let m = block(&spec([3, 2, 2], BlockElement::Tet10Five));
        assert_eq!(m.nodes.len(), 7 * 5 * 5 - 12);
    }

    #[test]
    fn hex8_block_counts_volume_and_face_sets() {
        let m = block(&spec([40, 6, 6], BlockElement::Hex8));
        assert_eq!(m.nodes.len(), 41 * 7 * 7);
        assert_eq!(m.elements.len(), 40 * 36);
        assert_eq!(m.node_sets["X0"].len(), 49);
        assert_eq!(m.node_sets["XL"].len(), 49);
        // Positive volume: (x2−x1)×(x4−x1)·(x5−x1) > 0 for every brick.
        for e in &m.elements {
            let p = |k: usize| m.nodes[e.nodes[k]].x;
            let (a, b, c) = (
                [0, 1, 2].map(|d| p(1)[d] - p(0)[d]),
                [0, 1, 2].map(|d| p(3)[d] - p(0)[d]),
                [0, 1, 2].map(|d| p(4)[d] - p(0)[d]),
            );
            let v = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
            assert!((v - 0.5 / 40.0 * 0.05 / 6.0 * 0.04 / 6.0).abs() < 1e-18);
        }
    }
}
