//! # flexbody
//!
//! Turns a finite-element model into a *reduced flexible-body file* for multibody solvers.
//! The library is a pipeline of plain stages, each a module with one job:
//!
//! ```text
//! import ─► Model ─► fe (assemble) ─► (K, M, DofMap) ─► reduce ─► ModeSet ─► invariants ─► write
//! ```
//!
//! * [`model`] — the resolved FE model (nodes, elements, sections, materials, sets, rigid elements).
//! * [`import`] — readers for Abaqus/CalculiX `.inp`, Nastran `.bdf`, Gmsh `.msh`, Matrix Market.
//! * [`fe`] — element matrices and sparse assembly of K and M.
//! * [`solve`] — sparse Cholesky with METIS ordering and the block shift-invert eigensolver.
//! * [`reduce`] — normal modes, Craig–Bampton, Craig–Chang, Dietz, reference conditions.
//! * [`write`](mod@write) — the reduced-body file writer (types from the `flexbody-reader` crate).
//! * [`body`] — faces, inertia invariants, modal stress/strain shapes (solids, shell fibres),
//!   damping.
//! * [`inspect`] — the summary `flexbody inspect` prints (mass properties, modes, entries).
//!
//! See `ARCHITECTURE.md` and `../shared/DESIGN.md`.
#![allow(non_snake_case)]

pub mod body;
pub mod cli;
pub mod export;
pub mod fe;
pub mod import;
pub mod model;
pub mod pipeline;
pub mod reduce;
pub mod solve;
pub mod write;

// Crate-root paths kept for programs written against the flat layout (`flexbody::build::…`,
// `flexbody::check::…`, `flexbody::stress`, …): each names the module where the code lives now.
pub use body::{damping, faces, invariants, invariants_consistent, shell_stress, stress};
pub use cli::{check, inspect};
pub use pipeline as build;
pub use pipeline::{
    deck, diagnose, interface, interface_entry, options, precheck, recipe, scene, verify,
};
