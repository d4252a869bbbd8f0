//! The Rust reader and the stdlib reference reader (`format-spec/reference_reader.py`) give the
//! same outcome on mutants of the conformance fixtures (issue 37: both readers follow the one
//! procedure of SPEC §7.1 and §4.1): zip headers, end record and central directory bytes
//! changed, files cut and extended, manifest and recipe JSON edited (numbers beyond binary64,
//! members twice, deep nesting, wrong types), and the golden files rewritten in Zip64 form
//! (both must accept them). Each mutant the Rust reader refuses goes into a
//! scratch `broken/` folder with its error name, each it accepts into `compat/` with its
//! summary; the reference reader's `--check-fixtures` must agree with every one.
use std::io::{Cursor, Read};
use std::path::Path;

use flexbody::write::{zip_entries, Compression};

fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

fn pick<T: Copy>(state: &mut u64, from: &[T]) -> T {
    from[(xorshift(state) % from.len() as u64) as usize]
}

/// The fixtures every mutant starts from: golden files (first) and compat files.
fn seeds() -> Vec<Vec<u8>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    let mut files = Vec::new();
    for dir in [
        "golden/v1.0",
        "golden/v1.2",
        "golden/v1.4",
        "golden/v1.6",
        "golden/v1.8",
        "golden/v1.9",
        "compat",
    ] {
        let mut names: Vec<_> = std::fs::read_dir(root.join(dir))
            .expect("fixture folder")
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "flexbody"))
            .collect();
        names.sort();
        files.extend(
            names
                .iter()
                .map(|p| std::fs::read(p).expect("read fixture")),
        );
    }
    files
}

/// (name, bytes) of every entry, in container order.
fn unzip(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut z = zip::ZipArchive::new(Cursor::new(bytes)).expect("fixture is a zip");
    (0..z.len())
        .map(|i| {
            let mut f = z.by_index(i).expect("entry");
            let mut b = Vec::new();
            f.read_to_end(&mut b).expect("inflate");
            (f.name().expect("UTF-8 name").to_string(), b)
        })
        .collect()
}

/// A byte of the zip structure changed: in an end record, a central directory header or a
/// local header, to an interesting value; or the file cut or extended.
fn container_mutant(state: &mut u64, file: &[u8]) -> Vec<u8> {
    let mut b = file.to_vec();
    let sigs: Vec<(usize, usize)> = (0..b.len().saturating_sub(4))
        .filter_map(|i| match &b[i..i + 4] {
            b"PK\x05\x06" => Some((i, 22)),
            b"PK\x01\x02" => Some((i, 46)),
            b"PK\x03\x04" => Some((i, 30)),
            _ => None,
        })
        .collect();
    match xorshift(state) % 8 {
        0 => {
            let cut = (xorshift(state) % b.len() as u64) as usize;
            b.truncate(cut);
        }
        1 => b.extend_from_slice(pick(
            state,
            &[&b"\0"[..], b"PK\x05\x06", b"junk after the end"],
        )),
        _ => {
            for _ in 0..1 + xorshift(state) % 2 {
                let (at, len) = pick(state, &sigs);
                let i = (at + (xorshift(state) % len as u64) as usize).min(b.len() - 1);
                b[i] = pick(state, &[0u8, 1, 2, 0x7F, 0x80, 0xFE, 0xFF])
                    .wrapping_add(if xorshift(state) % 2 == 0 { 0 } else { b[i] });
            }
        }
    }
    b
}

const NUMBERS: [&str; 12] = [
    "1e999",
    "-1e999",
    "-0",
    "1e-400",
    "18446744073709551616",
    "4294967296",
    "1.0",
    "null",
    "\"7\"",
    "[1]",
    "{}",
    "100000000000000000000000000000000000000000000000000",
];

/// `text` with one JSON edit: a number replaced, a member repeated, a deep unknown member
/// added, or a `null` written over a value.
fn json_mutant(state: &mut u64, text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let members: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].contains("\": ") && lines[i].trim_end().ends_with(','))
        .collect();
    match xorshift(state) % 4 {
        0 => {
            let numbers: Vec<usize> = (0..text.len())
                .filter(|&i| {
                    i > 0
                        && text.as_bytes()[i].is_ascii_digit()
                        && !text.as_bytes()[i - 1].is_ascii_alphanumeric()
                        && text.as_bytes()[i - 1] != b'.'
                        && text.as_bytes()[i - 1] != b'"'
                })
                .collect();
            let Some(&at) = numbers.get((xorshift(state) % numbers.len().max(1) as u64) as usize)
            else {
                return text.to_string();
            };
            let end = at
                + text[at..]
                    .find(|c: char| !(c.is_ascii_digit() || "eE+-.".contains(c)))
                    .unwrap_or(text.len() - at);
            format!("{}{}{}", &text[..at], pick(state, &NUMBERS), &text[end..])
        }
        1 if !members.is_empty() => {
            let i = pick(state, &members);
            let mut out = lines.clone();
            out.insert(i, lines[i]);
            out.join("\n")
        }
        2 => {
            let depth = pick(state, &[62usize, 63, 64, 65]);
            let deep = format!("{}{}", "[".repeat(depth), "]".repeat(depth));
            text.replacen('{', &format!("{{\"deep\": {deep}, "), 1)
        }
        _ if !members.is_empty() => {
            let i = pick(state, &members);
            let (key, _) = lines[i].split_once("\": ").expect("a member line");
            let mut out = lines.clone();
            let line = format!("{key}\": {},", pick(state, &NUMBERS));
            out[i] = &line;
            out.join("\n")
        }
        _ => text.to_string(),
    }
}

/// `file` with its manifest (or recipe, the manifest's size and SHA-256 then fixed) edited.
fn entry_mutant(state: &mut u64, file: &[u8]) -> Vec<u8> {
    let mut entries = unzip(file);
    let has_recipe = entries.iter().any(|e| e.0 == "recipe.json");
    if has_recipe && xorshift(state) % 2 == 0 {
        let k = entries
            .iter()
            .position(|e| e.0 == "recipe.json")
            .expect("recipe");
        let text = String::from_utf8(entries[k].1.clone()).expect("UTF-8");
        entries[k].1 = json_mutant(state, &text).into_bytes();
        let mut m: serde_json::Value = serde_json::from_slice(&entries[0].1).expect("manifest");
        for e in m["entries"].as_array_mut().expect("entries") {
            if e["name"] == "recipe.json" {
                e["size"] = serde_json::json!(entries[k].1.len());
                e["sha256"] = serde_json::json!(flexbody_reader::codec::sha256_hex(&entries[k].1));
            }
        }
        entries[0].1 = serde_json::to_vec_pretty(&m).expect("json");
    } else {
        let text = String::from_utf8(entries[0].1.clone()).expect("UTF-8");
        entries[0].1 = json_mutant(state, &text).into_bytes();
    }
    zip_entries(&entries, Compression::Deflate(6)).expect("zip")
}

fn u16_at(b: &[u8], i: usize) -> usize {
    u16::from_le_bytes([b[i], b[i + 1]]) as usize
}

fn u32_at(b: &[u8], i: usize) -> u64 {
    u32::from_le_bytes(b[i..i + 4].try_into().expect("4 bytes")).into()
}

/// `file` (no comment, no prefix) rewritten in Zip64 form: every central header's sizes and
/// local offset moved to a Zip64 extra field, a Zip64 end record and locator before an end
/// record whose count, size and offset fields all say "see Zip64".
fn zip64_form(file: &[u8]) -> Vec<u8> {
    let e = file.len() - 22;
    let (count, cd) = (u16_at(file, e + 10), u32_at(file, e + 16) as usize);
    let mut out = file[..cd].to_vec();
    let mut at = cd;
    for _ in 0..count {
        let (n, x, c) = (
            u16_at(file, at + 28),
            u16_at(file, at + 30),
            u16_at(file, at + 32),
        );
        let mut h = file[at..at + 46 + n + x + c].to_vec();
        let values = [u32_at(&h, 24), u32_at(&h, 20), u32_at(&h, 42)];
        for k in [20, 24, 42] {
            h[k..k + 4].copy_from_slice(&[0xFF; 4]);
        }
        h[30..32].copy_from_slice(&((x + 28) as u16).to_le_bytes());
        let mut extra = vec![1, 0, 24, 0];
        for v in values {
            extra.extend_from_slice(&v.to_le_bytes());
        }
        h.splice(46 + n + x..46 + n + x, extra);
        out.extend_from_slice(&h);
        at += 46 + n + x + c;
    }
    let (size, record) = ((out.len() - cd) as u64, out.len() as u64);
    out.extend_from_slice(b"PK\x06\x06");
    out.extend_from_slice(&44u64.to_le_bytes());
    out.extend_from_slice(&[45, 0, 45, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
    for v in [count as u64, count as u64, size, cd as u64] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(b"PK\x06\x07\0\0\0\0");
    out.extend_from_slice(&record.to_le_bytes());
    out.extend_from_slice(&1u32.to_le_bytes());
    out.extend_from_slice(b"PK\x05\x06\0\0\0\0");
    out.extend_from_slice(&[0xFF; 12]);
    out.extend_from_slice(&[0; 2]);
    out
}

#[test]
fn rust_and_reference_readers_give_the_same_outcome_on_mutants() {
    let dir = std::env::temp_dir().join(format!("flexbody-agree-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("broken")).expect("mkdir");
    std::fs::create_dir_all(dir.join("compat")).expect("mkdir");
    let seeds = seeds();
    let mut state = 0x2545f4914f6cdd1du64;
    let (mut refused, mut accepted) = (0, 0);
    // The golden files in Zip64 form (read as they are), then the mutants.
    let golden = 7; // golden/v1.0 (2 files), v1.2, v1.4, v1.6, v1.8, v1.9
    for k in 0..golden + 600 {
        let bytes = if k < golden {
            zip64_form(&seeds[k])
        } else if k % 3 == 0 {
            entry_mutant(&mut state, &seeds[k % seeds.len()])
        } else {
            container_mutant(&mut state, &seeds[k % seeds.len()])
        };
        let stem = format!("m{k:04}");
        match flexbody_reader::from_bytes_with_manifest(&bytes, &Default::default()) {
            Err(e) if k < golden => panic!("golden file {k} in Zip64 form is refused: {e}"),
            Err(e) => {
                let expect = serde_json::json!({"variant": e.variant(), "message": ""});
                std::fs::write(
                    dir.join(format!("broken/{stem}.expect")),
                    expect.to_string(),
                )
                .expect("write");
                std::fs::write(dir.join(format!("broken/{stem}.flexbody")), &bytes).expect("write");
                refused += 1;
            }
            Ok((body, manifest)) => {
                let summary = flexbody::inspect::summarize(&body, &manifest);
                std::fs::write(
                    dir.join(format!("compat/{stem}.json")),
                    serde_json::to_vec(&summary).expect("json"),
                )
                .expect("write");
                std::fs::write(dir.join(format!("compat/{stem}.flexbody")), &bytes).expect("write");
                accepted += 1;
            }
        }
    }
    let out = std::process::Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("format-spec/reference_reader.py"))
        .arg("--check-fixtures")
        .arg(&dir)
        .output()
        .expect("python3 runs");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let failures: Vec<&str> = text.lines().filter(|l| !l.starts_with("ok")).collect();
    println!("{refused} refused, {accepted} accepted by the Rust reader");
    assert!(
        out.status.success(),
        "the readers differ:\n{}\n{}",
        failures.join("\n"),
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        refused > 300 && accepted > 20,
        "{refused} refused, {accepted} accepted"
    );
}

/// The broken and compat fixtures of issue 49 (round 3: SPEC §6 rules 13 and 15, §7.1 step 1,
/// §9): each is on disk, the Rust reader refuses it with its `.expect` variant (or accepts it),
/// and the reference reader agrees on every fixture (`--check-fixtures fixtures`).
#[test]
fn round_3_fixtures_are_read_alike_by_both_readers() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    let broken = [
        "recipe_preload_max_displacement_1e999",
        "recipe_preload_max_displacement_negative",
        "recipe_preload_buckling_factor_1e999",
        "recipe_preload_buckling_factor_zero",
        "recipe_geometric_stiffness_option_without_entry",
        "recipe_geometric_stiffness_entry_without_option",
        "recipe_preload_with_geometric_stiffness",
        "recipe_preload_on_free_body",
        "normal_modes_removed_without_residual_vectors",
        "geometric_held_with_rigid_mode",
        "geometric_acceleration_not_zero_under_inertia_relief",
        "central_header_past_directory_end",
    ];
    for stem in broken {
        let bytes = std::fs::read(root.join(format!("broken/{stem}.flexbody"))).expect(stem);
        let expect: serde_json::Value = serde_json::from_slice(
            &std::fs::read(root.join(format!("broken/{stem}.expect"))).expect(stem),
        )
        .expect("expect json");
        let err = flexbody_reader::from_bytes(&bytes).expect_err(stem);
        assert_eq!(err.variant(), expect["variant"], "{stem}: {err}");
        let fragment = expect["message"].as_str().expect("message");
        assert!(err.to_string().contains(fragment), "{stem}: {err}");
    }
    for golden in [
        "compat/recipe_empty_optional_list",
        "golden/v1.7/three_node_chain_geometric_stiffness",
        "golden/v1.8/three_node_chain_geometric_stiffness",
    ] {
        let bytes = std::fs::read(root.join(format!("{golden}.flexbody"))).expect(golden);
        flexbody_reader::from_bytes(&bytes).unwrap_or_else(|e| panic!("{golden}: {e}"));
    }
    let out = std::process::Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("format-spec/reference_reader.py"))
        .arg("--check-fixtures")
        .arg(&root)
        .output()
        .expect("python3 runs");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    for stem in broken {
        assert!(
            text.lines()
                .any(|l| l.starts_with("ok") && l.contains(&format!("broken/{stem}.flexbody"))),
            "the reference reader does not refuse {stem} alike:\n{text}"
        );
    }
    assert!(out.status.success(), "the readers differ:\n{text}");
}

/// The fixtures of format 1.9 (issue 46: `eigen_residuals.bin`, SPEC §5.17 and §6 rule 16):
/// the golden file reads in both readers, each broken file is refused by the Rust reader with
/// its `.expect` variant and message and by the reference reader with the same variant.
#[test]
fn eigen_residual_fixtures_are_read_alike_by_both_readers() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    let broken = [
        "eigen_residuals_wrong_kind",
        "eigen_residuals_scale_zero",
        "eigen_residuals_residual_wrong_length",
        "eigen_residuals_fewer_than_modes",
        "eigen_residuals_residual_nan",
        "eigen_residuals_residual_negative",
        "eigen_residuals_inertia_below_stored",
        "eigen_residuals_truncated",
        "eigen_residuals_unknown_solver",
        "eigen_residuals_in_1_8_file",
    ];
    for stem in broken {
        let bytes = std::fs::read(root.join(format!("broken/{stem}.flexbody"))).expect(stem);
        let expect: serde_json::Value = serde_json::from_slice(
            &std::fs::read(root.join(format!("broken/{stem}.expect"))).expect(stem),
        )
        .expect("expect json");
        let err = flexbody_reader::from_bytes(&bytes).expect_err(stem);
        assert_eq!(err.variant(), expect["variant"], "{stem}: {err}");
        let fragment = expect["message"].as_str().expect("message");
        assert!(err.to_string().contains(fragment), "{stem}: {err}");
    }
    let golden = "golden/v1.9/three_node_chain_eigen_residuals";
    let bytes = std::fs::read(root.join(format!("{golden}.flexbody"))).expect(golden);
    let body = flexbody_reader::from_bytes(&bytes).unwrap_or_else(|e| panic!("{golden}: {e}"));
    assert_eq!((body.version.major, body.version.minor), (1, 9));
    let out = std::process::Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("format-spec/reference_reader.py"))
        .arg("--check-fixtures")
        .arg(&root)
        .output()
        .expect("python3 runs");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    for stem in broken {
        assert!(
            text.lines()
                .any(|l| l.starts_with("ok") && l.contains(&format!("broken/{stem}.flexbody"))),
            "the reference reader does not refuse {stem} alike:\n{text}"
        );
    }
    assert!(
        text.lines()
            .any(|l| l.starts_with("ok") && l.contains(&format!("{golden}.flexbody"))),
        "the reference reader does not read {golden} alike:\n{text}"
    );
}
