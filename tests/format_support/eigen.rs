//! The golden body of format 1.9: the 3-node chain with `eigen_residuals.bin` (SPEC §5.17).
use flexbody_reader::*;

use super::{body_3node_recipe, K3, M3};

/// The 3-node chain's normal modes with their eigenproblem record, as a dense solve returns
/// them: the closed-form vectors with eigenvalues off by a few ulps-of-a-solver (rigid
/// −2·10⁻¹³, the flexible ones +4·10⁻⁹ and −6·10⁻⁹ of 400 and 1200), and the residuals
/// computed here from K = k [1 −1 0; −1 2 −1; 0 −1 1], M = m I on the axial dofs by SPEC
/// §5.17's formula (s = median of K_ii/M_ii = k/m = 400): 5·10⁻⁸ for the rigid mode (its
/// 2·10⁻¹³·‖Mφ‖ against 10⁻⁸·s·‖Mφ‖), 10⁻¹¹ and 5·10⁻¹² for the flexible ones (|δλ|/λ). The
/// inertia count: 3 eigenvalues below 1200·(1 + 10⁻⁸).
pub fn body_3node_eigen_residuals() -> ReducedBody {
    let mut b = body_3node_recipe();
    b.header.title = "3-node chain with its eigenproblem's residuals (format 1.9)".into();
    let n = b.nodes.len();
    let omega2 = vec![-2e-13, K3 / M3 + 4e-9, 3.0 * K3 / M3 - 6e-9];
    let k = [[K3, -K3, 0.0], [-K3, 2.0 * K3, -K3], [0.0, -K3, K3]];
    let scale = K3 / M3;
    let residual: Vec<f64> = (0..3)
        .map(|j| {
            let phi: Vec<f64> = (0..3).map(|p| b.modes.shapes[(j * n + p) * 6]).collect();
            let kphi: Vec<f64> = (0..3)
                .map(|i| (0..3).map(|c| k[i][c] * phi[c]).sum())
                .collect();
            let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
            let r: Vec<f64> = (0..3).map(|i| kphi[i] - omega2[j] * M3 * phi[i]).collect();
            let mphi: Vec<f64> = phi.iter().map(|x| M3 * x).collect();
            norm(&r) / norm(&kphi).max(1e-8 * scale * norm(&mphi))
        })
        .collect();
    b.eigen_residuals = Some(EigenResiduals {
        problems: vec![EigenProblem {
            kind: EigenProblemKind::NormalModes,
            solver: EigenSolverKind::Dense,
            scale,
            inertia: Some(InertiaCount {
                shift: omega2[2] * (1.0 + 1e-8),
                below: 3,
            }),
            omega2,
            residual,
        }],
    });
    b.version = FORMAT_VERSION;
    b.version = version_for(&b);
    b
}
