//! The 15-node wedge from every format (issue 48): Nastran CPENTA with 15 grids and Gmsh's
//! prism15 (type 18) are formed as CalculiX forms its C3D15 (`fe/elements/prism15.rs`).
//!
//! * The decks of `fixtures/ccx_prism15` (a steel cantilever 1 × 0.1 × 0.1 m of C3D15 wedges,
//!   refined uniformly 2×1×1 → 4×2×2 → 8×4×4 cells) built through the CLI equal ccx 2.20's
//!   frequencies to its printed digits, and so does the same mesh written as a Nastran deck
//!   (CPENTA, grids 10–12 the vertical edges as Nastran orders them).
//! * The refinement converges: the first two bending frequencies' differences shrink by ≥ 4
//!   per halving (second order), and the extrapolated first frequency is within 1 % of
//!   Euler–Bernoulli's 1.8751²/(2π) √(EI/(ρAL⁴)) = 83.55 Hz (shear lowers it).
//! * One mesh read from a `.inp`, a `.bdf` and a `.msh` gives the same free-free frequencies
//!   to 1e-10 (measured: identical), lumped and consistent.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::common::{build_as_ccx, generalized_eigenvalues, hz, scratch};
use flexbody::fe::{assemble, AssemblySpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::{ElementKind, Model};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/ccx_prism15")
        .join(name)
}

/// CalculiX C3D15 order → Nastran CPENTA (vertical edges before the top ones).
fn nastran_order(n: &[u64]) -> Vec<u64> {
    [&n[..9], &n[12..15], &n[9..12]].concat()
}

/// CalculiX C3D15 order → Gmsh prism15 (edges 0-1, 0-2, 0-3, 1-2, 1-4, 2-5, 3-4, 3-5, 4-5).
fn gmsh_order(n: &[u64]) -> Vec<u64> {
    let ccx_of_gmsh = [0, 1, 2, 3, 4, 5, 6, 8, 12, 7, 13, 14, 9, 11, 10];
    ccx_of_gmsh.iter().map(|&i| n[i]).collect()
}

fn ids(m: &Model, e: usize) -> Vec<u64> {
    m.elements[e].nodes.iter().map(|&n| m.nodes[n].id).collect()
}

/// `m` (C3D15 wedges of steel) as a Nastran deck: clamped at x = 0 by SPC1 when `clamped`,
/// consistent mass (PARAM,COUPMASS), ten modes.
fn bdf(m: &Model, clamped: bool) -> String {
    let mut s = String::from("SOL 103\nCEND\n");
    if clamped {
        s.push_str("SPC = 1\n");
    }
    s.push_str(
        "METHOD = 1\nBEGIN BULK\nEIGRL,1,,,10\nPARAM,COUPMASS,1\nMAT1,1,2.1e11,,0.3,7850.\n\
         PSOLID,1,1\n",
    );
    for n in &m.nodes {
        writeln!(s, "GRID,{},,{:?},{:?},{:?}", n.id, n.x[0], n.x[1], n.x[2]).unwrap();
        if clamped && n.x[0] == 0.0 {
            writeln!(s, "SPC1,1,123,{}", n.id).unwrap();
        }
    }
    for (e, el) in m.elements.iter().enumerate() {
        assert_eq!(el.kind, ElementKind::Prism15);
        let g: Vec<String> = nastran_order(&ids(m, e))
            .iter()
            .map(u64::to_string)
            .collect();
        writeln!(
            s,
            "CPENTA,{},1,{},+\n+,{},+\n+,{}",
            el.id,
            g[..6].join(","),
            g[6..14].join(","),
            g[14]
        )
        .unwrap();
    }
    s.push_str("ENDDATA\n");
    s
}

/// `m` as a Gmsh 4.1 mesh (one volume entity, the wedges as type 18).
fn msh(m: &Model) -> String {
    let n = m.nodes.len();
    let mut s = format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 {n} 1 {n}\n3 1 0 {n}\n");
    for (i, node) in m.nodes.iter().enumerate() {
        assert_eq!(node.id, i as u64 + 1, "contiguous node ids");
        writeln!(s, "{}", node.id).unwrap();
    }
    for node in &m.nodes {
        writeln!(s, "{:?} {:?} {:?}", node.x[0], node.x[1], node.x[2]).unwrap();
    }
    let ne = m.elements.len();
    write!(s, "$EndNodes\n$Elements\n1 {ne} 1 {ne}\n3 1 18 {ne}\n").unwrap();
    for (e, el) in m.elements.iter().enumerate() {
        let g: Vec<String> = gmsh_order(&ids(m, e)).iter().map(u64::to_string).collect();
        writeln!(s, "{} {}", el.id, g.join(" ")).unwrap();
    }
    s.push_str("$EndElements\n");
    s
}

/// `m` as a CalculiX deck without its boundary (free-free).
fn inp(m: &Model) -> String {
    let mut s = String::from("*NODE\n");
    for n in &m.nodes {
        writeln!(s, "{}, {:?}, {:?}, {:?}", n.id, n.x[0], n.x[1], n.x[2]).unwrap();
    }
    s.push_str("*ELEMENT, TYPE=C3D15, ELSET=BAR\n");
    for (e, el) in m.elements.iter().enumerate() {
        let g: Vec<String> = ids(m, e).iter().map(u64::to_string).collect();
        writeln!(s, "{}, {}", el.id, g.join(", ")).unwrap();
    }
    s.push_str(
        "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850.\n\
         *SOLID SECTION, ELSET=BAR, MATERIAL=STEEL\n",
    );
    s
}

fn read(path: &Path) -> Model {
    let opts = ImportOptions {
        material: Some(crate::common::steel()),
        ..ImportOptions::default()
    };
    read_model(path, &opts).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Frequencies (Hz) of `flexbody build DECK --method normal --mass consistent` (CLI), the
/// file written into `dir`.
fn built_hz(deck: &Path, dir: &Path) -> Vec<f64> {
    let stem = deck.file_stem().and_then(|s| s.to_str()).unwrap_or("deck");
    let ext = deck.extension().and_then(|s| s.to_str()).unwrap_or("");
    let out = dir.join(format!("{stem}_{ext}.flexbody"));
    let o = build_as_ccx(deck, &["-q", "--modes", "10"], &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    flexbody_reader::read(&out).unwrap().modes.frequency_hz
}

fn worst_relative(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    (got.iter().zip(want))
        .map(|(g, w)| (g - w).abs() / w)
        .fold(0.0, f64::max)
}

const DECKS: [&str; 3] = ["bar_2x1x1", "bar_4x2x2", "bar_8x4x4"];

/// CalculiX's C3D15 decks and the same meshes as Nastran CPENTA decks, built through the CLI,
/// give ccx 2.20's frequencies.
#[test]
fn c3d15_and_cpenta15_decks_give_ccx_frequencies() {
    let dir = scratch("prism15-ccx");
    for name in DECKS {
        let want = crate::common::ccx_frequencies("ccx_prism15", name);
        let deck = fixture(&format!("{name}.inp"));
        let got = built_hz(&deck, &dir);
        // ccx prints 7 digits: measured ≤ 3.1e-7 relative (bar_8x4x4), .inp and .bdf alike
        let inp_error = worst_relative(&got, &want);
        assert!(inp_error < 1e-6, "{name}.inp: {got:?} vs ccx {want:?}");
        let bdf_path = dir.join(format!("{name}.bdf"));
        std::fs::write(&bdf_path, bdf(&read(&deck), true)).unwrap();
        let got_bdf = built_hz(&bdf_path, &dir);
        let bdf_error = worst_relative(&got_bdf, &want);
        assert!(bdf_error < 1e-6, "{name}.bdf: {got_bdf:?} vs ccx {want:?}");
        // the two readers give one model: measured 0 (the same bits)
        assert!(
            worst_relative(&got_bdf, &got) < 1e-10,
            "{got_bdf:?} vs {got:?}"
        );
    }
}

/// An orthotropic C3D15 bar (`*ELASTIC, TYPE=ENGINEERING CONSTANTS` turned by an
/// `*ORIENTATION` about two axes, so D is fully anisotropic in the bar's axes: the wedge's
/// anisotropic stiffness through the `Element` trait's integration points) gives ccx 2.20's
/// frequencies.
#[test]
fn orthotropic_c3d15_deck_gives_ccx_frequencies() {
    let dir = scratch("prism15-ortho");
    let want = crate::common::ccx_frequencies("ccx_prism15", "ortho_4x2x2");
    let got = built_hz(&fixture("ortho_4x2x2.inp"), &dir);
    let error = worst_relative(&got, &want);
    println!("ortho_4x2x2: {error:.1e} against ccx");
    // ccx prints 7 digits: measured 4.0e-7
    assert!(error < 1e-6, "{got:?} vs ccx {want:?}");
}

/// Uniform refinement converges at second order or better to the cantilever's first bending
/// frequencies, and the extrapolated value is within 1 % of Euler–Bernoulli.
#[test]
fn cpenta15_cantilever_converges() {
    let dir = scratch("prism15-convergence");
    let f: Vec<Vec<f64>> = DECKS
        .iter()
        .map(|name| {
            let path = dir.join(format!("{name}.bdf"));
            std::fs::write(&path, bdf(&read(&fixture(&format!("{name}.inp"))), true)).unwrap();
            built_hz(&path, &dir)
        })
        .collect();
    // Euler–Bernoulli, clamped–free: (1.8751²/2π) √(EI/(ρAL⁴)), I = bh³/12
    let (e, rho, b, h, l) = (2.1e11f64, 7850.0f64, 0.1f64, 0.1f64, 1.0f64);
    let eb = 1.875104f64.powi(2) / (2.0 * std::f64::consts::PI)
        * (e * b * h.powi(3) / 12.0 / (rho * b * h * l.powi(4))).sqrt();
    assert!((eb - 83.55).abs() < 0.01, "{eb}");
    let [coarse, middle, fine] = [&f[0], &f[1], &f[2]];
    for mode in 0..2 {
        let (f1, f2, f3) = (coarse[mode], middle[mode], fine[mode]);
        // from above (a stiff coarse mesh), each halving shrinking the change ≥ 4×:
        // measured 4.46 (mode 1), 4.01 (mode 2)
        let ratio = (f1 - f2) / (f2 - f3);
        assert!(
            f1 > f2 && f2 > f3 && ratio > 3.8,
            "mode {mode}: {f1} {f2} {f3}"
        );
        // Richardson with the observed order: measured 83.430 Hz (−0.145 %), 83.432 Hz
        let extrapolated = f3 - (f2 - f3) / (ratio - 1.0);
        let gap = (extrapolated - eb) / eb;
        assert!(
            gap.abs() < 0.01,
            "mode {mode}: {extrapolated} Hz vs EB {eb}"
        );
    }
}

/// Free-free frequencies (Hz) of `m` with `mass`, dense, the six rigid modes left out.
fn free_hz(m: &Model, mass: MassKind) -> Vec<f64> {
    let spec = AssemblySpec {
        mass,
        ..AssemblySpec::default()
    };
    let a = assemble(m, &spec).unwrap();
    let k = crate::common::dense(&a.k);
    let mut mm = crate::common::dense(&a.m);
    if mass == MassKind::Consistent {
        // ccx's 9-point mass has rank 9 of 15 per wedge: a tiny multiple of the lumped one
        // keeps M definite for the Cholesky without changing the comparison
        let lumped = crate::common::dense(&assemble(m, &AssemblySpec::default()).unwrap().m);
        for i in 0..mm.nrows() {
            mm[(i, i)] += 1e-3 * lumped[(i, i)];
        }
    }
    generalized_eigenvalues(&k, &mm)
        .into_iter()
        .skip(6)
        .map(hz)
        .collect()
}

/// One mesh through the three importers: the same frequencies (≤ 1e-10).
#[test]
fn one_wedge_mesh_through_three_importers_gives_one_answer() {
    let dir = scratch("prism15-formats");
    let mesh = read(&fixture("bar_4x2x2.inp"));
    let paths: Vec<PathBuf> = [("free.inp", inp(&mesh)), ("free.bdf", bdf(&mesh, false))]
        .into_iter()
        .chain([("free.msh", msh(&mesh))])
        .map(|(name, text)| {
            let p = dir.join(name);
            std::fs::write(&p, text).unwrap();
            p
        })
        .collect();
    let models: Vec<Model> = paths.iter().map(|p| read(p)).collect();
    for m in &models {
        assert_eq!(m.elements.len(), mesh.elements.len());
        assert!(m.elements.iter().all(|e| e.kind == ElementKind::Prism15));
    }
    for mass in [MassKind::Lumped, MassKind::Consistent] {
        let f: Vec<Vec<f64>> = models.iter().map(|m| free_hz(m, mass)).collect();
        assert!(
            f[0][0] > 50.0,
            "{mass:?}: the first elastic mode {}",
            f[0][0]
        );
        for (other, name) in [(&f[1], "bdf"), (&f[2], "msh")] {
            // measured 0: the three models are formed alike to the last bit
            let worst = worst_relative(other, &f[0]);
            assert!(worst <= 1e-10, "{mass:?} {name}: {worst:e}");
        }
    }
}
