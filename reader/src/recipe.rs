//! Entry `recipe.json` (format 1.2, optional): how the body was built — the tool, every model
//! file read with its SHA-256, the effective options as the user gave them (strings, so a new
//! option syntax needs no new layout), the resolved interfaces and spiders, and the band in
//! which the body is meant to be accurate (SPEC.md §5.11). UTF-8 JSON, not bincode: it is an
//! open record of option texts that grows with the tool, read by people and tools alike, and
//! JSON lets a newer writer add members that older readers ignore.
use serde::{Deserialize, Serialize};

use crate::types::{Generator, Units};

/// Entry `recipe.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Recipe {
    /// The program that built the body (name and version).
    pub tool: Generator,
    /// Every model file read: the main file first, then the includes in the order read.
    pub model_files: Vec<ModelFile>,
    /// The effective options of the build.
    pub options: RecipeOptions,
    /// Each `--interface` entry with the nodes it produced.
    pub interfaces: Vec<RecipeInterface>,
    /// The band in which the body is meant to be accurate.
    pub accuracy_band: AccuracyBand,
    /// The preload the modes were computed under (absent: none).
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub preload: Option<RecipePreload>,
}

/// A linear static preload of the modes (K + K_G of its stress, SPEC §5.11).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecipePreload {
    /// Where it came from: `--preload NAMES`, or the deck's step and line.
    pub source: String,
    /// The loads it is made of.
    pub loads: Vec<String>,
    /// The largest nodal translation of the static solution.
    pub max_displacement: f64,
    /// The external id of the node where it is.
    pub max_displacement_node: u64,
    /// The lowest buckling factor λ₁ (`null`: nothing in compression).
    pub buckling_factor: Option<f64>,
}

/// One model file read by the build.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ModelFile {
    /// Path relative to the main file's folder (`/`-separated); the main file: its file name.
    pub path: String,
    /// `main` or `include`.
    pub role: String,
    /// Size in bytes.
    pub size: u64,
    /// Lowercase hex SHA-256 of the file's bytes (64 digits).
    pub sha256: String,
}

/// The build options, each in the form `flexbody build` accepts. A member written `name?: T` in
/// SPEC §5.11 (`thickness` … `select`) is absent when not given; present, it is a `T` (`null`
/// is not).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecipeOptions {
    /// `--format` as given (`null`: from the extension).
    pub format: Option<String>,
    /// `--material` as `E=…,nu=…,rho=…` (`null`: none given).
    pub material: Option<String>,
    /// `--method`: `cb`, `normal`, `craig-chang` or `dietz`.
    pub method: String,
    /// `--modes` (`null`: not given).
    pub modes: Option<u64>,
    /// `--fmax` in Hz (`null`: not given).
    pub fmax_hz: Option<f64>,
    /// `--mass`: `lumped` or `consistent`.
    pub mass: String,
    /// `--beam-mass` as resolved: `section`, `torsion`, `none` or `nastran`.
    pub beam_mass: String,
    /// The unit system (equals the manifest's).
    pub units: Units,
    /// `--interface` entries exactly as given.
    pub interface: Vec<String>,
    /// `--spider`: `rbe2`, `rbe3` or `none`.
    pub spider: String,
    /// `--reference-conditions` as `NODE:DOFS` (Nastran dof digits).
    pub reference_conditions: Vec<String>,
    /// `--reference-method`: 1 or 2.
    pub reference_method: u8,
    /// `--keep-nodes`: `all`, `interface`, `surface` or a node-set name.
    pub keep_nodes: String,
    /// `--invariants`: `full`, `partial`, `constant` or `rigid`.
    pub invariants: String,
    /// Stress fields: `none`, `stress`, `strain` or `both`.
    pub stress_fields: String,
    /// `--damping` as given (`null`: no damping entry).
    pub damping: Option<String>,
    /// `--thickness` of shells without a section (absent: not given).
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub thickness: Option<f64>,
    /// `--subcase` of a Nastran deck (absent: not given).
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub subcase: Option<u64>,
    /// `--gravity` as given (absent: not given; format 1.4).
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub gravity: Option<String>,
    /// `--load` entries as given (absent: none; format 1.4).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loads: Vec<String>,
    /// `--residual-vectors`: `loads`, `interface` or `both` (absent: none; format 1.4).
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub residual_vectors: Option<String>,
    /// `--select`: `participation:ε` (absent: not given; the modes were selected by the
    /// scene's participation, so modes inside the band may be missing).
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub select: Option<String>,
    /// `--preload` load names as given (absent: none; the deck's own preload is recorded by
    /// the model files' SHA-256 and in [`Recipe::preload`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub preload: Vec<String>,
    /// `--ignore`: cards or keywords dropped on purpose although they could change the body
    /// (absent: none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ignore: Vec<String>,
    /// `--geometric-stiffness`: `inertia` (absent: not given; format 1.7): which unit loads
    /// `geometric_stiffness.bin` holds.
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub geometric_stiffness: Option<String>,
    /// `--inp-shells`: how an Abaqus/CalculiX deck's shells were formed, `expanded` (one layer
    /// of bricks, as ccx) or `native` (flexbody's shells); absent: not an Abaqus deck, or a
    /// build before this member, which formed them `native`.
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub inp_shells: Option<String>,
    /// `--eigensolver`: `lanczos`, `amls` or `amls:F` (absent: `auto`, which picks Lanczos
    /// or AMLS by size and mode count).
    #[serde(
        default,
        deserialize_with = "crate::json::present",
        skip_serializing_if = "Option::is_none"
    )]
    pub eigensolver: Option<String>,
}

/// One `--interface` entry as resolved.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecipeInterface {
    /// The entry as given.
    pub entry: String,
    /// External ids of the interface nodes it produced (each stored with `interface = true`).
    pub nodes: Vec<u64>,
    /// The spider, when the entry was a node set attached through one.
    pub spider: Option<RecipeSpider>,
}

/// A spider from a node set to a new centre node.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecipeSpider {
    /// `rbe2` or `rbe3`.
    pub kind: String,
    /// External id of the centre node.
    pub centre_node: u64,
    /// Centre position (length unit, body frame).
    pub centre: [f64; 3],
    /// How the centre was placed (`CylinderFit`, `AreaCentroid`, `NodeAverage`, …).
    pub fit: String,
    /// Distance of the centre from the plain node average of the set.
    pub offset_from_node_average: f64,
    /// External ids of the set's nodes (the spider's legs).
    pub set_nodes: Vec<u64>,
}

/// The frequency band in which the body is meant to be accurate: modes from 0 Hz to
/// `fmax_hz`, by the rule named in `rule` (SPEC.md §5.11).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AccuracyBand {
    /// Upper end in Hz (cycles per time unit), finite and > 0.
    pub fmax_hz: f64,
    /// `fmax`, `fixed-interface`, `free-free` or `normal-modes`.
    pub rule: String,
    /// The frequency the basis was selected to (3 × `--fmax`); `null` for a `--modes N` build.
    pub basis_cutoff_hz: Option<f64>,
}
