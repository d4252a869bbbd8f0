//! Orthotropic and anisotropic solids (issue 34): `*ELASTIC, TYPE=ORTHO | ENGINEERING
//! CONSTANTS | ANISO` with `*ORIENTATION`, through the command line and the importer, against
//! closed forms: a slender orthotropic cantilever bends with E1 along its axis (Euler–Bernoulli,
//! f₁ = β₁²/(2π) √(EI/(ρAL⁴)), β₁ = 1.8751; Blevins, *Formulas for Natural Frequency and Mode
//! Shape* (1979) Table 8-1) and with E2 once `*ORIENTATION` turns the material 90° about z;
//! ENGINEERING CONSTANTS give the D of the orthotropic compliance's closed-form inverse (Jones,
//! *Mechanics of Composite Materials* (1999) eq. 2.29); stress shapes are σ = D ε on a uniform
//! strain.

use crate::common::{build_as_ccx, scratch};
use flexbody::import::abaqus;
use flexbody::model::elasticity::rotate;
use flexbody::model::Model;
use flexbody::stress::{modal_fields, FieldRequest};
use flexbody_reader as file;
use std::fmt::Write as _;

const L: f64 = 1.0;
const B: f64 = 0.02; // along y
const H: f64 = 0.01; // along z
const RHO: f64 = 1600.0;
// E1, E2, E3, ν12, ν13, ν23, G12, G13, G23
const ENG: [f64; 9] = [100e9, 10e9, 10e9, 0.25, 0.25, 0.3, 5e9, 5e9, 3.85e9];

/// An `nx × 2 × 2` C3D8I cantilever along x, clamped at x = 0, with `material` lines and a
/// section line `section` (the `*SOLID SECTION` keyword line).
fn cantilever(material: &str, section: &str) -> String {
    let (nx, ny, nz) = (50, 2, 2);
    let id = |i: usize, j: usize, k: usize| 1 + i + (nx + 1) * (j + (ny + 1) * k);
    let mut s = String::from("*NODE, NSET=NALL\n");
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let (x, y, z) = (
                    L * i as f64 / nx as f64,
                    B * j as f64 / ny as f64,
                    H * k as f64 / nz as f64,
                );
                writeln!(s, "{}, {x}, {y}, {z}", id(i, j, k)).unwrap();
            }
        }
    }
    s.push_str("*ELEMENT, TYPE=C3D8I, ELSET=BAR\n");
    let mut e = 0;
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                e += 1;
                let c = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                let c: Vec<String> = c.iter().map(usize::to_string).collect();
                writeln!(s, "{e}, {}", c.join(", ")).unwrap();
            }
        }
    }
    s.push_str("*NSET, NSET=ROOT\n");
    for k in 0..=nz {
        for j in 0..=ny {
            writeln!(s, "{},", id(0, j, k)).unwrap();
        }
    }
    write!(
        s,
        "*MATERIAL, NAME=PLY\n{material}*DENSITY\n{RHO}\n{section}\n\
         *BOUNDARY\nROOT, 1, 3\n*STEP\n*FREQUENCY\n4\n*END STEP\n"
    )
    .unwrap();
    s
}

fn engineering() -> String {
    let v: Vec<String> = ENG.iter().map(|x| format!("{x:e}")).collect();
    format!(
        "*ELASTIC, TYPE=ENGINEERING CONSTANTS\n{}\n{}\n",
        v[..8].join(", "),
        v[8]
    )
}

/// Euler–Bernoulli first bending frequency of the cantilever about the axis whose bending
/// depth is `depth` (width `width`).
fn closed_form(e: f64, width: f64, depth: f64) -> f64 {
    let beta: f64 = 1.875_104_068_7;
    let (a, i) = (width * depth, width * depth.powi(3) / 12.0);
    beta * beta / (2.0 * std::f64::consts::PI) * (e * i / (RHO * a * L.powi(4))).sqrt()
}

fn build(name: &str, deck: &str) -> Result<file::ReducedBody, String> {
    let dir = scratch(&format!("aniso-{name}"));
    let path = dir.join(format!("{name}.inp"));
    std::fs::write(&path, deck).unwrap();
    let out = dir.join(format!("{name}.flexbody"));
    let o = build_as_ccx(&path, &["-q"], &out);
    if !o.status.success() {
        return Err(String::from_utf8_lossy(&o.stderr).into_owned());
    }
    Ok(file::read(&out).unwrap())
}

fn read(name: &str, deck: &str) -> Model {
    let dir = scratch(&format!("aniso-read-{name}"));
    let path = dir.join(format!("{name}.inp"));
    std::fs::write(&path, deck).unwrap();
    abaqus::read(&path).unwrap()
}

/// The cantilever bends with E1 along its axis; turned 90° about z by `*ORIENTATION` (axis 1
/// along y) it bends with E2. Both bending planes within 0.3 % of Euler–Bernoulli
/// (slenderness 50 and 100: shear and root effects measured at −0.14 … +0.10 %).
#[test]
fn orthotropic_cantilever_bends_with_e1_and_rotated_with_e2() {
    let section = "*SOLID SECTION, ELSET=BAR, MATERIAL=PLY";
    let along = build("along", &cantilever(&engineering(), section)).unwrap();
    let turned_section = "*ORIENTATION, NAME=TURN, SYSTEM=RECTANGULAR\n0, 1, 0, -1, 0, 0\n\
                          *SOLID SECTION, ELSET=BAR, MATERIAL=PLY, ORIENTATION=TURN";
    let turned = build("turned", &cantilever(&engineering(), turned_section)).unwrap();
    // The same turn given as a 90° additional rotation about axis 3 of the basic axes.
    let rotation = "*ORIENTATION, NAME=TURN\n1, 0, 0, 0, 1, 0\n3, 90\n\
                    *SOLID SECTION, ELSET=BAR, MATERIAL=PLY, ORIENTATION=TURN";
    let rotated = build("rotated", &cantilever(&engineering(), rotation)).unwrap();
    for (body, e, what) in [(&along, ENG[0], "E1"), (&turned, ENG[1], "E2")] {
        let f = &body.modes.frequency_hz;
        let want = [closed_form(e, B, H), closed_form(e, H, B)];
        for (got, want) in f.iter().zip(want) {
            let rel = got / want - 1.0;
            eprintln!("{what}: {got:.4} Hz against Euler–Bernoulli {want:.4} Hz ({rel:+.2e})");
            assert!(rel.abs() < 3e-3, "{what}: {f:?} against {want}");
        }
    }
    // equal to the eigensolver's convergence (cos 90° = 6e-17 apart)
    for (a, b) in turned
        .modes
        .frequency_hz
        .iter()
        .zip(&rotated.modes.frequency_hz)
    {
        assert!((a / b - 1.0).abs() < 1e-8, "{a} {b}");
    }
}

/// ENGINEERING CONSTANTS give the D of the closed-form inverse of the orthotropic compliance
/// (Jones eq. 2.29), and ORTHO given that D gives the same frequencies.
#[test]
fn engineering_constants_equal_the_ortho_d() {
    let m = read(
        "eng",
        &cantilever(&engineering(), "*SOLID SECTION, ELSET=BAR, MATERIAL=PLY"),
    );
    let d = *m.materials[0].stiffness().unwrap();
    let [e1, e2, e3, n12, n13, n23, g12, g13, g23] = ENG;
    let (n21, n31, n32) = (n12 * e2 / e1, n13 * e3 / e1, n23 * e3 / e2);
    let delta = (1.0 - n12 * n21 - n23 * n32 - n31 * n13 - 2.0 * n21 * n32 * n13) / (e1 * e2 * e3);
    let c11 = (1.0 - n23 * n32) / (e2 * e3 * delta);
    let c12 = (n21 + n31 * n23) / (e2 * e3 * delta);
    let c13 = (n31 + n21 * n32) / (e2 * e3 * delta);
    let c22 = (1.0 - n13 * n31) / (e1 * e3 * delta);
    let c23 = (n32 + n12 * n31) / (e1 * e3 * delta);
    let c33 = (1.0 - n12 * n21) / (e1 * e2 * delta);
    // model order xx yy zz xy yz zx
    let want = [
        [c11, c12, c13, 0.0, 0.0, 0.0],
        [c12, c22, c23, 0.0, 0.0, 0.0],
        [c13, c23, c33, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, g12, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, g23, 0.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, g13],
    ];
    for i in 0..6 {
        for j in 0..6 {
            assert!(
                (d[i][j] - want[i][j]).abs() <= 1e-12 * c11,
                "D{i}{j} = {} against {}",
                d[i][j],
                want[i][j]
            );
        }
    }
    // ORTHO in Abaqus order: D1111, D1122, D2222, D1133, D2233, D3333, D1212, D1313, D2323.
    let ortho = format!(
        "*ELASTIC, TYPE=ORTHO\n{c11:e}, {c12:e}, {c22:e}, {c13:e}, {c23:e}, {c33:e}, {g12:e}, {g13:e}\n{g23:e}\n"
    );
    let section = "*SOLID SECTION, ELSET=BAR, MATERIAL=PLY";
    let a = build("eng-f", &cantilever(&engineering(), section)).unwrap();
    let b = build("ortho-f", &cantilever(&ortho, section)).unwrap();
    for (x, y) in a.modes.frequency_hz.iter().zip(&b.modes.frequency_hz) {
        assert!((x / y - 1.0).abs() < 1e-8, "{x} {y}");
    }
    // ANISO: the same D as 21 constants of the lower triangle (order 11 22 33 12 13 23).
    let lower = [
        c11, c12, c22, c13, c23, c33, 0.0, 0.0, 0.0, g12, 0.0, 0.0, 0.0, 0.0, g13, 0.0, 0.0, 0.0,
        0.0, 0.0, g23,
    ];
    let v: Vec<String> = lower.iter().map(|x| format!("{x:e}")).collect();
    let aniso = format!(
        "*ELASTIC, TYPE=ANISO\n{}\n{}\n{}\n",
        v[..8].join(", "),
        v[8..16].join(", "),
        v[16..].join(", ")
    );
    let c = build("aniso-f", &cantilever(&aniso, section)).unwrap();
    for (x, y) in a.modes.frequency_hz.iter().zip(&c.modes.frequency_hz) {
        assert!((x / y - 1.0).abs() < 1e-8, "{x} {y}");
    }
}

/// An indefinite D, an unknown orientation and LAMINA on a solid are errors naming the line.
#[test]
fn bad_materials_are_refused_with_their_line() {
    let section = "*SOLID SECTION, ELSET=BAR, MATERIAL=PLY";
    // D1122 > √(D1111 D2222): indefinite
    let bad = "*ELASTIC, TYPE=ORTHO\n1e9, 5e9, 1e9, 0, 0, 1e9, 1e8, 1e8\n1e8\n";
    let err = build("indefinite", &cantilever(bad, section)).unwrap_err();
    assert!(
        err.contains("not positive definite") && err.contains("*MATERIAL PLY"),
        "{err}"
    );
    let err = build(
        "no-orientation",
        &cantilever(
            &engineering(),
            "*SOLID SECTION, ELSET=BAR, MATERIAL=PLY, ORIENTATION=NONE",
        ),
    )
    .unwrap_err();
    assert!(err.contains("ORIENTATION=NONE"), "{err}");
    let lamina = "*ELASTIC, TYPE=LAMINA\n1e11, 1e10, 0.25, 5e9, 5e9, 4e9\n";
    let err = build("lamina", &cantilever(lamina, section)).unwrap_err();
    assert!(err.contains("TYPE=LAMINA"), "{err}");
}

/// σ = D ε at every node of a uniform strain field, with D turned by a cylindrical
/// `*ORIENTATION` (each node its own axes).
#[test]
fn stress_shapes_are_d_times_strain_in_the_material_axes() {
    let deck = cantilever(
        &engineering(),
        "*ORIENTATION, NAME=CYL, SYSTEM=CYLINDRICAL\n0, -1, -1, 1, -1, -0.5\n\
         *SOLID SECTION, ELSET=BAR, MATERIAL=PLY, ORIENTATION=CYL",
    );
    let model = read("stress", &deck);
    let eps = [1e-4, -2e-4, 0.5e-4, 3e-4, -1e-4, 2e-4]; // xx yy zz γxy γyz γzx
                                                        // u = E x with E the (symmetric) tensor of eps
    let e = [
        [eps[0], eps[3] / 2.0, eps[5] / 2.0],
        [eps[3] / 2.0, eps[1], eps[4] / 2.0],
        [eps[5] / 2.0, eps[4] / 2.0, eps[2]],
    ];
    let u = |n: usize, _mode: usize| {
        let x = model.nodes[n].x;
        std::array::from_fn(|i| (0..3).map(|j| e[i][j] * x[j]).sum())
    };
    let wanted: Vec<usize> = (0..model.nodes.len()).collect();
    let request = FieldRequest {
        stress: true,
        strain: true,
    };
    let f = modal_fields(&model, &wanted, 1, &u, request).unwrap();
    let d = *model.materials[0].stiffness().unwrap();
    let axes = &model.property_axes[&0];
    let stress = f.stress.unwrap();
    let scale = 1e-4 * ENG[0];
    let mut worst = 0.0f64;
    for (q, &n) in f.nodes.iter().enumerate() {
        let dn = rotate(&d, &axes.at(&model.nodes[n].x));
        for i in 0..6 {
            let want: f64 = (0..6).map(|j| dn[i][j] * eps[j]).sum();
            worst = worst.max((stress[q * 6 + i] - want).abs() / scale);
        }
    }
    // nodal averages of elements whose D differs node by node only as the axes turn: the
    // recovery evaluates D at the node, so the values agree to rounding
    assert!(worst < 1e-9, "{worst:e}");
}

/// The cantilever as a Nastran deck: CHEXA (MSC's default bubble modes, as C3D8I) on PSOLID
/// with CORDM `cordm` and MAT9 `d` (order xx yy zz xy yz zx), clamped by SPC1.
fn nastran_cantilever(d: &flexbody::model::Stiffness6, cordm: &str) -> String {
    let abaqus = cantilever("", "");
    let mut s = String::from(
        "SOL 103\nCEND\nSPC = 1\nMETHOD = 1\nBEGIN BULK\nEIGRL,1,,,4\n\
         CORD2R,5,,0.,0.,0.,0.,0.,1.\n,0.,1.,0.\n",
    );
    writeln!(s, "PSOLID,1,9,{cordm}").unwrap();
    let g: Vec<String> = (d.iter().enumerate())
        .flat_map(|(i, row)| row[i..].iter().map(|v| format!("{v:e}")))
        .collect();
    writeln!(
        s,
        "MAT9,9,{}\n,{}\n,{},{RHO:e}",
        g[..7].join(","),
        g[7..15].join(","),
        g[15..].join(",")
    )
    .unwrap();
    let mut block = "";
    for line in abaqus.lines() {
        if line.starts_with('*') {
            block = if line.starts_with("*NODE") {
                "node"
            } else if line.starts_with("*ELEMENT") {
                "el"
            } else if line.starts_with("*NSET, NSET=ROOT") {
                "root"
            } else {
                ""
            };
            continue;
        }
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        match block {
            "node" => writeln!(s, "GRID,{},,{},{},{}", f[0], f[1], f[2], f[3]).unwrap(),
            "el" => writeln!(
                s,
                "CHEXA,{},1,{},+\n+,{}",
                f[0],
                f[1..7].join(","),
                f[7..].join(",")
            )
            .unwrap(),
            "root" => writeln!(s, "SPC1,1,123,{}", f[0]).unwrap(),
            _ => {}
        }
    }
    s.push_str("ENDDATA\n");
    s
}

/// Nastran MAT9 on PSOLID gives the frequencies of the same D read from Abaqus (CHEXA has
/// C3D8I's bubble modes), and PSOLID CORDM (a CORD2R with axis 1 along y) those of the
/// `*ORIENTATION` turn; CORDM = −1 is refused naming the card.
#[test]
fn nastran_mat9_and_cordm_equal_the_abaqus_material() {
    let [e1, e2, e3, n12, n13, n23, g12, g13, g23] = ENG;
    let d = flexbody::model::elasticity::from_engineering_constants(
        [e1, e2, e3],
        [n12, n13, n23],
        [g12, g13, g23],
    )
    .unwrap();
    let run = |name: &str, deck: &str| -> Result<file::ReducedBody, String> {
        let dir = scratch(&format!("aniso-nastran-{name}"));
        let path = dir.join(format!("{name}.bdf"));
        std::fs::write(&path, deck).unwrap();
        let out = dir.join(format!("{name}.flexbody"));
        let o = build_as_ccx(&path, &["-q"], &out);
        if !o.status.success() {
            return Err(String::from_utf8_lossy(&o.stderr).into_owned());
        }
        Ok(file::read(&out).unwrap())
    };
    let section = "*SOLID SECTION, ELSET=BAR, MATERIAL=PLY";
    let turned_section = "*ORIENTATION, NAME=TURN, SYSTEM=RECTANGULAR\n0, 1, 0, -1, 0, 0\n\
                          *SOLID SECTION, ELSET=BAR, MATERIAL=PLY, ORIENTATION=TURN";
    let pairs = [("basic", "", section), ("cordm", "5", turned_section)];
    for (name, cordm, abaqus_section) in pairs {
        let n = run(name, &nastran_cantilever(&d, cordm)).unwrap();
        let a = build(
            &format!("nastran-ref-{name}"),
            &cantilever(&engineering(), abaqus_section),
        )
        .unwrap();
        for (x, y) in n.modes.frequency_hz.iter().zip(&a.modes.frequency_hz) {
            assert!((x / y - 1.0).abs() < 1e-8, "{name}: {x} {y}");
        }
    }
    let err = run("element-axes", &nastran_cantilever(&d, "-1")).unwrap_err();
    assert!(err.contains("PSOLID 1") && err.contains("CORDM"), "{err}");
}
