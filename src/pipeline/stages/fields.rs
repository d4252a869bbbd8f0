//! Stress shapes: modal stress/strain shapes at the stored nodes (when asked) — the solids'
//! nodal averages ([`modal_fields`]) with the shells' top fibre merged in, the shells' bottom
//! fibre apart ([`shell_fields`], format 1.5).

use crate::body::shell_stress::{merge, shell_fields};
use crate::body::stress::modal_fields_with_modes;
use crate::model::{Model, NodeIndex};
use crate::pipeline::plan::Plan;
use crate::pipeline::stages::node_shape;
use crate::pipeline::stages::Constrained;
use crate::pipeline::stages::FieldShapes;
use crate::pipeline::stages::ReducedBasis;
use crate::pipeline::stages::StoredNodes;
use crate::pipeline::{BuildError, BuildReport};

/// The stress shapes stage.
pub fn fields(
    plan: &Plan,
    model: &Model,
    constrained: &Constrained,
    basis: &ReducedBasis,
    stored: &StoredNodes,
    report: &mut BuildReport,
) -> Result<FieldShapes, BuildError> {
    let (dofs, phi) = (&constrained.assembled.dofs, &basis.phi);
    let request = plan.spec.fields;
    let u = |p: NodeIndex, j: usize| -> [f64; 3] {
        let s = node_shape(dofs, phi, p, j);
        [s[0], s[1], s[2]]
    };
    // ccx's C3D8I: its mode amplitudes are rows of Φ (interior dofs, basic frame)
    let amplitudes = |e: usize, j: usize| -> Option<[[f64; 3]; 3]> {
        let rows = dofs.interior_of(e)?;
        Some(std::array::from_fn(|m| {
            std::array::from_fn(|c| phi[(rows.start + 3 * m + c, j)])
        }))
    };
    let f = modal_fields_with_modes(model, &stored.nodes, phi.ncols(), &u, &amplitudes, request)?;
    // Shells: top fibre in the solids' entries, bottom fibre in the 1.5 entries.
    let u6 = |p: NodeIndex, j: usize| node_shape(dofs, phi, p, j);
    let sf = shell_fields(model, &stored.nodes, phi.ncols(), &u6, request)?;
    let (f, bottom) = merge(f, &sf, phi.ncols());
    if f.nodes.is_empty() {
        report.warnings.push(
            "stress/strain shapes asked for, but no stored node belongs to a solid or shell element: none written".into(),
        );
    }
    if f.centroid_fallbacks > 0 {
        report.warnings.push(format!(
            "stress/strain shapes: {} element corners have a non-positive Jacobian (strongly distorted elements); their centroid values were used there",
            f.centroid_fallbacks
        ));
    }
    Ok(FieldShapes {
        top: Some(f).filter(|f| !f.nodes.is_empty()),
        bottom,
    })
}
