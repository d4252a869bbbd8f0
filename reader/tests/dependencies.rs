//! Architecture invariant: the reader links no linear algebra or solver code. Its direct
//! dependencies are exactly the inflate, encoding, checksum and error crates (the zip
//! container itself is read by the reader's own code, `src/archive.rs`).
#[test]
fn reader_depends_only_on_inflate_encoding_checksum_and_error_crates() {
    let manifest = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"))
        .expect("Cargo.toml");
    let mut section = String::new();
    let mut deps = Vec::new();
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            section = line.to_string();
        } else if section == "[dependencies]" && !line.is_empty() && !line.starts_with('#') {
            deps.push(
                line.split(['=', '.'])
                    .next()
                    .unwrap_or_default()
                    .trim()
                    .to_string(),
            );
        }
    }
    deps.sort();
    assert_eq!(
        deps,
        [
            "bincode",
            "flate2",
            "serde",
            "serde_json",
            "sha2",
            "thiserror"
        ]
    );
}
