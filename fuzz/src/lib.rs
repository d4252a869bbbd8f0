//! Helpers shared by the fuzz targets: a per-process scratch file for the importers (which read
//! paths, following includes, exactly as the CLI does) and the structure-aware rebuild of a
//! `.flexbody` container (one entry replaced, manifest size and SHA-256 rebuilt).

use std::io::{Cursor, Read, Write};
use std::path::PathBuf;

/// Writes `data` to `<scratch>/<name>` (a directory private to this process, on tmpfs when
/// `/dev/shm` exists) and returns the path.
pub fn scratch_file(name: &str, data: &[u8]) -> PathBuf {
    let base = if std::path::Path::new("/dev/shm").is_dir() {
        PathBuf::from("/dev/shm")
    } else {
        std::env::temp_dir()
    };
    let dir = base.join(format!("flexbody-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let path = dir.join(name);
    std::fs::write(&path, data).expect("scratch file");
    path
}

/// The (name, bytes) of every entry of a well-formed container, in zip order.
pub fn entries_of(file: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut zip = zip::ZipArchive::new(Cursor::new(file)).expect("seed is a zip");
    (0..zip.len())
        .map(|i| {
            let mut f = zip.by_index(i).expect("seed entry");
            let mut b = Vec::new();
            f.read_to_end(&mut b).expect("seed entry bytes");
            (f.name().as_ref().expect("seed entry name").to_string(), b)
        })
        .collect()
}

/// A container of `entries` (stored, in order), with `manifest.json`'s size and `sha256` of
/// every listed entry recomputed from the bytes (unless the manifest itself is the entry that
/// was replaced, or no longer parses as JSON).
pub fn rebuild(entries: &[(String, Vec<u8>)], keep_manifest: bool) -> Vec<u8> {
    let mut entries = entries.to_vec();
    if !keep_manifest {
        if let Some(mi) = entries.iter().position(|(n, _)| n == "manifest.json") {
            if let Ok(mut v) = serde_json::from_slice::<serde_json::Value>(&entries[mi].1) {
                if let Some(list) = v.get_mut("entries").and_then(|e| e.as_array_mut()) {
                    for item in list {
                        let Some(name) = item.get("name").and_then(|n| n.as_str()) else {
                            continue;
                        };
                        if let Some((_, b)) = entries.iter().find(|(n, _)| n == name) {
                            item["size"] = serde_json::json!(b.len());
                            item["sha256"] =
                                serde_json::json!(flexbody_reader::codec::sha256_hex(b));
                        }
                    }
                }
                entries[mi].1 = serde_json::to_vec_pretty(&v).expect("json");
            }
        }
    }
    let mut out = Cursor::new(Vec::new());
    {
        let mut zw = zip::ZipWriter::new(&mut out);
        let opts = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Stored);
        for (name, bytes) in &entries {
            zw.start_file(name.as_str(), opts).expect("zip entry");
            zw.write_all(bytes).expect("zip write");
        }
        zw.finish().expect("zip finish");
    }
    out.into_inner()
}

/// The seed containers the structure-aware target mutates (golden files of each minor version).
pub const BASES: [&[u8]; 4] = [
    include_bytes!("../../fixtures/golden/v1.0/three_node_chain.flexbody"),
    include_bytes!("../../fixtures/golden/v1.0/twenty_node_chain.flexbody"),
    include_bytes!("../../fixtures/golden/v1.1/three_node_chain_lines.flexbody"),
    include_bytes!("../../fixtures/golden/v1.2/three_node_chain_recipe.flexbody"),
];

/// The structure-aware mutation: `data[0]` picks the base file and the entry, `data[1]` the
/// mode (replace the entry's bytes, or splice the fuzz bytes into the middle of it), the rest
/// are the new bytes. Returns the rebuilt container.
pub fn structured(data: &[u8]) -> Option<Vec<u8>> {
    let (&sel, rest) = data.split_first()?;
    let (&mode, bytes) = rest.split_first()?;
    static PARSED: std::sync::OnceLock<Vec<Vec<(String, Vec<u8>)>>> = std::sync::OnceLock::new();
    let parsed = PARSED.get_or_init(|| BASES.iter().map(|b| entries_of(b)).collect());
    let mut entries = parsed[usize::from(sel & 3)].clone();
    let i = usize::from(sel >> 2) % entries.len();
    let keep_manifest = entries[i].0 == "manifest.json";
    let old = std::mem::take(&mut entries[i].1);
    entries[i].1 = match mode % 4 {
        0 => bytes.to_vec(),
        // Overwrite in place from an offset (the length prefixes stay meaningful).
        1 => {
            let mut v = old.clone();
            let at = if v.is_empty() {
                0
            } else {
                usize::from(mode) % v.len()
            };
            for (k, b) in bytes.iter().enumerate() {
                match v.get_mut(at + k) {
                    Some(slot) => *slot = *b,
                    None => v.push(*b),
                }
            }
            v
        }
        // Truncate to the fuzz bytes' length, then append them.
        2 => {
            let mut v = old[..old.len().min(bytes.len())].to_vec();
            v.extend_from_slice(bytes);
            v
        }
        // A new optional entry besides the others (the name from the first bytes).
        _ => {
            let cut = bytes
                .iter()
                .position(|&b| b == 0)
                .unwrap_or(bytes.len().min(16));
            let name = String::from_utf8_lossy(&bytes[..cut]).into_owned();
            entries[i].1 = old;
            if name.is_empty() || entries.iter().any(|(n, _)| *n == name) {
                return Some(rebuild(&entries, false));
            }
            entries.push((name, bytes[cut..].to_vec()));
            if let Some(mi) = entries.iter().position(|(n, _)| n == "manifest.json") {
                if let Ok(mut v) = serde_json::from_slice::<serde_json::Value>(&entries[mi].1) {
                    if let Some(list) = v.get_mut("entries").and_then(|e| e.as_array_mut()) {
                        let n = entries.last().expect("pushed").0.clone();
                        list.push(serde_json::json!({
                            "name": n, "size": 0, "sha256": "", "required": mode & 0x80 != 0
                        }));
                    }
                    entries[mi].1 = serde_json::to_vec(&v).expect("json");
                }
            }
            return Some(rebuild(&entries, false));
        }
    };
    Some(rebuild(&entries, keep_manifest))
}
