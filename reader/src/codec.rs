//! Entry names, the manifest, and the one fixed bincode configuration of v1 payloads.
//!
//! Layout (SPEC.md §4): little-endian; integers fixed width (u32 = 4 bytes, u64 = 8);
//! sequence and string lengths are u64; enum tags are u32 variant indices; `Option` is one
//! byte 0/1 then the value; `bool` one byte 0/1; `f64` 8 bytes IEEE-754 LE; fixed-size arrays
//! and structs are their elements in order without prefix.
use serde::{de::DeserializeOwned, Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::error::ReadError;

/// Format name in the manifest.
pub const FORMAT_NAME: &str = "flexbody-reduced-body";
/// Name of the manifest entry.
pub const MANIFEST: &str = "manifest.json";

/// Payload entries known to v1, in the fixed container order: name, required flag, and the
/// minor version that introduced the entry (a file stamped older must not hold it, SPEC §7.1).
pub const ENTRIES: [(&str, bool, u32); 19] = [
    (HEADER, true, 0),
    (NODES, true, 0),
    (FACES, true, 0),
    (NODAL_MASS, true, 0),
    (MODES, true, 0),
    (INVARIANTS, true, 0),
    (METHOD, true, 0),
    (STRESS_SHAPES, false, 0),
    (STRAIN_SHAPES, false, 0),
    (DAMPING, false, 0),
    (LINES, false, 1),
    (RECIPE, false, 2),
    (LABEL_SHARES, false, 2),
    (INTERFACES, false, 3),
    (MODAL_LOADS, false, 4),
    (STRESS_SHAPES_BOTTOM, false, 5),
    (STRAIN_SHAPES_BOTTOM, false, 5),
    (GEOMETRIC_STIFFNESS, false, 7),
    (EIGEN_RESIDUALS, false, 9),
];
/// The `.bin` records that hold strings: each, as a whole, at most [`STRING_RECORD_LIMIT`]
/// bytes (SPEC §7.2), so a string's length prefix can never claim more.
pub const STRING_RECORDS: [&str; 3] = [HEADER, INTERFACES, MODAL_LOADS];
/// `header.bin`.
pub const HEADER: &str = "header.bin";
/// `nodes.bin`.
pub const NODES: &str = "nodes.bin";
/// `faces.bin`.
pub const FACES: &str = "faces.bin";
/// `nodal_mass.bin`.
pub const NODAL_MASS: &str = "nodal_mass.bin";
/// `modes.bin`.
pub const MODES: &str = "modes.bin";
/// `invariants.bin`.
pub const INVARIANTS: &str = "invariants.bin";
/// `method.bin`.
pub const METHOD: &str = "method.bin";
/// `stress_shapes.bin`.
pub const STRESS_SHAPES: &str = "stress_shapes.bin";
/// `strain_shapes.bin`.
pub const STRAIN_SHAPES: &str = "strain_shapes.bin";
/// `damping.bin`.
pub const DAMPING: &str = "damping.bin";
/// `lines.bin` (format 1.1).
pub const LINES: &str = "lines.bin";
/// `recipe.json` (format 1.2): UTF-8 JSON, not a bincode record.
pub const RECIPE: &str = "recipe.json";
/// `label_shares.bin` (format 1.2).
pub const LABEL_SHARES: &str = "label_shares.bin";
/// `interfaces.bin` (format 1.3): per interface node its name, kind, dependent nodes and centre
/// fit.
pub const INTERFACES: &str = "interfaces.bin";
/// `modal_loads.bin` (format 1.4).
pub const MODAL_LOADS: &str = "modal_loads.bin";
/// `stress_shapes_bottom.bin` (format 1.5): shell bottom-fibre stress shapes.
pub const STRESS_SHAPES_BOTTOM: &str = "stress_shapes_bottom.bin";
/// `strain_shapes_bottom.bin` (format 1.5): shell bottom-fibre strain shapes.
pub const STRAIN_SHAPES_BOTTOM: &str = "strain_shapes_bottom.bin";
/// `geometric_stiffness.bin` (format 1.7): modal geometric stiffness per unit inertia load.
pub const GEOMETRIC_STIFFNESS: &str = "geometric_stiffness.bin";
/// `eigen_residuals.bin` (format 1.9): per eigenproblem, each mode's eigenvalue and residual.
pub const EIGEN_RESIDUALS: &str = "eigen_residuals.bin";

/// `manifest.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Always [`FORMAT_NAME`].
    pub format: String,
    /// Format version.
    pub version: crate::Version,
    /// Writer program.
    pub generator: crate::Generator,
    /// Unit system.
    pub units: crate::Units,
    /// Every other entry, in container order.
    pub entries: Vec<ManifestEntry>,
}

/// One line of the manifest's entry list.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ManifestEntry {
    /// Zip entry name.
    pub name: String,
    /// Uncompressed size in bytes.
    pub size: u64,
    /// Lowercase hex SHA-256 of the uncompressed bytes.
    pub sha256: String,
    /// Whether a reader that does not know the entry must refuse the file.
    pub required: bool,
}

/// Lowercase hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let digest = Sha256::digest(bytes);
    let mut s = String::with_capacity(64);
    for b in digest.iter() {
        s.push_str(&format!("{b:02x}"));
    }
    s
}

/// The v1 configuration (no decode limit: see [`decode`] for how allocation is bounded).
fn config() -> bincode::config::Configuration<bincode::config::LittleEndian, bincode::config::Fixint>
{
    bincode::config::standard()
        .with_little_endian()
        .with_fixed_int_encoding()
}

/// Byte limit of the records that hold strings ([`STRING_RECORDS`]) and of `recipe.json`:
/// bincode allocates a string's buffer from its length prefix before reading it, so bounding
/// the whole record bounds that allocation.
pub const STRING_RECORD_LIMIT: usize = 16 << 20;

fn over_limit(entry: &str, len: usize) -> Option<ReadError> {
    (len > STRING_RECORD_LIMIT).then(|| ReadError::Decode {
        entry: entry.to_string(),
        detail: format!("{len} bytes exceed the {STRING_RECORD_LIMIT}-byte record limit"),
    })
}

/// Decodes `recipe.json`: UTF-8 JSON (read as SPEC.md §4.1 says) with the members of §5.11
/// (unknown members ignored), at most [`STRING_RECORD_LIMIT`] bytes; anything else is `Decode`.
pub fn decode_recipe(bytes: &[u8]) -> Result<crate::Recipe, ReadError> {
    let fail = |detail: String| ReadError::Decode {
        entry: RECIPE.to_string(),
        detail,
    };
    if let Some(e) = over_limit(RECIPE, bytes.len()) {
        return Err(e);
    }
    let text = std::str::from_utf8(bytes).map_err(|e| fail(format!("not UTF-8: {e}")))?;
    let value = crate::json::parse(text).map_err(|e| fail(format!("not JSON: {e}")))?;
    crate::json::from_json(&value).map_err(|e| fail(format!("not a valid recipe: {e}")))
}

/// Encodes `recipe.json`: pretty JSON (two-space indent, members in declaration order) and a
/// final newline.
pub fn encode_recipe(recipe: &crate::Recipe) -> Vec<u8> {
    // Cannot fail: plain structs of strings, numbers and vectors (non-finite numbers become
    // `null`, which the validation refuses before writing).
    let mut v = serde_json::to_vec_pretty(recipe).expect("recipe JSON into Vec is infallible");
    v.push(b'\n');
    v
}

/// Encodes a payload record with the v1 layout.
pub fn encode<T: Serialize>(value: &T) -> Vec<u8> {
    // Cannot fail: encoding serde-derived plain records into a Vec does no I/O, and the
    // unlimited config has no size limit to exceed.
    bincode::serde::encode_to_vec(value, config()).expect("bincode encode into Vec is infallible")
}

/// Decodes a payload record with the v1 layout; the entry must be consumed exactly.
///
/// Allocation is bounded: a record with strings (`has_strings`, the [`STRING_RECORDS`]) is at
/// most [`STRING_RECORD_LIMIT`] bytes as a whole and decodes under that bincode limit;
/// sequences of numbers and structs go through serde's cautious preallocation (at most 1 MiB)
/// and grow only as elements are actually read from `bytes`, whose size the caller bounded.
pub fn decode<T: DeserializeOwned>(
    entry: &str,
    bytes: &[u8],
    has_strings: bool,
) -> Result<T, ReadError> {
    if let Some(e) = over_limit(entry, bytes.len()).filter(|_| has_strings) {
        return Err(e);
    }
    let result = if has_strings {
        let cfg = config().with_limit::<STRING_RECORD_LIMIT>();
        bincode::serde::decode_from_slice::<T, _>(bytes, cfg)
    } else {
        bincode::serde::decode_from_slice::<T, _>(bytes, config())
    };
    let (value, used) = result.map_err(|e| {
        let detail = match e {
            bincode::error::DecodeError::UnexpectedEnd { additional } => format!(
                "record ends early: {additional} more bytes needed; a length prefix claims more \
                 elements than the entry holds, or the entry is truncated"
            ),
            bincode::error::DecodeError::LimitExceeded => {
                format!("a length prefix exceeds the {STRING_RECORD_LIMIT}-byte record limit")
            }
            other => other.to_string(),
        };
        ReadError::Decode {
            entry: entry.to_string(),
            detail,
        }
    })?;
    if used != bytes.len() {
        return Err(ReadError::TrailingBytes {
            entry: entry.to_string(),
            count: (bytes.len() - used) as u64,
        });
    }
    Ok(value)
}
