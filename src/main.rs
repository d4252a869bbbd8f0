//! The `flexbody` command line. The only place where errors become text and exit codes.
fn main() {
    println!("flexbody {}", env!("CARGO_PKG_VERSION"));
}
