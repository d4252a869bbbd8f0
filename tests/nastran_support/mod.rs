//! What the Nastran card tests share: writing a deck into a scratch folder, building it through
//! the CLI (frequencies from `--json`, or the refusal's message), a card's line in a deck.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// Write `text` as `name` in the scratch folder `dir` of this test binary.
pub fn write(dir: &str, name: &str, text: &str) -> PathBuf {
    let p = crate::common::scratch(dir).join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The line (1-based) of the first line of `text` that starts with `needle`.
pub fn line_of(text: &str, needle: &str) -> usize {
    1 + text.lines().position(|l| l.starts_with(needle)).unwrap()
}

fn build(deck: &Path, args: &[&str]) -> std::process::Output {
    crate::common::exe()
        .arg("build")
        .arg(deck)
        .args(["--units", "si", "--method", "normal"])
        .args(args)
        .arg("-o")
        .arg(deck.with_extension("flexbody"))
        .output()
        .unwrap()
}

/// Frequencies (Hz) of `flexbody build DECK --units si --method normal --modes n --json` with
/// `extra` options.
pub fn built_hz(deck: &Path, modes: usize, extra: &[&str]) -> Vec<f64> {
    let n = modes.to_string();
    let args: Vec<&str> = ["--json", "--modes", n.as_str()]
        .into_iter()
        .chain(extra.iter().copied())
        .collect();
    let out = build(deck, &args);
    assert!(
        out.status.success(),
        "{}: {}",
        deck.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["frequency_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_f64().unwrap())
        .collect()
}

/// The build of `deck` exits 2 and writes nothing: its message (stderr).
pub fn build_refused(deck: &Path) -> String {
    let out = build(deck, &[]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(!deck.with_extension("flexbody").exists(), "{err}");
    err
}
