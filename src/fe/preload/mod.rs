//! The preload stage: a linear static solve of a preload case, the initial stress σ₀ it
//! leaves, and the tangent stiffness K_T = K + K_G(σ₀) the modes of the loaded part use; and
//! the modal geometric-stiffness terms Φᵀ K_G(σ(unit load)) Φ a multibody solver needs to
//! stiffen a spinning or loaded body during the simulation (issue 35).
//!
//! # How the stage plugs in (design note)
//!
//! ```text
//! assemble ─► eliminate (K_r, M_r, T) ─► preload ─► (K_T,r replaces K_r) ─► reduce ─► …
//!                                         ▲
//!                          PreloadCase (loads, inertia fields, ΔT)
//! ```
//! Plain data in, plain data out; nothing here reads files or options:
//! * in: the [`System`] the build already has after the elimination (model, assembled dofs and
//!   M, the elimination `Reduced` with K_r, M_r, T, the `AssemblySpec`) and a [`PreloadCase`]
//!   — the deck's or scene's mechanical loads (`model::Load`: nodal forces, gravity M·g,
//!   pressures), inertia fields (a spin, CalculiX CENTRIF / Nastran RFORCE; any rigid
//!   acceleration field) and a thermal strain (ΔT with α per material: `*TEMPERATURE`,
//!   `TEMP(LOAD)`, MAT1 A, `*EXPANSION`).
//! * out: [`Preload`] — the static displacement u₀ (physical dofs), K_G,r = Tᵀ K_G T and
//!   K_T,r = K_r + K_G,r, checked positive definite. Phase 2 hands `k_t` to the reduction in
//!   place of K_r (every method unchanged), records the case in the recipe, and stops with the
//!   [`PreloadError::Buckling`] message when the check fails.
//! * the file's geometric-stiffness terms: [`modal_geometric_stiffness`] gives, for a mode set
//!   Φ (on the independent dofs) and unit load cases, K̂_G,j = Φᵀ K_G(σ(case j)) Φ. With the
//!   twelve [`unit_inertia_fields`] (translational acceleration, the six products ω_iω_j of
//!   the angular velocity, angular acceleration) and unit interface or scene loads as cases,
//!   the body's stiffening during a simulation is K̂ + Σ_j q_j K̂_G,j with q_j the current
//!   accelerations, angular-velocity products and loads: the Simpack SID "ksigma" terms. The
//!   preload is linear, so a spin Ω about a unit axis n contributes exactly
//!   Ω² Σ_{i≤j} n_i n_j K̂_G,ij. A free body's unit cases are balanced by inertia relief; a body
//!   held at its interface (Craig–Bampton) is eliminated with the interface fixed first.
//!
//! # Conventions
//! * The static solve is linear (small displacements, σ₀ from the linear strain); K_G is the
//!   exact second variation of ∫σ₀ : E dV (Green–Lagrange E) for solids and the consistent
//!   beam-column / membrane forms for beams, rods and shells (`fe::geometric`).
//! * Loads that depend on the deformation (follower pressure, the change of the centrifugal
//!   force with the displacement) are not linearized into K_T; the spin softening −Ω²PᵀMP of a
//!   rotating frame is a separate term, [`spin_softening`], for in-plane motion.
//! * The check: K_T,r (with the inertia-relief support held for a free body) must factor as
//!   LLᵀ; otherwise the error carries the lowest buckling factor λ₁ (the preload × λ₁ buckles
//!   the part) from [`crate::solve::buckling`].

pub mod inertia;
pub mod statics;

use faer::sparse::SparseColMat;
use faer::{Mat, MatRef, Par};

use super::assembly::{Assembled, AssemblySpec};
use super::constraints::Reduced;
use super::geometric::{self, Thermal};
use super::FeError;
use crate::model::{Load, LoadPart, Model};
use crate::solve::{buckling, sparse_ops, EigenSpec, SolveError, SparseLlt};

pub use inertia::{spin_softening, unit_inertia_fields, InertiaField, InertiaLoad, Spin};

/// Errors of the preload stage.
#[derive(Debug, thiserror::Error)]
pub enum PreloadError {
    /// Assembly of K_G or of a load failed (names the element).
    #[error(transparent)]
    Fe(#[from] FeError),
    /// A factorization or a small eigenproblem failed.
    #[error("preload: {0}")]
    Solve(#[from] SolveError),
    /// A load of the case cannot be applied (its `problem`, e.g. a card the importer could not
    /// use): refused, never dropped.
    #[error("{source_file}: preload load {name} ({origin}) cannot be applied: {problem}")]
    Load {
        /// Model file.
        source_file: String,
        /// The load's name.
        name: String,
        /// Where it came from.
        origin: String,
        /// Why it cannot be used.
        problem: String,
    },
    /// The static problem is singular away from the rigid-body motions: a mechanism.
    #[error(
        "{source_file}: the preload's static problem is singular at node {node} dof {dof}: the \
         body has a mechanism (a dof without stiffness that no rigid-body motion explains); \
         hold it or connect it"
    )]
    Singular {
        /// Model file.
        source_file: String,
        /// External node id.
        node: u64,
        /// 1-based component.
        dof: usize,
    },
    /// `Support::Held` but the constraints leave rigid-body motions free.
    #[error(
        "{source_file}: the preload asks for a held body but its constraints leave {rigid} \
         rigid-body motion(s) free; hold them, or let inertia relief balance the load \
         (Support::Auto)"
    )]
    NotHeld {
        /// Model file.
        source_file: String,
        /// Free rigid-body motions.
        rigid: usize,
    },
    /// K + K_G is not positive definite: compression beyond the first buckling load.
    #[error(
        "{source_file}: the preload makes the tangent stiffness K + K_G indefinite (not positive \
         definite at node {node} dof {dof}): the part buckles under it{}; the modes of a buckled \
         part are not defined — reduce the preload below the first buckling load",
        match factor {
            Some(l) => format!(
                " (lowest buckling factor λ₁ = {l:.6}: λ₁ × the preload is the first buckling \
                 load)"
            ),
            None => String::new(),
        }
    )]
    Buckling {
        /// Model file.
        source_file: String,
        /// External node id of the failing pivot.
        node: u64,
        /// Its 1-based component.
        dof: usize,
        /// The lowest buckling factor λ₁ < 1 (when it could be computed).
        factor: Option<f64>,
    },
}

/// What holds the body in the static solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Support {
    /// Inertia relief against the rigid-body motions the constraints leave free; a direct
    /// solve when they leave none.
    #[default]
    Auto,
    /// The constraints must hold the body (free rigid-body motions are an error).
    Held,
}

/// Options of the preload stage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreloadSpec {
    /// Held or inertia relief.
    pub support: Support,
    /// Parallelism of the factorizations (default sequential, as `EigenSpec`).
    pub par: Par,
}

impl Default for PreloadSpec {
    fn default() -> Self {
        PreloadSpec {
            support: Support::Auto,
            par: Par::Seq,
        }
    }
}

/// One preload case: the sum of its parts.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PreloadCase {
    /// Mechanical loads (nodal forces and moments, gravity M·g, surface tractions).
    pub loads: Vec<Load>,
    /// Inertia body forces f = M b (spins, rigid accelerations).
    pub inertia: Vec<InertiaField>,
    /// Thermal strain.
    pub thermal: Option<Thermal>,
    /// The tangent also carries the initial-displacement stiffness K_L(u₀) of the static state
    /// (solids; `geometric::initial_displacement_stiffness`): K_T = K + K_G + K_L, what
    /// CalculiX's `*STEP, PERTURBATION` perturbs. Off: the linear preload K + K_G.
    pub initial_displacement: bool,
    /// The tangent also carries the spin softening −Ω² Pᵀ M P of every centrifugal load part
    /// ([`spin_softening`]): the modes in the rotating frame, as CalculiX's perturbation step
    /// forms them (ccx e_c3d, "stiffness contribution of centrifugal forces"). Off: a solver
    /// that spins the body adds it itself.
    pub spin_softening: bool,
}

impl PreloadCase {
    /// The case of a spin alone.
    pub fn spin(spin: &Spin) -> PreloadCase {
        PreloadCase {
            inertia: spin.field().into_iter().collect(),
            ..Default::default()
        }
    }
}

/// The data the build has after the elimination (design note).
#[derive(Debug, Clone, Copy)]
pub struct System<'a> {
    /// The model.
    pub model: &'a Model,
    /// Dofs and the physical M (the physical K is not needed).
    pub assembled: &'a Assembled,
    /// The elimination: T, K_r, M_r.
    pub reduced: &'a Reduced,
    /// The assembly options (beam theory for K_G).
    pub assembly: &'a AssemblySpec,
}

/// A preloaded system.
#[derive(Debug, Clone)]
pub struct Preload {
    /// Static displacement on the physical dofs (u₀ = T u_r).
    pub u: Vec<f64>,
    /// K_G,r = Tᵀ K_G(σ₀) T on the independent dofs.
    pub kg: SparseColMat<usize, f64>,
    /// K_T,r = K_r + K_G,r (+ K_L,r with [`PreloadCase::initial_displacement`]), positive
    /// definite (on the free dofs for a free body).
    pub k_t: SparseColMat<usize, f64>,
    /// Rigid-body motions balanced by inertia relief (0: held).
    pub rigid_modes: usize,
    /// The inertia-relief support (independent-dof indices; empty when held).
    pub support: Vec<usize>,
}

/// The load vector of `case` over the physical dofs.
pub fn load_vector(sys: &System, case: &PreloadCase) -> Result<Vec<f64>, PreloadError> {
    let (model, asm) = (sys.model, sys.assembled);
    let mut f = vec![0.0; asm.dofs.n_dofs];
    if let Some(l) = case.loads.iter().find(|l| l.problem.is_some()) {
        return Err(PreloadError::Load {
            source_file: model.source.clone(),
            name: l.name.clone(),
            origin: l.source.clone(),
            problem: l.problem.clone().unwrap_or_default(),
        });
    }
    if !case.loads.is_empty() {
        let lv = super::loads::load_vectors(model, &asm.dofs, &asm.m, &case.loads)?;
        for j in 0..lv.ncols() {
            for (i, v) in f.iter_mut().enumerate() {
                *v += lv[(i, j)];
            }
        }
    }
    for field in &case.inertia {
        let fi = inertia::inertia_load(model, &asm.dofs, &asm.m, field);
        f.iter_mut().zip(fi).for_each(|(a, b)| *a += b);
    }
    if let Some(t) = &case.thermal {
        let ft = geometric::thermal_loads(model, &asm.dofs, sys.assembly, t)?;
        f.iter_mut().zip(ft).for_each(|(a, b)| *a += b);
    }
    Ok(f)
}

/// Static displacements of the cases on the physical dofs (n × L, one column per case), with
/// the rigid-mode count and support of the solve (`statics`).
pub fn static_displacements(
    sys: &System,
    cases: &[PreloadCase],
    spec: &PreloadSpec,
) -> Result<(Mat<f64>, usize, Vec<usize>), PreloadError> {
    let red = sys.reduced;
    let dofs = &sys.assembled.dofs;
    let xr = statics::free_rigid_modes(sys.model, dofs, red)?;
    let rigid = xr.ncols();
    if spec.support == Support::Held && rigid > 0 {
        return Err(PreloadError::NotHeld {
            source_file: sys.model.source.clone(),
            rigid,
        });
    }
    let mut f = Mat::<f64>::zeros(dofs.n_dofs, cases.len());
    for (j, case) in cases.iter().enumerate() {
        for (i, v) in load_vector(sys, case)?.into_iter().enumerate() {
            f[(i, j)] = v;
        }
    }
    let f_r = super::loads::reduce_loads(&red.t, &f);
    let eig = EigenSpec {
        par: spec.par,
        ..Default::default()
    };
    let (u_r, support) = statics::solve(sys.model, dofs, red, xr, &f_r, &eig)?;
    Ok((red.expand(u_r.as_ref()), rigid, support))
}

/// Column `j` of the static displacements `u` and the physical K_G of its stress (with the
/// case's thermal strain).
fn case_geometric_stiffness(
    sys: &System,
    u: &Mat<f64>,
    j: usize,
    case: &PreloadCase,
) -> Result<(Vec<f64>, SparseColMat<usize, f64>), PreloadError> {
    let uj: Vec<f64> = (0..u.nrows()).map(|i| u[(i, j)]).collect();
    let kg = geometric::geometric_stiffness(
        sys.model,
        &sys.assembled.dofs,
        sys.assembly,
        &uj,
        case.thermal.as_ref(),
    )?;
    Ok((uj, kg))
}

/// The preload of `case` (module doc): static solve, K_G(σ₀), K_T and its check.
pub fn preload(
    sys: &System,
    case: &PreloadCase,
    spec: &PreloadSpec,
) -> Result<Preload, PreloadError> {
    let (u, rigid_modes, support) = static_displacements(sys, std::slice::from_ref(case), spec)?;
    let (u, kg_phys) = case_geometric_stiffness(sys, &u, 0, case)?;
    let red = sys.reduced;
    let kg = sparse_ops::congruence(red.t.as_ref(), kg_phys.as_ref(), spec.par)?;
    let mut k_t = sparse_ops::add_scaled(red.k.as_ref(), kg.as_ref(), 1.0)?;
    if case.initial_displacement {
        let kl_phys = geometric::initial_displacement_stiffness(
            sys.model,
            &sys.assembled.dofs,
            sys.assembly,
            &u,
        )?;
        let kl = sparse_ops::congruence(red.t.as_ref(), kl_phys.as_ref(), spec.par)?;
        k_t = sparse_ops::add_scaled(k_t.as_ref(), kl.as_ref(), 1.0)?;
    }
    if case.spin_softening {
        for spin in centrifugal_spins(case) {
            let soft = spin_softening(sys.model, &sys.assembled.dofs, &sys.assembled.m, &spin)?;
            let soft = sparse_ops::congruence(red.t.as_ref(), soft.as_ref(), spec.par)?;
            k_t = sparse_ops::add_scaled(k_t.as_ref(), soft.as_ref(), 1.0)?;
        }
    }
    check_stability(sys, &kg, &k_t, &support, spec.par)?;
    Ok(Preload {
        u,
        kg,
        k_t,
        rigid_modes,
        support,
    })
}

/// The spins of the case's centrifugal load parts (Ω = √Ω²).
fn centrifugal_spins(case: &PreloadCase) -> Vec<Spin> {
    (case.loads.iter().flat_map(|l| &l.parts))
        .filter_map(|p| match p {
            LoadPart::Centrifugal {
                omega2,
                point,
                axis,
            } => Some(Spin {
                point: *point,
                axis: *axis,
                omega: omega2.sqrt(),
            }),
            _ => None,
        })
        .collect()
}

/// The free part A[free, free] (A itself without a support).
fn free_part(
    a: &SparseColMat<usize, f64>,
    support: &[usize],
    free: &[usize],
) -> Result<SparseColMat<usize, f64>, SolveError> {
    if support.is_empty() {
        Ok(a.clone())
    } else {
        sparse_ops::submatrix(a.as_ref(), free, free)
    }
}

/// The buckling check (module doc): K_T (support dofs held) must be positive definite; if not,
/// [`PreloadError::Buckling`] with the lowest buckling factor.
pub fn check_stability(
    sys: &System,
    kg: &SparseColMat<usize, f64>,
    k_t: &SparseColMat<usize, f64>,
    support: &[usize],
    par: Par,
) -> Result<(), PreloadError> {
    let red = sys.reduced;
    let free = sparse_ops::complement(support, k_t.nrows());
    let k_t_ff = free_part(k_t, support, &free)?;
    match SparseLlt::factor(k_t_ff.as_ref(), None, par) {
        Ok(_) => Ok(()),
        Err(SolveError::NonPositivePivot { dof }) => {
            let (k, kg) = (
                free_part(&red.k, support, &free)?,
                free_part(kg, support, &free)?,
            );
            let factor = buckling::lowest_buckling_factor(&k, &kg, par)
                .ok()
                .flatten();
            let (node, comp) = (free.get(dof))
                .and_then(|&r| sys.assembled.dofs.node_of(red.retained[r]))
                .map_or((0, 0), |(p, c)| (sys.model.nodes[p].id, c + 1));
            Err(PreloadError::Buckling {
                source_file: sys.model.source.clone(),
                node,
                dof: comp,
                factor,
            })
        }
        Err(e) => Err(e.into()),
    }
}

/// The lowest buckling factor λ₁ of the preload (K_r φ = −λ K_G,r φ on the free dofs; `None`
/// when nothing is in compression).
pub fn buckling_factor(
    sys: &System,
    preload: &Preload,
    par: Par,
) -> Result<Option<f64>, PreloadError> {
    let support = &preload.support;
    let free = sparse_ops::complement(support, preload.k_t.nrows());
    let k = free_part(&sys.reduced.k, support, &free)?;
    let kg = free_part(&preload.kg, support, &free)?;
    Ok(buckling::lowest_buckling_factor(&k, &kg, par)?)
}

/// The file's geometric-stiffness terms (design note): K̂_G,j = Φᵀ K_G(σ(case j)) Φ (q × q) for
/// the modes `phi_r` (independent dofs × q) and each case.
pub fn modal_geometric_stiffness(
    sys: &System,
    phi_r: MatRef<'_, f64>,
    cases: &[PreloadCase],
    spec: &PreloadSpec,
) -> Result<Vec<Mat<f64>>, PreloadError> {
    let (u, _, _) = static_displacements(sys, cases, spec)?;
    let phi = sys.reduced.expand(phi_r);
    cases
        .iter()
        .enumerate()
        .map(|(j, case)| {
            let (_, kg) = case_geometric_stiffness(sys, &u, j, case)?;
            let kphi = sparse_ops::spmm(kg.as_ref(), phi.as_ref());
            let g = phi.transpose() * &kphi;
            Ok(Mat::from_fn(g.nrows(), g.ncols(), |a, b| {
                0.5 * (g[(a, b)] + g[(b, a)])
            }))
        })
        .collect()
}
