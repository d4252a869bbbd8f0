//! The golden body of format 1.6: normal modes with residual vectors, one of them removed as
//! dependent (SPEC §5.7, §5.12, §5.14), in closed form.
use flexbody_reader::*;

use super::{body_3node_recipe, hz};

/// The 3-node chain as a normal-modes build with residual vectors (format 1.6): the rigid mode
/// and the first elastic mode kept as eigenpairs (`--modes 2`), then the inertia-relief static
/// responses to 10 N along x at node 103 (`TIP`) and at node 101 (`TIP_LEFT`) added. With
/// f_p the load at node p, each response is r = Σ_{j elastic} φ_j (φ_jᵀ f_p)/ω_j²; beyond the
/// kept mode φ₂ both are multiples of φ₃, so `TIP_LEFT`'s is removed as dependent and `TIP`'s
/// becomes mode 3 = φ₃ (an exact eigenpair here, labelled `Attachment`, residual flag 1).
/// Counts: rigid 1, normal 1 + 2 residual vectors, removed 1 (1 + 3 − 1 = 3 modes).
/// Label share of mode 3 (SPEC §5.5 with T = [φ₁, φ₂, r]): φ₃ = (r − c φ₂)/d, c = φ₂ᵀf/ω₂²,
/// d = φ₃ᵀf/ω₃², so w = (c/d on φ₂, ‖r‖/d on r) and the residual share is
/// (c² + d²)/(2c² + d²) = 28/55. Accuracy band: the highest eigenmode kept, mode 2.
pub fn body_3node_residual_vectors() -> ReducedBody {
    let mut b = body_3node_recipe();
    b.header.title = "3-node chain, normal modes + residual vectors (closed form)".into();
    b.header.request.mode_count = Some(2);
    b.modes.labels[2] = ModeLabel::Attachment;
    b.method.counts = ModeCounts {
        rigid: 1,
        normal: 3,
        removed_dependent: 1,
        ..Default::default()
    };
    let n = b.nodes.len();
    let phi = |j: usize, p: usize| b.modes.shapes[(j * n + p) * 6];
    // generalized force φ_jᵀ f of 10 N along x at node p
    let load = |p: usize| -> Vec<f64> { (0..3).map(|j| 10.0 * phi(j, p)).collect() };
    let (tip, tip_left) = (load(2), load(0));
    let c = tip[1] / b.modes.omega2[1];
    let d = tip[2] / b.modes.omega2[2];
    b.label_shares = Some(vec![1.0, 1.0, (c * c + d * d) / (2.0 * c * c + d * d)]);
    b.modal_loads = Some(ModalLoads {
        loads: vec![
            ModalLoad {
                name: "TIP".into(),
                source: "--load TIP:103:10,0,0".into(),
                values: tip,
            },
            ModalLoad {
                name: "TIP_LEFT".into(),
                source: "--load TIP_LEFT:101:10,0,0".into(),
                values: tip_left,
            },
        ],
        residual: vec![0, 0, 1],
    });
    let band = hz(b.modes.omega2[1]);
    if let Some(r) = &mut b.recipe {
        r.options.modes = Some(2);
        r.options.loads = vec!["TIP:103:10,0,0".into(), "TIP_LEFT:101:10,0,0".into()];
        r.options.residual_vectors = Some("loads".into());
        r.accuracy_band.fmax_hz = band;
    }
    b.version = version_for(&b);
    b
}
