//! Residual vectors (static correction, Nastran RESVEC): the static response to each scene
//! load added to any method's basis, so the reduced body's quasi-static response to those loads
//! is exact with few modes.
//!
//! For a body with rigid-body modes Xr in the set (free or partly restrained), the response is
//! the inertia-relief one, as Craig–Chang's attachment modes: K r = P f with P = I − M Xr Xrᵀ,
//! solved on a statically determinate support and purified (r ← r − Xr XrᵀM r), so r carries no
//! rigid-body content (XrᵀM r = 0). Dofs the set holds at zero (reference conditions) are held
//! in the solve too. The set's rigid modes are kept as they are; its flexible modes and the
//! residual vectors are made independent and orthonormalized together in the second
//! eigenproblem of [`orthonormalize_held`]; dependent residual vectors (already in the span) are
//! removed and reported.

use super::orthonormalize::{diagnose, origin_labels, orthonormalize_held, Orthonormalized};
use super::OriginWeights;
use super::{ModeLabel, ModeSet, ReduceError};
use crate::solve::inertia_relief::InertiaRelief;
use crate::solve::sparse_ops::complement;
use crate::solve::{sparse_ops, EigenSpec, SolveError, SparseColMat};
use faer::Mat;

/// A load whose inertia-relief part ‖P f‖ is below this fraction of ‖f‖ is a rigid-body load
/// (balanced entirely by the body's inertia): its response is zero and it adds no vector.
pub const BALANCED_TOL: f64 = 1e-10;

/// A static response whose part outside the flexible modes holds less than this fraction of its
/// strain energy (≈ the relative static error of leaving it out) is already in the basis.
pub const RESIDUAL_ENERGY_TOL: f64 = 1e-12;

/// Which static responses to add (`--residual-vectors`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ResidualKind {
    /// One per scene load.
    Loads,
    /// One per interface dof (unit load): the attachment modes.
    Interface,
    /// Both.
    Both,
}

/// What the augmentation did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ResidualReport {
    /// Load columns whose residual vector was removed as dependent (already in the basis), with
    /// the remaining M-norm² fraction.
    pub removed: Vec<(usize, f64)>,
    /// Residual vectors kept.
    pub kept: usize,
    /// Load columns with no static response (the body's inertia balances the load entirely,
    /// or the held dofs take it): no residual vector, and counted nowhere (SPEC §5.7).
    pub no_response: Vec<usize>,
}

/// The static responses r (n × L) to the loads `f` (n × L) of the body `set` describes (module
/// doc): inertia-relief balanced against the set's rigid modes, `set.reference_dofs` held.
pub fn static_responses(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    set: &ModeSet,
    f: &Mat<f64>,
    eig: &EigenSpec,
) -> Result<Mat<f64>, ReduceError> {
    let n = k.nrows();
    if f.nrows() != n {
        return Err(ReduceError::Dofs {
            what: "residual-vector loads",
            detail: format!("{} rows for n = {n}", f.nrows()),
        });
    }
    let mut held = set.reference_dofs.clone();
    held.sort_unstable();
    held.dedup();
    let free = complement(&held, n);
    let rigid: Vec<usize> = (0..set.len())
        .filter(|&j| set.labels[j] == ModeLabel::Rigid)
        .collect();
    let xr = Mat::from_fn(free.len(), rigid.len(), |i, j| set.phi[(free[i], rigid[j])]);
    let fs = Mat::from_fn(free.len(), f.ncols(), |i, j| f[(free[i], j)]);
    let (ks, ms);
    let (kr, mr) = if held.is_empty() {
        (k, m)
    } else {
        ks = sparse_ops::submatrix(k.as_ref(), &free, &free)?;
        ms = sparse_ops::submatrix(m.as_ref(), &free, &free)?;
        (&ks, &ms)
    };
    let ir = InertiaRelief::new(kr, mr, xr, eig).map_err(|e| match e {
        SolveError::NoDeterminateSupport => ReduceError::Solve(e),
        s => ReduceError::Rigid(format!(
            "residual vectors: the static solve failed ({s}); the set's {} rigid-body mode(s) do not cover every zero-stiffness motion of the model",
            rigid.len()
        )),
    })?;
    let pf = ir.equilibrate(&fs);
    // A load the rigid-body inertia balances entirely (gravity on a free body) deforms nothing:
    // its equilibrated part is rounding, and its response is zero, not noise.
    let mut pf = pf;
    for j in 0..pf.ncols() {
        let norm = |x: &Mat<f64>| {
            (0..x.nrows())
                .map(|i| x[(i, j)].powi(2))
                .sum::<f64>()
                .sqrt()
        };
        if norm(&pf) <= BALANCED_TOL * norm(&fs) {
            pf.as_mut().col_mut(j).fill(0.0);
        }
    }
    let rs = ir.solve_equilibrated(&pf);
    let mut r = Mat::<f64>::zeros(n, f.ncols());
    for (a, &i) in free.iter().enumerate() {
        for j in 0..f.ncols() {
            r[(i, j)] = rs[(a, j)];
        }
    }
    Ok(r)
}

/// `set` with the static responses to `f` (n × L, column j labelled `Residual { load: j }`)
/// added (module doc).
pub fn add_residual_vectors(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    set: ModeSet,
    f: &Mat<f64>,
    eig: &EigenSpec,
) -> Result<(ModeSet, ResidualReport), ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let r = static_responses(k, m, &set, f, eig)?;
    let n = k.nrows();
    let rigid: Vec<usize> = (0..set.len())
        .filter(|&j| set.labels[j] == ModeLabel::Rigid)
        .collect();
    let flex: Vec<usize> = (0..set.len())
        .filter(|&j| set.labels[j] != ModeLabel::Rigid)
        .collect();
    let (nf, nl) = (flex.len(), f.ncols());
    // The part of each response the flexible modes miss, r⊥ = r − Φ_f Φ_fᵀ M r (Φ_f is
    // M-orthonormal): a response is already in the basis when r⊥ carries a fraction of its
    // strain energy below RESIDUAL_ENERGY_TOL (the static compliance the basis misses). The
    // M-norm dependency test of the orthonormalization would drop responses whose missing part
    // is small in mass but not in compliance (a static error of ~1e-4 with 12 normal modes).
    let phi_f = Mat::from_fn(n, nf, |i, c| set.phi[(i, flex[c])]);
    let mr = sparse_ops::spmm(m.as_ref(), r.as_ref());
    let coeff = phi_f.transpose() * &mr;
    let r_perp = &r - &phi_f * &coeff;
    let kr = sparse_ops::spmm(k.as_ref(), r.as_ref());
    let kp = sparse_ops::spmm(k.as_ref(), r_perp.as_ref());
    let energy = |a: &Mat<f64>, b: &Mat<f64>, j: usize| -> f64 {
        (0..n).map(|i| a[(i, j)] * b[(i, j)]).sum::<f64>()
    };
    let missing: Vec<f64> = (0..nl)
        .map(|j| {
            let full = energy(&r, &kr, j);
            if full > 0.0 {
                (energy(&r_perp, &kp, j) / full).max(0.0)
            } else {
                0.0
            }
        })
        .collect();
    // A zero load (or one the held dofs take entirely) has no response: nothing to add.
    let nonzero: Vec<usize> = (0..nl)
        .filter(|&j| (0..n).any(|i| r[(i, j)] != 0.0))
        .collect();
    // √(rᵀMr) of each response itself: its basis-vector weight scale (SPEC §5.5)
    let m_norms: Vec<f64> = (0..nl)
        .map(|j| energy(&r, &mr, j).max(0.0).sqrt())
        .collect();
    let r = r_perp;
    let norms: Vec<f64> = (0..nl)
        .map(|j| (0..n).map(|i| r[(i, j)] * r[(i, j)]).sum::<f64>().sqrt())
        .collect();
    let live: Vec<usize> = (nonzero.iter().copied())
        .filter(|&j| norms[j] > 0.0 && missing[j] > RESIDUAL_ENERGY_TOL)
        .collect();
    // already in the basis (counted as added and removed as dependent, like the ones the
    // orthonormalization removes)
    let in_basis: Vec<crate::reduce::RemovedVector> = (nonzero.iter().copied())
        .filter(|j| !live.contains(j))
        .map(|j| crate::reduce::RemovedVector {
            column: nf + j,
            label: ModeLabel::Residual { load: j },
            remaining: missing[j],
        })
        .collect();
    let mut basis = Mat::<f64>::zeros(n, nf + live.len());
    let mut labels = Vec::with_capacity(nf + live.len());
    for (c, &j) in flex.iter().enumerate() {
        basis.as_mut().col_mut(c).copy_from(set.phi.col(j));
        labels.push(set.labels[j].clone());
    }
    for (c, &j) in live.iter().enumerate() {
        for i in 0..n {
            basis[(i, nf + c)] = r[(i, j)] / norms[j];
        }
        labels.push(ModeLabel::Residual { load: j });
    }
    let o = orthonormalize_held(k, m, &basis, &labels, &set.reference_dofs)?;
    let mut report = ResidualReport::default();
    for rv in &o.diagnostics.removed {
        if let ModeLabel::Residual { load } = rv.label {
            report.removed.push((load, rv.remaining));
        }
    }
    for j in (0..nl).filter(|j| !live.contains(j)) {
        if nonzero.contains(&j) {
            report.removed.push((j, missing[j]));
        } else {
            report.no_response.push(j);
        }
    }
    report.removed.sort_by_key(|x| x.0);
    report.kept = live.len()
        - (o.diagnostics.removed.iter())
            .filter(|rv| matches!(rv.label, ModeLabel::Residual { .. }))
            .count();
    // [rigid modes as they were | new flexible modes]
    let nr = rigid.len();
    let q = o.omega2.len();
    let mut phi = Mat::<f64>::zeros(n, nr + q);
    for (c, &j) in rigid.iter().enumerate() {
        phi.as_mut().col_mut(c).copy_from(set.phi.col(j));
    }
    phi.as_mut().subcols_mut(nr, q).copy_from(o.phi.as_ref());
    let mut omega2: Vec<f64> = rigid.iter().map(|&j| set.omega2[j]).collect();
    omega2.extend(&o.omega2);
    let stages = StageCoefficients {
        first: &set,
        rigid: &rigid,
        flex: &flex,
        live: &live,
        projection: &coeff,
        norms: &norms,
        m_norms: &m_norms,
    };
    let origin = composed_origin(&stages, &o);
    let is_rigid: Vec<bool> = (0..nr + q)
        .map(|j| j < nr || o.labels[j - nr] == ModeLabel::Rigid)
        .collect();
    let (out_labels, shares) = origin_labels(&is_rigid, &origin.weights, &origin.basis);
    let mut diagnostics = diagnose(k, m, &phi, &omega2)?;
    let old = set.diagnostics;
    diagnostics.label_shares = shares;
    diagnostics.origin = Some(origin);
    diagnostics.removed = old.removed;
    diagnostics
        .removed
        .extend(o.diagnostics.removed.iter().cloned());
    diagnostics.removed.extend(in_basis);
    diagnostics.dependency_tol = o.diagnostics.dependency_tol;
    diagnostics.massless_directions = old.massless_directions + o.diagnostics.massless_directions;
    diagnostics.massless_dofs = old.massless_dofs;
    diagnostics.held_massless = old.held_massless;
    diagnostics.basis_top_omega2 = old.basis_top_omega2;
    diagnostics.basis_normal_modes = old.basis_normal_modes;
    diagnostics.eigenproblem = old.eigenproblem;
    diagnostics.notes = old.notes;
    diagnostics.residual_vectors = old.residual_vectors + nonzero.len();
    let mut note = format!(
        "residual vectors: {} of {nl} static load responses added",
        report.kept
    );
    if !report.removed.is_empty() {
        note += &format!(
            "; {} removed as dependent (already in the basis): load columns {:?}",
            report.removed.len(),
            report.removed.iter().map(|x| x.0).collect::<Vec<_>>()
        );
    }
    if !report.no_response.is_empty() {
        note += &format!(
            "; no residual vector for load columns {:?} (zero static response: balanced by the \
             body's inertia or taken by the held dofs)",
            report.no_response
        );
    }
    diagnostics.notes.push(note);
    Ok((
        ModeSet {
            phi,
            omega2,
            labels: out_labels,
            method: set.method,
            reference_dofs: set.reference_dofs,
            selection: set.selection,
            diagnostics,
        },
        report,
    ))
}

/// What the two stages of a residual-vector build know about their coefficients.
struct StageCoefficients<'a> {
    /// The method's mode set (stage 1).
    first: &'a ModeSet,
    /// Its rigid and flexible columns.
    rigid: &'a [usize],
    flex: &'a [usize],
    /// The responses put into the stage-2 basis, as r⊥_j / ‖r⊥_j‖.
    live: &'a [usize],
    /// C = Φ_fᵀ M r (flexible modes × loads): r⊥ = r − Φ_f C.
    projection: &'a Mat<f64>,
    /// ‖r⊥_j‖ (Euclidean) and √(r_jᵀ M r_j).
    norms: &'a [f64],
    m_norms: &'a [f64],
}

/// The final modes' weights on the original basis vectors, SPEC §5.5: with stage 2's
/// φ = Φ_f N_f + Σ_i r⊥_i/‖r⊥_i‖ N_i and r⊥ = r − Φ_f C, φ = Φ_f (N_f − C D⁻¹ N_r) + r D⁻¹ N_r,
/// and Φ_f's own weights W₁ on the method's basis (identity for normal modes) compose:
/// w = [W₁ (N_f − C D⁻¹ N_r) ; diag(√(rᵀMr)) D⁻¹ N_r]. Columns: the rigid modes (unchanged,
/// their stage-1 weights) then stage 2's modes.
fn composed_origin(s: &StageCoefficients<'_>, o: &Orthonormalized) -> OriginWeights {
    let set = s.first;
    let (nm, nf, nr) = (set.len(), s.flex.len(), s.rigid.len());
    // W₁ over every column of stage 1; each mode its own basis vector when stage 1 has none
    let first = match &set.diagnostics.origin {
        Some(w) if w.weights.ncols() == nm => w.clone(),
        _ => OriginWeights {
            basis: set.labels.clone(),
            weights: Mat::identity(nm, nm),
        },
    };
    let b = first.basis.len();
    let n2 = &o.coefficients;
    let q = n2.ncols();
    // A = N_f − C D⁻¹ N_r (nf × q)
    let a = Mat::from_fn(nf, q, |c, j| {
        n2[(c, j)]
            - (s.live.iter().enumerate())
                .map(|(i, &l)| s.projection[(c, l)] / s.norms[l] * n2[(nf + i, j)])
                .sum::<f64>()
    });
    let w1_flex = Mat::from_fn(b, nf, |row, c| first.weights[(row, s.flex[c])]);
    let top = &w1_flex * &a;
    let rows = b + s.live.len();
    let weights = Mat::from_fn(rows, nr + q, |row, col| match (row < b, col < nr) {
        (true, true) => first.weights[(row, s.rigid[col])],
        (true, false) => top[(row, col - nr)],
        (false, true) => 0.0,
        (false, false) => {
            let l = s.live[row - b];
            s.m_norms[l] / s.norms[l] * n2[(nf + row - b, col - nr)]
        }
    });
    let mut basis = first.basis;
    basis.extend(s.live.iter().map(|&l| ModeLabel::Residual { load: l }));
    OriginWeights { basis, weights }
}
