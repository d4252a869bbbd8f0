//! A simply supported rectangular plate under a uniform in-plane force N_x (issue 35): the mode
//! (1, 1) keeps its shape sin(πx/a) sin(πy/b), and ρt ω² = D k⁴ + N_x (π/a)² with
//! k² = (π/a)² + (π/b)², so f(N_x)/f(0) = √(1 + N_x/N_cr) with
//! N_cr = D (π/a)² (1 + (a/b)²)² (Timoshenko & Gere, *Theory of Elastic Stability* (1961)
//! §9.2; Leissa, *Vibration of Plates* (1969) §4.3 for the frequency with in-plane force).
//! MITC4 quadrilaterals and DKT triangles, the membrane force from the static solve of edge
//! forces (the resultants checked uniform), tension and compression: within 1e-3 (quads) and
//! 3e-3 (triangles) at 24×24. And the same plate heated with its edges held in-plane: the
//! biaxial N = −E t αΔT/(1 − ν) gives ρt ω² = D k⁴ + N k², f/f0 = √(1 + N/(D k²)).

use crate::common::shell_grid;
use crate::preload_support::{check_ratio, eigenvalues, heated, hold, Built};
use flexbody::fe::geometric::{element_stresses, ElementStress};
use flexbody::fe::preload::{preload, PreloadCase, PreloadSpec};
use flexbody::fe::{AssemblySpec, MassKind};
use flexbody::model::{Load, LoadPart, Material, Model};
use std::f64::consts::PI;

const A: f64 = 1.0; // along x, the loaded direction
const B: f64 = 1.2;
const T: f64 = 0.01;
const N: usize = 24;

fn plate(tris: bool) -> Model {
    let alu = Material::isotropic(1, "ALU", 70e9, 0.33, 2700.0);
    let mut model = shell_grid(N, N, tris, T, alu, |s, r| [A * s, B * r, 0.0]);
    // simply supported edges; in-plane: u = 0 along x = 0, v = 0 at the origin (the plate
    // contracts freely across)
    for k in 0..model.nodes.len() {
        let [x, y, _] = model.nodes[k].x;
        let edge = |v: f64, e: f64| (v - e).abs() < 1e-9;
        if edge(x, 0.0) || edge(x, A) || edge(y, 0.0) || edge(y, B) {
            hold(&mut model, k, "3");
        }
        if edge(x, 0.0) {
            hold(&mut model, k, "1");
        }
        if edge(x, 0.0) && edge(y, 0.0) {
            hold(&mut model, k, "2");
        }
    }
    model
}

fn kind(tris: bool) -> &'static str {
    if tris {
        "triangles"
    } else {
        "quads"
    }
}

/// N_x (force per length) along the edge x = A: consistent nodal forces of a uniform traction.
fn edge_force(model: &Model, nx: f64) -> Load {
    let h = B / N as f64;
    let parts = (0..model.nodes.len())
        .filter(|&k| (model.nodes[k].x[0] - A).abs() < 1e-9)
        .map(|k| {
            let y = model.nodes[k].x[1];
            let end = y.abs() < 1e-9 || (y - B).abs() < 1e-9;
            LoadPart::Nodal {
                node: k,
                values: [
                    nx * h * if end { 0.5 } else { 1.0 },
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                ],
            }
        })
        .collect();
    Load {
        name: "NX".into(),
        source: "test".into(),
        selected: true,
        parts,
        problem: None,
    }
}

#[test]
fn simply_supported_plate_under_in_plane_force_matches_closed_form() {
    let m = Material::isotropic(1, "ALU", 70e9, 0.33, 2700.0);
    let d = m.e * T.powi(3) / (12.0 * (1.0 - m.nu * m.nu));
    let n_cr = d * (PI / A).powi(2) * (1.0 + (A / B).powi(2)).powi(2);
    for tris in [false, true] {
        let b = Built::new(
            plate(tris),
            AssemblySpec {
                mass: MassKind::Consistent,
                ..Default::default()
            },
        );
        let w0 = eigenvalues(&b.red.k, &b.red.m)[0];
        for ratio in [1.0, -0.5, -0.9] {
            let nx = ratio * n_cr;
            let case = PreloadCase {
                loads: vec![edge_force(&b.model, nx)],
                ..Default::default()
            };
            let pre = preload(&b.system(), &case, &PreloadSpec::default()).unwrap();
            // the membrane force is uniform N_x along x: in each element's frame (the
            // triangles' e₁ runs along their first edge) trace N_x and determinant 0
            let stresses = element_stresses(&b.model, &b.asm.dofs, &b.spec, &pre.u, None).unwrap();
            for (e, s) in &stresses {
                let ElementStress::Shell(res) = s else {
                    panic!("{s:?}")
                };
                for r in res {
                    let trace = (r[0] + r[1] - nx).abs();
                    let det = (r[0] * r[1] - r[2] * r[2]).abs();
                    assert!(
                        trace < 1e-8 * nx.abs() && det < 1e-10 * nx * nx,
                        "element {e}: {r:?} vs N_x = {nx}"
                    );
                }
            }
            let got = (eigenvalues(&pre.k_t, &b.red.m)[0] / w0).sqrt();
            // measured at 24×24: quads ≤ 5.7e-4, triangles ≤ 2.1e-3 (at N_x = −0.9 N_cr, where
            // the ratio is most sensitive to the mesh's own N_cr)
            check_ratio(
                &format!("SS plate {} {N}×{N}: N_x/N_cr = {ratio:+}", kind(tris)),
                got,
                (1.0 + ratio).sqrt(),
                if tris { 3e-3 } else { 1e-3 },
            );
        }
    }
}

#[test]
fn heated_plate_with_held_edges_matches_biaxial_closed_form() {
    let m = Material::isotropic(1, "ALU", 70e9, 0.33, 2700.0);
    let d = m.e * T.powi(3) / (12.0 * (1.0 - m.nu * m.nu));
    let k2 = (PI / A).powi(2) + (PI / B).powi(2);
    let n_cr = d * k2;
    let alpha = 2.3e-5;
    for tris in [false, true] {
        let mut model = plate(tris);
        for k in 0..model.nodes.len() {
            let [x, y, _] = model.nodes[k].x;
            let edge = |v: f64, e: f64| (v - e).abs() < 1e-9;
            if edge(x, 0.0) || edge(x, A) || edge(y, 0.0) || edge(y, B) {
                hold(&mut model, k, "12");
            }
        }
        let b = Built::new(
            model,
            AssemblySpec {
                mass: MassKind::Consistent,
                ..Default::default()
            },
        );
        let w0 = eigenvalues(&b.red.k, &b.red.m)[0];
        let ratio = -0.5;
        let n = ratio * n_cr;
        let dt = -n * (1.0 - m.nu) / (m.e * T * alpha);
        let (pre, stresses) = heated(&b, vec![alpha], dt);
        for (e, s) in &stresses {
            let ElementStress::Shell(res) = s else {
                panic!("{s:?}")
            };
            for r in res {
                let dev = (r[0] - n).abs().max((r[1] - n).abs()).max(r[2].abs());
                assert!(dev < 1e-8 * n.abs(), "element {e}: {r:?} vs N = {n}");
            }
        }
        let got = (eigenvalues(&pre.k_t, &b.red.m)[0] / w0).sqrt();
        check_ratio(
            &format!(
                "heated SS plate {} {N}×{N}: N/(D k²) = {ratio:+} (ΔT = {dt:.3} K)",
                kind(tris)
            ),
            got,
            (1.0 + ratio).sqrt(),
            if tris { 3e-3 } else { 1e-3 },
        );
    }
}
