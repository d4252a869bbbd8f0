//! Preloaded solid models (issue 35): a slender solid column, pinned at both ends, under axial
//! compression and tension — f(P)/f(0) = √(1 − P/P_cr) with the column's P_cr (Euler with the
//! Timoshenko shear correction, P_cr = P_E/(1 + P_E/(κGA)), Timoshenko & Gere, *Theory of
//! Elastic Stability* (1961) §2.17; 0.08 % below P_E here) — in hex8 with incompatible modes,
//! hex20 and tet10; a bar with roller ends heated uniformly (σ_xx = −EαΔT, the other components
//! zero, at every integration point).

use std::collections::HashMap;

use crate::preload_support::{check_ratio, eigenvalues, frequency_ratio, heated, hold, Built};
use flexbody::fe::geometric::ElementStress;
use flexbody::fe::preload::{buckling_factor, preload, PreloadCase, PreloadSpec};
use flexbody::fe::{AssemblySpec, MassKind};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::load::{face_nodes, solid_faces};
use flexbody::model::{Element, ElementKind, Load, LoadPart, Material, Model, Node};
use std::f64::consts::PI;

const L: f64 = 1.0;
const B: f64 = 0.04; // along y
const H: f64 = 0.02; // along z: the weak bending plane is x–z

fn material() -> Material {
    // ν = 0: the end supports hold the lateral displacement without restraining a Poisson
    // expansion, so the axial stress is uniform up to the load's introduction
    Material::isotropic(1, "STEEL_NU0", 210e9, 0.0, 7850.0)
}

/// The hex8 block turned into hex20 (mid-edge nodes shared between neighbours).
fn to_hex20(model: Model) -> Model {
    let edges = solid_faces(ElementKind::Hex20).unwrap().1;
    let mut nodes = model.nodes.clone();
    let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
    let elements = (model.elements.iter())
        .map(|e| {
            let mut conn = e.nodes.clone();
            for &(a, b) in edges {
                let (p, q) = (e.nodes[a], e.nodes[b]);
                let key = (p.min(q), p.max(q));
                let idx = *mid.entry(key).or_insert_with(|| {
                    let x = std::array::from_fn(|k| 0.5 * (nodes[p].x[k] + nodes[q].x[k]));
                    nodes.push(Node {
                        id: nodes.len() as u64 + 1,
                        x,
                        displacement_frame: None,
                    });
                    nodes.len() - 1
                });
                conn.push(idx);
            }
            Element {
                kind: ElementKind::Hex20,
                nodes: conn,
                ..e.clone()
            }
        })
        .collect();
    Model {
        nodes,
        elements,
        ..model
    }
}

/// The column: `n` bricks, element kind, incompatible modes for hex8.
fn column(n: [usize; 3], kind: BlockElement, hex20: bool, bubbles: bool) -> Model {
    let mut m = block(&BlockSpec {
        n,
        size: [L, B, H],
        element: kind,
        material: material(),
    });
    m.params.solid_bubbles = bubbles;
    if hex20 {
        m = to_hex20(m);
    }
    m
}

fn on(x: f64, v: f64) -> bool {
    (x - v).abs() < 1e-9
}

/// Uniform pressure `p` on the faces at x = 0 and x = L (pushing into the solid: compression for
/// p > 0).
fn end_pressure(model: &Model, p: f64) -> Load {
    let mut parts = Vec::new();
    for el in &model.elements {
        let (faces, edges) = solid_faces(el.kind).unwrap();
        for face in faces {
            let nodes = face_nodes(&el.nodes, face, edges).unwrap();
            for end in [0.0, L] {
                if nodes.iter().all(|&q| on(model.nodes[q].x[0], end)) {
                    parts.push(LoadPart::Surface {
                        nodes: nodes.clone(),
                        traction: -p,
                        element: el.id,
                    });
                }
            }
        }
    }
    Load {
        name: "AXIAL".into(),
        source: "test".into(),
        selected: true,
        parts,
        problem: None,
    }
}

/// Pinned ends: the end faces hold v and w (the section turns freely, its warping is free); u
/// is held at one node of the mid-span section, which does not move axially in the symmetric
/// first mode.
fn pin(model: &mut Model) {
    let mut mid = None;
    for i in 0..model.nodes.len() {
        let x = model.nodes[i].x;
        if on(x[0], 0.0) || on(x[0], L) {
            hold(model, i, "23");
        }
        if on(x[0], 0.5 * L) && mid.is_none() {
            mid = Some(i);
        }
    }
    hold(model, mid.expect("a node at mid-span"), "1");
}

fn check_column(name: &str, model: Model) {
    let b = Built::new(
        model,
        AssemblySpec {
            mass: MassKind::Consistent,
            ..Default::default()
        },
    );
    let m = material();
    let p_e = PI * PI * m.e * (B * H.powi(3) / 12.0) / (L * L);
    let p_cr = p_e / (1.0 + p_e / (5.0 / 6.0 * m.g * B * H));
    let w0 = eigenvalues(&b.red.k, &b.red.m)[0];
    let case = |ratio: f64| PreloadCase {
        loads: vec![end_pressure(&b.model, ratio * p_cr / (B * H))],
        ..Default::default()
    };
    let pre = preload(&b.system(), &case(0.5), &PreloadSpec::default()).unwrap();
    let l1 = buckling_factor(&b.system(), &pre, faer::Par::Seq)
        .unwrap()
        .unwrap();
    eprintln!(
        "{name}: the mesh's own P_cr = {:.6} × the shear-corrected Euler load",
        0.5 * l1
    );
    for ratio in [0.5, 0.9, -1.0] {
        let got = frequency_ratio(&b, &case(ratio), w0).unwrap();
        check_ratio(
            &format!("{name}: P/P_cr = {ratio:+}"),
            got,
            (1.0 - ratio).sqrt(),
            1e-3,
        );
    }
}

#[test]
fn hex8_incompatible_column_frequency_ratio_matches_euler() {
    let mut m = column([50, 2, 1], BlockElement::Hex8, false, true);
    pin(&mut m);
    check_column("hex8 incompatible 50×2×1", m);
}

#[test]
fn hex20_column_frequency_ratio_matches_euler() {
    let mut m = column([25, 1, 1], BlockElement::Hex8, true, false);
    pin(&mut m);
    check_column("hex20 25×1×1", m);
}

#[test]
fn tet10_column_frequency_ratio_matches_euler() {
    let mut m = column([50, 2, 1], BlockElement::Tet10Six, false, false);
    pin(&mut m);
    check_column("tet10 50×2×1 (6 per brick)", m);
}

/// Roller ends (u = 0 on both end faces, the lateral motion free apart from the rigid-body
/// holds), ν = 0.3, uniform ΔT: σ_xx = −EαΔT, every other component zero.
#[test]
fn heated_bar_between_rollers_carries_the_thermal_stress() {
    let mut m = block(&BlockSpec {
        n: [10, 2, 2],
        size: [L, B, H],
        element: BlockElement::Hex8,
        material: Material::steel(),
    });
    m.params.solid_bubbles = true;
    for i in 0..m.nodes.len() {
        let x = m.nodes[i].x;
        if on(x[0], 0.0) || on(x[0], L) {
            hold(&mut m, i, "1");
        }
        if on(x[0], 0.0) && on(x[1], 0.0) && on(x[2], 0.0) {
            hold(&mut m, i, "23");
        }
        if on(x[0], 0.0) && on(x[1], B) && on(x[2], 0.0) {
            hold(&mut m, i, "3");
        }
    }
    let b = Built::new(m, AssemblySpec::default());
    let (alpha, dt) = (1.2e-5, 10.0);
    let (pre, stresses) = heated(&b, vec![alpha], dt);
    assert_eq!(pre.rigid_modes, 0);
    let want = -210e9 * alpha * dt;
    let mut worst = 0.0f64;
    for (_, s) in &stresses {
        let ElementStress::Solid(points) = s else {
            panic!("{s:?}")
        };
        for sg in points {
            worst = worst.max((sg[0] - want).abs());
            for v in &sg[1..] {
                worst = worst.max(v.abs());
            }
        }
    }
    eprintln!("heated bar: σ_xx = −EαΔT = {want:.4e}, largest deviation {worst:.2e}");
    assert!(worst < 1e-8 * want.abs());
}
