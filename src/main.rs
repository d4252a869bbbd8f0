//! The `flexbody` command line ([`flexbody::cli`]). The one place where the outcome becomes an
//! exit code: 0 ok, 1 a `check` failed, 2 error (printed as `flexbody: ` and its cause chain).
use std::process::ExitCode;

/// The system allocator, with a failed allocation reported by stage and size (exit 2), never an
/// abort ([`flexbody::cli::alloc_guard`]).
#[global_allocator]
static ALLOCATOR: flexbody::cli::alloc_guard::GuardedAlloc =
    flexbody::cli::alloc_guard::GuardedAlloc;

fn main() -> ExitCode {
    flexbody::cli::alloc_guard::install();
    match flexbody::cli::run(&flexbody::cli::parse_command_line()) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("flexbody: {}", flexbody::cli::error_message(&e));
            ExitCode::from(2)
        }
    }
}
