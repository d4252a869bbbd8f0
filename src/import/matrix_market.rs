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
use super::text::{parse_f64, parse_u64, read_text};
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
    let mut dofs = Vec::with_capacity(k.n);
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
            x[d] = parse_f64(f[1 + d])
                .ok_or_else(|| err(ent.clone(), format!("bad number '{}'", f[1 + d])))?;
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
    let mut entries: HashMap<(usize, usize), (f64, usize)> = HashMap::new();
    let mut count = 0usize;
    for (i, raw) in lines {
        let s = raw.trim();
        if s.is_empty() || s.starts_with('%') {
            continue;
        }
        let f: Vec<&str> = s.split_whitespace().collect();
        let Some((n, nnz)) = size else {
            let (r, c, z) = match f.as_slice() {
                [r, c, z] => (parse_u64(r), parse_u64(c), parse_u64(z)),
                _ => (None, None, None),
            };
            match (r, c, z) {
                (Some(r), Some(c), Some(z)) if r == c => size = Some((r as usize, z as usize)),
                _ => {
                    return Err(err(
                        i + 1,
                        "size",
                        format!("expected `n n nnz` of a square matrix, found `{s}`"),
                    ))
                }
            }
            continue;
        };
        let ent = format!("entry {}", count + 1);
        let [r, c, v] = f.as_slice() else {
            return Err(err(
                i + 1,
                &ent,
                format!("expected `row col value`, found `{s}`"),
            ));
        };
        let (Some(r), Some(c)) = (parse_u64(r), parse_u64(c)) else {
            return Err(err(i + 1, &ent, format!("bad index in `{s}`")));
        };
        let v = parse_f64(v)
            .filter(|v| v.is_finite())
            .ok_or_else(|| err(i + 1, &ent, format!("bad value '{v}'")))?;
        let (r, c) = (r as usize, c as usize);
        if r == 0 || c == 0 || r > n || c > n {
            return Err(err(i + 1, &ent, format!("index ({r},{c}) outside 1..{n}")));
        }
        count += 1;
        if count > nnz {
            return Err(err(
                i + 1,
                &ent,
                format!("more entries than the {nnz} announced"),
            ));
        }
        if entries.insert((r - 1, c - 1), (v, i + 1)).is_some() {
            return Err(err(i + 1, &ent, format!("duplicate entry ({r},{c})")));
        }
    }
    let Some((n, nnz)) = size else {
        return Err(err(
            text.lines().count(),
            "size",
            "missing size line".into(),
        ));
    };
    if count != nnz {
        return Err(err(
            text.lines().count(),
            "size",
            format!("{count} entries, {nnz} announced"),
        ));
    }
    let mut upper = Vec::with_capacity(entries.len());
    for (&(r, c), &(v, line)) in &entries {
        let mirror = entries.get(&(c, r));
        if r == c {
            upper.push((r, c, v));
        } else if symmetric {
            if mirror.is_some() {
                return Err(err(
                    line,
                    &format!("entry ({},{})", r + 1, c + 1),
                    "both triangles stored in a symmetric file".into(),
                ));
            }
            upper.push((r.min(c), r.max(c), v));
        } else {
            let w = mirror.map_or(0.0, |m| m.0);
            if (v - w).abs() > 1e-12 * v.abs().max(w.abs()) {
                return Err(err(
                    line,
                    &format!("entry ({},{})", r + 1, c + 1),
                    format!("general matrix is not symmetric: {v} vs {w}"),
                ));
            }
            if r < c {
                upper.push((r, c, v));
            }
        }
    }
    upper.sort_by_key(|e| (e.1, e.0));
    Ok(SymmetricTriplets { n, upper })
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
