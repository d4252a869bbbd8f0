//! 2-node 3D beam (B31, CBAR, CBEAM): axial, torsion and bending in two planes; Euler–Bernoulli
//! or Timoshenko (shear-flexible) bending.
//!
//! ```text
//!        y (v, θy ↑ in the x–v plane)
//!        |                         local x = (x2 − x1)/L
//!        1 ──────────────── 2 ─ x  local y = v − (v·x)x normalised (v = orientation vector)
//!       /                          local z = x × y
//!      z                           dofs per node [u v w θx θy θz], 12 per element
//! ```
//! Stiffness: Przemieniecki, *Theory of Matrix Structural Analysis* (1968) eq. 5.116 (with shear
//! parameters Φ_y = 12EI_z/(G k_y A L²), Φ_z = 12EI_y/(G k_z A L²); Φ = 0 is Euler–Bernoulli).
//! I1 = I_z bends in the x–y plane (Nastran plane 1), I2 = I_y in the x–z plane.
//! Consistent mass: Przemieniecki eq. 11.42 without the rotary-inertia terms of bending (the
//! Euler–Bernoulli mass), plus axial m/6·[2 1; 1 2] and torsional ρI_pL/6·[2 1; 1 2] with
//! I_p = I_y + I_z. Lumped mass: m/2 on each node's translations, section rotary inertia
//! ρL/2·(I_p, I_y, I_z) on its rotations. Non-structural mass adds to the translational mass only.

use super::{ElementError, Isotropic, Xyz};
use crate::model::geometry::{cross, dot, norm, scale, sub};

/// Section constants of a beam element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamProps {
    /// Area A.
    pub area: f64,
    /// I_z: bending in the local x–y plane (Nastran I1).
    pub iz: f64,
    /// I_y: bending in the local x–z plane (Nastran I2).
    pub iy: f64,
    /// Torsion constant J.
    pub j: f64,
    /// Shear area factors (k_y, k_z); `None` = Euler–Bernoulli.
    pub shear: Option<[f64; 2]>,
    /// Non-structural mass per length.
    pub nsm: f64,
}

/// Local frame of a line element: rows e_x, e_y, e_z (basic components) and the length.
pub fn local_frame(x: &[Xyz; 2], v: Option<Xyz>) -> Result<([Xyz; 3], f64), ElementError> {
    let d = sub(x[1], x[0]);
    let l = norm(d);
    if l.is_nan() || l <= 0.0 {
        return Err(ElementError::ZeroLength);
    }
    let ex = scale(d, 1.0 / l);
    let v = match v {
        Some(v) => v,
        // No orientation (rods): any vector not parallel to the axis.
        None => {
            let k = (0..3)
                .min_by(|&a, &b| ex[a].abs().total_cmp(&ex[b].abs()))
                .unwrap_or(0);
            let mut e = [0.0; 3];
            e[k] = 1.0;
            e
        }
    };
    let y = sub(v, scale(ex, dot(v, ex)));
    let ny = norm(y);
    if ny.is_nan() || ny <= 1e-9 * norm(v) {
        return Err(ElementError::BadOrientation { v });
    }
    let ey = scale(y, 1.0 / ny);
    Ok(([ex, ey, cross(ex, ey)], l))
}

/// A section with a product of inertia I12 = ∫yz dA ≠ 0 (Nastran PBAR/PBEAM I12, PBARL L or Z)
/// bends about its principal axes: the orientation vector turned about the element axis to
/// the principal y' = y cos θ + z sin θ, with (I1', I2', θ) from
/// [`crate::model::beam_library::principal_axes`]. Returns (v', I1', I2'); I12 = 0 returns
/// the inputs.
pub fn principal_orientation(
    x: &[Xyz; 2],
    v: Xyz,
    i1: f64,
    i2: f64,
    i12: f64,
) -> Result<(Xyz, f64, f64), ElementError> {
    if i12 == 0.0 {
        return Ok((v, i1, i2));
    }
    if i1 * i2 <= i12 * i12 {
        return Err(ElementError::BadConstants(format!(
            "beam needs I1·I2 > I12² (I1 = {i1}, I2 = {i2}, I12 = {i12})"
        )));
    }
    let ([_, ey, ez], _) = local_frame(x, Some(v))?;
    let (i1p, i2p, theta) = crate::model::beam_library::principal_axes(i1, i2, i12);
    let (s, c) = theta.sin_cos();
    let yp = [0, 1, 2].map(|k| ey[k] * c + ez[k] * s);
    Ok((yp, i1p, i2p))
}

/// The shear parameters (Φ_y, Φ_z) = (12EI_z/(G k_y A L²), 12EI_y/(G k_z A L²)) of the two
/// bending planes (module doc); zero for Euler–Bernoulli.
pub fn shear_parameters(l: f64, mat: &Isotropic, p: &BeamProps) -> (f64, f64) {
    let phi = |i: f64, ks: f64| {
        if ks > 0.0 {
            12.0 * mat.e * i / (mat.g * ks * p.area * l * l)
        } else {
            0.0
        }
    };
    match p.shear {
        Some([ky, kz]) => (phi(p.iz, ky), phi(p.iy, kz)),
        None => (0.0, 0.0),
    }
}

/// Local 12×12 stiffness, Przemieniecki eq. 5.116.
pub fn stiffness_local(l: f64, mat: &Isotropic, p: &BeamProps) -> [[f64; 12]; 12] {
    let mut k = [[0.0; 12]; 12];
    let ea = mat.e * p.area / l;
    let gj = mat.g * p.j / l;
    add2(&mut k, 0, 6, [[ea, -ea], [-ea, ea]]);
    add2(&mut k, 3, 9, [[gj, -gj], [-gj, gj]]);
    let (phy, phz) = shear_parameters(l, mat, p);
    // Bending in x–y: dofs (v1, θz1, v2, θz2) = (1, 5, 7, 11); s = +1.
    // Bending in x–z: dofs (w1, θy1, w2, θy2) = (2, 4, 8, 10); s = −1.
    for (dofs, i, ph, s) in [
        ([1, 5, 7, 11], p.iz, phy, 1.0),
        ([2, 4, 8, 10], p.iy, phz, -1.0),
    ] {
        let c = mat.e * i / ((1.0 + ph) * l * l * l);
        let b = [
            [12.0, s * 6.0 * l, -12.0, s * 6.0 * l],
            [
                s * 6.0 * l,
                (4.0 + ph) * l * l,
                -s * 6.0 * l,
                (2.0 - ph) * l * l,
            ],
            [-12.0, -s * 6.0 * l, 12.0, -s * 6.0 * l],
            [
                s * 6.0 * l,
                (2.0 - ph) * l * l,
                -s * 6.0 * l,
                (4.0 + ph) * l * l,
            ],
        ];
        for r in 0..4 {
            for cc in 0..4 {
                k[dofs[r]][dofs[cc]] += c * b[r][cc];
            }
        }
    }
    k
}

/// Local 12×12 consistent mass (module formula).
pub fn consistent_mass_local(l: f64, mat: &Isotropic, p: &BeamProps) -> [[f64; 12]; 12] {
    let mut m = [[0.0; 12]; 12];
    let mass = (mat.rho * p.area + p.nsm) * l;
    let a = mass / 6.0;
    add2(&mut m, 0, 6, [[2.0 * a, a], [a, 2.0 * a]]);
    let t = mat.rho * (p.iy + p.iz) * l / 6.0;
    add2(&mut m, 3, 9, [[2.0 * t, t], [t, 2.0 * t]]);
    for (dofs, s) in [([1, 5, 7, 11], 1.0), ([2, 4, 8, 10], -1.0)] {
        let c = mass / 420.0;
        let b = [
            [156.0, s * 22.0 * l, 54.0, -s * 13.0 * l],
            [s * 22.0 * l, 4.0 * l * l, s * 13.0 * l, -3.0 * l * l],
            [54.0, s * 13.0 * l, 156.0, -s * 22.0 * l],
            [-s * 13.0 * l, -3.0 * l * l, -s * 22.0 * l, 4.0 * l * l],
        ];
        for r in 0..4 {
            for cc in 0..4 {
                m[dofs[r]][dofs[cc]] += c * b[r][cc];
            }
        }
    }
    m
}

pub use super::element::BeamLumping;

/// Local 12×12 lumped (diagonal) mass (module formula; rotational part per `lumping`).
pub fn lumped_mass_local(
    l: f64,
    mat: &Isotropic,
    p: &BeamProps,
    lumping: BeamLumping,
) -> [[f64; 12]; 12] {
    let mut m = [[0.0; 12]; 12];
    let half = 0.5 * (mat.rho * p.area + p.nsm) * l;
    let r = 0.5 * mat.rho * l;
    let (tors, bend) = match lumping {
        BeamLumping::SectionRotary => (1.0, 1.0),
        BeamLumping::TorsionOnly | BeamLumping::Nastran => (1.0, 0.0),
        BeamLumping::TranslationsOnly => (0.0, 0.0),
    };
    for n in [0, 6] {
        for i in 0..3 {
            m[n + i][n + i] = half;
        }
        m[n + 3][n + 3] = tors * r * (p.iy + p.iz);
        m[n + 4][n + 4] = bend * r * p.iy;
        m[n + 5][n + 5] = bend * r * p.iz;
    }
    m
}

/// Rotate a local 12×12 matrix to the basic frame: A = Tᵀ A_l T, T = diag(R, R, R, R),
/// R rows = local axes.
pub fn to_basic(a: &[[f64; 12]; 12], r: &[Xyz; 3]) -> Vec<f64> {
    // t[i][j] = T_ij (block diagonal)
    let t = |i: usize, j: usize| {
        if i / 3 == j / 3 {
            r[i % 3][j % 3]
        } else {
            0.0
        }
    };
    let mut at = [[0.0; 12]; 12]; // A_l T
    for i in 0..12 {
        for j in 0..12 {
            let blk = j / 3 * 3;
            at[i][j] = (0..3).map(|k| a[i][blk + k] * t(blk + k, j)).sum();
        }
    }
    let mut out = vec![0.0; 144];
    for i in 0..12 {
        let blk = i / 3 * 3;
        for j in 0..12 {
            out[i * 12 + j] = (0..3).map(|k| t(blk + k, i) * at[blk + k][j]).sum();
        }
    }
    out
}

/// Checks section and material constants.
pub fn check(mat: &Isotropic, p: &BeamProps) -> Result<(), ElementError> {
    let ok = mat.e > 0.0
        && mat.g > 0.0
        && mat.rho >= 0.0
        && p.area > 0.0
        && p.iy >= 0.0
        && p.iz >= 0.0
        && p.j >= 0.0
        && p.nsm >= 0.0;
    if !ok {
        return Err(ElementError::BadConstants(format!(
            "beam needs E, G, A > 0 and ρ, I, J, nsm ≥ 0 (E = {}, G = {}, A = {}, Iz = {}, Iy = {}, J = {})",
            mat.e, mat.g, p.area, p.iz, p.iy, p.j
        )));
    }
    Ok(())
}

/// Releases element dofs (pin flags, Nastran CBAR/CBEAM PA/PB; `released` local indices 0–11)
/// by static condensation: with T = [I; −K_rr⁻¹ K_re] mapping the kept dofs to all, K ← TᵀKT
/// and M ← TᵀMT (Guyan on the released dofs), whose rows and columns become zero (Przemieniecki
/// 1968, §10.6 "elements with released end connections"). One dof at a time; a release that
/// leaves a dof without stiffness (a rigid motion of the element) is an error.
pub fn release(
    k: &mut [[f64; 12]; 12],
    m: &mut [[f64; 12]; 12],
    released: &[usize],
) -> Result<(), ElementError> {
    let scale = (0..12).map(|i| k[i][i].abs()).fold(0.0, f64::max);
    for &r in released {
        let krr = k[r][r];
        if krr.is_nan() || krr <= 1e-12 * scale {
            return Err(ElementError::BadConstants(format!(
                "pin flags release dof {} of the element frame at end {} with nothing left to \
                 hold it (the element would have a rigid motion)",
                r % 6 + 1,
                if r < 6 { 'A' } else { 'B' }
            )));
        }
        // u_r = Σ t_j u_j with t_j = −k_rj / k_rr; A ← Tᵀ A T for A = K, M.
        let t: [f64; 12] = std::array::from_fn(|j| if j == r { 0.0 } else { -k[r][j] / krr });
        for a in [&mut *k, &mut *m] {
            let old = *a;
            for i in 0..12 {
                for j in 0..12 {
                    a[i][j] =
                        old[i][j] + t[i] * old[r][j] + old[i][r] * t[j] + t[i] * old[r][r] * t[j];
                }
            }
            for i in 0..12 {
                a[r][i] = 0.0;
                a[i][r] = 0.0;
            }
        }
    }
    Ok(())
}

/// Basic-frame stiffness and mass of a beam with released dofs (`pins`: end A, end B in the
/// element frame; see [`release`]).
pub fn matrices_pinned(
    x: &[Xyz; 2],
    v: Option<Xyz>,
    mat: &Isotropic,
    p: &BeamProps,
    lumped: Option<BeamLumping>,
    pins: [crate::model::DofMask; 2],
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    check(mat, p)?;
    let v = v.ok_or(ElementError::BadOrientation { v: [0.0; 3] })?;
    let (r, l) = local_frame(x, Some(v))?;
    let mut k = stiffness_local(l, mat, p);
    let mut m = match lumped {
        Some(lumping) => lumped_mass_local(l, mat, p, lumping),
        None => consistent_mass_local(l, mat, p),
    };
    let released: Vec<usize> = (0..12).filter(|&i| pins[i / 6].contains(i % 6)).collect();
    release(&mut k, &mut m, &released)?;
    Ok((to_basic(&k, &r), to_basic(&m, &r)))
}

/// A basic-frame 12×12 element matrix (row-major) at offset ends moved to the grids: the end
/// moves rigidly with its grid, u_end = u_grid + θ × w = u_grid − w̃ θ (Nastran CBAR WA/WB;
/// Przemieniecki 1968 §6.9 "rigid links"), so A_grid = Tᵀ A T with T = diag(T_A, T_B),
/// T_i = [[I, −w̃_i], [0, I]].
pub fn offset(a: &[f64], w: &[Xyz; 2]) -> Vec<f64> {
    // t[i][j]: end dof i from grid dof j.
    let mut t = [[0.0; 12]; 12];
    for (node, wi) in w.iter().enumerate() {
        let o = 6 * node;
        for i in 0..6 {
            t[o + i][o + i] = 1.0;
        }
        // −w̃ = [[0, w3, −w2], [−w3, 0, w1], [w2, −w1, 0]].
        let m = [
            [0.0, wi[2], -wi[1]],
            [-wi[2], 0.0, wi[0]],
            [wi[1], -wi[0], 0.0],
        ];
        for r in 0..3 {
            for c in 0..3 {
                t[o + r][o + 3 + c] = m[r][c];
            }
        }
    }
    let mut at = [[0.0; 12]; 12]; // A T
    for i in 0..12 {
        for j in 0..12 {
            at[i][j] = (0..12).map(|k| a[i * 12 + k] * t[k][j]).sum();
        }
    }
    let mut out = vec![0.0; 144];
    for i in 0..12 {
        for j in 0..12 {
            out[i * 12 + j] = (0..12).map(|k| t[k][i] * at[k][j]).sum();
        }
    }
    out
}

/// Basic-frame stiffness and mass (12×12 each) of a beam.
pub fn matrices(
    x: &[Xyz; 2],
    v: Option<Xyz>,
    mat: &Isotropic,
    p: &BeamProps,
    lumped: Option<BeamLumping>,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    check(mat, p)?;
    let v = v.ok_or(ElementError::BadOrientation { v: [0.0; 3] })?;
    let (r, l) = local_frame(x, Some(v))?;
    let k = stiffness_local(l, mat, p);
    let m = match lumped {
        Some(lumping) => lumped_mass_local(l, mat, p, lumping),
        None => consistent_mass_local(l, mat, p),
    };
    Ok((to_basic(&k, &r), to_basic(&m, &r)))
}

fn add2(k: &mut [[f64; 12]; 12], a: usize, b: usize, v: [[f64; 2]; 2]) {
    let d = [a, b];
    for r in 0..2 {
        for c in 0..2 {
            k[d[r]][d[c]] += v[r][c];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::shell::test_util::{residual, rigid};

    fn props() -> BeamProps {
        BeamProps {
            area: 2e-4,
            iz: 3e-9,
            iy: 5e-9,
            j: 6e-9,
            shear: Some([0.85, 0.85]),
            nsm: 0.0,
        }
    }

    /// Six rigid motions u = a + θ × x give zero force; the rotated element keeps it.
    #[test]
    fn beam_rigid_body_motion_gives_zero_force() {
        let x = [[0.1, 0.2, -0.3], [0.5, -0.1, 0.4]];
        let mat = Isotropic::new(210e9, 0.3, 7850.0);
        let (k, _) = matrices(&x, Some([0.0, 0.3, 1.0]), &mat, &props(), None).unwrap();
        for mode in 0..6 {
            let r = residual(&k, &rigid(&x, mode));
            assert!(r < 1e-12, "mode {mode}: {r}");
        }
    }

    /// A cantilever tip load P along local y gives the closed-form tip deflection
    /// PL³/(3EI) + PL/(kGA) (Timoshenko) — one element is exact.
    #[test]
    fn beam_cantilever_tip_deflection_is_exact() {
        let mat = Isotropic::new(200e9, 0.3, 0.0);
        let p = props();
        let l = 0.7;
        let k = stiffness_local(l, &mat, &p);
        // Free dofs v2, θz2 = (7, 11).
        let (a, b, c) = (k[7][7], k[7][11], k[11][11]);
        let det = a * c - b * b;
        let v2 = c / det; // unit load
        let want = l.powi(3) / (3.0 * mat.e * p.iz) + l / (0.85 * mat.g * p.area);
        assert!((v2 - want).abs() < 1e-12 * want);
        let (a, b, c) = (k[8][8], k[8][10], k[10][10]);
        let w2 = c / (a * c - b * b);
        let want = l.powi(3) / (3.0 * mat.e * p.iy) + l / (0.85 * mat.g * p.area);
        assert!((w2 - want).abs() < 1e-12 * want);
    }
}
