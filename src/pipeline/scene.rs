//! The scene's loads as the command line gives them (`--gravity`, `--load`,
//! `--residual-vectors`) and their resolution against a model into named [`Load`]s: the deck's
//! selected load sets, then the CLI's own, in that order (the order of the file's modal loads).
//!
//! * `--gravity 0,0,-9.81` → load `GRAVITY` (acceleration, basic frame).
//! * `--load NAME:NODE:FX,FY,FZ[,MX,MY,MZ]` → a force (and moment) at node id NODE.
//! * `--load NAME:SET:P` → a uniform pressure P on the free faces of the solid elements (and the
//!   shell elements) whose nodes all lie in node set SET; positive P pushes into the solid
//!   (against the outward normal), on a shell against its normal (the Abaqus convention).
//! * `--load NAME` → a load set of the deck by name (e.g. `LOAD_20`, not selected by the case
//!   control).

use std::collections::HashMap;

use faer::Mat;
use flexbody_reader as file;

use crate::model::load::{face_nodes, solid_faces};
use crate::model::{ElementKind, Load, LoadPart, Model, NodeIndex};
use crate::pipeline::options::OptionError;
use crate::reduce::residual::ResidualKind;

pub use crate::pipeline::SceneSpec;

fn bad(option: &'static str, value: &str, expected: &str) -> OptionError {
    OptionError {
        option,
        value: value.to_string(),
        expected: expected.to_string(),
    }
}

/// `--residual-vectors` value: `loads`, `interface` or `both`.
pub fn parse_residual_vectors(s: &str) -> Result<ResidualKind, OptionError> {
    match s.trim().to_ascii_lowercase().as_str() {
        "loads" => Ok(ResidualKind::Loads),
        "interface" => Ok(ResidualKind::Interface),
        "both" => Ok(ResidualKind::Both),
        _ => Err(bad("residual-vectors", s, "loads, interface or both")),
    }
}

/// `--select` value: `participation:ε` with 0 < ε (e.g. `participation:0.01`).
pub fn parse_select(s: &str) -> Result<f64, OptionError> {
    let expected = "participation:EPS with EPS > 0, e.g. participation:0.01";
    let (kind, eps) = s
        .split_once(':')
        .ok_or_else(|| bad("select", s, expected))?;
    if !kind.trim().eq_ignore_ascii_case("participation") {
        return Err(bad("select", s, expected));
    }
    eps.trim()
        .parse::<f64>()
        .ok()
        .filter(|e| e.is_finite() && *e > 0.0)
        .ok_or_else(|| bad("select", s, expected))
}

/// `--select` as the recipe records it.
pub fn select_text(eps: f64) -> String {
    format!("participation:{eps}")
}

fn reals(option: &'static str, whole: &str, s: &str) -> Result<Vec<f64>, OptionError> {
    s.split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(option, whole, &format!("'{v}' is not a finite number")))
        })
        .collect()
}

/// `--gravity ax,ay,az` → acceleration.
pub fn parse_gravity(s: &str) -> Result<[f64; 3], OptionError> {
    let v = reals("gravity", s, s)?;
    match v[..] {
        [a, b, c] if [a, b, c] != [0.0; 3] => Ok([a, b, c]),
        _ => Err(bad(
            "gravity",
            s,
            "three components of a non-zero acceleration, e.g. 0,0,-9.81",
        )),
    }
}

/// Free faces (corners outward, then mid-side nodes) of the solids, and the shell faces, whose
/// nodes all lie in `set`; with the traction a pressure `p` gives each (module doc).
fn pressure_faces(model: &Model, set: &[NodeIndex], p: f64) -> Vec<LoadPart> {
    let mut inset = vec![false; model.nodes.len()];
    for &n in set {
        inset[n] = true;
    }
    let key = |nodes: &[NodeIndex]| {
        let mut k = nodes.to_vec();
        k.sort_unstable();
        k
    };
    let mut count: HashMap<Vec<NodeIndex>, u32> = HashMap::new();
    for e in &model.elements {
        if let Some((faces, _)) = solid_faces(e.kind) {
            for f in faces {
                let c: Vec<NodeIndex> = f.iter().map(|&i| e.nodes[i]).collect();
                *count.entry(key(&c)).or_insert(0) += 1;
            }
        }
    }
    let mut parts = Vec::new();
    for e in &model.elements {
        if let Some((faces, edges)) = solid_faces(e.kind) {
            for f in faces {
                let c: Vec<NodeIndex> = f.iter().map(|&i| e.nodes[i]).collect();
                if count[&key(&c)] != 1 {
                    continue;
                }
                if let Some(nodes) = face_nodes(&e.nodes, f, edges) {
                    if nodes.iter().all(|&n| inset[n]) {
                        parts.push(LoadPart::Surface {
                            nodes,
                            traction: -p,
                            element: e.id,
                        });
                    }
                }
            }
        } else if matches!(
            e.kind,
            ElementKind::Quad4 | ElementKind::Tri3 | ElementKind::Quad8 | ElementKind::Tri6
        ) && e.property.is_some()
            && e.nodes.iter().all(|&n| inset[n])
        {
            parts.push(LoadPart::Surface {
                nodes: e.nodes.clone(),
                traction: -p,
                element: e.id,
            });
        }
    }
    parts
}

/// The scene's loads for `model` (module doc): the deck's selected load sets, `--gravity`, then
/// each `--load` in order. Names are unique.
pub fn scene_loads(model: &Model, scene: &SceneSpec) -> Result<Vec<Load>, OptionError> {
    // Selected deck loads the tool cannot read are left out (the import warned about them).
    let mut loads: Vec<Load> = model
        .loads
        .iter()
        .filter(|l| l.selected && l.problem.is_none())
        .cloned()
        .collect();
    if let Some(g) = &scene.gravity {
        loads.push(Load {
            name: "GRAVITY".into(),
            source: format!("--gravity {g}"),
            selected: true,
            parts: vec![LoadPart::Gravity {
                accel: parse_gravity(g)?,
            }],
            problem: None,
        });
    }
    let by_id = model.node_index_by_id();
    for entry in &scene.loads {
        let fields: Vec<&str> = entry.splitn(3, ':').map(str::trim).collect();
        let name = fields[0].to_string();
        if name.is_empty() {
            return Err(bad(
                "load",
                entry,
                "NAME:NODE:FX,FY,FZ[,MX,MY,MZ], NAME:SET:PRESSURE or a deck load set's NAME",
            ));
        }
        if loads.iter().any(|l| l.name.eq_ignore_ascii_case(&name)) {
            return Err(bad("load", entry, &format!("a load named {name} is already in the scene (the deck's selected sets and --gravity's GRAVITY count too)")));
        }
        let load = match fields[..] {
            [_] => {
                let mut l = model
                    .loads
                    .iter()
                    .find(|l| l.name.eq_ignore_ascii_case(&name))
                    .cloned()
                    .ok_or_else(|| {
                        let names: Vec<&str> =
                            model.loads.iter().map(|l| l.name.as_str()).collect();
                        bad(
                            "load",
                            entry,
                            &format!(
                                "no load set of that name in the deck (it has: {})",
                                if names.is_empty() {
                                    "none".to_string()
                                } else {
                                    names.join(", ")
                                }
                            ),
                        )
                    })?;
                if let Some(p) = &l.problem {
                    return Err(bad(
                        "load",
                        entry,
                        &format!("the deck's load {name} cannot be used: {p}"),
                    ));
                }
                l.selected = true;
                l
            }
            [_, at, values] => {
                let v = reals("load", entry, values)?;
                if let Ok(id) = at.parse::<u64>() {
                    let node = *by_id
                        .get(&id)
                        .ok_or_else(|| bad("load", entry, &format!("node {id} does not exist")))?;
                    let mut values = [0.0; 6];
                    match v.len() {
                        3 | 6 => values[..v.len()].copy_from_slice(&v),
                        _ => {
                            return Err(bad(
                                "load",
                                entry,
                                "3 force components FX,FY,FZ or 6 with moments MX,MY,MZ",
                            ))
                        }
                    }
                    Load {
                        name: name.clone(),
                        source: format!("--load {entry}"),
                        selected: true,
                        parts: vec![LoadPart::Nodal { node, values }],
                        problem: None,
                    }
                } else {
                    let set = model
                        .node_sets
                        .iter()
                        .find(|(k, _)| k.eq_ignore_ascii_case(at))
                        .map(|(_, v)| v)
                        .ok_or_else(|| {
                            bad(
                                "load",
                                entry,
                                &format!("'{at}' is neither a node id nor a node set of the model"),
                            )
                        })?;
                    let [p] = v[..] else {
                        return Err(bad(
                            "load",
                            entry,
                            &format!(
                                "one pressure value after a node set ({at} is a node set; a force \
                                 at an interface goes on its centre node's id, which the build \
                                 report and `inspect` list)"
                            ),
                        ));
                    };
                    let parts = pressure_faces(model, set, p);
                    if parts.is_empty() {
                        return Err(bad(
                            "load",
                            entry,
                            &format!(
                                "node set {at} covers no free solid face and no shell element"
                            ),
                        ));
                    }
                    Load {
                        name: name.clone(),
                        source: format!("--load {entry}"),
                        selected: true,
                        parts,
                        problem: None,
                    }
                }
            }
            _ => {
                return Err(bad(
                    "load",
                    entry,
                    "NAME:NODE:FX,FY,FZ[,MX,MY,MZ], NAME:SET:PRESSURE or a deck load set's NAME",
                ))
            }
        };
        loads.push(load);
    }
    Ok(loads)
}

/// The scene's loads and their vectors on the independent dofs of the build (f_r = Tᵀ f).
#[derive(Debug, Clone)]
pub struct SceneLoads {
    /// The loads, in order.
    pub loads: Vec<Load>,
    /// n_r × loads.len().
    pub f: Mat<f64>,
}

/// [`scene_loads`] assembled (`fe::loads`) with the build's mass and reduced by its T. The outer
/// error is a bad option, the inner one an assembly error.
pub fn reduced_loads(
    scene: &SceneSpec,
    model: &Model,
    assembled: &crate::fe::Assembled,
    reduced: &crate::fe::Reduced,
) -> Result<Result<SceneLoads, crate::fe::FeError>, OptionError> {
    let loads = scene_loads(model, scene)?;
    if loads.is_empty() {
        return Ok(Ok(SceneLoads {
            loads,
            f: Mat::zeros(reduced.k.nrows(), 0),
        }));
    }
    Ok(
        crate::fe::loads::load_vectors(model, &assembled.dofs, &assembled.m, &loads).map(|f| {
            SceneLoads {
                f: crate::fe::loads::reduce_loads(&reduced.t, &f),
                loads,
            }
        }),
    )
}

/// The loads whose static responses become residual vectors: the scene's loads (`loads`, in
/// order), then unit loads at the interface dofs (`interface`), or both; column j is
/// `Residual { load: j }`.
pub fn residual_loads(
    kind: ResidualKind,
    scene: &SceneLoads,
    interface_dofs: &[usize],
    n: usize,
) -> Result<Mat<f64>, String> {
    let with_loads = kind != ResidualKind::Interface;
    let with_interface = kind != ResidualKind::Loads;
    if with_loads && scene.loads.is_empty() {
        return Err("--residual-vectors loads: the scene has no loads (give --gravity or --load, or a deck with LOAD = n / *CLOAD in its step)".into());
    }
    if with_interface && interface_dofs.is_empty() {
        return Err(
            "--residual-vectors interface: the build has no interface dofs (give --interface)"
                .into(),
        );
    }
    let nl = if with_loads { scene.loads.len() } else { 0 };
    let ni = if with_interface {
        interface_dofs.len()
    } else {
        0
    };
    let mut f = Mat::<f64>::zeros(n, nl + ni);
    for j in 0..nl {
        f.as_mut().col_mut(j).copy_from(scene.f.col(j));
    }
    for (c, &d) in interface_dofs.iter().enumerate().take(ni) {
        f[(d, nl + c)] = 1.0;
    }
    Ok(f)
}

/// `--select participation:ε` on a candidate set (module doc of
/// [`crate::reduce::participation`]): the scene's loads and unit loads at the interface dofs
/// rank the modes over [0, `band_hz`]; a load is corrected when `residual` will add its static
/// response. The static compliances come from the same inertia-relief solve as the residual
/// vectors.
#[allow(clippy::too_many_arguments)]
pub fn select_by_scene(
    k: &crate::solve::SparseColMat<usize, f64>,
    m: &crate::solve::SparseColMat<usize, f64>,
    set: crate::reduce::ModeSet,
    scene: &SceneLoads,
    interface_dofs: &[usize],
    residual: Option<ResidualKind>,
    epsilon: f64,
    band_hz: f64,
    eig: &crate::solve::EigenSpec,
) -> Result<
    (
        crate::reduce::ModeSet,
        crate::reduce::participation::SelectionReport,
    ),
    crate::reduce::ReduceError,
> {
    use crate::reduce::participation::{select_by_participation, Participation, DEFAULT_DAMPING};
    let n = k.nrows();
    let (nl, ni) = (scene.loads.len(), interface_dofs.len());
    if nl + ni == 0 {
        return Err(crate::reduce::ReduceError::Dofs {
            what: "--select participation",
            detail: "the scene has no loads and the build no interface: give --gravity, --load \
                     or --interface"
                .into(),
        });
    }
    let mut f = Mat::<f64>::zeros(n, nl + ni);
    for j in 0..nl {
        f.as_mut().col_mut(j).copy_from(scene.f.col(j));
    }
    for (c, &d) in interface_dofs.iter().enumerate() {
        f[(d, nl + c)] = 1.0;
    }
    let _par = crate::solve::ParGuard::new(eig.par);
    let r = crate::reduce::residual::static_responses(k, m, &set, &f, eig)?;
    let compliance: Vec<f64> = (0..nl + ni)
        .map(|j| (0..n).map(|i| f[(i, j)] * r[(i, j)]).sum::<f64>().max(0.0))
        .collect();
    let corrected: Vec<bool> = (0..nl + ni)
        .map(|j| match residual {
            None => false,
            Some(ResidualKind::Both) => true,
            Some(ResidualKind::Loads) => j < nl,
            Some(ResidualKind::Interface) => j >= nl,
        })
        .collect();
    select_by_participation(
        set,
        &f,
        &compliance,
        &corrected,
        &Participation {
            epsilon,
            band_hz,
            damping: DEFAULT_DAMPING,
        },
    )
}

/// The build-report note for residual vectors removed as dependent.
pub fn removed_note(rep: &crate::reduce::residual::ResidualReport, scene: &SceneLoads) -> String {
    let name = |j: usize| match scene.loads.get(j) {
        Some(l) => l.name.clone(),
        None => format!("interface unit load {}", j - scene.loads.len() + 1),
    };
    let mut parts = Vec::new();
    if !rep.removed.is_empty() {
        let names: Vec<String> = (rep.removed.iter())
            .map(|&(j, rem)| format!("{} (remaining {rem:.1e})", name(j)))
            .collect();
        parts.push(format!(
            "residual vectors removed as dependent (their static response is already in the \
             basis): {}",
            names.join(", ")
        ));
    }
    if !rep.no_response.is_empty() {
        let names: Vec<String> = rep.no_response.iter().map(|&j| name(j)).collect();
        parts.push(format!(
            "no residual vector for {} (zero static response: the body's inertia balances it, \
             or the held dofs take it)",
            names.join(", ")
        ));
    }
    parts.join("; ")
}

/// `modal_loads.bin`: Φᵀf_r per scene load (= Φ_physᵀ f_phys, since f_r = Tᵀf and Φ_phys = TΦ)
/// and the residual origin per mode; `None` without loads and residual vectors.
pub fn modal_loads(scene: &SceneLoads, set: &crate::reduce::ModeSet) -> Option<file::ModalLoads> {
    use crate::reduce::ModeLabel;
    let any_residual = set.diagnostics.residual_vectors > 0;
    if scene.loads.is_empty() && !any_residual {
        return None;
    }
    let g = set.phi.transpose() * &scene.f;
    Some(file::ModalLoads {
        loads: scene
            .loads
            .iter()
            .enumerate()
            .map(|(q, l)| file::ModalLoad {
                name: l.name.clone(),
                source: l.source.clone(),
                values: (0..set.len()).map(|j| g[(j, q)]).collect(),
            })
            .collect(),
        residual: if any_residual {
            set.labels
                .iter()
                .map(|l| u8::from(matches!(l, ModeLabel::Residual { .. })))
                .collect()
        } else {
            vec![]
        },
    })
}

/// Whether the basis holds residual vectors (`modal_loads.bin`'s `residual` is non-empty,
/// SPEC §5.14): its modes are then not all eigenvectors of the model, even for the
/// normal-modes method — also when no mode's dominant origin is a residual vector (a static
/// response mostly in the span of the modes mixes into them).
pub fn has_residual_vectors(body: &file::ReducedBody) -> bool {
    body.modal_loads
        .as_ref()
        .is_some_and(|m| !m.residual.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_parse_and_refuse() {
        assert_eq!(parse_gravity("0,0,-9.81").unwrap(), [0.0, 0.0, -9.81]);
        assert!(parse_gravity("0,0").is_err());
        assert!(parse_gravity("0,0,0").is_err());
        assert!(parse_gravity("0,x,1").is_err());
        assert_eq!(parse_residual_vectors("Both").unwrap(), ResidualKind::Both);
        assert!(parse_residual_vectors("all").is_err());
        assert_eq!(parse_select("participation:0.01").unwrap(), 0.01);
        assert_eq!(parse_select("Participation: 1e-3").unwrap(), 1e-3);
        assert!(parse_select("participation:0").is_err());
        assert!(parse_select("participation").is_err());
        assert!(parse_select("count:3").is_err());
    }
}
