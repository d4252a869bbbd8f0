//! A Nastran deck's lumped quadratic solids (issue 44 b). MSC Nastran's lumped mass of
//! CTETRA(10), CPENTA(15), CHEXA(20) and CPYRAM(13) follows a rule MSC does not publish; the
//! build lumps them by HRZ (`fe::mass`), which on coarse meshes differs from MSC's by several
//! per cent. So that the difference is measured on the user's own mesh rather than guessed, the
//! warning gives the first elastic frequency of the mesh, under the build's constraints, with
//! the lumped mass and with the consistent one: one more assembly (consistent mass) and two
//! eigen solves of the lowest [`MODES`] modes, on meshes of at most [`DOF_LIMIT`] independent
//! dofs; a larger mesh gets the warning without the figures. `--mass consistent` (or
//! `PARAM,COUPMASS,1`) builds with the consistent mass.

use crate::fe::{assemble, AssemblySpec, MassKind};
use crate::model::ElementKind;
use crate::pipeline::plan::Plan;
use crate::pipeline::stages::constraints::eliminate_constraints;
use crate::pipeline::stages::Constrained;
use crate::pipeline::stages::WithInterfaces;
use crate::solve::{hz, is_flexible, lowest_modes, trace_ratio, EigenSpec, SparseColMat};

/// Largest system (independent dofs) the two extra eigen solves are made on.
pub const DOF_LIMIT: usize = 30_000;

/// Modes solved for in each mass: room for six rigid motions and the first elastic mode.
pub const MODES: usize = 12;

/// The number of quadratic solids (midside nodes) a Nastran deck lumps in this build; 0 when
/// the deck is not Nastran or the mass is consistent.
pub fn lumped_quadratic_solids(plan: &Plan, interfaced: &WithInterfaces) -> usize {
    let model = &interfaced.model;
    if !model.params.nastran_deck || plan.assembly.mass != MassKind::Lumped {
        return 0;
    }
    let quadratic = |k: ElementKind| {
        matches!(
            k,
            ElementKind::Tet10 | ElementKind::Hex20 | ElementKind::Prism15 | ElementKind::Pyram13
        )
    };
    model.elements.iter().filter(|e| quadratic(e.kind)).count()
}

/// The first eigenvalue above the rigid-body threshold (10⁻⁸ of the system's K/M scale, as the
/// eigen solver's own), in Hz; `None` when the lowest [`MODES`] are all rigid.
fn first_elastic_hz(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    eigen: &EigenSpec,
) -> Result<Option<f64>, String> {
    let n = k.nrows();
    let spec = EigenSpec {
        count: MODES.min(n),
        upper: None,
        verify_band: false,
        ..eigen.clone()
    };
    let scale = trace_ratio(k, m);
    let modes = lowest_modes(k, m, &spec).map_err(|e| e.to_string())?;
    Ok(modes
        .eigenvalues
        .iter()
        .find(|&&l| is_flexible(l, scale))
        .map(|&l| hz(l)))
}

/// The first elastic frequency with the build's lumped mass and with the consistent mass.
fn both_masses(
    plan: &Plan,
    interfaced: &WithInterfaces,
    constrained: &Constrained,
) -> Result<(Option<f64>, Option<f64>), String> {
    let lumped = first_elastic_hz(&constrained.reduced.k, &constrained.reduced.m, &plan.eigen)?;
    let consistent_spec = AssemblySpec {
        mass: MassKind::Consistent,
        ..plan.assembly
    };
    let assembled = assemble(&interfaced.model, &consistent_spec).map_err(|e| e.to_string())?;
    let reduced = eliminate_constraints(interfaced, &assembled).map_err(|e| e.to_string())?;
    let consistent = first_elastic_hz(&reduced.k, &reduced.m, &plan.eigen)?;
    Ok((lumped, consistent))
}

/// The warning for a Nastran deck whose quadratic solids are lumped (module doc); `None` when
/// there are none. Called before a preload changes K.
pub fn quadratic_lumping_warning(
    plan: &Plan,
    interfaced: &WithInterfaces,
    constrained: &Constrained,
) -> Option<String> {
    let count = lumped_quadratic_solids(plan, interfaced);
    if count == 0 {
        return None;
    }
    let head = format!(
        "mass: the {count} CTETRA/CPENTA/CHEXA/CPYRAM with midside grids are lumped by HRZ (the \
         consistent diagonal scaled to the element mass, the rule Autodesk Nastran documents for \
         PARAM,COUPMASS < 0); MSC Nastran lumps them by a rule it does not publish, and the two \
         differ on coarse meshes"
    );
    let tail = "--mass consistent (or PARAM,COUPMASS,1) builds with the consistent mass";
    let n = constrained.reduced.k.nrows();
    if n > DOF_LIMIT {
        return Some(format!(
            "{head}; the mesh's {n} dofs are more than the {DOF_LIMIT} on which the first \
             frequency is compared with both masses; {tail}"
        ));
    }
    Some(match both_masses(plan, interfaced, constrained) {
        Ok((Some(l), Some(c))) => format!(
            "{head}: the first elastic frequency of this mesh is {l:.6} Hz with this lumped mass \
             and {c:.6} Hz with the consistent mass ({:+.2} %); {tail}",
            100.0 * (l / c - 1.0)
        ),
        Ok(_) => format!(
            "{head}; the lowest {MODES} modes of this mesh are rigid, no elastic frequency to \
             compare; {tail}"
        ),
        Err(e) => {
            format!("{head}; comparing the first frequency with both masses failed: {e}; {tail}")
        }
    })
}
