//! What an expanded shell node is and where a shell element was read: the types the expansion
//! (`shell_expansion.rs`) and its joining equations (`shell_equations.rs`) share.

use std::collections::HashMap;

use crate::import::ImportError;
use crate::model::NodeIndex;

/// Where a shell element was read and as what.
#[derive(Debug, Clone)]
pub struct Place {
    /// The element type (one of [`super::shell_expansion::SHELL_TYPES`]).
    pub card: &'static str,
    /// File it is in.
    pub file: String,
    /// 1-based line.
    pub line: usize,
}

/// The deck's shell elements: external element id → where and what.
pub type ShellElements = HashMap<u64, Place>;

/// ccx's limit for a rotation axis along the normal (gen3dboun: a drilling rotation).
pub(super) const DRILLING: f64 = 0.999;
/// ccx's limit for a second held rotation along the first (gen3dboun).
pub(super) const SAME_AXIS: f64 = 0.9999;

pub(super) type Xyz = [f64; 3];

/// a / |a|, or `None` for a length of 1e-10 or less.
pub(super) fn unit(a: Xyz) -> Option<Xyz> {
    crate::model::geometry::unit_if(a, |n| n > 1e-10 && n.is_finite())
}

pub(super) fn parse_err(place: &Place, entity: String, message: String) -> ImportError {
    ImportError::Parse {
        file: place.file.clone(),
        line: place.line,
        entity,
        message,
    }
}

/// The expanded nodes of one shell node.
#[derive(Debug, Clone, Copy)]
pub(super) struct Expanded {
    pub(super) bottom: NodeIndex,
    pub(super) middle: Option<NodeIndex>,
    pub(super) top: NodeIndex,
    pub(super) normal: Xyz,
}
