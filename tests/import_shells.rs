//! Shell sections through the importers: PSHELL fields, element thickness overrides, PCOMP
//! plies, THETA/MCID, offsets, and the inputs that are errors (a CQUAD8 without mid-side grids).
//! The Abaqus decks are read as flexbody's shells (`--inp-shells native`; expanded into bricks
//! as ccx does: tests/ccx_shell_expansion.rs).

use flexbody::import::{read_model, ImportOptions, InpShells};
use flexbody::model::{Model, Ply, Section, ShellMaterialAxis, ShellSection};

fn read(name: &str, text: &str) -> Result<Model, String> {
    let dir = std::env::temp_dir().join(format!("flexbody-import-shells-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let opts = ImportOptions {
        inp_shells: InpShells::Native,
        ..Default::default()
    };
    read_model(&path, &opts).map_err(|e| e.to_string())
}

const GRIDS: &str = "GRID    1               0.      0.      0.
GRID    2               1.      0.      0.
GRID    3               1.      1.      0.
GRID    4               0.      1.      0.
MAT1    1       2.1+11          .3      7850.
MAT1    2       7.0+10          .33     2700.
";

fn shell(m: &Model, elem: usize) -> &ShellSection {
    let p = m.elements[elem].property.unwrap();
    match &m.properties[p].section {
        Section::Shell(s) => s,
        other => panic!("{other:?}"),
    }
}

#[test]
fn pshell_fields_and_element_thickness_override() {
    // PSHELL PID MID1 T MID2 12I/T3 MID3 TS/T NSM
    let deck = format!(
        "BEGIN BULK
{GRIDS}PSHELL  7       1       .002    2       .8      2       .7      1.5
CQUAD4  10      7       1       2       3       4
CTRIA3  11      7       1       2       3
CQUAD4  12      7       1       2       3       4
                        .003    .003    .003    .005
CTRIA3  13      7       1       2       3
                1       .5      .5      .5
ENDDATA
"
    );
    let m = read("pshell.bdf", &deck).unwrap();
    let s = shell(&m, 0);
    assert_eq!(s.thickness, 0.002);
    assert!(s.membrane);
    assert_eq!(s.bending, Some((1, 0.8)));
    assert_eq!(s.shear, Some((1, 0.7)));
    assert_eq!(s.nsm, 1.5);
    assert_eq!(m.properties[m.elements[0].property.unwrap()].material, 0);
    assert_eq!(shell(&m, 1).thickness, 0.002);
    // corner thicknesses: the mean, with a warning for unequal corners; TFLAG = 1 relative
    assert!((shell(&m, 2).thickness - 0.0035).abs() < 1e-15);
    assert!((shell(&m, 3).thickness - 0.001).abs() < 1e-15);
    assert!(
        m.warnings
            .iter()
            .any(|w| w.message.contains("different corner thicknesses")),
        "{:?}",
        m.warnings
    );
}

#[test]
fn pcomp_plies_are_read_bottom_to_top_with_sym_and_theta() {
    let deck = format!(
        "BEGIN BULK
{GRIDS}PCOMP,6,,0.25,,,,,
,1,0.1,45.
,1,0.2,-45.
CQUAD4  10      6       1       2       3       4
ENDDATA
"
    );
    let m = read("pcomp.bdf", &deck).unwrap();
    let s = shell(&m, 0);
    assert!((s.thickness - 0.3).abs() < 1e-15);
    assert_eq!((s.bending, s.nsm), (Some((0, 1.0)), 0.25));
    let ply = |material, thickness, angle_deg| Ply {
        material,
        thickness,
        angle_deg,
    };
    assert_eq!(s.plies, [ply(0, 0.1, 45.0), ply(0, 0.2, -45.0)]);
    let sym = deck.replace("PCOMP,6,,0.25,,,,,", "PCOMP,6,,0.25,,,,,SYM");
    let s = shell(&read("sym.bdf", &sym).unwrap(), 0).clone();
    assert!((s.thickness - 0.6).abs() < 1e-15);
    assert_eq!(s.plies[2..], [ply(0, 0.2, -45.0), ply(0, 0.1, 45.0)]);
    // plies of two materials (model indices 0, 1), THETA on the element
    let mixed = deck.replace(",1,0.2,-45.", ",2,0.2,-45.").replace(
        "CQUAD4  10      6       1       2       3       4",
        "CQUAD4  10      6       1       2       3       4       30.",
    );
    let m = read("mixed.bdf", &mixed).unwrap();
    assert_eq!(shell(&m, 0).plies[1], ply(1, 0.2, -45.0));
    assert_eq!(
        m.shell_axes.get(&0),
        Some(&ShellMaterialAxis::FromSide12 { theta_deg: 30.0 })
    );
    let mcid = mixed.replace("       30.", "       0");
    let m = read("mcid.bdf", &mcid).unwrap();
    assert_eq!(
        m.shell_axes.get(&0),
        Some(&ShellMaterialAxis::Projected([1.0, 0.0, 0.0]))
    );
    let e = read("mcid9.bdf", &mixed.replace("       30.", "       9")).unwrap_err();
    assert!(e.contains("element 10") && e.contains("MCID 9"), "{e}");
    let offset = deck.replace("PCOMP,6,,0.25", "PCOMP,6,0.,0.25");
    // Z0 = 0: the bottom on the grids, the mid-plane T/2 = 0.15 above them (shell_offset)
    let m = read("z0.bdf", &offset).unwrap();
    let quad = &m.elements[0];
    assert!(quad
        .nodes
        .iter()
        .all(|&n| (m.nodes[n].x[2] - 0.15).abs() < 1e-12));
}

#[test]
fn shell_offsets_are_read_mid4_is_an_error_and_blank_midsides_are_straight() {
    let base = format!(
        "BEGIN BULK
{GRIDS}PSHELL  7       1       .002    1
CQUAD4  10      7       1       2       3       4
ENDDATA
"
    );
    assert!(read("ok.bdf", &base).is_ok());
    let z = base.replace(
        "CQUAD4  10      7       1       2       3       4",
        "CQUAD4  10      7       1       2       3       4       0.      .001",
    );
    // ZOFFS = 1 mm: the element moves onto four new nodes 1 mm above its grids (normal +z from
    // the diagonals G1→G3 × G2→G4), tied to them by an RBE2 per grid
    let m = read("zoffs.bdf", &z).unwrap();
    assert_eq!(m.nodes.len(), 8);
    let quad = &m.elements[0];
    for (k, &n) in quad.nodes.iter().enumerate() {
        assert_eq!(m.nodes[n].x[2], 0.001);
        assert_eq!(m.nodes[n].x[..2], m.nodes[k].x[..2]);
    }
    assert_eq!(m.rigid_elements.len(), 4);
    let flipped = z.replace("1       2       3       4  ", "4       3       2       1  ");
    let m = read("zoffs-flipped.bdf", &flipped).unwrap();
    assert_eq!(m.nodes[m.elements[0].nodes[0]].x[2], -0.001);
    let mid4 = base.replace(
        "PSHELL  7       1       .002    1",
        "PSHELL  7       1       .002    1\n                        2",
    );
    let e = read("mid4.bdf", &mid4).unwrap_err();
    assert!(e.contains("MID4"), "{e}");
    // T blank on the PSHELL and none on the element: the assembler names both
    let blank_t = base.replace(
        "PSHELL  7       1       .002    1",
        "PSHELL  7       1               1",
    );
    let m = read("blank_t.bdf", &blank_t).unwrap();
    let e = flexbody::fe::assemble(&m, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("element 10") && e.contains("PSHELL T blank"),
        "{e}"
    );
    let q8 = base.replace(
        "CQUAD4  10      7       1       2       3       4",
        "CQUAD8  10      7       1       2       3       4",
    );
    // a CQUAD8 with its four mid-side grids blank has straight edges, as MSC Nastran forms it
    // (issue 44, docs/nastran-structural-cards.md): a node at each edge's mid-point tied by an
    // MPC on each of its six dofs (the 4-grid form is not read as a CQUAD4)
    let m = read("q8.bdf", &q8).unwrap();
    assert_eq!((m.nodes.len(), m.mpcs.len()), (8, 4 * 6));
    assert!(
        m.deck
            .notes
            .iter()
            .any(|n| n.contains("4 edges made straight")),
        "{:?}",
        m.deck.notes
    );
}

const INP: &str = "*NODE
1, 0., 0., 0.
2, 1., 0., 0.
3, 1., 1., 0.
4, 0., 1., 0.
*ELEMENT, TYPE=S4, ELSET=P
1, 1, 2, 3, 4
*SHELL SECTION, ELSET=P, MATERIAL=AL
0.003, 5
*MATERIAL, NAME=AL
*ELASTIC
7e10, 0.33
*DENSITY
2700.
";

#[test]
fn abaqus_shell_section_thickness_points_note_and_offset() {
    let m = read("s.inp", INP).unwrap();
    let s = shell(&m, 0);
    assert_eq!(*s, ShellSection::homogeneous(0.003, 0));
    assert!(
        m.warnings
            .iter()
            .any(|w| w.message.contains("section points")),
        "{:?}",
        m.warnings
    );
    // OFFSET=SPOS: the nodes on the top surface, the native shell's mid-surface t/2 below
    // them (Nastran's ZOFFS = −OFFSET·t, model::shell_offset: a node per corner there, rigidly
    // linked to its grid point)
    let off = INP.replace("MATERIAL=AL\n", "MATERIAL=AL, OFFSET=SPOS\n");
    let m = read("off.inp", &off).unwrap();
    assert_eq!(m.nodes.len(), 8);
    assert_eq!(m.rigid_elements.len(), 4);
    let mid = &m.nodes[m.elements[0].nodes[0]];
    assert!((mid.x[2] + 0.0015).abs() < 1e-15, "{:?}", mid.x);
    let bad = INP.replace("MATERIAL=AL\n", "MATERIAL=AL, OFFSET=TOP\n");
    let e = read("bad.inp", &bad).unwrap_err();
    assert!(e.contains("bad.inp:") && e.contains("OFFSET=TOP"), "{e}");
    let s8 = INP
        .replace("TYPE=S4,", "TYPE=S8R,")
        .replace("1, 1, 2, 3, 4\n", "1, 1, 2, 3, 4, 5, 6, 7, 8\n")
        .replace(
            "*ELEMENT",
            "5, .5, 0., 0.\n6, 1., .5, 0.\n7, .5, 1., 0.\n8, 0., .5, 0.\n*ELEMENT",
        );
    // S8R: the 8-node shell (fe::elements::quad8_shell), 6 dofs at each of its nodes
    let m = read("s8.inp", &s8).unwrap();
    let asm = flexbody::fe::assemble(&m, &Default::default()).unwrap();
    assert_eq!(asm.k.nrows(), 48);
}
