//! What one element kind is and can do, in one place: the [`Element`] trait each element
//! module implements (matrices, integration points of a solid for general materials and
//! initial stress, nodal gradients for stress recovery), the input it is given
//! ([`ElementInput`]) and what it returns ([`ElementMatrices`]). `super::kinds::element` is the
//! one lookup from an [`ElementKind`] to its implementation; the topology (corner faces,
//! mid-side edges) is the model's (`crate::model::load::solid_faces`), as importers need it.
//!
//! This file uses no element module, so every element module can use it without a circle.

use super::{map_point, ElementError, Isotropic, ShapeFn, Xyz};
use crate::fe::mass::{self, MassKind};
use crate::fe::quadrature::QuadPoint;
use crate::model::{ElementKind, Material, Model, Property};

/// Bending theory of beam elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BeamTheory {
    /// Euler–Bernoulli (shear-rigid) everywhere, whatever the sections say.
    EulerBernoulli,
    /// Timoshenko: shear flexibility from the section's shear factors (Euler–Bernoulli where a
    /// section has none). The default: the section says what its card means (Nastran PBEAM and
    /// PBARL shear flexible, PBAR without K1/K2 shear-rigid; see the importers).
    #[default]
    Timoshenko,
}

/// Which integration rule forms the tet10 consistent mass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tet10MassRule {
    /// The 4-point rule, as CalculiX C3D10 (matches its dumped matrices).
    #[default]
    CalculixFourPoint,
    /// Exact integration of N_a N_b (degree 4) for straight-edged elements.
    Exact,
}

/// Which rotational inertia a lumped beam mass carries (translations always get m/2 per node).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BeamLumping {
    /// Section rotary inertia ρL/2·(I_p, I_y, I_z) on the rotations; the default.
    #[default]
    SectionRotary,
    /// Torsional inertia ρI_pL/2 only, no bending rotary inertia (as Nastran CBEAM lumped).
    TorsionOnly,
    /// No rotational inertia at all (as Nastran CBAR lumped).
    TranslationsOnly,
    /// As Nastran lumps each element: a bar (CBAR) none, a beam (CBEAM) torsion only. Resolved
    /// per element by [`BeamLumping::for_element`]; on its own it means `TorsionOnly`. Shells
    /// (CQUAD4/CTRIA3) then get translational lumped mass only, as MSC Nastran lumps them
    /// (`ShellProps::lumped_rotary`).
    Nastran,
}

impl BeamLumping {
    /// The lumping of one element of this kind (resolves `Nastran`).
    pub fn for_element(self, kind: ElementKind) -> BeamLumping {
        match (self, kind) {
            (BeamLumping::Nastran, ElementKind::Bar2) => BeamLumping::TranslationsOnly,
            (BeamLumping::Nastran, _) => BeamLumping::TorsionOnly,
            (other, _) => other,
        }
    }
}

/// Options of the assembly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AssemblySpec {
    /// Lumped (default) or consistent mass.
    pub mass: MassKind,
    /// Integration of the tet10 consistent mass (CalculiX 4-point by default).
    pub tet10_mass: Tet10MassRule,
    /// Beam bending theory.
    pub beam: BeamTheory,
    /// Rotational inertia of lumped beam masses.
    pub beam_lumping: BeamLumping,
}

/// One element's matrices in the basic frame, node-major with `dpn` dofs per node, then its
/// `interior` dofs (ccx's C3D8I: the incompatible modes, `DofMap::interior`).
#[derive(Debug, Clone, PartialEq)]
pub struct ElementMatrices {
    /// Dofs per element node (3 solids, 6 beams, rods and shells).
    pub dpn: usize,
    /// Interior dofs after the nodal ones (0 but for ccx's C3D8I).
    pub interior: usize,
    /// Stiffness, row-major.
    pub k: Vec<f64>,
    /// Mass, row-major.
    pub m: Vec<f64>,
}

impl ElementMatrices {
    /// Node-major matrices without interior dofs.
    pub fn nodal(dpn: usize, k: Vec<f64>, m: Vec<f64>) -> ElementMatrices {
        ElementMatrices {
            dpn,
            interior: 0,
            k,
            m,
        }
    }

    /// Rows (and columns) of `k` and `m`: the nodal dofs, then the interior ones.
    pub fn size(&self) -> usize {
        self.k.len().isqrt()
    }

    /// The mass over the nodal dofs only: the leading block of `m` (the interior dofs' rows
    /// dropped — what a rigid motion, which excites no interior dof, sees).
    pub fn nodal_mass(&self) -> Vec<f64> {
        let nt = self.size();
        let nc = nt - self.interior;
        (0..nc * nc)
            .map(|ij| self.m[(ij / nc) * nt + ij % nc])
            .collect()
    }
}

/// An integration point of a solid: weight × det J, shape functions, and the physical
/// gradients of the nodal shape functions, then of the incompatible modes (if any).
#[derive(Debug, Clone, PartialEq)]
pub struct ModePoint {
    /// w_q det J.
    pub w: f64,
    /// N_a at the point.
    pub n: Vec<f64>,
    /// ∂N_a/∂x for the N nodes, then ∂P_m/∂x for the modes.
    pub grads: Vec<Xyz>,
}

/// Which integration a solid uses (the model's `ModelParams`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SolidRules {
    /// Incompatible modes of hex8 and prism6 (Nastran CHEXA/CPENTA, CalculiX C3D8I).
    pub incompatible: bool,
    /// CalculiX's rules (C3D6 on two points).
    pub ccx: bool,
    /// ANSYS's rules (SOLID186 with full integration on Irons' 14 points).
    pub ansys: bool,
}

impl SolidRules {
    /// The rules a model's solids use (`ModelParams::solid_bubbles`, `ccx_solid_rules`,
    /// `ansys_solid_rules`).
    pub fn of(params: &crate::model::ModelParams) -> SolidRules {
        SolidRules {
            incompatible: params.solid_bubbles,
            ccx: params.ccx_solid_rules,
            ansys: params.ansys_solid_rules,
        }
    }
}

/// Physical shape-function gradients ∂N_b/∂x at each of the element's own nodes (index a), plus
/// the number of corners where the map is degenerate (the centroid gradients stand in there).
pub type NodalGradients = (Vec<Vec<Xyz>>, usize);

/// Why an element's matrices could not be formed.
#[derive(Debug, Clone, PartialEq)]
pub enum MatricesError {
    /// The element's input does not fit its formulation (section, options): what is wrong.
    Unsupported(String),
    /// The formulation failed (material constants, a folded element).
    Element(ElementError),
}

impl From<ElementError> for MatricesError {
    fn from(err: ElementError) -> MatricesError {
        MatricesError::Element(err)
    }
}

/// What an element is given: the model, the element, its property and material (checked to
/// exist, a solid's section checked to be solid), and the assembly options.
pub struct ElementInput<'a> {
    /// The model.
    pub model: &'a Model,
    /// Index of the element in `model.elements`.
    pub index: usize,
    /// The element's node indices (as many as its kind has, each valid).
    pub nodes: &'a [usize],
    /// The element's kind.
    pub kind: ElementKind,
    /// The element's property.
    pub property: &'a Property,
    /// The property's material.
    pub material: &'a Material,
    /// The material's isotropic constants.
    pub iso: Isotropic,
    /// The assembly options.
    pub spec: &'a AssemblySpec,
    /// A solid's stiffness with the material's general D (orthotropic/anisotropic), formed by
    /// `anisotropic::stiffness`; `None` for an isotropic material.
    pub general: Option<Vec<f64>>,
}

impl ElementInput<'_> {
    /// Lumped mass asked for.
    pub fn lumped(&self) -> bool {
        self.spec.mass == MassKind::Lumped
    }

    /// The coordinates of the element's N nodes.
    pub fn coords<const N: usize>(&self) -> [Xyz; N] {
        std::array::from_fn(|i| self.model.nodes[self.nodes[i]].x)
    }

    /// The solid's stiffness: the general-material one when there is one, else `isotropic`'s.
    pub fn stiffness(
        &self,
        isotropic: impl FnOnce() -> Result<Vec<f64>, ElementError>,
    ) -> Result<Vec<f64>, ElementError> {
        match &self.general {
            Some(k) => Ok(k.clone()),
            None => isotropic(),
        }
    }

    /// A solid's matrices from its stiffness and its scalar mass `ms` (nn × nn): consistent,
    /// row-summed (linear kinds) or HRZ (quadratic kinds) lumped.
    pub fn solid(&self, k: Vec<f64>, ms: Vec<f64>, nn: usize, quadratic: bool) -> ElementMatrices {
        let m = match (self.lumped(), quadratic) {
            (false, _) => super::expand_scalar_mass(&ms, nn),
            (true, false) => mass::diagonal_solid_mass(&mass::row_sum(&ms, nn)),
            (true, true) => mass::diagonal_solid_mass(&mass::hrz(&ms, nn)),
        };
        ElementMatrices::nodal(3, k, m)
    }
}

/// One element formulation: what the assembly, the stress recovery, the general-material
/// kernel and the initial-stress (preload) kernel ask of an element kind.
pub trait Element: Sync {
    /// The element's stiffness and mass in the basic frame.
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError>;

    /// A solid's integration points through `x` (model node order) with the rules of its
    /// stiffness (incompatible modes last); `None` for a kind without such a formulation
    /// (non-solids, C3D8R's hourglass control).
    fn stiffness_points(
        &self,
        x: &[Xyz],
        rules: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError>;

    /// The gradients at the element's nodes for nodal stress recovery; `None` for a kind whose
    /// fields are not recovered.
    fn nodal_gradients(&self, x: &[Xyz]) -> Result<Option<NodalGradients>, ElementError>;
}

/// The first N points of `x` as an array (`x` holds at least N: the callers check the count).
pub fn first<const N: usize>(x: &[Xyz]) -> [Xyz; N] {
    std::array::from_fn(|a| x[a])
}

/// Gradients ∂N_b/∂x_i at ξ = ξ_a for every node a (isoparametric map, `map_point`); where
/// the map is degenerate the centroid's gradients stand in (counted).
pub fn nodal_gradients<const N: usize>(
    x: &[Xyz; N],
    shape: ShapeFn<N>,
    reference_nodes: &[Xyz; N],
    centroid: Xyz,
) -> Result<NodalGradients, ElementError> {
    let mut fallbacks = 0;
    let mut centre: Option<[Xyz; N]> = None;
    let mut out = Vec::with_capacity(N);
    for (a, xi) in reference_nodes.iter().enumerate() {
        let g = match map_point(x, shape, xi, a) {
            Ok((_, g, _)) => g,
            Err(_) => {
                fallbacks += 1;
                match centre {
                    Some(g) => g,
                    None => {
                        let g = map_point(x, shape, &centroid, N)?.1;
                        centre = Some(g);
                        g
                    }
                }
            }
        };
        out.push(g.to_vec());
    }
    Ok((out, fallbacks))
}

/// The integration points of an N-node solid without incompatible modes at `rule`.
pub fn integration_points<const N: usize>(
    x: &[Xyz],
    shape: ShapeFn<N>,
    rule: &[QuadPoint],
) -> Result<Vec<ModePoint>, ElementError> {
    let x: [Xyz; N] = first(x);
    rule.iter()
        .enumerate()
        .map(|(p, q)| {
            let (n, g, det) = map_point(&x, shape, &q.xi, p)?;
            Ok(ModePoint {
                w: q.w * det,
                n: n.to_vec(),
                grads: g.to_vec(),
            })
        })
        .collect()
}

/// A kind read from a deck but never assembled (Abaqus B32, expanded into bricks on import).
pub struct Unassembled;

impl Element for Unassembled {
    fn matrices(&self, input: &ElementInput) -> Result<ElementMatrices, MatricesError> {
        Err(MatricesError::Unsupported(format!(
            "{:?} elements are not assembled (no element formulation yet)",
            input.kind
        )))
    }

    fn stiffness_points(
        &self,
        _: &[Xyz],
        _: SolidRules,
    ) -> Result<Option<Vec<ModePoint>>, ElementError> {
        Ok(None)
    }

    fn nodal_gradients(&self, _: &[Xyz]) -> Result<Option<NodalGradients>, ElementError> {
        Ok(None)
    }
}
