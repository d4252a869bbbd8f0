//! Reduced-body file writer: temp file + rename, deterministic bytes.
