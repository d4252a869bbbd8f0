//! The 8-node hexahedron as ANSYS forms SOLID185's default (KEYOPT(2)=0): the B-bar method —
//! the selective reduced integration of the volumetric terms of Hughes ("Generalization of
//! selective integration procedures to anisotropic and nonlinear media", *IJNME* 15 (1980)
//! 1413) and Nagtegaal, Parks & Rice (*CMAME* 4 (1974) 153), which the MAPDL Theory Reference
//! cites for it (§13.185).
//!
//! On each of the 2×2×2 Gauss points the strain keeps its deviatoric part and takes the
//! element's mean dilatation: B̄ = B − B_vol + B̄_vol, with B_vol the rows of (1/3) ∂N_a/∂x_j
//! in the three normal strains and B̄_vol the same of the volume-averaged gradients
//! ḡ_a = (1/V) ∫ ∇N_a dV; K = Σ_q B̄_qᵀ D B̄_q w_q det J_q (Hughes 1980, eq. 4.13). The mass is
//! the compatible brick's on the same 2×2×2 points (the Theory Reference: "same as stiffness
//! matrix").
//!
//! Written with nodes 3 = 4 and 7 = 8 (ANSYS's wedge pattern of a collapsed brick), ANSYS forms
//! the brick as written with full 2×2×2 integration and without the volumetric average (shown
//! against ANSYS's element forces, docs/ansys.md), so this kind does too; any other repeated
//! node is refused.
//!
//! The volume average makes the element's strain no gradient of its displacement: the nodal
//! strain recovered for stresses is the compatible brick's (`nodal_gradients`), and there is no
//! integration-point form for general materials or preload (`stiffness_points` is `None`).

use super::element::{
    first, nodal_gradients, Element, ElementInput, ElementMatrices, MatricesError, ModePoint,
    NodalGradients, SolidRules,
};
use super::{check_solid_material, hex8, hex8r, map_point, ElementError, Isotropic, Xyz};
use crate::fe::quadrature;

/// Stiffness 24×24 of the B-bar brick (module doc; Hughes 1980, eq. 4.13).
pub fn stiffness(x: &[Xyz; 8], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    check_solid_material(mat)?;
    // V and ḡ_a = (1/V) ∫ ∇N_a dV, exact on 2×2×2 points for the trilinear brick
    let (_, mean) = hex8r::uniform_gradients(x)?;
    let (lam, mu) = mat.lame();
    let d = |i: usize, j: usize| -> f64 {
        match (i < 3, j < 3) {
            (true, true) => lam + if i == j { 2.0 * mu } else { 0.0 },
            (false, false) if i == j => mu,
            _ => 0.0,
        }
    };
    let mut k = vec![0.0; 24 * 24];
    for (p, q) in quadrature::cube(2).iter().enumerate() {
        let (_, g, det) = map_point(x, hex8::shape, &q.xi, p)?;
        let b = b_bar(&g, &mean);
        let w = q.w * det;
        // DB̄ (6×24), then K += B̄ᵀ (D B̄) w
        let mut db = [[0.0; 24]; 6];
        for (i, row) in db.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = (0..6).map(|m| d(i, m) * b[m][c]).sum();
            }
        }
        for r in 0..24 {
            for c in 0..24 {
                k[r * 24 + c] += w * (0..6).map(|m| b[m][r] * db[m][c]).sum::<f64>();
            }
        }
    }
    Ok(k)
}

/// B̄ (6×24; strains xx, yy, zz, xy, yz, zx) from the point's gradients `g` and the element's
/// mean gradients `mean`: the normal rows take (1/3)(ḡ_a,j − g_a,j) more in each column.
fn b_bar(g: &[Xyz; 8], mean: &[Xyz; 8]) -> [[f64; 24]; 6] {
    let mut b = [[0.0; 24]; 6];
    for a in 0..8 {
        let c = 3 * a;
        for j in 0..3 {
            let shift = (mean[a][j] - g[a][j]) / 3.0;
            for row in b.iter_mut().take(3) {
                row[c + j] += shift;
            }
            b[j][c + j] += g[a][j];
        }
        b[3][c] = g[a][1];
        b[3][c + 1] = g[a][0];
        b[4][c + 1] = g[a][2];
        b[4][c + 2] = g[a][1];
        b[5][c] = g[a][2];
        b[5][c + 2] = g[a][0];
    }
    b
}

/// Whether the element's node indices are the brick collapsed into ANSYS's wedge (3 = 4,
/// 7 = 8, the six others distinct); `Err` for another repeated node.
fn collapsed_wedge(nodes: &[usize]) -> Result<bool, MatricesError> {
    let distinct = |ids: &[usize]| {
        let mut v = ids.to_vec();
        v.sort_unstable();
        v.windows(2).all(|w| w[0] != w[1])
    };
    if distinct(nodes) {
        return Ok(false);
    }
    let kept = [nodes[0], nodes[1], nodes[2], nodes[4], nodes[5], nodes[6]];
    if nodes[2] == nodes[3] && nodes[6] == nodes[7] && distinct(&kept) {
        return Ok(true);
    }
    Err(MatricesError::Unsupported(
        "the B-bar brick with repeated nodes other than ANSYS's wedge (nodes 3 = 4 and 7 = 8)"
            .into(),
    ))
}

/// SOLID185's default brick as an [`Element`].
pub struct Hex8BbarElement;

impl Element for Hex8BbarElement {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<8>();
        let k = if collapsed_wedge(input.nodes)? {
            // the collapsed brick as written, fully integrated (module doc)
            input.stiffness(|| hex8::stiffness(&x, &input.iso))?
        } else {
            input.stiffness(|| stiffness(&x, &input.iso))?
        };
        let ms = hex8::scalar_mass(&x, input.iso.rho)?;
        Ok(input.solid(k, ms, 8, false))
    }

    fn stiffness_points(
        &self,
        _: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        // the volume average is no integration-point form (module doc)
        Ok(None)
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        let grads = nodal_gradients(&first(x), hex8::shape, &hex8::NODES, [0.0; 3])?;
        Ok(Some(grads))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brick() -> [Xyz; 8] {
        // a skewed, tapered brick: no parallelepiped, so the mean and centre gradients differ
        let mut x = hex8::NODES;
        for (a, p) in x.iter_mut().enumerate() {
            p[0] = 1.3 * p[0] + 0.2 * p[1] + 0.05 * a as f64;
            p[1] = 0.8 * p[1] + 0.1 * p[2] * p[0];
            p[2] = 0.6 * p[2] + 0.07 * (a % 3) as f64;
        }
        x
    }

    /// K is symmetric, the six rigid motions free of strain energy, and a uniform strain gives
    /// the stress it gives any consistent brick (B̄ u = B u when the strain is uniform).
    #[test]
    fn b_bar_brick_passes_rigid_motions_and_uniform_strain() {
        let x = brick();
        let mat = Isotropic::new(2.0e11, 0.3, 7800.0);
        let k = stiffness(&x, &mat).unwrap();
        let full = hex8::stiffness(&x, &mat).unwrap();
        let scale = k.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for r in 0..24 {
            for c in 0..24 {
                assert!((k[r * 24 + c] - k[c * 24 + r]).abs() < 1e-12 * scale);
            }
        }
        // rigid translations and rotations, then a uniform strain field u = E x
        let fields: [[[f64; 3]; 3]; 4] = [
            [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
            [[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]],
            [[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]],
            [[1.0, 0.3, 0.0], [0.3, -0.5, 0.2], [0.0, 0.2, 0.7]],
        ];
        for (f, e) in fields.iter().enumerate() {
            let u: Vec<f64> = (0..24)
                .map(|r| (0..3).map(|j| e[r % 3][j] * x[r / 3][j]).sum::<f64>())
                .collect();
            let ku: Vec<f64> = (0..24)
                .map(|r| (0..24).map(|c| k[r * 24 + c] * u[c]).sum())
                .collect();
            let kfu: Vec<f64> = (0..24)
                .map(|r| (0..24).map(|c| full[r * 24 + c] * u[c]).sum())
                .collect();
            let size = kfu.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1.0);
            for r in 0..24 {
                if f < 3 {
                    assert!(ku[r].abs() < 1e-9 * scale, "rigid field {f}: {}", ku[r]);
                } else {
                    assert!((ku[r] - kfu[r]).abs() < 1e-12 * size.max(scale));
                }
            }
        }
    }
}
