//! `eigen_residuals.bin` (format 1.9, SPEC §5.17; issue 46) on real builds through the CLI:
//! the stored residuals equal numpy's recomputation from the matrices the build reduced
//! (`--write-matrices`) and the file's shapes; an AMLS build with a low cutoff stores residuals
//! far above Lanczos's; `check --model` recomputes them; a hand-damaged entry is refused by
//! the Rust reader and both Python readers under the same error name.

use std::path::Path;

use flexbody_reader as file;

fn conrod() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/models/conrod/conrod.inp")
}

/// Normal modes of the conrod (`--modes 20`, one thread) with `solver`, the constrained K and M
/// written beside; the body read back.
fn build(dir: &Path, solver: &str) -> file::ReducedBody {
    let o = crate::common::exe()
        .arg("build")
        .arg(conrod())
        .args(["--interface", "BIG_END,SMALL_END", "--units", "si"])
        .args([
            "--method",
            "normal",
            "--modes",
            "20",
            "--threads",
            "1",
            "-q",
        ])
        .args(["--eigensolver", solver])
        .arg("--write-matrices")
        .arg(dir.join(format!("{solver}-mats")))
        .arg("-o")
        .arg(dir.join(format!("{solver}.flexbody")))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    file::read(dir.join(format!("{solver}.flexbody"))).unwrap()
}

/// numpy's recomputation (tests/python/eigen_residuals_check.py) of `solver`'s build.
fn numpy_check(dir: &Path, solver: &str) -> serde_json::Value {
    let out = crate::common::run_python(
        "tests/python/eigen_residuals_check.py",
        &[
            dir.join(format!("{solver}.flexbody")),
            dir.join(format!("{solver}-mats")),
        ],
        None,
    );
    serde_json::from_str(out.lines().last().unwrap()).unwrap()
}

fn problem(body: &file::ReducedBody) -> &file::EigenProblem {
    let e = body
        .eigen_residuals
        .as_ref()
        .expect("every build writes the entry");
    assert_eq!(e.problems.len(), 1);
    &e.problems[0]
}

/// The stored residuals against numpy's, and Lanczos's against AMLS's with a cutoff of 1.5×
/// the band top (too low: its Rayleigh–Ritz pairs are far from eigenpairs).
#[test]
fn stored_residuals_are_numpys_and_a_low_amls_cutoff_shows_in_them() {
    if !crate::common::python_has("scipy") {
        crate::common::skipped_install("eigen residuals against numpy", "pip install scipy");
        return;
    }
    let dir = crate::common::scratch("eigen-residuals");
    let mut largest = vec![];
    for solver in ["lanczos", "amls:1.5"] {
        let body = build(&dir, solver);
        assert_eq!((body.version.major, body.version.minor), (1, 9));
        let p = problem(&body);
        assert_eq!(p.kind, file::EigenProblemKind::NormalModes);
        let expected_solver = if solver == "lanczos" {
            file::EigenSolverKind::Lanczos
        } else {
            file::EigenSolverKind::Amls
        };
        assert_eq!(p.solver, expected_solver);
        assert_eq!(p.omega2.len(), body.mode_count());
        // AMLS always counts its band; Lanczos only with --verify-band
        assert_eq!(p.inertia.is_some(), solver != "lanczos");
        if let Some(i) = p.inertia {
            assert_eq!(i.below, 20, "complete band: {i:?}");
        }
        let v = numpy_check(&dir, solver);
        // measured: s equal to the last bit (the same median of the same diagonals)
        assert_eq!(v["scale"].as_f64(), Some(p.scale), "{v}");
        // measured: |r − r_stored| ≤ 2.7 (Lanczos) and 2.4 (AMLS) rounding floors
        // ε‖|K||φ|‖ / max(‖Kφ‖, 1e-8 s‖Mφ‖): the rigid modes' and Lanczos's residuals are
        // at that floor; above 1000 floors they agree to 2.2e-6 and 1.4e-4 relative
        let floors = v["max_diff_over_floor"].as_f64().unwrap();
        assert!(floors < 25.0, "{solver}: {v}");
        largest.push(p.largest_flexible_residual().unwrap().1);
    }
    // measured: Lanczos 6.3e-9, AMLS with cutoff factor 1.5: 2.8e-3
    println!(
        "largest flexible residual: lanczos {:.3e}, amls:1.5 {:.3e}",
        largest[0], largest[1]
    );
    assert!(largest[0] < 6e-8, "{largest:?}");
    assert!(largest[1] > 3e-4, "{largest:?}");
    assert!(largest[1] > 1e4 * largest[0], "{largest:?}");
    // check --model recomputes them from the rebuilt model and agrees (measured: exactly)
    for solver in ["lanczos", "amls:1.5"] {
        let o = crate::common::exe()
            .arg("check")
            .arg(dir.join(format!("{solver}.flexbody")))
            .arg("--model")
            .arg(conrod())
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{text}");
        let line = text
            .lines()
            .find(|l| l.contains("eigen residuals against the model"))
            .unwrap_or_else(|| panic!("no residual check: {text}"));
        assert!(line.starts_with("ok"), "{line}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A hand damage to an eigenproblem record.
type Damage = dyn Fn(&mut file::EigenProblem);

/// A built file whose `eigen_residuals.bin` is damaged by hand (a NaN residual, a residual
/// list one short) with a manifest that matches: the Rust reader, the reference reader and the
/// numpy reader refuse it under one error name.
#[test]
fn a_hand_damaged_entry_is_refused_by_every_reader() {
    let dir = crate::common::scratch("eigen-damaged");
    let o = crate::common::exe()
        .arg("build")
        .arg(conrod())
        .args(["--interface", "BIG_END,SMALL_END", "--units", "si"])
        .args(["--method", "cb", "--modes", "6", "-q", "-o"])
        .arg(dir.join("cb.flexbody"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let body = file::read(dir.join("cb.flexbody")).unwrap();
    assert_eq!(problem(&body).kind, file::EigenProblemKind::FixedInterface);
    assert_eq!(
        problem(&body).omega2.len() as u64,
        body.method.counts.fixed_interface
    );
    let cases: [(&str, &Damage, &str); 3] = [
        ("nan", &|p| p.residual[3] = f64::NAN, "NonFinite"),
        (
            "short",
            &|p| {
                p.residual.pop();
            },
            "CountMismatch",
        ),
        (
            "both_short",
            &|p| {
                p.residual.pop();
                p.omega2.pop();
            },
            "CountMismatch",
        ),
    ];
    for (name, damage, variant) in cases {
        let mut b = body.clone();
        if let Some(e) = b.eigen_residuals.as_mut() {
            damage(&mut e.problems[0]);
        }
        // the entries and a manifest that matches them, zipped without the writer's check
        let entries = file::encode_entries(&b);
        let manifest = file::manifest_for(&b, &entries);
        let mut all = vec![(
            "manifest.json".to_string(),
            serde_json::to_vec_pretty(&manifest).unwrap(),
        )];
        all.extend(entries.into_iter().map(|(n, _, x)| (n.to_string(), x)));
        let bytes =
            flexbody::write::zip_entries(&all, flexbody::write::Compression::Deflate(6)).unwrap();
        let path = dir.join(format!("{name}.flexbody"));
        std::fs::write(&path, &bytes).unwrap();
        let err = file::from_bytes(&bytes).expect_err(name);
        assert_eq!(err.variant(), variant, "{name}: {err}");
        assert!(err.to_string().contains("eigen_residuals.bin"), "{err}");
        for read in ["reference_reader.read_bytes", "flexbody.read_bytes_body"] {
            let code = format!(
                "import sys\nsys.path[:0] = ['python', 'format-spec']\n\
                 import flexbody, reference_reader\n\
                 try:\n    {read}(open(sys.argv[1], 'rb').read())\n\
                 except Exception as e:\n    print(getattr(e, 'variant', repr(e)))\n"
            );
            let o = std::process::Command::new("python3")
                .current_dir(env!("CARGO_MANIFEST_DIR"))
                .args(["-c", &code])
                .arg(&path)
                .output()
                .unwrap();
            let said = String::from_utf8_lossy(&o.stdout);
            assert_eq!(
                said.trim(),
                variant,
                "{read} on {name}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
