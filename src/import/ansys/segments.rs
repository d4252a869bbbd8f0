//! The contact and target records of an archive (TARGE170, CONTA173/174/175) as
//! [`super::contact`] and [`super::bonded`] read them: which element types they are, their
//! faces and shapes, a pair's refusal.

use std::collections::{BTreeMap, BTreeSet};

use super::blocks::ElementRecord;
use super::catalogue::Disposition;
use super::elements::ElementType;

/// A refusal of a pair: the record it is named by and the reason.
pub(super) type PairRefusal<'a> = (&'a ElementRecord, String);

/// A pair: the TARGE170 and contact records of one real constant set, with the element types
/// and the set's real constants that judge them.
pub(super) struct Pair<'a, 't> {
    pub types: &'t BTreeMap<i64, ElementType>,
    pub constants: Option<&'t Vec<f64>>,
    pub real: i64,
    pub targets: Vec<&'a ElementRecord>,
    pub contacts: Vec<&'a ElementRecord>,
}

/// TARGE170's shape keys of a pilot node (`TSHAPE,PILO`): 19, and 99 as ANSYS also writes it
/// (ansys-mapdl-reader's `mesh.py` reads both as the pilot).
pub(super) const PILOT_SHAPES: [i64; 2] = [19, 99];

/// Whether records of type `t` are contact or target segments read here (TARGE170,
/// CONTA173, CONTA174, CONTA175).
pub(super) fn is_segment(t: &ElementType) -> bool {
    matches!(
        t.row,
        Some((170 | 173 | 174 | 175, _, Disposition::Honoured(_)))
    )
}

/// The node count of a TARGE170 face of shape key `shape` (TRIA 6, QUAD 7, TRI6 8, QUA8 9, as
/// ansys-mapdl-reader's `SHAPE_MAP` names them); `None` for the other shapes.
pub(super) fn face_nodes(shape: i64) -> Option<usize> {
    Some(match shape {
        6 => 3,
        7 => 4,
        8 => 6,
        9 => 8,
        _ => return None,
    })
}

/// A contact record's nodes as a face (corners, then mid-side nodes of edges 1-2, 2-3, …):
/// CONTA175 one node; CONTA173 I, J, K, L (K = L: the 3-node triangle); CONTA174 I…L, M…P
/// (K = L = O: the 6-node triangle I, J, K, M, N, P, ANSYS's degenerate form).
pub(super) fn contact_face(r: &ElementRecord) -> Result<Vec<u64>, String> {
    let n = &r.nodes;
    match n.len() {
        1 => Ok(n.clone()),
        4 if n[2] == n[3] => Ok(n[..3].to_vec()),
        4 => Ok(n.clone()),
        8 if n[2] == n[3] && n[3] == n[6] => Ok(vec![n[0], n[1], n[2], n[4], n[5], n[7]]),
        8 => Ok(n.clone()),
        k => Err(format!(
            "contact record of {k} nodes (CONTA175: 1, CONTA173: 4, CONTA174: 8 expected)"
        )),
    }
}

/// The records of `elements` split into contact and target segments (their element type read
/// here and not dropped by `--ignore`) and the others, each in the archive's order.
pub(super) fn split<'a>(
    elements: &'a [ElementRecord],
    types: &BTreeMap<i64, ElementType>,
    ignored: &BTreeSet<String>,
) -> (Vec<&'a ElementRecord>, Vec<&'a ElementRecord>) {
    let segment = |r: &&ElementRecord| {
        (types.get(&r.etype)).is_some_and(|t| is_segment(t) && !ignored.contains(&t.name()))
    };
    elements.iter().partition(segment)
}
