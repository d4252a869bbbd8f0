//! The constrained K and M in Matrix Market, with a dof table — the files `flexbody build
//! --write-matrices DIR` and `flexbody export --to mtx` write (the system itself comes from the
//! pipeline, [`crate::pipeline::matrices`]).
//!
//! Files in DIR:
//! * `K.mtx`, `M.mtx`: `%%MatrixMarket matrix coordinate real symmetric`, the lower triangle
//!   (row ≥ column, 1-based), column by column, rows ascending; values as the shortest decimal
//!   that reads back to the same binary64 (so a reader gets the matrices bit for bit). Explicit
//!   zeros are not written. Units: the model's.
//! * `dofs.txt`: equation k (1-based, line k after the `#` comments) = `k node component`, with
//!   the node's external id and the component 1…6 = ux uy uz rx ry rz in the node's
//!   displacement frame (Nastran's CD; the basic frame for Abaqus/Gmsh models). The interior
//!   dofs of ccx 2.20's C3D8I (its incompatible-mode amplitudes, no node) come after all the
//!   nodes' dofs as `k element component` with the element's external id and component
//!   7…15 = modes 1 − ξ², 1 − η², 1 − ζ² × x y z (basic frame), as ccx numbers them after its
//!   nodes (its three extra nodes per element).
//! * `coords.csv`: the coordinates of the nodes `dofs.txt` names, for a peer that needs the
//!   geometry with K and M (a spider fit, its own Craig–Bampton on nodes it picks by place):
//!   a `node,x,y,z` header, then one line per node in the order of its first dof, the node's
//!   external id and its position in the basic frame (model units, shortest round-trip
//!   decimals). Spider centres `build` added are there too.
//!
//! **Dof order**: the independent dofs node by node in the model's node order (the order the
//! deck defines its nodes; spider centre nodes `build` adds come last), and within a node by
//! component. A dof is absent when an SPC or a held component fixes it or when it is dependent
//! (an RBE2 leg, an RBE3 reference not at an interface). For a deck whose nodes are numbered in
//! ascending order this is CalculiX's equation order (`*FREQUENCY, SOLVER=MATRIXSTORAGE`): its
//! `.dof` table equals `dofs.txt` line for line (`tests/export_mtx.rs`).
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::fe;
use crate::solve::SparseColMat;

/// The constrained system: K_r, M_r and the dof each equation is.
#[derive(Debug, Clone)]
pub struct ConstrainedSystem {
    /// K_r = Tᵀ K T, full symmetric.
    pub k: SparseColMat<usize, f64>,
    /// M_r = Tᵀ M T, full symmetric.
    pub m: SparseColMat<usize, f64>,
    /// Equation k ↔ (external node id, component 0…5), or for an interior dof (external
    /// element id, 6 + its index).
    pub dofs: Vec<(u64, u8)>,
    /// Lumped or consistent.
    pub mass: fe::MassKind,
    /// Number of physical dofs before the elimination.
    pub physical_dofs: usize,
    /// (external id, basic-frame position) of each node with a dof in `dofs`, in the order of
    /// its first dof.
    pub nodes: Vec<(u64, [f64; 3])>,
}

/// A matrix file could not be written.
#[derive(Debug, thiserror::Error)]
#[error("{path}: cannot write ({source})")]
pub struct MatrixWriteError {
    /// The file.
    pub path: PathBuf,
    /// The cause.
    pub source: std::io::Error,
}

/// Writes `K.mtx`, `M.mtx`, `dofs.txt` and `coords.csv` of `sys` into `dir` (created if missing); each file
/// goes to a temporary name first and is renamed when complete. Returns the paths written.
pub fn write_matrices(
    dir: &Path,
    sys: &ConstrainedSystem,
    source: &str,
) -> Result<Vec<PathBuf>, MatrixWriteError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| MatrixWriteError { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let mass = match sys.mass {
        fe::MassKind::Lumped => "lumped",
        fe::MassKind::Consistent => "consistent",
    };
    let about = format!(
        "% flexbody {}: {source}, constrained ({} of {} dofs independent), {mass} mass; dof table dofs.txt\n",
        env!("CARGO_PKG_VERSION"),
        sys.dofs.len(),
        sys.physical_dofs
    );
    let mut written = Vec::new();
    for (name, a) in [("K.mtx", &sys.k), ("M.mtx", &sys.m)] {
        let path = dir.join(name);
        write_atomically(&path, |w| write_lower(w, a, &about)).map_err(io(&path))?;
        written.push(path);
    }
    let path = dir.join("dofs.txt");
    write_atomically(&path, |w| {
        writeln!(
            w,
            "# flexbody {}: {source}; equation k = line k: k node component (1-6 = ux uy uz rx ry rz, node displacement frame)",
            env!("CARGO_PKG_VERSION")
        )?;
        if sys.dofs.iter().any(|&(_, c)| c >= 6) {
            writeln!(
                w,
                "# after the nodes: k element component (7-15 = C3D8I incompatible modes 1-xi^2, 1-eta^2, 1-zeta^2 x ux uy uz, basic frame)"
            )?;
        }
        for (k, (node, c)) in sys.dofs.iter().enumerate() {
            writeln!(w, "{} {node} {}", k + 1, c + 1)?;
        }
        Ok(())
    })
    .map_err(io(&path))?;
    written.push(path);
    let path = dir.join("coords.csv");
    write_atomically(&path, |w| {
        writeln!(w, "node,x,y,z")?;
        for (id, x) in &sys.nodes {
            writeln!(w, "{id},{:e},{:e},{:e}", x[0], x[1], x[2])?;
        }
        Ok(())
    })
    .map_err(io(&path))?;
    written.push(path);
    Ok(written)
}

/// One symmetric matrix: header, size line, lower triangle column by column.
fn write_lower(
    w: &mut dyn Write,
    a: &SparseColMat<usize, f64>,
    about: &str,
) -> std::io::Result<()> {
    let n = a.ncols();
    let lower = |j: usize| {
        a.row_idx_of_col(j)
            .zip(a.val_of_col(j).iter().copied())
            .filter(move |&(i, v)| i >= j && v != 0.0)
    };
    let nnz: usize = (0..n).map(|j| lower(j).count()).sum();
    writeln!(w, "%%MatrixMarket matrix coordinate real symmetric")?;
    w.write_all(about.as_bytes())?;
    writeln!(w, "{n} {n} {nnz}")?;
    for j in 0..n {
        let mut col: Vec<(usize, f64)> = lower(j).collect();
        col.sort_unstable_by_key(|e| e.0);
        for (i, v) in col {
            writeln!(w, "{} {} {v:e}", i + 1, j + 1)?;
        }
    }
    Ok(())
}

/// One file of the folder by [`super::write_replacing`].
fn write_atomically(
    path: &Path,
    body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    super::write_replacing(path, body).map_err(|(_, source)| source)
}
