//! Issue 16, the recipe: a body records how it was built (`recipe.json`, format 1.2), so
//! `flexbody check FILE --model MODEL` needs no option repeated, notices an edited model file,
//! and judges frequencies inside the recorded accuracy band. Through the real binary, on the
//! bundled connecting rod (fixtures/models/conrod: a main deck that includes the mesh).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use flexbody_reader as file;

fn exe() -> &'static str {
    env!("CARGO_BIN_EXE_flexbody")
}

/// A private copy of the conrod deck (main file + include), so the test may edit it.
fn conrod_copy(tag: &str) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod");
    let dir = std::env::temp_dir().join(format!("flexbody-recipe-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for f in ["conrod.inp", "conrod_mesh.inp"] {
        std::fs::copy(src.join(f), dir.join(f)).unwrap();
    }
    dir
}

fn run(args: &[&str]) -> Output {
    Command::new(exe()).args(args).output().unwrap()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The held-out case of the issue: CB with RBE2 spiders on both bores, 20 fixed-interface
/// modes, consistent mass. `check FILE --model MODEL` passes with no other option; a mode
/// scaled by 1 % fails; an edited include fails with exit 1 naming the file.
#[test]
fn conrod_cb_check_needs_no_repeated_option() {
    let dir = conrod_copy("cb");
    let model = dir.join("conrod.inp");
    let out = dir.join("rod.flexbody");
    let (model_s, out_s) = (model.to_str().unwrap(), out.to_str().unwrap());
    let built = run(&[
        "build",
        model_s,
        "--interface",
        "BIG_END,SMALL_END",
        "--modes",
        "20",
        "--mass",
        "consistent",
        "--units",
        "si",
        "-q",
        "-o",
        out_s,
    ]);
    assert!(
        built.status.success(),
        "{}",
        String::from_utf8_lossy(&built.stderr)
    );
    let body = file::read(&out).unwrap();
    // 1.9 for the eigenproblem's record (every build), 1.3 for the interfaces without it
    assert_eq!(body.version, file::Version { major: 1, minor: 9 });
    let mut bare = body.clone();
    bare.eigen_residuals = None;
    assert_eq!(
        file::version_for(&bare),
        file::Version { major: 1, minor: 3 }
    );
    let r = body
        .recipe
        .as_ref()
        .expect("build always writes the recipe");

    // Every model file read, with the SHA-256 of its bytes (main first, then the include).
    let files: Vec<&str> = r.model_files.iter().map(|f| f.path.as_str()).collect();
    assert_eq!(files, ["conrod.inp", "conrod_mesh.inp"]);
    for f in &r.model_files {
        let bytes = std::fs::read(dir.join(&f.path)).unwrap();
        assert_eq!(f.size, bytes.len() as u64);
        assert_eq!(f.sha256, file::codec::sha256_hex(&bytes));
    }
    // Options as given, spiders as resolved: the bores' axes are at x = 0 and x = 150 mm
    // (README geometry), and each spider lists every node of its set.
    assert_eq!(r.options.interface, ["BIG_END", "SMALL_END"]);
    assert_eq!(
        (r.options.method.as_str(), r.options.mass.as_str()),
        ("cb", "consistent")
    );
    assert_eq!(r.options.modes, Some(20));
    for (itf, x) in r.interfaces.iter().zip([0.0, 0.150]) {
        let s = itf.spider.as_ref().expect("node sets become spiders");
        assert_eq!(s.kind, "rbe2");
        assert_eq!(s.fit, "CylinderFit");
        assert!(
            (s.centre[0] - x).abs() < 1e-6 && s.centre[1].abs() < 1e-6,
            "{s:?}"
        );
        assert_eq!(itf.nodes, vec![s.centre_node]);
    }
    assert_eq!(
        r.interfaces[0].spider.as_ref().unwrap().set_nodes.len(),
        510
    );
    assert_eq!(
        r.interfaces[1].spider.as_ref().unwrap().set_nodes.len(),
        240
    );
    // The band of a `--modes N` CB build: a third of the highest fixed-interface frequency.
    assert_eq!(r.accuracy_band.rule, "fixed-interface");
    let fixed_top = r.accuracy_band.fmax_hz * 3.0;
    assert!(
        fixed_top > body.modes.frequency_hz[6] && r.accuracy_band.fmax_hz > 10_000.0,
        "band {:?}",
        r.accuracy_band
    );
    // inspect shows it, inspect --json has it.
    let text = stdout(&run(&["inspect", out_s]));
    assert!(
        text.contains("model file conrod_mesh.inp (include"),
        "{text}"
    );
    assert!(text.contains("rule fixed-interface"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&stdout(&run(&["inspect", "--json", out_s]))).unwrap();
    assert_eq!(json["recipe"]["options"]["interface"][1], "SMALL_END");

    // check with the model and nothing else passes, judging several modes in the band.
    let checked = run(&["check", out_s, "--model", model_s]);
    let text = stdout(&checked);
    assert_eq!(checked.status.code(), Some(0), "{text}");
    let freq = text
        .lines()
        .find(|l| l.contains("frequencies vs full normal-mode solve"))
        .expect("frequency check ran");
    assert!(freq.starts_with("ok"), "{freq}");
    let compared: usize = freq
        .split("over the ")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert!(compared >= 5, "{freq}");

    // A flexible mode scaled by 1 % still fails.
    let mut bad = body.clone();
    let n = bad.node_count();
    let j = bad
        .modes
        .labels
        .iter()
        .position(|l| *l != file::ModeLabel::Rigid)
        .unwrap();
    for v in &mut bad.modes.shapes[j * n * 6..(j + 1) * n * 6] {
        *v *= 1.01;
    }
    let bad_path = dir.join("rod_scaled.flexbody");
    flexbody::write::write_reduced_body(&bad_path, &bad, &Default::default()).unwrap();
    let checked = run(&["check", bad_path.to_str().unwrap(), "--model", model_s]);
    let text = stdout(&checked);
    assert_eq!(checked.status.code(), Some(1), "{text}");
    assert!(
        text.lines()
            .any(|l| l.starts_with("FAIL") && l.contains("Φᵀ M Φ = I against the model")),
        "{text}"
    );

    // Editing the model afterwards: exit 1, naming the edited file.
    let mesh = dir.join("conrod_mesh.inp");
    let mut bytes = std::fs::read(&mesh).unwrap();
    bytes.extend_from_slice(b"** edited after the build\n");
    std::fs::write(&mesh, bytes).unwrap();
    let checked = run(&["check", out_s, "--model", model_s]);
    let text = stdout(&checked);
    assert_eq!(checked.status.code(), Some(1), "{text}");
    let line = text
        .lines()
        .find(|l| l.starts_with("FAIL") && l.contains("model files as built"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(
        line.contains("conrod_mesh.inp: changed since the build"),
        "{line}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Explicit options still override the recipe: the same file checked with `--spider none`
/// rebuilds a model without spiders, whose interface nodes are not the file's.
#[test]
fn explicit_options_override_the_recipe() {
    let dir = conrod_copy("override");
    let model = dir.join("conrod.inp");
    let out = dir.join("rod.flexbody");
    let (model_s, out_s) = (model.to_str().unwrap(), out.to_str().unwrap());
    let built = run(&[
        "build",
        model_s,
        "--interface",
        "BIG_END,SMALL_END",
        "--fmax",
        "3000",
        "--units",
        "si",
        "-q",
        "-o",
        out_s,
    ]);
    assert!(built.status.success());
    let body = file::read(&out).unwrap();
    let r = body.recipe.as_ref().unwrap();
    assert_eq!(
        (r.accuracy_band.rule.as_str(), r.accuracy_band.fmax_hz),
        ("fmax", 3000.0)
    );
    assert_eq!(r.accuracy_band.basis_cutoff_hz, Some(9000.0));
    assert_eq!(body.method.cutoffs.fmax_hz, Some(3000.0), "the user's fmax");
    let from_recipe =
        flexbody::recipe::model_input(body.recipe.as_ref(), model.clone(), Default::default())
            .unwrap();
    assert_eq!(from_recipe.interface, ["BIG_END", "SMALL_END"]);
    assert_eq!(from_recipe.spider, flexbody::interface::SpiderKind::Rbe2);
    let overridden = flexbody::recipe::model_input(
        body.recipe.as_ref(),
        model.clone(),
        flexbody::recipe::ModelOverrides {
            spider: Some(flexbody::interface::SpiderKind::None),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(overridden.spider, flexbody::interface::SpiderKind::None);
    let checked = run(&["check", out_s, "--model", model_s]);
    assert_eq!(checked.status.code(), Some(0), "{}", stdout(&checked));
    let _ = std::fs::remove_dir_all(&dir);
}
