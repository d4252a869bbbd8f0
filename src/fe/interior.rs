//! The elements' interior dofs (ccx 2.20's C3D8I: its incompatible-mode amplitudes,
//! [`super::DofMap::interior`]) recovered from the rows of the nodes: a file stores the nodes'
//! rows of its modes only. For an eigenvector (K − ω²M) φ = 0 the interior rows of each element
//! follow exactly from its own rows of that equation — the interior dofs of one element couple
//! to its nodes and to nothing else: (K_ii − ω²M_ii) φ_i = −(K_ip − ω²M_ip) φ_p (dynamic
//! condensation, Paz, *Structural Dynamics* (1984) §13.3, element by element).
//!
//! Also the assembly's part for them: an element's interior columns ([`interior_block`]) and
//! K, M extended by them ([`with_interior`]).

use faer::sparse::SparseColMat;
use faer::Mat;

use super::assembly::ElementMatrices;
use super::{DofMap, FeError};
use crate::model::Model;

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

/// One element's interior dofs and their columns of K and M (consistent mass).
pub(crate) struct InteriorBlock {
    /// First interior dof (global).
    first: usize,
    /// Number of interior dofs.
    ni: usize,
    /// Global dofs of the element's nodal rows, in element order.
    nodal: Vec<usize>,
    /// Columns of the interior dofs over all element rows (nodal, then interior): `(nt × ni)`.
    k: Vec<f64>,
    /// The same for M.
    m: Vec<f64>,
}

/// The interior block of element `e` from its matrices `em`, or `None` when it has none.
pub(crate) fn interior_block(
    model: &Model,
    dofs: &DofMap,
    e: usize,
    em: &ElementMatrices,
) -> Result<Option<InteriorBlock>, FeError> {
    let range = dofs.interior_of(e).unwrap_or(0..0);
    let el = &model.elements[e];
    if range.len() != em.interior {
        return Err(FeError::Unsupported {
            source_file: model.element_origin(el.id),
            id: el.id,
            kind: el.kind,
            message: format!(
                "formed with {} interior dofs where the dof numbering gave it {}",
                em.interior,
                range.len()
            ),
        });
    }
    if range.is_empty() {
        return Ok(None);
    }
    let (nt, ni) = (em.size(), em.interior);
    let nodal: Vec<usize> = el
        .nodes
        .iter()
        .flat_map(|&a| (0..em.dpn).map(move |c| (a, c)))
        .map(|(a, c)| dofs.dof(a, c).unwrap_or(usize::MAX))
        .collect();
    if nodal.contains(&usize::MAX) || nodal.len() + ni != nt {
        return Err(FeError::Unsupported {
            source_file: model.element_origin(el.id),
            id: el.id,
            kind: el.kind,
            message: "a node of an element with interior dofs lacks a translation dof".into(),
        });
    }
    let columns = |a: &[f64]| -> Vec<f64> {
        (0..nt * ni)
            .map(|ri| a[(ri / ni) * nt + nt - ni + ri % ni])
            .collect()
    };
    Ok(Some(InteriorBlock {
        first: range.start,
        ni,
        nodal,
        k: columns(&em.k),
        m: columns(&em.m),
    }))
}

/// K and M (CSC over the nodes' dofs, one pattern for both) extended by the elements' interior
/// dofs: the physical columns gain the interior rows their elements couple to, each interior
/// column holds its element's nodal rows and interior rows (rows ascending in every column).
pub(crate) fn with_interior(
    dofs: &DofMap,
    (col_ptr, row_idx): (&[usize], &[usize]),
    (kv, mv): (&[f64], &[f64]),
    blocks: &[InteriorBlock],
) -> (Vec<usize>, Vec<usize>, Vec<f64>, Vec<f64>) {
    let (np, n) = (dofs.n_physical, dofs.n_dofs);
    let mut extra = vec![0usize; np];
    for b in blocks {
        for &p in &b.nodal {
            extra[p] += b.ni;
        }
    }
    let mut cp = Vec::with_capacity(n + 1);
    cp.push(0usize);
    for j in 0..np {
        let len = col_ptr[j + 1] - col_ptr[j] + extra[j];
        cp.push(cp[j] + len);
    }
    for b in blocks {
        let ni = b.ni;
        for _ in 0..ni {
            let last = cp[cp.len() - 1];
            cp.push(last + b.nodal.len() + ni);
        }
    }
    let nnz = cp[n];
    let (mut ri, mut kk, mut mm) = (vec![0usize; nnz], vec![0.0; nnz], vec![0.0; nnz]);
    // physical columns: their own entries, then the interior rows in block order
    let mut fill: Vec<usize> = (0..np)
        .map(|j| {
            let (lo, hi) = (col_ptr[j], col_ptr[j + 1]);
            let at = cp[j];
            ri[at..at + hi - lo].copy_from_slice(&row_idx[lo..hi]);
            kk[at..at + hi - lo].copy_from_slice(&kv[lo..hi]);
            mm[at..at + hi - lo].copy_from_slice(&mv[lo..hi]);
            at + hi - lo
        })
        .collect();
    for b in blocks {
        let ni = b.ni;
        for (l, &p) in b.nodal.iter().enumerate() {
            for i in 0..ni {
                let at = fill[p];
                ri[at] = b.first + i;
                kk[at] = b.k[l * ni + i];
                mm[at] = b.m[l * ni + i];
                fill[p] += 1;
            }
        }
    }
    // interior columns: the nodal rows ascending, then the block's interior rows
    for b in blocks {
        let ni = b.ni;
        let nc = b.nodal.len();
        let mut order: Vec<usize> = (0..nc).collect();
        order.sort_unstable_by_key(|&l| b.nodal[l]);
        for i in 0..ni {
            let mut at = cp[b.first + i];
            for &l in &order {
                ri[at] = b.nodal[l];
                kk[at] = b.k[l * ni + i];
                mm[at] = b.m[l * ni + i];
                at += 1;
            }
            for r in 0..ni {
                ri[at] = b.first + r;
                kk[at] = b.k[(nc + r) * ni + i];
                mm[at] = b.m[(nc + r) * ni + i];
                at += 1;
            }
        }
    }
    (cp, ri, kk, mm)
}
