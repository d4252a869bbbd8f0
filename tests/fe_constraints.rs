//! Rigid elements, constraints and displacement frames: an RBE2 spider on a bore makes its centre
//! node carry rigid motion exactly (zero strain), an RBE3 reference node recovers a rigid motion
//! of its independent nodes exactly, conflicting definitions are errors, and displacement frames
//! (Nastran CD) leave the frequencies unchanged.

use crate::common::{dense, generalized_eigenvalues, steel};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec, FeError, MassKind};
use flexbody::model::{
    CoordKind, CoordSystem, DofMask, Element, ElementKind, Model, Node, PointMass, Property,
    RigidElement, Section, Spc,
};

/// Hex8 ring (bore radius 0.01, outer 0.03, height 0.01; 16 × 2 × 2) plus a centre node at
/// (0, 0, 0.004) — deliberately off the mid-plane so rotations couple into translations.
/// Returns the model, the bore node indices and the centre node index.
fn ring() -> (Model, Vec<usize>, usize) {
    let mut model = Model {
        source: "ring".into(),
        ..Model::default()
    };
    model.materials.push(steel());
    model.properties.push(Property {
        id: 1,
        name: "P".into(),
        material: 0,
        section: Section::Solid,
    });
    let (nr, nt, nz) = (2, 16, 2);
    let id = |i: usize, j: usize, k: usize| i + (nr + 1) * ((j % nt) + nt * k);
    for k in 0..=nz {
        for j in 0..nt {
            for i in 0..=nr {
                let r = 0.01 + 0.02 * i as f64 / nr as f64;
                let t = 2.0 * std::f64::consts::PI * j as f64 / nt as f64;
                model.nodes.push(Node {
                    id: model.nodes.len() as u64 + 1,
                    x: [r * t.cos(), r * t.sin(), 0.01 * k as f64 / nz as f64],
                    displacement_frame: None,
                });
            }
        }
    }
    for k in 0..nz {
        for j in 0..nt {
            for i in 0..nr {
                let nodes = vec![
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                model.elements.push(Element {
                    id: model.elements.len() as u64 + 1,
                    kind: ElementKind::Hex8,
                    nodes,
                    property: Some(0),
                    orientation: None,
                });
            }
        }
    }
    let bore: Vec<usize> = (0..=nz)
        .flat_map(|k| (0..nt).map(move |j| id(0, j, k)))
        .collect();
    model.nodes.push(Node {
        id: 9999,
        x: [0.0, 0.0, 0.004],
        displacement_frame: None,
    });
    let centre = model.nodes.len() - 1;
    (model, bore, centre)
}

fn rigid(t: [f64; 3], th: [f64; 3], x: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let r = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
    [
        t[0] + th[1] * r[2] - th[2] * r[1],
        t[1] + th[2] * r[0] - th[0] * r[2],
        t[2] + th[0] * r[1] - th[1] * r[0],
    ]
}

#[test]
fn rbe2_spider_on_a_bore_carries_rigid_motion_of_the_centre_exactly() {
    let (mut model, bore, centre) = ring();
    model.rigid_elements.push(RigidElement::Rbe2 {
        id: 1,
        independent: centre,
        dependent: bore.clone(),
        dofs: DofMask::ALL,
    });
    let asm = assemble(&model, &AssemblySpec::default()).unwrap();
    assert_eq!(asm.dofs.count[centre], 6);
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec::default(),
    )
    .unwrap();
    assert_eq!(red.retained.len(), asm.dofs.n_dofs - 3 * bore.len());
    let (t, th) = ([1e-3, -2e-3, 0.5e-3], [0.01, -0.02, 0.03]);
    let xc = model.nodes[centre].x;
    // Reduced vector: the centre moves (t, θ); every retained ring node follows the same rigid motion.
    let mut ur = faer::Mat::<f64>::zeros(red.retained.len(), 1);
    for (j, &d) in red.retained.iter().enumerate() {
        let (node, c) = asm.dofs.node_of(d).unwrap();
        ur[(j, 0)] = if node == centre {
            if c < 3 {
                t[c]
            } else {
                th[c - 3]
            }
        } else {
            rigid(t, th, model.nodes[node].x, xc)[c]
        };
    }
    let u = red.expand(ur.as_ref());
    for &b in &bore {
        let want = rigid(t, th, model.nodes[b].x, xc);
        for c in 0..3 {
            let got = u[(asm.dofs.dof(b, c).unwrap(), 0)];
            assert!(
                (got - want[c]).abs() < 1e-15,
                "bore node {} dof {c}: {got} vs {}",
                model.nodes[b].id,
                want[c]
            );
        }
    }
    // Zero strain: K u = 0 relative to |K||u|.
    let k = dense(&asm.k);
    let n = k.nrows();
    let kmax = (0..n).map(|i| k[(i, i)]).fold(0.0, f64::max);
    let umax = (0..n).map(|i| u[(i, 0)].abs()).fold(0.0, f64::max);
    let f = (0..n)
        .map(|i| (0..n).map(|j| k[(i, j)] * u[(j, 0)]).sum::<f64>().abs())
        .fold(0.0, f64::max);
    assert!(f < 1e-12 * kmax * umax, "force {f:e}");
    // The reduced free body still has exactly six rigid modes.
    let kr = dense(&red.k);
    let mut ev = kr.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
    ev.sort_by(f64::total_cmp);
    let top = ev[ev.len() - 1];
    assert_eq!(ev.iter().filter(|&&l| l.abs() < 1e-10 * top).count(), 6);
}

#[test]
fn rbe3_reference_recovers_rigid_motion_of_weighted_bore_nodes() {
    let (mut model, bore, centre) = ring();
    let indep = bore
        .iter()
        .enumerate()
        .map(|(i, &b)| (b, 1.0 + (i % 3) as f64, DofMask::TRANSLATIONS))
        .collect();
    model.rigid_elements.push(RigidElement::Rbe3 {
        id: 7,
        reference: centre,
        ref_dofs: DofMask::ALL,
        independent: indep,
    });
    let asm = assemble(&model, &AssemblySpec::default()).unwrap();
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec::default(),
    )
    .unwrap();
    let (t, th) = ([2e-3, 1e-3, -1e-3], [-0.02, 0.01, 0.04]);
    let xc = model.nodes[centre].x;
    let mut ur = faer::Mat::<f64>::zeros(red.retained.len(), 1);
    for (j, &d) in red.retained.iter().enumerate() {
        let (node, c) = asm.dofs.node_of(d).unwrap();
        ur[(j, 0)] = rigid(t, th, model.nodes[node].x, xc)[c];
    }
    let u = red.expand(ur.as_ref());
    let want = [t[0], t[1], t[2], th[0], th[1], th[2]];
    for c in 0..6 {
        let got = u[(asm.dofs.dof(centre, c).unwrap(), 0)];
        assert!(
            (got - want[c]).abs() < 1e-13,
            "reference dof {c}: {got} vs {}",
            want[c]
        );
    }
    // RBE3 adds no stiffness: the reduced K is the ring's K (six rigid modes, same spectrum).
    assert_eq!(red.retained.len(), asm.dofs.n_dofs - 6);
}

#[test]
fn conflicting_constraints_are_errors_naming_the_entities() {
    let (model, bore, centre) = ring();
    // SPC on a dependent dof.
    let mut m1 = model.clone();
    m1.rigid_elements.push(RigidElement::Rbe2 {
        id: 3,
        independent: centre,
        dependent: bore.clone(),
        dofs: DofMask::ALL,
    });
    m1.spcs.push(Spc {
        node: bore[0],
        dofs: DofMask::TRANSLATIONS,
        set_id: 1,
    });
    let a = assemble(&m1, &AssemblySpec::default()).unwrap();
    let e = eliminate(&m1, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap_err();
    assert!(
        matches!(&e, FeError::Constraint { message, .. } if message.contains("rigid element 3")),
        "{e}"
    );
    // Dependent in two rigid elements.
    let mut m2 = model.clone();
    m2.rigid_elements.push(RigidElement::Rbe2 {
        id: 4,
        independent: centre,
        dependent: vec![bore[0]],
        dofs: DofMask::ALL,
    });
    m2.rigid_elements.push(RigidElement::Rbe2 {
        id: 5,
        independent: centre,
        dependent: vec![bore[0]],
        dofs: DofMask(1),
    });
    let a = assemble(&m2, &AssemblySpec::default()).unwrap();
    let e = eliminate(&m2, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap_err();
    assert!(e.to_string().contains("rigid elements 4 and 5"), "{e}");
    // A dependency cycle.
    let mut m3 = model;
    m3.rigid_elements.push(RigidElement::Rbe2 {
        id: 8,
        independent: bore[0],
        dependent: vec![bore[1]],
        dofs: DofMask::ALL,
    });
    m3.rigid_elements.push(RigidElement::Rbe2 {
        id: 9,
        independent: bore[1],
        dependent: vec![bore[0]],
        dofs: DofMask::ALL,
    });
    let a = assemble(&m3, &AssemblySpec::default()).unwrap();
    let e = eliminate(&m3, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap_err();
    assert!(e.to_string().contains("cycle"), "{e}");
}

#[test]
fn displacement_frames_leave_frequencies_unchanged_and_spcs_act_in_the_frame() {
    let (mut model, bore, centre) = ring();
    model.rigid_elements.push(RigidElement::Rbe2 {
        id: 1,
        independent: centre,
        dependent: bore.clone(),
        dofs: DofMask::ALL,
    });
    model.point_masses.push(PointMass {
        id: 2,
        node: centre,
        mass: 0.05,
        offset: [0.0, 0.01, 0.02],
        inertia: [[1e-5, 0.0, 0.0], [0.0, 2e-5, 0.0], [0.0, 0.0, 3e-5]],
    });
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        ..Default::default()
    };
    let freqs = |m: &Model| {
        let a = assemble(m, &spec).unwrap();
        let r = eliminate(m, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
        generalized_eigenvalues(&dense(&r.k), &dense(&r.m))
    };
    let base = freqs(&model);
    let mut framed = model.clone();
    framed.coord_systems.push(CoordSystem {
        id: 5,
        kind: CoordKind::Cylindrical,
        origin: [0.0, 0.0, -1.0],
        axes: [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    });
    framed.coord_systems.push(CoordSystem {
        id: 6,
        kind: CoordKind::Rectangular,
        origin: [0.0; 3],
        axes: [[0.6, 0.8, 0.0], [-0.8, 0.6, 0.0], [0.0, 0.0, 1.0]],
    });
    for (i, n) in framed.nodes.iter_mut().enumerate() {
        n.displacement_frame = Some(i % 2);
    }
    let rot = freqs(&framed);
    let top = base[base.len() - 1];
    for (a, b) in base.iter().zip(&rot) {
        assert!((a - b).abs() < 1e-12 * top + 1e-9 * a.abs(), "{a} vs {b}");
    }
    // A radial SPC in a cylindrical frame about z fixes the radial motion of the outer nodes:
    // rigid x-translation is then impossible, rotation about z stays free.
    let mut cyl = model.clone();
    cyl.coord_systems.push(CoordSystem {
        id: 9,
        kind: CoordKind::Cylindrical,
        origin: [0.0; 3],
        axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    });
    for (i, n) in cyl.nodes.iter_mut().enumerate() {
        let r = (n.x[0] * n.x[0] + n.x[1] * n.x[1]).sqrt();
        if (r - 0.03).abs() < 1e-12 {
            n.displacement_frame = Some(0);
            cyl.spcs.push(Spc {
                node: i,
                dofs: DofMask(0b001),
                set_id: 1,
            });
        }
    }
    let ev = freqs(&cyl);
    let top = ev[ev.len() - 1];
    let zeros = ev.iter().filter(|&&l| l.abs() < 1e-10 * top).count();
    assert_eq!(
        zeros,
        2,
        "free: rotation about z and translation along z; {:?}",
        &ev[..4]
    );
}
