//! The command line: each subcommand reads its arguments, runs the library and prints what it
//! found. `src/main.rs` parses, calls [`run`] and turns the outcome into an exit code.
//!
//! * [`alloc_guard`] — a failed allocation as an error naming the stage and the size.
//! * [`args`](mod@args) — the arguments (clap) and their conversion into the library's specs.
//! * `build` — `flexbody build`: the pipeline with stage progress, the file, the report.
//! * [`check`](mod@check) — the verification report behind `flexbody check`.
//! * [`inspect`](mod@inspect) — the summary behind `flexbody inspect`.
//! * `export` — `flexbody export`: a file to another solver's format.
//! * `view` — `flexbody view`: the HTML page that animates a file's modes.

pub mod alloc_guard;
pub mod args;
mod build;
pub mod check;
mod export;
pub mod inspect;
mod progress;
mod view;

pub use args::Cli;
use args::Command;

/// The process's command line, parsed ([`args::attach_optional_values`] first).
pub fn parse_command_line() -> Cli {
    use clap::Parser;
    Cli::parse_from(args::attach_optional_values(std::env::args_os()))
}

/// Runs the parsed command line: `Ok(true)` when it succeeded, `Ok(false)` when `check` found a
/// failed check, `Err` when it could not run.
pub fn run(cli: &Cli) -> anyhow::Result<bool> {
    alloc_guard::set_stage(match &cli.command {
        Command::Build(_) => "import",
        Command::Inspect { .. } => "inspect",
        Command::Check(_) => "check",
        Command::Export { .. } => "export",
        Command::View { .. } => "view",
    });
    match &cli.command {
        Command::Build(args) => build::command(args).map(|()| true),
        Command::Inspect { file, json } => inspect::command(file, *json).map(|()| true),
        Command::Check(args) => check::command(args),
        Command::Export {
            file,
            to,
            output,
            model,
            model_args,
            mass,
        } => export::command(
            file,
            to,
            export::ExportArgs {
                output,
                model: model.as_ref(),
                model_args,
                mass: mass.as_deref(),
            },
        )
        .map(|()| true),
        Command::View { file, output } => view::command(file, output).map(|()| true),
    }
}

/// An error as one line: the chain, each cause once. Errors whose text already holds their
/// cause (most `thiserror` types) would otherwise print it twice ("X: X").
pub fn error_message(e: &anyhow::Error) -> String {
    let mut msg = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if msg.contains(&text) {
            continue;
        }
        // A cause that begins by repeating the end of the message (the file it names,
        // "cannot build P" then "P: …") continues it.
        let mut rest = text.as_str();
        while let Some((head, tail)) = rest.split_once(": ") {
            if msg.ends_with(head) {
                rest = tail;
            } else {
                break;
            }
        }
        if !msg.is_empty() {
            msg.push_str(": ");
        }
        msg.push_str(rest);
    }
    msg
}
