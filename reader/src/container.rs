//! The zip container: manifest checks, bounded entry reads, checksums (SPEC.md §2, §3, §7).
use std::collections::BTreeMap;
use std::io::{Cursor, Read};

use zip::{CompressionMethod, ZipArchive};

use crate::codec::{self, Manifest, ENTRIES, FORMAT_NAME, MANIFEST};
use crate::error::ReadError;
use crate::limits::ReadLimits;
use crate::FORMAT_VERSION;

/// The checked manifest and the verified bytes of every listed entry.
pub struct Container {
    /// The parsed manifest.
    pub manifest: Manifest,
    /// Entry name → verified uncompressed bytes (known and unknown-optional entries).
    pub entries: BTreeMap<String, Vec<u8>>,
}

fn known_required(name: &str) -> Option<bool> {
    ENTRIES.iter().find(|(n, _)| *n == name).map(|(_, r)| *r)
}

fn limit_err(entry: &str, what: &str, value: u64, limit: u64) -> ReadError {
    ReadError::LimitExceeded {
        entry: entry.to_string(),
        what: what.to_string(),
        value,
        limit,
    }
}

/// Reads one entry, refusing other compressions and reading at most `declared + 1` bytes.
fn read_entry(
    zip: &mut ZipArchive<Cursor<&[u8]>>,
    index: usize,
    name: &str,
    declared: u64,
) -> Result<Vec<u8>, ReadError> {
    let container = |e: &dyn std::fmt::Display| ReadError::Container {
        entry: name.to_string(),
        detail: e.to_string(),
    };
    let file = zip.by_index(index).map_err(|e| container(&e))?;
    // The zip directory's own size must agree before anything is decompressed: a bomb that
    // declares a small size there (or a large one) is refused without inflating it.
    if file.size() != declared {
        return Err(ReadError::SizeMismatch {
            entry: name.to_string(),
            declared,
            actual: file.size(),
        });
    }
    match file.compression() {
        CompressionMethod::Stored | CompressionMethod::Deflated => {}
        other => {
            return Err(ReadError::Compression {
                entry: name.to_string(),
                method: format!("{other:?}"),
            })
        }
    }
    // Capacity exactly the declared size, trusted only because the caller checked it against
    // the limits (including the expansion cap: total ≤ file bytes × max_expansion) and the zip
    // directory agrees: `read_to_end` then fills it without doubling and stops on a probe.
    let mut buf = Vec::with_capacity(usize::try_from(declared).unwrap_or(usize::MAX));
    let mut limited = file.take(declared.saturating_add(1));
    limited.read_to_end(&mut buf).map_err(|e| container(&e))?;
    if buf.len() as u64 != declared {
        return Err(ReadError::SizeMismatch {
            entry: name.to_string(),
            declared,
            actual: buf.len() as u64,
        });
    }
    // Drain to EOF is unnecessary: a longer entry already failed above, and the zip layer's
    // CRC-32 is superseded by the manifest's SHA-256.
    Ok(buf)
}

/// SPEC §7.1 step 3: `format` and a newer major `version` are judged before any other member
/// is looked at (a newer major version may change them).
fn format_and_version_first(v: &serde_json::Value) -> Result<(), ReadError> {
    if let Some(f) = v.get("format").and_then(|f| f.as_str()) {
        if f != FORMAT_NAME {
            return Err(ReadError::WrongFormat {
                found: f.to_string(),
            });
        }
    }
    let part = |k: &str| {
        v.get("version")
            .and_then(|x| x.get(k))
            .and_then(|x| x.as_u64())
            .and_then(|x| u32::try_from(x).ok())
    };
    if let (Some(major), Some(minor)) = (part("major"), part("minor")) {
        if major > FORMAT_VERSION.major {
            return Err(ReadError::UnsupportedVersion {
                major,
                minor,
                supported: FORMAT_VERSION.major,
            });
        }
    }
    Ok(())
}

fn check_manifest(m: &Manifest, limits: &ReadLimits, file_bytes: u64) -> Result<(), ReadError> {
    let cap = limits.expansion_cap(file_bytes);
    if m.format != FORMAT_NAME {
        return Err(ReadError::WrongFormat {
            found: m.format.clone(),
        });
    }
    if m.version.major > FORMAT_VERSION.major {
        return Err(ReadError::UnsupportedVersion {
            major: m.version.major,
            minor: m.version.minor,
            supported: FORMAT_VERSION.major,
        });
    }
    if m.version.major < 1 {
        return Err(ReadError::Manifest {
            detail: format!(
                "version {}.{} was never released",
                m.version.major, m.version.minor
            ),
        });
    }
    if m.entries.len() as u64 > limits.max_entries {
        return Err(limit_err(
            MANIFEST,
            "entry count",
            m.entries.len() as u64,
            limits.max_entries,
        ));
    }
    let mut total: u64 = 0;
    let mut seen = std::collections::BTreeSet::new();
    for e in &m.entries {
        if e.name == MANIFEST || !seen.insert(e.name.as_str()) {
            return Err(ReadError::DuplicateEntry {
                entry: e.name.clone(),
            });
        }
        let hex_ok = e.sha256.len() == 64
            && e.sha256
                .bytes()
                .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b));
        if !hex_ok {
            return Err(ReadError::Manifest {
                detail: format!("entry {}: sha256 must be 64 lowercase hex digits", e.name),
            });
        }
        match known_required(&e.name) {
            Some(req) if req != e.required => {
                return Err(ReadError::Manifest {
                    detail: format!("entry {}: required flag must be {req} in v1", e.name),
                })
            }
            None if e.required => {
                return Err(ReadError::UnknownRequiredEntry {
                    entry: e.name.clone(),
                })
            }
            _ => {}
        }
        if e.size > limits.max_entry_bytes {
            return Err(limit_err(
                &e.name,
                "declared size (bytes)",
                e.size,
                limits.max_entry_bytes,
            ));
        }
        total = total.saturating_add(e.size);
        if total > limits.max_total_bytes {
            return Err(limit_err(
                &e.name,
                "total declared size (bytes)",
                total,
                limits.max_total_bytes,
            ));
        }
        if total > cap {
            return Err(limit_err(
                &e.name,
                &format!("total declared size (bytes) of a {file_bytes}-byte file (at most {}× its size or {} bytes)", limits.max_expansion, limits.max_expansion_floor),
                total,
                cap,
            ));
        }
    }
    for (name, required) in ENTRIES {
        if required && !seen.contains(name) {
            return Err(ReadError::MissingEntry {
                entry: name.to_string(),
                rule: "required in v1 but not listed in manifest.json".into(),
            });
        }
    }
    Ok(())
}

/// The first entry name that occurs twice in the central directory (APPNOTE 4.3.12, 4.3.16),
/// read from the raw bytes: the zip layer keeps one entry per name, so duplicates would
/// otherwise pass unseen. `None` when there is none or the directory cannot be walked (the zip
/// layer then reports the damage itself).
fn duplicate_in_central_directory(bytes: &[u8]) -> Option<String> {
    let u16_at = |i: usize| -> Option<usize> {
        Some(u16::from_le_bytes(bytes.get(i..i + 2)?.try_into().ok()?) as usize)
    };
    let u32_at = |i: usize| -> Option<usize> {
        Some(u32::from_le_bytes(bytes.get(i..i + 4)?.try_into().ok()?) as usize)
    };
    // End of central directory: the last signature within 22 + 65535 bytes of the end.
    let lo = bytes.len().saturating_sub(22 + 65_535);
    let eocd = (lo..bytes.len().saturating_sub(21))
        .rev()
        .find(|&i| bytes[i..i + 4] == [0x50, 0x4b, 0x05, 0x06])?;
    let count = u16_at(eocd + 10)?;
    let mut at = u32_at(eocd + 16)?;
    let mut seen = std::collections::BTreeSet::new();
    for _ in 0..count {
        if bytes.get(at..at + 4)? != [0x50, 0x4b, 0x01, 0x02] {
            return None;
        }
        let (n, extra, comment) = (u16_at(at + 28)?, u16_at(at + 30)?, u16_at(at + 32)?);
        let name = String::from_utf8_lossy(bytes.get(at + 46..at + 46 + n)?).into_owned();
        if !seen.insert(name.clone()) {
            return Some(name);
        }
        at += 46 + n + extra + comment;
    }
    None
}

/// Opens the container, checks the manifest, reads and verifies every listed entry.
pub fn open(bytes: &[u8], limits: &ReadLimits) -> Result<Container, ReadError> {
    let mut zip = ZipArchive::new(Cursor::new(bytes)).map_err(|e| ReadError::NotZip {
        detail: e.to_string(),
    })?;
    if zip.len() as u64 > limits.max_entries.saturating_add(1) {
        return Err(limit_err(
            MANIFEST,
            "zip entry count",
            zip.len() as u64,
            limits.max_entries + 1,
        ));
    }
    if let Some(entry) = duplicate_in_central_directory(bytes) {
        return Err(ReadError::DuplicateEntry { entry });
    }
    let mut index_of: BTreeMap<String, usize> = BTreeMap::new();
    for i in 0..zip.len() {
        let name = match zip.name_for_index(i) {
            Some(Ok(n)) => n.into_owned(),
            _ => {
                return Err(ReadError::NotZip {
                    detail: format!("entry #{i} has no readable name"),
                })
            }
        };
        if index_of.insert(name.clone(), i).is_some() {
            return Err(ReadError::DuplicateEntry { entry: name });
        }
    }
    let Some(&mi) = index_of.get(MANIFEST) else {
        return Err(ReadError::MissingEntry {
            entry: MANIFEST.into(),
            rule: "every flexbody file starts with manifest.json".into(),
        });
    };
    let declared = {
        let f = zip.by_index(mi).map_err(|e| ReadError::Container {
            entry: MANIFEST.into(),
            detail: e.to_string(),
        })?;
        f.size()
    };
    if declared > limits.max_manifest_bytes {
        return Err(limit_err(
            MANIFEST,
            "size (bytes)",
            declared,
            limits.max_manifest_bytes,
        ));
    }
    let raw = read_entry(&mut zip, mi, MANIFEST, declared)?;
    let text = std::str::from_utf8(&raw).map_err(|e| ReadError::Manifest {
        detail: format!("not UTF-8: {e}"),
    })?;
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| ReadError::Manifest {
        detail: format!("not valid manifest JSON: {e}"),
    })?;
    format_and_version_first(&value)?;
    let manifest: Manifest = serde_json::from_value(value).map_err(|e| ReadError::Manifest {
        detail: format!("not valid manifest JSON: {e}"),
    })?;
    check_manifest(&manifest, limits, bytes.len() as u64)?;
    for name in index_of.keys() {
        if name != MANIFEST && !manifest.entries.iter().any(|e| &e.name == name) {
            return Err(ReadError::UnlistedEntry {
                entry: name.clone(),
            });
        }
    }
    let mut entries = BTreeMap::new();
    for e in &manifest.entries {
        let Some(&i) = index_of.get(&e.name) else {
            return Err(ReadError::MissingEntry {
                entry: e.name.clone(),
                rule: "listed in manifest.json but absent from the container".into(),
            });
        };
        let data = read_entry(&mut zip, i, &e.name, e.size)?;
        let actual = codec::sha256_hex(&data);
        if actual != e.sha256 {
            return Err(ReadError::Checksum {
                entry: e.name.clone(),
                expected: e.sha256.clone(),
                actual,
            });
        }
        entries.insert(e.name.clone(), data);
    }
    Ok(Container { manifest, entries })
}
