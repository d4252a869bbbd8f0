//! The constrained system `build` reduces — K_r = Tᵀ K T and M_r = Tᵀ M T over the independent
//! dofs, after the same import, deck defaults, interface spiders, lumped or consistent mass and
//! elimination u = T u_r of rigid elements, SPCs and held components — for Chrono's modal
//! reduction, pyyeti, SciPy and one's own checks: `flexbody build --write-matrices DIR`, and
//! `flexbody export --to mtx` with the model (the options from the file's recipe,
//! [`export_body_matrices`]). The files are written by [`crate::write::mtx`].
use std::path::{Path, PathBuf};

use crate::fe::{self, assemble};
use crate::model::Model;
use crate::pipeline::plan::Plan;
use crate::pipeline::stages::constraints::eliminate_constraints;
use crate::pipeline::stages::import::import;
use crate::pipeline::stages::interfaces::attach;
use crate::pipeline::stages::{PreloadSummary, WithInterfaces};
use crate::pipeline::{BuildError, BuildSpec};
use crate::write::mtx::{write_matrices, ConstrainedSystem, MatrixWriteError};

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
    Options(#[from] crate::pipeline::options::OptionError),
    /// A file could not be written.
    #[error(transparent)]
    Write(#[from] MatrixWriteError),
}

/// The constrained system `build` would reduce for `spec` (reads the model).
pub fn constrained_system(spec: &BuildSpec) -> Result<ConstrainedSystem, BuildError> {
    let model = import(spec)?;
    constrained_system_of_model(&spec.with_beam_lumping_resolved(), model)
}

/// The stages up to the reduction as `build` runs them, for a model in memory: the plan (deck
/// defaults), the interface spiders, assembly, elimination and the preload (K_T,r in place of
/// K_r). `export --to mtx` and `check --model` rebuild through this.
pub fn constrained_stages(spec: &BuildSpec, model: Model) -> Result<ConstrainedStages, BuildError> {
    let plan = Plan::resolve(spec, &model)?;
    let interfaced = attach(&plan, model)?;
    let assembled = assemble(&interfaced.model, &plan.assembly)?;
    let mut reduced = eliminate_constraints(&interfaced, &assembled)?;
    // a preloaded build reduces K_T,r = K_r + Tᵀ K_G T: that is the K written
    let preload = crate::pipeline::stages::preload::apply(
        &interfaced.model,
        &assembled,
        &mut reduced,
        &plan.assembly,
        &plan.spec.scene,
        plan.spec.par(),
    )?;
    Ok(ConstrainedStages {
        plan,
        interfaced,
        assembled,
        reduced,
        preload,
    })
}

/// What [`constrained_stages`] returns: each stage's result up to the reduction.
pub struct ConstrainedStages {
    /// The options resolved.
    pub plan: Plan,
    /// The model with its interface spiders.
    pub interfaced: WithInterfaces,
    /// The physical K, M and dof map.
    pub assembled: fe::Assembled,
    /// K_r (K_T,r with a preload), M_r and T.
    pub reduced: fe::Reduced,
    /// The preload applied, if any.
    pub preload: Option<PreloadSummary>,
}

/// [`constrained_system`] for a model in memory.
pub fn constrained_system_of_model(
    spec: &BuildSpec,
    model: Model,
) -> Result<ConstrainedSystem, BuildError> {
    let c = constrained_stages(spec, model)?;
    Ok(system_of(
        &c.plan,
        &c.interfaced.model,
        &c.assembled.dofs,
        &c.reduced.retained,
        c.reduced.k,
        c.reduced.m,
    ))
}

/// The constrained system of the build's own stages (`build --write-matrices`): `k`, `m` the
/// K_r, M_r the reduction starts from, with the dof table and the nodes' coordinates.
pub fn system_of(
    plan: &Plan,
    model: &Model,
    d: &fe::DofMap,
    retained: &[usize],
    k: crate::solve::SparseColMat<usize, f64>,
    m: crate::solve::SparseColMat<usize, f64>,
) -> ConstrainedSystem {
    // Physical dof → (node, component): dofs are numbered node-major from `first`.
    let mut owner = vec![(0u64, 0u8); d.n_dofs];
    for (node, (&first, &count)) in d.first.iter().zip(&d.count).enumerate() {
        for c in 0..usize::from(count) {
            owner[first + c] = (model.nodes[node].id, c as u8);
        }
    }
    // an interior dof (ccx's C3D8I mode amplitude): its element's id, components 7… (mtx.rs)
    for b in &d.interior {
        for i in 0..b.count {
            owner[b.first + i] = (model.elements[b.element].id, (6 + i) as u8);
        }
    }
    let dofs: Vec<(u64, u8)> = retained.iter().map(|&p| owner[p]).collect();
    // Each node with a retained dof, once, in the order of its first dof.
    let position: std::collections::HashMap<u64, [f64; 3]> =
        model.nodes.iter().map(|nd| (nd.id, nd.x)).collect();
    let mut seen = std::collections::HashSet::new();
    let nodes = dofs
        .iter()
        .filter(|(_, c)| *c < 6)
        .filter(|(id, _)| seen.insert(*id))
        .filter_map(|(id, _)| position.get(id).map(|&x| (*id, x)))
        .collect();
    ConstrainedSystem {
        dofs,
        nodes,
        k,
        m,
        mass: plan.spec.mass,
        physical_dofs: d.n_dofs,
    }
}

/// The `mtx` export target: the constrained K, M of `spec`'s model written to `dir`.
pub fn export_mtx(spec: &BuildSpec, dir: &Path) -> Result<Vec<PathBuf>, MtxError> {
    let sys = constrained_system(spec)?;
    Ok(write_matrices(dir, &sys, &source_name(&spec.model))?)
}

/// The model as the Matrix Market files' headers name it: its file name.
pub fn source_name(model: &Path) -> String {
    model.file_name().map_or_else(
        || model.display().to_string(),
        |f| f.to_string_lossy().into_owned(),
    )
}

/// The build options a body was made with, from its recipe (`recipe.json`), for exporting the
/// constrained matrices of that build from `model`: format, material, thickness, subcase,
/// interfaces, spider, beam mass as the recipe records them, the mass kind as `method.bin`
/// does. Without a recipe: the defaults of `build` with the body's mass kind.
pub fn spec_from_body(
    body: &flexbody_reader::ReducedBody,
    model: &Path,
) -> Result<BuildSpec, crate::pipeline::options::OptionError> {
    spec_from_body_with(body, model, Default::default())
}

/// [`spec_from_body`] with explicit options on top of the recipe's, as `check --model` takes
/// them.
pub fn spec_from_body_with(
    body: &flexbody_reader::ReducedBody,
    model: &Path,
    overrides: crate::pipeline::recipe::ModelOverrides,
) -> Result<BuildSpec, crate::pipeline::options::OptionError> {
    let input =
        crate::pipeline::recipe::model_input(body.recipe.as_ref(), model.to_path_buf(), overrides)?;
    Ok(spec_of_input(body, input))
}

/// The spec of the build that made `body`, from its model input (the recipe's options with
/// the ones given on top): what `check --model` and `export --to mtx` rebuild.
pub fn spec_of_input(
    body: &flexbody_reader::ReducedBody,
    input: crate::pipeline::recipe::ModelInput,
) -> BuildSpec {
    let mut spec = BuildSpec::new(input.path, body.units.clone(), &[]);
    spec.format = input.format;
    spec.material = input.material;
    spec.thickness = input.thickness;
    spec.subcase = input.subcase;
    spec.ignore = input.ignore;
    spec.inp_shells = input.inp_shells;
    spec.interface = input.interface;
    spec.spider = input.spider;
    spec.beam_mass = input.beam_mass;
    spec.scene = input.scene;
    spec.mass = match body.method.mass_kind {
        flexbody_reader::MassKind::Lumped => fe::MassKind::Lumped,
        flexbody_reader::MassKind::Consistent => fe::MassKind::Consistent,
    };
    spec.mass_explicit = true;
    spec
}

/// `flexbody export FILE --to mtx --model MODEL -o DIR`: the constrained K, M of the build that
/// made `body`, rebuilt from `model` with the file's recipe (format, material, thickness,
/// subcase, interfaces, spiders, beam mass; the mass kind of `method.bin`) as `check --model`
/// rebuilds it; `overrides` and `mass` replace the recorded options. A model whose files differ
/// from the recipe's SHA-256 is refused with `check`'s messages, before anything is written.
pub fn export_body_matrices(
    body: &flexbody_reader::ReducedBody,
    model: &Path,
    overrides: crate::pipeline::recipe::ModelOverrides,
    mass: Option<fe::MassKind>,
    dir: &Path,
) -> Result<Vec<PathBuf>, MtxError> {
    if let Some(recipe) = &body.recipe {
        let changed = crate::pipeline::recipe::changed_model_files(recipe, model);
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
