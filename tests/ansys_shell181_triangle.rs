//! SHELL181's degenerate triangle (K = L) against ANSYS's own element energies: a part (7
//! triangles, the 44 quadrilaterals sharing a node with one and 21 others (every 50th); 72
//! elements, 165 nodes) of ansys/example-data's `msup_distributed` modal result (ANSYS 2022 R1,
//! a 1 mm steel sheet meshed by Workbench, KEYOPT(3)=2, six mass-normalised modes; converted by
//! `tests/data/ansys/make_shell181_tri.py`). The sheet is flat (y = 0): mode 1 (111.6 Hz) moves
//! it in its plane, modes 2–6 out of it. Each element's ENG record holds SENE (the strain energy
//! without the drilling penalty), AENE (the drilling penalty's) and KENE = ½ω² φ_eᵀ M_e φ_e.
//!
//! Through the importer (`fe::assembly::element_matrices` of the archive's model), element by
//! element and mode by mode:
//! - ½ φ_eᵀ K_e φ_e less the drilling penalty's energy equals SENE — bending and transverse
//!   shear (modes 2–6) and the membrane (mode 1) of the triangles, with the quadrilaterals as
//!   control;
//! - ½ω² φ_eᵀ M_e φ_e less flexbody's drilling inertia equals KENE.
//!
//! The drilling penalty's energy is not ANSYS's AENE (printed, not asserted: docs/ansys.md).

use std::collections::HashMap;

use crate::ansys_support::data;
use flexbody::fe::assembly::element_matrices;
use flexbody::fe::{AssemblySpec, MassKind};
use flexbody::import::{read_model, ImportOptions};

const E: f64 = 2e11;
const NU: f64 = 0.3;
const RHO: f64 = 7850.0;
const T: f64 = 1e-3;

/// ANSYS's solution: frequencies, node id → x, y, z then per mode the six dofs; element id →
/// volume then per mode SENE, AENE, KENE.
struct Solution {
    frequencies: Vec<f64>,
    nodes: HashMap<u64, Vec<f64>>,
    elements: HashMap<u64, Vec<f64>>,
}

fn solution() -> Solution {
    let text = std::fs::read_to_string(data("shell181_tri.csv")).unwrap();
    let mut s = Solution {
        frequencies: Vec::new(),
        nodes: HashMap::new(),
        elements: HashMap::new(),
    };
    for line in text.lines() {
        let f: Vec<&str> = line.split(',').collect();
        let id: u64 = f[1].parse().unwrap();
        let v: Vec<f64> = f[2..].iter().map(|t| t.parse().unwrap()).collect();
        match f[0] {
            "mode" => s.frequencies.push(v[0]),
            "node" => {
                s.nodes.insert(id, v);
            }
            "element" => {
                s.elements.insert(id, v);
            }
            other => panic!("unexpected row {other}"),
        }
    }
    s
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

/// The flat element's 2×2 Gauss points: (det J, N_a, [N_a,x N_a,y]) in an in-plane frame
/// (e₁, e₂) ⟂ e₃ ∥ (x₃ − x₁) × (x₄ − x₂), and e₃.
type Point = (f64, [f64; 4], [[f64; 2]; 4]);

fn gauss_points(x: &[[f64; 3]; 4]) -> (Vec<Point>, [[f64; 3]; 3]) {
    let e3 = unit(cross(sub(x[2], x[0]), sub(x[3], x[1])));
    let edge = sub(x[1], x[0]);
    let e1 = unit(sub(edge, e3.map(|v| v * dot(edge, e3))));
    let e2 = cross(e3, e1);
    let p: Vec<[f64; 2]> = x
        .iter()
        .map(|xa| [dot(sub(*xa, x[0]), e1), dot(sub(*xa, x[0]), e2)])
        .collect();
    let g = 1.0 / 3f64.sqrt();
    let corners = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    let points = [[-g, -g], [g, -g], [g, g], [-g, g]]
        .iter()
        .map(|&[xi, eta]| {
            let n: [f64; 4] = std::array::from_fn(|a| {
                0.25 * (1.0 + corners[a][0] * xi) * (1.0 + corners[a][1] * eta)
            });
            let d: [[f64; 2]; 4] = std::array::from_fn(|a| {
                [
                    0.25 * corners[a][0] * (1.0 + corners[a][1] * eta),
                    0.25 * corners[a][1] * (1.0 + corners[a][0] * xi),
                ]
            });
            let j: [[f64; 2]; 2] = std::array::from_fn(|r| {
                std::array::from_fn(|c| (0..4).map(|a| d[a][r] * p[a][c]).sum())
            });
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let grad = d.map(|da| {
                [
                    (j[1][1] * da[0] - j[0][1] * da[1]) / det,
                    (-j[1][0] * da[0] + j[0][0] * da[1]) / det,
                ]
            });
            (det, n, grad)
        })
        .collect();
    (points, [e1, e2, e3])
}

/// The drilling penalty's energy as flexbody forms SHELL181's (docs/ansys.md: γ_d = s k G t/200
/// at the 2×2 points, s = 1/(1 + A/(160 000 t²)), k = 5/6): ½ Σ γ_d det J (θ·e₃ − ω)², ω =
/// ½(v,x − u,y); and ½ Σ det J ε ρt³/12 (θ·e₃)² with ε = 10⁻⁴, flexbody's drilling inertia
/// (per ω² of the mode).
fn drilling(x: &[[f64; 3]; 4], u: &[f64]) -> (f64, f64) {
    let (points, [e1, e2, e3]) = gauss_points(x);
    let area: f64 = points.iter().map(|p| p.0).sum();
    let s = 1.0 / (1.0 + area / (160_000.0 * T * T));
    let gamma = s * (5.0 / 6.0) * E / (2.0 * (1.0 + NU)) * T / 200.0;
    let at = |a: usize, c: usize| [u[6 * a + c], u[6 * a + c + 1], u[6 * a + c + 2]];
    let (mut penalty, mut inertia) = (0.0, 0.0);
    for (det, n, g) in &points {
        let theta: f64 = (0..4).map(|a| n[a] * dot(at(a, 3), e3)).sum();
        let omega: f64 = (0..4)
            .map(|a| 0.5 * (g[a][0] * dot(at(a, 0), e2) - g[a][1] * dot(at(a, 0), e1)))
            .sum();
        penalty += 0.5 * gamma * det * (theta - omega).powi(2);
        inertia += 0.5 * det * 1e-4 * RHO * T.powi(3) / 12.0 * theta * theta;
    }
    (penalty, inertia)
}

/// u less a rigid motion (node 1's translation, the nodes' mean rotation): the strain energy
/// is unchanged (K's null space) and the rounding of a mode's large rigid part (mode 1 turns
/// the sheet about its held node) drops out.
fn without_rigid(x: &[[f64; 3]; 4], u: &[f64]) -> Vec<f64> {
    let th: [f64; 3] = std::array::from_fn(|c| (0..4).map(|a| u[6 * a + 3 + c]).sum::<f64>() / 4.0);
    let mut out = u.to_vec();
    for a in 0..4 {
        let r = cross(th, sub(x[a], x[0]));
        for c in 0..3 {
            out[6 * a + c] -= u[c] + r[c];
            out[6 * a + 3 + c] -= th[c];
        }
    }
    out
}

fn quadratic(a: &[f64], u: &[f64]) -> f64 {
    let n = u.len();
    (0..n)
        .map(|i| u[i] * (0..n).map(|j| a[i * n + j] * u[j]).sum::<f64>())
        .sum::<f64>()
        / 2.0
}

/// Worst relative differences, [triangles, quadrilaterals] × [mode 1, modes 2–6].
type Worst = [[f64; 2]; 2];

/// Each element's energies against ANSYS's: ½ φ̃ᵀ K_e φ̃ less the drilling penalty against SENE
/// (φ̃: the mode less the element's rigid motion), ½ω² φᵀ M_e φ less the drilling inertia
/// against KENE. Measured: SENE triangles 1.2e-6 (mode 1) and 7.2e-8 (modes 2–6),
/// quadrilaterals 1.1e-6 and 1.4e-7; KENE triangles 4.5e-8, quadrilaterals 5.8e-8 (ANSYS writes
/// ENG in single precision: 6e-8; mode 1's energies reach down to 1e-7 of the mode's largest
/// element's). The collapsed quadrilateral's membrane is the constant-strain triangle (its
/// three nodes' values span the affine fields; Taylor's modes carry no energy at constant
/// strain), its curvatures constant, its shear MITC4's tied on the collapsed side.
#[test]
fn shell181_triangle_equals_ansys_element_energies() {
    let s = solution();
    let model = read_model(&data("shell181_tri.cdb"), &ImportOptions::default()).unwrap();
    // ANSYS's consistent mass (flexbody's default is lumped)
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        ..AssemblySpec::default()
    };
    let (mut strain, mut kinetic): (Worst, Worst) = Default::default();
    let (mut drill_ratio, mut drill_inertia) = ([f64::MAX, 0.0f64], 0.0f64);
    let mut triangles = 0;
    for (e, el) in model.elements.iter().enumerate() {
        let ids: Vec<u64> = el.nodes.iter().map(|&n| model.nodes[n].id).collect();
        // 0: a triangle (K = L), 1: a quadrilateral
        let kind = usize::from(ids[2] != ids[3]);
        triangles += 1 - kind;
        let em = element_matrices(&model, e, &spec).unwrap();
        let x: [[f64; 3]; 4] =
            std::array::from_fn(|a| std::array::from_fn(|c| s.nodes[&ids[a]][c]));
        let ansys = &s.elements[&el.id];
        for (k, f) in s.frequencies.iter().enumerate() {
            let w2 = (2.0 * std::f64::consts::PI * f).powi(2);
            let u: Vec<f64> = (ids.iter())
                .flat_map(|n| s.nodes[n][3 + 6 * k..9 + 6 * k].to_vec())
                .collect();
            let (sene, aene, kene) = (ansys[1 + 3 * k], ansys[2 + 3 * k], ansys[3 + 3 * k]);
            let elastic = without_rigid(&x, &u);
            let (penalty, _) = drilling(&x, &elastic);
            let energy = quadratic(&em.k, &elastic) - penalty;
            let (_, inertia) = drilling(&x, &u);
            let kin = w2 * (quadratic(&em.m, &u) - inertia);
            let band = usize::from(k > 0);
            strain[kind][band] = strain[kind][band].max((energy / sene - 1.0).abs());
            kinetic[kind][band] = kinetic[kind][band].max((kin / kene - 1.0).abs());
            if k == 0 && aene > 1e-3 {
                drill_ratio = [
                    drill_ratio[0].min(aene / penalty),
                    drill_ratio[1].max(aene / penalty),
                ];
                drill_inertia = drill_inertia.max(w2 * inertia / kene);
            }
        }
    }
    println!(
        "SENE: triangles {:.1e} (mode 1), {:.1e} (2–6); quadrilaterals {:.1e}, {:.1e}",
        strain[0][0], strain[0][1], strain[1][0], strain[1][1]
    );
    println!(
        "KENE: triangles {:.1e}, {:.1e}; quadrilaterals {:.1e}, {:.1e}",
        kinetic[0][0], kinetic[0][1], kinetic[1][0], kinetic[1][1]
    );
    println!(
        "mode 1: AENE / the drilling penalty's energy {:.2}…{:.2}; flexbody's drilling inertia \
         {drill_inertia:.1e} of KENE",
        drill_ratio[0], drill_ratio[1]
    );
    assert_eq!((triangles, model.elements.len()), (7, 72));
    // measured 1.2e-6 and 1.1e-6 (mode 1), 7.2e-8 and 1.4e-7 (modes 2–6)
    for w in strain {
        assert!(w[0] < 3e-6 && w[1] < 4e-7, "{strain:?}");
    }
    // measured 4.5e-8 (triangles) and 5.8e-8 (quadrilaterals), every mode
    for w in kinetic {
        assert!(w[0] < 2e-7 && w[1] < 2e-7, "{kinetic:?}");
    }
}
