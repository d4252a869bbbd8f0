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
    /// Largest ratio of the summed decompressed entry sizes to the file's size (default 64;
    /// real files stay below 5, deflate alone allows ~1032). Together with
    /// [`max_expansion_floor`](Self::max_expansion_floor) it bounds a decompression bomb: a small
    /// file cannot make the reader allocate more than `file bytes × max_expansion` (or the floor).
    pub max_expansion: u64,
    /// Summed decompressed size (bytes) always allowed whatever the file's size (default 64 MiB).
    pub max_expansion_floor: u64,
}

impl ReadLimits {
    /// The most decompressed bytes (all entries together) a `file_bytes`-byte file may declare.
    pub fn expansion_cap(&self, file_bytes: u64) -> u64 {
        file_bytes
            .saturating_mul(self.max_expansion)
            .max(self.max_expansion_floor)
    }
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
            max_expansion: 64,
            max_expansion_floor: 64 << 20,
        }
    }
}
