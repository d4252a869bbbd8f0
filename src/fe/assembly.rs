//! Sparse assembly of K and M: element matrices computed in parallel (rayon), rotated into the
//! nodes' displacement frames, and scattered straight into the compressed columns of a pattern
//! built once per `DofMap` (no triplet list, so a 10⁶-dof model stays within a few GB).
//!
//! K = Σ_e A_eᵀ K_e A_e and M = Σ_e A_eᵀ M_e A_e + Σ_p M_p (A_e the Boolean gather of element e's
//! dofs; M_p point masses; springs, scalar masses and bushes as small elements,
//! [`super::connectors`]), both stored full symmetric (both triangles). The scatter is parallel
//! over disjoint column ranges, so no two threads write the same value.

use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use rayon::prelude::*;

use super::dofs::DofMap;
use super::elements::beam::{BeamLumping, BeamProps};
use super::elements::tet10::Tet10MassRule;
use super::elements::{
    beam, hex20, hex20_beam, hex8, hex8r, prism15, prism6, pyram13, pyram5, quad4_shell,
    quad8_shell, rod, solid_incompatible, tet10, tet4, tri3_shell, tri6_shell, ElementError,
    Isotropic, Xyz,
};
use super::interior::{interior_block, with_interior};
use super::mass::{self, MassKind};
use super::pattern::Pattern;
use super::FeError;
use crate::model::{ElementKind, Model, Section};

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

/// The assembled physical system.
#[derive(Debug, Clone)]
pub struct Assembled {
    /// Dof numbering.
    pub dofs: DofMap,
    /// Stiffness, full symmetric.
    pub k: SparseColMat<usize, f64>,
    /// Mass, full symmetric (lumped: node-block diagonal, explicit zeros dropped).
    pub m: SparseColMat<usize, f64>,
}

/// One element's matrices in the basic frame, node-major with `dpn` dofs per node, then its
/// `interior` dofs (ccx's C3D8I: the incompatible modes, [`DofMap::interior`]).
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

/// Does the assembler form matrices for this element (solids, beams, rods with a property)?
pub fn is_structural(kind: ElementKind) -> bool {
    kind.is_solid()
        || matches!(
            kind,
            ElementKind::Beam2 | ElementKind::Bar2 | ElementKind::Rod2
        )
}

fn coords<const N: usize>(model: &Model, nodes: &[usize]) -> [Xyz; N] {
    std::array::from_fn(|i| model.nodes[nodes[i]].x)
}

/// Why an element has no property, and what to do: a mesh without any material (a Gmsh mesh)
/// needs `--material` (issue 31: the bare "no (valid) property" left a user guessing).
fn no_property_hint(model: &Model) -> String {
    if model.materials.is_empty() {
        "has no section and the model defines no material (a mesh such as Gmsh's holds none): \
         give --material E=…,nu=…,rho=… (and --thickness T for shell elements)"
            .into()
    } else {
        "has no section: no section or property card of the model covers it".into()
    }
}

/// Matrices of element `e` of `model` in the basic frame.
pub fn element_matrices(
    model: &Model,
    e: usize,
    spec: &AssemblySpec,
) -> Result<ElementMatrices, FeError> {
    let el = &model.elements[e];
    let fail = |message: String| FeError::Unsupported {
        source_file: model.element_origin(el.id),
        id: el.id,
        kind: el.kind,
        message,
    };
    let elem_err = |err: ElementError| FeError::Element {
        source_file: model.element_origin(el.id),
        id: el.id,
        kind: el.kind,
        err,
    };
    if el.nodes.len() != el.kind.node_count() || el.nodes.iter().any(|&n| n >= model.nodes.len()) {
        return Err(fail(format!(
            "has {} node indices, expected {} valid ones",
            el.nodes.len(),
            el.kind.node_count()
        )));
    }
    let prop = el
        .property
        .and_then(|p| model.properties.get(p))
        .ok_or_else(|| fail(no_property_hint(model)))?;
    let mat = model
        .materials
        .get(prop.material)
        .ok_or_else(|| fail(format!("property {} names a missing material", prop.id)))?;
    // material constants are the material's fault: name it
    let elem_err = |err: ElementError| {
        elem_err(match err {
            ElementError::BadConstants(s) => {
                ElementError::BadConstants(format!("material {} '{}': {s}", mat.id, mat.name))
            }
            e => e,
        })
    };
    let iso = Isotropic {
        e: mat.e,
        nu: mat.nu,
        g: mat.g,
        rho: mat.rho,
    };
    let lumped = spec.mass == MassKind::Lumped;
    if mat.plane_stress().is_some() && !matches!(prop.section, Section::Shell(_)) {
        return Err(fail(format!(
            "material {} '{}' is a plane-stress (shell) material (MAT8, MAT2, *ELASTIC, \
             TYPE=LAMINA): only shell elements take it",
            mat.id, mat.name
        )));
    }
    if el.kind.is_solid() && prop.section != Section::Solid {
        return Err(fail(format!(
            "solid element with non-solid property {}",
            prop.id
        )));
    }
    let n = &el.nodes;
    // A general D (orthotropic/anisotropic material): its solid kernel; the isotropic kernels
    // below only when there is none.
    let mut general = match mat.stiffness() {
        None => None,
        Some(d) if el.kind.is_solid() => {
            let x: Vec<Xyz> = n.iter().map(|&i| model.nodes[i].x).collect();
            let axes = el.property.and_then(|p| model.property_axes.get(&p));
            let k = super::elements::anisotropic::stiffness(
                el.kind,
                &x,
                model.params.solid_bubbles,
                model.params.ccx_solid_rules,
                d,
                axes,
            )
            .map_err(elem_err)?;
            Some(k.ok_or_else(|| {
                fail(format!(
                    "material {} '{}' is anisotropic and this element has no anisotropic \
                     formulation (C3D8R's hourglass control is isotropic): mesh with C3D8, \
                     C3D8I or C3D20R",
                    mat.id, mat.name
                ))
            })?)
        }
        Some(_) => {
            return Err(fail(format!(
                "material {} '{}' is anisotropic (*ELASTIC, TYPE=ORTHO/ENGINEERING \
                 CONSTANTS/ANISO, MAT9): only solid elements take it (beams, rods and shells \
                 take isotropic materials only; laminated shells are not supported)",
                mat.id, mat.name
            )))
        }
    };
    let isotropic = general.is_none();
    let mut k_or = |iso_k: &dyn Fn() -> Result<Vec<f64>, ElementError>| match general.take() {
        Some(k) => Ok(k),
        None => iso_k(),
    };
    let solid = |k: Vec<f64>, ms: Vec<f64>, nn: usize, quadratic: bool| -> ElementMatrices {
        let m = match (lumped, quadratic) {
            (false, _) => super::elements::expand_scalar_mass(&ms, nn),
            (true, false) => mass::diagonal_solid_mass(&mass::row_sum(&ms, nn)),
            (true, true) => mass::diagonal_solid_mass(&mass::hrz(&ms, nn)),
        };
        ElementMatrices::nodal(3, k, m)
    };
    let out = match el.kind {
        ElementKind::Tet4 => {
            let x = coords::<4>(model, n);
            solid(
                k_or(&|| tet4::stiffness(&x, &iso)).map_err(elem_err)?,
                if model.params.ccx_solid_rules {
                    tet4::scalar_mass_one_point(&x, iso.rho)
                } else {
                    tet4::scalar_mass(&x, iso.rho)
                }
                .map_err(elem_err)?,
                4,
                false,
            )
        }
        ElementKind::Tet10 => {
            let x = coords::<10>(model, n);
            // HRZ lumping uses the exact consistent diagonal (the 4-point one is a cruder estimate).
            let rule = if lumped {
                Tet10MassRule::Exact
            } else {
                spec.tet10_mass
            };
            solid(
                k_or(&|| tet10::stiffness(&x, &iso)).map_err(elem_err)?,
                tet10::scalar_mass(&x, iso.rho, rule).map_err(elem_err)?,
                10,
                true,
            )
        }
        // CalculiX 2.20's C3D8I (modes with mass, kept as interior dofs) in a consistent build
        ElementKind::Hex8 if isotropic && keeps_ccx_modes(model, e, spec) => {
            let x = coords::<8>(model, n);
            let (k, m) = solid_incompatible::hex8_ccx_matrices(&x, &iso).map_err(elem_err)?;
            ElementMatrices {
                dpn: 3,
                interior: solid_incompatible::HEX8_CCX_MODE_DOFS,
                k,
                m,
            }
        }
        ElementKind::Hex8 => {
            let x = coords::<8>(model, n);
            let k = k_or(&|| {
                if model.params.solid_bubbles {
                    solid_incompatible::hex8_stiffness(&x, &iso)
                } else {
                    hex8::stiffness(&x, &iso)
                }
            });
            solid(
                k.map_err(elem_err)?,
                hex8::scalar_mass(&x, iso.rho).map_err(elem_err)?,
                8,
                false,
            )
        }
        ElementKind::Hex8R => {
            let x = coords::<8>(model, n);
            solid(
                k_or(&|| hex8r::stiffness(&x, &iso)).map_err(elem_err)?,
                hex8r::scalar_mass(&x, iso.rho).map_err(elem_err)?,
                8,
                false,
            )
        }
        ElementKind::Hex20R if model.beam_bricks.contains_key(&e) => {
            let x = coords::<20>(model, n);
            let section = &model.beam_bricks[&e];
            if general.is_some() {
                return Err(fail(format!(
                    "material {} '{}' is anisotropic: a CalculiX beam expanded into a brick \
                     takes an isotropic material",
                    mat.id, mat.name
                )));
            }
            solid(
                hex20_beam::stiffness(&x, &iso, section).map_err(elem_err)?,
                hex20_beam::scalar_mass(&x, iso.rho, section).map_err(elem_err)?,
                20,
                true,
            )
        }
        ElementKind::Hex20 | ElementKind::Hex20R => {
            let x = coords::<20>(model, n);
            let reduced = el.kind == ElementKind::Hex20R;
            let mass = if model.params.ansys_solid_rules && !lumped {
                hex20::scalar_mass_irons14(&x, iso.rho)
            } else {
                hex20::scalar_mass(&x, iso.rho, reduced && !lumped)
            };
            solid(
                k_or(&|| hex20::stiffness(&x, &iso, reduced)).map_err(elem_err)?,
                mass.map_err(elem_err)?,
                20,
                true,
            )
        }
        ElementKind::Prism6 => {
            let x = coords::<6>(model, n);
            let (k, ms) = if model.params.solid_bubbles {
                (
                    k_or(&|| solid_incompatible::prism6_stiffness(&x, &iso)),
                    prism6::scalar_mass(&x, iso.rho),
                )
            } else if model.params.ccx_solid_rules {
                (
                    k_or(&|| prism6::stiffness_ccx(&x, &iso)),
                    prism6::scalar_mass_ccx(&x, iso.rho),
                )
            } else {
                (
                    k_or(&|| prism6::stiffness(&x, &iso)),
                    prism6::scalar_mass(&x, iso.rho),
                )
            };
            solid(k.map_err(elem_err)?, ms.map_err(elem_err)?, 6, false)
        }
        // C3D15 as CalculiX integrates it; no other format's 15-node wedge is formed yet
        ElementKind::Prism15 if model.params.ccx_solid_rules => {
            let x = coords::<15>(model, n);
            solid(
                k_or(&|| prism15::stiffness_ccx(&x, &iso)).map_err(elem_err)?,
                prism15::scalar_mass_ccx(&x, iso.rho).map_err(elem_err)?,
                15,
                true,
            )
        }
        ElementKind::Pyram5 => {
            let x = coords::<5>(model, n);
            solid(
                k_or(&|| pyram5::stiffness(&x, &iso)).map_err(elem_err)?,
                pyram5::scalar_mass(&x, iso.rho).map_err(elem_err)?,
                5,
                false,
            )
        }
        ElementKind::Pyram13 => {
            let x = coords::<13>(model, n);
            solid(
                k_or(&|| pyram13::stiffness(&x, &iso)).map_err(elem_err)?,
                pyram13::scalar_mass(&x, iso.rho).map_err(elem_err)?,
                13,
                true,
            )
        }
        ElementKind::Beam2 | ElementKind::Bar2 => {
            let Section::Beam(s) = &prop.section else {
                return Err(fail(format!(
                    "beam element with non-beam property {}",
                    prop.id
                )));
            };
            let grid_x = coords::<2>(model, n);
            let offsets = model.beam_offsets.get(&e).copied();
            if offsets.is_some() && lumped {
                return Err(fail(
                    "offsets WA/WB with lumped mass are not implemented (the lumped masses at \
                     the offset ends would couple the grids' translations and rotations); use \
                     consistent mass (PARAM,COUPMASS,1 or --mass consistent)"
                        .into(),
                ));
            }
            // The element runs between its offset ends (grid + W); rigid links join them below.
            let x = match offsets {
                Some(w) => [0, 1].map(|i| [0, 1, 2].map(|c| grid_x[i][c] + w[i][c])),
                None => grid_x,
            };
            let (v, iz, iy) = match el.orientation {
                Some(v) => {
                    let (v, iz, iy) =
                        beam::principal_orientation(&x, v, s.i1, s.i2, s.i12).map_err(elem_err)?;
                    (Some(v), iz, iy)
                }
                None => (None, s.i1, s.i2),
            };
            let p = BeamProps {
                area: s.area,
                iz,
                iy,
                j: s.j,
                // Nastran ignores K1, K2 when I12 ≠ 0 (QRG PBAR Remark 4).
                shear: if spec.beam == BeamTheory::Timoshenko && s.i12 == 0.0 {
                    s.shear_factors
                } else {
                    None
                },
                nsm: s.nsm,
            };
            let lumping = lumped.then_some(spec.beam_lumping.for_element(el.kind));
            let pins = model.beam_pins.get(&e).copied();
            let (k, m) = match (&s.taper, pins) {
                (None, None) => beam::matrices(&x, v, &iso, &p, lumping),
                (None, Some(pins)) => beam::matrices_pinned(&x, v, &iso, &p, lumping, pins),
                (Some(_), Some(_)) => {
                    return Err(fail(
                        "pin flags on a tapered beam are not implemented".into(),
                    ))
                }
                (Some(_), None) => {
                    let timoshenko = spec.beam == BeamTheory::Timoshenko;
                    let at = |xi: f64| {
                        let ([area, iz, iy, j, nsm], k) = s.at(xi);
                        let shear = k.filter(|_| timoshenko);
                        BeamProps {
                            area,
                            iz,
                            iy,
                            j,
                            shear,
                            nsm,
                        }
                    };
                    let breaks = s.breakpoints();
                    super::elements::tapered_beam::matrices(&x, v, &iso, &at, &breaks, lumping)
                }
            }
            .map_err(elem_err)?;
            let (k, m) = match offsets {
                Some(w) => (beam::offset(&k, &w), beam::offset(&m, &w)),
                None => (k, m),
            };
            ElementMatrices::nodal(6, k, m)
        }
        ElementKind::Rod2 => {
            let (area, j, nsm) = match &prop.section {
                Section::Rod { area, j, nsm } => (*area, *j, *nsm),
                _ => {
                    return Err(fail(format!(
                        "rod element with non-rod property {}",
                        prop.id
                    )))
                }
            };
            let (k, m) = rod::matrices(&coords::<2>(model, n), &iso, area, j, nsm, lumped)
                .map_err(elem_err)?;
            ElementMatrices::nodal(6, k, m)
        }
        ElementKind::Quad4 | ElementKind::Tri3 => {
            let Section::Shell(s) = &prop.section else {
                return Err(fail(format!(
                    "shell element with non-shell property {} (plane-stress/strain CPS/CPE \
                     elements are not supported)",
                    prop.id
                )));
            };
            let mut p = super::shell_section::shell_props(model, e, prop, s).map_err(fail)?;
            // Nastran lumps CQUAD4/CTRIA3 without rotary inertia (BeamLumping::Nastran doc).
            p.lumped_rotary = spec.beam_lumping != BeamLumping::Nastran;
            let drilling = model.drilling_membranes.contains(&e);
            if drilling && (p.general.is_some() || p.membrane.is_none()) {
                return Err(fail(format!(
                    "a CQUADR/CTRIAR needs a homogeneous section with a membrane (PSHELL MID1 of \
                     a MAT1); property {} is a laminate, plane-stress or has no membrane \
                     (not implemented for the drilling membrane)",
                    prop.id
                )));
            }
            let (k, m) = match (el.kind == ElementKind::Quad4, drilling) {
                (true, false) => quad4_shell::matrices(&coords::<4>(model, n), &p, lumped),
                (true, true) => quad4_shell::matrices_drilling(&coords::<4>(model, n), &p, lumped),
                (false, false) => tri3_shell::matrices(&coords::<3>(model, n), &p, lumped),
                (false, true) => tri3_shell::matrices_drilling(&coords::<3>(model, n), &p, lumped),
            }
            .map_err(elem_err)?;
            ElementMatrices::nodal(6, k, m)
        }
        ElementKind::Quad8 | ElementKind::Tri6 => {
            let Section::Shell(s) = &prop.section else {
                return Err(fail(format!(
                    "shell element with non-shell property {} (plane-stress/strain CPS/CPE \
                     elements are not supported)",
                    prop.id
                )));
            };
            let mut p = super::shell_section::shell_props(model, e, prop, s).map_err(fail)?;
            if p.general.is_some() {
                return Err(fail(format!(
                    "property {} is a laminate or plane-stress (PCOMP of several materials, \
                     MAT8, MAT2) section: the quadratic shells (CQUAD8/CTRIA6, S8/S8R/S6) take \
                     isotropic sections only; mesh the part with CQUAD4/CTRIA3 (S4/S3)",
                    prop.id
                )));
            }
            p.lumped_rotary = spec.beam_lumping != BeamLumping::Nastran;
            let nodal = model.shell_thickness.get(&e);
            let t = |a: usize| nodal.map_or(p.t, |t| t[a]);
            if nodal.is_some_and(|t| t.len() != n.len()) {
                return Err(fail("nodal thicknesses do not match the node count".into()));
            }
            let (k, m) = if el.kind == ElementKind::Quad8 {
                quad8_shell::matrices(&coords::<8>(model, n), &std::array::from_fn(t), &p, lumped)
            } else {
                tri6_shell::matrices(&coords::<6>(model, n), &std::array::from_fn(t), &p, lumped)
            }
            .map_err(elem_err)?;
            ElementMatrices::nodal(6, k, m)
        }
        other => {
            return Err(fail(format!(
                "{other:?} elements are not assembled (no element formulation yet)"
            )))
        }
    };
    Ok(out)
}

/// Rotate an element matrix into the nodes' displacement frames: A' = T A Tᵀ, T = diag(R_a)
/// (interior dofs after the nodal ones, if any, stay in the basic frame: T = I there).
pub(crate) fn to_frames(
    a: &mut [f64],
    nodes: &[usize],
    dpn: usize,
    frames: &[Option<[[f64; 3]; 3]>],
) {
    let nd = a.len().isqrt();
    let blocks: Vec<Option<&[[f64; 3]; 3]>> = nodes
        .iter()
        .flat_map(|&n| std::iter::repeat_n(frames[n].as_ref(), dpn / 3))
        .collect();
    // rows: A ← T A
    for (bi, r) in blocks.iter().enumerate() {
        let Some(r) = r else { continue };
        for col in 0..nd {
            let v: [f64; 3] = std::array::from_fn(|k| a[(3 * bi + k) * nd + col]);
            for i in 0..3 {
                a[(3 * bi + i) * nd + col] = r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2];
            }
        }
    }
    // columns: A ← A Tᵀ
    for (bj, r) in blocks.iter().enumerate() {
        let Some(r) = r else { continue };
        for row in 0..nd {
            let v: [f64; 3] = std::array::from_fn(|k| a[row * nd + 3 * bj + k]);
            for j in 0..3 {
                a[row * nd + 3 * bj + j] = r[j][0] * v[0] + r[j][1] * v[1] + r[j][2] * v[2];
            }
        }
    }
}

/// Assemble K and M of `model`.
pub fn assemble(model: &Model, spec: &AssemblySpec) -> Result<Assembled, FeError> {
    let mut dofs = DofMap::from_model(model)?;
    let elems: Vec<usize> = model
        .elements
        .iter()
        .enumerate()
        .filter(|(_, e)| e.property.is_some() || is_structural(e.kind))
        .map(|(i, _)| i)
        .collect();
    for &e in &elems {
        if keeps_ccx_modes(model, e, spec) {
            dofs.append_interior(e, solid_incompatible::HEX8_CCX_MODE_DOFS);
        }
    }
    let mut interior_blocks = Vec::with_capacity(dofs.interior.len());
    let connectors = super::connectors::connector_matrices(model)?;
    let conn: Vec<&[usize]> = (elems.iter())
        .map(|&e| model.elements[e].nodes.as_slice())
        .chain(connectors.iter().map(|c| c.nodes.as_slice()))
        .collect();
    if let Some(&e) = elems.iter().find(|&&e| {
        model.elements[e]
            .nodes
            .iter()
            .any(|&n| n >= model.nodes.len())
    }) {
        let el = &model.elements[e];
        return Err(FeError::BadReference {
            source_file: model.source.clone(),
            message: format!(
                "element {} refers to a node index beyond the {} nodes",
                el.id,
                model.nodes.len()
            ),
        });
    }
    let pattern = Pattern::build(&dofs, &conn);
    let nnz = pattern.nnz();
    let nn = model.nodes.len();
    let lumped = spec.mass == MassKind::Lumped;
    // Lumped M lives in the nodes' own diagonal blocks only (column-major count² per node).
    let mut moff = vec![0usize; nn + 1];
    for a in 0..nn {
        moff[a + 1] = moff[a] + usize::from(dofs.count[a]).pow(2);
    }
    let mut kv = vec![0.0f64; nnz];
    let mut mv = vec![0.0f64; if lumped { moff[nn] } else { nnz }];

    // Column ranges (by node) of roughly equal size, one per parallel part.
    let parts = (4 * rayon::current_num_threads()).max(1);
    let mut cuts = vec![0usize];
    for a in 0..nn {
        let end = pattern.base[a] + usize::from(dofs.count[a]) * pattern.col_len[a];
        if end * parts >= nnz * cuts.len() && cuts.len() < parts {
            cuts.push(a + 1);
        }
    }
    cuts.push(nn);
    cuts.dedup();
    let value_start = |a: usize| if a < nn { pattern.base[a] } else { nnz };
    let mass_start = |a: usize| if lumped { moff[a] } else { value_start(a) };

    const CHUNK: usize = 4096;
    for chunk in elems.chunks(CHUNK) {
        // every element's result first, then the first error in element order: rayon's
        // collect into a Result returns whichever error a thread met first, so a deck with
        // several bad elements named a different one from run to run
        let results: Vec<Result<ElementMatrices, FeError>> = chunk
            .par_iter()
            .map(|&e| {
                let mut em = element_matrices(model, e, spec)?;
                let nodes = &model.elements[e].nodes;
                if nodes.iter().any(|&n| dofs.frames[n].is_some()) {
                    to_frames(&mut em.k, nodes, em.dpn, &dofs.frames);
                    to_frames(&mut em.m, nodes, em.dpn, &dofs.frames);
                }
                Ok(em)
            })
            .collect();
        let mats = results.into_iter().collect::<Result<Vec<_>, FeError>>()?;
        for (&e, em) in chunk.iter().zip(&mats) {
            if let Some(block) = interior_block(model, &dofs, e, em)? {
                interior_blocks.push(block);
            }
        }
        // Split the value arrays at the cuts and scatter each range in parallel.
        let mut kparts = Vec::new();
        let mut mparts = Vec::new();
        let (mut krest, mut mrest): (&mut [f64], &mut [f64]) = (&mut kv, &mut mv);
        for w in cuts.windows(2) {
            let (kh, kt) = krest.split_at_mut(value_start(w[1]) - value_start(w[0]));
            let (mh, mt) = mrest.split_at_mut(mass_start(w[1]) - mass_start(w[0]));
            kparts.push((w[0], w[1], kh));
            mparts.push(mh);
            krest = kt;
            mrest = mt;
        }
        kparts
            .into_par_iter()
            .zip(mparts)
            .for_each(|((lo, hi, kp), mp)| {
                let (koff, moff0) = (value_start(lo), mass_start(lo));
                for (&e, em) in chunk.iter().zip(&mats) {
                    let nodes = &model.elements[e].nodes;
                    let (dpn, nd) = (em.dpn, em.size());
                    for (la, &a) in nodes.iter().enumerate() {
                        if a < lo || a >= hi {
                            continue;
                        }
                        let na = usize::from(dofs.count[a]);
                        for c in 0..dpn.min(na) {
                            let col = la * dpn + c;
                            for (lb, &b) in nodes.iter().enumerate() {
                                let p = pattern.block(a, c, b) - koff;
                                let rows = dpn.min(usize::from(dofs.count[b]));
                                for r in 0..rows {
                                    kp[p + r] += em.k[(lb * dpn + r) * nd + col];
                                }
                                if !lumped {
                                    for r in 0..rows {
                                        mp[p + r] += em.m[(lb * dpn + r) * nd + col];
                                    }
                                } else if b == a {
                                    let q = moff[a] - moff0 + c * na;
                                    for r in 0..rows {
                                        mp[q + r] += em.m[(lb * dpn + r) * nd + col];
                                    }
                                }
                            }
                        }
                    }
                }
            });
    }

    for pm in &model.point_masses {
        let a = pm.node;
        let mut m6: Vec<f64> = mass::point_mass_matrix(pm)
            .iter()
            .flatten()
            .copied()
            .collect();
        if dofs.frames[a].is_some() {
            to_frames(&mut m6, &[a], 6, &dofs.frames);
        }
        let na = usize::from(dofs.count[a]);
        for c in 0..na {
            let p = if lumped {
                moff[a] + c * na
            } else {
                pattern.block(a, c, a)
            };
            for r in 0..na {
                mv[p + r] += m6[r * 6 + c];
            }
        }
    }

    for c in connectors {
        scatter_connector(model, &dofs, &pattern, &moff, lumped, c, &mut kv, &mut mv)?;
    }

    let n = dofs.n_dofs;
    let Pattern {
        mut col_ptr,
        mut row_idx,
        ..
    } = pattern;
    if !interior_blocks.is_empty() {
        (col_ptr, row_idx, kv, mv) =
            with_interior(&dofs, (&col_ptr, &row_idx), (&kv, &mv), &interior_blocks);
    }
    let m = match spec.mass {
        MassKind::Consistent => {
            let sym =
                SymbolicSparseColMat::new_checked(n, n, col_ptr.clone(), None, row_idx.clone());
            SparseColMat::new(sym, mv)
        }
        MassKind::Lumped => {
            // Node blocks as CSC: column (a, c) holds rows first[a]..first[a] + count[a].
            let mut cp = vec![0usize];
            let mut ri = Vec::with_capacity(mv.len());
            for a in 0..nn {
                let na = usize::from(dofs.count[a]);
                for _ in 0..na {
                    ri.extend((0..na).map(|r| dofs.first[a] + r));
                    cp.push(ri.len());
                }
            }
            drop_zeros(n, &cp, &ri, &mv)
        }
    };
    let k = SparseColMat::new(
        SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx),
        kv,
    );
    Ok(Assembled { dofs, k, m })
}

/// Add one connector's matrices ([`super::connectors`]) into the values of K (`kv`, full
/// pattern) and M (`mv`: node blocks when `lumped`, else the full pattern). A coupling mass
/// between two nodes has no place in a lumped (node-block) M: an error naming it.
#[allow(clippy::too_many_arguments)]
fn scatter_connector(
    model: &Model,
    dofs: &DofMap,
    pattern: &Pattern,
    moff: &[usize],
    lumped: bool,
    mut c: super::connectors::ConnectorMatrices,
    kv: &mut [f64],
    mv: &mut [f64],
) -> Result<(), FeError> {
    if c.basic && c.nodes.iter().any(|&n| dofs.frames[n].is_some()) {
        to_frames(&mut c.k, &c.nodes, 6, &dofs.frames);
        to_frames(&mut c.m, &c.nodes, 6, &dofs.frames);
    }
    let nd = 6 * c.nodes.len();
    let fail = |message: String| FeError::BadReference {
        source_file: model.source.clone(),
        message: format!("{}: {message}", c.what),
    };
    for (la, &a) in c.nodes.iter().enumerate() {
        let na = usize::from(dofs.count[a]);
        for col in 0..6 {
            for (lb, &b) in c.nodes.iter().enumerate() {
                let nb = usize::from(dofs.count[b]);
                for r in 0..6 {
                    let (kij, mij) = (
                        c.k[(6 * lb + r) * nd + 6 * la + col],
                        c.m[(6 * lb + r) * nd + 6 * la + col],
                    );
                    if kij == 0.0 && mij == 0.0 {
                        continue;
                    }
                    if col >= na || r >= nb {
                        return Err(fail(format!(
                            "acts on a component node {} or {} does not have",
                            model.nodes[a].id, model.nodes[b].id
                        )));
                    }
                    let p = pattern.block(a, col, b) + r;
                    kv[p] += kij;
                    if !lumped {
                        mv[p] += mij;
                    } else if a == b {
                        mv[moff[a] + col * na + r] += mij;
                    } else if mij != 0.0 {
                        return Err(fail(format!(
                            "couples the motion of nodes {} and {} by mass, which a lumped \
                             (node-block) mass matrix cannot hold; ground one end or use \
                             consistent mass (--mass consistent)",
                            model.nodes[a].id, model.nodes[b].id
                        )));
                    }
                }
            }
        }
    }
    Ok(())
}

/// Copy a CSC matrix without its explicit zeros (diagonal entries are always kept).
pub fn drop_zeros(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
    val: &[f64],
) -> SparseColMat<usize, f64> {
    let mut cp = Vec::with_capacity(n + 1);
    let (mut ri, mut vv) = (Vec::new(), Vec::new());
    cp.push(0);
    for j in 0..n {
        for p in col_ptr[j]..col_ptr[j + 1] {
            if val[p] != 0.0 || row_idx[p] == j {
                ri.push(row_idx[p]);
                vv.push(val[p]);
            }
        }
        cp.push(ri.len());
    }
    SparseColMat::new(SymbolicSparseColMat::new_checked(n, n, cp, None, ri), vv)
}
