//! The `mtx` target of `flexbody export`: the constrained K and M of the build that made a file.
//! Unlike the other targets it needs the FE model, not just the file, so the pipeline makes it
//! ([`crate::pipeline::matrices`]) and [`crate::write::mtx`] writes it; this module keeps its
//! paths.

pub use crate::pipeline::matrices::{
    constrained_system, constrained_system_of_model, export_body_matrices, export_mtx,
    spec_from_body, spec_from_body_with, MtxError,
};
pub use crate::write::mtx::{write_matrices, ConstrainedSystem, MatrixWriteError};
