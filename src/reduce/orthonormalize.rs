//! Orthonormalization of a reduction basis T by the second (dense) eigenproblem
//! K̂N = M̂NΛ with K̂ = TᵀKT, M̂ = TᵀMT (Craig–Bampton, Craig–Chang, Dietz), after a rank-revealing
//! pivoted Cholesky of the diagonally scaled M̂ that removes dependent basis vectors.

use super::{Diagnostics, ModeLabel, ReduceError, RemovedVector};
use crate::solve::{dense, sparse_ops::abs_energy, sparse_ops::spmm, trace_ratio, SolveError};
use faer::sparse::SparseColMat;
use faer::Mat;

/// Relative pivot tolerance of the rank-revealing step: a basis column is dependent when the
/// M-norm² left after projecting out the kept columns is below this fraction of its own
/// (i.e. it is within angle ~1e-4 rad of their span), see [`orthonormalize`].
pub const DEPENDENCY_TOL: f64 = 1e-8;

/// ω² ≤ RIGID_REL · scale (scale = [`trace_ratio`], the median K_ii/M_ii) counts as a rigid-body
/// mode, besides the per-vector rounding floor of [`rigid_flags`]. Was 1e-9: on a free beam of
/// 1000 elements the first bending pair lies at 4e-11 of the scale and was taken for two more
/// rigid modes (docs/stability.md, row 2); computed rigid ω² are ~1e-16 of it.
pub const RIGID_REL: f64 = 1e-12;

/// Per column of Φ: is ω²_j a rigid-body (zero) eigenvalue? |ω²_j| ≤ RIGID_REL·scale (scale =
/// [`trace_ratio`]), or within the rounding floor ROUNDING_FACTOR·ε·(|φ_j|ᵀ|K||φ_j|) that a stiff
/// insert leaves on a rigid mode (a 1e10 contrast put rigid ω² at 1e-4 of the first flexible one,
/// docs/stability.md row 7).
pub fn rigid_flags(
    k: &SparseColMat<usize, f64>,
    phi: &Mat<f64>,
    omega2: &[f64],
    scale: f64,
) -> Vec<bool> {
    let (energy, _) = crate::solve::sparse_ops::abs_products(k.as_ref(), phi.as_ref());
    omega2
        .iter()
        .zip(energy)
        .map(|(&l, e)| l.abs() <= (RIGID_REL * scale).max(ROUNDING_FACTOR * f64::EPSILON * e))
        .collect()
}

/// Kind of a label (its variant, without the dof or index it carries).
fn kind(l: &ModeLabel) -> usize {
    match l {
        ModeLabel::Rigid => 0,
        ModeLabel::Normal => 1,
        ModeLabel::Constraint { .. } => 2,
        ModeLabel::FixedInterface { .. } => 3,
        ModeLabel::Attachment { .. } => 4,
        ModeLabel::FrequencyResponse { .. } => 5,
    }
}

/// Labels of the modes φ_j = Σ_c T_c N_cj of an orthonormalized multi-stage basis, and the share
/// of the origin each label names (SPEC.md §5.5). With w_cj = N_cj·√(T_cᵀMT_c) (`weights`, row c
/// = basis column `basis[c]`), the share of origin kind k in mode j is Σ_{c∈k} w_cj² / Σ_c w_cj².
/// `Rigid` only where `rigid[j]` (the zero-frequency test of [`rigid_flags`], the same for every
/// method; share 1); any other mode gets the non-rigid kind with the largest share, named by its
/// column of largest |w_cj|.
pub fn origin_labels(
    rigid: &[bool],
    weights: &Mat<f64>,
    basis: &[ModeLabel],
) -> (Vec<ModeLabel>, Vec<f64>) {
    let q = basis.len();
    (0..rigid.len())
        .map(|j| {
            if rigid[j] {
                return (ModeLabel::Rigid, 1.0);
            }
            let mut by_kind = [0.0f64; 6];
            let mut total = 0.0;
            for (c, l) in basis.iter().enumerate().take(q) {
                let w2 = weights[(c, j)].powi(2);
                by_kind[kind(l)] += w2;
                total += w2;
            }
            let best_kind = (1..6).fold(1, |b, k| if by_kind[k] > by_kind[b] { k } else { b });
            let column = (0..q)
                .filter(|&c| kind(&basis[c]) == best_kind)
                .max_by(|&a, &b| weights[(a, j)].abs().total_cmp(&weights[(b, j)].abs()));
            let label = column.map_or(ModeLabel::Normal, |c| basis[c].clone());
            let share = if total > 0.0 {
                by_kind[best_kind] / total
            } else {
                0.0
            };
            (label, share)
        })
        .unzip()
}

/// Limit enforced on ‖ΦᵀMΦ − I‖_max and ‖ΦᵀKΦ − diag‖_max/max ω² of every returned set.
pub const CHECK_LIMIT: f64 = 1e-9;

/// An orthonormalized basis.
#[derive(Clone, Debug)]
pub struct Orthonormalized {
    /// Φ = T_kept · N, n × modes.
    pub phi: Mat<f64>,
    /// ω², ascending.
    pub omega2: Vec<f64>,
    /// Label per mode: rigid, or the origin of its dominant basis component.
    pub labels: Vec<ModeLabel>,
    /// Kept basis columns (indices into T).
    pub kept: Vec<usize>,
    /// Checked diagnostics (orthonormality, stiffness, residuals, removed vectors).
    pub diagnostics: Diagnostics,
}

/// Pivoted Cholesky of a symmetric positive semi-definite matrix `a` with unit diagonal: the
/// greedily chosen pivots (largest remaining diagonal first) until it falls below `tol`, and the
/// remaining diagonal of every column.
fn pivoted_cholesky(a: &Mat<f64>, tol: f64) -> (Vec<usize>, Vec<f64>) {
    let p = a.nrows();
    let mut l = Mat::<f64>::zeros(p, p);
    let mut d: Vec<f64> = (0..p).map(|i| a[(i, i)]).collect();
    let mut chosen = vec![false; p];
    let mut piv = Vec::new();
    for step in 0..p {
        let (mut best, mut bv) = (usize::MAX, tol);
        for j in 0..p {
            if !chosen[j] && d[j] > bv {
                best = j;
                bv = d[j];
            }
        }
        if best == usize::MAX {
            break;
        }
        chosen[best] = true;
        piv.push(best);
        let s = d[best].sqrt();
        for j in 0..p {
            if chosen[j] && j != best {
                continue;
            }
            let mut v = a[(j, best)];
            for q in 0..step {
                v -= l[(j, q)] * l[(best, q)];
            }
            l[(j, step)] = v / s;
        }
        for j in 0..p {
            if !chosen[j] {
                d[j] -= l[(j, step)] * l[(j, step)];
            }
        }
    }
    (piv, d)
}

pub use crate::solve::sparse_ops::ROUNDING_FACTOR;

/// Full-model quality figures of Φ with ω²; errors when orthonormality or the stiffness diagonal
/// exceed [`CHECK_LIMIT`] (the stiffness one raised to the rounding floor of ΦᵀKΦ when that is
/// higher, see [`ROUNDING_FACTOR`]).
pub fn diagnose(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    phi: &Mat<f64>,
    omega2: &[f64],
) -> Result<Diagnostics, ReduceError> {
    let kp = spmm(k.as_ref(), phi.as_ref());
    let mp = spmm(m.as_ref(), phi.as_ref());
    let kk = phi.transpose() * &kp;
    let mm = phi.transpose() * &mp;
    let c = omega2.len();
    let lmax = omega2
        .iter()
        .fold(0.0f64, |a, &b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE);
    let (mut orth, mut kd) = (0.0f64, 0.0f64);
    for j in 0..c {
        for i in 0..c {
            let id = if i == j { 1.0 } else { 0.0 };
            orth = orth.max((mm[(i, j)] - id).abs());
            kd = kd.max((kk[(i, j)] - id * omega2[j]).abs() / lmax);
        }
    }
    let mut residuals = Vec::with_capacity(c);
    for j in 0..c {
        let (mut rn, mut kn) = (0.0, 0.0);
        for i in 0..phi.nrows() {
            let r = kp[(i, j)] - omega2[j] * mp[(i, j)];
            rn += r * r;
            kn += kp[(i, j)] * kp[(i, j)];
        }
        residuals.push(if kn > 0.0 {
            (rn / kn).sqrt()
        } else {
            rn.sqrt()
        });
    }
    let k_limit = CHECK_LIMIT
        .max(ROUNDING_FACTOR * f64::EPSILON * abs_energy(k.as_ref(), phi.as_ref()) / lmax);
    for (what, value, limit) in [
        ("|PhiT M Phi - I|max", orth, CHECK_LIMIT),
        ("|PhiT K Phi - diag|max / max w2", kd, k_limit),
    ] {
        if value.is_nan() || value > limit {
            return Err(SolveError::CheckFailed { what, value, limit }.into());
        }
    }
    Ok(Diagnostics {
        orthonormality: orth,
        stiffness_diag: kd,
        residuals,
        ..Default::default()
    })
}

/// Solves K̂N = M̂NΛ for the basis `t` (n × p, columns labelled by `labels`) and returns
/// Φ = T·N with ΦᵀMΦ = I, ΦᵀKΦ = diag(ω²).
///
/// Dependent columns are removed first: with D = diag(M̂)^-½, a pivoted Cholesky of D M̂ D keeps
/// columns while their remaining M-norm² exceeds [`DEPENDENCY_TOL`]; the others are reported in
/// `diagnostics.removed`. A second Rayleigh–Ritz pass on Φ restores orthonormality to rounding.
pub fn orthonormalize(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    t: &Mat<f64>,
    labels: &[ModeLabel],
) -> Result<Orthonormalized, ReduceError> {
    let p = t.ncols();
    let kt = spmm(k.as_ref(), t.as_ref());
    let mt = spmm(m.as_ref(), t.as_ref());
    let kh = dense::sym((t.transpose() * &kt).as_ref());
    let mh = dense::sym((t.transpose() * &mt).as_ref());
    let dscale: Vec<f64> = (0..p)
        .map(|j| {
            if mh[(j, j)] > 0.0 {
                1.0 / mh[(j, j)].sqrt()
            } else {
                0.0
            }
        })
        .collect();
    let ms = Mat::from_fn(p, p, |i, j| mh[(i, j)] * dscale[i] * dscale[j]);
    let (mut kept, rem) = pivoted_cholesky(&ms, DEPENDENCY_TOL);
    kept.sort_unstable();
    if kept.is_empty() {
        return Err(ReduceError::EmptyBasis);
    }
    let mut is_kept = vec![false; p];
    for &c in &kept {
        is_kept[c] = true;
    }
    let removed: Vec<RemovedVector> = (0..p)
        .filter(|&c| !is_kept[c])
        .map(|c| RemovedVector {
            column: c,
            label: labels[c].clone(),
            remaining: rem[c].max(0.0),
        })
        .collect();
    let q = kept.len();
    let ks = Mat::from_fn(q, q, |i, j| kh[(kept[i], kept[j])]);
    let mss = Mat::from_fn(q, q, |i, j| mh[(kept[i], kept[j])]);
    let (_, y) = dense::projected(ks.as_ref(), mss.as_ref())?;
    let ts = Mat::from_fn(t.nrows(), q, |i, j| t[(i, kept[j])]);
    let phi1 = &ts * &y;
    // second pass on the (now well-conditioned) Φ
    let k1 = phi1.transpose() * spmm(k.as_ref(), phi1.as_ref());
    let m1 = phi1.transpose() * spmm(m.as_ref(), phi1.as_ref());
    let (omega2, y2) = dense::projected(k1.as_ref(), m1.as_ref())?;
    let phi = &phi1 * &y2;
    let n = &y * &y2; // coefficients of Φ on the kept columns
    let scale = trace_ratio(k, m);
    let rigid = rigid_flags(k, &phi, &omega2, scale);
    let kept_labels: Vec<ModeLabel> = kept.iter().map(|&c| labels[c].clone()).collect();
    let weights = Mat::from_fn(q, q, |r, j| {
        n[(r, j)] * mh[(kept[r], kept[r])].max(0.0).sqrt()
    });
    let (labels_out, shares) = origin_labels(&rigid, &weights, &kept_labels);
    let mut diagnostics = diagnose(k, m, &phi, &omega2)?;
    diagnostics.removed = removed;
    diagnostics.dependency_tol = DEPENDENCY_TOL;
    diagnostics.label_shares = shares;
    Ok(Orthonormalized {
        phi,
        omega2,
        labels: labels_out,
        kept,
        diagnostics,
    })
}
