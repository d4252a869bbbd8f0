//! Fill-reducing ordering: METIS nested dissection (`METIS_NodeND`) on the node graph (expanded
//! to dofs) or on the dof graph, returned as a permutation for faer's `SymmetricOrdering::Custom`.

use super::SolveError;
use faer::sparse::SymbolicSparseColMatRef;

/// Graphs smaller than this are ordered by identity: METIS gains nothing and dislikes tiny graphs.
const MIN_METIS_VERTICES: usize = 16;

/// Nested-dissection permutation `perm[new] = old` of the dofs of the symmetric pattern `a`.
///
/// With `block = Some(b)` and `n % b == 0` the dofs `b·i .. b·i+b` are treated as one node: METIS
/// orders the node graph (b² times smaller) and each node's dofs stay contiguous.
pub fn nested_dissection(
    a: SymbolicSparseColMatRef<'_, usize>,
    block: Option<usize>,
) -> Result<Vec<usize>, SolveError> {
    let n = a.nrows();
    let b = match block {
        Some(b) if b > 1 && n % b == 0 => b,
        _ => 1,
    };
    let nv = n / b;
    if nv < MIN_METIS_VERTICES {
        return Ok((0..n).collect());
    }
    // Node adjacency (CSR, no self loops, no duplicates).
    let mut mark = vec![usize::MAX; nv];
    let mut xadj: Vec<i32> = Vec::with_capacity(nv + 1);
    let mut adjncy: Vec<i32> = Vec::new();
    xadj.push(0);
    for v in 0..nv {
        mark[v] = v;
        for j in v * b..(v + 1) * b {
            for &i in a.row_idx_of_col_raw(j) {
                let w = i / b;
                if mark[w] != v {
                    mark[w] = v;
                    adjncy.push(to_idx(w)?);
                }
            }
        }
        xadj.push(to_idx(adjncy.len())?);
    }
    if adjncy.is_empty() {
        return Ok((0..n).collect());
    }
    let mut nvtxs = to_idx(nv)?;
    let mut options = [-1i32; metis_sys::METIS_NOPTIONS as usize];
    let mut perm = vec![0i32; nv];
    let mut iperm = vec![0i32; nv];
    // METIS seeds and draws from GKlib's random generator, a C global (vendor/GKlib/random.c,
    // `static uint64_t mt[NN]`): two calls at once race on it, and their orderings then differ
    // from run to run (seen in parallel tests: two analyses of one matrix gave L of 8.1 and
    // 9.7 MB). One call at a time keeps them reproducible.
    let _one_at_a_time = metis_lock();
    // SAFETY: every array has the length METIS_NodeND documents (xadj nv+1, adjncy xadj[nv],
    // options METIS_NOPTIONS, perm/iperm nv); vwgt may be null.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(SolveError::Ordering(format!(
            "METIS_NodeND returned status {status} on a graph of {nv} vertices"
        )));
    }
    let mut out = Vec::with_capacity(n);
    for &p in &perm {
        let p =
            usize::try_from(p).map_err(|_| SolveError::Ordering("negative METIS index".into()))?;
        if p >= nv {
            return Err(SolveError::Ordering(format!(
                "METIS index {p} out of range"
            )));
        }
        out.extend(p * b..(p + 1) * b);
    }
    Ok(out)
}

/// The lock every METIS call holds (its random generator is a C global; see
/// [`nested_dissection`]).
pub(crate) fn metis_lock() -> std::sync::MutexGuard<'static, ()> {
    static METIS: std::sync::Mutex<()> = std::sync::Mutex::new(());
    METIS.lock().unwrap_or_else(|e| e.into_inner())
}

fn to_idx(x: usize) -> Result<i32, SolveError> {
    i32::try_from(x)
        .map_err(|_| SolveError::Ordering(format!("graph too large for 32-bit METIS ({x})")))
}

/// Inverse of a permutation given as `perm[new] = old`.
pub fn inverse(perm: &[usize]) -> Vec<usize> {
    let mut inv = vec![0; perm.len()];
    for (new, &old) in perm.iter().enumerate() {
        inv[old] = new;
    }
    inv
}
