//! Hostile and careless input (issue 20): duplicate ids, non-finite numbers and memory bombs.
//! Every case must end in an error naming file, line and card/keyword — never a panic, a silent
//! double count, or an allocation the file's size cannot justify.

use std::path::PathBuf;

use flexbody::import::{read_model, ImportError, ImportOptions};

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("flexbody_hostile_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(name: &str, text: &[u8]) -> PathBuf {
    let p = dir().join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Reads the deck and removes it (the bombs are tens of MB: a run must not leave them behind).
fn read(name: &str, text: &[u8]) -> Result<flexbody::model::Model, ImportError> {
    let path = write(name, text);
    let model = read_model(&path, &ImportOptions::default());
    let _ = std::fs::remove_file(&path);
    model
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

const BDF_BASE: &str = "MAT1,1,2.1e11,,.3,7850.\nPBAR,2,1,1.e-4,1.e-9,1.e-9,2.e-9\n\
GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,2.,0.,0.\nCBAR,10,2,1,2,0.,1.,0.\n";

#[test]
fn nastran_distinct_ids_are_accepted_and_mass_counted_once() {
    let deck = format!("{BDF_BASE}CONM2,20,2,,1.5\nCONM2,21,3,,2.5\nRBE2,30,1,123456,3\n");
    let m = read("ok.bdf", deck.as_bytes()).unwrap();
    let total: f64 = m.point_masses.iter().map(|p| p.mass).sum();
    assert_eq!((m.point_masses.len(), total), (2, 4.0));
}

#[test]
fn nastran_duplicate_conm2_ids_name_both_lines() {
    let deck = format!("{BDF_BASE}CONM2,20,2,,1.5\nCONM2,20,3,,2.5\n");
    fails(
        "dup_conm2.bdf",
        deck.as_bytes(),
        8,
        "CONM2 20",
        &["duplicate element id 20", "CONM2 20 at ", "dup_conm2.bdf:7"],
    );
}

#[test]
fn nastran_conm2_with_a_cbar_id_is_a_duplicate() {
    let deck = format!("{BDF_BASE}CONM2,10,2,,1.5\n");
    fails(
        "dup_conm2_cbar.bdf",
        deck.as_bytes(),
        7,
        "CONM2 10",
        &["CBAR 10 at ", "dup_conm2_cbar.bdf:6", "one id space"],
    );
}

#[test]
fn nastran_duplicate_rigid_element_ids() {
    let deck = format!("{BDF_BASE}RBE2,30,1,123456,3\nRBE3,30,,2,123456,1.,123,1,3\n");
    fails(
        "dup_rbe.bdf",
        deck.as_bytes(),
        8,
        "RBE3 30",
        &["RBE2 30 at ", "dup_rbe.bdf:7"],
    );
    // A rigid element with the id of a structural element: MSC Nastran runs such a deck
    // (issue 32), so it is a warning naming both lines, not an error.
    let deck = format!("{BDF_BASE}RBE2,10,1,123456,3\n");
    let m = read("dup_rbe_cbar.bdf", deck.as_bytes()).unwrap();
    assert!(
        m.warnings
            .iter()
            .any(|w| w.file.ends_with("dup_rbe_cbar.bdf:7")
                && w.message.contains("RBE2 10 has the id of CBAR 10")
                && w.message.contains("dup_rbe_cbar.bdf:6")),
        "{:?}",
        m.warnings
    );
    assert_eq!((m.elements.len(), m.rigid_elements.len()), (1, 1));
}

#[test]
fn nastran_duplicate_grids_properties_materials() {
    let deck = format!("{BDF_BASE}GRID,2,,5.,0.,0.\n");
    fails(
        "dup_grid.bdf",
        deck.as_bytes(),
        7,
        "GRID 2",
        &["duplicate node id", "dup_grid.bdf:4"],
    );
    let deck = format!("{BDF_BASE}PROD,2,1,1.e-4\n");
    fails(
        "dup_prop.bdf",
        deck.as_bytes(),
        7,
        "PROD 2",
        &["duplicate property id 2", "PBAR 2 at ", ":2"],
    );
    // An unsupported property type still owns its id.
    let deck = format!("{BDF_BASE}PELAS,2,1.e3\n");
    fails(
        "dup_prop_pelas.bdf",
        deck.as_bytes(),
        7,
        "PELAS 2",
        &["PBAR 2 at ", ":2"],
    );
    let deck = format!("{BDF_BASE}MAT1,1,7.e10,,.33,2700.\n");
    fails(
        "dup_mat.bdf",
        deck.as_bytes(),
        7,
        "MAT1 1",
        &["duplicate material id 1", "MAT1 1 at ", "dup_mat.bdf:1"],
    );
}

#[test]
fn nastran_mat4_may_share_a_mat1_id() {
    // Nastran's rule: MAT4 (thermal) carries the thermal data of the MAT1 of the same MID.
    let deck = format!("{BDF_BASE}MAT4,1,50.\n");
    let m = read("mat4.bdf", deck.as_bytes()).unwrap();
    assert_eq!(m.materials.len(), 1);
}

const INP_NODES: &str = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n";

#[test]
fn abaqus_duplicate_nodes_and_elements_name_both_lines() {
    let deck = format!("{INP_NODES}3, 5, 5, 5\n");
    fails(
        "dup_node.inp",
        deck.as_bytes(),
        6,
        "*NODE 3",
        &["duplicate node id", "dup_node.inp:4"],
    );
    let deck = format!(
        "{INP_NODES}*ELEMENT, TYPE=C3D4\n7, 1, 2, 3, 4\n*ELEMENT, TYPE=C3D4\n7, 1, 2, 4, 3\n"
    );
    fails(
        "dup_elem.inp",
        deck.as_bytes(),
        9,
        "C3D4 7",
        &["duplicate element id", "dup_elem.inp:7"],
    );
    let deck = format!(
        "{INP_NODES}*ELEMENT, TYPE=C3D4\n7, 1, 2, 3, 4\n*ELEMENT, TYPE=MASS, ELSET=M\n7, 2\n"
    );
    fails(
        "dup_mass.inp",
        deck.as_bytes(),
        9,
        "*ELEMENT 7",
        &["duplicate element id", "dup_mass.inp:7"],
    );
    let deck = format!("{INP_NODES}*ELEMENT, TYPE=MASS, ELSET=M\n7, 2\n8, 3\n7, 4\n");
    fails(
        "dup_mass2.inp",
        deck.as_bytes(),
        9,
        "*ELEMENT 7",
        &["duplicate element id", "dup_mass2.inp:7"],
    );
}

// ---- non-finite and out-of-range numbers ----

#[test]
fn nastran_overflowing_and_nan_reals_are_errors_with_field() {
    let deck = BDF_BASE.replace("GRID,2,,1.,0.,0.", "GRID,2,,0.1e400,0.,0.");
    fails(
        "inf_grid.bdf",
        deck.as_bytes(),
        4,
        "GRID 2",
        &["field 4", "'0.1e400'", "infinite"],
    );
    let deck = BDF_BASE.replace("2.1e11", "1.+200");
    fails(
        "big_mat.bdf",
        deck.as_bytes(),
        1,
        "MAT1 1",
        &["field 3", "out of range", "1e150"],
    );
    let deck = BDF_BASE.replace("7850.", "NaN");
    fails(
        "nan_mat.bdf",
        deck.as_bytes(),
        1,
        "MAT1 1",
        &["field 6", "bad number 'NaN'"],
    );
    let deck = format!("{BDF_BASE}CONM2,20,2,,1.e160\n");
    fails(
        "big_conm2.bdf",
        deck.as_bytes(),
        7,
        "CONM2 20",
        &["field 5", "out of range"],
    );
}

#[test]
fn abaqus_nan_inf_and_huge_reals_are_errors() {
    let deck = INP_NODES.replace("2, 1, 0, 0", "2, NaN, 0, 0");
    fails(
        "nan_node.inp",
        deck.as_bytes(),
        3,
        "*NODE 2",
        &["'NaN'", "not a number"],
    );
    let deck = INP_NODES.replace("2, 1, 0, 0", "2, 1, inf, 0");
    fails("inf_node.inp", deck.as_bytes(), 3, "*NODE 2", &["infinite"]);
    let deck = format!("{INP_NODES}*MATERIAL, NAME=M\n*ELASTIC\n1e308, 0.3\n");
    fails(
        "big_e.inp",
        deck.as_bytes(),
        8,
        "*MATERIAL M",
        &["'1e308'", "out of range"],
    );
    let deck = format!("{INP_NODES}*MATERIAL, NAME=M\n*DENSITY\n1.0D400\n");
    fails(
        "big_rho.inp",
        deck.as_bytes(),
        8,
        "*MATERIAL M",
        &["'1.0D400'", "infinite"],
    );
}

#[test]
fn gmsh_non_finite_coordinates_are_errors() {
    let msh = b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n3 1 0 2\n1\n2\n0 0 0\n1 nan 0\n$EndNodes\n";
    fails("nan.msh", msh, 10, "$Nodes", &["'nan'", "not a number"]);
    let msh = b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n3 1 0 2\n1\n2\n0 0 0\n1 1e300 0\n$EndNodes\n";
    fails("big.msh", msh, 10, "$Nodes", &["out of range"]);
}

#[test]
fn matrix_market_non_finite_values_are_errors() {
    use flexbody::import::matrix_market::read_matrix;
    let p = write(
        "k_inf.mtx",
        b"%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1.0\n2 2 inf\n",
    );
    let e = read_matrix(&p).unwrap_err();
    assert_eq!(e.line(), Some(4), "{e}");
    assert!(e.to_string().contains("infinite"), "{e}");
    let p = write(
        "k_big.mtx",
        b"%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1e151\n2 2 1.0\n",
    );
    let e = read_matrix(&p).unwrap_err();
    assert_eq!(e.line(), Some(3), "{e}");
    assert!(e.to_string().contains("out of range"), "{e}");
}

#[test]
fn implausible_material_is_a_warning_not_an_error() {
    // E in Pa with ρ in t/mm³: wave speed 5.2e9 length/time, a unit mix-up; the deck still reads.
    let deck = BDF_BASE.replace("7850.", "7.85e-9");
    let m = read("units.bdf", deck.as_bytes()).unwrap();
    assert!(
        m.warnings
            .iter()
            .any(|w| w.message.contains("material MAT1 1") && w.message.contains("wave speed")),
        "{:?}",
        m.warnings
    );
    let m = read("units_ok.bdf", BDF_BASE.as_bytes()).unwrap();
    assert!(!m.warnings.iter().any(|w| w.message.contains("wave speed")));
}

// ---- memory bombs: small decks that asked for gigabytes before the input budget ----

/// The bomb decks of issue 20 (name, content).
fn bombs() -> Vec<(&'static str, Vec<u8>)> {
    // 40 ranges of 20 M ids on one SPC1 / ASET1 card (free field, continued).
    let card = |head: &[&str]| -> Vec<u8> {
        let mut f: Vec<String> = head.iter().map(|s| s.to_string()).collect();
        for _ in 0..40 {
            f.extend(["1", "THRU", "20000000"].map(String::from));
        }
        let mut out = String::from("GRID,1,,0.,0.,0.\n");
        out += &f[..9].join(",");
        for (i, chunk) in f[9..].chunks(8).enumerate() {
            out += &format!(",+A{i}\n+A{i},{}", chunk.join(","));
        }
        out.push('\n');
        out.into_bytes()
    };
    // Counts of 40 M with 41 MB of padding: fewer than the counts' smallest encoding.
    let pad = " ".repeat(41_000_000);
    vec![
        ("selfref.inp", format!("*NODE\n1, 0, 0, 0\n*NSET, NSET=A\n1\n{}", "A\n".repeat(60)).into_bytes()),
        ("generate.inp", format!("*NODE\n1, 0, 0, 0\n*NSET, NSET=G, GENERATE\n{}", "1, 20000000, 1\n".repeat(20)).into_bytes()),
        ("copies.inp", format!("*NODE\n1, 0, 0, 0\n*NSET, NSET=G, GENERATE\n1, 1000000, 1\n*NSET, NSET=B\n{}", "G, G, G, G, G, G, G, G\n".repeat(100)).into_bytes()),
        ("spc1.bdf", card(&["SPC1", "1", "123"])),
        ("aset1.bdf", card(&["ASET1", "123"])),
        ("nodes.msh", format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 40000000 1 40000000\n3 1 0 40000000\n{pad}\n").into_bytes()),
        ("elems.msh", format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n3 1 0 1\n1\n0 0 0\n$EndNodes\n$Elements\n1 40000000 1 40000000\n3 1 5 40000000\n{pad}\n").into_bytes()),
    ]
}

#[test]
fn bombs_end_in_a_budget_error_naming_file_line_and_card() {
    let want: [(&str, usize, &str, &str); 6] = [
        ("generate.inp", 4, "*NSET G", "GENERATE 1..20000000"),
        ("copies.inp", 6, "*NSET B", "adding set G"),
        ("spc1.bdf", 2, "SPC1 1", "THRU range 1..20000000"),
        ("aset1.bdf", 2, "ASET1 123", "THRU range 1..20000000"),
        ("nodes.msh", 5, "$Nodes", "claims 40000000 nodes"),
        ("elems.msh", 12, "$Elements", "claims 40000000 elements"),
    ];
    let bombs = bombs();
    for (name, line, entity, part) in want {
        let text = &bombs.iter().find(|b| b.0 == name).unwrap().1;
        fails(name, text, line, entity, &[part]);
    }
}

#[test]
fn a_set_naming_itself_is_resolved_once() {
    let deck = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n*NSET, NSET=A\n1\nA\nA, 2\nA\n*NSET, NSET=A\nA, 1\n";
    let m = read("selfref_small.inp", deck.as_bytes()).unwrap();
    assert_eq!(m.node_sets["A"], vec![0, 1]);
    let text = &bombs()[0].1;
    let m = read("selfref.inp", text).unwrap();
    assert_eq!(m.node_sets["A"], vec![0]);
}

#[test]
fn dev_zero_and_binary_junk_end_at_the_first_chunk() {
    for format in ["inp", "bdf", "msh"] {
        let f = flexbody::import::Format::from_name(format);
        let e = read_model(
            std::path::Path::new("/dev/zero"),
            &ImportOptions {
                format: f,
                ..Default::default()
            },
        )
        .unwrap_err();
        assert_eq!(
            (e.file(), e.line(), e.entity()),
            (Some("/dev/zero"), Some(1), Some("file")),
            "{e}"
        );
    }
}

/// Each bomb through the CLI in a child limited to 1 GB of address space: a named import
/// error (exit 2), not an allocation abort (exit 134). Before the input budget every one of
/// these aborted or ran out of memory under this limit.
#[test]
fn bombs_through_the_cli_stay_within_one_gigabyte() {
    let exe = env!("CARGO_BIN_EXE_flexbody");
    let mut cases: Vec<(String, Vec<&str>)> = bombs()
        .into_iter()
        .map(|(name, text)| {
            (
                write(&format!("cli_{name}"), &text).display().to_string(),
                vec![],
            )
        })
        .collect();
    cases.push(("/dev/zero".into(), vec!["--format", "inp"]));
    cases.push(("/dev/zero".into(), vec!["--format", "msh"]));
    for (path, extra) in cases {
        let out_file = dir().join("bomb.flexbody");
        let cmd = format!(
            "ulimit -v 1000000; exec '{exe}' build '{path}' {} -o '{}' --units si --interface 1",
            extra.join(" "),
            out_file.display()
        );
        let out = std::process::Command::new("sh")
            .arg("-c")
            .arg(&cmd)
            .output()
            .unwrap();
        if path.starts_with(&dir().display().to_string()) {
            let _ = std::fs::remove_file(&path);
        }
        let err = String::from_utf8_lossy(&out.stderr);
        if path.ends_with("selfref.inp") {
            // Resolved once: the deck is read (the one-node model then fails later, named).
            assert!(!err.contains("memory allocation"), "{path}: {err}");
            assert!(err.contains("selfref.inp"), "{path}: {err}");
            continue;
        }
        assert_eq!(out.status.code(), Some(2), "{path}: {err}");
        let file = std::path::Path::new(&path)
            .file_name()
            .unwrap()
            .to_string_lossy()
            .to_string();
        assert!(
            err.contains(&format!("{file}:")),
            "{path}: no file:line in {err}"
        );
        assert!(!out_file.exists(), "{path}: wrote an output");
    }
}

// ---- output path ----

fn cli_build(out: &std::path::Path) -> std::process::Output {
    let deck = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/models/planar_beam/planar_beam.bdf");
    std::process::Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .args([
            "build",
            &deck.display().to_string(),
            "--interface",
            "1,9",
            "--units",
            "si",
            "-o",
        ])
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn output_folder_or_missing_folder_is_refused_before_the_build() {
    let folder = dir().join("a_folder.flexbody");
    std::fs::create_dir_all(&folder).unwrap();
    let missing = dir().join("no/such/x.flexbody");
    for out in [folder.clone(), missing.clone()] {
        let o = cli_build(&out);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{err}");
        assert!(
            err.contains(&out.display().to_string()),
            "-o path not named: {err}"
        );
        assert!(!err.contains(".tmp-"), "temp file named: {err}");
        let first_line = err.lines().next().unwrap_or("");
        let tail = first_line.rsplit(": ").next().unwrap_or("");
        assert_eq!(first_line.matches(tail).count(), 1, "doubled text: {err}");
        // Refused before the build: no import stage ran.
        assert!(!err.contains("import "), "build ran first: {err}");
    }
    assert!(String::from_utf8_lossy(&cli_build(&folder).stderr).contains("it is a folder"));
    assert!(String::from_utf8_lossy(&cli_build(&missing).stderr).contains("does not exist"));
}

#[test]
fn a_stale_temp_file_of_a_killed_run_is_removed_by_the_next_run() {
    let d = dir().join("stale");
    std::fs::create_dir_all(&d).unwrap();
    let out = d.join("body.flexbody");
    // A pid that runs no process (as after `kill -9`), and another output's temp file.
    let dead = (400_000u32..)
        .find(|p| !std::path::Path::new(&format!("/proc/{p}")).exists())
        .unwrap();
    let stale = d.join(format!(".body.flexbody.tmp-{dead}"));
    let other = d.join(format!(".other.flexbody.tmp-{dead}"));
    std::fs::write(&stale, b"partial").unwrap();
    std::fs::write(&other, b"partial").unwrap();
    let o = cli_build(&out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.exists());
    assert!(!stale.exists(), "stale temp file left");
    assert!(other.exists(), "another output's temp file was touched");
}

#[test]
fn gmsh_entity_bounding_boxes_may_hold_dbl_max() {
    // Gmsh writes ±DBL_MAX for an empty bounding box; boxes are not model data.
    let m = "1.797693134862316e+308";
    let msh = format!(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n1 -{m} -{m} -{m} {m} {m} {m} 0 0\n$EndEntities\n\
$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n\
$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n"
    );
    let model = read("dblmax_box.msh", msh.as_bytes()).unwrap();
    assert_eq!((model.nodes.len(), model.elements.len()), (4, 1));
    // The same value as a node coordinate is an error.
    let bad = msh.replace("\n1 0 0\n", &format!("\n{m} 0 0\n"));
    fails(
        "dblmax_node.msh",
        bad.as_bytes(),
        16,
        "$Nodes",
        &["'1.797693134862316e+308'", "every real must be finite"],
    );
}

/// Errors found after import (element matrices) name the element's file and line, in every
/// importer, and the text appears once.
#[test]
fn post_import_element_errors_carry_the_source_line() {
    use flexbody::fe::{assembly::element_matrices, AssemblySpec};
    // A flat (zero-volume) tet on line 8 of an .inp.
    let inp = b"*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 1, 1, 0\n\
*ELEMENT, TYPE=C3D4, ELSET=S\n7, 1, 2, 3, 4\n\n*MATERIAL, NAME=M\n*ELASTIC\n1e9, 0.3\n\
*DENSITY\n1000\n*SOLID SECTION, ELSET=S, MATERIAL=M\n";
    let m = read("flat_tet.inp", inp).unwrap();
    let loc = m.element_location(7).unwrap();
    assert!(loc.ends_with("flat_tet.inp:7"), "{loc}");
    let Err(err) = element_matrices(&m, 0, &AssemblySpec::default()) else {
        panic!("a flat tet fails")
    };
    let msg = err.to_string();
    assert!(msg.contains("flat_tet.inp:7: element 7"), "{msg}");
    assert_eq!(msg.matches("element 7").count(), 1, "{msg}");
    // Nastran: the card's first line.
    let bdf = "MAT1,1,2.1e11,,.3,7850.\nPSOLID,3,1\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\n\
GRID,3,,0.,1.,0.\nGRID,4,,1.,1.,0.\n$ comment\nCTETRA,44,3,1,2,3,4\n";
    let m = read("flat_tet.bdf", bdf.as_bytes()).unwrap();
    let Err(err) = element_matrices(&m, 0, &AssemblySpec::default()) else {
        panic!("a flat tet fails")
    };
    let msg = err.to_string();
    assert!(msg.contains("flat_tet.bdf:8: element 44"), "{msg}");
    // A model built in memory has no lines: the source alone.
    let mut m2 = m.clone();
    m2.element_sources.clear();
    assert_eq!(m2.element_origin(44), m2.source);
}

/// A solver failure deep in the reduction is reported with the model file and, when the
/// materials explain it, the material named: an implausible one, or a stiffness contrast.
#[test]
fn solver_failures_are_translated_into_the_models_terms() {
    use flexbody::build::BuildError;
    use flexbody::diagnose::SolverContext;
    use flexbody::reduce::ReduceError;
    use flexbody::solve::SolveError;
    let not_pd = || {
        BuildError::Reduce(ReduceError::Solve(SolveError::NotPositiveDefinite {
            shift: -8.75e7,
        }))
    };
    // E in Pa with ρ in t/mm³: a wave speed no solid has.
    let deck = BDF_BASE.replace("MAT1,1,2.1e11,,.3,7850.", "MAT1,1,2.1e11,,.3,7.85e-9");
    let m = read("units_mixed.bdf", deck.as_bytes()).unwrap();
    let msg = SolverContext::of(&m).explain(not_pd()).to_string();
    assert!(
        msg.contains("units_mixed.bdf: K - sigma*M is not positive definite"),
        "{msg}"
    );
    assert!(
        msg.contains("likely cause: material") && msg.contains("wave speed"),
        "{msg}"
    );
    // Two plausible materials 1e7 apart.
    let deck = format!(
        "{BDF_BASE}MAT1,2,2.1e4,,.3,7850.\nPBAR,3,2,1.e-4,1.e-9,1.e-9,2.e-9\nCBAR,11,3,2,3,0.,1.,0.\n"
    );
    let m = read("contrast.bdf", deck.as_bytes()).unwrap();
    let msg = SolverContext::of(&m).explain(not_pd()).to_string();
    assert!(msg.contains("stiffer than material"), "{msg}");
    // Nothing extreme: the message says where else to look.
    let m = read("plain.bdf", BDF_BASE.as_bytes()).unwrap();
    let msg = SolverContext::of(&m).explain(not_pd()).to_string();
    assert!(
        msg.starts_with("plain.bdf: ") || msg.contains("/plain.bdf: "),
        "{msg}"
    );
    assert!(msg.contains("distorted or inverted elements"), "{msg}");
    // A mechanism found by the free-free solve names the file.
    let mech = BuildError::Reduce(ReduceError::Mechanism {
        zero_modes: 12,
        at_least: true,
    });
    let msg = SolverContext::of(&m).explain(mech).to_string();
    assert!(
        msg.contains("plain.bdf: free-free analysis found 12 or more"),
        "{msg}"
    );
    // Other errors pass unchanged.
    let other = BuildError::Request {
        file: "x".into(),
        message: "y".into(),
    };
    assert_eq!(SolverContext::of(&m).explain(other).to_string(), "x: y");
}
