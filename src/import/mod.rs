//! FE model importers: Abaqus/CalculiX `.inp`, Nastran `.bdf`, ANSYS `.cdb` (and `.full`
//! matrices), Gmsh `.msh`, Matrix Market.
//!
//! [`read_model`] picks the reader from the file's content and extension (module `detect`; or
//! [`ImportOptions::format`]) and
//! returns a resolved [`Model`]. Every failure is an [`ImportError`] naming file, line and entity.
//! Readers never panic on bad input.
pub mod abaqus;
pub mod ansys;
pub mod budget;
pub mod ccx_matrices;
mod detect;
pub mod error;
pub mod gmsh;
pub mod material_file;
pub mod matrix_market;
pub mod nastran;
pub mod plausibility;
pub(crate) mod text;

pub use error::{ImportError, RefusedCard};
pub use material_file::read_material_file;

use std::path::Path;

use crate::model::{ElementKind, ImportWarning, Material, Model, Property, Section};

/// Input formats with a model reader.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Abaqus / CalculiX input deck (`.inp`).
    Abaqus,
    /// Nastran bulk data (`.bdf`, `.nas`, `.dat`, `.blk`, `.bulk`).
    Nastran,
    /// Gmsh 4.1 mesh, ASCII or binary (`.msh`).
    Gmsh,
    /// ANSYS Mechanical APDL archive (`.cdb`, as `CDWRITE` writes it).
    Ansys,
    /// ANSYS full file (`Jobname.full`: assembled K and M), nodes from `Jobname.cdb` beside it.
    AnsysFull,
}

impl Format {
    /// Format from a file extension (case-insensitive).
    pub fn from_extension(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "inp" => Some(Format::Abaqus),
            "bdf" | "nas" | "dat" | "blk" | "bulk" => Some(Format::Nastran),
            "msh" => Some(Format::Gmsh),
            "cdb" => Some(Format::Ansys),
            "full" => Some(Format::AnsysFull),
            _ => None,
        }
    }

    /// Format from a user-given name (`inp`/`abaqus`/`calculix`).
    pub fn from_name(name: &str) -> Option<Format> {
        match name.to_ascii_lowercase().as_str() {
            "inp" | "abaqus" | "calculix" | "ccx" => Some(Format::Abaqus),
            "bdf" | "nastran" | "nas" => Some(Format::Nastran),
            "msh" | "gmsh" => Some(Format::Gmsh),
            "cdb" | "ansys" | "mapdl" => Some(Format::Ansys),
            "full" | "ansys-full" => Some(Format::AnsysFull),
            _ => None,
        }
    }
}

/// Options of [`read_model`].
#[derive(Debug, Clone, Default)]
pub struct ImportOptions {
    /// Force a format instead of guessing from the extension.
    pub format: Option<Format>,
    /// Material for solid elements that have no section in the file (always the case for
    /// `.msh`; also for a bare Abaqus mesh without *SOLID SECTION). From the command line or
    /// a side file ([`read_material_file`]).
    pub material: Option<Material>,
    /// Nastran: the case-control subcase whose SPC and METHOD selections apply (needed when the
    /// deck's subcases differ; `None` otherwise).
    pub subcase: Option<u64>,
    /// Thickness of shell elements (S3/S4-type 2D elements, Gmsh triangles and quadrangles)
    /// without a section: with `material`, they become homogeneous shells of that material.
    pub shell_thickness: Option<f64>,
    /// Cards to drop on purpose, by name (`CGAP`; a Nastran parameter as `PARAM:SNORM`;
    /// case-insensitive): not read even when supported, so a card that would be refused does
    /// not stop the import. Each dropped card type becomes a warning naming its lines and
    /// count (`--ignore CARD[,CARD…]`, recorded in the recipe). Abaqus/CalculiX decks: keyword
    /// names (`*TIE` or `TIE`, blanks ignored), element types (`B32R`) and `PERTURBATION` (a
    /// *FREQUENCY step's preload).
    pub ignore_cards: Vec<String>,
    /// How the shells of an Abaqus/CalculiX deck are formed (`--inp-shells`, recorded in the
    /// recipe): expanded into one layer of bricks as ccx 2.20 does (the default), or as
    /// flexbody's own shell elements.
    pub inp_shells: InpShells,
}

/// The shells (S3, S4, S4R, S6, S8, S8R) of an Abaqus/CalculiX deck (`--inp-shells`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InpShells {
    /// As ccx 2.20 computes them: one layer of C3D6/C3D8R/C3D15/C3D20/C3D20R bricks along the
    /// nodal normals, the shell nodes joined to them by ccx's equations
    /// (`import::abaqus::shell_expansion`).
    #[default]
    Expanded,
    /// flexbody's shell elements (MITC4, DKT, MITC9/MITC6 curved shells).
    Native,
}

impl InpShells {
    /// The option's value as text (`expanded`, `native`).
    pub fn name(self) -> &'static str {
        match self {
            InpShells::Expanded => "expanded",
            InpShells::Native => "native",
        }
    }

    /// From the option's text.
    pub fn from_name(s: &str) -> Option<InpShells> {
        match s.trim().to_ascii_lowercase().as_str() {
            "expanded" => Some(InpShells::Expanded),
            "native" => Some(InpShells::Native),
            _ => None,
        }
    }
}

/// Read a model file in any supported format.
pub fn read_model(path: &Path, opts: &ImportOptions) -> Result<Model, ImportError> {
    let format = match opts.format {
        Some(f) => f,
        None => detect::format_of(path)?,
    };
    let mut model = match format {
        Format::Abaqus => abaqus::read_with_options(path, opts)?,
        Format::Nastran => nastran::read_with_options(path, opts)?.0,
        Format::Gmsh => gmsh::read(path, None)?,
        Format::Ansys => ansys::read_with_options(path, opts)?,
        Format::AnsysFull => ansys::full::read_model(path)?,
    };
    if model.files.is_empty() {
        model.files.push(path.display().to_string());
    }
    if let Some(m) = &opts.material {
        apply_default_material(&mut model, m);
    }
    let warnings = plausibility::material_warnings(&model, &path.display().to_string());
    model.warnings.extend(warnings);
    match (opts.shell_thickness, &opts.material) {
        (Some(t), Some(m)) => apply_default_shell(&mut model, m, t),
        (Some(_), None) => model.warnings.push(ImportWarning {
            file: path.display().to_string(),
            message: "a shell thickness was given without a material: shells without a section stay unassembled".into(),
        }),
        _ => {}
    }
    Ok(model)
}

/// Give every 3-, 4-, 6- and 8-node surface element without a property a homogeneous shell section of
/// material `m` and thickness `t` (a new material and property named `DEFAULT_SHELL`).
pub fn apply_default_shell(model: &mut Model, m: &Material, t: f64) {
    add_default_property(
        model,
        m,
        "DEFAULT_SHELL",
        |mat| Section::Shell(crate::model::ShellSection::homogeneous(t, mat)),
        |e| {
            matches!(
                e.kind,
                ElementKind::Tri3 | ElementKind::Quad4 | ElementKind::Tri6 | ElementKind::Quad8
            )
        },
    );
}

/// Give every solid element without a property a solid section of material `m`
/// (added as a new material and property named `DEFAULT`). No-op if all elements have one.
pub fn apply_default_material(model: &mut Model, m: &Material) {
    add_default_property(
        model,
        m,
        "DEFAULT",
        |_| Section::Solid,
        |e| e.kind.is_solid(),
    );
}

/// Adds material `m` and a property `name` with `section(material index)`, and gives it to every
/// element without a property for which `takes` holds. No-op if there is no such element.
fn add_default_property(
    model: &mut Model,
    m: &Material,
    name: &str,
    section: impl FnOnce(usize) -> Section,
    takes: impl Fn(&crate::model::Element) -> bool,
) {
    let bare = |e: &crate::model::Element| e.property.is_none() && takes(e);
    if !model.elements.iter().any(bare) {
        return;
    }
    model.materials.push(Material {
        name: if m.name.is_empty() {
            "DEFAULT".into()
        } else {
            m.name.clone()
        },
        ..m.clone()
    });
    let mat = model.materials.len() - 1;
    let pid = model.properties.iter().map(|p| p.id).max().unwrap_or(0) + 1;
    model.properties.push(Property {
        id: pid,
        name: name.into(),
        material: mat,
        section: section(mat),
    });
    let prop = model.properties.len() - 1;
    for e in &mut model.elements {
        if bare(e) {
            e.property = Some(prop);
        }
    }
}
