//! Small dense linear algebra of the element kernels, in one place: Gaussian elimination and
//! the static condensation of internal dofs (incompatible modes, a curved shell's centre node).

use super::ElementError;

/// Solve A X = B in place (A n×n, B n×m, row-major) by Gaussian elimination with partial
/// pivoting; `None` when A is singular to rounding.
pub fn solve_dense(a: &mut [f64], n: usize, b: &mut [f64], m: usize) -> Option<()> {
    let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for c in 0..n {
        let piv = (c..n).max_by(|&i, &j| a[i * n + c].abs().total_cmp(&a[j * n + c].abs()))?;
        let p = a[piv * n + c].abs();
        if p.is_nan() || p <= 1e-13 * scale {
            return None;
        }
        for j in 0..n {
            a.swap(c * n + j, piv * n + j);
        }
        for j in 0..m {
            b.swap(c * m + j, piv * m + j);
        }
        for r in c + 1..n {
            let f = a[r * n + c] / a[c * n + c];
            if f == 0.0 {
                continue;
            }
            for j in c..n {
                a[r * n + j] -= f * a[c * n + j];
            }
            for j in 0..m {
                b[r * m + j] -= f * b[c * m + j];
            }
        }
    }
    for c in (0..n).rev() {
        for j in 0..m {
            let s: f64 = (c + 1..n).map(|q| a[c * n + q] * b[q * m + j]).sum();
            b[c * m + j] = (b[c * m + j] - s) / a[c * n + c];
        }
    }
    Some(())
}

/// Static condensation of the last `ni` dofs of the symmetric `k` ((nc + ni)², row-major):
/// K_cc − K_ci K_ii⁻¹ K_ic (nc², symmetrized); `singular` names K_ii in the error when it is
/// singular.
pub fn condense(k: &[f64], nc: usize, ni: usize, singular: &str) -> Result<Vec<f64>, ElementError> {
    let nt = nc + ni;
    let mut kii: Vec<f64> = (0..ni * ni)
        .map(|q| k[(nc + q / ni) * nt + nc + q % ni])
        .collect();
    // right-hand sides K_ic (ni × nc)
    let mut x: Vec<f64> = (0..ni * nc)
        .map(|q| k[(nc + q / nc) * nt + q % nc])
        .collect();
    solve_dense(&mut kii, ni, &mut x, nc).ok_or_else(|| {
        ElementError::BadConstants(format!("singular {singular} (degenerate element)"))
    })?;
    let mut out = vec![0.0; nc * nc];
    for i in 0..nc {
        for j in 0..nc {
            let corr: f64 = (0..ni).map(|m| k[i * nt + nc + m] * x[m * nc + j]).sum();
            out[i * nc + j] = k[i * nt + j] - corr;
        }
    }
    symmetrize(&mut out, nc);
    Ok(out)
}

/// (A + Aᵀ)/2 in place (n × n, row-major).
pub fn symmetrize(a: &mut [f64], n: usize) {
    for i in 0..n {
        for j in 0..i {
            let v = 0.5 * (a[i * n + j] + a[j * n + i]);
            a[i * n + j] = v;
            a[j * n + i] = v;
        }
    }
}
