//! Anisotropic linear elasticity: a material's 6×6 stiffness D and the material axes it is
//! given in.
//!
//! **Convention (one place for the whole crate)**: Voigt order `[xx yy zz xy yz zx]` with
//! engineering shear strains γ_ij = 2ε_ij, so that σ = D ε and the strain energy is ½ εᵀ D ε
//! (the order of `body::stress` and Nastran MAT9; Abaqus/CalculiX list D in the order
//! 11 22 33 12 13 23 — their importer permutes). D is given in the material axes; an element's
//! D in the basic frame is D' = T D Tᵀ with T the Bond stress transformation of the axes
//! (Ting, *Anisotropic Elasticity* (1996) §2.8).

// Index notation, as the formulas are written.
#![allow(clippy::needless_range_loop)]

use super::geometry::{cross, det3, dot, inverse3, scale, sub, unit};

/// A 6×6 elasticity matrix in the order of the module doc, row-major.
pub type Stiffness6 = [[f64; 6]; 6];

/// Voigt index of the tensor pair (i, j), i, j ∈ 0..3, in the order `[xx yy zz xy yz zx]`.
pub const fn voigt(i: usize, j: usize) -> usize {
    match (i, j) {
        (0, 0) => 0,
        (1, 1) => 1,
        (2, 2) => 2,
        (0, 1) | (1, 0) => 3,
        (1, 2) | (2, 1) => 4,
        _ => 5,
    }
}

/// A material's elasticity beyond the isotropic E, ν of [`super::Material`].
#[derive(Debug, Clone, PartialEq)]
pub enum Elasticity {
    /// Isotropic: E, ν, G of the material.
    Isotropic,
    /// General (orthotropic or anisotropic) 3-D stiffness in the material axes.
    Anisotropic(Box<Stiffness6>),
    /// A plane-stress material of shells only (Nastran MAT8, MAT2).
    PlaneStress(Box<PlaneStress>),
}

/// A plane-stress shell material in its material axes (1 = the element's material x-axis
/// turned by the ply angle): σ = Q ε in the order `[11 22 12]` with engineering shear γ12, and
/// the transverse shear stiffness on (γ13, γ23).
#[derive(Debug, Clone, PartialEq)]
pub struct PlaneStress {
    /// In-plane Q (3×3).
    pub q: [[f64; 3]; 3],
    /// Transverse shear stiffness (2×2) on (γ13, γ23): MAT8 diag(G1Z, G2Z); `None`: MAT8
    /// G1Z/G2Z blank (shear-rigid) and MAT2.
    pub transverse: Option<[[f64; 2]; 2]>,
    /// The transverse shear stiffness when a PSHELL names the material as MID3 (MAT2: its
    /// [G11 G12; G12 G22], MSC QRG MAT2), if it differs from `transverse`.
    pub as_mid3: Option<[[f64; 2]; 2]>,
}

impl PlaneStress {
    /// An orthotropic lamina (Nastran MAT8): Q11 = E1/(1−ν12ν21), Q22 = E2/(1−ν12ν21),
    /// Q12 = ν12E2/(1−ν12ν21), Q66 = G12, ν21 = ν12E2/E1 (Reddy, *Mechanics of Laminated
    /// Composite Plates and Shells* (2004) eq. 3.3.2).
    pub fn lamina(
        e1: f64,
        e2: f64,
        nu12: f64,
        g12: f64,
        gz: Option<[f64; 2]>,
    ) -> Result<Self, String> {
        let nu21 = nu12 * e2 / e1;
        let den = 1.0 - nu12 * nu21;
        if [e1, e2, g12].iter().any(|v| !(v.is_finite() && *v > 0.0)) || den.is_nan() || den <= 0.0
        {
            return Err(format!(
                "a lamina needs E1, E2, G12 > 0 and ν12²E2/E1 < 1 (E1 = {e1}, E2 = {e2}, ν12 = {nu12}, G12 = {g12})"
            ));
        }
        if let Some([a, b]) = gz {
            if !(a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite()) {
                return Err(format!(
                    "transverse shear moduli G1Z = {a}, G2Z = {b} must be > 0"
                ));
            }
        }
        Ok(PlaneStress {
            q: [
                [e1 / den, nu12 * e2 / den, 0.0],
                [nu12 * e2 / den, e2 / den, 0.0],
                [0.0, 0.0, g12],
            ],
            transverse: gz.map(|[a, b]| [[a, 0.0], [0.0, b]]),
            as_mid3: None,
        })
    }
}

/// The material axes of a property (Abaqus `*ORIENTATION`, Nastran PSOLID CORDM).
#[derive(Debug, Clone, PartialEq)]
pub enum MaterialAxes {
    /// Fixed axes: rows are the unit material axes 1, 2, 3 in the basic frame.
    Rectangular([[f64; 3]; 3]),
    /// Cylindrical axes about the line from `a` to `b` (CalculiX `transformatrix`): axis 1
    /// radial through the point, 3 along b − a, 2 = 3 × 1 (tangential).
    Cylindrical {
        /// First point on the axis.
        a: [f64; 3],
        /// Second point on the axis.
        b: [f64; 3],
    },
}

impl MaterialAxes {
    /// Rectangular axes from the point `a` on axis 1 and the point `b` in the 1–2 plane (both
    /// relative to the origin; Abaqus/CalculiX `*ORIENTATION, SYSTEM=RECTANGULAR`), then
    /// rotated by `angle_deg` about local axis `axis` (1–3; 0 = none). `None` when a and b
    /// are zero or parallel.
    pub fn rectangular(a: [f64; 3], b: [f64; 3], axis: usize, angle_deg: f64) -> Option<Self> {
        let e1 = unit(a)?;
        let e2 = unit(sub(b, scale(e1, dot(b, e1))))?;
        let e3 = cross(e1, e2);
        let mut r = [e1, e2, e3];
        if (1..=3).contains(&axis) && angle_deg != 0.0 {
            // Right-handed rotation about local axis k: the other two turn in their plane.
            let (c, s) = (angle_deg.to_radians().cos(), angle_deg.to_radians().sin());
            let (i, j) = (axis % 3, (axis + 1) % 3);
            let (ei, ej) = (r[i], r[j]);
            r[i] = std::array::from_fn(|k| c * ei[k] + s * ej[k]);
            r[j] = std::array::from_fn(|k| -s * ei[k] + c * ej[k]);
        }
        Some(MaterialAxes::Rectangular(r))
    }

    /// The material axes at the point `x` (rows: axes 1, 2, 3 in the basic frame). On the axis
    /// of a cylindrical system any radial direction is taken, as CalculiX does.
    pub fn at(&self, x: &[f64; 3]) -> [[f64; 3]; 3] {
        match self {
            MaterialAxes::Rectangular(r) => *r,
            MaterialAxes::Cylindrical { a, b } => {
                let e3 = unit(sub(*b, *a)).unwrap_or([0.0, 0.0, 1.0]);
                let p = sub(*x, *a);
                let radial = sub(p, scale(e3, dot(p, e3)));
                let e1 = unit(radial).unwrap_or_else(|| {
                    let trial = if e3[0].abs() < 0.9 {
                        [1.0, 0.0, 0.0]
                    } else {
                        [0.0, 1.0, 0.0]
                    };
                    unit(cross(e3, trial)).unwrap_or([1.0, 0.0, 0.0])
                });
                let e2 = cross(e3, e1);
                [e1, e2, e3]
            }
        }
    }
}

/// D in the basic frame from D in the material axes `r` (rows: axes in the basic frame):
/// C'_ijkl = R_pi R_qj R_rk R_sl C_pqrs, as the Bond matrix T: D' = T D Tᵀ (Ting §2.8).
pub fn rotate(d: &Stiffness6, r: &[[f64; 3]; 3]) -> Stiffness6 {
    // T_(ij),(pq): stress in basic (ij) from stress in material axes (pq): σ'_ij = R_pi R_qj σ_pq.
    let pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0)];
    let mut t = [[0.0; 6]; 6];
    for (a, &(i, j)) in pairs.iter().enumerate() {
        for p in 0..3 {
            for q in 0..3 {
                t[a][voigt(p, q)] += r[p][i] * r[q][j];
            }
        }
    }
    let mut td = [[0.0; 6]; 6];
    for a in 0..6 {
        for b in 0..6 {
            td[a][b] = (0..6).map(|c| t[a][c] * d[c][b]).sum();
        }
    }
    let mut out = [[0.0; 6]; 6];
    for a in 0..6 {
        for b in 0..6 {
            out[a][b] = (0..6).map(|c| td[a][c] * t[b][c]).sum();
        }
    }
    out
}

/// The isotropic D (λ, μ): σ = λ tr ε I + 2μ ε in the module's convention.
pub fn isotropic(lambda: f64, mu: f64) -> Stiffness6 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| match (i < 3, j < 3) {
            (true, true) => lambda + if i == j { 2.0 * mu } else { 0.0 },
            _ if i == j => mu,
            _ => 0.0,
        })
    })
}

/// Orthotropic D from the engineering constants by inverting the compliance
/// S = [1/E1 −ν21/E2 −ν31/E3; −ν12/E1 1/E2 −ν32/E3; −ν13/E1 −ν23/E2 1/E3] ⊕ diag(1/G12, 1/G23,
/// 1/G13), ν_ji/E_j = ν_ij/E_i (Jones, *Mechanics of Composite Materials* (1999) §2.4).
pub fn from_engineering_constants(
    [e1, e2, e3]: [f64; 3],
    [nu12, nu13, nu23]: [f64; 3],
    [g12, g13, g23]: [f64; 3],
) -> Result<Stiffness6, String> {
    if [e1, e2, e3, g12, g13, g23]
        .iter()
        .any(|v| !(v.is_finite() && *v > 0.0))
    {
        return Err(format!(
            "engineering constants need E1, E2, E3, G12, G13, G23 > 0 (E = {e1}, {e2}, {e3}; G = {g12}, {g13}, {g23})"
        ));
    }
    let s = [
        [1.0 / e1, -nu12 / e1, -nu13 / e1],
        [-nu12 / e1, 1.0 / e2, -nu23 / e2],
        [-nu13 / e1, -nu23 / e2, 1.0 / e3],
    ];
    let c = invert3(&s).ok_or_else(|| {
        format!("engineering constants give a singular compliance (ν12 = {nu12}, ν13 = {nu13}, ν23 = {nu23})")
    })?;
    let mut d = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            d[i][j] = c[i][j];
        }
    }
    d[3][3] = g12;
    d[4][4] = g23;
    d[5][5] = g13;
    Ok(d)
}

fn invert3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let det = det3(m);
    (det != 0.0 && det.is_finite()).then(|| inverse3(m, det))
}

/// Eigenvalues of a symmetric 6×6 matrix, ascending (cyclic Jacobi; Golub & Van Loan §8.5).
pub fn eigenvalues(d: &Stiffness6) -> [f64; 6] {
    let mut a = *d;
    for _ in 0..100 {
        let off: f64 = (0..6)
            .flat_map(|i| (0..6).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        let diag: f64 = (0..6).map(|i| a[i][i] * a[i][i]).sum();
        if off <= 1e-30 * diag || off == 0.0 {
            break;
        }
        for p in 0..6 {
            for q in p + 1..6 {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..6 {
                    let (akp, akq) = (a[k][p], a[k][q]);
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for k in 0..6 {
                    let (apk, aqk) = (a[p][k], a[q][k]);
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
            }
        }
    }
    let mut ev: [f64; 6] = std::array::from_fn(|i| a[i][i]);
    ev.sort_by(f64::total_cmp);
    ev
}

/// How definite a material's D is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Definiteness {
    /// Every eigenvalue positive: a stable solid.
    Positive,
    /// Positive semi-definite with `rank` < 6 (strain states without stress: CalculiX's acou3
    /// models air this way); accepted with a note, as CalculiX accepts it.
    Singular {
        /// Number of eigenvalues above the tolerance.
        rank: usize,
    },
}

/// D must be symmetric and positive (semi-)definite; the error says which eigenvalue fails.
/// Tolerance: 1e-12 of the largest eigenvalue.
pub fn check(d: &Stiffness6) -> Result<Definiteness, String> {
    if d.iter().flatten().any(|v| !v.is_finite()) {
        return Err("the elasticity matrix has a value that is not finite".into());
    }
    for i in 0..6 {
        for j in 0..i {
            let tol = 1e-12 * (d[i][i].abs() + d[j][j].abs());
            if (d[i][j] - d[j][i]).abs() > tol {
                return Err(format!(
                    "the elasticity matrix is not symmetric (entry {}{} = {:e}, {}{} = {:e})",
                    i + 1,
                    j + 1,
                    d[i][j],
                    j + 1,
                    i + 1,
                    d[j][i]
                ));
            }
        }
    }
    let ev = eigenvalues(d);
    let top = ev[5];
    if top <= 0.0 {
        return Err(
            "the elasticity matrix has no positive eigenvalue (all constants zero?)".into(),
        );
    }
    let tol = 1e-12 * top;
    if ev[0] < -tol {
        return Err(format!(
            "the elasticity matrix is not positive definite (eigenvalues {}): the material \
             would release energy under some strain",
            ev.iter()
                .map(|v| format!("{v:.4e}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let rank = ev.iter().filter(|&&v| v > tol).count();
    Ok(if rank == 6 {
        Definiteness::Positive
    } else {
        Definiteness::Singular { rank }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Engineering constants of an isotropic material give the Lamé D exactly.
    #[test]
    fn engineering_constants_of_an_isotropic_material_are_lame() {
        let (e, nu) = (210e9, 0.3);
        let g = e / (2.0 * (1.0 + nu));
        let d = from_engineering_constants([e; 3], [nu; 3], [g; 3]).unwrap();
        let lam = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let want = isotropic(lam, g);
        for i in 0..6 {
            for j in 0..6 {
                assert!((d[i][j] - want[i][j]).abs() < 1e-12 * e, "{i}{j}");
            }
        }
        assert_eq!(check(&d), Ok(Definiteness::Positive));
    }

    /// Rotating an isotropic D changes nothing; rotating an orthotropic one by 90° about z
    /// swaps its 1 and 2 constants and G13 with G23.
    #[test]
    fn rotation_of_d_follows_the_axes() {
        let iso = isotropic(1.2, 0.8);
        let r = MaterialAxes::rectangular([1.0, 1.0, 0.3], [0.0, 1.0, 1.0], 3, 17.0)
            .unwrap()
            .at(&[0.0; 3]);
        let d = rotate(&iso, &r);
        for i in 0..6 {
            for j in 0..6 {
                assert!((d[i][j] - iso[i][j]).abs() < 1e-14, "{i}{j}");
            }
        }
        let o = from_engineering_constants([10.0, 2.0, 3.0], [0.2, 0.25, 0.3], [1.5, 0.7, 0.4])
            .unwrap();
        let r = MaterialAxes::rectangular([0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], 0, 0.0)
            .unwrap()
            .at(&[0.0; 3]);
        let d = rotate(&o, &r);
        assert!((d[1][1] - o[0][0]).abs() < 1e-14);
        assert!((d[0][0] - o[1][1]).abs() < 1e-14);
        assert!((d[0][2] - o[1][2]).abs() < 1e-14);
        assert!((d[3][3] - o[3][3]).abs() < 1e-14);
        assert!((d[4][4] - o[5][5]).abs() < 1e-14);
        assert!((d[5][5] - o[4][4]).abs() < 1e-14);
    }

    /// The additional rotation turns axis 1 toward axis 2 about axis 3.
    #[test]
    fn additional_rotation_is_right_handed() {
        let r = MaterialAxes::rectangular([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 3, 90.0)
            .unwrap()
            .at(&[0.0; 3]);
        assert!((r[0][1] - 1.0).abs() < 1e-15 && (r[1][0] + 1.0).abs() < 1e-15);
        let c = MaterialAxes::Cylindrical {
            a: [0.0; 3],
            b: [0.0, 0.0, 2.0],
        }
        .at(&[0.0, 3.0, 1.0]);
        assert_eq!(c, [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
    }

    /// acou3's D (every normal entry and the shears equal) is singular of rank 4; an
    /// indefinite one is refused.
    #[test]
    fn definiteness_is_checked() {
        let mut d = [[0.0; 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                d[i][j] = 5.0;
            }
            d[i + 3][i + 3] = 5.0;
        }
        assert_eq!(check(&d), Ok(Definiteness::Singular { rank: 4 }));
        d[0][1] = 6.0;
        d[1][0] = 6.0;
        assert!(check(&d).unwrap_err().contains("not positive definite"));
    }
}
