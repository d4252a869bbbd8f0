//! Shell fibre stress/strain shapes (format 1.5) against closed form: on a distorted mesh of
//! quadrilaterals and triangles in a skew plane, a displacement state of constant membrane
//! strain ε_m and constant curvature κ must give, at every node, the top/bottom fibre strain
//! ε_m ± (t/2)κ and the plane-stress stress — in bending, σ = 6M/t² with M = Dκ — rotated to
//! body axes; and through the CLI the shells' bottom fibre is written (format 1.5).

use flexbody::model::{
    Element, ElementKind, Material, Model, Node, Property, Section, ShellSection,
};
use flexbody::shell_stress::shell_fields;
use flexbody::stress::FieldRequest;

const E: f64 = 210e9;
const NU: f64 = 0.3;
const T: f64 = 0.004;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    a.map(|v| v / n)
}

/// Plane axes a1, a2 and normal n = a1 × a2 of a skew plane.
fn axes() -> [[f64; 3]; 3] {
    let a1 = unit([0.8, 0.3, -0.5]);
    let t = [0.1, 0.9, 0.4];
    let d: f64 = (0..3).map(|i| t[i] * a1[i]).sum();
    let a2 = unit([t[0] - d * a1[0], t[1] - d * a1[1], t[2] - d * a1[2]]);
    [a1, a2, cross(a1, a2)]
}

/// 3×3 distorted grid in the plane: the left column quads, the others split into triangles;
/// node order counter-clockwise about n. Returns the model and the plane coordinates.
fn mesh() -> (Model, Vec<[f64; 2]>) {
    let ax = axes();
    let n = 3;
    let mut model = Model {
        source: "generated".into(),
        ..Model::default()
    };
    let mut plane = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (s, r) = (i as f64 * 0.1, j as f64 * 0.1);
            let bump = if 0 < i && i < n && 0 < j && j < n {
                0.025 * ((i * 7 + j * 3) % 5) as f64 / 4.0 - 0.012
            } else {
                0.0
            };
            let (s, r) = (s + bump, r - 0.7 * bump);
            plane.push([s, r]);
            model.nodes.push(Node {
                id: (j * (n + 1) + i + 1) as u64,
                x: std::array::from_fn(|c| 1.0 + s * ax[0][c] + r * ax[1][c]),
                displacement_frame: None,
            });
        }
    }
    model
        .materials
        .push(Material::isotropic(1, "STEEL", E, NU, 7850.0));
    model.properties.push(Property {
        id: 1,
        name: "SHELL".into(),
        material: 0,
        section: Section::Shell(ShellSection::homogeneous(T, 0)),
    });
    let idx = |i: usize, j: usize| j * (n + 1) + i;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            let cells: Vec<(ElementKind, Vec<usize>)> = if i == 0 {
                vec![(ElementKind::Quad4, vec![a, b, c, d])]
            } else {
                vec![
                    (ElementKind::Tri3, vec![a, b, c]),
                    (ElementKind::Tri3, vec![a, c, d]),
                ]
            };
            for (kind, nodes) in cells {
                let id = model.elements.len() as u64 + 1;
                model.elements.push(Element {
                    id,
                    kind,
                    nodes,
                    property: Some(0),
                    orientation: None,
                });
            }
        }
    }
    (model, plane)
}

/// The state (ε_m, κ) as basic-frame nodal values [u v w θx θy θz]: in plane coordinates
/// u = εx x + ½γ y, v = ½γ x + εy y, w = −½(κx x² + κy y² + κxy xy), θx = w,y, θy = −w,x.
fn state(p: [f64; 2], em: [f64; 3], k: [f64; 3]) -> [f64; 6] {
    let ax = axes();
    let [x, y] = p;
    let u = em[0] * x + 0.5 * em[2] * y;
    let v = 0.5 * em[2] * x + em[1] * y;
    let w = -0.5 * (k[0] * x * x + k[1] * y * y + k[2] * x * y);
    let wx = -(k[0] * x + 0.5 * k[2] * y);
    let wy = -(k[1] * y + 0.5 * k[2] * x);
    let (tx, ty) = (wy, -wx);
    let mut out = [0.0; 6];
    for c in 0..3 {
        out[c] = u * ax[0][c] + v * ax[1][c] + w * ax[2][c];
        out[3 + c] = tx * ax[0][c] + ty * ax[1][c];
    }
    out
}

/// Closed form: plane tensor (xx, yy, xy) + zz → body Voigt (engineering shear when `strain`).
fn body(t: [f64; 3], zz: f64, strain: bool) -> [f64; 6] {
    let ax = axes();
    let s = if strain { 0.5 } else { 1.0 };
    let m = |i: usize, j: usize| -> f64 {
        t[0] * ax[0][i] * ax[0][j]
            + t[1] * ax[1][i] * ax[1][j]
            + s * t[2] * (ax[0][i] * ax[1][j] + ax[1][i] * ax[0][j])
            + zz * ax[2][i] * ax[2][j]
    };
    let f = if strain { 2.0 } else { 1.0 };
    [
        m(0, 0),
        m(1, 1),
        m(2, 2),
        f * m(0, 1),
        f * m(1, 2),
        f * m(2, 0),
    ]
}

#[test]
fn shell_fibre_fields_of_constant_strain_and_curvature_match_closed_form() {
    let (model, plane) = mesh();
    let cases = [
        ([2e-4, -1e-4, 3e-4], [0.0; 3]),
        ([0.0; 3], [0.5, 0.2, -0.3]),
        ([1e-4, 2e-4, -1e-4], [-0.2, 0.4, 0.1]),
    ];
    let disp = |n: usize, j: usize| state(plane[n], cases[j].0, cases[j].1);
    let wanted: Vec<usize> = (0..model.nodes.len()).collect();
    let f = shell_fields(
        &model,
        &wanted,
        cases.len(),
        &disp,
        FieldRequest {
            stress: true,
            strain: true,
        },
    )
    .unwrap();
    assert_eq!(f.nodes, wanted);
    let k = f.nodes.len();
    let c = E / (1.0 - NU * NU);
    let q = |e: [f64; 3]| {
        [
            c * (e[0] + NU * e[1]),
            c * (e[1] + NU * e[0]),
            c * 0.5 * (1.0 - NU) * e[2],
        ]
    };
    let mut worst = 0.0f64;
    for (j, (em, kap)) in cases.iter().enumerate() {
        for (top, z) in [(true, 0.5 * T), (false, -0.5 * T)] {
            let e: [f64; 3] = std::array::from_fn(|i| em[i] + z * kap[i]);
            let want_e = body(e, -NU / (1.0 - NU) * (e[0] + e[1]), true);
            let want_s = body(q(e), 0.0, false);
            let (got_s, got_e) = if top {
                (
                    f.top_stress.as_ref().unwrap(),
                    f.top_strain.as_ref().unwrap(),
                )
            } else {
                (
                    f.bottom_stress.as_ref().unwrap(),
                    f.bottom_strain.as_ref().unwrap(),
                )
            };
            let scale_s = want_s.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let scale_e = want_e.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            for n in 0..k {
                for comp in 0..6 {
                    let i = (j * k + n) * 6 + comp;
                    let ds = (got_s[i] - want_s[comp]).abs() / scale_s;
                    let de = (got_e[i] - want_e[comp]).abs() / scale_e;
                    worst = worst.max(ds).max(de);
                    assert!(
                        ds < 1e-9 && de < 1e-9,
                        "case {j} top={top} node {n} comp {comp}: σ {} vs {}, ε {} vs {}",
                        got_s[i],
                        want_s[comp],
                        got_e[i],
                        want_e[comp]
                    );
                }
            }
        }
    }
    // bending only: the top fibre's σ_x in plane axes is 6 M_x / t², M = D κ
    let d = E * T.powi(3) / (12.0 * (1.0 - NU * NU));
    let mx = d * (0.5 + NU * 0.2);
    let ax = axes();
    let s = f.top_stress.as_ref().unwrap();
    let v = &s[(k) * 6..(k) * 6 + 6]; // case 1, node 0
    let t = [[v[0], v[3], v[5]], [v[3], v[1], v[4]], [v[5], v[4], v[2]]];
    let sx: f64 = (0..3)
        .map(|i| {
            (0..3)
                .map(|jj| ax[0][i] * t[i][jj] * ax[0][jj])
                .sum::<f64>()
        })
        .sum();
    assert!((sx - 6.0 * mx / (T * T)).abs() < 1e-9 * sx.abs(), "{sx}");
    eprintln!("worst relative deviation {worst:.2e}");
}
