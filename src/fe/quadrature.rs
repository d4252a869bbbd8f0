//! Quadrature rules on the reference line, tetrahedron, triangle × line (wedge) and cube.
//!
//! Gauss–Legendre points and weights are the classical values (Abramowitz & Stegun, Table 25.4);
//! the 4-point tetrahedron rule is the degree-2 rule of Zienkiewicz & Taylor, *The Finite Element
//! Method* Vol. 1, Table 5.4 (as used by CalculiX C3D10, `gauss3d5`); the exact tetrahedron rule
//! is a collapsed (Duffy) Gauss product rule, Stroud, *Approximate Calculation of Multiple
//! Integrals* (1971) §2.

/// One quadrature point in reference coordinates with its weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadPoint {
    /// Reference coordinates (ξ, η, ζ).
    pub xi: [f64; 3],
    /// Weight (reference volume measure included).
    pub w: f64,
}

/// Gauss–Legendre points and weights on [−1, 1], n = 1..=4 (exact for degree 2n − 1).
pub fn gauss_legendre(n: usize) -> &'static [(f64, f64)] {
    const G1: [(f64, f64); 1] = [(0.0, 2.0)];
    const G2: [(f64, f64); 2] = [
        (-0.577_350_269_189_625_8, 1.0),
        (0.577_350_269_189_625_8, 1.0),
    ];
    const G3: [(f64, f64); 3] = [
        (-0.774_596_669_241_483_4, 5.0 / 9.0),
        (0.0, 8.0 / 9.0),
        (0.774_596_669_241_483_4, 5.0 / 9.0),
    ];
    const G4: [(f64, f64); 4] = [
        (-0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
        (-0.339_981_043_584_856_3, 0.652_145_154_862_546_2),
        (0.339_981_043_584_856_3, 0.652_145_154_862_546_2),
        (0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
    ];
    match n {
        1 => &G1,
        2 => &G2,
        3 => &G3,
        _ => &G4,
    }
}

/// n×n×n Gauss product rule on the cube [−1, 1]³ (ζ slowest, ξ fastest).
pub fn cube(n: usize) -> Vec<QuadPoint> {
    let g = gauss_legendre(n);
    let mut out = Vec::with_capacity(g.len().pow(3));
    for &(z, wz) in g {
        for &(y, wy) in g {
            for &(x, wx) in g {
                out.push(QuadPoint {
                    xi: [x, y, z],
                    w: wx * wy * wz,
                });
            }
        }
    }
    out
}

/// Irons' 14-point rule on the cube [−1, 1]³ (degree 5): the six points (±b, 0, 0)… with weight
/// 320/361 and the eight (±c, ±c, ±c) with weight 121/361, b² = 19/30, c² = 19/33 (Irons, "Quadrature
/// rules for brick based finite elements", IJNME 3 (1971) 293). ANSYS integrates SOLID186's
/// consistent mass with it.
pub fn cube_irons14() -> Vec<QuadPoint> {
    let (b, c) = ((19.0f64 / 30.0).sqrt(), (19.0f64 / 33.0).sqrt());
    let (wb, wc) = (320.0 / 361.0, 121.0 / 361.0);
    let mut out = Vec::with_capacity(14);
    for k in 0..3 {
        for s in [-1.0, 1.0] {
            let mut xi = [0.0; 3];
            xi[k] = s * b;
            out.push(QuadPoint { xi, w: wb });
        }
    }
    for sz in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sx in [-1.0, 1.0] {
                out.push(QuadPoint {
                    xi: [sx * c, sy * c, sz * c],
                    w: wc,
                });
            }
        }
    }
    out
}

/// Centroid rule on the unit tetrahedron {ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1} (degree 1).
pub fn tet1() -> Vec<QuadPoint> {
    vec![QuadPoint {
        xi: [0.25; 3],
        w: 1.0 / 6.0,
    }]
}

/// 4-point degree-2 rule on the unit tetrahedron: a = (5 − √5)/20, b = (5 + 3√5)/20, w = 1/24.
pub fn tet4() -> Vec<QuadPoint> {
    let a = (5.0 - 5f64.sqrt()) / 20.0;
    let b = (5.0 + 3.0 * 5f64.sqrt()) / 20.0;
    let w = 1.0 / 24.0;
    vec![
        QuadPoint { xi: [a, a, a], w },
        QuadPoint { xi: [b, a, a], w },
        QuadPoint { xi: [a, b, a], w },
        QuadPoint { xi: [a, a, b], w },
    ]
}

/// Collapsed Gauss product rule on the unit tetrahedron, exact for polynomials of degree ≤ 5
/// with 4 points per direction: ξ = u, η = v(1−u), ζ = w(1−u)(1−v), dV = (1−u)²(1−v) du dv dw.
pub fn tet_duffy(n: usize) -> Vec<QuadPoint> {
    let g = gauss_legendre(n);
    let mut out = Vec::with_capacity(g.len().pow(3));
    for &(a, wa) in g {
        let u = 0.5 * (a + 1.0);
        for &(b, wb) in g {
            let v = 0.5 * (b + 1.0);
            for &(c, wc) in g {
                let w = 0.5 * (c + 1.0);
                out.push(QuadPoint {
                    xi: [u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v)],
                    w: wa * wb * wc / 8.0 * (1.0 - u) * (1.0 - u) * (1.0 - v),
                });
            }
        }
    }
    out
}

/// Wedge rule: 3-point degree-2 triangle rule (midside points, w = 1/6) × n-point Gauss in ζ.
pub fn wedge(n: usize) -> Vec<QuadPoint> {
    let tri = [[0.5, 0.0], [0.5, 0.5], [0.0, 0.5]];
    let mut out = Vec::with_capacity(3 * n);
    for &(z, wz) in gauss_legendre(n) {
        for t in tri {
            out.push(QuadPoint {
                xi: [t[0], t[1], z],
                w: wz / 6.0,
            });
        }
    }
    out
}

/// CalculiX's wedge rule (C3D6, ccx `gauss3d7`): the triangle's centroid × 2 Gauss–Legendre
/// points through the thickness — exact for constants in the triangle only (an under-integrated
/// C3D6, softer than [`wedge`]`(2)`).
pub fn wedge_centroid() -> Vec<QuadPoint> {
    gauss_legendre(2)
        .iter()
        .map(|&(z, wz)| QuadPoint {
            xi: [1.0 / 3.0, 1.0 / 3.0, z],
            w: wz / 2.0,
        })
        .collect()
}

/// CalculiX's 9-point wedge rule (C3D15, ccx `gauss3d8`): the interior 3-point degree-2
/// triangle rule ((1/6, 1/6), (2/3, 1/6), (1/6, 2/3), w = 1/6) × 3 Gauss–Legendre points.
pub fn wedge_ccx() -> Vec<QuadPoint> {
    let tri = [
        [1.0 / 6.0, 1.0 / 6.0],
        [2.0 / 3.0, 1.0 / 6.0],
        [1.0 / 6.0, 2.0 / 3.0],
    ];
    let mut out = Vec::with_capacity(9);
    for &(z, wz) in gauss_legendre(3) {
        for t in tri {
            out.push(QuadPoint {
                xi: [t[0], t[1], z],
                w: wz / 6.0,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn integrate(rule: &[QuadPoint], f: impl Fn([f64; 3]) -> f64) -> f64 {
        rule.iter().map(|q| q.w * f(q.xi)).sum()
    }

    /// ∫_tet ξ^a η^b ζ^c = a! b! c! / (a + b + c + 3)!.
    fn tet_monomial(a: u32, b: u32, c: u32) -> f64 {
        let f = |n: u32| (1..=n).map(f64::from).product::<f64>();
        f(a) * f(b) * f(c) / f(a + b + c + 3)
    }

    #[test]
    fn tet_rules_integrate_monomials_to_their_degree() {
        let exact = tet_duffy(4);
        let four = tet4();
        for a in 0..=5u32 {
            for b in 0..=(5 - a) {
                for c in 0..=(5 - a - b) {
                    let f = |x: [f64; 3]| {
                        x[0].powi(a as i32) * x[1].powi(b as i32) * x[2].powi(c as i32)
                    };
                    let want = tet_monomial(a, b, c);
                    assert!(
                        (integrate(&exact, f) - want).abs() < 1e-15,
                        "duffy {a}{b}{c}"
                    );
                    if a + b + c <= 2 {
                        assert!((integrate(&four, f) - want).abs() < 1e-15, "tet4 {a}{b}{c}");
                    }
                }
            }
        }
    }

    #[test]
    fn gauss_cube_is_exact_to_degree_2n_minus_1() {
        for n in 1..=4 {
            let r = cube(n);
            let p = (2 * n - 1) as i32;
            let got = integrate(&r, |x| {
                x[0].powi(p - 1) * x[1].powi(p - 1) * x[2].powi(p - 1)
            });
            let one = if (p - 1) % 2 == 0 {
                2.0 / p as f64
            } else {
                0.0
            };
            assert!((got - one * one * one).abs() < 1e-14, "n={n}");
        }
        let w = wedge(2);
        // ∫ over unit triangle × [−1,1] of ξη(1+ζ)ζ = (1/24)·(2/3)
        assert!((integrate(&w, |x| x[0] * x[1] * (1.0 + x[2]) * x[2]) - 2.0 / 72.0).abs() < 1e-15);
    }
}
