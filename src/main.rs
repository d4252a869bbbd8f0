//! The `flexbody` command line. The only place where errors become text and exit codes:
//! 0 ok, 1 a `check` failed, 2 error.
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// FE model → reduced flexible-body file for multibody solvers.
#[derive(Parser)]
#[command(name = "flexbody", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
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
    /// (Standard Input Data, .SID_FEM text) or mtx (the constrained K and M the build reduced,
    /// Matrix Market, with --model).
    Export {
        /// The .flexbody file.
        file: PathBuf,
        /// Target format: exudyn, mbdyn, sid or mtx.
        #[arg(long)]
        to: String,
        /// Output file (mtx: a folder for K.mtx, M.mtx and dofs.txt).
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
}

/// Model options shared by `build` and `check --model`.
#[derive(clap::Args, Clone)]
struct ModelArgs {
    /// Input format (default: from the extension): inp, bdf, msh.
    #[arg(long)]
    format: Option<String>,
    /// Material for elements without a section (Gmsh meshes): E=…,nu=…,rho=…
    #[arg(long)]
    material: Option<String>,
    /// Thickness of shell elements without a section (Gmsh triangles/quadrangles), with
    /// --material.
    #[arg(long)]
    thickness: Option<f64>,
    /// Interface nodes: node ids (every free component), NODE:DOFS with Nastran component digits
    /// (e.g. 1:126) and/or node-set names, comma separated. Default: the deck's ASET/BSET.
    #[arg(long, value_delimiter = ',')]
    interface: Vec<String>,
    /// How a node set named in --interface is attached: rbe2 (rigid spider, default), rbe3
    /// (weighted average) or none (every node of the set is an interface node). `check`: default
    /// from the file's recipe.
    #[arg(long)]
    spider: Option<String>,
    /// Nastran: the case-control subcase whose SPC and METHOD selections apply (needed when
    /// the deck's subcases select different sets). `check`: default
    /// from the file's recipe.
    #[arg(long, value_name = "N")]
    subcase: Option<u64>,
}

#[derive(clap::Args)]
struct BuildArgs {
    /// The FE model file.
    model: PathBuf,
    #[command(flatten)]
    model_args: ModelArgs,
    /// Output file (.flexbody).
    #[arg(short, long)]
    output: PathBuf,
    /// Reduction method: cb (Craig–Bampton), normal, craig-chang or dietz.
    #[arg(long, default_value = "cb")]
    method: String,
    /// Number of fixed-interface modes (cb), free-free modes (craig-chang, dietz) or normal
    /// modes (normal); default 20 without --fmax.
    #[arg(long)]
    modes: Option<usize>,
    /// Highest frequency of the scene in Hz: modes are kept up to 3× it.
    #[arg(long)]
    fmax: Option<f64>,
    /// Reference conditions NODE:DOFS (Nastran dof digits), e.g. 1:12,9:2; a plain node id (its
    /// free components) or a set name (a node set, or a deck's constraint set such as SPC_1
    /// with the components it holds).
    #[arg(long, value_delimiter = ',')]
    reference_conditions: Vec<String>,
    /// Improved Craig–Bampton method for reference conditions: 1 or 2.
    #[arg(long, default_value_t = 1)]
    reference_method: u8,
    /// Mass matrix: lumped (default; what multibody invariants need) or consistent. Default for
    /// a Nastran deck with PARAM,COUPMASS > 0: consistent, as the deck asks.
    #[arg(long)]
    mass: Option<String>,
    /// Rotational inertia of lumped beam masses: auto (default: as Nastran lumps each card for
    /// Nastran decks, CBAR none, CBEAM torsion only, CQUAD4/CTRIA3 translations only; the
    /// section's rotary inertia otherwise),
    /// section, torsion, none or nastran.
    #[arg(long, default_value = "auto", value_name = "KIND")]
    beam_mass: String,
    /// The model's consistent unit system (recorded in the file, never guessed): si (kg m s N),
    /// mm-t-s (t mm s N), mm-kg-ms (kg mm ms kN), cm-g-s (g cm s dyn), in-lbf-s (lbf·s²/in in s lbf).
    #[arg(long)]
    units: String,
    /// Which nodes get mode shapes in the file: all, interface, surface, or a node-set name.
    #[arg(long, default_value = "all")]
    keep_nodes: String,
    /// Invariant set: full, partial (no 5, 9), constant (1, 2, 6, 7) or rigid (1, 2, 7).
    /// Invariant 9 costs 72·M² bytes for M modes.
    #[arg(long, default_value = "full")]
    invariants: String,
    /// Store modal stress and strain shapes of the solid and shell elements at the kept nodes
    /// (nodal averages, body axes, xx yy zz xy yz zx; shells: top fibre, and the bottom fibre
    /// in the format-1.5 `*_bottom.bin` entries): both (default when given), stress or strain.
    /// Costs 48·M bytes per kept node and field for M modes.
    #[arg(long, num_args = 0..=1, default_missing_value = "both", value_name = "FIELDS")]
    stress_modes: Option<String>,
    /// Threads for the sparse factorization, the block solves and the dense kernels (default:
    /// the available cores; 1 for a sequential run; see docs/benchmarks.md for 1 vs 2 measured).
    #[arg(long, default_value_t = default_threads(), value_name = "N")]
    threads: usize,
    /// Memory a sparse factorization may use, e.g. 8G (bytes, or with a K, M or G suffix);
    /// default: MemAvailable. The factor size is estimated before factoring and the build stops
    /// with a clear error instead of being killed. Same as the FLEXBODY_MAX_MEMORY variable.
    #[arg(long, value_name = "SIZE")]
    max_memory: Option<String>,
    /// Modal damping stored in the file: one ratio (2% or 0.02), ratios by frequency band
    /// (0-1000:1%,1000-:3%, Hz, [lo, hi), empty hi = open), or rayleigh:ALPHA,BETA
    /// (ζ = α/2ω + βω/2). Rigid-body modes get 0.
    #[arg(long, value_name = "SPEC")]
    damping: Option<String>,
    /// Scene gravity: acceleration ax,ay,az in the basic frame (e.g. 0,0,-9.81): load GRAVITY =
    /// M·g, stored as a modal load.
    #[arg(long, value_name = "AX,AY,AZ", allow_hyphen_values = true)]
    gravity: Option<String>,
    /// A scene load (repeatable): NAME:NODE:FX,FY,FZ[,MX,MY,MZ] (a node id), NAME:SET:P (uniform
    /// pressure on the free faces within node set SET, positive into the body) or NAME of a
    /// deck's load set (LOAD_10). The deck's selected loads (LOAD = n) are always included.
    #[arg(long = "load", value_name = "SPEC", allow_hyphen_values = true)]
    loads: Vec<String>,
    /// Add residual vectors (static responses) to the basis: loads (each scene load), interface
    /// (unit loads at the interface dofs) or both; inertia-relief balanced for a free body.
    #[arg(long, value_name = "KIND", num_args = 0..=1, default_missing_value = "loads")]
    residual_vectors: Option<String>,
    /// Prove each eigenproblem's modes complete: Sylvester's inertia count of K − σM just above
    /// the highest mode returned must equal the modes returned, else the build fails (one
    /// extra LDLᵀ factorization per eigenproblem; the report states the proven band).
    #[arg(long)]
    verify_band: bool,
    /// Solver engine for the Craig–Bampton interior: native (ours) or slepc (PETSc/SLEPc with
    /// MUMPS under MPI: needs mpirun and slepc4py, e.g. Debian's openmpi-bin and
    /// python3-slepc4py-real). The reduction, invariants and file stay ours.
    #[arg(long, default_value = "native", value_name = "native|slepc")]
    engine: String,
    /// MPI ranks for --engine slepc (mpirun -np N).
    #[arg(long, default_value_t = 2, value_name = "N")]
    mpi: usize,
    /// Arithmetic of the Craig–Bampton interior's factorization: auto (f64, unless the f64
    /// factor would exceed --max-memory/MemAvailable and an f32 one fits), f64, or mixed (an
    /// f32 factor, half the memory, with solves refined to f64 accuracy and a leaner Krylov
    /// basis: slower, see docs/benchmarks.md and docs/memory.md; f64 again where K_ii is too
    /// ill-conditioned for it).
    #[arg(long, default_value = "auto", value_name = "auto|f64|mixed")]
    precision: String,
    /// Keep the fewest modes whose estimated frequency-response error at the scene's loads and
    /// interfaces over [0, fmax] stays below EPS (relative to the static response):
    /// participation:EPS, e.g. participation:0.01. The candidates are the modes --fmax/--modes
    /// computes; what was dropped and the estimate are in the build report.
    #[arg(long, value_name = "participation:EPS")]
    select: Option<String>,
    /// No stress or strain shapes (the default; for scripts that want to say so).
    #[arg(long, conflicts_with = "stress_modes")]
    no_stress: bool,
    /// Title stored in the header (default: the model file name).
    #[arg(long)]
    title: Option<String>,
    /// Record the creation time in the header (makes the output non-reproducible).
    #[arg(long)]
    timestamp: bool,
    /// No progress on stderr.
    #[arg(long, short)]
    quiet: bool,
    /// Print the build report as JSON on stdout.
    #[arg(long)]
    json: bool,
    /// Also write the constrained K and M the reduction starts from (Matrix Market K.mtx,
    /// M.mtx, lumped or consistent as built) and their dof table dofs.txt into DIR.
    #[arg(long, value_name = "DIR")]
    write_matrices: Option<PathBuf>,
}

#[derive(clap::Args)]
struct CheckArgs {
    /// The .flexbody file.
    file: PathBuf,
    /// The FE model the file was built from. The model is rebuilt with the options recorded in
    /// the file's recipe (interfaces, spiders, format, material, beam mass); options given here
    /// override them. A model file changed since the build fails the check.
    #[arg(long)]
    model: Option<PathBuf>,
    #[command(flatten)]
    model_args: ModelArgs,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

fn inspect(file: &PathBuf, json: bool) -> anyhow::Result<()> {
    use anyhow::Context;
    let bytes = std::fs::read(file).with_context(|| format!("cannot read {}", file.display()))?;
    let limits = flexbody_reader::ReadLimits::default();
    let (body, manifest) = flexbody_reader::from_bytes_with_manifest(&bytes, &limits)
        .with_context(|| format!("{} is not a valid flexbody file", file.display()))?;
    let summary = flexbody::inspect::summarize(&body, &manifest);
    if json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        print!("{}", flexbody::inspect::render_text(&summary));
    }
    Ok(())
}

fn import_format(name: &Option<String>) -> anyhow::Result<Option<flexbody::import::Format>> {
    name.as_deref()
        .map(|n| {
            flexbody::import::Format::from_name(n)
                .ok_or_else(|| anyhow::anyhow!("--format {n}: expected inp, bdf or msh"))
        })
        .transpose()
}

/// clap arguments → the library's build spec (the one conversion point).
fn build_spec(a: &BuildArgs) -> anyhow::Result<flexbody::build::BuildSpec> {
    use flexbody::options::*;
    Ok(flexbody::build::BuildSpec {
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
            "slepc" => Some(flexbody::solve::slepc::SlepcEngine {
                ranks: a.mpi.max(1),
            }),
            other => anyhow::bail!("--engine {other}: expected native or slepc"),
        },
        precision: a
            .precision
            .parse()
            .map_err(|e: String| anyhow::anyhow!("--precision {e}"))?,
        beam_mass: parse_beam_mass(&a.beam_mass)?,
        scene: flexbody::scene::SceneSpec {
            gravity: a.gravity.clone(),
            loads: a.loads.clone(),
            residual_vectors: a
                .residual_vectors
                .as_deref()
                .map(flexbody::scene::parse_residual_vectors)
                .transpose()?,
            select: a
                .select
                .as_deref()
                .map(flexbody::scene::parse_select)
                .transpose()?,
        },
    })
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

fn build(a: &BuildArgs) -> anyhow::Result<()> {
    use anyhow::Context;
    let spec = build_spec(a)?;
    if let Some(d) = &a.damping {
        flexbody::damping::parse_damping(d)?; // refuse a bad value before the build
    }
    if let Some(limit) = &a.max_memory {
        // Read by the solve layer right before each factorization; set before any thread starts.
        std::env::set_var(flexbody::solve::cholesky::MEMORY_ENV, limit);
    }
    // Refuse an unusable -o (a folder, a missing folder, no permission) before the build.
    flexbody::write::check_output_path(&a.output)?;
    let mut progress = StageProgress::new(a.quiet || a.json);
    let mut run = || -> anyhow::Result<flexbody::build::BuildOutput> {
        let out = flexbody::build::build(&spec, &mut |stage| progress.stage(stage))
            .with_context(|| format!("cannot build {}", a.model.display()))?;
        let mut out = out;
        if let Some(d) = &a.damping {
            flexbody::damping::apply(&mut out.body, d)?;
        }
        progress.stage("write");
        flexbody::write::write_reduced_body(&a.output, &out.body, &Default::default())?;
        if let Some(dir) = &a.write_matrices {
            flexbody::pipeline::matrices::export_mtx(&spec, dir)?;
        }
        Ok(out)
    };
    let result = run();
    progress.finish();
    let out = result?;
    let r = &out.report;
    if a.json {
        let summary = serde_json::json!({
            "output": a.output.display().to_string(),
            "dofs": r.dofs.0,
            "independent_dofs": r.dofs.1,
            "modes": out.body.mode_count(),
            "frequency_hz": out.body.modes.frequency_hz,
            "stages_s": r.stages.iter().map(|(k, v)| (k.clone(), *v)).collect::<std::collections::BTreeMap<_, _>>(),
            "interfaces": r.interfaces.iter().map(|i| serde_json::json!({
                "entry": i.entry,
                "nodes": i.nodes.len(),
                "spider_centre": i.spider.as_ref().map(|s| s.centre),
                "spider_centre_node": i.spider.as_ref().map(|s| s.centre_node_id),
                "offset_from_node_average": i.spider.as_ref().map(|s| s.offset_from_node_average),
            })).collect::<Vec<_>>(),
            "orthonormality": r.diagnostics.orthonormality,
            "removed_dependent": r.diagnostics.removed.len(),
            "warnings": r.warnings,
            "notes": r.diagnostics.notes,
            "deck": r.notes,
            "constraints": r.constraints,
            // VmHWM of this process: the whole build, file writing included
            "peak_memory_mb": flexbody::solve::memory::peak_resident_bytes()
                .map(|b| b as f64 / 1048576.0),
        });
        println!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    if !a.quiet {
        for w in &r.warnings {
            eprintln!("flexbody: warning: {w}");
        }
        for n in r.notes.iter().chain(&r.diagnostics.notes) {
            eprintln!("flexbody: note: {n}");
        }
        for c in &r.constraints {
            eprintln!("flexbody: constraint: {c}");
        }
        for i in &r.interfaces {
            if let Some(s) = &i.spider {
                eprintln!(
                    "flexbody: interface {}: {} nodes → centre node {} at ({:.6e}, {:.6e}, {:.6e}) by {:?} ({:.3e} from the node average)",
                    i.entry, s.set_nodes, s.centre_node_id, s.centre[0], s.centre[1], s.centre[2], s.method, s.offset_from_node_average
                );
            }
        }
        eprintln!(
            "flexbody: {} dofs ({} independent); total {:.2} s",
            r.dofs.0,
            r.dofs.1,
            r.stages.iter().map(|(_, t)| t).sum::<f64>()
        );
        let f = &out.body.modes.frequency_hz;
        eprintln!(
            "flexbody: wrote {} — {} modes ({} rigid), {} nodes; first flexible modes: {}",
            a.output.display(),
            f.len(),
            out.body.method.counts.rigid,
            out.body.node_count(),
            f.iter()
                .zip(&out.body.modes.labels)
                .filter(|(_, l)| **l != flexbody_reader::ModeLabel::Rigid)
                .take(6)
                .map(|(f, _)| format!("{f:.2} Hz"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(())
}

/// Stage progress on stderr: on a terminal a spinner shows the running stage and its elapsed
/// time; every finished stage leaves one line with its duration (also when stderr is a log).
struct StageProgress {
    quiet: bool,
    bar: Option<indicatif::ProgressBar>,
    current: Option<(String, std::time::Instant)>,
}

impl StageProgress {
    fn new(quiet: bool) -> StageProgress {
        let bar = (!quiet).then(|| {
            let bar = indicatif::ProgressBar::new_spinner();
            if let Ok(style) =
                indicatif::ProgressStyle::with_template("flexbody: {spinner} {msg:<14} {elapsed}")
            {
                bar.set_style(style);
            }
            bar.enable_steady_tick(std::time::Duration::from_millis(120));
            bar
        });
        StageProgress {
            quiet,
            bar,
            current: None,
        }
    }

    fn stage(&mut self, name: &str) {
        self.end_current();
        self.current = Some((name.to_string(), std::time::Instant::now()));
        if let Some(bar) = &self.bar {
            bar.set_message(name.to_string());
        }
    }

    fn end_current(&mut self) {
        let Some((name, t)) = self.current.take() else {
            return;
        };
        if self.quiet {
            return;
        }
        let line = format!("flexbody: {name:<14} {:8.2} s", t.elapsed().as_secs_f64());
        match &self.bar {
            Some(bar) if !bar.is_hidden() => bar.println(line),
            _ => eprintln!("{line}"),
        }
    }

    fn finish(&mut self) {
        self.end_current();
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

fn check(a: &CheckArgs) -> anyhow::Result<bool> {
    use anyhow::Context;
    let body = flexbody_reader::read(&a.file)
        .with_context(|| format!("{} is not a valid flexbody file", a.file.display()))?;
    let model = match &a.model {
        None => None,
        Some(path) => Some(flexbody::recipe::model_input(
            body.recipe.as_ref(),
            path.clone(),
            flexbody::recipe::ModelOverrides {
                format: import_format(&a.model_args.format)?,
                material: a
                    .model_args
                    .material
                    .as_deref()
                    .map(flexbody::options::parse_material)
                    .transpose()?,
                interface: a.model_args.interface.clone(),
                spider: a
                    .model_args
                    .spider
                    .as_deref()
                    .map(flexbody::options::parse_spider)
                    .transpose()?,
                thickness: a.model_args.thickness,
                subcase: a.model_args.subcase,
            },
        )?),
    };
    let report = flexbody::check::check(&body, model.as_ref())?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        for i in &report.items {
            println!(
                "{} {:<52} {:>12.3e} (limit {:.1e})  {}",
                if i.pass { "ok  " } else { "FAIL" },
                i.name,
                i.value,
                i.limit,
                i.detail
            );
        }
        for s in &report.skipped {
            println!("skip {s}");
        }
        let failed = report.items.iter().filter(|i| !i.pass).count();
        println!(
            "{} checks, {} failed: {}",
            report.items.len(),
            failed,
            if failed == 0 { "PASS" } else { "FAIL" }
        );
    }
    Ok(report.passed())
}

/// `--model` options given explicitly; each overrides the file's recipe.
fn model_overrides(a: &ModelArgs) -> anyhow::Result<flexbody::recipe::ModelOverrides> {
    Ok(flexbody::recipe::ModelOverrides {
        format: import_format(&a.format)?,
        material: a
            .material
            .as_deref()
            .map(flexbody::options::parse_material)
            .transpose()?,
        interface: a.interface.clone(),
        spider: a
            .spider
            .as_deref()
            .map(flexbody::options::parse_spider)
            .transpose()?,
        thickness: a.thickness,
        subcase: a.subcase,
    })
}

/// What `flexbody export` was given besides the file and the target.
struct ExportArgs<'a> {
    output: &'a std::path::Path,
    model: Option<&'a PathBuf>,
    model_args: &'a ModelArgs,
    mass: Option<&'a str>,
}

fn export(file: &PathBuf, to: &str, a: ExportArgs) -> anyhow::Result<()> {
    use anyhow::Context;
    let output = a.output;
    let target = flexbody::export::Target::from_name(to)
        .ok_or_else(|| anyhow::anyhow!("--to {to}: expected exudyn, mbdyn, sid or mtx"))?;
    let body = flexbody_reader::read(file)
        .with_context(|| format!("{} is not a valid flexbody file", file.display()))?;
    if target == flexbody::export::Target::Mtx {
        let model = a.model.ok_or_else(|| {
            anyhow::anyhow!(
                "--to mtx writes the FE model's K and M, which the file does not hold: give the \
                 model it was built from with --model MODEL (its recipe says how it was built)"
            )
        })?;
        let mass = a.mass.map(flexbody::options::parse_mass).transpose()?;
        let written = flexbody::pipeline::matrices::export_body_matrices(
            &body,
            model,
            model_overrides(a.model_args)?,
            mass,
            output,
        )
        .with_context(|| format!("cannot export the matrices of {}", model.display()))?;
        eprintln!(
            "flexbody: wrote {}",
            written
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
        return Ok(());
    }
    if let Some(model) = a.model {
        anyhow::bail!(
            "--model {}: only --to mtx reads the model; {to} is exported from the file alone",
            model.display()
        );
    }
    if let Some(mass) = a.mass {
        anyhow::bail!("--mass {mass}: only --to mtx writes a mass matrix");
    }
    let summary = flexbody::export::export(&body, target, output)?;
    for n in &summary.notes {
        eprintln!("flexbody: note: {n}");
    }
    eprintln!(
        "flexbody: wrote {} — {} flexible modes, {} nodes",
        output.display(),
        summary.modes,
        summary.nodes
    );
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Build(args) => build(args).map(|()| true),
        Command::Inspect { file, json } => inspect(file, *json).map(|()| true),
        Command::Check(args) => check(args),
        Command::Export {
            file,
            to,
            output,
            model,
            model_args,
            mass,
        } => export(
            file,
            to,
            ExportArgs {
                output,
                model: model.as_ref(),
                model_args,
                mass: mass.as_deref(),
            },
        )
        .map(|()| true),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            // The chain, each cause once: errors whose text already holds their cause (most
            // `thiserror` types) would otherwise print it twice ("X: X").
            let mut msg = String::new();
            for cause in e.chain() {
                let text = cause.to_string();
                if msg.contains(&text) {
                    continue;
                }
                // A cause that begins by repeating the end of the message (the file it names,
                // "cannot build P" then "P: …") continues it.
                let mut rest = text.as_str();
                while let Some((head, tail)) = rest.split_once(": ") {
                    if msg.ends_with(head) {
                        rest = tail;
                    } else {
                        break;
                    }
                }
                if !msg.is_empty() {
                    msg.push_str(": ");
                }
                msg.push_str(rest);
            }
            eprintln!("flexbody: {msg}");
            ExitCode::from(2)
        }
    }
}
