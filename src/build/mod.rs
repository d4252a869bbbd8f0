//! End to end: FE model file → reduced flexible body ([`ReducedBody`]), the job of
//! `flexbody build`.
//!
//! ```text
//! import ─► interface spiders ─► assemble K, M ─► eliminate (u = T u_r) ─► reduce ─► Φ = T Φ_r
//!        ─► mass points (lumped, every node + point masses) ─► invariants ─► keep nodes
//!        ─► stress/strain shapes at the kept nodes (when asked) ─► body
//! ```
//!
//! Every stage is a call into its own module; this one only connects them, converts between the
//! compute types and the file types, and times the stages. It never prints: progress goes to a
//! callback, findings into the [`BuildReport`].

use std::path::PathBuf;
use std::time::Instant;

use faer::Par;
use flexbody_reader as file;

use crate::faces::graphics_faces;
use crate::fe::{self, assemble, eliminate, AssemblySpec, BeamLumping, ConstraintSpec};
use crate::import::{self, Format, ImportOptions};
use crate::interface::{resolve_interfaces, InterfaceReport, SpiderKind};
use crate::invariants::compute_invariants;
use crate::model::{DofMask, Material, Model, NodeIndex};
use crate::reduce::select::{self, ModeCount};
use crate::reduce::{self, ModeSet};
use crate::solve::EigenSpec;
use crate::stress::{modal_fields, FieldRequest, ModalFields};

mod body;
use body::*;

/// Reduction method asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BuildMethod {
    /// Normal modes (free-free, or with the reference conditions held).
    Normal,
    /// Craig–Bampton on the interface dofs.
    CraigBampton,
    /// Craig–Chang: free-free modes + inertia-relief attachment modes at the interface dofs.
    CraigChang,
    /// Dietz frequency-response modes at the interface dofs (static procedure).
    Dietz,
}

/// Which nodes get their mode shapes stored in the file (invariants always use every node).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum KeepNodes {
    /// Every node.
    All,
    /// Interface nodes only.
    Interface,
    /// Interface nodes and the nodes of the graphics faces.
    Surface,
    /// Interface nodes and the nodes of this node set.
    Set(String),
}

/// Everything `flexbody build` needs to know.
#[derive(Debug, Clone)]
pub struct BuildSpec {
    /// The model file.
    pub model: PathBuf,
    /// Format override (default: from the extension).
    pub format: Option<Format>,
    /// Material for elements without a section (Gmsh meshes).
    pub material: Option<Material>,
    /// Thickness of shell elements without a section (Gmsh triangles/quadrangles), with
    /// `material`.
    pub thickness: Option<f64>,
    /// Interface entries: node ids or node-set names.
    pub interface: Vec<String>,
    /// How node sets are attached.
    pub spider: SpiderKind,
    /// Reduction method.
    pub method: BuildMethod,
    /// Number of fixed-interface (CB) or normal modes.
    pub modes: Option<usize>,
    /// Highest frequency of the scene (Hz); modes are kept to `FMAX_FACTOR` times it.
    pub fmax_hz: Option<f64>,
    /// Reference conditions: (external node id, dofs).
    pub reference_conditions: Vec<(u64, DofMask)>,
    /// Reference conditions by name: plain node ids (free components), node-set names, or a
    /// deck's constraint set (`SPC_1`: the components it holds) — see [`crate::deck`].
    pub reference_sets: Vec<String>,
    /// Improved-CB method (1 or 2) for reference conditions.
    pub reference_method: u8,
    /// Mass matrix of the reduction.
    pub mass: fe::MassKind,
    /// The model's consistent units (recorded, never guessed).
    pub units: file::Units,
    /// Which nodes to store.
    pub keep_nodes: KeepNodes,
    /// Invariant selection.
    pub invariants: file::InvariantSet,
    /// Modal stress/strain shapes of the solid elements at the stored nodes.
    pub fields: FieldRequest,
    /// Title for the header (default: the model file name).
    pub title: Option<String>,
    /// Creation time to record (only when the user asks; default output is deterministic).
    pub created_utc: Option<String>,
    /// Threads for the factorization, the block solves and the dense kernels (1: sequential).
    pub threads: usize,
    /// Rotational inertia of lumped beam masses; `None` = automatic: as Nastran lumps each card
    /// (CBAR none, CBEAM torsion) for Nastran decks, the section's rotary inertia otherwise.
    pub beam_mass: Option<BeamLumping>,
    /// Nastran: the case-control subcase whose SPC and METHOD selections apply.
    pub subcase: Option<u64>,
    /// `mass` was chosen by the user (`--mass`); when false a deck's PARAM,COUPMASS > 0 selects
    /// consistent mass (see [`crate::deck`]).
    pub mass_explicit: bool,
    /// The scene: loads (`--gravity`, `--load`) and residual vectors (`--residual-vectors`).
    pub scene: crate::scene::SceneSpec,
    /// `--verify-band`: prove every eigenproblem's returned modes complete by an inertia count
    /// (one extra LDLᵀ factorization each; [`EigenSpec::verify_band`]).
    pub verify_band: bool,
    /// `--engine slepc --mpi N`: the Craig–Bampton interior (factorization, constraint modes,
    /// fixed-interface eigenproblem) on PETSc/SLEPc under MPI; `None`: our own solvers.
    pub engine: Option<crate::solve::slepc::SlepcEngine>,
    /// `--precision`: arithmetic of the Craig–Bampton interior's factorization.
    pub precision: crate::solve::Precision,
}

impl BuildSpec {
    /// A spec with the CLI's defaults (Craig–Bampton on RBE2 spiders, lumped mass, every node
    /// kept, full invariants, no stress shapes) for `model` in `units` with these interfaces.
    pub fn new(model: PathBuf, units: file::Units, interface: &[&str]) -> BuildSpec {
        BuildSpec {
            model,
            format: None,
            material: None,
            thickness: None,
            interface: interface.iter().map(|s| s.to_string()).collect(),
            spider: SpiderKind::Rbe2,
            method: BuildMethod::CraigBampton,
            modes: None,
            fmax_hz: None,
            reference_conditions: Vec::new(),
            reference_sets: Vec::new(),
            reference_method: 1,
            mass: fe::MassKind::Lumped,
            units,
            keep_nodes: KeepNodes::All,
            invariants: file::InvariantSet::Full,
            fields: FieldRequest::default(),
            title: None,
            created_utc: None,
            threads: 1,
            beam_mass: None,
            subcase: None,
            mass_explicit: false,
            scene: Default::default(),
            verify_band: false,
            engine: None,
            precision: Default::default(),
        }
    }

    /// The beam lumping of the build: `beam_mass`, or for `None` Nastran's per-card lumping
    /// when the model is a Nastran deck (by `format` or the file extension), else the section's.
    pub fn beam_lumping(&self) -> BeamLumping {
        self.beam_mass.unwrap_or_else(|| {
            match self.format.or_else(|| Format::from_extension(&self.model)) {
                Some(Format::Nastran) => BeamLumping::Nastran,
                _ => BeamLumping::SectionRotary,
            }
        })
    }

    /// The parallelism of the solver stages: `Par::Seq` for one thread.
    pub fn par(&self) -> Par {
        if self.threads > 1 {
            Par::rayon(self.threads)
        } else {
            Par::Seq
        }
    }
}

/// Default number of modes when neither `modes` nor `fmax_hz` is given.
pub const DEFAULT_MODES: usize = 20;

/// What happened, for the user.
#[derive(Debug, Clone, Default)]
pub struct BuildReport {
    /// (stage, seconds).
    pub stages: Vec<(String, f64)>,
    /// Interfaces and spiders.
    pub interfaces: Vec<InterfaceReport>,
    /// Import warnings and pipeline notes.
    pub warnings: Vec<String>,
    /// Number of physical and independent dofs.
    pub dofs: (usize, usize),
    /// Checked diagnostics of the mode set.
    pub diagnostics: reduce::Diagnostics,
    /// What the build took from the deck (mass, mode count, interface, subcase), and
    /// constraint components dropped from interface/reference nodes.
    pub notes: Vec<String>,
    /// Every applied constraint: card, line, set, dofs held.
    pub constraints: Vec<crate::deck::ConstraintSummary>,
}

/// A built body with its report.
#[derive(Debug, Clone)]
pub struct BuildOutput {
    /// The reduced body, ready to write.
    pub body: file::ReducedBody,
    /// What was done.
    pub report: BuildReport,
}

/// Errors of the pipeline; each names the file and the entity.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// Import failed.
    #[error(transparent)]
    Import(#[from] import::ImportError),
    /// Interface resolution failed.
    #[error(transparent)]
    Interface(#[from] crate::interface::InterfaceError),
    /// Assembly or constraint elimination failed.
    #[error(transparent)]
    Fe(#[from] fe::FeError),
    /// The reduction failed.
    #[error(transparent)]
    Reduce(#[from] reduce::ReduceError),
    /// Invariants could not be formed.
    #[error(transparent)]
    Invariants(#[from] crate::invariants::InvariantError),
    /// Stress/strain shapes could not be recovered.
    #[error(transparent)]
    Fields(#[from] crate::stress::StressError),
    /// The built body failed its own verification (nothing was written).
    #[error("{file}: {failures}")]
    Verify {
        /// Model file.
        file: String,
        /// The failed checks.
        failures: crate::verify::VerifyError,
    },
    /// The request does not fit the model.
    #[error("{file}: {message}")]
    Request {
        /// Model file.
        file: String,
        /// What is wrong and what to do.
        message: String,
    },
}

/// Stages reported to the progress callback, in order.
pub const STAGES: [&str; 9] = [
    "import",
    "interfaces",
    "assembly",
    "constraints",
    "reduction",
    "invariants",
    "stress shapes",
    "assemble file",
    "verify",
];

/// A 0 × 0 sparse matrix (what a freed matrix is replaced by).
fn empty_matrix() -> crate::solve::SparseColMat<usize, f64> {
    crate::solve::SparseColMat::new(
        faer::sparse::SymbolicSparseColMat::new_checked(0, 0, vec![0], None, vec![]),
        vec![],
    )
}

/// Run the pipeline. `progress(stage)` is called as each stage starts.
pub fn build(spec: &BuildSpec, progress: &mut dyn FnMut(&str)) -> Result<BuildOutput, BuildError> {
    let clock = Instant::now();
    progress(STAGES[0]);
    let model = import::read_model(
        &spec.model,
        &ImportOptions {
            format: spec.format,
            material: spec.material.clone(),
            subcase: spec.subcase,
            shell_thickness: spec.thickness,
            ..Default::default()
        },
    )?;
    let import_s = clock.elapsed().as_secs_f64();
    let resolved = BuildSpec {
        beam_mass: Some(spec.beam_lumping()),
        ..spec.clone()
    };
    let mut out = build_model(&resolved, model, progress)?;
    out.report
        .stages
        .insert(0, (STAGES[0].to_string(), import_s));
    Ok(out)
}

/// The pipeline after import, for a model already in memory (generated meshes, models edited
/// by a program); `spec.model` only names it in messages and the header. `progress(stage)` is
/// called as each stage starts.
pub fn build_model(
    spec: &BuildSpec,
    model: Model,
    progress: &mut dyn FnMut(&str),
) -> Result<BuildOutput, BuildError> {
    // Solver failures in the model's terms (crate::diagnose).
    let ctx = crate::diagnose::SolverContext::of(&model);
    build_model_with_hook(spec, model, progress, &mut |_| {}).map_err(|e| ctx.explain(e))
}

/// [`build_model`] with `hook` applied to the mode set (over the independent dofs) right after
/// the reduction, before the body is assembled and verified: for tests of the verification
/// (a corrupted basis must be refused) and for programs that post-process a set.
pub fn build_model_with_hook(
    spec: &BuildSpec,
    mut model: Model,
    progress: &mut dyn FnMut(&str),
    hook: &mut dyn FnMut(&mut ModeSet),
) -> Result<BuildOutput, BuildError> {
    let mut report = BuildReport::default();
    // The deck's own requests (COUPMASS, METHOD, ASET, TITLE) fill the choices left open.
    let defaults = crate::deck::deck_defaults(spec, &model);
    let spec = &defaults.spec;
    report.notes = defaults.notes.clone();
    let mut clock = Instant::now();
    let mut lap = |report: &mut BuildReport, name: &str| {
        report
            .stages
            .push((name.to_string(), clock.elapsed().as_secs_f64()));
        clock = Instant::now();
    };
    let file_name = spec.model.display().to_string();
    let request_err = |message: String| BuildError::Request {
        file: file_name.clone(),
        message,
    };
    report.warnings.extend(
        model
            .warnings
            .iter()
            .map(|w| format!("{}: {}", w.file, w.message)),
    );

    progress(STAGES[1]);
    if spec.method != BuildMethod::Normal && spec.interface.is_empty() {
        return Err(request_err(format!(
            "{:?} needs interface nodes: give --interface with node ids or node-set names",
            spec.method
        )));
    }
    if !spec.reference_conditions.is_empty()
        && matches!(spec.method, BuildMethod::CraigChang | BuildMethod::Dietz)
    {
        return Err(request_err("reference conditions are defined for normal modes and Craig–Bampton (improved CB methods 1 and 2), not for Craig–Chang or Dietz".into()));
    }
    report.interfaces = resolve_interfaces(&mut model, &spec.interface, spec.spider)?;
    let interface_nodes: Vec<NodeIndex> = report
        .interfaces
        .iter()
        .flat_map(|r| r.nodes.iter().copied())
        .collect();
    // A bad --load/--gravity is reported now, not after the reduction.
    crate::scene::scene_loads(&model, &spec.scene).map_err(|e| request_err(e.to_string()))?;
    lap(&mut report, STAGES[1]);

    progress(STAGES[2]);
    let assembly = AssemblySpec {
        mass: spec.mass,
        beam_lumping: spec.beam_mass.unwrap_or_default(),
        ..Default::default()
    };
    let mut assembled = assemble(&model, &assembly)?;
    report.constraints = crate::deck::constraint_summary(&model, &assembled.dofs);
    lap(&mut report, STAGES[2]);

    progress(STAGES[3]);
    let mut reduced = eliminate(
        &model,
        &assembled.dofs,
        &assembled.k,
        &assembled.m,
        &ConstraintSpec {
            // RBE3 spiders at interface nodes keep their centre independent (UM-style).
            independent_rbe3_reference: interface_nodes.clone(),
            ..Default::default()
        },
    )?;
    // The physical K is not used past the elimination (the reduction works on reduced.k; the
    // invariants and mass points use M): free it before the factorization, the build's peak
    // (issue 22: 16 bytes per non-zero, ~0.6 GB at 519k tet10 dofs).
    assembled.k = empty_matrix();
    let dofs = &assembled.dofs;
    report.dofs = (dofs.n_dofs, reduced.retained.len());
    // Physical dof → independent (reduced) dof.
    let mut reduced_index = vec![usize::MAX; dofs.n_dofs];
    for (r, &p) in reduced.retained.iter().enumerate() {
        reduced_index[p] = r;
    }
    let node_dofs = |node: NodeIndex,
                     mask: DofMask,
                     what: &str|
     -> Result<Vec<usize>, BuildError> {
        let id = model.nodes[node].id;
        let count = usize::from(dofs.count[node]);
        if count == 0 {
            return Err(request_err(format!("{what} node {id} carries no dofs (no element, mass or rigid element attaches to it)")));
        }
        mask.dofs()
            .filter(|&c| c < count)
            .map(|c| {
                let r = reduced_index[dofs.first[node] + c];
                if r == usize::MAX {
                    Err(request_err(format!(
                        "{what} node {id} dof {} is not independent (constrained by an SPC or a dependent dof of a rigid element); \
                         interface and reference dofs must be independent — use an RBE2 spider (--spider rbe2) or another node",
                        c + 1
                    )))
                } else {
                    Ok(r)
                }
            })
            .collect()
    };
    // Interface and reference dofs: the free components (held ones drop out of plain ids; a
    // held component given explicitly is an error naming its constraint).
    let mut interface_dofs = Vec::new();
    let mut interface_masks = Vec::new();
    let mut dropped: Vec<String> = Vec::new();
    for r in &report.interfaces {
        for &n in &r.nodes {
            let count = usize::from(dofs.count[n]);
            let (mask, held) = crate::deck::node_mask(&model, n, count, r.dofs, "interface")
                .map_err(&request_err)?;
            if held.0 != 0 {
                dropped.push(format!(
                    "interface node {} ({})",
                    model.nodes[n].id,
                    held.digits()
                ));
            }
            interface_dofs.extend(node_dofs(n, mask, "interface")?);
            interface_masks.push(mask);
        }
    }
    let by_id = model.node_index_by_id();
    let mut reference = Vec::new();
    let mut reference_records = Vec::new();
    // Reference conditions by interface name (`BIG_END:123456`) are node ids from here on.
    let (named_references, reference_sets) =
        crate::interface::reference_names(&model, &report.interfaces, &spec.reference_sets)?;
    for &(id, mask) in spec.reference_conditions.iter().chain(&named_references) {
        let node = *by_id
            .get(&id)
            .ok_or_else(|| request_err(format!("reference-condition node {id} does not exist")))?;
        // All six digits mean "the node": its free components.
        let explicit = (mask != DofMask::ALL).then_some(mask);
        let count = usize::from(dofs.count[node]);
        let (mask, held) =
            crate::deck::node_mask(&model, node, count, explicit, "reference-condition")
                .map_err(&request_err)?;
        if held.0 != 0 {
            dropped.push(format!("reference node {id} ({})", held.digits()));
        }
        reference.extend(node_dofs(node, mask, "reference-condition")?);
        reference_records.push((node, mask));
    }
    for (node, explicit, entry) in
        crate::deck::reference_entries(&model, &reference_sets).map_err(&request_err)?
    {
        let count = usize::from(dofs.count[node]);
        let (mask, held) = crate::deck::node_mask(&model, node, count, None, "reference-condition")
            .map_err(&request_err)?;
        // A constraint set's components, less the held ones (they are held already).
        let mask = DofMask(mask.0 & explicit.map_or(0x3f, |m| m.0));
        if held.0 != 0 && explicit.is_none_or(|m| m.0 & held.0 != 0) {
            dropped.push(format!(
                "reference {entry} node {} ({})",
                model.nodes[node].id,
                held.digits()
            ));
        }
        if mask.0 == 0 {
            continue;
        }
        reference.extend(node_dofs(node, mask, "reference-condition")?);
        match reference_records.iter_mut().find(|r| r.0 == node) {
            Some(r) => r.1 = DofMask(r.1 .0 | mask.0),
            None => reference_records.push((node, mask)),
        }
    }
    if !dropped.is_empty() {
        report.notes.push(format!(
            "held components (GRID PS / GRDSET / selected SPC) are not interface or reference dofs: {}",
            dropped.join(", ")
        ));
    }
    // what a flexible body cannot hold of springs, scalar masses and scalar points
    let lumped = spec.mass == fe::MassKind::Lumped;
    if let Some(why) = fe::connectors::body_restrictions(&model, dofs, &assembled.m, lumped) {
        return Err(request_err(why));
    }
    // parts, masses, interface and reference restraints, named by ids (docs/stability.md)
    crate::precheck::before_reduction(
        &model,
        dofs,
        &assembled.m,
        spec.method,
        &interface_nodes,
        &reference_records,
    )
    .map_err(&request_err)?;
    // The model's own SPCs hold the body too: record them with the reference conditions, so the
    // file (and `check`) say the modes are those of a supported body.
    let mut held: std::collections::BTreeMap<NodeIndex, u8> = Default::default();
    for s in &model.spcs {
        let existing = (1u8 << dofs.count.get(s.node).copied().unwrap_or(0)) - 1;
        if s.dofs.0 & existing != 0 {
            *held.entry(s.node).or_default() |= s.dofs.0 & existing;
        }
    }
    // Permanent constraints only (GRID PS / GRDSET: a planar or restricted model) are a note.
    let only_permanent = model.constraint_sources.iter().all(|c| c.permanent)
        && model
            .constraint_sources
            .iter()
            .map(|c| c.spcs.len())
            .sum::<usize>()
            == model.spcs.len();
    if !held.is_empty() && only_permanent {
        report.notes.push(format!(
            "the deck's permanent constraints (GRID PS / GRDSET) hold {} dofs at {} nodes: the body moves only in its free components (recorded as reference conditions)",
            held.values().map(|m| m.count_ones()).sum::<u32>(),
            held.len()
        ));
    } else if !held.is_empty() {
        report.warnings.push(format!(
            "the model's SPCs hold {} dofs at {} nodes: the modes are those of the supported body, not free-free (recorded as reference conditions)",
            held.values().map(|m| m.count_ones()).sum::<u32>(),
            held.len()
        ));
    }
    if !held.is_empty() {
        for (node, m) in held {
            match reference_records.iter_mut().find(|r| r.0 == node) {
                Some(r) => r.1 = DofMask(r.1 .0 | m),
                None => reference_records.push((node, DofMask(m))),
            }
        }
    }
    lap(&mut report, STAGES[3]);

    progress(STAGES[4]);
    let count = match (spec.modes, spec.fmax_hz, defaults.band) {
        (_, Some(f), _) if !(f.is_finite() && f > 0.0) => {
            return Err(request_err(format!(
                "--fmax {f} must be a positive frequency in Hz"
            )))
        }
        (_, Some(f), _) => ModeCount::BelowHz(select::FMAX_FACTOR * f),
        (_, None, Some(band)) => band,
        (Some(n), None, None) => ModeCount::Count(n),
        (None, None, None) => ModeCount::Count(DEFAULT_MODES),
    };
    let eig = EigenSpec {
        dofs_per_node: Some(3),
        par: spec.par(),
        verify_band: spec.verify_band,
        precision: spec.precision,
        ..Default::default()
    };
    let (k_r, m_r) = (&reduced.k, &reduced.m);
    // massless dofs: motions with neither mass nor stiffness are held (reduce::massless)
    let massless = match spec.method {
        BuildMethod::CraigBampton => reduce::massless::MasslessDofs {
            massless: reduce::massless::massless_dofs(m_r),
            held: vec![],
        },
        BuildMethod::Normal => reduce::massless::analyse(k_r, m_r, &reference, &[], eig.par)?,
        _ => reduce::massless::analyse(k_r, m_r, &[], &interface_dofs, eig.par)?,
    };
    let unit_loads_at = |map: &[usize], k: &crate::solve::SparseColMat<usize, f64>| {
        let dofs: Vec<usize> = interface_dofs
            .iter()
            .filter_map(|&d| Some(map[d]).filter(|&r| r != usize::MAX))
            .collect();
        reduce::craig_chang::unit_loads(k.nrows(), &dofs)
    };
    // an explicit --precision mixed that nothing would use is refused, not ignored
    if spec.precision == crate::solve::Precision::Mixed
        && (spec.method != BuildMethod::CraigBampton || spec.engine.is_some())
    {
        return Err(request_err(
            "--precision mixed applies to the Craig-Bampton interior of the native engine: use \
             --method cb without --engine slepc (the other methods factor in f64)"
                .into(),
        ));
    }
    if spec.engine.is_some() && !(spec.method == BuildMethod::CraigBampton && reference.is_empty())
    {
        return Err(request_err(
            "--engine slepc runs the Craig-Bampton interior only: use --method cb without \
             --reference-conditions, or the default engine"
                .into(),
        ));
    }
    // The scene's loads on the independent dofs (f_r = Tᵀf; gravity is M·g with the physical M).
    let scene = crate::scene::reduced_loads(&spec.scene, &model, &assembled, &reduced)
        .map_err(|e| request_err(e.to_string()))??;
    // The native Craig–Bampton reduction takes K and M over (craig_bampton_owned).
    let native_cb =
        spec.method == BuildMethod::CraigBampton && reference.is_empty() && spec.engine.is_none();
    // A consistent physical M is as large as K: not held through that reduction either (issue
    // 22: +0.69 GB at 519k dofs), but assembled again for the invariants after it (the
    // assembly's time, ~1.5 % of such a build). A lumped M is node-block diagonal.
    let reassemble_mass = spec.mass == fe::MassKind::Consistent && native_cb;
    if reassemble_mass {
        assembled.m = empty_matrix();
    }
    let mut set: ModeSet = match spec.method {
        BuildMethod::CraigBampton if reference.is_empty() && spec.engine.is_some() => {
            let engine = spec
                .engine
                .as_ref()
                .ok_or_else(|| request_err("engine".into()))?;
            reduce::craig_bampton::craig_bampton_slepc(
                &reduced.k,
                &reduced.m,
                &interface_dofs,
                count,
                &eig,
                engine,
            )?
        }
        BuildMethod::Normal => {
            reduce::massless::on_held(&reduced.k, &reduced.m, &massless, |k, m, map| {
                let fixed = reduce::massless::map_dofs(map, &reference, "reference dofs")?;
                reduce::normal::normal_modes(k, m, count, &fixed, &eig)
            })?
        }
        BuildMethod::CraigBampton if native_cb => {
            // K and M handed over: not resident beside K_ii, M_ii and L (issue 22)
            let k = std::mem::replace(&mut reduced.k, empty_matrix());
            let m = std::mem::replace(&mut reduced.m, empty_matrix());
            let (set, k, m) =
                reduce::craig_bampton::craig_bampton_owned(k, m, &interface_dofs, count, &eig)?;
            (reduced.k, reduced.m) = (k, m);
            set
        }
        BuildMethod::CraigBampton => match spec.reference_method {
            1 => reduce::reference::improved_cb_method1(
                &reduced.k,
                &reduced.m,
                &interface_dofs,
                &reference,
                count,
                &eig,
            )?,
            2 => reduce::reference::improved_cb_method2(
                &reduced.k,
                &reduced.m,
                &interface_dofs,
                &reference,
                count,
                &eig,
            )?,
            other => {
                return Err(request_err(format!(
                    "--reference-method {other}: must be 1 or 2"
                )))
            }
        },
        BuildMethod::CraigChang => {
            reduce::massless::on_held(&reduced.k, &reduced.m, &massless, |k, m, map| {
                let fa = unit_loads_at(map, k)?;
                reduce::craig_chang::craig_chang(k, m, &fa, count, &eig)
            })?
        }
        BuildMethod::Dietz => {
            reduce::massless::on_held(&reduced.k, &reduced.m, &massless, |k, m, map| {
                let fa = unit_loads_at(map, k)?;
                reduce::dietz::dietz(k, m, &fa, count, None, &eig)
            })?
        }
    };
    let (k_r, m_r) = (&reduced.k, &reduced.m);
    if spec.method == BuildMethod::CraigBampton {
        set.diagnostics.massless_dofs = massless.massless.len();
        if !massless.massless.is_empty() {
            set.diagnostics.notes.push(format!(
                "{} massless dofs (zero mass row and column): condensed statically by the \
                 constraint-mode and fixed-interface solves",
                massless.massless.len()
            ));
        }
    }
    if let (Some(n), true) = (
        spec.modes,
        spec.fmax_hz.is_some() || defaults.band.is_some(),
    ) {
        // Both given: the count caps the band (CB keeps its constraint-derived modes on top).
        let extra = if spec.method == BuildMethod::Normal {
            0
        } else {
            interface_dofs.len()
        };
        set = select::by_count(set, n + extra);
    }
    // The scene's mode selection and residual vectors.
    if let Some(eps) = spec.scene.select {
        // the band: --fmax, else the candidates' top read back through FMAX_FACTOR
        let top = set.frequencies_hz().into_iter().fold(0.0f64, f64::max);
        let band = spec.fmax_hz.unwrap_or(top / select::FMAX_FACTOR);
        let (s, rep) = crate::scene::select_by_scene(
            k_r,
            m_r,
            set,
            &scene,
            &interface_dofs,
            spec.scene.residual_vectors,
            eps,
            band,
            &eig,
        )?;
        set = s;
        if rep.estimate_all > eps {
            report.warnings.push(crate::reduce::participation::note(
                &rep,
                &crate::reduce::participation::Participation {
                    epsilon: eps,
                    band_hz: band,
                    damping: crate::reduce::participation::DEFAULT_DAMPING,
                },
            ));
        }
    }
    if let Some(kind) = spec.scene.residual_vectors {
        let f = crate::scene::residual_loads(kind, &scene, &interface_dofs, k_r.nrows())
            .map_err(&request_err)?;
        let (s, rep) = reduce::residual::add_residual_vectors(k_r, m_r, set, &f, &eig)?;
        set = s;
        if !rep.removed.is_empty() {
            report.notes.push(crate::scene::removed_note(&rep, &scene));
        }
    }
    hook(&mut set);
    report.diagnostics = set.diagnostics.clone();
    let phi = reduced.expand(set.phi.as_ref());
    lap(&mut report, STAGES[4]);

    progress(STAGES[5]);
    if reassemble_mass {
        assembled.m = assemble(&model, &assembly)?.m;
    }
    // The lumped M of the reduction already holds the nodal masses unless point masses were
    // added to it (they are separate mass points) or the reduction used consistent mass.
    let reusable =
        (spec.mass == fe::MassKind::Lumped && model.point_masses.is_empty()).then_some(&assembled);
    let beam_lumping = spec.beam_mass.unwrap_or_default();
    let (points, point_shapes, nodal) = mass_points(&model, dofs, &phi, reusable, beam_lumping)?;
    let inv = if spec.mass == fe::MassKind::Consistent {
        // SPEC §5.6: the invariants use the mass the modes are orthonormal in.
        let x: Vec<[f64; 3]> = model.nodes.iter().map(|n| n.x).collect();
        let shape = |p: NodeIndex, j: usize| -> [f64; 3] {
            let s = node_shape(dofs, &phi, p, j);
            [s[0], s[1], s[2]]
        };
        crate::invariants_consistent::consistent_invariants(
            &assembled.m,
            dofs,
            &x,
            &phi,
            &shape,
            spec.invariants,
        )
    } else {
        compute_invariants(&points, point_shapes.as_ref(), spec.invariants, spec.par())?
    };
    lap(&mut report, STAGES[5]);

    let faces = graphics_faces(&model);
    let always: Vec<NodeIndex> = interface_nodes
        .iter()
        .copied()
        .chain(reference_records.iter().map(|r| r.0))
        .collect();
    let stored = stored_nodes(&model, &spec.keep_nodes, &always, &faces).map_err(request_err)?;
    let mut shell_bottom: Option<ModalFields> = None;
    let fields = if spec.fields.is_empty() {
        None
    } else {
        progress(STAGES[6]);
        let u = |p: NodeIndex, j: usize| -> [f64; 3] {
            let s = node_shape(dofs, &phi, p, j);
            [s[0], s[1], s[2]]
        };
        let f = modal_fields(&model, &stored, phi.ncols(), &u, spec.fields)?;
        // Shells: top fibre in the solids' entries, bottom fibre in the 1.5 entries.
        let u6 = |p: NodeIndex, j: usize| node_shape(dofs, &phi, p, j);
        let sf = crate::shell_stress::shell_fields(&model, &stored, phi.ncols(), &u6, spec.fields)?;
        let (f, bottom) = crate::shell_stress::merge(f, &sf, phi.ncols());
        shell_bottom = bottom;
        if f.nodes.is_empty() {
            report.warnings.push(
                "stress/strain shapes asked for, but no stored node belongs to a solid or shell element: none written".into(),
            );
        }
        if f.centroid_fallbacks > 0 {
            report.warnings.push(format!(
                "stress/strain shapes: {} element corners have a non-positive Jacobian (strongly distorted elements); their centroid values were used there",
                f.centroid_fallbacks
            ));
        }
        lap(&mut report, STAGES[6]);
        Some(f).filter(|f| !f.nodes.is_empty())
    };

    progress(STAGES[7]);
    let mut body = assemble_body(
        spec,
        &model,
        dofs,
        &phi,
        &set,
        &stored,
        &interface_nodes,
        &interface_masks,
        &reference_records,
        &faces,
        &nodal,
        &inv,
        fields.as_ref(),
    )?;
    body.modal_loads = crate::scene::modal_loads(&scene, &set);
    let band = crate::recipe::accuracy_band(spec, &set);
    let recipe =
        crate::recipe::recipe(spec, &model, &report.interfaces, band).map_err(request_err)?;
    body.recipe = Some(recipe);
    if let Some(b) = &shell_bottom {
        let mut position = vec![u32::MAX; model.nodes.len()];
        for (i, &n) in stored.iter().enumerate() {
            position[n] = i as u32;
        }
        body.stress_shapes_bottom = field_shapes(b, b.stress.as_ref(), &position);
        body.strain_shapes_bottom = field_shapes(b, b.strain.as_ref(), &position);
    }
    body.interfaces =
        crate::interface_entry::interfaces_entry(&model, &report.interfaces, &body.nodes);
    body.version = file::version_for(&body);
    lap(&mut report, STAGES[7]);

    progress(STAGES[8]);
    crate::verify::verify_body(&body, Some((k_r, m_r, &set.phi, &reference))).map_err(
        |failures| BuildError::Verify {
            file: file_name.clone(),
            failures,
        },
    )?;
    lap(&mut report, STAGES[8]);
    Ok(BuildOutput { body, report })
}
