//! Duplicate ids and non-finite numbers in the Abaqus `.inp` and Gmsh `.msh` importers (issue
//! 20: "a test per entity kind and format"; Nastran is covered in `tests/hostile_input.rs`).
//! Every case is an error naming file, line and entity, and for a duplicate the line of the
//! first definition; each has a control deck that reads, so the check cannot pass by refusing
//! everything.

use std::path::PathBuf;

use flexbody::import::{read_model, ImportError, ImportOptions};
use flexbody::model::Material;

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("flexbody_ids_numbers_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn read(name: &str, text: &[u8]) -> Result<flexbody::model::Model, ImportError> {
    let p = dir().join(name);
    std::fs::write(&p, text).unwrap();
    // Gmsh meshes carry no material: give one, as the CLI's --material does.
    // the Abaqus decks' shells as flexbody's shells: the decks are about ids and numbers
    let opts = ImportOptions {
        material: Some(Material::steel()),
        inp_shells: flexbody::import::InpShells::Native,
        ..ImportOptions::default()
    };
    read_model(&p, &opts)
}

/// The deck must fail at `line` on `entity`, and the message must hold every `parts`.
fn fails(name: &str, text: &[u8], line: usize, entity: &str, parts: &[&str]) {
    let e = match read(name, text) {
        Ok(_) => panic!("{name}: accepted"),
        Err(e) => e,
    };
    let msg = e.to_string();
    assert!(e.file().is_some_and(|f| f.ends_with(name)), "{name}: {msg}");
    assert_eq!(
        (e.line(), e.entity()),
        (Some(line), Some(entity)),
        "{name}: {msg}"
    );
    for p in parts {
        assert!(msg.contains(p), "{name}: '{p}' not in: {msg}");
    }
}

/// Lines joined with newlines: line k of the deck is `lines[k - 1]`.
fn deck(lines: &[&str]) -> String {
    lines.join("\n") + "\n"
}

// ---- Abaqus / CalculiX .inp ----

/// A one-tet model with material, section, a point mass and a shell: every real-valued
/// keyword this test file corrupts, in a deck that reads.
const INP: [&str; 22] = [
    "*NODE",                                                       // 1
    "1, 0, 0, 0",                                                  // 2
    "2, 1, 0, 0",                                                  // 3
    "3, 0, 1, 0",                                                  // 4
    "4, 0, 0, 1",                                                  // 5
    "*ELEMENT, TYPE=C3D4, ELSET=SOLID",                            // 6
    "7, 1, 2, 3, 4",                                               // 7
    "*ELEMENT, TYPE=S3, ELSET=SKIN",                               // 8
    "8, 1, 2, 3",                                                  // 9
    "*ELEMENT, TYPE=MASS, ELSET=PM",                               // 10
    "9, 4",                                                        // 11
    "*MATERIAL, NAME=Steel",                                       // 12
    "*ELASTIC",                                                    // 13
    "2.1e11, 0.3",                                                 // 14
    "*DENSITY",                                                    // 15
    "7850.",                                                       // 16
    "*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL",                 // 17
    "*SHELL SECTION, ELSET=SKIN, MATERIAL=steel",                  // 18
    "0.002",                                                       // 19
    "*MASS, ELSET=PM",                                             // 20
    "1.5",                                                         // 21
    "*MATERIAL, NAME=Alu\n*ELASTIC\n7.e10, 0.33\n*DENSITY\n2700.", // 22..26
];

/// The deck with line `line` (1-based) replaced.
fn inp_with(line: usize, text: &str) -> String {
    let mut l = INP;
    l[line - 1] = text;
    deck(&l)
}

#[test]
fn abaqus_control_deck_reads_with_its_numbers() {
    let m = read("control.inp", deck(&INP).as_bytes()).unwrap();
    // The MASS element becomes a point mass, not a model element.
    assert_eq!(
        (m.nodes.len(), m.elements.len(), m.point_masses.len()),
        (4, 2, 1)
    );
    assert_eq!(m.materials.len(), 2);
    let steel = m.materials.iter().find(|x| x.name == "STEEL").unwrap();
    assert_eq!((steel.e, steel.nu, steel.rho), (2.1e11, 0.3, 7850.0));
    let total: f64 = m.point_masses.iter().map(|p| p.mass).sum();
    assert_eq!(total, 1.5);
}

#[test]
fn abaqus_duplicate_material_names_name_both_lines() {
    // Abaqus names are case-insensitive: ALU on line 27 is the Alu of line 22.
    let d = format!("{}*MATERIAL, NAME=ALU\n*ELASTIC\n1.e9, 0.3\n", deck(&INP));
    fails(
        "dup_material.inp",
        d.as_bytes(),
        27,
        "*MATERIAL ALU",
        &["duplicate material name", "dup_material.inp:22"],
    );
    // Reported even when the second one is incomplete (no *ELASTIC).
    let d = format!("{}*MATERIAL, NAME=steel\n", deck(&INP));
    fails(
        "dup_material_bare.inp",
        d.as_bytes(),
        27,
        "*MATERIAL STEEL",
        &["duplicate material name", "dup_material_bare.inp:12"],
    );
}

#[test]
fn abaqus_duplicate_node_across_node_blocks_and_element_across_types() {
    // A node redefined in a later *NODE block.
    let d = format!("{}*NODE, NSET=EXTRA\n5, 2, 0, 0\n2, 3, 0, 0\n", deck(&INP));
    fails(
        "dup_node_block.inp",
        d.as_bytes(),
        29,
        "*NODE 2",
        &["duplicate node id", "dup_node_block.inp:3"],
    );
    // A shell element reusing the tet's id: one element id space across types.
    let d = inp_with(9, "7, 1, 2, 3");
    fails(
        "dup_elem_types.inp",
        d.as_bytes(),
        9,
        "S3 7",
        &["duplicate element id", "dup_elem_types.inp:7"],
    );
}

/// The format's own rule for a repeated set name: a later *NSET/*ELSET of an existing name adds
/// its members (CalculiX manual, "Sets": two `*NSET,NSET=N1` blocks make one set N1; Abaqus
/// likewise). Not a duplicate: the union, each member once, names case-insensitive.
#[test]
fn abaqus_repeated_set_name_adds_members() {
    let d = format!(
        "{}*NSET, NSET=Ends\n1, 2\n*NSET, NSET=ENDS\n2, 4\n*ELSET, ELSET=all\n7\n*ELSET, ELSET=ALL\n8, 7\n",
        deck(&INP)
    );
    let m = read("sets.inp", d.as_bytes()).unwrap();
    let ids = |v: &[usize]| v.iter().map(|&k| m.nodes[k].id).collect::<Vec<_>>();
    assert_eq!(ids(&m.node_sets["ENDS"]), [1, 2, 4]);
    let e: Vec<u64> = m.element_sets["ALL"]
        .iter()
        .map(|&k| m.elements[k].id)
        .collect();
    assert_eq!(e, [7, 8]);
}

#[test]
fn abaqus_material_constants_non_finite_or_out_of_range() {
    let cases: [(&str, usize, &str, &str, &str); 6] = [
        (
            "nu_nan.inp",
            14,
            "2.1e11, NaN",
            "*MATERIAL STEEL",
            "not a number",
        ),
        (
            "e_neg_inf.inp",
            14,
            "-inf, 0.3",
            "*MATERIAL STEEL",
            "infinite",
        ),
        (
            "e_at_bound.inp",
            14,
            "1.0e150, 0.3",
            "*MATERIAL STEEL",
            "out of range",
        ),
        ("rho_nan.inp", 16, "nan", "*MATERIAL STEEL", "not a number"),
        (
            "rho_fortran.inp",
            16,
            "7.85D+400",
            "*MATERIAL STEEL",
            "infinite",
        ),
        (
            "nu_junk.inp",
            14,
            "2.1e11, 0.3x",
            "*MATERIAL STEEL",
            "bad number '0.3x'",
        ),
    ];
    for (name, line, text, entity, what) in cases {
        fails(name, inp_with(line, text).as_bytes(), line, entity, &[what]);
    }
    // Just inside the bound: read (a warning at most, no error).
    let m = read("e_in_bound.inp", inp_with(14, "9.9e149, 0.3").as_bytes()).unwrap();
    let steel = m.materials.iter().find(|x| x.name == "STEEL").unwrap();
    assert_eq!(steel.e, 9.9e149);
}

#[test]
fn abaqus_node_and_element_data_non_finite_or_out_of_range() {
    let cases: [(&str, usize, &str, &str, &str); 6] = [
        (
            "node_neg_inf.inp",
            3,
            "2, -Infinity, 0, 0",
            "*NODE 2",
            "infinite",
        ),
        (
            "node_big.inp",
            4,
            "3, 0, 1e200, 0",
            "*NODE 3",
            "out of range",
        ),
        (
            "node_fortran.inp",
            5,
            "4, 0, 0, 1.D151",
            "*NODE 4",
            "out of range",
        ),
        ("mass_nan.inp", 21, "NaN", "*MASS ELSET=PM", "not a number"),
        (
            "shell_t_inf.inp",
            19,
            "inf",
            "*SECTION ELSET=SKIN",
            "infinite",
        ),
        (
            "shell_t_big.inp",
            19,
            "-3e170",
            "*SECTION ELSET=SKIN",
            "out of range",
        ),
    ];
    for (name, line, text, entity, what) in cases {
        fails(name, inp_with(line, text).as_bytes(), line, entity, &[what]);
    }
    // An element's node field that is a real, not an id.
    let e = read(
        "elem_real_node.inp",
        inp_with(7, "7, 1, 2, 3, 1e400").as_bytes(),
    )
    .unwrap_err();
    assert_eq!(e.line(), Some(7), "{e}");
    assert!(e.to_string().contains("1e400"), "{e}");
}

// ---- Gmsh .msh 4.1 ----

/// Two tets sharing a face, plus one boundary triangle (physical group "FACE"), ASCII.
/// `tri_tag` is the triangle's tag, `tet2_tag` the second tet's.
fn msh(tri_tag: u64, tet2_tag: u64, coord: &str) -> String {
    deck(&[
        "$MeshFormat",                  // 1
        "4.1 0 8",                      // 2
        "$EndMeshFormat",               // 3
        "$PhysicalNames",               // 4
        "1",                            // 5
        "2 1 \"FACE\"",                 // 6
        "$EndPhysicalNames",            // 7
        "$Entities",                    // 8
        "0 0 1 1",                      // 9
        "1 0 0 0 1 1 0 1 1 0",          // 10
        "1 0 0 0 1 1 1 0 0",            // 11
        "$EndEntities",                 // 12
        "$Nodes",                       // 13
        "2 5 1 5",                      // 14
        "3 1 0 3",                      // 15
        "1",                            // 16
        "2",                            // 17
        "3",                            // 18
        "0 0 0",                        // 19
        "1 0 0",                        // 20
        coord,                          // 21  (node 3)
        "3 1 0 2",                      // 22
        "4",                            // 23
        "5",                            // 24
        "0 0 1",                        // 25
        "0 0 -1",                       // 26
        "$EndNodes",                    // 27
        "$Elements",                    // 28
        "2 3 1 3",                      // 29
        "2 1 2 1",                      // 30
        &format!("{tri_tag} 1 2 3"),    // 31
        "3 1 4 2",                      // 32
        "1 1 2 3 4",                    // 33
        &format!("{tet2_tag} 1 3 2 5"), // 34
        "$EndElements",                 // 35
    ])
}

#[test]
fn gmsh_control_mesh_reads() {
    let m = read("control.msh", msh(3, 2, "0 1 0").as_bytes()).unwrap();
    assert_eq!((m.nodes.len(), m.elements.len()), (5, 2));
    let ids: Vec<u64> = m.elements.iter().map(|e| e.id).collect();
    assert_eq!(ids, [1, 2]);
    assert_eq!(m.node_sets["FACE"].len(), 3);
    // Node and element tags are separate spaces: element 1 beside node 1 is no duplicate.
    assert_eq!(m.nodes[0].id, 1);
}

#[test]
fn gmsh_duplicate_node_tags_name_both_lines() {
    // Within one block: node 3 (coordinates on line 21) is node 2 again.
    let d = msh(3, 2, "0 1 0").replace("1\n2\n3\n0 0 0", "1\n2\n2\n0 0 0");
    fails(
        "dup_node.msh",
        d.as_bytes(),
        21,
        "node 2",
        &["duplicate node id", "dup_node.msh:20"],
    );
    // Across blocks: the second block's node 4 is node 1 again.
    let d = msh(3, 2, "0 1 0").replace("4\n5\n0 0 1", "1\n5\n0 0 1");
    fails(
        "dup_node_blocks.msh",
        d.as_bytes(),
        25,
        "node 1",
        &["duplicate node id", "dup_node_blocks.msh:19"],
    );
}

#[test]
fn gmsh_duplicate_element_tags_name_both_lines() {
    // Two tets with tag 1.
    fails(
        "dup_tet.msh",
        msh(3, 1, "0 1 0").as_bytes(),
        34,
        "element 1",
        &["duplicate element id", "dup_tet.msh:33"],
    );
    // A boundary triangle with a tet's tag: tags are unique across all dimensions.
    fails(
        "dup_tri_tet.msh",
        msh(2, 2, "0 1 0").as_bytes(),
        34,
        "element 2",
        &[
            "duplicate element id",
            "dup_tri_tet.msh:31",
            "all dimensions",
        ],
    );
    // Two boundary triangles with one tag.
    let d = msh(3, 2, "0 1 0").replace(
        "2 3 1 3\n2 1 2 1\n3 1 2 3\n",
        "2 4 1 3\n2 1 2 2\n3 1 2 3\n3 1 2 4\n",
    );
    fails(
        "dup_tri.msh",
        d.as_bytes(),
        32,
        "element 3",
        &["duplicate element id", "dup_tri.msh:31"],
    );
}

#[test]
fn gmsh_node_coordinates_non_finite_or_out_of_range_ascii() {
    let cases: [(&str, &str, &str); 5] = [
        ("inf.msh", "0 inf 0", "infinite"),
        ("neg_inf.msh", "0 1 -inf", "infinite"),
        ("nan.msh", "NaN 1 0", "not a number"),
        ("bound.msh", "0 1e150 0", "out of range"),
        ("junk.msh", "0 1.0.0 0", "bad number '1.0.0'"),
    ];
    for (name, coord, what) in cases {
        fails(name, msh(3, 2, coord).as_bytes(), 21, "$Nodes", &[what]);
    }
    let m = read("in_bound.msh", msh(3, 2, "0 9.9e149 0").as_bytes()).unwrap();
    assert_eq!(m.nodes[2].x, [0.0, 9.9e149, 0.0]);
}

/// The same two-tet mesh in binary MSH 4.1 (little-endian, size_t = 8), node 3 at `node3`.
fn msh_binary(node3: [f64; 3]) -> Vec<u8> {
    let mut v = b"$MeshFormat\n4.1 1 8\n".to_vec();
    v.extend(1i32.to_le_bytes());
    v.extend(b"\n$EndMeshFormat\n$Nodes\n");
    let size = |v: &mut Vec<u8>, x: u64| v.extend(x.to_le_bytes());
    for x in [1u64, 5, 1, 5] {
        size(&mut v, x);
    }
    for x in [3i32, 1, 0] {
        v.extend(x.to_le_bytes());
    }
    size(&mut v, 5);
    for t in 1..=5u64 {
        size(&mut v, t);
    }
    let coords = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        node3,
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    for c in coords {
        for x in c {
            v.extend(f64::to_le_bytes(x));
        }
    }
    v.extend(b"\n$EndNodes\n$Elements\n");
    for x in [1u64, 2, 1, 2] {
        size(&mut v, x);
    }
    for x in [3i32, 1, 4] {
        v.extend(x.to_le_bytes());
    }
    size(&mut v, 2);
    for x in [1u64, 1, 2, 3, 4, 2, 1, 3, 2, 5] {
        size(&mut v, x);
    }
    v.extend(b"\n$EndElements\n");
    v
}

#[test]
fn gmsh_node_coordinates_non_finite_or_out_of_range_binary() {
    let m = read("control_bin.msh", &msh_binary([0.0, 1.0, 0.0])).unwrap();
    assert_eq!((m.nodes.len(), m.elements.len()), (5, 2));
    assert_eq!(m.nodes[2].x, [0.0, 1.0, 0.0]);
    for (name, node3, what) in [
        ("nan_bin.msh", [f64::NAN, 1.0, 0.0], "not a number"),
        ("inf_bin.msh", [0.0, f64::NEG_INFINITY, 0.0], "infinite"),
        ("big_bin.msh", [0.0, 1.0, 1e300], "out of range"),
    ] {
        let e = read(name, &msh_binary(node3)).unwrap_err();
        let msg = e.to_string();
        assert_eq!(e.entity(), Some("$Nodes"), "{msg}");
        assert!(msg.contains(what) && msg.contains("byte offset"), "{msg}");
    }
}
