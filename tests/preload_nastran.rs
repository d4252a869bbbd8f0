//! Nastran `STATSUB(PRELOAD)` (issue 35): SOL 103 modes with the differential stiffness of a
//! static subcase, through the CLI. A pinned-pinned CBAR column under axial compression P and
//! tension: f(P)/f(0) = √(1 − P/P_cr) (Euler, P_cr = π²EI/L²) to 1e-3; the same as
//! `--preload LOAD_10` on the deck without STATSUB; `check --model` rebuilds it. A thermal
//! preload (TEMP(LOAD), MAT1 A/TREF) of a column held at both ends: Euler again. What cannot be
//! honoured is refused naming the line: STATSUB(BUCKLE), a temperature set the bulk data lacks,
//! a static subcase held differently from the modes', a STATSUB naming no subcase.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use crate::common::{build_as_ccx, exe, scratch};
use flexbody_reader as file;

const L: f64 = 2.0;
const NE: usize = 40;
const W: f64 = 0.03; // element y (orientation vector along y): I1 = H W³/12
const H: f64 = 0.02; // element z: the weak plane x–z, I2 = W H³/12
const E: f64 = 2.1e11;

fn p_cr() -> f64 {
    PI * PI * E * (W * H.powi(3) / 12.0) / (L * L)
}

/// The column: grid 1 holds u, v, w and the twist, the last grid v and w; FORCE at the last
/// grid along x (P < 0 compresses). `case` is the case control after CEND.
fn deck(dir: &Path, name: &str, case: &str, p: f64) -> PathBuf {
    let mut s = format!(
        "SOL 103\nCEND\n{case}BEGIN BULK\nEIGRL,20,,,6\nMAT1,1,{E:?},,0.3,7850.\n\
         PBAR,2,1,{:?},{:?},{:?},{:?}\n",
        W * H,
        H * W.powi(3) / 12.0,
        W * H.powi(3) / 12.0,
        0.1406 * W * H.powi(3) * 1.2
    );
    for i in 0..=NE {
        s += &format!("GRID,{},,{:?},0.,0.\n", i + 1, L * i as f64 / NE as f64);
    }
    for i in 1..=NE {
        s += &format!("CBAR,{i},2,{i},{},0.,1.,0.\n", i + 1);
    }
    s += &format!(
        "SPC1,1,1234,1\nSPC1,1,23,{}\nFORCE,10,{},,{p:?},1.,0.,0.\nENDDATA\n",
        NE + 1,
        NE + 1
    );
    let path = dir.join(name);
    std::fs::write(&path, s).unwrap();
    path
}

const STATSUB: &str =
    "SPC = 1\nSUBCASE 1\n  LOAD = 10\nSUBCASE 2\n  STATSUB(PRELOAD) = 1\n  METHOD = 20\n";
const PLAIN: &str = "SPC = 1\nMETHOD = 20\n";

/// `crate::common::build_as_ccx` (normal modes, consistent mass, SI): success and stderr.
fn build(model: &Path, out: &Path, extra: &[&str]) -> (bool, String) {
    let o = build_as_ccx(model, extra, out);
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

fn first_hz(out: &Path) -> f64 {
    file::read(out).unwrap().modes.frequency_hz[0]
}

#[test]
fn statsub_preload_stiffens_and_softens_a_column_as_euler_says() {
    let dir = scratch("statsub");
    let unloaded = deck(&dir, "plain.bdf", PLAIN, 0.0);
    let (ok, err) = build(&unloaded, &dir.join("f0.flexbody"), &[]);
    assert!(ok, "{err}");
    let f0 = first_hz(&dir.join("f0.flexbody"));
    for (name, ratio) in [("compressed", -0.5), ("stretched", 0.8)] {
        let p = ratio * p_cr();
        let bdf = deck(&dir, &format!("{name}.bdf"), STATSUB, p);
        let out = dir.join(format!("{name}.flexbody"));
        let (ok, err) = build(&bdf, &out, &[]);
        assert!(ok, "{name}: {err}");
        let f = first_hz(&out);
        let exact = (1.0 + ratio).sqrt();
        println!("{name}: f/f0 = {} vs Euler {exact}", f / f0);
        assert!(
            (f / f0 - exact).abs() < 1e-3 * exact,
            "{name}: {} vs {exact}",
            f / f0
        );
        // the recipe names the static subcase; check rebuilds the preload
        let body = file::read(&out).unwrap();
        let recipe = body.recipe.as_ref().unwrap();
        let pre = recipe.preload.as_ref().expect("recipe preload");
        assert!(
            pre.source.contains("static subcase 1 (STATSUB(PRELOAD)"),
            "{pre:?}"
        );
        let o = exe()
            .arg("check")
            .arg(&out)
            .arg("--model")
            .arg(&bdf)
            .output()
            .unwrap();
        let report = String::from_utf8_lossy(&o.stdout);
        assert!(
            o.status.success() && report.contains("preload as built"),
            "{report}"
        );
        // the same preload given on the command line, deck without STATSUB
        let plain = deck(&dir, &format!("{name}-plain.bdf"), PLAIN, p);
        let out2 = dir.join(format!("{name}-cli.flexbody"));
        let (ok, err) = build(&plain, &out2, &["--preload", "LOAD_10"]);
        assert!(ok, "{name}: {err}");
        let g = first_hz(&out2);
        assert!(
            (f - g).abs() < 1e-10 * f,
            "{name}: STATSUB {f} vs --preload {g}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn statsub_preloads_the_tool_cannot_apply_are_refused_by_line() {
    let dir = scratch("statsub-refused");
    let cases: [(&str, &str, &str); 4] = [
        (
            "buckle",
            "SPC = 1\nSUBCASE 1\n  LOAD = 10\nSUBCASE 2\n  STATSUB(BUCKLE) = 1\n  METHOD = 20\n",
            "buckle.bdf:7: STATSUB(BUCKLE) (case control)",
        ),
        (
            "thermal",
            "SPC = 1\nSUBCASE 1\n  LOAD = 10\n  TEMP(LOAD) = 5\nSUBCASE 2\n  STATSUB(PRELOAD) = 1\n  METHOD = 20\n",
            "thermal.bdf:6: TEMP(LOAD) = 5: the bulk data has no TEMP or TEMPD of set 5",
        ),
        (
            "supports",
            "SUBCASE 1\n  SPC = 2\n  LOAD = 10\nSUBCASE 2\n  SPC = 1\n  STATSUB(PRELOAD) = 1\n  METHOD = 20\n",
            "supports.bdf:8: STATSUB(PRELOAD) = 1",
        ),
        (
            "missing",
            "SPC = 1\nSUBCASE 2\n  STATSUB(PRELOAD) = 7\n  METHOD = 20\n",
            "the deck has no SUBCASE 7",
        ),
    ];
    for (name, case, expect) in cases {
        let bdf = deck(&dir, &format!("{name}.bdf"), case, -1000.0);
        let out = dir.join(format!("{name}.flexbody"));
        let (ok, err) = build(&bdf, &out, &[]);
        assert!(!ok, "{name}: built");
        assert!(err.contains(expect), "{name}: {err}");
        assert!(!out.exists(), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A thermal preload: the column held axially at both ends and heated by ΔT from TREF
/// (MAT1 A = α, TREF; TEMPD default or TEMP per grid) carries N = −EAαΔT: f/f0 = √(1 − N/P_cr)
/// (Euler) to 1e-3, the same with the temperatures given grid by grid; two expanding materials
/// with different TREF are refused naming the card.
#[test]
fn statsub_thermal_preload_compresses_a_held_column_as_euler_says() {
    let dir = scratch("statsub-thermal");
    let alpha = 1.2e-5;
    let dt = 0.5 * p_cr() / (E * W * H * alpha);
    let held = |name: &str, case: &str, extra: &str| {
        let path = deck(&dir, name, case, 0.0);
        let text = std::fs::read_to_string(&path).unwrap();
        let text = text
            .replace(
                &format!("MAT1,1,{E:?},,0.3,7850.\n"),
                &format!("MAT1,1,{E:?},,0.3,7850.,{alpha:?},20.\n"),
            )
            .replace(
                &format!("SPC1,1,23,{}\n", NE + 1),
                &format!("SPC1,1,123,{}\n", NE + 1),
            )
            .replace("ENDDATA\n", &format!("{extra}ENDDATA\n"));
        std::fs::write(&path, text).unwrap();
        path
    };
    let thermal =
        "SPC = 1\nSUBCASE 1\n  TEMP(LOAD) = 5\nSUBCASE 2\n  STATSUB(PRELOAD) = 1\n  METHOD = 20\n";
    let plain = held("held.bdf", PLAIN, "");
    let (ok, err) = build(&plain, &dir.join("f0.flexbody"), &[]);
    assert!(ok, "{err}");
    let f0 = first_hz(&dir.join("f0.flexbody"));
    let exact = 0.5f64.sqrt();
    let tempd = held("tempd.bdf", thermal, &format!("TEMPD,5,{:?}\n", 20.0 + dt));
    let by_grid: String = (1..=NE + 1)
        .map(|g| format!("TEMP,5,{g},{:?}\n", 20.0 + dt))
        .collect();
    let temp = held("temp.bdf", thermal, &by_grid);
    let mut got = Vec::new();
    for path in [&tempd, &temp] {
        let out = path.with_extension("flexbody");
        let (ok, err) = build(path, &out, &[]);
        assert!(ok, "{err}");
        let f = first_hz(&out);
        println!("{}: f/f0 = {} vs Euler {exact}", path.display(), f / f0);
        assert!(
            (f / f0 - exact).abs() < 1e-3 * exact,
            "{} vs {exact}",
            f / f0
        );
        got.push(f);
    }
    assert!((got[0] - got[1]).abs() < 1e-12 * got[0], "{got:?}");
    // two expanding materials from different reference temperatures
    let two = held(
        "tref.bdf",
        thermal,
        &format!("TEMPD,5,30.\nMAT1,3,{E:?},,0.3,7850.,{alpha:?},0.\n"),
    );
    let (ok, err) = build(&two, &dir.join("tref.flexbody"), &[]);
    assert!(
        !ok && err.contains("MAT1 3") && err.contains("TREF"),
        "{err}"
    );
    // a grid of an element without a temperature, no TEMPD default
    let partial = held("partial.bdf", thermal, "TEMP,5,1,30.\n");
    let (ok, err) = build(&partial, &dir.join("partial.flexbody"), &[]);
    assert!(
        !ok && err.contains("grid 2 has no temperature in set 5"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A pressure (PLOAD4 on CQUAD4s) in the static subcase that STATSUB names: MSC adds the
/// pressure's follower stiffness (PARAM,FOLLOWK), not formed here — refused naming the load,
/// with the dead-load alternative `--preload LOAD_10`, which builds.
#[test]
fn statsub_pressure_preload_is_refused_as_a_follower_load() {
    let mut s = format!(
        "SOL 103\nCEND\n{STATSUB}BEGIN BULK\nEIGRL,20,,,4\nMAT1,1,{E:?},,0.3,7850.\nPSHELL,1,1,0.01,1,,1\n"
    );
    let id = |i: usize, j: usize| 1 + i + 5 * j;
    for j in 0..5 {
        for i in 0..5 {
            s += &format!(
                "GRID,{},,{:?},{:?},0.\n",
                id(i, j),
                0.25 * i as f64,
                0.25 * j as f64
            );
            if i == 0 {
                s += &format!("SPC1,1,123456,{}\n", id(i, j));
            }
        }
    }
    for j in 0..4 {
        for i in 0..4 {
            let e = 1 + i + 4 * j;
            s += &format!(
                "CQUAD4,{e},1,{},{},{},{}\nPLOAD4,10,{e},1000.\n",
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j + 1)
            );
        }
    }
    s += "ENDDATA\n";
    let dir = scratch("statsub-pressure");
    let path = dir.join("plate.bdf");
    std::fs::write(&path, s).unwrap();
    let (ok, err) = build(&path, &dir.join("plate.flexbody"), &[]);
    assert!(!ok);
    for w in ["LOAD_10", "pressure", "FOLLOWK", "--preload LOAD_10"] {
        assert!(err.contains(w), "missing '{w}' in {err}");
    }
    assert!(!dir.join("plate.flexbody").exists());
    let plain = dir.join("plain.bdf");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace(STATSUB, PLAIN);
    std::fs::write(&plain, text).unwrap();
    let (ok, err) = build(
        &plain,
        &dir.join("plain.flexbody"),
        &["--preload", "LOAD_10"],
    );
    assert!(ok, "{err}");
}
