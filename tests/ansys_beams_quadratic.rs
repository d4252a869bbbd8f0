//! BEAM188 with KEYOPT(3)=2 (quadratic: ANSYS adds an internal node at the middle of each
//! element; Workbench writes its line bodies so) against ANSYS's own strain energies: the frame
//! of ansys/example-data's `post_beam_result_01.rst` (ANSYS 2024 R2, static; 40 beams; converted
//! by `tests/data/ansys/make_beam188_quadratic.py`), whose ENG record holds each element's
//! strain energy SENE = ½ u_eᵀ K_e u_e at ANSYS's displacements and rotations u, the internal
//! nodes' included.
//!
//! - the archive (nodes I, J and the orientation node, as an archive holds them) builds with an
//!   internal node per beam at the middle of IJ, where ANSYS's result file has it;
//! - element by element, with the section constants ANSYS computed on its section mesh (in the
//!   csv: J and the shear factors differ from the rectangle's closed form by 1.4 % and 0.9 %),
//!   ½ u_eᵀ K_e u_e equals ANSYS's SENE: the internal node is a node of the element's quadratic
//!   functions with two points along the length, as BEAM189;
//! - through the CLI the archive equals the same beams written as BEAM189 with the middle nodes
//!   given.

use std::collections::HashMap;

use crate::ansys_support::writers::{eblock, nblock};
use crate::ansys_support::{build_modes, data};
use crate::common::{assert_frequencies, scratch};
use flexbody::fe::assembly::element_matrices;
use flexbody::fe::AssemblySpec;
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::{ElementKind, Section};

/// ANSYS's solution: node id → (x, u, rot), element id → (volume, SENE), section id → (A, Iyy,
/// Izz, J, ky, kz).
struct Solution {
    nodes: HashMap<u64, [f64; 9]>,
    elements: HashMap<u64, [f64; 2]>,
    sections: HashMap<u64, [f64; 6]>,
}

fn solution() -> Solution {
    let text = std::fs::read_to_string(data("beam188_quadratic.csv")).unwrap();
    let mut s = Solution {
        nodes: HashMap::new(),
        elements: HashMap::new(),
        sections: HashMap::new(),
    };
    for line in text.lines() {
        let f: Vec<&str> = line.split(',').collect();
        let id: u64 = f[1].parse().unwrap();
        let v: Vec<f64> = f[2..].iter().map(|t| t.parse().unwrap()).collect();
        match f[0] {
            "node" => drop(s.nodes.insert(id, std::array::from_fn(|i| v[i]))),
            "element" => drop(s.elements.insert(id, [v[0], v[1]])),
            _ => drop(s.sections.insert(id, std::array::from_fn(|i| v[i]))),
        }
    }
    s
}

/// Each beam's ½ u_eᵀ K_e u_e against ANSYS's SENE, on ANSYS's section constants. ANSYS writes
/// ENG in single precision (6e-8 relative) and the energies span 0.59 to 1.7e-6, so the
/// measure is |½ u_eᵀ K_e u_e − SENE| over the largest SENE: measured 3.3e-8 (the
/// rectangle's closed-form shear factor instead of ANSYS's: 1.0e-7; its closed-form J: 3.5e-5;
/// J = Iyy + Izz: 4.1e-4), and over the element's own SENE where it is at least 1 % of the
/// largest: 6.4e-7. The internal nodes: each at ANSYS's internal node's place to 1.2e-15 of
/// the element's length.
#[test]
fn beam188_quadratic_equals_ansys_strain_energies() {
    let s = solution();
    let mut model = read_model(&data("beam188_quadratic.cdb"), &ImportOptions::default()).unwrap();
    assert_eq!(model.elements.len(), 40);
    assert_eq!(model.nodes.len(), 81 + 40, "one internal node per beam");
    // ANSYS's section constants (its section mesh's J and shear factors) for the comparison
    // of the element's formulation
    let mut beam_properties = 0;
    for p in &mut model.properties {
        let Section::Beam(b) = &mut p.section else {
            continue;
        };
        // named "BEAM188 KEYOPT(3)=2 SECNUM s MATm" by the importer
        let secnum: u64 = (p.name.split("SECNUM ").nth(1))
            .and_then(|t| t.split(' ').next())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("{}: no SECNUM", p.name));
        let [a, iyy, izz, j, ky, kz] = s.sections[&secnum];
        (b.area, b.i1, b.i2, b.j, b.shear_factors) = (a, izz, iyy, j, Some([ky, kz]));
        beam_properties += 1;
    }
    assert_eq!(beam_properties, 4);
    let spec = AssemblySpec::default();
    let largest = s.elements.values().map(|v| v[1]).fold(0.0, f64::max);
    let (mut worst, mut worst_large, mut placed) = (0.0f64, 0.0f64, 0.0f64);
    for (e, el) in model.elements.iter().enumerate() {
        assert_eq!(el.kind, ElementKind::Beam3Quadratic);
        // ANSYS's internal node of this element: the solved node at the middle of IJ
        let [xi, xj, xm] = [0, 1, 2].map(|k| model.nodes[el.nodes[k]].x);
        let length = (0..3).map(|c| (xj[c] - xi[c]).powi(2)).sum::<f64>().sqrt();
        let ansys_mid = (s.nodes.iter())
            .filter(|(_, v)| (0..3).all(|c| (v[c] - xm[c]).abs() < 1e-6 * length))
            .map(|(&id, _)| id)
            .collect::<Vec<_>>();
        assert_eq!(ansys_mid.len(), 1, "element {}: {ansys_mid:?}", el.id);
        let at = s.nodes[&ansys_mid[0]];
        placed = placed.max((0..3).map(|c| (at[c] - xm[c]).abs()).fold(0.0, f64::max) / length);
        let solved = |k: usize| match k {
            2 => at,
            _ => s.nodes[&model.nodes[el.nodes[k]].id],
        };
        let u: Vec<f64> = (0..3).flat_map(|k| solved(k)[3..9].to_vec()).collect();
        let em = element_matrices(&model, e, &spec).unwrap();
        let nd = u.len();
        assert_eq!(em.k.len(), nd * nd);
        let energy: f64 = (0..nd)
            .map(|i| u[i] * (0..nd).map(|j| em.k[i * nd + j] * u[j]).sum::<f64>())
            .sum::<f64>()
            / 2.0;
        let sene = s.elements[&el.id][1];
        worst = worst.max((energy - sene).abs() / largest);
        if sene >= 1e-2 * largest {
            worst_large = worst_large.max((energy / sene - 1.0).abs());
        }
    }
    println!(
        "max |½ uᵀ K_e u − SENE| / max SENE = {worst:.2e}, relative on the larger elements \
         {worst_large:.2e}; internal nodes placed to {placed:.1e}"
    );
    assert!(placed < 1e-12, "{placed:e}");
    assert!(worst < 5e-8, "{worst:e}");
    assert!(worst_large < 2e-6, "{worst_large:e}");
}

/// Through the CLI, free-free: the archive of BEAM188 KEYOPT(3)=2 equals the same beams written
/// as BEAM189 (ET 189) with the middle nodes given (at the internal nodes' places and numbers):
/// the internal node is the quadratic beam's middle node, stiffness and mass. Measured: the
/// frequencies equal to the last bit (0.0).
#[test]
fn beam188_quadratic_archive_equals_beam189_with_the_middle_nodes() {
    let text = std::fs::read_to_string(data("beam188_quadratic.cdb")).unwrap();
    let model = read_model(&data("beam188_quadratic.cdb"), &ImportOptions::default()).unwrap();
    // the archive's records: element id → (section, I, J, K)
    let start = text.lines().position(|l| l == "(19i9)").unwrap() + 1;
    let records: HashMap<u64, [u64; 4]> = (text.lines().skip(start))
        .take_while(|l| l.trim() != "-1")
        .map(|l| {
            let f: Vec<u64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            (f[10], [f[3], f[11], f[12], f[13]])
        })
        .collect();
    let nodes: Vec<(u64, [f64; 3], [f64; 3])> = (model.nodes.iter())
        .map(|n| (n.id, n.x, [0.0; 3]))
        .collect();
    let beam189: Vec<(usize, usize, Vec<u64>)> = (model.elements.iter())
        .map(|el| {
            let [section, i, j, k] = records[&el.id];
            let mid = model.nodes[el.nodes[2]].id;
            (1, section as usize, vec![i, j, mid, k])
        })
        .collect();
    let kept = |l: &&str| l.starts_with("SEC") || l.starts_with("MP");
    let constants: String = text
        .lines()
        .filter(kept)
        .map(|l| format!("{l}\n"))
        .collect();
    let dir = scratch("ansys-beam188-quadratic");
    let quadratic = dir.join("quadratic.cdb");
    std::fs::write(&quadratic, &text).unwrap();
    let written = dir.join("beam189.cdb");
    let archive = format!(
        "ET,        1,189\n{}{}{constants}",
        nblock(&nodes),
        eblock(&beam189)
    );
    std::fs::write(&written, archive).unwrap();
    let ours = build_modes(&quadratic, 12, &[]);
    let reference = build_modes(&written, 12, &[]);
    assert!(ours[5] < 1e-3 * ours[6], "six rigid modes first: {ours:?}");
    let worst = assert_frequencies("BEAM188 KEYOPT(3)=2", &ours, &reference, 6, 1e-12);
    println!("BEAM188 KEYOPT(3)=2 against BEAM189: {worst:.1e}");
    let _ = std::fs::remove_dir_all(&dir);
}
