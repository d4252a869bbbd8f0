//! CalculiX's quadratic beams B32/B32R as ccx 2.20 computes them (issue 34): our own decks in
//! `fixtures/ccx_beams/` (RECT, CIRC, PIPE, BOX, a beam oblique to the axes, an arc in an oblique
//! plane, with section offsets, B32's full integration, a simply supported pipe; frames whose
//! legs meet at knots: an L, a portal with a T; preloaded by a pull on the tip's
//! beam node or by gravity, as ccx perturbs the static state) match ccx's frequencies stored in
//! its `results.json` to ccx's printed digits; a slender cantilever bends as Euler–Bernoulli
//! says in each plane (so the section's 1- and 2-directions are where the card puts them); the
//! sections and joints flexbody does not expand are refused naming the card and line.

use std::path::{Path, PathBuf};

use crate::common::{build_as_ccx, scratch};
use flexbody::import::abaqus;
use flexbody_reader as file;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/ccx_beams")
        .join(name)
}

fn build(stem: &str, dir: &Path) -> Vec<f64> {
    let out = dir.join(format!("{stem}.flexbody"));
    let o = build_as_ccx(&fixture(&format!("{stem}.inp")), &["-q"], &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stem}: {err}");
    file::read(&out).unwrap().modes.frequency_hz
}

#[test]
fn expanded_beams_match_calculix() {
    let dir = scratch("ccx_beams");
    for stem in [
        "rect_cantilever",
        "rect_b32",
        "circ_cantilever",
        "circ_b32",
        "pipe_cantilever",
        "pipe_pinned",
        "box_cantilever",
        "oblique_rect",
        "oblique_arc_box",
        "slender_rect",
        "arc_offset",
        "knot_l_rect",
        "knot_portal",
        "mass_spring_rect",
        "pull_rect",
        "gravity_rect",
    ] {
        let ours = build(stem, &dir);
        let ccx = crate::common::ccx_frequencies("ccx_beams", stem);
        // ccx prints 7 significant digits
        crate::common::assert_frequencies(stem, &ours, &ccx, 0, 1e-6);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The slender cantilever (1 m, section 0.02 along the card's 1-direction y, 0.01 along the
/// 2-direction z, ten B32R, the tip held in y): bending in z is a cantilever on the 0.01
/// thickness, bending in y is clamped–pinned on the 0.02 width. Euler–Bernoulli,
/// f = β²/(2π) √(E I / (ρ A)) / L² with I/A = h²/12: β = 1.8751, 4.6941 (cantilever),
/// 3.9266 (clamped–pinned). The ten bricks are 1.1 % stiff in z and 0.5 % in y (halving with
/// the element length: +0.55 % and +0.28 % in z at 20 and 40 elements); swapped axes would
/// put the first mode at 16.7 Hz.
#[test]
fn slender_cantilever_bends_as_euler_bernoulli_in_both_planes() {
    let dir = scratch("ccx_beams_eb");
    let f = build("slender_rect", &dir);
    let (e, rho, l) = (210e9_f64, 7850.0, 1.0);
    let eb = |beta: f64, h: f64| {
        beta * beta / (2.0 * std::f64::consts::PI) * (e / rho * h * h / 12.0).sqrt() / (l * l)
    };
    let (z1, z2, y1) = (eb(1.8751, 0.01), eb(4.6941, 0.01), eb(3.9266, 0.02));
    assert!((z1 - 8.355).abs() < 1e-3, "{z1}");
    let near = |target: f64, tol: f64| f.iter().any(|x| (x - target).abs() / target < tol);
    assert!(
        (f[0] - z1) / z1 > 0.0 && (f[0] - z1) / z1 < 0.012,
        "{f:?} against {z1}"
    );
    assert!(near(z2, 0.012), "{f:?} against {z2}");
    assert!(near(y1, 0.006), "{f:?} against {y1}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A deck of two B32R beams from `nodes` with `section` lines and `extra` model data.
fn small_deck(nodes: &str, elements: &str, section: &str, extra: &str) -> String {
    format!(
        "*NODE, NSET=NALL\n{nodes}*ELEMENT, TYPE=B32R, ELSET=EALL\n{elements}*MATERIAL, \
         NAME=STEEL\n*ELASTIC\n210e9, 0.3\n*DENSITY\n7850.\n{section}{extra}*BOUNDARY\n1, 1, \
         6\n*STEP\n*FREQUENCY\n4\n*END STEP\n"
    )
}

const LINE: &str = "1, 0, 0, 0\n2, 0.5, 0, 0\n3, 1, 0, 0\n4, 1.5, 0, 0\n5, 2, 0, 0\n";
const TWO: &str = "1, 1, 2, 3\n2, 3, 4, 5\n";
const RECT: &str = "*BEAM SECTION, ELSET=EALL, MATERIAL=STEEL, SECTION=RECT\n0.1, 0.05\n0, 1, 0\n";

fn refusal(name: &str, text: &str) -> String {
    let dir = scratch(&format!("ccx_beams_{name}"));
    let path = dir.join(format!("{name}.inp"));
    std::fs::write(&path, text).unwrap();
    let e = abaqus::read(&path).expect_err(name).to_string();
    let _ = std::fs::remove_dir_all(&dir);
    e
}

#[test]
fn sections_and_joints_not_expanded_are_refused_by_name() {
    // *BEAM SECTION, SECTION=PIPE: ccx 2.20 knows RECT and CIRC there (PIPE under *BEAM
    // GENERAL SECTION)
    let e = refusal(
        "pipe",
        &small_deck(
            LINE,
            TWO,
            "*BEAM SECTION, ELSET=EALL, MATERIAL=STEEL, SECTION=PIPE\n0.1, 0.01\n0, 1, 0\n",
            "",
        ),
    );
    assert!(
        e.contains("pipe.inp:15: *BEAM SECTION ELSET=EALL") && e.contains("RECT or CIRC"),
        "{e}"
    );
    // *BEAM GENERAL SECTION on B31: ccx takes PIPE and BOX for B32R only
    let b31 = small_deck(
        "1, 0, 0, 0\n2, 1, 0, 0\n",
        "1, 1, 2\n",
        "*BEAM GENERAL SECTION, ELSET=EALL, MATERIAL=STEEL, SECTION=PIPE\n0.05, 0.005\n0, 1, 0\n",
        "",
    )
    .replace("TYPE=B32R", "TYPE=B31");
    let e = refusal("b31", &b31);
    assert!(
        e.contains("b31.inp:11: *BEAM GENERAL SECTION ELSET=EALL") && e.contains("B32R"),
        "{e}"
    );
    // OFFSET1 that is no number
    let e = refusal(
        "offset",
        &small_deck(
            LINE,
            TWO,
            &RECT.replace("SECTION=RECT", "SECTION=RECT, OFFSET1=half"),
            "",
        ),
    );
    assert!(
        e.contains("offset.inp:15") && e.contains("bad OFFSET1=half"),
        "{e}"
    );
    // rotary inertia on a beam node: not joined here
    let mass = "*ELEMENT, TYPE=ROTARYI, ELSET=M\n9, 5\n*ROTARY INERTIA, ELSET=M\n2., 2., 2.\n";
    let e = refusal("rotary", &small_deck(LINE, TWO, RECT, mass));
    assert!(
        e.contains("*ELEMENT 2 (TYPE=B32R)")
            && e.contains("beam node 5 is also used by rotary inertia 9"),
        "{e}"
    );
    // a shell on a beam node
    let shell = "*ELEMENT, TYPE=S4, ELSET=P\n9, 5, 6, 7, 8\n";
    let nodes = format!("{LINE}6, 3, 0, 0\n7, 3, 1, 0\n8, 2, 1, 0\n");
    let e = refusal("shell", &small_deck(&nodes, TWO, RECT, shell));
    assert!(e.contains("beam node 5 is also used by element 9"), "{e}");
}

/// The beam node stays in the model as an interface node: a Craig–Bampton body with the tip's
/// beam node as interface (its six dofs follow the section, no stiffer than ccx's model) has
/// the full model's first frequencies, ccx's.
#[test]
fn a_beam_node_is_an_interface_node() {
    let dir = scratch("ccx_beams_interface");
    let out = dir.join("tip.flexbody");
    let o = crate::common::exe()
        .arg("build")
        .arg(fixture("rect_cantilever.inp"))
        .args(["--interface", "21", "--fmax", "3000", "--units", "si"])
        .args(["--mass", "consistent", "-q", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let body = file::read(&out).unwrap();
    let ccx = crate::common::ccx_frequencies("ccx_beams", "rect_cantilever");
    let ours = &body.modes.frequency_hz;
    assert!(ours.len() >= 3, "{ours:?}");
    // measured 8.3e-6
    let worst = crate::common::assert_frequencies("tip interface", &ours[..3], &ccx[..3], 0, 5e-5);
    eprintln!("a_beam_node_is_an_interface_node: worst {worst:.2e}");
    let _ = std::fs::remove_dir_all(&dir);
}
