//! Modal fibre stress and strain shapes of shell elements (format 1.5, SPEC §5.15): for each
//! mode, at every corner of every shell element, the membrane strain and the curvature in the
//! element frame, the top (+t/2 along the element normal) and bottom (−t/2) fibre strains
//! ε = ε_m ± (t/2) κ, plane-stress Hooke σ = Q_m ε_m ± (t/2) Q_b κ (membrane and bending
//! materials, Nastran MID1/MID2), ε_zz = −ν/(1−ν)(ε_xx + ε_yy), rotated to body axes and
//! averaged over the shell elements that share the node (each contributes its own top and
//! bottom fibre: the normal is each element's own, by the right-hand rule on its node order).
//! Voigt order xx yy zz xy yz zx, engineering shear strains, per unit modal coordinate, as the
//! solids' fields in [`crate::body::stress`].

use crate::body::stress::{FieldRequest, ModalFields, StressError};
use crate::fe::elements::shell::{plane_stress, ShellFrame, ShellProps};
use crate::fe::elements::{quad4_shell, tri3_shell, Xyz};
use crate::model::{ElementKind, Model, NodeIndex, Section};

/// Membrane strain and curvature (element frame) at one corner.
type CornerStrains = ([f64; 3], [f64; 3]);

/// Nodal fibre fields of the shell nodes, mode-major `values[(j*K + q)*6 + c]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ShellFields {
    /// Wanted nodes that shell elements carry, ascending.
    pub nodes: Vec<NodeIndex>,
    /// Top-fibre stress, when asked for.
    pub top_stress: Option<Vec<f64>>,
    /// Bottom-fibre stress, when asked for.
    pub bottom_stress: Option<Vec<f64>>,
    /// Top-fibre strain, when asked for.
    pub top_strain: Option<Vec<f64>>,
    /// Bottom-fibre strain, when asked for.
    pub bottom_strain: Option<Vec<f64>>,
}

/// Local symmetric tensor `t` (3×3) → body-axes Voigt (xx yy zz xy yz zx); `shear_factor` 2
/// for engineering strains, 1 for stresses.
fn to_body(t: &[[f64; 3]; 3], r: &[Xyz; 3], shear_factor: f64) -> [f64; 6] {
    let mut b = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            b[i][j] = (0..3)
                .map(|k| (0..3).map(|l| r[k][i] * t[k][l] * r[l][j]).sum::<f64>())
                .sum();
        }
    }
    [
        b[0][0],
        b[1][1],
        b[2][2],
        shear_factor * b[0][1],
        shear_factor * b[1][2],
        shear_factor * b[2][0],
    ]
}

/// Fibre strain and stress tensors (element frame) of one corner at height z.
fn fibre(
    em: &[f64; 3],
    k: &[f64; 3],
    z: f64,
    props: &ShellProps,
) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    let e: [f64; 3] = std::array::from_fn(|c| em[c] + z * k[c]);
    let (qm, num) = match props.membrane {
        Some(m) => (plane_stress(m.e, m.nu), m.nu),
        None => ([[0.0; 3]; 3], props.bending.map_or(0.0, |b| b.0.nu)),
    };
    let qb = props
        .bending
        .map_or([[0.0; 3]; 3], |(m, _)| plane_stress(m.e, m.nu));
    let s: [f64; 3] =
        std::array::from_fn(|i| (0..3).map(|j| qm[i][j] * em[j] + z * qb[i][j] * k[j]).sum());
    let ezz = -num / (1.0 - num) * (e[0] + e[1]);
    let strain = [
        [e[0], 0.5 * e[2], 0.0],
        [0.5 * e[2], e[1], 0.0],
        [0.0, 0.0, ezz],
    ];
    let stress = [[s[0], s[2], 0.0], [s[2], s[1], 0.0], [0.0, 0.0, 0.0]];
    (strain, stress)
}

/// Recover the fibre fields of `n_modes` modes at the `wanted` nodes that shells carry.
/// `displacement(node, mode)` gives the node's 6 components `[u v w θx θy θz]` (basic frame).
pub fn shell_fields(
    model: &Model,
    wanted: &[NodeIndex],
    n_modes: usize,
    displacement: &dyn Fn(NodeIndex, usize) -> [f64; 6],
    request: FieldRequest,
) -> Result<ShellFields, StressError> {
    let nn = model.nodes.len();
    let shell_section = |el: &crate::model::Element| {
        let p = el.property.and_then(|p| model.properties.get(p))?;
        match &p.section {
            Section::Shell(s) => Some((p, s)),
            _ => None,
        }
    };
    let is_shell = |el: &crate::model::Element| {
        matches!(el.kind, ElementKind::Quad4 | ElementKind::Tri3) && shell_section(el).is_some()
    };
    let super::stress::WantedSlots {
        is_wanted,
        slot,
        nodes,
    } = super::stress::wanted_slots(model, wanted, is_shell);
    // quadratic shells have no fibre recovery yet: an error, never shapes left out
    let quadratic = model.elements.iter().find(|el| {
        matches!(el.kind, ElementKind::Quad8 | ElementKind::Tri6)
            && shell_section(el).is_some()
            && el.nodes.iter().any(|&n| n < nn && is_wanted[n])
    });
    if let (Some(el), false) = (quadratic, request.is_empty()) {
        return Err(StressError::Element {
            file: model.element_origin(el.id),
            id: el.id,
            kind: el.kind,
            message: "stress/strain shapes of quadratic shells (S8/S8R/S6, CQUAD8/CTRIA6) are \
                      not implemented: build without stress/strain shapes, or mesh the part \
                      with S4/S3 (CQUAD4/CTRIA3)"
                .into(),
        });
    }
    let k = nodes.len();
    let size = n_modes * k * 6;
    let mut sums = [(); 4].map(|_| vec![0.0; size]); // top σ, bottom σ, top ε, bottom ε
    let mut count = vec![0u32; k];
    for (e, el) in model
        .elements
        .iter()
        .enumerate()
        .filter(|(_, e)| is_shell(e))
    {
        if !el.nodes.iter().any(|&n| n < nn && is_wanted[n]) {
            continue;
        }
        let fail = |message: String| StressError::Element {
            file: model.source.clone(),
            id: el.id,
            kind: el.kind,
            message,
        };
        if el.nodes.len() != el.kind.node_count() || el.nodes.iter().any(|&n| n >= nn) {
            return Err(fail("node list does not match the element kind".into()));
        }
        let (prop, section) = shell_section(el).ok_or_else(|| fail("no shell section".into()))?;
        let props = crate::fe::shell_section::shell_props(model, e, prop, section).map_err(fail)?;
        if model.drilling_membranes.contains(&e) {
            return Err(fail(
                "stress/strain shapes of CQUADR/CTRIAR (drilling membrane) are not implemented: \
                 build without stress/strain shapes"
                    .into(),
            ));
        }
        if props.general.is_some() {
            return Err(fail(
                "stress/strain shapes of laminate and plane-stress (PCOMP of several materials, \
                 MAT8, MAT2) shells are not implemented: build without stress/strain shapes"
                    .into(),
            ));
        }
        let x: Vec<Xyz> = el.nodes.iter().map(|&n| model.nodes[n].x).collect();
        let half = 0.5 * props.t;
        for j in 0..n_modes {
            let local = |n: NodeIndex, axes: &[Xyz; 3]| -> [f64; 6] {
                let d = displacement(n, j);
                let mut out = [0.0; 6];
                for i in 0..3 {
                    out[i] = (0..3).map(|c| axes[i][c] * d[c]).sum();
                    out[3 + i] = (0..3).map(|c| axes[i][c] * d[3 + c]).sum();
                }
                out
            };
            let (axes, corners): ([Xyz; 3], Vec<CornerStrains>) = if el.kind == ElementKind::Quad4 {
                let xa: [Xyz; 4] = std::array::from_fn(|a| x[a]);
                let f = ShellFrame::new(&xa).map_err(|e| fail(e.to_string()))?;
                let u: [[f64; 6]; 4] = std::array::from_fn(|a| local(el.nodes[a], &f.axes));
                (f.axes, quad4_shell::corner_strains(&f, &u).to_vec())
            } else {
                let xa: [Xyz; 3] = std::array::from_fn(|a| x[a]);
                let f = ShellFrame::new(&xa).map_err(|e| fail(e.to_string()))?;
                let u: [[f64; 6]; 3] = std::array::from_fn(|a| local(el.nodes[a], &f.axes));
                (f.axes, tri3_shell::corner_strains(&f, &props, &u).to_vec())
            };
            for (a, &n) in el.nodes.iter().enumerate() {
                if !is_wanted[n] {
                    continue;
                }
                let base = (j * k + slot[n]) * 6;
                let (em, kap) = &corners[a];
                for (side, z) in [(0, half), (1, -half)] {
                    let (strain, stress) = fibre(em, kap, z, &props);
                    let s = to_body(&stress, &axes, 1.0);
                    let e = to_body(&strain, &axes, 2.0);
                    for c in 0..6 {
                        sums[side][base + c] += s[c];
                        sums[2 + side][base + c] += e[c];
                    }
                }
            }
        }
        for &n in &el.nodes {
            if is_wanted[n] {
                count[slot[n]] += 1;
            }
        }
    }
    let [ts, bs, te, be] = sums.map(|mut v| {
        for (i, x) in v.iter_mut().enumerate() {
            *x /= f64::from(count[(i / 6) % k]);
        }
        v
    });
    Ok(ShellFields {
        nodes,
        top_stress: request.stress.then_some(ts),
        bottom_stress: request.stress.then_some(bs),
        top_strain: request.strain.then_some(te),
        bottom_strain: request.strain.then_some(be),
    })
}

/// The solids' fields and the shells' fibres as the file stores them (SPEC §5.15): the top
/// entry lists solid nodes with their solid value and shell-only nodes with their top fibre;
/// the bottom entry lists the shell-only nodes with their bottom fibre (`None` when there are
/// none). A node that solids and shells share keeps the solid value.
pub fn merge(
    solid: ModalFields,
    shell: &ShellFields,
    n_modes: usize,
) -> (ModalFields, Option<ModalFields>) {
    let shell_only: Vec<(usize, NodeIndex)> = shell
        .nodes
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, n)| solid.nodes.binary_search(n).is_err())
        .collect();
    if shell_only.is_empty() {
        return (solid, None);
    }
    // top: (node, Some(solid slot) | None = shell slot)
    let mut top: Vec<(NodeIndex, Result<usize, usize>)> = solid
        .nodes
        .iter()
        .enumerate()
        .map(|(q, &n)| (n, Ok(q)))
        .chain(shell_only.iter().map(|&(q, n)| (n, Err(q))))
        .collect();
    top.sort_unstable_by_key(|t| t.0);
    let (ks, kh, kt) = (solid.nodes.len(), shell.nodes.len(), top.len());
    let pick = |solid_v: Option<&Vec<f64>>, shell_v: Option<&Vec<f64>>| -> Option<Vec<f64>> {
        let (sv, hv) = (solid_v, shell_v?);
        let mut out = Vec::with_capacity(n_modes * kt * 6);
        for j in 0..n_modes {
            for (_, from) in &top {
                let s = match *from {
                    Ok(q) => &sv?[(j * ks + q) * 6..(j * ks + q) * 6 + 6],
                    Err(q) => &hv[(j * kh + q) * 6..(j * kh + q) * 6 + 6],
                };
                out.extend_from_slice(s);
            }
        }
        Some(out)
    };
    let bottom_of = |v: Option<&Vec<f64>>| -> Option<Vec<f64>> {
        let v = v?;
        let mut out = Vec::with_capacity(n_modes * shell_only.len() * 6);
        for j in 0..n_modes {
            for &(q, _) in &shell_only {
                out.extend_from_slice(&v[(j * kh + q) * 6..(j * kh + q) * 6 + 6]);
            }
        }
        Some(out)
    };
    let merged = ModalFields {
        nodes: top.iter().map(|t| t.0).collect(),
        stress: pick(solid.stress.as_ref(), shell.top_stress.as_ref()),
        strain: pick(solid.strain.as_ref(), shell.top_strain.as_ref()),
        centroid_fallbacks: solid.centroid_fallbacks,
    };
    let bottom = ModalFields {
        nodes: shell_only.iter().map(|t| t.1).collect(),
        stress: bottom_of(shell.bottom_stress.as_ref()),
        strain: bottom_of(shell.bottom_strain.as_ref()),
        centroid_fallbacks: 0,
    };
    (merged, Some(bottom))
}
