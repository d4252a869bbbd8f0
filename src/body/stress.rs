//! Modal stress and strain shapes of solid elements: for each mode, the strain at every element
//! node from the shape-function gradients, Hooke's law for the stress, and the average over the
//! elements that share a node (the "corner" recovery of Nastran's MNF and RecurDyn's RFI
//! export).
//!
//! Values are in the basic (body) frame, Voigt order **xx yy zz xy yz zx**, per unit modal
//! coordinate; strain shear components are engineering strains γ = 2ε (format spec §5.8).
//! Only solid elements carry fields; a node touched by no solid element gets none. Nodal
//! averaging mixes the values of elements of different materials at a shared node, as every
//! corner-averaging post-processor does; the jump is not resolved.
//!
//! ccx 2.20's C3D8I, whose incompatible-mode amplitudes are dofs of the system
//! (`fe::DofMap::interior`), adds its modes' strain: Σ_m ∇P_m(ξ_a) ⊗ α_m at each corner, so a
//! bending field has no parasitic shear there (the amplitudes cancel it). Other hexahedra with
//! bubble modes (condensed) are recovered from the nodes alone.

use crate::fe::elements::element::NodalGradients;
use crate::fe::elements::{self, hex8, ElementError, Xyz};
use crate::model::elasticity::rotate;
use crate::model::{ElementKind, Model, NodeIndex, Stiffness6};

/// Which field shapes to recover.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FieldRequest {
    /// Stress shapes (force/length²).
    pub stress: bool,
    /// Strain shapes (engineering shear).
    pub strain: bool,
}

impl FieldRequest {
    /// Nothing asked for.
    pub fn is_empty(self) -> bool {
        !(self.stress || self.strain)
    }
}

/// Nodal field shapes, mode-major `values[(j*K + q)*6 + c]` over the K listed nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalFields {
    /// Nodes that carry values, ascending (those of the wanted nodes that a solid touches).
    pub nodes: Vec<NodeIndex>,
    /// Stress shapes, when asked for.
    pub stress: Option<Vec<f64>>,
    /// Strain shapes, when asked for.
    pub strain: Option<Vec<f64>>,
    /// Element corners whose Jacobian is not positive (strongly distorted elements): the value
    /// used there is the element's centroid value.
    pub centroid_fallbacks: usize,
}

/// Why fields could not be recovered.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StressError {
    /// An element cannot be evaluated at all (no valid material, degenerate at its centroid).
    #[error("{file}: element {id} ({kind:?}): {message}")]
    Element {
        /// Model file.
        file: String,
        /// External element id.
        id: u64,
        /// Element kind.
        kind: ElementKind,
        /// What is wrong.
        message: String,
    },
}

fn coords<const N: usize>(model: &Model, nodes: &[NodeIndex]) -> [Xyz; N] {
    std::array::from_fn(|i| model.nodes[nodes[i]].x)
}

/// Gradients at the nodes of a solid element, or `None` for kinds whose fields are not
/// recovered (the element's own answer, `Element::nodal_gradients`).
fn element_gradients(
    model: &Model,
    nodes: &[NodeIndex],
    kind: ElementKind,
) -> Result<Option<NodalGradients>, ElementError> {
    let x: Vec<Xyz> = nodes.iter().map(|&n| model.nodes[n].x).collect();
    elements::kinds::element(kind).nodal_gradients(&x)
}

/// Small-strain tensor in Voigt form with engineering shears:
/// ε_ij = ½ Σ_b (∂_j N_b u_bi + ∂_i N_b u_bj), γ_ij = 2 ε_ij.
fn strain(gradients: &[Xyz], u: &[[f64; 3]]) -> [f64; 6] {
    let mut h = [[0.0; 3]; 3]; // displacement gradient h_ij = ∂u_i/∂x_j
    for (g, ub) in gradients.iter().zip(u) {
        for i in 0..3 {
            for j in 0..3 {
                h[i][j] += ub[i] * g[j];
            }
        }
    }
    [
        h[0][0],
        h[1][1],
        h[2][2],
        h[0][1] + h[1][0],
        h[1][2] + h[2][1],
        h[2][0] + h[0][2],
    ]
}

/// Hooke's law σ = D ε in Voigt form (`[xx yy zz xy yz zx]`, engineering shears;
/// [`crate::model::elasticity`]).
fn hooke(d: &Stiffness6, e: &[f64; 6]) -> [f64; 6] {
    std::array::from_fn(|i| (0..6).map(|j| d[i][j] * e[j]).sum())
}

/// The wanted nodes that elements of one family touch, numbered for per-node accumulators.
pub(crate) struct WantedSlots {
    /// Per model node: asked for.
    pub is_wanted: Vec<bool>,
    /// Per model node: its index into `nodes` (`usize::MAX` when not touched or not wanted).
    pub slot: Vec<usize>,
    /// The wanted nodes touched by an element of the family, ascending.
    pub nodes: Vec<NodeIndex>,
}

/// [`WantedSlots`] of the `wanted` nodes over the elements `family` accepts (the averaging
/// set of nodal field recovery: solids here, shells in `shell_stress`).
pub(crate) fn wanted_slots(
    model: &Model,
    wanted: &[NodeIndex],
    family: impl Fn(&crate::model::Element) -> bool,
) -> WantedSlots {
    let nn = model.nodes.len();
    let mut is_wanted = vec![false; nn];
    for &n in wanted {
        if n < nn {
            is_wanted[n] = true;
        }
    }
    let mut slot = vec![usize::MAX; nn];
    let mut nodes: Vec<NodeIndex> = Vec::new();
    for el in model.elements.iter().filter(|e| family(e)) {
        for &n in &el.nodes {
            if n < nn && is_wanted[n] && slot[n] == usize::MAX {
                slot[n] = 0;
                nodes.push(n);
            }
        }
    }
    nodes.sort_unstable();
    for (q, &n) in nodes.iter().enumerate() {
        slot[n] = q;
    }
    WantedSlots {
        is_wanted,
        slot,
        nodes,
    }
}

/// Recover nodal stress/strain shapes of `n_modes` modes at the `wanted` nodes.
/// `displacement(node, mode)` gives the node's translation (basic frame) in that mode.
pub fn modal_fields(
    model: &Model,
    wanted: &[NodeIndex],
    n_modes: usize,
    displacement: &dyn Fn(NodeIndex, usize) -> [f64; 3],
    request: FieldRequest,
) -> Result<ModalFields, StressError> {
    modal_fields_with_modes(model, wanted, n_modes, displacement, &|_, _| None, request)
}

/// The amplitudes (basic frame) of the three incompatible modes of a ccx C3D8I (element index,
/// mode), or `None` for an element without them.
pub type ModeAmplitudes<'a> = &'a dyn Fn(usize, usize) -> Option<[[f64; 3]; 3]>;

/// [`modal_fields`] with the incompatible-mode amplitudes of ccx's C3D8I elements (module doc).
pub fn modal_fields_with_modes(
    model: &Model,
    wanted: &[NodeIndex],
    n_modes: usize,
    displacement: &dyn Fn(NodeIndex, usize) -> [f64; 3],
    amplitudes: ModeAmplitudes<'_>,
    request: FieldRequest,
) -> Result<ModalFields, StressError> {
    let nn = model.nodes.len();
    // Accumulators per wanted node touched by a solid: slot → (count, sums).
    let WantedSlots {
        is_wanted,
        slot,
        nodes: touched,
    } = wanted_slots(model, wanted, |el| el.kind.is_solid());
    let k = touched.len();
    let mut count = vec![0u32; k];
    let mut sum_strain = vec![0.0; n_modes * k * 6];
    let mut sum_stress = vec![0.0; if request.stress { n_modes * k * 6 } else { 0 }];
    let mut fallbacks = 0;
    let mut u = Vec::new();
    for (e, el) in model.elements.iter().enumerate() {
        if !el.kind.is_solid() || !el.nodes.iter().any(|&n| n < nn && is_wanted[n]) {
            continue;
        }
        let fail = |message: String| StressError::Element {
            file: model.source.clone(),
            id: el.id,
            kind: el.kind,
            message,
        };
        if el.nodes.len() != el.kind.node_count() || el.nodes.iter().any(|&n| n >= nn) {
            return Err(fail("node list does not match the element kind".into()));
        }
        let material = el
            .property
            .and_then(|p| model.properties.get(p))
            .and_then(|p| model.materials.get(p.material))
            .ok_or_else(|| fail("has no property with a valid material".into()))?;
        // σ = D ε: the material's D in the basic axes at each node (cylindrical axes follow
        // the node), or the isotropic one.
        let axes = el.property.and_then(|p| model.property_axes.get(&p));
        let hooke_at = |node: NodeIndex| -> Stiffness6 {
            match (material.stiffness(), axes) {
                (Some(d), Some(axes)) => rotate(d, &axes.at(&model.nodes[node].x)),
                (Some(d), None) => *d,
                (None, _) => {
                    let (lambda, mu) =
                        elements::Isotropic::new(material.e, material.nu, material.rho).lame();
                    crate::model::elasticity::isotropic(lambda, mu)
                }
            }
        };
        let d_nodes: Vec<Stiffness6> = if request.stress {
            el.nodes.iter().map(|&n| hooke_at(n)).collect()
        } else {
            Vec::new()
        };
        let Some((mut grads, fb)) = element_gradients(model, &el.nodes, el.kind)
            .map_err(|e| fail(format!("cannot evaluate strains: {e}")))?
        else {
            continue; // a solid kind without a formulation (assembly reports it)
        };
        fallbacks += fb;
        let with_modes = el.kind == ElementKind::Hex8 && amplitudes(e, 0).is_some();
        if with_modes {
            let x = coords::<8>(model, &el.nodes);
            for (a, g) in grads.iter_mut().enumerate() {
                let modes =
                    elements::solid_incompatible::hex8_ccx_mode_gradients(&x, &hex8::NODES[a])
                        .map_err(|e| fail(format!("cannot evaluate strains: {e}")))?;
                g.extend(modes);
            }
        }
        for j in 0..n_modes {
            u.clear();
            u.extend(el.nodes.iter().map(|&n| displacement(n, j)));
            if with_modes {
                u.extend(amplitudes(e, j).unwrap_or_default());
            }
            for (a, &n) in el.nodes.iter().enumerate() {
                if !is_wanted[n] {
                    continue;
                }
                let q = slot[n];
                let e = strain(&grads[a], &u);
                let base = (j * k + q) * 6;
                for c in 0..6 {
                    sum_strain[base + c] += e[c];
                }
                if request.stress {
                    let s = hooke(&d_nodes[a], &e);
                    for c in 0..6 {
                        sum_stress[base + c] += s[c];
                    }
                }
            }
        }
        for &n in &el.nodes {
            if is_wanted[n] {
                count[slot[n]] += 1;
            }
        }
    }
    let average = |mut v: Vec<f64>| -> Vec<f64> {
        for (i, x) in v.iter_mut().enumerate() {
            *x /= f64::from(count[(i / 6) % k]);
        }
        v
    };
    Ok(ModalFields {
        nodes: touched,
        stress: request.stress.then(|| average(sum_stress)),
        strain: request.strain.then(|| average(sum_strain)),
        centroid_fallbacks: fallbacks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::generate::{block, BlockElement, BlockSpec};
    use crate::model::Material;

    /// Every solid reproduces a linear displacement field exactly, so the recovered strain is
    /// the field's constant strain at every node (patch test).
    #[test]
    fn linear_field_gives_its_constant_strain_everywhere() {
        let h = [
            [1.0e-3, 2.0e-4, -3.0e-4],
            [5.0e-4, -2.0e-3, 7.0e-4],
            [-1.0e-4, 4.0e-4, 3.0e-3],
        ];
        let exact = [
            h[0][0],
            h[1][1],
            h[2][2],
            h[0][1] + h[1][0],
            h[1][2] + h[2][1],
            h[2][0] + h[0][2],
        ];
        for element in [
            BlockElement::Hex8,
            BlockElement::Tet10Six,
            BlockElement::Tet10Five,
        ] {
            let mut model = block(&BlockSpec {
                n: [3, 2, 2],
                size: [0.3, 0.1, 0.12],
                element,
                material: Material::steel(),
            });
            // Distort the interior a little so the Jacobians are not constant.
            for node in &mut model.nodes {
                let [x, y, z] = node.x;
                node.x = [
                    x + 0.01 * (y * 10.0).sin() * (z * 8.0).sin(),
                    y + 0.004 * (x * 9.0).sin(),
                    z,
                ];
            }
            let disp = |n: NodeIndex, _j: usize| -> [f64; 3] {
                let x = model.nodes[n].x;
                std::array::from_fn(|i| (0..3).map(|j| h[i][j] * x[j]).sum())
            };
            let all: Vec<NodeIndex> = (0..model.nodes.len()).collect();
            let f = modal_fields(
                &model,
                &all,
                1,
                &disp,
                FieldRequest {
                    stress: false,
                    strain: true,
                },
            )
            .unwrap(); // the block has only valid solids: cannot fail
            assert_eq!(f.nodes.len(), model.nodes.len());
            assert_eq!(f.centroid_fallbacks, 0);
            let strain = f.strain.unwrap(); // asked for: always present
            for q in 0..f.nodes.len() {
                for c in 0..6 {
                    let err = (strain[q * 6 + c] - exact[c]).abs();
                    assert!(err < 1e-13, "{element:?} node {q} comp {c}: error {err:e}");
                }
            }
        }
    }

    /// Uniaxial stress: u = ε (x, −ν y, −ν z) gives σ_xx = E ε and every other component 0.
    #[test]
    fn uniaxial_strain_field_gives_e_times_strain() {
        let steel = Material::steel();
        let model = block(&BlockSpec {
            n: [2, 2, 2],
            size: [1.0, 0.5, 0.25],
            element: BlockElement::Tet10Six,
            material: steel.clone(),
        });
        let eps = 1.0e-3;
        let nu = steel.nu;
        let disp = |n: NodeIndex, j: usize| -> [f64; 3] {
            let x = model.nodes[n].x;
            let s = eps * (j + 1) as f64;
            [s * x[0], -nu * s * x[1], -nu * s * x[2]]
        };
        let wanted = [0, 5, model.nodes.len() - 1];
        let f = modal_fields(
            &model,
            &wanted,
            2,
            &disp,
            FieldRequest {
                stress: true,
                strain: true,
            },
        )
        .unwrap(); // valid solids: cannot fail
        assert_eq!(f.nodes, wanted.to_vec());
        let stress = f.stress.unwrap(); // asked for
        let strain = f.strain.unwrap(); // asked for
        for j in 0..2 {
            let s = eps * (j + 1) as f64;
            for q in 0..3 {
                let b = (j * 3 + q) * 6;
                assert!((stress[b] / (steel.e * s) - 1.0).abs() < 1e-12);
                for c in 1..6 {
                    assert!(stress[b + c].abs() < 1e-12 * steel.e * s, "σ comp {c}");
                }
                assert!((strain[b] / s - 1.0).abs() < 1e-12);
                assert!((strain[b + 1] / (-nu * s) - 1.0).abs() < 1e-12);
            }
        }
    }

    /// Simple shear: u_x = γ y gives γ_xy = γ and σ_xy = G γ.
    #[test]
    fn simple_shear_gives_g_times_gamma() {
        let steel = Material::steel();
        let model = block(&BlockSpec {
            n: [2, 2, 1],
            size: [1.0, 1.0, 0.5],
            element: BlockElement::Hex8,
            material: steel.clone(),
        });
        let gamma = 2.0e-4;
        let disp = |n: NodeIndex, _j: usize| [gamma * model.nodes[n].x[1], 0.0, 0.0];
        let f = modal_fields(
            &model,
            &[4],
            1,
            &disp,
            FieldRequest {
                stress: true,
                strain: true,
            },
        )
        .unwrap(); // valid solids: cannot fail
        let (stress, strain) = (f.stress.unwrap(), f.strain.unwrap()); // both asked for
        assert!((strain[3] / gamma - 1.0).abs() < 1e-12);
        assert!((stress[3] / (steel.g * gamma) - 1.0).abs() < 1e-12);
        assert!(stress[0].abs() < 1e-9 * steel.g * gamma);
    }

    /// ccx's C3D8I in pure bending u = κxz, w = −κx²/2: with its mode amplitude (the w
    /// component of 1 − ξ² is κL²/8, the quadratic rest of w) every corner has the exact strain
    /// ε_xx = κz and no shear; the nodes alone give the parasitic shear γ_zx = κ(x − L/2).
    #[test]
    fn c3d8i_mode_amplitudes_remove_the_parasitic_shear_at_the_corners() {
        let (l, kappa) = (2.0, 1e-3);
        let model = block(&BlockSpec {
            n: [1, 1, 1],
            size: [l, 0.5, 0.4],
            element: BlockElement::Hex8,
            material: Material::steel(),
        });
        let disp = |n: NodeIndex, _j: usize| -> [f64; 3] {
            let [x, _, z] = model.nodes[n].x;
            [kappa * x * z, 0.0, -0.5 * kappa * x * x]
        };
        let amplitudes = |_e: usize, _j: usize| -> Option<[[f64; 3]; 3]> {
            Some([[0.0, 0.0, kappa * l * l / 8.0], [0.0; 3], [0.0; 3]])
        };
        let all: Vec<NodeIndex> = (0..8).collect();
        let request = FieldRequest {
            stress: false,
            strain: true,
        };
        let with = modal_fields_with_modes(&model, &all, 1, &disp, &amplitudes, request).unwrap();
        let without = modal_fields(&model, &all, 1, &disp, request).unwrap(); // valid solid
        let (with, without) = (with.strain.unwrap(), without.strain.unwrap()); // asked for
        for (q, &n) in all.iter().enumerate() {
            let [x, _, z] = model.nodes[n].x;
            let want = [kappa * z, 0.0, 0.0, 0.0, 0.0, 0.0];
            for c in 0..6 {
                assert!(
                    (with[6 * q + c] - want[c]).abs() < 1e-15,
                    "node {n} comp {c}"
                );
            }
            assert!(
                (without[6 * q + 5] - kappa * (x - 0.5 * l)).abs() < 1e-15,
                "node {n}"
            );
        }
    }
}
