//! The input budget of every importer, stated in one place: how large a file may be, how many
//! ids one set, range or card may expand to, and which reals are accepted. Every limit is
//! checked *before* the memory it guards is allocated, and its error names the file, the line
//! and the card/keyword that asked for too much.
//!
//! | limit | value | applies to |
//! |---|---|---|
//! | [`MAX_FILE_BYTES`] | 8 GiB | every file an importer reads (streamed, stops at the cap) |
//! | [`expansion_limit`] | file bytes, at least 2²⁰, at most 2²⁸ | ids one Abaqus set (all its lines) or one Nastran card (all its `THRU` ranges) expands to |
//! | [`total_expansion_limit`] | 16 × [`expansion_limit`] | ids all sets / all cards of a deck expand to |
//! | Gmsh counts | a count × its smallest encoding ≤ the bytes that remain | `$Nodes`, `$Elements`, `$Entities` |
//! | Matrix Market entries | count × 6 bytes ≤ the bytes that remain | the size line's entry count |
//! | [`MAX_ABS_REAL`] | 1e150 | every real read: NaN, ±∞ and larger magnitudes are errors |
//!
//! A set cannot usefully hold more ids than the file defines nodes or elements, and each of
//! those takes at least a byte of the file, so the file's size bounds every legitimate
//! expansion; the floor of 2²⁰ keeps small hand-written decks with wide `GENERATE` ranges valid.

use std::io::Read;
use std::path::Path;

use super::error::{parse_err, ImportError};

/// Largest file (bytes) an importer reads; reading stops with an error past it.
pub const MAX_FILE_BYTES: u64 = 8 << 30;

/// Largest magnitude of a real any importer accepts (NaN and ±∞ are refused too): the squares
/// and products the assembly forms stay finite.
pub const MAX_ABS_REAL: f64 = 1e150;

/// Ids one Abaqus set (over all its data lines) or one Nastran card (over all its `THRU`
/// ranges) may expand to, for a deck of `bytes` bytes in all.
pub fn expansion_limit(bytes: u64) -> u64 {
    bytes.clamp(1 << 20, 1 << 28)
}

/// Ids all sets, or all cards, of one deck may expand to together.
pub fn total_expansion_limit(bytes: u64) -> u64 {
    16 * expansion_limit(bytes)
}

/// `v` if it is finite and |v| < [`MAX_ABS_REAL`].
pub(crate) fn in_range(v: f64) -> Option<f64> {
    (v.abs() < MAX_ABS_REAL).then_some(v)
}

/// The message for a real field `s` that failed to parse; `parsed` is what an unbounded parse
/// made of it (`Some` when only the range check failed).
pub(crate) fn bad_number(s: &str, parsed: Option<f64>) -> String {
    let s = s.trim();
    match parsed {
        Some(v) if !v.is_finite() || v.abs() >= MAX_ABS_REAL => format!(
            "bad number '{s}': {} (every real must be finite with |x| < {MAX_ABS_REAL:e})",
            if v.is_nan() {
                "not a number".to_owned()
            } else if v.is_infinite() {
                "infinite".to_owned()
            } else {
                format!("{v:e} is out of range")
            }
        ),
        _ => format!("bad number '{s}'"),
    }
}

/// What a file must look like, checked while streaming so junk stops the read early.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Content {
    /// A text file: a NUL byte is an error at once (names its line).
    Text,
    /// A Gmsh mesh (may hold binary blocks): its first non-blank byte must be `$`.
    Mesh,
}

/// Read `path` whole, streaming in chunks: stops with an error naming the file at
/// [`MAX_FILE_BYTES`] (so `/dev/zero` or a runaway pipe cannot exhaust memory) and at the
/// first byte `content` rules out.
pub(crate) fn read_bounded(path: &Path, content: Content) -> Result<Vec<u8>, ImportError> {
    read_bounded_with(path, content, MAX_FILE_BYTES)
}

/// [`read_bounded`] with an explicit size cap.
pub(crate) fn read_bounded_with(
    path: &Path,
    content: Content,
    cap: u64,
) -> Result<Vec<u8>, ImportError> {
    let file = path.display().to_string();
    let io = |source| ImportError::Io {
        file: file.clone(),
        source,
    };
    let f = std::fs::File::open(path).map_err(io)?;
    let meta_len = f.metadata().map(|m| m.len()).unwrap_or(0);
    let too_big = |at: u64| {
        parse_err(
            &file,
            1,
            "file",
            format!(
                "{at} bytes or more: larger than the input limit of {cap} bytes (flexbody::import::budget::MAX_FILE_BYTES)"
            ),
        )
    };
    if meta_len > cap {
        return Err(too_big(meta_len));
    }
    let mut out: Vec<u8> = Vec::with_capacity(meta_len as usize);
    let mut reader = f.take(cap + 1);
    let mut chunk = vec![0u8; 1 << 20];
    let mut lines = 1usize;
    let mut seen_start = false;
    loop {
        let n = match reader.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(io(e)),
        };
        let part = &chunk[..n];
        match content {
            Content::Text => {
                if let Some(pos) = part.iter().position(|&b| b == 0) {
                    let line = lines + part[..pos].iter().filter(|&&b| b == b'\n').count();
                    return Err(parse_err(
                        &file,
                        line,
                        "file",
                        "binary data (NUL byte) in a text model file",
                    ));
                }
                lines += part.iter().filter(|&&b| b == b'\n').count();
            }
            Content::Mesh if !seen_start => {
                if let Some(&b) = part.iter().find(|b| !b.is_ascii_whitespace()) {
                    if b != b'$' {
                        let line = 1 + out.iter().filter(|&&b| b == b'\n').count();
                        return Err(parse_err(
                            &file,
                            line,
                            "file",
                            "not a Gmsh mesh: the file does not start with $MeshFormat",
                        ));
                    }
                    seen_start = true;
                }
            }
            Content::Mesh => {}
        }
        if out.len() as u64 + n as u64 > cap {
            return Err(too_big(out.len() as u64 + n as u64));
        }
        out.extend_from_slice(part);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_follow_the_file_size_between_floor_and_cap() {
        assert_eq!(expansion_limit(10), 1 << 20);
        assert_eq!(expansion_limit(5_000_000), 5_000_000);
        assert_eq!(expansion_limit(u64::MAX), 1 << 28);
        assert_eq!(total_expansion_limit(10), 16 << 20);
    }

    #[test]
    fn numbers_out_of_range_say_why() {
        assert_eq!(in_range(1e149), Some(1e149));
        assert_eq!(in_range(-1e150), None);
        assert_eq!(in_range(f64::NAN), None);
        assert!(bad_number("inf", Some(f64::INFINITY)).contains("infinite"));
        assert!(bad_number("1e200", Some(1e200)).contains("1e200 is out of range"));
        assert_eq!(bad_number("x", None), "bad number 'x'");
    }

    #[test]
    fn streaming_read_stops_at_the_cap_and_at_nul() {
        let d = std::env::temp_dir().join(format!("flexbody_budget_{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let p = d.join("a.txt");
        std::fs::write(&p, b"12345678\n").unwrap();
        assert_eq!(read_bounded_with(&p, Content::Text, 9).unwrap().len(), 9);
        let e = read_bounded_with(&p, Content::Text, 8).unwrap_err();
        assert!(e.to_string().contains("input limit of 8 bytes"), "{e}");
        std::fs::write(&p, b"a\nb\n\0").unwrap();
        assert_eq!(
            read_bounded_with(&p, Content::Text, 100)
                .unwrap_err()
                .line(),
            Some(3)
        );
        std::fs::write(&p, b"\n\n junk").unwrap();
        let e = read_bounded_with(&p, Content::Mesh, 100).unwrap_err();
        assert!(e.to_string().contains("$MeshFormat"), "{e}");
    }
}
