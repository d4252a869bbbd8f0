//! Two threads on one solve: the supernodal elimination tree split into two groups of
//! independent subtrees and the supernodes above them.
//!
//! Splitting a block's columns between threads made each thread stream all of L: at 178k dofs
//! two threads cut the eigen phase's solves only from 7.1 s to 6.2 s (memory bandwidth). Two
//! subtrees with no common descendant touch disjoint rows of X below their common ancestors, so
//! each thread reads only its own part of L. The forward substitution runs the two groups side
//! by side (the second on a copy of X whose rows above both are zeroed, added back after) and
//! then the rest in order; the backward substitution runs the rest first, then the two groups
//! side by side, each writing only its own rows.

use super::{Entry, Supernodal};

/// Supernodes of two groups of independent subtrees (`a`, `b`) and of the rest (the ancestors
/// of both), each ascending: children before parents.
#[derive(Clone, Debug)]
pub(crate) struct Schedule {
    pub(crate) a: Vec<usize>,
    pub(crate) b: Vec<usize>,
    pub(crate) rest: Vec<usize>,
}

/// The rest may hold at most this share of L's values, or the split is not worth a thread.
const MAX_REST: f64 = 0.5;

/// The split of `f`'s elimination tree that balances the stored values of L between the two
/// groups: walk down from the roots, moving the heaviest subtree's root to the rest while that
/// subtree outweighs all the others together, then deal the subtrees out heaviest first to the
/// lighter group. `None` when the rest would hold more than [`MAX_REST`] of L or a group would
/// be empty.
pub(crate) fn schedule<T: Entry>(f: &Supernodal<'_, T>) -> Option<Schedule> {
    let ns = f.n_supernodes();
    let mut of_col = vec![0usize; f.n];
    for s in 0..ns {
        of_col[f.begin[s]..f.end[s]].fill(s);
    }
    let weight: Vec<f64> = (0..ns)
        .map(|s| (f.val_ptr[s + 1] - f.val_ptr[s]) as f64)
        .collect();
    let mut children = vec![Vec::new(); ns];
    let mut roots = Vec::new();
    let mut sub = weight.clone();
    for s in 0..ns {
        // the parent holds the first row below the supernode; parents come after children
        match f.node(s).pattern.iter().min() {
            Some(&row) => {
                let p = of_col[row];
                children[p].push(s);
                sub[p] += sub[s];
            }
            None => roots.push(s),
        }
    }
    let total: f64 = roots.iter().map(|&r| sub[r]).sum();
    let mut frontier = roots;
    let mut rest = Vec::new();
    loop {
        let (i, &h) = frontier
            .iter()
            .enumerate()
            .max_by(|x, y| sub[*x.1].total_cmp(&sub[*y.1]))?;
        let others: f64 = frontier.iter().map(|&s| sub[s]).sum::<f64>() - sub[h];
        if sub[h] <= others || children[h].is_empty() {
            break;
        }
        frontier.swap_remove(i);
        rest.push(h);
        frontier.extend_from_slice(&children[h]);
    }
    let rest_weight: f64 = rest.iter().map(|&s| weight[s]).sum();
    if frontier.len() < 2 || rest_weight > MAX_REST * total {
        return None;
    }
    frontier.sort_by(|x, y| sub[*y].total_cmp(&sub[*x]));
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let (mut wa, mut wb) = (0.0, 0.0);
    for &r in &frontier {
        let (group, w) = if wa <= wb {
            (&mut a, &mut wa)
        } else {
            (&mut b, &mut wb)
        };
        *w += sub[r];
        // the whole subtree of r
        let mut stack = vec![r];
        while let Some(s) = stack.pop() {
            group.push(s);
            stack.extend_from_slice(&children[s]);
        }
    }
    for v in [&mut a, &mut b, &mut rest] {
        v.sort_unstable();
    }
    Some(Schedule { a, b, rest })
}
