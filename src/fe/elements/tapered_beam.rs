//! 2-node 3D beam whose section varies along its length (Nastran tapered PBEAM/PBEAML):
//! the stiffness is the exact inverse of the element's flexibility integrated along it, the
//! mass the prismatic element's shape functions integrated against the varying mass.
//!
//! Stiffness (force method, Przemieniecki, *Theory of Matrix Structural Analysis* (1968)
//! §6.3, "tapered beams"): clamped at end A, the tip flexibility of each bending plane is
//! F = [[∫(L−x)²/EI dx + ∫dx/(kGA), s∫(L−x)/EI dx], [s∫(L−x)/EI dx, ∫dx/EI]] (s = +1 in x–y,
//! −1 in x–z, the sign convention of `beam`); K = Bᵀ F⁻¹ B with B the map from the element's
//! four dofs to the deformation of end B relative to the tangent at end A,
//! [v_B − v_A − s L θ_A, θ_B − θ_A]. Axial EA and torsion GJ: k = 1/∫dx/EA, 1/∫dx/GJ. For a
//! prismatic section this is exactly `beam::stiffness_local` (tested).
//! Mass: consistent — the cubic Hermite (bending) and linear (axial, torsion) functions of
//! `beam::consistent_mass_local` integrated against m(x) = ρA(x) + NSM(x) and ρI_p(x); lumped —
//! each node the integral of m(x) times its linear function (the prismatic m/2), rotary
//! inertia likewise per `BeamLumping`.
//! Integration: 8 four-point Gauss–Legendre cells between consecutive stations (the section
//! is smooth between them).

use super::beam::{local_frame, to_basic, BeamLumping, BeamProps};
use super::{ElementError, Isotropic, Xyz};
use crate::fe::quadrature::gauss_legendre;

/// Cells of the Gauss rule between two stations.
const CELLS: usize = 8;

/// Gauss points (ξ, weight in ξ) over [0, 1] with cells between the `breaks`.
fn points(breaks: &[f64]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for w in breaks.windows(2) {
        let h = (w[1] - w[0]) / CELLS as f64;
        for c in 0..CELLS {
            let a = w[0] + c as f64 * h;
            for &(t, wt) in gauss_legendre(4) {
                out.push((a + (t + 1.0) * h / 2.0, wt * h / 2.0));
            }
        }
    }
    out
}

/// Local 12×12 stiffness of the tapered beam (module doc); `props(ξ)` the section at ξ.
pub fn stiffness_local(
    l: f64,
    mat: &Isotropic,
    props: &dyn Fn(f64) -> BeamProps,
    breaks: &[f64],
) -> Result<[[f64; 12]; 12], ElementError> {
    let pts = points(breaks);
    let integral = |f: &dyn Fn(f64, &BeamProps) -> f64| -> f64 {
        pts.iter().map(|&(xi, w)| w * l * f(xi, &props(xi))).sum()
    };
    let mut k = [[0.0; 12]; 12];
    let ea = 1.0 / integral(&|_, p| 1.0 / (mat.e * p.area));
    let gj = 1.0 / integral(&|_, p| 1.0 / (mat.g * p.j));
    for (a, b, v) in [(0, 6, ea), (3, 9, gj)] {
        k[a][a] += v;
        k[b][b] += v;
        k[a][b] -= v;
        k[b][a] -= v;
    }
    // (dofs v_A θ_A v_B θ_B, sign s, I of the plane, shear factor index)
    for (dofs, s, plane) in [([1, 5, 7, 11], 1.0, 0), ([2, 4, 8, 10], -1.0, 1)] {
        let ei = |p: &BeamProps| mat.e * if plane == 0 { p.iz } else { p.iy };
        let f_vv = integral(&|xi, p| {
            let shear = match p.shear {
                Some(ks) if ks[plane] > 0.0 => 1.0 / (ks[plane] * mat.g * p.area),
                _ => 0.0,
            };
            (l - xi * l).powi(2) / ei(p) + shear
        });
        let f_vt = s * integral(&|xi, p| (l - xi * l) / ei(p));
        let f_tt = integral(&|_, p| 1.0 / ei(p));
        let det = f_vv * f_tt - f_vt * f_vt;
        if det.is_nan() || det <= 0.0 {
            return Err(ElementError::BadConstants(format!(
                "tapered beam: singular flexibility in plane {} (det = {det})",
                plane + 1
            )));
        }
        let k22 = [[f_tt / det, -f_vt / det], [-f_vt / det, f_vv / det]];
        let b = [[-1.0, -s * l, 1.0, 0.0], [0.0, -1.0, 0.0, 1.0]];
        for r in 0..4 {
            for c in 0..4 {
                let v: f64 = (0..2)
                    .flat_map(|i| (0..2).map(move |j| (i, j)))
                    .map(|(i, j)| b[i][r] * k22[i][j] * b[j][c])
                    .sum();
                k[dofs[r]][dofs[c]] += v;
            }
        }
    }
    Ok(k)
}

/// Local 12×12 mass of the tapered beam (module doc): consistent (`lumped` = None) or lumped.
pub fn mass_local(
    l: f64,
    mat: &Isotropic,
    props: &dyn Fn(f64) -> BeamProps,
    breaks: &[f64],
    lumped: Option<BeamLumping>,
) -> [[f64; 12]; 12] {
    let mut m = [[0.0; 12]; 12];
    for (xi, w) in points(breaks) {
        let p = props(xi);
        let dm = w * l * (mat.rho * p.area + p.nsm);
        let dr = w * l * mat.rho;
        let lin = [1.0 - xi, xi];
        match lumped {
            Some(lumping) => {
                let (tors, bend) = match lumping {
                    BeamLumping::SectionRotary => (1.0, 1.0),
                    BeamLumping::TorsionOnly | BeamLumping::Nastran => (1.0, 0.0),
                    BeamLumping::TranslationsOnly => (0.0, 0.0),
                };
                for (node, n) in [0, 6].into_iter().zip(lin) {
                    for i in 0..3 {
                        m[node + i][node + i] += dm * n;
                    }
                    m[node + 3][node + 3] += tors * dr * (p.iy + p.iz) * n;
                    m[node + 4][node + 4] += bend * dr * p.iy * n;
                    m[node + 5][node + 5] += bend * dr * p.iz * n;
                }
            }
            None => {
                for (dofs, rho_i) in [([0, 6], dm), ([3, 9], dr * (p.iy + p.iz))] {
                    for r in 0..2 {
                        for c in 0..2 {
                            m[dofs[r]][dofs[c]] += rho_i * lin[r] * lin[c];
                        }
                    }
                }
                // Cubic Hermite functions (v_A, θ_A, v_B, θ_B) with the rotations scaled s L.
                let h = [
                    1.0 - 3.0 * xi * xi + 2.0 * xi.powi(3),
                    xi - 2.0 * xi * xi + xi.powi(3),
                    3.0 * xi * xi - 2.0 * xi.powi(3),
                    -xi * xi + xi.powi(3),
                ];
                for (dofs, s) in [([1, 5, 7, 11], 1.0), ([2, 4, 8, 10], -1.0)] {
                    let n = [h[0], s * l * h[1], h[2], s * l * h[3]];
                    for r in 0..4 {
                        for c in 0..4 {
                            m[dofs[r]][dofs[c]] += dm * n[r] * n[c];
                        }
                    }
                }
            }
        }
    }
    m
}

/// Basic-frame stiffness and mass (12×12 each) of a tapered beam; `props(ξ)` the section at
/// ξ = x/L, `breaks` the stations' ξ (from 0 to 1).
pub fn matrices(
    x: &[Xyz; 2],
    v: Option<Xyz>,
    mat: &Isotropic,
    props: &dyn Fn(f64) -> BeamProps,
    breaks: &[f64],
    lumped: Option<BeamLumping>,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    for &(xi, _) in &points(breaks) {
        super::beam::check(mat, &props(xi))?;
    }
    let v = v.ok_or(ElementError::BadOrientation { v: [0.0; 3] })?;
    let (r, l) = local_frame(x, Some(v))?;
    let k = stiffness_local(l, mat, props, breaks)?;
    let m = mass_local(l, mat, props, breaks, lumped);
    Ok((to_basic(&k, &r), to_basic(&m, &r)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::beam;

    /// A prismatic section through the tapered formulation gives `beam`'s matrices (stiffness
    /// Timoshenko, consistent and lumped mass).
    #[test]
    fn prismatic_section_equals_the_prismatic_element() {
        let mat = Isotropic::new(210e9, 0.3, 7850.0);
        let p = BeamProps {
            area: 2e-4,
            iz: 3e-9,
            iy: 5e-9,
            j: 6e-9,
            shear: Some([0.85, 0.6]),
            nsm: 0.3,
        };
        let l = 0.7;
        let at = |_: f64| p;
        let pairs = [
            (
                stiffness_local(l, &mat, &at, &[0.0, 0.4, 1.0]).unwrap(),
                beam::stiffness_local(l, &mat, &p),
            ),
            (
                mass_local(l, &mat, &at, &[0.0, 1.0], None),
                beam::consistent_mass_local(l, &mat, &p),
            ),
            (
                mass_local(l, &mat, &at, &[0.0, 1.0], Some(BeamLumping::SectionRotary)),
                beam::lumped_mass_local(l, &mat, &p, BeamLumping::SectionRotary),
            ),
        ];
        for (got, want) in pairs {
            let scale = want.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
            for r in 0..12 {
                for c in 0..12 {
                    assert!(
                        (got[r][c] - want[r][c]).abs() < 1e-11 * scale,
                        "[{r}][{c}]: {} vs {}",
                        got[r][c],
                        want[r][c]
                    );
                }
            }
        }
    }
}
