//! Planar 2D frame element of Wang, Niu & Feng 2023 (§4, Table 1): 2 nodes, 3 dofs per node
//! (u, v, θ): linear axial bar plus Euler–Bernoulli bending (cubic Hermite), consistent or
//! lumped (HRZ) mass, rotated into the global x–y plane. Used for the paper's Tables 2–4 checks.

use faer::sparse::{SparseColMat, Triplet};

/// Section and material of a planar frame member.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameSection {
    /// Young's modulus E (Pa).
    pub e: f64,
    /// Cross-section area A (m²).
    pub area: f64,
    /// Second moment of area I (m⁴).
    pub inertia: f64,
    /// Density ρ (kg/m³).
    pub density: f64,
}

impl FrameSection {
    /// Table 1 of Wang, Niu & Feng 2023: steel beam, A = 3.167e-5 m², I = 7.981e-11 m⁴.
    pub fn paper_table1() -> Self {
        Self {
            e: 2.068e11,
            area: 3.167e-5,
            inertia: 7.981e-11,
            density: 7.840e3,
        }
    }
}

/// Length of the paper's beam (Table 1), m.
pub const PAPER_LENGTH: f64 = 0.4572;
/// Number of elements of the paper's beam (Table 1).
pub const PAPER_ELEMENTS: usize = 12;

/// Mass formulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameMass {
    /// Consistent mass (linear axial, cubic Hermite bending shape functions).
    Consistent,
    /// HRZ lumping: the consistent diagonal scaled to the element mass per direction
    /// (u, v: ρAL/2 per node; θ: ρAL³/78 per node).
    Lumped,
}

/// Element stiffness in local axes (u1, v1, θ1, u2, v2, θ2): EA/L bar + EI/L³ Hermite beam.
pub fn local_stiffness(s: &FrameSection, l: f64) -> [[f64; 6]; 6] {
    let a = s.e * s.area / l;
    let b = s.e * s.inertia / (l * l * l);
    let mut k = [[0.0; 6]; 6];
    k[0][0] = a;
    k[3][3] = a;
    k[0][3] = -a;
    k[3][0] = -a;
    let kb = [
        [12.0, 6.0 * l, -12.0, 6.0 * l],
        [6.0 * l, 4.0 * l * l, -6.0 * l, 2.0 * l * l],
        [-12.0, -6.0 * l, 12.0, -6.0 * l],
        [6.0 * l, 2.0 * l * l, -6.0 * l, 4.0 * l * l],
    ];
    let idx = [1, 2, 4, 5];
    for i in 0..4 {
        for j in 0..4 {
            k[idx[i]][idx[j]] = b * kb[i][j];
        }
    }
    k
}

/// Element mass in local axes; consistent: ρAL/6·[2 1; 1 2] axial, ρAL/420·[156 22L 54 −13L; …]
/// bending.
pub fn local_mass(s: &FrameSection, l: f64, kind: FrameMass) -> [[f64; 6]; 6] {
    let mtot = s.density * s.area * l;
    let mut m = [[0.0; 6]; 6];
    match kind {
        FrameMass::Consistent => {
            m[0][0] = mtot / 3.0;
            m[3][3] = mtot / 3.0;
            m[0][3] = mtot / 6.0;
            m[3][0] = mtot / 6.0;
            let mb = [
                [156.0, 22.0 * l, 54.0, -13.0 * l],
                [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
                [54.0, 13.0 * l, 156.0, -22.0 * l],
                [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
            ];
            let idx = [1, 2, 4, 5];
            for i in 0..4 {
                for j in 0..4 {
                    m[idx[i]][idx[j]] = mtot / 420.0 * mb[i][j];
                }
            }
        }
        FrameMass::Lumped => {
            for d in [0, 1, 3, 4] {
                m[d][d] = mtot / 2.0;
            }
            m[2][2] = mtot * l * l / 78.0;
            m[5][5] = mtot * l * l / 78.0;
        }
    }
    m
}

/// Tᵀ A T with T = diag(R, 1, R, 1), R = [c s; −s c] (local from global).
fn rotate(a: &[[f64; 6]; 6], c: f64, s: f64) -> [[f64; 6]; 6] {
    let mut t = [[0.0; 6]; 6];
    for o in [0, 3] {
        t[o][o] = c;
        t[o][o + 1] = s;
        t[o + 1][o] = -s;
        t[o + 1][o + 1] = c;
        t[o + 2][o + 2] = 1.0;
    }
    let mut out = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            let mut v = 0.0;
            for p in 0..6 {
                for q in 0..6 {
                    v += t[p][i] * a[p][q] * t[q][j];
                }
            }
            out[i][j] = v;
        }
    }
    out
}

/// Global element stiffness and mass of a member from (x1, y1) to (x2, y2).
pub fn element_matrices(
    s: &FrameSection,
    p1: [f64; 2],
    p2: [f64; 2],
    kind: FrameMass,
) -> ([[f64; 6]; 6], [[f64; 6]; 6]) {
    let (dx, dy) = (p2[0] - p1[0], p2[1] - p1[1]);
    let l = (dx * dx + dy * dy).sqrt();
    let (c, sn) = (dx / l, dy / l);
    (
        rotate(&local_stiffness(s, l), c, sn),
        rotate(&local_mass(s, l, kind), c, sn),
    )
}

/// Assembles a frame of members `elements` (node index pairs) over `nodes` (x, y); dof 3·node + d
/// with d = 0 (u), 1 (v), 2 (θ). Returns full symmetric (K, M).
pub fn assemble(
    s: &FrameSection,
    nodes: &[[f64; 2]],
    elements: &[[usize; 2]],
    kind: FrameMass,
) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    let n = 3 * nodes.len();
    let (mut kt, mut mt) = (Vec::new(), Vec::new());
    for e in elements {
        let (ke, me) = element_matrices(s, nodes[e[0]], nodes[e[1]], kind);
        let dofs = [
            3 * e[0],
            3 * e[0] + 1,
            3 * e[0] + 2,
            3 * e[1],
            3 * e[1] + 1,
            3 * e[1] + 2,
        ];
        for i in 0..6 {
            for j in 0..6 {
                kt.push(Triplet::new(dofs[i], dofs[j], ke[i][j]));
                if me[i][j] != 0.0 {
                    mt.push(Triplet::new(dofs[i], dofs[j], me[i][j]));
                }
            }
        }
    }
    // Cannot fail: all dof indices are < 3·nodes.len() by construction (element nodes index
    // `nodes`, which panics earlier on a bad index).
    let k = SparseColMat::try_new_from_triplets(n, n, &kt).expect("dofs in range");
    let m = SparseColMat::try_new_from_triplets(n, n, &mt).expect("dofs in range");
    (k, m)
}

/// Straight beam along x of `length` split into `elements` equal members (nodes 0..=elements).
pub fn straight_beam(
    s: &FrameSection,
    length: f64,
    elements: usize,
    kind: FrameMass,
) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    let nodes: Vec<[f64; 2]> = (0..=elements)
        .map(|i| [length * i as f64 / elements as f64, 0.0])
        .collect();
    let els: Vec<[usize; 2]> = (0..elements).map(|i| [i, i + 1]).collect();
    assemble(s, &nodes, &els, kind)
}
