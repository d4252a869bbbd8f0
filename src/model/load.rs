//! Scene loads: the named load cases a multibody scene applies to the body (gravity, point
//! forces and moments, pressures). Importers fill them from the deck (Nastran FORCE, MOMENT,
//! GRAV, PLOAD4, LOAD; see `import::nastran::loads`), the CLI adds its own (`--gravity`,
//! `--load`). Plain data: `fe::loads` turns each into a load vector over the model's dofs.

use super::{ElementKind, ImportWarning, NodeIndex};

/// One named load case.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    /// The name it is known by: `LOAD_<sid>` for a Nastran load set, the CLI name, `GRAVITY`.
    pub name: String,
    /// Where it came from, e.g. `FORCE (deck.bdf:12), GRAV (deck.bdf:14)` or `--gravity`.
    pub source: String,
    /// Selected by the deck's case control (`LOAD = n`) or given on the command line; the
    /// unselected load sets of a deck stay available by name.
    pub selected: bool,
    /// The parts, summed.
    pub parts: Vec<LoadPart>,
    /// Why the load cannot be used (a card of it the tool does not support, e.g. a non-uniform
    /// pressure), naming file, line and card; `None` = usable. The importer keeps such a load
    /// by name with a warning instead of failing the whole deck.
    pub problem: Option<String>,
}

/// One contribution to a load case (basic-frame components).
#[derive(Debug, Clone, PartialEq)]
pub enum LoadPart {
    /// Force `[fx fy fz]` and moment `[mx my mz]` at a node.
    Nodal {
        /// The node.
        node: NodeIndex,
        /// `[fx fy fz mx my mz]`, basic frame.
        values: [f64; 6],
    },
    /// A uniform acceleration field of the whole body (gravity): the load is M·g with the
    /// build's mass matrix.
    Gravity {
        /// Acceleration vector, basic frame (e.g. `[0, 0, -9.81]`).
        accel: [f64; 3],
    },
    /// A uniform traction normal to an element face: `traction` along the face's right-hand
    /// normal (node order corners first, then mid-side nodes: 3, 4, 6 or 8 nodes). A pressure
    /// p pushing into a solid is `traction = −p` on its outward-ordered face.
    Surface {
        /// Face nodes, corners first in right-hand order, then mid-side nodes.
        nodes: Vec<NodeIndex>,
        /// Force per area along the right-hand normal.
        traction: f64,
        /// The element the face belongs to (external id, for messages).
        element: u64,
    },
    /// The centrifugal field of a rotation about an axis, b = Ω² (I − n nᵀ)(x − p) per unit
    /// mass (CalculiX `*DLOAD … CENTRIF`): the load is M·b with the build's mass matrix.
    Centrifugal {
        /// Ω² (rad² per unit time², as CENTRIF gives it).
        omega2: f64,
        /// A point p of the axis, basic frame.
        point: [f64; 3],
        /// The axis direction n (any length), basic frame.
        axis: [f64; 3],
    },
}

impl Load {
    /// A copy with every part scaled by `s` (Nastran LOAD combination factors).
    pub fn scaled(parts: &[LoadPart], s: f64) -> Vec<LoadPart> {
        parts
            .iter()
            .map(|p| match p {
                LoadPart::Nodal { node, values } => LoadPart::Nodal {
                    node: *node,
                    values: values.map(|v| v * s),
                },
                LoadPart::Gravity { accel } => LoadPart::Gravity {
                    accel: accel.map(|v| v * s),
                },
                LoadPart::Surface {
                    nodes,
                    traction,
                    element,
                } => LoadPart::Surface {
                    nodes: nodes.clone(),
                    traction: traction * s,
                    element: *element,
                },
                LoadPart::Centrifugal {
                    omega2,
                    point,
                    axis,
                } => LoadPart::Centrifugal {
                    omega2: omega2 * s,
                    point: *point,
                    axis: *axis,
                },
            })
            .collect()
    }
}

/// Corner faces (0-based local corners) as in `faces.rs`; [`face_nodes`] orders them outward.
pub(crate) const TET_FACES: &[&[usize]] = &[&[0, 1, 2], &[0, 3, 1], &[1, 3, 2], &[2, 3, 0]];
pub(crate) const PRISM_FACES: &[&[usize]] = &[
    &[0, 1, 2],
    &[3, 5, 4],
    &[0, 3, 4, 1],
    &[1, 4, 5, 2],
    &[2, 5, 3, 0],
];
pub(crate) const HEX_FACES: &[&[usize]] = &[
    &[0, 1, 2, 3],
    &[4, 7, 6, 5],
    &[0, 4, 5, 1],
    &[1, 5, 6, 2],
    &[2, 6, 7, 3],
    &[3, 7, 4, 0],
];
pub(crate) const PYRAM_FACES: &[&[usize]] = &[
    &[0, 1, 2, 3],
    &[0, 4, 1],
    &[1, 4, 2],
    &[2, 4, 3],
    &[3, 4, 0],
];
/// Mid-side node edges (0-based corners) of the quadratic solids, in node order after the corners.
pub(crate) const TET10_EDGES: &[(usize, usize)] = &[(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)];
pub(crate) const PRISM15_EDGES: &[(usize, usize)] = &[
    (0, 1),
    (1, 2),
    (2, 0),
    (3, 4),
    (4, 5),
    (5, 3),
    (0, 3),
    (1, 4),
    (2, 5),
];
pub(crate) const PYRAM13_EDGES: &[(usize, usize)] = &[
    (0, 1),
    (1, 2),
    (2, 3),
    (3, 0),
    (0, 4),
    (1, 4),
    (2, 4),
    (3, 4),
];
pub(crate) const HEX20_EDGES: &[(usize, usize)] = &[
    (0, 1),
    (1, 2),
    (2, 3),
    (3, 0),
    (4, 5),
    (5, 6),
    (6, 7),
    (7, 4),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];

/// Corner faces of a solid kind (local 0-based corners).
pub type FaceTable = &'static [&'static [usize]];
/// Mid-side node edges of a quadratic solid kind (local corner pairs, in node order).
pub type EdgeTable = &'static [(usize, usize)];

/// The corner faces and the mid-side edge list (empty for linear kinds) of a
/// solid element kind; `None` for other kinds.
pub fn solid_faces(kind: ElementKind) -> Option<(FaceTable, EdgeTable)> {
    Some(match kind {
        ElementKind::Tet4 => (TET_FACES, &[]),
        ElementKind::Tet10 => (TET_FACES, TET10_EDGES),
        ElementKind::Prism6 => (PRISM_FACES, &[]),
        ElementKind::Prism15 => (PRISM_FACES, PRISM15_EDGES),
        ElementKind::Pyram5 => (PYRAM_FACES, &[]),
        ElementKind::Pyram13 | ElementKind::Pyram13Ansys => (PYRAM_FACES, PYRAM13_EDGES),
        ElementKind::Hex8 | ElementKind::Hex8R | ElementKind::Hex8Bbar => (HEX_FACES, &[]),
        ElementKind::Hex20 | ElementKind::Hex20R => (HEX_FACES, HEX20_EDGES),
        ElementKind::Beam2
        | ElementKind::Bar2
        | ElementKind::Beam2Linear
        | ElementKind::Beam3Quadratic
        | ElementKind::Beam4Cubic
        | ElementKind::Rod2
        | ElementKind::Beam3
        | ElementKind::Tri3
        | ElementKind::Quad4
        | ElementKind::Tri6
        | ElementKind::Quad8 => return None,
    })
}

/// The model nodes of one face of an element (`nodes`: its connectivity): the corners of
/// `face` ordered with the right-hand normal out of the element, then for a quadratic element
/// the mid-side node of each face edge in that order.
pub fn face_nodes(
    nodes: &[NodeIndex],
    face: &[usize],
    edges: &[(usize, usize)],
) -> Option<Vec<NodeIndex>> {
    // The tables order a face with its right-hand normal into a positive-Jacobian element
    // (e.g. hex 1-2-3-4 counter-clockwise seen from node 5's side): reversed, it points out.
    let face: Vec<usize> = std::iter::once(face[0])
        .chain(face[1..].iter().rev().copied())
        .collect();
    let mut out: Vec<NodeIndex> = face.iter().map(|&c| nodes[c]).collect();
    if !edges.is_empty() {
        let corners = face.len();
        for i in 0..corners {
            let (a, b) = (face[i], face[(i + 1) % corners]);
            let e = edges
                .iter()
                .position(|&(p, q)| (p, q) == (a, b) || (q, p) == (a, b))?;
            out.push(*nodes.get(nodes.len() - edges.len() + e)?);
        }
    }
    Some(out)
}

/// One import warning per load that cannot be used (its `problem`), for the deck's `file`.
pub fn problem_warnings(loads: &[Load], file: &str) -> Vec<ImportWarning> {
    loads
        .iter()
        .filter_map(|l| {
            l.problem.as_ref().map(|p| ImportWarning {
                file: file.to_owned(),
                message: format!(
                    "load {} ({}) is not available as a scene load: {p}",
                    l.name, l.source
                ),
            })
        })
        .collect()
}
