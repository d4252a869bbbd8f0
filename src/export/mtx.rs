//! K and M of the constrained model in Matrix Market, with a dof table — for Chrono's modal
//! reduction, pyyeti, SciPy and one's own checks (`flexbody build --write-matrices DIR`, or the
//! `mtx` export target with the model).
//!
//! What is written is the system the reduction starts from: the model as `build` assembles it
//! (the same import, deck defaults, interface spiders, lumped or consistent mass) after the
//! elimination u = T u_r of rigid elements, SPCs and held components — K_r = Tᵀ K T and
//! M_r = Tᵀ M T over the independent dofs.
//!
//! Files in DIR:
//! * `K.mtx`, `M.mtx`: `%%MatrixMarket matrix coordinate real symmetric`, the lower triangle
//!   (row ≥ column, 1-based), column by column, rows ascending; values as the shortest decimal
//!   that reads back to the same binary64 (so a reader gets the matrices bit for bit). Explicit
//!   zeros are not written. Units: the model's.
//! * `dofs.txt`: equation k (1-based, line k after the `#` comments) = `k node component`, with
//!   the node's external id and the component 1…6 = ux uy uz rx ry rz in the node's
//!   displacement frame (Nastran's CD; the basic frame for Abaqus/Gmsh models).
//!
//! **Dof order**: the independent dofs node by node in the model's node order (the order the
//! deck defines its nodes; spider centre nodes `build` adds come last), and within a node by
//! component. A dof is absent when an SPC or a held component fixes it or when it is dependent
//! (an RBE2 leg, an RBE3 reference not at an interface). For a deck whose nodes are numbered in
//! ascending order this is CalculiX's equation order (`*FREQUENCY, SOLVER=MATRIXSTORAGE`): its
//! `.dof` table equals `dofs.txt` line for line (`tests/export_mtx.rs`).
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::build::{BuildError, BuildSpec};
use crate::fe::{self, assemble, eliminate, AssemblySpec, ConstraintSpec};
use crate::import::{self, ImportOptions};
use crate::interface::resolve_interfaces;
use crate::model::Model;
use crate::solve::SparseColMat;

/// The constrained system: K_r, M_r and the dof each equation is.
#[derive(Debug, Clone)]
pub struct ConstrainedSystem {
    /// K_r = Tᵀ K T, full symmetric.
    pub k: SparseColMat<usize, f64>,
    /// M_r = Tᵀ M T, full symmetric.
    pub m: SparseColMat<usize, f64>,
    /// Equation k ↔ (external node id, component 0…5).
    pub dofs: Vec<(u64, u8)>,
    /// Lumped or consistent.
    pub mass: fe::MassKind,
    /// Number of physical dofs before the elimination.
    pub physical_dofs: usize,
}

/// Errors of the export.
#[derive(Debug, thiserror::Error)]
pub enum MtxError {
    /// Building the constrained model failed.
    #[error(transparent)]
    Build(#[from] BuildError),
    /// The model files differ from the ones the body was built from (the recipe's SHA-256);
    /// the same messages as `check`'s "model files as built" line.
    #[error("the model is not the one the file was built from (recipe SHA-256): {}", .0.join("; "))]
    ModelChanged(Vec<String>),
    /// An option recorded in the recipe or given explicitly is not valid.
    #[error(transparent)]
    Options(#[from] crate::options::OptionError),
    /// A file could not be written.
    #[error("{path}: cannot write ({source})")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// The constrained system `build` would reduce for `spec` (reads the model).
pub fn constrained_system(spec: &BuildSpec) -> Result<ConstrainedSystem, BuildError> {
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
    let resolved = BuildSpec {
        beam_mass: Some(spec.beam_lumping()),
        ..spec.clone()
    };
    constrained_system_of_model(&resolved, model)
}

/// [`constrained_system`] for a model in memory: the deck's defaults, the interface spiders,
/// assembly and elimination exactly as `build` does them.
pub fn constrained_system_of_model(
    spec: &BuildSpec,
    mut model: Model,
) -> Result<ConstrainedSystem, BuildError> {
    let defaults = crate::deck::deck_defaults(spec, &model);
    let spec = &defaults.spec;
    let interfaces = resolve_interfaces(&mut model, &spec.interface, spec.spider)?;
    let interface_nodes: Vec<usize> = interfaces
        .iter()
        .flat_map(|r| r.nodes.iter().copied())
        .collect();
    let assembled = assemble(
        &model,
        &AssemblySpec {
            mass: spec.mass,
            beam_lumping: spec.beam_mass.unwrap_or_default(),
            ..Default::default()
        },
    )?;
    let reduced = eliminate(
        &model,
        &assembled.dofs,
        &assembled.k,
        &assembled.m,
        &ConstraintSpec {
            independent_rbe3_reference: interface_nodes,
            ..Default::default()
        },
    )?;
    let d = &assembled.dofs;
    // Physical dof → (node, component): dofs are numbered node-major from `first`.
    let mut owner = vec![(0u64, 0u8); d.n_dofs];
    for (node, (&first, &count)) in d.first.iter().zip(&d.count).enumerate() {
        for c in 0..usize::from(count) {
            owner[first + c] = (model.nodes[node].id, c as u8);
        }
    }
    Ok(ConstrainedSystem {
        dofs: reduced.retained.iter().map(|&p| owner[p]).collect(),
        k: reduced.k,
        m: reduced.m,
        mass: spec.mass,
        physical_dofs: d.n_dofs,
    })
}

/// Writes `K.mtx`, `M.mtx` and `dofs.txt` of `sys` into `dir` (created if missing); each file
/// goes to a temporary name first and is renamed when complete. Returns the paths written.
pub fn write_matrices(
    dir: &Path,
    sys: &ConstrainedSystem,
    source: &str,
) -> Result<Vec<PathBuf>, MtxError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| MtxError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let mass = match sys.mass {
        fe::MassKind::Lumped => "lumped",
        fe::MassKind::Consistent => "consistent",
    };
    let about = format!(
        "% flexbody {}: {source}, constrained ({} of {} dofs independent), {mass} mass; dof table dofs.txt\n",
        env!("CARGO_PKG_VERSION"),
        sys.dofs.len(),
        sys.physical_dofs
    );
    let mut written = Vec::new();
    for (name, a) in [("K.mtx", &sys.k), ("M.mtx", &sys.m)] {
        let path = dir.join(name);
        write_atomically(&path, |w| write_lower(w, a, &about)).map_err(io(&path))?;
        written.push(path);
    }
    let path = dir.join("dofs.txt");
    write_atomically(&path, |w| {
        writeln!(
            w,
            "# flexbody {}: {source}; equation k = line k: k node component (1-6 = ux uy uz rx ry rz, node displacement frame)",
            env!("CARGO_PKG_VERSION")
        )?;
        for (k, (node, c)) in sys.dofs.iter().enumerate() {
            writeln!(w, "{} {node} {}", k + 1, c + 1)?;
        }
        Ok(())
    })
    .map_err(io(&path))?;
    written.push(path);
    Ok(written)
}

/// One symmetric matrix: header, size line, lower triangle column by column.
fn write_lower(
    w: &mut dyn Write,
    a: &SparseColMat<usize, f64>,
    about: &str,
) -> std::io::Result<()> {
    let n = a.ncols();
    let lower = |j: usize| {
        a.row_idx_of_col(j)
            .zip(a.val_of_col(j).iter().copied())
            .filter(move |&(i, v)| i >= j && v != 0.0)
    };
    let nnz: usize = (0..n).map(|j| lower(j).count()).sum();
    writeln!(w, "%%MatrixMarket matrix coordinate real symmetric")?;
    w.write_all(about.as_bytes())?;
    writeln!(w, "{n} {n} {nnz}")?;
    for j in 0..n {
        let mut col: Vec<(usize, f64)> = lower(j).collect();
        col.sort_unstable_by_key(|e| e.0);
        for (i, v) in col {
            writeln!(w, "{} {} {v:e}", i + 1, j + 1)?;
        }
    }
    Ok(())
}

fn write_atomically(
    path: &Path,
    body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    let tmp = PathBuf::from(tmp);
    let result = (|| {
        let mut w = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
        body(&mut w)?;
        w.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        std::fs::remove_file(&tmp).ok();
    }
    result
}

/// The `mtx` export target: the constrained K, M of `spec`'s model written to `dir`.
pub fn export_mtx(spec: &BuildSpec, dir: &Path) -> Result<Vec<PathBuf>, MtxError> {
    let sys = constrained_system(spec)?;
    let source = spec.model.file_name().map_or_else(
        || spec.model.display().to_string(),
        |f| f.to_string_lossy().into_owned(),
    );
    write_matrices(dir, &sys, &source)
}

/// The build options a body was made with, from its recipe (`recipe.json`), for exporting the
/// constrained matrices of that build from `model`: format, material, thickness, subcase,
/// interfaces, spider, beam mass as the recipe records them, the mass kind as `method.bin`
/// does. Without a recipe: the defaults of `build` with the body's mass kind.
pub fn spec_from_body(
    body: &flexbody_reader::ReducedBody,
    model: &Path,
) -> Result<BuildSpec, crate::options::OptionError> {
    spec_from_body_with(body, model, Default::default())
}

/// [`spec_from_body`] with explicit options on top of the recipe's, as `check --model` takes
/// them.
pub fn spec_from_body_with(
    body: &flexbody_reader::ReducedBody,
    model: &Path,
    overrides: crate::recipe::ModelOverrides,
) -> Result<BuildSpec, crate::options::OptionError> {
    let input = crate::recipe::model_input(body.recipe.as_ref(), model.to_path_buf(), overrides)?;
    let mut spec = BuildSpec::new(model.to_path_buf(), body.units.clone(), &[]);
    spec.format = input.format;
    spec.material = input.material;
    spec.thickness = input.thickness;
    spec.subcase = input.subcase;
    spec.interface = input.interface;
    spec.spider = input.spider;
    spec.beam_mass = input.beam_mass;
    spec.mass = match body.method.mass_kind {
        flexbody_reader::MassKind::Lumped => fe::MassKind::Lumped,
        flexbody_reader::MassKind::Consistent => fe::MassKind::Consistent,
    };
    spec.mass_explicit = true;
    Ok(spec)
}

/// `flexbody export FILE --to mtx --model MODEL -o DIR`: the constrained K, M of the build that
/// made `body`, rebuilt from `model` with the file's recipe (format, material, thickness,
/// subcase, interfaces, spiders, beam mass; the mass kind of `method.bin`) as `check --model`
/// rebuilds it; `overrides` and `mass` replace the recorded options. A model whose files differ
/// from the recipe's SHA-256 is refused with `check`'s messages, before anything is written.
pub fn export_body_matrices(
    body: &flexbody_reader::ReducedBody,
    model: &Path,
    overrides: crate::recipe::ModelOverrides,
    mass: Option<fe::MassKind>,
    dir: &Path,
) -> Result<Vec<PathBuf>, MtxError> {
    if let Some(recipe) = &body.recipe {
        let changed = crate::recipe::changed_model_files(recipe, model);
        if !changed.is_empty() {
            return Err(MtxError::ModelChanged(changed));
        }
    }
    let mut spec = spec_from_body_with(body, model, overrides)?;
    if let Some(mass) = mass {
        spec.mass = mass;
    }
    export_mtx(&spec, dir)
}
