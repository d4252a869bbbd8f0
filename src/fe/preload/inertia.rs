//! Inertia loads of a preload: body forces per unit mass that are linear in position,
//! b(x) = c + G (x − x₀), applied with the build's mass matrix, f = M b (lumped or consistent,
//! point masses included) — gravity, a rigid acceleration, a spin (CalculiX `*DLOAD … CENTRIF`,
//! Nastran RFORCE: b = Ω² r_⊥), an angular acceleration (b = −α × r); and the rotating frame's
//! spin softening −Ω² Pᵀ M P.
//!
//! The nodal rotations take the rotational part of the field, the axial vector of the skew part
//! of G (−α for an angular acceleration, none for a spin), so that a rigid acceleration field
//! acts on rotary inertia too.

use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;

use crate::fe::dofs::DofMap;
use crate::model::Model;
use crate::solve::{sparse_ops, SolveError};

/// A body force per unit mass linear in position: b(x) = `constant` + `gradient` (x − `origin`)
/// (basic frame; module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct InertiaField {
    /// x₀.
    pub origin: [f64; 3],
    /// c.
    pub constant: [f64; 3],
    /// G, row-major: b_i = c_i + Σ_j G_ij (x − x₀)_j.
    pub gradient: [[f64; 3]; 3],
}

/// A rotation at constant speed about an axis (CalculiX CENTRIF, Nastran RFORCE).
#[derive(Debug, Clone, PartialEq)]
pub struct Spin {
    /// A point of the axis.
    pub point: [f64; 3],
    /// The axis direction (any length).
    pub axis: [f64; 3],
    /// Speed Ω (rad per unit time).
    pub omega: f64,
}

impl Spin {
    /// The unit axis n, or `None` for a zero axis.
    fn unit_axis(&self) -> Option<[f64; 3]> {
        let l = self.axis.iter().map(|v| v * v).sum::<f64>().sqrt();
        (l > 0.0 && l.is_finite()).then(|| self.axis.map(|v| v / l))
    }

    /// The centrifugal field b = Ω² (I − n nᵀ)(x − p) (`None` for a zero axis).
    pub fn field(&self) -> Option<InertiaField> {
        let n = self.unit_axis()?;
        let w2 = self.omega * self.omega;
        Some(InertiaField {
            origin: self.point,
            constant: [0.0; 3],
            gradient: std::array::from_fn(|i| {
                std::array::from_fn(|j| w2 * (f64::from(u8::from(i == j)) - n[i] * n[j]))
            }),
        })
    }
}

/// Which unit inertia load of a floating body a field is (see [`unit_inertia_fields`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InertiaLoad {
    /// Translational acceleration a_i = 1 of the frame (b = −e_i).
    Acceleration(usize),
    /// Angular-velocity product ω_i ω_j = 1 (i ≤ j): its part of b = |ω|² r − ω (ω·r).
    AngularVelocity(usize, usize),
    /// Angular acceleration α_i = 1 (b = −e_i × r).
    AngularAcceleration(usize),
}

/// The twelve unit inertia loads of a body whose floating frame has its origin at `origin`
/// (d'Alembert body forces per unit mass, r = x − origin): three translational accelerations,
/// the six products ω_iω_j (i ≤ j) of the angular velocity (the centrifugal field is
/// Σ_{i≤j} ω_iω_j b_ij) and three angular accelerations.
pub fn unit_inertia_fields(origin: [f64; 3]) -> Vec<(InertiaLoad, InertiaField)> {
    let e = |i: usize, j: usize| f64::from(u8::from(i == j));
    let field = |constant: [f64; 3], gradient: [[f64; 3]; 3]| InertiaField {
        origin,
        constant,
        gradient,
    };
    let mut out = Vec::with_capacity(12);
    for i in 0..3 {
        out.push((
            InertiaLoad::Acceleration(i),
            field(std::array::from_fn(|k| -e(i, k)), [[0.0; 3]; 3]),
        ));
    }
    for i in 0..3 {
        for j in i..3 {
            // ω_i² : I − e_i e_iᵀ; ω_iω_j (i < j): −(e_i e_jᵀ + e_j e_iᵀ)
            let g = std::array::from_fn(|r| {
                std::array::from_fn(|c| {
                    if i == j {
                        e(r, c) - e(r, i) * e(c, i)
                    } else {
                        -(e(r, i) * e(c, j) + e(r, j) * e(c, i))
                    }
                })
            });
            out.push((InertiaLoad::AngularVelocity(i, j), field([0.0; 3], g)));
        }
    }
    for i in 0..3 {
        // −e_i × r = −[e_i]ₓ r
        let g = std::array::from_fn(|r| {
            std::array::from_fn(|c| {
                let (a, b) = ((i + 1) % 3, (i + 2) % 3);
                if r == a && c == b {
                    1.0
                } else if r == b && c == a {
                    -1.0
                } else {
                    0.0
                }
            })
        });
        out.push((InertiaLoad::AngularAcceleration(i), field([0.0; 3], g)));
    }
    out
}

/// Basic → node displacement frame (rows of R are the local axes).
pub(crate) fn to_node_frame(dofs: &DofMap, node: usize, v: [f64; 3]) -> [f64; 3] {
    match &dofs.frames[node] {
        Some(r) => std::array::from_fn(|i| (0..3).map(|k| r[i][k] * v[k]).sum()),
        None => v,
    }
}

/// The nodal values of a field on the physical dofs: b(x_p) on the translations, the axial
/// vector of the skew part of G on the rotations (module doc).
fn nodal_field(model: &Model, dofs: &DofMap, field: &InertiaField) -> Mat<f64> {
    let g = &field.gradient;
    let rot = [
        0.5 * (g[2][1] - g[1][2]),
        0.5 * (g[0][2] - g[2][0]),
        0.5 * (g[1][0] - g[0][1]),
    ];
    let mut b = Mat::<f64>::zeros(dofs.n_dofs, 1);
    for (p, node) in model.nodes.iter().enumerate() {
        let count = usize::from(dofs.count[p]);
        if count == 0 {
            continue;
        }
        let r: [f64; 3] = std::array::from_fn(|k| node.x[k] - field.origin[k]);
        let t = std::array::from_fn(|i| {
            field.constant[i] + (0..3).map(|j| g[i][j] * r[j]).sum::<f64>()
        });
        for (off, v) in [(0, t), (3, rot)] {
            if off < count {
                let l = to_node_frame(dofs, p, v);
                for k in 0..3 {
                    b[(dofs.first[p] + off + k, 0)] = l[k];
                }
            }
        }
    }
    b
}

/// f = M b over the physical dofs (module doc); `m` the build's mass matrix.
pub fn inertia_load(
    model: &Model,
    dofs: &DofMap,
    m: &SparseColMat<usize, f64>,
    field: &InertiaField,
) -> Vec<f64> {
    let b = nodal_field(model, dofs, field);
    let f = sparse_ops::spmm(m.as_ref(), b.as_ref());
    (0..dofs.n_dofs).map(|i| f[(i, 0)]).collect()
}

/// The spin softening of the rotating frame, −Ω² Pᵀ M P over the physical dofs: P keeps each
/// node's translation perpendicular to the axis (I − n nᵀ, in its displacement frame) and drops
/// the rotations. Added to K_T it gives the in-plane (lead-lag) frequencies of a rotating body
/// seen in its rotating frame (ω² = ω²_flap − Ω² for a uniform beam); the out-of-plane (flap)
/// motion along the axis is unchanged.
pub fn spin_softening(
    model: &Model,
    dofs: &DofMap,
    m: &SparseColMat<usize, f64>,
    spin: &Spin,
) -> Result<SparseColMat<usize, f64>, SolveError> {
    let n = spin
        .unit_axis()
        .ok_or_else(|| SolveError::Invalid("spin softening: zero axis".into()))?;
    let mut trips = Vec::new();
    for p in 0..model.nodes.len() {
        if dofs.count[p] == 0 {
            continue;
        }
        // P_local = R (I − n nᵀ) Rᵀ
        let cols: [[f64; 3]; 3] = std::array::from_fn(|j| {
            let mut e = [0.0; 3];
            e[j] = 1.0;
            // column j of Rᵀ is the basic vector of local axis j
            let basic = match &dofs.frames[p] {
                Some(r) => r[j],
                None => e,
            };
            let d: f64 = (0..3).map(|k| n[k] * basic[k]).sum();
            let perp: [f64; 3] = std::array::from_fn(|k| basic[k] - d * n[k]);
            to_node_frame(dofs, p, perp)
        });
        for (j, col) in cols.iter().enumerate() {
            for (i, v) in col.iter().enumerate() {
                if *v != 0.0 {
                    trips.push(Triplet::new(dofs.first[p] + i, dofs.first[p] + j, *v));
                }
            }
        }
    }
    let nd = dofs.n_dofs;
    let proj = SparseColMat::try_new_from_triplets(nd, nd, &trips)
        .map_err(|e| SolveError::Invalid(format!("spin softening: {e:?}")))?;
    let w2 = spin.omega * spin.omega;
    let mut ptmp = sparse_ops::congruence(proj.as_ref(), m.as_ref(), faer::Par::Seq)?;
    for v in ptmp.val_mut() {
        *v *= -w2;
    }
    Ok(ptmp)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Σ_{i≤j} ω_iω_j b_ij is the centrifugal field |ω|² r − ω(ω·r) of the spin about ω.
    #[test]
    fn unit_angular_velocity_fields_sum_to_the_spin_field() {
        let w = [0.3, -1.2, 0.7];
        let fields = unit_inertia_fields([0.0; 3]);
        let mut g = [[0.0; 3]; 3];
        for (label, f) in &fields {
            if let InertiaLoad::AngularVelocity(i, j) = label {
                for r in 0..3 {
                    for c in 0..3 {
                        g[r][c] += w[*i] * w[*j] * f.gradient[r][c];
                    }
                }
            }
        }
        let norm = w.iter().map(|v| v * v).sum::<f64>().sqrt();
        let spin = Spin {
            point: [0.0; 3],
            axis: w,
            omega: norm,
        }
        .field()
        .unwrap();
        for r in 0..3 {
            for c in 0..3 {
                assert!((g[r][c] - spin.gradient[r][c]).abs() < 1e-14, "{r}{c}");
            }
        }
    }
}
