//! The typed error of the reader: each variant names the entry and the rule broken.
use std::path::PathBuf;

/// Why a file was refused. Variant names are part of the conformance suite
/// (`fixtures/broken/*.expect`), so they are stable.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReadError {
    /// The file could not be read from disk.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The bytes are not a readable zip container.
    #[error("not a flexbody file: not a zip container ({detail})")]
    NotZip {
        /// What the zip layer said.
        detail: String,
    },
    /// The container is damaged (an entry cannot be read, or its zip CRC fails).
    #[error("entry {entry}: damaged zip data ({detail})")]
    Container {
        /// Entry name.
        entry: String,
        /// What the zip layer said.
        detail: String,
    },
    /// A required entry is absent (manifest.json, or an entry the manifest lists).
    #[error("missing entry {entry}: {rule}")]
    MissingEntry {
        /// Entry name.
        entry: String,
        /// Which rule requires it.
        rule: String,
    },
    /// The same entry name occurs twice.
    #[error("entry {entry}: occurs more than once")]
    DuplicateEntry {
        /// Entry name.
        entry: String,
    },
    /// A zip entry not listed in the manifest.
    #[error("entry {entry}: present in the container but not listed in manifest.json")]
    UnlistedEntry {
        /// Entry name.
        entry: String,
    },
    /// manifest.json is not valid UTF-8 JSON of the expected shape.
    #[error("manifest.json: {detail}")]
    Manifest {
        /// The rule broken.
        detail: String,
    },
    /// The manifest names another format.
    #[error("manifest.json: format is {found:?}, expected \"flexbody-reduced-body\"")]
    WrongFormat {
        /// The format string found.
        found: String,
    },
    /// The file's major version is newer than this reader.
    #[error(
        "manifest.json: format version {major}.{minor} is newer than this reader supports \
         ({supported}.x); update flexbody-reader"
    )]
    UnsupportedVersion {
        /// File major version.
        major: u32,
        /// File minor version.
        minor: u32,
        /// Supported major version.
        supported: u32,
    },
    /// The manifest marks an entry this reader does not know as required.
    #[error("entry {entry}: unknown entry marked required (written by a newer writer?)")]
    UnknownRequiredEntry {
        /// Entry name.
        entry: String,
    },
    /// An entry uses a compression method other than stored or deflate.
    #[error("entry {entry}: compression method {method} not supported (only stored and deflate)")]
    Compression {
        /// Entry name.
        entry: String,
        /// The method found.
        method: String,
    },
    /// An entry, the total, or an element count exceeds [`crate::ReadLimits`].
    #[error("entry {entry}: {what} {value} exceeds the limit {limit}")]
    LimitExceeded {
        /// Entry name.
        entry: String,
        /// What was counted.
        what: String,
        /// The value found.
        value: u64,
        /// The limit.
        limit: u64,
    },
    /// An entry's decompressed byte count differs from the manifest.
    #[error("entry {entry}: size {actual} bytes differs from the manifest's {declared}")]
    SizeMismatch {
        /// Entry name.
        entry: String,
        /// Size in the manifest.
        declared: u64,
        /// Size found (or a lower bound when reading stopped early).
        actual: u64,
    },
    /// An entry's SHA-256 differs from the manifest.
    #[error("entry {entry}: SHA-256 {actual} differs from the manifest's {expected}")]
    Checksum {
        /// Entry name.
        entry: String,
        /// Hex digest in the manifest.
        expected: String,
        /// Hex digest of the bytes.
        actual: String,
    },
    /// A payload does not decode with the v1 layout.
    #[error("entry {entry}: cannot decode ({detail})")]
    Decode {
        /// Entry name.
        entry: String,
        /// The decoder's message.
        detail: String,
    },
    /// A payload decodes but leaves bytes over.
    #[error("entry {entry}: {count} trailing bytes after the record")]
    TrailingBytes {
        /// Entry name.
        entry: String,
        /// Extra bytes.
        count: u64,
    },
    /// Array lengths disagree within or between entries.
    #[error("entry {entry}: {field} has length {found}, expected {expected} ({rule})")]
    CountMismatch {
        /// Entry name.
        entry: String,
        /// Field.
        field: String,
        /// Expected length.
        expected: u64,
        /// Length found.
        found: u64,
        /// Why that length is expected.
        rule: String,
    },
    /// A NaN or infinity.
    #[error("entry {entry}: {field}[{index}] is not finite ({value})")]
    NonFinite {
        /// Entry name.
        entry: String,
        /// Field.
        field: String,
        /// Flat index in the field.
        index: u64,
        /// The value.
        value: f64,
    },
    /// A node index points past the node list.
    #[error("entry {entry}: {field} node index {value} out of range (N = {bound})")]
    IndexOutOfRange {
        /// Entry name.
        entry: String,
        /// Field (with the element position).
        field: String,
        /// The index.
        value: u64,
        /// Number of nodes.
        bound: u64,
    },
    /// A matrix that must be symmetric is not.
    #[error("entry {entry}: {field} not symmetric at ({row}, {col}): {a} vs {b}")]
    NotSymmetric {
        /// Entry name.
        entry: String,
        /// Field.
        field: String,
        /// Row.
        row: u64,
        /// Column.
        col: u64,
        /// Value at (row, col).
        a: f64,
        /// Value at (col, row).
        b: f64,
    },
    /// Any other consistency rule of the spec.
    #[error("entry {entry}: {rule}")]
    Inconsistent {
        /// Entry name.
        entry: String,
        /// The rule broken, with the values.
        rule: String,
    },
}

impl ReadError {
    /// The error with its SPEC §8 name in front (`Checksum: entry modes.bin: SHA-256 …`), for a
    /// program that prints it: `.map_err(ReadError::named)` where it reads a file.
    pub fn named(self) -> NamedError {
        NamedError(self)
    }

    /// The variant name (SPEC §8), as used in `fixtures/broken/*.expect`.
    pub fn variant(&self) -> &'static str {
        match self {
            ReadError::Io { .. } => "Io",
            ReadError::NotZip { .. } => "NotZip",
            ReadError::Container { .. } => "Container",
            ReadError::MissingEntry { .. } => "MissingEntry",
            ReadError::DuplicateEntry { .. } => "DuplicateEntry",
            ReadError::UnlistedEntry { .. } => "UnlistedEntry",
            ReadError::Manifest { .. } => "Manifest",
            ReadError::WrongFormat { .. } => "WrongFormat",
            ReadError::UnsupportedVersion { .. } => "UnsupportedVersion",
            ReadError::UnknownRequiredEntry { .. } => "UnknownRequiredEntry",
            ReadError::Compression { .. } => "Compression",
            ReadError::LimitExceeded { .. } => "LimitExceeded",
            ReadError::SizeMismatch { .. } => "SizeMismatch",
            ReadError::Checksum { .. } => "Checksum",
            ReadError::Decode { .. } => "Decode",
            ReadError::TrailingBytes { .. } => "TrailingBytes",
            ReadError::CountMismatch { .. } => "CountMismatch",
            ReadError::NonFinite { .. } => "NonFinite",
            ReadError::IndexOutOfRange { .. } => "IndexOutOfRange",
            ReadError::NotSymmetric { .. } => "NotSymmetric",
            ReadError::Inconsistent { .. } => "Inconsistent",
        }
    }
}

/// A [`ReadError`] displayed with its SPEC §8 name in front, so that a reader of the text need
/// not map messages to names. Its `source` is the `ReadError`'s own.
#[derive(Debug)]
pub struct NamedError(pub ReadError);

impl std::fmt::Display for NamedError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.0.variant(), self.0)
    }
}

impl std::error::Error for NamedError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        std::error::Error::source(&self.0)
    }
}
