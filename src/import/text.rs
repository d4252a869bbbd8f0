//! Shared plumbing of the text importers: reading a whole file with empty/binary detection,
//! allocation-free number parsing, external-id → index maps and the resolve pass that turns
//! raw records keyed by external ids into a dense [`Model`].

use std::collections::HashMap;
use std::path::Path;

use super::error::{parse_err, ImportError};
use crate::model::{Element, ElementKind, Model, Node};

/// Read a text model file whole. An empty file, a NUL byte or invalid UTF-8 is an error naming
/// the line where it occurs.
pub(crate) fn read_text(path: &Path) -> Result<String, ImportError> {
    let file = path.display().to_string();
    let bytes = super::budget::read_bounded(path, super::budget::Content::Text)?;
    check_text(&file, bytes)
}

/// See [`read_text`]; `bytes` are the file's content.
pub(crate) fn check_text(file: &str, bytes: Vec<u8>) -> Result<String, ImportError> {
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(parse_err(file, 1, "file", "empty file"));
    }
    let line_of =
        |bytes: &[u8], pos: usize| 1 + bytes[..pos].iter().filter(|&&b| b == b'\n').count();
    if let Some(pos) = bytes.iter().position(|&b| b == 0) {
        return Err(parse_err(
            file,
            line_of(&bytes, pos),
            "file",
            "binary data (NUL byte) in a text model file",
        ));
    }
    match String::from_utf8(bytes) {
        Ok(s) => Ok(s),
        Err(e) => {
            let pos = e.utf8_error().valid_up_to();
            let line = line_of(e.as_bytes(), pos);
            Err(parse_err(
                file,
                line,
                "file",
                "binary data (invalid UTF-8) in a text model file",
            ))
        }
    }
}

/// Parse a real number, accepting Fortran `D` exponents (`1.5D3`); `None` also for NaN, ±∞
/// and |x| ≥ [`super::budget::MAX_ABS_REAL`] (see [`bad_number`] for the message).
pub(crate) fn parse_f64(s: &str) -> Option<f64> {
    parse_f64_unbounded(s).and_then(super::budget::in_range)
}

/// The error message for a real field `s` that [`parse_f64`] refused.
pub(crate) fn bad_number(s: &str) -> String {
    super::budget::bad_number(s, parse_f64_unbounded(s))
}

fn parse_f64_unbounded(s: &str) -> Option<f64> {
    let s = s.trim();
    if let Ok(v) = s.parse::<f64>() {
        return Some(v);
    }
    if s.contains(['d', 'D']) {
        return s.replace(['d', 'D'], "e").parse().ok();
    }
    None
}

/// Parse a non-negative integer id.
pub(crate) fn parse_u64(s: &str) -> Option<u64> {
    s.trim().parse::<u64>().ok()
}

/// Where a record came from: index into the builder's file list and 1-based line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Loc {
    pub file: u32,
    pub line: u32,
}

/// External id → dense index. A direct table when ids are compact, a hash map otherwise.
#[derive(Debug, Clone)]
pub(crate) enum IdMap {
    Dense(Vec<u32>),
    Sparse(HashMap<u64, u32>),
}

impl IdMap {
    /// Build from ids in order. `Err((first, second))` gives the positions of a duplicate id.
    pub(crate) fn build(
        ids: impl ExactSizeIterator<Item = u64> + Clone,
    ) -> Result<IdMap, (usize, usize)> {
        let n = ids.len();
        let max = ids.clone().max().unwrap_or(0);
        if max <= 4 * n as u64 + 1024 {
            let mut table = vec![u32::MAX; max as usize + 1];
            for (i, id) in ids.enumerate() {
                let slot = &mut table[id as usize];
                if *slot != u32::MAX {
                    return Err((*slot as usize, i));
                }
                *slot = i as u32;
            }
            Ok(IdMap::Dense(table))
        } else {
            let mut map = HashMap::with_capacity(n);
            for (i, id) in ids.enumerate() {
                if let Some(&first) = map.get(&id) {
                    return Err((first as usize, i));
                }
                map.insert(id, i as u32);
            }
            Ok(IdMap::Sparse(map))
        }
    }

    /// Dense index of an external id.
    #[inline]
    pub(crate) fn get(&self, id: u64) -> Option<usize> {
        match self {
            IdMap::Dense(t) => match t.get(usize::try_from(id).ok()?) {
                Some(&i) if i != u32::MAX => Some(i as usize),
                _ => None,
            },
            IdMap::Sparse(m) => m.get(&id).map(|&i| i as usize),
        }
    }
}

/// Accumulates nodes and elements keyed by external ids, with their source locations, and
/// resolves them into a [`Model`].
#[derive(Debug, Default)]
pub(crate) struct Builder {
    /// Files read (main file first, then includes).
    pub files: Vec<String>,
    /// The model under construction; element node lists hold *external* ids until
    /// [`Builder::resolve`].
    pub model: Model,
    pub node_loc: Vec<Loc>,
    pub elem_loc: Vec<Loc>,
    /// Card/keyword name of each element, for messages.
    pub elem_card: Vec<&'static str>,
}

impl Builder {
    pub(crate) fn new(main_file: &str) -> Builder {
        let mut b = Builder {
            files: vec![main_file.to_owned()],
            ..Default::default()
        };
        b.model.source = main_file.to_owned();
        b.model.params.wtmass = 1.0;
        b
    }

    pub(crate) fn file_name(&self, loc: Loc) -> &str {
        &self.files[loc.file as usize]
    }

    pub(crate) fn err(
        &self,
        loc: Loc,
        entity: impl Into<String>,
        msg: impl Into<String>,
    ) -> ImportError {
        parse_err(self.file_name(loc), loc.line as usize, entity, msg)
    }

    pub(crate) fn add_node(&mut self, id: u64, x: [f64; 3], loc: Loc) {
        self.model.nodes.push(Node {
            id,
            x,
            displacement_frame: None,
        });
        self.node_loc.push(loc);
    }

    /// Add an element whose `ext_nodes` are external node ids.
    pub(crate) fn add_element(
        &mut self,
        id: u64,
        kind: ElementKind,
        ext_nodes: Vec<usize>,
        property: Option<usize>,
        card: &'static str,
        loc: Loc,
    ) {
        self.model.elements.push(Element {
            id,
            kind,
            nodes: ext_nodes,
            property,
            orientation: None,
        });
        self.elem_loc.push(loc);
        self.elem_card.push(card);
    }

    /// Record every element's source line in [`Model::element_sources`] (call while
    /// `elem_loc` still matches `model.elements`, after the duplicate-id check).
    pub(crate) fn record_element_sources(&mut self) {
        let mut v: Vec<(u64, u32, u32)> = self
            .model
            .elements
            .iter()
            .zip(&self.elem_loc)
            .map(|(e, l)| (e.id, l.file, l.line))
            .collect();
        v.sort_unstable_by_key(|&(id, _, _)| id);
        self.model.element_sources = v;
    }

    /// Node id map, failing on a duplicate node id.
    pub(crate) fn node_map(&self, card: &str) -> Result<IdMap, ImportError> {
        IdMap::build(self.model.nodes.iter().map(|n| n.id)).map_err(|(a, b)| {
            let loca = self.node_loc[a];
            self.err(
                self.node_loc[b],
                format!("{card} {}", self.model.nodes[b].id),
                format!(
                    "duplicate node id (first defined at {}:{})",
                    self.file_name(loca),
                    loca.line
                ),
            )
        })
    }

    /// Element id map, failing on a duplicate element id.
    pub(crate) fn element_map(&self) -> Result<IdMap, ImportError> {
        IdMap::build(self.model.elements.iter().map(|e| e.id)).map_err(|(a, b)| {
            let loca = self.elem_loc[a];
            self.err(
                self.elem_loc[b],
                format!("{} {}", self.elem_card[b], self.model.elements[b].id),
                format!(
                    "duplicate element id (first defined at {}:{})",
                    self.file_name(loca),
                    loca.line
                ),
            )
        })
    }

    /// Replace external node ids in element connectivity by dense indices.
    pub(crate) fn resolve_element_nodes(&mut self, nodes: &IdMap) -> Result<(), ImportError> {
        for (k, e) in self.model.elements.iter_mut().enumerate() {
            for n in e.nodes.iter_mut() {
                match nodes.get(*n as u64) {
                    Some(i) => *n = i,
                    None => {
                        let loc = self.elem_loc[k];
                        return Err(parse_err(
                            &self.files[loc.file as usize],
                            loc.line as usize,
                            format!("{} {}", self.elem_card[k], e.id),
                            format!("references unknown node {n}"),
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}

/// At most this many places are listed per card type in a note or warning.
const LISTED_PLACES: usize = 8;

/// "3 CDAMP1 (a.bdf:12, 14; b.bdf:3)": the count and the first places, lines grouped by file.
pub(crate) fn places(key: &str, locs: &[Loc], files: &[String]) -> String {
    let mut groups: Vec<(u32, Vec<String>)> = Vec::new();
    for l in locs.iter().take(LISTED_PLACES) {
        match groups.last_mut() {
            Some((f, lines)) if *f == l.file => lines.push(l.line.to_string()),
            _ => groups.push((l.file, vec![l.line.to_string()])),
        }
    }
    let mut list: Vec<String> = groups
        .iter()
        .map(|(f, lines)| format!("{}:{}", files[*f as usize], lines.join(", ")))
        .collect();
    if locs.len() > LISTED_PLACES {
        list.push("…".into());
    }
    format!("{} {key} ({})", locs.len(), list.join("; "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn id_map_dense_and_sparse_find_ids_and_duplicates() {
        let m = IdMap::build([5u64, 3, 9].into_iter()).unwrap();
        assert!(matches!(m, IdMap::Dense(_)));
        assert_eq!(
            (m.get(3), m.get(9), m.get(4), m.get(1 << 40)),
            (Some(1), Some(2), None, None)
        );
        let m = IdMap::build([5u64, 1 << 40].into_iter()).unwrap();
        assert!(matches!(m, IdMap::Sparse(_)));
        assert_eq!(m.get(1 << 40), Some(1));
        assert_eq!(IdMap::build([5u64, 3, 5].into_iter()).unwrap_err(), (0, 2));
        assert_eq!(
            IdMap::build([5u64, 1 << 40, 5].into_iter()).unwrap_err(),
            (0, 2)
        );
    }

    #[test]
    fn numbers_with_fortran_exponent() {
        assert_eq!(parse_f64(" 1.5D3 "), Some(1500.0));
        assert_eq!(parse_f64("2.1e11"), Some(2.1e11));
        assert_eq!(parse_f64("1.2.3"), None);
        assert_eq!(
            (parse_f64("nan"), parse_f64("inf"), parse_f64("1e400")),
            (None, None, None)
        );
        assert!(bad_number("-inf").contains("infinite"));
    }

    #[test]
    fn empty_and_binary_text_are_errors_with_line() {
        let e = check_text("f", b"  \n".to_vec()).unwrap_err();
        assert_eq!((e.line(), e.entity()), (Some(1), Some("file")));
        let e = check_text("f", b"a\nb\n\x00c".to_vec()).unwrap_err();
        assert_eq!(e.line(), Some(3));
        let e = check_text("f", b"a\n\xff\xfe".to_vec()).unwrap_err();
        assert_eq!(e.line(), Some(2));
    }
}
