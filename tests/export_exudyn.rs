//! Issue 18, `flexbody export --to exudyn`: the NPZ checked by exudyn itself
//! (`tests/python/exudyn_export_check.py`): LoadFromFile reads it (with flexbody's extra keys,
//! among them each interface's bore nodes, issue 36, equal to the file's `interfaces.bin`), exudyn's own constructor
//! recomputes the inertia terms from the exported nodes, masses and shapes (equal to 1e-12),
//! and an exudyn simulation of the free body vibrating in each of the first 3 flexible modes
//! gives the stored frequency to 1e-6. Through the real binary on the bundled connecting rod.
//! Without an importable exudyn the Python part is skipped with a visible message (CI installs
//! exudyn, see `.ci/run`).

use crate::common::{exe, python_has, run_python, scratch};
use std::path::Path;

#[test]
fn exudyn_loads_the_npz_recomputes_its_inertia_terms_and_vibrates_at_the_stored_frequencies() {
    let dir = scratch("exudyn-exudyn");
    let body = dir.join("rod.flexbody");
    let npz = dir.join("rod.npz");
    crate::common::build_conrod(&body, &["--stress-modes", "--damping", "2%"]);
    let o = crate::common::export(&body, "exudyn", &npz);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "export failed: {stderr}");
    assert!(stderr.contains("8 flexible modes, 6963 nodes"), "{stderr}");
    assert!(
        stderr.contains("2020 surface triangles with 6 nodes"),
        "{stderr}"
    );
    // An NPZ is a zip of .npy files; exudyn's keys are there whatever Python can do.
    let zip = zip::ZipArchive::new(std::fs::File::open(&npz).unwrap()).unwrap();
    for key in [
        "modeBasis",
        "trigList",
        "postProcessingModes",
        "massMatrixReduced",
        "stiffnessMatrixReduced",
        "infoList",
        "rigidBodyNodeType",
        "xRef",
        "inertiaLocal",
        "Mtt",
        "totalMass",
        "chiU",
        "chiUtilde",
        "mPsiTildePsi",
        "mPsiTildePsiTilde",
        "mPhitTPsi",
        "mPhitTPsiTilde",
        "mXRefTildePsi",
        "mXRefTildePsiTilde",
        "fileVersion",
        "type",
        // flexbody's own: each interface's dependent (bore) nodes, flat with offsets (issue 36)
        "interfaceDependentOffsets",
        "interfaceDependentNodeIndices",
        "interfaceDependentNodeIds",
        "interfaceNames",
        "interfaceKinds",
    ] {
        assert!(
            zip.file_names()
                .any(|n| n.is_ok_and(|n| n == format!("{key}.npy"))),
            "{key}.npy missing"
        );
    }

    if !python_has("exudyn") || !python_has("scipy") {
        crate::common::skipped_install(
            "the exudyn checks of export_exudyn: python3 cannot import exudyn and scipy; the NPZ \
             was written but not loaded in exudyn",
            "pip install exudyn scipy",
        );
        return;
    }
    let stdout = run_python("tests/python/exudyn_export_check.py", &[&npz, &body], None);
    assert!(stdout.contains("all exudyn checks passed"), "{stdout}");
    assert_eq!(stdout.matches("ok   free vibration mode").count(), 3);
    // The bore nodes a rigid marker needs, equal to the file's interfaces.bin (checked there
    // node by node): all 510 and 240 legs are stored nodes of the default build.
    assert!(
        stdout.contains("interface 0 BIG_END (Rbe2): 510 dependent nodes, 510 stored")
            && stdout.contains("interface 1 SMALL_END (Rbe2): 240 dependent nodes, 240 stored")
            && stdout.contains("ok   interfaces' dependent nodes differing")
            && stdout.contains("ok   RBE2 centre rotations fitted over the NPZ's bore nodes"),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The worked example (examples/pendulum_exudyn.py, built with this test's binary) runs and its
/// swing agrees with the rigid physical pendulum of the file's mass properties (the conrod's
/// elastic deflection is ~0.01 µm, far below what changes the swing). It also reports the small
/// end's deflection relative to the pinned end (issue 36), with the big end's rotation fitted
/// over the NPZ's bore nodes (residual ≤ 1e-12; measured 1.70e-8 m against 7.3e-9 m in the
/// body frame). Run without an argument,
/// it plots into the current folder and leaves the tracked docs/pendulum_exudyn.png alone.
#[test]
fn the_pendulum_example_runs_and_swings_like_the_rigid_pendulum_of_the_files_mass_properties() {
    if !python_has("exudyn") || !python_has("scipy") || !python_has("matplotlib") {
        crate::common::skipped_install(
            "the pendulum example (export_exudyn): python3 cannot import exudyn, scipy and \
             matplotlib",
            "pip install exudyn scipy matplotlib",
        );
        return;
    }
    let dir = scratch("exudyn-pendulum");
    let png = dir.join("pendulum_exudyn.png");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let docs_png = std::fs::read(root.join("docs/pendulum_exudyn.png")).unwrap();
    let stdout = run_python::<&str>("examples/pendulum_exudyn.py", &[], Some(&dir));
    assert!(png.exists(), "no {} from the example", png.display());
    assert!(
        std::fs::read(root.join("docs/pendulum_exudyn.png")).unwrap() == docs_png,
        "the example without an argument changed docs/pendulum_exudyn.png"
    );
    // Issue 36: the deflection relative to the pinned end (the big-end bore's rigid motion,
    // fitted over the NPZ's bore nodes, subtracted) — the fit exact for the RBE2 bore, and the
    // figure larger than the body frame's (the mean-axis frame moves the pin as well).
    let body_frame = figure(&stdout, "in the body frame: max |v| = ");
    let pinned = figure(&stdout, "relative to the pinned end: max |v| = ");
    let residual = figure(&stdout, "residual ");
    println!("pin-relative {pinned} um, body frame {body_frame} um, fit residual {residual}");
    assert!(residual < 1e-12, "bore fit residual {residual}");
    assert!(
        pinned > 1.5 * body_frame && pinned < 1.0,
        "pin-relative {pinned} um vs body frame {body_frame} um"
    );
    let diff: f64 = stdout
        .split("largest difference to exudyn's flexible body: ")
        .nth(1)
        .and_then(|r| r.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no difference line in {stdout}"));
    assert!(
        diff < 1e-3,
        "swing differs from the rigid pendulum by {diff} deg"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The number after `label` in `text` (up to the next blank).
fn figure(text: &str, label: &str) -> f64 {
    text.split(label)
        .nth(1)
        .and_then(|r| r.split_whitespace().next())
        .and_then(|v| v.trim_end_matches([')', ';', ',']).parse().ok())
        .unwrap_or_else(|| panic!("no '{label}' figure in {text}"))
}

/// Issue 36: the slider-crank example (examples/slider_crank_exudyn.py: rigid crank at 3000 rpm,
/// r = 40 mm, the conrod flexible, rigid slider) over half a crank turn. The slider follows the
/// rigid slider-crank's closed form x(θ) = r cos θ + √(l² − r² sin² θ) at the simulated crank
/// angle to within the rod's elastic stretch |ΔL| (times dx/dl ≤ 1/√(1 − (r/l)²) = 1.037:
/// limit 1.04 |ΔL|; measured equal to it, 7.9e-6 m), and to 1 % of |ΔL| after the first-order
/// correction ΔL·dx/dl (measured 4.5e-11 m); the stretch is a real elastic effect of the
/// inertia loads, not a blow-up (1e-7 m < |ΔL| < 1e-4 m); the rod does not spin about its own
/// axis (its frame's z axis within 1e-3° of global z; measured 1.2e-6°). No matplotlib needed.
#[test]
fn the_slider_crank_example_follows_the_rigid_closed_form_within_the_rods_stretch() {
    if !python_has("exudyn") || !python_has("numpy") {
        crate::common::skipped_install(
            "the slider-crank example (export_exudyn): python3 cannot import exudyn and numpy",
            "pip install exudyn numpy",
        );
        return;
    }
    let out = run_python("examples/slider_crank_exudyn.py", &["0.01"], None);
    let difference = figure(&out, "max |x - x_rigid(theta)| = ");
    let stretch = figure(&out, "max |dL| = ");
    let residual = figure(&out, "first-order stretch correction: ");
    let spin = figure(&out, "rod's z axis off global z: max ");
    assert!((1e-7..1e-4).contains(&stretch), "rod stretch {stretch} m");
    assert!(
        difference <= 1.04 * stretch,
        "slider off the closed form by {difference} m, stretch {stretch} m"
    );
    assert!(
        residual <= 0.01 * stretch,
        "first-order residual {residual} m vs stretch {stretch} m"
    );
    assert!(spin < 1e-3, "the rod turned {spin} deg about its axis");
    assert!(out.contains("(0.498 crank turns)"), "{out}");
}

#[test]
fn a_file_without_every_invariant_is_refused_and_nothing_is_written() {
    let dir = scratch("exudyn-partial");
    let body = dir.join("rod.flexbody");
    let npz = dir.join("rod.npz");
    crate::common::build_conrod(&body, &["--invariants", "partial"]);
    let o = crate::common::export(&body, "exudyn", &npz);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("lacks I5, I9") && stderr.contains("--invariants full"),
        "{stderr}"
    );
    assert!(!npz.exists());
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "a temp file was left"
    );
    let o = crate::common::export(&body, "adams", &npz);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--to adams: expected"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The Python package's one-call helper `flexbody.exudyn.add_body(mbs, FILE)` (and
/// `flexbody.exudyn.interface(FILE)`) builds the same exudyn body as `LoadFromFile` of the
/// exported NPZ: every inertia term, array and object parameter equal, the file's damping
/// applied, the object's frequencies = the file's (`tests/python/exudyn_helper_check.py`, run
/// with this repository's `python/` on PYTHONPATH). On the conrod (6-node triangles, stress
/// modes, damping) and on a hex8 block (quads split, strain modes, no damping).
#[test]
fn python_add_body_builds_the_same_exudyn_body_as_the_exported_npz() {
    if !python_has("exudyn") || !python_has("numpy") {
        crate::common::skipped_install(
            "the flexbody.exudyn helper check (export_exudyn): python3 cannot import exudyn and \
             numpy",
            "pip install exudyn numpy",
        );
        return;
    }
    let dir = scratch("exudyn-helper");
    let rod = dir.join("rod.flexbody");
    crate::common::build_conrod(&rod, &["--stress-modes", "--damping", "2%"]);
    let block = dir.join("block.flexbody");
    let o = exe()
        .arg("build")
        .arg(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("fixtures/reference/e_matrices/hex8_block_coarse/ccx_matrix_free.inp"),
        )
        .args([
            "--method",
            "normal",
            "--modes",
            "12",
            "--stress-modes",
            "strain",
        ])
        .args(["--units", "si", "-q", "-o"])
        .arg(&block)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for (body, what) in [(&rod, "6 nodes"), (&block, "3 nodes")] {
        let npz = body.with_extension("npz");
        let o = crate::common::export(body, "exudyn", &npz);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let stdout = run_python(
            "tests/python/exudyn_helper_check.py",
            &[npz.as_os_str(), body.as_os_str()],
            None,
        );
        assert!(stdout.contains("all helper checks passed"), "{stdout}");
        assert!(stdout.contains(&format!("triangles of {what}")), "{stdout}");
        assert!(
            stdout.matches("ok   object parameter").count() >= 10,
            "{stdout}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
