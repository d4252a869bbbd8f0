//! Vectors of 3D space, the one home of the small helpers every part of the code needs
//! (element kernels, material axes, the importers' frames and expansions).

/// A point or vector in 3D.
pub type Vec3 = [f64; 3];

/// a − b.
pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a · b.
pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a × b.
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// |a|.
pub fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// s a.
pub fn scale(a: Vec3, s: f64) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// a / |a| when `keep(|a|)` holds (e.g. a length floor), else `None`.
pub fn unit_if(a: Vec3, keep: impl Fn(f64) -> bool) -> Option<Vec3> {
    let n = norm(a);
    keep(n).then(|| a.map(|c| c / n))
}

/// a / |a|; `None` for a zero or non-finite vector.
pub fn unit(a: Vec3) -> Option<Vec3> {
    unit_if(a, |n| n > 0.0 && n.is_finite())
}

/// A 3×3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

/// det M, by the cofactors of the first row.
pub fn det3(m: &Mat3) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// M⁻¹ = adj(M) / det M, with `det` = [`det3`] of M (the caller checks it is not zero).
pub fn inverse3(m: &Mat3, det: f64) -> Mat3 {
    [
        [
            (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det,
            (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det,
            (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det,
        ],
        [
            (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det,
            (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det,
            (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det,
        ],
        [
            (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det,
            (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det,
            (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det,
        ],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The right-handed basis: x × y = z, and a unit vector of (3, 4, 0) is (0.6, 0.8, 0).
    #[test]
    fn cross_of_the_basis_and_unit_of_a_3_4_5_vector() {
        assert_eq!(cross([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
        assert_eq!(unit([3.0, 4.0, 0.0]), Some([0.6, 0.8, 0.0]));
        assert_eq!(unit([0.0; 3]), None);
        assert_eq!(unit([f64::INFINITY, 0.0, 0.0]), None);
        assert_eq!(norm(sub([4.0, 6.0, 0.0], [1.0, 2.0, 0.0])), 5.0);
        assert_eq!(dot(scale([1.0, 2.0, 3.0], 2.0), [1.0, 1.0, 1.0]), 12.0);
    }

    /// M M⁻¹ = I for a general matrix: det = 2·(−3 − 1) − 1·(−1 − 0) = −7 by hand.
    #[test]
    fn inverse3_times_the_matrix_is_the_identity() {
        let m = [[2.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, -1.0]];
        let det = det3(&m);
        assert_eq!(det, -7.0);
        let inv = inverse3(&m, det);
        for (i, row) in m.iter().enumerate() {
            for j in 0..3 {
                let p: f64 = (row.iter().zip(&inv)).map(|(a, b)| a * b[j]).sum();
                let want = f64::from(u8::from(i == j));
                assert!((p - want).abs() < 1e-15, "{i}{j}: {p}");
            }
        }
    }
}
