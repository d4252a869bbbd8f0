//! CPYRAM, the 5- and 13-node pyramids (issue 32), as decks written here: the constant-strain
//! patch test on a cube split into six pyramids around an off-centre apex, and a free block whose
//! cells are split into pyramids against the same block of CHEXA (8 and 20 nodes) and of the
//! pyramids split into CTETRA.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use flexbody::fe::{assemble, AssemblySpec};
use flexbody::import::{read_model, ImportOptions};

/// The faces of a hexahedron (Nastran CHEXA corner order, 0-based), each ordered so that its
/// right-hand normal points into the cell: the base of a pyramid with its apex inside.
const HEX_FACES: [[usize; 4]; 6] = [
    [0, 1, 2, 3],
    [4, 7, 6, 5],
    [0, 4, 5, 1],
    [1, 5, 6, 2],
    [2, 6, 7, 3],
    [3, 7, 4, 0],
];

/// How the cells of a block are meshed.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Cells {
    Hex20,
    Pyram5,
    Pyram13,
    /// Each pyramid of `Pyram5` split into two CTETRA along the base diagonal from its
    /// lowest-numbered corner (the same diagonal on both sides of a face).
    Tet4,
}

/// A deck of a block of `n` cells of size `h`, meshed as `cells` (steel, PSOLID ISOP FULL),
/// each cell centre moved by `shift` (times the cell size) for the pyramids' apex.
fn block(n: [usize; 3], h: f64, cells: Cells, shift: [f64; 3]) -> String {
    let mut grids: BTreeMap<[i64; 3], (u64, [f64; 3])> = BTreeMap::new();
    // nodes on a grid of half-cells, keyed by their half-cell index
    let mut node = |k: [i64; 3], x: [f64; 3]| -> u64 {
        let next = grids.len() as u64 + 1;
        grids.entry(k).or_insert((next, x)).0
    };
    let mut elems = String::new();
    let mut eid = 0;
    for (i, j, l) in
        (0..n[0]).flat_map(|i| (0..n[1]).flat_map(move |j| (0..n[2]).map(move |l| (i, j, l))))
    {
        let c = [i as i64 * 2, j as i64 * 2, l as i64 * 2];
        let corner = |a: usize| {
            let o = [
                [0, 0, 0],
                [2, 0, 0],
                [2, 2, 0],
                [0, 2, 0],
                [0, 0, 2],
                [2, 0, 2],
                [2, 2, 2],
                [0, 2, 2],
            ][a];
            [c[0] + o[0], c[1] + o[1], c[2] + o[2]]
        };
        let at = |k: [i64; 3]| k.map(|v| v as f64 * h / 2.0);
        let mid =
            |a: [i64; 3], b: [i64; 3]| [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2];
        let cen_k = [c[0] + 1, c[1] + 1, c[2] + 1];
        let cen_x = std::array::from_fn(|d| at(cen_k)[d] + shift[d] * h);
        let ks: Vec<[i64; 3]> = (0..8).map(corner).collect();
        let ids: Vec<u64> = ks.iter().map(|&k| node(k, at(k))).collect();
        match cells {
            Cells::Hex20 => {
                // Nastran CHEXA 20: corners, bottom edges, vertical edges, top edges
                let edges = [
                    (0, 1),
                    (1, 2),
                    (2, 3),
                    (3, 0),
                    (0, 4),
                    (1, 5),
                    (2, 6),
                    (3, 7),
                    (4, 5),
                    (5, 6),
                    (6, 7),
                    (7, 4),
                ];
                let mut all = ids.clone();
                for (a, b) in edges {
                    let k = mid(ks[a], ks[b]);
                    all.push(node(k, at(k)));
                }
                eid += 1;
                elems += &format!(
                    "CHEXA,{eid},1,{},+\n+,{},+\n+,{}\n",
                    join(&all[..6]),
                    join(&all[6..14]),
                    join(&all[14..])
                );
            }
            Cells::Pyram5 | Cells::Pyram13 | Cells::Tet4 => {
                // a centre key no grid point shares: odd in every direction
                let apex = node(cen_k, cen_x);
                for f in HEX_FACES {
                    let base: Vec<u64> = f.iter().map(|&a| ids[a]).collect();
                    eid += 1;
                    match cells {
                        Cells::Pyram5 => {
                            elems += &format!("CPYRAM,{eid},1,{},{apex}\n", join(&base));
                        }
                        Cells::Pyram13 => {
                            let mut all = base.clone();
                            all.push(apex);
                            for e in 0..4 {
                                let k = mid(ks[f[e]], ks[f[(e + 1) % 4]]);
                                all.push(node(k, at(k)));
                            }
                            for &a in &f {
                                // the lateral mid-side: halfway to the (shifted) apex
                                let key = [
                                    ks[a][0] * 2 + cen_k[0] * 2,
                                    ks[a][1] * 2 + cen_k[1] * 2,
                                    ks[a][2] * 2 + cen_k[2] * 2,
                                ];
                                let x = std::array::from_fn(|d| 0.5 * (at(ks[a])[d] + cen_x[d]));
                                all.push(node([key[0] + 1_000_000, key[1], key[2]], x));
                            }
                            elems += &format!(
                                "CPYRAM,{eid},1,{},+\n+,{}\n",
                                join(&all[..6]),
                                join(&all[6..])
                            );
                        }
                        _ => {
                            // split along the diagonal from the lowest-numbered corner
                            let s = (0..4).min_by_key(|&q| base[q]).unwrap_or(0);
                            let r = |q: usize| base[(s + q) % 4];
                            elems += &format!("CTETRA,{eid},1,{},{},{},{apex}\n", r(0), r(1), r(2));
                            eid += 1;
                            elems += &format!("CTETRA,{eid},1,{},{},{},{apex}\n", r(0), r(2), r(3));
                        }
                    }
                }
            }
        }
    }
    let mut s = String::from("BEGIN BULK\nMAT1,1,2.1e11,,.3,7850.\nPSOLID,1,1,,,,FULL\n");
    for (id, x) in grids.values() {
        s += &format!("GRID,{id},,{:?},{:?},{:?}\n", x[0], x[1], x[2]);
    }
    s + &elems + "ENDDATA\n"
}

fn join(ids: &[u64]) -> String {
    ids.iter()
        .map(|i| i.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

fn write(name: &str, text: &str) -> PathBuf {
    crate::nastran_support::write("cpyram", name, text)
}

/// Constant-strain patch test: on a unit cube of six pyramids around an off-centre apex, the
/// displacement u = B x gives zero force at every interior node and the strain energy
/// ½uᵀKu = ½ σ:ε · V of the exact solution.
#[test]
fn cpyram_passes_the_constant_strain_patch_test() {
    let b = [
        [1e-3, 2e-4, -3e-4],
        [5e-4, -2e-3, 1e-4],
        [-4e-4, 3e-4, 1.5e-3],
    ];
    let (e, nu) = (2.1e11, 0.3);
    let (lam, mu) = (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        e / (2.0 * (1.0 + nu)),
    );
    let eps: [[f64; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (b[i][j] + b[j][i])));
    let tr = eps[0][0] + eps[1][1] + eps[2][2];
    let w: f64 = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| (lam * tr * f64::from(u8::from(i == j)) + 2.0 * mu * eps[i][j]) * eps[i][j])
        .sum::<f64>()
        / 2.0;
    for cells in [Cells::Pyram5, Cells::Pyram13] {
        let path = write(
            &format!("patch_{cells:?}.bdf"),
            &block([1, 1, 1], 1.0, cells, [-0.05, 0.05, 0.1]),
        );
        let model = read_model(&path, &ImportOptions::default()).unwrap();
        let a = assemble(&model, &AssemblySpec::default()).unwrap();
        let k = crate::common::dense(&a.k);
        let n = a.dofs.n_dofs;
        let mut u = vec![0.0; n];
        let on_boundary = |x: [f64; 3]| {
            x.iter()
                .any(|&v| v.abs() < 1e-12 || (v - 1.0).abs() < 1e-12)
        };
        let mut interior = Vec::new();
        for (p, node) in model.nodes.iter().enumerate() {
            for i in 0..3 {
                u[a.dofs.first[p] + i] = (0..3).map(|j| b[i][j] * node.x[j]).sum();
            }
            if !on_boundary(node.x) {
                interior.extend((0..3).map(|i| a.dofs.first[p] + i));
            }
        }
        let ku: Vec<f64> = (0..n)
            .map(|r| (0..n).map(|c| k[(r, c)] * u[c]).sum())
            .collect();
        let top = ku.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let force = interior.iter().fold(0.0f64, |m, &d| m.max(ku[d].abs())) / top;
        let energy = 0.5 * u.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>();
        println!(
            "{cells:?}: {} interior nodes, force {force:.1e} of the largest, energy {energy:e} vs {w:e} ({:.1e})",
            interior.len() / 3,
            (energy - w).abs() / w
        );
        assert!(force < 1e-12 && (energy - w).abs() < 1e-12 * w, "{cells:?}");
    }
}

/// Frequencies (Hz) of a free block through the CLI with consistent mass, its six rigid
/// modes dropped.
fn flexible_hz(path: &Path, modes: usize) -> Vec<f64> {
    let f = crate::nastran_support::built_hz(path, modes + 6, &["--mass", "consistent"]);
    assert!(
        f[..6].iter().all(|&x| x < 1e-3 * f[6]),
        "six rigid modes: {f:?}"
    );
    f[6..].to_vec()
}

/// A free steel block 50 × 50 × 200 mm, its cells split into six pyramids around the cell
/// centre, on 2 × 2 × 8 and 4 × 4 × 16 cells with consistent mass (conforming elements: the
/// frequencies are upper bounds that fall with refinement), against CHEXA 20 on the fine cells
/// as the reference, on the first three flexible modes (two bending, one axial; higher modes
/// change order between the linear and the quadratic meshes): both pyramids converge to it at the rate of a linearly complete element
/// (error ratio ≈ 4 per halving; the collapsed 13-node pyramid is not quadratically
/// complete), CPYRAM 13 within 0.5 % of it on the fine cells, and CPYRAM 5 no worse than its
/// own split into two CTETRA per pyramid.
#[test]
fn cpyram_block_converges_to_chexa20_and_beats_its_tetrahedra() {
    let f = |cells: Cells, n: [usize; 3]| {
        let h = 0.05 / n[0] as f64;
        let path = write(
            &format!("block_{cells:?}_{}.bdf", n[0]),
            &block(n, h, cells, [0.0; 3]),
        );
        flexible_hz(&path, 3)
    };
    let (coarse, fine) = ([2, 2, 8], [4, 4, 16]);
    let reference = f(Cells::Hex20, fine);
    println!("CHEXA20 {fine:?}: {reference:.2?}");
    let err =
        |v: &[f64]| -> Vec<f64> { v.iter().zip(&reference).map(|(a, b)| a / b - 1.0).collect() };
    for cells in [Cells::Pyram13, Cells::Pyram5] {
        let (ec, ef) = (err(&f(cells, coarse)), err(&f(cells, fine)));
        println!("{cells:?}: error {ec:.4?} on {coarse:?}, {ef:.4?} on {fine:?}");
        for j in 0..3 {
            assert!(
                ef[j] > 0.0 && ec[j] / ef[j] > 3.0,
                "{cells:?} mode {j}: {} {}",
                ec[j],
                ef[j]
            );
        }
        if cells == Cells::Pyram13 {
            assert!(ef.iter().all(|&e| e < 5e-3), "{ef:?}");
        } else {
            for n in [coarse, fine] {
                let (ep, et) = (err(&f(Cells::Pyram5, n)), err(&f(Cells::Tet4, n)));
                println!("  {n:?}: CPYRAM5 {ep:.4?}, its CTETRA split {et:.4?}");
                assert!((0..3).all(|j| ep[j] <= et[j]), "{n:?}");
            }
        }
    }
}

/// Stress shapes on pyramids through the CLI (`--stress-modes`; before, the apex's singular
/// map left NaN and the build failed): a free block of skewed CPYRAM 5 and 13 has a finite
/// value at every node (the apex takes its element's centroid gradients), and its six rigid
/// modes, being linear fields, are strain-free next to the flexible modes (measured ≤ 1.7e-14
/// of them).
#[test]
fn cpyram_stress_modes_are_finite_and_rigid_modes_strain_free() {
    for cells in [Cells::Pyram5, Cells::Pyram13] {
        let path = write(
            &format!("stress_{cells:?}.bdf"),
            &block([2, 1, 1], 0.05, cells, [-0.05, 0.05, 0.1]),
        );
        crate::nastran_support::built_hz(&path, 9, &["--stress-modes", "--mass", "consistent"]);
        let body = flexbody_reader::read(path.with_extension("flexbody")).unwrap();
        let stress = body
            .stress_shapes
            .as_ref()
            .expect("--stress-modes stores stress");
        assert_eq!(stress.nodes.len(), body.node_count(), "{cells:?}");
        assert!(stress.values.iter().all(|v| v.is_finite()), "{cells:?}");
        let k = stress.nodes.len() * 6;
        let mode_max = |j: usize| {
            stress.values[j * k..(j + 1) * k]
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()))
        };
        let rigid = (0..6).map(mode_max).fold(0.0, f64::max);
        let flexible = (6..9).map(mode_max).fold(f64::INFINITY, f64::min);
        println!(
            "{cells:?}: rigid-mode stress {:.1e} of flexible",
            rigid / flexible
        );
        assert!(
            rigid < 2e-13 * flexible,
            "{cells:?}: {rigid:e} vs {flexible:e}"
        );
    }
}
