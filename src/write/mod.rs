//! Reduced-body file writer: validates with the reader's own rules, zips the v1 entries in
//! their fixed order with fixed timestamps and a fixed deflate level (byte-identical output
//! for identical input), writes a temp file beside the target and renames it into place.
//! By default a large entry that deflate does not shrink (random-looking doubles) is stored
//! instead ([`Compression::Auto`]), so readers do not pay for inflating it.
//!
//! ```no_run
//! # fn demo(body: &flexbody_reader::ReducedBody) -> Result<(), flexbody::write::WriteError> {
//! flexbody::write::write_reduced_body("rod.flexbody", body, &Default::default())?;
//! # Ok(()) }
//! ```
pub mod mtx;

use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};

use flexbody_reader::{codec, ReadError, ReadLimits, ReducedBody};
use rayon::prelude::*;
use zip::write::{PreparedZipFile, SimpleFileOptions};
use zip::{CompressionMethod, DateTime, ZipWriter};

/// Deflate level used by default; fixed so output is reproducible.
pub const DEFAULT_DEFLATE_LEVEL: i64 = 6;

/// An entry smaller than this (uncompressed bytes) is always deflated by [`Compression::Auto`].
pub const AUTO_STORE_MIN_BYTES: usize = 1 << 20;

/// [`Compression::Auto`] stores an entry of at least [`AUTO_STORE_MIN_BYTES`] when deflating
/// it saves less than `1 / AUTO_STORE_MIN_SAVING` of its bytes.
pub const AUTO_STORE_MIN_SAVING: u64 = 16;

/// How entries are compressed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Compression {
    /// Deflate at the given level (1–9).
    Deflate(i64),
    /// No compression.
    Stored,
    /// Deflate at `level`, except that an entry of `n ≥` [`AUTO_STORE_MIN_BYTES`] bytes whose
    /// deflated form has `c` bytes with `16·(n − c) < n` (it saves less than 1/16,
    /// [`AUTO_STORE_MIN_SAVING`]) is stored. The deflate is run once (large entries in
    /// parallel); the decision is a function of the bytes, so output stays deterministic. The
    /// default (level 6).
    Auto {
        /// Deflate level (1–9).
        level: i64,
    },
}

impl Compression {
    /// Whether [`Compression::Auto`] stores an entry of `uncompressed` bytes that deflates to
    /// `deflated` bytes (only asked for entries of at least [`AUTO_STORE_MIN_BYTES`]).
    pub fn auto_stores(uncompressed: u64, deflated: u64) -> bool {
        uncompressed >= AUTO_STORE_MIN_BYTES as u64
            && AUTO_STORE_MIN_SAVING * uncompressed.saturating_sub(deflated) < uncompressed
    }
}

/// Writer options. The creation time is not an option here: it is `header.created_utc`,
/// set by the caller only when the user asks for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WriteOptions {
    /// Entry compression (default [`Compression::Auto`] at deflate level 6).
    pub compression: Compression,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions {
            compression: Compression::Auto {
                level: DEFAULT_DEFLATE_LEVEL,
            },
        }
    }
}

/// Why a file was not written. No partial file is left behind in any case.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The body breaks a format rule (the reader would refuse it).
    #[error("{path}: not written, the body breaks a format rule: {source}")]
    Invalid {
        /// Target path.
        path: PathBuf,
        /// The rule broken.
        source: ReadError,
    },
    /// Creating, writing or renaming failed.
    #[error("{path}: {action} failed: {source}")]
    Io {
        /// The output path (`-o`), also when its temp file failed.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// The cause.
        source: std::io::Error,
    },
    /// The zip layer failed (should not happen for in-memory output).
    #[error("{path}: zip container: {detail}")]
    Zip {
        /// Target path.
        path: PathBuf,
        /// The zip layer's message.
        detail: String,
    },
}

/// Zips `entries` (name, uncompressed bytes) in the given order with fixed timestamps
/// (1980-01-01 00:00), fixed permissions and the chosen compression (decided per entry for
/// [`Compression::Auto`]). Low level: no manifest is added and nothing is checked (the
/// fixture generator uses it for broken files).
pub fn zip_entries(
    entries: &[(String, Vec<u8>)],
    compression: Compression,
) -> zip::result::ZipResult<Vec<u8>> {
    let mut zw = ZipWriter::new(Cursor::new(Vec::new()));
    let base = SimpleFileOptions::default()
        .last_modified_time(DateTime::default())
        .unix_permissions(0o644);
    let stored = base.compression_method(CompressionMethod::Stored);
    let deflated = |level| {
        base.compression_method(CompressionMethod::Deflated)
            .compression_level(Some(level))
    };
    // Auto: every large entry is deflated once, in memory and in parallel (each entry on its
    // own, so the bytes do not depend on the threads); that result is kept unless it saves
    // too little.
    let prepared: Vec<Option<PreparedZipFile>> = match compression {
        Compression::Auto { level } => entries
            .par_iter()
            .map(|(name, bytes)| {
                (bytes.len() >= AUTO_STORE_MIN_BYTES)
                    .then(|| PreparedZipFile::from_data(name, deflated(level), bytes))
                    .transpose()
            })
            .collect::<zip::result::ZipResult<_>>()?,
        _ => Vec::new(),
    };
    let mut prepared = prepared.into_iter();
    for (name, bytes) in entries {
        let opts = match compression {
            Compression::Stored => stored,
            Compression::Deflate(level) => deflated(level),
            Compression::Auto { level } => match prepared.next().flatten() {
                None => deflated(level),
                Some(p) if Compression::auto_stores(bytes.len() as u64, p.compressed_size()) => {
                    stored
                }
                Some(p) => {
                    zw.add_prepared_file(p)?;
                    continue;
                }
            },
        };
        zw.start_file(name.as_str(), opts)?;
        zw.write_all(bytes)?;
    }
    Ok(zw.finish()?.into_inner())
}

/// The complete file as bytes: `manifest.json` (pretty JSON) then the payload entries.
pub fn to_bytes(body: &ReducedBody, opts: &WriteOptions) -> Result<Vec<u8>, WriteError> {
    to_bytes_at(Path::new("<memory>"), body, opts)
}

fn to_bytes_at(
    path: &Path,
    body: &ReducedBody,
    opts: &WriteOptions,
) -> Result<Vec<u8>, WriteError> {
    flexbody_reader::validate(body, &ReadLimits::default()).map_err(|source| {
        WriteError::Invalid {
            path: path.to_path_buf(),
            source,
        }
    })?;
    let payload = flexbody_reader::encode_entries(body);
    // Refuse what the reader's default limits would refuse, so every written file reads back.
    let limits = ReadLimits::default();
    for (name, _, bytes) in &payload {
        let limit = if codec::STRING_RECORDS.contains(name) || *name == codec::RECIPE {
            codec::STRING_RECORD_LIMIT as u64
        } else {
            limits.max_entry_bytes
        };
        if bytes.len() as u64 > limit {
            let source = ReadError::LimitExceeded {
                entry: name.to_string(),
                what: "encoded size (bytes)".into(),
                value: bytes.len() as u64,
                limit,
            };
            return Err(WriteError::Invalid {
                path: path.to_path_buf(),
                source,
            });
        }
    }
    let manifest = flexbody_reader::manifest_for(body, &payload);
    let mut json = serde_json::to_vec_pretty(&manifest).map_err(|e| WriteError::Zip {
        path: path.to_path_buf(),
        detail: e.to_string(),
    })?;
    json.push(b'\n');
    let mut entries = vec![(codec::MANIFEST.to_string(), json)];
    entries.extend(payload.into_iter().map(|(n, _, b)| (n.to_string(), b)));
    zip_entries(&entries, opts.compression).map_err(|e| WriteError::Zip {
        path: path.to_path_buf(),
        detail: e.to_string(),
    })
}

/// The folder `path` goes into, its file name and the temp-file prefix `.NAME.tmp-`.
fn output_parts(path: &Path) -> (PathBuf, String, String) {
    let file_name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out.flexbody".into());
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf();
    let prefix = format!(".{file_name}.tmp-");
    (dir, file_name, prefix)
}

fn io<'a>(p: &'a Path, action: &'static str) -> impl FnOnce(std::io::Error) -> WriteError + 'a {
    move |source| WriteError::Io {
        path: p.to_path_buf(),
        action,
        source,
    }
}

/// Check, before any work, that `path` can take the output: not a folder, its folder exists
/// and a file can be created there (probed with the temp file, removed at once). Also removes
/// stale temp files `.NAME.tmp-PID` of this output left by runs that were killed (their process
/// is gone). Errors name `path` itself.
pub fn check_output_path(path: impl AsRef<Path>) -> Result<(), WriteError> {
    let path = path.as_ref();
    let ends_in_separator = path.as_os_str().to_string_lossy().ends_with(['/', '\\']);
    if path.is_dir() || ends_in_separator {
        return Err(io(path, "checking the output")(std::io::Error::new(
            std::io::ErrorKind::IsADirectory,
            "it is a folder: give a file name (e.g. body.flexbody)",
        )));
    }
    let (dir, _, prefix) = output_parts(path);
    if !dir.is_dir() {
        return Err(io(path, "checking the output")(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("its folder {} does not exist", dir.display()),
        )));
    }
    remove_stale_temp_files(&dir, &prefix);
    let probe = dir.join(format!("{prefix}{}", std::process::id()));
    std::fs::File::create(&probe).map_err(io(path, "creating a file beside the output"))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Remove `dir/PREFIX<pid>` files whose process no longer runs (Linux: no `/proc/<pid>`; on
/// systems without `/proc` nothing is removed, as liveness cannot be told).
fn remove_stale_temp_files(dir: &Path, prefix: &str) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let Some(pid) = name
            .strip_prefix(prefix)
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        if pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists() {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// Writes `body` to `path`: validate, encode, write `path`'s folder/.name.tmp-PID, fsync,
/// rename over `path`. On any error the temp file is removed and `path` is untouched; errors
/// name `path` (the temp file is an implementation detail). Stale temp files of killed runs
/// are removed first.
pub fn write_reduced_body(
    path: impl AsRef<Path>,
    body: &ReducedBody,
    opts: &WriteOptions,
) -> Result<(), WriteError> {
    let path = path.as_ref();
    let bytes = to_bytes_at(path, body, opts)?;
    if path.is_dir() {
        return check_output_path(path);
    }
    let (dir, _, prefix) = output_parts(path);
    remove_stale_temp_files(&dir, &prefix);
    write_replacing(path, |w| w.write_all(&bytes)).map_err(|(action, source)| WriteError::Io {
        path: path.to_path_buf(),
        action,
        source,
    })
}

/// What failed in [`write_replacing`]: the step (`"creating the temp file beside it"`, …) and
/// its cause.
pub type ReplaceError = (&'static str, std::io::Error);

/// The one way flexbody writes a file (the `.flexbody` file, every export, the Matrix Market
/// files): `fill` writes the content into `path`'s folder/.NAME.tmp-PID (buffered), then fsync
/// and rename over `path`. On any error the temp file is removed and `path` is untouched; the
/// error names the step that failed.
pub fn write_replacing(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), ReplaceError> {
    let (dir, _, prefix) = output_parts(path);
    let tmp = dir.join(format!("{prefix}{}", std::process::id()));
    let result = (|| {
        let file =
            std::fs::File::create(&tmp).map_err(|e| ("creating the temp file beside it", e))?;
        let mut w = std::io::BufWriter::new(file);
        fill(&mut w).map_err(|e| ("writing the temp file beside it", e))?;
        let file =
            (w.into_inner()).map_err(|e| ("writing the temp file beside it", e.into_error()))?;
        file.sync_all()
            .map_err(|e| ("syncing the temp file beside it", e))?;
        drop(file);
        std::fs::rename(&tmp, path).map_err(|e| ("renaming the temp file onto the target", e))
    })();
    if result.is_err() {
        // Best effort: the temp file may not exist if creation itself failed.
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
