//! What a build is asked: [`BuildSpec`] (the model, the method, the options of every stage), as
//! the command line or a program states it. The deck's own requests fill what it leaves open
//! ([`super::plan`]).

use std::path::PathBuf;

use faer::Par;
use flexbody_reader as file;

use crate::body::stress::FieldRequest;
use crate::fe::{self, BeamLumping};
use crate::import::Format;
use crate::model::{DofMask, Material};
use crate::pipeline::interface::SpiderKind;
use crate::reduce::residual::ResidualKind;

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
    /// deck's constraint set (`SPC_1`: the components it holds) — see [`crate::pipeline::deck`].
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
    /// `--ignore`: cards or keywords dropped on purpose although they could change the body
    /// ([`crate::import::ImportOptions::ignore_cards`]; recorded in the recipe).
    pub ignore: Vec<String>,
    /// `--inp-shells`: an Abaqus/CalculiX deck's shells expanded into bricks as ccx does (the
    /// default) or flexbody's shells ([`crate::import::ImportOptions::inp_shells`]; recorded
    /// in the recipe).
    pub inp_shells: crate::import::InpShells,
    /// `mass` was chosen by the user (`--mass`); when false a deck's PARAM,COUPMASS > 0 selects
    /// consistent mass (see [`crate::pipeline::deck`]).
    pub mass_explicit: bool,
    /// The scene: loads (`--gravity`, `--load`) and residual vectors (`--residual-vectors`).
    pub scene: SceneSpec,
    /// `--verify-band`: prove every eigenproblem's returned modes complete by an inertia count
    /// (one extra LDLᵀ factorization each; [`crate::solve::EigenSpec::verify_band`]).
    pub verify_band: bool,
    /// `--engine slepc --mpi N`: the eigenproblem of normal modes and Craig–Chang, and the
    /// Craig–Bampton interior (factorization, constraint modes, fixed-interface eigenproblem), on
    /// PETSc/SLEPc under MPI; `None`: our own solvers.
    pub engine: Option<crate::solve::slepc::SlepcEngine>,
    /// `--precision`: arithmetic of the Craig–Bampton interior's factorization.
    pub precision: crate::solve::Precision,
    /// `--eigensolver`: Lanczos, AMLS or auto for every eigen solve of the build.
    pub eigensolver: crate::solve::EigenMethod,
    /// `--geometric-stiffness`: which unit loads' modal geometric stiffness the file holds
    /// (`geometric_stiffness.bin`, format 1.7; `None`: no entry).
    pub geometric_stiffness: Option<GeometricLoads>,
    /// `--damping` as given: the modal damping ratios the file holds
    /// ([`crate::body::damping::parse_damping`]; `None`: no `damping.bin`).
    pub damping: Option<String>,
    /// `--write-matrices`: the output carries the constrained K_r, M_r the reduction starts
    /// from (copied after the preload stage; [`super::BuildOutput::constrained_system`]).
    pub constrained_system: bool,
}

/// The unit loads of `--geometric-stiffness` (SPEC §5.16).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GeometricLoads {
    /// The twelve unit inertia loads: translational accelerations, angular-velocity products,
    /// angular accelerations.
    Inertia,
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
            ignore: Vec::new(),
            inp_shells: Default::default(),
            mass_explicit: false,
            scene: Default::default(),
            verify_band: false,
            engine: None,
            precision: Default::default(),
            eigensolver: Default::default(),
            geometric_stiffness: None,
            damping: None,
            constrained_system: false,
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

    /// This spec with [`Self::beam_lumping`] made explicit, as [`super::build`] passes it on once
    /// the model file is known.
    pub fn with_beam_lumping_resolved(&self) -> BuildSpec {
        BuildSpec {
            beam_mass: Some(self.beam_lumping()),
            ..self.clone()
        }
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

/// The scene options of a build.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SceneSpec {
    /// `--gravity` as given.
    pub gravity: Option<String>,
    /// `--load` entries as given.
    pub loads: Vec<String>,
    /// `--residual-vectors`.
    pub residual_vectors: Option<ResidualKind>,
    /// `--select participation:ε`: the ε (see [`crate::reduce::participation`]).
    pub select: Option<f64>,
    /// `--preload LOAD[,LOAD…]`: the scene loads whose linear static state preloads the modes
    /// (the preload stage); empty: the deck's preload, if any.
    pub preload: Vec<String>,
}

impl SceneSpec {
    /// Whether the scene asks for anything.
    pub fn is_empty(&self) -> bool {
        self.gravity.is_none()
            && self.loads.is_empty()
            && self.residual_vectors.is_none()
            && self.select.is_none()
    }
}
