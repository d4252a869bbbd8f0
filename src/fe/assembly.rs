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
pub use super::elements::element::{AssemblySpec, BeamTheory, ElementMatrices};
use super::elements::element::{ElementInput, MatricesError};
pub use super::elements::solid_incompatible::keeps_ccx_modes;
use super::elements::{kinds, solid_incompatible, ElementError, Isotropic, Xyz};
use super::interior::{interior_block, with_interior};
use super::mass::{self, MassKind};
use super::pattern::Pattern;
use super::FeError;
use crate::model::{ElementKind, Model, Section};

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

/// Does the assembler form matrices for this element (solids, beams, rods with a property)?
pub fn is_structural(kind: ElementKind) -> bool {
    kind.is_solid()
        || matches!(
            kind,
            ElementKind::Beam2
                | ElementKind::Bar2
                | ElementKind::Beam2Linear
                | ElementKind::Beam3Quadratic
                | ElementKind::Beam4Cubic
                | ElementKind::Rod2
        )
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
    let general = match mat.stiffness() {
        None => None,
        Some(d) if el.kind.is_solid() => {
            let x: Vec<Xyz> = n.iter().map(|&i| model.nodes[i].x).collect();
            let axes = el.property.and_then(|p| model.property_axes.get(&p));
            let k = super::elements::anisotropic::stiffness(
                el.kind,
                &x,
                super::elements::element::SolidRules::of(&model.params),
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
    let input = ElementInput {
        model,
        index: e,
        nodes: n,
        kind: el.kind,
        property: prop,
        material: mat,
        iso,
        spec,
        general,
    };
    kinds::element(el.kind)
        .matrices(&input)
        .map_err(|err| match err {
            MatricesError::Unsupported(message) => fail(message),
            MatricesError::Element(err) => elem_err(err),
        })
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
