//! ANSYS's SHELL281 as ANSYS forms it (issue 50), through archives:
//!
//! - against ANSYS's own element forces: ansys-mapdl-reader's `tests/testfiles/shell281.rst`
//!   (ANSYS 19.0; converted by `tests/data/ansys/make_shell281.py`), 8 SHELL281 on a section
//!   offset to its bottom surface with user transverse shear stiffnesses;
//! - a simply supported thin square plate (NAFEMS FV12's) against Kirchhoff's closed form, on
//!   its mid-surface and offset to its bottom surface (four times the bending rigidity);
//! - what is not formed is refused by its line naming the KEYOPT, shape or command.

use std::collections::HashMap;

use crate::ansys_support::writers::{eblock, material, nblock};
use crate::ansys_support::{
    assert_refused_at, build, data, line_of, multiply, node_table, read_dofs,
};
use crate::common::scratch;

/// The solution csv of make_shell281.py: node id → [x y z, u (6), ANSYS's K u (6), force and
/// moment scale].
fn read_solution(name: &str) -> HashMap<u64, [f64; 17]> {
    node_table(&std::fs::read_to_string(data(name)).unwrap(), 1)
}

/// SHELL281 against ANSYS 19.0's element forces (ansys-mapdl-reader's `shell281.rst`): 8 flat
/// 2.5 × 2.5 elements on the face of a solid block, a section of thickness 0.03 offset to its
/// bottom surface with user transverse shear stiffnesses E11 = E22 = E12 = 1. At each of the
/// 192 free dofs our K u equals ANSYS's element forces assembled.
///
/// K is the archive's constrained K as `build --write-matrices` writes it, taken without the
/// modal build (`export_mtx`): with a transverse shear stiffness of 1 against a membrane
/// stiffness E t = 6·10⁷, the normal displacement and the drilling rotation are all but free,
/// which the build's verification rightly refuses as near-rigid modes.
///
/// Measured 6.3e-8 of the largest element force (moment) at the node (ANSYS writes ENF in
/// single precision). The same comparison in numpy, element by element (once; largest error
/// over the largest ENF force, moment): 4.2e-8, 7.6e-8 as here; the section on the nodes'
/// surface (MID) 2.9, 31 and on their top (TOP) 5.9, 2.4e2; the transverse shear on 3 × 3
/// points 5.6e-8, 2.5e-4 and on one point 1.4e-5, 2.8e-2; SHELL181's drilling penalty (1/200
/// of the shear stiffness) 4.2e-8, 1.9e-7 — the element forces tell the 2 × 2 rule, the BOT
/// offset and the user shear stiffnesses apart, and bound the drilling penalty only.
#[test]
fn shell281_offset_block_face_equals_ansys_element_forces() {
    let dir = scratch("ansys-shell281");
    let cdb = dir.join("shell281_block.cdb");
    std::fs::copy(data("shell281_block.cdb"), &cdb).unwrap();
    let solution = read_solution("shell281_block_solution.csv");
    let mats = dir.join("mats");
    let spec = flexbody::build::BuildSpec::new(cdb, flexbody_reader::Units::si(), &[]);
    flexbody::export::mtx::export_mtx(&spec, &mats).unwrap();
    let dofs = read_dofs(&mats.join("dofs.txt"));
    assert_eq!(dofs.len(), (37 - 5) * 6, "every free node's six dofs");
    let u: Vec<f64> = dofs.iter().map(|&(n, c)| solution[&n][3 + c]).collect();
    let ku = multiply(&mats.join("K.mtx"), &u);
    let worst = (dofs.iter().zip(&ku))
        .map(|(&(n, c), k)| {
            let s = &solution[&n];
            (k - s[9 + c]).abs() / s[15 + c / 3]
        })
        .fold(0.0f64, f64::max);
    println!("SHELL281: max |K u − (K u)_ANSYS| / ENF scale = {worst:.2e}");
    assert!(worst < 6e-7, "{worst:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Nodes as (id, position).
type Nodes = Vec<(u64, [f64; 3])>;

/// An n × n mesh of SHELL281 over [0, L]² at z = 0: nodes (id, position) and element node
/// lists (I, J, K, L, M, N, O, P), node ids 1 + i + (2n + 1) j on the (2n + 1)² grid without
/// the element centres.
fn plate_mesh(n: usize, l: f64) -> (Nodes, Vec<Vec<u64>>) {
    let m = 2 * n + 1;
    let id = |i: usize, j: usize| (1 + i + m * j) as u64;
    let h = l / (2 * n) as f64;
    let nodes = (0..m)
        .flat_map(|j| (0..m).map(move |i| (i, j)))
        .filter(|&(i, j)| i % 2 == 0 || j % 2 == 0)
        .map(|(i, j)| (id(i, j), [i as f64 * h, j as f64 * h, 0.0]))
        .collect();
    let mut elements = Vec::new();
    for ej in 0..n {
        for ei in 0..n {
            let (i, j) = (2 * ei, 2 * ej);
            elements.push(vec![
                id(i, j),
                id(i + 2, j),
                id(i + 2, j + 2),
                id(i, j + 2),
                id(i + 1, j),
                id(i + 2, j + 1),
                id(i + 1, j + 2),
                id(i, j + 1),
            ]);
        }
    }
    (nodes, elements)
}

/// NAFEMS FV12's simply supported thin square plate: L = 10, t = 0.05, E = 200 GPa, ν = 0.3,
/// ρ = 8000.
const PLATE: (f64, f64, [f64; 3]) = (10.0, 0.05, [200e9, 0.3, 8000.0]);

/// The six lowest frequencies of FV12's plate as 16 × 16 SHELL281 on a section with
/// `SECOFFSET,{offset}` (UX, UY, ROTZ held at every node, UZ on the edges, the rotation about
/// the edge's normal on each edge).
fn plate_frequencies(offset: &str) -> Vec<f64> {
    let (l, t, [e, nu, rho]) = PLATE;
    let (nodes, elements) = plate_mesh(16, l);
    let mut s = String::from("ET,        1,281\nSECTYPE,       1,SHELL,,\n");
    s += &format!("SECDATA,  {t},  1,  0.0,  3\nSECOFFSET,{offset}\n");
    s += &nblock(
        &nodes
            .iter()
            .map(|&(n, x)| (n, x, [0.0; 3]))
            .collect::<Vec<_>>(),
    );
    s += &eblock(
        &elements
            .iter()
            .map(|e| (1, 1, e.clone()))
            .collect::<Vec<_>>(),
    );
    s += &material([e, nu, rho]);
    let on = |v: f64| v.abs() < 1e-9 || (v - l).abs() < 1e-9;
    for (n, x) in &nodes {
        let mut held = vec!["UX", "UY", "ROTZ"];
        if on(x[0]) || on(x[1]) {
            held.push("UZ");
        }
        if on(x[0]) {
            held.push("ROTX");
        }
        if on(x[1]) {
            held.push("ROTY");
        }
        for lab in held {
            s += &format!("D,{n:>9},{lab:<4},  0.00000000    ,  0.00000000    \n");
        }
    }
    let dir = scratch(&format!("ansys-shell281-plate-{offset}"));
    let cdb = dir.join("plate.cdb");
    std::fs::write(&cdb, &s).unwrap();
    let o = build(&cdb, "si", 6, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let f = flexbody_reader::read(cdb.with_extension("flexbody"))
        .unwrap()
        .modes
        .frequency_hz;
    let _ = std::fs::remove_dir_all(&dir);
    f
}

/// Kirchhoff's f_mn = (π/2)(m² + n²)/L² √(D/(ρt)) of FV12's plate, its six lowest (2.3767 Hz,
/// 5.9418 ×2, 9.5069, 11.884 ×2), the bending rigidity D scaled by `rigidity`.
fn kirchhoff(rigidity: f64) -> [f64; 6] {
    let (l, t, [e, nu, rho]) = PLATE;
    let d = rigidity * e * t * t * t / (12.0 * (1.0 - nu * nu));
    let base = std::f64::consts::FRAC_PI_2 / (l * l) * (d / (rho * t)).sqrt();
    [2.0, 5.0, 5.0, 8.0, 10.0, 10.0].map(|k| k * base)
}

/// Largest |f/f_ref − 1|.
fn worst(f: &[f64], want: &[f64]) -> f64 {
    (f.iter().zip(want))
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0f64, f64::max)
}

/// FV12's plate of SHELL281 on a MID section: the six lowest frequencies equal Kirchhoff's.
///
/// Measured 2.7e-4 (the Mindlin plate's transverse shear and rotary inertia lower it, t/L =
/// 1/200; 8 × 8 elements: 7.5e-3, the mesh's discretization).
#[test]
fn shell281_simply_supported_plate_equals_kirchhoff() {
    let f = plate_frequencies("MID");
    let w = worst(&f, &kirchhoff(1.0));
    println!("SHELL281 plate: {f:?}: {w:.2e}");
    assert!(w < 2.7e-3, "{w:e}");
}

/// The same plate on a BOT section (the nodes on its bottom surface, held in plane): it bends
/// about the nodes' plane, D + E t (t/2)²/(1 − ν²) = 4 D, so Kirchhoff's frequencies double —
/// the offset through the build (nodes at the mid-surface, RBE2s to the plate's nodes).
///
/// Measured 1.5e-3 (the rotary inertia about the nodes' plane, 4 × ρt³/12, and the transverse
/// shear, whose share grows with the rigidity; MID: 2.7e-4).
#[test]
fn shell281_plate_offset_to_its_bottom_bends_about_its_nodes() {
    let f = plate_frequencies("BOT");
    let w = worst(&f, &kirchhoff(4.0));
    println!("SHELL281 BOT plate: {f:?}: {w:.2e}");
    assert!(w < 1.5e-2, "{w:e}");
}

/// What SHELL281 does not form is refused by its line: the membrane option KEYOPT(1)=1, the
/// triangle K = L = O, a record without a section, an offset element that is not flat, and
/// `LUMPM,ON` with a SHELL281 in the model.
#[test]
fn unformed_shell281_options_are_refused_by_line() {
    let (mut nodes, elements) = plate_mesh(2, 2.0);
    // lift one mid-side node of the last element: a curved element
    let lifted = elements[3][5];
    for (n, x) in nodes.iter_mut() {
        if *n == lifted {
            x[2] = 0.1;
        }
    }
    let mut s = String::from(
        "ET,        1,281\nET,        2,281\nKEYOP,        2, 1,        1\nLUMPM,ON\n",
    );
    s += "SECTYPE,       1,SHELL,,\nSECDATA,  0.01,  1,  0.0,  3\nSECOFFSET,TOP\n";
    s += &nblock(
        &nodes
            .iter()
            .map(|&(n, x)| (n, x, [0.0; 3]))
            .collect::<Vec<_>>(),
    );
    let mut triangle = elements[2].clone();
    triangle[3] = triangle[2];
    triangle[6] = triangle[2];
    // (type, section, nodes): the membrane option, no section (9), the triangle, the curved
    // offset element
    let records = vec![
        (2, 1, elements[0].clone()),
        (1, 9, elements[1].clone()),
        (1, 1, triangle),
        (1, 1, elements[3].clone()),
    ];
    s += &eblock(&records);
    s += &material([200e9, 0.3, 8000.0]);
    let first = line_of(&s, "(19i9)") + 1;
    let expected = [
        (first, "SHELL281 KEYOPT(1)=1"),
        (first + 1, "SHELL281 without a shell section (SECNUM 9)"),
        (first + 2, "SHELL281 with repeated nodes"),
        (first + 3, "formed flat only"),
    ];
    assert_refused_at(&s, "ansys-shell281-refusals", "si", &expected);
    // LUMPM is judged once the elements are formed: an archive of formed SHELL281 with it
    let lumped = String::from("ET,        1,281\nLUMPM,ON\n")
        + "SECTYPE,       1,SHELL,,\nSECDATA,  0.01,  1,  0.0,  3\n"
        + &nblock(
            &nodes
                .iter()
                .map(|&(n, x)| (n, x, [0.0; 3]))
                .collect::<Vec<_>>(),
        )
        + &eblock(&[(1, 1, elements[0].clone())])
        + &material([200e9, 0.3, 8000.0]);
    let dir = scratch("ansys-shell281-lumped");
    let cdb = dir.join("lumped.cdb");
    std::fs::write(&cdb, &lumped).unwrap();
    let o = build(&cdb, "si", 4, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("lumped.cdb:2: ") && err.contains("LUMPM,ON with SHELL281"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
