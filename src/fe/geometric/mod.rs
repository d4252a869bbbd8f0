//! Geometric (initial-stress) stiffness K_G(σ₀) of every element family, assembled in the dof
//! numbering of K, so that K_T = K + K_G feeds every reduction unchanged.
//!
//! ```text
//! u₀ (static displacement, physical dofs) + αΔT ──► element stresses σ₀ ──► K_G,e ──► K_G
//! ```
//! * [`solid`] — tet4, tet10, hex8 (with or without incompatible modes), hex20, hex20R, prism6:
//!   K_G = ∫ Gᵀ S G dV with the 3×3 stress at the stiffness integration points.
//! * [`shell`] — MITC4 quadrilateral, DKT/DKMT triangle: membrane resultants N on the gradients
//!   of the deflection and of the in-plane displacements.
//! * [`line`](mod@line) — beams (consistent beam-column K_G, Euler–Bernoulli or Timoshenko)
//!   and rods (N/L (I − e eᵀ)).
//!
//! * [`initial_displacement_stiffness`] — solids only: K_L(u₀), the initial-displacement
//!   (large-deformation) part of the tangent at u₀, for a solver's perturbation of a static
//!   state (CalculiX `*STEP, PERTURBATION`); quadratic in u₀.
//!
//! The stress is linear in (u₀, ΔT), so K_G is too: K_G(s·u₀) = s K_G(u₀). Elements without a
//! formulation here (quadratic shells; prism15, which the assembler refuses too) are an error,
//! never left out. Thermal strain: [`Thermal`] gives ΔT (uniform or per node) and the expansion
//! coefficient α of each material; [`thermal_loads`] are the consistent forces ∫ Bᵀ D ε_th dV
//! that the stresses of [`element_stresses`] subtract again (a free expansion is stress free).

pub mod line;
pub mod shell;
pub mod solid;

use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use rayon::prelude::*;

use super::assembly::{is_structural, to_frames, AssemblySpec, BeamTheory};
use super::dofs::DofMap;
use super::elements::beam::BeamProps;
use super::elements::{ElementError, Isotropic, Xyz};
use super::pattern::Pattern;
use super::FeError;
use crate::model::{ElementKind, Model, Section};

pub use shell::{Resultant, ShellElement};
pub use solid::{SolidElement, Stress};

/// Temperature change ΔT from the stress-free state.
#[derive(Debug, Clone, PartialEq)]
pub enum Temperature {
    /// The same ΔT at every node.
    Uniform(f64),
    /// ΔT per node (indexed like `Model::nodes`).
    Nodal(Vec<f64>),
}

/// A thermal preload: ΔT and the linear expansion coefficient α of each material (indexed like
/// `Model::materials`; 0 for a material that does not expand). Plain data: the importers'
/// MAT1 A / *EXPANSION fill `alpha`.
#[derive(Debug, Clone, PartialEq)]
pub struct Thermal {
    /// ΔT.
    pub delta_t: Temperature,
    /// α per material.
    pub alpha: Vec<f64>,
}

/// The initial stress of one element.
#[derive(Debug, Clone, PartialEq)]
pub enum ElementStress {
    /// Solids: σ at the stiffness integration points.
    Solid(Vec<Stress>),
    /// Shells: membrane resultants at the membrane's points (element frame).
    Shell(Vec<Resultant>),
    /// Beams and rods: the axial force N (tension positive).
    Axial(f64),
}

/// One element prepared for initial-stress work.
enum Formulation {
    Solid(SolidElement),
    Shell(Box<ShellElement>),
    Beam {
        x: [Xyz; 2],
        v: Option<Xyz>,
        mat: Isotropic,
        props: BeamProps,
    },
    Rod {
        x: [Xyz; 2],
        ea: f64,
    },
}

impl Formulation {
    fn dpn(&self) -> usize {
        match self {
            Formulation::Solid(_) => 3,
            _ => 6,
        }
    }

    fn stress(&self, u: &[f64], theta: &[f64]) -> Result<ElementStress, ElementError> {
        let th2 = || [theta[0], theta[1]];
        Ok(match self {
            Formulation::Solid(s) => ElementStress::Solid(s.stresses(u, theta)?),
            Formulation::Shell(s) => ElementStress::Shell(s.resultants(u, theta)?),
            Formulation::Beam { x, mat, props, .. } => {
                ElementStress::Axial(line::axial_force(x, mat.e * props.area, u, &th2())?)
            }
            Formulation::Rod { x, ea } => {
                ElementStress::Axial(line::axial_force(x, *ea, u, &th2())?)
            }
        })
    }

    fn geometric_stiffness(&self, stress: &ElementStress) -> Result<Vec<f64>, ElementError> {
        match (self, stress) {
            (Formulation::Solid(s), ElementStress::Solid(sig)) => Ok(s.geometric_stiffness(sig)),
            (Formulation::Shell(s), ElementStress::Shell(n)) => Ok(s.geometric_stiffness(n)),
            (
                Formulation::Beam {
                    x, v, mat, props, ..
                },
                ElementStress::Axial(n),
            ) => line::beam_geometric_stiffness(x, *v, mat, props, *n),
            (Formulation::Rod { x, .. }, ElementStress::Axial(n)) => {
                line::rod_geometric_stiffness(x, *n)
            }
            _ => Err(ElementError::BadConstants(
                "stress of another element family".into(),
            )),
        }
    }

    fn thermal_load(&self, theta: &[f64]) -> Result<Vec<f64>, ElementError> {
        let th2 = [theta[0], theta[1]];
        match self {
            Formulation::Solid(s) => Ok(s.thermal_load(theta)),
            Formulation::Shell(s) => Ok(s.thermal_load(theta)),
            Formulation::Beam { x, mat, props, .. } => {
                line::thermal_load(x, mat.e * props.area, &th2)
            }
            Formulation::Rod { x, ea } => line::thermal_load(x, *ea, &th2),
        }
    }
}

/// The elements the assembler forms matrices for (the same list and order as
/// [`super::assemble`], so the patterns agree).
fn structural_elements(model: &Model) -> Vec<usize> {
    (model.elements.iter().enumerate())
        .filter(|(_, e)| e.property.is_some() || is_structural(e.kind))
        .map(|(i, _)| i)
        .collect()
}

/// Element `e` of `model` with its resolved section and material, and the index of the
/// material whose α expands it.
fn formulation(
    model: &Model,
    e: usize,
    spec: &AssemblySpec,
) -> Result<(Formulation, usize), FeError> {
    let el = &model.elements[e];
    let origin = || model.element_origin(el.id);
    let fail = |message: String| FeError::Unsupported {
        source_file: origin(),
        id: el.id,
        kind: el.kind,
        message,
    };
    let elem_err = |err: ElementError| FeError::Element {
        source_file: origin(),
        id: el.id,
        kind: el.kind,
        err,
    };
    let prop = (el.property.and_then(|p| model.properties.get(p)))
        .ok_or_else(|| fail("has no (valid) property".into()))?;
    let m = (model.materials.get(prop.material))
        .ok_or_else(|| fail(format!("property {} names a missing material", prop.id)))?;
    if m.stiffness().is_some() {
        return Err(fail(format!(
            "material {} '{}' is anisotropic: the preload's initial stress is formed with \
             isotropic materials only",
            m.id, m.name
        )));
    }
    let mat = Isotropic {
        e: m.e,
        nu: m.nu,
        g: m.g,
        rho: m.rho,
    };
    let x: Vec<Xyz> = (el.nodes.iter())
        .map(|&n| model.nodes.get(n).map(|p| p.x))
        .collect::<Option<_>>()
        .ok_or_else(|| fail("refers to a node index beyond the model's nodes".into()))?;
    let two = || -> Result<[Xyz; 2], FeError> {
        (x.len() == 2)
            .then(|| [x[0], x[1]])
            .ok_or_else(|| fail(format!("has {} nodes, a line element 2", x.len())))
    };
    let f = match (&prop.section, el.kind) {
        // a CalculiX B32R expanded into a brick: at its section's points
        (Section::Solid, ElementKind::Hex20R) if model.beam_bricks.contains_key(&e) => {
            let rule = crate::fe::elements::hex20_beam::rule(&model.beam_bricks[&e]);
            Formulation::Solid(SolidElement::hex20_at(&x, mat, &rule).map_err(elem_err)?)
        }
        (Section::Solid, k) if k.is_solid() => Formulation::Solid(
            SolidElement::with_rules(
                k,
                &x,
                mat,
                crate::fe::elements::element::SolidRules::of(&model.params),
            )
            .map_err(elem_err)?,
        ),
        (Section::Shell(s), ElementKind::Quad4 | ElementKind::Tri3) => {
            let p = super::shell_section::shell_props(model, e, prop, s).map_err(fail)?;
            if p.general.is_some() {
                return Err(fail(format!(
                    "property {} is a laminate or plane-stress (PCOMP of several materials, \
                     MAT8, MAT2) shell: its preload's initial stress is not implemented",
                    prop.id
                )));
            }
            if model.drilling_membranes.contains(&e) {
                return Err(fail(
                    "a CQUADR/CTRIAR (drilling membrane) has no geometric stiffness: a preload on \
                     it is not implemented (CQUAD4/CTRIA3 have one)"
                        .into(),
                ));
            }
            Formulation::Shell(Box::new(ShellElement::new(&x, &p).map_err(elem_err)?))
        }
        (Section::Beam(s), ElementKind::Beam2 | ElementKind::Bar2) => {
            if s.taper.is_some()
                || model.beam_pins.contains_key(&e)
                || model.beam_offsets.contains_key(&e)
            {
                return Err(fail(format!(
                    "a tapered (property {}), pinned or offset beam has no geometric stiffness \
                     (not implemented)",
                    prop.id
                )));
            }
            let x = two()?;
            // I12 ≠ 0: the principal frame, without shear factors (as the assembler).
            let (v, iz, iy) = match el.orientation {
                Some(v) => {
                    let p =
                        crate::fe::elements::beam::principal_orientation(&x, v, s.i1, s.i2, s.i12)
                            .map_err(elem_err)?;
                    (Some(p.0), p.1, p.2)
                }
                None => (None, s.i1, s.i2),
            };
            Formulation::Beam {
                x,
                v,
                mat,
                props: BeamProps {
                    area: s.area,
                    iz,
                    iy,
                    j: s.j,
                    shear: (s.shear_factors)
                        .filter(|_| spec.beam == BeamTheory::Timoshenko && s.i12 == 0.0),
                    nsm: s.nsm,
                },
            }
        }
        (Section::Rod { area, .. }, ElementKind::Rod2) => Formulation::Rod {
            x: two()?,
            ea: mat.e * area,
        },
        (Section::Shell(_), ElementKind::Quad8 | ElementKind::Tri6) => {
            return Err(fail(
                "a quadratic shell (S8/S8R/S6, CQUAD8/CTRIA6) has no geometric stiffness: a \
                 preload on it is not implemented (mesh the preloaded part with S4/S3, \
                 CQUAD4/CTRIA3)"
                    .into(),
            ))
        }
        (_, kind) => {
            return Err(fail(format!(
                "{kind:?} with property {} has no geometric stiffness (no element formulation)",
                prop.id
            )))
        }
    };
    Ok((f, prop.material))
}

/// αΔT at the nodes of element `e` (material index `mat`), zeros without a thermal load.
fn element_theta(
    model: &Model,
    e: usize,
    mat: usize,
    thermal: Option<&Thermal>,
) -> Result<Vec<f64>, FeError> {
    let el = &model.elements[e];
    let Some(t) = thermal else {
        return Ok(vec![0.0; el.nodes.len()]);
    };
    let alpha = *t.alpha.get(mat).ok_or_else(|| FeError::BadReference {
        source_file: model.source.clone(),
        message: format!(
            "thermal preload: {} expansion coefficients for {} materials",
            t.alpha.len(),
            model.materials.len()
        ),
    })?;
    el.nodes
        .iter()
        .map(|&n| match &t.delta_t {
            Temperature::Uniform(dt) => Ok(alpha * dt),
            Temperature::Nodal(dt) => {
                dt.get(n)
                    .map(|d| alpha * d)
                    .ok_or_else(|| FeError::BadReference {
                        source_file: model.source.clone(),
                        message: format!(
                            "thermal preload: {} nodal temperatures for {} nodes",
                            dt.len(),
                            model.nodes.len()
                        ),
                    })
            }
        })
        .collect()
}

/// The element's displacements in the basic frame (`dpn` per node) from the physical dofs `u`.
fn gather(dofs: &DofMap, nodes: &[usize], dpn: usize, u: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; dpn * nodes.len()];
    for (la, &a) in nodes.iter().enumerate() {
        let na = usize::from(dofs.count[a]).min(dpn);
        for blk in 0..na / 3 {
            let v: [f64; 3] = std::array::from_fn(|k| u[dofs.first[a] + 3 * blk + k]);
            // u_basic = Rᵀ u_local (rows of R are the local axes)
            let b = match &dofs.frames[a] {
                Some(r) => std::array::from_fn(|i| (0..3).map(|k| r[k][i] * v[k]).sum()),
                None => v,
            };
            out[la * dpn + 3 * blk..la * dpn + 3 * blk + 3].copy_from_slice(&b);
        }
    }
    out
}

/// Elements in chunks, each chunk's results computed in parallel and handed over in element
/// order (the first error in element order wins, as in the assembly).
fn for_each_element<T: Send>(
    elems: &[usize],
    work: impl Fn(usize) -> Result<T, FeError> + Sync,
    mut take: impl FnMut(usize, T),
) -> Result<(), FeError> {
    for chunk in elems.chunks(4096) {
        let results: Vec<Result<T, FeError>> = chunk.par_iter().map(|&e| work(e)).collect();
        for (&e, r) in chunk.iter().zip(results) {
            take(e, r?);
        }
    }
    Ok(())
}

/// Initial stress of every structural element from the physical static displacement `u` and
/// the thermal strain (module doc), as (element index, stress).
pub fn element_stresses(
    model: &Model,
    dofs: &DofMap,
    spec: &AssemblySpec,
    u: &[f64],
    thermal: Option<&Thermal>,
) -> Result<Vec<(usize, ElementStress)>, FeError> {
    check_len(model, dofs, u)?;
    let elems = structural_elements(model);
    let mut out = Vec::with_capacity(elems.len());
    for_each_element(
        &elems,
        |e| {
            let (f, mat) = formulation(model, e, spec)?;
            let theta = element_theta(model, e, mat, thermal)?;
            let ue = gather(dofs, &model.elements[e].nodes, f.dpn(), u);
            f.stress(&ue, &theta)
                .map_err(|err| element_error(model, e, err))
        },
        |e, s| out.push((e, s)),
    )?;
    Ok(out)
}

fn element_error(model: &Model, e: usize, err: ElementError) -> FeError {
    let el = &model.elements[e];
    FeError::Element {
        source_file: model.element_origin(el.id),
        id: el.id,
        kind: el.kind,
        err,
    }
}

fn check_len(model: &Model, dofs: &DofMap, u: &[f64]) -> Result<(), FeError> {
    if u.len() != dofs.n_dofs {
        return Err(FeError::BadReference {
            source_file: model.source.clone(),
            message: format!(
                "geometric stiffness: a displacement of {} values for {} dofs",
                u.len(),
                dofs.n_dofs
            ),
        });
    }
    Ok(())
}

/// K_G(σ₀) over the physical dofs of `dofs`, σ₀ the initial stress of the physical static
/// displacement `u` and the thermal strain (module doc). Full symmetric, with the sparsity
/// pattern of [`super::assemble`]'s K for the same model (so K + K_G adds value by value).
pub fn geometric_stiffness(
    model: &Model,
    dofs: &DofMap,
    spec: &AssemblySpec,
    u: &[f64],
    thermal: Option<&Thermal>,
) -> Result<SparseColMat<usize, f64>, FeError> {
    assemble_elementwise(model, dofs, spec, u, thermal, |f, ue, theta| {
        f.stress(ue, theta).and_then(|s| f.geometric_stiffness(&s))
    })
}

/// The initial-displacement stiffness K_L(u₀) over the physical dofs (solids:
/// [`SolidElement::initial_displacement_stiffness`]; other element families are an error), in
/// the pattern of [`geometric_stiffness`]. With K + K_G it is the total-Lagrangian tangent at
/// the static state u₀, as CalculiX's `*STEP, PERTURBATION` forms it.
pub fn initial_displacement_stiffness(
    model: &Model,
    dofs: &DofMap,
    spec: &AssemblySpec,
    u: &[f64],
) -> Result<SparseColMat<usize, f64>, FeError> {
    assemble_elementwise(model, dofs, spec, u, None, |f, ue, _| match f {
        Formulation::Solid(s) => s.initial_displacement_stiffness(ue),
        _ => Err(ElementError::BadConstants(
            "the initial-displacement stiffness of a perturbed static state (CalculiX \
             *STEP, PERTURBATION) is formed for solid elements only; beams, rods and shells \
             have none here"
                .into(),
        )),
    })
}

/// Σ_e of the element matrices `element(formulation, u_e, αΔT_e)` (`dpn` dofs per node, basic
/// frame) over the physical dofs, in the pattern of the assembled K.
fn assemble_elementwise(
    model: &Model,
    dofs: &DofMap,
    spec: &AssemblySpec,
    u: &[f64],
    thermal: Option<&Thermal>,
    element: impl Fn(&Formulation, &[f64], &[f64]) -> Result<Vec<f64>, ElementError> + Sync,
) -> Result<SparseColMat<usize, f64>, FeError> {
    check_len(model, dofs, u)?;
    let elems = structural_elements(model);
    let conn: Vec<&[usize]> = (elems.iter())
        .map(|&e| model.elements[e].nodes.as_slice())
        .collect();
    let pattern = Pattern::build(dofs, &conn);
    let mut values = vec![0.0f64; pattern.nnz()];
    for_each_element(
        &elems,
        |e| {
            let nodes = &model.elements[e].nodes;
            let (f, mat) = formulation(model, e, spec)?;
            let theta = element_theta(model, e, mat, thermal)?;
            let ue = gather(dofs, nodes, f.dpn(), u);
            let mut k = element(&f, &ue, &theta).map_err(|err| element_error(model, e, err))?;
            if nodes.iter().any(|&n| dofs.frames[n].is_some()) {
                to_frames(&mut k, nodes, f.dpn(), &dofs.frames);
            }
            Ok((f.dpn(), k))
        },
        |e, (dpn, k)| {
            let nodes = &model.elements[e].nodes;
            let nd = dpn * nodes.len();
            for (la, &a) in nodes.iter().enumerate() {
                for c in 0..dpn.min(usize::from(dofs.count[a])) {
                    for (lb, &b) in nodes.iter().enumerate() {
                        let p = pattern.block(a, c, b);
                        for r in 0..dpn.min(usize::from(dofs.count[b])) {
                            values[p + r] += k[(lb * dpn + r) * nd + la * dpn + c];
                        }
                    }
                }
            }
        },
    )?;
    let n = dofs.n_dofs;
    let Pattern {
        mut col_ptr,
        row_idx,
        ..
    } = pattern;
    // the interior dofs (ccx's C3D8I modes) carry no K_G: empty columns
    let nnz = col_ptr.last().copied().unwrap_or(0);
    col_ptr.resize(n + 1, nnz);
    Ok(SparseColMat::new(
        SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx),
        values,
    ))
}

/// Consistent nodal forces of the thermal strain over the physical dofs (module doc), in the
/// nodes' displacement frames.
pub fn thermal_loads(
    model: &Model,
    dofs: &DofMap,
    spec: &AssemblySpec,
    thermal: &Thermal,
) -> Result<Vec<f64>, FeError> {
    let mut f = vec![0.0; dofs.n_dofs];
    let elems = structural_elements(model);
    for_each_element(
        &elems,
        |e| {
            let (form, mat) = formulation(model, e, spec)?;
            let theta = element_theta(model, e, mat, Some(thermal))?;
            let fe = (form.thermal_load(&theta)).map_err(|err| element_error(model, e, err))?;
            Ok((form.dpn(), fe))
        },
        |e, (dpn, fe)| {
            for (la, &a) in model.elements[e].nodes.iter().enumerate() {
                for blk in 0..usize::from(dofs.count[a]).min(dpn) / 3 {
                    let v: [f64; 3] = std::array::from_fn(|k| fe[la * dpn + 3 * blk + k]);
                    let l = match &dofs.frames[a] {
                        Some(r) => std::array::from_fn(|i| (0..3).map(|k| r[i][k] * v[k]).sum()),
                        None => v,
                    };
                    for k in 0..3 {
                        f[dofs.first[a] + 3 * blk + k] += l[k];
                    }
                }
            }
        },
    )?;
    Ok(f)
}
