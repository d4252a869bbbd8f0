//! Craig–Bampton reduction: constraint modes Ψ = −K_ii⁻¹K_ib (one multi-RHS solve), fixed-interface
//! modes K_ii φ = ω² M_ii φ (same factorization, σ = 0), the basis T = [I 0; Ψ Φ_i], and its
//! orthonormalization by the second eigenproblem (Wang, Niu & Feng 2023 eqs. 24–31).

use super::orthonormalize::{orthonormalize_projected, Orthonormalized, Projection};
use super::select::{solve_count_with, ModeCount};
use super::{check_dofs, Method, ModeLabel, ModeSet, ReduceError};
use crate::solve::cholesky::{self, Analysis, REFINE_F64, SINGULAR_PIVOT};
use crate::solve::sparse_ops::complement;
use crate::solve::{
    lowest_modes, lowest_modes_factored, sparse_ops, EigenSolution, EigenSpec, Precision,
    SolveError, SparseColMat, SparseLlt, DENSE_MAX,
};
use faer::Mat;
use std::f64::consts::PI;
use std::time::Instant;

/// Smallest L_jj² / A_jj an f32 factor may keep; below it K_ii is factored in f64 at once.
/// Measured on the stability insert block (3087 dofs, docs/stability.md row 7): contrast 1 gives
/// 4.7e-3 and refines in ~3 steps, 1e2 gives 4.7e-5 and refines slowly (ω² still 4e-11 from
/// f64), 1e3 gives 6.2e-6 and refinement stalls after 12 steps; from 1e4 the f32 factorization
/// meets a non-positive pivot.
const F32_PIVOT: f64 = 1e-5;

/// The un-orthonormalized Craig–Bampton basis.
#[derive(Clone, Debug)]
pub struct CbBasis {
    /// T, n × (n_b + n_q): interface columns first (in `interface` order), then fixed-interface
    /// modes.
    pub t: Mat<f64>,
    /// Origin of each column of T.
    pub labels: Vec<ModeLabel>,
    /// ω² of the fixed-interface modes.
    pub fixed_omega2: Vec<f64>,
    /// Phase timings (s): ordering+factorization, constraint modes, eigen.
    pub timings: Vec<(&'static str, f64)>,
    /// How the fixed-interface eigenproblem was solved (vectors, steps, factor size, times).
    pub eigen: crate::solve::EigenInfo,
    /// Its eigenpairs' residuals on K_ii, M_ii (`None`: no fixed-interface mode was asked).
    pub record: Option<super::EigenRecord>,
    /// Choices made on the way (e.g. the precision of the factorization), for the report.
    pub notes: Vec<String>,
}

/// A result with the K and M that were handed over by value, given back unchanged.
pub type WithKm<T> = (T, SparseColMat<usize, f64>, SparseColMat<usize, f64>);

/// Builds the Craig–Bampton basis for the interface dofs `interface` (K and M borrowed: their
/// interior blocks are copies, resident beside them; [`craig_bampton_basis_owned`] avoids that).
pub fn craig_bampton_basis(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    interface: &[usize],
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<CbBasis, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let inner = interior_dofs(k.nrows(), interface, modes)?;
    let kii = sparse_ops::submatrix(k.as_ref(), &inner, &inner)?;
    let kib = sparse_ops::submatrix(k.as_ref(), &inner, interface)?;
    let make_mii = || Ok(sparse_ops::submatrix(m.as_ref(), &inner, &inner)?);
    let (basis, _) = basis_of_blocks(&kii, &kib, make_mii, interface, &inner, modes, eig)?;
    Ok(basis)
}

/// [`craig_bampton_basis`] on K and M handed over by value, given back unchanged with the basis.
/// Each is split into its interior block and its border before the factorization and joined
/// again once L is freed, so neither is resident beside K_ii, M_ii and L: the
/// build's peak loses 2 × nnz(K) × 16 bytes (1.4 GB at 519k dofs, docs/memory.md).
pub fn craig_bampton_basis_owned(
    k: SparseColMat<usize, f64>,
    m: SparseColMat<usize, f64>,
    interface: &[usize],
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<WithKm<CbBasis>, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let inner = interior_dofs(k.nrows(), interface, modes)?;
    if m.nrows() != k.nrows() {
        return Err(ReduceError::Dofs {
            what: "mass matrix",
            detail: format!("M has {} rows, K {}", m.nrows(), k.nrows()),
        });
    }
    let k_split = sparse_ops::split_interior(k, &inner)?;
    let kib = sparse_ops::submatrix(k_split.border.as_ref(), &inner, interface)?;
    // M's halves take M's own place (unlike the borrowed path, where M_ii is made late so as
    // not to sit beside the factorization's scratch as an extra copy)
    let sparse_ops::InteriorSplit {
        interior: mii,
        border: m_border,
    } = sparse_ops::split_interior(m, &inner)?;
    let (basis, mii) = basis_of_blocks(
        &k_split.interior,
        &kib,
        move || Ok(mii),
        interface,
        &inner,
        modes,
        eig,
    )?;
    let k = sparse_ops::join_interior(k_split, &inner)?;
    let m = sparse_ops::join_interior(
        sparse_ops::InteriorSplit {
            interior: mii,
            border: m_border,
        },
        &inner,
    )?;
    Ok((basis, k, m))
}

/// The interior dofs (all but `interface`, increasing) after checking the request.
fn interior_dofs(
    n: usize,
    interface: &[usize],
    modes: ModeCount,
) -> Result<Vec<usize>, ReduceError> {
    check_dofs("interface dofs", interface, n)?;
    if interface.is_empty() {
        return Err(ReduceError::Dofs {
            what: "interface dofs",
            detail: "empty interface".into(),
        });
    }
    let inner = complement(interface, n);
    if modes != ModeCount::Count(0) {
        super::select::check_count(modes, inner.len(), "the interior (non-interface dofs)")?;
    }
    Ok(inner)
}

/// The CB basis from K_ii, K_ib and M_ii, which `make_mii` makes after the factorization (not
/// resident beside its scratch); M_ii is given back. L is freed on return.
fn basis_of_blocks(
    kii: &SparseColMat<usize, f64>,
    kib: &SparseColMat<usize, f64>,
    make_mii: impl FnOnce() -> Result<SparseColMat<usize, f64>, ReduceError>,
    interface: &[usize],
    inner: &[usize],
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<(CbBasis, SparseColMat<usize, f64>), ReduceError> {
    let n = inner.len() + interface.len();
    let t0 = Instant::now();
    let (mut llt, mut notes) = factor_kii(kii, kib, inner, eig, eig.precision, None)?;
    let mii = make_mii()?;
    let mut t_factor = t0.elapsed().as_secs_f64();
    let (psi, fixed, t_constraint, t_eigen) =
        match constraint_and_fixed(kii, kib, &mii, &llt, modes, eig) {
            Err(ReduceError::Solve(e @ SolveError::Refinement { .. })) if llt.is_mixed() => {
                // the f32 factor is too far from K_ii for refinement: factor again in f64, on
                // the same analysis
                let analysis = llt.into_analysis();
                let t = Instant::now();
                (llt, _) = factor_kii(kii, kib, inner, eig, Precision::F64, Some(analysis))?;
                t_factor += t.elapsed().as_secs_f64();
                notes.push(format!(
                    "mixed precision abandoned ({e}); K_ii factored again in f64"
                ));
                constraint_and_fixed(kii, kib, &mii, &llt, modes, eig)?
            }
            other => other?,
        };
    if llt.is_mixed() {
        notes.push(format!(
            "K_ii factored in mixed precision (f32 L, {}; solves refined against K_ii to f64 \
             accuracy: {} extra triangular solves in the eigen phase)",
            cholesky::format_bytes(llt.stats.factor_bytes as u64),
            fixed.info.refinement_solves
        ));
    }
    drop(llt);
    let eigen = fixed.info.clone();
    let record = (modes != ModeCount::Count(0))
        .then(|| super::EigenRecord::of(super::EigenProblem::FixedInterface, kii, &mii, &fixed));
    let (t, labels) = basis_matrix(n, interface, inner, &psi, &fixed.vectors);
    let basis = CbBasis {
        t,
        labels,
        fixed_omega2: fixed.eigenvalues,
        timings: vec![
            ("factorization", t_factor),
            ("constraint modes", t_constraint),
            ("eigen", t_eigen),
        ],
        eigen,
        record,
        notes,
    };
    Ok((basis, mii))
}

/// Constraint modes X = K_ii⁻¹ K_ib (n_i × n_b; Ψ = −X) and the fixed-interface modes with the
/// factorization `llt` of K_ii, and the time of each.
fn constraint_and_fixed(
    kii: &SparseColMat<usize, f64>,
    kib: &SparseColMat<usize, f64>,
    mii: &SparseColMat<usize, f64>,
    llt: &SparseLlt,
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<(Mat<f64>, EigenSolution, f64, f64), ReduceError> {
    let t1 = Instant::now();
    let mut x = sparse_ops::to_dense(kib.as_ref());
    crate::solve::progress::report(crate::solve::progress::Event::Solves { columns: x.ncols() });
    llt.solve_refined_in_place(kii.as_ref(), x.as_mut(), REFINE_F64)?;
    let t_constraint = t1.elapsed().as_secs_f64();
    let t2 = Instant::now();
    let fixed = fixed_interface_modes(kii, mii, llt, modes, eig)?;
    Ok((x, fixed, t_constraint, t2.elapsed().as_secs_f64()))
}

/// T = [I 0; Ψ Φ_i] over all n dofs with Ψ = −X, X = K_ii⁻¹ K_ib (n_i × n_b) and the
/// fixed-interface modes Φ_i (n_i × n_q), and the label of each column.
fn basis_matrix(
    n: usize,
    interface: &[usize],
    inner: &[usize],
    x: &Mat<f64>,
    fixed: &Mat<f64>,
) -> (Mat<f64>, Vec<ModeLabel>) {
    let (nb, nq) = (interface.len(), fixed.ncols());
    let mut t = Mat::<f64>::zeros(n, nb + nq);
    for (c, &d) in interface.iter().enumerate() {
        t[(d, c)] = 1.0;
        for (r, &i) in inner.iter().enumerate() {
            t[(i, c)] = -x[(r, c)];
        }
    }
    for q in 0..nq {
        for (r, &i) in inner.iter().enumerate() {
            t[(i, nb + q)] = fixed[(r, q)];
        }
    }
    let mut labels: Vec<ModeLabel> = interface
        .iter()
        .map(|&d| ModeLabel::Constraint { dof: d })
        .collect();
    labels.extend((0..nq).map(|index| ModeLabel::FixedInterface { index }));
    (t, labels)
}

/// LLᵀ of K_ii in the asked `precision` ([`Precision::Auto`]: f64 unless its factor exceeds the
/// memory limit and the f32 one fits; a mixed factorization whose pivots lost their digits is
/// done again in f64), with notes for the report; on `analysis` when given (else K_ii is
/// ordered and analysed here). A zero pivot of the f64 factorization
/// (non-positive, or positive below [`SINGULAR_PIVOT`] of its diagonal) becomes
/// [`ReduceError::UnrestrainedInterior`] naming the dof and its region.
fn factor_kii(
    kii: &SparseColMat<usize, f64>,
    kib: &SparseColMat<usize, f64>,
    inner: &[usize],
    eig: &EigenSpec,
    precision: Precision,
    analysis: Option<Analysis>,
) -> Result<(SparseLlt, Vec<String>), ReduceError> {
    let mut notes = vec![];
    let (symbolic, stats) = match analysis {
        Some(a) => a,
        None => cholesky::analyze(kii.as_ref(), eig.dofs_per_node)?,
    };
    let mixed = match precision {
        Precision::F64 => false,
        Precision::Mixed => true,
        Precision::Auto => {
            let f64_bytes = cholesky::factor_memory(&symbolic, eig.par);
            match cholesky::check_memory(f64_bytes, kii.nrows()) {
                Ok(()) => false,
                Err(SolveError::OutOfMemory { .. })
                    if cholesky::check_memory(
                        cholesky::factor_memory_mixed(&symbolic, kii.as_ref(), eig.par),
                        kii.nrows(),
                    )
                    .is_ok() =>
                {
                    notes.push(format!(
                        "the f64 factor of K_ii ({}) exceeds the memory limit: factored in mixed \
                         precision (--precision auto)",
                        cholesky::format_bytes(f64_bytes as u64)
                    ));
                    true
                }
                Err(e) => return Err(e.into()),
            }
        }
    };
    let first = if mixed {
        let abandoned = "mixed precision abandoned: K_ii is too ill-conditioned for an f32 factor \
                         (a pivot lost its digits); factored in f64";
        match SparseLlt::factor_mixed_with(symbolic, stats, kii.as_ref(), eig.par) {
            Ok(l) if l.min_pivot().0 > F32_PIVOT => Ok(l),
            Ok(l) => {
                notes.push(abandoned.into());
                let (symbolic, stats) = l.into_analysis();
                SparseLlt::factor_with(symbolic, stats, kii.as_ref(), eig.par)
            }
            // the failed factorization consumed the analysis: ordered again
            Err(SolveError::NonPositivePivot { .. }) => {
                notes.push(abandoned.into());
                SparseLlt::factor(kii.as_ref(), eig.dofs_per_node, eig.par)
            }
            Err(e) => Err(e),
        }
    } else {
        SparseLlt::factor_with(symbolic, stats, kii.as_ref(), eig.par)
    };
    let (local, pivot, llt) = match first {
        Err(SolveError::NonPositivePivot { dof }) => (dof, 0.0, None),
        Err(e) => return Err(e.into()),
        Ok(l) if l.min_pivot().0 <= SINGULAR_PIVOT => (l.min_pivot().1, l.min_pivot().0, None),
        Ok(l) => (0, 1.0, Some(l)),
    };
    if let Some(l) = llt {
        return Ok((l, notes));
    }
    // the region of K_ii's graph around the zero pivot, and whether K_ib couples it to the interface
    let ni = kii.nrows();
    let mut seen = vec![false; ni];
    let mut stack = vec![local];
    seen[local] = true;
    let mut region = 0;
    while let Some(i) = stack.pop() {
        region += 1;
        for &r in kii.row_idx_of_col_raw(i) {
            if !seen[r] {
                seen[r] = true;
                stack.push(r);
            }
        }
    }
    let connected = (0..kib.ncols()).any(|c| {
        kib.row_idx_of_col_raw(c)
            .iter()
            .zip(kib.val_of_col(c))
            .any(|(&r, &v)| seen[r] && v != 0.0)
    });
    Err(ReduceError::UnrestrainedInterior {
        dof: inner[local],
        pivot,
        region,
        connected,
    })
}

/// Fixed-interface modes, reusing the factorization of K_ii (σ = 0) on the sparse path.
fn fixed_interface_modes(
    kii: &SparseColMat<usize, f64>,
    mii: &SparseColMat<usize, f64>,
    llt: &SparseLlt,
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<EigenSolution, ReduceError> {
    let ni = kii.nrows();
    let run = |c: usize, upper: Option<f64>| -> Result<EigenSolution, ReduceError> {
        let spec = EigenSpec {
            count: c,
            shift: Some(0.0),
            upper,
            ..eig.clone()
        };
        let b = spec
            .block
            .unwrap_or(c.min(crate::solve::DEFAULT_BLOCK))
            .max(1);
        if ni <= DENSE_MAX || c + 4 * b > ni / 2 {
            Ok(lowest_modes(kii, mii, &spec)?)
        } else {
            Ok(lowest_modes_factored(kii, mii, llt, 0.0, &spec)?)
        }
    };
    if modes == ModeCount::Count(0) {
        return Ok(EigenSolution {
            eigenvalues: vec![],
            vectors: Mat::zeros(ni, 0),
            residuals: vec![],
            info: Default::default(),
        });
    }
    solve_count_with(kii, mii, modes, Some(0.0), &run)
}

/// Craig–Bampton mode set: the basis orthonormalized by K̂N = M̂NΛ (exact I and diag(ω²)).
pub fn craig_bampton(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    interface: &[usize],
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<ModeSet, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let basis = craig_bampton_basis(k, m, interface, modes, eig)?;
    craig_bampton_from_basis(k, m, interface, modes, basis)
}

/// [`craig_bampton`] on K and M handed over by value and given back unchanged
/// ([`craig_bampton_basis_owned`]: neither is resident beside the factorization).
pub fn craig_bampton_owned(
    k: SparseColMat<usize, f64>,
    m: SparseColMat<usize, f64>,
    interface: &[usize],
    modes: ModeCount,
    eig: &EigenSpec,
) -> Result<WithKm<ModeSet>, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let (basis, k, m) = craig_bampton_basis_owned(k, m, interface, modes, eig)?;
    let set = craig_bampton_from_basis(&k, &m, interface, modes, basis)?;
    Ok((set, k, m))
}

/// Craig–Bampton with the factorization of K_ii, the constraint modes and the fixed-interface
/// eigenproblem on PETSc/SLEPc under MPI ([`crate::solve::slepc`]), for a mode count or a band
/// (`--fmax`: proven complete by Sylvester's inertia count of our K_ii − σM_ii, a missed mode is
/// an error). The basis is then orthonormalized here as on the native path.
pub fn craig_bampton_slepc(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    interface: &[usize],
    modes: ModeCount,
    eig: &EigenSpec,
    engine: &crate::solve::slepc::SlepcEngine,
) -> Result<ModeSet, ReduceError> {
    let _par = crate::solve::ParGuard::new(eig.par);
    let n = k.nrows();
    check_dofs("interface dofs", interface, n)?;
    let inner = complement(interface, n);
    let (count, upper) = match modes {
        ModeCount::Count(c) => (c, None),
        ModeCount::BelowHz(f) => (12.min(inner.len()), Some((2.0 * PI * f).powi(2))),
        ModeCount::All => {
            return Err(ReduceError::Dofs {
                what: "mode count",
                detail: "--engine slepc takes a mode count (--modes N) or a band (--fmax), not \
                         every mode"
                    .into(),
            })
        }
    };
    if interface.is_empty() || count == 0 {
        return Err(ReduceError::Dofs {
            what: "interface dofs",
            detail: "--engine slepc needs interface dofs and at least one fixed-interface mode"
                .into(),
        });
    }
    super::select::check_count(modes, inner.len(), "the interior (non-interface dofs)")?;
    let kii = sparse_ops::submatrix(k.as_ref(), &inner, &inner)?;
    let kib = sparse_ops::submatrix(k.as_ref(), &inner, interface)?;
    let mii = sparse_ops::submatrix(m.as_ref(), &inner, &inner)?;
    let request = crate::solve::slepc::Request {
        count,
        upper,
        shift: 0.0,
        tol: eig.tol,
    };
    let mut sol = crate::solve::slepc::fixed_interface(
        kii.as_ref(),
        mii.as_ref(),
        kib.as_ref(),
        request,
        engine,
    )?;
    // --verify-band, and always for a band: the same inertia count as the native engine, on our
    // K_ii and M_ii (with a band, over the modes found up to the first one above it)
    let mut eigen = crate::solve::EigenInfo::default();
    if eig.verify_band || upper.is_some() {
        // the vectors lent to the count (which tells rigid modes from their rounding) and back
        let mut checked = crate::solve::verify_band(
            &kii,
            &mii,
            EigenSolution {
                eigenvalues: sol.eigenvalues.clone(),
                vectors: std::mem::replace(&mut sol.vectors, Mat::zeros(0, 0)),
                residuals: vec![],
                info: Default::default(),
            },
            &EigenSpec {
                verify_band: true,
                ..eig.clone()
            },
        )?;
        eigen.band_proof = checked.info.band_proof;
        sol.vectors = std::mem::replace(&mut checked.vectors, Mat::zeros(0, 0));
    }
    if let Some(top) = upper {
        let keep = sol.eigenvalues.iter().filter(|&&l| l <= top).count();
        sol.eigenvalues.truncate(keep);
        sol.vectors = sol.vectors.as_ref().subcols(0, keep).to_owned();
    }
    let record = super::EigenRecord::from_pairs(
        super::EigenProblem::FixedInterface,
        crate::solve::Solver::Slepc,
        (&kii, &mii),
        (sol.vectors.as_ref(), &sol.eigenvalues),
        eigen.band_proof,
    );
    let (t, labels) = basis_matrix(n, interface, &inner, &sol.x, &sol.vectors);
    let basis = CbBasis {
        t,
        labels,
        fixed_omega2: sol.eigenvalues,
        timings: vec![("slepc engine (write, MPI run, read back)", sol.seconds)],
        eigen,
        record: Some(record),
        notes: vec![],
    };
    let mut set = craig_bampton_from_basis(k, m, interface, modes, basis)?;
    set.diagnostics.notes.push(format!(
        "engine slepc, {} MPI ranks: {}",
        engine.ranks, sol.report
    ));
    Ok(set)
}

/// The note of a set with no fixed-interface mode below the cutoff (the CLI shows it as a
/// warning instead, with the cutoff).
pub const GUYAN_NOTE: &str = "no fixed-interface mode lies below the cutoff: the set holds the \
                              constraint (static) modes only, a Guyan reduction; raise --fmax \
                              for dynamic content";

/// The Craig–Bampton mode set of a basis (orthonormalization and diagnostics).
fn craig_bampton_from_basis(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    interface: &[usize],
    modes: ModeCount,
    basis: CbBasis,
) -> Result<ModeSet, ReduceError> {
    let nq = basis.fixed_omega2.len();
    let t3 = Instant::now();
    let o = orthonormalize_basis(k, m, &basis)?;
    let mut diagnostics = o.diagnostics;
    diagnostics.basis_top_omega2 = basis.fixed_omega2.last().copied();
    diagnostics.fixed_interface_omega2 = basis.fixed_omega2.clone();
    diagnostics.eigenproblem = basis.record.clone();
    for (name, s) in &basis.timings {
        diagnostics.notes.push(format!("time {name}: {s:.3} s"));
    }
    diagnostics.notes.extend(basis.notes.iter().cloned());
    diagnostics
        .notes
        .extend(super::band_note(&basis.eigen, "fixed-interface"));
    if nq == 0 && matches!(modes, ModeCount::BelowHz(_)) {
        diagnostics.notes.push(GUYAN_NOTE.into());
    }
    diagnostics.notes.push(format!(
        "time orthonormalization: {:.3} s",
        t3.elapsed().as_secs_f64()
    ));
    Ok(ModeSet {
        phi: o.phi,
        omega2: o.omega2,
        labels: o.labels,
        method: Method::CraigBampton {
            interface: interface.to_vec(),
            fixed_interface_modes: nq,
        },
        reference_dofs: vec![],
        selection: None,
        diagnostics,
    })
}

/// The basis orthonormalized ([`orthonormalize_projected`]) with K̂ and M̂ from
/// [`projection`].
pub fn orthonormalize_basis(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    basis: &CbBasis,
) -> Result<Orthonormalized, ReduceError> {
    let known = projection(k, m, &basis.t, &basis.fixed_omega2);
    orthonormalize_projected(k, m, &basis.t, &basis.labels, &[], Some(known))
}

/// K̂ = TᵀKT and M̂ = TᵀMT of T = [T_c T_q] (constraint columns first, then the n_q
/// fixed-interface modes, zero at the interface) with products of K and M with T_c only:
/// T_qᵀKT_q = Φᵀ K_ii Φ = diag(ω²) and T_qᵀMT_q = I (the eigensolver's Rayleigh–Ritz step made
/// them so to rounding), the rest is Tᵀ(K T_c) and Tᵀ(M T_c). Measured at 68.5k dofs (12
/// constraint columns, 30 modes): two products with 12 columns instead of two with 42.
pub fn projection(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    t: &Mat<f64>,
    fixed_omega2: &[f64],
) -> Projection {
    let p = t.ncols();
    let nb = p - fixed_omega2.len();
    let tc = t.as_ref().subcols(0, nb);
    let block = |a: &SparseColMat<usize, f64>, qq: &dyn Fn(usize) -> f64| {
        let atc = t.transpose() * sparse_ops::spmm(a.as_ref(), tc); // p × nb
        let mut h = Mat::<f64>::zeros(p, p);
        h.as_mut().subcols_mut(0, nb).copy_from(&atc);
        h.as_mut()
            .submatrix_mut(0, nb, nb, p - nb)
            .copy_from(atc.as_ref().subrows(nb, p - nb).transpose());
        for (j, d) in (nb..p).enumerate() {
            h[(d, d)] = qq(j);
        }
        crate::solve::dense::sym(h.as_ref())
    };
    Projection {
        kh: block(k, &|j| fixed_omega2[j]),
        mh: block(m, &|_| 1.0),
    }
}
