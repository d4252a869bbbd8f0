//! Patch tests and matrix properties of every solid element on a distorted 2×2×2 patch filling
//! the unit cube (interior node moved off-centre): linear displacement fields give zero force at
//! interior nodes and strain energy ½ε:D:ε·V with V = 1 exactly (Irons patch test, Zienkiewicz &
//! Taylor Vol. 1 §10); rigid motions give zero force; K is symmetric PSD with exactly six zero
//! eigenvalues; both mass lumpings and the consistent mass total ρV; HRZ masses are positive.

use std::collections::HashMap;

use crate::common::{dense, steel};
use flexbody::fe::{assemble, AssemblySpec, MassKind, Tet10MassRule};
use flexbody::model::{Element, ElementKind, Model, Node, Property, Section};

/// Unit-cube 2×2×2 patch of the given kind; the centre node is moved to (0.55, 0.43, 0.52).
fn patch(kind: ElementKind) -> Model {
    let mut model = Model {
        source: format!("patch {kind:?}"),
        ..Model::default()
    };
    model.materials.push(steel());
    model.properties.push(Property {
        id: 1,
        name: "P".into(),
        material: 0,
        section: Section::Solid,
    });
    let id = |i: usize, j: usize, k: usize| i + 3 * (j + 3 * k);
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..3 {
                let mut x = [i as f64 * 0.5, j as f64 * 0.5, k as f64 * 0.5];
                if (i, j, k) == (1, 1, 1) {
                    x = [0.55, 0.43, 0.52];
                }
                model.nodes.push(Node {
                    id: id(i, j, k) as u64 + 1,
                    x,
                    displacement_frame: None,
                });
            }
        }
    }
    let mut mids: HashMap<(usize, usize), usize> = HashMap::new();
    let mut mid = |model: &mut Model, a: usize, b: usize| -> usize {
        let key = (a.min(b), a.max(b));
        *mids.entry(key).or_insert_with(|| {
            let (xa, xb) = (model.nodes[a].x, model.nodes[b].x);
            model.nodes.push(Node {
                id: model.nodes.len() as u64 + 1,
                x: std::array::from_fn(|d| 0.5 * (xa[d] + xb[d])),
                displacement_frame: None,
            });
            model.nodes.len() - 1
        })
    };
    let mut cells: Vec<(ElementKind, Vec<usize>)> = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
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
                match kind {
                    ElementKind::Hex8 | ElementKind::Hex20 | ElementKind::Hex20R => {
                        cells.push((kind, h.to_vec()))
                    }
                    ElementKind::Prism6 => {
                        cells.push((kind, vec![h[0], h[1], h[2], h[4], h[5], h[6]]));
                        cells.push((kind, vec![h[0], h[2], h[3], h[4], h[6], h[7]]));
                    }
                    _ => {
                        // Kuhn split along the 1–7 diagonal: 6 positive tets.
                        for t in [
                            [0, 1, 2, 6],
                            [0, 2, 3, 6],
                            [0, 3, 7, 6],
                            [0, 7, 4, 6],
                            [0, 4, 5, 6],
                            [0, 5, 1, 6],
                        ] {
                            cells.push((kind, t.iter().map(|&q| h[q]).collect()));
                        }
                    }
                }
            }
        }
    }
    for (e, (kind, mut nodes)) in cells.into_iter().enumerate() {
        match kind {
            ElementKind::Tet10 => {
                for (a, b) in [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)] {
                    let m = mid(&mut model, nodes[a], nodes[b]);
                    nodes.push(m);
                }
            }
            ElementKind::Hex20 | ElementKind::Hex20R => {
                for (a, b) in [
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
                ] {
                    let m = mid(&mut model, nodes[a], nodes[b]);
                    nodes.push(m);
                }
            }
            _ => {}
        }
        // Tet orientation: swap two nodes if the volume is negative.
        if matches!(kind, ElementKind::Tet4 | ElementKind::Tet10) {
            let x: Vec<[f64; 3]> = nodes[..4].iter().map(|&n| model.nodes[n].x).collect();
            let d = |a: usize| std::array::from_fn::<f64, 3, _>(|c| x[a][c] - x[0][c]);
            let (u, v, w) = (d(1), d(2), d(3));
            let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                + u[2] * (v[0] * w[1] - v[1] * w[0]);
            if det < 0.0 {
                nodes.swap(1, 2);
                if kind == ElementKind::Tet10 {
                    // edges (1,2)↔(1,3) i.e. 5↔7, and (2,4)↔(3,4) i.e. 9↔10
                    nodes.swap(4, 6);
                    nodes.swap(8, 9);
                }
            }
        }
        model.elements.push(Element {
            id: e as u64 + 1,
            kind,
            nodes,
            property: Some(0),
            orientation: None,
        });
    }
    model
}

fn on_boundary(x: [f64; 3]) -> bool {
    x.iter()
        .any(|&c| c.abs() < 1e-12 || (c - 1.0).abs() < 1e-12)
}

const KINDS: [ElementKind; 6] = [
    ElementKind::Tet4,
    ElementKind::Tet10,
    ElementKind::Hex8,
    ElementKind::Hex20,
    ElementKind::Hex20R,
    ElementKind::Prism6,
];

#[test]
fn every_solid_passes_the_constant_strain_patch_test() {
    // u = b + A x with a general A (symmetric part = strain ε).
    let a = [
        [1.0e-3, 2.0e-4, -3.0e-4],
        [5.0e-4, -7.0e-4, 1.0e-4],
        [-2.0e-4, 6.0e-4, 4.0e-4],
    ];
    let b = [1e-3, -2e-3, 5e-4];
    let mat = steel();
    let lam = mat.e * mat.nu / ((1.0 + mat.nu) * (1.0 - 2.0 * mat.nu));
    let mu = mat.g;
    let eps: [[f64; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (a[i][j] + a[j][i])));
    let tr = eps[0][0] + eps[1][1] + eps[2][2];
    let energy_density =
        0.5 * lam * tr * tr + mu * eps.iter().flatten().map(|e| e * e).sum::<f64>();
    for kind in KINDS {
        let model = patch(kind);
        let asm = assemble(&model, &AssemblySpec::default()).unwrap();
        let k = dense(&asm.k);
        let n = asm.dofs.n_dofs;
        let mut u = vec![0.0; n];
        for (p, node) in model.nodes.iter().enumerate() {
            for i in 0..3 {
                u[asm.dofs.dof(p, i).unwrap()] =
                    b[i] + (0..3).map(|j| a[i][j] * node.x[j]).sum::<f64>();
            }
        }
        let f: Vec<f64> = (0..n)
            .map(|r| (0..n).map(|c| k[(r, c)] * u[c]).sum())
            .collect();
        let fscale = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut interior = 0;
        for (p, node) in model.nodes.iter().enumerate() {
            if !on_boundary(node.x) {
                interior += 1;
                for i in 0..3 {
                    let fi = f[asm.dofs.dof(p, i).unwrap()];
                    assert!(
                        fi.abs() < 1e-11 * fscale,
                        "{kind:?}: interior node {} force {fi:e} (scale {fscale:e})",
                        node.id
                    );
                }
            }
        }
        assert!(interior >= 1);
        let energy = 0.5 * u.iter().zip(&f).map(|(a, b)| a * b).sum::<f64>();
        assert!(
            (energy - energy_density).abs() < 1e-11 * energy_density,
            "{kind:?}: energy {energy} vs {energy_density}"
        );
    }
}

#[test]
fn every_solid_k_is_symmetric_psd_with_six_rigid_modes_and_zero_rigid_force() {
    for kind in KINDS {
        let model = patch(kind);
        let asm = assemble(&model, &AssemblySpec::default()).unwrap();
        let k = dense(&asm.k);
        let n = k.nrows();
        let kmax = (0..n).map(|i| k[(i, i)]).fold(0.0f64, f64::max);
        for i in 0..n {
            for j in 0..n {
                assert!((k[(i, j)] - k[(j, i)]).abs() <= 1e-14 * kmax);
            }
        }
        // Rigid rotation about z through (0.3, 0.2, 0.1): u = θ × (x − c).
        let mut u = vec![0.0; n];
        for (p, node) in model.nodes.iter().enumerate() {
            let r = [node.x[0] - 0.3, node.x[1] - 0.2, node.x[2] - 0.1];
            u[asm.dofs.dof(p, 0).unwrap()] = -r[1];
            u[asm.dofs.dof(p, 1).unwrap()] = r[0];
        }
        let fmax = (0..n)
            .map(|r| (0..n).map(|c| k[(r, c)] * u[c]).sum::<f64>().abs())
            .fold(0.0, f64::max);
        assert!(
            fmax < 1e-11 * kmax,
            "{kind:?}: rigid rotation force {fmax:e}"
        );
        let mut ev = k.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
        ev.sort_by(f64::total_cmp);
        let top = ev[n - 1];
        let zeros = ev.iter().filter(|&&l| l.abs() < 1e-10 * top).count();
        assert_eq!(zeros, 6, "{kind:?}: {:?}", &ev[..8]);
        assert!(
            ev[0] > -1e-10 * top,
            "{kind:?}: negative eigenvalue {}",
            ev[0]
        );
        assert!(
            ev[6] > 1e-6 * top,
            "{kind:?}: 7th eigenvalue {} too small (mechanism)",
            ev[6]
        );
    }
}

#[test]
fn mass_totals_rho_v_for_both_lumpings_and_hrz_is_positive() {
    let rho = steel().rho;
    for kind in KINDS {
        let model = patch(kind);
        for (mass, tet10_mass) in [
            (MassKind::Lumped, Tet10MassRule::CalculixFourPoint),
            (MassKind::Consistent, Tet10MassRule::CalculixFourPoint),
            (MassKind::Consistent, Tet10MassRule::Exact),
        ] {
            let asm = assemble(
                &model,
                &AssemblySpec {
                    mass,
                    tet10_mass,
                    ..Default::default()
                },
            )
            .unwrap();
            let m = dense(&asm.m);
            let n = m.nrows();
            // Total mass in x: Σ over x-dofs of all entries.
            let xd: Vec<usize> = (0..model.nodes.len())
                .map(|p| asm.dofs.dof(p, 0).unwrap())
                .collect();
            let total: f64 = xd
                .iter()
                .flat_map(|&i| xd.iter().map(move |&j| (i, j)))
                .map(|(i, j)| m[(i, j)])
                .sum();
            assert!(
                (total - rho).abs() < 1e-12 * rho,
                "{kind:?} {mass:?}: total {total} vs ρV {rho}"
            );
            if mass == MassKind::Lumped {
                for i in 0..n {
                    assert!(m[(i, i)] > 0.0, "{kind:?}: lumped mass {i} not positive");
                    for j in 0..n {
                        assert!(i == j || m[(i, j)] == 0.0);
                    }
                }
            }
        }
    }
}
