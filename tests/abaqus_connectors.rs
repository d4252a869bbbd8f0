//! The Abaqus/CalculiX connectors (issue 32) against independent references: a SPRINGA equals
//! a massless rod of the same EA/L; SPRING1 of 1e12 equals a clamp; *EQUATION tying coincident
//! nodes equals the merged mesh; a MASS element on a spring gives ω² = k/m; ROTARYI on a
//! rotational spring ω² = k/I; a *RIGID BODY (ELSET, REF NODE, ROT NODE) of a brick on springs
//! moves with the brick's mass and its exact inertia ρV(a² + b²)/12; SPRING2 between two masses
//! gives k(1/m₁ + 1/m₂); supports in *TRANSFORM frames (R and C) as CalculiX holds them; the
//! keyword rule (blanks, refusals in one error, --ignore, later steps,
//! a PERTURBATION frequency step after a *STATIC step refused until the preload is read).

use crate::common::{dense, generalized_eigenvalues};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec, MassKind};
use flexbody::import::{abaqus, ImportError, ImportOptions};
use flexbody::model::{Element, ElementKind, Model, Property, Section};

fn write(name: &str, text: &str) -> std::path::PathBuf {
    let dir = crate::common::scratch(&format!("abaqus-conn-{name}"));
    let path = dir.join(format!("{name}.inp"));
    std::fs::write(&path, text).unwrap();
    path
}

fn read(name: &str, text: &str) -> Model {
    abaqus::read(&write(name, text)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// ω² of the constrained model, ascending (consistent mass).
fn omega2(model: &Model) -> Vec<f64> {
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        ..Default::default()
    };
    let a = assemble(model, &spec).unwrap();
    let r = eliminate(model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    generalized_eigenvalues(&dense(&r.k), &dense(&r.m))
}

fn assert_close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: {got:?} against {want:?}");
    // relative, with an absolute floor of 1e-12 of the largest for the zero modes
    let top = want.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= tol * w.abs() + 1e-12 * top,
            "{what}: {got:?} against {want:?}"
        );
    }
}

/// A unit cube of C3D8 (nodes 1–8, element 1, set BLOCK), E = 1e6, ν = 0.3, ρ = 1000.
const CUBE: &str = "*NODE, NSET=NALL\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n\
5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n\
*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n1, 1, 2, 3, 4, 5, 6, 7, 8\n\
*MATERIAL, NAME=M\n*ELASTIC\n1e6, 0.3\n*DENSITY\n1000\n*SOLID SECTION, ELSET=BLOCK, MATERIAL=M\n";

#[test]
fn springa_equals_a_massless_rod_of_the_same_axial_stiffness() {
    // node 2 at 5·(0.6, 0.8, 0) on a SPRINGA k = 300 from a clamped node 1, mass 2 on node 2
    let deck = "*NODE\n1, 0, 0, 0\n2, 3, 4, 0\n*ELEMENT, TYPE=SPRINGA, ELSET=S\n10, 1, 2\n\
*ELEMENT, TYPE=MASS, ELSET=P\n11, 2\n*SPRING, ELSET=S\n\n300.\n*MASS, ELSET=P\n2.\n\
*BOUNDARY\n1, 1, 6\n2, 4, 6\n";
    // (node 2's rotations carry no mass: held, so that the dense M is positive definite)
    let m = read("springa", deck);
    assert_eq!(m.bushes.len(), 1);
    let w = omega2(&m);
    // the rod: EA/L = 300 with L = 5, massless
    let mut rod = m.clone();
    rod.bushes.clear();
    rod.materials.push(flexbody::model::Material::isotropic(
        9, "ROD", 1.5e3, 0.3, 0.0,
    ));
    rod.properties.push(Property {
        id: 9,
        name: "ROD".into(),
        material: rod.materials.len() - 1,
        section: Section::Rod {
            area: 1.0,
            j: 0.0,
            nsm: 0.0,
        },
    });
    rod.elements.push(Element {
        id: 10,
        kind: ElementKind::Rod2,
        nodes: vec![0, 1],
        property: Some(rod.properties.len() - 1),
        orientation: None,
    });
    let w_rod = omega2(&rod);
    assert_close(&w, &w_rod, 1e-12, "SPRINGA against the rod");
    // and the closed form: one mode k/m along the axis, two without stiffness
    assert_close(&w, &[0.0, 0.0, 150.0], 1e-12, "SPRINGA k/m");
}

#[test]
fn spring1_of_1e12_equals_a_clamp() {
    let clamped = read(
        "clamp",
        &format!("{CUBE}*BOUNDARY\n1, 1, 3\n2, 1, 3\n3, 1, 3\n4, 1, 3\n"),
    );
    let mut springs = String::from(CUBE);
    for dof in 1..=3 {
        springs += &format!("*ELEMENT, TYPE=SPRING1, ELSET=K{dof}\n");
        for n in 1..=4 {
            springs += &format!("{}, {n}\n", 100 + 10 * dof + n);
        }
        springs += &format!("*SPRING, ELSET=K{dof}\n{dof}\n1e12\n");
    }
    let sprung = read("spring1", &springs);
    assert_eq!(sprung.springs.len(), 12);
    let (a, b) = (omega2(&clamped), omega2(&sprung));
    // the twelve stiff modes of the springs lie far above the cube's twelve
    assert_close(&b[..12], &a, 1e-5, "SPRING1 1e12 against the clamp");
    assert!(b[12] > 1e3 * a[11]);
}

#[test]
fn equation_tying_coincident_nodes_equals_the_merged_mesh() {
    // two cubes side by side: merged (shared nodes 2, 3, 6, 7) …
    let second = "*NODE\n9, 2, 0, 0\n10, 2, 1, 0\n11, 2, 0, 1\n12, 2, 1, 1\n";
    let merged = format!(
        "{CUBE}{second}*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n2, 2, 9, 10, 3, 6, 11, 12, 7\n\
*BOUNDARY\n1, 1, 3\n4, 1, 3\n5, 1, 3\n8, 1, 3\n"
    );
    // … and with the second cube on its own nodes 22, 23, 26, 27 tied by *EQUATION
    let mut tied = format!(
        "{CUBE}{second}*NODE\n22, 1, 0, 0\n23, 1, 1, 0\n26, 1, 0, 1\n27, 1, 1, 1\n\
*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n2, 22, 9, 10, 23, 26, 11, 12, 27\n\
*BOUNDARY\n1, 1, 3\n4, 1, 3\n5, 1, 3\n8, 1, 3\n"
    );
    for n in [2, 3, 6, 7] {
        for dof in 1..=3 {
            tied += &format!("*EQUATION\n2\n{}, {dof}, 1., {n}, {dof}, -1.\n", n + 20);
        }
    }
    let (a, b) = (read("merged", &merged), read("tied", &tied));
    assert_eq!(b.mpcs.len(), 12);
    assert_close(
        &omega2(&b),
        &omega2(&a),
        1e-9,
        "*EQUATION tie against merged nodes",
    );
}

#[test]
fn mass_and_rotary_inertia_on_springs_give_k_over_m_and_k_over_i() {
    // MASS 4 on SPRING1 k = 100 in x; ROTARYI I33 = 0.5 on SPRING1 k = 8 about z
    let deck = "*NODE\n1, 0, 0, 0\n*ELEMENT, TYPE=MASS, ELSET=P\n1, 1\n\
*ELEMENT, TYPE=ROTARYI, ELSET=R\n2, 1\n*ELEMENT, TYPE=SPRING1, ELSET=KX\n3, 1\n\
*ELEMENT, TYPE=SPRING1, ELSET=KR\n4, 1\n*MASS, ELSET=P\n4.\n\
*ROTARY INERTIA, ELSET=R\n1., 1., 0.5\n*SPRING, ELSET=KX\n1\n100.\n*SPRING, ELSET=KR\n6\n8.\n\
*BOUNDARY\n1, 2, 5\n";
    let m = read("mass", deck);
    assert_close(&omega2(&m), &[16.0, 25.0], 1e-12, "k/I and k/m");
}

#[test]
fn rigid_body_with_rot_node_moves_with_the_bricks_mass_and_inertia() {
    // the cube rigid (ELSET, blanks in the names), reference node 20 at its centre, rotation
    // node 21; springs: x translation k = 10 on node 20, rotation about z k = 3 on node 21's
    // x; every other rigid motion held at the reference node
    let deck = format!(
        "{CUBE}*NODE\n20, 0.5, 0.5, 0.5\n21, 5, 5, 5\n*RIGIDBODY, ELSET=BLOCK, REFNODE=20, Rot Node=21\n\
*ELEMENT, TYPE=SPRING1, ELSET=KT\n30, 20\n*ELEMENT, TYPE=SPRING1, ELSET=KR\n31, 21\n\
*SPRING, ELSET=KT\n1\n10.\n*SPRING, ELSET=KR\n3\n3.\n*BOUNDARY\n20, 2, 5\n"
    );
    let m = read("rigid", &deck);
    assert_eq!((m.rigid_elements.len(), m.mpcs.len()), (1, 3));
    // mass ρV = 1000, inertia about the centre's z axis ρV(1 + 1)/12
    let (mass, izz) = (1000.0, 1000.0 * 2.0 / 12.0);
    assert_close(&omega2(&m), &[10.0 / mass, 3.0 / izz], 1e-10, "rigid brick");
}

#[test]
fn keyword_rule_refuses_every_unread_keyword_at_once_and_ignores_later_steps() {
    let deck = format!(
        "{CUBE}*CONTACT PAIR, INTERACTION=SI\nA, B\n*NODE PRINT, NSET=NALL\nU\n*GAP, ELSET=G\n\
*ELEMENT, TYPE=GAPUNI, ELSET=G\n5, 1, 2\n*SURFACE, NAME=F\nBLOCK, S1\n*RESTART, WRITE\n*BOUNDARY\n1, 1, 3\n2, 1, 3\n3, 1, 3\n4, 1, 3\n\
*STEP\n*FREQUENCY\n4\n*END STEP\n*STEP\n*MODAL DYNAMIC\n*BOUNDARY\n5, 1, 1, 0.5\n*END STEP\n"
    );
    let path = write("rule", &deck);
    let e = abaqus::read(&path).unwrap_err();
    let ImportError::Refused { cards, .. } = &e else {
        panic!("{e}")
    };
    let got: Vec<(usize, &str, &str)> = (cards.iter())
        .map(|c| (c.line, c.entity.as_str(), c.key.as_str()))
        .collect();
    assert_eq!(
        got,
        vec![
            (18, "*CONTACT PAIR", "*CONTACT PAIR"),
            (22, "*GAP", "*GAP"),
            (23, "*ELEMENT, TYPE=GAPUNI", "GAPUNI")
        ],
        "{e}"
    );
    // dropped on purpose (names with or without * and blanks), the rest builds: *NODE PRINT a
    // note, the later step's non-zero *BOUNDARY ignored with one warning
    let opts = ImportOptions {
        ignore_cards: ["contact pair", "*GAP", "GAPUNI"]
            .map(String::from)
            .to_vec(),
        ..Default::default()
    };
    let m = abaqus::read_with_options(&path, &opts).unwrap();
    for note in ["*NODE PRINT", "*RESTART"] {
        assert!(
            m.deck.notes.iter().any(|n| n.contains(note)),
            "{note}: {:?}",
            m.deck.notes
        );
    }
    let w: Vec<&str> = m.warnings.iter().map(|w| w.message.as_str()).collect();
    assert!(
        w.iter().any(|w| w.contains("dropped on request")
            && w.contains("GAPUNI")
            && w.contains("*CONTACT PAIR")),
        "{w:?}"
    );
    assert!(
        w.iter()
            .any(|w| w.contains("after the first *FREQUENCY step")
                && w.contains("*MODAL DYNAMIC")
                && w.contains("*BOUNDARY")),
        "{w:?}"
    );
    assert_eq!(m.spcs.len(), 4);
}

#[test]
fn spring2_joins_two_masses_and_refuses_transformed_nodes() {
    // masses 2 and 3 on x of nodes 1 and 2, SPRING2 k = 12 between x of 1 and y of 2
    // (SPRING2 joins any two dofs): the two-mass oscillator ω² = k (1/m₁ + 1/m₂) = 10
    let deck = "*NODE, NSET=BOTH\n1, 0, 0, 0\n2, 1, 0, 0\n*ELEMENT, TYPE=MASS, ELSET=P1\n1, 1\n\
*ELEMENT, TYPE=MASS, ELSET=P2\n2, 2\n*ELEMENT, TYPE=SPRING2, ELSET=K\n3, 1, 2\n\
*MASS, ELSET=P1\n2.\n*MASS, ELSET=P2\n3.\n*SPRING, ELSET=K\n1, 2\n12.\n\
*BOUNDARY\n1, 2, 6\n2, 1, 1\n2, 3, 6\n";
    let m = read("spring2", deck);
    assert_close(&omega2(&m), &[0.0, 10.0], 1e-12, "two-mass oscillator");
    // a *TRANSFORM frame on a spring's node: the global dofs would be misread, refused
    let framed = format!("{deck}*TRANSFORM, NSET=BOTH\n0, 1, 0, -1, 0, 0\n");
    let e = abaqus::read(&write("spring2_frame", &framed)).unwrap_err();
    assert!(
        e.to_string().contains("*ELEMENT 3 (SPRING2)")
            && e.to_string().contains("*TRANSFORM frame"),
        "{e}"
    );
}

/// A `*STEP, PERTURBATION` frequency step after a loaded `*STATIC` step is the preload the
/// pipeline's preload stage honours (issue 35): the reader records it, never drops it; without
/// PERTURBATION the frequency step is the unloaded body's, as in ccx.
#[test]
fn a_perturbation_frequency_step_after_a_static_step_is_a_preload() {
    let deck = format!(
        "{CUBE}*BOUNDARY\n1, 1, 3\n2, 1, 3\n3, 1, 3\n4, 1, 3\n*STEP\n*STATIC\n*CLOAD\n7, 3, -1.\n\
*END STEP\n*STEP, PERTURBATION\n*FREQUENCY\n4\n*END STEP\n"
    );
    let m = abaqus::read(&write("perturbation", &deck)).unwrap();
    assert!(m.deck.preload.is_some(), "the preload request is recorded");
    let plain = deck.replace("*STEP, PERTURBATION", "*STEP");
    let m = abaqus::read(&write("plain", &plain)).unwrap();
    assert!(m.deck.preload.is_none());
}

/// *TRANSFORM frames with supports in them: the a_block cantilever held radially and axially
/// about an oblique cylinder axis (TYPE=C) at its root and along a rectangular frame's y
/// (TYPE=R) at its tip — CalculiX 2.20's frequencies of the same deck, to 2e-6.
#[test]
fn transform_frames_hold_as_calculix_holds_them() {
    let deck = format!(
        "*INCLUDE, INPUT={}\n*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n\
*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL\n\
*TRANSFORM, NSET=FIXED, TYPE=C\n0.0, 0.01, 0.02, 0.3, 0.05, 0.04\n\
*TRANSFORM, NSET=TIP, TYPE=R\n1., 1., 0., 0., 1., 1.\n\
*BOUNDARY\nFIXED, 1, 1\nFIXED, 3, 3\nTIP, 2, 2\n*STEP\n*FREQUENCY\n8\n*END STEP\n",
        crate::common::reference("a_block_hex8/mesh.inp").display()
    );
    let path = write("transform_ccx", &deck);
    let out = path.with_extension("flexbody");
    let o = crate::common::build_as_ccx(&path, &["-q"], &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let body = flexbody_reader::read(&out).unwrap();
    // ccx 2.20 (Debian calculix-ccx 2.20-1) on this deck
    let ccx = [
        174.7557, 823.1897, 980.9745, 1403.720, 2243.561, 2637.578, 2720.346, 3941.905,
    ];
    let worst =
        crate::common::assert_frequencies("transform_ccx", &body.modes.frequency_hz, &ccx, 0, 2e-6);
    eprintln!("transform_ccx: worst {worst:.1e}");
}
