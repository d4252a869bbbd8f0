//! CalculiX matrix dump reader: `JOB.sti` (K), `JOB.mas` (M) and `JOB.dof`, as written by
//! `*FREQUENCY, SOLVER=MATRIXSTORAGE`.
//!
//! Layout (checked against `fixtures/reference/e_matrices/`): each line of `.sti`/`.mas` is
//! `row col value` with 1-based *equation* numbers, upper triangle including the diagonal
//! (row ≤ col), column by column; line k of `.dof` is `node.direction` for equation k
//! (e.g. `17.2` = node 17, uy). Constrained dofs are absent from the equation system.
//!
//! The result is plain triplets (no linear algebra in `import`).

use std::path::Path;

pub use crate::import::error::CcxMatrixError;

/// Upper-triangle (row ≤ col) entries of a symmetric n×n matrix, 0-based.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SymmetricTriplets {
    /// Matrix dimension.
    pub n: usize,
    /// (row, col, value) with row ≤ col.
    pub upper: Vec<(usize, usize, f64)>,
}

impl SymmetricTriplets {
    /// All entries of the full symmetric matrix (off-diagonal entries mirrored).
    pub fn full(&self) -> Vec<(usize, usize, f64)> {
        let mut out = Vec::with_capacity(2 * self.upper.len());
        for &(r, c, v) in &self.upper {
            out.push((r, c, v));
            if r != c {
                out.push((c, r, v));
            }
        }
        out
    }
}

/// One equation of the dump: external node id and 0-based direction (0 = ux … 5 = rz).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EquationDof {
    /// External node id.
    pub node: u64,
    /// 0-based dof direction.
    pub dir: u8,
}

/// K, M and the equation → dof table of one CalculiX matrix dump.
#[derive(Debug, Clone, PartialEq)]
pub struct CcxMatrices {
    /// Equation k ↔ (node, direction).
    pub dofs: Vec<EquationDof>,
    /// Stiffness, upper triangle.
    pub k: SymmetricTriplets,
    /// Mass, upper triangle (`None` when no `.mas` file exists).
    pub m: Option<SymmetricTriplets>,
}

fn read(path: &Path) -> Result<String, CcxMatrixError> {
    use crate::import::budget::{read_bounded, Content};
    let text = match read_bounded(path, Content::Text) {
        Ok(bytes) => String::from_utf8(bytes).map_err(|_| "invalid UTF-8".to_owned()),
        Err(crate::import::ImportError::Io { source, .. }) => {
            return Err(CcxMatrixError::Io {
                path: path.to_owned(),
                source,
            })
        }
        Err(e) => Err(e.to_string()),
    };
    text.map_err(|message| syntax(path, 1, message))
}

fn syntax(path: &Path, line: usize, message: String) -> CcxMatrixError {
    CcxMatrixError::Syntax {
        path: path.to_owned(),
        line,
        message,
    }
}

/// Parse a `.dof` file: one `node.direction` per line.
pub fn parse_dof_table(path: &Path, text: &str) -> Result<Vec<EquationDof>, CcxMatrixError> {
    let mut dofs = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let s = raw.trim();
        if s.is_empty() {
            continue;
        }
        let bad = || {
            syntax(
                path,
                i + 1,
                format!("expected `node.direction` (e.g. 17.2), found `{s}`"),
            )
        };
        let (node, dir) = s.split_once('.').ok_or_else(bad)?;
        let node: u64 = node.parse().map_err(|_| bad())?;
        let dir: u8 = dir.parse().map_err(|_| bad())?;
        if !(1..=6).contains(&dir) {
            return Err(syntax(
                path,
                i + 1,
                format!("direction {dir} of node {node} is not in 1..6"),
            ));
        }
        dofs.push(EquationDof { node, dir: dir - 1 });
    }
    Ok(dofs)
}

/// Parse a `.sti`/`.mas` file of `n` equations: `row col value`, 1-based, row ≤ col.
pub fn parse_upper_triplets(
    path: &Path,
    text: &str,
    n: usize,
) -> Result<SymmetricTriplets, CcxMatrixError> {
    let mut upper = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let mut it = raw.split_whitespace();
        let (Some(r), Some(c), Some(v), None) = (it.next(), it.next(), it.next(), it.next()) else {
            if raw.trim().is_empty() {
                continue;
            }
            return Err(syntax(
                path,
                i + 1,
                format!("expected `row col value`, found `{}`", raw.trim()),
            ));
        };
        let r: usize = r
            .parse()
            .map_err(|_| syntax(path, i + 1, format!("bad row number `{r}`")))?;
        let c: usize = c
            .parse()
            .map_err(|_| syntax(path, i + 1, format!("bad column number `{c}`")))?;
        let v: f64 = v
            .parse()
            .ok()
            .and_then(crate::import::budget::in_range)
            .ok_or_else(|| {
                syntax(
                    path,
                    i + 1,
                    format!("bad value `{v}`: not a finite real with |x| < 1e150"),
                )
            })?;
        if r == 0 || c == 0 || r > n || c > n {
            return Err(syntax(
                path,
                i + 1,
                format!("entry ({r},{c}) outside the {n} equations of the .dof table"),
            ));
        }
        if r > c {
            return Err(syntax(
                path,
                i + 1,
                format!(
                    "entry ({r},{c}) is below the diagonal; the dump stores the upper triangle"
                ),
            ));
        }
        if !v.is_finite() {
            return Err(syntax(
                path,
                i + 1,
                format!("entry ({r},{c}) is not finite"),
            ));
        }
        upper.push((r - 1, c - 1, v));
    }
    Ok(SymmetricTriplets { n, upper })
}

/// Read `STEM.dof`, `STEM.sti` and (if present) `STEM.mas`.
pub fn read_ccx_matrices(stem: &Path) -> Result<CcxMatrices, CcxMatrixError> {
    let with = |ext: &str| stem.with_extension(ext);
    let dof_path = with("dof");
    let dofs = parse_dof_table(&dof_path, &read(&dof_path)?)?;
    let sti_path = with("sti");
    let k = parse_upper_triplets(&sti_path, &read(&sti_path)?, dofs.len())?;
    let mas_path = with("mas");
    let m = if mas_path.exists() {
        Some(parse_upper_triplets(
            &mas_path,
            &read(&mas_path)?,
            dofs.len(),
        )?)
    } else {
        None
    };
    Ok(CcxMatrices { dofs, k, m })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_hex8_single_dump() {
        let stem = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("fixtures/reference/e_matrices/hex8_single/ccx_matrix_free");
        let d = read_ccx_matrices(&stem).unwrap();
        assert_eq!(d.dofs.len(), 24);
        assert_eq!(d.dofs[0], EquationDof { node: 1, dir: 0 });
        // case.json: 300 stored upper entries of K, total mass sum(M)/3 = 5.40161012 kg.
        assert_eq!(d.k.upper.len(), 300);
        let m = d.m.unwrap();
        let total: f64 = m.full().iter().map(|e| e.2).sum::<f64>() / 3.0;
        assert!((total - 5.401610119999975).abs() < 1e-9, "{total}");
    }

    #[test]
    fn rejects_lower_triangle_and_bad_dof() {
        let p = Path::new("x.sti");
        assert!(matches!(
            parse_upper_triplets(p, "2 1 1.0\n", 2),
            Err(CcxMatrixError::Syntax { line: 1, .. })
        ));
        assert!(parse_dof_table(Path::new("x.dof"), "1.1\n3.9\n")
            .unwrap_err()
            .to_string()
            .contains("x.dof:2"));
    }
}
