//! The sparsity pattern of K and M, built once per `DofMap` from the node graph, and the lookup
//! that scatters an element's node blocks into the compressed columns.
//!
//! Column (a, c) — dof c of node a — holds, for every neighbour b of a in ascending order
//! (a included), the rows `first[b] .. first[b] + count[b]`. So its length `L_a = Σ_b count[b]` is the
//! same for all columns of node a, the row indices are sorted, and the block of node b in it
//! starts at `base[a] + c·L_a + off(a, b)`.

use rayon::prelude::*;

use super::dofs::DofMap;

/// CSC pattern of the assembled matrices plus the node-graph lookup tables.
#[derive(Debug, Clone)]
pub struct Pattern {
    /// Neighbour list of each node (CSR over `adj`).
    pub adj_ptr: Vec<usize>,
    /// Neighbour node indices, ascending per node, self included.
    pub adj: Vec<u32>,
    /// Row offset of neighbour `adj[k]` inside every column of its owner node.
    pub off: Vec<u32>,
    /// Start of each node's first column in the value array.
    pub base: Vec<usize>,
    /// Column length per node.
    pub col_len: Vec<usize>,
    /// CSC column pointers (n_dofs + 1).
    pub col_ptr: Vec<usize>,
    /// CSC row indices.
    pub row_idx: Vec<usize>,
}

impl Pattern {
    /// Build from element connectivities (any node lists) for the dofs in `dofs`; every node with
    /// dofs gets at least its own diagonal block.
    pub fn build(dofs: &DofMap, connectivity: &[&[usize]]) -> Pattern {
        let nn = dofs.count.len();
        // node → elements incidence (counting sort)
        let mut inc_ptr = vec![0usize; nn + 1];
        for conn in connectivity {
            for &a in *conn {
                inc_ptr[a + 1] += 1;
            }
        }
        for a in 0..nn {
            inc_ptr[a + 1] += inc_ptr[a];
        }
        let mut fill = inc_ptr.clone();
        let mut inc = vec![0u32; inc_ptr[nn]];
        for (e, conn) in connectivity.iter().enumerate() {
            for &a in *conn {
                inc[fill[a]] = e as u32;
                fill[a] += 1;
            }
        }
        let lists: Vec<Vec<u32>> = (0..nn)
            .into_par_iter()
            .map(|a| {
                if dofs.count[a] == 0 {
                    return Vec::new();
                }
                let mut v = vec![a as u32];
                for &e in &inc[inc_ptr[a]..inc_ptr[a + 1]] {
                    v.extend(connectivity[e as usize].iter().map(|&b| b as u32));
                }
                v.sort_unstable();
                v.dedup();
                v.retain(|&b| dofs.count[b as usize] > 0);
                v
            })
            .collect();
        drop(inc);
        let mut adj_ptr = Vec::with_capacity(nn + 1);
        adj_ptr.push(0);
        let mut adj = Vec::with_capacity(lists.iter().map(Vec::len).sum());
        let mut off = Vec::with_capacity(adj.capacity());
        let mut col_len = vec![0usize; nn];
        for (a, l) in lists.into_iter().enumerate() {
            let mut o = 0usize;
            for b in l {
                adj.push(b);
                off.push(o as u32);
                o += usize::from(dofs.count[b as usize]);
            }
            col_len[a] = o;
            adj_ptr.push(adj.len());
        }
        let mut base = vec![0usize; nn];
        let mut col_ptr = Vec::with_capacity(dofs.n_dofs + 1);
        col_ptr.push(0usize);
        let mut pos = 0usize;
        for a in 0..nn {
            base[a] = pos;
            for _ in 0..dofs.count[a] {
                pos += col_len[a];
                col_ptr.push(pos);
            }
        }
        let mut row_idx = vec![0usize; pos];
        // One disjoint slice per node, filled in parallel: column 0 from the neighbour list,
        // the node's other columns are copies.
        let mut slices: Vec<(usize, &mut [usize])> = Vec::with_capacity(nn);
        let mut rest: &mut [usize] = &mut row_idx;
        for a in 0..nn {
            let (head, tail) = rest.split_at_mut(usize::from(dofs.count[a]) * col_len[a]);
            slices.push((a, head));
            rest = tail;
        }
        slices.into_par_iter().for_each(|(a, out)| {
            let l = col_len[a];
            if l == 0 {
                return;
            }
            let mut t = 0;
            for &b in &adj[adj_ptr[a]..adj_ptr[a + 1]] {
                let b = b as usize;
                for r in 0..usize::from(dofs.count[b]) {
                    out[t] = dofs.first[b] + r;
                    t += 1;
                }
            }
            let (first, others) = out.split_at_mut(l);
            for col in others.chunks_mut(l) {
                col.copy_from_slice(first);
            }
        });
        Pattern {
            adj_ptr,
            adj,
            off,
            base,
            col_len,
            col_ptr,
            row_idx,
        }
    }

    /// Value index of the block (row node b, column dof (a, c)): rows of b start there.
    #[inline]
    pub fn block(&self, a: usize, c: usize, b: usize) -> usize {
        let nb = &self.adj[self.adj_ptr[a]..self.adj_ptr[a + 1]];
        // b is a neighbour of a by construction of the pattern from the same connectivity.
        let k = nb
            .binary_search(&(b as u32))
            .unwrap_or_else(|_| unreachable!("node {b} not adjacent to {a}"));
        self.base[a] + c * self.col_len[a] + self.off[self.adj_ptr[a] + k] as usize
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }
}
