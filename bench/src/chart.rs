//! Charts (placeholder).
use crate::Res;
/// Draws the charts.
pub fn run() -> Res<serde_json::Value> { Err("todo".into()) }
