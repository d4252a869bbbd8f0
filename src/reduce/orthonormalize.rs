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
    rigid_flags_of_energy(&energy, omega2, scale)
}

/// [`rigid_flags`] with the energies (|φ_j|ᵀ|K||φ_j|) already at hand.
fn rigid_flags_of_energy(energy: &[f64], omega2: &[f64], scale: f64) -> Vec<bool> {
    omega2
        .iter()
        .zip(energy)
        .map(|(&l, &e)| l.abs() <= (RIGID_REL * scale).max(ROUNDING_FACTOR * f64::EPSILON * e))
        .collect()
}

/// Number of label kinds of [`kind`].
const KINDS: usize = 7;

/// Kind of a label (its variant, without the dof or index it carries).
fn kind(l: &ModeLabel) -> usize {
    match l {
        ModeLabel::Rigid => 0,
        ModeLabel::Normal => 1,
        ModeLabel::Constraint { .. } => 2,
        ModeLabel::FixedInterface { .. } => 3,
        ModeLabel::Attachment { .. } => 4,
        ModeLabel::FrequencyResponse { .. } => 5,
        ModeLabel::Residual { .. } => 6,
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
            let mut by_kind = [0.0f64; KINDS];
            let mut total = 0.0;
            for (c, l) in basis.iter().enumerate().take(q) {
                let w2 = weights[(c, j)].powi(2);
                by_kind[kind(l)] += w2;
                total += w2;
            }
            let best_kind = (1..KINDS).fold(1, |b, k| if by_kind[k] > by_kind[b] { k } else { b });
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
    /// N: the modes' coefficients on the columns of T (Φ = T N), T's columns × modes.
    pub coefficients: Mat<f64>,
    /// Checked diagnostics (orthonormality, stiffness, residuals, removed vectors).
    pub diagnostics: Diagnostics,
}

/// Pivots within this factor of the largest remaining diagonal are numerically equal choices;
/// among them the stiffest-per-mass column is taken last ([`pivoted_cholesky`]).
pub const PIVOT_BAND: f64 = 0.5;

/// Pivoted Cholesky of a symmetric positive semi-definite matrix `a` with unit diagonal: the
/// greedily chosen pivots until the remaining diagonal falls below `tol`, and the remaining
/// diagonal of every column. Each pivot is, among the columns whose remaining diagonal is within
/// [`PIVOT_BAND`] of the largest, the one of least `rayleigh` (K̂_jj/M̂_jj; ties: lowest index):
/// of two M-dependent columns the softer is kept and the stiffer removed — a rigid motion is
/// kept exactly, and the stiff column left is what it is, a massless direction to condense
/// (a lumped beam's twist that moves only an offset mass: the twist of the fixed-interface
/// mode has no mass of its own).
fn pivoted_cholesky(a: &Mat<f64>, tol: f64, rayleigh: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let p = a.nrows();
    let mut l = Mat::<f64>::zeros(p, p);
    let mut d: Vec<f64> = (0..p).map(|i| a[(i, i)]).collect();
    let mut chosen = vec![false; p];
    let mut piv = Vec::new();
    for step in 0..p {
        let top = (0..p)
            .filter(|&j| !chosen[j])
            .map(|j| d[j])
            .fold(0.0f64, f64::max);
        let band = (PIVOT_BAND * top).max(tol);
        let mut best = usize::MAX;
        for j in 0..p {
            if !chosen[j] && d[j] > band && (best == usize::MAX || rayleigh[j] < rayleigh[best]) {
                best = j;
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
    diagnose_products(phi, &kp, &mp, omega2, abs_energy(k.as_ref(), phi.as_ref()))
}

/// [`diagnose`] with K·Φ, M·Φ and max_j |φ_j|ᵀ|K||φ_j| already at hand.
fn diagnose_products(
    phi: &Mat<f64>,
    kp: &Mat<f64>,
    mp: &Mat<f64>,
    omega2: &[f64],
    abs_energy_max: f64,
) -> Result<Diagnostics, ReduceError> {
    let kk = phi.transpose() * kp;
    let mm = phi.transpose() * mp;
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
    let k_limit = CHECK_LIMIT.max(ROUNDING_FACTOR * f64::EPSILON * abs_energy_max / lmax);
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
/// Φ = T·N with ΦᵀMΦ = I, ΦᵀKΦ = diag(ω²); [`orthonormalize_held`] with no dof held.
pub fn orthonormalize(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    t: &Mat<f64>,
    labels: &[ModeLabel],
) -> Result<Orthonormalized, ReduceError> {
    orthonormalize_held(k, m, t, labels, &[])
}

/// Solves K̂N = M̂NΛ for the basis `t` (n × p, columns labelled by `labels`, zero at the `held`
/// dofs: reference conditions) and returns Φ = T·N with ΦᵀMΦ = I, ΦᵀKΦ = diag(ω²).
///
/// The massless dofs of T (zero mass row and column, not held) are first condensed statically
/// ([`super::massless::condense_basis`]: T_s ← −K_ss⁻¹K_sm T_m), so that the Ritz problem is
/// that of the model with its massless dofs condensed, whose eigenvalues are the model's finite
/// ones. Dependent columns are removed next: with D = diag(M̂)^-½, a pivoted Cholesky of D M̂ D
/// keeps columns while their remaining M-norm² exceeds [`DEPENDENCY_TOL`]; the others are
/// reported in `diagnostics.removed`, except massless directions, condensed ([`condense_massless`]).
/// A second Rayleigh–Ritz pass on Φ restores orthonormality to rounding.
pub fn orthonormalize_held(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    t: &Mat<f64>,
    labels: &[ModeLabel],
    held: &[usize],
) -> Result<Orthonormalized, ReduceError> {
    orthonormalize_projected(k, m, t, labels, held, None)
}

/// K̂ = TᵀKT and M̂ = TᵀMT of a basis T, formed by the method that built T from what it knows of
/// its columns (Craig–Bampton: [`super::craig_bampton::projection`]) with fewer products with K
/// and M than Tᵀ(K T), Tᵀ(M T).
#[derive(Clone, Debug)]
pub struct Projection {
    /// TᵀKT (p × p).
    pub kh: Mat<f64>,
    /// TᵀMT (p × p).
    pub mh: Mat<f64>,
}

/// The projections of a basis as the orthonormalization uses them.
struct Projected {
    /// K̂ of the basis as given (the stiffness scale of its columns).
    kh_given: Mat<f64>,
    /// The basis with its massless dofs condensed (`None`: nothing to condense).
    condensed: Option<super::massless::CondensedBasis>,
    /// K̂ of the condensed basis.
    kh_condensed: Option<Mat<f64>>,
    /// M̂ of the (condensed) basis.
    mh: Mat<f64>,
}

/// K̂ and M̂ of `t`: `known` when no dof outside `held` is massless (a massless dof may need
/// condensing, which changes T), else TᵀKT and TᵀMT after [`super::massless::condense_basis`].
fn project(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    t_in: &Mat<f64>,
    held: &[usize],
    known: Option<Projection>,
) -> Result<Projected, ReduceError> {
    if let Some(Projection { kh, mh }) = known {
        let massless = super::massless::massless_dofs(m);
        if massless.iter().all(|d| held.contains(d)) {
            return Ok(Projected {
                kh_given: kh,
                condensed: None,
                kh_condensed: None,
                mh,
            });
        }
    }
    let kt = spmm(k.as_ref(), t_in.as_ref());
    let kh_given = dense::sym((t_in.transpose() * &kt).as_ref());
    let condensed =
        super::massless::condense_basis(k, m, t_in, &kt, held, faer::get_global_parallelism())?;
    drop(kt);
    let t = condensed.as_ref().map_or(t_in, |c| &c.t);
    let kh_condensed = condensed
        .as_ref()
        .map(|_| dense::sym((t.transpose() * spmm(k.as_ref(), t.as_ref())).as_ref()));
    let mt = spmm(m.as_ref(), t.as_ref());
    let mh = dense::sym((t.transpose() * &mt).as_ref());
    Ok(Projected {
        kh_given,
        condensed,
        kh_condensed,
        mh,
    })
}

/// [`orthonormalize_held`] with K̂ = TᵀKT and M̂ = TᵀMT given by the caller (`known`, used
/// unless T has massless dofs to condense). They steer the first Rayleigh–Ritz pass and the
/// dependency test only: the second pass and the checks use K·Φ and M·Φ of the result itself.
pub fn orthonormalize_projected(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    t_in: &Mat<f64>,
    labels: &[ModeLabel],
    held: &[usize],
    known: Option<Projection>,
) -> Result<Orthonormalized, ReduceError> {
    let p = t_in.ncols();
    let Projected {
        kh_given,
        condensed,
        kh_condensed,
        mh,
    } = project(k, m, t_in, held, known)?;
    let t = condensed.as_ref().map_or(t_in, |c| &c.t);
    let kh = kh_condensed.as_ref().unwrap_or(&kh_given);
    // a column whose M-norm² is rounding (≤ MASSLESS_COLUMN_TOL of ‖t‖²·max M_ii: a rotation
    // field of a lumped beam without rotary inertia) is massless: kept out of the pivoting, it
    // is condensed below instead of lending its rounding noise a direction
    let m_diag_max = (0..m.ncols())
        .flat_map(|j| {
            m.row_idx_of_col_raw(j)
                .iter()
                .zip(m.val_of_col(j))
                .filter(move |(&i, _)| i == j)
                .map(|(_, &v)| v.abs())
        })
        .fold(0.0f64, f64::max);
    let massless_column = |j: usize| -> bool {
        let norm2: f64 = (0..t_in.nrows()).map(|i| t_in[(i, j)] * t_in[(i, j)]).sum();
        mh[(j, j)] <= MASSLESS_COLUMN_TOL * norm2 * m_diag_max
    };
    let dscale: Vec<f64> = (0..p)
        .map(|j| {
            if mh[(j, j)] > 0.0 && !massless_column(j) {
                1.0 / mh[(j, j)].sqrt()
            } else {
                0.0
            }
        })
        .collect();
    let ms = Mat::from_fn(p, p, |i, j| mh[(i, j)] * dscale[i] * dscale[j]);
    let rayleigh: Vec<f64> = (0..p)
        .map(|j| {
            if dscale[j] > 0.0 {
                kh[(j, j)] * dscale[j] * dscale[j]
            } else {
                f64::INFINITY
            }
        })
        .collect();
    let (mut kept, rem) = pivoted_cholesky(&ms, DEPENDENCY_TOL, &rayleigh);
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
    // Columns left out of the M-independent set are either dependent (T x ≈ 0) or carry a
    // massless direction (M T x = 0 with stiffness): the latter are condensed statically.
    let q = kept.len();
    let cond = condense_massless(&kh_given, kh_condensed.as_ref(), &mh, &kept, &removed)?;
    let g = &cond.g;
    let removed: Vec<RemovedVector> = removed
        .into_iter()
        .filter(|r| !cond.massless.contains(&r.column))
        .collect();
    let (ks, mss, ts) = if cond.massless.is_empty() {
        (
            Mat::from_fn(q, q, |i, j| kh[(kept[i], kept[j])]),
            Mat::from_fn(q, q, |i, j| mh[(kept[i], kept[j])]),
            Mat::from_fn(t.nrows(), q, |i, j| t[(i, kept[j])]),
        )
    } else {
        (
            dense::sym((g.transpose() * kh * g).as_ref()),
            dense::sym((g.transpose() * &mh * g).as_ref()),
            t * g,
        )
    };
    let (_, y) = dense::projected(ks.as_ref(), mss.as_ref())?;
    // second pass on the (now well-conditioned) Φ₁ = T_s Y; Φ = Φ₁Y₂ and its products with K
    // and M (for the checks) are Φ₁'s rotated in place, not formed again
    let mut phi = &ts * &y;
    drop(ts);
    let mut kphi = spmm(k.as_ref(), phi.as_ref());
    let mut mphi = spmm(m.as_ref(), phi.as_ref());
    let k1 = phi.transpose() * &kphi;
    let m1 = phi.transpose() * &mphi;
    let (omega2, y2) = dense::projected(k1.as_ref(), m1.as_ref())?;
    for v in [&mut phi, &mut kphi, &mut mphi] {
        crate::solve::thin_ops::mul_in_place(v.as_mut(), y2.as_ref());
    }
    let n = g * (&y * &y2); // coefficients of Φ on the columns of T
    let scale = trace_ratio(k, m);
    let (energy, _) = crate::solve::sparse_ops::abs_products(k.as_ref(), phi.as_ref());
    let rigid = rigid_flags_of_energy(&energy, &omega2, scale);
    let weights = Mat::from_fn(labels.len(), q, |c, j| {
        n[(c, j)] * mh[(c, c)].max(0.0).sqrt()
    });
    let (labels_out, shares) = origin_labels(&rigid, &weights, labels);
    let abs_energy_max = energy.iter().fold(0.0f64, |a, &b| a.max(b));
    let mut diagnostics = diagnose_products(&phi, &kphi, &mphi, &omega2, abs_energy_max)?;
    drop((kphi, mphi));
    diagnostics.removed = removed;
    diagnostics.dependency_tol = DEPENDENCY_TOL;
    diagnostics.label_shares = shares;
    diagnostics.origin = Some(super::OriginWeights {
        basis: labels.to_vec(),
        weights,
    });
    if let Some(c) = &condensed {
        diagnostics.notes.push(format!(
            "the basis vectors' {} massless dofs condensed statically (u_s = -K_ss^-1 K_sm u_m{}): \
             no mode of a (nearly) massless direction, e.g. an interface rotation without \
             rotary inertia",
            c.condensed,
            if c.held > 0 {
                format!(
                    "; {} dof(s) of motions with neither mass nor stiffness kept as they were",
                    c.held
                )
            } else {
                String::new()
            }
        ));
    }
    if !cond.massless.is_empty() {
        diagnostics.massless_directions = cond.massless.len();
        diagnostics.notes.push(format!(
            "{} massless basis direction(s) (stiffness without mass, e.g. rotations of a lumped \
             beam without rotary inertia) condensed statically{}",
            cond.massless.len(),
            if cond.zero_energy > 0 {
                format!(
                    "; {} of them with neither mass nor stiffness (e.g. the rotation about a \
                     line of point masses) dropped",
                    cond.zero_energy
                )
            } else {
                String::new()
            }
        ));
    }
    Ok(Orthonormalized {
        phi,
        omega2,
        labels: labels_out,
        kept,
        coefficients: n,
        diagnostics,
    })
}

/// A removed column counts as massless (to be condensed) when the stiffness energy left after
/// M-projecting out the kept columns exceeds this fraction of its own: a dependent column leaves
/// (near) nothing in either norm, a massless direction its stiffness.
pub const MASSLESS_ENERGY_TOL: f64 = 1e-6;

/// A basis column t is massless when tᵀMt ≤ MASSLESS_COLUMN_TOL · ‖t‖² · max M_ii: its mass is
/// rounding (a rotation field of a lumped beam without rotary inertia has translations of ~1e-16
/// of its rotations, i.e. ~1e-32 here), not the ≥ 1e-6 of a column that moves any mass.
pub const MASSLESS_COLUMN_TOL: f64 = 1e-20;

/// Static condensation of the massless directions of a basis, in the coefficient space of T.
struct Condensation {
    /// p × q: column j is kept column j with its massless directions condensed,
    /// e_kept − Z K_zz⁺ K_z,kept (Z: the massless residual directions).
    g: Mat<f64>,
    /// Removed columns whose residual is a massless direction.
    massless: Vec<usize>,
    /// Directions of the massless set with no stiffness either (dropped by the pseudo-inverse).
    zero_energy: usize,
}

/// The condensed coefficients G: x = G x_kept with the massless residuals z_j = e_j − kept·C_j
/// (C = M̂_kk⁻¹M̂_kj, so M̂z ≈ 0) at their static optimum z-part = −K_zz⁺K_zk (Guyan on the
/// massless set: exact for it, since it carries no inertia). `kh_given` is K̂ of the basis before
/// [`super::massless::condense_basis`], `kh_condensed` after it (`None`: nothing condensed): a
/// residual is massless by the stiffness it had (after that condensation a massless direction
/// has next to none left, and is then dropped here by the pseudo-inverse); K_zz and K_zk are
/// taken from the condensed K̂, on the scale of the given one.
fn condense_massless(
    kh_given: &Mat<f64>,
    kh_condensed: Option<&Mat<f64>>,
    mh: &Mat<f64>,
    kept: &[usize],
    removed: &[RemovedVector],
) -> Result<Condensation, ReduceError> {
    let (p, q) = (kh_given.nrows(), kept.len());
    let mut g = Mat::<f64>::zeros(p, q);
    for (r, &c) in kept.iter().enumerate() {
        g[(c, r)] = 1.0;
    }
    if removed.is_empty() {
        return Ok(Condensation {
            g,
            massless: vec![],
            zero_energy: 0,
        });
    }
    // C = M̂_kk⁻¹ M̂_kj on the unit-diagonal scaling D M̂_kk D (columns differ by orders of
    // magnitude in M-norm; unscaled, C was measured to lose every digit)
    let dk: Vec<f64> = kept
        .iter()
        .map(|&c| 1.0 / mh[(c, c)].max(f64::MIN_POSITIVE).sqrt())
        .collect();
    let mkk = Mat::from_fn(q, q, |i, j| mh[(kept[i], kept[j])] * dk[i] * dk[j]);
    let l = dense::cholesky(mkk.as_ref()).ok_or(SolveError::DependentBasis)?;
    // residual coefficient vectors of every removed column
    let s_all = removed.len();
    let mut rhs = Mat::from_fn(q, s_all, |i, j| mh[(kept[i], removed[j].column)] * dk[i]);
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(
        l.as_ref(),
        rhs.as_mut(),
        faer::Par::Seq,
    );
    faer::linalg::triangular_solve::solve_upper_triangular_in_place(
        l.transpose(),
        rhs.as_mut(),
        faer::Par::Seq,
    );
    let mut z_all = Mat::<f64>::zeros(p, s_all);
    for j in 0..s_all {
        z_all[(removed[j].column, j)] = 1.0;
        for (r, &c) in kept.iter().enumerate() {
            z_all[(c, j)] -= rhs[(r, j)] * dk[r];
        }
    }
    let kz = kh_given * &z_all;
    let massless_idx: Vec<usize> = (0..s_all)
        .filter(|&j| {
            let c = removed[j].column;
            let own = kh_given[(c, c)];
            let left: f64 = (0..p).map(|i| z_all[(i, j)] * kz[(i, j)]).sum();
            own > 0.0 && left > MASSLESS_ENERGY_TOL * own
        })
        .collect();
    if massless_idx.is_empty() {
        return Ok(Condensation {
            g,
            massless: vec![],
            zero_energy: 0,
        });
    }
    let s = massless_idx.len();
    let z = Mat::from_fn(p, s, |i, j| z_all[(i, massless_idx[j])]);
    // pseudo-inverse of K_zz on the unit-diagonal scaling of the given K̂: directions with no
    // stiffness either (rigid motions without mass), or none left after the condensation of the
    // massless dofs, are dropped
    let kzz_given = dense::sym((z.transpose() * kh_given * &z).as_ref());
    let d: Vec<f64> = (0..s)
        .map(|i| 1.0 / kzz_given[(i, i)].max(f64::MIN_POSITIVE).sqrt())
        .collect();
    let scaled = |a: &Mat<f64>| Mat::from_fn(s, s, |i, j| a[(i, j)] * d[i] * d[j]);
    let (vals_given, vecs_given) = dense::eigh(scaled(&kzz_given).as_ref())?;
    let top = vals_given.iter().fold(0.0f64, |a, &b| a.max(b));
    let zero_energy = (vals_given.iter())
        .filter(|&&v| v <= ZERO_ENERGY_TOL * top)
        .count();
    let kh = kh_condensed.unwrap_or(kh_given);
    let (vals, vecs) = match kh_condensed {
        Some(kc) => dense::eigh(scaled(&dense::sym((z.transpose() * kc * &z).as_ref())).as_ref())?,
        None => (vals_given, vecs_given),
    };
    let kzk = Mat::from_fn(s, q, |i, j| {
        (0..p).map(|r| z[(r, i)] * kh[(r, kept[j])]).sum::<f64>() * d[i]
    });
    // X = D V Λ⁺ Vᵀ D K_zk (D applied to K_zk above)
    let mut x = Mat::<f64>::zeros(s, q);
    for (e, &lam) in vals.iter().enumerate() {
        if lam <= ZERO_ENERGY_TOL * top {
            continue;
        }
        for j in 0..q {
            let proj: f64 = (0..s).map(|i| vecs[(i, e)] * kzk[(i, j)]).sum::<f64>() / lam;
            for i in 0..s {
                x[(i, j)] += d[i] * vecs[(i, e)] * proj;
            }
        }
    }
    let g = g - &z * &x;
    Ok(Condensation {
        g,
        massless: massless_idx.iter().map(|&j| removed[j].column).collect(),
        zero_energy,
    })
}

/// Relative eigenvalue of the scaled massless stiffness below which a massless direction has no
/// stiffness either (a zero-energy, zero-mass motion).
const ZERO_ENERGY_TOL: f64 = 1e-10;
