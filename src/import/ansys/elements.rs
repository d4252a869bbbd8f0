//! Element types (`ET`, `KEYOPT`) and the elements of an `EBLOCK` as the model's element kinds,
//! formed as ANSYS forms them for the KEYOPTs the archive sets, or refused naming the KEYOPT.
//!
//! Node orders: SOLID186's I…P, Q…X, Y…B (corners, bottom and top mid-sides, vertical
//! mid-sides) and SOLID187's I…L, M…R are Abaqus's C3D20 and C3D10 orders (MAPDL Element
//! Reference, SOLID186/SOLID187 geometry figures), so the node lists are taken as written.

use std::collections::BTreeMap;

use super::blocks::ElementRecord;
use super::catalogue::{self, Disposition};
use crate::model::ElementKind;

/// An element type of the archive (`ET,ITYPE,Ename` and its `KEYOPT`s).
#[derive(Debug, Clone)]
pub(super) struct ElementType {
    /// The `ET` line.
    pub line: usize,
    /// As written (`186` or `SOLID186`).
    pub written: String,
    /// The catalogue row (`None`: not in the catalogue).
    pub row: Option<(u32, &'static str, Disposition)>,
    /// KEYOPT(k) → value, nonzero ones only.
    pub keyopts: BTreeMap<u32, i64>,
}

impl ElementType {
    /// The name in messages (`SOLID186`, or the text written).
    pub fn name(&self) -> String {
        self.row
            .map_or_else(|| self.written.clone(), |r| r.1.to_owned())
    }

    /// From the `ET` fields (type number, name or number, KOP1…KOP6).
    pub fn new(line: usize, written: &str) -> ElementType {
        ElementType {
            line,
            written: written.trim().to_owned(),
            row: catalogue::element_type(written),
            keyopts: BTreeMap::new(),
        }
    }
}

/// What an element record becomes.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Formed {
    /// An element of this kind on these node ids.
    Element(ElementKind, Vec<u64>),
    /// An element without stiffness or mass (MESH200): not in the model.
    NoStiffness,
    /// A point mass (MASS21) at this node id: mass and the diagonal rotary inertia.
    PointMass(u64, f64, [f64; 3]),
    /// A spring (COMBIN14) between two node ids.
    Spring(Spring),
    /// A LINK180 spar on these node ids: the rod of this area and added mass per length,
    /// without torsion.
    Rod([u64; 2], f64, f64),
    /// An MPC184 rigid link (KEYOPT(1)=0) from node id I to J: their distance kept.
    RigidLink(u64, u64),
    /// An MPC184 rigid beam (KEYOPT(1)=1) from node id I to J: J follows I's rigid motion.
    RigidBeam(u64, u64),
    /// A SHELL181 (KEYOPT(3)=2) or SHELL281 on its homogeneous section ([`super::shells`]).
    Shell(super::shells::Shell),
    /// A BEAM188 (KEYOPT(3)=0) or BEAM189 on its nodes and orientation node ([`super::beams`]).
    Beam(super::beams::Beam),
}

/// A LINK section (`SECTYPE,id,LINK`): its line, the area (`SECDATA`) and the added mass per
/// length (`SECCONTROL`).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct LinkSection {
    pub line: usize,
    pub area: f64,
    pub added_mass: f64,
}

/// A COMBIN14 spring between nodes `a` and `b` (ids).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Spring {
    pub a: u64,
    pub b: u64,
    /// The stiffness K (real constant 1).
    pub k: f64,
    /// Along the line from a to b (KEYOPT(2)=0, KEYOPT(3)=0), or between the same translation
    /// 0…2 of both nodes (KEYOPT(2)=1…3).
    pub along: Option<u8>,
    /// Damping CV1 or CV2 is set (not read: an undamped body).
    pub damped: bool,
}

/// Why an element cannot be formed (the refusal's reason; the KEYOPT named when it is one).
pub(super) type Refusal = String;

/// The KEYOPTs of `t` other than `allowed` that are set: each one refused by name.
pub(super) fn unsupported_keyopts(t: &ElementType, allowed: &[u32]) -> Result<(), Refusal> {
    match t.keyopts.iter().find(|(k, _)| !allowed.contains(k)) {
        Some((k, v)) => Err(format!(
            "{} KEYOPT({k})={v}: this option's formulation is not formed here",
            t.name()
        )),
        None => Ok(()),
    }
}

/// The element of record `rec` of type `t` (a type the catalogue honours or notes).
pub(super) fn form(
    t: &ElementType,
    rec: &ElementRecord,
    reals: Option<&[f64]>,
    section: Option<&LinkSection>,
    shell: Option<&super::shells::ShellSection>,
) -> Result<Formed, Refusal> {
    let Some((number, name, disposition)) = t.row else {
        return Err(format!(
            "element type {} is not in the catalogue",
            t.written
        ));
    };
    match disposition {
        Disposition::Refused(why) => return Err(format!("{name}: {why}")),
        Disposition::Note(_) => return Ok(Formed::NoStiffness),
        Disposition::Honoured(_) => {}
    }
    match number {
        14 => combin14(t, rec, reals),
        21 => mass21(t, rec, reals),
        180 => link180(t, rec, reals, section),
        181 => super::shells::shell181(&t.keyopts, rec, reals, shell).map(Formed::Shell),
        281 => super::shells::shell281(&t.keyopts, rec, shell).map(Formed::Shell),
        184 => mpc184(t, rec),
        188 => super::beams::beam188(&t.keyopts, rec).map(Formed::Beam),
        189 => super::beams::beam189(&t.keyopts, rec).map(Formed::Beam),
        185 => solid185(t, rec),
        186 => solid186(t, rec),
        45 => solid45(t, rec),
        95 => solid95(t, rec),
        187 => solid187(t, rec),
        // every honoured row of the catalogue is matched above; a new one must be added here
        other => Err(format!("element type {other} ({name}) has no former")),
    }
}

/// COMBIN14 (MAPDL Element Reference "COMBIN14"): KEYOPT(2)=0 with KEYOPT(3)=0, the 3-D
/// longitudinal spring (uniaxial along I→J, no bending or torsion), and KEYOPT(2)=1…3, the 1-D
/// spring between UX, UY or UZ of I and J (nodal directions: the archive's nodes have no
/// rotation); real constants K, CV1, CV2 (the damping not read), a nonzero initial length or
/// preload (ILEN, IFORCE) refused. The torsional (KEYOPT(3)=1), 2-D (KEYOPT(3)=2) and rotational
/// 1-D (KEYOPT(2)=4…6) springs need rotational dofs no element read here gives stiffness or
/// mass; KEYOPT(2)=7, 8 are thermal and pressure elements.
fn combin14(
    t: &ElementType,
    rec: &ElementRecord,
    reals: Option<&[f64]>,
) -> Result<Formed, Refusal> {
    unsupported_keyopts(t, &[1, 2, 3])?;
    let keyopt = |k: u32| t.keyopts.get(&k).copied().unwrap_or(0);
    let along = match (keyopt(2), keyopt(3)) {
        (0, 0) => None,
        (0, k3) => {
            return Err(format!(
                "COMBIN14 KEYOPT(3)={k3} ({}): not formed here",
                if k3 == 1 {
                    "torsional: its rotations have no stiffness or mass from another element read here"
                } else {
                    "a 2-D element"
                }
            ))
        }
        (k2 @ 1..=3, _) => Some((k2 - 1) as u8),
        (k2, _) => {
            return Err(format!(
                "COMBIN14 KEYOPT(2)={k2} ({}): not formed here",
                if k2 <= 6 {
                    "a 1-D rotational spring: its rotations have no stiffness or mass from another element read here"
                } else {
                    "a thermal or pressure element"
                }
            ))
        }
    };
    let Some(reals) = reals else {
        return Err(format!(
            "COMBIN14: real constant set {} is not defined",
            rec.real
        ));
    };
    let real = |k: usize| reals.get(k).copied().unwrap_or(0.0);
    if !(real(0) >= 0.0 && real(0).is_finite()) {
        return Err(format!(
            "COMBIN14: stiffness K = {} (negative or not finite)",
            real(0)
        ));
    }
    if let Some(v) = reals.iter().skip(3).find(|v| **v != 0.0) {
        return Err(format!(
            "COMBIN14: real constant {v} past CV2 (an initial length or preload, ILEN/IFORCE): not read"
        ));
    }
    let nodes: Vec<u64> = rec.nodes.iter().copied().filter(|&n| n != 0).collect();
    let [a, b] = nodes[..] else {
        return Err(format!(
            "COMBIN14 with {} nodes (I and J expected)",
            nodes.len()
        ));
    };
    if real(0) == 0.0 {
        return Ok(Formed::NoStiffness);
    }
    Ok(Formed::Spring(Spring {
        a,
        b,
        k: real(0),
        along,
        damped: real(1) != 0.0 || real(2) != 0.0,
    }))
}

/// LINK180 (MAPDL Element Reference "LINK180"; Theory Reference 13.180: one integration point,
/// mass by its equations 11–6 and 11–7): the 2-node spar, axial stiffness EA/L along I→J,
/// consistent mass ρAL/6·[2 1; 1 2] on each translation (lumped ρAL/2), no bending or torsion —
/// the rod of [`ElementKind::Rod2`] with J = 0 (Nastran CROD without torsion). Area and added
/// mass per length from its LINK section, or without one from real constants AREA, ADDMAS
/// (TENSKEY must be 0). Tension- or compression-only (KEYOPT(3)=1, 2) is refused.
fn link180(
    t: &ElementType,
    rec: &ElementRecord,
    reals: Option<&[f64]>,
    section: Option<&LinkSection>,
) -> Result<Formed, Refusal> {
    unsupported_keyopts(t, &[2, 3])?;
    if let Some(&k) = t.keyopts.get(&3) {
        return Err(format!(
            "LINK180 KEYOPT(3)={k} ({}-only): a nonlinear element, not formed here",
            if k == 1 { "tension" } else { "compression" }
        ));
    }
    let nodes: Vec<u64> = rec.nodes.iter().copied().filter(|&n| n != 0).collect();
    let [a, b] = nodes[..] else {
        return Err(format!(
            "LINK180 with {} nodes (I and J expected)",
            nodes.len()
        ));
    };
    if a == b {
        return Err("LINK180 from a node to itself".into());
    }
    let (area, added_mass) = match (section, reals) {
        (Some(s), _) => (s.area, s.added_mass),
        (None, Some(r)) => {
            if r.get(2).is_some_and(|&v| v != 0.0) {
                return Err(format!(
                    "LINK180 real constant TENSKEY = {} (tension- or compression-only): not formed here",
                    r[2]
                ));
            }
            (
                r.first().copied().unwrap_or(0.0),
                r.get(1).copied().unwrap_or(0.0),
            )
        }
        (None, None) => {
            return Err(format!(
                "LINK180 without a LINK section (section {}) or real constants (set {})",
                rec.section, rec.real
            ))
        }
    };
    if !(area > 0.0 && area.is_finite() && added_mass >= 0.0 && added_mass.is_finite()) {
        let from = section.map_or_else(
            || format!("real constant set {}", rec.real),
            |s| format!("the LINK section of line {}", s.line),
        );
        return Err(format!(
            "LINK180 with area {area} and added mass {added_mass} from {from} (area > 0, added \
             mass ≥ 0)"
        ));
    }
    Ok(Formed::Rod([a, b], area, added_mass))
}

/// MPC184 (MAPDL Element Reference "MPC184-Link/Beam"): KEYOPT(1)=0, the rigid link (UX, UY,
/// UZ at I and J; the linearized constraint keeps their distance: e·(u_J − u_I) = 0, e the unit
/// vector I→J), KEYOPT(1)=1, the rigid beam (all six dofs: J moves rigidly with I, an RBE2);
/// KEYOPT(2)=0 (direct elimination) and 1 (Lagrange multipliers) impose the same constraint.
/// Other KEYOPT(1) values (the slider and the joints) are refused.
fn mpc184(t: &ElementType, rec: &ElementRecord) -> Result<Formed, Refusal> {
    unsupported_keyopts(t, &[1, 2])?;
    let nodes: Vec<u64> = rec.nodes.iter().copied().filter(|&n| n != 0).collect();
    let [a, b] = nodes[..] else {
        return Err(format!(
            "MPC184 with {} nodes (I and J expected)",
            nodes.len()
        ));
    };
    if a == b {
        return Err("MPC184 from a node to itself".into());
    }
    match (
        t.keyopts.get(&1).copied().unwrap_or(0),
        t.keyopts.get(&2).copied().unwrap_or(0),
    ) {
        (_, k2) if k2 != 0 && k2 != 1 => Err(format!("MPC184 KEYOPT(2)={k2}: not formed here")),
        (0, _) => Ok(Formed::RigidLink(a, b)),
        (1, _) => Ok(Formed::RigidBeam(a, b)),
        (k1, _) => Err(format!(
            "MPC184 KEYOPT(1)={k1} (a slider or joint): not formed here"
        )),
    }
}

/// SOLID186 (MAPDL Theory Reference §13.186): the 20-node brick with uniform reduced 2×2×2
/// integration (KEYOPT(2)=0, the default: C3D20R's K, the mass on Irons' 14 points) or full
/// integration on Irons' 14 points (KEYOPT(2)=1: K and mass); its degenerate shapes as
/// [`brick20`] forms them, whatever KEYOPT(2) says (the Theory Reference's table).
fn solid186(t: &ElementType, rec: &ElementRecord) -> Result<Formed, Refusal> {
    unsupported_keyopts(t, &[2])?;
    let rule = match t.keyopts.get(&2).copied().unwrap_or(0) {
        0 => Brick20Rule::Reduced,
        1 => Brick20Rule::Irons14,
        k => return Err(format!("SOLID186 KEYOPT(2)={k}: not an option of SOLID186")),
    };
    brick20("SOLID186", rec, rule)
}

/// How a 20-node brick written with 20 distinct nodes is integrated (ANSYS's SOLID186 and the
/// archived SOLID95; their degenerate shapes take the Theory Reference's rule per shape).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Brick20Rule {
    /// K on 2×2×2 points, the mass on Irons' 14 (SOLID186 KEYOPT(2)=0): [`ElementKind::Hex20R`].
    Reduced,
    /// K and mass on Irons' 14 points (SOLID186 KEYOPT(2)=1, SOLID95 KEYOPT(11)=0):
    /// [`ElementKind::Hex20`].
    Irons14,
    /// K and mass on 2×2×2 points (SOLID95 KEYOPT(11)=1): [`ElementKind::Hex20R`] with its
    /// index in `Model::hex20_mass_2x2x2` (`legacy::solid_rule`).
    Gauss2,
}

/// A 20-node brick record of element `name` (SOLID186, SOLID95): with 20 distinct nodes the
/// brick on `rule`; written as a collapsed brick in ANSYS's wedge or tetrahedron pattern
/// ([`degenerate_shape`]) the 15-node wedge on the 3 × 3 rule, the 10-node tetrahedron on 4
/// points or ANSYS's 13-node pyramid on 2×2×2 points ([`ElementKind::Pyram13Ansys`]); dropped
/// mid-side nodes are refused.
pub(super) fn brick20(
    name: &str,
    rec: &ElementRecord,
    rule: Brick20Rule,
) -> Result<Formed, Refusal> {
    let n = &rec.nodes;
    if n.len() != 20 || n.contains(&0) {
        return Err(format!(
            "{name} with {} of its 20 nodes (dropped mid-side nodes): not formed here",
            n.iter().filter(|&&v| v != 0).count()
        ));
    }
    if distinct(n) {
        let kind = match rule {
            Brick20Rule::Irons14 => ElementKind::Hex20,
            Brick20Rule::Reduced | Brick20Rule::Gauss2 => ElementKind::Hex20R,
        };
        return Ok(Formed::Element(kind, n.clone()));
    }
    match degenerate_shape(n) {
        Some(Degenerate::Wedge) => Ok(Formed::Element(ElementKind::Prism15, pick(n, &WEDGE))),
        Some(Degenerate::Tetrahedron) => Ok(Formed::Element(ElementKind::Tet10, pick(n, &TET))),
        Some(Degenerate::Pyramid) => Ok(Formed::Element(
            ElementKind::Pyram13Ansys,
            pick(n, &PYRAMID),
        )),
        None => Err(format!(
            "{name} with repeated nodes in no pattern of ANSYS's degenerate shapes (wedge: \
             K = L = S, O = P = W, A = B; tetrahedron: K = L = S, M…P = U…X, A = B; pyramid: \
             M…P = U…X): not formed here"
        )),
    }
}

/// SOLID45 (module doc): KEYOPT(1)=0 (the default) with 8 unique nodes, the brick with Wilson's
/// incompatible modes and Taylor's correction ([`ElementKind::Hex8`] with incompatible modes);
/// KEYOPT(1)=1, the trilinear brick on 2×2×2 points ([`ElementKind::Hex8`] without them, in an
/// archive whose other bricks have none: `legacy::Archive::archived_solid_rules`); collapsed into
/// ANSYS's wedge (K = L, O = P), either KEYOPT(1), the brick as written on 2×2×2 points
/// ([`ElementKind::Hex8Bbar`]'s wedge). Refused by line: KEYOPT(2)=1 (one point with
/// Flanagan–Belytschko hourglass control, whose hourglass stiffness the text does not give, as
/// SOLID185 KEYOPT(2)=1), the pyramid and tetrahedron patterns, KEYOPTs other than the output
/// controls KEYOPT(5) and KEYOPT(6) (the element axes KEYOPT(4), the initial stress subroutine
/// KEYOPT(9)).
pub(super) fn solid45(t: &ElementType, rec: &ElementRecord) -> Result<Formed, Refusal> {
    unsupported_keyopts(t, &[1, 2, 5, 6])?;
    match t.keyopts.get(&2).copied().unwrap_or(0) {
        0 => {}
        1 => {
            return Err(
                "SOLID45 KEYOPT(2)=1 (uniform reduced integration with Flanagan–Belytschko \
                 hourglass control): its hourglass stiffness is not given in the Theory \
                 Reference (as SOLID185 KEYOPT(2)=1): not formed here"
                    .into(),
            )
        }
        k => return Err(format!("SOLID45 KEYOPT(2)={k}: not an option of SOLID45")),
    }
    // KEYOPT(1): 0 with the extra shapes, 1 without (`solid_rule` records which: flexbody's
    // incompatible modes are model-wide)
    if let k @ 2.. | k @ ..=-1 = t.keyopts.get(&1).copied().unwrap_or(0) {
        return Err(format!("SOLID45 KEYOPT(1)={k}: not an option of SOLID45"));
    }
    let n = &rec.nodes;
    if n.len() != 8 || n.contains(&0) {
        return Err("SOLID45 without its 8 nodes".into());
    }
    if distinct(n) {
        return Ok(Formed::Element(ElementKind::Hex8, n.clone()));
    }
    if collapsed_wedge8(n) {
        return Ok(Formed::Element(ElementKind::Hex8Bbar, n.clone()));
    }
    Err(
        "SOLID45 with repeated nodes other than ANSYS's wedge (K = L, O = P): the collapsed \
         pyramid and tetrahedron are not formed here"
            .into(),
    )
}

/// SOLID95 (module doc): the 20-node brick on Irons' 14 points (KEYOPT(11)=0, the default) or
/// on 2×2×2 points (KEYOPT(11)=1), stiffness and mass alike; its degenerate shapes as
/// SOLID186's ([`brick20`]). Refused by line: KEYOPT(3)=1 (this element type's mass lumped —
/// "diagonalized as described in Lumped Matrices" — while flexbody's mass is consistent or
/// lumped for the whole body: `LUMPM`, `--mass`), KEYOPTs other than the output controls
/// KEYOPT(5) and KEYOPT(6) (the element axes KEYOPT(4), the initial stress subroutine
/// KEYOPT(9)), dropped mid-side nodes.
pub(super) fn solid95(t: &ElementType, rec: &ElementRecord) -> Result<Formed, Refusal> {
    unsupported_keyopts(t, &[3, 5, 6, 11])?;
    match t.keyopts.get(&3).copied().unwrap_or(0) {
        0 => {}
        1 => {
            return Err(
                "SOLID95 KEYOPT(3)=1 (lumped mass for this element type alone): flexbody's \
                 mass is consistent or lumped for the whole body (LUMPM,ON or --mass lumped), \
                 and ANSYS's diagonalization of the 20-node brick is not shown here: not \
                 formed here"
                    .into(),
            )
        }
        k => return Err(format!("SOLID95 KEYOPT(3)={k}: not an option of SOLID95")),
    }
    let rule = match t.keyopts.get(&11).copied().unwrap_or(0) {
        0 => Brick20Rule::Irons14,
        1 => Brick20Rule::Gauss2,
        k => return Err(format!("SOLID95 KEYOPT(11)={k}: not an option of SOLID95")),
    };
    brick20("SOLID95", rec, rule)
}

/// ANSYS's degenerate shapes of a 20-node brick (MAPDL Element Reference, SOLID186's geometry
/// figure; ansys-mapdl-reader reads them the same way).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Degenerate {
    Wedge,
    Pyramid,
    Tetrahedron,
}

/// The 20 node positions I…P, Q…X, Y…B, 0-based: the wedge's 15 nodes in C3D15's order (bottom
/// I, J, K; top M, N, O; edges IJ, JK, KI (T), MN, NO, OM (X); verticals IM, JN, KO (A)).
const WEDGE: [usize; 15] = [0, 1, 2, 4, 5, 6, 8, 9, 11, 12, 13, 15, 16, 17, 18];
/// The tetrahedron's 10 nodes in C3D10's order (I, J, K, apex M; IJ, JK, KI, IM, JM, KM).
const TET: [usize; 10] = [0, 1, 2, 4, 8, 9, 11, 16, 17, 18];
/// The pyramid's 13 nodes in [`ElementKind::Pyram13Ansys`]'s order (base I…L, apex M; base
/// edges Q…T; edges to the apex Y…B).
const PYRAMID: [usize; 13] = [0, 1, 2, 3, 4, 8, 9, 10, 11, 16, 17, 18, 19];

/// The shape of a brick written with repeated nodes: K = L = S (the edge KL collapsed), the top
/// face to one node (M…P and U…X equal), and what both make; `None` for another pattern. Every
/// node the shape keeps must be distinct.
fn degenerate_shape(n: &[u64]) -> Option<Degenerate> {
    let same = |ix: &[usize]| ix.iter().all(|&i| n[i] == n[ix[0]]);
    let kl = same(&[2, 3, 10]) && same(&[18, 19]);
    let apex = same(&[4, 5, 6, 7, 12, 13, 14, 15]);
    let wedge = kl && same(&[6, 7, 14]);
    let (shape, kept): (Degenerate, &[usize]) = match (kl, apex, wedge) {
        (true, true, _) => (Degenerate::Tetrahedron, &TET),
        (true, false, true) => (Degenerate::Wedge, &WEDGE),
        (false, true, _) => (Degenerate::Pyramid, &PYRAMID),
        _ => return None,
    };
    distinct(&pick(n, kept)).then_some(shape)
}

/// The ids at `positions`.
fn pick(n: &[u64], positions: &[usize]) -> Vec<u64> {
    positions.iter().map(|&i| n[i]).collect()
}

/// SOLID187: the 10-node tetrahedron (C3D10); with its mid-side nodes dropped the element's
/// displacement is linear on straight edges, which is exactly the 4-node tetrahedron (C3D4).
fn solid187(t: &ElementType, rec: &ElementRecord) -> Result<Formed, Refusal> {
    unsupported_keyopts(t, &[])?;
    let n = &rec.nodes;
    let corners = &n[..n.len().min(4)];
    if corners.len() < 4 || corners.contains(&0) || !distinct(corners) {
        return Err("SOLID187 without four distinct corner nodes".into());
    }
    let mids: Vec<u64> = n.iter().skip(4).copied().collect();
    if mids.iter().all(|&m| m == 0) {
        return Ok(Formed::Element(ElementKind::Tet4, corners.to_vec()));
    }
    if mids.len() != 6 || mids.contains(&0) || !distinct(n) {
        return Err(
            "SOLID187 with some of its mid-side nodes dropped: not formed here (all or none)"
                .into(),
        );
    }
    Ok(Formed::Element(ElementKind::Tet10, n.clone()))
}

/// MASS21: KEYOPT(3)=0 (3-D mass with rotary inertia: reals MASSX, MASSY, MASSZ, IXX, IYY, IZZ)
/// with MASSX = MASSY = MASSZ, or KEYOPT(3)=2 (3-D mass without rotary inertia: the real MASS),
/// in the global frame (KEYOPT(2)=0); directional masses and the 2-D forms are refused.
fn mass21(t: &ElementType, rec: &ElementRecord, reals: Option<&[f64]>) -> Result<Formed, Refusal> {
    unsupported_keyopts(t, &[3])?;
    let node = match rec.nodes.as_slice() {
        [n] if *n > 0 => *n,
        _ => return Err("MASS21 without its one node".into()),
    };
    let Some(r) = reals else {
        return Err(format!(
            "MASS21 with real constant set {} not defined",
            rec.real
        ));
    };
    let value = |k: usize| r.get(k).copied().unwrap_or(0.0);
    match t.keyopts.get(&3).copied().unwrap_or(0) {
        0 => {
            let (mx, my, mz) = (value(0), value(1), value(2));
            if mx != my || mx != mz {
                return Err(format!(
                    "MASS21 with directional masses MASSX={mx}, MASSY={my}, MASSZ={mz}: only \
                     equal masses are formed here"
                ));
            }
            // a rotary inertia is kept only on a node an MPC184 rigid beam joins (the model's
            // check after every element is formed): no other element read here has rotations
            let inertia = [value(3), value(4), value(5)];
            Ok(Formed::PointMass(node, mx, inertia))
        }
        2 => Ok(Formed::PointMass(node, value(0), [0.0; 3])),
        k => Err(format!(
            "MASS21 KEYOPT(3)={k} (a 2-D mass): formulation not formed here"
        )),
    }
}

/// SOLID185 (MAPDL Theory Reference §13.185): KEYOPT(2)=0, the default, the B-bar brick
/// (mean dilatation on 2×2×2 points, [`ElementKind::Hex8Bbar`]), also written as ANSYS's
/// collapsed wedge (K = L, O = P: the brick as written, fully integrated — what ANSYS's element
/// forces show); KEYOPT(2)=3, simplified enhanced strain — the 8-node brick with Wilson's
/// incompatible modes and Taylor's correction on 2×2×2 points, its mass the compatible brick's
/// on 2×2×2 ([`ElementKind::Hex8`] with `ModelParams::solid_bubbles`). Both shown against ANSYS
/// results (docs/ansys.md). Refused naming KEYOPT(2): uniform reduced with ANSYS's hourglass
/// control (1), enhanced strain (2); the collapsed pyramid and tetrahedron, a collapsed
/// KEYOPT(2)=3 brick, and the layered and mixed u-P forms (KEYOPT(3), KEYOPT(6)).
fn solid185(t: &ElementType, rec: &ElementRecord) -> Result<Formed, Refusal> {
    let k2 = t.keyopts.get(&2).copied().unwrap_or(0);
    let what = match k2 {
        0 => {
            unsupported_keyopts(t, &[2])?;
            let n = &rec.nodes;
            if n.len() != 8 || n.contains(&0) {
                return Err("SOLID185 without its 8 nodes".into());
            }
            if distinct(n) || collapsed_wedge8(n) {
                return Ok(Formed::Element(ElementKind::Hex8Bbar, n.clone()));
            }
            return Err(
                "SOLID185 KEYOPT(2)=0 with repeated nodes other than ANSYS's wedge (K = L, \
                 O = P): the collapsed pyramid and tetrahedron — no ANSYS result of them was \
                 at hand to show their form: not formed here"
                    .into(),
            );
        }
        1 => {
            "uniform reduced integration with ANSYS's hourglass control: its hourglass \
              stiffness is not shown here"
        }
        2 => {
            "enhanced strain (Simo–Rifai: 9 shear and 4 volumetric internal modes, ANSYS's \
              own): not shown here"
        }
        3 => {
            unsupported_keyopts(t, &[2])?;
            let n = &rec.nodes;
            if n.len() != 8 || n.contains(&0) || !distinct(n) {
                return Err(
                    "SOLID185 KEYOPT(2)=3 with repeated nodes (a degenerate wedge, \
                            pyramid or tetrahedron): ANSYS's form of the degenerate shapes is \
                            not shown here"
                        .into(),
                );
            }
            return Ok(Formed::Element(ElementKind::Hex8, n.clone()));
        }
        _ => "not an option of SOLID185",
    };
    Err(format!(
        "SOLID185 KEYOPT(2)={k2} ({what}): formulation not formed here"
    ))
}

/// An 8-node brick (SOLID185, SOLID45) collapsed into ANSYS's wedge: K = L and O = P (0-based
/// 2 = 3, 6 = 7), the six nodes kept distinct (MAPDL Element Reference, SOLID185's and
/// SOLID45's geometry figures).
pub(super) fn collapsed_wedge8(n: &[u64]) -> bool {
    n[2] == n[3] && n[6] == n[7] && distinct(&pick(n, &[0, 1, 2, 4, 5, 6]))
}

/// No id repeats.
pub(super) fn distinct(ids: &[u64]) -> bool {
    let mut v = ids.to_vec();
    v.sort_unstable();
    v.windows(2).all(|w| w[0] != w[1])
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A record of type 1, material 1, on line 9 with `nodes` (also `legacy`'s tests').
    pub(in crate::import::ansys) fn record(nodes: Vec<u64>) -> ElementRecord {
        ElementRecord {
            line: 9,
            id: 1,
            mat: 1,
            etype: 1,
            real: 0,
            section: 0,
            esys: 0,
            shape: Some(0),
            nodes,
        }
    }

    #[test]
    fn solid186_keyopt2_picks_the_rule_and_degenerate_bricks_their_shape() {
        let mut t = ElementType::new(3, "186");
        let nodes: Vec<u64> = (1..=20).collect();
        assert_eq!(
            form(&t, &record(nodes.clone()), None, None, None),
            Ok(Formed::Element(ElementKind::Hex20R, nodes.clone()))
        );
        t.keyopts.insert(2, 1);
        assert_eq!(
            form(&t, &record(nodes.clone()), None, None, None),
            Ok(Formed::Element(ElementKind::Hex20, nodes.clone()))
        );
        // the wedge: K = L = S (3), O = P = W (7), A = B (19)
        let mut wedge = nodes.clone();
        (wedge[3], wedge[10], wedge[7], wedge[14], wedge[19]) = (3, 3, 7, 7, 19);
        let want = vec![1, 2, 3, 5, 6, 7, 9, 10, 12, 13, 14, 16, 17, 18, 19];
        assert_eq!(
            form(&t, &record(wedge.clone()), None, None, None),
            Ok(Formed::Element(ElementKind::Prism15, want))
        );
        // the tetrahedron: K = L = S (3), M…P = U…X (5), A = B (19)
        let mut tet = wedge;
        for p in [4, 5, 6, 7, 12, 13, 14, 15] {
            tet[p] = 5;
        }
        assert_eq!(
            form(&t, &record(tet.clone()), None, None, None),
            Ok(Formed::Element(
                ElementKind::Tet10,
                vec![1, 2, 3, 5, 9, 10, 12, 17, 18, 19]
            ))
        );
        // the pyramid: M…P = U…X (5)
        let mut pyramid = nodes.clone();
        for p in [4, 5, 6, 7, 12, 13, 14, 15] {
            pyramid[p] = 5;
        }
        assert_eq!(
            form(&t, &record(pyramid), None, None, None),
            Ok(Formed::Element(
                ElementKind::Pyram13Ansys,
                vec![1, 2, 3, 4, 5, 9, 10, 11, 12, 17, 18, 19, 20]
            ))
        );
        // another pattern of repeats is refused
        tet[0] = 2;
        let why = form(&t, &record(tet), None, None, None).unwrap_err();
        assert!(why.contains("no pattern"), "{why}");
        t.keyopts.insert(2, 2);
        let why = form(&t, &record(nodes), None, None, None).unwrap_err();
        assert!(why.contains("SOLID186 KEYOPT(2)=2"), "{why}");
    }

    #[test]
    fn solid185_default_is_the_b_bar_brick_also_as_ansys_wedge() {
        let t = ElementType::new(3, "185");
        let brick: Vec<u64> = (1..=8).collect();
        assert_eq!(
            form(&t, &record(brick.clone()), None, None, None),
            Ok(Formed::Element(ElementKind::Hex8Bbar, brick))
        );
        // ANSYS's wedge: K = L, O = P, written as the 8 nodes
        let wedge = vec![1, 2, 3, 3, 5, 6, 7, 7];
        assert_eq!(
            form(&t, &record(wedge.clone()), None, None, None),
            Ok(Formed::Element(ElementKind::Hex8Bbar, wedge))
        );
        // a pyramid (M…P one node) and a tetrahedron are refused
        for n in [vec![1, 2, 3, 4, 5, 5, 5, 5], vec![1, 2, 3, 3, 5, 5, 5, 5]] {
            let why = form(&t, &record(n), None, None, None).unwrap_err();
            assert!(
                why.contains("SOLID185 KEYOPT(2)=0 with repeated nodes"),
                "{why}"
            );
        }
    }

    #[test]
    fn solid187_without_mid_sides_is_the_linear_tetrahedron() {
        let t = ElementType::new(3, "SOLID187");
        let r = record(vec![4, 5, 6, 7]);
        assert_eq!(
            form(&t, &r, None, None, None),
            Ok(Formed::Element(ElementKind::Tet4, vec![4, 5, 6, 7]))
        );
        let r = record(vec![4, 5, 6, 7, 8, 0, 0, 0, 0, 0]);
        assert!(form(&t, &r, None, None, None).is_err());
        let t = ElementType::new(3, "200");
        assert_eq!(form(&t, &r, None, None, None), Ok(Formed::NoStiffness));
        let t = ElementType::new(3, "181");
        assert!(form(&t, &r, None, None, None)
            .unwrap_err()
            .contains("SHELL181"));
    }

    #[test]
    fn mass21_keeps_its_rotary_inertia_for_the_model_to_check() {
        let t = ElementType::new(3, "21");
        let r = record(vec![22]);
        let mass_only = [2.0e-4, 2.0e-4, 2.0e-4, 0.0, 0.0, 0.0];
        assert_eq!(
            form(&t, &r, Some(&mass_only), None, None),
            Ok(Formed::PointMass(22, 2.0e-4, [0.0; 3]))
        );
        let with_inertia = [2.0e-4, 2.0e-4, 2.0e-4, 1.0e-7, 0.0, 0.0];
        assert_eq!(
            form(&t, &r, Some(&with_inertia), None, None),
            Ok(Formed::PointMass(22, 2.0e-4, [1.0e-7, 0.0, 0.0]))
        );
    }
}
