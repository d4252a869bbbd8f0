//! The build's recipe (entry `recipe.json`, SPEC.md §5.11): what `build` read and was asked,
//! so that `check` and later tools need nothing repeated.
//!
//! * [`recipe`] records the tool, every model file read with its SHA-256 and size, the
//!   effective options in the form `flexbody build` accepts (interface entries verbatim), the
//!   interfaces and spiders as resolved, and the [`accuracy_band`].
//! * [`changed_model_files`] compares the recorded files with the ones on disk now.
//! * [`model_input`] turns the recipe (plus explicit overrides) back into the model `check`
//!   rebuilds ([`ModelInput`]).

use std::path::{Path, PathBuf};

use flexbody_reader as file;

use crate::fe::{self, BeamLumping};
use crate::import::Format;
use crate::model::{DofMask, Material, Model, RigidElement};
use crate::pipeline::interface::{InterfaceReport, SpiderKind};
use crate::pipeline::plan::ModeRequest;
use crate::pipeline::scene::SceneSpec;
use crate::pipeline::stages::PreloadSummary;
use crate::pipeline::{BuildMethod, BuildSpec, KeepNodes};
use crate::reduce::select::FMAX_FACTOR;
use crate::reduce::ModeSet;

/// `fixed-interface`: a `--modes N` Craig–Bampton build is accurate below its highest retained
/// fixed-interface frequency divided by [`FMAX_FACTOR`].
pub const BAND_FIXED_INTERFACE: &str = "fixed-interface";
/// `free-free`: a `--modes N` Craig–Chang or Dietz build holds its free-free modes exactly, so
/// it is accurate up to its highest retained free-free frequency.
pub const BAND_FREE_FREE: &str = "free-free";
/// `normal-modes`: normal modes are exact eigenpairs through the highest one kept.
pub const BAND_NORMAL_MODES: &str = "normal-modes";
/// `fmax`: the user's `--fmax` (the scene's highest frequency; modes are kept to 3× it).
pub const BAND_FMAX: &str = "fmax";

/// The band in which the body is meant to be accurate, by one rule per build (SPEC.md §5.11):
/// the user's `--fmax` when given (the basis then reaches [`FMAX_FACTOR`]× it); otherwise, for
/// Craig–Bampton, the same factor read backwards (the highest retained fixed-interface frequency
/// divided by [`FMAX_FACTOR`]); for Craig–Chang and Dietz, whose basis holds the free-free modes
/// exactly, the highest retained free-free frequency; for normal modes, which are exact
/// eigenpairs, the highest mode kept that is not a residual-vector mode.
pub fn accuracy_band(spec: &BuildSpec, modes: &ModeRequest, set: &ModeSet) -> file::AccuracyBand {
    use crate::solve::hz;
    if let Some(f) = modes.fmax_hz {
        return file::AccuracyBand {
            fmax_hz: f,
            rule: BAND_FMAX.into(),
            basis_cutoff_hz: Some(FMAX_FACTOR * f),
        };
    }
    // the highest eigenmode kept: a residual-vector mode is a static correction whose
    // pseudo-frequency lies far beyond the band (SPEC §5.11)
    let top_kept = (set.omega2.iter().zip(&set.labels))
        .filter(|(_, l)| !matches!(l, crate::reduce::ModeLabel::Residual { .. }))
        .map(|(&w2, _)| w2)
        .fold(0.0f64, f64::max);
    let (w2, rule) = match (spec.method, set.diagnostics.basis_top_omega2) {
        (BuildMethod::Normal, _) | (_, None) => (top_kept, BAND_NORMAL_MODES),
        (BuildMethod::CraigBampton, Some(w2)) => (w2, BAND_FIXED_INTERFACE),
        (_, Some(w2)) => (w2, BAND_FREE_FREE),
    };
    let divisor = if rule == BAND_FIXED_INTERFACE {
        FMAX_FACTOR
    } else {
        1.0
    };
    file::AccuracyBand {
        fmax_hz: hz(w2) / divisor,
        rule: rule.into(),
        basis_cutoff_hz: None,
    }
}

/// Whether the build reads an Abaqus/CalculiX deck (its shells follow `--inp-shells`).
fn is_abaqus(spec: &BuildSpec) -> bool {
    spec.format.or_else(|| Format::from_extension(&spec.model)) == Some(Format::Abaqus)
}

/// Name of a format as `--format` takes it.
fn format_name(f: Format) -> &'static str {
    match f {
        Format::Abaqus => "inp",
        Format::Nastran => "bdf",
        Format::Gmsh => "msh",
        Format::Ansys => "cdb",
        Format::AnsysFull => "full",
    }
}

/// `--beam-mass` value of a resolved lumping.
pub fn beam_mass_name(b: BeamLumping) -> &'static str {
    match b {
        BeamLumping::SectionRotary => "section",
        BeamLumping::TorsionOnly => "torsion",
        BeamLumping::TranslationsOnly => "none",
        BeamLumping::Nastran => "nastran",
    }
}

fn spider_name(s: SpiderKind) -> &'static str {
    match s {
        SpiderKind::Rbe2 => "rbe2",
        SpiderKind::Rbe3 => "rbe3",
        SpiderKind::None => "none",
    }
}

fn digits(m: DofMask) -> String {
    (0..6)
        .filter(|&k| m.contains(k))
        .map(|k| char::from(b'1' + k as u8))
        .collect()
}

/// A path as recorded: relative to `dir` when inside it, `/`-separated.
fn relative(path: &Path, dir: &Path) -> String {
    let rel = path.strip_prefix(dir).unwrap_or(path);
    rel.components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join("/")
}

/// SHA-256 and size of every file in `files` (the main file first); paths recorded relative to
/// the main file's folder.
pub fn model_files(files: &[String]) -> Result<Vec<file::ModelFile>, String> {
    let Some(main) = files.first().map(Path::new) else {
        return Ok(Vec::new());
    };
    let dir = main.parent().unwrap_or(Path::new(""));
    files
        .iter()
        .enumerate()
        .map(|(q, f)| {
            let bytes =
                std::fs::read(f).map_err(|e| format!("{f}: cannot read for the recipe: {e}"))?;
            Ok(file::ModelFile {
                path: if q == 0 {
                    main.file_name()
                        .map(|s| s.to_string_lossy().into_owned())
                        .unwrap_or_else(|| f.clone())
                } else {
                    relative(Path::new(f), dir)
                },
                role: if q == 0 { "main" } else { "include" }.into(),
                size: bytes.len() as u64,
                sha256: file::codec::sha256_hex(&bytes),
            })
        })
        .collect()
}

/// The recipe of a build: `spec` as the options, `model` after interface resolution (its files,
/// node ids and spiders), the interfaces as resolved, the accuracy band and the preload.
pub fn recipe(
    spec: &BuildSpec,
    modes: &ModeRequest,
    model: &Model,
    interfaces: &[InterfaceReport],
    band: file::AccuracyBand,
    preload: Option<&PreloadSummary>,
) -> Result<file::Recipe, String> {
    let ids = |nodes: &[usize]| nodes.iter().map(|&n| model.nodes[n].id).collect::<Vec<_>>();
    let options = file::RecipeOptions {
        format: spec.format.map(|f| format_name(f).to_string()),
        material: spec
            .material
            .as_ref()
            .map(|m: &Material| format!("E={},nu={},rho={}", m.e, m.nu, m.rho)),
        method: match spec.method {
            BuildMethod::Normal => "normal",
            BuildMethod::CraigBampton => "cb",
            BuildMethod::CraigChang => "craig-chang",
            BuildMethod::Dietz => "dietz",
        }
        .into(),
        modes: modes.count.map(|n| n as u64),
        fmax_hz: modes.fmax_hz,
        mass: match spec.mass {
            fe::MassKind::Lumped => "lumped",
            fe::MassKind::Consistent => "consistent",
        }
        .into(),
        beam_mass: beam_mass_name(spec.beam_lumping()).into(),
        units: spec.units.clone(),
        interface: spec.interface.clone(),
        spider: spider_name(spec.spider).into(),
        // NODE:DOFS pairs, then the entries given by name (interfaces, sets) as given.
        reference_conditions: spec
            .reference_conditions
            .iter()
            .map(|(id, m)| format!("{id}:{}", digits(*m)))
            .chain(spec.reference_sets.iter().cloned())
            .collect(),
        reference_method: spec.reference_method,
        keep_nodes: match &spec.keep_nodes {
            KeepNodes::All => "all".into(),
            KeepNodes::Interface => "interface".into(),
            KeepNodes::Surface => "surface".into(),
            KeepNodes::Set(s) => s.clone(),
        },
        invariants: match spec.invariants {
            file::InvariantSet::Full => "full",
            file::InvariantSet::Partial => "partial",
            file::InvariantSet::Constant => "constant",
            file::InvariantSet::Rigid => "rigid",
        }
        .into(),
        stress_fields: match (spec.fields.stress, spec.fields.strain) {
            (false, false) => "none",
            (true, false) => "stress",
            (false, true) => "strain",
            (true, true) => "both",
        }
        .into(),
        damping: None,
        thickness: spec.thickness,
        subcase: spec.subcase,
        ignore: spec.ignore.clone(),
        inp_shells: is_abaqus(spec).then(|| spec.inp_shells.name().to_owned()),
        gravity: spec.scene.gravity.clone(),
        loads: spec.scene.loads.clone(),
        residual_vectors: spec.scene.residual_vectors.map(|k| {
            match k {
                crate::reduce::residual::ResidualKind::Loads => "loads",
                crate::reduce::residual::ResidualKind::Interface => "interface",
                crate::reduce::residual::ResidualKind::Both => "both",
            }
            .into()
        }),
        select: spec.scene.select.map(crate::pipeline::scene::select_text),
        preload: spec.scene.preload.clone(),
        geometric_stiffness: (spec.geometric_stiffness)
            .map(|g| crate::pipeline::options::geometric_stiffness_name(g).into()),
        eigensolver: (spec.eigensolver != crate::solve::EigenMethod::Auto)
            .then(|| spec.eigensolver.name()),
    };
    let interfaces = interfaces
        .iter()
        .map(|r| file::RecipeInterface {
            entry: r.entry.clone(),
            nodes: ids(&r.nodes),
            spider: r.spider.as_ref().map(|s| {
                let legs: Vec<usize> = model
                    .rigid_elements
                    .iter()
                    .find_map(|e| match e {
                        RigidElement::Rbe2 {
                            independent,
                            dependent,
                            ..
                        } if model.nodes[*independent].id == s.centre_node_id => {
                            Some(dependent.clone())
                        }
                        RigidElement::Rbe3 {
                            reference,
                            independent,
                            ..
                        } if model.nodes[*reference].id == s.centre_node_id => {
                            Some(independent.iter().map(|x| x.0).collect())
                        }
                        _ => None,
                    })
                    .unwrap_or_default();
                file::RecipeSpider {
                    kind: spider_name(spec.spider).into(),
                    centre_node: s.centre_node_id,
                    centre: s.centre,
                    fit: format!("{:?}", s.method),
                    offset_from_node_average: s.offset_from_node_average,
                    set_nodes: ids(&legs),
                }
            }),
        })
        .collect();
    Ok(file::Recipe {
        tool: file::Generator {
            name: "flexbody".into(),
            version: env!("CARGO_PKG_VERSION").into(),
        },
        model_files: model_files(&model.files)?,
        options,
        interfaces,
        accuracy_band: band,
        preload: preload.map(|p| file::RecipePreload {
            // the deck's step named by the file name, as `model_files` does
            source: match Path::new(&model.source).parent() {
                Some(dir) if !dir.as_os_str().is_empty() => {
                    p.source.replace(&format!("{}/", dir.display()), "")
                }
                _ => p.source.clone(),
            },
            loads: p.loads.clone(),
            max_displacement: p.max_displacement,
            max_displacement_node: p.max_displacement_node,
            buckling_factor: p.buckling_factor,
        }),
    })
}

/// The recorded model files that differ from the files beside `main` now (the main file is
/// `main` itself, includes are found relative to its folder): one message per file naming it
/// and what differs. Empty when everything is as built.
pub fn changed_model_files(recipe: &file::Recipe, main: &Path) -> Vec<String> {
    let dir = main.parent().unwrap_or(Path::new(""));
    recipe
        .model_files
        .iter()
        .enumerate()
        .filter_map(|(q, f)| {
            let path: PathBuf = if q == 0 {
                main.to_path_buf()
            } else {
                dir.join(&f.path)
            };
            match std::fs::read(&path) {
                Err(e) => Some(format!("{}: cannot read ({e})", path.display())),
                Ok(bytes) => {
                    let sha = file::codec::sha256_hex(&bytes);
                    (sha != f.sha256).then(|| {
                        format!(
                            "{}: changed since the build (SHA-256 {}…, size {} bytes; built from {}…, {} bytes)",
                            path.display(),
                            &sha[..12],
                            bytes.len(),
                            &f.sha256[..f.sha256.len().min(12)],
                            f.size
                        )
                    })
                }
            }
        })
        .collect()
}

/// The FE model to check against, rebuilt as `build` did.
#[derive(Debug, Clone)]
pub struct ModelInput {
    /// Model file.
    pub path: PathBuf,
    /// Format override.
    pub format: Option<Format>,
    /// Material for elements without a section.
    pub material: Option<Material>,
    /// Shell thickness for 2D elements without a section.
    pub thickness: Option<f64>,
    /// Nastran subcase whose SPC and METHOD selections apply.
    pub subcase: Option<u64>,
    /// Cards or keywords the build dropped on purpose (`--ignore`).
    pub ignore: Vec<String>,
    /// How an Abaqus/CalculiX deck's shells were formed (`--inp-shells`).
    pub inp_shells: crate::import::InpShells,
    /// The interface entries given to `build`.
    pub interface: Vec<String>,
    /// The spider kind given to `build`.
    pub spider: SpiderKind,
    /// Rotational inertia of lumped beam masses (`None`: as `build` resolves it by default).
    pub beam_mass: Option<crate::fe::BeamLumping>,
    /// The scene's loads as far as the preload needs them: `--gravity`, `--load`, `--preload`.
    pub scene: SceneSpec,
}

/// Model options given explicitly to `check`; each overrides the recipe's.
#[derive(Debug, Clone, Default)]
pub struct ModelOverrides {
    /// `--format`.
    pub format: Option<Format>,
    /// `--material`.
    pub material: Option<Material>,
    /// `--interface` (empty: not given).
    pub interface: Vec<String>,
    /// `--spider`.
    pub spider: Option<SpiderKind>,
    /// `--thickness`.
    pub thickness: Option<f64>,
    /// `--subcase`.
    pub subcase: Option<u64>,
    /// `--ignore` (empty: not given).
    pub ignore: Vec<String>,
    /// `--inp-shells`.
    pub inp_shells: Option<crate::import::InpShells>,
}

/// The model `check` rebuilds: the recipe's options where the file has one, explicit overrides
/// on top, the CLI defaults otherwise.
pub fn model_input(
    recipe: Option<&file::Recipe>,
    path: PathBuf,
    o: ModelOverrides,
) -> Result<ModelInput, crate::pipeline::options::OptionError> {
    use crate::pipeline::options::{parse_material, parse_spider};
    let opts = recipe.map(|r| &r.options);
    let format = match o.format {
        Some(f) => Some(f),
        None => opts
            .and_then(|r| r.format.as_deref())
            .and_then(Format::from_name),
    };
    let material = match o.material {
        Some(m) => Some(m),
        None => opts
            .and_then(|r| r.material.as_deref())
            .map(parse_material)
            .transpose()?,
    };
    let interface = if o.interface.is_empty() {
        opts.map(|r| r.interface.clone()).unwrap_or_default()
    } else {
        o.interface
    };
    let spider = match o.spider {
        Some(s) => s,
        None => opts
            .map(|r| parse_spider(&r.spider))
            .transpose()?
            .unwrap_or_default(),
    };
    let beam_mass = opts
        .map(|r| crate::pipeline::options::parse_beam_mass(&r.beam_mass))
        .transpose()?
        .flatten();
    Ok(ModelInput {
        path,
        format,
        material,
        interface,
        spider,
        beam_mass,
        thickness: o.thickness.or_else(|| opts.and_then(|r| r.thickness)),
        subcase: o.subcase.or_else(|| opts.and_then(|r| r.subcase)),
        ignore: if o.ignore.is_empty() {
            opts.map(|r| r.ignore.clone()).unwrap_or_default()
        } else {
            o.ignore
        },
        // a recipe without the member is from a build that formed flexbody's shells
        inp_shells: match o.inp_shells {
            Some(s) => s,
            None => match opts {
                Some(r) => match r.inp_shells.as_deref() {
                    Some(s) => crate::pipeline::options::parse_inp_shells(s)?,
                    None => crate::import::InpShells::Native,
                },
                None => crate::import::InpShells::default(),
            },
        },
        scene: SceneSpec {
            gravity: opts.and_then(|r| r.gravity.clone()),
            loads: opts.map(|r| r.loads.clone()).unwrap_or_default(),
            preload: opts.map(|r| r.preload.clone()).unwrap_or_default(),
            ..Default::default()
        },
    })
}
