//! Stress shapes end to end (issue 6): a tet10 cantilever block, root and tip faces attached by
//! RBE2 spiders, reduced by Craig–Bampton with stress and strain shapes stored. The static stress
//! of a tip load from the reduced body (modal superposition with the root spider held) must match
//! a direct static FE solution of the full model — the CB basis contains that static response
//! exactly — and the direct solution's bending stress must match beam theory away from the ends.

use std::path::PathBuf;

use faer::linalg::solvers::Solve;
use faer::Mat;
use flexbody::build::{build_model, BuildSpec};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec};
use flexbody::interface::{resolve_interfaces, SpiderKind};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::{Material, Model, NodeIndex};
use flexbody::solve::{sparse_ops, SparseLlt};
use flexbody::stress::{modal_fields, FieldRequest};
use flexbody_reader as file;

const L: f64 = 1.0;
const H: f64 = 0.1;
const P: f64 = 1000.0; // tip load, N, in −z

fn cantilever() -> Model {
    block(&BlockSpec {
        n: [20, 4, 4],
        size: [L, H, H],
        element: BlockElement::Tet10Six,
        material: Material::steel(),
    })
}

fn spec() -> BuildSpec {
    BuildSpec {
        modes: Some(6),
        invariants: file::InvariantSet::Rigid,
        fields: FieldRequest {
            stress: true,
            strain: true,
        },
        ..BuildSpec::new(
            PathBuf::from("cantilever (generated)"),
            file::Units::si(),
            &["X0", "XL"],
        )
    }
}

/// Direct static solution of the full model: root spider centre held, −P at the tip centre.
/// Returns the model with its spiders and the stress at every node (one "mode").
fn direct_static_stress() -> (Model, Vec<NodeIndex>, Vec<f64>, f64) {
    let mut model = cantilever();
    let ifaces = resolve_interfaces(
        &mut model,
        &["X0".to_string(), "XL".to_string()],
        SpiderKind::Rbe2,
    )
    .unwrap();
    let (root, tip) = (ifaces[0].nodes[0], ifaces[1].nodes[0]);
    let a = assemble(&model, &AssemblySpec::default()).unwrap();
    let red = eliminate(&model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    let n = red.retained.len();
    let mut reduced_of = vec![usize::MAX; a.dofs.n_dofs];
    for (r, &p) in red.retained.iter().enumerate() {
        reduced_of[p] = r;
    }
    let held: Vec<usize> = (0..6)
        .map(|c| reduced_of[a.dofs.dof(root, c).unwrap()])
        .collect();
    let free: Vec<usize> = (0..n).filter(|i| !held.contains(i)).collect();
    let kff = sparse_ops::submatrix(red.k.as_ref(), &free, &free).unwrap();
    let llt = SparseLlt::factor(kff.as_ref(), Some(3), faer::Par::Seq).unwrap();
    let tip_z = reduced_of[a.dofs.dof(tip, 2).unwrap()];
    let mut f = Mat::<f64>::zeros(free.len(), 1);
    let tip_row = free.iter().position(|&i| i == tip_z).unwrap();
    f[(tip_row, 0)] = -P;
    let uf = llt.solve(f.as_ref());
    let mut ur = Mat::<f64>::zeros(n, 1);
    for (k, &i) in free.iter().enumerate() {
        ur[(i, 0)] = uf[(k, 0)];
    }
    let u = red.expand(ur.as_ref());
    let tip_w = u[(a.dofs.dof(tip, 2).unwrap(), 0)];
    let disp = |p: NodeIndex, _j: usize| -> [f64; 3] {
        std::array::from_fn(|c| a.dofs.dof(p, c).map_or(0.0, |d| u[(d, 0)]))
    };
    let all: Vec<NodeIndex> = (0..model.nodes.len()).collect();
    let fields = modal_fields(
        &model,
        &all,
        1,
        &disp,
        FieldRequest {
            stress: true,
            strain: false,
        },
    )
    .unwrap();
    (model, fields.nodes, fields.stress.unwrap(), tip_w)
}

#[test]
fn cantilever_tip_load_stress_from_cb_modes_matches_direct_static_solution() {
    let out = build_model(&spec(), cantilever(), &mut |_| {}).unwrap();
    let dir = std::env::temp_dir().join(format!("flexbody-stress-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cantilever.flexbody");
    flexbody::write::write_reduced_body(&path, &out.body, &Default::default()).unwrap();
    let body = file::read(&path).unwrap();
    assert_eq!(body, out.body, "the reader returns what build made");
    let report = flexbody::check::check(&body, None).unwrap();
    assert!(report.passed(), "check: {:?}", report.items);
    let stress = body.stress_shapes.as_ref().expect("stress shapes stored");
    let strain = body.strain_shapes.as_ref().expect("strain shapes stored");
    let (nn, nm) = (body.nodes.len(), body.mode_count());
    // Every node of the block touches a tet; the two spider centres touch none.
    assert_eq!(stress.nodes.len(), nn - 2);
    assert_eq!(strain.nodes, stress.nodes);
    assert_eq!(stress.values.len(), nm * stress.nodes.len() * 6);

    // Reduced static problem: min ½qᵀΩ²q − gᵀq with the root centre's 6 dofs held (C q = 0):
    // [Ω² Cᵀ; C 0] [q; λ] = [g; 0].
    let pos_of = |id: u64| body.nodes.iter().position(|n| n.id == id).unwrap();
    let centre = |k: usize| {
        out.report.interfaces[k]
            .spider
            .as_ref()
            .unwrap()
            .centre_node_id
    };
    let (root, tip) = (pos_of(centre(0)), pos_of(centre(1)));
    let shape = |p: usize, j: usize, c: usize| body.modes.shapes[(j * nn + p) * 6 + c];
    let mut kkt = Mat::<f64>::zeros(nm + 6, nm + 6);
    let mut rhs = Mat::<f64>::zeros(nm + 6, 1);
    for j in 0..nm {
        kkt[(j, j)] = body.modes.omega2[j];
        rhs[(j, 0)] = -P * shape(tip, j, 2);
        for c in 0..6 {
            kkt[(nm + c, j)] = shape(root, j, c);
            kkt[(j, nm + c)] = shape(root, j, c);
        }
    }
    let q = kkt.as_ref().partial_piv_lu().solve(&rhs);
    let tip_w_modal: f64 = (0..nm).map(|j| q[(j, 0)] * shape(tip, j, 2)).sum();

    let (model, direct_nodes, direct, tip_w) = direct_static_stress();
    // Euler–Bernoulli + Timoshenko shear: w = PL³/3EI + PL/(κGA), κ = 5/6.
    let steel = Material::steel();
    let i = H.powi(4) / 12.0;
    let w_beam = P * L.powi(3) / (3.0 * steel.e * i) + P * L / (5.0 / 6.0 * steel.g * H * H);
    let tip_err = (tip_w_modal / tip_w - 1.0).abs();
    println!("tip deflection: modal {tip_w_modal:.6e}, direct {tip_w:.6e}, beam theory {:.6e}; modal vs direct {tip_err:.2e}", -w_beam);
    assert!(tip_err < 1e-6, "static response is in the CB span");
    assert!((-tip_w / w_beam - 1.0).abs() < 0.03, "FE vs beam theory");

    // Stress at the root face nodes: modal superposition vs direct.
    let stored_pos: Vec<usize> = stress.nodes.iter().map(|&p| p as usize).collect();
    let direct_at = |node: NodeIndex| -> &[f64] {
        let q = direct_nodes.binary_search(&node).unwrap();
        &direct[q * 6..q * 6 + 6]
    };
    let node_index_of_id = model.node_index_by_id();
    let root_face = &model.node_sets["X0"];
    let (mut max_err, mut max_ref) = (0.0f64, 0.0f64);
    for (k, &p) in stored_pos.iter().enumerate() {
        let node = node_index_of_id[&body.nodes[p].id];
        if !root_face.contains(&node) {
            continue;
        }
        let d = direct_at(node);
        for (c, direct_c) in d.iter().enumerate() {
            let modal: f64 = (0..nm)
                .map(|j| q[(j, 0)] * stress.values[(j * stress.nodes.len() + k) * 6 + c])
                .sum();
            max_err = max_err.max((modal - direct_c).abs());
            max_ref = max_ref.max(direct_c.abs());
        }
    }
    println!(
        "root-face stress: max |modal − direct| = {max_err:.3e} Pa of max |σ| {max_ref:.3e} Pa ({:.2e})",
        max_err / max_ref
    );
    assert!(max_ref > 1e6, "the root carries the bending stress");
    // The issue asks for 2%; the CB span holds the static response exactly, so ask for far more.
    assert!(
        max_err / max_ref < 1e-6,
        "modal stress at the root equals the direct one"
    );

    // Beam theory away from the ends: σ_xx = P (L − x)(z − H/2) / I at mid-span, top and bottom
    // fibres (average over the nodes across the width).
    let x_mid = 0.5 * L;
    for z in [0.0, H] {
        let vals: Vec<f64> = model
            .nodes
            .iter()
            .enumerate()
            .filter(|(_, n)| (n.x[0] - x_mid).abs() < 1e-9 && (n.x[2] - z).abs() < 1e-9)
            .map(|(p, _)| direct_at(p)[0])
            .collect();
        let mean = vals.iter().sum::<f64>() / vals.len() as f64;
        let beam = P * (L - x_mid) * (z - H / 2.0) / i;
        let err = (mean / beam - 1.0).abs();
        println!(
            "mid-span σ_xx at z = {z}: FE {mean:.4e} Pa, beam {beam:.4e} Pa ({err:.2e}, {} nodes)",
            vals.len()
        );
        assert!(err < 0.01, "bending stress vs beam theory");
    }
    std::fs::remove_dir_all(&dir).ok();
}
