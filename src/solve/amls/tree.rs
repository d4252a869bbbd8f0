//! The substructure tree of AMLS: recursive vertex separators of the node graph by METIS
//! (`METIS_ComputeVertexSeparator`, the bisection step of its own nested dissection), down to
//! leaves of at most a given number of dofs.

use super::super::{ordering, sparse_ops, SolveError, SparseColMat};

/// A subtree: a leaf substructure, or two subtrees that only its separator couples.
#[derive(Debug)]
pub enum Substructure {
    /// Dofs of a leaf in METIS's nested-dissection order of the leaf (so that the tree's order,
    /// each subtree's dofs before its separator, is a fill-reducing order of every subtree).
    Leaf(Vec<usize>),
    /// A separator's dofs (ascending) and the two subtrees it separates.
    Split {
        separator: Vec<usize>,
        children: Box<[Substructure; 2]>,
    },
}

impl Substructure {
    /// Leaves and separators: (number of leaves, largest leaf, total separator dofs, depth).
    pub fn shape(&self) -> (usize, usize, usize, usize) {
        match self {
            Substructure::Leaf(d) => (1, d.len(), 0, 0),
            Substructure::Split {
                separator,
                children,
            } => {
                let a = children[0].shape();
                let b = children[1].shape();
                (
                    a.0 + b.0,
                    a.1.max(b.1),
                    separator.len() + a.2 + b.2,
                    1 + a.3.max(b.3),
                )
            }
        }
    }
}

/// The tree of the symmetric matrix `a` (n × n): groups of `block` consecutive dofs (one node)
/// stay together when `block` divides n; subsets of more than `leaf_dofs` dofs are split while
/// METIS finds a separator that leaves both parts non-empty.
pub fn build(
    matrix: &SparseColMat<usize, f64>,
    block: Option<usize>,
    leaf_dofs: usize,
) -> Result<Substructure, SolveError> {
    let a = matrix.symbolic();
    let n = a.nrows();
    let b = match block {
        Some(b) if b > 1 && n % b == 0 => b,
        _ => 1,
    };
    let nv = n / b;
    // node adjacency, no self loops, no duplicates
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); nv];
    let mut mark = vec![usize::MAX; nv];
    for (v, list) in adj.iter_mut().enumerate() {
        mark[v] = v;
        for j in v * b..(v + 1) * b {
            for &i in a.row_idx_of_col_raw(j) {
                let w = i / b;
                if mark[w] != v {
                    mark[w] = v;
                    list.push(w);
                }
            }
        }
    }
    let graph = Graph { adj, b };
    let mut root = graph.split((0..nv).collect(), leaf_dofs.max(b))?;
    order_leaves(&mut root, matrix, block)?;
    Ok(root)
}

/// Puts every leaf's dofs into METIS's nested-dissection order of the leaf's own matrix.
fn order_leaves(
    node: &mut Substructure,
    a: &SparseColMat<usize, f64>,
    block: Option<usize>,
) -> Result<(), SolveError> {
    match node {
        Substructure::Leaf(dofs) => {
            if dofs.len() > 1 {
                let sub = sparse_ops::submatrix(a.as_ref(), dofs, dofs)?;
                let fwd = ordering::nested_dissection(sub.symbolic(), block)?;
                *dofs = fwd.iter().map(|&i| dofs[i]).collect();
            }
            Ok(())
        }
        Substructure::Split { children, .. } => {
            let [c1, c2] = &mut **children;
            order_leaves(c1, a, block)?;
            order_leaves(c2, a, block)
        }
    }
}

struct Graph {
    adj: Vec<Vec<usize>>,
    b: usize,
}

impl Graph {
    fn dofs(&self, nodes: &[usize]) -> Vec<usize> {
        let mut d: Vec<usize> = nodes
            .iter()
            .flat_map(|&v| v * self.b..(v + 1) * self.b)
            .collect();
        d.sort_unstable();
        d
    }

    fn split(&self, nodes: Vec<usize>, leaf_dofs: usize) -> Result<Substructure, SolveError> {
        if nodes.len() * self.b <= leaf_dofs || nodes.len() < 8 {
            return Ok(Substructure::Leaf(self.dofs(&nodes)));
        }
        let part = self.separate(&nodes)?;
        let pick = |p: i32| -> Vec<usize> {
            nodes
                .iter()
                .zip(&part)
                .filter(|(_, &q)| q == p)
                .map(|(&v, _)| v)
                .collect()
        };
        let (left, right, sep) = (pick(0), pick(1), pick(2));
        if left.is_empty() || right.is_empty() || sep.len() * 2 > nodes.len() {
            return Ok(Substructure::Leaf(self.dofs(&nodes)));
        }
        let children = Box::new([self.split(left, leaf_dofs)?, self.split(right, leaf_dofs)?]);
        Ok(Substructure::Split {
            separator: self.dofs(&sep),
            children,
        })
    }

    /// METIS vertex separator of the subgraph induced by `nodes`: 0, 1 (the parts) or 2 (the
    /// separator) per node.
    fn separate(&self, nodes: &[usize]) -> Result<Vec<i32>, SolveError> {
        let mut local = std::collections::HashMap::with_capacity(nodes.len());
        for (i, &v) in nodes.iter().enumerate() {
            local.insert(v, i);
        }
        let mut xadj: Vec<i32> = Vec::with_capacity(nodes.len() + 1);
        let mut adjncy: Vec<i32> = Vec::new();
        xadj.push(0);
        for &v in nodes {
            for w in &self.adj[v] {
                if let Some(&j) = local.get(w) {
                    adjncy.push(to_idx(j)?);
                }
            }
            xadj.push(to_idx(adjncy.len())?);
        }
        let mut part = vec![0i32; nodes.len()];
        if adjncy.is_empty() {
            // no edges: two halves, no separator
            for p in part.iter_mut().skip(nodes.len() / 2) {
                *p = 1;
            }
            return Ok(part);
        }
        let mut nvtxs = to_idx(nodes.len())?;
        let mut options = [-1i32; metis_sys::METIS_NOPTIONS as usize];
        let mut sepsize = 0i32;
        // one METIS call at a time: its random generator is a C global (see solve::ordering)
        let _one_at_a_time = super::super::ordering::metis_lock();
        // SAFETY: xadj has nvtxs+1 entries, adjncy xadj[nvtxs], options METIS_NOPTIONS, part
        // nvtxs; vwgt may be null.
        let status = unsafe {
            metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
            metis_sys::METIS_ComputeVertexSeparator(
                &mut nvtxs,
                xadj.as_mut_ptr(),
                adjncy.as_mut_ptr(),
                std::ptr::null_mut(),
                options.as_mut_ptr(),
                &mut sepsize,
                part.as_mut_ptr(),
            )
        };
        if status != metis_sys::rstatus_et_METIS_OK {
            return Err(SolveError::Ordering(format!(
                "METIS_ComputeVertexSeparator returned status {status} on {} vertices",
                nodes.len()
            )));
        }
        Ok(part)
    }
}

fn to_idx(x: usize) -> Result<i32, SolveError> {
    i32::try_from(x)
        .map_err(|_| SolveError::Ordering(format!("graph too large for 32-bit METIS ({x})")))
}
