//! Bonded MPC contact between two surfaces (MAPDL Contact Technology Guide §10.1, "Modeling
//! Solid-Solid and Shell-Shell Assemblies"): CONTA173/174 faces against TARGE170 faces of one
//! real constant set, KEYOPT(2)=2 (MPC) and KEYOPT(12)=5 (bonded always) — each contact node
//! within the pinball of the target surface held on its nearest target face point by the face's
//! shape functions, u_c = Σᵢ Nᵢ(ξ, η) u_i for the three translations (one MPC per component, as
//! CalculiX's `*TIE` with ADJUST=NO: the node is not moved).
//!
//! Read as ANSYS's documentation states it, not shown against an ANSYS result:
//! * the contact element's KEYOPT(4)=2 (nodal detection, "normal to target surface"): the
//!   target face point nearest the node; the other detection options (Gauss points, the contact
//!   surface's normal, the projection-based method) are refused;
//! * the pinball: a negative PINB (real constant 6) is its radius; ANSYS's default and a
//!   positive PINB scale with the underlying elements' depth, which is not reproduced: refused.
//!   Contact nodes farther than the radius from every target face stay free, counted in a note;
//! * KEYOPT(9), the effect of the initial gap: 1 excludes it (Workbench writes `keyo,cid,9,1 !
//!   ignore initial gaps/penetration`; an ANSYS contact course: with 1 "the gap is ignored and
//!   the contact and target surfaces are held together in their 'as assembled' position", with
//!   0 the contact elements "bring the contact and surfaces together such that the gap is
//!   closed"): the node bonded where it is, u_c = Σ Nᵢ uᵢ, the form above. Any other value is
//!   read only when every tied node lies on its target face (its nearest face point within
//!   1e-9 of the target faces' extent: no gap to close, CNOF being refused), else refused
//!   naming KEYOPT(9) and the largest gap (a closed gap is another geometry or a preload);
//! * solid-solid assemblies only: a contact or target node of a shell, beam or link element
//!   (a shell-solid or shell-shell assembly, Contact Technology Guide §10.1, §10.2: "the program
//!   automatically constrains both translational and rotational degrees of freedom for a
//!   shell-solid assembly", TARGE170 KEYOPT(5)=0 set internally to 4, in equations the guide
//!   does not give, and which no ANSYS result at hand shows: none holds a shell-solid or
//!   shell-shell MPC pair, docs/ansys.md) is refused;
//! * a symmetric couple (a pair whose mirror, contact and target swapped, is another real
//!   constant set of the archive: Workbench writes bonded contact so): "only asymmetric contact
//!   is supported. If symmetric pairs are defined, the program automatically selects one pair
//!   and ignores the other" — which one is not stated. On congruent meshes it does not matter:
//!   when every contact node of both pairs coincides with a target node (within 1e-9 of the
//!   smallest target face's size, so its nearest target point is that node and u_c = u_t) and
//!   the two pairs tie the same node pairs, either pair is the same equations; the lower set
//!   is formed and the other's duplicate equations dropped, with a note (ANSYS's static field
//!   of ansys/example-data's `two_cubes_contact.rst` holds u_c = u_t at every contact node of
//!   both sets of such a couple). Any other couple is refused, both sets named;
//! * refused by line: KEYOPT(12)=6 (bonded initial: which initially open nodes ANSYS leaves free
//!   is not established), ICONT and CNOF, contact KEYOPTs other than 2, 4, 9, 12 and the ignored
//!   8 and 10, TARGE170 KEYOPTs other than 2 (the rigid target's boundary condition, no effect on
//!   a target on deformable faces), a node in a nodal coordinate system (the equations are on
//!   global components).

use std::collections::BTreeSet;

use super::blocks::ElementRecord;
use super::segments::{contact_face, face_nodes, Pair, PairRefusal};
use crate::import::abaqus::tie::{face_shape, project};
use crate::model::{Model, Mpc, NodeDof, NodeIndex};

/// A target face: its nodes (indices) and their coordinates.
struct TargetFace {
    nodes: Vec<NodeIndex>,
    x: Vec<[f64; 3]>,
}

/// A symmetric pair's mirror (contact and target swapped): its real constant set, and whether
/// the two pairs tie the same node pairs on congruent meshes ([`coincident_ties`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Mirror {
    pub real: i64,
    pub same_ties: bool,
}

/// The contact nodes of `contacts` tied to the target faces `targets` (module doc): MPCs into
/// `model` and a note counting the nodes tied and left free; or the pair's refusal.
/// `mirror` is the pair with contact and target swapped, if any: a couple on congruent meshes
/// is formed once, by its lower set.
pub(super) fn tie<'a, E>(
    pair: &Pair<'a, '_>,
    mirror: Option<Mirror>,
    node_of: &impl Fn(&ElementRecord, u64) -> Result<NodeIndex, E>,
    model: &mut Model,
) -> Result<Result<(), PairRefusal<'a>>, E> {
    let (real, targets, contacts) = (pair.real, &pair.targets[..], &pair.contacts[..]);
    let (radius, keyopt9) = match options(pair) {
        Ok(options) => options,
        Err(refusal) => return Ok(Err(refusal)),
    };
    let mut faces = Vec::with_capacity(targets.len());
    for &r in targets {
        let n = r.shape.and_then(face_nodes).unwrap_or(0);
        let ids: Vec<u64> = r.nodes.iter().copied().filter(|&id| id != 0).collect();
        if ids.len() != n {
            let why = format!(
                "TARGE170 face of shape key {:?} with {} nodes ({n} expected)",
                r.shape,
                ids.len()
            );
            return Ok(Err((r, why)));
        }
        let nodes = (ids.iter().map(|&id| node_of(r, id))).collect::<Result<Vec<_>, E>>()?;
        let x = nodes.iter().map(|&k| model.nodes[k].x).collect();
        faces.push(TargetFace { nodes, x });
    }
    let mut slaves: Vec<NodeIndex> = Vec::new();
    for &r in contacts {
        let face = match contact_face(r) {
            Ok(face) if face.len() > 1 => face,
            Ok(_) => {
                let why = "CONTA175 against target faces: not read (CONTA173/174 faces are)";
                return Ok(Err((r, why.into())));
            }
            Err(why) => return Ok(Err((r, why))),
        };
        for id in face.into_iter().filter(|&id| id != 0) {
            let n = node_of(r, id)?;
            if !slaves.contains(&n) {
                slaves.push(n);
            }
        }
    }
    let on_target: BTreeSet<NodeIndex> =
        faces.iter().flat_map(|f| f.nodes.iter().copied()).collect();
    if let Some(why) = assembly_refusal(model, &slaves, &on_target, real, mirror) {
        return Ok(Err((contacts[0], why)));
    }
    let framed =
        (slaves.iter().chain(&on_target)).find(|&&n| model.nodes[n].displacement_frame.is_some());
    if let Some(&n) = framed {
        let why = format!(
            "bonded contact on node {} with a nodal coordinate system (NBLOCK angles): its \
             equations are formed on global components",
            model.nodes[n].id
        );
        return Ok(Err((contacts[0], why)));
    }
    if let Some(m) = mirror.filter(|m| m.real < real) {
        model.deck.notes.push(format!(
            "ANSYS archive: bonded MPC contact of real constant set {real} (contact element {} \
             at line {}) is the mirror of set {} on congruent meshes: the same node pairs tied, \
             formed once (by set {})",
            contacts[0].id, contacts[0].line, m.real, m.real
        ));
        return Ok(Ok(()));
    }
    // each contact node within the pinball: its face, the face point and its gap
    let (mut ties, mut free) = (Vec::new(), Vec::new());
    for &s in slaves.iter().filter(|s| !on_target.contains(s)) {
        let p = model.nodes[s].x;
        let nearest = (faces.iter())
            .filter_map(|f| project(&f.x, p).map(|(q, at)| (f, q, distance(at, p))))
            .min_by(|a, b| a.2.total_cmp(&b.2));
        match nearest {
            Some((face, q, d)) if d <= radius => ties.push((s, face, q, d)),
            _ => free.push(model.nodes[s].id),
        }
    }
    if let Some(why) = gap_refusal(model, &faces, &ties, keyopt9, real) {
        return Ok(Err((contacts[0], why)));
    }
    let tied = ties.len();
    for (s, face, q, _) in ties {
        let (shape, _) = face_shape(face.x.len(), q);
        for component in 0..3u8 {
            let mut terms = vec![(NodeDof { node: s, component }, 1.0)];
            for (&node, &n) in face.nodes.iter().zip(&shape) {
                if n != 0.0 {
                    terms.push((NodeDof { node, component }, -n));
                }
            }
            model.mpcs.push(Mpc {
                id: contacts[0].id,
                terms,
            });
        }
    }
    let mut note = format!(
        "ANSYS archive: bonded MPC contact of real constant set {real} (contact element {} at \
         line {}): {tied} contact nodes tied to the target faces within the pinball radius {radius}",
        contacts[0].id, contacts[0].line
    );
    if !free.is_empty() {
        let shown: Vec<String> = free.iter().take(8).map(u64::to_string).collect();
        note += &format!(
            "; {} outside it left free (nodes {}{})",
            free.len(),
            shown.join(", "),
            if free.len() > 8 { ", …" } else { "" }
        );
    }
    model.deck.notes.push(note);
    Ok(Ok(()))
}

/// Why a pair is not a solid-solid assembly flexbody forms (module doc): a contact or target
/// node of an element that is not a solid (a shell, beam or link: ANSYS ties its rotations
/// too), or a mirror pair of real constant set `mirror`.
fn assembly_refusal(
    model: &Model,
    slaves: &[NodeIndex],
    on_target: &BTreeSet<NodeIndex>,
    real: i64,
    mirror: Option<Mirror>,
) -> Option<String> {
    let in_pair: BTreeSet<NodeIndex> = slaves.iter().chain(on_target).copied().collect();
    let structural = (model.elements.iter())
        .filter(|e| e.property.is_some() && !e.kind.is_solid())
        .find_map(|e| {
            e.nodes
                .iter()
                .find(|n| in_pair.contains(n))
                .map(|&n| (e, n))
        });
    if let Some((e, n)) = structural {
        let side = if on_target.contains(&n) {
            "target"
        } else {
            "contact"
        };
        return Some(format!(
            "bonded MPC contact of real constant set {real} on {side} node {} of element {} \
             ({:?}, not a solid): a shell-solid or shell-shell assembly, for which ANSYS \
             constrains the shell nodes' rotations as well as their translations (Contact \
             Technology Guide §10.2, TARGE170 KEYOPT(5)=0 set internally to 4) by equations the \
             guide does not give — tying the translations alone would be another body; not \
             formed",
            model.nodes[n].id, e.id, e.kind
        ));
    }
    mirror.filter(|m| !m.same_ties).map(|m| {
        format!(
            "bonded MPC contact of real constant set {real} and its mirror, set {} (contact \
             and target swapped): ANSYS supports only asymmetric MPC contact and \"automatically \
             selects one pair and ignores the other\" (Contact Technology Guide §10.1) — which \
             one is not stated, and the meshes are not congruent (a contact node of either set \
             off every target node, or the two sets tie different node pairs), so the choice \
             changes the body; forming both over-constrains the interface; not formed",
            m.real
        )
    })
}

/// The (contact node, target node) pairs of `pair` when every contact node coincides with a
/// target node — within 1e-9 of the smallest target face's size (its bounding-box diagonal),
/// the node then its nearest target point with u_c = u_t — else `None` (also for a record
/// that is not a contact face or a target face).
pub(super) fn coincident_ties<E>(
    pair: &Pair<'_, '_>,
    node_of: &impl Fn(&ElementRecord, u64) -> Result<NodeIndex, E>,
    model: &Model,
) -> Result<Option<BTreeSet<(NodeIndex, NodeIndex)>>, E> {
    let mut size = f64::INFINITY;
    let mut targets: Vec<(NodeIndex, [f64; 3])> = Vec::new();
    for &r in &pair.targets {
        let ids: Vec<u64> = r.nodes.iter().copied().filter(|&id| id != 0).collect();
        if r.shape.and_then(face_nodes) != Some(ids.len()) {
            return Ok(None);
        }
        let (mut low, mut high) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &id in &ids {
            let n = node_of(r, id)?;
            let x = model.nodes[n].x;
            for k in 0..3 {
                low[k] = low[k].min(x[k]);
                high[k] = high[k].max(x[k]);
            }
            targets.push((n, x));
        }
        size = size.min(distance(low, high));
    }
    let tol = 1e-9 * size;
    if !(tol > 0.0 && tol.is_finite()) {
        return Ok(None);
    }
    targets.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]));
    let mut ties = BTreeSet::new();
    for &r in &pair.contacts {
        let Ok(face) = contact_face(r) else {
            return Ok(None);
        };
        for id in face.into_iter().filter(|&id| id != 0) {
            let c = node_of(r, id)?;
            let x = model.nodes[c].x;
            // the target nodes within tol in x, then the nearest of them
            let from = targets.partition_point(|t| t.1[0] < x[0] - tol);
            let near = (targets[from..].iter())
                .take_while(|t| t.1[0] <= x[0] + tol)
                .map(|t| (t.0, distance(t.1, x)))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            match near {
                Some((t, d)) if d <= tol && t != c => {
                    ties.insert((c, t));
                }
                _ => return Ok(None),
            }
        }
    }
    Ok(Some(ties))
}

/// Why the initial gaps of `ties` (contact node, face, face point, gap) are refused under
/// KEYOPT(9)=`keyopt9` (module doc): any value but 1 with a gap beyond 1e-9 of the target
/// faces' extent.
fn gap_refusal(
    model: &Model,
    faces: &[TargetFace],
    ties: &[(NodeIndex, &TargetFace, [f64; 2], f64)],
    keyopt9: i64,
    real: i64,
) -> Option<String> {
    if keyopt9 == 1 {
        return None;
    }
    let (mut low, mut high) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for x in faces.iter().flat_map(|f| &f.x) {
        for k in 0..3 {
            low[k] = low[k].min(x[k]);
            high[k] = high[k].max(x[k]);
        }
    }
    let extent = distance(low, high);
    let &(node, _, _, gap) = ties.iter().max_by(|a, b| a.3.total_cmp(&b.3))?;
    (gap > 1e-9 * extent).then(|| {
        format!(
            "real constant set {real}: KEYOPT(9)={keyopt9} includes the initial gap, which ANSYS \
             closes, and contact node {} lies {gap:.4e} from its nearest target face point (the \
             largest gap of the pair; the target faces span {extent:.4e}) — the closed geometry \
             is not formed; KEYOPT(9)=1 (exclude it: bonded as placed) is read",
            model.nodes[node].id
        )
    })
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The pair's KEYOPTs and real constants (module doc): the pinball radius and KEYOPT(9), or the
/// refusal.
fn options<'a>(pair: &Pair<'a, '_>) -> Result<(f64, i64), PairRefusal<'a>> {
    let (types, constants, real) = (pair.types, pair.constants, pair.real);
    let (targets, contacts) = (&pair.targets[..], &pair.contacts[..]);
    let first = contacts[0];
    if let Some(other) = contacts.iter().find(|r| r.etype != first.etype) {
        let why = format!(
            "contact elements of types {} and {} in one pair (one contact type expected)",
            first.etype, other.etype
        );
        return Err((other, why));
    }
    let t = &types[&first.etype];
    let name = t.name();
    let keyopt = |k: u32| t.keyopts.get(&k).copied().unwrap_or(0);
    let why =
        match (keyopt(2), keyopt(12), keyopt(4)) {
            (2, 5, 2) => None,
            (k2 @ (0 | 1 | 3 | 4), _, _) => Some(format!(
            "{name} KEYOPT(2)={k2} ({}): a contact ANSYS forms by its contact stiffness at the \
             initial status, not a constraint — not formed (dropping it would change the \
             body); only MPC contact (KEYOPT(2)=2) is read",
            ["augmented Lagrange", "penalty", "", "Lagrange multipliers", "Lagrange multipliers"]
                [k2 as usize]
        )),
            (2, 6, _) => Some(format!(
            "{name} KEYOPT(12)=6 (bonded initial): which initially open contact nodes ANSYS leaves \
             free is not established; bonded always (KEYOPT(12)=5) is read"
        )),
            (2, 5, k4) => Some(format!(
            "{name} KEYOPT(4)={k4}: bonded contact between surfaces is read with nodal detection \
             normal to the target (KEYOPT(4)=2, the nearest target point)"
        )),
            (k2, k12, _) => Some(format!(
                "{name} KEYOPT(2)={k2}, KEYOPT(12)={k12}: only MPC (KEYOPT(2)=2) bonded always \
             (KEYOPT(12)=5) contact between surfaces is read"
            )),
        };
    if let Some(why) = why {
        return Err((first, why));
    }
    if let Some((k, v)) = (t.keyopts.iter()).find(|(k, _)| ![2, 4, 8, 9, 10, 12].contains(*k)) {
        return Err((
            first,
            format!("{name} KEYOPT({k})={v}: not read for bonded contact"),
        ));
    }
    for &r in targets {
        let t = &types[&r.etype];
        if let Some((k, v)) = t.keyopts.iter().find(|(k, _)| **k != 2) {
            return Err((
                r,
                format!("TARGE170 KEYOPT({k})={v}: not read for bonded contact"),
            ));
        }
    }
    let value = |k: usize| constants.and_then(|c| c.get(k - 1)).copied().unwrap_or(0.0);
    for (k, label) in [(5, "ICONT"), (10, "CNOF")] {
        if value(k) != 0.0 {
            let why = format!(
                "real constant set {real}: {label} (constant {k}) = {}: an adjustment of the \
                 contact surface, not reproduced",
                value(k)
            );
            return Err((first, why));
        }
    }
    let pinb = value(6);
    if pinb >= 0.0 {
        return Err((
            first,
            format!(
                "real constant set {real}: PINB = {pinb} — ANSYS's default pinball and a positive \
                 PINB scale with the underlying elements' depth, not reproduced; give the radius \
                 as a negative (absolute) PINB"
            ),
        ));
    }
    Ok((-pinb, keyopt(9)))
}
