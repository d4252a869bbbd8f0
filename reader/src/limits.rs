//! Resource limits a reader enforces on untrusted files (SPEC.md §7).

/// Limits checked before any allocation that depends on the file's contents.
/// Defaults fit any realistic reduced body; raise them for huge stress-shape files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReadLimits {
    /// Largest decompressed size of one entry, bytes (default 2 GiB).
    pub max_entry_bytes: u64,
    /// Largest sum of decompressed entry sizes, bytes (default 8 GiB).
    pub max_total_bytes: u64,
    /// Largest manifest.json, bytes (default 1 MiB).
    pub max_manifest_bytes: u64,
    /// Most entries besides the manifest (default 64).
    pub max_entries: u64,
    /// Most stored nodes (default 10 000 000).
    pub max_nodes: u64,
    /// Most graphics faces (default 50 000 000).
    pub max_faces: u64,
    /// Most modes (default 100 000).
    pub max_modes: u64,
}

impl Default for ReadLimits {
    fn default() -> Self {
        ReadLimits {
            max_entry_bytes: 2 << 30,
            max_total_bytes: 8 << 30,
            max_manifest_bytes: 1 << 20,
            max_entries: 64,
            max_nodes: 10_000_000,
            max_faces: 50_000_000,
            max_modes: 100_000,
        }
    }
}
