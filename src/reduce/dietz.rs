//! Dietz (placeholder while in progress).
