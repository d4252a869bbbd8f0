//! The general element GENEL (MSC QRG "GENEL"), honoured as its stiffness on the dofs it names,
//! into a [`crate::model::DofMatrix`].
//!
//! `GENEL EID – UI1 CI1 UI2 CI2 … / "UD" – UD1 CD1 … / "K"|"Z" KZ11 KZ21 … / "S" S11 S12 …`:
//! the independent dofs {u_i} (m of them) and the dependent dofs {u_d} (n, optional), grid
//! components 1–6 or a scalar point's 0; the stiffness K (or the flexibility Z, K = Z⁻¹) of
//! the {u_i}, m × m, written as its lower triangle column by column (KZ11 KZ21 … KZm1 KZ22 …);
//! the rigid-body matrix S (m × n, row by row: S11 … S1n S21 …) with u_i = S u_d in a rigid
//! motion. The element's stiffness (QRG):
//!
//! `[f_i; f_d] = [K, −K S; −Sᵀ K, Sᵀ K S] [u_i; u_d]`.
//!
//! Without UD and S the element is K on the {u_i} (which then grounds them).

use super::fields::C;
use super::reading::Bulk;
use crate::import::error::ImportError;
use crate::model::{DofMatrix, NodeDof};

/// The part of a GENEL being read.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Part {
    Ui,
    Ud,
    Kz,
    S,
}

/// Reader of GENEL (module doc).
pub(super) fn genel<'a>(d: &mut Bulk<'a>, g: &C<'a>) -> Result<(), ImportError> {
    let eid = g.id(0, "EID")?;
    d.elements.other_ids.push((eid, g.card));
    let (mut ui, mut ud): (Vec<NodeDof>, Vec<NodeDof>) = (Vec::new(), Vec::new());
    let (mut kz, mut s): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
    let mut flexibility = false;
    let mut part = Part::Ui;
    let mut k = 2;
    while k < g.card.fields.len() {
        let word = g.text(k).to_ascii_uppercase();
        let next = match word.as_str() {
            "UD" => Some(Part::Ud),
            "K" | "Z" => Some(Part::Kz),
            "S" => Some(Part::S),
            _ => None,
        };
        if let Some(next) = next {
            if next <= part {
                return Err(g.err(k, format!("'{word}' out of order (UI, UD, K or Z, S)")));
            }
            flexibility |= word == "Z";
            part = next;
            // UD is followed by a blank field: its pairs start on the next pair of fields
            k += if next == Part::Ud { 2 } else { 1 };
            continue;
        }
        match part {
            Part::Ui | Part::Ud => {
                if !g.text(k).is_empty() || !g.text(k + 1).is_empty() {
                    let dof = d
                        .dof(g, k, Some(k + 1))?
                        .ok_or_else(|| g.err(k, "a GENEL dof needs a grid or scalar point"))?;
                    if ui.contains(&dof) || ud.contains(&dof) {
                        return Err(g.err(k, "dof listed twice"));
                    }
                    (if part == Part::Ui { &mut ui } else { &mut ud }).push(dof);
                }
                k += 2;
            }
            Part::Kz | Part::S => {
                if let Some(v) = g.real(k)? {
                    if !v.is_finite() {
                        return Err(g.err(k, format!("value {v} is not finite")));
                    }
                    (if part == Part::Kz { &mut kz } else { &mut s }).push(v);
                }
                k += 1;
            }
        }
    }
    let (m, n) = (ui.len(), ud.len());
    if m == 0 {
        return Err(g.err(2, "no independent dofs UI"));
    }
    if kz.len() != m * (m + 1) / 2 {
        return Err(g.err_card(format!(
            "{} K or Z terms for {m} UI dofs: the lower triangle has {}",
            kz.len(),
            m * (m + 1) / 2
        )));
    }
    if s.len() != m * n {
        return Err(g.err_card(format!(
            "{} S terms for {m} UI and {n} UD dofs: {} expected",
            s.len(),
            m * n
        )));
    }
    let mut full = vec![0.0; m * m];
    let mut it = kz.iter();
    for col in 0..m {
        for row in col..m {
            let v = *it.next().unwrap_or(&0.0); // exactly m(m+1)/2 terms, checked above
            full[row * m + col] = v;
            full[col * m + row] = v;
        }
    }
    if flexibility {
        full = inverse(&full, m)
            .ok_or_else(|| g.err_card("the flexibility Z is singular: no stiffness K = Z⁻¹"))?;
    }
    let terms = stiffness_terms(&ui, &ud, &full, &s);
    d.b.model.dof_matrices.push(DofMatrix {
        what: format!("GENEL {eid}"),
        stiffness: terms,
        mass: Vec::new(),
        basic: false,
    });
    Ok(())
}

/// The terms of `[K, −K S; −Sᵀ K, Sᵀ K S]` on (u_i, u_d) (module doc); `k` is m × m, `s`
/// m × n, both row-major.
fn stiffness_terms(
    ui: &[NodeDof],
    ud: &[NodeDof],
    k: &[f64],
    s: &[f64],
) -> Vec<(NodeDof, NodeDof, f64)> {
    let (m, n) = (ui.len(), ud.len());
    // K S (m × n)
    let ks: Vec<f64> = (0..m * n)
        .map(|ij| {
            (0..m)
                .map(|l| k[(ij / n) * m + l] * s[l * n + ij % n])
                .sum()
        })
        .collect();
    let mut out = Vec::new();
    let mut push = |a: NodeDof, b: NodeDof, v: f64| {
        if v != 0.0 {
            out.push((a, b, v));
        }
    };
    for (i, &p) in ui.iter().enumerate() {
        for (j, &q) in ui.iter().enumerate() {
            push(p, q, k[i * m + j]);
        }
        for (j, &q) in ud.iter().enumerate() {
            push(p, q, -ks[i * n + j]);
            push(q, p, -ks[i * n + j]);
        }
    }
    for (a, &p) in ud.iter().enumerate() {
        for (b, &q) in ud.iter().enumerate() {
            // (Sᵀ K S)_ab = Σ_l S_la (K S)_lb
            let v: f64 = (0..m).map(|l| s[l * n + a] * ks[l * n + b]).sum();
            push(p, q, v);
        }
    }
    out
}

/// The inverse of the m × m matrix `a` (row-major) by Gauss–Jordan elimination with partial
/// pivoting; `None` when a pivot is below 1e-13 of the largest term (singular).
fn inverse(a: &[f64], m: usize) -> Option<Vec<f64>> {
    let largest = a.iter().fold(0.0f64, |x, v| x.max(v.abs()));
    let mut w = a.to_vec();
    let mut inv: Vec<f64> = (0..m * m)
        .map(|ij| f64::from(u8::from(ij / m == ij % m)))
        .collect();
    for c in 0..m {
        let p = (c..m).max_by(|&x, &y| w[x * m + c].abs().total_cmp(&w[y * m + c].abs()))?;
        if w[p * m + c].abs() <= 1e-13 * largest {
            return None;
        }
        for j in 0..m {
            w.swap(c * m + j, p * m + j);
            inv.swap(c * m + j, p * m + j);
        }
        let pivot = w[c * m + c];
        for j in 0..m {
            w[c * m + j] /= pivot;
            inv[c * m + j] /= pivot;
        }
        for r in (0..m).filter(|&r| r != c) {
            let f = w[r * m + c];
            if f != 0.0 {
                for j in 0..m {
                    w[r * m + j] -= f * w[c * m + j];
                    inv[r * m + j] -= f * inv[c * m + j];
                }
            }
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::inverse;

    /// The inverse of a symmetric 3 × 3 times the matrix is the identity.
    #[test]
    fn gauss_jordan_inverse() {
        let a = [4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0];
        let inv = inverse(&a, 3).unwrap();
        for i in 0..3 {
            for j in 0..3 {
                let v: f64 = (0..3).map(|l| a[i * 3 + l] * inv[l * 3 + j]).sum();
                assert!(
                    (v - f64::from(u8::from(i == j))).abs() < 1e-14,
                    "{i}{j}: {v}"
                );
            }
        }
        assert!(inverse(&[1.0, 2.0, 2.0, 4.0], 2).is_none());
    }
}
