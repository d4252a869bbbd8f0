//! The shear panel CSHEAR with its property PSHEAR (MSC QRG "CSHEAR", "PSHEAR"), into a
//! [`crate::model::DofMatrix`] on the translations of its four grids (basic frame).
//!
//! * `CSHEAR EID PID G1 G2 G3 G4`; `PSHEAR PID MID T NSM F1 F2` with a MAT1.
//! * Shear: the panel carries a constant shear strain γ, the bilinear quadrilateral's at its
//!   centre in the panel's mean plane (normal d₁₃ × d₂₄), with strain energy ½ G T PA γ² (PA
//!   the panel area, half the cross product of the diagonals). For a rectangle or a
//!   parallelogram this is the uniform shear flow of MSC's panel; a panel carries no normal
//!   stress and no bending.
//! * Extension: rods on the edges (QRG PSHEAR remark): on 1-2 and 3-4 each of area
//!   F1·T·PA/(L₁₂ + L₃₄) when F1 ≤ 1.01 (F1 = 1: the panel fully effective in that
//!   direction), else 0.5·F1·T²; on 2-3 and 4-1 alike with F2. Default 0: none.
//! * Mass: (ρ T + NSM)·PA, a quarter at each grid's translations (lumped).

use super::coord::{cross, sub, unit};
use super::fields::C;
use super::reading::Bulk;
use crate::import::error::ImportError;
use crate::import::text::IdMap;
use crate::model::geometry::norm;
use crate::model::{DofMatrix, Elasticity, NodeDof};

/// Reader of CSHEAR.
pub(super) fn cshear<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.other_ids.push((eid, g.card));
    let mut grids = [0; 4];
    for (i, n) in grids.iter_mut().enumerate() {
        *n = d.grid(g, 2 + i, g.id(2 + i, &format!("G{}", i + 1))?)?;
    }
    let mut seen = grids.to_vec();
    seen.sort_unstable();
    seen.dedup();
    if seen.len() < 4 {
        return Err(g.err(2, "a grid is listed twice: a shear panel needs four grids"));
    }
    d.shear.cshear.push((g.card, grids));
    Ok(())
}

/// Reader of PSHEAR.
pub(super) fn pshear<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let pid = g.id(0, "PID")?;
    d.properties.others.push((pid, g.card));
    let mid = g.id(1, "MID")?;
    let t = g.real(2)?.ok_or_else(|| g.err(2, "thickness T is blank"))?;
    let values = [
        t,
        g.real_or(3, 0.0)?,
        g.real_or(4, 0.0)?,
        g.real_or(5, 0.0)?,
    ];
    if !(t > 0.0 && t.is_finite()) || values.iter().any(|v| !v.is_finite()) {
        return Err(g.err(2, format!("T = {t}: a positive thickness is needed")));
    }
    if values[2] < 0.0 || values[3] < 0.0 {
        return Err(g.err(4, "F1 and F2 must be ≥ 0"));
    }
    d.shear.pshear.insert(pid, (mid, values, g.card));
    Ok(())
}

/// The panels into the model (module doc); `mids`: material id → index of the model's
/// materials (densities already times WTMASS).
pub(super) fn resolve(d: &mut Bulk, mids: &IdMap) -> Result<(), ImportError> {
    let wtmass = d.solution.wtmass;
    let mut out = Vec::new();
    for &(card, grids) in &d.shear.cshear {
        let g = C::new(card, d.files);
        let eid = g.id(0, "EID")?;
        let pid = match g.int(1)? {
            None => eid,
            Some(p) if p > 0 => p as u64,
            Some(p) => return Err(g.err(1, format!("bad property id {p}"))),
        };
        let &(mid, [t, nsm, f1, f2], _) = d.shear.pshear.get(&pid).ok_or_else(|| {
            g.err(
                1,
                format!("references PSHEAR {pid}, which the deck does not define"),
            )
        })?;
        let material = mids
            .get(mid)
            .map(|m| &d.b.model.materials[m])
            .ok_or_else(|| g.err(1, format!("PSHEAR {pid} references unknown material {mid}")))?;
        if !matches!(material.elasticity, Elasticity::Isotropic) {
            return Err(g.err(
                1,
                format!("PSHEAR {pid}: material {mid} is not a MAT1 (isotropic)"),
            ));
        }
        let x = grids.map(|n| d.b.model.nodes[n].x);
        let panel = Panel::new(x).ok_or_else(|| g.err(2, "the panel has no area"))?;
        let what = format!("CSHEAR {eid}");
        let mut stiffness = panel.shear(material.g * t, &grids);
        for (edges, f) in [([(0, 1), (2, 3)], f1), ([(1, 2), (3, 0)], f2)] {
            if f == 0.0 {
                continue;
            }
            let lengths = edges.map(|(i, j)| norm(sub(x[j], x[i])));
            let area = if f <= 1.01 {
                f * t * panel.area / (lengths[0] + lengths[1])
            } else {
                0.5 * f * t * t
            };
            for (i, j) in edges {
                rod(
                    material.e * area,
                    x[i],
                    x[j],
                    grids[i],
                    grids[j],
                    &mut stiffness,
                );
            }
        }
        let m = (material.rho * t + nsm * wtmass) * panel.area / 4.0;
        let mass = if m == 0.0 {
            Vec::new()
        } else {
            (grids.iter().flat_map(|&n| (0..3).map(move |c| dof(n, c))))
                .map(|p| (p, p, m))
                .collect()
        };
        out.push(DofMatrix {
            what,
            stiffness,
            mass,
            basic: true,
        });
    }
    d.b.model.dof_matrices.extend(out);
    Ok(())
}

fn dof(node: usize, component: u8) -> NodeDof {
    NodeDof { node, component }
}

/// A panel's mean plane: its area PA, in-plane axes e₁, e₂ and the corners in them.
struct Panel {
    area: f64,
    axes: [[f64; 3]; 2],
    local: [[f64; 2]; 4],
}

impl Panel {
    /// The plane of normal d₁₃ × d₂₄ through the corners' centroid; `None` without area.
    fn new(x: [[f64; 3]; 4]) -> Option<Panel> {
        let n = cross(sub(x[2], x[0]), sub(x[3], x[1]));
        let area = 0.5 * norm(n);
        let ez = unit(n).filter(|_| area > 0.0)?;
        let mid: [f64; 3] = std::array::from_fn(|i| 0.25 * x.iter().map(|p| p[i]).sum::<f64>());
        // e₁ along the mean direction of sides 1-2 and 4-3, projected on the plane
        let along = sub(
            std::array::from_fn(|i| x[1][i] + x[2][i]),
            std::array::from_fn(|i| x[0][i] + x[3][i]),
        );
        let e1 = unit(cross(cross(ez, along), ez))?;
        let e2 = cross(ez, e1);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let local = x.map(|p| [dot(sub(p, mid), e1), dot(sub(p, mid), e2)]);
        Some(Panel {
            area,
            axes: [e1, e2],
            local,
        })
    }

    /// Shear stiffness terms G T PA bbᵀ, γ = b·u with b from the bilinear map's derivatives at
    /// the centre: γ = Σᵢ (∂Nᵢ/∂y uᵢ + ∂Nᵢ/∂x vᵢ), uᵢ = e₁·Uᵢ, vᵢ = e₂·Uᵢ.
    fn shear(&self, gt: f64, grids: &[usize; 4]) -> Vec<(NodeDof, NodeDof, f64)> {
        const DXI: [f64; 4] = [-0.25, 0.25, 0.25, -0.25];
        const DETA: [f64; 4] = [-0.25, -0.25, 0.25, 0.25];
        let p = &self.local;
        let j = [
            [
                (0..4).map(|i| DXI[i] * p[i][0]).sum::<f64>(),
                (0..4).map(|i| DXI[i] * p[i][1]).sum::<f64>(),
            ],
            [
                (0..4).map(|i| DETA[i] * p[i][0]).sum::<f64>(),
                (0..4).map(|i| DETA[i] * p[i][1]).sum::<f64>(),
            ],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        // [∂N/∂x; ∂N/∂y] = J⁻¹ [∂N/∂ξ; ∂N/∂η]
        let dx: [f64; 4] = std::array::from_fn(|i| (j[1][1] * DXI[i] - j[0][1] * DETA[i]) / det);
        let dy: [f64; 4] = std::array::from_fn(|i| (-j[1][0] * DXI[i] + j[0][0] * DETA[i]) / det);
        let [e1, e2] = self.axes;
        let b: Vec<(NodeDof, f64)> = (0..4)
            .flat_map(|i| {
                (0..3u8).map(move |c| {
                    let c_ = usize::from(c);
                    (dof(grids[i], c), dy[i] * e1[c_] + dx[i] * e2[c_])
                })
            })
            .collect();
        let scale = gt * self.area;
        let mut out = Vec::with_capacity(b.len() * b.len());
        for &(p, bp) in &b {
            for &(q, bq) in &b {
                out.push((p, q, scale * bp * bq));
            }
        }
        out
    }
}

/// The terms of a rod of axial stiffness EA between corners at `xa`, `xb` (grids `a`, `b`).
fn rod(
    ea: f64,
    xa: [f64; 3],
    xb: [f64; 3],
    a: usize,
    b: usize,
    out: &mut Vec<(NodeDof, NodeDof, f64)>,
) {
    let d = sub(xb, xa);
    if let Some(e) = unit(d) {
        super::bush::axial_spring(ea / norm(d), e, a, b, out);
    }
}
