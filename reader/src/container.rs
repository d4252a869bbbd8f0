//! The manifest and the reading procedure of SPEC.md §7.1: manifest checks, then every listed
//! entry read (by [`crate::archive`]) and checked against its SHA-256.
use std::collections::BTreeMap;

use crate::archive::{self, Archive};
use crate::codec::{self, Manifest, ENTRIES, FORMAT_NAME, MANIFEST};
use crate::error::ReadError;
use crate::json::Json;
use crate::limits::ReadLimits;
use crate::FORMAT_VERSION;

/// The checked manifest and the verified bytes of every listed entry.
pub struct Container {
    /// The parsed manifest.
    pub manifest: Manifest,
    /// Entry name → verified uncompressed bytes (known and unknown-optional entries).
    pub entries: BTreeMap<String, Vec<u8>>,
}

/// The required flag and the introducing minor version of a known entry.
fn known(name: &str) -> Option<(bool, u32)> {
    ENTRIES
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|&(_, r, minor)| (r, minor))
}

fn limit_err(entry: &str, what: &str, value: u64, limit: u64) -> ReadError {
    ReadError::LimitExceeded {
        entry: entry.to_string(),
        what: what.to_string(),
        value,
        limit,
    }
}

/// SPEC §7.1 step 3: `format` and a newer major `version` are judged before any other member
/// is looked at (a newer major version may change them).
fn format_and_version_first(v: &Json) -> Result<(), ReadError> {
    if let Some(Json::String(f)) = v.get("format") {
        if f != FORMAT_NAME {
            return Err(ReadError::WrongFormat { found: f.clone() });
        }
    }
    let part = |k: &str| {
        v.get("version")
            .and_then(|x| x.get(k))
            .and_then(Json::as_u64)
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
        match known(&e.name) {
            Some((req, _)) if req != e.required => {
                return Err(ReadError::Manifest {
                    detail: format!("entry {}: required flag must be {req} in v1", e.name),
                })
            }
            Some((_, minor)) if minor > m.version.minor => {
                return Err(ReadError::Manifest {
                    detail: format!(
                        "entry {} came with format 1.{minor}, but the file says {}.{}",
                        e.name, m.version.major, m.version.minor
                    ),
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
    for (name, required, _) in ENTRIES {
        if required && !seen.contains(name) {
            return Err(ReadError::MissingEntry {
                entry: name.to_string(),
                rule: "required in v1 but not listed in manifest.json".into(),
            });
        }
    }
    Ok(())
}

/// Opens the container, checks the manifest, reads and verifies every listed entry, in the
/// order of SPEC §7.1.
pub fn open(bytes: &[u8], limits: &ReadLimits) -> Result<Container, ReadError> {
    let zip = archive::open(bytes, limits.max_entries.saturating_add(1))?;
    let manifest = read_manifest(&zip, limits, bytes.len() as u64)?;
    // Step 5, before any payload is read: nothing unlisted, nothing listed missing.
    if let Some(e) = zip
        .entries
        .iter()
        .find(|z| z.name != MANIFEST && !manifest.entries.iter().any(|e| e.name == z.name))
    {
        return Err(ReadError::UnlistedEntry {
            entry: e.name.clone(),
        });
    }
    if let Some(e) = manifest.entries.iter().find(|e| zip.get(&e.name).is_none()) {
        return Err(ReadError::MissingEntry {
            entry: e.name.clone(),
            rule: "listed in manifest.json but absent from the container".into(),
        });
    }
    let mut entries = BTreeMap::new();
    for e in &manifest.entries {
        // Step 5 found every listed entry.
        let Some(z) = zip.get(&e.name) else { continue };
        let data = zip.read(z, e.size)?;
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

/// SPEC §7.1 steps 2–4: `manifest.json` found, read, parsed and checked.
fn read_manifest(
    zip: &Archive,
    limits: &ReadLimits,
    file_bytes: u64,
) -> Result<Manifest, ReadError> {
    let Some(z) = zip.get(MANIFEST) else {
        return Err(ReadError::MissingEntry {
            entry: MANIFEST.into(),
            rule: "every flexbody file starts with manifest.json".into(),
        });
    };
    if z.size > limits.max_manifest_bytes {
        return Err(limit_err(
            MANIFEST,
            "size (bytes)",
            z.size,
            limits.max_manifest_bytes,
        ));
    }
    let raw = zip.read(z, z.size)?;
    let invalid = |e: &dyn std::fmt::Display| ReadError::Manifest {
        detail: format!("not valid manifest JSON: {e}"),
    };
    let text = std::str::from_utf8(&raw).map_err(|e| ReadError::Manifest {
        detail: format!("not UTF-8: {e}"),
    })?;
    let value = crate::json::parse(text).map_err(|e| invalid(&e))?;
    format_and_version_first(&value)?;
    let manifest: Manifest = crate::json::from_json(&value).map_err(|e| invalid(&e))?;
    check_manifest(&manifest, limits, file_bytes)?;
    Ok(manifest)
}
