//! What the flat shell elements ([`super::quad4_shell`], [`super::tri3_shell`]) share: section
//! constants, the element's local frame, the drilling stiffness, the mass and the rotation of
//! local matrices to the basic frame.
//!
//! A flat shell element superposes, in its own local frame (e₁, e₂ in the element plane, e₃ the
//! normal), a membrane (u, v), a plate (w, θx, θy) and a drilling rotation θz; dofs per node
//! `[u v w θx θy θz]`, 6 per node. The rotation vector θ acts on the normal as β = θ × e₃, i.e.
//! the plate rotations of the mid-surface normal are βx = θy, βy = −θx (Bathe, *Finite Element
//! Procedures* (1996) §5.4.2 sign convention).
//!
//! Section resultants (plane stress, isotropic):
//! N = D_m ε, D_m = E₁t/(1−ν₁²)·[1 ν₁ 0; ν₁ 1 0; 0 0 (1−ν₁)/2] (membrane, MID1);
//! M = D_b κ, D_b = E₂ (12I/t³) t³/12/(1−ν₂²)·[…] (bending, MID2, Nastran PSHELL 12I/T³);
//! Q = D_s γ, D_s = (t_s/t)·G₃ t·I₂ (transverse shear, MID3, Nastran TS/T, default 5/6).
//!
//! Laminates and plane-stress materials (Nastran PCOMP, MAT8, MAT2; [`GeneralSection`]): the
//! classical-lamination resultants N = A ε + B κ, M = B ε + D κ, Q = A_s γ (Reddy, *Mechanics
//! of Laminated Composite Plates and Shells* (2004) eq. 3.3.17), A, B, D, A_s given in the
//! section's material axes and turned into the element's by the angle ψ of the material x-axis
//! ([`ShellProps::resultants`]): Q̄ = T_εᵀ Q T_ε, A̅_s = Rᵀ A_s R (Reddy eq. 2.3.17/2.3.18 in
//! strain form). The drilling penalty then uses the rotation-invariant in-plane shear rigidity
//! (A11 + A22 − 2A12 + 4A66)/8 (= G t isotropic).
//!
//! Drilling rotation: a penalty (Hughes & Brezzi, *CMAME* 72 (1989) 105) on the difference
//! between θz and the membrane's in-plane rotation ω = ½(∂v/∂x − ∂u/∂y),
//! Π_d = ½ ∫ γ_d (θz − ω)² dA with γ_d = [`DRILL_FACTOR`]·G₁t, integrated at as many points as
//! the element has nodes (no spurious drilling modes). A rigid rotation about the normal has
//! θz = ω and costs nothing, so a free flat plate has exactly 6 zero modes; a shell node joined to
//! a beam or a rigid element is not singular about its normal. The factor is Nastran's
//! `PARAM,K6ROT` × 10⁻⁶ (MSC's formula; the deck's value in `ModelParams::k6rot`): the
//! default 10⁻⁴ is K6ROT = 100 × 10⁻⁶. It does not enter flat-plate bending or membrane patch tests (θz = ω
//! there); on folded and curved shells it changes frequencies by far less than the
//! discretisation error (test `shell_drilling_factor_barely_moves_folded_plate_frequencies`
//! in tests/shell_plates.rs).
//!
//! Mass (consistent): translations ∫ (ρt + nsm) N_a N_b dA ⊗ I₃; rotations ∫ ρt³/12 N_a N_b dA
//! ⊗ (I − (1 − ε) e₃e₃ᵀ): the plate's rotary inertia on the two bending rotations and a small
//! ε = [`DRILL_INERTIA`] = 10⁻⁴ of it on the drilling rotation, so that no rotation is massless.
//! Lumped: the row sums of the same matrices (translations by the area ∫N_a dA, rotations
//! ρt³/12 ∫N_a dA); Nastran decks lump translations only, as MSC Nastran does
//! ([`ShellProps::lumped_rotary`]). Why ε is small: the drilling dof is a numerical device, and
//! its penalty spring against an inertia ε ρt³/12 makes a local "drilling oscillation" at
//! ω ≈ √(c·DRILL_FACTOR·G/(ε ρ))/t (c of order 10). With the full ρt³/12 (ε = 1) that was
//! measured at about 1.6 kHz on a 4 mm and 3 kHz on a 2 mm steel sheet — a cluster of spurious
//! modes inside a multibody band; with ε = 10⁻⁴ it sits 100× higher (≈ 0.3 MHz at 2 mm).

use super::{ElementError, Isotropic, Xyz};
use crate::model::geometry::{cross, dot, norm, scale, sub};
use crate::model::ShellMaterialAxis;

/// A 3×3 matrix.
pub type M3 = [[f64; 3]; 3];
/// A 2×2 matrix.
pub type M2 = [[f64; 2]; 2];

/// A shell section given by its rigidities (laminate or plane-stress material; module doc),
/// in the section's material axes (x = the element's material x-axis).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneralSection {
    /// Membrane A (N = A ε + B κ).
    pub a: M3,
    /// Membrane–bending coupling B (zero for a symmetric laminate).
    pub b: M3,
    /// Bending D (M = B ε + D κ).
    pub d: M3,
    /// Transverse shear A_s on (γxz, γyz).
    pub shear: M2,
    /// Mass per unit area Σ ρ_k t_k (without the non-structural mass).
    pub mass: f64,
    /// Rotary inertia per unit area Σ ρ_k ∫ z² dz about the reference surface.
    pub rotary: f64,
    /// Where the element's material x-axis lies.
    pub axis: ShellMaterialAxis,
}

/// The section rigidities of one element in its own local axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resultants {
    /// Membrane.
    pub a: M3,
    /// Coupling (zero for isotropic sections).
    pub b: M3,
    /// Bending.
    pub d: M3,
    /// Transverse shear.
    pub shear: M2,
    /// B ≠ 0.
    pub coupled: bool,
    /// The section has transverse shear of its own (the DKMT's switch, tri3_shell.rs).
    pub has_shear: bool,
}

/// Drilling penalty factor: γ_d = DRILL_FACTOR · G t (module doc; Nastran K6ROT = 100 × 10⁻⁶).
pub const DRILL_FACTOR: f64 = 1e-4;

/// Section constants of a shell element (per element, thickness already resolved).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellProps {
    /// Thickness t.
    pub t: f64,
    /// Membrane material (MID1); `None` = no membrane stiffness.
    pub membrane: Option<Isotropic>,
    /// Bending material (MID2) and the bending-inertia ratio 12I/t³; `None` = no bending.
    pub bending: Option<(Isotropic, f64)>,
    /// Transverse shear material (MID3) and the ratio t_s/t; `None` = shear-rigid (taken as
    /// 5/6 of the bending material's shear modulus, see [`ShellProps::shear_modulus`]).
    pub shear: Option<(Isotropic, f64)>,
    /// Mass density ρ of the structural mass (MID1, else MID2).
    pub rho: f64,
    /// Non-structural mass per unit area.
    pub nsm: f64,
    /// Drilling penalty factor ([`DRILL_FACTOR`] unless studying its effect).
    pub drill_factor: f64,
    /// The lumped mass carries the rotary inertia ρt³/12 (module doc); `false`: translations
    /// only, as MSC Nastran lumps CQUAD4/CTRIA3 (its grid-point kinetic energies of shell grids
    /// have no rotational part). The consistent mass always has it.
    pub lumped_rotary: bool,
    /// A laminate or plane-stress section: its rigidities replace those of the isotropic
    /// materials above (which then only name the section's primary material).
    pub general: Option<GeneralSection>,
    /// Which solver's 4-node shell the quadrilateral is ([`Quad4Form`]); the triangle and the
    /// quadratic shells ignore it.
    pub quad4: Quad4Form,
}

/// Which solver's 4-node shell a quadrilateral is formed as: the transverse shear and drilling
/// of MITC4 + QM6 as each solver modifies them ([`super::quad4_shell`] module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Quad4Form {
    /// Plain MITC4 with the drilling penalty [`ShellProps::drill`] (Abaqus S4, Gmsh).
    #[default]
    Mitc4,
    /// MSC Nastran's QUAD4 (MacNeal 1978): the transverse shear compliance carries the residual
    /// bending flexibility ℓ²/(12 D), as a Nastran deck's CQUAD4 is formed.
    NastranQuad4,
    /// ANSYS SHELL181 with KEYOPT(3)=2: the transverse shear scaled by 1/(1 + A/(160 000 t²))
    /// and the drilling penalty 1/200 of the scaled transverse shear rigidity, as ANSYS's
    /// element forces show (docs/ansys.md).
    AnsysShell181,
}

impl ShellProps {
    /// The same section without membrane stiffness and drilling penalty: the plate part of a
    /// shell whose membrane comes from elsewhere (CQUADR/CTRIAR, `drill_membrane`).
    pub fn plate_only(&self) -> ShellProps {
        ShellProps {
            membrane: None,
            drill_factor: 0.0,
            ..*self
        }
    }

    /// One isotropic material for membrane, bending and shear (12I/t³ = 1, t_s/t = 5/6).
    pub fn isotropic(t: f64, mat: Isotropic) -> ShellProps {
        ShellProps {
            t,
            membrane: Some(mat),
            bending: Some((mat, 1.0)),
            shear: Some((mat, 5.0 / 6.0)),
            rho: mat.rho,
            nsm: 0.0,
            drill_factor: DRILL_FACTOR,
            lumped_rotary: true,
            general: None,
            quad4: Quad4Form::Mitc4,
        }
    }

    /// The element's section rigidities in its local axes (`axes` rows e₁, e₂, e₃; `side12` the
    /// G1→G2 side in local in-plane coordinates): the isotropic ones as they are, a
    /// [`GeneralSection`] turned by the angle ψ of its material x-axis (module doc).
    pub fn resultants(
        &self,
        axes: &[Xyz; 3],
        side12: [f64; 2],
    ) -> Result<Resultants, ElementError> {
        let Some(g) = &self.general else {
            let ds = self.shear_modulus();
            return Ok(Resultants {
                a: self.d_membrane(),
                b: [[0.0; 3]; 3],
                d: self.d_bending(),
                shear: [[ds, 0.0], [0.0, ds]],
                coupled: false,
                has_shear: self.shear.is_some(),
            });
        };
        let psi = material_angle(&g.axis, axes, side12)?;
        let b = rotate_plane(&g.b, psi);
        Ok(Resultants {
            a: rotate_plane(&g.a, psi),
            coupled: b.iter().flatten().any(|v| *v != 0.0),
            b,
            d: rotate_plane(&g.d, psi),
            shear: rotate_shear(&g.shear, psi),
            has_shear: true,
        })
    }

    /// Checks the constants.
    pub fn check(&self) -> Result<(), ElementError> {
        if let Some(g) = &self.general {
            let ok = self.t > 0.0
                && self.t.is_finite()
                && g.mass >= 0.0
                && g.rotary >= 0.0
                && self.nsm >= 0.0
                && positive_definite3(&g.a)
                && positive_definite3(&g.d)
                && g.shear[0][0] > 0.0
                && g.shear[0][0] * g.shear[1][1] > g.shear[0][1] * g.shear[1][0];
            if !ok {
                return Err(ElementError::BadConstants(format!(
                    "laminate/plane-stress section needs t > 0, positive definite A, D and \
                     transverse shear, mass ≥ 0 (t = {}, A = {:?}, D = {:?}, A_s = {:?})",
                    self.t, g.a, g.d, g.shear
                )));
            }
            return Ok(());
        }
        let mat_ok =
            |m: &Isotropic| m.e > 0.0 && m.e.is_finite() && m.nu > -1.0 && m.nu < 0.5 && m.g > 0.0;
        let ok = self.t > 0.0
            && self.t.is_finite()
            && self.rho >= 0.0
            && self.nsm >= 0.0
            && self.membrane.as_ref().is_none_or(mat_ok)
            && self
                .bending
                .as_ref()
                .is_none_or(|(m, r)| mat_ok(m) && *r > 0.0)
            && self
                .shear
                .as_ref()
                .is_none_or(|(m, r)| mat_ok(m) && *r > 0.0)
            && (self.membrane.is_some() || self.bending.is_some());
        if !ok {
            return Err(ElementError::BadConstants(format!(
                "shell needs t > 0, E > 0, −1 < ν < 0.5, positive 12I/t³ and TS/T, ρ, nsm ≥ 0 \
                 and a membrane or bending material (t = {}, ρ = {}, nsm = {})",
                self.t, self.rho, self.nsm
            )));
        }
        Ok(())
    }

    /// Membrane rigidity D_m (3×3, module formula); zero without a membrane material.
    pub fn d_membrane(&self) -> [[f64; 3]; 3] {
        match self.membrane {
            Some(m) => plane_stress(m.e * self.t, m.nu),
            None => [[0.0; 3]; 3],
        }
    }

    /// Bending rigidity D_b (3×3, module formula); zero without a bending material.
    pub fn d_bending(&self) -> [[f64; 3]; 3] {
        match self.bending {
            Some((m, r)) => plane_stress(m.e * r * self.t.powi(3) / 12.0, m.nu),
            None => [[0.0; 3]; 3],
        }
    }

    /// Transverse shear rigidity (t_s/t)·G t (module formula); zero without bending.
    pub fn shear_modulus(&self) -> f64 {
        match (self.shear, self.bending) {
            (Some((m, r)), Some(_)) => r * m.g * self.t,
            // MID3 blank: Nastran's shear-rigid plate; MITC4 does not lock, so the
            // Reissner–Mindlin value 5/6·G₂t gives the same thin-plate answer.
            (None, Some((m, _))) => 5.0 / 6.0 * m.g * self.t,
            _ => 0.0,
        }
    }

    /// The section has no transverse shear flexibility of its own: a homogeneous PSHELL with
    /// MID3 blank (the element then takes 5/6 G₂t, [`Self::shear_modulus`]).
    pub fn shear_rigid(&self) -> bool {
        self.shear.is_none() && self.general.is_none()
    }

    /// Drilling penalty γ_d = drill_factor·G t (membrane G, else bending G; a general section:
    /// its invariant in-plane shear rigidity, module doc).
    pub fn drill(&self) -> f64 {
        if let Some(s) = &self.general {
            let a = &s.a;
            return self.drill_factor * (a[0][0] + a[1][1] - 2.0 * a[0][1] + 4.0 * a[2][2]) / 8.0;
        }
        let g = self
            .membrane
            .map(|m| m.g)
            .or(self.bending.map(|b| b.0.g))
            .unwrap_or(0.0);
        self.drill_factor * g * self.t
    }

    /// Translational mass per unit area ρt + nsm (a general section: Σ ρ_k t_k + nsm).
    pub fn mass_per_area(&self) -> f64 {
        match &self.general {
            Some(g) => g.mass + self.nsm,
            None => self.rho * self.t + self.nsm,
        }
    }

    /// Rotary inertia per unit area ρt³/12 (a general section: Σ ρ_k ∫ z² dz).
    pub fn rotary_per_area(&self) -> f64 {
        match &self.general {
            Some(g) => g.rotary,
            None => self.rho * self.t.powi(3) / 12.0,
        }
    }
}

fn positive_definite3(m: &M3) -> bool {
    let d2 = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let d3 = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    m[0][0] > 0.0 && d2 > 0.0 && d3 > 0.0 && d3.is_finite()
}

/// Angle ψ of the element's material x-axis from its local e₁ (module doc): THETA from the
/// G1→G2 side, or the projection of a vector onto the element plane (MCID).
pub fn material_angle(
    axis: &ShellMaterialAxis,
    axes: &[Xyz; 3],
    side12: [f64; 2],
) -> Result<f64, ElementError> {
    match axis {
        ShellMaterialAxis::FromSide12 { theta_deg } => {
            Ok(side12[1].atan2(side12[0]) + theta_deg.to_radians())
        }
        ShellMaterialAxis::AbaqusDefault => {
            let near_normal = axes[2][0].abs() > 0.1f64.to_radians().cos();
            let v = if near_normal {
                [0.0, 0.0, 1.0]
            } else {
                [1.0, 0.0, 0.0]
            };
            material_angle(&ShellMaterialAxis::Projected(v), axes, side12)
        }
        ShellMaterialAxis::Projected(v) => {
            let (x, y) = (dot(*v, axes[0]), dot(*v, axes[1]));
            if x.hypot(y) <= 1e-6 * norm(*v) {
                return Err(ElementError::BadConstants(format!(
                    "the material axis {v:?} (MCID x-axis) is normal to the element: its \
                     projection defines no direction"
                )));
            }
            Ok(y.atan2(x))
        }
    }
}

/// A plane stiffness (order xx, yy, xy; engineering shear) given in axes turned by ψ from the
/// element's, in the element's: Q̄ = T_εᵀ Q T_ε, T_ε the strain transformation with m = cos ψ,
/// n = sin ψ (Reddy (2004) eq. 2.3.17).
pub fn rotate_plane(q: &M3, psi: f64) -> M3 {
    let (n, m) = psi.sin_cos();
    let t = [
        [m * m, n * n, m * n],
        [n * n, m * m, -m * n],
        [-2.0 * m * n, 2.0 * m * n, m * m - n * n],
    ];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..3)
                .map(|k| t[k][i] * (0..3).map(|l| q[k][l] * t[l][j]).sum::<f64>())
                .sum()
        })
    })
}

/// Transverse shear stiffness on (γ13, γ23) in axes turned by ψ, in the element's (γxz, γyz):
/// Rᵀ A_s R, R = [m n; −n m].
pub fn rotate_shear(s: &M2, psi: f64) -> M2 {
    let (n, m) = psi.sin_cos();
    let r = [[m, n], [-n, m]];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..2)
                .map(|k| r[k][i] * (0..2).map(|l| s[k][l] * r[l][j]).sum::<f64>())
                .sum()
        })
    })
}

/// Isotropic plane-stress matrix c/(1−ν²)·[1 ν 0; ν 1 0; 0 0 (1−ν)/2].
pub fn plane_stress(c: f64, nu: f64) -> [[f64; 3]; 3] {
    let f = c / (1.0 - nu * nu);
    [
        [f, f * nu, 0.0],
        [f * nu, f, 0.0],
        [0.0, 0.0, f * (1.0 - nu) / 2.0],
    ]
}

/// Local frame of a flat shell element: rows e₁, e₂, e₃ (basic components), the centroid, the
/// in-plane coordinates of the nodes and their heights above the mean plane (warping).
#[derive(Debug, Clone, PartialEq)]
pub struct ShellFrame<const N: usize> {
    /// Rows: local axes in the basic frame.
    pub axes: [Xyz; 3],
    /// In-plane coordinates (x, y) of the projected nodes.
    pub p: [[f64; 2]; N],
    /// Distance of each node from the mean plane along e₃.
    pub h: [f64; N],
}

impl<const N: usize> ShellFrame<N> {
    /// Frame of a triangle (e₁ along 1→2) or a quadrilateral (e₃ along the cross product of
    /// the diagonals, e₁ along the mean of the edges 1→2 and 4→3 projected into the plane).
    pub fn new(x: &[Xyz; N]) -> Result<ShellFrame<N>, ElementError> {
        let (e1_raw, e3_raw) = if N == 3 {
            let a = sub(x[1], x[0]);
            (a, cross(a, sub(x[2], x[0])))
        } else {
            let d1 = sub(x[2], x[0]);
            let d2 = sub(x[3], x[1]);
            let a = sub(x[1], x[0]);
            let b = sub(x[2], x[3]);
            ([a[0] + b[0], a[1] + b[1], a[2] + b[2]], cross(d1, d2))
        };
        let n3 = norm(e3_raw);
        let size = (0..N)
            .map(|a| norm(sub(x[(a + 1) % N], x[a])))
            .fold(0.0, f64::max);
        if n3.is_nan() || n3 <= 1e-12 * size * size || size <= 0.0 {
            return Err(ElementError::BadConstants(
                "degenerate shell element (zero area or collinear nodes)".into(),
            ));
        }
        let e3 = scale(e3_raw, 1.0 / n3);
        let e1p = sub(e1_raw, scale(e3, dot(e1_raw, e3)));
        let n1 = norm(e1p);
        if n1 <= 1e-12 * size {
            return Err(ElementError::BadConstants(
                "degenerate shell element (no in-plane axis)".into(),
            ));
        }
        let e1 = scale(e1p, 1.0 / n1);
        let e2 = cross(e3, e1);
        let mut c = [0.0; 3];
        for xa in x {
            for i in 0..3 {
                c[i] += xa[i] / N as f64;
            }
        }
        let mut p = [[0.0; 2]; N];
        let mut h = [0.0; N];
        for a in 0..N {
            let d = sub(x[a], c);
            p[a] = [dot(d, e1), dot(d, e2)];
            h[a] = dot(d, e3);
        }
        Ok(ShellFrame {
            axes: [e1, e2, e3],
            p,
            h,
        })
    }
}

/// Adds a membrane with drilling rotations (3n×3n on [u v θz] per node, `drill_membrane`) into
/// the 6n×6n local stiffness `k` of an n-node flat shell.
pub fn add_drilling_membrane(k: &mut [f64], membrane: &[f64], n: usize) {
    let dofs: Vec<usize> = (0..n).flat_map(|a| [6 * a, 6 * a + 1, 6 * a + 5]).collect();
    let (nd, nm) = (6 * n, 3 * n);
    for (i, &di) in dofs.iter().enumerate() {
        for (j, &dj) in dofs.iter().enumerate() {
            k[di * nd + dj] += membrane[i * nm + j];
        }
    }
}

/// Rigid links from the real (warped) nodes to the flat element's projected nodes (Taylor's
/// warping correction, MacNeal, *Finite Elements: Their Design and Performance* (1994) §8.4):
/// u_flat = u + θ × (−h e₃), i.e. u_f = u − hθy, v_f = v + hθx. K ← Wᵀ K W, in place.
/// Rigid motions of the real nodes map to rigid motions of the flat element.
pub fn apply_warping(k: &mut [f64], h: &[f64]) {
    let n = h.len();
    let nd = 6 * n;
    if h.iter().all(|&v| v == 0.0) {
        return;
    }
    // K W: column u_a (6a) feeds θy_a (6a+4) with −h, column v_a (6a+1) feeds θx_a (6a+3) with +h.
    for a in 0..n {
        let ha = h[a];
        for r in 0..nd {
            let ku = k[r * nd + 6 * a];
            let kv = k[r * nd + 6 * a + 1];
            k[r * nd + 6 * a + 4] -= ha * ku;
            k[r * nd + 6 * a + 3] += ha * kv;
        }
    }
    // Wᵀ (K W): same on rows.
    for a in 0..n {
        let ha = h[a];
        for c in 0..nd {
            let ku = k[6 * a * nd + c];
            let kv = k[(6 * a + 1) * nd + c];
            k[(6 * a + 4) * nd + c] -= ha * ku;
            k[(6 * a + 3) * nd + c] += ha * kv;
        }
    }
}

/// Rotate a local node-major 6N×6N matrix to the basic frame: A = Tᵀ A_l T, T = diag(R, …),
/// R rows = local axes.
pub fn to_basic(a: &[f64], n: usize, r: &[Xyz; 3]) -> Vec<f64> {
    let nd = 6 * n;
    let nb = 2 * n;
    // at = A_l T (columns by 3-blocks): (A_l T)_{i,3b+j} = Σ_k A_{i,3b+k} R_kj
    let mut at = vec![0.0; nd * nd];
    for i in 0..nd {
        for b in 0..nb {
            for j in 0..3 {
                at[i * nd + 3 * b + j] = (0..3).map(|k| a[i * nd + 3 * b + k] * r[k][j]).sum();
            }
        }
    }
    let mut out = vec![0.0; nd * nd];
    for b in 0..nb {
        for i in 0..3 {
            for c in 0..nd {
                out[(3 * b + i) * nd + c] =
                    (0..3).map(|k| r[k][i] * at[(3 * b + k) * nd + c]).sum();
            }
        }
    }
    out
}

/// Relative rotary inertia of the drilling rotation: ρt³/12 · DRILL_INERTIA (module doc).
pub const DRILL_INERTIA: f64 = 1e-4;

/// 6N×6N basic-frame shell mass from the scalar area integrals s_ab = ∫ N_a N_b dA (module doc),
/// lumped as row sums when `lumped`; `normal` = e₃ of the element. Rotational block per node
/// pair: ρt³/12 · s_ab · (I − (1 − DRILL_INERTIA) e₃e₃ᵀ).
pub fn mass_matrix(
    s: &[f64],
    n: usize,
    props: &ShellProps,
    lumped: bool,
    normal: &Xyz,
) -> Vec<f64> {
    let nd = 6 * n;
    let mt = props.mass_per_area();
    let mr = if lumped && !props.lumped_rotary {
        0.0
    } else {
        props.rotary_per_area()
    };
    let rot: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let d = if i == j { 1.0 } else { 0.0 };
            mr * (d - (1.0 - DRILL_INERTIA) * normal[i] * normal[j])
        })
    });
    let mut m = vec![0.0; nd * nd];
    let mut put = |a: usize, b: usize, v: f64| {
        for i in 0..3 {
            m[(6 * a + i) * nd + 6 * b + i] += mt * v;
            for j in 0..3 {
                m[(6 * a + 3 + i) * nd + 6 * b + 3 + j] += rot[i][j] * v;
            }
        }
    };
    for a in 0..n {
        if lumped {
            put(a, a, s[a * n..(a + 1) * n].iter().sum());
        } else {
            for b in 0..n {
                put(a, b, s[a * n + b]);
            }
        }
    }
    m
}

/// Add `c · bᵀ D b` to the local matrix `k` (6N wide), where b (3 × nb) acts on the local dofs
/// listed in `dofs`.
pub fn add_btdb(
    k: &mut [f64],
    nd: usize,
    b: &[Vec<f64>; 3],
    dofs: &[usize],
    d: &[[f64; 3]; 3],
    c: f64,
) {
    let nb = dofs.len();
    let mut db = [vec![0.0; nb], vec![0.0; nb], vec![0.0; nb]];
    for i in 0..3 {
        for j in 0..nb {
            db[i][j] = (0..3).map(|l| d[i][l] * b[l][j]).sum();
        }
    }
    for p in 0..nb {
        for q in 0..nb {
            let v: f64 = (0..3).map(|i| b[i][p] * db[i][q]).sum();
            k[dofs[p] * nd + dofs[q]] += c * v;
        }
    }
}

/// Add `c · (b₁ᵀ C b₂ + b₂ᵀ Cᵀ b₁)`: the symmetric coupling of strain rows b₁ on `dofs1` and b₂
/// on `dofs2` through C (3×3), e.g. membrane strains and curvatures through B.
pub fn add_coupling(
    k: &mut [f64],
    nd: usize,
    (b1, dofs1): (&[Vec<f64>; 3], &[usize]),
    (b2, dofs2): (&[Vec<f64>; 3], &[usize]),
    c3: &M3,
    c: f64,
) {
    for (p, &dp) in dofs1.iter().enumerate() {
        for (q, &dq) in dofs2.iter().enumerate() {
            let v: f64 = (0..3)
                .map(|i| b1[i][p] * (0..3).map(|j| c3[i][j] * b2[j][q]).sum::<f64>())
                .sum();
            k[dp * nd + dq] += c * v;
            k[dq * nd + dp] += c * v;
        }
    }
}

/// Add `c/div · Σ_rs S_rs g_r g_sᵀ` for the two transverse shear rows (γxz, γyz) on `dofs`
/// (the diagonal terms as S_rr·c/div, the rounding of the isotropic elements' D_s·c/div).
pub fn add_shear(
    k: &mut [f64],
    nd: usize,
    g: [&[f64]; 2],
    dofs: &[usize],
    s: &M2,
    (c, div): (f64, f64),
) {
    for r in 0..2 {
        add_outer(k, nd, g[r], dofs, s[r][r] * c / div);
    }
    let off = 0.5 * (s[0][1] + s[1][0]) * c / div;
    if off != 0.0 {
        for (p, &dp) in dofs.iter().enumerate() {
            for (q, &dq) in dofs.iter().enumerate() {
                k[dp * nd + dq] += off * (g[0][p] * g[1][q] + g[1][p] * g[0][q]);
            }
        }
    }
}

/// Add `c · g gᵀ` for a row vector g on `dofs`.
pub fn add_outer(k: &mut [f64], nd: usize, g: &[f64], dofs: &[usize], c: f64) {
    for (p, &dp) in dofs.iter().enumerate() {
        for (q, &dq) in dofs.iter().enumerate() {
            k[dp * nd + dq] += c * g[p] * g[q];
        }
    }
}

#[cfg(test)]
pub(crate) mod test_util {
    use super::*;

    /// Rigid motion u = a + θ × x, rotations θ, at nodes x (6 dofs per node).
    pub fn rigid(x: &[Xyz], mode: usize) -> Vec<f64> {
        let mut u = vec![0.0; 6 * x.len()];
        for (n, xn) in x.iter().enumerate() {
            let (mut t, mut th) = ([0.0; 3], [0.0; 3]);
            if mode < 3 {
                t[mode] = 1.0;
            } else {
                th[mode - 3] = 1.0;
                t = cross(th, *xn);
            }
            u[6 * n..6 * n + 3].copy_from_slice(&t);
            u[6 * n + 3..6 * n + 6].copy_from_slice(&th);
        }
        u
    }

    /// uᵀ K v.
    pub fn form(k: &[f64], u: &[f64], v: &[f64]) -> f64 {
        let n = u.len();
        (0..n)
            .map(|i| u[i] * (0..n).map(|j| k[i * n + j] * v[j]).sum::<f64>())
            .sum()
    }

    /// max |K u| relative to max |K|.
    pub fn residual(k: &[f64], u: &[f64]) -> f64 {
        let n = u.len();
        let kmax = k.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        (0..n)
            .map(|i| (0..n).map(|j| k[i * n + j] * u[j]).sum::<f64>().abs())
            .fold(0.0, f64::max)
            / kmax
    }

    /// Local-frame field on a flat element in the z = 0 plane (basic = local): membrane strain
    /// (ex, ey, gxy) with θz = ω, and constant curvature (kx, ky, kxy) from w = ½(kx x² + ky y²
    /// + kxy xy), θx = w,y, θy = −w,x.
    pub fn constant_field(x: &[Xyz], eps: [f64; 3], kap: [f64; 3]) -> Vec<f64> {
        let mut u = vec![0.0; 6 * x.len()];
        for (a, p) in x.iter().enumerate() {
            let (px, py) = (p[0], p[1]);
            // u = ex x + ½gxy y, v = ½gxy x + ey y: ω = ½(v,x − u,y) = 0
            u[6 * a] = eps[0] * px + 0.5 * eps[2] * py;
            u[6 * a + 1] = 0.5 * eps[2] * px + eps[1] * py;
            // κ = (βx,x, βy,y, βx,y + βy,x) with β = −∇w: w = −½(kx x² + ky y² + kxy xy)
            let w = -0.5 * (kap[0] * px * px + kap[1] * py * py + kap[2] * px * py);
            let wx = -(kap[0] * px + 0.5 * kap[2] * py);
            let wy = -(kap[1] * py + 0.5 * kap[2] * px);
            u[6 * a + 2] = w;
            u[6 * a + 3] = wy;
            u[6 * a + 4] = -wx;
        }
        u
    }

    /// Patch test of a flat element in the z = 0 plane: constant membrane strain and curvature
    /// fields have energy A(εᵀD_mε + κᵀD_bκ) to `tol` (relative).
    pub fn patch_energy(k: &[f64], x: &[Xyz], a: f64, props: &ShellProps, tol: f64) {
        let (dm, db) = (props.d_membrane(), props.d_bending());
        let q = |d: &[[f64; 3]; 3], e: [f64; 3]| -> f64 {
            (0..3)
                .map(|i| (0..3).map(|j| e[i] * d[i][j] * e[j]).sum::<f64>())
                .sum()
        };
        for (eps, kap) in [
            ([1e-3, 0.0, 0.0], [0.0; 3]),
            ([0.0, -2e-3, 0.0], [0.0; 3]),
            ([0.0, 0.0, 3e-3], [0.0; 3]),
            ([0.0; 3], [0.5, 0.0, 0.0]),
            ([0.0; 3], [0.0, 0.3, 0.0]),
            ([0.0; 3], [0.0, 0.0, 0.7]),
            ([1e-3, 2e-3, -1e-3], [0.2, -0.4, 0.1]),
        ] {
            let u = constant_field(x, eps, kap);
            let want = a * (q(&dm, eps) + q(&db, kap));
            let got = form(k, &u, &u);
            assert!(
                (got - want).abs() < tol * want,
                "{eps:?} {kap:?}: {got} vs {want}"
            );
        }
    }

    /// A laminate-like section with full A, B, D (the 6×6 [A B; B D] positive definite) and
    /// anisotropic transverse shear, its material x-axis `axis`.
    pub fn coupled_section(t: f64, axis: ShellMaterialAxis) -> ShellProps {
        let e = 1e11 * t;
        let a = [
            [e, 0.3 * e, 0.1 * e],
            [0.3 * e, 0.5 * e, -0.05 * e],
            [0.1 * e, -0.05 * e, 0.25 * e],
        ];
        let b = a.map(|r| r.map(|v| 0.05 * t * v));
        let d = [[0.9, 0.2, 0.05], [0.2, 0.6, 0.03], [0.05, 0.03, 0.3]]
            .map(|r| r.map(|v| v * e * t * t / 12.0));
        ShellProps {
            general: Some(GeneralSection {
                a,
                b,
                d,
                shear: [[0.4 * e, 0.05 * e], [0.05 * e, 0.3 * e]],
                mass: 1600.0 * t,
                rotary: 1600.0 * t.powi(3) / 12.0,
                axis,
            }),
            ..ShellProps::isotropic(t, Isotropic::new(1e11, 0.3, 1600.0))
        }
    }

    /// Patch test of a general section on a flat element in the z = 0 plane (normal +z): constant
    /// membrane strain and curvature (basic axes) have energy A(εᵀĀε + 2εᵀB̄κ + κᵀD̄κ), Ā, B̄, D̄
    /// the section turned by its material angle `psi` from basic x.
    pub fn patch_energy_general(
        k: &[f64],
        x: &[Xyz],
        a: f64,
        props: &ShellProps,
        psi: f64,
        tol: f64,
    ) {
        let g = props.general.expect("a general section");
        let (am, bm, dm) = (
            rotate_plane(&g.a, psi),
            rotate_plane(&g.b, psi),
            rotate_plane(&g.d, psi),
        );
        let q = |d: &M3, e: [f64; 3], f: [f64; 3]| -> f64 {
            (0..3)
                .map(|i| (0..3).map(|j| e[i] * d[i][j] * f[j]).sum::<f64>())
                .sum()
        };
        for (eps, kap) in [
            ([1e-3, 0.0, 0.0], [0.0; 3]),
            ([0.0, 0.0, 3e-3], [0.0; 3]),
            ([0.0; 3], [0.5, 0.0, 0.0]),
            ([0.0; 3], [0.0, 0.0, 0.7]),
            ([1e-3, 2e-3, -1e-3], [0.2, -0.4, 0.1]),
            ([-2e-3, 1e-3, 1e-3], [-0.3, 0.1, 0.6]),
        ] {
            let u = constant_field(x, eps, kap);
            let want = a * (q(&am, eps, eps) + 2.0 * q(&bm, eps, kap) + q(&dm, kap, kap));
            let got = form(k, &u, &u);
            assert!(
                (got - want).abs() < tol * want.abs(),
                "{eps:?} {kap:?}: {got} vs {want}"
            );
        }
    }
}
