//! Issue 36: the exudyn snippets of `docs/using-in-solvers.md` run as they stand, and the
//! joints section's recipes (`examples/joints_exudyn.py`: revolute, prismatic, rigid,
//! marker-based) run and agree with exudyn's own Hurty–Craig–Bampton body (the acceptance,
//! last test).
//!
//! `examples/using_in_exudyn.py` holds the exudyn section's three Python blocks between
//! `# --- snippet N` and `# --- end`; the first test checks they equal the docs' blocks line for
//! line (always runs). The second builds the conrod with and without `--damping`, exports the
//! NPZ and runs the example on both (skipped visibly without exudyn): every block runs, and the
//! damping block sets diag(2 ζ ω) — its largest entry 2 · 0.02 · 2π f of the highest flexible
//! mode — only when the NPZ has it (before issue 36 it used an undefined `mbs` and `data` and
//! raised KeyError without `--damping`).

use std::path::Path;
use std::process::Command;

use crate::common::{exe, python_has, run_python, scratch, skipped_install};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The Python blocks of the docs' exudyn section, dedented.
fn docs_blocks() -> Vec<Vec<String>> {
    section_blocks("## exudyn (`--to exudyn`)")
}

/// The Python blocks of the docs' section titled `title` (up to the next `## `), dedented.
fn section_blocks(title: &str) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(root().join("docs/using-in-solvers.md")).unwrap();
    let start = text.find(title).unwrap();
    let end = start + 3 + text[start + 3..].find("\n## ").unwrap();
    let mut blocks = Vec::new();
    let mut current: Option<(usize, Vec<String>)> = None;
    for line in text[start..end].lines() {
        let trimmed = line.trim_start();
        match &mut current {
            None if trimmed == "```python" => current = Some((line.len() - trimmed.len(), vec![])),
            Some(_) if trimmed == "```" => blocks.push(current.take().unwrap().1),
            Some((indent, lines)) => lines.push(line.get(*indent..).unwrap_or("").to_string()),
            None => {}
        }
    }
    blocks
}

/// The example's `# --- snippet N` … `# --- end` blocks.
fn example_blocks() -> Vec<Vec<String>> {
    snippet_blocks("examples/using_in_exudyn.py")
}

/// The `# --- snippet N` … `# --- end` blocks of the file `rel` of the repository.
fn snippet_blocks(rel: &str) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(root().join(rel)).unwrap();
    let mut blocks = Vec::new();
    let mut current: Option<Vec<String>> = None;
    for line in text.lines() {
        if line.starts_with("# --- snippet") {
            current = Some(Vec::new());
        } else if line == "# --- end" {
            blocks.push(current.take().unwrap());
        } else if let Some(lines) = &mut current {
            lines.push(line.to_string());
        }
    }
    blocks
}

#[test]
fn the_docs_exudyn_snippets_are_the_examples_line_for_line() {
    let docs = docs_blocks();
    let example = example_blocks();
    assert_eq!(
        docs.len(),
        3,
        "the exudyn section's Python blocks: {docs:?}"
    );
    assert_eq!(docs, example);
    // Each block defines what it uses: the system container before `mbs`.
    for block in &docs[..2] {
        let defined = block.iter().position(|l| l.starts_with("mbs = ")).unwrap();
        let used = block.iter().position(|l| l.contains("(mbs")).unwrap();
        assert!(defined < used);
    }
}

#[test]
fn the_docs_exudyn_snippets_run_with_and_without_damping() {
    if !python_has("exudyn") || !python_has("numpy") {
        skipped_install(
            "the docs' exudyn snippets (docs_snippets): python3 cannot import exudyn and numpy",
            "pip install exudyn numpy",
        );
        return;
    }
    for damping in [true, false] {
        let dir = scratch(&format!("snippets-{damping}"));
        let body = dir.join("conrod.flexbody");
        let npz = dir.join("conrod.npz");
        crate::common::build_conrod(&body, if damping { &["--damping", "2%"] } else { &[] });
        let export = crate::common::export(&body, "exudyn", &npz);
        assert!(export.status.success());
        println!("damping {damping}:");
        let out = run_python("examples/using_in_exudyn.py", &[&npz, &body], None);
        assert!(out.contains("all snippets ran"));
        let file = flexbody_reader::read(&body).unwrap();
        if damping {
            let f = *file.modes.frequency_hz.last().unwrap();
            let expected = 2.0 * 0.02 * 2.0 * std::f64::consts::PI * f;
            let at = out.find("max diagonal ").expect("the damping line") + "max diagonal ".len();
            let value: f64 = out[at..at + out[at..].find(')').unwrap()].parse().unwrap();
            println!("2 zeta omega of the highest mode: {value} (expected {expected})");
            assert!(
                (value / expected - 1.0).abs() < 1e-12,
                "{value} vs {expected}"
            );
        } else {
            assert!(out.contains("no dampingMatrixReduced"), "{out}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn the_docs_joint_recipes_are_the_joints_examples_line_for_line() {
    let docs = section_blocks("## Joints at interfaces in exudyn");
    // setup, revolute, prismatic, rigid, marker-based revolute
    assert_eq!(
        docs.len(),
        5,
        "the joints section's Python blocks: {docs:?}"
    );
    assert_eq!(docs, snippet_blocks("examples/joints_exudyn.py"));
    assert!(docs[0].iter().any(|l| l.contains("constrainedAxes=axes")));
    assert!(docs[4]
        .iter()
        .any(|l| l.contains("MarkerSuperElementRigid")));
}

/// Issue 36's acceptance: the conrod pendulum with the docs' revolute recipe (default mean-axis
/// file, spherical joint at the big-end centre + z held at two bore nodes; the example run as it
/// stands) against exudyn's own Hurty–Craig–Bampton pendulum (its reduction of the bare mesh's K
/// and M, frame attached at the big-end bore, revolute on the frame node): the small end's
/// position at 0.05 s equal to 1e-6 relative (measured 7.6e-11 to 7.7e-11) and the difference under 10 %
/// of the pin-relative elastic deflection (measured 0.3 %). Also: a `--reference-conditions`
/// build with a revolute on its frame node against the same reference (≤ 1e-11 m; measured
/// 4e-14 to 4e-13 m), and exudyn's built-in gravity in the attached frame loads the modes
/// (static modal coordinates = K⁻¹ Ψᵀ M g to 1e-12; measured 9e-16). About 10 s of Python.
#[test]
fn the_revolute_recipe_pendulum_equals_exudyns_own_hcb_pendulum() {
    if !python_has("exudyn") || !python_has("numpy") || !python_has("scipy") {
        skipped_install(
            "the revolute recipe's acceptance (docs_snippets): python3 cannot import exudyn, \
             numpy and scipy",
            "pip install exudyn numpy scipy",
        );
        return;
    }
    let dir = scratch("revolute");
    let body = dir.join("conrod.flexbody");
    let mesh = dir.join("mesh");
    crate::common::build_conrod(&body, &[]);
    // the same rod with its frame attached at the BIG_END centre (node 6962)
    let attached = dir.join("conrod_rc.flexbody");
    crate::common::build_conrod(&attached, &["--reference-conditions", "6962:123456"]);
    let export = exe()
        .arg("export")
        .arg(&body)
        .args(["--to", "mtx", "--model"])
        .arg(root().join("fixtures/models/conrod/conrod.inp"))
        .args(["--spider", "none", "-o"])
        .arg(&mesh)
        .output()
        .unwrap();
    assert!(
        export.status.success(),
        "{}",
        String::from_utf8_lossy(&export.stderr)
    );
    let out = run_python(
        "tests/python/revolute_hcb_check.py",
        &[
            body.as_os_str(),
            mesh.as_os_str(),
            "0.05".as_ref(),
            attached.as_os_str(),
        ],
        None,
    );
    assert!(out.contains("revolute acceptance passed"), "{out}");
    // revolute (2), frame-node revolute of the attached build, gravity, rigid, prismatic (2)
    assert_eq!(out.matches("ok   ").count(), 7, "{out}");
    assert!(
        out.contains("exudyn HCB: 8 modes (6 static + 2 fixed-interface) of 20883 dofs"),
        "{out}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The stress recipe (`examples/stress_exudyn.py`, the docs' block line for line): exudyn's
/// `SensorSuperElement` (StressLocal) on the clamped conrod under gravity equals the file's own
/// stress shapes (reference reader, the file's component order) times the modal coordinates, all
/// six components to 1e-12 relative (measured 7e-17), and the stress is real (|σ| > 1e3 Pa:
/// measured σ_xx = −2.59e4 Pa at node 237).
#[test]
fn exudyns_stress_sensor_gives_the_files_stress_shapes_times_the_modal_coordinates() {
    let docs = section_blocks("## Stresses through exudyn's sensor");
    assert_eq!(docs.len(), 1, "{docs:?}");
    assert_eq!(docs, snippet_blocks("examples/stress_exudyn.py"));
    if !python_has("exudyn") || !python_has("numpy") {
        skipped_install(
            "the stress recipe (docs_snippets): python3 cannot import exudyn and numpy",
            "pip install exudyn numpy",
        );
        return;
    }
    let out = run_python::<&str>("examples/stress_exudyn.py", &[], None);
    let after = |label: &str| -> Vec<f64> {
        let rest = out
            .split(label)
            .nth(1)
            .unwrap_or_else(|| panic!("no '{label}' in {out}"));
        rest.split([' ', ';', '\n'])
            .filter(|w| !w.is_empty())
            .map_while(|w| w.parse().ok())
            .collect()
    };
    let sensor = after("[Pa]: sensor ");
    let from_file = after("from the file's stress shapes: ");
    assert_eq!((sensor.len(), from_file.len()), (6, 6), "{out}");
    let scale = from_file.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(scale > 1e3, "stress {scale} Pa");
    let worst = after("largest difference ")[0];
    assert!(worst <= 1e-12, "sensor vs file: {worst}");
    // the printed values (7 digits) agree too
    for (a, b) in sensor.iter().zip(&from_file) {
        assert!((a - b).abs() <= 1e-6 * scale, "{a} vs {b}");
    }
}

/// The `sh` blocks of the whole page, in order (the shell commands a reader types).
fn shell_blocks() -> Vec<String> {
    let text = std::fs::read_to_string(root().join("docs/using-in-solvers.md")).unwrap();
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in text.lines() {
        match &mut current {
            None if line.trim_start() == "```sh" => current = Some(String::new()),
            Some(_) if line.trim_start() == "```" => blocks.push(current.take().unwrap()),
            Some(block) => {
                block.push_str(line.trim_start());
                block.push('\n');
            }
            None => {}
        }
    }
    blocks
}

/// Every shell block of docs/using-in-solvers.md runs as it stands, in order, in one folder
/// (with `flexbody` on PATH and the repository's `fixtures/` beside it, as a reader in a
/// checkout has them): build, the exports (exudyn, MBDyn, VTU, both K/M exports, SID), the
/// stress section's `conrod_stress.flexbody` (issue 47), view and the geometric-stiffness build
/// each make their file; then the exudyn section's Python blocks run on that NPZ and file.
#[cfg(unix)]
#[test]
fn the_docs_shell_blocks_run_as_they_stand_in_order() {
    let blocks = shell_blocks();
    assert_eq!(blocks.len(), 7, "{blocks:?}");
    let dir = scratch("shell-blocks");
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_flexbody"), bin.join("flexbody")).unwrap();
    std::os::unix::fs::symlink(root().join("fixtures"), dir.join("fixtures")).unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    for (k, block) in blocks.iter().enumerate() {
        let o = Command::new("bash")
            .args(["-euo", "pipefail", "-c", block])
            .current_dir(&dir)
            .env("PATH", &path)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "sh block {} failed:\n{block}\n{}",
            k + 1,
            String::from_utf8_lossy(&o.stderr)
        );
    }
    for made in [
        "conrod.flexbody",
        "beam.flexbody",
        "conrod.npz",
        "conrod.fem",
        "conrod.vtu",
        "conrod.html",
        "mats/K.mtx",
        "mats/coords.csv",
        "mesh/K.mtx",
        "conrod.SID_FEM",
    ] {
        let len = std::fs::metadata(dir.join(made)).map_or(0, |m| m.len());
        assert!(len > 0, "{made} not made by the docs' shell blocks");
    }
    if python_has("exudyn") && python_has("numpy") {
        let out = run_python(
            "examples/using_in_exudyn.py",
            &[dir.join("conrod.npz"), dir.join("conrod.flexbody")],
            None,
        );
        assert!(out.contains("all snippets ran"), "{out}");
        // the first block builds with --damping 2%: the damping block sets the matrix
        assert!(out.contains("dampingMatrixReduced set (8 modes"), "{out}");
    } else {
        skipped_install(
            "the exudyn blocks on the shell blocks' files (docs_snippets): python3 cannot \
             import exudyn and numpy",
            "pip install exudyn numpy",
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
