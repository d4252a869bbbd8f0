//! 3-node flat shell triangle (CTRIA3, S3; S3R only read as S3 on request): DKT/DKMT plate bending, constant-strain membrane
//! and a drilling penalty; 6 dofs per node.
//!
//! ```text
//!      3            local frame (shell.rs): e₁ along 1→2, e₃ ∥ (x₂ − x₁) × (x₃ − x₁)
//!     / \           mid-side nodes 4 (1–2), 5 (2–3), 6 (3–1) of the DKT rotation field
//!    6   5          (internal: eliminated by the discrete Kirchhoff constraints)
//!   /     \
//!  1 ── 4 ── 2
//! ```
//! * Bending: the Discrete Kirchhoff Triangle, Batoz, Bathe & Ho, *IJNME* 15 (1980) 1771 —
//!   rotations β (βx = θy, βy = −θx) quadratic over the 6 nodes; at each mid-side node k of edge
//!   i–j (length l, tangent s, normal n) the tangential rotation follows the cubic deflection of
//!   the edge, β_s,k = −3/(2l)(w_j − w_i) − ¼(β_s,i + β_s,j), and the normal rotation is linear,
//!   β_n,k = ½(β_n,i + β_n,j). Curvatures κ = (βx,x, βy,y, βx,y + βy,x) are linear: 3-point
//!   rule, exact. Without transverse shear (Nastran PSHELL MID3 blank) this is the element.
//! * Transverse shear (the section has it: PSHELL MID3, PCOMP, Abaqus, Gmsh): the Discrete
//!   Kirchhoff–Mindlin Triangle, Katili, *IJNME* 36 (1993) 1859 — each edge a Timoshenko beam
//!   with constant shear γ_s,k: with X_k = (w_j − w_i)/l + ½(β_s,i + β_s,j) and
//!   φ_k = 12 D/(D_s l²) (= 2/(κ(1−ν)) (t/l)² isotropic), β_s,k = ½(β_s,i + β_s,j) −
//!   (3/2) X_k/(1 + φ_k) and γ_s,k = X_k φ_k/(1 + φ_k); the shear field inside is the
//!   lowest-order one with these tangential edge values, γ = (a₁ − c y, a₂ + c x), and
//!   Π_s = ½ ∫ D_s |γ|² dA (3-point rule, exact). φ_k → 0 for thin plates: the DKT again (no
//!   shear locking); constant-curvature states have X_k = 0, so the patch test still holds.
//!   Measured against MSC Nastran's CTRIA3 on PCOMP walls of t/L = 1–1.5: element strain
//!   energies within 5 % (DKT: 2–5×; tests/fe_nastran_shells_energy.rs).
//! * Membrane: constant-strain triangle (Turner et al. 1956); stiff in in-plane bending, which
//!   meshes of sheet-metal parts rarely load (the quadrilateral has the better membrane).
//! * Drilling: γ_d (θz − ω)² at 3 interior points (shell.rs), ω constant.
//! * Mass: lumped as shell.rs (A/3 per node); consistent: the deflection w with the BCIZ cubic
//!   through the nodal w and slopes (Bazeley, Cheung, Irons & Zienkiewicz 1965; the DKT itself
//!   has no interior w), membrane and rotations with ∫N_aN_b dA = A/12 (1 + δ_ab) (shell.rs). With
//!   a linear w the simply supported plate's mode (2,2) was +1.28 % at 20×20, now −0.47 %.

use super::element::{
    Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::shell::{self, add_btdb, add_outer, ShellFrame, ShellProps};
use super::{ElementError, Xyz};
use crate::fe::shell_section;
use crate::model::geometry::{det3, inverse3};

/// Interior 3-point rule on area coordinates (degree 2), weights 1/3 of the area.
const RULE: [[f64; 3]; 3] = [
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
];
/// Mid-side nodes 4, 5, 6 (indices 3, 4, 5) between corners (i, j).
const EDGES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

/// Area and gradients ∂L_i/∂(x, y) of the area coordinates of a triangle.
pub(crate) fn linear(p: &[[f64; 2]; 3]) -> (f64, [[f64; 2]; 3]) {
    let a2 = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    let mut g = [[0.0; 2]; 3];
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        g[i] = [(p[j][1] - p[k][1]) / a2, (p[k][0] - p[j][0]) / a2];
    }
    (a2 / 2.0, g)
}

/// Shear factors c_k = 1/(1 + φ_k) of the three edges, φ_k = 12 D/(D_s l_k²) (Katili 1993, eq.
/// for φ_k = 2/(κ(1−ν)) (t/l_k)² of an isotropic plate); all 1 (DKT) for a shear-rigid section.
/// An anisotropic section takes D = D11 and D_s = A_s,11 of its local axes (for an isotropic
/// one these are the D and D_s above; φ_k → 0 on thin plates either way).
fn edge_factors(p: &[[f64; 2]; 3], (d, ds, has_shear): (f64, f64, bool)) -> [f64; 3] {
    std::array::from_fn(|k| {
        let (i, j) = EDGES[k];
        let l2 = (p[j][0] - p[i][0]).powi(2) + (p[j][1] - p[i][1]).powi(2);
        if has_shear && ds > 0.0 {
            1.0 / (1.0 + 12.0 * d / (ds * l2))
        } else {
            1.0
        }
    })
}

/// DKT/DKMT: the 6-node rotation values (βx, βy at nodes 1–6) as a 12×9 matrix on [w θx θy] ×3,
/// and the three edges' constant tangential shear strains γ_s,k as rows on the same dofs.
///
/// Edge k = i–j as a Timoshenko beam (module doc): with X_k = (w_j − w_i)/l + ½(β_s,i + β_s,j)
/// the mid-side tangential rotation is β_s,k = ½(β_s,i + β_s,j) − (3/2) c_k X_k and the edge
/// shear γ_s,k = (1 − c_k) X_k; c_k = 1 is the DKT.
fn dkt_nodal_rotations(p: &[[f64; 2]; 3], c: &[f64; 3]) -> ([[f64; 9]; 12], [[f64; 9]; 3]) {
    let mut t = [[0.0; 9]; 12];
    let mut gam = [[0.0; 9]; 3];
    for a in 0..3 {
        // βx = θy, βy = −θx at the corners
        t[2 * a][3 * a + 2] = 1.0;
        t[2 * a + 1][3 * a + 1] = -1.0;
    }
    for (k, &(i, j)) in EDGES.iter().enumerate() {
        let d = [p[j][0] - p[i][0], p[j][1] - p[i][1]];
        let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let s = [d[0] / l, d[1] / l];
        let n = [s[1], -s[0]];
        let ck = c[k];
        // β_k = β_s s + β_n n; β_s,k and β_n,k as rows on the 9 dofs.
        let mut bs = [0.0; 9];
        let mut bn = [0.0; 9];
        bs[3 * j] -= 1.5 * ck / l;
        bs[3 * i] += 1.5 * ck / l;
        gam[k][3 * j] += (1.0 - ck) / l;
        gam[k][3 * i] -= (1.0 - ck) / l;
        for corner in [i, j] {
            // β at a corner: βx = θy, βy = −θx
            let corner_s = [(3 * corner + 2, s[0]), (3 * corner + 1, -s[1])];
            let corner_n = [(3 * corner + 2, n[0]), (3 * corner + 1, -n[1])];
            for (dof, v) in corner_s {
                bs[dof] += (0.5 - 0.75 * ck) * v;
                gam[k][dof] += 0.5 * (1.0 - ck) * v;
            }
            for (dof, v) in corner_n {
                bn[dof] += 0.5 * v;
            }
        }
        let row = 2 * (3 + k);
        for m in 0..9 {
            t[row][m] = bs[m] * s[0] + bn[m] * n[0];
            t[row + 1][m] = bs[m] * s[1] + bn[m] * n[1];
        }
    }
    (t, gam)
}

/// Transverse shear field γ(x, y) = (a₁ − c y, a₂ + c x) whose tangential component along each
/// edge is that edge's γ_s,k (lowest-order tangentially continuous field, as in MITC3): the
/// rows of (a₁, a₂, c) on the 9 plate dofs.
fn shear_field(p: &[[f64; 2]; 3], gam: &[[f64; 9]; 3]) -> [[f64; 9]; 3] {
    // A [a₁ a₂ c]ᵀ = γ_s, row k = [s_x, s_y, m_x s_y − m_y s_x] (m_k the edge midpoint)
    let a: [[f64; 3]; 3] = std::array::from_fn(|k| {
        let (i, j) = EDGES[k];
        let d = [p[j][0] - p[i][0], p[j][1] - p[i][1]];
        let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let s = [d[0] / l, d[1] / l];
        let m = [0.5 * (p[i][0] + p[j][0]), 0.5 * (p[i][1] + p[j][1])];
        [s[0], s[1], m[0] * s[1] - m[1] * s[0]]
    });
    let inv = inverse3(&a, det3(&a));
    std::array::from_fn(|r| std::array::from_fn(|m| (0..3).map(|k| inv[r][k] * gam[k][m]).sum()))
}

/// Gradients of the 6 quadratic shape functions at area coordinates `l`.
fn quadratic_gradients(l: &[f64; 3], gl: &[[f64; 2]; 3]) -> [[f64; 2]; 6] {
    let mut g = [[0.0; 2]; 6];
    for a in 0..3 {
        // N_a = L_a (2L_a − 1)
        for c in 0..2 {
            g[a][c] = (4.0 * l[a] - 1.0) * gl[a][c];
        }
    }
    for (k, &(i, j)) in EDGES.iter().enumerate() {
        // N = 4 L_i L_j
        for c in 0..2 {
            g[3 + k][c] = 4.0 * (l[i] * gl[j][c] + l[j] * gl[i][c]);
        }
    }
    g
}

/// Local 18×18 stiffness of the flat triangle.
fn local_stiffness(f: &ShellFrame<3>, props: &ShellProps) -> Result<Vec<f64>, ElementError> {
    const ND: usize = 18;
    let mut k = vec![0.0; ND * ND];
    let (area, gl) = linear(&f.p);
    if area.is_nan() || area <= 0.0 {
        return Err(ElementError::NonPositiveJacobian {
            det: 2.0 * area,
            point: 0,
        });
    }
    let sec = props.resultants(&f.axes, [f.p[1][0] - f.p[0][0], f.p[1][1] - f.p[0][1]])?;
    // Membrane (CST).
    let mem_dofs: Vec<usize> = (0..3).flat_map(|a| [6 * a, 6 * a + 1]).collect();
    let mut bm = [vec![0.0; 6], vec![0.0; 6], vec![0.0; 6]];
    for a in 0..3 {
        bm[0][2 * a] = gl[a][0];
        bm[1][2 * a + 1] = gl[a][1];
        bm[2][2 * a] = gl[a][1];
        bm[2][2 * a + 1] = gl[a][0];
    }
    add_btdb(&mut k, ND, &bm, &mem_dofs, &sec.a, area);
    // Bending (DKT).
    let db = sec.d;
    let (t, gam) = dkt_nodal_rotations(
        &f.p,
        &edge_factors(&f.p, (sec.d[0][0], sec.shear[0][0], sec.has_shear)),
    );
    let shear = sec.has_shear.then(|| shear_field(&f.p, &gam));
    let plate_dofs: Vec<usize> = (0..3)
        .flat_map(|a| [6 * a + 2, 6 * a + 3, 6 * a + 4])
        .collect();
    let gd = props.drill();
    let drill_dofs: Vec<usize> = (0..3).flat_map(|a| [6 * a, 6 * a + 1, 6 * a + 5]).collect();
    for l in &RULE {
        let g = quadratic_gradients(l, &gl);
        let mut bb = [vec![0.0; 9], vec![0.0; 9], vec![0.0; 9]];
        for m in 0..9 {
            for a in 0..6 {
                let (bx, by) = (t[2 * a][m], t[2 * a + 1][m]);
                bb[0][m] += g[a][0] * bx;
                bb[1][m] += g[a][1] * by;
                bb[2][m] += g[a][1] * bx + g[a][0] * by;
            }
        }
        add_btdb(&mut k, ND, &bb, &plate_dofs, &db, area / 3.0);
        if sec.coupled {
            shell::add_coupling(
                &mut k,
                ND,
                (&bm, &mem_dofs),
                (&bb, &plate_dofs),
                &sec.b,
                area / 3.0,
            );
        }
        if let Some(sf) = &shear {
            // γ at the point: (a₁ − c y, a₂ + c x), x = Σ L_a x_a
            let (x, y) = (
                (0..3).map(|a| l[a] * f.p[a][0]).sum::<f64>(),
                (0..3).map(|a| l[a] * f.p[a][1]).sum::<f64>(),
            );
            let gx: Vec<f64> = (0..9).map(|m| sf[0][m] - y * sf[2][m]).collect();
            let gy: Vec<f64> = (0..9).map(|m| sf[1][m] + x * sf[2][m]).collect();
            shell::add_shear(&mut k, ND, [&gx, &gy], &plate_dofs, &sec.shear, (area, 3.0));
        }
        if gd > 0.0 {
            let row: Vec<f64> = (0..3)
                .flat_map(|a| [0.5 * gl[a][1], -0.5 * gl[a][0], l[a]])
                .collect();
            add_outer(&mut k, ND, &row, &drill_dofs, gd * area / 3.0);
        }
    }
    Ok(k)
}

/// BCIZ cubic deflection basis (Bazeley, Cheung, Irons & Zienkiewicz, *Proc. Conf. Matrix
/// Methods in Structural Mechanics* (1965) 547): L₁, L₂, L₃ and L_i²L_j + ½L₁L₂L₃ (i ≠ j), with
/// their derivatives by L₁, L₂, L₃.
fn bciz_basis(l: &[f64; 3]) -> ([f64; 9], [[f64; 3]; 9]) {
    let mut f = [0.0; 9];
    let mut d = [[0.0; 3]; 9];
    let prod = l[0] * l[1] * l[2];
    let dprod = [l[1] * l[2], l[0] * l[2], l[0] * l[1]];
    for i in 0..3 {
        f[i] = l[i];
        d[i][i] = 1.0;
    }
    let mut k = 3;
    for i in 0..3 {
        for j in 0..3 {
            if i == j {
                continue;
            }
            f[k] = l[i] * l[i] * l[j] + 0.5 * prod;
            for m in 0..3 {
                d[k][m] = 0.5 * dprod[m];
            }
            d[k][i] += 2.0 * l[i] * l[j];
            d[k][j] += l[i] * l[i];
            k += 1;
        }
    }
    (f, d)
}

/// Consistent translational mass of the plate deflection with the BCIZ cubic w through the
/// nodal w, θx = w,y, θy = −w,x: 9×9 on [w θx θy] ×3, ∫ N_w N_wᵀ dA (per unit ρt), exact
/// (collapsed 4×4 Gauss rule, degree 7).
fn bciz_mass(p: &[[f64; 2]; 3]) -> Result<Vec<f64>, ElementError> {
    let (area, gl) = linear(p);
    // C: nodal conditions (rows) of the basis (columns); N_wᵀ = fᵀ C⁻¹
    let mut c = vec![0.0; 81];
    for a in 0..3 {
        let mut l = [0.0; 3];
        l[a] = 1.0;
        let (f, d) = bciz_basis(&l);
        for k in 0..9 {
            let gx: f64 = (0..3).map(|m| d[k][m] * gl[m][0]).sum();
            let gy: f64 = (0..3).map(|m| d[k][m] * gl[m][1]).sum();
            c[(3 * a) * 9 + k] = f[k];
            c[(3 * a + 1) * 9 + k] = gy;
            c[(3 * a + 2) * 9 + k] = -gx;
        }
    }
    let cinv = invert9(&c)?;
    let mut ff = [0.0; 81];
    let g = super::super::quadrature::gauss_legendre(4);
    for &(u, wu) in g {
        for &(v, wv) in g {
            let r = 0.5 * (1.0 + u);
            let s = 0.5 * (1.0 - r) * (1.0 + v);
            let w = wu * wv * 0.25 * (1.0 - r) * 2.0 * area;
            let (f, _) = bciz_basis(&[1.0 - r - s, r, s]);
            for i in 0..9 {
                for j in 0..9 {
                    ff[i * 9 + j] += w * f[i] * f[j];
                }
            }
        }
    }
    // M = C⁻ᵀ F C⁻¹
    let mut fc = [0.0; 81];
    for i in 0..9 {
        for j in 0..9 {
            fc[i * 9 + j] = (0..9).map(|k| ff[i * 9 + k] * cinv[k * 9 + j]).sum();
        }
    }
    Ok((0..81)
        .map(|ij| {
            let (i, j) = (ij / 9, ij % 9);
            (0..9).map(|k| cinv[k * 9 + i] * fc[k * 9 + j]).sum()
        })
        .collect())
}

/// Inverse of a 9×9 matrix (Gauss–Jordan, partial pivoting).
fn invert9(a: &[f64]) -> Result<Vec<f64>, ElementError> {
    let mut m = a.to_vec();
    let mut inv: Vec<f64> = (0..81)
        .map(|k| if k / 9 == k % 9 { 1.0 } else { 0.0 })
        .collect();
    let scale = m.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for c in 0..9 {
        let piv = (c..9)
            .max_by(|&i, &j| m[i * 9 + c].abs().total_cmp(&m[j * 9 + c].abs()))
            .unwrap_or(c);
        let pv = m[piv * 9 + c];
        if pv.is_nan() || pv.abs() <= 1e-14 * scale {
            return Err(ElementError::BadConstants(
                "degenerate shell triangle (singular cubic deflection basis)".into(),
            ));
        }
        for j in 0..9 {
            m.swap(c * 9 + j, piv * 9 + j);
            inv.swap(c * 9 + j, piv * 9 + j);
        }
        let d = m[c * 9 + c];
        for j in 0..9 {
            m[c * 9 + j] /= d;
            inv[c * 9 + j] /= d;
        }
        for r in 0..9 {
            if r != c {
                let f = m[r * 9 + c];
                if f != 0.0 {
                    for j in 0..9 {
                        m[r * 9 + j] -= f * m[c * 9 + j];
                        inv[r * 9 + j] -= f * inv[c * 9 + j];
                    }
                }
            }
        }
    }
    Ok(inv)
}

/// Basic-frame stiffness and mass (18×18 each, node-major `[u v w θx θy θz]`).
pub fn matrices(
    x: &[Xyz; 3],
    props: &ShellProps,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    props.check()?;
    let f = ShellFrame::new(x)?;
    let k = local_stiffness(&f, props)?;
    let k = shell::to_basic(&k, 3, &f.axes);
    Ok((k, mass(&f, props, lumped)?))
}

/// [`matrices`] of the CTRIAR: the same plate (DKT/DKMT) and mass, with the Allman membrane of
/// `drill_membrane` carrying θz in place of the CST membrane and its drilling penalty.
/// Homogeneous sections with a membrane only.
pub fn matrices_drilling(
    x: &[Xyz; 3],
    props: &ShellProps,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    props.check()?;
    let f = ShellFrame::new(x)?;
    let mut k = local_stiffness(&f, &props.plate_only())?;
    let membrane = super::drill_membrane::tri_stiffness(&f.p, &props.d_membrane(), 1.0)?;
    shell::add_drilling_membrane(&mut k, &membrane, 3);
    let k = shell::to_basic(&k, 3, &f.axes);
    Ok((k, mass(&f, props, lumped)?))
}

/// Basic-frame mass (18×18): the linear translations and rotary inertia, with the BCIZ cubic
/// deflection's consistent mass when not lumped (module doc).
fn mass(f: &ShellFrame<3>, props: &ShellProps, lumped: bool) -> Result<Vec<f64>, ElementError> {
    let a = linear(&f.p).0;
    let s: Vec<f64> = (0..9)
        .map(|i| a / 12.0 * if i % 4 == 0 { 2.0 } else { 1.0 })
        .collect();
    let mut m = shell::mass_matrix(&s, 3, props, lumped, &f.axes[2]);
    if !lumped {
        // The deflection's consistent mass with the BCIZ cubic w (module doc) replaces the
        // linear one: local frame, then to basic.
        let mut ml = vec![0.0; 18 * 18];
        let mut lin = shell::mass_matrix(&s, 3, props, false, &[0.0, 0.0, 1.0]);
        let wdofs = [2, 8, 14];
        for &i in &wdofs {
            for &j in &wdofs {
                lin[i * 18 + j] = 0.0;
            }
        }
        let mw = bciz_mass(&f.p)?;
        let plate: Vec<usize> = (0..3)
            .flat_map(|a| [6 * a + 2, 6 * a + 3, 6 * a + 4])
            .collect();
        for (p, &i) in plate.iter().enumerate() {
            for (q, &j) in plate.iter().enumerate() {
                ml[i * 18 + j] += props.mass_per_area() * mw[p * 9 + q];
            }
        }
        for (v, l) in ml.iter_mut().zip(&lin) {
            *v += l;
        }
        m = shell::to_basic(&ml, 3, &f.axes);
    }
    Ok(m)
}

/// Membrane strain (ε_x, ε_y, γ_xy) and curvature (κ_x, κ_y, κ_xy) at each corner, in the
/// element frame, from the local nodal values `[u v w θx θy θz]` (CST: constant membrane strain;
/// DKT/DKMT: the rotation field's gradient at the corner).
pub fn corner_strains(
    f: &ShellFrame<3>,
    props: &ShellProps,
    u: &[[f64; 6]; 3],
) -> [([f64; 3], [f64; 3]); 3] {
    let (_, gl) = linear(&f.p);
    let mut em = [0.0; 3];
    for a in 0..3 {
        em[0] += gl[a][0] * u[a][0];
        em[1] += gl[a][1] * u[a][1];
        em[2] += gl[a][1] * u[a][0] + gl[a][0] * u[a][1];
    }
    let shear = (
        props.d_bending()[0][0],
        props.shear_modulus(),
        props.shear.is_some(),
    );
    let (t, _) = dkt_nodal_rotations(&f.p, &edge_factors(&f.p, shear));
    let plate: Vec<f64> = (0..3).flat_map(|a| [u[a][2], u[a][3], u[a][4]]).collect();
    // β at the 6 DKT nodes
    let beta: Vec<f64> = (0..12)
        .map(|r| (0..9).map(|m| t[r][m] * plate[m]).sum())
        .collect();
    std::array::from_fn(|c| {
        let mut l = [0.0; 3];
        l[c] = 1.0;
        let g = quadratic_gradients(&l, &gl);
        let mut k = [0.0; 3];
        for a in 0..6 {
            let (bx, by) = (beta[2 * a], beta[2 * a + 1]);
            k[0] += g[a][0] * bx;
            k[1] += g[a][1] * by;
            k[2] += g[a][1] * bx + g[a][0] * by;
        }
        (em, k)
    })
}

/// The 3-node flat shell (DKT/DKMT + CST, or the drilling membrane) as an [`Element`].
pub struct Tri3Element;

impl Element for Tri3Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let (p, drilling) = shell_section::flat_shell_props(input)?;
        let x = input.coords::<3>();
        let (k, m) = if drilling {
            matrices_drilling(&x, &p, input.lumped())
        } else {
            matrices(&x, &p, input.lumped())
        }?;
        Ok(ElementMatrices::nodal(6, k, m))
    }

    fn stiffness_points(
        &self,
        _: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(None)
    }

    fn nodal_gradients(&self, _: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::super::shell::test_util::*;
    use super::super::Isotropic;
    use super::*;

    fn steel_plate(t: f64) -> ShellProps {
        ShellProps::isotropic(t, Isotropic::new(210e9, 0.3, 7850.0))
    }

    const TRI: [Xyz; 3] = [[0.1, -0.2, 0.0], [2.0, 0.3, 0.0], [0.7, 1.6, 0.0]];

    /// A coupled anisotropic section (B ≠ 0, material axis 25° from G1→G2) passes the patch test
    /// with the coupling energy on the triangle.
    #[test]
    fn tri3_shell_laminate_patch_test_with_coupling_and_material_axis() {
        use crate::model::ShellMaterialAxis;
        let side = [TRI[1][0] - TRI[0][0], TRI[1][1] - TRI[0][1]];
        let props = coupled_section(0.02, ShellMaterialAxis::FromSide12 { theta_deg: 25.0 });
        let (k, _) = matrices(&TRI, &props, false).unwrap();
        let a = linear(&[
            [TRI[0][0], TRI[0][1]],
            [TRI[1][0], TRI[1][1]],
            [TRI[2][0], TRI[2][1]],
        ])
        .0;
        let psi = side[1].atan2(side[0]) + 25f64.to_radians();
        patch_energy_general(&k, &TRI, a, &props, psi, 1e-10);
    }

    #[test]
    fn tri3_shell_rigid_motions_cost_no_energy_in_any_orientation() {
        let x = [[0.1, -0.2, 0.3], [2.0, 0.3, -0.4], [0.7, 1.6, 1.1]];
        let (k, _) = matrices(&x, &steel_plate(0.01), false).unwrap();
        for mode in 0..6 {
            let u = rigid(&x, mode);
            assert!(
                residual(&k, &u) < 1e-12,
                "mode {mode}: {}",
                residual(&k, &u)
            );
        }
    }

    #[test]
    fn tri3_shell_patch_test_constant_strain_and_curvature() {
        let props = steel_plate(0.02);
        let (k, _) = matrices(&TRI, &props, false).unwrap();
        let f = ShellFrame::new(&TRI).unwrap();
        let a = linear(&f.p).0;
        patch_energy(&k, &TRI, a, &props, 1e-10);
    }

    /// The BCIZ deflection mass integrates rigid plate motions exactly: w = 1 gives ρtA,
    /// w = y (θx = 1) gives ρt ∫y² dA, w = x (θy = −1) gives ρt ∫x² dA.
    #[test]
    fn tri3_shell_consistent_deflection_mass_is_exact_for_rigid_motions() {
        let props = steel_plate(0.02);
        let (_, m) = matrices(&TRI, &props, false).unwrap();
        let f = ShellFrame::new(&TRI).unwrap();
        let a = linear(&f.p).0;
        let mt = props.mass_per_area();
        // second moments of the triangle about the origin of the basic frame (z = 0 plane)
        let sec = |i: usize, j: usize| {
            a / 12.0
                * ((0..3).map(|k| TRI[k][i] * TRI[k][j]).sum::<f64>()
                    + (0..3).map(|k| TRI[k][i]).sum::<f64>()
                        * (0..3).map(|k| TRI[k][j]).sum::<f64>())
        };
        let mut u = vec![0.0; 18];
        for k in 0..3 {
            u[6 * k + 2] = 1.0;
        }
        assert!((form(&m, &u, &u) - mt * a).abs() < 1e-12 * mt * a);
        for (c, sign, i) in [(3, 1.0, 1), (4, -1.0, 0)] {
            let mut u = vec![0.0; 18];
            for k in 0..3 {
                u[6 * k + 2] = TRI[k][i];
                u[6 * k + c] = sign;
            }
            // translational part exact; the rotary part adds ρt³/12 · A
            let want = mt * sec(i, i) + props.rotary_per_area() * a;
            let got = form(&m, &u, &u);
            assert!((got - want).abs() < 1e-10 * want, "{got} vs {want}");
        }
    }

    /// DKMT: thin sections give the DKT (φ_k → 0), thick ones are softer (transverse shear).
    #[test]
    fn tri3_shell_dkmt_tends_to_dkt_when_thin_and_is_softer_when_thick() {
        for (t, thin) in [(1e-4, true), (0.5, false)] {
            let props = steel_plate(t);
            let dkt = ShellProps {
                shear: None,
                ..props
            };
            let (k, _) = matrices(&TRI, &props, false).unwrap();
            let (k0, _) = matrices(&TRI, &dkt, false).unwrap();
            // a non-Kirchhoff state: one corner's deflection
            let mut u = vec![0.0; 18];
            u[2] = 1e-3;
            let (e, e0) = (form(&k, &u, &u), form(&k0, &u, &u));
            if thin {
                assert!((e - e0).abs() < 1e-6 * e0, "{e} vs {e0}");
            } else {
                assert!(e < 0.9 * e0, "{e} vs {e0}");
            }
        }
    }

    #[test]
    fn tri3_shell_single_element_has_six_zero_modes() {
        let (k, _) = matrices(&TRI, &steel_plate(0.01), false).unwrap();
        let n = 18;
        let mat = faer::Mat::<f64>::from_fn(n, n, |i, j| k[i * n + j]);
        let ev = mat.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
        let top = ev.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let zeros = ev.iter().filter(|v| v.abs() < 1e-10 * top).count();
        assert_eq!(zeros, 6, "{ev:?}");
    }
}
