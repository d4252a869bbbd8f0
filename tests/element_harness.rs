//! One harness over every element formulation (issue 48): each kind is read from a one-element
//! deck of the importer that makes it (Nastran for the Nastran cards, CalculiX for its own
//! variants C3D4/C3D10/C3D8/C3D8I/C3D8R/C3D20/C3D20R/C3D6/C3D15, an ANSYS archive for SOLID185's
//! B-bar brick), and its matrices are checked
//! against what any sound element must satisfy:
//!
//! * K symmetric; positive semi-definite with exactly the null space of its rigid motions
//!   (6, a rod 10: it carries only axial force and torque; one C3D20R 12, its six
//!   non-communicable spurious modes;
//!   CalculiX's two-point C3D6 7);
//! * the six rigid motions store no strain energy (translations, and rotations θ × x with the
//!   rotational dofs θ on 6-dof nodes);
//! * the translational mass of a rigid motion is ρV (solids), ρtA (shells), ρAL (beams, rods),
//!   lumped and consistent;
//! * the patch test: a linear displacement field u = G x on an affine element stores the energy
//!   V εᵀ D ε of its constant strain (solids; the membrane of shells, t A εᵀ D_ps ε);
//! * invariance: the spectra of K and M do not change when the element is turned in space.

use faer::Mat;
use flexbody::fe::assembly::{element_matrices, ElementMatrices};
use flexbody::fe::{AssemblySpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::{ElementKind, Model};

type X = [f64; 3];

const E: f64 = 2.1e11;
const NU: f64 = 0.3;
const RHO: f64 = 7850.0;
const SHELL_T: f64 = 0.02;
const BAR_A: f64 = 4.0e-4;

/// Which importer writes the deck.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Deck {
    /// A Nastran element card (CHEXA, CPENTA, …).
    Nastran(&'static str),
    /// A CalculiX element type (C3D8I, …).
    Ccx(&'static str),
    /// An ANSYS element type (`ET,1,185`) with its KEYOPT(2).
    Ansys(&'static str, u32),
}

/// One element case of the harness.
struct Case {
    deck: Deck,
    kind: ElementKind,
    /// Reference node positions, model (Abaqus) order.
    nodes: Vec<X>,
    /// Zero-energy modes of K (the rigid motions it must carry, no more).
    null_space: usize,
    /// Checked on the bent (warped, curved) element; else on an affine one only: ccx's C3D8R
    /// hourglass vectors are orthogonal to linear fields on parallelepipeds only, so a rigid
    /// rotation of a warped C3D8R stores energy (measured 7.6e-7 of λmax|r|², and its K
    /// turned in space changes by 1.7e-6 of λmax), as in ccx 2.20, whose digits it matches.
    warped: bool,
}

fn lerp(a: X, b: X) -> X {
    std::array::from_fn(|i| 0.5 * (a[i] + b[i]))
}

fn with_edges(corners: &[X], edges: &[(usize, usize)]) -> Vec<X> {
    let mut out = corners.to_vec();
    out.extend(edges.iter().map(|&(a, b)| lerp(corners[a], corners[b])));
    out
}

const HEX: [X; 8] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [0.0, 1.0, 1.0],
];
const HEX20_EDGES: [(usize, usize); 12] = [
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
const TET: [X; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];
const TET10_EDGES: [(usize, usize); 6] = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)];
const WEDGE: [X; 6] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
];
/// The 15-node wedge's mid-side nodes in CalculiX order: bottom, top, then vertical edges.
pub const WEDGE15_EDGES: [(usize, usize); 9] = [
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
const PYRAMID: [X; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.5, 0.5, 1.0],
];
const PYRAM13_EDGES: [(usize, usize); 8] = [
    (0, 1),
    (1, 2),
    (2, 3),
    (3, 0),
    (0, 4),
    (1, 4),
    (2, 4),
    (3, 4),
];
const QUAD: [X; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];
const TRI: [X; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

fn cases() -> Vec<Case> {
    use Deck::{Ansys, Ccx, Nastran};
    use ElementKind::*;
    let case = |deck, kind, nodes: Vec<X>, null_space| Case {
        deck,
        kind,
        nodes,
        null_space,
        warped: deck != Ccx("C3D8R"),
    };
    let hex20 = with_edges(&HEX, &HEX20_EDGES);
    let tet10 = with_edges(&TET, &TET10_EDGES);
    let wedge15 = with_edges(&WEDGE, &WEDGE15_EDGES);
    vec![
        case(Nastran("CTETRA"), Tet4, TET.to_vec(), 6),
        case(Nastran("CTETRA"), Tet10, tet10.clone(), 6),
        case(Nastran("CHEXA"), Hex8, HEX.to_vec(), 6),
        case(Nastran("CHEXA"), Hex20, hex20.clone(), 6),
        case(Nastran("CPENTA"), Prism6, WEDGE.to_vec(), 6),
        case(Nastran("CPENTA"), Prism15, wedge15.clone(), 6),
        case(Nastran("CPYRAM"), Pyram5, PYRAMID.to_vec(), 6),
        case(
            Nastran("CPYRAM"),
            Pyram13,
            with_edges(&PYRAMID, &PYRAM13_EDGES),
            6,
        ),
        case(Nastran("CBAR"), Bar2, vec![[0.0; 3], [1.0, 0.0, 0.0]], 6),
        case(Nastran("CBEAM"), Beam2, vec![[0.0; 3], [1.0, 0.0, 0.0]], 6),
        case(Nastran("CROD"), Rod2, vec![[0.0; 3], [1.0, 0.0, 0.0]], 10),
        case(Nastran("CQUAD4"), Quad4, QUAD.to_vec(), 6),
        case(Nastran("CTRIA3"), Tri3, TRI.to_vec(), 6),
        case(
            Nastran("CQUAD8"),
            Quad8,
            with_edges(&QUAD, &HEX20_EDGES[..4]),
            6,
        ),
        case(
            Nastran("CTRIA6"),
            Tri6,
            with_edges(&TRI, &TET10_EDGES[..3]),
            6,
        ),
        case(Ccx("C3D4"), Tet4, TET.to_vec(), 6),
        case(Ccx("C3D10"), Tet10, tet10, 6),
        case(Ccx("C3D8"), Hex8, HEX.to_vec(), 6),
        case(Ccx("C3D8I"), Hex8, HEX.to_vec(), 6),
        case(Ccx("C3D8R"), Hex8R, HEX.to_vec(), 6),
        case(Ccx("C3D20"), Hex20, hex20.clone(), 6),
        // one 20-node brick on 2×2×2 points has six spurious zero-energy modes besides the
        // rigid ones (non-communicable: a mesh of two or more carries none; Bathe, *Finite
        // Element Procedures* (1996) §5.5.6)
        case(Ccx("C3D20R"), Hex20R, hex20, 12),
        // CalculiX integrates C3D6 on two points (centroid × 2 Gauss): a lone element has one
        // zero-energy mode besides the rigid ones (measured; so has ccx 2.20's, whose matrices
        // flexbody's equal)
        case(Ccx("C3D6"), Prism6, WEDGE.to_vec(), 7),
        case(Ccx("C3D15"), Prism15, wedge15, 6),
        case(Ansys("185", 0), Hex8Bbar, HEX.to_vec(), 6),
        // SOLID186 written as ANSYS's pyramid: one element on 2×2×2 points has one zero-energy
        // mode besides the rigid ones on an affine pyramid (measured; not communicable in a
        // mesh); the bent element stiffens it a little (7.5e4 against λmax 2.0e9, measured), so
        // it is checked on the affine one
        Case {
            warped: false,
            ..case(
                Ansys("186", 0),
                Pyram13Ansys,
                with_edges(&PYRAMID, &PYRAM13_EDGES),
                7,
            )
        },
        case(
            Ansys("188", 0),
            Beam2Linear,
            vec![[0.0; 3], [1.0, 0.0, 0.0]],
            6,
        ),
        // straight, its mid node at the middle (a bent one is refused as curved)
        Case {
            warped: false,
            ..case(
                Ansys("189", 0),
                Beam3Quadratic,
                vec![[0.0; 3], [1.0, 0.0, 0.0], [0.5, 0.0, 0.0]],
                6,
            )
        },
        // BEAM188 KEYOPT(3)=3: the archive holds I and J, the importer makes the internal
        // nodes at 1/3 and 2/3 of IJ (the last two here); straight, as they are made
        Case {
            warped: false,
            ..case(
                Ansys("188", 0),
                Beam4Cubic,
                vec![
                    [0.0; 3],
                    [1.0, 0.0, 0.0],
                    [1.0 / 3.0, 0.0, 0.0],
                    [2.0 / 3.0, 0.0, 0.0],
                ],
                6,
            )
        },
    ]
}

/// Where the reference node `p` goes: the affine map A p + b, plus (`bent`) a smooth
/// quadratic bend that curves the quadratic elements' edges and warps the linear ones'
/// (in the plane for shells, whose elements must stay flat for the membrane patch).
fn place(p: X, bent: bool, flat: bool) -> X {
    let q = if bent {
        let z = if flat { 0.0 } else { 0.05 * p[0] * p[1] };
        [
            p[0] + 0.04 * p[1] * p[2] + 0.06 * p[0] * p[1],
            p[1] - 0.05 * p[0] * p[1],
            p[2] + z,
        ]
    } else {
        p
    };
    let a = [[0.9, 0.1, 0.05], [0.05, 1.1, -0.1], [0.02, 0.08, 0.8]];
    let a = if flat {
        [[0.9, 0.1, 0.0], [0.05, 1.1, 0.0], [0.0, 0.0, 1.0]]
    } else {
        a
    };
    std::array::from_fn(|i| 0.3 + (0..3).map(|k| a[i][k] * q[k]).sum::<f64>())
}

/// Rotation by `angle` about the unit axis `n` (Rodrigues).
fn rotation(n: X, angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let cross = [[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]][i][j];
            c * f64::from(u8::from(i == j)) + s * cross + (1.0 - c) * n[i] * n[j]
        })
    })
}

fn turn(r: &[[f64; 3]; 3], x: X) -> X {
    std::array::from_fn(|i| (0..3).map(|k| r[i][k] * x[k]).sum())
}

/// Nastran free-field fields after `NAME,EID`: 7 on the first line (fields 3–9), then
/// continuation lines of 8.
fn fields(values: &[String]) -> String {
    let mut out = String::new();
    for (i, v) in values.iter().enumerate() {
        if i >= 7 && (i - 7) % 8 == 0 {
            out.push_str(",+\n+");
        }
        out.push(',');
        out.push_str(v);
    }
    out.push('\n');
    out
}

/// The deck of one element of `case` through the points `x` (model order), and its file name.
fn deck(case: &Case, x: &[X], orientation: X) -> (String, String) {
    let grids: String = (x.iter().enumerate())
        .map(|(i, p)| {
            format!(
                "GRID,{},,{:.17e},{:.17e},{:.17e}\n",
                i + 1,
                p[0],
                p[1],
                p[2]
            )
        })
        .collect();
    let mut ids: Vec<usize> = (1..=x.len()).collect();
    match case.deck {
        Deck::Nastran(card) => {
            // Nastran orders a CHEXA20's and a CPENTA15's vertical edges before the top ones
            if case.kind == ElementKind::Hex20 {
                ids = [&ids[..12], &ids[16..20], &ids[12..16]].concat();
            }
            if case.kind == ElementKind::Prism15 {
                ids = [&ids[..9], &ids[12..15], &ids[9..12]].concat();
            }
            let (prop, pid) = match card {
                "CBAR" => (format!("PBAR,3,1,{BAR_A},2.e-8,3.e-8,4.e-8\n"), 3),
                "CBEAM" => (format!("PBEAM,4,1,{BAR_A},2.e-8,3.e-8,,4.e-8\n"), 4),
                "CROD" => (format!("PROD,5,1,{BAR_A},4.e-8\n"), 5),
                "CQUAD4" | "CTRIA3" | "CQUAD8" | "CTRIA6" => {
                    (format!("PSHELL,2,1,{SHELL_T},1,,1\n"), 2)
                }
                _ => ("PSOLID,1,1\n".into(), 1),
            };
            let mut values: Vec<String> = std::iter::once(pid.to_string())
                .chain(ids.iter().map(|i| i.to_string()))
                .collect();
            if matches!(card, "CBAR" | "CBEAM") {
                values.extend(orientation.iter().map(|v| format!("{v:.17e}")));
            }
            let text = format!(
                "BEGIN BULK\nMAT1,1,{E},,{NU},{RHO}\n{prop}{grids}{card},1{}ENDDATA\n",
                fields(&values)
            );
            (text, "element.bdf".into())
        }
        Deck::Ccx(ty) => {
            let nodes: String = (x.iter().enumerate())
                .map(|(i, p)| format!("{}, {:.17e}, {:.17e}, {:.17e}\n", i + 1, p[0], p[1], p[2]))
                .collect();
            let conn: Vec<String> = ids.iter().map(|i| i.to_string()).collect();
            let conn = if conn.len() > 15 {
                format!("{},\n{}", conn[..15].join(", "), conn[15..].join(", "))
            } else {
                conn.join(", ")
            };
            let text = format!(
                "*NODE\n{nodes}*ELEMENT, TYPE={ty}, ELSET=E\n1, {conn}\n*MATERIAL, NAME=M\n\
                 *ELASTIC\n{E}, {NU}\n*DENSITY\n{RHO}\n*SOLID SECTION, ELSET=E, MATERIAL=M\n"
            );
            (text, "element.inp".into())
        }
        Deck::Ansys(ty, keyopt2) => {
            // BEAM188 KEYOPT(3)=3: I and J only (the internal nodes are the importer's)
            let cubic = case.kind == ElementKind::Beam4Cubic;
            let x = if cubic { &x[..2] } else { x };
            ids.truncate(x.len());
            let keyopt3 = if cubic {
                "KEYOP,        1, 3,        3\n"
            } else {
                ""
            };
            // BEAM188: an ASEC section and the orientation node K = I + the orientation
            let beam = ty == "188" || ty == "189";
            let k_node = beam.then(|| std::array::from_fn(|c| x[0][c] + orientation[c]));
            let x: Vec<X> = x.iter().copied().chain(k_node).collect();
            ids.extend(beam.then_some(x.len()));
            let section = if beam {
                format!("SECTYPE,1,BEAM,ASEC\nSECDATA,{BAR_A},3.e-8,0,2.e-8,0,4.e-8\n")
            } else {
                String::new()
            };
            // SOLID186 as a pyramid: the brick's top corners and mid-sides all the apex (M…P,
            // U…X), written over its 20 positions
            if case.kind == ElementKind::Pyram13Ansys {
                ids = [&ids[..5], &[5; 3], &ids[5..9], &[5; 4], &ids[9..13]].concat();
            }
            let n = x.len();
            let nodes: String = (x.iter().enumerate())
                .map(|(i, p)| {
                    format!(
                        "{:>9}{:>9}{:>9}{:>21.13E}{:>21.13E}{:>21.13E}\n",
                        i + 1,
                        0,
                        0,
                        p[0],
                        p[1],
                        p[2]
                    )
                })
                .collect();
            let head = [1, 1, 1, 1, 0, 0, 0, 0, ids.len(), 0, 1];
            let values: Vec<usize> = head.iter().chain(&ids).copied().collect();
            let record: Vec<String> = (values.chunks(19))
                .map(|line| line.iter().map(|v| format!("{v:>9}")).collect())
                .collect();
            let record = record.join("\n");
            let text = format!(
                "ET,        1,{ty}\nKEYOP,        1, 2,{keyopt2:>9}\n{keyopt3}{section}\
                 NBLOCK,6,SOLID,{n:>10},{n:>10}\n(3i9,6e21.13e3)\n{nodes}N,R5.3,LOC,       -1,\n\
                 EBLOCK,19,SOLID,         1,         1\n(19i9)\n{record}\n       -1\n\
                 MPTEMP,R5.0, 1, 1,  0.00000000    ,\n\
                 MPDATA,R5.0, 1,EX  ,       1, 1, {E:e},\n\
                 MPDATA,R5.0, 1,NUXY,       1, 1, {NU:e},\n\
                 MPDATA,R5.0, 1,DENS,       1, 1, {RHO:e},\n"
            );
            (text, "element.cdb".into())
        }
    }
}

/// The model of `case` through the points `x`.
fn model(case: &Case, x: &[X], orientation: X, tag: &str) -> Model {
    let (text, name) = deck(case, x, orientation);
    let dir = crate::common::scratch(&format!("harness-{tag}"));
    let path = dir.join(name);
    std::fs::write(&path, &text).unwrap();
    let m = read_model(&path, &ImportOptions::default())
        .unwrap_or_else(|e| panic!("{tag}: {e}\n{text}"));
    assert_eq!(m.elements.len(), 1, "{tag}");
    assert_eq!(m.elements[0].kind, case.kind, "{tag}");
    m
}

fn matrices(m: &Model, mass: MassKind, tag: &str) -> ElementMatrices {
    let spec = AssemblySpec {
        mass,
        ..AssemblySpec::default()
    };
    element_matrices(m, 0, &spec).unwrap_or_else(|e| panic!("{tag}: {e}"))
}

fn square(a: &[f64]) -> Mat<f64> {
    let n = a.len().isqrt();
    Mat::from_fn(n, n, |i, j| a[i * n + j])
}

fn eigenvalues(a: &[f64]) -> Vec<f64> {
    let mut ev = square(a)
        .self_adjoint_eigenvalues(faer::Side::Lower)
        .expect("eigenvalues");
    ev.sort_by(f64::total_cmp);
    ev
}

/// xᵀ A y over the leading rows/columns of A (x, y shorter than A: the interior dofs zero).
fn form(a: &[f64], x: &[f64], y: &[f64]) -> f64 {
    let n = a.len().isqrt();
    (0..x.len())
        .map(|i| x[i] * (0..y.len()).map(|j| a[i * n + j] * y[j]).sum::<f64>())
        .sum()
}

/// The nodal vector of the rigid motion `mode` (0–2 translations, 3–5 rotations about the
/// axes through the origin) at the points `x` with `dpn` dofs per node.
fn rigid(mode: usize, x: &[X], dpn: usize) -> Vec<f64> {
    let mut v = vec![0.0; x.len() * dpn];
    for (a, p) in x.iter().enumerate() {
        if mode < 3 {
            v[a * dpn + mode] = 1.0;
        } else {
            let w: X = std::array::from_fn(|i| f64::from(u8::from(i == mode - 3)));
            let u = [
                w[1] * p[2] - w[2] * p[1],
                w[2] * p[0] - w[0] * p[2],
                w[0] * p[1] - w[1] * p[0],
            ];
            v[a * dpn..a * dpn + 3].copy_from_slice(&u);
            if dpn == 6 {
                v[a * dpn + 3..a * dpn + 6].copy_from_slice(&w);
            }
        }
    }
    v
}

/// The volume (solids), area × thickness (shells) or length × area (beams) of the element:
/// what the rigid translation's mass is, over ρ.
fn measure(case: &Case, x: &[X]) -> f64 {
    let sub = |a: X, b: X| -> X { std::array::from_fn(|i| a[i] - b[i]) };
    let cross = |a: X, b: X| -> X {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: X, b: X| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let tet = |a: X, b: X, c: X, d: X| dot(sub(b, a), cross(sub(c, a), sub(d, a))) / 6.0;
    let tri = |a: X, b: X, c: X| dot(cross(sub(b, a), sub(c, a)), [0.0, 0.0, 1.0]) / 2.0;
    use ElementKind::*;
    match case.kind {
        Tet4 | Tet10 => tet(x[0], x[1], x[2], x[3]),
        // affine images of the unit cube, wedge and pyramid: |det A| × the reference volume
        Hex8 | Hex8R | Hex8Bbar | Hex20 | Hex20R => 6.0 * tet(x[0], x[1], x[3], x[4]),
        Prism6 | Prism15 => 3.0 * tet(x[0], x[1], x[2], x[3]),
        Pyram5 | Pyram13 | Pyram13Ansys => 2.0 * tet(x[0], x[1], x[3], x[4]),
        Bar2 | Beam2 | Beam2Linear | Beam3Quadratic | Beam4Cubic | Rod2 => {
            BAR_A * dot(sub(x[1], x[0]), sub(x[1], x[0])).sqrt()
        }
        Tri3 | Tri6 => SHELL_T * tri(x[0], x[1], x[2]),
        Quad4 | Quad8 => SHELL_T * 2.0 * tri(x[0], x[1], x[3]),
        Beam3 => unreachable!("not in the harness"),
    }
}

fn name(case: &Case) -> String {
    match case.deck {
        Deck::Nastran(c) => format!("{c}-{:?}", case.kind),
        Deck::Ccx(t) => t.to_string(),
        Deck::Ansys(t, k) => format!("ANSYS{t}-KEYOPT2={k}-{:?}", case.kind),
    }
}

fn is_shell(kind: ElementKind) -> bool {
    use ElementKind::*;
    matches!(kind, Tri3 | Quad4 | Tri6 | Quad8)
}

/// Symmetry, semi-definiteness, the null space and zero rigid-motion energy, on the bent
/// element; the rigid translation's mass on the affine one.
#[test]
fn every_element_is_symmetric_psd_with_the_rigid_null_space_and_rho_v_mass() {
    for case in cases() {
        let tag = name(&case);
        let shell = is_shell(case.kind);
        let bent: Vec<X> = (case.nodes.iter())
            .map(|&p| place(p, case.warped, shell))
            .collect();
        let m = model(&case, &bent, [0.0, 1.0, 0.2], &tag);
        for mass in [MassKind::Consistent, MassKind::Lumped] {
            let em = matrices(&m, mass, &tag);
            let n = em.size();
            let top = em.k.iter().fold(0.0f64, |t, v| t.max(v.abs()));
            let asym = (0..n * n)
                .map(|ij| (em.k[ij] - em.k[(ij % n) * n + ij / n]).abs())
                .fold(0.0, f64::max);
            // measured ≤ 1.6e-16 of the largest term (CTRIA3)
            assert!(asym <= 1.5e-15 * top, "{tag}: K asymmetric by {asym:e}");
            let ev = eigenvalues(&em.k);
            let lmax = ev[n - 1];
            // measured: the lowest eigenvalue ≥ −1.9e-16 λmax (C3D8)
            assert!(
                ev[0] >= -2e-15 * lmax,
                "{tag}: λmin {:e} of {lmax:e}",
                ev[0]
            );
            let null = ev.iter().filter(|&&l| l < 1e-9 * lmax).count();
            assert_eq!(
                null,
                case.null_space,
                "{tag}: zero-energy modes {:?}",
                &ev[..8]
            );
            for mode in 0..6 {
                let r = rigid(mode, &bent, em.dpn);
                let rr: f64 = r.iter().map(|v| v * v).sum();
                let energy = form(&em.k, &r, &r);
                // measured ≤ 7.7e-17 λmax |r|² (CQUAD8)
                assert!(
                    energy.abs() <= 1e-15 * lmax * rr,
                    "{tag}: rigid {mode}: {energy:e}"
                );
            }
        }
        let affine: Vec<X> = case.nodes.iter().map(|&p| place(p, false, shell)).collect();
        let m = model(&case, &affine, [0.0, 1.0, 0.2], &format!("{tag}-affine"));
        for mass in [MassKind::Consistent, MassKind::Lumped] {
            let em = matrices(&m, mass, &tag);
            let want = RHO * measure(&case, &affine);
            for d in 0..3 {
                let r = rigid(d, &affine, em.dpn);
                let got = form(&em.m, &r, &r);
                // measured ≤ 1.1e-15 relative (CHEXA20 lumped): every rule integrates the
                // affine element's volume
                assert!(
                    (got - want).abs() <= 1e-14 * want,
                    "{tag} {mass:?}: {got} vs ρV {want}"
                );
            }
        }
    }
}

/// Isotropic D in Voigt form (xx yy zz xy yz zx, engineering shears).
fn hooke() -> [[f64; 6]; 6] {
    let l = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let mu = E / (2.0 * (1.0 + NU));
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let normal = i < 3 && j < 3;
            let diag = if i == j {
                if i < 3 {
                    2.0 * mu
                } else {
                    mu
                }
            } else {
                0.0
            };
            diag + if normal { l } else { 0.0 }
        })
    })
}

/// The patch test on one affine element: u = G x stores V εᵀ D ε (solids) or t A εᵀ D_ps ε (the
/// shells' membrane, a symmetric in-plane G so the drilling rotation is zero).
#[test]
fn every_element_passes_the_constant_strain_patch_test() {
    for case in cases() {
        use ElementKind::*;
        let tag = name(&case);
        let shell = is_shell(case.kind);
        if matches!(
            case.kind,
            Bar2 | Beam2 | Beam2Linear | Beam3Quadratic | Beam4Cubic | Rod2
        ) {
            continue; // line elements: no strain field to patch
        }
        let x: Vec<X> = case.nodes.iter().map(|&p| place(p, false, shell)).collect();
        let m = model(&case, &x, [0.0, 1.0, 0.0], &format!("{tag}-patch"));
        let em = matrices(&m, MassKind::Consistent, &tag);
        let g = if shell {
            [[1.0e-4, 0.5e-4, 0.0], [0.5e-4, -2.0e-4, 0.0], [0.0; 3]]
        } else {
            [
                [1.0e-4, 0.3e-4, -0.2e-4],
                [0.5e-4, -2.0e-4, 0.1e-4],
                [0.4e-4, 0.2e-4, 1.5e-4],
            ]
        };
        let mut u = vec![0.0; x.len() * em.dpn];
        for (a, p) in x.iter().enumerate() {
            for i in 0..3 {
                u[a * em.dpn + i] = (0..3).map(|k| g[i][k] * p[k]).sum();
            }
        }
        let energy = form(&em.k, &u, &u);
        let eps = [
            g[0][0],
            g[1][1],
            g[2][2],
            g[0][1] + g[1][0],
            g[1][2] + g[2][1],
            g[2][0] + g[0][2],
        ];
        let want = if shell {
            // plane stress: σ = E/(1−ν²) [1 ν 0; ν 1 0; 0 0 (1−ν)/2] ε
            let c = E / (1.0 - NU * NU);
            let (exx, eyy, gxy) = (eps[0], eps[1], eps[3]);
            let density = c * (exx * exx + eyy * eyy + 2.0 * NU * exx * eyy)
                + c * (1.0 - NU) / 2.0 * gxy * gxy;
            measure(&case, &x) * density
        } else {
            let d = hooke();
            let density: f64 = (0..6)
                .map(|i| eps[i] * (0..6).map(|j| d[i][j] * eps[j]).sum::<f64>())
                .sum();
            measure(&case, &x) * density
        };
        // measured ≤ 2.5e-15 relative (CPYRAM 5)
        assert!(
            (energy - want).abs() <= 2.5e-14 * want,
            "{tag}: uᵀKu {energy:e} vs {want:e} ({:e})",
            (energy - want) / want
        );
    }
}

/// Turned in space (the beams' orientation vector with them), an element keeps the spectra of
/// its K and M.
#[test]
fn every_element_is_invariant_under_a_rotation() {
    let r = rotation([0.48, 0.6, 0.64], 0.9);
    for case in cases() {
        let tag = name(&case);
        let shell = is_shell(case.kind);
        let x: Vec<X> = (case.nodes.iter())
            .map(|&p| place(p, case.warped, shell))
            .collect();
        let turned: Vec<X> = x.iter().map(|&p| turn(&r, p)).collect();
        let v = [0.0, 1.0, 0.2];
        let a = model(&case, &x, v, &format!("{tag}-here"));
        let b = model(&case, &turned, turn(&r, v), &format!("{tag}-turned"));
        for mass in [MassKind::Consistent, MassKind::Lumped] {
            let (ea, eb) = (matrices(&a, mass, &tag), matrices(&b, mass, &tag));
            for (ka, kb, what) in [(&ea.k, &eb.k, "K"), (&ea.m, &eb.m, "M")] {
                let (la, lb) = (eigenvalues(ka), eigenvalues(kb));
                let top = la.last().copied().unwrap_or(0.0).abs();
                let worst = (la.iter().zip(&lb))
                    .map(|(p, q)| (p - q).abs())
                    .fold(0.0, f64::max);
                // measured ≤ 6.0e-15 of the largest eigenvalue (CPYRAM 13)
                assert!(
                    worst <= 6e-14 * top,
                    "{tag} {mass:?} {what}: {worst:e} of {top:e}"
                );
            }
        }
    }
}

/// Every kind the assembly forms has a case: the match below is exhaustive, so a new kind does
/// not compile here until it is placed.
#[test]
fn the_harness_covers_every_element_kind() {
    use ElementKind::*;
    let harnessed: Vec<ElementKind> = cases().iter().map(|c| c.kind).collect();
    let all = [
        Tet4,
        Tet10,
        Hex8,
        Hex8R,
        Hex8Bbar,
        Hex20,
        Hex20R,
        Prism6,
        Prism15,
        Pyram5,
        Pyram13,
        Pyram13Ansys,
        Beam2,
        Bar2,
        Beam2Linear,
        Beam3Quadratic,
        Beam4Cubic,
        Rod2,
        Tri3,
        Quad4,
        Tri6,
        Quad8,
        Beam3,
    ];
    for kind in all {
        let formed = match kind {
            Tet4 | Tet10 | Hex8 | Hex8R | Hex8Bbar | Hex20 | Hex20R | Prism6 | Prism15 | Pyram5
            | Pyram13 | Pyram13Ansys | Beam2 | Bar2 | Beam2Linear | Beam3Quadratic | Beam4Cubic
            | Rod2 | Tri3 | Quad4 | Tri6 | Quad8 => true,
            // expanded into bricks on import
            Beam3 => false,
        };
        assert_eq!(harnessed.contains(&kind), formed, "{kind:?}");
    }
}
