//! The `flexbody` command line. The only place where errors become text and exit codes:
//! 0 ok, 1 a `check` failed (later), 2 error.
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// FE model → reduced flexible-body file for multibody solvers.
#[derive(Parser)]
#[command(name = "flexbody", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print what a .flexbody file holds: header, units, counts, mass properties, modes, entries.
    Inspect {
        /// The .flexbody file.
        file: PathBuf,
        /// Print the summary as JSON instead of text.
        #[arg(long)]
        json: bool,
    },
}

fn inspect(file: &PathBuf, json: bool) -> anyhow::Result<()> {
    use anyhow::Context;
    let bytes = std::fs::read(file).with_context(|| format!("cannot read {}", file.display()))?;
    let limits = flexbody_reader::ReadLimits::default();
    let (body, manifest) = flexbody_reader::from_bytes_with_manifest(&bytes, &limits)
        .with_context(|| format!("{} is not a valid flexbody file", file.display()))?;
    let summary = flexbody::inspect::summarize(&body, &manifest);
    if json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        print!("{}", flexbody::inspect::render_text(&summary));
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Inspect { file, json } => inspect(file, *json),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("flexbody: {e:#}");
            ExitCode::from(2)
        }
    }
}
