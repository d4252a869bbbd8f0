//! ANSYS's SHELL281 (8-node shell), formed as ANSYS's element forces show it (docs/ansys.md,
//! "SHELL281"); 6 dofs per node, nodes I, J, K, L, M, N, O, P in flexbody's `Quad8` order.
//!
//! * Kinematics: the continuum shell of [`super::curved_shell`] on the 8-node serendipity
//!   functions ([`super::curved_shell::shape8`]), directors the surface normals at the nodes.
//! * Stiffness on the 2 × 2 Gauss points (MAPDL Theory Reference §13.281: "In-plane: 2 x 2"),
//!   displacement-based — no assumed strain — for membrane, bending and transverse shear
//!   alike; two points through the thickness (exact for a homogeneous linear section).
//! * Transverse shear: energy ½ γᵀ E γ per area with E = k G t I, k = 5/6, or the section's
//!   `SECCONTROL` stiffnesses [[E11, E12], [E12, E22]] in the lamina frame (ê₁ along ∂x/∂r:
//!   the I→J side of a rectangle).
//! * Drilling: the Hughes–Brezzi penalty of the curved shells at the 2 × 2 points with
//!   γ_d = 10⁻⁴ (E11 + E22)/2 — not shown against ANSYS: its element forces bound it only
//!   (docs/ansys.md).
//! * Offset (`SECOFFSET` TOP, BOT): not here — the importer moves a flat offset element onto
//!   nodes at its mid-surface joined rigidly to its own ([`crate::model::shell_offset`]), which
//!   ANSYS's element forces of an offset section equal to their single precision.
//! * Mass: curved_shell's consistent shell mass on the same 2 × 2 points (the Theory
//!   Reference's table: "Same as stiffness matrix"; not shown against ANSYS).

use super::curved_shell::{
    self, add_btdb_rows, covariant_pair, point_rows, shape8, Lamina, SERENDIPITY8 as REF,
};
use super::shell::{add_outer, ShellProps};
use super::{ElementError, Xyz};
use crate::model::AnsysShell281;

/// The drilling penalty's share of the transverse shear stiffness (module doc).
const DRILL_OF_SHEAR: f64 = 1e-4;

/// The 2 × 2 Gauss rule.
fn gauss2x2() -> Vec<([f64; 2], f64)> {
    let g = 0.577_350_269_189_625_8;
    [-g, g]
        .into_iter()
        .flat_map(|r| [-g, g].into_iter().map(move |s| ([r, s], 1.0)))
        .collect()
}

/// The transverse shear stiffness [[E11, E12], [E12, E22]] at local thickness `t`.
fn shear_stiffness(props: &ShellProps, t: f64, sec: &AnsysShell281) -> [[f64; 2]; 2] {
    match sec.shear {
        Some([e11, e22, e12]) => [[e11, e12], [e12, e22]],
        None => {
            let g = ShellProps { t, ..*props }.shear_modulus();
            [[g, 0.0], [0.0, g]]
        }
    }
}

/// Stiffness of the 8-node lamina `l` on its mid-surface (module doc), 48×48, basic frame.
fn stiffness(
    l: &Lamina,
    props: &ShellProps,
    sec: &AnsysShell281,
) -> Result<Vec<f64>, ElementError> {
    let nd = 48;
    let all: Vec<usize> = (0..nd).collect();
    let mut k = vec![0.0; nd * nd];
    for (ip, ([r, s], w)) in gauss2x2().into_iter().enumerate() {
        let rows = point_rows(l, [r, s], &covariant_pair(l, r, s), ip)?;
        let p = ShellProps {
            t: rows.t,
            ..*props
        };
        let dw = rows.da * w;
        let m = &rows.mem;
        add_btdb_rows(&mut k, &[&m[0], &m[1], &m[2]], &p.d_membrane(), dw);
        let b = &rows.kap;
        add_btdb_rows(&mut k, &[&b[0], &b[1], &b[2]], &p.d_bending(), dw);
        let e = shear_stiffness(props, rows.t, sec);
        // ½ Σ over the two thickness points of γᵀ E γ: the mean over the thickness
        for [g13, g23] in &rows.shear {
            add_outer(&mut k, nd, g13, &all, 0.5 * e[0][0] * dw);
            add_outer(&mut k, nd, g23, &all, 0.5 * e[1][1] * dw);
            if e[0][1] != 0.0 {
                for (i, (a, b)) in g13.iter().zip(g23).enumerate() {
                    for (j, (c, d)) in g13.iter().zip(g23).enumerate() {
                        k[i * nd + j] += 0.5 * e[0][1] * dw * (a * d + b * c);
                    }
                }
            }
        }
        let gd = DRILL_OF_SHEAR * 0.5 * (e[0][0] + e[1][1]);
        add_outer(&mut k, nd, &rows.drill, &all, gd * dw);
    }
    curved_shell::symmetrize(&mut k, nd);
    Ok(k)
}

/// Basic-frame stiffness and mass (48×48 each, node-major `[u v w θx θy θz]`) of the SHELL281
/// at nodes `x` with thickness `t` and the section's transverse shear `sec`.
pub fn matrices(
    x: &[Xyz; 8],
    t: f64,
    props: &ShellProps,
    sec: &AnsysShell281,
    lumped: bool,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    props.check()?;
    let thick = [t; 8];
    let lam = Lamina::new(x, &thick, shape8, &REF)?;
    let k = stiffness(&lam, props, sec)?;
    let m = curved_shell::mass(&lam, &gauss2x2(), props, lumped)?;
    Ok((k, m))
}

#[cfg(test)]
mod tests {
    use super::super::shell::test_util::*;
    use super::super::Isotropic;
    use super::*;

    fn steel(t: f64) -> ShellProps {
        ShellProps::isotropic(t, Isotropic::new(210e9, 0.3, 7850.0))
    }

    /// A doubly curved element on a sphere of radius 2.
    fn curved() -> [Xyz; 8] {
        std::array::from_fn(|a| {
            let p = REF[a];
            let (u, v) = (0.4 * p[0] + 0.05 * p[1] * p[1], 0.3 * p[1]);
            [
                2.0 * u.sin() * v.cos(),
                2.0 * v.sin(),
                2.0 * u.cos() * v.cos(),
            ]
        })
    }

    /// Rigid motions cost no energy, with ANSYS's shear or the user's.
    #[test]
    fn shell281_rigid_motions_cost_no_energy() {
        let x = curved();
        for sec in [
            AnsysShell281 { shear: None },
            AnsysShell281 {
                shear: Some([1e6, 2e6, 5e5]),
            },
        ] {
            let (k, _) = matrices(&x, 0.02, &steel(0.02), &sec, false).unwrap();
            for mode in 0..6 {
                let res = residual(&k, &rigid(&x, mode));
                assert!(res < 1e-10, "mode {mode}: {res}");
            }
        }
    }
}
