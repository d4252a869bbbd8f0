//! Craig–Chang (placeholder while in progress).
