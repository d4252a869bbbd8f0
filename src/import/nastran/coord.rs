//! Nastran coordinate systems: CORD2R/C/S from three points, chained through RID, and the
//! conversion of a point given in a system to the basic frame.

use crate::model::{CoordKind, CoordSystem};

/// Local coordinates (x1, x2, x3) in a system of `kind` → local rectangular coordinates.
/// Cylindrical (r, θ°, z): (r cos θ, r sin θ, z); spherical (r, θ°, φ°):
/// (r sin θ cos φ, r sin θ sin φ, r cos θ).
pub(crate) fn to_rect(kind: CoordKind, p: [f64; 3]) -> [f64; 3] {
    match kind {
        CoordKind::Rectangular => p,
        CoordKind::Cylindrical => {
            let t = p[1].to_radians();
            [p[0] * t.cos(), p[0] * t.sin(), p[2]]
        }
        CoordKind::Spherical => {
            let (t, f) = (p[1].to_radians(), p[2].to_radians());
            [
                p[0] * t.sin() * f.cos(),
                p[0] * t.sin() * f.sin(),
                p[0] * t.cos(),
            ]
        }
    }
}

/// A point given in system `cs` → basic: x = origin + Σ_k rect_k · e_k.
pub(crate) fn to_basic(cs: &CoordSystem, p: [f64; 3]) -> [f64; 3] {
    let r = to_rect(cs.kind, p);
    let mut x = cs.origin;
    for (k, rk) in r.iter().enumerate() {
        for (d, xd) in x.iter_mut().enumerate() {
            *xd += rk * cs.axes[k][d];
        }
    }
    x
}

/// A direction given in rectangular system `cs` → basic: v = Σ_k v_k · e_k.
pub(crate) fn dir_to_basic(cs: &CoordSystem, v: [f64; 3]) -> [f64; 3] {
    let mut x = [0.0; 3];
    for (k, vk) in v.iter().enumerate() {
        for (d, xd) in x.iter_mut().enumerate() {
            *xd += vk * cs.axes[k][d];
        }
    }
    x
}

pub(crate) use crate::model::geometry::{cross, sub, unit};

/// CORD2x from basic points A (origin), B (on +z) and C (in the x–z plane):
/// e3 = (B−A)/|B−A|, e2 = e3 × (C−A) normalised, e1 = e2 × e3. `None` if degenerate.
pub(crate) fn from_points(
    id: u64,
    kind: CoordKind,
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
) -> Option<CoordSystem> {
    let e3 = unit(sub(b, a))?;
    let e2 = unit(cross(e3, sub(c, a)))?;
    let e1 = cross(e2, e3);
    Some(CoordSystem {
        id,
        kind,
        origin: a,
        axes: [e1, e2, e3],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylindrical_point_and_rotated_system() {
        // System rotated 90° about z: e1 = y, e2 = −x, origin (1, 0, 0).
        let cs = from_points(
            5,
            CoordKind::Cylindrical,
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 0.0],
        )
        .unwrap();
        let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|d| (a[d] - b[d]).abs() < 1e-12);
        assert!(close(cs.axes[0], [0.0, 1.0, 0.0]) && close(cs.axes[1], [-1.0, 0.0, 0.0]));
        // r = 2, θ = 90° → local (0, 2, 0) → basic origin + 2 e2 = (−1, 0, 0).
        assert!(close(to_basic(&cs, [2.0, 90.0, 3.0]), [-1.0, 0.0, 3.0]));
        let sph = CoordSystem {
            kind: CoordKind::Spherical,
            ..cs.clone()
        };
        // r = 1, θ = 90°, φ = 0 → local (1, 0, 0) → (1, 1, 0).
        assert!(close(to_basic(&sph, [1.0, 90.0, 0.0]), [1.0, 1.0, 0.0]));
        assert!(from_points(
            1,
            CoordKind::Rectangular,
            [0.0; 3],
            [0.0; 3],
            [1.0, 0.0, 0.0]
        )
        .is_none());
    }
}
