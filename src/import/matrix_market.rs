//! Matrix Market K/M plus a node table → [`MatrixModel`], for users who only have matrices.
//!
//! * Matrices: `%%MatrixMarket matrix coordinate real symmetric` (lower or upper triangle
//!   stored, never both for the same pair) or `… real general` (then checked to be symmetric to
//!   1e-12 relative). Indices are 1-based. The result is upper-triangle triplets; no linear
//!   algebra here.
//! * Node table: one node a line, `id x y z ndof` (ndof 3 or 6), whitespace- or
//!   comma-separated, `#` or `%` comments. Matrix row k belongs to the node whose dof block
//!   holds k, in table order: node 1 rows 0..ndof₁, node 2 the next ndof₂, …

use std::collections::HashMap;
use std::path::Path;

use super::ccx_matrices::{EquationDof, SymmetricTriplets};
use super::error::{parse_err, ImportError};
use super::text::{bad_number, parse_f64, parse_u64, read_text};
use crate::model::Node;

/// A body given only by its matrices.
#[derive(Debug, Clone, PartialEq)]
pub struct MatrixModel {
    /// Files read (K path).
    pub source: String,
    /// Nodes in table order (basic-frame coordinates).
    pub nodes: Vec<Node>,
    /// Equation k ↔ (external node id, direction 0..5).
    pub dofs: Vec<EquationDof>,
    /// Stiffness, upper triangle.
    pub k: SymmetricTriplets,
    /// Mass, upper triangle.
    pub m: SymmetricTriplets,
}

/// Read K, M and the node table; checks that the dimensions agree.
pub fn read(k_path: &Path, m_path: &Path, nodes_path: &Path) -> Result<MatrixModel, ImportError> {
    let (nodes, ndof) = read_node_table(nodes_path)?;
    let k = read_matrix(k_path)?;
    let m = read_matrix(m_path)?;
    // Sized by the node table (read in full), not by a count a matrix header claims.
    let mut dofs = Vec::with_capacity(ndof.iter().map(|&d| d as usize).sum());
    for (n, &nd) in nodes.iter().zip(&ndof) {
        dofs.extend((0..nd).map(|d| EquationDof { node: n.id, dir: d }));
    }
    for (path, mat) in [(k_path, &k), (m_path, &m)] {
        if mat.n != dofs.len() {
            return Err(parse_err(
                &path.display().to_string(),
                1,
                "matrix",
                format!(
                    "matrix is {0}×{0} but the node table {1} defines {2} dofs",
                    mat.n,
                    nodes_path.display(),
                    dofs.len()
                ),
            ));
        }
    }
    Ok(MatrixModel {
        source: k_path.display().to_string(),
        nodes,
        dofs,
        k,
        m,
    })
}

/// Read a node table: nodes and their dof counts.
pub fn read_node_table(path: &Path) -> Result<(Vec<Node>, Vec<u8>), ImportError> {
    let file = path.display().to_string();
    let text = read_text(path)?;
    let mut nodes = Vec::new();
    let mut ndof = Vec::new();
    let mut seen = HashMap::new();
    for (i, raw) in text.lines().enumerate() {
        let s = raw.split(['#', '%']).next().unwrap_or("").trim();
        if s.is_empty() {
            continue;
        }
        let f: Vec<&str> = s
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .collect();
        let err = |ent: String, m: String| parse_err(&file, i + 1, ent, m);
        if f.len() != 5 {
            return Err(err(
                "node".into(),
                format!("expected `id x y z ndof`, found `{s}`"),
            ));
        }
        let id =
            parse_u64(f[0]).ok_or_else(|| err("node".into(), format!("bad node id '{}'", f[0])))?;
        let ent = format!("node {id}");
        let mut x = [0.0; 3];
        for d in 0..3 {
            x[d] = parse_f64(f[1 + d]).ok_or_else(|| err(ent.clone(), bad_number(f[1 + d])))?;
        }
        let nd = match f[4] {
            "3" => 3,
            "6" => 6,
            o => return Err(err(ent, format!("ndof must be 3 or 6, found '{o}'"))),
        };
        if let Some(first) = seen.insert(id, i + 1) {
            return Err(err(
                ent,
                format!("duplicate node id (first on line {first})"),
            ));
        }
        nodes.push(Node {
            id,
            x,
            displacement_frame: None,
        });
        ndof.push(nd);
    }
    Ok((nodes, ndof))
}

/// Read one symmetric Matrix Market matrix as upper-triangle triplets.
pub fn read_matrix(path: &Path) -> Result<SymmetricTriplets, ImportError> {
    let file = path.display().to_string();
    let text = read_text(path)?;
    let mut lines = text.lines().enumerate();
    let err = |line: usize, ent: &str, m: String| parse_err(&file, line, ent, m);
    let (_, header) = lines
        .next()
        .ok_or_else(|| err(1, "header", "empty file".into()))?;
    let h: Vec<String> = header
        .split_whitespace()
        .map(str::to_ascii_lowercase)
        .collect();
    if h.len() != 5
        || h[0] != "%%matrixmarket"
        || h[1] != "matrix"
        || h[2] != "coordinate"
        || h[3] != "real"
    {
        return Err(err(1, "header", format!("expected `%%MatrixMarket matrix coordinate real symmetric|general`, found `{header}`")));
    }
    let symmetric = match h[4].as_str() {
        "symmetric" => true,
        "general" => false,
        o => return Err(err(1, "header", format!("symmetry `{o}` not supported"))),
    };
    let mut size = None;
    let mut entries: Vec<Entry> = Vec::new();
    for (i, raw) in lines {
        let s = raw.trim();
        if s.is_empty() || s.starts_with('%') {
            continue;
        }
        let mut f = s.split_whitespace();
        let fields = [f.next(), f.next(), f.next(), f.next()];
        let Some((n, nnz)) = size else {
            let parsed = match fields {
                [Some(r), Some(c), Some(z), None] => (parse_u64(r), parse_u64(c), parse_u64(z)),
                _ => (None, None, None),
            };
            match parsed {
                (Some(r), Some(c), Some(z)) if r == c && r <= u64::from(u32::MAX) => {
                    // The input budget (import::budget): an entry `i j v` takes at least 6
                    // bytes, so the count must fit in what remains before it is reserved.
                    let at = raw.as_ptr() as usize - text.as_ptr() as usize + raw.len();
                    let remaining = (text.len() - at) as u64;
                    if z.saturating_mul(6) > remaining {
                        return Err(err(
                            i + 1,
                            "size",
                            format!("the size line claims {z} entries (at least {} bytes), but only {remaining} bytes remain", z.saturating_mul(6)),
                        ));
                    }
                    size = Some((r as usize, z as usize));
                    entries.reserve_exact(z as usize);
                }
                _ => {
                    return Err(err(
                        i + 1,
                        "size",
                        format!("expected `n n nnz` of a square matrix (n < 2³²), found `{s}`"),
                    ))
                }
            }
            continue;
        };
        let ent = || format!("entry {}", entries.len() + 1);
        let [Some(r), Some(c), Some(v), None] = fields else {
            return Err(err(
                i + 1,
                &ent(),
                format!("expected `row col value`, found `{s}`"),
            ));
        };
        let (Some(r), Some(c)) = (parse_u64(r), parse_u64(c)) else {
            return Err(err(i + 1, &ent(), format!("bad index in `{s}`")));
        };
        let v = parse_f64(v).ok_or_else(|| err(i + 1, &ent(), bad_number(v)))?;
        if r == 0 || c == 0 || r > n as u64 || c > n as u64 {
            return Err(err(
                i + 1,
                &ent(),
                format!("index ({r},{c}) outside 1..{n}"),
            ));
        }
        if entries.len() == nnz {
            return Err(err(
                i + 1,
                &ent(),
                format!("more entries than the {nnz} announced"),
            ));
        }
        // r, c ≤ n < 2³² (checked on the size line), so the casts are exact.
        entries.push(Entry {
            row: (r - 1) as u32,
            col: (c - 1) as u32,
            value: v,
            line: i + 1,
        });
    }
    let Some((n, nnz)) = size else {
        return Err(err(
            text.lines().count(),
            "size",
            "missing size line".into(),
        ));
    };
    if entries.len() != nnz {
        return Err(err(
            text.lines().count(),
            "size",
            format!("{} entries, {nnz} announced", entries.len()),
        ));
    }
    // One sort puts both triangles' entries of a pair side by side (upper first) and the
    // result in column-major upper-triangle order; no hashing (13 M entries at 180k dofs).
    entries.sort_unstable_by_key(|e| (e.row.max(e.col), e.row.min(e.col), e.row > e.col));
    let entity = |e: &Entry| format!("entry ({},{})", e.row + 1, e.col + 1);
    let mut upper = Vec::with_capacity(entries.len());
    for group in entries.chunk_by(|a, b| {
        (a.row.max(a.col), a.row.min(a.col)) == (b.row.max(b.col), b.row.min(b.col))
    }) {
        if let Some(w) = group.windows(2).find(|w| w[0].row == w[1].row) {
            let later = if w[0].line > w[1].line { &w[0] } else { &w[1] };
            return Err(err(later.line, &entity(later), "duplicate entry".into()));
        }
        // Now at most two entries: the upper (row ≤ col) one first, then its mirror.
        let first = &group[0];
        let (r, c) = (first.row as usize, first.col as usize);
        let mirror = group.get(1);
        if r == c {
            upper.push((r, c, first.value));
        } else if symmetric {
            if let Some(m) = mirror {
                let later = if m.line > first.line { m } else { first };
                return Err(err(
                    later.line,
                    &entity(later),
                    "both triangles stored in a symmetric file".into(),
                ));
            }
            upper.push((r.min(c), r.max(c), first.value));
        } else {
            let w = mirror.map_or(0.0, |m| m.value);
            let v = first.value;
            if (v - w).abs() > 1e-12 * v.abs().max(w.abs()) {
                return Err(err(
                    first.line,
                    &entity(first),
                    format!("general matrix is not symmetric: {v} vs {w}"),
                ));
            }
            if r < c {
                upper.push((r, c, v));
            }
        }
    }
    Ok(SymmetricTriplets { n, upper })
}

/// One stored entry of a Matrix Market file (0-based indices, 1-based line).
struct Entry {
    row: u32,
    col: u32,
    value: f64,
    line: usize,
}

/// A [`MatrixModel`] from a CalculiX matrix dump (`STEM.sti/.mas/.dof`, see
/// [`super::ccx_matrices`]) plus the mesh it was made from (for node coordinates). Nodes are
/// those of the dump's equations, in order of first appearance. The dump must hold M.
pub fn from_ccx_dump(stem: &Path, mesh: &crate::model::Model) -> Result<MatrixModel, ImportError> {
    let dump = super::ccx_matrices::read_ccx_matrices(stem)?;
    let dof_file = stem.with_extension("dof").display().to_string();
    let m = dump.m.ok_or_else(|| {
        parse_err(
            &stem.with_extension("mas").display().to_string(),
            1,
            "file",
            "no .mas (mass) file next to the .sti",
        )
    })?;
    let index = mesh.node_index_by_id();
    let mut nodes: Vec<Node> = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for (k, eq) in dump.dofs.iter().enumerate() {
        if !seen.insert(eq.node) {
            continue;
        }
        let i = index.get(&eq.node).ok_or_else(|| {
            parse_err(
                &dof_file,
                k + 1,
                format!("node {}", eq.node),
                format!("node not in the mesh {}", mesh.source),
            )
        })?;
        nodes.push(mesh.nodes[*i].clone());
    }
    Ok(MatrixModel {
        source: stem.display().to_string(),
        nodes,
        dofs: dump.dofs,
        k: dump.k,
        m,
    })
}
