//! Nodal coordinate systems: an `NBLOCK` record's rotation angles THXY, THYZ, THZX (degrees)
//! → the node's displacement frame. The MAPDL Command Reference (`N`, release 18.2): "THXY —
//! First rotation about nodal Z (positive X toward Y). THYZ — Second rotation about nodal X
//! (positive Y toward Z). THZX — Third rotation about nodal Y (positive Z toward X)": each
//! rotation about the axis as the rotations before it left it, so the nodal axes (columns, in
//! global components) are A = R_z(THXY) R_x(THYZ) R_y(THZX). ANSYS reads `D`, `F`, `CE` and `CP`
//! of a rotated node in its nodal system; flexbody's displacement frame is the same notion
//! (the node's dofs, SPCs and MPC terms in that frame; `model::Node::displacement_frame`).

use std::collections::BTreeMap;

use crate::model::{CoordKind, CoordSystem, Model};

/// The nodal axes of the rotation angles `[THXY, THYZ, THZX]` (degrees): rows are the nodal
/// X, Y, Z unit vectors in global components (A = R_z R_x R_y, module doc; rows of Aᵀ).
pub(super) fn nodal_axes(angles: [f64; 3]) -> [[f64; 3]; 3] {
    let [a, b, c] = angles.map(f64::to_radians);
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (sc, cc) = c.sin_cos();
    let rz = [[ca, -sa, 0.0], [sa, ca, 0.0], [0.0, 0.0, 1.0]];
    let rx = [[1.0, 0.0, 0.0], [0.0, cb, -sb], [0.0, sb, cb]];
    let ry = [[cc, 0.0, sc], [0.0, 1.0, 0.0], [-sc, 0.0, cc]];
    let product = |p: [[f64; 3]; 3], q: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| p[i][k] * q[k][j]).sum()))
    };
    let a = product(product(rz, rx), ry);
    // row i of the result = column i of A: the nodal axis i in global components
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// The frames of the rotated nodes: one rectangular coordinate system per distinct angle
/// triple, pushed into `model.coord_systems` (ids 1, 2, …); returns its index.
#[derive(Debug, Default)]
pub(super) struct NodalFrames {
    by_angles: BTreeMap<[u64; 3], usize>,
}

impl NodalFrames {
    /// The coordinate system index of `angles` (none for three zeros).
    pub fn frame(&mut self, angles: [f64; 3], model: &mut Model) -> Option<usize> {
        if angles == [0.0; 3] {
            return None;
        }
        let key = angles.map(f64::to_bits);
        Some(*self.by_angles.entry(key).or_insert_with(|| {
            model.coord_systems.push(CoordSystem {
                id: model.coord_systems.len() as u64 + 1,
                kind: CoordKind::Rectangular,
                origin: [0.0; 3],
                axes: nodal_axes(angles),
            });
            model.coord_systems.len() - 1
        }))
    }
}

/// A vector given in node `node`'s nodal system, in global components (its own frame's
/// axes: v_global = Σ_i v_i e_i; unchanged for a node without one).
pub(super) fn to_global(model: &Model, node: usize, v: [f64; 3]) -> [f64; 3] {
    let frame = model.nodes[node].displacement_frame;
    match frame.and_then(|cs| model.coord_systems.get(cs)) {
        Some(cs) => std::array::from_fn(|j| (0..3).map(|i| v[i] * cs.axes[i][j]).sum()),
        None => v,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// THXY alone turns X toward Y; the three axes stay orthonormal and right-handed for any
    /// triple; the order matters (Z, then the new X, then the new Y).
    #[test]
    fn nodal_axes_follow_the_documented_order() {
        let a = nodal_axes([90.0, 0.0, 0.0]);
        let close = |p: [f64; 3], q: [f64; 3]| (0..3).all(|i| (p[i] - q[i]).abs() < 1e-15);
        assert!(close(a[0], [0.0, 1.0, 0.0]) && close(a[1], [-1.0, 0.0, 0.0]));
        // THYZ after THXY = 90: about the new X (global Y), the new Y (−X) turns toward Z
        let a = nodal_axes([90.0, 90.0, 0.0]);
        assert!(close(a[1], [0.0, 0.0, 1.0]), "{a:?}");
        let a = nodal_axes([30.0, 20.0, 10.0]);
        let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        for i in 0..3 {
            for j in 0..3 {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((dot(a[i], a[j]) - want).abs() < 1e-15);
            }
        }
        let cross = [
            a[0][1] * a[1][2] - a[0][2] * a[1][1],
            a[0][2] * a[1][0] - a[0][0] * a[1][2],
            a[0][0] * a[1][1] - a[0][1] * a[1][0],
        ];
        assert!(close(cross, a[2]));
    }
}
