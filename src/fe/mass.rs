//! Mass lumping and point masses.
//!
//! * Row-sum lumping for linear solids: m_a = Σ_b m_ab (Zienkiewicz & Taylor Vol. 1 §16.2.4);
//!   it preserves the element mass because Σ_a N_a = 1.
//! * HRZ lumping for quadratic solids (Hinton, Rock & Zienkiewicz, *Earthquake Eng. Struct.
//!   Dyn.* 4 (1976) 245): m_a = m_aa · (Σ_bc m_bc) / (Σ_b m_bb) — proportional to the consistent
//!   diagonal, scaled to the element mass; always positive (row sums of tet10 are negative at
//!   corners). Nastran decks: MSC Nastran does not publish how it lumps solids with midside
//!   grids (on a two-element CTETRA(10) deck HRZ is 7 … 23 % below MSC 2005's f06), so the
//!   build notes it (`pipeline::deck`); Autodesk Nastran documents HRZ for PARAM,COUPMASS < 0.
//! * Point mass (CONM2) with centre-of-gravity offset e and inertia I_cg about the centre of
//!   gravity, acting on the node's [u θ]: kinetic energy ½ m |u + θ × e|² + ½ θᵀ I_cg θ gives
//!   M = [m I, −m ẽ; m ẽ, I_cg − m ẽ ẽ] (ẽ the cross-product matrix of e).

use crate::model::PointMass;

/// How element masses are formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MassKind {
    /// Lumped (diagonal per node block): row-sum for linear solids, HRZ for quadratic ones,
    /// beams with rotary inertia. The default (multibody invariants need nodal masses).
    #[default]
    Lumped,
    /// Consistent (the element's integrated N_a N_b mass).
    Consistent,
}

/// Row-sum lumping of a scalar N×N mass.
pub fn row_sum(ms: &[f64], n: usize) -> Vec<f64> {
    (0..n)
        .map(|a| ms[a * n..(a + 1) * n].iter().sum())
        .collect()
}

/// HRZ lumping of a scalar N×N mass (module formula).
pub fn hrz(ms: &[f64], n: usize) -> Vec<f64> {
    let total: f64 = ms.iter().sum();
    let diag: f64 = (0..n).map(|a| ms[a * n + a]).sum();
    (0..n).map(|a| ms[a * n + a] * total / diag).collect()
}

/// Diagonal 3N×3N solid mass from nodal masses.
pub fn diagonal_solid_mass(nodal: &[f64]) -> Vec<f64> {
    let nd = 3 * nodal.len();
    let mut m = vec![0.0; nd * nd];
    for (a, &v) in nodal.iter().enumerate() {
        for i in 0..3 {
            m[(3 * a + i) * nd + 3 * a + i] = v;
        }
    }
    m
}

/// 6×6 node mass of a point mass (module formula), row-major, basic frame.
pub fn point_mass_matrix(p: &PointMass) -> [[f64; 6]; 6] {
    let m = p.mass;
    let e = p.offset;
    let et = [[0.0, -e[2], e[1]], [e[2], 0.0, -e[0]], [-e[1], e[0], 0.0]];
    let mut out = [[0.0; 6]; 6];
    for i in 0..3 {
        out[i][i] = m;
        for j in 0..3 {
            out[i][3 + j] = -m * et[i][j];
            out[3 + i][j] = m * et[i][j];
            let ee: f64 = (0..3).map(|k| et[i][k] * et[k][j]).sum();
            out[3 + i][3 + j] = p.inertia[i][j] - m * ee;
        }
    }
    out
}

/// Does a point mass need rotational dofs (inertia or offset)?
pub fn point_mass_has_rotary(p: &PointMass) -> bool {
    p.offset.iter().any(|&v| v != 0.0) || p.inertia.iter().flatten().any(|&v| v != 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The point-mass matrix reproduces the rigid-body kinetic energy of a mass at the offset:
    /// for u = 0, θ = e_z, the centre of gravity moves with θ × e, energy m|θ × e|² + θᵀIθ.
    #[test]
    fn point_mass_offset_matches_parallel_axis_theorem() {
        let p = PointMass {
            id: 1,
            node: 0,
            mass: 2.0,
            offset: [0.3, -0.1, 0.2],
            inertia: [[0.5, 0.01, 0.0], [0.01, 0.4, 0.0], [0.0, 0.0, 0.3]],
        };
        let m = point_mass_matrix(&p);
        // Rotation about z at the node: I_zz + m (ex² + ey²).
        assert!((m[5][5] - (0.3 + 2.0 * (0.09 + 0.01))).abs() < 1e-15);
        // Translation x with rotation z: force x from θz is −m (ẽ)_x,z = −m·e_y·(+1)…
        // v_cg = θ × e = (−e_y, e_x, 0) for θ = e_z, so M_xθz = m·(−e_y).
        assert!((m[0][5] - 2.0 * 0.1).abs() < 1e-15);
        for i in 0..6 {
            for j in 0..6 {
                assert!((m[i][j] - m[j][i]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn hrz_keeps_total_and_is_positive_where_row_sum_is_not() {
        // tet10 exact consistent scalar mass pattern in units of 1/420: corners 6, mids 32.
        let n = 10;
        let x: [[f64; 3]; 10] = crate::fe::elements::tet10::NODES;
        let ms = crate::fe::elements::tet10::scalar_mass(
            &x,
            1.0,
            crate::fe::elements::tet10::Tet10MassRule::Exact,
        )
        .unwrap();
        let rs = row_sum(&ms, n);
        assert!(
            rs[0] < 0.0,
            "corner row sum of tet10 is negative: {}",
            rs[0]
        );
        let h = hrz(&ms, n);
        let v = 1.0 / 6.0;
        assert!(h.iter().all(|&m| m > 0.0));
        assert!((h.iter().sum::<f64>() - v).abs() < 1e-15);
        assert!((h[0] - v / 36.0).abs() < 1e-15 && (h[5] - v * 4.0 / 27.0).abs() < 1e-15);
    }
}
