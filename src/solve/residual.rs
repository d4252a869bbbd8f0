//! The relative residual of each returned eigenpair on the problem's own K and M, as the file
//! records it (`eigen_residuals.bin`, SPEC §5.17): computed once from the vectors, never taken
//! from a solver's own estimate.

use faer::{Mat, MatRef};

#[cfg(doc)]
use super::trace_ratio;
use super::{sparse_ops, SparseColMat};

/// Columns multiplied at a time: K·X and M·X for 16 vectors at once (2 × 16 × 8 bytes per
/// dof: 256 MB at a million dofs) whatever the mode count.
const COLUMNS: usize = 16;

/// Rigid modes are measured against this fraction of the stiffness-over-mass scale s: the
/// rigid threshold of [`super::is_flexible`].
pub const RIGID_FRACTION: f64 = 1e-8;

/// Per column φ_j of `x` with eigenvalue `values[j]`: (‖Kφ_j − λ_j Mφ_j‖₂, the denominator
/// max(‖Kφ_j‖₂, 10⁻⁸ s ‖Mφ_j‖₂)), s = `scale`.
fn residual_parts(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    x: MatRef<'_, f64>,
    values: &[f64],
    scale: f64,
) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(x.ncols());
    let mut start = 0;
    while start < x.ncols() {
        let c = COLUMNS.min(x.ncols() - start);
        let block = x.subcols(start, c);
        let kx: Mat<f64> = sparse_ops::spmm(k.as_ref(), block);
        let mx: Mat<f64> = sparse_ops::spmm(m.as_ref(), block);
        for j in 0..c {
            let lambda = values[start + j];
            let (mut rn, mut kn, mut mn) = (0.0f64, 0.0f64, 0.0f64);
            for i in 0..x.nrows() {
                let (a, b) = (kx[(i, j)], mx[(i, j)]);
                let r = a - lambda * b;
                rn += r * r;
                kn += a * a;
                mn += b * b;
            }
            out.push((rn.sqrt(), kn.sqrt().max(RIGID_FRACTION * scale * mn.sqrt())));
        }
        start += c;
    }
    out
}

/// r_j = ‖Kφ_j − λ_j Mφ_j‖₂ / max(‖Kφ_j‖₂, 10⁻⁸ s ‖Mφ_j‖₂) per column φ_j of `x` (SPEC §5.17),
/// s = `scale`, the median of K_ii/M_ii ([`trace_ratio`]): the plain ‖Kφ − λMφ‖/‖Kφ‖ of every
/// flexible mode, and for a rigid mode (‖Kφ‖ rounding noise) its residual against the rigid
/// threshold's scale. One sparse K·φ and M·φ per mode.
pub fn relative_residuals(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    x: MatRef<'_, f64>,
    values: &[f64],
    scale: f64,
) -> Vec<f64> {
    residual_parts(k, m, x, values, scale)
        .into_iter()
        .map(|(r, d)| if d > 0.0 { r / d } else { 0.0 })
        .collect()
}

/// What rounding alone may leave in [`relative_residuals`]: ROUNDING_FACTOR · ε · ‖|K||φ_j|‖₂
/// over the same denominator (the floating-point bound of K·φ, as the solvers' own checks
/// take it, [`sparse_ops::ROUNDING_FACTOR`]).
pub fn rounding_floors(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    x: MatRef<'_, f64>,
    scale: f64,
) -> Vec<f64> {
    let (_, abs_norm) = sparse_ops::abs_products(k.as_ref(), x);
    let zeros = vec![0.0; x.ncols()];
    residual_parts(k, m, x, &zeros, scale)
        .into_iter()
        .zip(abs_norm)
        .map(|((_, d), a)| {
            let floor = sparse_ops::ROUNDING_FACTOR * f64::EPSILON * a;
            if d > 0.0 {
                floor / d
            } else {
                floor
            }
        })
        .collect()
}
