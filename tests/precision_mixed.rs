//! Issue 22, `build --precision`: the Craig–Bampton interior factored in f32 with solves refined
//! against K_ii. Through the real binary on the bundled conrod:
//! * `--precision mixed` gives the f64 build's frequencies (to 1e-10) and passes `check --model`,
//!   and the report says the factor was f32;
//! * `--precision auto` under a `--max-memory` that holds the f32 factor but not the f64 one
//!   builds in mixed precision and says why, where `--precision f64` stops before factoring;
//! * a bad value, or `mixed` where no Craig–Bampton interior is factored, is refused.

use crate::common::{exe, scratch};
use std::path::{Path, PathBuf};
use std::process::Output;

fn conrod() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/models/conrod/conrod.inp")
        .display()
        .to_string()
}

fn build(out: &Path, extra: &[&str]) -> Output {
    exe()
        .args(["build", &conrod(), "--interface", "BIG_END,SMALL_END"])
        .args(["--modes", "12", "--units", "si", "--threads", "1"])
        .args(extra)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap()
}

fn flexible_frequencies(file: &Path) -> Vec<f64> {
    let body = flexbody_reader::read(file).unwrap();
    body.modes
        .frequency_hz
        .iter()
        .zip(&body.modes.labels)
        .filter(|(_, l)| **l != flexbody_reader::ModeLabel::Rigid)
        .map(|(f, _)| *f)
        .collect()
}

fn worst_relative(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / x.abs())
        .fold(0.0, f64::max)
}

fn check_model(file: &Path) {
    let c = exe()
        .arg("check")
        .arg(file)
        .args(["--model", &conrod()])
        .output()
        .unwrap();
    assert!(
        c.status.success(),
        "check --model failed: {}{}",
        String::from_utf8_lossy(&c.stdout),
        String::from_utf8_lossy(&c.stderr)
    );
}

/// "needs about 61.2 MiB" in an out-of-memory error → bytes.
fn needed_bytes(stderr: &str) -> f64 {
    let rest = stderr
        .split("needs about ")
        .nth(1)
        .unwrap_or_else(|| panic!("no 'needs about' in: {stderr}"));
    let mut it = rest.split_whitespace();
    let v: f64 = it.next().unwrap().parse().unwrap();
    let unit = match it.next().unwrap() {
        "GiB" => 1u64 << 30,
        "MiB" => 1 << 20,
        "KiB" => 1 << 10,
        _ => 1,
    };
    v * unit as f64
}

#[test]
fn mixed_precision_gives_the_f64_frequencies_on_the_conrod() {
    let dir = scratch("precision-mixed");
    let mut files: Vec<PathBuf> = vec![];
    for precision in ["f64", "mixed"] {
        let out = dir.join(format!("{precision}.flexbody"));
        let o = build(&out, &["--precision", precision]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{precision}: {stderr}");
        assert_eq!(
            stderr.contains("K_ii factored in mixed precision (f32 L"),
            precision == "mixed",
            "{stderr}"
        );
        check_model(&out);
        files.push(out);
    }
    let (a, b) = (
        flexible_frequencies(&files[0]),
        flexible_frequencies(&files[1]),
    );
    let worst = worst_relative(&a, &b);
    println!("conrod CB, 12 modes: f64 vs mixed precision frequencies {worst:.2e}");
    assert!(worst < 1e-10, "frequencies differ by {worst:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn auto_precision_falls_back_to_f32_when_the_f64_factor_does_not_fit() {
    let dir = scratch("precision-auto");
    let reference = dir.join("f64.flexbody");
    assert!(build(&reference, &["--precision", "f64"]).status.success());
    // the f64 factor's need, from the error under a limit far too small
    let tiny = dir.join("tiny.flexbody");
    let o = build(&tiny, &["--precision", "f64", "--max-memory", "1M"]);
    assert!(!o.status.success() && !tiny.exists());
    let need = needed_bytes(&String::from_utf8_lossy(&o.stderr));
    // 0.75 of it: too little for f64, enough for the f32 factor (half of L and scratch, plus an
    // f32 copy of K_ii)
    let limit = format!("{}K", (0.75 * need / 1024.0) as u64);
    let o = build(&tiny, &["--precision", "f64", "--max-memory", &limit]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && !tiny.exists(), "{stderr}");
    assert!(stderr.contains("needs about"), "{stderr}");
    let auto = dir.join("auto.flexbody");
    let o = build(&auto, &["--max-memory", &limit]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("exceeds the memory limit: factored in mixed precision")
            && stderr.contains("K_ii factored in mixed precision (f32 L"),
        "{stderr}"
    );
    check_model(&auto);
    let worst = worst_relative(
        &flexible_frequencies(&reference),
        &flexible_frequencies(&auto),
    );
    println!("conrod, --max-memory {limit}: auto (mixed) vs f64 frequencies {worst:.2e}");
    assert!(worst < 1e-10, "{worst:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bad_precision_is_refused() {
    let dir = scratch("precision-bad");
    let out = dir.join("x.flexbody");
    let o = build(&out, &["--precision", "half"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && !out.exists());
    assert!(
        stderr.contains("--precision half: expected auto, f64 or mixed"),
        "{stderr}"
    );
    for other in [["--method", "normal"], ["--engine", "slepc"]] {
        let o = build(&out, &["--precision", "mixed", other[0], other[1]]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && !out.exists(), "{other:?}: {stderr}");
        assert!(
            stderr.contains("--precision mixed applies to the Craig-Bampton interior"),
            "{other:?}: {stderr}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
