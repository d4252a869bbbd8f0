//! A bad scene option (`--load`, `--gravity`) is refused right after import, before assembly and
//! the reduction, with the model file named once and the option's text quoted.

use std::path::Path;
use std::process::Command;

fn build_with(extra: &[&str]) -> (bool, String) {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp");
    let out = std::env::temp_dir().join(format!(
        "flexbody-scene-err-{}.flexbody",
        std::process::id()
    ));
    let o = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .arg("build")
        .arg(&deck)
        .args([
            "--interface",
            "BIG_END,SMALL_END",
            "--modes",
            "4",
            "--units",
            "si",
        ])
        .args(extra)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(!out.exists(), "an output was written");
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn bad_scene_options_are_refused_before_assembly_naming_the_model_once() {
    let cases: [(&[&str], &str); 4] = [
        (
            &["--load", "PULL:SMALL_END:100,0,0"],
            "one pressure value after a node set (SMALL_END is a node set",
        ),
        (
            &["--load", "TIP:999999:1,0,0"],
            "node 999999 does not exist",
        ),
        (
            &["--load", "LOAD_7"],
            "no load set of that name in the deck",
        ),
        (&["--gravity", "0,0,x"], "'x' is not a finite number"),
    ];
    for (args, expected) in cases {
        let (ok, err) = build_with(args);
        assert!(!ok, "{args:?} was accepted");
        let first = err
            .lines()
            .find(|l| l.contains("cannot build"))
            .unwrap_or("");
        assert!(first.contains(expected), "{args:?}: {err}");
        assert!(
            first.contains(args[1]),
            "{args:?}: option text not quoted: {err}"
        );
        assert_eq!(
            first.matches("conrod.inp").count(),
            1,
            "model named twice: {first}"
        );
        // refused after import and interfaces, before the assembly stage
        assert!(err.contains("interfaces"), "{err}");
        assert!(!err.contains("assembly"), "assembly ran first: {err}");
    }
}
