//! # flexbody
//!
//! Turns a finite-element model into a *reduced flexible-body file* for multibody solvers.
//! The library is a pipeline of plain stages, each a module with one job:
//!
//! ```text
//! import ─► Model ─► fe (assemble) ─► (K, M, DofMap) ─► reduce ─► ModeSet ─► body ─► write
//! ```
//!
//! * [`import`] — readers for Abaqus/CalculiX `.inp`, Nastran `.bdf`, Gmsh `.msh`, Matrix Market.
//! * [`model`] — the resolved FE model (nodes, elements, sections, materials, sets, rigid elements).
//! * [`fe`] — element matrices and sparse assembly of K and M; constraint elimination.
//! * [`solve`] — sparse Cholesky with METIS ordering and the block shift-invert eigensolver.
//! * [`reduce`] — normal modes, Craig–Bampton, Craig–Chang, Dietz, reference conditions.
//! * [`body`] — faces, inertia invariants, modal stress/strain shapes (solids, shell fibres),
//!   damping.
//! * [`write`](mod@write) — the reduced-body file writer (types from the `flexbody-reader`
//!   crate) and the Matrix Market writer of K and M.
//! * [`pipeline`] — `flexbody build` as the list of those stages ([`build::build`], also
//!   [`build`]), and what they share: deck defaults, interfaces, scene loads, checks, recipe.
//! * [`cli`] — the command line: arguments, the commands, what they print
//!   ([`inspect`](mod@inspect)).
//! * [`export`] — a `.flexbody` file → other solvers' formats.
//!
//! See `ARCHITECTURE.md` and `docs/design.md`.
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
pub use body::{damping, shell_stress, stress};
pub use cli::inspect;
pub use pipeline as build;
pub use pipeline::{check, diagnose, interface, options, recipe, scene};
