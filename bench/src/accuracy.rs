//! Accuracy suite (placeholder).
use crate::Res;
/// Runs the suite.
pub fn run(_model: Option<&str>) -> Res<serde_json::Value> { Err("todo".into()) }
