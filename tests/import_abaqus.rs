//! Abaqus/CalculiX `.inp` import against the reference decks in `fixtures/reference/` (written by
//! gmsh + make_reference.py and run by ccx 2.20), plus small inline decks for the keywords the
//! reference meshes do not use.

use std::path::{Path, PathBuf};

use flexbody::import::{abaqus, read_model, ImportOptions};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::{DofMask, ElementKind, Material, Model, RigidElement, Section};

fn reference(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/reference")
        .join(rel)
}

fn write_deck(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "flexbody_import_abaqus_{name}_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    for (f, text) in files {
        std::fs::write(dir.join(f), text).unwrap();
    }
    dir.join(files[0].0)
}

fn node_by_id(m: &Model, id: u64) -> [f64; 3] {
    m.nodes[m.node_index_by_id()[&id]].x
}

#[test]
fn a_block_hex8_mesh_counts_coordinates_connectivity_sets() {
    let m = abaqus::read(&reference("a_block_hex8/mesh.inp")).unwrap();
    // Counts from fixtures/reference/format_consistency.json.
    assert_eq!((m.nodes.len(), m.elements.len()), (2009, 1440));
    assert!(m.elements.iter().all(|e| e.kind == ElementKind::Hex8));
    assert_eq!(node_by_id(&m, 9), [0.0, 0.0, 0.008333333333333349]);
    assert_eq!(
        node_by_id(&m, 2009),
        [
            0.48750000000000004,
            0.04166666666666669,
            0.04166666666666669
        ]
    );
    let e = &m.elements[0];
    let ids: Vec<u64> = e.nodes.iter().map(|&i| m.nodes[i].id).collect();
    assert_eq!((e.id, ids), (73, vec![205, 9, 2, 24, 1035, 255, 49, 645]));
    assert_eq!(m.node_sets["FIXED"].len(), 49);
    assert_eq!(m.node_sets["TIP"].len(), 49);
    assert_eq!(m.node_sets["NALL"].len(), 2009);
    assert_eq!(m.element_sets["SOLID"].len(), 1440);
    assert!(m.node_sets["FIXED"].iter().all(|&i| m.nodes[i].x[0] == 0.0));
    // A bare mesh has no section: elements have no property until a material is supplied.
    assert!(m.elements.iter().all(|e| e.property.is_none()));
    let opts = ImportOptions {
        material: Some(Material::steel()),
        ..Default::default()
    };
    let m = read_model(&reference("a_block_hex8/mesh.inp"), &opts).unwrap();
    assert!(m.elements.iter().all(|e| e.property == Some(0)));
}

#[test]
fn ccx_deck_with_include_has_material_section_and_boundary() {
    let m = read_model(
        &reference("a_block_hex8/ccx_fixed.inp"),
        &ImportOptions::default(),
    )
    .unwrap();
    assert_eq!(m.nodes.len(), 2009);
    assert_eq!(m.materials.len(), 1);
    let mat = &m.materials[0];
    assert_eq!(
        (mat.name.as_str(), mat.e, mat.nu, mat.rho),
        ("STEEL", 2.1e11, 0.3, 7850.0)
    );
    assert!((mat.g - 2.1e11 / 2.6).abs() < 1e-3);
    assert_eq!(m.properties.len(), 1);
    assert_eq!(m.properties[0].section, Section::Solid);
    assert!(m.elements.iter().all(|e| e.property == Some(0)));
    assert_eq!(m.spcs.len(), 49);
    assert!(m
        .spcs
        .iter()
        .all(|s| s.dofs == DofMask::TRANSLATIONS && m.nodes[s.node].x[0] == 0.0));
    // *STEP / *FREQUENCY / *END STEP are read: the frequency step's eigenvalue count is the
    // deck's mode-count request (they used to be ignored with a warning).
    let eigen = m.deck.eigen.as_ref().expect("*FREQUENCY read");
    assert_eq!(eigen.count, Some(20));
    assert!(eigen.source.contains("*FREQUENCY"), "{}", eigen.source);
}

#[test]
fn b_tet10_and_d_plate_meshes() {
    let m = abaqus::read(&reference("b_block_tet10/ccx_free.inp")).unwrap();
    assert_eq!((m.nodes.len(), m.elements.len()), (5089, 2702));
    assert!(m.elements.iter().all(|e| e.kind == ElementKind::Tet10));
    let ids: Vec<u64> = m.elements[0].nodes.iter().map(|&i| m.nodes[i].id).collect();
    assert_eq!(
        ids,
        vec![1697, 2844, 437, 2865, 2955, 2956, 2957, 2958, 2960, 2959]
    );
    assert_eq!(m.node_sets["FIXED"].len(), 101);
    assert!(m.spcs.is_empty());
    let m = abaqus::read(&reference("d_plate_hex8/ccx_fixed.inp")).unwrap();
    assert_eq!((m.nodes.len(), m.elements.len()), (7503, 4800));
    assert_eq!(m.node_sets["CLAMPED_EDGE"].len(), 123);
    assert_eq!(m.spcs.len(), 123);
}

/// Every node of the e_matrices decks appears in ccx's own equation table (.dof, 3 per node).
#[test]
fn e_matrices_decks_match_ccx_dof_tables() {
    for case in [
        "hex8_single",
        "tet10_single",
        "hex8_block_coarse",
        "tet10_block_coarse",
    ] {
        let m = abaqus::read(&reference(&format!(
            "e_matrices/{case}/ccx_matrix_free.inp"
        )))
        .unwrap();
        let dof =
            std::fs::read_to_string(reference(&format!("e_matrices/{case}/ccx_matrix_free.dof")))
                .unwrap();
        let mut dof_nodes: Vec<u64> = dof
            .lines()
            .map(|l| l.trim().split('.').next().unwrap().parse().unwrap())
            .collect();
        dof_nodes.dedup();
        let mut ids: Vec<u64> = m.nodes.iter().map(|n| n.id).collect();
        ids.sort_unstable();
        dof_nodes.sort_unstable();
        assert_eq!(ids, dof_nodes, "{case}");
        assert_eq!(dof.lines().count(), 3 * m.nodes.len(), "{case}");
        assert_eq!(m.materials[0].rho, 7850.0);
    }
    let m = abaqus::read(&reference("e_matrices/hex8_block_coarse/ccx_fixed.inp")).unwrap();
    assert_eq!(m.node_sets["ENDS"].len(), 18);
    assert_eq!(m.spcs.len(), m.node_sets["END_X0"].len());
}

/// The generator's 40×6×6 hex8 block has the same node coordinates as gmsh's structured
/// a_block_hex8 mesh (ids differ).
#[test]
fn generated_hex_block_matches_gmsh_reference_coordinates() {
    let r = abaqus::read(&reference("a_block_hex8/mesh.inp")).unwrap();
    let g = block(&BlockSpec {
        n: [40, 6, 6],
        size: [0.5, 0.05, 0.05],
        element: BlockElement::Hex8,
        material: Material::steel(),
    });
    let key = |x: [f64; 3]| x.map(|c| (c * 1e9).round() as i64);
    let mut a: Vec<_> = r.nodes.iter().map(|n| key(n.x)).collect();
    let mut b: Vec<_> = g.nodes.iter().map(|n| key(n.x)).collect();
    a.sort_unstable();
    b.sort_unstable();
    assert_eq!(a, b);
    assert_eq!(g.elements.len(), r.elements.len());
    assert_eq!(g.node_sets["X0"].len(), r.node_sets["FIXED"].len());
}

#[test]
fn keywords_generate_continuation_mass_rigid_coupling_beam() {
    let main = "** test deck\n*Heading\n x\n*NODE, NSET=ALL\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n\
5,1,1,1\n6, 2, 0, 0\n*include, input=more.inp\n\
*ELEMENT, TYPE=C3D4,\n  ELSET=TETS\n10, 1, 2,\n 3, 4\n*ELEMENT, TYPE=B31, ELSET=BEAMS\n11, 2, 6\n\
*ELEMENT, TYPE=MASS, ELSET=PM\n20, 5\n*MASS, ELSET=PM\n2.5\n*ROTARY INERTIA, ELSET=PM\n1, 2, 3, 0.1, 0.2, 0.3\n\
*NSET, NSET=GEN, GENERATE\n1, 5, 2\n*NSET, NSET=BOTH\nGEN, 2\n*ELSET, ELSET=EALL\nTETS, BEAMS\n\
*MATERIAL, NAME=Al\n*ELASTIC\n70e9, 0.33\n*DENSITY\n2.7D3\n\
*SOLID SECTION, ELSET=TETS, MATERIAL=AL\n\
*BEAM SECTION, ELSET=BEAMS, MATERIAL=AL, SECTION=RECT\n0.02, 0.01\n0, 0, 1\n\
*BOUNDARY\nGEN, 1, 6\n4, 2\n\
*RIGID BODY, NSET=BOTH, REF NODE=5\n\
*SURFACE, TYPE=NODE, NAME=S1\nGEN, 2.0\n*COUPLING, REF NODE=6, SURFACE=S1, CONSTRAINT NAME=C\n*DISTRIBUTING\n1, 3\n";
    let path = write_deck(
        "kw",
        &[("main.inp", main), ("more.inp", "*NODE\n7, 3, 0, 0\n")],
    );
    let m = abaqus::read(&path).unwrap();
    assert_eq!(m.nodes.len(), 7);
    assert_eq!(m.elements.len(), 2);
    assert_eq!(m.elements[0].nodes, vec![0, 1, 2, 3]);
    assert_eq!(m.node_sets["GEN"], vec![0, 2, 4]);
    assert_eq!(m.node_sets["BOTH"], vec![0, 1, 2, 4]);
    assert_eq!(m.element_sets["EALL"], vec![0, 1]);
    assert_eq!(m.materials[0].rho, 2700.0);
    let Section::Beam(b) = &m.properties[1].section else {
        panic!("beam section expected")
    };
    assert!((b.area - 2e-4).abs() < 1e-18 && (b.i1 - 0.01 * 0.02f64.powi(3) / 12.0).abs() < 1e-20);
    assert_eq!(m.elements[1].orientation, Some([0.0, 0.0, 1.0]));
    assert_eq!(m.spcs.len(), 4);
    assert_eq!(m.spcs[3].dofs, DofMask(0b10));
    assert_eq!(m.point_masses.len(), 1);
    let pm = &m.point_masses[0];
    assert_eq!(
        (pm.node, pm.mass, pm.inertia[0][1], pm.inertia[2][2]),
        (4, 2.5, 0.1, 3.0)
    );
    assert_eq!(
        m.rigid_elements[0],
        RigidElement::Rbe2 {
            id: 1,
            independent: 4,
            dependent: vec![0, 1, 2],
            dofs: DofMask::ALL
        }
    );
    let RigidElement::Rbe3 {
        reference,
        ref_dofs,
        independent,
        ..
    } = &m.rigid_elements[1]
    else {
        panic!("rbe3 expected")
    };
    assert_eq!(
        (*reference, *ref_dofs, independent.len(), independent[0].1),
        (5, DofMask::TRANSLATIONS, 3, 2.0)
    );
    // *HEADING cannot change the body: a note naming it
    assert!(
        m.deck.notes.iter().any(|n| n.contains("*HEADING")),
        "{:?}",
        m.deck.notes
    );
}

/// An extension that names no format leaves the format to the content (issue 44: an Abaqus
/// deck saved as `.txt` is read as Abaqus), and a forced format reads it alike.
#[test]
fn format_detection_by_extension_with_override() {
    use flexbody::import::Format;
    let text = std::fs::read_to_string(reference("e_matrices/hex8_single/mesh.inp")).unwrap();
    let path = write_deck("fmt", &[("deck.txt", &text)]);
    let m = read_model(&path, &ImportOptions::default()).unwrap();
    assert_eq!((m.nodes.len(), m.elements.len()), (8, 1));
    let opts = ImportOptions {
        format: Format::from_name("abaqus"),
        ..Default::default()
    };
    let m = read_model(&path, &opts).unwrap();
    assert_eq!((m.nodes.len(), m.elements.len()), (8, 1));
    assert_eq!(
        Format::from_extension(Path::new("x.BDF")),
        Some(Format::Nastran)
    );
    assert_eq!(
        Format::from_extension(Path::new("x.msh")),
        Some(Format::Gmsh)
    );
}

/// *TRANSFORM gives the nodes of its set a displacement frame; C3D8I is the incompatible-mode
/// hexahedron (the model's `solid_bubbles`), and refused beside C3D8.
#[test]
fn transform_frames_and_substituted_types() {
    let deck = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n\
*ELEMENT, TYPE=C3D8I, ELSET=E\n1, 1, 2, 3, 4, 5, 6, 7, 8\n*NSET, NSET=R\n1, 2\n*NSET, NSET=C\n7\n\
*TRANSFORM, NSET=R\n0, 1, 0, -1, 0, 0\n*TRANSFORM, NSET=C, TYPE=C\n0, 0, 0, 0, 0, 2\n";
    let path = write_deck("transform", &[("t.inp", deck)]);
    let m = abaqus::read(&path).unwrap();
    let r = &m.coord_systems[m.nodes[0].displacement_frame.unwrap()];
    // a = +y is local x, b = −x in the x–y plane: e3 = a × b = +z, e2 = e3 × e1 = −x.
    assert_eq!(r.axes, [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
    assert_eq!(m.nodes[1].displacement_frame, m.nodes[0].displacement_frame);
    let c = &m.coord_systems[m.nodes[6].displacement_frame.unwrap()];
    assert_eq!(
        (c.kind, c.axes[2]),
        (flexbody::model::CoordKind::Cylindrical, [0.0, 0.0, 1.0])
    );
    assert_eq!(m.nodes[2].displacement_frame, None);
    assert_eq!(m.elements[0].kind, ElementKind::Hex8);
    assert!(m.params.solid_bubbles);
    assert!(!m.warnings.iter().any(|w| w.message.contains("C3D8I")));
    let mixed = deck.replace(
        "*NSET, NSET=R",
        "*ELEMENT, TYPE=C3D8, ELSET=F\n2, 1, 2, 3, 4, 5, 6, 7, 8\n*NSET, NSET=R",
    );
    let path = write_deck("transform_mixed", &[("t.inp", &mixed)]);
    let e = abaqus::read(&path).unwrap_err().to_string();
    assert!(
        e.contains(":10: *ELEMENT, TYPE=C3D8I: C3D8I beside C3D8 elements"),
        "{e}"
    );
}

/// *NSET from an element set, and named boundary conditions.
#[test]
fn nset_from_elset_and_named_boundaries() {
    let deck = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n5, 1, 1, 1\n\
*ELEMENT, TYPE=C3D4, ELSET=E\n1, 1, 2, 3, 4\n*NSET, NSET=N, ELSET=E\n\
*BOUNDARY\nN, ENCASTRE\n5, XSYMM\n";
    let path = write_deck("nsetelset", &[("t.inp", deck)]);
    let m = abaqus::read(&path).unwrap();
    assert_eq!(m.node_sets["N"], vec![0, 1, 2, 3]);
    assert_eq!(m.spcs.len(), 5);
    assert!(m.spcs[..4].iter().all(|s| s.dofs == DofMask::ALL));
    // XSYMM: u1 = ur2 = ur3 = 0.
    assert_eq!(m.spcs[4].dofs, DofMask::from_digits("156").unwrap());
}

/// B31 sections the beam element cannot form as Abaqus places them are errors naming the
/// keyword's line and why: a BOX with unequal opposite walls, an I whose node (l) is off its
/// centroid. The I with l at its centroid and the even BOX are read.
#[test]
fn b31_sections_off_their_centroid_are_refused() {
    let deck = |section: &str, dims: &str| {
        format!(
            "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n*ELEMENT, TYPE=B31, ELSET=B\n1, 1, 2\n\
             *MATERIAL, NAME=S\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850\n\
             *BEAM SECTION, ELSET=B, MATERIAL=S, SECTION={section}\n{dims}\n0, 0, 1\n"
        )
    };
    let read = |name: &str, text: String| {
        abaqus::read(&write_deck(name, &[("main.inp", &text)])).map_err(|e| e.to_string())
    };
    let e = read(
        "box-uneven",
        deck("BOX", "0.05, 0.03, 0.004, 0.002, 0.003, 0.002"),
    )
    .unwrap_err();
    assert!(
        e.contains("main.inp:12") && e.contains("unequal opposite walls"),
        "{e}"
    );
    assert!(read(
        "box-even",
        deck("BOX", "0.05, 0.03, 0.004, 0.002, 0.004, 0.002")
    )
    .is_ok());
    // h = 0.1, b1 = 0.08 (t1 = 0.01), b2 = 0.04 (t2 = 0.01), web 0.005: centroid at
    // (0.0008·0.005 + 0.0004·0.05 + 0.0004·0.095)/0.0016 = 0.03875 above the bottom
    let e = read(
        "i-off",
        deck("I", "0.05, 0.1, 0.08, 0.04, 0.01, 0.01, 0.005"),
    )
    .unwrap_err();
    assert!(
        e.contains("main.inp:12") && e.contains("3.875000e-2"),
        "{e}"
    );
    assert!(read(
        "i-on",
        deck("I", "0.03875, 0.1, 0.08, 0.04, 0.01, 0.01, 0.005")
    )
    .is_ok());
}

/// C3D8I with an orthotropic material keeps massless incompatible modes (ccx 2.20 gives them
/// mass for every material; flexbody forms that for isotropic C3D8I): a warning says so; an
/// isotropic C3D8I deck has none.
#[test]
fn anisotropic_c3d8i_is_a_warning() {
    let deck = |elastic: &str| {
        format!(
            "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n\
             *ELEMENT, TYPE=C3D8I, ELSET=E\n1,1,2,3,4,5,6,7,8\n*MATERIAL, NAME=M\n{elastic}\
             *DENSITY\n7850\n*SOLID SECTION, ELSET=E, MATERIAL=M\n"
        )
    };
    let ortho = "*ELASTIC, TYPE=ORTHO\n2.2e11, 1e11, 2.1e11, 1e11, 1e11, 2e11, 8e10, 8e10,\n8e10\n";
    let m = abaqus::read(&write_deck("c3d8i-ortho", &[("main.inp", &deck(ortho))])).unwrap();
    assert!(
        m.warnings.iter().any(|w| w
            .message
            .starts_with("1 C3D8I elements with an anisotropic material")),
        "{:?}",
        m.warnings
    );
    let iso = "*ELASTIC\n2.1e11, 0.3\n";
    let m = abaqus::read(&write_deck("c3d8i-iso", &[("main.inp", &deck(iso))])).unwrap();
    assert!(!m.warnings.iter().any(|w| w.message.contains("C3D8I")));
}
