//! A model of several disconnected parts (issue 32, CalculiX's damper1): the rigid-body modes the
//! build's verification and `check` expect are the free motions summed over the parts, each
//! part less what its own constraints hold — a clamped bar 0, a free bar 6, a bar held along x
//! on one end face 3 (y and z translations and the rotation about x stay free) — counted by hand
//! here, not from the file's reference conditions of the whole body (0 for all of them).

use std::path::{Path, PathBuf};

use crate::common::{exe, scratch};
use flexbody_reader as file;

/// A steel bar of `n` C3D8 elements along x (1 m × 0.1 m × 0.1 m) starting at `x0`, node ids
/// from `base + 1`, element ids from `base + 1`, end face x = x0 in node set `END<base>`.
fn bar(base: u64, x0: f64, n: u64) -> String {
    let mut s = String::from("*NODE\n");
    let (l, h) = (1.0 / n as f64, 0.1);
    for i in 0..=n {
        for (k, (y, z)) in [(0.0, 0.0), (h, 0.0), (h, h), (0.0, h)].iter().enumerate() {
            s += &format!(
                "{}, {}, {y}, {z}\n",
                base + 4 * i + k as u64 + 1,
                x0 + l * i as f64
            );
        }
    }
    s += "*ELEMENT, TYPE=C3D8, ELSET=EALL\n";
    for e in 0..n {
        let a = base + 4 * e;
        s += &format!(
            "{}, {}, {}, {}, {}, {}, {}, {}, {}\n",
            base + e + 1,
            a + 1,
            a + 2,
            a + 3,
            a + 4,
            a + 5,
            a + 6,
            a + 7,
            a + 8
        );
    }
    s += &format!(
        "*NSET, NSET=END{base}\n{}, {}, {}, {}\n",
        base + 1,
        base + 2,
        base + 3,
        base + 4
    );
    s
}

/// A deck of the bars `(base, x0, held dofs of the end face or "")`.
fn deck(dir: &Path, name: &str, bars: &[(u64, f64, &str)]) -> PathBuf {
    let mut s = String::new();
    for &(base, x0, _) in bars {
        s += &bar(base, x0, 6);
    }
    s += "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7800.\n";
    s += "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n";
    for &(base, _, held) in bars.iter().filter(|b| !b.2.is_empty()) {
        s += &format!("*BOUNDARY\nEND{base}, {held}\n");
    }
    s += "*STEP\n*FREQUENCY\n16\n*END STEP\n";
    let path = dir.join(format!("{name}.inp"));
    std::fs::write(&path, s).unwrap();
    path
}

/// Builds `deck` (16 modes, lumped mass) and reads the file; panics with stderr on failure.
fn build(deck: &Path) -> file::ReducedBody {
    let out = deck.with_extension("flexbody");
    let o = exe()
        .arg("build")
        .arg(deck)
        .args(["--units", "si", "--method", "normal", "-q", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{}: {}",
        deck.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    file::read(&out).unwrap()
}

fn rigid_count(body: &file::ReducedBody) -> usize {
    (body.modes.labels.iter())
        .filter(|l| **l == file::ModeLabel::Rigid)
        .count()
}

/// `flexbody check FILE [--model DECK]`: exit code and the rigid-body mode line.
fn check(body_file: &Path, model: Option<&Path>) -> (bool, String) {
    let mut c = exe();
    c.arg("check").arg(body_file);
    if let Some(m) = model {
        c.arg("--model").arg(m);
    }
    let o = c.output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let line = text
        .lines()
        .find(|l| l.contains("rigid-body modes as expected"))
        .unwrap_or_default()
        .to_owned();
    (o.status.success(), line)
}

/// The elastic frequencies (modes not labelled rigid).
fn elastic(body: &file::ReducedBody) -> Vec<f64> {
    (body.modes.frequency_hz.iter().zip(&body.modes.labels))
        .filter(|(_, l)| **l != file::ModeLabel::Rigid)
        .map(|(f, _)| *f)
        .collect()
}

#[test]
fn clamped_and_free_bars_have_the_free_bars_six_rigid_modes() {
    let dir = scratch("multi-part-free");
    let both = deck(&dir, "both", &[(0, 0.0, "1, 3"), (1000, 2.0, "")]);
    let body = build(&both);
    assert_eq!(rigid_count(&body), 6, "{:?}", body.modes.frequency_hz);
    // the file's reference conditions (the clamped face) leave 0: the build counted the parts
    assert!(!body.method.reference_conditions.is_empty());
    let (ok, line) = check(&both.with_extension("flexbody"), None);
    assert!(
        ok && line.contains("expected 6 (the build's count"),
        "{line}"
    );
    let (ok, line) = check(&both.with_extension("flexbody"), Some(&both));
    assert!(
        ok && line.contains("expected 6 (the model's 2 connected parts")
            && line.contains(": 6 free")
            && line.contains(": 0 free"),
        "{line}"
    );
    // the parts do not interact: the elastic modes are the clamped bar's and the free bar's
    let clamped = build(&deck(&dir, "clamped", &[(0, 0.0, "1, 3")]));
    let free = build(&deck(&dir, "free", &[(1000, 2.0, "")]));
    assert_eq!(rigid_count(&clamped), 0);
    assert_eq!(rigid_count(&free), 6);
    let mut merged: Vec<f64> = elastic(&clamped)
        .into_iter()
        .chain(elastic(&free))
        .collect();
    merged.sort_by(f64::total_cmp);
    let ours = elastic(&body);
    assert_eq!(ours.len(), 10);
    for (a, b) in ours.iter().zip(&merged) {
        assert!((a - b).abs() <= 1e-8 * b, "{ours:?} against {merged:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bar_held_along_x_on_one_face_keeps_three_rigid_motions() {
    let dir = scratch("multi-part-partly");
    let path = deck(&dir, "partly", &[(0, 0.0, "1, 3"), (1000, 2.0, "1, 1")]);
    let body = build(&path);
    // ux held on a face holds the x translation and the rotations about y and z
    assert_eq!(rigid_count(&body), 3, "{:?}", body.modes.frequency_hz);
    let (ok, line) = check(&path.with_extension("flexbody"), Some(&path));
    assert!(
        ok && line.contains("expected 3") && line.contains(": 3 free"),
        "{line}"
    );
    // a free third bar beside it: two loose parts are two bodies, refused naming both
    let three = deck(
        &dir,
        "three",
        &[(0, 0.0, "1, 3"), (1000, 2.0, "1, 1"), (2000, 4.0, "")],
    );
    let o = exe()
        .arg("build")
        .arg(&three)
        .args(["--units", "si", "--method", "normal", "-q", "-o"])
        .arg(dir.join("three.flexbody"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success()
            && err.contains("2 disconnected parts")
            && err.contains("ids 2001–2006"),
        "{err}"
    );
    assert!(!dir.join("three.flexbody").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A chain of `n` point masses `m` (`*MASS`) joined by axial springs `k` (SPRINGA) along x, 1 m
/// apart, held laterally (`*BOUNDARY` 2-3 on every node) and, with `grounded`, along x at node 1.
fn chain(dir: &Path, name: &str, n: u64, k: f64, m: f64, grounded: bool) -> PathBuf {
    let mut s = String::from("*NODE, NSET=NALL\n");
    for i in 1..=n {
        s += &format!("{i}, {}, 0., 0.\n", (i - 1) as f64);
    }
    s += "*ELEMENT, TYPE=SPRINGA, ELSET=SPR\n";
    for i in 1..n {
        s += &format!("{i}, {i}, {}\n", i + 1);
    }
    s += "*ELEMENT, TYPE=MASS, ELSET=MS\n";
    for i in 1..=n {
        s += &format!("{}, {i}\n", 100 + i);
    }
    s += &format!("*SPRING, ELSET=SPR\n\n{k}\n*MASS, ELSET=MS\n{m}\n*BOUNDARY\nNALL, 2, 3\n");
    if grounded {
        s += "*BOUNDARY\n1, 1, 1\n";
    }
    s += &format!("*STEP\n*FREQUENCY\n{}\n*END STEP\n", n - 1);
    let path = dir.join(format!("{name}.inp"));
    std::fs::write(&path, s).unwrap();
    path
}

#[test]
fn a_collinear_spring_mass_chain_has_no_rotation_about_its_line() {
    // translations only, on one line: the rotation about it moves no dof and carries no inertia;
    // the build's verification (and `check`) expected it as a rigid mode ("expected 1")
    let dir = scratch("chain");
    let (n, k, m) = (6u64, 1000.0, 2.0);
    let hz = |w2: f64| w2.sqrt() / (2.0 * std::f64::consts::PI);
    // free along x: ω_j² = (4k/m) sin²(jπ/2n), j = 0 … n−1 (j = 0: the translation)
    let free = build(&chain(&dir, "free", n, k, m, false));
    assert_eq!(rigid_count(&free), 1, "{:?}", free.modes.frequency_hz);
    let exact: Vec<f64> = (1..n - 1)
        .map(|j| {
            let s = (j as f64 * std::f64::consts::PI / (2.0 * n as f64)).sin();
            hz(4.0 * k / m * s * s)
        })
        .collect();
    for (a, b) in elastic(&free).iter().zip(&exact) {
        // measured: 2.4e-16
        assert!((a - b).abs() <= 4e-15 * b, "{a} against {b}");
    }
    assert_eq!(elastic(&free).len(), exact.len());
    // grounded at node 1: the n − 1 masses of a fixed-free chain, ω_j² = (4k/m)
    // sin²((2j−1)π / (2(2n−1))), j = 1 … n−1, no rigid mode
    let grounded = build(&chain(&dir, "grounded", n, k, m, true));
    assert_eq!(rigid_count(&grounded), 0);
    let exact: Vec<f64> = (1..n)
        .map(|j| {
            let s = ((2 * j - 1) as f64 * std::f64::consts::PI / (2.0 * (2 * n - 1) as f64)).sin();
            hz(4.0 * k / m * s * s)
        })
        .collect();
    let ours = elastic(&grounded);
    assert_eq!(ours.len(), exact.len());
    for (a, b) in ours.iter().zip(&exact) {
        // measured: 9.0e-16
        assert!((a - b).abs() <= 9e-15 * b, "{a} against {b}");
    }
    for path in [dir.join("free.flexbody"), dir.join("grounded.flexbody")] {
        let (ok, line) = check(&path, None);
        assert!(ok, "{line}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
