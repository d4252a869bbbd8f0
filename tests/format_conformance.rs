//! Conformance suite: every file under `fixtures/` is checked by its kind, so a new fixture
//! needs no new code. `golden/*/*.flexbody` and `compat/*.flexbody` must be read and give
//! exactly their `.json` summary; `broken/*.flexbody` must be refused with the variant and
//! message fragment of their `.expect`, without panicking.
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures")
}

fn files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(rd) = std::fs::read_dir(dir) else {
        return out;
    };
    for e in rd.flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(files(&p, ext));
        } else if p.extension().is_some_and(|x| x == ext) {
            out.push(p);
        }
    }
    out.sort();
    out
}

/// Structural equality with numbers equal to 1e-12 relative (serde_json's default float
/// parser is not correctly rounded, so a printed-and-parsed f64 may differ in the last ulp).
fn json_close(a: &serde_json::Value, b: &serde_json::Value, at: &str) -> Result<(), String> {
    use serde_json::Value as V;
    match (a, b) {
        (V::Number(x), V::Number(y)) => {
            let (x, y) = (
                x.as_f64().unwrap_or(f64::NAN),
                y.as_f64().unwrap_or(f64::NAN),
            );
            if (x - y).abs() <= 1e-12 * x.abs().max(y.abs()) {
                Ok(())
            } else {
                Err(format!("{at}: {x} vs {y}"))
            }
        }
        (V::Array(x), V::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .try_for_each(|(i, (x, y))| json_close(x, y, &format!("{at}[{i}]"))),
        (V::Object(x), V::Object(y)) if x.len() == y.len() => {
            x.iter().try_for_each(|(k, v)| match y.get(k) {
                Some(w) => json_close(v, w, &format!("{at}.{k}")),
                None => Err(format!("{at}.{k} missing")),
            })
        }
        _ if a == b => Ok(()),
        _ => Err(format!("{at}: {a} vs {b}")),
    }
}

fn summary_matches(file: &Path) {
    let bytes = std::fs::read(file).expect("read fixture");
    let (body, manifest) = flexbody_reader::from_bytes_with_manifest(&bytes, &Default::default())
        .unwrap_or_else(|e| panic!("{} must be accepted: {e}", file.display()));
    let got = serde_json::to_value(flexbody::inspect::summarize(&body, &manifest)).expect("json");
    let want: serde_json::Value =
        serde_json::from_slice(&std::fs::read(file.with_extension("json")).expect("summary"))
            .expect("summary json");
    if let Err(at) = json_close(&got, &want, "$") {
        panic!(
            "{}: content differs from its summary at {at}",
            file.display()
        );
    }
    // The path API gives the same body.
    assert_eq!(flexbody_reader::read(file).expect("read by path"), body);
}

#[test]
fn golden_and_compat_files_match_their_summaries() {
    let mut n = 0;
    for dir in ["golden", "compat"] {
        for f in files(&fixtures().join(dir), "flexbody") {
            summary_matches(&f);
            n += 1;
        }
    }
    assert!(
        n >= 3,
        "expected at least 2 golden and 1 compat file, found {n}"
    );
}

#[test]
fn every_broken_file_gives_its_named_error_without_panic() {
    let list = files(&fixtures().join("broken"), "flexbody");
    assert!(
        list.len() >= 12,
        "at least 12 broken fixtures, found {}",
        list.len()
    );
    let mut failures = Vec::new();
    for f in &list {
        let expect: serde_json::Value = serde_json::from_slice(
            &std::fs::read(f.with_extension("expect")).expect(".expect file"),
        )
        .expect("expect json");
        let (variant, message) = (
            expect["variant"].as_str().expect("variant"),
            expect["message"].as_str().expect("message"),
        );
        let bytes = std::fs::read(f).expect("read");
        let outcome = std::panic::catch_unwind(|| flexbody_reader::from_bytes(&bytes));
        match outcome {
            Err(_) => failures.push(format!("{}: PANICKED", f.display())),
            Ok(Ok(_)) => failures.push(format!("{}: accepted, expected {variant}", f.display())),
            Ok(Err(e)) => {
                let text = e.to_string();
                if e.variant() != variant || !text.contains(message) {
                    failures.push(format!(
                        "{}: got {} \"{text}\", expected {variant} containing \"{message}\"",
                        f.display(),
                        e.variant()
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn truncating_a_golden_file_anywhere_never_panics() {
    let bytes =
        std::fs::read(fixtures().join("golden/v1.0/three_node_chain.flexbody")).expect("golden");
    for cut in (0..bytes.len()).step_by(7) {
        let r = std::panic::catch_unwind(|| flexbody_reader::from_bytes(&bytes[..cut]));
        assert!(matches!(r, Ok(Err(_))), "cut at {cut}: {r:?}");
    }
    // Flipping any single byte is either refused or (zip slack bytes) harmless: never a panic.
    for i in (0..bytes.len()).step_by(3) {
        let mut b = bytes.clone();
        b[i] ^= 0x5a;
        let r = std::panic::catch_unwind(|| flexbody_reader::from_bytes(&b));
        assert!(r.is_ok(), "flip at {i} panicked");
    }
}

/// Deterministic xorshift64 so the mutations are the same on every run.
fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

#[test]
fn mutated_payloads_with_valid_checksums_never_panic() {
    // Mutations behind a correct manifest reach the decoder and the rules: each must give an
    // Ok or a typed error, never a panic or an unbounded allocation.
    let mut bodies = vec![crate::format_support::body_3node()];
    let mut b = crate::format_support::body_20node();
    b.stress_shapes = b.strain_shapes.clone();
    bodies.push(b);
    let mut state = 0x9e3779b97f4a7c15u64;
    let (mut refused, mut total) = (0, 0);
    for body in &bodies {
        for (name, bytes) in crate::format_support::broken::payloads(body) {
            for _ in 0..150 {
                let mut m = bytes.clone();
                for _ in 0..1 + xorshift(&mut state) % 3 {
                    let i = (xorshift(&mut state) % m.len() as u64) as usize;
                    m[i] = (xorshift(&mut state) & 0xff) as u8;
                }
                if xorshift(&mut state) % 5 == 0 {
                    let cut = (xorshift(&mut state) % m.len() as u64) as usize;
                    m.truncate(cut);
                }
                let file = crate::format_support::broken::with_entry(body, &name, m);
                let r = std::panic::catch_unwind(|| flexbody_reader::from_bytes(&file));
                assert!(r.is_ok(), "{name}: mutation panicked");
                total += 1;
                refused += matches!(r, Ok(Err(_))) as usize;
            }
        }
    }
    // Most random byte changes in headers, counts or floats break a rule.
    assert!(
        refused > total / 3,
        "only {refused} of {total} mutations refused"
    );
}
