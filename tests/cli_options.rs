//! Issue 31/32: option values are checked before the model is read, with our own message —
//! negative numbers in either spelling (`--fmax=-5`, `--fmax -5`), ζ ≥ 1. The model path here
//! does not exist: an error about the option (not the file) proves the order.

use std::process::Command;

fn run(args: &[&str]) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn numeric_options_are_refused_before_the_model_is_read() {
    let missing = std::env::temp_dir().join("flexbody-no-such-model.inp");
    let out = std::env::temp_dir().join(format!("flexbody-opts-{}.flexbody", std::process::id()));
    let (m, o) = (missing.to_str().unwrap(), out.to_str().unwrap());
    for (extra, says) in [
        (
            vec!["--fmax=-5"],
            "--fmax -5: must be a positive frequency in Hz",
        ),
        (
            vec!["--fmax", "-5"],
            "--fmax -5: must be a positive frequency in Hz",
        ),
        (
            vec!["--fmax", "0"],
            "--fmax 0: must be a positive frequency in Hz",
        ),
        (
            vec!["--fmax", "inf"],
            "--fmax inf: must be a positive frequency in Hz",
        ),
        (
            vec!["--thickness", "-1"],
            "--thickness -1: must be a positive length",
        ),
        (
            vec!["--damping", "200%"],
            "--damping 200%: a modal damping ratio must be below 1",
        ),
        (
            vec!["--reference-method", "3"],
            "--reference-method 3: expected 1 or 2",
        ),
    ] {
        let mut args = vec!["build", m, "--units", "si", "-o", o];
        args.extend(&extra);
        let (code, err) = run(&args);
        assert_eq!(code, Some(2), "{extra:?}: {err}");
        assert!(err.contains(says), "{extra:?}: {err}");
        assert!(!err.contains("use '--"), "clap's '-- -5' tip: {err}");
        assert!(
            !err.contains("no-such-model"),
            "the model was read first: {err}"
        );
        assert!(!out.exists());
    }
}

fn conrod() -> String {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/models/conrod/conrod.inp")
        .display()
        .to_string()
}

/// Issue 31: `--units mm-t-s` on the SI conrod is named (E = 2.1e11 read as MPa is no solid's),
/// with the preset that fits; a build that then fails (an unknown interface) still prints it;
/// `--fmax 1` (no fixed-interface mode under 3 Hz) is a warning, not a note; the reduction's
/// phase times are not printed a second time as notes.
#[test]
fn warnings_are_printed_on_success_and_on_failure() {
    let dir = std::env::temp_dir().join(format!("flexbody-warn-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("u.flexbody");
    let (model, o) = (conrod(), out.to_str().unwrap().to_string());
    let build = |extra: &[&str]| {
        let mut args = vec!["build", &model, "-o", &o];
        args.extend(extra);
        run(&args)
    };
    let units_warning = "warning: material STEEL: E = 2.1e11, ρ = 7.85e3 read in mm-t-s";
    let (code, err) = build(&[
        "--interface",
        "BIG_END,SMALL_END",
        "--fmax",
        "3000",
        "--units",
        "mm-t-s",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        err.contains(units_warning) && err.contains("they fit --units si"),
        "{err}"
    );
    assert!(!err.contains("note: time "), "{err}");
    let (code, err) = build(&["--interface", "NOPE", "--fmax", "3000", "--units", "mm-t-s"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains(units_warning) && err.contains("interface `NOPE`"),
        "{err}"
    );
    let (code, err) = build(&[
        "--interface",
        "BIG_END,SMALL_END",
        "--fmax",
        "1",
        "--units",
        "si",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        err.contains("warning: no fixed-interface mode lies below the basis cutoff 3.000000 Hz"),
        "{err}"
    );
    assert!(
        !err.contains("material STEEL"),
        "SI is right for the conrod: {err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 31: a missing output folder is the same error for every command and target, before
/// any work (it was a temp-file error for exudyn and silently created for mtx).
#[test]
fn a_missing_output_folder_is_one_error_everywhere() {
    let golden = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/golden/v1.2/three_node_chain_recipe.flexbody");
    let g = golden.to_str().unwrap();
    let missing = std::env::temp_dir().join(format!("flexbody-nofolder-{}", std::process::id()));
    let file_in = |name: &str| missing.join(name).display().to_string();
    let model = conrod();
    let runs: Vec<Vec<String>> = vec![
        vec![
            "build".into(),
            model.clone(),
            "--units".into(),
            "si".into(),
            "-o".into(),
            file_in("b.flexbody"),
        ],
        vec![
            "export".into(),
            g.into(),
            "--to".into(),
            "exudyn".into(),
            "-o".into(),
            file_in("e.npz"),
        ],
        vec![
            "export".into(),
            g.into(),
            "--to".into(),
            "mbdyn".into(),
            "-o".into(),
            file_in("e.fem"),
        ],
        vec![
            "export".into(),
            g.into(),
            "--to".into(),
            "sid".into(),
            "-o".into(),
            file_in("e.SID_FEM"),
        ],
        vec![
            "export".into(),
            g.into(),
            "--to".into(),
            "vtu".into(),
            "-o".into(),
            file_in("e.vtu"),
        ],
        vec!["view".into(), g.into(), "-o".into(), file_in("v.html")],
        vec![
            "export".into(),
            g.into(),
            "--to".into(),
            "mtx".into(),
            "--model".into(),
            model.clone(),
            "-o".into(),
            missing.join("sub").join("mtx").display().to_string(),
        ],
    ];
    for args in runs {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, err) = run(&a);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains("does not exist"), "{args:?}: {err}");
        assert!(!missing.exists(), "{args:?} created {}", missing.display());
    }
}

/// Issue 31: a Gmsh mesh built without `--material` says what to give (it said "element 29
/// (Tet10) has no (valid) property").
#[test]
fn a_mesh_without_material_asks_for_material() {
    let mesh = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/reference/e_matrices/tet10_block_coarse/mesh.msh");
    let out = std::env::temp_dir().join(format!("flexbody-nomat-{}.flexbody", std::process::id()));
    let (code, err) = run(&[
        "build",
        mesh.to_str().unwrap(),
        "--units",
        "si",
        "--method",
        "normal",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("the model defines no material") && err.contains("give --material E="),
        "{err}"
    );
    assert!(!out.exists());
}

/// Issue 31: inside the reduction a log (stderr not a terminal) hears what the solver does —
/// the factorization's size, the eigenpairs converged of those wanted — every
/// FLEXBODY_PROGRESS_SECONDS (5 s by default; 0 here: every step), not only a seconds counter.
#[test]
fn long_stages_report_the_solver_in_a_log() {
    let out = std::env::temp_dir().join(format!("flexbody-prog-{}.flexbody", std::process::id()));
    let o = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .env("FLEXBODY_PROGRESS_SECONDS", "0")
        .args([
            "build",
            &conrod(),
            "--interface",
            "BIG_END,SMALL_END",
            "--fmax",
            "3000",
            "--units",
            "si",
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("flexbody:   reduction      factorizing K (") && err.contains(" equations, "),
        "{err}"
    );
    let eigen = err
        .lines()
        .filter(|l| l.contains("reduction      eigen ") && l.contains(" converged"))
        .count();
    assert!(eigen >= 1, "{err}");
    let _ = std::fs::remove_file(&out);
}
