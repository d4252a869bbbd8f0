//! Quadratic shells read from decks (Abaqus S8, S8R, S6 with *NODAL THICKNESS; Nastran CQUAD8,
//! CTRIA6 with corner thicknesses T1..T4) through the importers, the assembler, the
//! elimination and the eigensolver, against Leissa's cantilever plate (λ = ωa²√(ρh/D) = 3.492,
//! 8.525, 21.43; *Vibration of Plates*, NASA SP-160 (1969) Table 4.53) and against each other:
//! a thickness given at the nodes (or corners) equal everywhere to t must give the section-t
//! plate exactly. The Abaqus decks are read with `--inp-shells native` (flexbody's shells; by
//! default a deck's shells are expanded into bricks as ccx does: tests/ccx_shell_expansion.rs).

use std::path::Path;

use crate::common::scratch;
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec, MassKind};
use flexbody::import::{read_model, ImportOptions, InpShells};
use flexbody::solve::{lowest_modes, EigenSpec};

const E: f64 = 210e9;
const NU: f64 = 0.3;
const RHO: f64 = 7850.0;
const N: usize = 8;

/// Grid points of an N×N cell mesh of the unit square with mid-side points: (id, x, y); quad8
/// meshes leave out the cell centres.
fn grid(quad8: bool) -> Vec<(usize, f64, f64)> {
    let g = 2 * N;
    let mut out = Vec::new();
    for j in 0..=g {
        for i in 0..=g {
            if quad8 && i % 2 == 1 && j % 2 == 1 {
                continue;
            }
            out.push((
                j * (g + 1) + i + 1,
                i as f64 / g as f64,
                j as f64 / g as f64,
            ));
        }
    }
    out
}

/// Element node lists (ids, Abaqus = Nastran order) of the N×N mesh.
fn elements(quad8: bool) -> Vec<Vec<usize>> {
    let g = 2 * N;
    let id = |i: usize, j: usize| j * (g + 1) + i + 1;
    let mut out = Vec::new();
    for j in 0..N {
        for i in 0..N {
            let (a, b) = (2 * i, 2 * j);
            let c = [id(a, b), id(a + 2, b), id(a + 2, b + 2), id(a, b + 2)];
            let m = [
                id(a + 1, b),
                id(a + 2, b + 1),
                id(a + 1, b + 2),
                id(a, b + 1),
            ];
            if quad8 {
                out.push([c, m].concat());
            } else {
                let mid = id(a + 1, b + 1);
                out.push(vec![c[0], c[1], c[2], m[0], m[1], mid]);
                out.push(vec![c[0], c[2], c[3], mid, m[2], m[3]]);
            }
        }
    }
    out
}

/// Abaqus deck: `ty` elements, section thickness `t`, clamped at x = 0; `section_extra` is
/// appended to the *SHELL SECTION line, `tail` after the section's data line.
fn abaqus(ty: &str, t: f64, section_extra: &str, tail: &str) -> String {
    let quad8 = ty.starts_with("S8");
    let mut s = String::from("*NODE, NSET=NALL\n");
    for (id, x, y) in grid(quad8) {
        s += &format!("{id}, {x}, {y}, 0.0\n");
    }
    s += &format!("*ELEMENT, TYPE={ty}, ELSET=EALL\n");
    for (k, e) in elements(quad8).iter().enumerate() {
        let ids: Vec<String> = e.iter().map(|v| v.to_string()).collect();
        s += &format!("{}, {}\n", k + 1, ids.join(", "));
    }
    s += "*NSET, NSET=ROOT\n";
    for (id, x, _) in grid(quad8) {
        if x == 0.0 {
            s += &format!("{id},\n");
        }
    }
    s += &format!(
        "*BOUNDARY\nROOT, 1, 6\n*MATERIAL, NAME=STEEL\n*ELASTIC\n{E}, {NU}\n*DENSITY\n{RHO}\n\
         *SHELL SECTION, ELSET=EALL, MATERIAL=STEEL{section_extra}\n{t}\n{tail}\
         *STEP\n*FREQUENCY\n3\n*END STEP\n"
    );
    s
}

/// Nastran deck of CQUAD8 or CTRIA6 on PSHELL T = `t`, clamped at x = 0 by SPC1; `corner`:
/// the card's T1.. fields (blank when `None`), `zoffs` its ZOFFS.
fn nastran(quad8: bool, t: f64, corner: Option<f64>, zoffs: f64) -> String {
    let mut s = String::from("SOL 103\nCEND\nSPC = 1\nBEGIN BULK\n");
    for (id, x, y) in grid(quad8) {
        s += &format!("GRID,{id},,{x},{y},0.0\n");
    }
    let tc = corner.map_or(String::new(), |v| v.to_string());
    for (k, e) in elements(quad8).iter().enumerate() {
        let g: Vec<String> = e.iter().map(|v| v.to_string()).collect();
        if quad8 {
            s += &format!(
                "CQUAD8,{},1,{}\n,{},{},{tc},{tc},{tc},{tc},,{zoffs}\n",
                k + 1,
                g[..6].join(","),
                g[6],
                g[7]
            );
        } else {
            s += &format!(
                "CTRIA6,{},1,{}\n,,{zoffs},{tc},{tc},{tc}\n",
                k + 1,
                g.join(",")
            );
        }
    }
    for (id, x, _) in grid(quad8) {
        if x == 0.0 {
            s += &format!("SPC1,1,123456,{id}\n");
        }
    }
    s += &format!("PSHELL,1,1,{t},1,,1\nMAT1,1,{E},,{NU},{RHO}\nENDDATA\n");
    s
}

fn write(name: &str, text: &str) -> std::path::PathBuf {
    let path = scratch("shell-quadratic-import").join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// flexbody's own shells for the Abaqus decks.
fn native() -> ImportOptions {
    ImportOptions {
        inp_shells: InpShells::Native,
        ..Default::default()
    }
}

/// The first three frequencies [rad/s] of a deck, consistent mass, and its warnings.
fn frequencies(path: &Path) -> (Vec<f64>, Vec<String>) {
    let model = read_model(path, &native()).unwrap();
    let warnings = model.warnings.iter().map(|w| w.message.clone()).collect();
    (modes(&model), warnings)
}

/// The first three frequencies [rad/s] of a model, consistent mass.
fn modes(model: &flexbody::model::Model) -> Vec<f64> {
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        ..Default::default()
    };
    let asm = assemble(model, &spec).unwrap();
    let red = eliminate(model, &asm.dofs, &asm.k, &asm.m, &ConstraintSpec::default()).unwrap();
    let sol = lowest_modes(
        &red.k,
        &red.m,
        &EigenSpec {
            count: 3,
            ..Default::default()
        },
    )
    .unwrap();
    sol.eigenvalues.iter().map(|l| l.sqrt()).collect()
}

fn leissa(got: &[f64], t: f64, tol: f64, what: &str) {
    let d = E * t.powi(3) / (12.0 * (1.0 - NU * NU));
    let scale = (d / (RHO * t)).sqrt();
    for (g, l) in got.iter().zip([3.492, 8.525, 21.43]) {
        let err = (g / scale - l) / l;
        eprintln!(
            "{what}: λ = {:.4} vs {l} ({:+.3} %)",
            g / scale,
            100.0 * err
        );
        assert!(err.abs() < tol, "{what}: λ {} vs {l}", g / scale);
    }
}

fn same(a: &[f64], b: &[f64], what: &str) {
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() < 1e-9 * y, "{what}: {x} vs {y}");
    }
}

/// S8, S8R and S6 cantilever plates (8×8 cells, t = 10 mm) within 1 % of Leissa on the first
/// two modes and 2 % on the third (measured at most −0.71 %, −0.40 %, −1.19 %); S8R is read as
/// the same shell as S8 (ccx expands S8 into C3D20 and S8R into C3D20R bricks,
/// docs/conformance.md).
#[test]
fn abaqus_s8_s8r_s6_cantilever_plates_match_leissa() {
    let t = 0.01;
    let s8 = frequencies(&write("s8.inp", &abaqus("S8", t, "", ""))).0;
    leissa(&s8, t, 0.02, "S8");
    let s8r = frequencies(&write("s8r.inp", &abaqus("S8R", t, "", ""))).0;
    same(&s8r, &s8, "S8R = S8");
    let s6 = frequencies(&write("s6.inp", &abaqus("S6", t, "", ""))).0;
    leissa(&s6, t, 0.02, "S6");
}

/// *NODAL THICKNESS with *SHELL SECTION, NODAL THICKNESS: 20 mm at every node is the 20 mm
/// section exactly (not the section's 10 mm); without the parameter the nodal values are not
/// used (as Abaqus and ccx 2.20), with a warning; a node without a value is an error naming the
/// section and the node.
#[test]
fn abaqus_nodal_thickness_replaces_the_section_thickness_with_the_parameter_only() {
    let want = frequencies(&write("t20.inp", &abaqus("S8", 0.02, "", ""))).0;
    let nodal = "*NODAL THICKNESS\nNALL, 0.02\n";
    let (got, _) = frequencies(&write(
        "nt.inp",
        &abaqus("S8", 0.01, ", NODAL THICKNESS", nodal),
    ));
    same(&got, &want, "S8 nodal 0.02");
    let (got, _) = frequencies(&write(
        "nt6.inp",
        &abaqus("S6", 0.01, ", NODAL THICKNESS", nodal),
    ));
    same(
        &got,
        &frequencies(&write("t20s6.inp", &abaqus("S6", 0.02, "", ""))).0,
        "S6 nodal 0.02",
    );
    let (got, warnings) = frequencies(&write("np.inp", &abaqus("S8", 0.01, "", nodal)));
    same(
        &got,
        &frequencies(&write("t10.inp", &abaqus("S8", 0.01, "", ""))).0,
        "no parameter",
    );
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("*NODAL THICKNESS") && w.contains("section's thickness")),
        "{warnings:?}"
    );
    let partial = "*NSET, NSET=SOME\n1, 2, 3\n*NODAL THICKNESS\nSOME, 0.02\n";
    let err = read_model(
        &write(
            "partial.inp",
            &abaqus("S8", 0.01, ", NODAL THICKNESS", partial),
        ),
        &native(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("*SHELL SECTION ELSET=EALL") && err.contains("has no *NODAL THICKNESS"),
        "{err}"
    );
}

/// Nastran CQUAD8 and CTRIA6: the 10 mm PSHELL within Leissa's tolerances as the Abaqus decks,
/// equal to the Abaqus S8/S6 decks; corner thicknesses T1..T4 = 20 mm on the 10 mm PSHELL are
/// the 20 mm plate exactly; ZOFFS ≠ 0 is an error naming the card.
#[test]
fn nastran_cquad8_ctria6_with_corner_thicknesses() {
    for quad8 in [true, false] {
        let ty = if quad8 { "S8" } else { "S6" };
        let plain = frequencies(&write("n10.bdf", &nastran(quad8, 0.01, None, 0.0))).0;
        same(
            &plain,
            &frequencies(&write("a10.inp", &abaqus(ty, 0.01, "", ""))).0,
            "Nastran = Abaqus",
        );
        let got = frequencies(&write("nt.bdf", &nastran(quad8, 0.01, Some(0.02), 0.0))).0;
        same(
            &got,
            &frequencies(&write("a20.inp", &abaqus(ty, 0.02, "", ""))).0,
            "T1.. = 0.02",
        );
        let err = read_model(
            &write("z.bdf", &nastran(quad8, 0.01, None, 0.001)),
            &ImportOptions::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("ZOFFS"), "{err}");
        assert!(
            err.contains(if quad8 { "CQUAD8" } else { "CTRIA6" }),
            "{err}"
        );
    }
}

/// CalculiX's shellf deck (Debian's `calculix-ccx-test`, read from the package: the suite is
/// GPL and not in the repository): a 1 × 1 cantilever of 2×2 S8 elements, t = 0.01 (its
/// *NODAL THICKNESS is not used: its *SHELL SECTION has no NODAL THICKNESS parameter, as ccx
/// 2.20 reads it), E = 210000, ν = 0.3, ρ = 7.8e-9. Its first five modes are Leissa's within
/// 1 % (two) and 6 % (three, on the coarse mesh; measured −0.42, −0.67, +4.82, +4.62,
/// +3.88 %); ccx 2.20's one layer of C3D20 bricks is +11, +11, +77, +84, +80 % (the deck read
/// by default, expanded as ccx does, matches ccx: docs/conformance.md).
#[test]
fn calculix_shellf_s8_plate_is_leissas_plate() {
    let deck = Path::new("/usr/share/doc/calculix-ccx-test/examples/test/shellf.inp");
    if !deck.exists() {
        crate::common::skipped_install(
            &format!(
                "calculix_shellf_s8_plate_is_leissas_plate: needs {}",
                deck.display()
            ),
            "apt-get install calculix-ccx-test",
        );
        return;
    }
    let model = read_model(deck, &native()).unwrap();
    assert!(model
        .warnings
        .iter()
        .any(|w| w.message.contains("section's thickness")));
    let spec = AssemblySpec {
        mass: MassKind::Consistent,
        ..Default::default()
    };
    let asm = assemble(&model, &spec).unwrap();
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec::default(),
    )
    .unwrap();
    let sol = lowest_modes(
        &red.k,
        &red.m,
        &EigenSpec {
            count: 5,
            ..Default::default()
        },
    )
    .unwrap();
    let (e, nu, rho, t): (f64, f64, f64, f64) = (210000.0, 0.3, 7.8e-9, 0.01);
    let scale = (e * t * t / (12.0 * (1.0 - nu * nu) * rho)).sqrt();
    for (k, (l, want)) in sol
        .eigenvalues
        .iter()
        .zip([3.492, 8.525, 21.43, 27.33, 31.11])
        .enumerate()
    {
        let err = (l.sqrt() / scale - want) / want;
        eprintln!("shellf mode {}: {:+.2} % of Leissa", k + 1, 100.0 * err);
        assert!(
            err.abs() < if k < 2 { 0.01 } else { 0.06 },
            "mode {}: {err}",
            k + 1
        );
    }
}

/// Stress/strain shapes of quadratic shells are not recovered: asking for them is an error
/// naming the element (never shapes left out); without them the S8 plate builds; a preload
/// (geometric stiffness) on them is an error naming the element too.
#[test]
fn stress_shapes_and_preload_of_quadratic_shells_are_refused_by_element() {
    let deck = write("stress.inp", &abaqus("S8", 0.01, "", ""));
    let out = deck.with_extension("flexbody");
    let run = |extra: &[&str]| {
        crate::common::exe()
            .arg("build")
            .arg(&deck)
            .args([
                "--units",
                "si",
                "--method",
                "normal",
                "--modes",
                "3",
                "--inp-shells",
                "native",
                "-q",
                "-o",
            ])
            .arg(&out)
            .args(extra)
            .output()
            .unwrap()
    };
    let o = run(&["--stress-modes"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("element 1 (Quad8)") && err.contains("quadratic shells"),
        "{err}"
    );
    assert!(!out.exists());
    let o = run(&[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // a preload needs the geometric stiffness, which quadratic shells do not have
    std::fs::remove_file(&out).ok();
    let o = run(&["--gravity", "0,0,-9.81", "--preload", "GRAVITY"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("Quad8") && err.contains("no geometric stiffness"),
        "{err}"
    );
    assert!(!out.exists());
}

/// A Gmsh 4.1 mesh of second-order quadrangles (type 16) and of second-order triangles (type 9)
/// becomes quadratic shells with `--material` and `--thickness`: the same cantilever plate as
/// the Abaqus decks, the same frequencies.
#[test]
fn gmsh_second_order_surfaces_with_thickness_are_quadratic_shells() {
    use flexbody::model::{DofMask, Material, Spc};
    for quad8 in [true, false] {
        let nodes = grid(quad8);
        let elems = elements(quad8);
        let (ty, ty_name) = if quad8 { (16, "S8") } else { (9, "S6") };
        let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
        let nn = nodes.len();
        let max = nodes.iter().map(|p| p.0).max().unwrap();
        s += &format!("$Nodes\n1 {nn} 1 {max}\n2 1 0 {nn}\n");
        for p in &nodes {
            s += &format!("{}\n", p.0);
        }
        for p in &nodes {
            s += &format!("{} {} 0\n", p.1, p.2);
        }
        s += "$EndNodes\n";
        let ne = elems.len();
        s += &format!("$Elements\n1 {ne} 1 {ne}\n2 1 {ty} {ne}\n");
        for (k, e) in elems.iter().enumerate() {
            let ids: Vec<String> = e.iter().map(|v| v.to_string()).collect();
            s += &format!("{} {}\n", k + 1, ids.join(" "));
        }
        s += "$EndElements\n";
        let path = write(if quad8 { "q8.msh" } else { "t6.msh" }, &s);
        let mut model = read_model(
            &path,
            &ImportOptions {
                material: Some(Material::isotropic(1, "STEEL", E, NU, RHO)),
                shell_thickness: Some(0.01),
                ..Default::default()
            },
        )
        .unwrap();
        for k in 0..model.nodes.len() {
            if model.nodes[k].x[0] == 0.0 {
                model.spcs.push(Spc {
                    node: k,
                    dofs: DofMask::from_digits("123456").unwrap(),
                    set_id: 0,
                });
            }
        }
        let want = frequencies(&write("g.inp", &abaqus(ty_name, 0.01, "", ""))).0;
        let got = modes(&model);
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() < 1e-9 * w, "{ty_name}: {g} vs {w}");
        }
    }
}
