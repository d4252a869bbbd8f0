//! Linear solids enriched with incompatible (bubble) displacement modes, condensed statically:
//! the 8-node hexahedron with Wilson's modes 1 − ξ², 1 − η², 1 − ζ² per displacement component
//! (9 internal dofs) and the 6-node wedge with 1 − ζ² (3 internal dofs), both with Taylor's
//! correction (mode gradients through J₀ at the element centre, scaled by det J₀/det J), so that
//! they pass the patch test on distorted elements (Wilson, Taylor, Doherty & Ghaboussi, in
//! *Numerical and Computer Methods in Structural Mechanics* (1973) 43; Taylor, Beresford &
//! Wilson, *IJNME* 10 (1976) 1211). This is the formulation of Abaqus C3D8I and what MSC
//! Nastran's CHEXA/CPENTA without mid-side nodes use by default (PSOLID ISOP blank: "reduced
//! shear integration with bubble functions"): free of the shear locking of the fully
//! integrated element in bending.
//!
//! K = K_cc − K_ci K_ii⁻¹ K_ic, each block ∫ Bᵀ D B dV over the element's full rule; the mass is
//! the compatible element's (massless modes: the condensation is exact in the eigenproblem too).
//! CalculiX 2.20's C3D8I gives its modes mass: [`hex8_ccx_matrices`] returns the uncondensed
//! element, whose mode dofs the assembly keeps as interior dofs (`fe::dofs::DofMap::interior`).

pub use super::element::ModePoint;
use super::element::{
    first, integration_points, nodal_gradients, AssemblySpec, Element, ElementInput,
    ElementMatrices, MatricesError, NodalGradients, SolidRules,
};
use super::{
    check_solid_material, dense, hex8, map_point, prism6, ElementError, Isotropic, ShapeFn, Xyz,
};
use crate::fe::mass::MassKind;
use crate::fe::quadrature::{self, QuadPoint};
use crate::model::geometry::{det3, inverse3};
use crate::model::{ElementKind, Model};

/// Reference gradients of the incompatible modes at ξ.
type ModeGradients = fn(&Xyz) -> Vec<Xyz>;

fn hex_modes(p: &Xyz) -> Vec<Xyz> {
    vec![
        [-2.0 * p[0], 0.0, 0.0],
        [0.0, -2.0 * p[1], 0.0],
        [0.0, 0.0, -2.0 * p[2]],
    ]
}

fn wedge_modes(p: &Xyz) -> Vec<Xyz> {
    vec![[0.0, 0.0, -2.0 * p[2]]]
}

/// Stiffness of the 8-node hexahedron with incompatible modes (24×24, 2×2×2 Gauss).
pub fn hex8_stiffness(x: &[Xyz; 8], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    check_solid_material(mat)?;
    condense(&full_stiffness(&hex8_points(x)?, mat), 24, 9)
}

/// Stiffness of the 6-node wedge with the incompatible mode 1 − ζ² (18×18, 3×2 points).
pub fn prism6_stiffness(x: &[Xyz; 6], mat: &Isotropic) -> Result<Vec<f64>, ElementError> {
    check_solid_material(mat)?;
    condense(&full_stiffness(&prism6_points(x)?, mat), 18, 3)
}

/// Interior dofs of ccx 2.20's C3D8I: the three incompatible modes × xyz, mode-major
/// (`[a1x a1y a1z a2x …]`, basic frame), after the 24 nodal dofs.
pub const HEX8_CCX_MODE_DOFS: usize = 9;

/// CalculiX 2.20's C3D8I (its shape8hu, shape8humass, e_c3d), stiffness and consistent mass
/// over the 24 nodal dofs followed by the [`HEX8_CCX_MODE_DOFS`] mode dofs (33×33 each, the
/// uncondensed element ccx solves with): Wilson's modes with gradients through J₀⁻¹ (no
/// det J₀/det J factor), 2×2×2 Gauss, and — unlike Abaqus and ccx 2.11 — mass on the modes:
/// ρ∫[N, P]ᵀ[N, P] dV over the 8 nodal functions and P = 1 − ξ², 1 − η², 1 − ζ². ccx keeps the
/// mode dofs as three extra nodes per element; the assembly keeps them as interior dofs.
pub fn hex8_ccx_matrices(
    x: &[Xyz; 8],
    mat: &Isotropic,
) -> Result<(Vec<f64>, Vec<f64>), ElementError> {
    check_solid_material(mat)?;
    let rule = quadrature::cube(2);
    let (_, _, _) = map_point(x, hex8::shape, &[0.0; 3], 0)?;
    let inv0 = jacobian_inverse(x, hex8::shape, &[0.0; 3]);
    let nt = 24 + HEX8_CCX_MODE_DOFS;
    let mut points = Vec::with_capacity(rule.len());
    // scalar mass over the 8 nodal functions and the 3 modes (11×11)
    let mut ms = [[0.0; 11]; 11];
    for (p, q) in rule.iter().enumerate() {
        let (n, g, det) = map_point(x, hex8::shape, &q.xi, p)?;
        let mut grads: Vec<Xyz> = g.to_vec();
        for m in hex_modes(&q.xi) {
            grads.push(std::array::from_fn(|i| {
                (0..3).map(|c| inv0[i][c] * m[c]).sum::<f64>()
            }));
        }
        let w = q.w * det;
        let vals: Vec<f64> = n
            .iter()
            .copied()
            .chain(q.xi.iter().map(|c| 1.0 - c * c))
            .collect();
        for a in 0..11 {
            for b in 0..11 {
                ms[a][b] += mat.rho * vals[a] * vals[b] * w;
            }
        }
        points.push(ModePoint {
            w,
            n: n.to_vec(),
            grads,
        });
    }
    let k = full_stiffness(&points, mat);
    // the mode block must be regular (a degenerate element otherwise)
    solve_modes(&k, 24, HEX8_CCX_MODE_DOFS, vec![0.0; HEX8_CCX_MODE_DOFS], 1)?;
    // M = m ⊗ I₃ over the 11 functions (dofs: 8 nodes × xyz, then 3 modes × xyz)
    let m = (0..nt * nt)
        .map(|ij| {
            let (i, j) = (ij / nt, ij % nt);
            if i % 3 == j % 3 {
                ms[i / 3][j / 3]
            } else {
                0.0
            }
        })
        .collect();
    Ok((k, m))
}

/// Physical gradients of ccx 2.20's C3D8I modes 1 − ξ², 1 − η², 1 − ζ² at ξ, as
/// [`hex8_ccx_matrices`] forms them: J₀⁻¹ ∂P/∂ξ (J₀ at the centre).
pub fn hex8_ccx_mode_gradients(x: &[Xyz; 8], xi: &Xyz) -> Result<[Xyz; 3], ElementError> {
    map_point(x, hex8::shape, &[0.0; 3], 0)?;
    let inv0 = jacobian_inverse(x, hex8::shape, &[0.0; 3]);
    let modes = hex_modes(xi);
    Ok(std::array::from_fn(|m| {
        std::array::from_fn(|i| (0..3).map(|c| inv0[i][c] * modes[m][c]).sum::<f64>())
    }))
}

/// Strain rows (6 × 3n: εxx εyy εzz γxy γyz γzx) of gradients g.
pub(crate) fn strain_rows(g: &[Xyz]) -> Vec<[f64; 6]> {
    let mut b = vec![[0.0; 6]; 3 * g.len()];
    for (a, gr) in g.iter().enumerate() {
        b[3 * a][0] = gr[0];
        b[3 * a + 1][1] = gr[1];
        b[3 * a + 2][2] = gr[2];
        b[3 * a][3] = gr[1];
        b[3 * a + 1][3] = gr[0];
        b[3 * a + 1][4] = gr[2];
        b[3 * a + 2][4] = gr[1];
        b[3 * a][5] = gr[2];
        b[3 * a + 2][5] = gr[0];
    }
    b
}

/// The integration points of an N-node element with the incompatible modes `modes` (centre
/// `centre`): nodal gradients, then the modes' ∂P/∂x = det J₀/det J · J₀⁻¹ ∂P/∂ξ (Taylor).
pub(crate) fn mode_points<const N: usize>(
    x: &[Xyz; N],
    shape: ShapeFn<N>,
    rule: &[QuadPoint],
    centre: Xyz,
    modes: ModeGradients,
) -> Result<Vec<ModePoint>, ElementError> {
    let (_, _, det0) = map_point(x, shape, &centre, 0)?;
    let inv0 = jacobian_inverse(x, shape, &centre);
    let mut out = Vec::with_capacity(rule.len());
    for (p, q) in rule.iter().enumerate() {
        let (n, g, det) = map_point(x, shape, &q.xi, p)?;
        let mut grads: Vec<Xyz> = g.to_vec();
        for m in modes(&q.xi) {
            grads.push(std::array::from_fn(|i| {
                det0 / det * (0..3).map(|c| inv0[i][c] * m[c]).sum::<f64>()
            }));
        }
        out.push(ModePoint {
            w: q.w * det,
            n: n.to_vec(),
            grads,
        });
    }
    Ok(out)
}

/// Integration points of the 8-node hexahedron with Wilson's three modes (2×2×2 Gauss).
pub(crate) fn hex8_points(x: &[Xyz; 8]) -> Result<Vec<ModePoint>, ElementError> {
    mode_points(x, hex8::shape, &quadrature::cube(2), [0.0; 3], hex_modes)
}

/// Integration points of the 6-node wedge with the mode 1 − ζ² (3×2 points).
pub(crate) fn prism6_points(x: &[Xyz; 6]) -> Result<Vec<ModePoint>, ElementError> {
    mode_points(
        x,
        prism6::shape,
        &quadrature::wedge(2),
        [1.0 / 3.0, 1.0 / 3.0, 0.0],
        wedge_modes,
    )
}

/// The uncondensed stiffness ∫ Bᵀ D B dV over nodal and mode dofs ((3N + 3m)², row-major; the
/// nodal dofs first), module formula.
pub(crate) fn full_stiffness(points: &[ModePoint], mat: &Isotropic) -> Vec<f64> {
    let (lam, mu) = mat.lame();
    let d = crate::model::elasticity::isotropic(lam, mu);
    full_stiffness_d(points, &|_| d)
}

/// ∫ Bᵀ D B dV with D given per integration point (`d(p)`; [`crate::model::elasticity`]
/// convention), over all the gradients of the points (Zienkiewicz & Taylor Vol. 1 §6.2).
pub(crate) fn full_stiffness_d(
    points: &[ModePoint],
    d: &dyn Fn(usize) -> crate::model::Stiffness6,
) -> Vec<f64> {
    let nt = 3 * points.first().map_or(0, |p| p.grads.len());
    let mut k = vec![0.0; nt * nt];
    for (p, pt) in points.iter().enumerate() {
        let d = d(p);
        let b = strain_rows(&pt.grads);
        let db: Vec<[f64; 6]> = b
            .iter()
            .map(|bj| std::array::from_fn(|r| (0..6).map(|c| d[r][c] * bj[c]).sum()))
            .collect();
        for i in 0..nt {
            for j in i..nt {
                let v: f64 = (0..6).map(|r| b[i][r] * db[j][r]).sum();
                k[i * nt + j] += pt.w * v;
            }
        }
    }
    for i in 0..nt {
        for j in 0..i {
            k[i * nt + j] = k[j * nt + i];
        }
    }
    k
}

/// ∂ξ/∂x (J⁻¹, J_ki = ∂x_i/∂ξ_k) at a reference point, as rows i: ∂N/∂x_i = Σ_k inv[i][k] ∂N/∂ξ_k.
fn jacobian_inverse<const N: usize>(x: &[Xyz; N], shape: ShapeFn<N>, xi: &Xyz) -> [[f64; 3]; 3] {
    let (_, dn) = shape(xi);
    let mut j = [[0.0; 3]; 3];
    for a in 0..N {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += dn[a][r] * x[a][c];
            }
        }
    }
    inverse3(&j, det3(&j))
}

/// Solve K_ii X = B for the mode block K_ii of `k` ((nc + ni)², row-major) and `cols`
/// right-hand sides B (ni × cols, row-major).
pub(crate) fn solve_modes(
    k: &[f64],
    nc: usize,
    ni: usize,
    mut b: Vec<f64>,
    cols: usize,
) -> Result<Vec<f64>, ElementError> {
    let nt = nc + ni;
    let mut a: Vec<f64> = (0..ni)
        .flat_map(|i| (0..ni).map(move |j| (i, j)))
        .map(|(i, j)| k[(nc + i) * nt + nc + j])
        .collect();
    dense::solve_dense(&mut a, ni, &mut b, cols).ok_or_else(|| {
        ElementError::BadConstants("singular incompatible-mode matrix (degenerate element)".into())
    })?;
    Ok(b)
}

/// Static condensation of the `ni` mode dofs after the `nc` nodal ones.
pub(crate) fn condense(k: &[f64], nc: usize, ni: usize) -> Result<Vec<f64>, ElementError> {
    dense::condense(k, nc, ni, "incompatible-mode matrix")
}

/// Does element `e` keep interior dofs in the system — ccx 2.20's C3D8I (CalculiX deck, linear
/// hexahedra with incompatible modes, isotropic material) under consistent mass, whose nine
/// mode amplitudes carry mass and stay unknowns as ccx keeps them? Under lumped mass the modes
/// are massless and condensed exactly (ccx's `*FREQUENCY` always uses its consistent mass).
pub fn keeps_ccx_modes(model: &Model, e: usize, spec: &AssemblySpec) -> bool {
    let el = &model.elements[e];
    el.kind == ElementKind::Hex8
        && model.params.solid_bubbles
        && model.params.ccx_solid_rules
        && spec.mass == MassKind::Consistent
        && el
            .property
            .and_then(|p| model.properties.get(p))
            .and_then(|p| model.materials.get(p.material))
            .is_some_and(|m| m.stiffness().is_none() && m.plane_stress().is_none())
}

/// The 8-node hexahedron as an [`Element`]: formed here because its incompatible-mode forms
/// are (`hex8.rs` holds the compatible kernel).
pub struct Hex8Element;

impl Element for Hex8Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<8>();
        // CalculiX 2.20's C3D8I (modes with mass, kept as interior dofs) in a consistent build
        if input.general.is_none() && keeps_ccx_modes(input.model, input.index, input.spec) {
            let (k, m) = hex8_ccx_matrices(&x, &input.iso)?;
            return Ok(ElementMatrices {
                dpn: 3,
                interior: HEX8_CCX_MODE_DOFS,
                k,
                m,
            });
        }
        let k = input.stiffness(|| {
            if input.model.params.solid_bubbles {
                hex8_stiffness(&x, &input.iso)
            } else {
                hex8::stiffness(&x, &input.iso)
            }
        })?;
        let ms = hex8::scalar_mass(&x, input.iso.rho)?;
        Ok(input.solid(k, ms, 8, false))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        rules: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(Some(if rules.incompatible {
            hex8_points(&first(x))?
        } else {
            integration_points(x, hex8::shape, &quadrature::cube(2))?
        }))
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        let grads = nodal_gradients(&first(x), hex8::shape, &hex8::NODES, [0.0; 3])?;
        Ok(Some(grads))
    }
}

/// The 6-node wedge as an [`Element`]: formed here because its incompatible-mode form is
/// (`prism6.rs` holds the compatible kernels).
pub struct Prism6Element;

impl Element for Prism6Element {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        let x = input.coords::<6>();
        let (iso, params) = (&input.iso, &input.model.params);
        let (k, ms) = if params.solid_bubbles {
            (
                input.stiffness(|| prism6_stiffness(&x, iso)),
                prism6::scalar_mass(&x, iso.rho),
            )
        } else if params.ccx_solid_rules {
            (
                input.stiffness(|| prism6::stiffness_ccx(&x, iso)),
                prism6::scalar_mass_ccx(&x, iso.rho),
            )
        } else {
            (
                input.stiffness(|| prism6::stiffness(&x, iso)),
                prism6::scalar_mass(&x, iso.rho),
            )
        };
        Ok(input.solid(k?, ms?, 6, false))
    }

    fn stiffness_points(
        &self,
        x: &[Xyz],
        rules: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(Some(if rules.incompatible {
            prism6_points(&first(x))?
        } else if rules.ccx {
            integration_points(x, prism6::shape, &quadrature::wedge_centroid())?
        } else {
            integration_points(x, prism6::shape, &quadrature::wedge(2))?
        }))
    }

    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        const THIRD: f64 = 1.0 / 3.0;
        let centroid = [THIRD, THIRD, 0.0];
        let grads = nodal_gradients(&first(x), prism6::shape, &prism6::NODES, centroid)?;
        Ok(Some(grads))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Isotropic {
        Isotropic::new(210e9, 0.3, 7850.0)
    }

    const HEX: [Xyz; 8] = [
        [0.0, 0.0, 0.0],
        [2.1, 0.2, 0.1],
        [2.3, 1.8, -0.1],
        [-0.1, 1.5, 0.2],
        [0.1, -0.2, 1.3],
        [2.0, 0.1, 1.1],
        [2.2, 1.9, 1.4],
        [0.2, 1.6, 1.2],
    ];

    fn energy(k: &[f64], u: &[f64]) -> f64 {
        let n = u.len();
        (0..n)
            .map(|i| u[i] * (0..n).map(|j| k[i * n + j] * u[j]).sum::<f64>())
            .sum()
    }

    /// Patch test on a distorted hexahedron: a linear displacement field u = G x (constant
    /// strain) costs exactly V εᵀDε (the modes stay silent), and rigid motions cost nothing.
    #[test]
    fn incompatible_hex8_passes_patch_test_on_distorted_element() {
        let mat = steel();
        let k = hex8_stiffness(&HEX, &mat).unwrap();
        let v = super::super::solid_volume(&HEX, super::hex8::shape, &quadrature::cube(2)).unwrap();
        let full = super::super::hex8::stiffness(&HEX, &mat).unwrap();
        let grad = [[1e-3, 2e-4, -3e-4], [5e-4, -2e-3, 1e-4], [0.0, 7e-4, 4e-4]];
        let u: Vec<f64> = HEX
            .iter()
            .flat_map(|x| (0..3).map(move |i| (0..3).map(|j| grad[i][j] * x[j]).sum::<f64>()))
            .collect();
        // the compatible element is exact for linear fields: the reference energy
        let want = energy(&full, &u);
        assert!((energy(&k, &u) - want).abs() < 1e-9 * want);
        assert!(want > 0.0 && v > 0.0);
        // rigid rotation about z
        let r: Vec<f64> = HEX.iter().flat_map(|x| [-x[1], x[0], 0.0]).collect();
        let kmax = k.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for i in 0..24 {
            let f: f64 = (0..24).map(|j| k[i * 24 + j] * r[j]).sum();
            assert!(f.abs() < 1e-9 * kmax, "{f}");
        }
    }

    /// Pure bending of a slender cube stack: a single element under the exact pure-bending
    /// field u = κxz, w = −κx²/2 (ν = 0) gives the beam energy ½ EI κ² L — the full-integration
    /// element is far stiffer (shear locking).
    #[test]
    fn incompatible_hex8_is_exact_in_pure_bending() {
        let mat = Isotropic::new(1000.0, 0.0, 1.0);
        let (l, h, b) = (4.0, 1.0, 1.0);
        let x: [Xyz; 8] = std::array::from_fn(|a| {
            let r = super::super::hex8::NODES[a];
            [0.5 * l * (1.0 + r[0]), 0.5 * b * r[1], 0.5 * h * r[2]]
        });
        let kap = 0.01;
        let u: Vec<f64> = x
            .iter()
            .flat_map(|p| [kap * p[0] * p[2], 0.0, -0.5 * kap * p[0] * p[0]])
            .collect();
        let want = mat.e * b * h.powi(3) / 12.0 * kap * kap * l;
        let got = energy(&hex8_stiffness(&x, &mat).unwrap(), &u);
        assert!((got - want).abs() < 1e-9 * want, "{got} vs {want}");
        let locked = energy(&super::super::hex8::stiffness(&x, &mat).unwrap(), &u);
        assert!(locked > 1.5 * want, "{locked} vs {want}");
    }

    /// ccx 2.20's C3D8I: on a brick (J = J₀ everywhere) its stiffness condensed is the
    /// Taylor-corrected one; a rigid translation (zero mode amplitudes) carries ρV, and each
    /// mode carries ρV·4/9 per component ((1 − ξ²)² = 4/9 at the 2 × 2 × 2 Gauss points).
    #[test]
    fn ccx_c3d8i_on_a_brick() {
        let x: [Xyz; 8] = std::array::from_fn(|a| {
            let c = crate::fe::elements::hex8::NODES[a];
            [0.3 * c[0], 0.1 * c[1], 0.2 * c[2]]
        });
        let (k, m) = hex8_ccx_matrices(&x, &steel()).unwrap();
        let nt = 24 + HEX8_CCX_MODE_DOFS;
        assert_eq!((k.len(), m.len()), (nt * nt, nt * nt));
        let condensed = condense(&k, 24, HEX8_CCX_MODE_DOFS).unwrap();
        let taylor = hex8_stiffness(&x, &steel()).unwrap();
        let scale = taylor.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        assert!(condensed
            .iter()
            .zip(&taylor)
            .all(|(a, b)| (a - b).abs() <= 1e-12 * scale));
        let rho_v = 7850.0 * 0.6 * 0.2 * 0.4;
        for dir in 0..3 {
            let r: Vec<f64> = (0..nt)
                .map(|i| f64::from(u8::from(i < 24 && i % 3 == dir)))
                .collect();
            let mass: f64 = (0..nt * nt).map(|ij| r[ij / nt] * m[ij] * r[ij % nt]).sum();
            assert!((mass - rho_v).abs() <= 1e-12 * mass, "{mass}");
            let mode = 24 + dir;
            assert!((m[mode * nt + mode] - rho_v * 4.0 / 9.0).abs() <= 1e-12 * rho_v);
        }
    }
}
