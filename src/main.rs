//! The `flexbody` command line ([`flexbody::cli`]). The one place where the outcome becomes an
//! exit code: 0 ok, 1 a `check` failed, 2 error (printed as `flexbody: ` and its cause chain).
use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    match flexbody::cli::run(&flexbody::cli::Cli::parse()) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("flexbody: {}", flexbody::cli::error_message(&e));
            ExitCode::from(2)
        }
    }
}
