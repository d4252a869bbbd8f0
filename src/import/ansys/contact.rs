//! ANSYS contact elements as the constraints ANSYS's MPC contact forms (MAPDL Contact Technology
//! Guide, "Multipoint Constraints and Assemblies", §10.3 "Surface-Based Constraints"): a
//! contact pair is the TARGE170 and CONTA173/174/175 records sharing a real constant set.
//!
//! **Surface-based constraints** (a remote point): one TARGE170 pilot record (`TSHAPE,PILO`:
//! the SOLID layout's shape key 19, or 99) and contact records with KEYOPT(2)=2 (MPC) and
//! KEYOPT(12)=5 (bonded always):
//! * the contact element's KEYOPT(4) picks the kind: CONTA173/174 KEYOPT(4)=2 and CONTA175
//!   KEYOPT(4)=0 the **rigid surface constraint** ("the contact nodes are constrained to the
//!   rigid body motion defined by the pilot node, similar to CERIG"): an RBE2 from the pilot to
//!   every contact node's translations (the contact elements carry UX, UY, UZ); CONTA173/174
//!   KEYOPT(4)=1 the **force-distributed constraint** ("forces or displacements applied on the
//!   pilot node are distributed to contact nodes (in an average sense) through shape
//!   functions, similar to RBE3"): an RBE3 at the pilot over the contact nodes' translations,
//!   each node weighted by its consistent area ∫Nᵢ dA over the contact faces (the faces' shape
//!   functions — as CalculiX's `*DISTRIBUTING`, [`crate::import::abaqus::coupling`]);
//! * TARGE170's KEYOPT(4) names the pilot dofs constrained: 0 or 111111 (all six) for both
//!   kinds; for the force-distributed one any six-digit pattern of 0 and 1 as the RBE3's
//!   reference dofs, read from the right: the units digit UX, then UY, UZ, ROTX, ROTY, ROTZ
//!   (ROTZ first, as written). ANSYS's own field shows the split: in ansys-mapdl-reader's
//!   `tests/testfiles/materials/file.rst` (ANSYS 21.2) two force-distributed pilots on the same
//!   contact nodes, KEYOPT(4)=111111 and 111, have equal translations — the translation rows of
//!   the six-dof area-weighted fit, to 1.7e-15 — and the 111 pilot's rotations are absent
//!   (zero), so 111 names the translations (docs/ansys.md); TARGE170 KEYOPT(2)=1 (the pilot's
//!   motion the user's: ANSYS's default 0 may hold a target it finds free);
//! * refused by line: a pinball radius (PINB), an initial adjustment (ICONT) or contact offset
//!   (CNOF) in the pair's real constants; other contact KEYOPTs than 2, 4, 12 and the ignored
//!   8 and 10; KEYOPT(12)=6 (bonded initial) and every other behaviour.
//!
//! **Bonded contact between surfaces** (TARGE170 faces, no pilot): [`super::bonded`].
//!
//! Every pair that is not MPC bonded (standard, rough, no-separation contact; penalty,
//! augmented Lagrange, Lagrange multipliers) is refused by line: ANSYS forms those with its
//! contact stiffness at the initial contact status, which a constraint cannot reproduce and
//! dropping would change the body (`docs/ansys.md`).

use std::collections::{BTreeMap, BTreeSet};

use super::blocks::ElementRecord;
use super::bonded;
use super::elements::ElementType;
use super::segments::{contact_face, face_nodes, Pair, PairRefusal, PILOT_SHAPES};
use super::Archive;
use crate::import::abaqus::coupling::{nodal_areas, Rule, QUAD_4, QUAD_9, TRI_1, TRI_3};
use crate::import::error::{parse_err, ImportError};
use crate::import::text::IdMap;
use crate::model::{DofMask, Model, NodeIndex, RigidElement};

/// Refusals by (element type, reason): the first record's line and the count, as
/// [`super::form`] gathers them.
pub(super) type Refusals = BTreeMap<(i64, String), (usize, usize)>;

/// What a pair's contact KEYOPT(4) makes of it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Rigid,
    ForceDistributed,
}

impl Archive {
    /// Every contact pair of `segments` (TARGE170 and CONTA17x records) into the model's rigid
    /// elements and MPCs, each record's id registered in `index` (no element of the model);
    /// each pair not formed a refusal in `refusals`.
    pub(super) fn contact_pairs(
        &self,
        file: &str,
        segments: &[&ElementRecord],
        node_map: &IdMap,
        model: &mut Model,
        refusals: &mut Refusals,
        index: &mut BTreeMap<u64, Option<usize>>,
    ) -> Result<(), ImportError> {
        pairs(self, file, segments, node_map, model, (refusals, index))
    }
}

/// [`Archive::contact_pairs`].
fn pairs(
    archive: &Archive,
    file: &str,
    segments: &[&ElementRecord],
    node_map: &IdMap,
    model: &mut Model,
    (refusals, index): (&mut Refusals, &mut BTreeMap<u64, Option<usize>>),
) -> Result<(), ImportError> {
    for r in segments {
        if index.insert(r.id, None).is_some() {
            let at = format!("element {}", r.id);
            return Err(parse_err(file, r.line, at, "duplicate element id"));
        }
    }
    let node_of = |r: &ElementRecord, id: u64| {
        node_map.get(id).ok_or_else(|| {
            let at = format!("EBLOCK element {}", r.id);
            parse_err(file, r.line, at, format!("references unknown node {id}"))
        })
    };
    let (types, reals) = (&archive.types, &archive.reals);
    let mut pairs: BTreeMap<i64, Vec<&ElementRecord>> = BTreeMap::new();
    for r in segments {
        pairs.entry(r.real).or_default().push(r);
    }
    let number = |r: &ElementRecord| types[&r.etype].row.map_or(0, |row| row.0);
    let sides = pair_sides(&pairs, &number);
    let pair_of = |real: i64| {
        let (targets, contacts): (Vec<&ElementRecord>, Vec<&ElementRecord>) =
            pairs[&real].iter().partition(|r| number(r) == 170);
        Pair {
            types,
            constants: reals.get(&real),
            real,
            targets,
            contacts,
        }
    };
    for &real in pairs.keys() {
        let pair = pair_of(real);
        let target_faces = !pair.targets.is_empty()
            && (pair.targets.iter()).all(|r| r.shape.and_then(face_nodes).is_some());
        if target_faces && !pair.contacts.is_empty() {
            let mirror = match mirror_of(real, &sides) {
                Some(other) => Some(couple(&pair, &pair_of(other), &node_of, model)?),
                None => None,
            };
            if let Err((r, why)) = bonded::tie(&pair, mirror, &node_of, model)? {
                add(refusals, r, why);
            }
            continue;
        }
        match pilot_constraint(&pair) {
            Ok((pilot, kind, dofs)) => {
                let element = spider(pilot, kind, dofs, &pair.contacts, &node_of, model)?;
                match element {
                    Ok(e) => model.rigid_elements.push(e),
                    Err((r, why)) => add(refusals, r, why),
                }
            }
            Err((r, why)) => add(refusals, r, why),
        }
    }
    Ok(())
}

/// Each pair's node ids: (contact records' nodes, TARGE170 records' nodes).
type Sides = BTreeMap<i64, (BTreeSet<u64>, BTreeSet<u64>)>;

fn pair_sides(
    pairs: &BTreeMap<i64, Vec<&ElementRecord>>,
    number: &impl Fn(&ElementRecord) -> u32,
) -> Sides {
    (pairs.iter())
        .map(|(&real, records)| {
            let ids = |target: bool| -> BTreeSet<u64> {
                (records.iter())
                    .filter(|r| (number(r) == 170) == target)
                    .flat_map(|r| r.nodes.iter().copied().filter(|&n| n != 0))
                    .collect()
            };
            (real, (ids(false), ids(true)))
        })
        .collect()
}

/// `pair`'s mirror `other` as a [`bonded::Mirror`]: the same ties when every contact node of
/// both coincides with a target node and the two tie the same node pairs, swapped.
fn couple<E>(
    pair: &Pair<'_, '_>,
    other: &Pair<'_, '_>,
    node_of: &impl Fn(&ElementRecord, u64) -> Result<NodeIndex, E>,
    model: &Model,
) -> Result<bonded::Mirror, E> {
    let ours = bonded::coincident_ties(pair, node_of, model)?;
    let theirs = bonded::coincident_ties(other, node_of, model)?;
    let same_ties = match (ours, theirs) {
        (Some(a), Some(b)) => a.iter().map(|&(c, t)| (t, c)).collect::<BTreeSet<_>>() == b,
        _ => false,
    };
    Ok(bonded::Mirror {
        real: other.real,
        same_ties,
    })
}

/// The real constant set of another pair whose contact nodes meet this pair's target nodes and
/// whose target nodes meet its contact nodes: a symmetric pair's mirror.
fn mirror_of(real: i64, sides: &Sides) -> Option<i64> {
    let (contact, target) = &sides[&real];
    (sides.iter())
        .find(|(&other, (c, t))| other != real && !c.is_disjoint(target) && !t.is_disjoint(contact))
        .map(|(&other, _)| other)
}

fn add(refusals: &mut Refusals, r: &ElementRecord, why: String) {
    refusals.entry((r.etype, why)).or_insert((r.line, 0)).1 += 1;
}

/// The pair of real constant set `real` as a surface-based constraint: its pilot record, kind
/// and the pilot dofs constrained; or why not.
fn pilot_constraint<'a>(
    pair: &Pair<'a, '_>,
) -> Result<(&'a ElementRecord, Kind, DofMask), PairRefusal<'a>> {
    let (types, constants, real) = (pair.types, pair.constants, pair.real);
    let (targets, contacts) = (&pair.targets[..], &pair.contacts[..]);
    let Some(&first_contact) = contacts.first() else {
        return Err((
            targets[0],
            format!("TARGE170 of real constant set {real}: no contact element shares the set"),
        ));
    };
    let Some(&first_target) = targets.first() else {
        return Err((
            first_contact,
            format!(
                "contact elements of real constant set {real}: no TARGE170 shares the set \
                 (a pair is the contact and target elements of one real constant set)"
            ),
        ));
    };
    let pilots: Vec<&ElementRecord> = (targets.iter().copied())
        .filter(|r| r.shape.is_some_and(|s| PILOT_SHAPES.contains(&s)))
        .collect();
    let unknown_shape = targets.iter().find(|r| r.shape.is_none());
    if let Some(r) = unknown_shape {
        return Err((
            r,
            "TARGE170 in the contact layout of EBLOCK: the layout does not write the segment \
             shape (TSHAPE), so a pilot cannot be told from a target point or face"
                .into(),
        ));
    }
    let [pilot] = pilots[..] else {
        let why = if pilots.is_empty() {
            "TARGE170 records without a pilot, not all faces (TRIA, QUAD, TRI6, QUA8): their \
             target shapes (lines, cylinders, cones, spheres, points) are not read"
                .to_string()
        } else {
            format!(
                "{} TARGE170 pilot records in one pair (one expected)",
                pilots.len()
            )
        };
        return Err((first_target, why));
    };
    if targets.len() > 1 {
        return Err((
            first_target,
            "a TARGE170 pilot with target faces (a rigid target surface driven by its pilot): \
             not formed here"
                .into(),
        ));
    }
    let kind = contact_kind(types, contacts)?;
    let dofs = pilot_dofs(&types[&pilot.etype], kind).map_err(|why| (pilot, why))?;
    real_constants_refusal(constants, real).map_or(Ok(()), |why| Err((first_contact, why)))?;
    Ok((pilot, kind, dofs))
}

/// The constraint kind of the contact records (one element type, MPC bonded always).
fn contact_kind<'a>(
    types: &BTreeMap<i64, ElementType>,
    contacts: &[&'a ElementRecord],
) -> Result<Kind, PairRefusal<'a>> {
    let first = contacts[0];
    if let Some(other) = contacts.iter().find(|r| r.etype != first.etype) {
        return Err((
            other,
            format!(
                "contact elements of types {} and {} in one pair (one contact type expected)",
                first.etype, other.etype
            ),
        ));
    }
    let t = &types[&first.etype];
    let name = t.name();
    let keyopt = |k: u32| t.keyopts.get(&k).copied().unwrap_or(0);
    if keyopt(2) != 2 {
        return Err((
            first,
            format!(
                "{name} KEYOPT(2)={} ({}): a contact ANSYS forms by its contact stiffness at the \
                 initial status, not a constraint — not formed (dropping it would change the \
                 body); only MPC contact (KEYOPT(2)=2) is read",
                keyopt(2),
                match keyopt(2) {
                    0 => "augmented Lagrange",
                    1 => "penalty",
                    _ => "Lagrange multipliers",
                }
            ),
        ));
    }
    if keyopt(12) != 5 {
        return Err((
            first,
            format!(
                "{name} KEYOPT(12)={}: a surface-based constraint is read with bonded always \
                 (KEYOPT(12)=5) only",
                keyopt(12)
            ),
        ));
    }
    if let Some((k, v)) = (t.keyopts.iter()).find(|(k, _)| ![2, 4, 8, 10, 12].contains(*k)) {
        return Err((
            first,
            format!("{name} KEYOPT({k})={v}: not read for a surface-based constraint"),
        ));
    }
    let number = t.row.map_or(0, |r| r.0);
    match (number, keyopt(4)) {
        (173 | 174, 2) | (175, 0) => Ok(Kind::Rigid),
        (173 | 174, 1) => Ok(Kind::ForceDistributed),
        (_, k) => Err((
            first,
            format!(
                "{name} KEYOPT(4)={k} with a pilot: the surface-based constraints read are \
                 CONTA173/174 KEYOPT(4)=2 and CONTA175 KEYOPT(4)=0 (rigid), CONTA173/174 \
                 KEYOPT(4)=1 (force-distributed)"
            ),
        )),
    }
}

/// TARGE170's KEYOPT(4) as the pilot dofs constrained (module doc); its KEYOPT(2) must be 1.
fn pilot_dofs(t: &ElementType, kind: Kind) -> Result<DofMask, String> {
    let keyopt = |k: u32| t.keyopts.get(&k).copied().unwrap_or(0);
    if keyopt(2) != 1 {
        return Err(format!(
            "TARGE170 KEYOPT(2)={}: ANSYS's automatic boundary condition may hold a pilot it \
             finds free; read with KEYOPT(2)=1 (the pilot's motion given by the user)",
            keyopt(2)
        ));
    }
    if let Some((k, v)) = (t.keyopts.iter()).find(|(k, _)| ![2, 4].contains(*k)) {
        return Err(format!("TARGE170 KEYOPT({k})={v}: not read for a pilot"));
    }
    let pattern = keyopt(4);
    let digits = format!("{pattern:06}");
    let valid = pattern >= 0 && digits.len() == 6 && digits.chars().all(|c| "01".contains(c));
    if !valid {
        return Err(format!(
            "TARGE170 KEYOPT(4)={pattern}: not a six-digit pattern of 0 and 1"
        ));
    }
    if pattern == 0 || pattern == 111_111 {
        return Ok(DofMask::ALL);
    }
    match kind {
        // the last (units) digit UX, then UY, UZ, ROTX, ROTY, ROTZ: ANSYS's pilots of
        // ansys-mapdl-reader's materials/file.rst (module doc)
        Kind::ForceDistributed => Ok(DofMask(
            (digits.bytes().rev().enumerate())
                .filter(|(_, b)| *b == b'1')
                .fold(0, |m, (i, _)| m | 1 << i),
        )),
        Kind::Rigid => Err(format!(
            "TARGE170 KEYOPT(4)={pattern} with a rigid surface constraint: which equations \
             ANSYS keeps for a subset of the pilot dofs is not established (no ANSYS result with \
             such a pilot was found); 0 or 111111 read"
        )),
    }
}

/// A refusal for the pair's real constants that change which nodes a constraint takes or
/// where: ICONT (5), PINB (6), CNOF (10).
fn real_constants_refusal(constants: Option<&Vec<f64>>, real: i64) -> Option<String> {
    let c = constants?;
    let value = |k: usize| c.get(k - 1).copied().unwrap_or(0.0);
    [
        (5, "ICONT", "an initial adjustment band"),
        (
            6,
            "PINB",
            "a pinball radius limiting which contact nodes the pilot takes",
        ),
        (10, "CNOF", "a contact surface offset"),
    ]
    .into_iter()
    .find(|(k, _, _)| value(*k) != 0.0)
    .map(|(k, label, what)| {
        format!(
            "real constant set {real}: {label} (constant {k}) = {} — {what}: not reproduced",
            value(k)
        )
    })
}

/// The pilot's spider over the contact records' nodes: an RBE2 (rigid) or an RBE3 with the
/// faces' consistent nodal areas (force-distributed); the pilot among the contact nodes or a
/// face whose shape is not read is the refusal.
fn spider<'a, E>(
    pilot: &'a ElementRecord,
    kind: Kind,
    dofs: DofMask,
    contacts: &[&'a ElementRecord],
    node_of: &impl Fn(&ElementRecord, u64) -> Result<NodeIndex, E>,
    model: &Model,
) -> Result<Result<RigidElement, PairRefusal<'a>>, E> {
    let Some(&pilot_id) = pilot.nodes.iter().find(|&&n| n != 0) else {
        return Ok(Err((pilot, "TARGE170 pilot record without a node".into())));
    };
    let reference = node_of(pilot, pilot_id)?;
    // node → weight, in the order first met
    let mut weight: Vec<(NodeIndex, f64)> = Vec::new();
    for &r in contacts {
        let face = match contact_face(r) {
            Ok(face) => face,
            Err(why) => return Ok(Err((r, why))),
        };
        let ids: Vec<u64> = face.iter().copied().filter(|&n| n != 0).collect();
        let nodes = (ids.iter().map(|&id| node_of(r, id))).collect::<Result<Vec<_>, E>>()?;
        if ids.contains(&pilot_id) {
            return Ok(Err((
                r,
                format!("the pilot node {pilot_id} is also a contact node of its pair"),
            )));
        }
        let areas = match kind {
            Kind::Rigid => vec![0.0; nodes.len()],
            Kind::ForceDistributed => match face_rule(face.len()) {
                Some(rule) if ids.len() == face.len() => {
                    let x: Vec<[f64; 3]> = nodes.iter().map(|&n| model.nodes[n].x).collect();
                    nodal_areas(&x, rule)
                }
                _ => {
                    return Ok(Err((
                        r,
                        "force-distributed constraint on a contact record without a face (a \
                         CONTA175 node or dropped mid-side nodes): its area weights are not \
                         formed"
                            .into(),
                    )))
                }
            },
        };
        for (n, a) in nodes.into_iter().zip(areas) {
            match weight.iter_mut().find(|(m, _)| *m == n) {
                Some(w) => w.1 += a,
                None => weight.push((n, a)),
            }
        }
    }
    Ok(Ok(match kind {
        Kind::Rigid => RigidElement::Rbe2 {
            id: pilot.id,
            independent: reference,
            dependent: weight.into_iter().map(|(n, _)| n).collect(),
            dofs: DofMask::TRANSLATIONS,
        },
        Kind::ForceDistributed => {
            let total: f64 = weight.iter().map(|w| w.1).sum();
            if !(total > 0.0 && total.is_finite()) {
                let why = format!("force-distributed constraint on faces of total area {total}");
                return Ok(Err((contacts[0], why)));
            }
            RigidElement::Rbe3 {
                id: pilot.id,
                reference,
                ref_dofs: dofs,
                independent: (weight.into_iter())
                    .map(|(n, a)| (n, a / total, DofMask::TRANSLATIONS))
                    .collect(),
            }
        }
    }))
}

/// The rule integrating a face of `n` nodes exactly on a flat face with straight edges.
fn face_rule(n: usize) -> Option<Rule> {
    Some(match n {
        3 => TRI_1,
        6 => TRI_3,
        4 => QUAD_4,
        8 => QUAD_9,
        _ => return None,
    })
}
