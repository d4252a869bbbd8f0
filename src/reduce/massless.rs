//! Massless dofs: dofs with a zero mass row and column (rotations of lumped beams without rotary
//! inertia, e.g. Nastran's lumped CBAR; massless spider centres; rotations of solid–beam joints).
//!
//! A massless dof with stiffness is harmless to every method: the shift-invert eigensolvers
//! apply (K − σM)⁻¹ with a zero right-hand side on it, which is its exact static condensation
//! (its eigenvalue is infinite and never computed), and the orthonormalization condenses massless
//! basis directions statically ([`super::orthonormalize`]). What breaks them is a motion of the
//! massless dofs with no stiffness either, z with Kz = 0 and Mz = 0 (e.g. the rotation of a free
//! lumped CBAR line about its own axis): K − σM is singular for every σ. Such a motion carries no
//! energy of either kind, so holding one dof of it at zero changes no eigenvalue and no mode
//! except by a multiple of z itself (for PSD K, a null vector of K_ss, s the massless dofs, is a
//! null vector of K). [`analyse`] finds these dofs (zero pivots of K_ss) and [`on_held`] runs a
//! method with them held and expands its modes back.

use super::{ModeSet, ReduceError};
use crate::solve::cholesky::SINGULAR_PIVOT;
use crate::solve::{sparse_ops, SolveError, SparseColMat, SparseLlt};
use faer::{Mat, Par};

/// At most this many zero-mass zero-stiffness motions are held (each needs a factorization of
/// K_ss); more means the massless dofs are mostly unconnected and is reported as an error.
pub const MAX_HELD: usize = 64;

/// The massless dofs of a model and the dofs held to remove their zero-energy motions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MasslessDofs {
    /// Dofs with a zero mass column (ascending).
    pub massless: Vec<usize>,
    /// One dof per motion of the massless dofs with neither mass nor stiffness (ascending).
    pub held: Vec<usize>,
}

/// Dofs whose column of `m` holds no nonzero value.
pub fn massless_dofs(m: &SparseColMat<usize, f64>) -> Vec<usize> {
    (0..m.ncols())
        .filter(|&j| m.val_of_col(j).iter().all(|&v| v == 0.0))
        .collect()
}

/// Finds the massless dofs of (K, M) and, among them (except `fixed`, dofs held anyway), one dof
/// per zero-energy motion: zero pivots of K_ss are held one at a time until K_ss factors. A
/// `protected` dof (interface, attachment) is not held when another dof of the same motion can
/// be: the motion's null vector is recovered and its largest unprotected component held.
pub fn analyse(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    fixed: &[usize],
    protected: &[usize],
    par: Par,
) -> Result<MasslessDofs, ReduceError> {
    let mut is_protected = vec![false; k.nrows()];
    for &d in protected {
        if d < is_protected.len() {
            is_protected[d] = true;
        }
    }
    let massless = massless_dofs(m);
    let mut is_fixed = vec![false; k.nrows()];
    for &d in fixed {
        if d < is_fixed.len() {
            is_fixed[d] = true;
        }
    }
    let set: Vec<usize> = massless.iter().copied().filter(|&d| !is_fixed[d]).collect();
    let mut held = factor_holding(k, set, &is_protected, par)?.held;
    held.sort_unstable();
    Ok(MasslessDofs { massless, held })
}

/// The block K_ss of a set of massless dofs factored once its zero-energy motions are held.
struct HeldFactor {
    /// Dofs held, one per motion with neither mass nor stiffness (in the order found).
    held: Vec<usize>,
    /// The rest of the set (ascending), the rows and columns of `llt`.
    free: Vec<usize>,
    /// LLᵀ of K over `free` (`None` when nothing is left).
    llt: Option<SparseLlt>,
}

/// Factors K_ss over the massless dofs `set`, holding one dof per zero pivot (an unprotected one
/// of the same motion where `is_protected` marks the pivot's dof) until K_ss factors.
fn factor_holding(
    k: &SparseColMat<usize, f64>,
    mut set: Vec<usize>,
    is_protected: &[bool],
    par: Par,
) -> Result<HeldFactor, ReduceError> {
    let total = set.len();
    let mut held = Vec::new();
    while !set.is_empty() {
        let kss = sparse_ops::submatrix(k.as_ref(), &set, &set)?;
        let zero = match SparseLlt::factor(kss.as_ref(), None, par) {
            Err(SolveError::NonPositivePivot { dof }) => dof,
            Err(e) => return Err(e.into()),
            Ok(l) if l.min_pivot().0 <= SINGULAR_PIVOT => l.min_pivot().1,
            Ok(l) => {
                return Ok(HeldFactor {
                    held,
                    free: set,
                    llt: Some(l),
                })
            }
        };
        if held.len() == MAX_HELD {
            return Err(ReduceError::Rigid(format!(
                "more than {MAX_HELD} motions of the {total} massless dofs have no stiffness \
                 either: the massless dofs are not connected to the structure (e.g. rotations of \
                 nodes that only solids or rods attach to); remove them or give them mass"
            )));
        }
        let zero = if is_protected[set[zero]] {
            unprotected_dof_of_motion(&kss, zero, &set, is_protected, par)?.unwrap_or(zero)
        } else {
            zero
        };
        held.push(set.remove(zero));
    }
    Ok(HeldFactor {
        held,
        free: set,
        llt: None,
    })
}

/// A basis with its massless dofs statically condensed, from [`condense_basis`].
pub struct CondensedBasis {
    /// T with the rows of the condensed massless dofs replaced.
    pub t: Mat<f64>,
    /// Massless dofs condensed.
    pub condensed: usize,
    /// Massless dofs kept as they were, one per motion with neither mass nor stiffness.
    pub held: usize,
}

/// Static condensation of the massless dofs in every column of a basis T (Guyan 1965, exact on
/// a set without inertia): T_s ← T_s − K_ss⁻¹ (K T)_s, i.e. u_s = −K_ss⁻¹ K_sm u_m, so that
/// (K T)_s = 0. With `kt` = K T. The massless dofs are those of [`massless_dofs`] except
/// `fixed` (held at zero by every column: reference conditions), less one dof per motion with
/// neither mass nor stiffness (kept as it is: such a motion changes no energy).
///
/// This is the K-orthogonal projection of each column onto {u : (K u)_s = 0}, where the model's
/// finite modes live: M T is unchanged (M has no entry in a massless row or column) and TᵀKT
/// can only decrease, so every Ritz value lies in the finite spectrum and no basis direction is
/// (nearly) massless motion. Uncondensed, the constraint modes of the drilling rotations of two
/// shell nodes with lumped translational mass (20 × 20 CQUAD4 plate, `--interface 1,441`) made
/// modes at 2.1 and 2.4 MHz, where λ_max(K_mm, M_mm) is 34.5 kHz; condensed, 10.5 and 11.6 kHz.
/// `None` when no column violates (K T)_s = 0 beyond the rounding of K T
/// (ROUNDING_FACTOR·ε·‖|K||t_j|‖): eigenvectors, and the constraint and fixed-interface modes of
/// an interface without massless dofs, are condensed already.
pub fn condense_basis(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    t: &Mat<f64>,
    kt: &Mat<f64>,
    fixed: &[usize],
    par: Par,
) -> Result<Option<CondensedBasis>, ReduceError> {
    let mut is_fixed = vec![false; k.nrows()];
    for &d in fixed {
        if d < is_fixed.len() {
            is_fixed[d] = true;
        }
    }
    let set: Vec<usize> = massless_dofs(m)
        .into_iter()
        .filter(|&d| !is_fixed[d])
        .collect();
    if set.is_empty() {
        return Ok(None);
    }
    let (_, abs_norms) = sparse_ops::abs_products(k.as_ref(), t.as_ref());
    let violates = (0..t.ncols()).any(|j| {
        let r2: f64 = set.iter().map(|&i| kt[(i, j)] * kt[(i, j)]).sum();
        r2.sqrt() > sparse_ops::ROUNDING_FACTOR * f64::EPSILON * abs_norms[j]
    });
    if !violates {
        return Ok(None);
    }
    let HeldFactor { held, free, llt } = factor_holding(k, set, &vec![false; k.nrows()], par)?;
    let Some(llt) = llt else {
        return Ok(None);
    };
    let mut x = Mat::from_fn(free.len(), t.ncols(), |r, j| kt[(free[r], j)]);
    llt.solve_in_place(x.as_mut());
    let mut out = t.clone();
    for j in 0..t.ncols() {
        for (r, &i) in free.iter().enumerate() {
            out[(i, j)] -= x[(r, j)];
        }
    }
    Ok(Some(CondensedBasis {
        t: out,
        condensed: free.len(),
        held: held.len(),
    }))
}

/// The local index of the unprotected dof with the largest component in the null vector of
/// `kss` through its zero pivot `zero`: v_zero = 1, the rest −K_rr⁻¹ K_r,zero (`None` when the
/// rest is singular too or no unprotected component is significant).
fn unprotected_dof_of_motion(
    kss: &SparseColMat<usize, f64>,
    zero: usize,
    set: &[usize],
    is_protected: &[bool],
    par: Par,
) -> Result<Option<usize>, ReduceError> {
    let rest = crate::solve::sparse_ops::complement(&[zero], kss.nrows());
    let krr = sparse_ops::submatrix(kss.as_ref(), &rest, &rest)?;
    let l = match SparseLlt::factor(krr.as_ref(), None, par) {
        Ok(l) if l.min_pivot().0 > SINGULAR_PIVOT => l,
        _ => return Ok(None),
    };
    let krz = sparse_ops::submatrix(kss.as_ref(), &rest, &[zero])?;
    let mut v = sparse_ops::to_dense(krz.as_ref());
    l.solve_in_place(v.as_mut());
    // v holds K_rr⁻¹ K_rz = −(null vector on `rest`); component at `zero` is 1
    let best = rest
        .iter()
        .enumerate()
        .filter(|&(_, &i)| !is_protected[set[i]])
        .map(|(r, &i)| (i, v[(r, 0)].abs()))
        .fold(None, |b: Option<(usize, f64)>, (i, a)| match b {
            Some((_, ba)) if ba >= a => b,
            _ => Some((i, a)),
        });
    Ok(best.filter(|&(_, a)| a > 1e-3).map(|(i, _)| i))
}

/// Runs `method` on (K, M) with the `held` dofs removed and expands its Φ back to all dofs (zero
/// rows at `held`). `method` gets the reduced matrices and the map old dof → new dof
/// (`usize::MAX` for a held dof); the set's diagnostics record the counts.
pub fn on_held<F>(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    dofs: &MasslessDofs,
    method: F,
) -> Result<ModeSet, ReduceError>
where
    F: FnOnce(
        &SparseColMat<usize, f64>,
        &SparseColMat<usize, f64>,
        &[usize],
    ) -> Result<ModeSet, ReduceError>,
{
    let n = k.nrows();
    let mut set = if dofs.held.is_empty() {
        let identity: Vec<usize> = (0..n).collect();
        method(k, m, &identity)?
    } else {
        let kept = crate::solve::sparse_ops::complement(&dofs.held, n);
        let mut map = vec![usize::MAX; n];
        for (r, &d) in kept.iter().enumerate() {
            map[d] = r;
        }
        let kk = sparse_ops::submatrix(k.as_ref(), &kept, &kept)?;
        let mk = sparse_ops::submatrix(m.as_ref(), &kept, &kept)?;
        let mut set = method(&kk, &mk, &map)?;
        let mut phi = Mat::<f64>::zeros(n, set.phi.ncols());
        for j in 0..phi.ncols() {
            for (r, &d) in kept.iter().enumerate() {
                phi[(d, j)] = set.phi[(r, j)];
            }
        }
        set.phi = phi;
        set.reference_dofs = set.reference_dofs.iter().map(|&r| kept[r]).collect();
        set.diagnostics.notes.push(format!(
            "{} motion(s) of the massless dofs with neither mass nor stiffness (e.g. the rotation \
             of a line of point masses about itself) held at dof(s) {:?}: they change no mode",
            dofs.held.len(),
            dofs.held
        ));
        set
    };
    set.diagnostics.massless_dofs = dofs.massless.len();
    set.diagnostics.held_massless = dofs.held.clone();
    if !dofs.massless.is_empty() {
        set.diagnostics.notes.push(format!(
            "{} massless dofs (zero mass row and column) condensed statically by the \
             shift-invert solves (their eigenvalues are infinite)",
            dofs.massless.len()
        ));
    }
    Ok(set)
}

/// Maps dof indices through `map` (from [`on_held`]); a held dof is an error naming `what`.
pub fn map_dofs(
    map: &[usize],
    dofs: &[usize],
    what: &'static str,
) -> Result<Vec<usize>, ReduceError> {
    dofs.iter()
        .map(|&d| match map.get(d) {
            Some(&r) if r != usize::MAX => Ok(r),
            _ => Err(ReduceError::Dofs {
                what,
                detail: format!(
                    "dof {d} is held: it belongs to a motion of massless dofs with neither mass \
                     nor stiffness"
                ),
            }),
        })
        .collect()
}
