//! The command line's arguments (clap) and their conversion into the library's specs: the one
//! place where typed text becomes a [`BuildSpec`] or [`ModelOverrides`]; the value grammar
//! itself is [`crate::pipeline::options`].
use std::path::PathBuf;

use clap::{Parser, Subcommand};

use crate::pipeline::recipe::ModelOverrides;
use crate::pipeline::BuildSpec;

/// FE model → reduced flexible-body file for multibody solvers.
#[derive(Parser)]
#[command(name = "flexbody", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Build a reduced flexible-body file from an FE model (.inp, .bdf, .msh).
    Build(Box<BuildArgs>),
    /// Print what a .flexbody file holds: header, units, counts, mass properties, modes, entries.
    Inspect {
        /// The .flexbody file.
        file: PathBuf,
        /// Print the summary as JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Verify a .flexbody file (orthonormality, mass properties, rigid modes; with --model also
    /// frequencies and residuals against the FE model). Exit code 1 when a check fails.
    Check(CheckArgs),
    /// Export a .flexbody file to another solver's format: exudyn (NPZ for
    /// ObjectFFRFreducedOrderInterface.LoadFromFile), mbdyn (modal element .fem file), sid
    /// (Standard Input Data, .SID_FEM text), vtu (VTK XML unstructured grid for ParaView: the
    /// kept mesh, mode shapes and stress/strain shapes) or mtx (the constrained K and M the
    /// build reduced, Matrix Market, with --model).
    Export {
        /// The .flexbody file.
        file: PathBuf,
        /// Target format: exudyn, mbdyn, sid, vtu or mtx.
        #[arg(long)]
        to: String,
        /// Output file (mtx: a folder for K.mtx, M.mtx, dofs.txt and coords.csv).
        #[arg(short, long)]
        output: PathBuf,
        /// mtx: the FE model the file was built from, rebuilt with the options recorded in the
        /// file's recipe (options given here override them). A model file changed since the
        /// build is refused.
        #[arg(long)]
        model: Option<PathBuf>,
        #[command(flatten)]
        model_args: ModelArgs,
        /// mtx: mass matrix lumped or consistent (default: as the file was built).
        #[arg(long)]
        mass: Option<String>,
    },
    /// Write one self-contained HTML page (no network) that animates the modes of a .flexbody
    /// file, marks its interfaces and lists its mass, modes and frequencies. The URL fragment
    /// #mode=7&t=0.25 selects a mode and freezes the animation.
    View {
        /// The .flexbody file.
        file: PathBuf,
        /// Output file (.html).
        #[arg(short, long)]
        output: PathBuf,
    },
}

/// Model options shared by `build`, `check --model` and `export --to mtx --model`.
#[derive(clap::Args, Clone)]
pub(crate) struct ModelArgs {
    /// Input format (default: from the extension): inp, bdf, msh.
    #[arg(long)]
    pub(crate) format: Option<String>,
    /// Material for elements without a section (Gmsh meshes): E=…,nu=…,rho=…
    #[arg(long)]
    pub(crate) material: Option<String>,
    /// Thickness of shell elements without a section (Gmsh triangles/quadrangles), with
    /// --material.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) thickness: Option<f64>,
    /// Interface nodes: node ids (every free component), NODE:DOFS with Nastran component digits
    /// (e.g. 1:126) and/or node-set names, comma separated. Default: for `build` the deck's
    /// ASET/BSET; with `check --model` and `export --to mtx` the file's recipe.
    #[arg(long, value_delimiter = ',')]
    pub(crate) interface: Vec<String>,
    /// How a node set named in --interface is attached: rbe2 (rigid spider, default), rbe3
    /// (weighted average) or none (every node of the set is an interface node). With `check
    /// --model` and `export --to mtx`: default from the file's recipe; `export --to mtx --spider
    /// none` keeps the sets' nodes free for a peer's own reduction.
    #[arg(long)]
    pub(crate) spider: Option<String>,
    /// Nastran: the case-control subcase whose SPC and METHOD selections apply (needed when
    /// the deck's subcases select different sets). With `check --model` and `export --to mtx`:
    /// default from the file's recipe.
    #[arg(long, value_name = "N")]
    pub(crate) subcase: Option<u64>,
    /// Drop these cards or keywords on purpose although they could change stiffness, mass,
    /// constraints or a preload (a build refuses them otherwise), comma separated: Nastran card
    /// names (CGAP, PARAM:SNORM), Abaqus keywords (*TIE or TIE) or element types; an Abaqus
    /// element variant flexbody does not form as VARIANT=BASE reads it as its base type
    /// (S4R=S4, B31R=B31, S3R=S3, C3D10M=C3D10). Each dropped card is a warning; the recipe
    /// records the list. With `check --model` and `export --to
    /// mtx`: default from the file's recipe.
    #[arg(long, value_delimiter = ',', value_name = "CARD")]
    pub(crate) ignore: Vec<String>,
    /// How an Abaqus/CalculiX deck's shells (S3, S4R, S6, S8, S8R; S4) are formed: `expanded`
    /// (default) into one layer of C3D6/C3D8R/C3D15/C3D20/C3D20R bricks joined to the shell
    /// nodes as ccx 2.20 does, so the deck means what CalculiX makes of it (S4, which ccx
    /// expands into its own C3D8I, is refused); `native`: flexbody's shell elements (MITC4,
    /// DKT, curved MITC9/MITC6; S4R refused as a variant). Recorded in the recipe; with `check
    /// --model` and `export --to mtx`: default from the file's recipe.
    #[arg(long, value_name = "expanded|native")]
    pub(crate) inp_shells: Option<String>,
}

#[derive(clap::Args)]
pub(crate) struct BuildArgs {
    /// The FE model file.
    pub(crate) model: PathBuf,
    #[command(flatten)]
    pub(crate) model_args: ModelArgs,
    /// Output file (.flexbody).
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// Reduction method: cb (Craig–Bampton), normal, craig-chang or dietz.
    #[arg(long, default_value = "cb")]
    pub(crate) method: String,
    /// Number of fixed-interface modes (cb), free-free modes (craig-chang, dietz) or normal
    /// modes (normal); default 20 without --fmax.
    #[arg(long)]
    pub(crate) modes: Option<usize>,
    /// Highest frequency of the scene in Hz: modes are kept up to 3× it.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) fmax: Option<f64>,
    /// Reference conditions NODE:DOFS (Nastran dof digits), e.g. 1:12,9:2; a plain node id (its
    /// free components) or a set name (a node set, or a deck's constraint set such as SPC_1
    /// with the components it holds).
    #[arg(long, value_delimiter = ',')]
    pub(crate) reference_conditions: Vec<String>,
    /// Improved Craig–Bampton method for reference conditions: 1 or 2.
    #[arg(long, default_value_t = 1)]
    pub(crate) reference_method: u8,
    /// Mass matrix: lumped (default; what multibody invariants need) or consistent. Default for
    /// a Nastran deck with PARAM,COUPMASS > 0: consistent, as the deck asks.
    #[arg(long)]
    pub(crate) mass: Option<String>,
    /// Rotational inertia of lumped beam masses: auto (default: as Nastran lumps each card for
    /// Nastran decks, CBAR none, CBEAM torsion only, CQUAD4/CTRIA3 translations only; the
    /// section's rotary inertia otherwise),
    /// section, torsion, none or nastran.
    #[arg(long, default_value = "auto", value_name = "KIND")]
    pub(crate) beam_mass: String,
    /// The model's consistent unit system (recorded in the file, never guessed): si (kg m s N),
    /// mm-t-s (t mm s N), mm-kg-ms (kg mm ms kN), cm-g-s (g cm s dyn), in-lbf-s (lbf·s²/in in s lbf).
    #[arg(long)]
    pub(crate) units: String,
    /// Which nodes get mode shapes in the file: all, interface, surface, or a node-set name.
    #[arg(long, default_value = "all")]
    pub(crate) keep_nodes: String,
    /// Invariant set: full, partial (no 5, 9), constant (1, 2, 6, 7) or rigid (1, 2, 7).
    /// Invariant 9 costs 72·M² bytes for M modes.
    #[arg(long, default_value = "full")]
    pub(crate) invariants: String,
    /// Store modal stress and strain shapes of the solid and shell elements at the kept nodes
    /// (nodal averages, body axes, xx yy zz xy yz zx; shells: top fibre, and the bottom fibre
    /// in the format-1.5 `*_bottom.bin` entries): both (default when given), stress or strain.
    /// Costs 48·M bytes per kept node and field for M modes.
    #[arg(long, num_args = 0..=1, default_missing_value = "both", value_name = "FIELDS")]
    pub(crate) stress_modes: Option<String>,
    /// Threads for the sparse factorization, the block solves and the dense kernels (default:
    /// the available cores; 1 for a sequential run; see docs/benchmarks.md for 1 vs 2 measured).
    #[arg(long, default_value_t = default_threads(), value_name = "N")]
    pub(crate) threads: usize,
    /// Memory a sparse factorization may use, e.g. 8G (bytes, or with a K, M or G suffix);
    /// default: MemAvailable. The factor size is estimated before factoring and the build stops
    /// with a clear error instead of being killed. Same as the FLEXBODY_MAX_MEMORY variable.
    #[arg(long, value_name = "SIZE")]
    pub(crate) max_memory: Option<String>,
    /// Modal damping stored in the file: one ratio (2% or 0.02), ratios by frequency band
    /// (0-1000:1%,1000-:3%, Hz, [lo, hi), empty hi = open), or rayleigh:ALPHA,BETA
    /// (ζ = α/2ω + βω/2). Rigid-body modes get 0.
    #[arg(long, value_name = "SPEC")]
    pub(crate) damping: Option<String>,
    /// Scene gravity: acceleration ax,ay,az in the basic frame (e.g. 0,0,-9.81): load GRAVITY =
    /// M·g, stored as a modal load.
    #[arg(long, value_name = "AX,AY,AZ", allow_hyphen_values = true)]
    pub(crate) gravity: Option<String>,
    /// A scene load (repeatable): NAME:NODE:FX,FY,FZ[,MX,MY,MZ] (a node id), NAME:SET:P (uniform
    /// pressure on the free faces within node set SET, positive into the body) or NAME of a
    /// deck's load set (LOAD_10). The deck's selected loads (LOAD = n) are always included.
    #[arg(long = "load", value_name = "SPEC", allow_hyphen_values = true)]
    pub(crate) loads: Vec<String>,
    /// Preload the modes with the linear static state of these scene loads (names of --gravity's
    /// GRAVITY, --load entries or the deck's load sets, comma-separated): the modes are those
    /// of K + K_G(σ₀); a preload beyond the first buckling load is an error. Default: the
    /// deck's own preload (CalculiX *STATIC before a *STEP, PERTURBATION frequency step).
    #[arg(long, value_name = "LOAD[,LOAD…]", value_delimiter = ',')]
    pub(crate) preload: Vec<String>,
    /// Add residual vectors (static responses) to the basis: loads (each scene load), interface
    /// (unit loads at the interface dofs) or both; inertia-relief balanced for a free body.
    #[arg(long, value_name = "KIND", num_args = 0..=1, default_missing_value = "loads")]
    pub(crate) residual_vectors: Option<String>,
    /// Prove each eigenproblem's modes complete: Sylvester's inertia count of K − σM just above
    /// the highest mode returned must equal the modes returned, else the build fails (one
    /// extra LDLᵀ factorization per eigenproblem; the report states the proven band).
    #[arg(long)]
    pub(crate) verify_band: bool,
    /// Solver engine for the eigenproblem of normal modes and Craig-Chang and for the
    /// Craig-Bampton interior: native (ours) or slepc (PETSc/SLEPc with MUMPS under MPI: needs
    /// mpirun and slepc4py, e.g. Debian's openmpi-bin and python3-slepc4py-real; a --fmax band
    /// is proven complete by an inertia count). The reduction, invariants and file stay ours.
    #[arg(long, default_value = "native", value_name = "native|slepc")]
    pub(crate) engine: String,
    /// MPI ranks for --engine slepc (mpirun -np N).
    #[arg(long, default_value_t = 2, value_name = "N")]
    pub(crate) mpi: usize,
    /// Arithmetic of the Craig–Bampton interior's factorization: auto (f64, unless the f64
    /// factor would exceed --max-memory/MemAvailable and an f32 one fits), f64, or mixed (an
    /// f32 factor, half the memory, with solves refined to f64 accuracy and a leaner Krylov
    /// basis: slower, see docs/benchmarks.md and docs/memory.md; f64 again where K_ii is too
    /// ill-conditioned for it).
    #[arg(long, default_value = "auto", value_name = "auto|f64|mixed")]
    pub(crate) precision: String,
    /// Eigensolver of normal modes, Craig–Bampton's fixed-interface modes and Craig–Chang:
    /// lanczos (block shift-invert, exact to 1e-10), amls (automated multilevel substructuring:
    /// substructure modes up to 4x the band's top eigenvalue, two subspace-iteration steps, a
    /// Rayleigh–Ritz step on K and M, per-mode residuals and an inertia count that fails the
    /// build if a mode is missing; amls:F sets the cutoff factor F), or auto (docs/amls.md).
    #[arg(long, default_value = "auto", value_name = "auto|lanczos|amls|amls:F")]
    pub(crate) eigensolver: String,
    /// Keep the fewest modes whose estimated frequency-response error at the scene's loads and
    /// interfaces over [0, fmax] stays below EPS (relative to the static response):
    /// participation:EPS, e.g. participation:0.01. The candidates are the modes --fmax/--modes
    /// computes; what was dropped and the estimate are in the build report.
    #[arg(long, value_name = "participation:EPS")]
    pub(crate) select: Option<String>,
    /// Store the modal geometric stiffness of the body's stress under unit loads, so a
    /// multibody solver can stiffen a spinning or accelerated body (format 1.7
    /// geometric_stiffness.bin): inertia = the twelve unit inertia loads (translational
    /// accelerations, angular-velocity products ω_iω_j, angular accelerations). Not with a
    /// preload.
    #[arg(long, value_name = "inertia")]
    pub(crate) geometric_stiffness: Option<String>,
    /// No stress or strain shapes (the default; for scripts that want to say so).
    #[arg(long, conflicts_with = "stress_modes")]
    pub(crate) no_stress: bool,
    /// Title stored in the header (default: the model file name).
    #[arg(long)]
    pub(crate) title: Option<String>,
    /// Record the creation time in the header (makes the output non-reproducible).
    #[arg(long)]
    pub(crate) timestamp: bool,
    /// No progress, notes or summary on stderr (warnings are still printed).
    #[arg(long, short)]
    pub(crate) quiet: bool,
    /// Print the build report as JSON on stdout.
    #[arg(long)]
    pub(crate) json: bool,
    /// Also write the constrained K and M the reduction starts from (Matrix Market K.mtx,
    /// M.mtx, lumped or consistent as built), their dof table dofs.txt and the nodes'
    /// coordinates coords.csv into DIR.
    #[arg(long, value_name = "DIR")]
    pub(crate) write_matrices: Option<PathBuf>,
}

#[derive(clap::Args)]
pub(crate) struct CheckArgs {
    /// The .flexbody file.
    pub(crate) file: PathBuf,
    /// The FE model the file was built from. The model is rebuilt with the options recorded in
    /// the file's recipe (interfaces, spiders, format, material, beam mass); options given here
    /// override them. A model file changed since the build fails the check.
    #[arg(long)]
    pub(crate) model: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) model_args: ModelArgs,
    /// Print the report as JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

pub(crate) fn import_format(
    name: &Option<String>,
) -> anyhow::Result<Option<crate::import::Format>> {
    name.as_deref()
        .map(|n| {
            crate::import::Format::from_name(n)
                .ok_or_else(|| anyhow::anyhow!("--format {n}: expected inp, bdf, msh, cdb or full"))
        })
        .transpose()
}

/// clap arguments → the library's build spec (the one conversion point).
pub(crate) fn build_spec(a: &BuildArgs) -> anyhow::Result<BuildSpec> {
    use crate::pipeline::options::*;
    check_numbers(a.fmax, a.model_args.thickness)?;
    if !matches!(a.reference_method, 1 | 2) {
        anyhow::bail!(
            "--reference-method {}: expected 1 or 2 (Wang, Niu & Feng 2023, methods 1 and 2)",
            a.reference_method
        );
    }
    Ok(BuildSpec {
        model: a.model.clone(),
        format: import_format(&a.model_args.format)?,
        material: a
            .model_args
            .material
            .as_deref()
            .map(parse_material)
            .transpose()?,
        thickness: a.model_args.thickness,
        interface: a.model_args.interface.clone(),
        spider: parse_spider(a.model_args.spider.as_deref().unwrap_or("rbe2"))?,
        method: parse_method(&a.method)?,
        modes: a.modes,
        fmax_hz: a.fmax,
        reference_conditions: parse_reference_entries(&a.reference_conditions)?.0,
        reference_sets: parse_reference_entries(&a.reference_conditions)?.1,
        reference_method: a.reference_method,
        mass: parse_mass(a.mass.as_deref().unwrap_or("lumped"))?,
        mass_explicit: a.mass.is_some(),
        subcase: a.model_args.subcase,
        ignore: a.model_args.ignore.clone(),
        inp_shells: (a.model_args.inp_shells.as_deref())
            .map(crate::pipeline::options::parse_inp_shells)
            .transpose()?
            .unwrap_or_default(),
        units: parse_units(&a.units)?,
        keep_nodes: parse_keep_nodes(&a.keep_nodes),
        invariants: parse_invariants(&a.invariants)?,
        fields: parse_field_request(if a.no_stress {
            None
        } else {
            a.stress_modes.as_deref()
        })?,
        title: a.title.clone(),
        created_utc: a.timestamp.then(utc_now),
        threads: a.threads.max(1),
        verify_band: a.verify_band,
        engine: match a.engine.as_str() {
            "native" => None,
            "slepc" => Some(crate::solve::slepc::SlepcEngine {
                ranks: a.mpi.max(1),
            }),
            other => anyhow::bail!("--engine {other}: expected native or slepc"),
        },
        precision: a
            .precision
            .parse()
            .map_err(|e: String| anyhow::anyhow!("--precision {e}"))?,
        eigensolver: a
            .eigensolver
            .parse()
            .map_err(|e: String| anyhow::anyhow!("--eigensolver {e}"))?,
        beam_mass: parse_beam_mass(&a.beam_mass)?,
        scene: crate::pipeline::SceneSpec {
            gravity: a.gravity.clone(),
            loads: a.loads.clone(),
            residual_vectors: a
                .residual_vectors
                .as_deref()
                .map(crate::pipeline::scene::parse_residual_vectors)
                .transpose()?,
            select: a
                .select
                .as_deref()
                .map(crate::pipeline::scene::parse_select)
                .transpose()?,
            preload: a.preload.clone(),
        },
        geometric_stiffness: a
            .geometric_stiffness
            .as_deref()
            .map(crate::pipeline::options::parse_geometric_stiffness)
            .transpose()?,
        damping: a.damping.clone(),
        constrained_system: a.write_matrices.is_some(),
    })
}

/// Numeric options checked before any model work (issue 31/32: `--fmax=-5` was refused only
/// after the reduction): finite and positive.
fn check_numbers(fmax: Option<f64>, thickness: Option<f64>) -> anyhow::Result<()> {
    for (name, value, what) in [
        ("--fmax", fmax, "a positive frequency in Hz"),
        (
            "--thickness",
            thickness,
            "a positive length in the model's units",
        ),
    ] {
        if let Some(v) = value {
            if !(v.is_finite() && v > 0.0) {
                anyhow::bail!("{name} {v}: must be {what}");
            }
        }
    }
    Ok(())
}

/// The `--threads` default: the cores this process may use (1 when unknown).
fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, usize::from)
}

/// Current time as RFC 3339 UTC (civil-from-days, no time-zone database needed).
fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = ((secs / 86_400) as i64, secs % 86_400);
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

impl ModelArgs {
    /// The model options given on the command line, as their flags (`--interface`, …): `check`
    /// and `export` use them only to rebuild the model, so without `--model` they are an error,
    /// never silently ignored.
    pub(crate) fn given(&self) -> Vec<&'static str> {
        let mut given = Vec::new();
        let flags = [
            ("--format", self.format.is_some()),
            ("--material", self.material.is_some()),
            ("--thickness", self.thickness.is_some()),
            ("--interface", !self.interface.is_empty()),
            ("--spider", self.spider.is_some()),
            ("--subcase", self.subcase.is_some()),
            ("--ignore", !self.ignore.is_empty()),
            ("--inp-shells", self.inp_shells.is_some()),
        ];
        for (flag, present) in flags {
            if present {
                given.push(flag);
            }
        }
        given
    }

    /// An error when model options were given although no model is read (`what` says which
    /// command and target reads none).
    pub(crate) fn refuse_without_model(&self, what: &str) -> anyhow::Result<()> {
        let given = self.given();
        if given.is_empty() {
            return Ok(());
        }
        anyhow::bail!(
            "{}: {what} reads no FE model, so {} would be ignored; these options rebuild the \
             model given with --model MODEL",
            given.join(", "),
            if given.len() == 1 { "it" } else { "they" }
        )
    }
}

/// Options whose value is optional, the words that value may be, and the value they take when
/// given alone (clap's `default_missing_value`, repeated here).
const OPTIONAL_VALUE_OPTIONS: [(&str, &[&str], &str); 2] = [
    ("--stress-modes", &["both", "stress", "strain"], "both"),
    (
        "--residual-vectors",
        &["loads", "interface", "both"],
        "loads",
    ),
];

/// The command line with an option of optional value (`--stress-modes [FIELDS]`,
/// `--residual-vectors [KIND]`) written `--stress-modes=both` when the word after it is a path
/// (it names an existing file, or holds a `.` or `/`, which none of the values does), so the
/// option does not swallow the model path: `build --stress-modes plate.bdf` (issue 47).
pub fn attach_optional_values<I: IntoIterator<Item = std::ffi::OsString>>(
    args: I,
) -> Vec<std::ffi::OsString> {
    let args: Vec<std::ffi::OsString> = args.into_iter().collect();
    let mut out = Vec::with_capacity(args.len());
    for (k, arg) in args.iter().enumerate() {
        let option = OPTIONAL_VALUE_OPTIONS
            .iter()
            .find(|(flag, _, _)| arg.to_str() == Some(flag));
        let next = args.get(k + 1).map(|n| n.to_string_lossy());
        match (option, next) {
            (Some((flag, values, default)), Some(next))
                if !next.starts_with('-')
                    && !values.contains(&next.trim().to_ascii_lowercase().as_str())
                    && (next.contains(['.', '/']) || std::path::Path::new(&*next).exists()) =>
            {
                out.push(format!("{flag}={default}").into());
            }
            _ => out.push(arg.clone()),
        }
    }
    out
}

/// `--model` options given explicitly; each overrides the file's recipe.
pub(crate) fn model_overrides(a: &ModelArgs) -> anyhow::Result<ModelOverrides> {
    check_numbers(None, a.thickness)?;
    Ok(ModelOverrides {
        format: import_format(&a.format)?,
        material: a
            .material
            .as_deref()
            .map(crate::pipeline::options::parse_material)
            .transpose()?,
        interface: a.interface.clone(),
        spider: a
            .spider
            .as_deref()
            .map(crate::pipeline::options::parse_spider)
            .transpose()?,
        thickness: a.thickness,
        subcase: a.subcase,
        ignore: a.ignore.clone(),
        inp_shells: (a.inp_shells.as_deref())
            .map(crate::pipeline::options::parse_inp_shells)
            .transpose()?,
    })
}
