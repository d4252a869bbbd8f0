//! Gmsh `.msh` 4.1 reader (ASCII and binary) → [`Model`].
//!
//! Sections read: `$MeshFormat`, `$PhysicalNames`, `$Entities`, `$Nodes`, `$Elements`; others
//! are skipped. Elements of the highest dimension present become [`Model::elements`] (the
//! solid mesh); lower-dimensional elements (surface triangles/quads, lines, points) only feed
//! the node sets. Physical groups: a group of the top dimension → element set (and no node
//! set); a lower-dimensional group → node set of every node of its elements (mid-side nodes
//! included), named by `$PhysicalNames` (upper-cased) or `PHYSICAL_<dim>_<tag>`.
//!
//! Node order: Gmsh orders the mid-side nodes of quadratic elements differently from Abaqus;
//! tet10 swaps nodes 9 and 10, hex20 and prism15 are permuted by edge (tables below).
//! The file carries no material: pass one, or no property is set.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::error::{parse_err, ImportError};
use super::text::{Builder, IdMap, Loc};
use crate::model::{ElementKind, Material, Model};

/// Read a Gmsh 4.1 mesh; solid elements get a solid section of `material` when given.
pub fn read(path: &Path, material: Option<&Material>) -> Result<Model, ImportError> {
    let file = path.display().to_string();
    let bytes = super::budget::read_bounded(path, super::budget::Content::Mesh)?;
    let mut model = parse(&file, &bytes)?;
    if let Some(m) = material {
        super::apply_default_material(&mut model, m);
    }
    Ok(model)
}

/// Abaqus node k = Gmsh node MAP[k].
const TET10: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];
const HEX20: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
];
const PRISM15: [usize; 15] = [0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11];

/// (dimension, node count, model kind, Abaqus permutation) of a Gmsh element type.
type TypeInfo = (u8, usize, Option<ElementKind>, Option<&'static [usize]>);

/// Gmsh element type → (dimension, node count, kind if a model element, Abaqus permutation).
fn element_type(t: i32) -> Option<TypeInfo> {
    use ElementKind::*;
    Some(match t {
        15 => (0, 1, None, None),
        1 => (1, 2, None, None),
        8 => (1, 3, None, None),
        2 => (2, 3, Some(Tri3), None),
        3 => (2, 4, Some(Quad4), None),
        9 => (2, 6, Some(Tri6), None),
        16 => (2, 8, Some(Quad8), None),
        10 => (2, 9, None, None),
        4 => (3, 4, Some(Tet4), None),
        11 => (3, 10, Some(Tet10), Some(&TET10)),
        5 => (3, 8, Some(Hex8), None),
        17 => (3, 20, Some(Hex20), Some(&HEX20)),
        6 => (3, 6, Some(Prism6), None),
        18 => (3, 15, Some(Prism15), Some(&PRISM15)),
        _ => return None,
    })
}

/// Cursor over the file: text lines for headers, tokens (ASCII) or raw values (binary).
struct Cur<'a> {
    file: &'a str,
    data: &'a [u8],
    pos: usize,
    /// 1-based line of `pos` (meaningless inside binary data).
    line: u32,
    binary: bool,
    size_t: usize,
    section: &'static str,
}

impl<'a> Cur<'a> {
    /// Error about the line last returned by [`Cur::next_line`].
    fn err_hdr(&self, msg: impl Into<String>) -> ImportError {
        parse_err(
            self.file,
            self.line.saturating_sub(1).max(1) as usize,
            self.section,
            msg,
        )
    }

    fn err(&self, msg: impl Into<String>) -> ImportError {
        let mut m = msg.into();
        if self.binary {
            m = format!("{m} (byte offset {})", self.pos);
        }
        parse_err(self.file, self.line as usize, self.section, m)
    }

    /// Next text line (without the newline), or `None` at the end.
    fn next_line(&mut self) -> Option<&'a str> {
        if self.pos >= self.data.len() {
            return None;
        }
        let rest = &self.data[self.pos..];
        let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        self.pos += (end + 1).min(rest.len());
        self.line += 1;
        let s = std::str::from_utf8(&rest[..end]).unwrap_or("\u{fffd}");
        Some(s.trim_end_matches('\r'))
    }

    fn token(&mut self) -> Result<&'a str, ImportError> {
        while self.pos < self.data.len() && self.data[self.pos].is_ascii_whitespace() {
            if self.data[self.pos] == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
        let start = self.pos;
        while self.pos < self.data.len() && !self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.err("unexpected end of file"));
        }
        std::str::from_utf8(&self.data[start..self.pos])
            .map_err(|_| self.err("binary data in an ASCII mesh"))
    }

    fn raw<const N: usize>(&mut self) -> Result<[u8; N], ImportError> {
        let b = self
            .data
            .get(self.pos..self.pos + N)
            .ok_or_else(|| self.err("unexpected end of file"))?;
        self.pos += N;
        let mut a = [0u8; N];
        a.copy_from_slice(b);
        Ok(a)
    }

    fn int(&mut self) -> Result<i64, ImportError> {
        if self.binary {
            return Ok(i32::from_le_bytes(self.raw::<4>()?) as i64);
        }
        let t = self.token()?;
        t.parse()
            .map_err(|_| self.err(format!("bad integer '{t}'")))
    }

    fn size(&mut self) -> Result<u64, ImportError> {
        if self.binary {
            return Ok(if self.size_t == 8 {
                u64::from_le_bytes(self.raw::<8>()?)
            } else {
                u32::from_le_bytes(self.raw::<4>()?) as u64
            });
        }
        let t = self.token()?;
        t.parse()
            .map_err(|_| self.err(format!("bad non-negative integer '{t}'")))
    }

    /// A count of items taking at least one tag each, bounded by the bytes that remain.
    fn count(&mut self) -> Result<usize, ImportError> {
        let tag = self.tag_bytes();
        self.count_of(tag, "items")
    }

    /// Smallest encoding of one tag: a digit and a separator, or a binary int.
    fn tag_bytes(&self) -> u64 {
        if self.binary {
            4
        } else {
            2
        }
    }

    /// A count of `what`, each taking at least `per_item` bytes: it must fit in the bytes that
    /// remain, checked before anything is reserved for it (the input budget, `import::budget`).
    fn count_of(&mut self, per_item: u64, what: &str) -> Result<usize, ImportError> {
        let n = self.size()?;
        let remaining = (self.data.len() - self.pos.min(self.data.len())) as u64;
        if n.saturating_mul(per_item) > remaining {
            return Err(self.err(format!(
                "the file claims {n} {what} (at least {} bytes), but only {remaining} bytes remain",
                n.saturating_mul(per_item)
            )));
        }
        Ok(n as usize)
    }

    /// A real that is skipped (any value, NaN included).
    fn dbl_any(&mut self) -> Result<f64, ImportError> {
        if self.binary {
            return Ok(f64::from_le_bytes(self.raw::<8>()?));
        }
        let t = self.token()?;
        t.parse().map_err(|_| self.err(format!("bad number '{t}'")))
    }

    /// A real used by the model: finite and within the input budget's range.
    fn dbl(&mut self) -> Result<f64, ImportError> {
        let (v, t) = if self.binary {
            let v = f64::from_le_bytes(self.raw::<8>()?);
            (Some(v), format!("{v:e}"))
        } else {
            let t = self.token()?;
            (t.parse::<f64>().ok(), t.to_owned())
        };
        v.and_then(super::budget::in_range)
            .ok_or_else(|| self.err(super::budget::bad_number(&t, v)))
    }

    /// Skip to the line `$End<name>`.
    fn end_section(&mut self, name: &str) -> Result<(), ImportError> {
        let want = format!("$End{name}");
        while let Some(l) = self.next_line() {
            if l.trim() == want {
                return Ok(());
            }
        }
        Err(self.err(format!("missing {want}")))
    }
}

/// What a mesh file's sections hold, gathered before the model is resolved.
struct Sections<'a> {
    b: Builder,
    /// $PhysicalNames: (dim, tag) → name.
    names: HashMap<(u8, i64), String>,
    /// $Entities: (dim, entity) → its physical groups.
    entity_phys: HashMap<(u8, i64), Vec<i64>>,
    /// Element blocks below the top dimension: (dim, entity, node ids), for node sets.
    low_dim: Vec<(u8, i64, Vec<u64>)>,
    /// Tags and lines of the lower-dimensional elements, for the duplicate-tag check.
    low_dim_tags: Vec<(u64, Loc)>,
    /// The entity of each model element.
    vol_entity: Vec<(u8, i64)>,
    file: &'a str,
}

fn parse(file: &str, bytes: &[u8]) -> Result<Model, ImportError> {
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(parse_err(file, 1, "file", "empty file"));
    }
    let mut c = Cur {
        file,
        data: bytes,
        pos: 0,
        line: 1,
        binary: false,
        size_t: 8,
        section: "file",
    };
    let mut s = Sections {
        b: Builder::new(file),
        names: HashMap::new(),
        entity_phys: HashMap::new(),
        low_dim: Vec::new(),
        low_dim_tags: Vec::new(),
        vol_entity: Vec::new(),
        file,
    };
    let mut seen_format = false;
    while let Some(l) = c.next_line() {
        let l = l.trim();
        if l.is_empty() {
            continue;
        }
        if !l.starts_with('$') {
            return Err(c.err(format!(
                "expected a section header, found '{}'",
                l.chars().take(40).collect::<String>()
            )));
        }
        match l {
            "$MeshFormat" => {
                mesh_format(&mut c)?;
                seen_format = true;
                c.end_section("MeshFormat")?;
            }
            _ if !seen_format => return Err(c.err_hdr("file does not start with $MeshFormat")),
            "$PhysicalNames" => physical_names(&mut c, &mut s.names)?,
            "$Entities" => entities(&mut c, &mut s.entity_phys)?,
            "$Nodes" => nodes(&mut c, &mut s.b)?,
            "$Elements" => elements(&mut c, &mut s)?,
            _ => {
                let name = l[1..].to_owned();
                c.section = "section";
                c.end_section(&name)?;
            }
        }
    }
    if !seen_format {
        return Err(parse_err(
            file,
            1,
            "file",
            "not a Gmsh mesh: no $MeshFormat",
        ));
    }
    s.into_model()
}

/// $MeshFormat: version 4.1, ASCII or little-endian binary, the size of size_t.
fn mesh_format(c: &mut Cur) -> Result<(), ImportError> {
    c.section = "$MeshFormat";
    let hdr = c.next_line().ok_or_else(|| c.err("missing version line"))?;
    let v: Vec<&str> = hdr.split_whitespace().collect();
    if v.len() < 3 || !v[0].starts_with("4.1") {
        return Err(c.err_hdr(format!("only MSH 4.1 is supported, found '{hdr}'")));
    }
    c.binary = v[1] == "1";
    c.size_t = v[2]
        .parse()
        .ok()
        .filter(|s| *s == 4 || *s == 8)
        .ok_or_else(|| c.err_hdr("bad data size"))?;
    if c.binary {
        if c.raw::<4>()? != 1i32.to_le_bytes() {
            return Err(c.err("big-endian binary mesh not supported"));
        }
        c.next_line();
    }
    Ok(())
}

/// $PhysicalNames: (dim, tag) → name, upper-cased.
fn physical_names(c: &mut Cur, names: &mut HashMap<(u8, i64), String>) -> Result<(), ImportError> {
    c.section = "$PhysicalNames";
    let n: usize = c
        .next_line()
        .and_then(|s| s.trim().parse().ok())
        .ok_or_else(|| c.err_hdr("bad count"))?;
    for _ in 0..n {
        let s = c
            .next_line()
            .ok_or_else(|| c.err("unexpected end of file"))?;
        let mut it = s.splitn(3, ' ');
        let dim = it.next().and_then(|x| x.parse::<u8>().ok());
        let tag = it.next().and_then(|x| x.parse::<i64>().ok());
        let name = it
            .next()
            .map(|x| x.trim().trim_matches('"').to_ascii_uppercase());
        match (dim, tag, name) {
            (Some(d), Some(t), Some(nm)) => names.insert((d, t), nm),
            _ => return Err(c.err_hdr(format!("bad physical name line '{s}'"))),
        };
    }
    c.end_section("PhysicalNames")?;
    Ok(())
}

/// $Entities: the physical groups of every entity (bounding boxes skipped).
fn entities(
    c: &mut Cur,
    entity_phys: &mut HashMap<(u8, i64), Vec<i64>>,
) -> Result<(), ImportError> {
    c.section = "$Entities";
    let counts = [c.count()?, c.count()?, c.count()?, c.count()?];
    for (dim, &n) in counts.iter().enumerate() {
        for _ in 0..n {
            let tag = c.int()?;
            let nbox = if dim == 0 { 3 } else { 6 };
            // Bounding boxes are ignored, and Gmsh may write ±DBL_MAX for an
            // empty one: parsed, not range-checked.
            for _ in 0..nbox {
                c.dbl_any()?;
            }
            let np = c.count()?;
            let mut phys = Vec::with_capacity(np);
            for _ in 0..np {
                phys.push(c.int()?);
            }
            if dim > 0 {
                let nb = c.count()?;
                for _ in 0..nb {
                    c.int()?;
                }
            }
            entity_phys.insert((dim as u8, tag), phys);
        }
    }
    c.end_section("Entities")?;
    Ok(())
}

/// $Nodes: node blocks (tags, then coordinates; parametric coordinates skipped).
fn nodes(c: &mut Cur, b: &mut Builder) -> Result<(), ImportError> {
    c.section = "$Nodes";
    // A node takes at least a tag and three coordinates.
    let per_node = if c.binary { c.size_t as u64 + 24 } else { 8 };
    let (blocks, total) = (c.count()?, c.count_of(per_node, "nodes")?);
    c.size()?;
    c.size()?;
    b.model.nodes.reserve(total);
    for _ in 0..blocks {
        let dim = c.int()?;
        c.int()?;
        let parametric = c.int()? != 0;
        let n = c.count_of(per_node, "nodes")?;
        let start = b.model.nodes.len();
        let loc = Loc {
            file: 0,
            line: c.line,
        };
        for _ in 0..n {
            let id = c.size()?;
            b.add_node(id, [0.0; 3], loc);
        }
        let extra = if parametric {
            dim.clamp(0, 3) as usize
        } else {
            0
        };
        for k in 0..n {
            let x = [c.dbl()?, c.dbl()?, c.dbl()?];
            for _ in 0..extra {
                c.dbl_any()?;
            }
            b.model.nodes[start + k].x = x;
            b.node_loc[start + k] = Loc {
                file: 0,
                line: c.line,
            };
        }
    }
    c.end_section("Nodes")?;
    Ok(())
}

/// $Elements: the top dimension's elements become the model's; lower-dimensional blocks are
/// kept for the node sets of their physical groups.
fn elements(c: &mut Cur, s: &mut Sections) -> Result<(), ImportError> {
    c.section = "$Elements";
    let blocks = c.count()?;
    c.size()?;
    c.size()?;
    c.size()?;
    let mut pending = Vec::new();
    for _ in 0..blocks {
        let dim = c.int()?;
        let ent = c.int()?;
        let ty = c.int()?;
        let (tdim, nn, kind, perm) = element_type(ty as i32)
            .ok_or_else(|| c.err(format!("unsupported element type {ty}")))?;
        // An element takes at least its tag and its node tags.
        let per_elem = (nn as u64 + 1) * if c.binary { c.size_t as u64 } else { 2 };
        let n = c.count_of(per_elem, "elements")?;
        if dim != tdim as i64 {
            return Err(c.err(format!("element type {ty} in an entity of dimension {dim}")));
        }
        let mut ids = Vec::with_capacity(n * (nn + 1));
        let mut locs = Vec::with_capacity(n);
        for _ in 0..n {
            locs.push(Loc {
                file: 0,
                line: c.line + u32::from(!c.binary),
            });
            for _ in 0..=nn {
                ids.push(c.size()?);
            }
        }
        pending.push((tdim, ent, nn, kind, perm, ids, locs));
    }
    c.end_section("Elements")?;
    let top = pending.iter().map(|p| p.0).max().unwrap_or(0);
    for (dim, ent, nn, kind, perm, ids, locs) in pending {
        if dim == top {
            let kind = kind.ok_or_else(|| {
                c.err(format!(
                    "top-dimension element of {nn} nodes is not a model element"
                ))
            })?;
            for (e, chunk) in ids.chunks_exact(nn + 1).enumerate() {
                let nodes: Vec<usize> = match perm {
                    Some(p) => p.iter().map(|&k| chunk[1 + k] as usize).collect(),
                    None => chunk[1..].iter().map(|&v| v as usize).collect(),
                };
                s.vol_entity.push((dim, ent));
                s.b.add_element(chunk[0], kind, nodes, None, "element", locs[e]);
            }
        } else {
            s.low_dim_tags
                .extend(ids.chunks_exact(nn + 1).map(|ch| ch[0]).zip(locs));
            let nodes = ids
                .chunks_exact(nn + 1)
                .flat_map(|ch| ch[1..].iter().copied())
                .collect();
            s.low_dim.push((dim, ent, nodes));
        }
    }
    Ok(())
}

impl Sections<'_> {
    /// Ids → indices; physical groups of the lower-dimensional blocks → node sets, of the
    /// model elements → element sets.
    fn into_model(self) -> Result<Model, ImportError> {
        let Sections {
            mut b,
            names,
            entity_phys,
            low_dim,
            low_dim_tags,
            vol_entity,
            file,
        } = self;
        let nodes = b.node_map("node")?;
        b.resolve_element_nodes(&nodes)?;
        let elements = b.element_map()?;
        duplicate_low_dim_tag(&b, &elements, &low_dim_tags)?;
        let group_name = |d: u8, t: i64| {
            names
                .get(&(d, t))
                .cloned()
                .unwrap_or_else(|| format!("PHYSICAL_{d}_{t}"))
        };
        let mut node_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        for (dim, ent, ids) in low_dim {
            for &t in entity_phys
                .get(&(dim, ent))
                .map(Vec::as_slice)
                .unwrap_or(&[])
            {
                let set = node_sets.entry(group_name(dim, t)).or_default();
                for &id in &ids {
                    set.push(nodes.get(id).ok_or_else(|| {
                        parse_err(
                            file,
                            1,
                            "$Elements",
                            format!(
                                "element of entity {ent} (dim {dim}) references unknown node {id}"
                            ),
                        )
                    })?);
                }
            }
        }
        for s in node_sets.values_mut() {
            s.sort_unstable();
            s.dedup();
        }
        let mut element_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        for (k, (dim, ent)) in vol_entity.iter().enumerate() {
            for &t in entity_phys
                .get(&(*dim, *ent))
                .map(Vec::as_slice)
                .unwrap_or(&[])
            {
                element_sets.entry(group_name(*dim, t)).or_default().push(k);
            }
        }
        b.model.node_sets = node_sets;
        b.model.element_sets = element_sets;
        b.model.files = b.files.clone();
        b.record_element_sources();
        Ok(b.model)
    }
}

/// Gmsh's element tags are unique across all dimensions (its API calls them "unique, strictly
/// positive identifiers"): a boundary element may not reuse the tag of a model element or of
/// another boundary element. The later of the two lines is reported, naming the first.
fn duplicate_low_dim_tag(
    b: &Builder,
    elements: &IdMap,
    low: &[(u64, Loc)],
) -> Result<(), ImportError> {
    let mut seen: HashMap<u64, Loc> = HashMap::with_capacity(low.len());
    for &(tag, loc) in low {
        let first = match elements.get(tag) {
            Some(k) => b.elem_loc[k],
            None => match seen.insert(tag, loc) {
                Some(prev) => prev,
                None => continue,
            },
        };
        let (first, later) = if first.line <= loc.line {
            (first, loc)
        } else {
            (loc, first)
        };
        return Err(b.err(
            later,
            format!("element {tag}"),
            format!(
                "duplicate element id (first defined at {}:{}; element tags are unique across \
                 all dimensions)",
                b.file_name(first),
                first.line
            ),
        ));
    }
    Ok(())
}
