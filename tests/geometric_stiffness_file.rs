//! The file's geometric-stiffness terms (format 1.7 `geometric_stiffness.bin`, issue 35) through
//! the command line: a spinning cantilever — a uniform Euler–Bernoulli beam (Nastran CBAR/PBAR
//! without shear factors) along x, clamped at the hub (hub radius 0), held in the flap plane
//! (GRDSET PS 26: bending along z only, axial and torsion free) — built with
//! `--method normal --modes 40 --mass consistent --geometric-stiffness inertia` and read back
//! through `flexbody-reader`.
//!
//! * The file's ω_z² term gives the flap frequencies at speed, ω² = eig(K̂ + Ω² K̂_G,zz), equal
//!   to the library's preloaded build (the linear static solve of the centrifugal load Ω² M r_⊥,
//!   K + K_G(σ), its lowest eigenvalue on the same imported deck) to 1e-6, and both equal to
//!   Wright, Smith, Thompson & Worley, *J. Appl. Mech.* 49 (1982) 197, Table 1 (first flap mode,
//!   hub radius 0; the table of `tests/preload_spin.rs`) to 2e-4 (measured ≤ 3.5e-5); K̂_G,zz of
//!   the first mode is the Southwell coefficient 1.1933 to 1e-3 (measured 1.6e-4).
//! * Lead-lag is not in the terms: the rotating frame's spin softening is the solver's own
//!   inertia term (SPEC §5.16).
//! * The entry holds the twelve unit inertia loads in flexbody's order; a clamped body is
//!   `Held` (SPEC §5.16).

use std::path::{Path, PathBuf};

use crate::preload_support::{eigenvalues, Built};
use faer::Mat;
use flexbody::fe::preload::{preload, PreloadCase, PreloadSpec, Spin};
use flexbody::fe::{AssemblySpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody_reader::{StaticSupport, UnitLoad};

const L: f64 = 2.0;
const NE: usize = 40;
/// Section 0.06 (y) × 0.03 (z): flap (along z) uses I2 = W H³/12 = 1.35e-7, lead-lag I1 =
/// H W³/12 = 5.4e-7 (four times stiffer: the flap mode is the lowest).
const AREA: f64 = 1.8e-3;
const I_FLAP: f64 = 1.35e-7;
const E: f64 = 2.1e11;
const RHO: f64 = 7850.0;

/// Wright et al. (1982), Table 1, first flap mode, hub radius 0: (Ω̄, ω̄), ω̄ = ω √(ρAL⁴/EI).
const WRIGHT_1982: [(f64, f64); 6] = [
    (1.0, 3.6816),
    (2.0, 4.1373),
    (4.0, 5.5850),
    (6.0, 7.3604),
    (8.0, 9.2568),
    (10.0, 11.2023),
];
const SOUTHWELL_1: f64 = 1.1933;

/// The cantilever as a Nastran deck (free-field cards).
fn deck(dir: &Path) -> PathBuf {
    let mut s = String::from(
        "$ spinning cantilever: CBAR/PBAR (no K1, K2: Euler-Bernoulli) along x, clamped at\n\
         $ GRID 1, flap plane only (PS 26 on every GRID)\nSOL 103\nCEND\nTITLE = spinning \
         cantilever\nBEGIN BULK\nGRDSET,,,,,,,26\n",
    );
    for i in 0..=NE {
        let x = L * i as f64 / NE as f64;
        let ps = if i == 0 { "123456" } else { "" };
        s.push_str(&format!("GRID,{},,{x:?},0.0,0.0,,{ps}\n", i + 1));
    }
    for e in 1..=NE {
        s.push_str(&format!("CBAR,{e},1,{e},{},0.0,1.0,0.0\n", e + 1));
    }
    s.push_str("PBAR,1,1,1.8-3,5.4-7,1.35-7,3.7098-7\nMAT1,1,2.1+11,,0.3,7850.0\nENDDATA\n");
    let path = dir.join("spinning_cantilever.bdf");
    std::fs::write(&path, s).unwrap();
    path
}

/// √(EI/(ρA L⁴)): ω̄ = ω / this.
fn unit() -> f64 {
    (E * I_FLAP / (RHO * AREA * L.powi(4))).sqrt()
}

/// The lowest eigenvalue of diag(ω²) + s K̂_G (q × q, row-major K̂_G).
fn lowest_with(omega2: &[f64], kg: &[f64], s: f64) -> f64 {
    let q = omega2.len();
    let a = Mat::from_fn(q, q, |i, j| {
        s * kg[i * q + j] + if i == j { omega2[i] } else { 0.0 }
    });
    a.self_adjoint_eigenvalues(faer::Side::Lower)
        .unwrap()
        .into_iter()
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn spinning_cantilever_from_the_files_terms_equals_the_preloaded_build_and_wright_1982() {
    let dir = crate::common::scratch("geometric_stiffness_file");
    let deck = deck(&dir);
    let out = dir.join("cantilever.flexbody");
    let o = crate::common::exe()
        .arg("build")
        .arg(&deck)
        .args(["--units", "si", "--method", "normal", "--modes", "40"])
        .args([
            "--mass",
            "consistent",
            "--geometric-stiffness",
            "inertia",
            "-q",
        ])
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "build failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let body = flexbody_reader::read(&out).expect("the file reads back");
    assert_eq!(body.version.minor, 9);
    let mut bare = body.clone();
    bare.eigen_residuals = None; // 1.9, in every build: the geometric terms alone are 1.8
    assert_eq!(flexbody_reader::version_for(&bare).minor, 8);
    let recipe = body.recipe.as_ref().expect("recipe");
    assert_eq!(
        recipe.options.geometric_stiffness.as_deref(),
        Some("inertia")
    );
    let g = body
        .geometric_stiffness
        .as_ref()
        .expect("geometric_stiffness.bin");
    assert_eq!(g.support, StaticSupport::Held, "clamped by its SPCs");
    let loads: Vec<UnitLoad> = g.fields.iter().map(|f| f.load).collect();
    assert_eq!(loads, UnitLoad::inertia());
    let field = |load: UnitLoad| &g.fields.iter().find(|f| f.load == load).unwrap().matrix;
    let kg_zz = field(UnitLoad::AngularVelocity([2, 2]));
    let omega2 = &body.modes.omega2;
    let q = omega2.len();
    assert_eq!(q, 40);
    // mode 1 is the first flap mode: K̂_G,zz[0][0] is its Southwell coefficient
    let southwell = kg_zz[0];
    eprintln!("Southwell K₁ from the file: {southwell:.6} (published {SOUTHWELL_1})");
    // measured 1.193489: +1.6e-4 (the published 1.1933 is rounded to 4e-5)
    assert!((southwell - SOUTHWELL_1).abs() < 1e-3 * SOUTHWELL_1);

    // the library's preloaded build of the same deck
    let model = read_model(&deck, &ImportOptions::default()).expect("deck imports");
    let b = Built::new(
        model,
        AssemblySpec {
            mass: MassKind::Consistent,
            ..Default::default()
        },
    );
    let u = unit();
    let w0 = eigenvalues(&b.red.k, &b.red.m)[0];
    assert!(
        (omega2[0] - w0).abs() < 1e-9 * w0,
        "the file's first mode {} vs the model's {w0}",
        omega2[0]
    );
    for &(om, want) in &WRIGHT_1982 {
        let omega = om * u;
        let spin = Spin {
            point: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            omega,
        };
        let pre = preload(
            &b.system(),
            &PreloadCase::spin(&spin),
            &PreloadSpec::default(),
        )
        .unwrap();
        let build = eigenvalues(&pre.k_t, &b.red.m)[0].sqrt();
        let file = lowest_with(omega2, kg_zz, omega * omega).sqrt();
        let rel = (file - build) / build;
        let err = (file / u - want) / want;
        eprintln!(
            "Ω̄ = {om:4.1}: ω̄ from the file {:.7}, preloaded build {:.7} (rel. {rel:+.2e}), \
             Wright et al. {want} (rel. {err:+.2e})",
            file / u,
            build / u
        );
        assert!(rel.abs() < 1e-6, "Ω̄ = {om}: {file} vs {build}");
        // measured ≤ 3.5e-5 (Ω̄ = 8; the table's 5 digits round to ≤ 1.4e-5)
        assert!(err.abs() < 2e-4, "Ω̄ = {om}: {} vs {want}", file / u);
    }
    // `check --model` recomputes the entry from the deck (the recipe's options)
    let o = crate::common::exe()
        .arg("check")
        .arg(&out)
        .arg("--model")
        .arg(&deck)
        .arg("--json")
        .output()
        .unwrap();
    let report: serde_json::Value = serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("check --json: {e}: {}", String::from_utf8_lossy(&o.stderr)));
    let item = (report["items"].as_array().unwrap().iter())
        .find(|i| i["name"] == "geometric stiffness against the model")
        .unwrap_or_else(|| panic!("no geometric-stiffness check in {report}"));
    eprintln!("check --model: {item}");
    assert_eq!(item["pass"], true, "{item}");
    assert!(item["value"].as_f64().unwrap() < 1e-9, "{item}");
    // … and fails a file whose ω_z² term is 1e-6 off (the same file otherwise)
    let mut tampered = body.clone();
    if let Some(g) = tampered.geometric_stiffness.as_mut() {
        let f = (g.fields.iter_mut())
            .find(|f| f.load == UnitLoad::AngularVelocity([2, 2]))
            .unwrap();
        f.matrix.iter_mut().for_each(|v| *v *= 1.0 + 1e-6);
    }
    let bad = dir.join("tampered.flexbody");
    let bytes = flexbody::write::to_bytes(&tampered, &Default::default()).unwrap();
    std::fs::write(&bad, bytes).unwrap();
    let o = crate::common::exe()
        .arg("check")
        .arg(&bad)
        .arg("--model")
        .arg(&deck)
        .arg("--json")
        .output()
        .unwrap();
    assert!(!o.status.success(), "a tampered entry passed check --model");
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let item = (report["items"].as_array().unwrap().iter())
        .find(|i| i["name"] == "geometric stiffness against the model")
        .unwrap();
    eprintln!("check --model, tampered: {item}");
    assert_eq!(item["pass"], false, "{item}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Refused, never approximated: a build with a preload (its modes are those of K + K_G(σ₀)),
/// and an unknown `--geometric-stiffness` value; no file is written.
#[test]
fn geometric_stiffness_with_a_preload_or_an_unknown_value_is_refused() {
    let dir = crate::common::scratch("geometric_stiffness_refused");
    let deck = deck(&dir);
    let out = dir.join("refused.flexbody");
    for (extra, want) in [
        (
            &[
                "--geometric-stiffness",
                "inertia",
                "--load",
                "TIP:41:1000,0,0",
                "--preload",
                "TIP",
            ][..],
            "--geometric-stiffness with a preload",
        ),
        (&["--geometric-stiffness", "loads"][..], "inertia"),
    ] {
        let o = crate::common::exe()
            .arg("build")
            .arg(&deck)
            .args(["--units", "si", "--method", "normal", "--modes", "4", "-q"])
            .args(extra)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{extra:?} was built");
        assert!(stderr.contains(want), "{extra:?}: {stderr}");
        assert!(!out.exists(), "{extra:?}: a refused build wrote a file");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The same comparison through the command line on both sides, with the preload a deck's own
/// centrifugal load: a CalculiX cantilever of B31 beams (circular section, radius 0.02 m, L = 2,
/// clamped at node 1) with a `*STATIC` step of `*DLOAD … CENTRIF` about the z axis through the
/// root, and a plain `*FREQUENCY` step. Built with `--preload STEP_1` at three speeds (K + K_G
/// of the linear static state — no spin softening, as a multibody solver that spins the body
/// needs), its lowest frequency equals eig(K̂ + Ω² K̂_G,zz) of the unloaded build's file (80 modes: both bending planes, axial and torsion share the basis) to
/// 1e-6, and Wright et al. 1982 to 2e-4 (measured ≤ 3.2e-5).
#[test]
fn centrif_preloaded_builds_equal_the_files_terms() {
    let dir = crate::common::scratch("geometric_stiffness_centrif");
    let (r, l, ne) = (0.02f64, 2.0f64, 40usize);
    let area = std::f64::consts::PI * r * r;
    let inertia = std::f64::consts::PI * r.powi(4) / 4.0;
    let unit = (E * inertia / (RHO * area * l.powi(4))).sqrt();
    let deck_at = |omega: f64| {
        let mut s = String::from("*NODE, NSET=NALL\n");
        for i in 0..=ne {
            s += &format!("{}, {:?}, 0.0, 0.0\n", i + 1, l * i as f64 / ne as f64);
        }
        s += "*ELEMENT, TYPE=B31, ELSET=EALL\n";
        for e in 1..=ne {
            s += &format!("{e}, {e}, {}\n", e + 1);
        }
        s += &format!(
            "*BEAM SECTION, ELSET=EALL, MATERIAL=STEEL, SECTION=CIRC\n{r}\n0., 1., 0.\n\
             *MATERIAL, NAME=STEEL\n*ELASTIC\n{E:?}, 0.3\n*DENSITY\n{RHO:?}\n*BOUNDARY\n1, 1, 6\n\
             *STEP\n*STATIC\n*DLOAD\nEALL, CENTRIF, {:?}, 0., 0., 0., 0., 0., 1.\n*END STEP\n\
             *STEP\n*FREQUENCY\n4\n*END STEP\n",
            omega * omega
        );
        let path = dir.join(format!("centrif_{omega:.3}.inp"));
        std::fs::write(&path, s).unwrap();
        path
    };
    let build = |deck: &Path, extra: &[&str], out: &Path| {
        let o = crate::common::exe()
            .arg("build")
            .arg(deck)
            .args([
                "--units",
                "si",
                "--method",
                "normal",
                "--mass",
                "consistent",
            ])
            .args(extra)
            .args(["-q", "-o"])
            .arg(out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        flexbody_reader::read(out).unwrap()
    };
    let plain = build(
        &deck_at(unit),
        &["--modes", "80", "--geometric-stiffness", "inertia"],
        &dir.join("plain.flexbody"),
    );
    let g = plain.geometric_stiffness.as_ref().expect("the entry");
    let kg_zz = &(g.fields.iter())
        .find(|f| f.load == UnitLoad::AngularVelocity([2, 2]))
        .unwrap()
        .matrix;
    for &(om, want) in &[WRIGHT_1982[0], WRIGHT_1982[2], WRIGHT_1982[5]] {
        let omega = om * unit;
        let loaded = build(
            &deck_at(omega),
            &["--modes", "4", "--preload", "STEP_1"],
            &dir.join("loaded.flexbody"),
        );
        let f_build = 2.0 * std::f64::consts::PI * loaded.modes.frequency_hz[0];
        let f_file = lowest_with(&plain.modes.omega2, kg_zz, omega * omega).sqrt();
        let rel = (f_file - f_build) / f_build;
        let err = (f_file / unit - want) / want;
        eprintln!(
            "Ω̄ = {om:4.1}: ω̄ from the file {:.7}, --preload STEP_1 build {:.7} ({rel:+.1e}), \
             Wright et al. {want} ({err:+.1e})",
            f_file / unit,
            f_build / unit
        );
        assert!(rel.abs() < 1e-6, "Ω̄ = {om}: {f_file} vs {f_build}");
        // measured ≤ 3.2e-5 (Ω̄ = 4)
        assert!(err.abs() < 2e-4, "Ω̄ = {om}: {} vs {want}", f_file / unit);
    }
    std::fs::remove_dir_all(&dir).ok();
}
