//! exudyn export: the NPZ that `exudyn.FEM.ObjectFFRFreducedOrderInterface.LoadFromFile`
//! reads (its `SaveToFile` NPZ layout, fileVersion 1), so that `AddObjectFFRFreducedOrder`
//! builds an `ObjectFFRFreducedOrder` from a `.flexbody` file without the FE data.
//!
//! exudyn's inertia terms are the file's invariants with exudyn's signs: its x̃ᵀ is the spec's
//! −x̃, so (flexible modes j, k; a, b = x y z)
//!
//! ```text
//! mPhitTPsi[a][j]               =  I3[a][j]
//! mXRefTildePsi[a][j]           = −I4[a][j]
//! mPsiTildePsi[3j+a][k]         = −I5[j][a][k]
//! massMatrixReduced[j][k]       =  I6[j][k]
//! inertiaLocal                  =  I7
//! mXRefTildePsiTilde[a][3j+b]   = −I8[j][a][b]
//! mPsiTildePsiTilde[3j+a][3k+b] = −I9[j][k][a][b]
//! mPhitTPsiTilde[a][3j+b]       =  skew(I3[:, j])[a][b]
//! ```
//!
//! Only flexible modes are written (exudyn's rigid motion is its floating frame); they are
//! picked by label, not by ω². Units are the file's (exudyn has none of its own).
use std::path::Path;

use flexbody_reader::{Face, FieldShapes, ReducedBody};

use super::npz::{npz_bytes, NpyValue, PyValue};
use super::{flexible_modes, write_atomic, ExportError, ExportSummary};

/// exudyn's stress component order xx yy zz yz xz xy, as indices into the file's
/// xx yy zz xy yz zx.
const EXUDYN_FROM_FILE_COMPONENT: [usize; 6] = [0, 1, 2, 4, 5, 3];

/// The rigid-body node type the NPZ names (exudyn's default for this interface).
const RIGID_BODY_NODE_TYPE: &str = "NodeType.RotationEulerParameters";

/// Writes the exudyn NPZ of `body` to `path` (temp file + rename).
pub fn export_exudyn(body: &ReducedBody, path: &Path) -> Result<ExportSummary, ExportError> {
    let (bytes, summary) = exudyn_npz(body)?;
    write_atomic(path, &bytes)?;
    Ok(summary)
}

fn unsupported(reason: impl Into<String>) -> ExportError {
    ExportError::Unsupported {
        target: "exudyn",
        reason: reason.into(),
    }
}

fn f64s(shape: Vec<usize>, data: Vec<f64>) -> NpyValue {
    NpyValue::F64 { shape, data }
}

fn skew(v: [f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]
}

/// The NPZ bytes and the summary (no file written).
pub fn exudyn_npz(body: &ReducedBody) -> Result<(Vec<u8>, ExportSummary), ExportError> {
    let inv = &body.invariants;
    if !inv.mask.iter().all(|&m| m) {
        let missing: Vec<String> = (0..9)
            .filter(|&k| !inv.mask[k])
            .map(|k| format!("I{}", k + 1))
            .collect();
        return Err(unsupported(format!(
            "exudyn's ObjectFFRFreducedOrder needs all nine invariants; the file lacks {} (build with --invariants full)",
            missing.join(", ")
        )));
    }
    let n = body.node_count();
    let flex = flexible_modes(body);
    let m = flex.len();
    if m == 0 {
        return Err(unsupported("the file has no flexible modes"));
    }
    if n == 0 {
        return Err(unsupported("the file stores no nodes"));
    }
    let rigid = RigidTerms::of(inv)?;
    let mut notes = Vec::new();
    let mut entries = ffrf_entries(body, &flex, &rigid, &mut notes);
    // flexbody's own keys (LoadFromFile ignores keys it does not know).
    entries.extend(flexbody_entries(body, &flex));
    if let Some(d) = &body.damping {
        // Modal damping as exudyn takes it: a reduced damping matrix D = diag(2 ζ_j ω_j)
        // (mass-orthonormal modes), for ObjectFFRFreducedOrder's dampingMatrixReduced.
        let mut dmat = vec![0.0; m * m];
        for (i, &j) in flex.iter().enumerate() {
            dmat[i * m + i] = 2.0 * d.ratio[j] * body.modes.omega2[j].max(0.0).sqrt();
        }
        entries.push(("dampingMatrixReduced", f64s(vec![m, m], dmat)));
        entries.push((
            "modalDampingRatio",
            f64s(vec![m], flex.iter().map(|&j| d.ratio[j]).collect()),
        ));
        notes.push(
            "modal damping is in key dampingMatrixReduced (diag 2ζω); LoadFromFile does not apply it: set the object's dampingMatrixReduced".into(),
        );
    }
    let bytes = npz_bytes(&entries).map_err(|e| ExportError::Archive {
        path: "<memory>".into(),
        detail: e.to_string(),
    })?;
    Ok((
        bytes,
        ExportSummary {
            modes: m,
            nodes: n,
            notes,
        },
    ))
}

/// The rigid-body terms: total mass I1 (must be positive), centre of mass χ_u = I2/I1 and the
/// translational mass block M_tt = I1·E.
struct RigidTerms {
    total_mass: f64,
    chi_u: [f64; 3],
    mtt: Vec<f64>,
}

impl RigidTerms {
    fn of(inv: &flexbody_reader::Invariants) -> Result<RigidTerms, ExportError> {
        let total_mass = inv.i1[0];
        if total_mass.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(unsupported(format!(
                "the body's mass I1 = {total_mass} is not positive"
            )));
        }
        let chi_u = [
            inv.i2[0] / total_mass,
            inv.i2[1] / total_mass,
            inv.i2[2] / total_mass,
        ];
        let mut mtt = vec![0.0; 9];
        for a in 0..3 {
            mtt[a * 3 + a] = total_mass;
        }
        Ok(RigidTerms {
            total_mass,
            chi_u,
            mtt,
        })
    }
}

/// Mode basis: 3 translations per node (node-major), one column per flexible mode.
fn mode_basis(body: &ReducedBody, flex: &[usize]) -> Vec<f64> {
    let (n, m) = (body.node_count(), flex.len());
    let shapes = &body.modes.shapes;
    let mut mode_basis = vec![0.0; 3 * n * m];
    for (i, &j) in flex.iter().enumerate() {
        for p in 0..n {
            for c in 0..3 {
                mode_basis[(3 * p + c) * m + i] = shapes[(j * n + p) * 6 + c];
            }
        }
    }
    mode_basis
}

/// The flexible modes' block of a modes × modes matrix (row-major, `big_m` modes).
fn flexible_block(mat: &[f64], flex: &[usize], big_m: usize) -> Vec<f64> {
    let m = flex.len();
    let mut out = vec![0.0; m * m];
    for (i, &j) in flex.iter().enumerate() {
        for (k, &l) in flex.iter().enumerate() {
            out[i * m + k] = mat[j * big_m + l];
        }
    }
    out
}

/// exudyn's inertia terms from the invariants, with its signs (the module doc's table).
struct InertiaTerms {
    m_phit_psi: Vec<f64>,
    m_xref_tilde_psi: Vec<f64>,
    m_phit_psi_tilde: Vec<f64>,
    m_xref_tilde_psi_tilde: Vec<f64>,
    m_psi_tilde_psi: Vec<f64>,
    m_psi_tilde_psi_tilde: Vec<f64>,
}

impl InertiaTerms {
    fn of(inv: &flexbody_reader::Invariants, flex: &[usize], big_m: usize) -> InertiaTerms {
        let m = flex.len();
        let mut m_phit_psi = vec![0.0; 3 * m];
        let mut m_xref_tilde_psi = vec![0.0; 3 * m];
        let mut m_phit_psi_tilde = vec![0.0; 9 * m];
        let mut m_xref_tilde_psi_tilde = vec![0.0; 9 * m];
        let mut m_psi_tilde_psi = vec![0.0; 3 * m * m];
        let mut m_psi_tilde_psi_tilde = vec![0.0; 9 * m * m];
        for (i, &j) in flex.iter().enumerate() {
            let i3j = [inv.i3[j], inv.i3[big_m + j], inv.i3[2 * big_m + j]];
            let s = skew(i3j);
            for a in 0..3 {
                m_phit_psi[a * m + i] = inv.i3[a * big_m + j];
                m_xref_tilde_psi[a * m + i] = -inv.i4[a * big_m + j];
                for b in 0..3 {
                    m_phit_psi_tilde[a * 3 * m + 3 * i + b] = s[a][b];
                    m_xref_tilde_psi_tilde[a * 3 * m + 3 * i + b] = -inv.i8[(j * 3 + a) * 3 + b];
                }
                for (k, &l) in flex.iter().enumerate() {
                    m_psi_tilde_psi[(3 * i + a) * m + k] = -inv.i5[(j * 3 + a) * big_m + l];
                    for b in 0..3 {
                        m_psi_tilde_psi_tilde[(3 * i + a) * 3 * m + 3 * k + b] =
                            -inv.i9[((j * big_m + l) * 3 + a) * 3 + b];
                    }
                }
            }
        }
        InertiaTerms {
            m_phit_psi,
            m_xref_tilde_psi,
            m_phit_psi_tilde,
            m_xref_tilde_psi_tilde,
            m_psi_tilde_psi,
            m_psi_tilde_psi_tilde,
        }
    }
}

/// The keys `LoadFromFile` reads (its `SaveToFile` layout), in its order; notes about the
/// surface triangles and rotary inertia into `notes`.
fn ffrf_entries(
    body: &ReducedBody,
    flex: &[usize],
    rigid: &RigidTerms,
    notes: &mut Vec<String>,
) -> Vec<(&'static str, NpyValue)> {
    let inv = &body.invariants;
    let (n, m, big_m) = (body.node_count(), flex.len(), body.mode_count());
    let x_ref: Vec<f64> = body.nodes.iter().flat_map(|nd| nd.xyz).collect();
    let terms = InertiaTerms::of(inv, flex, big_m);
    let (triangles, corners) = surface_triangles(body);
    if body.faces.is_empty() {
        notes.push("the file has no graphics faces: trigList is empty".into());
    } else if corners == 6 {
        notes.push(format!(
            "{} surface triangles with 6 nodes (quadratic mesh)",
            triangles.len() / 6
        ));
    }
    let trig_count = triangles.len() / corners;

    let post = match (&body.stress_shapes, &body.strain_shapes) {
        (Some(s), _) => post_processing(s, n, flex, "OutputVariableType.StressLocal", 1.0),
        // exudyn's StrainLocal is the tensor strain: the file's engineering shear γ = 2ε.
        (None, Some(s)) => post_processing(s, n, flex, "OutputVariableType.StrainLocal", 0.5),
        (None, None) => Vec::new(),
    };

    let has_rotary = body
        .nodal_mass
        .iter()
        .any(|nm| nm.inertia.iter().flatten().any(|&x| x != 0.0));
    if has_rotary {
        notes.push(
            "nodes carry rotary inertia: exudyn's mode basis holds translations only, the inertia terms include the rotary inertia (from the file's invariants)".into(),
        );
    }

    let node_rot = 4;
    let n_rigid = 3 + node_rot;
    vec![
        ("modeBasis", f64s(vec![3 * n, m], mode_basis(body, flex))),
        (
            "trigList",
            NpyValue::I64 {
                shape: vec![trig_count, corners],
                data: triangles.iter().map(|&x| x as i64).collect(),
            },
        ),
        ("postProcessingModes", NpyValue::Dict(post)),
        (
            "massMatrixReduced",
            f64s(vec![m, m], flexible_block(&inv.i6, flex, big_m)),
        ),
        (
            "stiffnessMatrixReduced",
            f64s(
                vec![m, m],
                flexible_block(&body.modes.generalized_stiffness, flex, big_m),
            ),
        ),
        (
            "infoList",
            NpyValue::I64 {
                shape: vec![6],
                data: vec![m as i64, n as i64, 3, node_rot, n_rigid, n_rigid + m as i64],
            },
        ),
        (
            "rigidBodyNodeType",
            NpyValue::Str(RIGID_BODY_NODE_TYPE.into()),
        ),
        ("xRef", f64s(vec![3 * n], x_ref)),
        ("inertiaLocal", f64s(vec![3, 3], inv.i7.clone())),
        ("Mtt", f64s(vec![3, 3], rigid.mtt.clone())),
        ("totalMass", f64s(vec![], vec![rigid.total_mass])),
        ("chiU", f64s(vec![3], rigid.chi_u.to_vec())),
        (
            "chiUtilde",
            f64s(
                vec![3, 3],
                skew(rigid.chi_u).iter().flatten().copied().collect(),
            ),
        ),
        ("mPsiTildePsi", f64s(vec![3 * m, m], terms.m_psi_tilde_psi)),
        (
            "mPsiTildePsiTilde",
            f64s(vec![3 * m, 3 * m], terms.m_psi_tilde_psi_tilde),
        ),
        ("mPhitTPsi", f64s(vec![3, m], terms.m_phit_psi)),
        (
            "mPhitTPsiTilde",
            f64s(vec![3, 3 * m], terms.m_phit_psi_tilde),
        ),
        ("mXRefTildePsi", f64s(vec![3, m], terms.m_xref_tilde_psi)),
        (
            "mXRefTildePsiTilde",
            f64s(vec![3, 3 * m], terms.m_xref_tilde_psi_tilde),
        ),
        (
            "fileVersion",
            NpyValue::I64 {
                shape: vec![],
                data: vec![1],
            },
        ),
        (
            "type",
            NpyValue::Str("ObjectFFRFreducedOrderInterface".into()),
        ),
    ]
}

/// Each interface's dependent (bore) nodes, flat in interface order: interface k's are
/// `[offsets[k], offsets[k + 1])` of `indices` (into the NPZ's nodes, −1 for a node the file
/// does not store) and `ids` (external ids); names and kinds (`Rbe2`, `Rbe3`, `Node`) per
/// interface. Without `interfaces.bin` (files before 1.3): no dependent nodes, names `NODE<id>`,
/// kinds `Node`.
struct DependentNodes {
    offsets: Vec<i64>,
    indices: Vec<i64>,
    ids: Vec<i64>,
    names: Vec<String>,
    kinds: Vec<String>,
}

impl DependentNodes {
    fn of(body: &ReducedBody) -> DependentNodes {
        let index_of: std::collections::HashMap<u64, i64> = body
            .nodes
            .iter()
            .enumerate()
            .map(|(i, nd)| (nd.id, i as i64))
            .collect();
        let mut out = DependentNodes {
            offsets: vec![0],
            indices: Vec::new(),
            ids: Vec::new(),
            names: Vec::new(),
            kinds: Vec::new(),
        };
        match &body.interfaces {
            Some(list) => {
                for info in list {
                    for &id in &info.dependent {
                        out.ids.push(id as i64);
                        out.indices.push(index_of.get(&id).copied().unwrap_or(-1));
                    }
                    out.offsets.push(out.ids.len() as i64);
                    out.names.push(info.name.clone());
                    out.kinds.push(format!("{:?}", info.kind));
                }
            }
            None => {
                for i in &body.method.interface {
                    out.offsets.push(0);
                    out.names
                        .push(format!("NODE{}", body.nodes[i.node as usize].id));
                    out.kinds.push("Node".into());
                }
            }
        }
        out
    }
}

/// flexbody's own keys: node ids, interface nodes and their dependent (bore) nodes, nodal
/// masses, the flexible modes' indices and frequencies, units.
fn flexbody_entries(body: &ReducedBody, flex: &[usize]) -> Vec<(&'static str, NpyValue)> {
    let (n, m) = (body.node_count(), flex.len());
    let dependent = DependentNodes::of(body);
    vec![
        (
            "nodeIds",
            NpyValue::I64 {
                shape: vec![n],
                data: body.nodes.iter().map(|nd| nd.id as i64).collect(),
            },
        ),
        (
            "interfaceNodeIndices",
            NpyValue::I64 {
                shape: vec![body.method.interface.len()],
                data: body
                    .method
                    .interface
                    .iter()
                    .map(|i| i64::from(i.node))
                    .collect(),
            },
        ),
        (
            "interfaceDependentOffsets",
            NpyValue::I64 {
                shape: vec![dependent.offsets.len()],
                data: dependent.offsets,
            },
        ),
        (
            "interfaceDependentNodeIndices",
            NpyValue::I64 {
                shape: vec![dependent.indices.len()],
                data: dependent.indices,
            },
        ),
        (
            "interfaceDependentNodeIds",
            NpyValue::I64 {
                shape: vec![dependent.ids.len()],
                data: dependent.ids,
            },
        ),
        ("interfaceNames", NpyValue::Str(dependent.names.join("\n"))),
        ("interfaceKinds", NpyValue::Str(dependent.kinds.join("\n"))),
        (
            "nodalMass",
            f64s(vec![n], body.nodal_mass.iter().map(|nm| nm.mass).collect()),
        ),
        (
            "flexibleModeIndices",
            NpyValue::I64 {
                shape: vec![m],
                data: flex.iter().map(|&j| j as i64).collect(),
            },
        ),
        (
            "eigenFrequenciesHz",
            f64s(
                vec![m],
                flex.iter().map(|&j| body.modes.frequency_hz[j]).collect(),
            ),
        ),
        (
            "units",
            NpyValue::Str(format!(
                "{} {} {} {}",
                body.units.mass.name,
                body.units.length.name,
                body.units.time.name,
                body.units.force.name
            )),
        ),
    ]
}

/// exudyn's `postProcessingModes` dict: `matrix` (nodes × 6·modes, exudyn's component order,
/// zero rows for nodes without values) and `outputVariableType`; empty without field shapes.
fn post_processing(
    s: &FieldShapes,
    n: usize,
    flex: &[usize],
    kind: &str,
    shear_scale: f64,
) -> Vec<(String, PyValue)> {
    let m = flex.len();
    let k_nodes = s.nodes.len();
    let mut matrix = vec![0.0; n * 6 * m];
    for (i, &j) in flex.iter().enumerate() {
        for (q, &node) in s.nodes.iter().enumerate() {
            for (e, &c) in EXUDYN_FROM_FILE_COMPONENT.iter().enumerate() {
                let scale = if c >= 3 { shear_scale } else { 1.0 };
                matrix[node as usize * 6 * m + 6 * i + e] =
                    scale * s.values[(j * k_nodes + q) * 6 + c];
            }
        }
    }
    vec![
        (
            "matrix".into(),
            PyValue::F64Array {
                shape: vec![n, 6 * m],
                data: matrix,
            },
        ),
        ("outputVariableType".into(), PyValue::Str(kind.into())),
    ]
}

/// Surface triangles for exudyn's `trigList`: quads split in two; 6-node triangles (corners,
/// then the mid nodes of edges 0-1, 1-2, 2-0) when every face is a triangle and every edge has
/// exactly one stored mid node near its middle (a quadratic mesh), 3-node otherwise.
/// Returns the flat list and the nodes per triangle.
fn surface_triangles(body: &ReducedBody) -> (Vec<u32>, usize) {
    let mut tris: Vec<[u32; 3]> = Vec::new();
    for f in &body.faces {
        match f {
            Face::Tri(t) => tris.push(*t),
            Face::Quad(q) => {
                tris.push([q[0], q[1], q[2]]);
                tris.push([q[0], q[2], q[3]]);
            }
        }
    }
    let all_tris = body.faces.iter().all(|f| matches!(f, Face::Tri(_)));
    if all_tris && !tris.is_empty() {
        if let Some(mids) = mid_nodes(body, &tris) {
            let mut out = Vec::with_capacity(tris.len() * 6);
            for (t, mid) in tris.iter().zip(&mids) {
                out.extend_from_slice(t);
                out.extend_from_slice(mid);
            }
            return (out, 6);
        }
    }
    (tris.iter().flatten().copied().collect(), 3)
}

/// For each triangle the mid nodes of its edges 0-1, 1-2, 2-0: the stored node (not a face
/// corner) nearest each edge's midpoint, within a quarter of the edge length; `None` unless
/// every edge has one and no node serves two edges.
fn mid_nodes(body: &ReducedBody, tris: &[[u32; 3]]) -> Option<Vec<[u32; 3]>> {
    use std::collections::{HashMap, HashSet};
    let xyz = |i: u32| body.nodes[i as usize].xyz;
    let corners: HashSet<u32> = tris.iter().flatten().copied().collect();
    let mut edge_len_sum = 0.0;
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for t in tris {
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            edges.push((a.min(b), a.max(b)));
        }
    }
    edges.sort_unstable();
    edges.dedup();
    let dist = |p: [f64; 3], q: [f64; 3]| {
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
    };
    for &(a, b) in &edges {
        edge_len_sum += dist(xyz(a), xyz(b));
    }
    let cell = 0.5 * edge_len_sum / edges.len() as f64;
    if !(cell > 0.0 && cell.is_finite()) {
        return None;
    }
    let key = |p: [f64; 3]| {
        [
            (p[0] / cell).floor() as i64,
            (p[1] / cell).floor() as i64,
            (p[2] / cell).floor() as i64,
        ]
    };
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for (i, nd) in body.nodes.iter().enumerate() {
        let i = i as u32;
        if !corners.contains(&i) {
            grid.entry(key(nd.xyz)).or_default().push(i);
        }
    }
    let mut mid_of: HashMap<(u32, u32), u32> = HashMap::with_capacity(edges.len());
    let mut used: HashSet<u32> = HashSet::with_capacity(edges.len());
    for &(a, b) in &edges {
        let (pa, pb) = (xyz(a), xyz(b));
        let mid = [
            0.5 * (pa[0] + pb[0]),
            0.5 * (pa[1] + pb[1]),
            0.5 * (pa[2] + pb[2]),
        ];
        let radius = 0.25 * dist(pa, pb);
        let reach = (radius / cell).ceil() as i64;
        let k = key(mid);
        let mut best: Option<(f64, u32)> = None;
        for dx in -reach..=reach {
            for dy in -reach..=reach {
                for dz in -reach..=reach {
                    let Some(cands) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) else {
                        continue;
                    };
                    for &c in cands {
                        let d = dist(xyz(c), mid);
                        if d <= radius && best.is_none_or(|(bd, _)| d < bd) {
                            best = Some((d, c));
                        }
                    }
                }
            }
        }
        let (_, node) = best?;
        if !used.insert(node) {
            return None;
        }
        mid_of.insert((a, b), node);
    }
    Some(
        tris.iter()
            .map(|t| {
                // Every edge got its mid node above (or the function returned None).
                let m = |e: usize| {
                    let (a, b) = (t[e], t[(e + 1) % 3]);
                    mid_of[&(a.min(b), a.max(b))]
                };
                [m(0), m(1), m(2)]
            })
            .collect(),
    )
}
