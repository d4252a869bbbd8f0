//! The command line: what each subcommand reads, runs and prints.
//!
//! * [`check`] — the verification report behind `flexbody check`.
//! * [`inspect`] — the summary behind `flexbody inspect`.

pub mod check;
pub mod inspect;
