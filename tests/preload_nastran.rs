//! Nastran `STATSUB(PRELOAD)` (issue 35): SOL 103 modes with the differential stiffness of a
//! static subcase, through the CLI. A pinned-pinned CBAR column under axial compression P and
//! tension: f(P)/f(0) = √(1 − P/P_cr) (Euler, P_cr = π²EI/L²) to 1e-3; the same as
//! `--preload LOAD_10` on the deck without STATSUB; `check --model` rebuilds it. What cannot be
//! honoured is refused naming the line: STATSUB(BUCKLE), a thermal static subcase, a static
//! subcase held differently from the modes', a STATSUB naming no subcase.

mod common;

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use common::{exe, scratch};
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

fn build(model: &Path, out: &Path, extra: &[&str]) -> (bool, String) {
    let o = exe()
        .arg("build")
        .arg(model)
        .args([
            "--units",
            "si",
            "--method",
            "normal",
            "--mass",
            "consistent",
        ])
        .args(extra)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
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
            "thermal.bdf:6: TEMP(LOAD) = 5",
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
