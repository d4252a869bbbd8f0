//! Exporters: the body (or its model) in other programs' formats.
pub mod mtx;
