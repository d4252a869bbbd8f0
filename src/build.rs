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

use faer::{Mat, Par};
use flexbody_reader as file;

use crate::faces::graphics_faces;
use crate::fe::{self, assemble, eliminate, AssemblySpec, BeamLumping, ConstraintSpec, DofMap};
use crate::import::{self, Format, ImportOptions};
use crate::interface::{resolve_interfaces, InterfaceReport, SpiderKind};
use crate::invariants::{compute_invariants, MassPoint};
use crate::model::{DofMask, Material, Model, NodeIndex};
use crate::reduce::select::{self, ModeCount};
use crate::reduce::{self, ModeSet};
use crate::solve::EigenSpec;
use crate::stress::{modal_fields, FieldRequest, ModalFields};

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
    let mut assembled = assemble(
        &model,
        &AssemblySpec {
            mass: spec.mass,
            beam_lumping: spec.beam_mass.unwrap_or_default(),
            ..Default::default()
        },
    )?;
    report.constraints = crate::deck::constraint_summary(&model, &assembled.dofs);
    lap(&mut report, STAGES[2]);

    progress(STAGES[3]);
    let reduced = eliminate(
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
    let mut set: ModeSet = match spec.method {
        BuildMethod::Normal => reduce::massless::on_held(k_r, m_r, &massless, |k, m, map| {
            let fixed = reduce::massless::map_dofs(map, &reference, "reference dofs")?;
            reduce::normal::normal_modes(k, m, count, &fixed, &eig)
        })?,
        BuildMethod::CraigBampton if reference.is_empty() => {
            reduce::craig_bampton::craig_bampton(k_r, m_r, &interface_dofs, count, &eig)?
        }
        BuildMethod::CraigBampton => match spec.reference_method {
            1 => reduce::reference::improved_cb_method1(
                k_r,
                m_r,
                &interface_dofs,
                &reference,
                count,
                &eig,
            )?,
            2 => reduce::reference::improved_cb_method2(
                k_r,
                m_r,
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
        BuildMethod::CraigChang => reduce::massless::on_held(k_r, m_r, &massless, |k, m, map| {
            let fa = unit_loads_at(map, k)?;
            reduce::craig_chang::craig_chang(k, m, &fa, count, &eig)
        })?,
        BuildMethod::Dietz => reduce::massless::on_held(k_r, m_r, &massless, |k, m, map| {
            let fa = unit_loads_at(map, k)?;
            reduce::dietz::dietz(k, m, &fa, count, None, &eig)
        })?,
    };
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
    // The scene's loads on the independent dofs (f_r = Tᵀf) and their residual vectors.
    let scene = crate::scene::reduced_loads(&spec.scene, &model, &assembled, &reduced)
        .map_err(|e| request_err(e.to_string()))??;
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
    crate::verify::verify_body(&body, Some((k_r, m_r, &set.phi))).map_err(|failures| {
        BuildError::Verify {
            file: file_name.clone(),
            failures,
        }
    })?;
    lap(&mut report, STAGES[8]);
    Ok(BuildOutput { body, report })
}

/// Rows `[ux uy uz rx ry rz]` of node `p` for mode `j` in the basic frame (zeros where the node
/// has no such dof): u_basic = Aᵀ u_local with A's rows the local axes.
fn node_shape(dofs: &DofMap, phi: &Mat<f64>, p: NodeIndex, j: usize) -> [f64; 6] {
    let count = usize::from(dofs.count[p]);
    let mut local = [0.0; 6];
    for (c, v) in local.iter_mut().enumerate().take(count) {
        *v = phi[(dofs.first[p] + c, j)];
    }
    match dofs.frames[p] {
        None => local,
        Some(a) => {
            let rot = |v: &[f64]| -> [f64; 3] {
                std::array::from_fn(|i| (0..3).map(|k| a[k][i] * v[k]).sum())
            };
            let (t, r) = (rot(&local[..3]), rot(&local[3..]));
            [t[0], t[1], t[2], r[0], r[1], r[2]]
        }
    }
}

/// Per-node lumped mass and inertia of the structure (point masses excluded), basic frame.
type NodalMass = Vec<(f64, [[f64; 3]; 3])>;

/// Mass points for the invariants: every node with its lumped structural mass (a lumped assembly
/// of the model without point masses, or `lumped` when that is already it), plus one point per point mass at its centre of gravity,
/// moving rigidly with its node (u + θ × d). Returns the points, their 6-row shapes, and the
/// per-node mass (structure + point masses lumped to the node, inertia shifted to the node) that
/// the file stores.
fn mass_points(
    model: &Model,
    dofs: &DofMap,
    phi: &Mat<f64>,
    lumped: Option<&fe::Assembled>,
    beam_lumping: BeamLumping,
) -> Result<(Vec<MassPoint>, Mat<f64>, NodalMass), BuildError> {
    let own;
    let lumped = match lumped {
        Some(l) => l,
        None => {
            let mut bare = model.clone();
            bare.point_masses.clear();
            own = assemble(
                &bare,
                &AssemblySpec {
                    mass: fe::MassKind::Lumped,
                    beam_lumping,
                    ..Default::default()
                },
            )?;
            &own
        }
    };
    let (ld, lm) = (&lumped.dofs, lumped.m.as_ref());
    let entry = |row: usize, col: usize| -> f64 {
        lm.row_idx_of_col(col)
            .zip(lm.val_of_col(col))
            .find(|(r, _)| *r == row)
            .map_or(0.0, |(_, v)| *v)
    };
    let nn = model.nodes.len();
    let mut nodal: NodalMass = Vec::with_capacity(nn);
    for p in 0..nn {
        let count = usize::from(ld.count[p]);
        if count == 0 {
            nodal.push((0.0, [[0.0; 3]; 3]));
            continue;
        }
        let f = ld.first[p];
        let mass = (0..3).map(|c| entry(f + c, f + c)).sum::<f64>() / 3.0;
        let mut inertia = [[0.0; 3]; 3];
        if count == 6 {
            let local: [[f64; 3]; 3] =
                std::array::from_fn(|r| std::array::from_fn(|c| entry(f + 3 + r, f + 3 + c)));
            // I_basic = Aᵀ I_local A.
            inertia = match ld.frames[p] {
                None => local,
                Some(a) => std::array::from_fn(|r| {
                    std::array::from_fn(|c| {
                        (0..3)
                            .map(|i| (0..3).map(|k| a[i][r] * local[i][k] * a[k][c]).sum::<f64>())
                            .sum()
                    })
                }),
            };
        }
        nodal.push((mass, inertia));
    }
    let nm = phi.ncols();
    let np = nn + model.point_masses.len();
    let mut points = Vec::with_capacity(np);
    let mut shapes = Mat::<f64>::zeros(6 * np, nm);
    for (p, node) in model.nodes.iter().enumerate() {
        points.push(MassPoint {
            position: node.x,
            mass: nodal[p].0,
            inertia: nodal[p].1,
        });
        for j in 0..nm {
            let s = node_shape(dofs, phi, p, j);
            for (c, v) in s.iter().enumerate() {
                shapes[(6 * p + c, j)] = *v;
            }
        }
    }
    for (q, pm) in model.point_masses.iter().enumerate() {
        let row = 6 * (nn + q);
        let d = pm.offset;
        let x = model.nodes[pm.node].x;
        points.push(MassPoint {
            position: std::array::from_fn(|k| x[k] + d[k]),
            mass: pm.mass,
            inertia: pm.inertia,
        });
        for j in 0..nm {
            let s = node_shape(dofs, phi, pm.node, j);
            let cross = [
                s[4] * d[2] - s[5] * d[1],
                s[5] * d[0] - s[3] * d[2],
                s[3] * d[1] - s[4] * d[0],
            ];
            for c in 0..3 {
                shapes[(row + c, j)] = s[c] + cross[c];
                shapes[(row + 3 + c, j)] = s[3 + c];
            }
        }
        // Lumped to the node for the stored nodal mass: inertia about the node = J + m(d·d E − d dᵀ).
        let dd = d.iter().map(|v| v * v).sum::<f64>();
        let (m0, i0) = &mut nodal[pm.node];
        *m0 += pm.mass;
        for r in 0..3 {
            for c in 0..3 {
                i0[r][c] +=
                    pm.inertia[r][c] + pm.mass * (if r == c { dd } else { 0.0 } - d[r] * d[c]);
            }
        }
    }
    Ok((points, shapes, nodal))
}

/// The nodes whose shapes go into the file, ascending; `always` (interface and reference nodes)
/// are always included.
fn stored_nodes(
    model: &Model,
    keep: &KeepNodes,
    always: &[NodeIndex],
    faces: &[crate::faces::GraphicsFace],
) -> Result<Vec<NodeIndex>, String> {
    let mut on = vec![false; model.nodes.len()];
    for &n in always {
        on[n] = true;
    }
    match keep {
        KeepNodes::All => on.iter_mut().for_each(|v| *v = true),
        KeepNodes::Interface => {}
        KeepNodes::Surface => faces
            .iter()
            .flat_map(|f| f.nodes.iter())
            .for_each(|&n| on[n] = true),
        KeepNodes::Set(name) => {
            let set = model
                .node_sets
                .iter()
                .find(|(k, _)| k.eq_ignore_ascii_case(name))
                .ok_or_else(|| {
                    format!(
                        "--keep-nodes {name}: no such node set (node sets: {})",
                        model
                            .node_sets
                            .keys()
                            .cloned()
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                })?;
            set.1.iter().for_each(|&n| on[n] = true);
        }
    }
    Ok((0..on.len()).filter(|&n| on[n]).collect())
}

fn file_label(l: &reduce::ModeLabel) -> file::ModeLabel {
    match l {
        reduce::ModeLabel::Rigid => file::ModeLabel::Rigid,
        reduce::ModeLabel::Normal => file::ModeLabel::Normal,
        reduce::ModeLabel::Constraint { .. } => file::ModeLabel::Constraint,
        reduce::ModeLabel::FixedInterface { .. } => file::ModeLabel::FixedInterface,
        reduce::ModeLabel::Attachment { .. } => file::ModeLabel::Attachment,
        reduce::ModeLabel::FrequencyResponse { .. } => file::ModeLabel::FrequencyResponse,
        // A static load response is an attachment mode of a distributed load; the file's
        // `modal_loads.bin` (format 1.4) marks it residual (the label enum keeps its 1.0 tags).
        reduce::ModeLabel::Residual { .. } => file::ModeLabel::Attachment,
    }
}

fn mask_bools(m: DofMask) -> [bool; 6] {
    std::array::from_fn(|k| m.contains(k))
}

fn flat(m: &Mat<f64>) -> Vec<f64> {
    (0..m.nrows())
        .flat_map(|r| (0..m.ncols()).map(move |c| m[(r, c)]))
        .collect()
}

/// Convert everything into the file's records.
#[allow(clippy::too_many_arguments)]
fn assemble_body(
    spec: &BuildSpec,
    model: &Model,
    dofs: &DofMap,
    phi: &Mat<f64>,
    set: &ModeSet,
    stored: &[NodeIndex],
    interface: &[NodeIndex],
    interface_masks: &[DofMask],
    reference: &[(NodeIndex, DofMask)],
    faces: &[crate::faces::GraphicsFace],
    nodal: &NodalMass,
    inv: &crate::invariants::Invariants,
    fields: Option<&ModalFields>,
) -> Result<file::ReducedBody, BuildError> {
    let mut position = vec![u32::MAX; model.nodes.len()];
    for (i, &n) in stored.iter().enumerate() {
        position[n] = i as u32;
    }
    let is_interface: std::collections::HashSet<NodeIndex> = interface.iter().copied().collect();
    let nodes = stored
        .iter()
        .map(|&n| file::Node {
            id: model.nodes[n].id,
            xyz: model.nodes[n].x,
            interface: is_interface.contains(&n),
        })
        .collect();
    let file_faces = faces
        .iter()
        .filter(|f| f.nodes.iter().all(|&n| position[n] != u32::MAX))
        .filter_map(|f| match f.nodes.len() {
            3 => Some(file::Face::Tri(std::array::from_fn(|k| {
                position[f.nodes[k]]
            }))),
            4 => Some(file::Face::Quad(std::array::from_fn(|k| {
                position[f.nodes[k]]
            }))),
            _ => None, // beam/rod lines go to `lines`
        })
        .collect();
    let lines: Vec<[u32; 2]> = faces
        .iter()
        .filter(|f| f.nodes.len() == 2 && f.nodes.iter().all(|&n| position[n] != u32::MAX))
        .map(|f| [position[f.nodes[0]], position[f.nodes[1]]])
        .collect();
    let nm = set.len();
    let ns = stored.len();
    let mut shapes = vec![0.0; nm * ns * 6];
    for j in 0..nm {
        for (q, &p) in stored.iter().enumerate() {
            shapes[(j * ns + q) * 6..(j * ns + q) * 6 + 6]
                .copy_from_slice(&node_shape(dofs, phi, p, j));
        }
    }
    let omega2 = set.omega2.clone();
    let identity: Vec<f64> = (0..nm * nm)
        .map(|i| if i / nm == i % nm { 1.0 } else { 0.0 })
        .collect();
    let diag: Vec<f64> = (0..nm * nm)
        .map(|i| {
            if i / nm == i % nm {
                omega2[i / nm]
            } else {
                0.0
            }
        })
        .collect();
    let labels: Vec<file::ModeLabel> = set.labels.iter().map(file_label).collect();
    let count_of = |l: file::ModeLabel| labels.iter().filter(|x| **x == l).count() as u64;
    // Constraint columns: one per interface dof, less the reference dofs (improved CB).
    let held = set.reference_dofs.len() as u64;
    let (method, interface_count, fixed_count) = match &set.method {
        reduce::Method::NormalModes => (file::Method::NormalModes, 0, 0),
        reduce::Method::CraigBampton {
            interface,
            fixed_interface_modes,
        } => (
            file::Method::CraigBampton,
            interface.len() as u64,
            *fixed_interface_modes as u64,
        ),
        reduce::Method::ImprovedCraigBampton1 {
            interface,
            fixed_interface_modes,
        }
        | reduce::Method::ImprovedCraigBampton2 {
            interface,
            fixed_interface_modes,
        } => (
            file::Method::CraigBampton,
            (interface.len() as u64).saturating_sub(held),
            *fixed_interface_modes as u64,
        ),
        reduce::Method::CraigChang { attachment, .. } => {
            (file::Method::CraigChang, attachment.len() as u64, 0)
        }
        reduce::Method::Dietz { attachment, .. }
        | reduce::Method::DietzModified { attachment, .. } => {
            (file::Method::Dietz, attachment.len() as u64, 0)
        }
    };
    let identity3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let interface_records = interface
        .iter()
        .zip(interface_masks)
        .map(|(&n, m)| file::InterfaceNode {
            node: position[n],
            dofs: std::array::from_fn(|k| k < usize::from(dofs.count[n]) && m.contains(k)),
            frame: dofs.frames[n].unwrap_or(identity3),
        })
        .collect();
    let mass_kind = match spec.mass {
        fe::MassKind::Lumped => file::MassKind::Lumped,
        fe::MassKind::Consistent => file::MassKind::Consistent,
    };
    let keep_nodes = match &spec.keep_nodes {
        KeepNodes::All => file::KeepNodes::All,
        KeepNodes::Surface => file::KeepNodes::InterfaceAndSurface,
        KeepNodes::Interface => file::KeepNodes::List(vec![]),
        KeepNodes::Set(_) => file::KeepNodes::List(
            stored
                .iter()
                .filter(|n| !is_interface.contains(n))
                .map(|&n| model.nodes[n].id)
                .collect(),
        ),
    };
    let invariants = file::Invariants {
        mask: spec.invariants.mask(),
        i1: vec![inv.i1],
        i2: inv.i2.to_vec(),
        i3: inv.i3.as_ref().map(flat).unwrap_or_default(),
        i4: inv.i4.as_ref().map(flat).unwrap_or_default(),
        i5: inv
            .i5
            .as_ref()
            .map(|v| v.iter().flat_map(flat).collect())
            .unwrap_or_default(),
        i6: inv.i6.as_ref().map(flat).unwrap_or_default(),
        i7: inv.i7.iter().flatten().copied().collect(),
        i8: inv
            .i8
            .as_ref()
            .map(|v| v.iter().flat_map(|m| m.iter().flatten().copied()).collect())
            .unwrap_or_default(),
        i9: inv
            .i9
            .as_ref()
            .map(|v| v.iter().flat_map(|m| m.iter().flatten().copied()).collect())
            .unwrap_or_default(),
    };
    let removed = set.diagnostics.removed.len() as u64;
    let residual = set.diagnostics.residual_vectors as u64;
    let shift_fraction = matches!(
        set.method,
        reduce::Method::Dietz { .. } | reduce::Method::DietzModified { .. }
    )
    .then_some(reduce::dietz::DEFAULT_SHIFT_FRACTION);
    let mut body = file::ReducedBody {
        version: flexbody_reader::FORMAT_VERSION,
        generator: file::Generator {
            name: "flexbody".into(),
            version: env!("CARGO_PKG_VERSION").into(),
        },
        units: spec.units.clone(),
        header: file::Header {
            title: spec.title.clone().unwrap_or_else(|| {
                spec.model
                    .file_name()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default()
            }),
            created_utc: spec.created_utc.clone(),
            request: file::Request {
                method,
                fmax_hz: spec.fmax_hz,
                mode_count: spec.modes.map(|n| n as u64),
                keep_nodes,
                invariant_set: spec.invariants,
                mass_kind,
            },
        },
        nodes,
        faces: file_faces,
        nodal_mass: stored
            .iter()
            .map(|&n| file::NodalMass {
                mass: nodal[n].0,
                inertia: nodal[n].1,
            })
            .collect(),
        modes: file::Modes {
            frequency_hz: set.frequencies_hz(),
            omega2,
            labels: labels.clone(),
            generalized_mass: identity,
            generalized_stiffness: diag,
            shapes,
        },
        invariants,
        method: file::MethodRecord {
            method,
            mass_kind,
            interface: interface_records,
            reference_conditions: reference
                .iter()
                .map(|&(n, m)| file::ReferenceCondition {
                    node: position[n],
                    dofs: mask_bools(m),
                })
                .collect(),
            // SPEC §5.7: rigid = modes labelled Rigid; the others count basis vectors by origin.
            counts: match method {
                file::Method::NormalModes => file::ModeCounts {
                    rigid: count_of(file::ModeLabel::Rigid),
                    normal: nm as u64 - count_of(file::ModeLabel::Rigid),
                    ..Default::default()
                },
                file::Method::CraigBampton => file::ModeCounts {
                    rigid: count_of(file::ModeLabel::Rigid),
                    constraint: interface_count,
                    // residual vectors count with the component modes (SPEC §5.14)
                    fixed_interface: fixed_count + residual,
                    removed_dependent: removed,
                    ..Default::default()
                },
                file::Method::CraigChang | file::Method::Dietz => file::ModeCounts {
                    rigid: count_of(file::ModeLabel::Rigid),
                    normal: set.diagnostics.basis_normal_modes.unwrap_or(0) as u64,
                    attachment: interface_count + residual,
                    removed_dependent: removed,
                    ..Default::default()
                },
            },
            cutoffs: file::Cutoffs {
                fmax_hz: spec.fmax_hz,
                shift_fraction,
                dependency_tolerance: (method != file::Method::NormalModes)
                    .then_some(set.diagnostics.dependency_tol),
            },
        },
        stress_shapes: fields.and_then(|f| field_shapes(f, f.stress.as_ref(), &position)),
        strain_shapes: fields.and_then(|f| field_shapes(f, f.strain.as_ref(), &position)),
        damping: None,
        lines: (!lines.is_empty()).then_some(lines),
        recipe: None,
        stress_shapes_bottom: None,
        strain_shapes_bottom: None,
        interfaces: None,
        label_shares: Some(if set.diagnostics.label_shares.len() == nm {
            set.diagnostics.label_shares.clone()
        } else {
            vec![1.0; nm]
        }),
        modal_loads: None,
    };
    body.version = flexbody_reader::version_for(&body);
    Ok(body)
}

/// Recovered fields → the file's entry: node indices become positions in the stored node list
/// (the fields were recovered at stored nodes only, so every position exists).
fn field_shapes(
    f: &ModalFields,
    values: Option<&Vec<f64>>,
    position: &[u32],
) -> Option<file::FieldShapes> {
    values.map(|v| file::FieldShapes {
        nodes: f.nodes.iter().map(|&n| position[n]).collect(),
        values: v.clone(),
    })
}
