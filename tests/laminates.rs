//! Composite shells (issue 34), what exists today: a PCOMP of one isotropic material is the
//! PSHELL of the same material and total thickness (to 1e-10 on the frequencies of a free
//! plate of CQUAD4 and CTRIA3); laminates are not formed yet, and every card or keyword that
//! asks for one is an error naming it and its line (PCOMP plies of several materials, MAT8,
//! MAT2, MAT9 on a shell, `*SHELL SECTION, COMPOSITE`, `*ELASTIC, TYPE=LAMINA`), never a
//! silently isotropic plate.

mod common;

use common::{build_as_ccx, scratch};
use flexbody_reader as file;
use std::fmt::Write as _;

/// A 0.4 × 0.3 m plate of 8 × 6 CQUAD4 (CTRIA3 in the last column) with the property and
/// material lines `cards`, free, 12 modes.
fn plate(cards: &str) -> String {
    let (nx, ny, a, b) = (8, 6, 0.4, 0.3);
    let mut s = String::from("SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\nEIGRL,1,,,12\n");
    s.push_str(cards);
    let id = |i: usize, j: usize| 1 + i + (nx + 1) * j;
    for j in 0..=ny {
        for i in 0..=nx {
            let (x, y) = (a * i as f64 / nx as f64, b * j as f64 / ny as f64);
            writeln!(s, "GRID,{},,{x},{y},0.", id(i, j)).unwrap();
        }
    }
    let mut e = 0;
    for j in 0..ny {
        for i in 0..nx {
            let c = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            e += 1;
            if i + 1 == nx {
                writeln!(s, "CTRIA3,{e},1,{},{},{}", c[0], c[1], c[2]).unwrap();
                e += 1;
                writeln!(s, "CTRIA3,{e},1,{},{},{}", c[0], c[2], c[3]).unwrap();
            } else {
                writeln!(s, "CQUAD4,{e},1,{},{},{},{}", c[0], c[1], c[2], c[3]).unwrap();
            }
        }
    }
    s.push_str("ENDDATA\n");
    s
}

fn build(name: &str, deck: &str, ext: &str) -> Result<file::ReducedBody, String> {
    let dir = scratch(&format!("laminates-{name}"));
    let path = dir.join(format!("{name}.{ext}"));
    std::fs::write(&path, deck).unwrap();
    let out = dir.join(format!("{name}.flexbody"));
    let o = build_as_ccx(&path, &["-q"], &out);
    if !o.status.success() {
        return Err(String::from_utf8_lossy(&o.stderr).into_owned());
    }
    Ok(file::read(&out).unwrap())
}

const MAT1: &str = "MAT1,7,7.e10,,0.33,2700.\n";

/// Three plies of one aluminium (0/45/90: an isotropic material turns into itself) are the
/// PSHELL of the total thickness with MID2 = MID3 = MID1, 12I/T³ = 1, TS/T = 5/6.
#[test]
fn one_material_pcomp_equals_pshell() {
    let pshell = build(
        "pshell",
        &plate(&format!("{MAT1}PSHELL,1,7,0.006,7,1.,7,0.833333333333\n")),
        "bdf",
    )
    .unwrap();
    let pcomp = build(
        "pcomp",
        &plate(&format!(
            "{MAT1}PCOMP,1\n,7,0.002,0.,YES,7,0.002,45.,YES\n,7,0.002,90.,YES\n"
        )),
        "bdf",
    )
    .unwrap();
    let (a, b) = (&pshell.modes.frequency_hz, &pcomp.modes.frequency_hz);
    assert_eq!(a.len(), b.len());
    // six rigid modes, then the plate's
    for (x, y) in a.iter().zip(b).skip(6) {
        assert!((x / y - 1.0).abs() < 1e-10, "{x} {y}");
    }
    assert!(a[6] > 1.0, "{a:?}");
}

/// Each way of asking for a laminate is an error naming the card or keyword and its line.
#[test]
fn laminates_are_refused_by_card_and_line() {
    let nastran = [
        (
            "two-materials",
            format!("{MAT1}MAT1,8,2.e11,,0.3,7800.\nPCOMP,1\n,7,0.002,0.,YES,8,0.002,90.,YES\n"),
            vec!["bdf:8: PCOMP 1", "plies of different materials"],
        ),
        (
            "mat8",
            "MAT8,7,1.4e11,1.e10,0.3,5.e9,5.e9,3.e9,1600.\nPCOMP,1\n,7,0.002,0.,YES\n".to_owned(),
            vec!["bdf:6", "MAT8"],
        ),
        (
            "mat2",
            "MAT2,7,1.e11,3.e10,0.,1.e11,0.,3.5e10,2700.\nPSHELL,1,7,0.006,7\n".to_owned(),
            vec!["bdf:6", "MAT2"],
        ),
        (
            "mat9-shell",
            "MAT9,7,1.e11,3.e10,3.e10,0.,0.,0.,1.e11\n,3.e10,0.,0.,0.,1.e11,0.,0.,0.\n\
             ,3.5e10,0.,0.,3.5e10,0.,3.5e10,2700.\nPSHELL,1,7,0.006,7\n"
                .to_owned(),
            vec!["MAT9 7", "anisotropic", "only solid elements take it"],
        ),
    ];
    for (name, cards, want) in nastran {
        let err = build(name, &plate(&cards), "bdf").unwrap_err();
        for w in want {
            assert!(err.contains(w), "{name}: no '{w}' in {err}");
        }
    }
    let mesh = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n\
                *ELEMENT, TYPE=S4, ELSET=P\n1, 1, 2, 3, 4\n";
    let abaqus = [
        (
            "composite",
            format!(
                "{mesh}*MATERIAL, NAME=AL\n*ELASTIC\n7e10, 0.33\n*DENSITY\n2700\n\
                 *SHELL SECTION, ELSET=P, COMPOSITE\n0.002, 3, AL, 0\n0.002, 3, AL, 90\n"
            ),
            vec!["inp:13", "COMPOSITE", "*SHELL SECTION ELSET=P"],
        ),
        (
            "lamina",
            format!(
                "{mesh}*MATERIAL, NAME=PLY\n*ELASTIC, TYPE=LAMINA\n1.4e11, 1e10, 0.3, 5e9, 5e9, 3e9\n\
                 *DENSITY\n1600\n*SHELL SECTION, ELSET=P, MATERIAL=PLY\n0.002\n"
            ),
            vec!["inp:9", "TYPE=LAMINA"],
        ),
    ];
    for (name, deck, want) in abaqus {
        let err = build(name, &deck, "inp").unwrap_err();
        for w in want {
            assert!(err.contains(w), "{name}: no '{w}' in {err}");
        }
    }
}
