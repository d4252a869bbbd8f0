//! 4-node flat shell quadrilateral (CQUAD4, S4; S4R only read as S4 on request): MITC4 plate bending and transverse shear
//! with an incompatible-mode membrane and a drilling penalty; 6 dofs per node.
//!
//! ```text
//!  4 ─────── 3      η        local frame (shell.rs): e₃ ∥ (x₃ − x₁) × (x₄ − x₂), e₁ along the
//!  │    D    │      ↑        mean of edges 1→2 and 4→3; nodes projected onto the mean plane,
//!  C         A      └─► ξ    warping heights h_a carried by rigid links (shell::apply_warping).
//!  │    B    │               A, B, C, D: MITC4 tying points of the transverse shear.
//!  1 ─────── 2
//! ```
//! * Bending/shear: MITC4, Dvorkin & Bathe, *Eng. Comput.* 1 (1984) 77; Bathe & Dvorkin,
//!   *IJNME* 21 (1985) 367 — bilinear w and β (βx = θy, βy = −θx), curvatures at 2×2 Gauss
//!   points; covariant shear strains e_ξ = w,ξ + β·x,ξ tied at B (0,−1), D (0,1) and
//!   e_η = w,η + β·x,η at C (−1,0), A (1,0), interpolated e_ξ = ½(1−η)e_ξᴮ + ½(1+η)e_ξᴰ,
//!   e_η = ½(1−ξ)e_ηᶜ + ½(1+ξ)e_ηᴬ, and γ = J⁻¹ e (J rows x,ξ and x,η). Free of shear
//!   locking; passes the constant-curvature patch test on distorted meshes.
//! * Membrane: bilinear u, v plus the incompatible modes 1−ξ², 1−η² (Wilson's Q6) with Taylor's
//!   correction (QM6: mode derivatives through J₀ at the centre, scaled by det J₀/det J; Taylor,
//!   Beresford & Wilson, *IJNME* 10 (1976) 1211), condensed statically; passes the membrane
//!   patch test on any quadrilateral and is free of in-plane shear locking in bending.
//! * Residual bending flexibility (a Nastran deck's CQUAD4, `Quad4Form::NastranQuad4`):
//!   MacNeal's QUAD4 (R. H. MacNeal, *Computers & Structures* 8 (1978) 175; *Finite Elements:
//!   Their Design and Performance* (1994) §6) adds to the transverse shear compliance the
//!   bending flexibility the element lacks. With its shear constant along a direction (as
//!   MITC4's e_ξ is along ξ), the element bends under a linearly varying moment as a
//!   Timoshenko beam element with one-point shear, whose end deflection lacks V ℓ³/(12 D) of
//!   the cubic beam's; adding ℓ²/(12 D) to the shear compliance restores it exactly:
//!   S'_k = 1/(1/S_k + ℓ_k²/(12 D_k)) for k = ξ, η, ℓ_k the distance between the midpoints of
//!   the element's opposite edges along k, S_k = u_kᵀ A_s u_k the shear rigidity and
//!   D_k = vᵀ D v (v = (c², s², 2cs), u_k = (c, s)) the cylindrical bending rigidity along u_k
//!   (a laminate's D included; its coupling B is left out). Shear-rigid sections (PSHELL MID3
//!   blank) keep the ℓ²/(12 D) term alone, as MSC's QUAD4 does. Applied by scaling the
//!   covariant strains e_k by √(S'_k/S_k): exact for rectangles, the same scaling on skewed
//!   elements. Rigid motions, constant curvatures (patch test) and converged meshes (ℓ → 0)
//!   are unchanged; one element over a cantilever's length bends as the beam does.
//! * ANSYS SHELL181 with KEYOPT(3)=2 (an archive's, `ShellProps::quad4`): the same MITC4 + QM6
//!   element with ANSYS's two changes, read from ANSYS's own element forces (docs/ansys.md):
//!   the transverse shear rigidity scaled by s = 1/(1 + A/(160 000 t²)) (A the element's area,
//!   t its thickness) and the drilling penalty γ_d = s·k G t/200 at the 2×2 points. Its
//!   degenerate triangle (K = L) is this element with nodes 3 and 4 at one point, as ANSYS's
//!   element energies show it (docs/ansys.md): the three nodes' values span the affine fields,
//!   so the membrane is the constant-strain triangle (Taylor's modes carry no energy at
//!   constant strain) and the curvatures are constant; MITC4's e_ξ tied at D, on the
//!   collapsed side, is zero there (x,ξ = 0, w₃ = w₄), and A is the triangle's area (det J
//!   vanishes only on that side, not at the 2×2 points).
//! * Drilling: γ_d (θz − ω)² at the 2×2 points (shell.rs), ω from the bilinear u, v.
//! * Warped elements: the flat projected element with rigid links to the real nodes (shell.rs);
//!   exact for rigid motions, approximate (as every flat-facet shell) for strong warping.
//! * Mass: 2×2 Gauss ∫N_aN_b dA (exact for a parallelogram), shell.rs.

use super::element::{
    Element, ElementInput, ElementMatrices, MatricesError, ModePoint, NodalGradients, SolidRules,
};
use super::shell::{self, add_btdb, add_outer, Quad4Form, Resultants, ShellFrame, ShellProps};
use super::{ElementError, Xyz};
use crate::fe::shell_section;

const G: f64 = 0.577_350_269_189_625_8; // 1/√3
const GAUSS: [[f64; 2]; 4] = [[-G, -G], [G, -G], [G, G], [-G, G]];
const REF: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Bilinear shape functions and their ξ, η derivatives.
fn shape(xi: f64, eta: f64) -> ([f64; 4], [[f64; 2]; 4]) {
    let mut n = [0.0; 4];
    let mut d = [[0.0; 2]; 4];
    for a in 0..4 {
        let (sa, ta) = (REF[a][0], REF[a][1]);
        n[a] = 0.25 * (1.0 + sa * xi) * (1.0 + ta * eta);
        d[a] = [0.25 * sa * (1.0 + ta * eta), 0.25 * ta * (1.0 + sa * xi)];
    }
    (n, d)
}

/// Jacobian J (rows x,ξ and x,η), its determinant and inverse at (ξ, η).
fn jacobian(p: &[[f64; 2]; 4], d: &[[f64; 2]; 4]) -> ([[f64; 2]; 2], f64, [[f64; 2]; 2]) {
    let mut j = [[0.0; 2]; 2];
    for a in 0..4 {
        for k in 0..2 {
            for i in 0..2 {
                j[k][i] += d[a][k] * p[a][i];
            }
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let inv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    (j, det, inv)
}

/// Physical derivatives [N,x N,y] = J⁻¹ [N,ξ N,η].
fn grad(inv: &[[f64; 2]; 2], d: &[f64; 2]) -> [f64; 2] {
    [
        inv[0][0] * d[0] + inv[0][1] * d[1],
        inv[1][0] * d[0] + inv[1][1] * d[1],
    ]
}

/// Covariant transverse shear strain e_k = w,k + βx x,k + βy y,k (k = ξ or η) at a tying point,
/// as a row on the 12 plate dofs [w θx θy] per node.
fn covariant_shear(p: &[[f64; 2]; 4], xi: f64, eta: f64, k: usize) -> [f64; 12] {
    let (n, d) = shape(xi, eta);
    let (j, _, _) = jacobian(p, &d);
    let (xk, yk) = (j[k][0], j[k][1]);
    let mut row = [0.0; 12];
    for a in 0..4 {
        row[3 * a] = d[a][k];
        // βx = θy, βy = −θx
        row[3 * a + 1] = -n[a] * yk;
        row[3 * a + 2] = n[a] * xk;
    }
    row
}

/// One 2×2 Gauss point of the flat element: weight det J (the Gauss weights are 1), shape
/// values, J⁻¹, physical gradients and the membrane strain rows (ε_x, ε_y, γ_xy) of the
/// compatible dofs `bc` ([u1 v1 u2 v2 …], 3 × 8) and of the incompatible modes `bi`
/// ([a1u a1v a2u a2v], 3 × 4; QM6, module doc).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MembranePoint {
    /// det J.
    pub w: f64,
    /// N_a.
    pub n: [f64; 4],
    /// J⁻¹.
    pub inv: [[f64; 2]; 2],
    /// [N_a,x N_a,y].
    pub g: [[f64; 2]; 4],
    /// Compatible membrane strain rows.
    pub bc: [Vec<f64>; 3],
    /// Incompatible-mode membrane strain rows.
    pub bi: [Vec<f64>; 3],
}

/// The four Gauss points of the projected element `p` (module doc).
pub(crate) fn membrane_points(p: &[[f64; 2]; 4]) -> Result<Vec<MembranePoint>, ElementError> {
    let (_, d0) = shape(0.0, 0.0);
    let (_, det0, inv0) = jacobian(p, &d0);
    let mut out = Vec::with_capacity(4);
    for (gp, &[xi, eta]) in GAUSS.iter().enumerate() {
        let (n, d) = shape(xi, eta);
        let (_, det, inv) = jacobian(p, &d);
        if det.is_nan() || det <= 0.0 {
            return Err(ElementError::NonPositiveJacobian { det, point: gp });
        }
        let g: [[f64; 2]; 4] = std::array::from_fn(|a| grad(&inv, &d[a]));
        let mut bc = [vec![0.0; 8], vec![0.0; 8], vec![0.0; 8]];
        for a in 0..4 {
            bc[0][2 * a] = g[a][0];
            bc[1][2 * a + 1] = g[a][1];
            bc[2][2 * a] = g[a][1];
            bc[2][2 * a + 1] = g[a][0];
        }
        // Incompatible modes P1 = 1 − ξ², P2 = 1 − η² via J₀ (QM6).
        let s = det0 / det;
        let pg = [
            grad(&inv0, &[-2.0 * xi, 0.0]),
            grad(&inv0, &[0.0, -2.0 * eta]),
        ];
        let mut bi = [vec![0.0; 4], vec![0.0; 4], vec![0.0; 4]];
        for m in 0..2 {
            bi[0][2 * m] = s * pg[m][0];
            bi[1][2 * m + 1] = s * pg[m][1];
            bi[2][2 * m] = s * pg[m][1];
            bi[2][2 * m + 1] = s * pg[m][0];
        }
        out.push(MembranePoint {
            w: det,
            n,
            inv,
            g,
            bc,
            bi,
        });
    }
    Ok(out)
}

/// The membrane blocks ∫ Bᵀ D_m B dA over the compatible (c, 8 dofs) and incompatible (i, 4)
/// parts: (K_cc 8×8, K_ci 8×4, K_ii 4×4), row-major.
pub(crate) fn membrane_blocks(
    points: &[MembranePoint],
    dm: &[[f64; 3]; 3],
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut kcc = vec![0.0; 64];
    let mut kci = vec![0.0; 32];
    let mut kii = vec![0.0; 16];
    for MembranePoint { w, bc, bi, .. } in points {
        for r in 0..3 {
            let dbc: Vec<f64> = (0..8)
                .map(|j| (0..3).map(|l| dm[r][l] * bc[l][j]).sum())
                .collect();
            let dbi: Vec<f64> = (0..4)
                .map(|j| (0..3).map(|l| dm[r][l] * bi[l][j]).sum())
                .collect();
            for i in 0..8 {
                for j in 0..8 {
                    kcc[i * 8 + j] += w * bc[r][i] * dbc[j];
                }
                for j in 0..4 {
                    kci[i * 4 + j] += w * bc[r][i] * dbi[j];
                }
            }
            for i in 0..4 {
                for j in 0..4 {
                    kii[i * 4 + j] += w * bi[r][i] * dbi[j];
                }
            }
        }
    }
    (kcc, kci, kii)
}

/// Local 24×24 stiffness of the flat element (before warping links and rotation). A coupled
/// section (B ≠ 0, module doc of shell.rs) couples membrane strains, the incompatible modes
/// included, with the curvatures through B before the modes are condensed.
fn local_stiffness(f: &ShellFrame<4>, props: &ShellProps) -> Result<Vec<f64>, ElementError> {
    const ND: usize = 24;
    let mut k = vec![0.0; ND * ND];
    let p = &f.p;
    let sec = props.resultants(&f.axes, [p[1][0] - p[0][0], p[1][1] - p[0][1]])?;
    // Membrane: compatible (8) + incompatible (4) modes, then condensation.
    let mem_dofs: Vec<usize> = (0..4).flat_map(|a| [6 * a, 6 * a + 1]).collect();
    let points = membrane_points(p)?;
    let (kcc, kci, kii) = membrane_blocks(&points, &sec.a);
    let plate_dofs: Vec<usize> = (0..4)
        .flat_map(|a| [6 * a + 2, 6 * a + 3, 6 * a + 4])
        .collect();
    // Incompatible modes × plate dofs through B (coupled sections only), 4×12.
    let mut kip = [[0.0; 12]; 4];
    // Shear tying rows.
    let eb = covariant_shear(p, 0.0, -1.0, 0);
    let ed = covariant_shear(p, 0.0, 1.0, 0);
    let ec = covariant_shear(p, -1.0, 0.0, 1);
    let ea = covariant_shear(p, 1.0, 0.0, 1);
    let has_shear = sec.shear[0][0] > 0.0 || sec.shear[1][1] > 0.0;
    let (rbf, gd) = match props.quad4 {
        Quad4Form::NastranQuad4 if has_shear => (
            residual_bending_scales(p, &sec, props.shear_rigid()),
            props.drill(),
        ),
        Quad4Form::AnsysShell181 => {
            let area: f64 = points.iter().map(|pt| pt.w).sum();
            ansys_shell181_shear_and_drill(area, props.t, &sec)
        }
        _ => ([1.0, 1.0], props.drill()),
    };
    for (pt, &[xi, eta]) in points.iter().zip(&GAUSS) {
        let MembranePoint { n, g, inv, .. } = pt;
        let w = pt.w;
        // Bending: κ = (βx,x, βy,y, βx,y + βy,x) on [w θx θy] per node.
        let mut bb = [vec![0.0; 12], vec![0.0; 12], vec![0.0; 12]];
        for a in 0..4 {
            bb[0][3 * a + 2] = g[a][0];
            bb[1][3 * a + 1] = -g[a][1];
            bb[2][3 * a + 1] = -g[a][0];
            bb[2][3 * a + 2] = g[a][1];
        }
        add_btdb(&mut k, ND, &bb, &plate_dofs, &sec.d, w);
        if sec.coupled {
            shell::add_coupling(
                &mut k,
                ND,
                (&pt.bc, &mem_dofs),
                (&bb, &plate_dofs),
                &sec.b,
                w,
            );
            for (m, row) in kip.iter_mut().enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    *v += w
                        * (0..3)
                            .map(|r| {
                                pt.bi[r][m] * (0..3).map(|c| sec.b[r][c] * bb[c][j]).sum::<f64>()
                            })
                            .sum::<f64>();
                }
            }
        }
        // MITC4 shear: e_ξ, e_η interpolated from the tying points, γ = J⁻¹ e.
        if has_shear {
            let exi: Vec<f64> = (0..12)
                .map(|j| rbf[0] * (0.5 * (1.0 - eta) * eb[j] + 0.5 * (1.0 + eta) * ed[j]))
                .collect();
            let eeta: Vec<f64> = (0..12)
                .map(|j| rbf[1] * (0.5 * (1.0 - xi) * ec[j] + 0.5 * (1.0 + xi) * ea[j]))
                .collect();
            let gam: [Vec<f64>; 2] = std::array::from_fn(|r| {
                (0..12)
                    .map(|j| inv[r][0] * exi[j] + inv[r][1] * eeta[j])
                    .collect()
            });
            shell::add_shear(
                &mut k,
                ND,
                [&gam[0], &gam[1]],
                &plate_dofs,
                &sec.shear,
                (w, 1.0),
            );
        }
        // Drilling: (θz − ω), ω = ½(v,x − u,y), on [u v θz] per node.
        if gd > 0.0 {
            let drill_dofs: Vec<usize> =
                (0..4).flat_map(|a| [6 * a, 6 * a + 1, 6 * a + 5]).collect();
            let row: Vec<f64> = (0..4)
                .flat_map(|a| [0.5 * g[a][1], -0.5 * g[a][0], n[a]])
                .collect();
            add_outer(&mut k, ND, &row, &drill_dofs, gd * w);
        }
    }
    if props.membrane.is_none() && props.general.is_none() {
        return Ok(k);
    }
    if !sec.coupled {
        // Condense the incompatible modes: K_m = Kcc − Kci Kii⁻¹ Kic.
        let x = solve4(&kii, &kci)?; // Kii⁻¹ Kic (4×8), from rows of Kci
        for i in 0..8 {
            for j in 0..8 {
                let corr: f64 = (0..4).map(|m| kci[i * 4 + m] * x[m * 8 + j]).sum();
                k[mem_dofs[i] * ND + mem_dofs[j]] += kcc[i * 8 + j] - corr;
            }
        }
        return Ok(k);
    }
    condense_coupled(&mut k, (&mem_dofs, &plate_dofs), &kcc, &kci, &kii, &kip)?;
    Ok(k)
}

/// ANSYS SHELL181 KEYOPT(3)=2 (module doc): the scale √s of both covariant shear strains,
/// s = 1/(1 + A/(160 000 t²)), and the drilling penalty γ_d = s·Ā_s/200, Ā_s the mean of the
/// transverse shear rigidities (k G t for a homogeneous section).
fn ansys_shell181_shear_and_drill(area: f64, t: f64, sec: &Resultants) -> ([f64; 2], f64) {
    let s = 1.0 / (1.0 + area / (160_000.0 * t * t));
    let shear = 0.5 * (sec.shear[0][0] + sec.shear[1][1]);
    ([s.sqrt(); 2], s * shear / 200.0)
}

/// √(S'_k/S_k) for k = ξ, η: MacNeal's residual bending flexibility (module doc),
/// S'_k = 1/(1/S_k + ℓ_k²/(12 D_k)); `shear_rigid`: 1/S_k left out (PSHELL MID3 blank).
fn residual_bending_scales(p: &[[f64; 2]; 4], sec: &Resultants, shear_rigid: bool) -> [f64; 2] {
    // between the midpoints of the opposite edges: ξ from edge 4–1 to 2–3, η from 1–2 to 3–4
    let mid = |a: usize, b: usize, k: usize| 0.5 * (p[a][k] + p[b][k]);
    let centre_lines = [
        [mid(1, 2, 0) - mid(3, 0, 0), mid(1, 2, 1) - mid(3, 0, 1)],
        [mid(2, 3, 0) - mid(0, 1, 0), mid(2, 3, 1) - mid(0, 1, 1)],
    ];
    centre_lines.map(|l| {
        let len2 = l[0] * l[0] + l[1] * l[1];
        let (c, s) = (l[0] / len2.sqrt(), l[1] / len2.sqrt());
        let u = [c, s];
        let v = [c * c, s * s, 2.0 * c * s];
        let s_k: f64 = (0..2)
            .map(|i| (0..2).map(|j| u[i] * sec.shear[i][j] * u[j]).sum::<f64>())
            .sum();
        let d_k: f64 = (0..3)
            .map(|i| (0..3).map(|j| v[i] * sec.d[i][j] * v[j]).sum::<f64>())
            .sum();
        let shear_compliance = if shear_rigid { 0.0 } else { 1.0 / s_k };
        let s_eff = 1.0 / (shear_compliance + len2 / (12.0 * d_k));
        (s_eff / s_k).sqrt()
    })
}

/// Adds K_cc and condenses the incompatible modes coupled to the membrane (K_ci) and plate
/// (K_ip) dofs: K ← K − K_xi K_ii⁻¹ K_ix over the 20 membrane and plate dofs.
fn condense_coupled(
    k: &mut [f64],
    (mem_dofs, plate_dofs): (&[usize], &[usize]),
    kcc: &[f64],
    kci: &[f64],
    kii: &[f64],
    kip: &[[f64; 12]; 4],
) -> Result<(), ElementError> {
    const ND: usize = 24;
    for i in 0..8 {
        for j in 0..8 {
            k[mem_dofs[i] * ND + mem_dofs[j]] += kcc[i * 8 + j];
        }
    }
    // K_xi (20×4): membrane rows from K_ci, plate rows from K_ipᵀ; dofs in that order.
    let dofs: Vec<usize> = mem_dofs.iter().chain(plate_dofs).copied().collect();
    let mut kxi = vec![0.0; 24 * 4];
    kxi[..32].copy_from_slice(kci);
    for j in 0..12 {
        for m in 0..4 {
            kxi[(8 + j) * 4 + m] = kip[m][j];
        }
    }
    // X = K_ii⁻¹ K_ix (4×20) in chunks of 8 rows of K_xi (the 24th row pads the last chunk).
    let mut x = vec![[0.0; 4]; 24];
    for chunk in 0..3 {
        let part = solve4(kii, &kxi[chunk * 32..(chunk + 1) * 32])?;
        for j in 0..8 {
            for m in 0..4 {
                x[chunk * 8 + j][m] = part[m * 8 + j];
            }
        }
    }
    for (p, &dp) in dofs.iter().enumerate() {
        for (q, &dq) in dofs.iter().enumerate() {
            let corr: f64 = (0..4).map(|m| kxi[p * 4 + m] * x[q][m]).sum();
            k[dp * ND + dq] -= corr;
        }
    }
    Ok(())
}

/// Kii⁻¹ Kciᵀ (4×8) by Gaussian elimination with partial pivoting.
pub(crate) fn solve4(kii: &[f64], kci: &[f64]) -> Result<Vec<f64>, ElementError> {
    let mut a = kii.to_vec();
    let mut b = vec![0.0; 32];
    for m in 0..4 {
        for j in 0..8 {
            b[m * 8 + j] = kci[j * 4 + m];
        }
    }
    let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for c in 0..4 {
        let piv = (c..4)
            .max_by(|&i, &j| a[i * 4 + c].abs().total_cmp(&a[j * 4 + c].abs()))
            .unwrap_or(c);
        if a[piv * 4 + c].abs() <= 1e-14 * scale || !a[piv * 4 + c].is_finite() {
            return Err(ElementError::BadConstants(
                "singular incompatible-mode membrane matrix (degenerate quadrilateral)".into(),
            ));
        }
        for j in 0..4 {
            a.swap(c * 4 + j, piv * 4 + j);
        }
        for j in 0..8 {
            b.swap(c * 8 + j, piv * 8 + j);
        }
        for r in c + 1..4 {
            let f = a[r * 4 + c] / a[c * 4 + c];
            for j in c..4 {
                a[r * 4 + j] -= f * a[c * 4 + j];
            }
            for j in 0..8 {
                b[r * 8 + j] -= f * b[c * 8 + j];
            }
        }
    }
    for c in (0..4).rev() {
        for j in 0..8 {
            let s: f64 = (c + 1..4).map(|m| a[c * 4 + m] * b[m * 8 + j]).sum();
            b[c * 8 + j] = (b[c * 8 + j] - s) / a[c * 4 + c];
        }
    }
    Ok(b)
}

/// Area integrals s_ab = ∫ N_a N_b dA (2×2 Gauss) of the projected element.
fn area_products(f: &ShellFrame<4>) -> Vec<f64> {
    let mut s = vec![0.0; 16];
    for &[xi, eta] in &GAUSS {
        let (n, d) = shape(xi, eta);
        let (_, det, _) = jacobian(&f.p, &d);
        for a in 0..4 {
            for b in 0..4 {
                s[a * 4 + b] += det * n[a] * n[b];
            }
        }
    }
    s
}

/// Basic-frame stiffness and mass (24×24 each, node-major `[u v w θx θy θz]`).
pub fn matrices(
    x: &[Xyz; 4],
    props: &ShellProps,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    props.check()?;
    let f = ShellFrame::new(x)?;
    let mut k = local_stiffness(&f, props)?;
    shell::apply_warping(&mut k, &f.h);
    let k = shell::to_basic(&k, 4, &f.axes);
    let m = shell::mass_matrix(&area_products(&f), 4, props, lumped, &f.axes[2]);
    Ok((k, m))
}

/// [`matrices`] of the CQUADR: the same plate (MITC4 bending and shear) and mass, with the
/// membrane of `drill_membrane` (Allman-type, Ibrahimbegovic–Taylor–Wilson) carrying θz in place
/// of the QM6 membrane and its drilling penalty. Homogeneous sections with a membrane only.
pub fn matrices_drilling(
    x: &[Xyz; 4],
    props: &ShellProps,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    props.check()?;
    let f = ShellFrame::new(x)?;
    let mut k = local_stiffness(&f, &props.plate_only())?;
    let membrane = super::drill_membrane::quad_stiffness(&f.p, &props.d_membrane(), 1.0)?;
    shell::add_drilling_membrane(&mut k, &membrane, 4);
    shell::apply_warping(&mut k, &f.h);
    let k = shell::to_basic(&k, 4, &f.axes);
    let m = shell::mass_matrix(&area_products(&f), 4, props, lumped, &f.axes[2]);
    Ok((k, m))
}

/// Area of the projected element.
pub fn area(x: &[Xyz; 4]) -> Result<f64, ElementError> {
    let f = ShellFrame::new(x)?;
    Ok(area_products(&f).iter().sum())
}

/// Membrane strain (ε_x, ε_y, γ_xy) and curvature (κ_x, κ_y, κ_xy) at each corner, in the
/// element frame, from the local nodal values `[u v w θx θy θz]` of the real (warped) nodes:
/// the bilinear fields' gradients at the corner (the condensed incompatible modes are left
/// out: they vanish for the constant states the patch test checks).
pub fn corner_strains(f: &ShellFrame<4>, u: &[[f64; 6]; 4]) -> [([f64; 3], [f64; 3]); 4] {
    // warping links (shell::apply_warping): u_f = u − hθy, v_f = v + hθx
    let uf: [[f64; 2]; 4] =
        std::array::from_fn(|a| [u[a][0] - f.h[a] * u[a][4], u[a][1] + f.h[a] * u[a][3]]);
    std::array::from_fn(|c| {
        let (_, d) = shape(REF[c][0], REF[c][1]);
        let (_, _, inv) = jacobian(&f.p, &d);
        let mut em = [0.0; 3];
        let mut k = [0.0; 3];
        for a in 0..4 {
            let g = grad(&inv, &d[a]);
            em[0] += g[0] * uf[a][0];
            em[1] += g[1] * uf[a][1];
            em[2] += g[1] * uf[a][0] + g[0] * uf[a][1];
            // βx = θy, βy = −θx
            let (bx, by) = (u[a][4], -u[a][3]);
            k[0] += g[0] * bx;
            k[1] += g[1] * by;
            k[2] += g[1] * bx + g[0] * by;
        }
        (em, k)
    })
}

/// The 4-node flat shell (MITC4 + QM6, or the drilling membrane) as an [`Element`].
pub struct Quad4Element;

impl Element for Quad4Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let (p, drilling) = shell_section::flat_shell_props(input)?;
        let x = input.coords::<4>();
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

    const DISTORTED: [Xyz; 4] = [
        [0.0, 0.0, 0.0],
        [2.0, 0.3, 0.0],
        [2.4, 1.9, 0.0],
        [0.2, 1.2, 0.0],
    ];

    #[test]
    fn quad4_shell_rigid_motions_cost_no_energy_even_warped() {
        let warped = [
            [0.1, 0.0, 0.02],
            [2.0, 0.3, -0.05],
            [2.4, 1.9, 0.1],
            [0.2, 1.2, -0.03],
        ];
        let (k, _) = matrices(&warped, &steel_plate(0.01), false).unwrap();
        for mode in 0..6 {
            let u = rigid(&warped, mode);
            assert!(
                residual(&k, &u) < 1e-12,
                "mode {mode}: {}",
                residual(&k, &u)
            );
        }
    }

    /// Constant membrane strain and constant curvature: uᵀKu = A (εᵀD_mε + κᵀD_bκ) exactly on a
    /// distorted element (the incompatible modes and the MITC shear stay silent).
    #[test]
    fn quad4_shell_patch_test_constant_strain_and_curvature_on_distorted_element() {
        let props = steel_plate(0.02);
        let (k, _) = matrices(&DISTORTED, &props, false).unwrap();
        let a = area(&DISTORTED).unwrap();
        patch_energy(&k, &DISTORTED, a, &props, 1e-10);
    }

    /// A free element has exactly 6 zero eigenvalues (no spurious drilling or hourglass modes).
    #[test]
    fn quad4_shell_single_element_has_six_zero_modes() {
        let (k, _) = matrices(&DISTORTED, &steel_plate(0.01), false).unwrap();
        let n = 24;
        let mat = faer::Mat::<f64>::from_fn(n, n, |i, j| k[i * n + j]);
        let ev = mat.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
        let top = ev.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let zeros = ev.iter().filter(|v| v.abs() < 1e-10 * top).count();
        assert_eq!(zeros, 6, "{ev:?}");
    }

    /// A coupled anisotropic section (B ≠ 0, material axis 25° from the G1→G2 side, or basic
    /// x by projection) passes the patch test with the coupling energy, and its element still
    /// has exactly 6 zero modes.
    #[test]
    fn quad4_shell_laminate_patch_test_with_coupling_and_material_axis() {
        use crate::model::ShellMaterialAxis;
        let side = [
            DISTORTED[1][0] - DISTORTED[0][0],
            DISTORTED[1][1] - DISTORTED[0][1],
        ];
        let a = area(&DISTORTED).unwrap();
        for (axis, psi) in [
            (
                ShellMaterialAxis::FromSide12 { theta_deg: 25.0 },
                side[1].atan2(side[0]) + 25f64.to_radians(),
            ),
            (ShellMaterialAxis::Projected([1.0, 0.0, 0.3]), 0.0),
        ] {
            let props = coupled_section(0.02, axis);
            let (k, _) = matrices(&DISTORTED, &props, false).unwrap();
            patch_energy_general(&k, &DISTORTED, a, &props, psi, 1e-10);
            let mat = faer::Mat::<f64>::from_fn(24, 24, |i, j| k[i * 24 + j]);
            let ev = mat.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
            let top = ev.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            assert_eq!(
                ev.iter().filter(|v| v.abs() < 1e-10 * top).count(),
                6,
                "{ev:?}"
            );
            assert!(ev.iter().all(|v| *v > -1e-10 * top), "{ev:?}");
        }
    }

    /// ANSYS SHELL181's form (shear factor, drilling penalty) keeps the constant-strain and
    /// constant-curvature patch energies and exactly 6 zero modes, and differs from plain
    /// MITC4 only in the shear and drilling terms.
    #[test]
    fn quad4_shell_ansys_shell181_form_passes_patch_test_and_has_six_zero_modes() {
        let props = ShellProps {
            quad4: Quad4Form::AnsysShell181,
            ..steel_plate(0.02)
        };
        let (k, _) = matrices(&DISTORTED, &props, false).unwrap();
        patch_energy(&k, &DISTORTED, area(&DISTORTED).unwrap(), &props, 1e-10);
        let mat = faer::Mat::<f64>::from_fn(24, 24, |i, j| k[i * 24 + j]);
        let ev = mat.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
        let top = ev.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert_eq!(
            ev.iter().filter(|v| v.abs() < 1e-10 * top).count(),
            6,
            "{ev:?}"
        );
        let (plain, _) = matrices(&DISTORTED, &steel_plate(0.02), false).unwrap();
        assert_ne!(k, plain);
    }

    #[test]
    fn quad4_shell_mass_totals() {
        let props = ShellProps {
            nsm: 0.5,
            ..steel_plate(0.01)
        };
        let a = area(&DISTORTED).unwrap();
        for lumped in [false, true] {
            let (_, m) = matrices(&DISTORTED, &props, lumped).unwrap();
            let tx: f64 = (0..4)
                .flat_map(|i| (0..4).map(move |j| (i, j)))
                .map(|(i, j)| m[(6 * i) * 24 + 6 * j])
                .sum();
            let want = a * (7850.0 * 0.01 + 0.5);
            assert!((tx - want).abs() < 1e-12 * want);
            // element in the x–y plane: θx, θy carry ρt³/12, θz (drilling) 10⁻⁴ of it
            let rx: f64 = (0..4).map(|i| m[(6 * i + 3) * 24 + 6 * i + 3]).sum::<f64>();
            let rz: f64 = (0..4).map(|i| m[(6 * i + 5) * 24 + 6 * i + 5]).sum::<f64>();
            if lumped {
                let want = a * 7850.0 * 1e-6 / 12.0;
                assert!((rx - want).abs() < 1e-12 * want);
                assert!((rz - 1e-4 * want).abs() < 1e-12 * want);
            }
        }
    }
}
