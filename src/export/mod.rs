//! Exporters: a `.flexbody` file (read through `flexbody-reader` only) → another solver's own
//! format. Each exporter is a plain function of the [`ReducedBody`]; output goes through a temp
//! file beside the target and a rename, so a failed export never leaves a half-written file.
//!
//! * [`exudyn`] — the NPZ that `exudyn.FEM.ObjectFFRFreducedOrderInterface.LoadFromFile` reads.
//! * [`mbdyn`] — the modal element's FEM file (MBDyn manual, "FEM File Format").
//! * [`sid`] — Wallrapp's Standard Input Data (`.SID_FEM` text, as EMBSlib reads it).
//! * [`vtu`] — a VTK XML unstructured grid (`.vtu`) of the kept mesh with the mode shapes and
//!   stress/strain shapes as point data, for ParaView.
//! * [`view`] — `flexbody view`: one self-contained HTML page that animates the modes.
//! * [`mtx`] — the model's K and M in Matrix Market (from the model, not the file: the file's
//!   recipe says how the model was built, [`mtx::export_body_matrices`]).
use std::path::{Path, PathBuf};

use flexbody_reader::{ModeLabel, ReducedBody};

pub mod exudyn;
pub mod mbdyn;
pub mod mtx;
pub mod npz;
pub mod sid;
pub mod view;
pub mod vtu;

/// Why an export failed. No output file is left behind in any case.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The body lacks something the target format needs.
    #[error("cannot export to {target}: {reason}")]
    Unsupported {
        /// Target format name.
        target: &'static str,
        /// What is missing and how to get it.
        reason: String,
    },
    /// Creating, writing or renaming the output failed.
    #[error("{path}: {action} failed: {source}")]
    Io {
        /// The output path.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// The cause.
        source: std::io::Error,
    },
    /// The archive layer failed.
    #[error("{path}: archive: {detail}")]
    Archive {
        /// The output path.
        path: PathBuf,
        /// The archive layer's message.
        detail: String,
    },
}

/// Export targets of `flexbody export --to`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// exudyn `ObjectFFRFreducedOrderInterface` NPZ.
    Exudyn,
    /// MBDyn modal element `.fem` file.
    Mbdyn,
    /// SID (Standard Input Data) `.SID_FEM` text.
    Sid,
    /// VTK XML unstructured grid `.vtu` (ParaView).
    Vtu,
    /// The constrained K and M in Matrix Market (`K.mtx`, `M.mtx`, `dofs.txt` in a folder);
    /// needs the FE model: [`mtx::export_body_matrices`].
    Mtx,
}

impl Target {
    /// Parses a `--to` value.
    pub fn from_name(name: &str) -> Option<Target> {
        match name.to_ascii_lowercase().as_str() {
            "exudyn" => Some(Target::Exudyn),
            "mbdyn" => Some(Target::Mbdyn),
            "sid" | "sid_fem" => Some(Target::Sid),
            "vtu" => Some(Target::Vtu),
            "mtx" => Some(Target::Mtx),
            _ => None,
        }
    }
}

/// What an export wrote, for the CLI's one-line summary.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportSummary {
    /// Flexible modes written.
    pub modes: usize,
    /// Nodes written.
    pub nodes: usize,
    /// Notes for the user (what was left out and why).
    pub notes: Vec<String>,
}

/// Exports `body` to `path` in the `target` format.
pub fn export(
    body: &ReducedBody,
    target: Target,
    path: &Path,
) -> Result<ExportSummary, ExportError> {
    match target {
        Target::Exudyn => exudyn::export_exudyn(body, path),
        Target::Mbdyn => mbdyn::export_mbdyn(body, path),
        Target::Sid => sid::export_sid(body, path),
        Target::Vtu => vtu::export_vtu(body, path),
        Target::Mtx => Err(ExportError::Unsupported {
            target: "mtx",
            reason: "K and M come from the FE model, not from the file: give the model the \
                     file was built from (`--model MODEL`, mtx::export_body_matrices)"
                .into(),
        }),
    }
}

/// Indices of the flexible modes (every mode not labelled `Rigid`), ascending. Selected by
/// label, not by ω²: a free body's rigid modes sit at ~1e-3 Hz, not at 0.
pub fn flexible_modes(body: &ReducedBody) -> Vec<usize> {
    body.modes
        .labels
        .iter()
        .enumerate()
        .filter(|(_, l)| **l != ModeLabel::Rigid)
        .map(|(j, _)| j)
        .collect()
}

/// A mode label as a word for names and captions: `rigid`, `normal`, `constraint`,
/// `fixed-interface`, `attachment`, `frequency-response`.
pub fn mode_label_name(label: ModeLabel) -> &'static str {
    match label {
        ModeLabel::Rigid => "rigid",
        ModeLabel::Normal => "normal",
        ModeLabel::Constraint => "constraint",
        ModeLabel::FixedInterface => "fixed-interface",
        ModeLabel::Attachment => "attachment",
        ModeLabel::FrequencyResponse => "frequency-response",
    }
}

/// Writes `bytes` to `path` by [`crate::write::write_replacing`] (temp file beside it, fsync,
/// rename; on any error `path` is untouched).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    let io = |action: &'static str| {
        move |source| ExportError::Io {
            path: path.to_path_buf(),
            action,
            source,
        }
    };
    if path.is_dir() {
        return Err(io("writing the output")(std::io::Error::new(
            std::io::ErrorKind::IsADirectory,
            "it is a folder: give a file name",
        )));
    }
    crate::write::write_replacing(path, |w| w.write_all(bytes))
        .map_err(|(action, source)| io(action)(source))
}
