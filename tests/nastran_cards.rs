//! The Nastran cards of issue 32, each honoured as MSC Nastran models it, tested on decks written
//! here against an independent reference: a closed form, or the same model with an equivalent
//! element (a CELAS2 equal to a CROD, a CMASS2 equal to a CONM2's inertia, CONM1 equal to the
//! CONM2 it describes, an MPC and RBAR/RBAR1/RBE1 equal to the RBE2 they describe, CONROD equal
//! to CROD + PROD, a CBUSH's offset and orientation equal to rigid links and a rotated system, a
//! CBUSH of 1e12 equal to a clamp, SPOINT spring–mass systems in closed form).

use std::f64::consts::PI;
use std::path::Path;

use crate::common::{generalized_eigenvalues, hz};
use crate::nastran_support::{build_refused, built_hz, write};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec};
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::Model;

/// Frequencies (Hz) of the constrained model by a dense generalized eigen-solve (small models),
/// independent of the build's eigensolver.
fn dense_hz(model: &Model) -> Vec<f64> {
    let a = assemble(model, &AssemblySpec::default()).unwrap();
    let r = eliminate(model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    let (k, m) = (crate::common::dense(&r.k), crate::common::dense(&r.m));
    generalized_eigenvalues(&k, &m)
        .into_iter()
        .map(hz)
        .collect()
}

/// The lowest `n` frequencies (Hz) of the constrained model by the library's shift-invert
/// eigensolver (for stiff models a dense solve through M⁻¹ cannot resolve).
fn sparse_hz(model: &Model, n: usize) -> Vec<f64> {
    use flexbody::reduce::{normal::normal_modes, select::ModeCount};
    let a = assemble(model, &AssemblySpec::default()).unwrap();
    let r = eliminate(model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    let set = normal_modes(&r.k, &r.m, ModeCount::Count(n), &[], &Default::default()).unwrap();
    set.frequencies_hz()
}

fn read(path: &Path) -> Model {
    read_model(path, &ImportOptions::default()).unwrap()
}

/// Largest relative difference of two frequency lists (same length).
fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / y.abs().max(1e-300))
        .fold(0.0, f64::max)
}

/// An axial chain: grid 1 clamped, grids 2–5 each with mass 2 on a CONM2, every grid moving
/// along x only (PS 23456); the four segments are `link(i)` (cards joining grid i to i + 1,
/// EA/L = 8e7 each). `bend` moves the grids off the x axis by y = bend·i² (scalar springs do
/// not care where their grids are; it keeps a line of 3-dof grids from hiding the rotation
/// about it from the build's rigid-mode count).
fn axial_chain(bend: f64, link: impl Fn(usize) -> String) -> String {
    let mut s = String::from("SOL 103\nCEND\nSPC = 1\nBEGIN BULK\nMAT1,1,2.e11,,.3,0.\n");
    for i in 1..=5 {
        let y = bend * (i * i) as f64;
        s += &format!("GRID,{i},,{:?},{y:?},0.,,23456\n", (i - 1) as f64 * 0.25);
    }
    for i in 2..=5 {
        s += &format!("CONM2,{},{i},,2.\n", 100 + i);
    }
    for i in 1..=4 {
        s += &link(i);
    }
    s + "SPC1,1,1,1\nENDDATA\n"
}

/// Fixed–free chain of n springs k and n masses m: ω_j = 2√(k/m) sin((2j − 1)π / (2(2n + 1))).
fn chain_closed_form(n: usize, k: f64, m: f64) -> Vec<f64> {
    (1..=n)
        .map(|j| {
            let w =
                2.0 * (k / m).sqrt() * ((2 * j - 1) as f64 * PI / (2.0 * (2 * n + 1) as f64)).sin();
            w / (2.0 * PI)
        })
        .collect()
}

#[test]
fn celas2_equals_crod_and_the_chain_closed_form() {
    let rods = axial_chain(0.0, |i| {
        format!("CROD,{i},7,{i},{}\n", i + 1) + if i == 1 { "PROD,7,1,1.e-4\n" } else { "" }
    });
    let springs = axial_chain(0.1, |i| format!("CELAS2,{i},8.e7,{i},1,{},1\n", i + 1));
    let (pr, ps) = (
        write("celas", "rods.bdf", &rods),
        write("celas", "springs.bdf", &springs),
    );
    let (fr, fs) = (built_hz(&pr, 4, &[]), built_hz(&ps, 4, &[]));
    let exact = chain_closed_form(4, 8e7, 2.0);
    println!("CROD {fr:?}\nCELAS2 {fs:?}\nclosed form {exact:?}");
    println!(
        "CELAS2 vs CROD {:.1e}, vs closed form {:.1e}",
        rel(&fs, &fr),
        rel(&fs, &exact)
    );
    assert!(rel(&fs, &fr) < 1e-12);
    assert!(rel(&fs, &exact) < 1e-12 && rel(&fr, &exact) < 1e-12);
}

/// A free-field continuation line may begin with blanks before its comma (MSC's fmondsp.dat
/// writes "       , 0., 0.02, …"): the CONM2 masses written so equal the chain's closed form.
#[test]
fn free_field_continuations_may_start_with_blanks() {
    let indented = axial_chain(0.0, |i| {
        format!("CROD,{i},7,{i},{}\n", i + 1) + if i == 1 { "PROD,7,1,1.e-4\n" } else { "" }
    })
    .replace(
        "CONM2,103,3,,2.\n",
        "CONM2,103,3,,2.,,,,\n       , 0., 0., 0., 0., 0., 0.\n",
    );
    assert!(indented.contains("\n       , 0."));
    let path = write("indented", "chain.bdf", &indented);
    let f = built_hz(&path, 4, &[]);
    let exact = chain_closed_form(4, 8e7, 2.0);
    // measured 1e-15 (before: the line was refused as "a line without a card name")
    assert!(rel(&f, &exact) < 1e-12, "{f:?} {exact:?}");
}

/// A massless torsion rod (CROD, GJ/L = 7.8e4·…) clamped at grid 1 with a tip body at grid 2
/// (mass 3, I_xx = 0.5), the tip held in y, z and the bending rotations: two modes, axial
/// ω² = (EA/L)/m and torsion ω² = (GJ/L)/I_xx. The tip body is a CONM2 (M, I11), or scalar
/// masses: CMASS2 on components 1, 2, 3 and CMASS1/PMASS on component 4.
fn torsion_deck(tip: &str) -> String {
    format!(
        "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\nMAT1,1,2.e11,8.e10,,0.\nPROD,7,1,1.e-4,2.e-8\n\
         GRID,1,,0.,0.,0.\nGRID,2,,0.5,0.,0.,,2356\nCROD,1,7,1,2\nSPC1,1,123456,1\n{tip}ENDDATA\n"
    )
}

#[test]
fn cmass2_equals_a_conm2_inertia_and_the_torsion_closed_form() {
    let conm2 = torsion_deck("CONM2,10,2,,3.,,,,,+\n+,0.5\n");
    let cmass = torsion_deck(
        "CMASS2,11,3.,2,1\nCMASS2,12,3.,2,2\nCMASS2,13,3.,2,3\nCMASS1,14,20,2,4\nPMASS,20,0.5\n",
    );
    let (pa, pb) = (
        write("cmass", "conm2.bdf", &conm2),
        write("cmass", "cmass.bdf", &cmass),
    );
    let (fa, fb) = (built_hz(&pa, 2, &[]), built_hz(&pb, 2, &[]));
    let (ea, gj) = (2e11 * 1e-4 / 0.5, 8e10 * 2e-8 / 0.5);
    let mut exact = vec![hz(gj / 0.5), hz(ea / 3.0)];
    exact.sort_by(f64::total_cmp);
    println!("CONM2 {fa:?}\nCMASS {fb:?}\nclosed form {exact:?}");
    println!(
        "CMASS vs CONM2 {:.1e}, vs closed form {:.1e}",
        rel(&fb, &fa),
        rel(&fb, &exact)
    );
    assert!(rel(&fb, &fa) < 1e-12 && rel(&fb, &exact) < 1e-12);
    // the scalar masses are the model's: three translations and one rotation at grid 2
    let m = read(&pb);
    assert_eq!(m.scalar_masses.len(), 4);
    assert_eq!(m.scalar_masses[3].m, 0.5);
}

/// A cantilever of four CBARs (grid 1 clamped) with a tip body at grid 5: mass 2, centre of
/// gravity offset (0.1, 0.05, −0.02), inertia about it with products of inertia.
fn tip_body_deck(tip: &str) -> String {
    let mut s = String::from(
        "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\nMAT1,1,7.e10,,.33,2700.\n\
         PBAR,2,1,1.e-4,2.e-9,1.e-9,3.e-9\n",
    );
    for i in 1..=5 {
        s += &format!("GRID,{i},,{:?},0.,0.\n", (i - 1) as f64 * 0.2);
    }
    for i in 1..=4 {
        s += &format!("CBAR,{i},2,{i},{},0.,1.,0.\n", i + 1);
    }
    s + "SPC1,1,123456,1\n" + tip + "ENDDATA\n"
}

/// The 6×6 mass matrix of a point mass m at offset e with inertia I_cg about its centre of
/// gravity (rigid-body kinetic energy): [m I, −m ẽ; m ẽ, I_cg − m ẽ ẽ].
fn point_mass_6x6(m: f64, e: [f64; 3], i: [[f64; 3]; 3]) -> [[f64; 6]; 6] {
    let et = [[0.0, -e[2], e[1]], [e[2], 0.0, -e[0]], [-e[1], e[0], 0.0]];
    let mut out = [[0.0; 6]; 6];
    for r in 0..3 {
        out[r][r] = m;
        for c in 0..3 {
            out[r][3 + c] = -m * et[r][c];
            out[3 + r][c] = m * et[r][c];
            let ee: f64 = (0..3).map(|k| et[r][k] * et[k][c]).sum();
            out[3 + r][3 + c] = i[r][c] - m * ee;
        }
    }
    out
}

#[test]
fn conm1_equals_the_conm2_it_describes() {
    let (m, e) = (2.0, [0.1, 0.05, -0.02]);
    // CONM2 I11 I21 I22 I31 I32 I33: the tensor [I11 −I21 −I31; −I21 I22 −I32; −I31 −I32 I33]
    let (i11, i21, i22, i31, i32, i33) = (0.03, 0.004, 0.05, -0.002, 0.001, 0.04);
    let conm2 = tip_body_deck(&format!(
        "CONM2,10,5,,{m:?},{:?},{:?},{:?},,+\n+,{i11:?},{i21:?},{i22:?},{i31:?},{i32:?},{i33:?}\n",
        e[0], e[1], e[2]
    ));
    let tensor = [[i11, -i21, -i31], [-i21, i22, -i32], [-i31, -i32, i33]];
    let mm = point_mass_6x6(m, e, tensor);
    let lower: Vec<String> = (0..6)
        .flat_map(|r| (0..=r).map(move |c| (r, c)))
        .map(|(r, c)| format!("{:?}", mm[r][c]))
        .collect();
    // EID G CID M11 M21 M22 M31 M32 | M33 … (free field, 8 data fields per line)
    let conm1 = tip_body_deck(&format!(
        "CONM1,10,5,,{},+\n+,{},+\n+,{}\n",
        lower[..5].join(","),
        lower[5..13].join(","),
        lower[13..].join(",")
    ));
    let (pa, pb) = (
        write("conm1", "conm2.bdf", &conm2),
        write("conm1", "conm1.bdf", &conm1),
    );
    let read_back = &read(&pb).point_masses[0];
    let want = &read(&pa).point_masses[0];
    for r in 0..3 {
        assert!((read_back.offset[r] - want.offset[r]).abs() < 1e-15);
        for c in 0..3 {
            assert!((read_back.inertia[r][c] - want.inertia[r][c]).abs() < 1e-15);
        }
    }
    let (fa, fb) = (dense_hz(&read(&pa)), dense_hz(&read(&pb)));
    println!(
        "CONM2 {fa:?}\nCONM1 {fb:?}\nCONM1 vs CONM2 {:.1e}",
        rel(&fb, &fa)
    );
    assert!(rel(&fb, &fa) < 1e-10);
}

/// A cantilever of four CBARs (grid 1 clamped) and a body at grid 10 (mass 1.5, inertia) off
/// the tip, linked to the tip grid 5 by `link`.
fn linked_body_deck(link: &str, case: &str) -> String {
    let mut s = format!(
        "SOL 103\nCEND\nSPC = 1\n{case}BEGIN BULK\nMAT1,1,7.e10,,.33,2700.\n\
         PBAR,2,1,1.e-4,2.e-9,1.e-9,3.e-9\n"
    );
    for i in 1..=5 {
        s += &format!("GRID,{i},,{:?},0.,0.\n", (i - 1) as f64 * 0.2);
    }
    for i in 1..=4 {
        s += &format!("CBAR,{i},2,{i},{},0.,1.,0.\n", i + 1);
    }
    s + "GRID,10,,1.2,0.1,0.05\nCONM2,30,10,,1.5,,,,,+\n+,0.01,,0.02,,,0.015\nSPC1,1,123456,1\n"
        + link
        + "ENDDATA\n"
}

/// MPC equations of the rigid link u_d = u_i + θ_i × (x_d − x_i), θ_d = θ_i from grid `i` at
/// `xi` to grid `d` at `xd`: for each component, 1·u_d − Σ coefficients·u_i = 0.
fn rigid_link_mpcs(sid: u64, d: u64, xd: [f64; 3], i: u64, xi: [f64; 3]) -> String {
    let r = [xd[0] - xi[0], xd[1] - xi[1], xd[2] - xi[2]];
    // (θ × r)_x = θy rz − θz ry, (θ × r)_y = θz rx − θx rz, (θ × r)_z = θx ry − θy rx
    let arms: [Vec<(usize, f64)>; 3] = [
        vec![(5, r[2]), (6, -r[1])],
        vec![(6, r[0]), (4, -r[2])],
        vec![(4, r[1]), (5, -r[0])],
    ];
    let mut s = String::new();
    for c in 1..=6 {
        let mut terms = vec![(d, c, 1.0), (i, c, -1.0)];
        if c <= 3 {
            terms.extend(arms[c - 1].iter().map(|&(q, a)| (i, q, -a)));
        }
        // G C A triples: two on the first line, two per continuation (fields 3–8)
        let t: Vec<String> = terms
            .iter()
            .map(|(g, c, a)| format!("{g},{c},{a:?}"))
            .collect();
        s += &format!("MPC,{sid},{},\n", t[..2].join(","));
        for chunk in t[2..].chunks(2) {
            s += &format!(",,{}\n", chunk.join(","));
        }
    }
    s
}

#[test]
fn mpc_and_rbar_rbar1_rbe1_equal_the_rbe2_they_describe() {
    let rbe2 = linked_body_deck("RBE2,40,10,123456,5\n", "");
    let mpc = linked_body_deck(
        &rigid_link_mpcs(3, 5, [0.8, 0.0, 0.0], 10, [1.2, 0.1, 0.05]),
        "MPC = 3\n",
    );
    // RBAR with the independent dofs split between its ends: the same six equations
    let rbar_split = linked_body_deck("RBAR,41,10,5,123,456,456,123\n", "");
    let rbar = linked_body_deck("RBAR,41,10,5,123456\n", "");
    let rbar1 = linked_body_deck("RBAR1,42,10,5,123456\n", "");
    let rbe1 = linked_body_deck("RBE1,43,10,123456,,,,,,+\n+,UM,5,123456\n", "");
    let reference = built_hz(&write("mpc", "rbe2.bdf", &rbe2), 8, &[]);
    println!("RBE2 {reference:?}");
    for (name, deck) in [
        ("mpc", &mpc),
        ("rbar_split", &rbar_split),
        ("rbar", &rbar),
        ("rbar1", &rbar1),
        ("rbe1", &rbe1),
    ] {
        let f = built_hz(&write("mpc", &format!("{name}.bdf"), deck), 8, &[]);
        println!("{name} vs RBE2 {:.1e}", rel(&f, &reference));
        assert!(rel(&f, &reference) < 1e-10, "{name}: {f:?}");
    }
    // MPC sets the case control does not select are a note and not applied
    let unselected = write("mpc", "unselected.bdf", &mpc.replace("MPC = 3\n", ""));
    let m = read(&unselected);
    assert!(m.mpcs.is_empty());
    assert!(
        m.deck
            .notes
            .iter()
            .any(|n| n.contains("MPC sets 3") && n.contains("selects no MPC set")),
        "{:?}",
        m.deck.notes
    );
}

#[test]
fn conrod_equals_crod_with_prod() {
    // a free space truss: a tetrahedron of six rods with non-structural mass
    let base = "SOL 103\nCEND\nBEGIN BULK\nMAT1,1,2.1e11,,.3,7850.\n\
                GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.3,0.9,0.\nGRID,4,,0.4,0.3,0.8\n";
    let pairs = [(1, 2), (1, 3), (1, 4), (2, 3), (2, 4), (3, 4)];
    // J = 0: a rod truss has no stiffness against turning its nodes
    let mut crod = String::from(base) + "PROD,7,1,2.e-4,0.,,0.4\n";
    let mut conrod = String::from(base);
    for (k, (a, b)) in pairs.iter().enumerate() {
        crod += &format!("CROD,{},7,{a},{b}\n", k + 1);
        conrod += &format!("CONROD,{},{a},{b},1,2.e-4,0.,,0.4\n", k + 1);
    }
    let (pa, pb) = (
        write("conrod", "crod.bdf", &(crod + "ENDDATA\n")),
        write("conrod", "conrod.bdf", &(conrod + "ENDDATA\n")),
    );
    let (fa, fb) = (built_hz(&pa, 12, &[]), built_hz(&pb, 12, &[]));
    let (fa, fb) = (&fa[6..], &fb[6..]); // the flexible modes
    println!(
        "CROD {fa:?}\nCONROD {fb:?}\nCONROD vs CROD {:.1e}",
        rel(fb, fa)
    );
    assert!(rel(fb, fa) < 1e-12);
    let m = read(&pb);
    assert_eq!(
        m.properties.len(),
        1,
        "one property for the six equal CONRODs"
    );
}

/// The cantilever of [`tip_body_deck`] (no tip body) held at grid 1 by `hold`.
fn held_cantilever(hold: &str, case: &str) -> String {
    let mut s = format!(
        "SOL 103\nCEND\n{case}BEGIN BULK\nMAT1,1,7.e10,,.33,2700.\nPBAR,2,1,1.e-4,2.e-9,1.e-9,3.e-9\n"
    );
    for i in 1..=5 {
        s += &format!("GRID,{i},,{:?},0.,0.\n", (i - 1) as f64 * 0.2);
    }
    for i in 1..=4 {
        s += &format!("CBAR,{i},2,{i},{},0.,1.,0.\n", i + 1);
    }
    s + hold + "ENDDATA\n"
}

/// A grounded CBUSH of 1e12 in every direction at the root equals the clamp: the frequencies
/// differ by the order of the structure's own stiffness over 1e12 (the bar's EA/L = 8.75e6 N/m:
/// ~1e-5 on the axial mode; bending ≤ 1e-7). The build refuses the grounded bush (a flexible
/// body is free or held at its interfaces), naming it.
#[test]
fn grounded_cbush_of_1e12_equals_a_clamp() {
    let clamp = write(
        "cbush_clamp",
        "spc.bdf",
        &held_cantilever("SPC1,1,123456,1\n", "SPC = 1\n"),
    );
    let bush = write(
        "cbush_clamp",
        "bush.bdf",
        &held_cantilever(
            "CBUSH,50,51,1,,,,,0\nPBUSH,51,K,1.e12,1.e12,1.e12,1.e12,1.e12,1.e12\n",
            "",
        ),
    );
    let (fa, fb) = (sparse_hz(&read(&clamp), 12), sparse_hz(&read(&bush), 12));
    for (j, (a, b)) in fa.iter().zip(&fb).enumerate() {
        println!(
            "mode {j}: clamp {a:.6} Hz, bush {b:.6} Hz, {:.1e}",
            (b - a).abs() / a
        );
    }
    let bending = rel(&fb[..4], &fa[..4]);
    let all = rel(&fb, &fa);
    println!("first four (bending) {bending:.1e}, all {all:.1e}");
    assert!(bending < 1e-7 && all < 2e-5, "{bending:e} {all:e}");
    let err = build_refused(&bush);
    assert!(
        err.contains("springs or bushes to ground hold the body")
            && err.contains(&format!("bush 50 ({}:", bush.display())),
        "{err}"
    );
}

/// The CBUSH element frame and spring point as MSC's QRG defines them, against an equivalent
/// construction: the same bush with zero length between two grids at the spring point, each
/// tied to its end grid by an RBE2, its axes given by a CORD2R built from the hand-computed
/// frame (x along GA–GB, z = x × v, y = z × x).
#[test]
fn cbush_orientation_and_offset_equal_rigid_links_and_a_rotated_system() {
    let (x5, x10, x7) = ([0.8, 0.0, 0.0], [1.2, 0.1, 0.05], [0.9, 0.5, 0.7]);
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let unit = |a: [f64; 3]| {
        let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        a.map(|v| v / n)
    };
    let ex = unit(sub(x10, x5));
    let ez = unit(cross(ex, sub(x7, x5)));
    let ey = cross(ez, ex);
    let pbush = "PBUSH,51,K,1.e5,2.e5,3.e5,1.e3,2.e3,3.e3\nGRID,7,,0.9,0.5,0.7\n";
    let f = |v: [f64; 3]| format!("{:?},{:?},{:?}", v[0], v[1], v[2]);
    // the equivalent: grids 51 and 101 at the spring point, rigid links, CID 9 = (ex, ey, ez)
    let equivalent = |s: [f64; 3]| {
        format!(
            "{pbush}GRID,51,,{p}\nGRID,101,,{p}\nRBE2,60,5,123456,51\nRBE2,61,10,123456,101\n\
             CORD2R,9,,0.,0.,0.,{},+\n+,{}\nCBUSH,50,51,51,101,,,,9\n",
            f(ez),
            f(ex),
            p = f(s)
        )
    };
    let offset = [0.05, 0.1, -0.02];
    let s_off = std::array::from_fn(|i| x5[i] + offset[i]);
    let s_03 = std::array::from_fn(|i| x5[i] + 0.3 * (x10[i] - x5[i]));
    // the orientation vector X1–X3 is the direction from GA to grid 7
    let v = sub(x7, x5);
    let cases = [
        (
            "g0_ocid",
            format!("{pbush}CBUSH,50,51,5,10,7,,,,+\n+,,0,{}\n", f(offset)),
            equivalent(s_off),
        ),
        (
            "x_s",
            format!("{pbush}CBUSH,50,51,5,10,{},,+\n+,0.3\n", f(v)),
            equivalent(s_03),
        ),
    ];
    for (name, bush, equiv) in cases {
        let pa = write(
            "cbush_frame",
            &format!("{name}.bdf"),
            &linked_body_deck(&bush, ""),
        );
        let pb = write(
            "cbush_frame",
            &format!("{name}_eq.bdf"),
            &linked_body_deck(&equiv, ""),
        );
        let m = read(&pa);
        let b = &m.bushes[0];
        for (got, want) in b.axes.iter().zip([ex, ey, ez]) {
            assert!(
                (0..3).all(|i| (got[i] - want[i]).abs() < 1e-15),
                "{name}: {:?}",
                b.axes
            );
        }
        let (fa, fb) = (built_hz(&pa, 10, &[]), built_hz(&pb, 10, &[]));
        println!(
            "{name}: bush {fa:?}\n  equivalent {fb:?}\n  {:.1e}",
            rel(&fa, &fb)
        );
        assert!(rel(&fa, &fb) < 1e-9, "{name}");
    }
    // B and GE are notes; a bush mass is refused
    let noted = linked_body_deck(
        &format!("{pbush}CBUSH,50,51,5,10,7\n").replace("3.e3\n", "3.e3\n,,B,1.\n,,GE,.02\n"),
        "",
    );
    let m = read(&write("cbush_frame", "noted.bdf", &noted));
    for key in ["PBUSH B (", "PBUSH GE ("] {
        assert!(
            m.deck
                .notes
                .iter()
                .any(|n| n.contains(key) && n.contains("damping")),
            "{key}"
        );
    }
}

/// Two scalar points: spring k1 to ground and k2 between them, masses m1, m2 — the closed form
/// λ = (a ± √(a² − 4 k1 k2/(m1 m2)))/2, a = (k1 + k2)/m1 + k2/m2; with values on the cards
/// (CELAS4, CMASS4) or by property (CELAS3/PELAS, CMASS3/PMASS), and a scalar point tied to a
/// grid's component by CELAS2 and an MPC. The build refuses scalar points, naming them.
#[test]
fn spoint_spring_mass_equals_the_closed_form() {
    let (k1, k2, m1, m2): (f64, f64, f64, f64) = (4.0e4, 1.5e4, 2.0, 0.5);
    let a = (k1 + k2) / m1 + k2 / m2;
    let d = (a * a - 4.0 * k1 * k2 / (m1 * m2)).sqrt();
    let exact = [hz((a - d) / 2.0), hz((a + d) / 2.0)];
    let on_cards = format!(
        "BEGIN BULK\nSPOINT,1,2\nCELAS4,11,{k1:?},1\nCELAS4,12,{k2:?},1,2\n\
         CMASS4,21,{m1:?},1\nCMASS4,22,{m2:?},2\nENDDATA\n"
    );
    let by_property = format!(
        "BEGIN BULK\nSPOINT,1,THRU,2\nCELAS3,11,31,0,1\nCELAS3,12,32,1,2\nPELAS,31,{k1:?},,,32,{k2:?}\n\
         CMASS3,21,41,1\nCMASS3,22,42,,2\nPMASS,41,{m1:?},42,{m2:?}\nENDDATA\n"
    );
    for (name, deck) in [("cards", on_cards), ("property", by_property)] {
        let p = write("spoint", &format!("{name}.bdf"), &deck);
        let f = dense_hz(&read(&p));
        println!(
            "{name}: {f:?} vs closed form {exact:?}: {:.1e}",
            rel(&f, &exact)
        );
        assert!(rel(&f, &exact) < 1e-12, "{name}");
    }
    // scalar point 2 tied to grid 5's x by an MPC, the mass m2 there: the same
    let tied = format!(
        "SOL 103\nCEND\nMPC = 1\nBEGIN BULK\nSPOINT,1,2\nGRID,5,,0.,0.,0.,,23456\n\
         CELAS2,11,{k1:?},1,0\nCELAS4,12,{k2:?},1,2\nMPC,1,2,0,1.,5,1,-1.\n\
         CMASS2,21,{m1:?},1\nCONM2,22,5,,{m2:?}\nQSET1,0,1\nENDDATA\n"
    );
    let tied = write("spoint", "tied.bdf", &tied);
    let model = read(&tied);
    let f = dense_hz(&model);
    println!("grid-coupled: {f:?}: {:.1e}", rel(&f, &exact));
    assert!(rel(&f, &exact) < 1e-12);
    assert_eq!(model.deck.qset_modes.as_ref().map(|q| q.0), Some(1));
    let err = build_refused(&tied);
    assert!(
        err.contains("scalar points (SPOINT 1, 2) carry dofs"),
        "{err}"
    );
    assert!(
        err.contains(&format!("spring 11 ({}:7)", tied.display())),
        "{err}"
    );
}

/// PARAM,K6ROT sets the shells' drilling penalty γ_d = K6ROT·10⁻⁶·G t (fe::elements::shell):
/// the drilling diagonal of a CQUAD4 is that of the element formed with that factor, K6ROT =
/// 1000 gives ten times MSC's default 100, and K6ROT = 0 is refused.
#[test]
fn k6rot_scales_the_drilling_stiffness_as_documented() {
    use flexbody::fe::elements::{quad4_shell, shell::ShellProps, Isotropic};
    let deck = |param: &str| {
        format!(
            "BEGIN BULK\n{param}MAT1,1,2.1e11,,.3,7850.\nPSHELL,1,1,.002,1\n\
             GRID,1,,0.,0.,0.\nGRID,2,,.1,0.,0.\nGRID,3,,.1,.12,0.\nGRID,4,,0.,.1,0.\n\
             CQUAD4,1,1,1,2,3,4\nENDDATA\n"
        )
    };
    let drill = |param: &str, name: &str| {
        let m = read(&write("k6rot", name, &deck(param)));
        let a = assemble(&m, &AssemblySpec::default()).unwrap();
        let k = crate::common::dense(&a.k);
        (m.params.k6rot, k[(5, 5)])
    };
    let (default, k100) = drill("", "default.bdf");
    let (k6, k1000) = drill("PARAM,K6ROT,1000.\n", "k1000.bdf");
    assert_eq!((default, k6), (None, Some(1000.0)));
    let x = [
        [0.0, 0.0, 0.0],
        [0.1, 0.0, 0.0],
        [0.1, 0.12, 0.0],
        [0.0, 0.1, 0.0],
    ];
    let mut props = ShellProps::isotropic(0.002, Isotropic::new(2.1e11, 0.3, 7850.0));
    props.drill_factor = 1000.0 * 1e-6;
    let (k, _) = quad4_shell::matrices(&x, &props, true).unwrap();
    println!(
        "drilling diagonal: K6ROT 100 {k100:e}, 1000 {k1000:e}, element {:e}",
        k[5 * 24 + 5]
    );
    assert!((k1000 - k[5 * 24 + 5]).abs() < 1e-12 * k1000);
    assert!((k1000 / k100 - 10.0).abs() < 1e-12);
    let e = read_model(
        &write("k6rot", "zero.bdf", &deck("PARAM,K6ROT,0.\n")),
        &ImportOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("K6ROT = 0") && e.contains("not supported"),
        "{e}"
    );
}
