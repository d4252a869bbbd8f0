//! ANSYS's SHELL181 as ANSYS forms it (issue 50), through the CLI from archives, against ANSYS's
//! own static solutions (ansys-mapdl-reader's `tests/elements/shell181/` result files, converted
//! by `tests/data/ansys/make_shell181.py`):
//!
//! - a box of 240 SHELL181 (KEYOPT(3)=2, legacy real constant thickness): our K times ANSYS's
//!   displacements equals ANSYS's element nodal forces assembled (less the pressure load they
//!   hold) at every free dof;
//! - one SHELL181 on a `SECTYPE,SHELL` section, clamped, a force at its free edge: K u = F + R;
//! - layers of one material are one homogeneous shell;
//! - what is not formed is refused by its line naming the KEYOPT, shape or section line.

use std::collections::HashMap;
use std::path::Path;

use crate::ansys_support::{
    assert_refused_at, build, data, line_of, multiply, node_table, read_dofs,
};
use crate::common::scratch;

/// A solution csv of make_shell181.py: node id → [x y z, u (6), ANSYS's K u (6), force and
/// moment scale].
fn read_solution(name: &str) -> HashMap<u64, [f64; 17]> {
    node_table(&std::fs::read_to_string(data(name)).unwrap(), 1)
}

/// Builds the archive `name` with `--write-matrices` and returns max over the free dofs of
/// |K u − (K u)_ANSYS| / scale, u ANSYS's displacements, and the number of dofs.
fn residual_against_ansys(name: &str, solution: &str, modes: usize) -> (f64, usize) {
    let dir = scratch(&format!("ansys-{name}"));
    let cdb = dir.join(name);
    std::fs::copy(data(name), &cdb).unwrap();
    let mats = dir.join("mats");
    let o = build(
        &cdb,
        "mm-t-s",
        modes,
        &["--write-matrices", mats.to_str().unwrap()],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let dofs = read_dofs(&mats.join("dofs.txt"));
    let solution = read_solution(solution);
    let u: Vec<f64> = dofs.iter().map(|&(n, c)| solution[&n][3 + c]).collect();
    let ku = multiply(&mats.join("K.mtx"), &u);
    let worst = (dofs.iter().zip(&ku))
        .map(|(&(n, c), k)| {
            let s = &solution[&n];
            (k - s[9 + c]).abs() / s[15 + c / 3]
        })
        .fold(0.0f64, f64::max);
    let _ = std::fs::remove_dir_all(&dir);
    (worst, dofs.len())
}

/// SHELL181 KEYOPT(3)=2 against ANSYS 18.2's static solution of a box of 240 elements
/// (thickness 15 by R, pressure 0.1 on faces, 40 nodes held): at each of the 1440 free dofs our
/// K u equals ANSYS's assembled element forces to their single-precision rounding.
///
/// Measured 1.1e-7 of the largest element force (moment) at the node. The same check in numpy
/// (once) leaves 2.3e-2 without ANSYS's transverse shear factor 1/(1 + A/(160 000 t²)) and
/// 1.1e-2 with flexbody's default drilling penalty (10⁻⁴ G t) in place of ANSYS's (1/200 of the
/// scaled shear rigidity): the element forces tell them apart.
#[test]
fn shell181_box_equals_ansys_element_forces() {
    let (worst, n) = residual_against_ansys("shell181_box.cdb", "shell181_box_solution.csv", 12);
    assert_eq!(n, (280 - 40) * 6, "every free node's six dofs");
    println!("SHELL181 box: max |K u − (K u)_ANSYS| / ENF scale = {worst:.2e}");
    assert!(worst < 1e-6, "{worst:e}");
}

/// One SHELL181 KEYOPT(3)=2 on `SECTYPE,1,SHELL` / `SECDATA,5` (ANSYS 17.2), clamped at one
/// edge, FX = 250 at each free node: K u = F + R at all 12 free dofs. Measured 6.0e-14 of the
/// load 500 (moments: of 500 × 61.85); ANSYS's shear factor s = 0.99933 here, and the check
/// without it (numpy, once) leaves 1.0e-2.
#[test]
fn shell181_on_a_shell_section_equals_ansys_cantilever() {
    let (worst, n) = residual_against_ansys("shell181_one.cdb", "shell181_one_solution.csv", 4);
    assert_eq!(n, 12);
    println!("SHELL181 on a section: max |K u − F − R| / load scale = {worst:.2e}");
    assert!(worst < 5e-13, "{worst:e}");
}

/// SHELL181's drilling penalty was shown to be ANSYS's only for elements larger than 100 t²
/// (docs/ansys.md): a build of smaller ones says so. The one-element cantilever (61.85 × 43.5,
/// t = 5: A = 107.6 t²) builds without the warning; the same element 10 thick (A = 26.9 t²)
/// builds with it, naming the element's line.
#[test]
fn shell181_smaller_than_100_t2_warns_about_its_drilling_stiffness() {
    let dir = scratch("ansys-shell181-drill-warning");
    let text = std::fs::read_to_string(data("shell181_one.cdb")).unwrap();
    let thick = text.replace("SECDATA,  5.0,", "SECDATA, 10.0,");
    assert_ne!(thick, text);
    let mut said = Vec::new();
    for (name, deck) in [("t5.cdb", &text), ("t10.cdb", &thick)] {
        let path = dir.join(name);
        std::fs::write(&path, deck).unwrap();
        let o = build(&path, "mm-t-s", 4, &[]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        said.push(
            err.lines()
                .find(|l| l.contains("drilling stiffness"))
                .map(str::to_string),
        );
    }
    assert_eq!(said[0], None, "A = 107.6 t²: no warning");
    let warned = said[1].clone().expect("A = 26.9 t²: the drilling warning");
    let line = line_of(&thick, "        4        0        1        2");
    assert!(
        warned.contains("1 SHELL181 element(s)") && warned.contains(&format!("line {line}")),
        "{warned}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Frequencies of a normal-modes build of `text` written as `name` (it must succeed).
fn frequencies(dir: &Path, name: &str, text: &str) -> Vec<f64> {
    let cdb = dir.join(name);
    std::fs::write(&cdb, text).unwrap();
    let o = build(&cdb, "mm-t-s", 4, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    flexbody_reader::read(cdb.with_extension("flexbody"))
        .unwrap()
        .modes
        .frequency_hz
}

/// Two SECDATA layers of 2 and 3 of the section's material (one with 5 integration points)
/// are the one layer of 5: the same body (0 difference: the same section is formed).
#[test]
fn layers_of_one_material_are_one_homogeneous_shell() {
    let one = std::fs::read_to_string(data("shell181_one.cdb")).unwrap();
    let layered = one.replace(
        "SECDATA,  5.0,  1,  0.0,  3",
        "SECDATA,  2.0,  1,  0.0,  3\nSECDATA,  3.0,  0, 45.0,  5",
    );
    assert_ne!(one, layered);
    let dir = scratch("ansys-shell-layers");
    let a = frequencies(&dir, "one.cdb", &one);
    let b = frequencies(&dir, "layered.cdb", &layered);
    assert_eq!(a, b);
    let _ = std::fs::remove_dir_all(&dir);
}

/// What is not formed is refused by its line naming the KEYOPT, the shape or the section line:
/// SHELL181's default KEYOPT(3)=0, the membrane option, repeated nodes other than ANSYS's
/// degenerate triangle K = L (formed: tests/ansys_shell181_triangle.rs); a laminate
/// of two materials, a TOP offset (at the SHELL181's record: SHELL281 forms it), a drill
/// stiffness factor, one integration point.
#[test]
fn unformed_shell181_options_are_refused_by_line() {
    let mut s = String::from(
        "ET,        1,181\nKEYOP,        1, 3,        2\nET,        2,181\nET,        3,181\n\
         KEYOP,        3, 1,        1\nKEYOP,        3, 3,        2\n",
    );
    s += "SECTYPE,       1,SHELL,,\nSECDATA,  1.0,  1,  0.0,  3\nSECDATA,  1.0,  2,  0.0,  3\n";
    s += "SECTYPE,       2,SHELL,,\nSECDATA,  1.0,  1,  0.0,  3\nSECOFFSET,TOP\n";
    s += "SECTYPE,       3,SHELL,,\nSECDATA,  1.0,  1,  0.0,  1\n";
    s += "SECTYPE,       4,SHELL,,\nSECDATA,  1.0,  1,  0.0,  3\nSECCONTROL,0,0,0,0,1,1,2\n";
    s += "SECTYPE,       5,SHELL,,\nSECDATA,  1.0,  1,  0.0,  3\n";
    s += "NBLOCK,6,SOLID,         4,         4\n(3i9,6e21.13e3)\n";
    for (id, x) in [
        (1, [0.0, 0.0]),
        (2, [1.0, 0.0]),
        (3, [1.0, 1.0]),
        (4, [0.0, 1.0]),
    ] {
        s += &format!(
            "{id:>9}{0:>9}{0:>9}{:>21.13E}{:>21.13E}{:>21.13E}\n",
            x[0], x[1], 0.0
        );
    }
    s += "N,R5.3,LOC,       -1,\nEBLOCK,19,SOLID,         5,         5\n(19i9)\n";
    // (type, section, nodes): the default KEYOPT(3), the membrane option, a triangle J = K, the
    // laminate section, the TOP offset
    let records: [(u64, u64, [u64; 4]); 5] = [
        (2, 5, [1, 2, 3, 4]),
        (3, 5, [1, 2, 3, 4]),
        (1, 5, [1, 2, 2, 3]),
        (1, 1, [1, 2, 3, 4]),
        (1, 2, [1, 2, 3, 4]),
    ];
    for (k, (etype, section, n)) in records.iter().enumerate() {
        let head = [1, *etype, 1, *section, 0, 0, 0, 0, 4, 0, 10 + k as u64];
        s += &head
            .iter()
            .chain(n)
            .map(|v| format!("{v:>9}"))
            .collect::<String>();
        s.push('\n');
    }
    s += "       -1\nMPTEMP,R5.0, 1, 1,  0.00000000    ,\n";
    for m in [1, 2] {
        for (label, v) in [("EX", 2.0e5), ("NUXY", 0.3), ("DENS", 7.85e-9)] {
            s += &format!("MPDATA,R5.0, 1,{label:<4},       {m}, 1, {v:e},\n");
        }
    }
    let first = line_of(&s, "(19i9)") + 1;
    let offset = format!(
        "SHELL181 on a section offset to its top surface (SECOFFSET line {})",
        line_of(&s, "SECOFFSET,TOP")
    );
    let expected = [
        (first, "SHELL181 KEYOPT(3)=0 (the default"),
        (first + 1, "SHELL181 KEYOPT(1)=1"),
        (first + 2, "other than ANSYS's degenerate triangle"),
        (first + 3, "layers of different materials"),
        (first + 4, offset.as_str()),
        (
            line_of(&s, "SECDATA,  1.0,  1,  0.0,  1"),
            "1 integration point(s)",
        ),
        (line_of(&s, "SECCONTROL"), "drill stiffness factor 2"),
    ];
    assert_refused_at(&s, "ansys-shell-refusals", "mm-t-s", &expected);
}
