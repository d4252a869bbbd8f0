//! ANSYS archives (`.cdb`) and full files (`.full`) against ANSYS's own matrices and the
//! example files ansys-mapdl-reader ships (`pip install ansys-mapdl-reader`, MIT licence; read
//! from the installed package, not committed):
//!
//! * `HexBeam.cdb` (40 SOLID186, ANSYS 2019 R2) and `file.full` (ANSYS's K and M of that mesh,
//!   constrained at its z = 0 face). The full file was solved with the material its companion
//!   `file.rst` states (EX = 1.69e7, NUXY = 0.31, DENS = 4.1408e-4, read here from the result
//!   file by ansys-mapdl-reader), not HexBeam.cdb's aluminium: our K and M of the mesh with that
//!   material equal the file's dof by dof, and the normal modes from the archive (clamped as the
//!   full file's constrained dofs say) and from the full file equal the package's 20 frequencies.
//! * `TetBeam.cdb` (3913 SOLID187 written with their corner nodes, MESH200 type): the same mesh
//!   as a Nastran deck of CTETRA 4.
//! * Archives written here: SOLID187 with mid-side nodes against the Nastran CTETRA 10 deck of
//!   the same mesh; a component as `--interface`; refusals by line.

use std::collections::HashMap;

use crate::ansys_support::{
    against_package, build_modes, clamp_lines, examples, hexbeam_as_solved, python, PACKAGE_HZ,
};
use crate::common::{exe, generalized_eigenvalues, hz, scratch};
use faer::Mat;
use flexbody::fe::{AssemblySpec, MassKind};
use flexbody::import::ansys::full;
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::Model;

fn consistent() -> AssemblySpec {
    AssemblySpec {
        mass: MassKind::Consistent,
        ..Default::default()
    }
}

/// The largest |ours − file| / sqrt(|a_ii a_jj|) over the file's pairs of free equations, and
/// over our pairs the file does not hold.
fn largest_difference(
    model: &Model,
    ours: &faer::sparse::SparseColMat<usize, f64>,
    dofs: &flexbody::fe::DofMap,
    f: &full::FullFile,
    theirs: &flexbody::import::ccx_matrices::SymmetricTriplets,
) -> f64 {
    let index = model.node_index_by_id();
    let ours_of: Vec<Option<usize>> = (f.dofs.iter().zip(&f.constrained))
        .map(|(d, c)| {
            let i = index[&d.node];
            (!c).then(|| dofs.dof(i, d.dir as usize).expect("a dof of the node"))
        })
        .collect();
    let dense = crate::common::dense(ours);
    let mut file_entry: HashMap<(usize, usize), f64> = HashMap::new();
    for &(r, c, v) in &theirs.upper {
        if let (Some(a), Some(b)) = (ours_of[r], ours_of[c]) {
            *file_entry.entry((a.min(b), a.max(b))).or_default() += v;
        }
    }
    let free: Vec<usize> = ours_of.iter().flatten().copied().collect();
    let scale = |a: usize, b: usize| (dense[(a, a)] * dense[(b, b)]).abs().sqrt();
    let mut worst: f64 = 0.0;
    for &a in &free {
        for &b in &free {
            if a > b {
                continue;
            }
            let theirs = file_entry.get(&(a, b)).copied().unwrap_or(0.0);
            worst = worst.max((dense[(a, b)] - theirs).abs() / scale(a, b));
        }
    }
    worst
}

/// Our K and M of HexBeam (with file.rst's material) equal file.full's, dof by dof.
#[test]
fn hexbeam_k_and_m_equal_the_full_file_dof_by_dof() {
    let Some(dir) = examples("HexBeam.cdb K and M against file.full") else {
        return;
    };
    let work = scratch("ansys-km");
    let cdb = work.join("hexbeam.cdb");
    std::fs::write(&cdb, hexbeam_as_solved(&dir, "")).unwrap();
    let model = read_model(&cdb, &ImportOptions::default()).unwrap();
    assert_eq!((model.nodes.len(), model.elements.len()), (321, 40));
    let asm = flexbody::fe::assemble(&model, &consistent()).unwrap();
    let f = full::read_full(&dir.join("file.full")).unwrap();
    assert_eq!(f.dofs.len(), 963);
    assert_eq!(f.constrained.iter().filter(|c| **c).count(), 63);
    let dk = largest_difference(&model, &asm.k, &asm.dofs, &f, &f.k);
    let dm = largest_difference(&model, &asm.m, &asm.dofs, &f, f.m.as_ref().unwrap());
    // relative to sqrt(a_ii a_jj); measured 3.2e-13 (K, SOLID186's reduced 2×2×2) and 5.1e-12
    // (M, ANSYS's 14-point rule); the acceptance asks 1e-10
    println!("largest relative differences: K {dk:.2e}, M {dm:.2e}");
    assert!(dk < 3e-12 && dm < 5e-11, "K {dk:e}, M {dm:e}");
}

/// Normal modes of the clamped archive through the CLI, and of the full file's free
/// equations, equal the package's 20 frequencies.
#[test]
fn hexbeam_modes_from_archive_and_full_file_equal_the_package() {
    let Some(dir) = examples("HexBeam modes against the package's frequencies") else {
        return;
    };
    let f = full::read_full(&dir.join("file.full")).unwrap();
    let work = scratch("ansys-modes");
    let cdb = work.join("clamped.cdb");
    std::fs::write(&cdb, hexbeam_as_solved(&dir, &clamp_lines(&f))).unwrap();
    let out = work.join("clamped.flexbody");
    let o = exe()
        .arg("build")
        .arg(&cdb)
        .args(["--units", "si", "--method", "normal", "--modes", "20", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("consistent"), "{stderr}");
    let body = flexbody_reader::read(&out).unwrap();
    let d_archive = against_package(&body.modes.frequency_hz);

    // the full file's free equations, with the archive's nodes
    let mesh = read_model(&cdb, &ImportOptions::default()).unwrap();
    let mm = full::matrix_model(&dir.join("file.full"), &mesh).unwrap();
    assert_eq!((mm.k.n, mm.nodes.len()), (900, 300));
    let dense = |t: &flexbody::import::ccx_matrices::SymmetricTriplets| {
        let mut a = Mat::zeros(t.n, t.n);
        for (r, c, v) in t.full() {
            a[(r, c)] += v;
        }
        a
    };
    let lambda = generalized_eigenvalues(&dense(&mm.k), &dense(&mm.m));
    let from_full: Vec<f64> = lambda[..20].iter().map(|&l| hz(l)).collect();
    let d_full = against_package(&from_full);
    // measured 1.4e-12 (archive, through the CLI) and 4.7e-11 (full file, dense solve); the
    // package's values have 12 digits, the acceptance asks 1e-8
    println!("largest relative differences: archive {d_archive:.2e}, full file {d_full:.2e}");
    assert!(
        d_archive < 1.5e-11 && d_full < 5e-10,
        "{d_archive:e} {d_full:e}"
    );
}

/// A Nastran deck of `model`'s tetrahedra (CTETRA 4 or 10) with steel-like MAT1.
fn nastran_deck(model: &Model, e: f64, nu: f64, rho: f64) -> String {
    let mut s = String::from("SOL 103\nCEND\nBEGIN BULK\nPARAM,COUPMASS,1\n");
    for n in &model.nodes {
        s.push_str(&format!(
            "GRID,{},,{:?},{:?},{:?}\n",
            n.id, n.x[0], n.x[1], n.x[2]
        ));
    }
    for el in &model.elements {
        let ids: Vec<String> = el
            .nodes
            .iter()
            .map(|&i| model.nodes[i].id.to_string())
            .collect();
        let (first, rest) = ids.split_at(ids.len().min(6));
        s.push_str(&format!("CTETRA,{},1,{}\n", el.id, first.join(",")));
        if !rest.is_empty() {
            s.push_str(&format!(",{}\n", rest.join(",")));
        }
    }
    s.push_str(&format!(
        "PSOLID,1,1\nMAT1,1,{e:e},,{nu},{rho:e}\nENDDATA\n"
    ));
    s
}

/// TetBeam.cdb (3913 SOLID187 written with 4 nodes: the linear tetrahedron; its ET 2, SOLID186,
/// has no element) and the same mesh as CTETRA 4 (the same modes with consistent mass, ANSYS's
/// default) and as C3D4 (the same modes with lumped mass: ccx's C3D4 consistent mass, which the
/// Abaqus importer forms, is another rule).
#[test]
fn tetbeam_equals_the_same_mesh_as_nastran_and_abaqus_decks() {
    let Some(dir) = examples("TetBeam.cdb against the same mesh as Nastran and Abaqus decks")
    else {
        return;
    };
    let material = "E=2.0e11,nu=0.3,rho=7850";
    let cdb = dir.join("TetBeam.cdb");
    let opts = ImportOptions {
        material: Some(flexbody::model::Material::isotropic(
            1, "M", 2.0e11, 0.3, 7850.0,
        )),
        ..Default::default()
    };
    let model = read_model(&cdb, &opts).unwrap();
    assert_eq!(model.elements.len(), 3913);
    assert!(model
        .elements
        .iter()
        .all(|e| e.kind == flexbody::model::ElementKind::Tet4));
    let work = scratch("ansys-tetbeam");
    let bdf = work.join("tetbeam.bdf");
    std::fs::write(&bdf, nastran_deck(&model, 2.0e11, 0.3, 7850.0)).unwrap();
    let inp = work.join("tetbeam.inp");
    std::fs::write(&inp, abaqus_deck(&model, [2.0e11, 0.3, 7850.0], "")).unwrap();
    let local = work.join("tetbeam.cdb");
    std::fs::copy(&cdb, &local).unwrap();
    let ours = build_modes(
        &local,
        12,
        &["--material", material, "--mass", "consistent"],
    );
    let nastran = build_modes(&bdf, 12, &["--mass", "consistent"]);
    let lumped = build_modes(&local, 12, &["--material", material, "--mass", "lumped"]);
    let abaqus = build_modes(&inp, 12, &["--mass", "lumped"]);
    let worst = |ours: &[f64], other: &[f64]| {
        (ours.iter().zip(other).skip(6))
            .map(|(a, b)| ((a - b) / b).abs())
            .fold(0.0, f64::max)
    };
    let (d_nastran, d_abaqus) = (worst(&ours, &nastran), worst(&lumped, &abaqus));
    // measured 0 and 1.0e-14 (the same element matrices through the three importers); C3D4's
    // consistent mass is CalculiX's one-point rule (every entry ρV/16), not the linear
    // tetrahedron's exact one, so the consistent builds of the Abaqus deck differ (1.6e-2,
    // measured once)
    println!("TetBeam against CTETRA 4 (consistent): {d_nastran:.2e}, against C3D4 (lumped): {d_abaqus:.2e}");
    assert!(d_nastran < 1e-10, "{ours:?} {nastran:?}");
    assert!(d_abaqus < 1e-13, "{lumped:?} {abaqus:?}");
}

/// One SOLID187 with its mid-side nodes (bowed edges), a second sharing a face: the archive
/// written here against the same mesh as CTETRA 10.
#[test]
fn solid187_with_mid_side_nodes_equals_ctetra10() {
    let x: [[f64; 3]; 5] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.8, 0.9, 1.1],
    ];
    let mid = |a: usize, b: usize, bow: f64| {
        [
            0.5 * (x[a][0] + x[b][0]) + bow,
            0.5 * (x[a][1] + x[b][1]),
            0.5 * (x[a][2] + x[b][2]) - bow,
        ]
    };
    // element 1: corners 1 2 3 4, element 2: corners 2 3 4 5 (shared face 2 3 4)
    let edges: [(usize, usize); 9] = [
        (0, 1),
        (1, 2),
        (2, 0),
        (0, 3),
        (1, 3),
        (2, 3),
        (1, 4),
        (2, 4),
        (3, 4),
    ];
    let mut coords: Vec<[f64; 3]> = x.to_vec();
    for (k, &(a, b)) in edges.iter().enumerate() {
        coords.push(mid(a, b, 0.02 * k as f64));
    }
    let e1 = [1, 2, 3, 4, 6, 7, 8, 9, 10, 11];
    // SOLID187 I J K L M(I-J) N(J-K) O(K-I) P(I-L) Q(J-L) R(K-L) with I..L = 2 3 4 5
    let e2 = [2, 3, 4, 5, 7, 11, 10, 12, 13, 14];
    let mut cdb = String::from("/PREP7\nET,1,187\nNBLOCK,6,SOLID,14,14\n(3i9,6e21.13e3)\n");
    for (i, p) in coords.iter().enumerate() {
        cdb.push_str(&format!(
            "{:>9}{:>9}{:>9}{:>21.13E}{:>21.13E}{:>21.13E}\n",
            i + 1,
            0,
            0,
            p[0],
            p[1],
            p[2]
        ));
    }
    cdb.push_str("N,R5.3,LOC,       -1,\nEBLOCK,19,SOLID,2,2\n(19i9)\n");
    for (id, e) in [(1, e1), (2, e2)] {
        let mut line = format!(
            "{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}",
            1, 1, 1, 1, 0, 0, 0, 0, 10, 0, id
        );
        for n in &e[..8] {
            line.push_str(&format!("{n:>9}"));
        }
        cdb.push_str(&format!("{line}\n{:>9}{:>9}\n", e[8], e[9]));
    }
    cdb.push_str("       -1\nMPTEMP,R5.0, 1, 1,  0.00000000    ,\nMPDATA,R5.0, 1,EX  ,       1, 1, 2.1e11,\n");
    cdb.push_str("MPTEMP,R5.0, 1, 1,  0.00000000    ,\nMPDATA,R5.0, 1,PRXY,       1, 1, 0.29,\n");
    cdb.push_str(
        "MPTEMP,R5.0, 1, 1,  0.00000000    ,\nMPDATA,R5.0, 1,DENS,       1, 1, 7800.,\nFINISH\n",
    );
    let work = scratch("ansys-solid187");
    let path = work.join("two.cdb");
    std::fs::write(&path, &cdb).unwrap();
    let model = read_model(&path, &ImportOptions::default()).unwrap();
    assert_eq!(model.elements.len(), 2);
    assert!(model
        .elements
        .iter()
        .all(|e| e.kind == flexbody::model::ElementKind::Tet10));
    let bdf = work.join("two.bdf");
    std::fs::write(&bdf, nastran_deck(&model, 2.1e11, 0.29, 7800.0)).unwrap();
    let ours = build_modes(&path, 20, &["--mass", "consistent"]);
    let nastran = build_modes(&bdf, 20, &["--mass", "consistent"]);
    let worst = (ours.iter().zip(&nastran).skip(6))
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(0.0, f64::max);
    // measured 0 (the same element matrices through both importers)
    assert!(worst < 1e-10, "{ours:?} {nastran:?}");
}

/// HexBeam's node component NCOMP2 as `--interface`: an RBE2 spider over the component's
/// nodes as ansys-mapdl-reader lists them.
#[test]
fn a_node_component_is_an_interface() {
    let Some(dir) = examples("a HexBeam component as --interface") else {
        return;
    };
    let listed = python(&format!(
        "import ansys.mapdl.reader as r; a = r.Archive(r'{}'); \
         print(' '.join(str(int(n)) for n in a.node_components['NCOMP2']))",
        dir.join("HexBeam.cdb").display()
    ))
    .expect("the package reads HexBeam's components");
    let mut expected: Vec<u64> = listed
        .split_whitespace()
        .map(|s| s.parse().unwrap())
        .collect();
    expected.sort_unstable();
    // 42 CMBLOCK items, ranges among them
    assert_eq!(expected.len(), 98);
    let work = scratch("ansys-interface");
    let cdb = work.join("hexbeam.cdb");
    std::fs::copy(dir.join("HexBeam.cdb"), &cdb).unwrap();
    let out = work.join("hexbeam.flexbody");
    let o = exe()
        .arg("build")
        .arg(&cdb)
        .args([
            "--units",
            "si",
            "--interface",
            "NCOMP2",
            "--modes",
            "6",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let body = flexbody_reader::read(&out).unwrap();
    let itf = body.interfaces.expect("interfaces.bin");
    assert_eq!(itf.len(), 1);
    assert_eq!(itf[0].name, "NCOMP2");
    let mut dependent = itf[0].dependent.clone();
    dependent.sort_unstable();
    assert_eq!(dependent, expected);
}

/// An archive with a command and an element type outside the catalogue, and a KEYOPT not
/// formed: exit 2, each named with its line.
#[test]
fn refusals_name_the_command_element_type_and_keyopt_by_line() {
    let nodes: String = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        .iter()
        .enumerate()
        .map(|(i, p)| {
            format!(
                "{:>9}{:>9}{:>9}{:>21.13E}{:>21.13E}\n",
                i + 1,
                0,
                0,
                p[0],
                p[1]
            )
        })
        .collect();
    let record = |etype: usize, nodes: &str| {
        format!(
            "{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{nodes}\n",
            1, etype, 1, 1, 0, 0, 0, 0, 4, 0, 7
        )
    };
    let cdb = format!(
        "/PREP7\nET,1,186\nKEYOPT,1,2,1\nET,2,181\nNBLOCK,6,SOLID,4,4\n(3i9,6e21.13e3)\n{nodes}\
         N,R5.3,LOC,       -1,\nEBLOCK,19,SOLID,1,1\n(19i9)\n{}       -1\nFOOBAR,1,2\nFINISH\n",
        record(2, "        1        2        3        4")
    );
    let work = scratch("ansys-refusals");
    let path = work.join("bad.cdb");
    std::fs::write(&path, &cdb).unwrap();
    let o = exe()
        .arg("build")
        .arg(&path)
        .args(["--units", "si", "-o"])
        .arg(work.join("bad.flexbody"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("bad.cdb:16: FOOBAR: command FOOBAR is not in the catalogue"),
        "{err}"
    );
    assert!(
        err.contains("bad.cdb:14: EBLOCK element of type 2 (SHELL181, ET line 4)")
            && err.contains("SHELL181 KEYOPT(3)=0 (the default"),
        "{err}"
    );
    assert!(!work.join("bad.flexbody").exists());

    // the same mesh as SOLID186 with KEYOPT(3)=1 (layered) refused by name (and no shell)
    let twenty = format!(
        "{}\n{}",
        "        1        2        3        4".repeat(2),
        "        1        2        3        4".repeat(3)
    );
    let solid = cdb
        .replace("ET,2,181\n", "")
        .replace("KEYOPT,1,2,1\n", "KEYOPT,1,3,1\n")
        .replace("FOOBAR,1,2\n", "")
        .replace(
            &record(2, "        1        2        3        4"),
            &record(1, &twenty).replacen(
                "        4        0        7",
                "       20        0        7",
                1,
            ),
        );
    std::fs::write(&path, &solid).unwrap();
    let o = exe()
        .arg("build")
        .arg(&path)
        .args(["--units", "si", "-o"])
        .arg(work.join("bad.flexbody"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("SOLID186 KEYOPT(3)=1"), "{err}");
}

/// The model's solid mesh as an Abaqus deck (C3D20R, C3D10 or C3D4 by node count, in the
/// node order SOLID186/187 share with them), of the material [E, ν, ρ], `extra` appended.
fn abaqus_deck(model: &Model, [e, nu, rho]: [f64; 3], extra: &str) -> String {
    let mut s = String::from("*NODE\n");
    for n in &model.nodes {
        s.push_str(&format!(
            "{}, {:?}, {:?}, {:?}\n",
            n.id, n.x[0], n.x[1], n.x[2]
        ));
    }
    let count = model.elements[0].nodes.len();
    assert!(model.elements.iter().all(|e| e.nodes.len() == count));
    let kind = match count {
        20 => "C3D20R",
        10 => "C3D10",
        4 => "C3D4",
        n => panic!("{n}-node elements"),
    };
    s.push_str(&format!("*ELEMENT, TYPE={kind}, ELSET=ALL\n"));
    for el in &model.elements {
        let ids: Vec<String> = el
            .nodes
            .iter()
            .map(|&i| model.nodes[i].id.to_string())
            .collect();
        // at most 16 entries a line, the element id first
        let (first, rest) = ids.split_at(ids.len().min(15));
        s.push_str(&format!("{}, {}", el.id, first.join(", ")));
        if !rest.is_empty() {
            s.push_str(&format!(",\n{}", rest.join(", ")));
        }
        s.push('\n');
    }
    s.push_str(&format!(
        "*MATERIAL, NAME=M\n*ELASTIC\n{e:?}, {nu:?}\n*DENSITY\n{rho:?}\n*SOLID SECTION, ELSET=ALL, MATERIAL=M\n{extra}"
    ));
    s
}

/// Material 1 of the model as [E, ν, ρ].
fn material_of(model: &Model) -> [f64; 3] {
    let m = &model.materials[0];
    [m.e, m.nu, m.rho]
}

/// D, CE and CP in an archive against the *BOUNDARY and *EQUATION they stand for in the same
/// mesh as C3D20R (lumped mass: the same element matrices through both importers).
#[test]
fn d_ce_and_cp_equal_the_abaqus_boundary_and_equations() {
    let Some(dir) = examples("D, CE and CP against Abaqus *BOUNDARY/*EQUATION") else {
        return;
    };
    let mut extra = String::new();
    for n in 1..=21 {
        extra.push_str(&format!("D,{n},ALL,0\n"));
    }
    extra.push_str("CP,1,UX,22,23,24\n");
    extra.push_str("CE,R5.0,DEFI,       2,       1,  0.00000000    \n");
    extra
        .push_str("CE,R5.0,NODE,       25,UY  ,  2.00000000    ,       26,UY  , -1.00000000    \n");
    let work = scratch("ansys-ce-cp");
    let cdb = work.join("tied.cdb");
    std::fs::write(&cdb, hexbeam_as_solved(&dir, &extra)).unwrap();
    let model = read_model(&cdb, &ImportOptions::default()).unwrap();
    assert_eq!((model.spcs.len(), model.mpcs.len()), (21, 3));
    let inp = work.join("tied.inp");
    let mut keywords = String::from("*BOUNDARY\n");
    for n in 1..=21 {
        keywords.push_str(&format!("{n}, 1, 3\n"));
    }
    keywords.push_str("*EQUATION\n2\n23, 1, 1.0, 22, 1, -1.0\n2\n24, 1, 1.0, 22, 1, -1.0\n");
    keywords.push_str("2\n25, 2, 2.0, 26, 2, -1.0\n");
    std::fs::write(&inp, abaqus_deck(&model, material_of(&model), &keywords)).unwrap();
    let ours = build_modes(&cdb, 12, &["--mass", "lumped"]);
    let abaqus = build_modes(&inp, 12, &["--mass", "lumped"]);
    let free = build_modes(
        &{
            let p = work.join("clamped.cdb");
            std::fs::write(
                &p,
                hexbeam_as_solved(&dir, &extra[..extra.find("CP").unwrap()]),
            )
            .unwrap();
            p
        },
        12,
        &["--mass", "lumped"],
    );
    let worst = (ours.iter().zip(&abaqus))
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(0.0, f64::max);
    // measured 0; the ties do change the modes (the untied clamp differs by 1e-4 or more)
    println!(
        "D/CE/CP against *BOUNDARY/*EQUATION: {worst:.2e}; untied {:?}",
        &free[..3]
    );
    assert!(worst < 1e-10, "{ours:?} {abaqus:?}");
    assert!(ours
        .iter()
        .zip(&free)
        .any(|(a, b)| ((a - b) / b).abs() > 1e-4));
}

/// LUMPM,ON builds the lumped mass (as --mass lumped); F and ACEL are scene loads.
#[test]
fn lumpm_and_loads_are_read() {
    let Some(dir) = examples("LUMPM, F and ACEL") else {
        return;
    };
    let work = scratch("ansys-lumpm");
    let clamp: String = (1..=21).map(|n| format!("D,{n},ALL,0\n")).collect();
    let lumped = work.join("lumpm.cdb");
    let extra =
        format!("{clamp}LUMPM,ON\nF,      22,FY  ,  150.0    ,  0.0\nACEL,  0.0,  0.0,  9.81\n");
    std::fs::write(&lumped, hexbeam_as_solved(&dir, &extra)).unwrap();
    let model = read_model(&lumped, &ImportOptions::default()).unwrap();
    assert_eq!(
        model.params.coupled_mass.as_ref().map(|m| m.consistent),
        Some(false)
    );
    let names: Vec<&str> = model.loads.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["F", "ACEL"]);
    assert!(matches!(
        model.loads[1].parts[..],
        [flexbody::model::load::LoadPart::Gravity { accel }] if accel == [0.0, 0.0, -9.81]
    ));
    let consistent = work.join("consistent.cdb");
    std::fs::write(&consistent, hexbeam_as_solved(&dir, &clamp)).unwrap();
    let by_lumpm = build_modes(&lumped, 8, &[]);
    let by_option = build_modes(&consistent, 8, &["--mass", "lumped"]);
    let by_default = build_modes(&consistent, 8, &[]);
    assert_eq!(by_lumpm, by_option);
    assert!((by_default[0] - PACKAGE_HZ[0]).abs() < 1e-6 * PACKAGE_HZ[0]);
    assert!((by_lumpm[0] - by_default[0]).abs() > 1e-3 * by_default[0]);
}

/// A temperature table is read at TREF when it holds TREF, refused otherwise.
#[test]
fn temperature_tables_are_read_at_tref_or_refused() {
    let Some(dir) = examples("temperature tables") else {
        return;
    };
    let text = std::fs::read_to_string(dir.join("HexBeam.cdb")).unwrap();
    let table =
        "MPTEMP,R5.0, 2, 1,  20.0, 100.0,\nMPDATA,R5.0, 2,EX  ,       1, 1, 7.1e10, 6.5e10,\n";
    let work = scratch("ansys-tables");
    let path = work.join("t.cdb");
    std::fs::write(&path, format!("{text}{table}TREF,100.0\n")).unwrap();
    let model = read_model(&path, &ImportOptions::default()).unwrap();
    assert_eq!(model.materials[0].e, 6.5e10);
    std::fs::write(&path, format!("{text}{table}TREF,50.0\n")).unwrap();
    let err = read_model(&path, &ImportOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("material 1 EX: a table over 2 temperatures"),
        "{err}"
    );
}

/// sector.cdb (105 SOLID185 with the default KEYOPT(2)=0, B-bar: bricks and bricks collapsed
/// into ANSYS's wedge; no material in the archive) builds with `--material`, and free-free it has
/// its six rigid modes and no spurious zero-energy mode (a degenerate brick formed wrongly can
/// add one). The formulation itself is shown against ANSYS's element forces in
/// `tests/ansys_solids.rs`.
#[test]
fn sector_solid185_builds_with_six_rigid_modes() {
    let Some(dir) = examples("sector.cdb builds") else {
        return;
    };
    let work = scratch("ansys-sector");
    let local = work.join("sector.cdb");
    std::fs::copy(dir.join("sector.cdb"), &local).unwrap();
    let opts = ImportOptions {
        material: Some(flexbody::model::Material::isotropic(
            1, "M", 1.7e7, 0.3, 5e-4,
        )),
        ..Default::default()
    };
    let model = read_model(&local, &opts).unwrap();
    let wedges = (model.elements.iter())
        .filter(|e| e.nodes[2] == e.nodes[3] && e.nodes[6] == e.nodes[7])
        .count();
    assert_eq!(model.elements.len(), 105);
    assert!(wedges > 0, "the sector holds collapsed wedges");
    assert!((model.elements.iter()).all(|e| e.kind == flexbody::model::ElementKind::Hex8Bbar));
    // no D in the archive: free-free
    let hz = build_modes(&local, 10, &["--material", "E=1.7e7,nu=0.3,rho=5e-4"]);
    // measured: the 6th 2.9e-3 Hz, the 7th 9487 Hz (ratio 3.3e6)
    assert!(hz[6] > 1e6 * hz[5].abs(), "{hz:?}");
    let _ = std::fs::remove_dir_all(&work);
}

/// MASS21 (KEYOPT(3)=2, a mass from its real constant set) on HexBeam's free end against the
/// Abaqus *MASS of the same mesh (lumped mass: the same element matrices through both
/// importers).
#[test]
fn mass21_equals_the_abaqus_point_mass() {
    let Some(dir) = examples("MASS21 against Abaqus *MASS") else {
        return;
    };
    let clamp: String = (1..=21).map(|n| format!("D,{n},ALL,0\n")).collect();
    let record = format!(
        "{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}\n",
        1, 5, 5, 0, 0, 0, 0, 0, 1, 0, 1000, 22
    );
    let extra = format!(
        "{clamp}ET,5,21\nKEYOPT,5,3,2\nR,5,2.0e-4\nEBLOCK,19,SOLID,1000,1\n(19i9)\n{record}       -1\n"
    );
    let work = scratch("ansys-mass21");
    let cdb = work.join("mass.cdb");
    std::fs::write(&cdb, hexbeam_as_solved(&dir, &extra)).unwrap();
    let model = read_model(&cdb, &ImportOptions::default()).unwrap();
    assert_eq!(model.point_masses.len(), 1);
    let inp = work.join("mass.inp");
    let mut keywords = String::from(
        "*ELEMENT, TYPE=MASS, ELSET=PM\n1000, 22\n*MASS, ELSET=PM\n2.0e-4\n*BOUNDARY\n",
    );
    for n in 1..=21 {
        keywords.push_str(&format!("{n}, 1, 3\n"));
    }
    std::fs::write(&inp, abaqus_deck(&model, material_of(&model), &keywords)).unwrap();
    let ours = build_modes(&cdb, 10, &["--mass", "lumped"]);
    let abaqus = build_modes(&inp, 10, &["--mass", "lumped"]);
    let worst = (ours.iter().zip(&abaqus))
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(0.0, f64::max);
    // measured 0; the mass lowers the first mode by about 4 % (the beam weighs 2.07e-3)
    assert!(worst < 1e-10, "{ours:?} {abaqus:?}");
    assert!(ours[0] < 0.99 * PACKAGE_HZ[0], "{ours:?}");
}

/// MPC184 rigid beams (KEYOPT(1)=1) from a pilot node 1000 above HexBeam's free end to each
/// node of that end, a MASS21 with rotary inertia on the pilot, the fixed end clamped: equal to
/// the same mesh as C3D20R with `*RIGID BODY, REF NODE=1000` over the end's nodes and `*MASS` +
/// `*ROTARY INERTIA` on the pilot (lumped mass: the same element matrices through both
/// importers). Without the rigid beams the rotary inertia is refused by its line.
#[test]
fn mpc184_rigid_beams_and_rotary_inertia_equal_the_abaqus_rigid_body() {
    let Some(dir) = examples("MPC184 rigid beams against Abaqus *RIGID BODY") else {
        return;
    };
    let plain = read_model(
        &{
            let p = scratch("ansys-mpc184-mesh").join("plain.cdb");
            std::fs::write(&p, hexbeam_as_solved(&dir, "")).unwrap();
            p
        },
        &ImportOptions::default(),
    )
    .unwrap();
    let tip: Vec<u64> = (plain.nodes.iter())
        .filter(|n| (n.x[2] - 5.0).abs() < 1e-9)
        .map(|n| n.id)
        .collect();
    assert_eq!(tip.len(), 21);
    let clamp: String = (1..=21).map(|n| format!("D,{n},ALL,0\n")).collect();
    let pilot = format!(
        "NBLOCK,6,SOLID,1000,1\n(3i9,6e21.13e3)\n{:>9}{:>9}{:>9}{:>21.13E}{:>21.13E}{:>21.13E}\nN,R5.3,LOC,       -1,\n",
        1000, 0, 0, 0.5, 0.5, 6.0
    );
    let (m, inertia) = (1.0e-3, [5.0e-4, 3.0e-4, 2.0e-4]);
    let mut records = String::new();
    for (k, n) in tip.iter().enumerate() {
        records.push_str(&format!(
            "{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}\n",
            1,
            5,
            1,
            0,
            0,
            0,
            0,
            0,
            2,
            0,
            2000 + k,
            1000,
            n
        ));
    }
    let mass_record = format!(
        "{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}\n",
        1, 6, 6, 0, 0, 0, 0, 0, 1, 0, 3000, 1000
    );
    let mass21 = format!(
        "ET,6,21\nR,6,{m:e},{m:e},{m:e},{:e},{:e},{:e}\n",
        inertia[0], inertia[1], inertia[2]
    );
    let extra = format!(
        "{clamp}{pilot}ET,5,184\nKEYOPT,5,1,1\n{mass21}EBLOCK,19,SOLID,3000,{}\n(19i9)\n{records}{mass_record}       -1\n",
        tip.len() + 1
    );
    let work = scratch("ansys-mpc184-beam");
    let cdb = work.join("pilot.cdb");
    std::fs::write(&cdb, hexbeam_as_solved(&dir, &extra)).unwrap();
    let model = read_model(&cdb, &ImportOptions::default()).unwrap();
    assert_eq!(
        (model.rigid_elements.len(), model.point_masses.len()),
        (21, 1)
    );
    let ids: Vec<String> = tip.iter().map(u64::to_string).collect();
    let mut keywords = format!(
        "*NSET, NSET=TIP\n{}\n*RIGID BODY, NSET=TIP, REF NODE=1000\n\
         *ELEMENT, TYPE=MASS, ELSET=PM\n3000, 1000\n*MASS, ELSET=PM\n{m:e}\n\
         *ELEMENT, TYPE=ROTARYI, ELSET=RI\n3001, 1000\n*ROTARY INERTIA, ELSET=RI\n{:e}, {:e}, {:e}\n*BOUNDARY\n",
        ids.join(", "),
        inertia[0],
        inertia[1],
        inertia[2]
    );
    for n in 1..=21 {
        keywords.push_str(&format!("{n}, 1, 3\n"));
    }
    let inp = work.join("pilot.inp");
    std::fs::write(&inp, abaqus_deck(&model, material_of(&model), &keywords)).unwrap();
    let ours = build_modes(&cdb, 12, &["--mass", "lumped"]);
    let abaqus = build_modes(&inp, 12, &["--mass", "lumped"]);
    let worst = (ours.iter().zip(&abaqus))
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(0.0, f64::max);
    // measured 0 (the same RBE2 and element matrices through both importers)
    println!(
        "MPC184 rigid beams against *RIGID BODY: {worst:.2e}; {:?}",
        &ours[..4]
    );
    assert!(worst < 1e-10, "{ours:?} {abaqus:?}");

    // the rotary inertia on a node no rigid beam joins: refused by the MASS21 record's line
    let alone = extra
        .replace("KEYOPT,5,1,1\n", "")
        .replace(&records, "")
        .replacen(&format!("{},", tip.len() + 1), "1,", 1);
    std::fs::write(&cdb, hexbeam_as_solved(&dir, &alone)).unwrap();
    let err = read_model(&cdb, &ImportOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("MASS21 on node 1000 with rotary inertia IXX=0.0005"),
        "{err}"
    );
}
