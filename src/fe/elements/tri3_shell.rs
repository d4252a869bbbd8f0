//! 3-node flat shell triangle (CTRIA3, S3, S3R): DKT/DKMT plate bending, constant-strain membrane
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
//! * Mass: exact ∫N_aN_b dA = A/12 (1 + δ_ab), shell.rs.

use super::shell::{self, add_btdb, add_outer, ShellFrame, ShellProps};
use super::{ElementError, Xyz};

/// Interior 3-point rule on area coordinates (degree 2), weights 1/3 of the area.
const RULE: [[f64; 3]; 3] = [
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
];
/// Mid-side nodes 4, 5, 6 (indices 3, 4, 5) between corners (i, j).
const EDGES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

/// Area and gradients ∂L_i/∂(x, y) of the area coordinates of a triangle.
fn linear(p: &[[f64; 2]; 3]) -> (f64, [[f64; 2]; 3]) {
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
fn edge_factors(p: &[[f64; 2]; 3], props: &ShellProps) -> [f64; 3] {
    let ds = props.shear_modulus();
    let d = props.d_bending()[0][0];
    std::array::from_fn(|k| {
        let (i, j) = EDGES[k];
        let l2 = (p[j][0] - p[i][0]).powi(2) + (p[j][1] - p[i][1]).powi(2);
        if props.shear.is_some() && ds > 0.0 {
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
    let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    let inv = [
        [
            (a[1][1] * a[2][2] - a[1][2] * a[2][1]) / det,
            (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det,
            (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det,
        ],
        [
            (a[1][2] * a[2][0] - a[1][0] * a[2][2]) / det,
            (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det,
            (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det,
        ],
        [
            (a[1][0] * a[2][1] - a[1][1] * a[2][0]) / det,
            (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det,
            (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det,
        ],
    ];
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
    // Membrane (CST).
    let mem_dofs: Vec<usize> = (0..3).flat_map(|a| [6 * a, 6 * a + 1]).collect();
    let mut bm = [vec![0.0; 6], vec![0.0; 6], vec![0.0; 6]];
    for a in 0..3 {
        bm[0][2 * a] = gl[a][0];
        bm[1][2 * a + 1] = gl[a][1];
        bm[2][2 * a] = gl[a][1];
        bm[2][2 * a + 1] = gl[a][0];
    }
    add_btdb(&mut k, ND, &bm, &mem_dofs, &props.d_membrane(), area);
    // Bending (DKT).
    let db = props.d_bending();
    let (t, gam) = dkt_nodal_rotations(&f.p, &edge_factors(&f.p, props));
    let shear = props.shear.is_some().then(|| shear_field(&f.p, &gam));
    let ds = props.shear_modulus();
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
        if let Some(sf) = &shear {
            // γ at the point: (a₁ − c y, a₂ + c x), x = Σ L_a x_a
            let (x, y) = (
                (0..3).map(|a| l[a] * f.p[a][0]).sum::<f64>(),
                (0..3).map(|a| l[a] * f.p[a][1]).sum::<f64>(),
            );
            let gx: Vec<f64> = (0..9).map(|m| sf[0][m] - y * sf[2][m]).collect();
            let gy: Vec<f64> = (0..9).map(|m| sf[1][m] + x * sf[2][m]).collect();
            add_outer(&mut k, ND, &gx, &plate_dofs, ds * area / 3.0);
            add_outer(&mut k, ND, &gy, &plate_dofs, ds * area / 3.0);
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
    let a = linear(&f.p).0;
    let s: Vec<f64> = (0..9)
        .map(|i| a / 12.0 * if i % 4 == 0 { 2.0 } else { 1.0 })
        .collect();
    let m = shell::mass_matrix(&s, 3, props, lumped, &f.axes[2]);
    Ok((k, m))
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
        let (dm, db) = (props.d_membrane(), props.d_bending());
        let q = |d: &[[f64; 3]; 3], e: [f64; 3]| -> f64 {
            (0..3)
                .map(|i| (0..3).map(|j| e[i] * d[i][j] * e[j]).sum::<f64>())
                .sum()
        };
        for (eps, kap) in [
            ([1e-3, 0.0, 0.0], [0.0; 3]),
            ([0.0, 0.0, 3e-3], [0.0; 3]),
            ([0.0; 3], [0.5, 0.0, 0.0]),
            ([0.0; 3], [0.0, 0.3, 0.0]),
            ([0.0; 3], [0.0, 0.0, 0.7]),
            ([1e-3, 2e-3, -1e-3], [0.2, -0.4, 0.1]),
        ] {
            let u = constant_field(&TRI, eps, kap);
            let want = a * (q(&dm, eps) + q(&db, kap));
            let got = form(&k, &u, &u);
            assert!(
                (got - want).abs() < 1e-10 * want,
                "{eps:?} {kap:?}: {got} vs {want}"
            );
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
