//! The zip container read by the one procedure of SPEC.md §7.1 (steps 1 and 6), byte by byte:
//! the end record found by its exact place, the central directory walked from it, each entry's
//! data found through its local header, inflated at most one byte beyond its declared size and
//! checked against the directory's CRC-32. A zip library's recovery heuristics (earlier end
//! records, sizes taken from elsewhere) would let two readers see two different files in one.
//!
//! Offsets follow PKWARE APPNOTE 6.3: end of central directory 4.3.16, Zip64 end record and
//! locator 4.3.14–15, central directory header 4.3.12, local header 4.3.7, Zip64 extra 4.5.3.
use flate2::{Crc, Decompress, FlushDecompress, Status};

use crate::error::ReadError;

const EOCD: [u8; 4] = *b"PK\x05\x06";
const ZIP64_LOCATOR: [u8; 4] = *b"PK\x06\x07";
const ZIP64_EOCD: [u8; 4] = *b"PK\x06\x06";
const CENTRAL: [u8; 4] = *b"PK\x01\x02";
const LOCAL: [u8; 4] = *b"PK\x03\x04";
/// General-purpose flag bits with no meaning in v1: 0 and 6 (encryption), 5 (patched data).
const REFUSED_FLAGS: u16 = 1 | 1 << 5 | 1 << 6;

/// One entry as the central directory describes it.
#[derive(Debug, Clone)]
pub(crate) struct ZipEntry {
    /// The name (UTF-8).
    pub name: String,
    flags: u16,
    method: u16,
    crc32: u32,
    compressed: u64,
    /// Uncompressed size.
    pub size: u64,
    /// Offset of the local header in the file (the archive offset added).
    local: u64,
}

/// The entries of a container, in central-directory order.
pub(crate) struct Archive<'a> {
    bytes: &'a [u8],
    /// Every entry, names unique.
    pub entries: Vec<ZipEntry>,
}

fn not_zip(detail: impl Into<String>) -> ReadError {
    ReadError::NotZip {
        detail: detail.into(),
    }
}

fn damaged(entry: &str, detail: impl Into<String>) -> ReadError {
    ReadError::Container {
        entry: entry.to_string(),
        detail: detail.into(),
    }
}

/// Little-endian reads that return `None` past the end of the file.
fn le<const N: usize>(b: &[u8], at: u64) -> Option<u64> {
    let at = usize::try_from(at).ok()?;
    let s: [u8; N] = b.get(at..at.checked_add(N)?)?.try_into().ok()?;
    Some(s.iter().rev().fold(0u64, |v, &x| v << 8 | u64::from(x)))
}

fn slice(b: &[u8], at: u64, len: u64) -> Option<&[u8]> {
    let at = usize::try_from(at).ok()?;
    b.get(at..at.checked_add(usize::try_from(len).ok()?)?)
}

/// SPEC §7.1 step 1: the end record is the last signature, within the last 22 + 65,535 bytes,
/// whose comment length reaches exactly the end of the file.
fn find_end(b: &[u8]) -> Result<u64, ReadError> {
    let last = b
        .len()
        .checked_sub(22)
        .ok_or_else(|| not_zip("shorter than an end-of-central-directory record"))?;
    (last.saturating_sub(65_535)..=last)
        .rev()
        .find(|&e| {
            b[e..e + 4] == EOCD
                && usize::from(u16::from_le_bytes([b[e + 20], b[e + 21]])) == last - e
        })
        .map(|e| e as u64)
        .ok_or_else(|| not_zip("no end-of-central-directory record ends the file"))
}

/// (entry count, directory size, directory offset, where the end records begin).
fn directory_location(b: &[u8], e: u64) -> Result<(u64, u64, u64, u64), ReadError> {
    let locator = e.checked_sub(20);
    let is_zip64 = locator.and_then(|l| slice(b, l, 4)) == Some(&ZIP64_LOCATOR[..]);
    if !is_zip64 {
        let bad = || not_zip("damaged end-of-central-directory record");
        let f16 = |at| le::<2>(b, e + at).ok_or_else(bad);
        let (disk, cd_disk, here, total) = (f16(4)?, f16(6)?, f16(8)?, f16(10)?);
        if disk != 0 || cd_disk != 0 || here != total {
            return Err(not_zip("a multi-disk archive (no meaning in v1)"));
        }
        let size = le::<4>(b, e + 12).ok_or_else(bad)?;
        let offset = le::<4>(b, e + 16).ok_or_else(bad)?;
        return Ok((total, size, offset, e));
    }
    // Zip64: the 56-byte end record right before the locator replaces the three fields.
    let bad64 = || not_zip("damaged Zip64 end-of-central-directory record or locator");
    let l = locator.ok_or_else(bad64)?;
    let r = l.checked_sub(56).ok_or_else(bad64)?;
    let g = |at: u64, n: usize| match n {
        4 => le::<4>(b, at),
        _ => le::<8>(b, at),
    };
    if slice(b, r, 4) != Some(&ZIP64_EOCD[..]) || g(r + 4, 8) != Some(44) {
        return Err(bad64());
    }
    let disks_ok = g(l + 4, 4) == Some(0)
        && g(l + 16, 4).is_some_and(|d| d <= 1)
        && g(r + 16, 4) == Some(0)
        && g(r + 20, 4) == Some(0);
    let (here, total) = (
        g(r + 24, 8).ok_or_else(bad64)?,
        g(r + 32, 8).ok_or_else(bad64)?,
    );
    if !disks_ok || here != total {
        return Err(not_zip("a multi-disk archive (no meaning in v1)"));
    }
    let (size, offset) = (
        g(r + 40, 8).ok_or_else(bad64)?,
        g(r + 48, 8).ok_or_else(bad64)?,
    );
    Ok((total, size, offset, r))
}

/// The Zip64 extra field (id 1) of a central header: the 8-byte values of the fields that hold
/// 0xFFFFFFFF, in the order uncompressed size, compressed size, local header offset. The first
/// record with id 1 is read; the records after it are not looked at (SPEC §7.1 step 1).
fn zip64_values(extra: &[u8], wanted: usize) -> Option<Vec<u64>> {
    let mut at = 0u64;
    while (at as usize) < extra.len() {
        let (id, len) = (le::<2>(extra, at)?, le::<2>(extra, at + 2)?);
        let data = slice(extra, at + 4, len)?;
        if id == 1 {
            return (0..wanted).map(|k| le::<8>(data, 8 * k as u64)).collect();
        }
        at += 4 + len;
    }
    None
}

/// SPEC §7.1 step 1: the central directory, walked from the end record. At most
/// `max_entries` entries (counted before any is read), names UTF-8 and unique.
pub(crate) fn open(bytes: &[u8], max_entries: u64) -> Result<Archive<'_>, ReadError> {
    let e = find_end(bytes)?;
    let (count, size, offset, end) = directory_location(bytes, e)?;
    let start = end
        .checked_sub(size)
        .filter(|&s| s >= offset)
        .ok_or_else(|| not_zip("the central directory does not fit before its end record"))?;
    let archive_offset = start - offset;
    if count > max_entries {
        return Err(ReadError::LimitExceeded {
            entry: crate::codec::MANIFEST.into(),
            what: "zip entry count".into(),
            value: count,
            limit: max_entries,
        });
    }
    let mut entries: Vec<ZipEntry> = Vec::with_capacity(count.min(1024) as usize);
    let mut at = start;
    for i in 0..count {
        let bad = || not_zip(format!("damaged central directory header #{i}"));
        if slice(bytes, at, 4) != Some(&CENTRAL[..]) {
            return Err(bad());
        }
        let f = |k: u64, n: usize| match n {
            2 => le::<2>(bytes, at + k),
            _ => le::<4>(bytes, at + k),
        };
        let field = |k, n| f(k, n).ok_or_else(bad);
        let (flags, method, crc32) = (field(8, 2)?, field(10, 2)?, field(16, 4)?);
        let (mut compressed, mut usize_, mut local) = (field(20, 4)?, field(24, 4)?, field(42, 4)?);
        let (n, x, c) = (field(28, 2)?, field(30, 2)?, field(32, 2)?);
        let name = slice(bytes, at + 46, n).ok_or_else(bad)?;
        let extra = slice(bytes, at + 46 + n, x).ok_or_else(bad)?;
        slice(bytes, at + 46 + n + x, c).ok_or_else(bad)?;
        // the header lies inside the directory, not only inside the file (SPEC §7.1 step 1)
        if at + 46 + n + x + c > end {
            return Err(not_zip(format!(
                "central directory header #{i} runs past the end of the directory"
            )));
        }
        let sentinel = 0xFFFF_FFFF;
        let wanted = [usize_, compressed, local]
            .iter()
            .filter(|&&v| v == sentinel)
            .count();
        if wanted > 0 {
            let v = zip64_values(extra, wanted).ok_or_else(bad)?;
            let mut v = v.into_iter();
            for slot in [&mut usize_, &mut compressed, &mut local] {
                if *slot == sentinel {
                    *slot = v.next().ok_or_else(bad)?;
                }
            }
        }
        let name = std::str::from_utf8(name)
            .map_err(|_| not_zip(format!("entry #{i} has a name that is not UTF-8")))?
            .to_string();
        entries.push(ZipEntry {
            name,
            flags: flags as u16,
            method: method as u16,
            crc32: crc32 as u32,
            compressed,
            size: usize_,
            local: local.checked_add(archive_offset).ok_or_else(bad)?,
        });
        at += 46 + n + x + c;
    }
    let mut seen = std::collections::BTreeSet::new();
    if let Some(dup) = entries.iter().find(|e| !seen.insert(e.name.as_str())) {
        return Err(ReadError::DuplicateEntry {
            entry: dup.name.clone(),
        });
    }
    Ok(Archive { bytes, entries })
}

/// Inflates raw deflate `data` into at most `cap` bytes: the output, cut at `cap` when the
/// stream holds more; an invalid stream or one that ends with its data unfinished is an error.
fn inflate(data: &[u8], cap: usize) -> Result<Vec<u8>, String> {
    let mut d = Decompress::new(false);
    let mut out = Vec::with_capacity(cap);
    loop {
        let (read, written) = (d.total_in(), d.total_out());
        // total_in never exceeds the input given, so the slice start lies within `data`.
        let rest = &data[(d.total_in() as usize).min(data.len())..];
        let status = d
            .decompress_vec(rest, &mut out, FlushDecompress::None)
            .map_err(|e| format!("invalid deflate data ({e})"))?;
        if status == Status::StreamEnd || out.len() == cap {
            return Ok(out);
        }
        if d.total_in() == read && d.total_out() == written {
            return Err("the deflate data ends before its stream does".into());
        }
    }
}

impl Archive<'_> {
    /// The entry named `name`.
    pub fn get(&self, name: &str) -> Option<&ZipEntry> {
        self.entries.iter().find(|e| e.name == name)
    }

    /// SPEC §7.1 step 6 (step 2 for the manifest, with `declared` its directory size): the
    /// verified uncompressed bytes of `e`, whose manifest size is `declared`.
    pub fn read(&self, e: &ZipEntry, declared: u64) -> Result<Vec<u8>, ReadError> {
        let name = e.name.as_str();
        if e.flags & REFUSED_FLAGS != 0 {
            return Err(damaged(
                name,
                format!(
                    "flags {:#06x}: encrypted or patched data has no meaning in v1",
                    e.flags
                ),
            ));
        }
        if e.method != 0 && e.method != 8 {
            return Err(ReadError::Compression {
                entry: name.into(),
                method: e.method.to_string(),
            });
        }
        let mismatch = |actual| ReadError::SizeMismatch {
            entry: name.into(),
            declared,
            actual,
        };
        // The directory's own size must agree before anything is inflated: a bomb that
        // declares a small size there (or a large one) is refused without inflating it.
        if e.size != declared {
            return Err(mismatch(e.size));
        }
        let b = self.bytes;
        let head = |k: u64| le::<2>(b, e.local + k);
        let (n, x) = match (slice(b, e.local, 4), head(26), head(28)) {
            (Some(sig), Some(n), Some(x)) if sig == LOCAL => (n, x),
            _ => return Err(damaged(name, "no local header where the directory points")),
        };
        if slice(b, e.local + 30, n) != Some(e.name.as_bytes()) {
            return Err(damaged(name, "the local header names another entry"));
        }
        let raw = slice(b, e.local + 30 + n + x, e.compressed)
            .ok_or_else(|| damaged(name, "the entry's data runs past the end of the file"))?;
        // Capacity one byte beyond the declared size, trusted only because the caller checked
        // the declared size against the limits (and the expansion cap) and the directory agrees.
        let cap = usize::try_from(declared.saturating_add(1)).unwrap_or(usize::MAX);
        let data = if e.method == 0 {
            raw[..raw.len().min(cap)].to_vec()
        } else {
            inflate(raw, cap).map_err(|d| damaged(name, d))?
        };
        if data.len() as u64 != declared {
            return Err(mismatch(if e.method == 0 {
                e.compressed
            } else {
                data.len() as u64
            }));
        }
        let mut crc = Crc::new();
        crc.update(&data);
        if crc.sum() != e.crc32 {
            return Err(damaged(
                name,
                format!(
                    "CRC-32 {:08x} differs from the directory's {:08x}",
                    crc.sum(),
                    e.crc32
                ),
            ));
        }
        Ok(data)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stored archive of `entries`, optionally behind `prefix`, with `comment`, built by hand
    /// (no zip library): local headers, central directory, end record.
    pub(super) fn build(entries: &[(&str, &[u8])], prefix: &[u8], comment: &[u8]) -> Vec<u8> {
        let mut out = prefix.to_vec();
        let mut central = Vec::new();
        for (name, data) in entries {
            let mut crc = Crc::new();
            crc.update(data);
            let local = (out.len() - prefix.len()) as u32;
            let common = |v: &mut Vec<u8>| {
                v.extend_from_slice(&[20, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
                v.extend_from_slice(&crc.sum().to_le_bytes());
                v.extend_from_slice(&(data.len() as u32).to_le_bytes());
                v.extend_from_slice(&(data.len() as u32).to_le_bytes());
                v.extend_from_slice(&(name.len() as u16).to_le_bytes());
                v.extend_from_slice(&[0, 0]);
            };
            out.extend_from_slice(&LOCAL);
            common(&mut out);
            out.extend_from_slice(name.as_bytes());
            out.extend_from_slice(data);
            central.extend_from_slice(&CENTRAL);
            central.extend_from_slice(&[20, 0]);
            common(&mut central);
            central.extend_from_slice(&[0; 10]);
            central.extend_from_slice(&local.to_le_bytes());
            central.extend_from_slice(name.as_bytes());
        }
        let offset = (out.len() - prefix.len()) as u32;
        out.extend_from_slice(&central);
        out.extend_from_slice(&EOCD);
        out.extend_from_slice(&[0; 4]);
        let n = (entries.len() as u16).to_le_bytes();
        out.extend_from_slice(&[n[0], n[1], n[0], n[1]]);
        out.extend_from_slice(&(central.len() as u32).to_le_bytes());
        out.extend_from_slice(&offset.to_le_bytes());
        out.extend_from_slice(&(comment.len() as u16).to_le_bytes());
        out.extend_from_slice(comment);
        out
    }

    fn names(b: &[u8]) -> Result<Vec<String>, ReadError> {
        Ok(open(b, 64)?.entries.into_iter().map(|e| e.name).collect())
    }

    #[test]
    fn entries_behind_a_prefix_and_a_comment_are_found_and_read() {
        let b = build(&[("a", b"xyz"), ("b", b"")], b"stub\n", b"hi");
        let ar = open(&b, 64).unwrap();
        assert_eq!(names(&b).unwrap(), ["a", "b"]);
        assert_eq!(ar.read(&ar.entries[0], 3).unwrap(), b"xyz");
        assert!(ar.read(&ar.entries[1], 0).unwrap().is_empty());
    }

    #[test]
    fn the_end_record_is_the_one_that_ends_the_file() {
        // A comment holding signatures: the true record still ends the file exactly, a false
        // one does not (its comment length points elsewhere, or it has no room for a record).
        let mut comment = EOCD.to_vec();
        comment.extend_from_slice(&[0; 16]);
        comment.extend_from_slice(&[9, 0, 0, 0, 0, 0]);
        comment.extend_from_slice(&EOCD);
        assert_eq!(names(&build(&[("a", b"1")], b"", &comment)).unwrap(), ["a"]);
        // One byte after the record: nothing ends the file.
        let mut b = build(&[("a", b"1")], b"", b"");
        b.push(0);
        assert!(matches!(names(&b), Err(ReadError::NotZip { .. })));
        assert!(matches!(
            names(b"PK\x05\x06"),
            Err(ReadError::NotZip { .. })
        ));
    }

    #[test]
    fn entry_count_is_judged_before_the_directory_is_walked() {
        let mut b = build(&[("a", b"1")], b"", b"");
        let e = b.len() - 22;
        b[e + 8..e + 12].copy_from_slice(&[0xFF, 0xFE, 0xFF, 0xFE]);
        assert!(matches!(
            open(&b, 64),
            Err(ReadError::LimitExceeded { value: 65279, .. })
        ));
    }

    #[test]
    fn zip64_end_record_and_extra_field_are_read() {
        // One stored entry whose sizes and offset live in a Zip64 extra field, and an end record
        // whose fields all point to the Zip64 end record.
        let data = b"hello";
        let mut crc = Crc::new();
        crc.update(data);
        let mut out = LOCAL.to_vec();
        out.extend_from_slice(&[45, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        out.extend_from_slice(&crc.sum().to_le_bytes());
        out.extend_from_slice(&[5, 0, 0, 0, 5, 0, 0, 0, 1, 0, 0, 0]);
        out.extend_from_slice(b"z");
        out.extend_from_slice(data);
        let cd = out.len() as u64;
        out.extend_from_slice(&CENTRAL);
        out.extend_from_slice(&[45, 0, 45, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        out.extend_from_slice(&crc.sum().to_le_bytes());
        out.extend_from_slice(&[0xFF; 8]);
        out.extend_from_slice(&[1, 0, 28, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        out.extend_from_slice(&[0xFF; 4]);
        out.extend_from_slice(b"z");
        out.extend_from_slice(&[1, 0, 24, 0]);
        for v in [5u64, 5, 0] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        let size = out.len() as u64 - cd;
        let rec = out.len() as u64;
        out.extend_from_slice(&ZIP64_EOCD);
        out.extend_from_slice(&44u64.to_le_bytes());
        out.extend_from_slice(&[45, 0, 45, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        for v in [1u64, 1, size, cd] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&ZIP64_LOCATOR);
        out.extend_from_slice(&[0; 4]);
        out.extend_from_slice(&rec.to_le_bytes());
        out.extend_from_slice(&1u32.to_le_bytes());
        out.extend_from_slice(&EOCD);
        out.extend_from_slice(&[0, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF]);
        out.extend_from_slice(&[0xFF; 8]);
        out.extend_from_slice(&[0, 0]);
        let ar = open(&out, 64).unwrap();
        assert_eq!(ar.entries[0].name, "z");
        assert_eq!(ar.read(&ar.entries[0], 5).unwrap(), data);
    }

    #[test]
    fn a_deflate_stream_longer_than_declared_is_cut_one_byte_beyond() {
        let mut c = flate2::Compress::new(flate2::Compression::new(6), false);
        let mut z = Vec::with_capacity(64);
        c.compress_vec(b"abcdef", &mut z, flate2::FlushCompress::Finish)
            .unwrap();
        assert_eq!(inflate(&z, 4).unwrap(), b"abcd");
        assert_eq!(inflate(&z, 7).unwrap(), b"abcdef");
        assert!(inflate(&z[..z.len() - 2], 7).is_err());
        assert!(inflate(&[0xFF, 0xFF], 7).is_err());
    }
}
