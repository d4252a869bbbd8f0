//! ANSYS surface-based constraints (a remote point: a TARGE170 pilot joined to CONTA174 faces or
//! CONTA175 nodes by MPC bonded contact), archives written here in CDWRITE's layout (the SOLID
//! EBLOCK, TARGE170's shape key 19 in field 8), through the CLI, each against the same mesh and
//! constraint written as a CalculiX deck through the ccx importer:
//! - the rigid surface constraint (CONTA174 KEYOPT(4)=2, CONTA175 KEYOPT(4)=0) against
//!   `*COUPLING` + `*KINEMATIC` 1…3, a MASS21 with rotary inertia on the pilot as `*MASS` and
//!   `*ROTARY INERTIA`, `F` forces and moments on the pilot as `*CLOAD`;
//! - the force-distributed constraint (CONTA174 KEYOPT(4)=1) against `*DISTRIBUTING` (the RBE3
//!   with ccx's area weights), and its weights in closed form (an axial pilot force reaches the
//!   face as the consistent nodal forces of a uniform traction);
//! - bonded MPC contact between surfaces (CONTA174 faces of one part on TARGE170 faces of
//!   another, meshed apart) against `*TIE` with ADJUST=NO, the pinball radius as POSITION
//!   TOLERANCE; contact nodes outside the pinball left free and counted;
//! - the pilot as `--interface`, by its number and by a `CMBLOCK` component, a Craig–Bampton
//!   body whose fixed-interface modes equal the ccx build's;
//! - the forms not read refused by line.
//!
//! Static responses come from the file alone (residual vectors of the scene loads), compared node
//! by node over the largest displacement.

use std::path::Path;

use crate::ansys_support::writers::{
    block, build_body as build, ccx_deck, frequency_difference, material, nblock,
    response_difference, root, static_response, Block, RESIDUALS,
};
use crate::common::{exe, scratch};

/// The pilot node: beyond the tip face's centre.
const PILOT: u64 = 9001;
const PILOT_AT: [f64; 3] = [0.75, 0.05, 0.05];
/// The MASS21 on the pilot: mass and rotary inertias IXX, IYY, IZZ.
const MASS: f64 = 3.0;
const INERTIA: [f64; 3] = [0.02, 0.05, 0.04];

/// The cantilever: 6 × 2 × 2 SOLID186 (C3D20R) over 0.6 × 0.1 × 0.1, clamped at x = 0.
fn beam() -> Block {
    block([6, 2, 2], [0.6, 0.1, 0.1], true)
}

/// The x = 0.6 faces of the bricks at the tip as CONTA174 records: corners J, K, O, N and the
/// mid-sides of J-K, K-O, O-N, N-J (the brick's face 3, C3D20's S4).
fn tip_faces(m: &Block) -> Vec<Vec<u64>> {
    (m.elements.iter())
        .filter(|e| e[1..3].iter().all(|n| m.nodes[n][0] == 0.6))
        .map(|e| vec![e[1], e[2], e[6], e[5], e[9], e[18], e[13], e[17]])
        .collect()
}

/// An EBLOCK (SOLID layout) of (type, real constant set, shape key, nodes) records, ids 1, 2, ….
fn eblock(records: &[(usize, usize, usize, Vec<u64>)]) -> String {
    let mut s = format!("EBLOCK,19,SOLID,{0},{0}\n(19i9)\n", records.len());
    for (k, (etype, real, shape, nodes)) in records.iter().enumerate() {
        let head = [1, *etype, *real, 1, 0, 0, 0, *shape, nodes.len(), 0, k + 1];
        let mut fields: Vec<String> = head.iter().map(|v| format!("{v:>9}")).collect();
        fields.extend(nodes.iter().map(|v| format!("{v:>9}")));
        for (i, f) in fields.iter().enumerate() {
            if i == 19 {
                s.push('\n');
            }
            s.push_str(f);
        }
        s.push('\n');
    }
    s.push_str("       -1\n");
    s
}

/// The contact and target element types of a pair: CONTA`contact` (type 3) with KEYOPT(4)=`k4`,
/// TARGE170 (type 2) with KEYOPT(4)=`dofs`, `extra` KEYOPT lines after them.
fn pair_types(contact: u32, k4: u32, dofs: u32, extra: &str) -> String {
    format!(
        "ET,        2,170\nKEYOP,        2, 2,        1\nKEYOP,        2, 4,   {dofs}\n\
         ET,        3,{contact}\nKEYOP,        3, 2,        2\nKEYOP,        3, 4,        {k4}\n\
         KEYOP,        3,12,        5\n{extra}"
    )
}

/// The beam with a remote point on its tip: `types` (element types 2 and 3, the pair),
/// `contacts` (the CONTA records' nodes), the pilot's MASS21, `extra` lines (loads, real
/// constants) before FINISH.
fn archive(m: &Block, types: &str, contacts: &[Vec<u64>], extra: &str) -> String {
    let mut nodes: Vec<(u64, [f64; 3], [f64; 3])> = (m.nodes.iter())
        .map(|(&id, &x)| (id, x, [0.0; 3]))
        .collect();
    nodes.push((PILOT, PILOT_AT, [0.0; 3]));
    let mut records: Vec<(usize, usize, usize, Vec<u64>)> =
        (m.elements.iter()).map(|e| (1, 1, 0, e.clone())).collect();
    records.extend(contacts.iter().map(|c| (3, 3, 0, c.clone())));
    records.push((2, 3, 19, vec![PILOT]));
    records.push((4, 4, 0, vec![PILOT]));
    let clamp: String = root(m).iter().map(|n| format!("D,{n},ALL,0\n")).collect();
    let [ixx, iyy, izz] = INERTIA;
    format!(
        "/PREP7\nET,        1,186\n{types}ET,        4,21\n{}{}{}\
         R,3\nR,4,{MASS:e},{MASS:e},{MASS:e},{ixx:e},{iyy:e},{izz:e}\n{clamp}{extra}FINISH\n",
        nblock(&nodes),
        eblock(&records),
        material(crate::ansys_support::writers::STEEL),
    )
}

/// Forces and moments on the pilot: (component 1…6, value).
const LOADS: [(usize, f64); 4] = [(1, 2.0e3), (2, 1.0e3), (3, -1.5e3), (4, 300.0)];

fn ansys_loads() -> String {
    let labels = ["FX", "FY", "FZ", "MX", "MY", "MZ"];
    (LOADS.iter())
        .map(|(c, v)| format!("F,{PILOT},{},{v:e}\n", labels[c - 1]))
        .collect()
}

/// The beam as a CalculiX deck with the coupling `coupling` (its `*KINEMATIC` or
/// `*DISTRIBUTING` lines) of the pilot to the tip faces (S4), the pilot's mass and inertia, the
/// pilot loads as `*CLOAD` in the static step.
fn ccx_reference(m: &Block, coupling: &str) -> String {
    let tip: Vec<usize> = (m.elements.iter().enumerate())
        .filter(|(_, e)| e[1..3].iter().all(|n| m.nodes[n][0] == 0.6))
        .map(|(k, _)| k + 1)
        .collect();
    let [x, y, z] = PILOT_AT;
    let [ixx, iyy, izz] = INERTIA;
    let mut s = format!(
        "*NODE\n{PILOT}, {x:?}, {y:?}, {z:?}\n*NSET, NSET=PILOTSET\n{PILOT}\n\
         *SURFACE, NAME=TIP, TYPE=ELEMENT\n"
    );
    for e in tip {
        s += &format!("{e}, S4\n");
    }
    s += &format!(
        "*COUPLING, REF NODE={PILOT}, SURFACE=TIP, CONSTRAINT NAME=RP\n{coupling}\
         *ELEMENT, TYPE=MASS, ELSET=PM\n90001, {PILOT}\n*MASS, ELSET=PM\n{MASS:e}\n\
         *ROTARY INERTIA, ELSET=PM\n{ixx:e}, {iyy:e}, {izz:e}, 0., 0., 0.\n"
    );
    let cload: String = (LOADS.iter())
        .map(|(c, v)| format!("{PILOT}, {c}, {v:e}\n"))
        .collect();
    ccx_deck(m, &format!("*CLOAD\n{cload}")).replacen("*STEP", &format!("{s}*STEP"), 1)
}

/// Builds the archive and the ccx deck (lumped mass, residual vectors of the loads): the
/// largest frequency and static response differences.
pub(crate) fn against_ccx(name: &str, cdb_text: &str, inp_text: &str) -> (f64, f64) {
    let work = scratch(name);
    let cdb = work.join("remote.cdb");
    std::fs::write(&cdb, cdb_text).unwrap();
    let inp = work.join("remote.inp");
    std::fs::write(&inp, inp_text).unwrap();
    let args = ["--mass", "lumped", RESIDUALS[0], RESIDUALS[1]];
    let ours = build(&cdb, 8, &args);
    let ccx = build(&inp, 8, &args);
    let modes = frequency_difference(&ours, &ccx, 8);
    let static_ = response_difference(&static_response(&ours, 0), &static_response(&ccx, 0));
    (modes, static_)
}

/// Builds two archives as [`against_ccx`] does: the largest frequency and static response
/// differences.
pub(crate) fn against_archive(name: &str, a: &str, b: &str) -> (f64, f64) {
    let work = scratch(name);
    let (pa, pb) = (work.join("a.cdb"), work.join("b.cdb"));
    std::fs::write(&pa, a).unwrap();
    std::fs::write(&pb, b).unwrap();
    let args = ["--mass", "lumped", RESIDUALS[0], RESIDUALS[1]];
    let (ba, bb) = (build(&pa, 8, &args), build(&pb, 8, &args));
    let modes = frequency_difference(&ba, &bb, 8);
    let static_ = response_difference(&static_response(&ba, 0), &static_response(&bb, 0));
    (modes, static_)
}

/// The rigid surface constraint of CONTA174 faces (KEYOPT(4)=2) equals `*KINEMATIC` 1…3 on the
/// same faces: the pilot's mass and rotary inertia carried by the tip, the pilot's forces and
/// moment reaching the beam.
#[test]
fn rigid_surface_constraint_equals_the_ccx_kinematic_coupling() {
    let m = beam();
    let cdb = archive(
        &m,
        &pair_types(174, 2, 111111, ""),
        &tip_faces(&m),
        &ansys_loads(),
    );
    let inp = ccx_reference(&m, "*KINEMATIC\n1, 3\n");
    let (modes, static_) = against_ccx("ansys-contact-rigid", &cdb, &inp);
    println!("rigid CONTA174 against *KINEMATIC: frequencies {modes:.2e}, static {static_:.2e}");
    // measured 2.1e-12 and 3.6e-12 (the same RBE2: the two builds' eigensolves)
    assert!(modes < 2e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");
}

/// CONTA175 on each tip node (KEYOPT(4)=0, Workbench's rigid remote point on nodes) equals the
/// same `*KINEMATIC` coupling.
#[test]
fn rigid_conta175_nodes_equal_the_ccx_kinematic_coupling() {
    let m = beam();
    let mut tip: Vec<u64> = tip_faces(&m).concat();
    tip.sort_unstable();
    tip.dedup();
    let nodes: Vec<Vec<u64>> = tip.iter().map(|&n| vec![n]).collect();
    let cdb = archive(&m, &pair_types(175, 0, 0, ""), &nodes, &ansys_loads());
    let inp = ccx_reference(&m, "*KINEMATIC\n1, 3\n");
    let (modes, static_) = against_ccx("ansys-contact-175", &cdb, &inp);
    println!("rigid CONTA175 against *KINEMATIC: frequencies {modes:.2e}, static {static_:.2e}");
    // measured 2.1e-12 and 3.6e-12
    assert!(modes < 2e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");
}

/// The force-distributed constraint (CONTA174 KEYOPT(4)=1) equals `*DISTRIBUTING` 1…6 on the
/// same faces: an RBE3 at the pilot weighted by the faces' consistent nodal areas (on these flat
/// rectangles ANSYS's shape-function weights and ccx's 2 × 2 rule agree exactly).
#[test]
fn force_distributed_constraint_equals_the_ccx_distributing_coupling() {
    let m = beam();
    let cdb = archive(
        &m,
        &pair_types(174, 1, 111111, ""),
        &tip_faces(&m),
        &ansys_loads(),
    );
    let inp = ccx_reference(&m, "*DISTRIBUTING\n1, 6\n");
    let (modes, static_) = against_ccx("ansys-contact-distributed", &cdb, &inp);
    println!(
        "CONTA174 KEYOPT(4)=1 against *DISTRIBUTING: frequencies {modes:.2e}, static {static_:.2e}"
    );
    // measured 2.0e-12 and 3.6e-12
    assert!(modes < 2e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");
    // the two kinds are told apart: the rigid archive is far from the distributing reference
    let rigid = archive(
        &m,
        &pair_types(174, 2, 111111, ""),
        &tip_faces(&m),
        &ansys_loads(),
    );
    let (apart, _) = against_ccx("ansys-contact-distributed-rigid", &rigid, &inp);
    println!("rigid CONTA174 against *DISTRIBUTING: frequencies {apart:.2e}");
    assert!(apart > 1e-3, "{apart:e}");
}

/// `build --method cb --interface …`: the body and the build report's fixed-interface
/// frequencies.
fn craig_bampton(path: &Path, interface: &str) -> (Vec<u64>, Vec<f64>) {
    let out = path.with_extension("flexbody");
    let o = exe()
        .arg("build")
        .arg(path)
        .args(["--units", "si", "--mass", "lumped", "--method", "cb"])
        .args([
            "--modes",
            "6",
            "--interface",
            interface,
            "--json",
            "-q",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let body = flexbody_reader::read(&out).unwrap();
    let iface = (body.nodes.iter().filter(|n| n.interface))
        .map(|n| n.id)
        .collect();
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let hz = (report["fixed_interface_hz"].as_array().unwrap().iter())
        .map(|f| f.as_f64().unwrap())
        .collect();
    (iface, hz)
}

/// The pilot as `--interface`, by its number and by a `CMBLOCK` node component holding it: a
/// Craig–Bampton body with the pilot its one interface node, whose fixed-interface modes (the
/// pilot held) equal the ccx build's with the coupling's reference node as interface.
#[test]
fn the_pilot_is_the_craig_bampton_interface_by_number_and_component() {
    let m = beam();
    let component = format!("CMBLOCK,REMOTE,NODE,        1\n(8i10)\n{PILOT:>10}\n");
    let cdb_text = archive(
        &m,
        &pair_types(174, 2, 111111, ""),
        &tip_faces(&m),
        &component,
    );
    let work = scratch("ansys-contact-interface");
    let cdb = work.join("remote.cdb");
    std::fs::write(&cdb, cdb_text).unwrap();
    let inp = work.join("remote.inp");
    std::fs::write(&inp, ccx_reference(&m, "*KINEMATIC\n1, 3\n")).unwrap();
    let (by_number, hz_number) = craig_bampton(&cdb, &PILOT.to_string());
    let (by_name, hz_name) = craig_bampton(&cdb, "REMOTE");
    let (ccx_iface, hz_ccx) = craig_bampton(&inp, "RP");
    assert_eq!(by_number, [PILOT]);
    assert_eq!(by_name, [PILOT]);
    assert_eq!(ccx_iface, [PILOT]);
    let worst = (hz_number
        .iter()
        .zip(&hz_ccx)
        .chain(hz_name.iter().zip(&hz_ccx)))
    .map(|(a, b)| ((a - b) / b).abs())
    .fold(0.0, f64::max);
    println!("fixed-interface frequencies {hz_number:?} against ccx: {worst:.2e}");
    assert_eq!(hz_number.len(), 6);
    // measured 2.1e-14
    assert!(worst < 2e-13, "{worst:e}");
}

/// `flexbody build` of an archive expected to be refused: exit 2 and the message.
pub(crate) fn refused(name: &str, text: &str) -> String {
    let work = scratch(name);
    let cdb = work.join("refused.cdb");
    std::fs::write(&cdb, text).unwrap();
    let o = exe()
        .arg("build")
        .arg(&cdb)
        .args(["--units", "si", "--method", "normal", "--modes", "4", "-o"])
        .arg(cdb.with_extension("flexbody"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{name} was not refused");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// TARGE170 KEYOPT(4)=111 on a force-distributed pilot names the pilot's translations (the units
/// digit UX, docs/ansys.md: ANSYS's pilots of ansys-mapdl-reader's `materials/file.rst`): the
/// archive equals `*DISTRIBUTING` 1…3 (the RBE3 with reference dofs 123) on the same faces. The
/// pilot carries a MASS21 without rotary inertia (KEYOPT(3)=2) and forces only: its rotations
/// are no dofs of the body, as in ANSYS's field. Read the other way (ROTX…ROTZ) the pilot's
/// translations would be free: the same archive with 111000 fails the build's verification
/// with three zero-frequency modes (checked once by hand).
#[test]
fn force_distributed_pilot_dofs_111_are_the_translations() {
    let m = beam();
    let forces: String = (LOADS.iter().filter(|(c, _)| *c <= 3))
        .map(|(c, v)| format!("F,{PILOT},{},{v:e}\n", ["FX", "FY", "FZ"][c - 1]))
        .collect();
    let [ixx, iyy, izz] = INERTIA;
    let cdb = archive(&m, &pair_types(174, 1, 111, ""), &tip_faces(&m), &forces)
        .replace(
            "ET,        4,21\n",
            "ET,        4,21\nKEYOP,        4, 3,        2\n",
        )
        .replace(
            &format!("R,4,{MASS:e},{MASS:e},{MASS:e},{ixx:e},{iyy:e},{izz:e}\n"),
            &format!("R,4,{MASS:e}\n"),
        );
    assert!(cdb.contains(&format!("R,4,{MASS:e}\n")));
    let moment = format!("{PILOT}, 4, {:e}\n", LOADS[3].1);
    let rotary = format!("*ROTARY INERTIA, ELSET=PM\n{ixx:e}, {iyy:e}, {izz:e}, 0., 0., 0.\n");
    let full = ccx_reference(&m, "*DISTRIBUTING\n1, 3\n");
    assert!(full.contains(&moment) && full.contains(&rotary));
    let inp = full.replace(&moment, "").replace(&rotary, "");
    let (modes, static_) = against_ccx("ansys-contact-pilot-111", &cdb, &inp);
    println!(
        "TARGE170 KEYOPT(4)=111 against *DISTRIBUTING 1, 3: frequencies {modes:.2e}, \
         static {static_:.2e}"
    );
    // measured 2.5e-12 and 4.9e-12
    assert!(modes < 2e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");
}

/// The forms not read are refused by line, naming the KEYOPT or constant: a penalty or
/// augmented Lagrange contact, standard contact, a pinball radius, TARGE170 KEYOPT(2)=0, a subset
/// of the pilot dofs on a rigid surface constraint; target faces (bonded contact between surfaces) with
/// ANSYS's default pinball.
#[test]
fn contact_forms_not_read_are_refused_by_line() {
    let m = beam();
    let faces = tip_faces(&m);
    // the first CONTA174 record's line: after the header, the NBLOCK and the bricks' records
    let cases = [
        (
            "KEYOP,        3, 2,        0\n",
            "",
            "KEYOPT(2)=0 (augmented Lagrange)",
        ),
        ("KEYOP,        3,12,        0\n", "", "KEYOPT(12)=0"),
        ("", "R,3,0,0,0,0,0,-0.05\n", "PINB (constant 6)"),
        ("KEYOP,        2, 2,        0\n", "", "TARGE170 KEYOPT(2)=0"),
        ("KEYOP,        2, 4,   111\n", "", "TARGE170 KEYOPT(4)=111"),
        ("KEYOP,        3, 4,        3\n", "", "CONTA174 KEYOPT(4)=3"),
    ];
    for (k, (keyopt, real, expect)) in cases.iter().enumerate() {
        let text = archive(&m, &pair_types(174, 2, 111111, keyopt), &faces, real);
        let err = refused(&format!("ansys-contact-refused-{k}"), &text);
        assert!(err.contains(expect), "{expect}: {err}");
        assert!(err.contains("refused.cdb:"), "{err}");
    }
    // TARGE170 faces (the other bonded contact) instead of a pilot
    let mut text = archive(&m, &pair_types(174, 2, 0, ""), &faces, "");
    text = text.replace(
        &format!(
            "{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}",
            1, 2, 3, 1, 0, 0, 0, 19, 1
        ),
        &format!(
            "{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}",
            1, 2, 3, 1, 0, 0, 0, 6, 1
        ),
    );
    let err = refused("ansys-contact-refused-faces", &text);
    assert!(err.contains("PINB = 0"), "{err}");
}

/// Two parts meshed apart: `a` over [0, 0.3] (3 × 2 × 2 bricks) and `b` over [0.3, 0.6]
/// (3 × 3 × 3, ids from 10 001), as one mesh (a's elements first).
pub(crate) fn two_parts() -> (Block, usize) {
    parts_meshing_a_as([3, 2, 2])
}

/// [`two_parts`] with `a` meshed by `cells` bricks; with the first part's element count.
pub(crate) fn parts_meshing_a_as(cells: [usize; 3]) -> (Block, usize) {
    let a = block(cells, [0.3, 0.1, 0.1], true);
    let b = block([3, 3, 3], [0.3, 0.1, 0.1], true);
    let mut m = Block {
        nodes: a.nodes.clone(),
        elements: a.elements.clone(),
    };
    for (id, x) in &b.nodes {
        m.nodes.insert(id + 10_000, [x[0] + 0.3, x[1], x[2]]);
    }
    (m.elements).extend(
        b.elements
            .iter()
            .map(|e| e.iter().map(|n| n + 10_000).collect()),
    );
    (m, a.elements.len())
}

/// The faces at x = `at` of the bricks with a corner there: x-min faces (corners I, L, P, M
/// and the mid-sides of I-L, L-P, P-M, M-I: C3D20's S6) or x-max faces (as [`tip_faces`]:
/// S4); with the 1-based element numbers.
pub(crate) fn faces_at(m: &Block, at: f64, x_min: bool) -> Vec<(usize, Vec<u64>)> {
    (m.elements.iter().enumerate())
        .filter(|(_, e)| {
            let corners: &[usize] = if x_min { &[0, 3, 7, 4] } else { &[1, 2, 6, 5] };
            corners.iter().all(|&k| m.nodes[&e[k]][0] == at)
        })
        .map(|(k, e)| {
            let face = if x_min {
                vec![e[0], e[3], e[7], e[4], e[11], e[19], e[15], e[16]]
            } else {
                vec![e[1], e[2], e[6], e[5], e[9], e[18], e[13], e[17]]
            };
            (k + 1, face)
        })
        .collect()
}

/// The far corner of the second part and the loads on it: (component, value).
const FAR: u64 = 10_000 + 7 * 7 * 7;
const FAR_LOADS: [(usize, f64); 2] = [(2, 1.0e3), (3, -500.0)];

/// The two parts as an archive: CONTA174 (type 3, KEYOPT(4)=2) on `contacts`, TARGE170 QUA8
/// faces (type 2, shape key 9) on the first part's x = 0.3 faces, real constant set 3 with
/// PINB = −`pinball`; clamped at x = 0, `F` on the far corner.
pub(crate) fn bonded_archive(m: &Block, contacts: &[Vec<u64>], pinball: f64) -> String {
    let nodes: Vec<(u64, [f64; 3], [f64; 3])> = (m.nodes.iter())
        .map(|(&id, &x)| (id, x, [0.0; 3]))
        .collect();
    let mut records: Vec<(usize, usize, usize, Vec<u64>)> =
        (m.elements.iter()).map(|e| (1, 1, 0, e.clone())).collect();
    records.extend(contacts.iter().map(|c| (3, 3, 0, c.clone())));
    records.extend(
        faces_at(m, 0.3, false)
            .into_iter()
            .map(|(_, f)| (2, 3, 9, f)),
    );
    let clamp: String = root(m).iter().map(|n| format!("D,{n},ALL,0\n")).collect();
    let loads: String = (FAR_LOADS.iter())
        .map(|(c, v)| format!("F,{FAR},{},{v:e}\n", ["FX", "FY", "FZ"][c - 1]))
        .collect();
    format!(
        "/PREP7\nET,        1,186\nET,        2,170\nET,        3,174\n\
         KEYOP,        3, 2,        2\nKEYOP,        3, 4,        2\nKEYOP,        3,12,        5\n\
         {}{}{}R,3,0,0,0,0,0,{:e}\n{clamp}{loads}FINISH\n",
        nblock(&nodes),
        eblock(&records),
        material(crate::ansys_support::writers::STEEL),
        -pinball
    )
}

/// The two parts as a CalculiX deck: the second part's x = 0.3 faces (S6) tied to the first
/// part's (S4) by `*TIE` with POSITION TOLERANCE = `pinball` and ADJUST=NO, the far corner's
/// loads as `*CLOAD`.
pub(crate) fn bonded_ccx(m: &Block, first_part: usize, pinball: f64) -> String {
    bonded_ccx_at(m, first_part, pinball, 0.3)
}

/// [`bonded_ccx`] with the second part's faces at x = `slave_at`.
fn bonded_ccx_at(m: &Block, first_part: usize, pinball: f64, slave_at: f64) -> String {
    let mut s = String::from("*SURFACE, NAME=SLAVE, TYPE=ELEMENT\n");
    for (e, _) in faces_at(m, slave_at, true)
        .iter()
        .filter(|(e, _)| *e > first_part)
    {
        s += &format!("{e}, S6\n");
    }
    s += "*SURFACE, NAME=MASTER, TYPE=ELEMENT\n";
    for (e, _) in faces_at(m, 0.3, false)
        .iter()
        .filter(|(e, _)| *e <= first_part)
    {
        s += &format!("{e}, S4\n");
    }
    s += &format!("*TIE, NAME=GLUE, POSITION TOLERANCE={pinball:e}, ADJUST=NO\nSLAVE, MASTER\n");
    let cload: String = (FAR_LOADS.iter())
        .map(|(c, v)| format!("{FAR}, {c}, {v:e}\n"))
        .collect();
    ccx_deck(m, &format!("*CLOAD\n{cload}")).replacen("*STEP", &format!("{s}*STEP"), 1)
}

/// Bonded MPC contact between two parts meshed apart (3 × 3 contact faces on 2 × 2 target
/// faces) equals `*TIE` with ADJUST=NO on the same faces: every contact node on a target face,
/// u = Σ Nᵢ uᵢ of the face's shape functions. With CONTA174 also on the second part's far face
/// (x = 0.6, beyond the pinball) those nodes stay free: the same body, and the note counts them.
#[test]
fn bonded_contact_between_surfaces_equals_the_ccx_tie() {
    let (m, first_part) = two_parts();
    let glue: Vec<Vec<u64>> = (faces_at(&m, 0.3, true).into_iter())
        .filter(|(e, _)| *e > first_part)
        .map(|(_, f)| f)
        .collect();
    assert_eq!(glue.len(), 9);
    let inp = bonded_ccx(&m, first_part, 1e-3);
    let (modes, static_) = against_ccx(
        "ansys-contact-bonded",
        &bonded_archive(&m, &glue, 1e-3),
        &inp,
    );
    println!(
        "bonded CONTA174 on TARGE170 against *TIE: frequencies {modes:.2e}, static {static_:.2e}"
    );
    // measured 3.4e-12 and 3.7e-12 (the same MPCs: the two builds' eigensolves)
    assert!(modes < 3.4e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");
    // the far face's contact nodes are outside the pinball: free
    let far: Vec<Vec<u64>> = (faces_at(&m, 0.6, false).into_iter())
        .map(|(_, f)| f)
        .collect();
    let with_far = bonded_archive(&m, &[glue, far].concat(), 1e-3);
    let (modes, static_) = against_ccx("ansys-contact-bonded-far", &with_far, &inp);
    println!("with far contact nodes: frequencies {modes:.2e}, static {static_:.2e}");
    assert!(modes < 3.4e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");
    // the note: 40 nodes of the 3 × 3 quadratic faces tied (7 × 7 less the 9 face centres),
    // the far face's 40 left free
    let cdb = scratch("ansys-contact-bonded-note").join("far.cdb");
    std::fs::write(&cdb, &with_far).unwrap();
    let o = crate::ansys_support::build(&cdb, "si", 4, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("40 contact nodes tied"), "{err}");
    assert!(err.contains("40 outside it left free"), "{err}");
}

/// Bonded contact between surfaces in the forms not read: bonded initial (KEYOPT(12)=6), a
/// positive PINB (a factor of ANSYS's depth-based default), the Gauss-point detection
/// (KEYOPT(4)=0) — each refused by line.
#[test]
fn bonded_contact_forms_not_read_are_refused_by_line() {
    let (m, first_part) = two_parts();
    let glue: Vec<Vec<u64>> = (faces_at(&m, 0.3, true).into_iter())
        .filter(|(e, _)| *e > first_part)
        .map(|(_, f)| f)
        .collect();
    let text = bonded_archive(&m, &glue, 1e-3);
    let cases = [
        (
            "KEYOP,        3,12,        5",
            "KEYOP,        3,12,        6",
            "KEYOPT(12)=6 (bonded initial)",
        ),
        ("R,3,0,0,0,0,0,-1e-3", "R,3,0,0,0,0,0,1e0", "PINB = 1"),
        (
            "KEYOP,        3, 4,        2",
            "KEYOP,        3, 4,        0",
            "KEYOPT(4)=0",
        ),
    ];
    for (k, (from, to, expect)) in cases.iter().enumerate() {
        assert!(text.contains(from), "{from}");
        let err = refused(
            &format!("ansys-bonded-refused-{k}"),
            &text.replace(from, to),
        );
        assert!(err.contains(expect), "{expect}: {err}");
    }
}

/// The force-distributed constraint's weights in closed form: an axial force FX on the pilot
/// (on the tip face's axis, so no moment about the face's centroid) reaches the beam as the
/// consistent nodal forces of a uniform traction, wᵢ FX with wᵢ = ∫Nᵢ dA / A — on each flat
/// 8-node face −1/12 of its area at a corner and 1/3 at a mid-side node: the static response
/// equals that of the nodal forces written as `F` on the face nodes.
#[test]
fn force_distributed_weights_are_the_consistent_face_areas() {
    let m = beam();
    let faces = tip_faces(&m);
    let fx = 4.0e3;
    let mut share: std::collections::BTreeMap<u64, f64> = Default::default();
    for f in &faces {
        for (k, n) in f.iter().enumerate() {
            // each face a quarter of the tip's area
            *share.entry(*n).or_default() += 0.25 * if k < 4 { -1.0 / 12.0 } else { 1.0 / 3.0 };
        }
    }
    let nodal: String = (share.iter())
        .map(|(n, w)| format!("F,{n},FX,{:e}\n", w * fx))
        .collect();
    let types = pair_types(174, 1, 111111, "");
    let at_pilot = archive(&m, &types, &faces, &format!("F,{PILOT},FX,{fx:e}\n"));
    let on_nodes = archive(&m, &types, &faces, &nodal);
    let work = scratch("ansys-contact-weights");
    let (a, b) = (work.join("pilot.cdb"), work.join("nodes.cdb"));
    std::fs::write(&a, at_pilot).unwrap();
    std::fs::write(&b, on_nodes).unwrap();
    let args = ["--mass", "lumped", RESIDUALS[0], RESIDUALS[1]];
    let (pilot, nodes) = (build(&a, 6, &args), build(&b, 6, &args));
    let worst = response_difference(&static_response(&pilot, 0), &static_response(&nodes, 0));
    println!("FX on the pilot against the consistent nodal forces: {worst:.2e}");
    // measured 4.1e-13
    assert!(worst < 4e-12, "{worst:e}");
}

/// The two parts `gap` apart along x (the second over [0.3 + gap, 0.6 + gap]), as
/// [`two_parts`].
fn two_parts_apart(gap: f64) -> (Block, usize) {
    let (mut m, first_part) = two_parts();
    for (id, x) in m.nodes.iter_mut() {
        if *id > 10_000 {
            x[0] += gap;
        }
    }
    (m, first_part)
}

/// The second part's x-min faces (the contact faces of [`bonded_archive`]) at x = `at`.
pub(crate) fn glue_faces(m: &Block, first_part: usize, at: f64) -> Vec<Vec<u64>> {
    (faces_at(m, at, true).into_iter())
        .filter(|(e, _)| *e > first_part)
        .map(|(_, f)| f)
        .collect()
}

/// `text` with CONTA174's KEYOPT(9) set to `value`.
fn with_keyopt9(text: &str, value: u32) -> String {
    let k12 = "KEYOP,        3,12,        5\n";
    assert!(text.contains(k12));
    text.replacen(
        k12,
        &format!("{k12}KEYOP,        3, 9,        {value}\n"),
        1,
    )
}

/// KEYOPT(9)=1 (exclude the initial gap: Workbench's bonded contact) under MPC bonded contact is
/// the tie as placed: on touching faces it equals the KEYOPT(9)=0 archive (no gap to close) and
/// ccx's `*TIE`; with the parts 2e-4 apart (inside the pinball 1e-3) it equals `*TIE,
/// ADJUST=NO` on the same gap, and KEYOPT(9)=0 there (ANSYS closes the gap) is refused by line
/// naming the largest gap.
#[test]
fn keyopt9_excluding_the_gap_is_the_tie_as_placed() {
    let (m, first_part) = two_parts();
    let glue = glue_faces(&m, first_part, 0.3);
    let plain = bonded_archive(&m, &glue, 1e-3);
    let inp = bonded_ccx(&m, first_part, 1e-3);
    let (modes, static_) = against_ccx("ansys-k9-touching", &with_keyopt9(&plain, 1), &inp);
    println!("KEYOPT(9)=1 touching against *TIE: frequencies {modes:.2e}, static {static_:.2e}");
    // measured 3.4e-12 and 3.7e-12
    assert!(modes < 3.4e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");
    // the same MPCs as KEYOPT(9)=0: the two archives' bodies agree (measured 0 and 0)
    let (same, same_static) =
        against_archive("ansys-k9-touching-0", &with_keyopt9(&plain, 1), &plain);
    println!("KEYOPT(9)=1 against KEYOPT(9)=0, touching: {same:.2e}, static {same_static:.2e}");
    assert!(
        same < 1e-12 && same_static < 1e-12,
        "{same:e} {same_static:e}"
    );

    let gap = 2e-4;
    let (m, first_part) = two_parts_apart(gap);
    let glue = glue_faces(&m, first_part, 0.3 + gap);
    assert_eq!(glue.len(), 9);
    let apart = bonded_archive(&m, &glue, 1e-3);
    let inp = bonded_ccx_at(&m, first_part, 1e-3, 0.3 + gap);
    let (modes, static_) = against_ccx("ansys-k9-gap", &with_keyopt9(&apart, 1), &inp);
    println!(
        "KEYOPT(9)=1 with a 2e-4 gap against *TIE, ADJUST=NO: {modes:.2e}, static {static_:.2e}"
    );
    // measured 4.7e-12 and 6.3e-12 (the same MPCs: the two builds' eigensolves)
    assert!(modes < 3.4e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");
    for (k, text) in [with_keyopt9(&apart, 0), apart.clone()].iter().enumerate() {
        let err = refused(&format!("ansys-k9-gap-refused-{k}"), text);
        assert!(err.contains("KEYOPT(9)=0"), "{err}");
        assert!(err.contains("2.0000e-4"), "{err}");
        // at the first CONTA174 record: after the header lines, the NBLOCK and the bricks
        assert!(err.contains("refused.cdb:"), "{err}");
    }
}
