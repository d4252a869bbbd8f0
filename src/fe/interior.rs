//! The elements' interior dofs (ccx 2.20's C3D8I: its incompatible-mode amplitudes,
//! [`super::DofMap::interior`]) recovered from the rows of the nodes: a file stores the nodes'
//! rows of its modes only. For an eigenvector (K − ω²M) φ = 0 the interior rows of each element
//! follow exactly from its own rows of that equation — the interior dofs of one element couple
//! to its nodes and to nothing else: (K_ii − ω²M_ii) φ_i = −(K_ip − ω²M_ip) φ_p (dynamic
//! condensation, Paz, *Structural Dynamics* (1984) §13.3, element by element).

use faer::sparse::SparseColMat;
use faer::Mat;

use super::DofMap;

/// Fill the interior rows of `phi` (rows: the independent dofs `retained`, ascending; columns:
/// modes with eigenvalues `omega2`) from its other rows, by the module's recovery on K_r, M_r
/// (the interior dofs are never constrained: their rows of K_r, M_r are the model's). An
/// interior dof not among `retained`, or a singular element block at ω², leaves its rows as
/// they are and is counted in the returned number.
pub fn recover_interior(
    dofs: &DofMap,
    retained: &[usize],
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    omega2: &[f64],
    phi: &mut Mat<f64>,
) -> usize {
    let mut failed = 0;
    for block in &dofs.interior {
        let rows: Option<Vec<usize>> = (block.first..block.first + block.count)
            .map(|d| retained.binary_search(&d).ok())
            .collect();
        let Some(rows) = rows else {
            failed += 1;
            continue;
        };
        for (j, &w2) in omega2.iter().enumerate().take(phi.ncols()) {
            if !recover_block(&rows, k, m, w2, j, phi) {
                failed += 1;
            }
        }
    }
    failed
}

/// One element's interior rows `rows` of mode `j` (module formula); false when singular.
fn recover_block(
    rows: &[usize],
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    w2: f64,
    j: usize,
    phi: &mut Mat<f64>,
) -> bool {
    let n = rows.len();
    let (kr, mr) = (k.as_ref(), m.as_ref());
    let mut a = vec![0.0; n * n];
    let mut b = vec![0.0; n];
    // column r of the symmetric K, M is row r: the element's coupling to every other dof
    let mut add = |mat: faer::sparse::SparseColMatRef<'_, usize, f64>, scale: f64| {
        for (i, &r) in rows.iter().enumerate() {
            for (row, v) in mat.row_idx_of_col(r).zip(mat.val_of_col(r)) {
                match rows.iter().position(|&q| q == row) {
                    Some(q) => a[i * n + q] += scale * v,
                    None => b[i] -= scale * v * phi[(row, j)],
                }
            }
        }
    };
    add(kr, 1.0);
    add(mr, -w2);
    // A is a dense n × n block: the incompatible-mode solver with no condensed dofs
    let Ok(x) = super::elements::solid_incompatible::solve_modes(&a, 0, n, b, 1) else {
        return false;
    };
    for (i, &r) in rows.iter().enumerate() {
        phi[(r, j)] = x[i];
    }
    true
}
