//! The structural Nastran cards of issue 44 that real decks carry, each honoured as MSC Nastran
//! reads it and tested against an independent reference: BAROR/BEAMOR against the same fields
//! written on each CBAR/CBEAM, the older orientation flag in CBAR/CBEAM field 9 against OFFT,
//! implicit scalar points against SPOINT, DMIG selected by K2GG/M2GG against the CELAS2 and
//! CONM2 it replaces, GENEL against the CBUSH it stands for, CBUSH1D against a CROD.

use crate::common::{generalized_eigenvalues, hz};
use crate::nastran_support::{build_refused, built_hz, write};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec};
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::Model;

/// Largest relative difference of two frequency lists (same length).
fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    (a.iter().zip(b))
        .map(|(x, y)| (x - y).abs() / y.abs().max(1e-300))
        .fold(0.0, f64::max)
}

fn read(path: &std::path::Path) -> Model {
    read_model(path, &ImportOptions::default()).unwrap()
}

/// Frequencies (Hz) of the constrained model by a dense generalized eigen-solve.
fn dense_hz(model: &Model) -> Vec<f64> {
    let a = assemble(model, &AssemblySpec::default()).unwrap();
    let r = eliminate(model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    generalized_eigenvalues(&crate::common::dense(&r.k), &crate::common::dense(&r.m))
        .into_iter()
        .map(hz)
        .collect()
}

/// The assembled stiffness of a model, dense.
fn dense_k(model: &Model) -> faer::Mat<f64> {
    crate::common::dense(&assemble(model, &AssemblySpec::default()).unwrap().k)
}

/// Largest difference of two dense matrices relative to the largest term of the second.
fn rel_mat(a: &faer::Mat<f64>, b: &faer::Mat<f64>) -> f64 {
    assert_eq!((a.nrows(), a.ncols()), (b.nrows(), b.ncols()));
    let (mut diff, mut top) = (0.0f64, 0.0f64);
    for j in 0..b.ncols() {
        for i in 0..b.nrows() {
            diff = diff.max((a[(i, j)] - b[(i, j)]).abs());
            top = top.max(b[(i, j)].abs());
        }
    }
    diff / top
}

/// A clamped frame of three CBARs and a CBEAM with a tip mass; `bars` are the element cards.
fn frame(bars: &str) -> String {
    format!(
        "BEGIN BULK\nMAT1,1,2.1e11,,.3,7850.\nPBAR,7,1,2.e-4,3.e-9,1.e-9,2.e-9\n\
         PBEAM,8,1,1.5e-4,2.e-9,1.2e-9,,1.5e-9\n\
         GRID,1,,0.,0.,0.,,123456\nGRID,2,,1.,0.,0.\nGRID,3,,1.,1.,0.\nGRID,4,,1.,1.,1.\n\
         GRID,5,,2.,1.,1.\nGRID,9,,0.,0.,5.\nCONM2,30,5,,3.\n{bars}ENDDATA\n"
    )
}

/// BAROR/BEAMOR give the blank PID, orientation and OFFT of every CBAR/CBEAM: the frame built
/// with them equals the frame with the fields written on each element (to 1e-12; measured 0),
/// and an orientation differing from the default changes the modes (so the defaults are used).
#[test]
fn baror_and_beamor_equal_the_fields_written_on_each_element() {
    let defaults = "BAROR,,7,,,0.6,0.3,0.9,BGG\nBEAMOR,,8,,,9\n\
                    CBAR,1,,1,2\nCBAR,2,,2,3\nCBAR,3,,3,4\nCBEAM,4,,4,5\n";
    let written = "CBAR,1,7,1,2,0.6,0.3,0.9,BGG\nCBAR,2,7,2,3,0.6,0.3,0.9,BGG\n\
                   CBAR,3,7,3,4,0.6,0.3,0.9,BGG\nCBEAM,4,8,4,5,9\n";
    // BAROR after the bars, and a bar that writes its own vector: the card's fields win
    let late = "CBAR,1,,1,2\nCBAR,2,,2,3,0.,0.,1.\nCBAR,3,,3,4\nCBEAM,4,,4,5\n\
                BEAMOR,,8,,,9\nBAROR,,7,,,0.6,0.3,0.9,BGG\n";
    let late_written = "CBAR,1,7,1,2,0.6,0.3,0.9,BGG\nCBAR,2,7,2,3,0.,0.,1.,BGG\n\
                        CBAR,3,7,3,4,0.6,0.3,0.9,BGG\nCBEAM,4,8,4,5,9\n";
    let hz = |name: &str, bars: &str| built_hz(&write("baror", name, &frame(bars)), 6, &[]);
    let (a, b) = (hz("defaults.bdf", defaults), hz("written.bdf", written));
    let (c, d) = (hz("late.bdf", late), hz("late_written.bdf", late_written));
    println!("BAROR {a:?}\nwritten {b:?}: {:.1e}", rel(&a, &b));
    println!("late {c:?}\nwritten {d:?}: {:.1e}", rel(&c, &d));
    assert!(rel(&a, &b) < 1e-12 && rel(&c, &d) < 1e-12);
    assert!(rel(&a, &c) > 1e-3, "bar 2's own vector changes the modes");
    // a second BAROR is an error naming the first
    let two = write(
        "baror",
        "two.bdf",
        &frame("BAROR,,7,,,0.6,0.3,0.9\nBAROR,,7,,,0.,0.,1.\nCBAR,1,,1,2\n"),
    );
    let err = build_refused(&two);
    assert!(err.contains("second BAROR card"), "{err}");
}

/// The integer 1 or 2 of older decks in CBAR/CBEAM field 9 (NASTRAN-95's orientation flag F)
/// reads as that flag with OFFT GGG: the frame equals the one with OFFT blank (measured 0),
/// with a note; a bad OFFT is still an error naming it and the codes.
#[test]
fn the_old_orientation_flag_in_field_9_reads_as_offt_ggg() {
    let flags = "CBAR,1,7,1,2,0.6,0.3,0.9,1\nCBAR,2,7,2,3,0.6,0.3,0.9,1\n\
                 CBAR,3,7,3,4,0.6,0.3,0.9,1\nCBEAM,4,8,4,5,9,,,2\n";
    let blank = "CBAR,1,7,1,2,0.6,0.3,0.9\nCBAR,2,7,2,3,0.6,0.3,0.9\n\
                 CBAR,3,7,3,4,0.6,0.3,0.9\nCBEAM,4,8,4,5,9\n";
    let pf = write("oldflag", "flags.bdf", &frame(flags));
    let a = built_hz(&pf, 6, &[]);
    let b = built_hz(&write("oldflag", "blank.bdf", &frame(blank)), 6, &[]);
    println!("flag {a:?}\nblank {b:?}: {:.1e}", rel(&a, &b));
    assert!(rel(&a, &b) < 1e-12);
    let notes = read(&pf).deck.notes.join("\n");
    assert!(notes.contains("CBAR field 9 = 1 or 2"), "{notes}");
    assert!(notes.contains("CBEAM field 9 = 1 or 2"), "{notes}");
    let bad = write(
        "oldflag",
        "bad.bdf",
        &frame("CBAR,1,7,1,2,0.6,0.3,0.9,GXG\n"),
    );
    let err = build_refused(&bad);
    assert!(err.contains("OFFT GXG: one of GGG, BGG"), "{err}");
}

/// CELAS3/CELAS4/CMASS3/CMASS4 on scalar points no SPOINT declares make them, as Nastran does:
/// the model equals the one with the SPOINT card (but for the note saying so), and its two
/// frequencies are the closed form's (measured 0).
#[test]
fn scalar_points_are_made_by_the_scalar_elements_that_name_them() {
    let (k1, k2, m1, m2): (f64, f64, f64, f64) = (4.0e4, 1.5e4, 2.0, 0.5);
    let a = (k1 + k2) / m1 + k2 / m2;
    let d = (a * a - 4.0 * k1 * k2 / (m1 * m2)).sqrt();
    let exact = [hz((a - d) / 2.0), hz((a + d) / 2.0)];
    let body = format!(
        "CELAS3,11,31,0,1\nCELAS3,12,32,1,2\nPELAS,31,{k1:?},,,32,{k2:?}\n\
         CMASS3,21,41,1\nCMASS4,22,{m2:?},,2\nPMASS,41,{m1:?}\n"
    );
    // the SPOINT last, so that every other card keeps its line
    let declared = read(&write(
        "implicit",
        "declared.bdf",
        &format!("BEGIN BULK\n{body}SPOINT,1,2\nENDDATA\n"),
    ));
    let mut implicit = read(&write(
        "implicit",
        "implicit.bdf",
        &format!("BEGIN BULK\n{body}ENDDATA\n"),
    ));
    let notes = std::mem::take(&mut implicit.deck.notes);
    assert!(
        notes
            .iter()
            .any(|n| n.contains("scalar points 1, 2 declared by no SPOINT")),
        "{notes:?}"
    );
    // the same model but for where its nodes came from (files differ by name)
    implicit.source.clone_from(&declared.source);
    implicit.files.clone_from(&declared.files);
    assert_eq!(implicit, declared);
    let f = dense_hz(&implicit);
    println!(
        "implicit: {f:?} vs closed form {exact:?}: {:.1e}",
        rel(&f, &exact)
    );
    assert!(rel(&f, &exact) < 1e-12);
}

/// A cantilever CBAR with three CELAS2 to a second grid carrying a CONM2; the same with the
/// springs and the mass as DMIG matrices selected by `K2GG`/`M2GG`.
fn springs_deck(case: &str, cards: &str) -> String {
    format!(
        "SOL 103\nCEND\n{case}BEGIN BULK\nMAT1,1,2.1e11,,.3,7850.\n\
         PBAR,7,1,1.e-4,8.e-10,6.e-10,1.4e-9\nGRID,1,,0.,0.,0.,,123456\nGRID,2,,1.,0.,0.\n\
         GRID,3,,1.2,0.1,0.\nCBAR,1,7,1,2,0.,1.,0.\nCONM2,20,2,,0.7\n{cards}ENDDATA\n"
    )
}

/// DMIG matrices selected by K2GG/M2GG are added to K and M on the g-set: a symmetric (IFO 6,
/// terms above and below the diagonal mixed) stiffness with a factor 2 and a square (IFO 1)
/// mass equal the CELAS2 springs and the CONM2 they are written from (frequencies through the
/// CLI, measured 0); an unselected DMIG is a note; K2PP is refused with its reason.
#[test]
fn dmig_selected_by_k2gg_and_m2gg_equals_the_elements_it_replaces() {
    let (ka, kb, kc, m) = (5.0e4, 3.0e4, 4.0e4, 2.5);
    let elements = format!(
        "CELAS2,11,{ka:?},2,1,3,1\nCELAS2,12,{kb:?},2,2,3,2\nCELAS2,13,{kc:?},2,3,3,3\n\
         CONM2,21,3,,{m:?}\n"
    );
    let (ha, hb, hc) = (ka / 2.0, kb / 2.0, kc / 2.0);
    let dmig = format!(
        "DMIG,KSPR,0,6,2,0\n\
         DMIG,KSPR,2,1,,2,1,{ha:?},\n,3,1,{:?}\nDMIG,KSPR,3,1,,3,1,{ha:?}\n\
         DMIG,KSPR,3,2,,2,2,{:?},\n,3,2,{hb:?}\nDMIG,KSPR,2,2,,2,2,{hb:?}\n\
         DMIG,KSPR,2,3,,2,3,{hc:?},\n,3,3,{:?}\nDMIG,KSPR,3,3,,3,3,{hc:?}\n\
         DMIG,MCON,0,1,1,0\nDMIG,MCON,3,1,,3,1,{m:?}\nDMIG,MCON,3,2,,3,2,{m:?}\n\
         DMIG,MCON,3,3,,3,3,{m:?}\nDMIG,SPARE,0,6,1,0\nDMIG,SPARE,2,1,,2,1,1.e9\n",
        -ha, -hb, -hc
    );
    let a = write("dmig", "elements.bdf", &springs_deck("", &elements));
    let b = write(
        "dmig",
        "dmig.bdf",
        &springs_deck("K2GG = 2.0*KSPR\nM2GG = MCON\n", &dmig),
    );
    let (fa, fb) = (built_hz(&a, 6, &[]), built_hz(&b, 6, &[]));
    println!("elements {fa:?}\nDMIG {fb:?}: {:.1e}", rel(&fb, &fa));
    assert!(rel(&fb, &fa) < 1e-12);
    let notes = read(&b).deck.notes.join("\n");
    assert!(
        notes.contains("DMIG SPARE") && notes.contains("no K2GG or M2GG"),
        "{notes}"
    );
    // without the factor, half the springs: the frequencies move (the factor is used)
    let half = write(
        "dmig",
        "half.bdf",
        &springs_deck("K2GG = KSPR\nM2GG = MCON\n", &dmig),
    );
    assert!(rel(&built_hz(&half, 6, &[]), &fa) > 1e-2);
    let pp = write("dmig", "k2pp.bdf", &springs_deck("K2PP = KSPR\n", &dmig));
    let err = build_refused(&pp);
    assert!(err.contains("K2PP") && err.contains("p-set"), "{err}");
    let unknown = write(
        "dmig",
        "unknown.bdf",
        &springs_deck("K2GG = KNONE\n", &dmig),
    );
    let err = build_refused(&unknown);
    assert!(err.contains("selects DMIG KNONE"), "{err}");
}

/// Two grids, the second with a CONM2 of mass and inertia; `link` joins them; grid 1 clamped
/// when `clamp`.
fn linked(clamp: bool, link: &str) -> String {
    let ps = if clamp { "123456" } else { "" };
    format!(
        "BEGIN BULK\nGRID,1,,0.,0.,0.,,{ps}\nGRID,2,,.5,.2,.1\nCONM2,10,2,,3.,,,,\n\
         ,.02,.001,.03,.002,.003,.04\nCONM2,11,1,,5.,,,,\n,.05,,.05,,,.05\n{link}ENDDATA\n"
    )
}

/// A GENEL's stiffness, in its K form and its Z (flexibility) form, with the rigid-body matrix
/// S of its dependent grid, equals the CBUSH it stands for (spring point at GB, basic axes):
/// the assembled free-free K to 1e-10 (measured 0 for K, 1e-16 for Z) and the clamped
/// frequencies through the CLI (measured 0).
#[test]
fn genel_equals_the_bush_it_stands_for() {
    let k = [1.0e5, 2.0e5, 3.0e5, 4.0e3, 5.0e3, 6.0e3];
    let bush = format!(
        "CBUSH,1,5,1,2,,,,0\n,1.\nPBUSH,5,K,{:?},{:?},{:?},{:?},{:?},{:?}\n",
        k[0], k[1], k[2], k[3], k[4], k[5]
    );
    // lower triangle of a diagonal 6 × 6, column by column
    let triangle = |diag: [f64; 6]| {
        let mut v = Vec::new();
        for (c, d) in diag.iter().enumerate() {
            v.push(format!("{d:?}"));
            v.extend((c + 1..6).map(|_| "0.".to_owned()));
        }
        v
    };
    // u_2 = u_1 + θ_1 × (x_2 − x_1), θ_2 = θ_1, by rows (d = (.5, .2, .1))
    let s = [
        "1.", "0.", "0.", "0.", ".1", "-.2", "0.", "1.", "0.", "-.1", "0.", ".5", "0.", "0.", "1.",
        ".2", "-.5", "0.", "0.", "0.", "0.", "1.", "0.", "0.", "0.", "0.", "0.", "0.", "1.", "0.",
        "0.", "0.", "0.", "0.", "0.", "1.",
    ];
    let lines = |word: &str, values: &[String]| {
        let mut out = String::new();
        for (i, chunk) in values.chunks(7).enumerate() {
            let head = if i == 0 { word } else { "" };
            out.push_str(&format!(",{head},{}\n", chunk.join(",")));
        }
        out
    };
    let genel = |form: &str, values: Vec<String>| {
        format!(
            "GENEL,1,,2,1,2,2,2,3\n,2,4,2,5,2,6\n,UD,,1,1,1,2,1,3\n,1,4,1,5,1,6\n{}{}",
            lines(form, &values),
            lines("S", &s.map(str::to_owned))
        )
    };
    let k_form = genel("K", triangle(k));
    let z_form = genel("Z", triangle(k.map(|v| 1.0 / v)));
    let model =
        |name: &str, clamp: bool, link: &str| read(&write("genel", name, &linked(clamp, link)));
    let kb = dense_k(&model("bush.bdf", false, &bush));
    for (name, link) in [("k.bdf", &k_form), ("z.bdf", &z_form)] {
        let e = rel_mat(&dense_k(&model(name, false, link)), &kb);
        println!("GENEL {name} vs CBUSH: K differs by {e:.1e}");
        assert!(e < 1e-10, "{name}: {e}");
    }
    let hz = |name: &str, link: &str| built_hz(&write("genel", name, &linked(true, link)), 6, &[]);
    let (fb, fk) = (hz("bush_clamped.bdf", &bush), hz("k_clamped.bdf", &k_form));
    println!("CBUSH {fb:?}\nGENEL {fk:?}: {:.1e}", rel(&fk, &fb));
    assert!(rel(&fk, &fb) < 1e-10);
    // a wrong count of terms is an error naming the count
    let short = write(
        "genel",
        "short.bdf",
        &linked(true, &genel("K", triangle(k)[..20].to_vec())),
    );
    let err = build_refused(&short);
    assert!(err.contains("20 K or Z terms for 6 UI dofs"), "{err}");
}

/// A CBUSH1D (PBUSH1D K = EA/L) on an oblique axis equals a massless CROD of that axial
/// stiffness (frequencies through the CLI, measured 2.5e-16). The clamped grid 1 carries a CONM2 with inertia:
/// its six dofs are then held by its PS in both decks (with translations alone, the build's
/// rigid-mode expectation would take the CELAS2s, which resist rigid rotation, for free ones); PBUSH1D's damping and nonlinear
/// SPRING line are notes, its mass is refused.
#[test]
fn cbush1d_equals_a_crod_of_the_same_axial_stiffness() {
    let (e, area) = (2.0e11, 1.0e-4);
    let length = (0.3f64 * 0.3 + 0.4 * 0.4 + 1.2 * 1.2).sqrt();
    let deck = |link: &str| {
        format!(
            "BEGIN BULK\nMAT1,1,{e:?},,.3,0.\nGRID,1,,0.,0.,0.,,123456\nGRID,2,,.3,.4,1.2\n\
             CONM2,10,2,,2.\nCONM2,13,1,,1.,,,,\n,1.,,1.,,,1.\nCELAS2,11,1.e6,2,1,1,1\nCELAS2,12,3.e6,2,2,1,2\n{link}ENDDATA\n"
        )
    };
    let rod = "CROD,1,5,1,2\nPROD,5,1,1.e-4\n";
    let k = e * area / length;
    let bush1d = format!(
        "CBUSH1D,1,6,1,2\nPBUSH1D,6,{k:?},15.\n,SPRING,TABLE,3\nTABLED1,3\n,0.,0.,1.,1.,ENDT\n"
    );
    let fr = built_hz(&write("cbush1d", "rod.bdf", &deck(rod)), 3, &[]);
    let p = write("cbush1d", "bush1d.bdf", &deck(&bush1d));
    let fb = built_hz(&p, 3, &[]);
    println!("CROD {fr:?}\nCBUSH1D {fb:?}: {:.1e}", rel(&fb, &fr));
    assert!(rel(&fb, &fr) < 1e-10);
    let notes = read(&p).deck.notes.join("\n");
    assert!(
        notes.contains("PBUSH1D C") && notes.contains("PBUSH1D SPRING"),
        "{notes}"
    );
    let massive = write(
        "cbush1d",
        "mass.bdf",
        &deck(&format!("CBUSH1D,1,6,1,2\nPBUSH1D,6,{k:?},,1.5\n")),
    );
    let err = build_refused(&massive);
    // refused where a CBUSH1D uses it (a PBUSH1D no element uses forms nothing)
    assert!(
        err.contains("PBUSH1D 6") && err.contains("M = 1.5, used by CBUSH1D 1"),
        "{err}"
    );
}

/// Two CQUAD8 of a clamped strip: `g7` and `g6` are element 1's seventh and element 2's sixth
/// grid fields (blank or grid 13 / 17), `extra` more cards.
fn quad8_strip(case: &str, g7: &str, g6: &str, extra: &str) -> String {
    format!(
        "SOL 103\nCEND\n{case}BEGIN BULK\nMAT1,1,7.e10,,.3,2700.\nPSHELL,1,1,.002,1,,1\n\
         GRID,1,,0.,0.,0.,,123456\nGRID,2,,.1,0.,0.\nGRID,3,,.2,0.,0.\n\
         GRID,4,,0.,.1,0.,,123456\nGRID,5,,.1,.1,0.\nGRID,6,,.2,.1,0.\nGRID,11,,.05,0.,0.\n\
         GRID,12,,.15,0.,0.\nGRID,14,,.15,.1,0.\nGRID,15,,0.,.05,0.,,123456\n\
         GRID,16,,.1,.05,0.\nCQUAD8,1,1,1,2,5,4,11,16\n,{g7},15\n\
         CQUAD8,2,1,2,3,6,5,12,{g6}\n,14,16\n{extra}ENDDATA\n"
    )
}

/// CQUAD8 mid-side grids left blank make their edges straight, as MSC Nastran forms them: the
/// strip equals the one with those grids written at the edges' mid-points and tied to the mean
/// of the corners by MPC cards (frequencies through the CLI, measured 0), and differs from
/// the strip whose mid-side grids are free (so the edges are really straight).
#[test]
fn blank_quad8_midsides_are_straight_edges() {
    let blank = write("midside", "blank.bdf", &quad8_strip("", "", "", ""));
    let mut mpc = String::new();
    for c in 1..=6 {
        mpc.push_str(&format!("MPC,1,13,{c},1.,5,{c},-.5,\n,,4,{c},-.5\n"));
        mpc.push_str(&format!("MPC,1,17,{c},1.,3,{c},-.5,\n,,6,{c},-.5\n"));
    }
    let grids = "GRID,13,,.05,.1,0.\nGRID,17,,.2,.05,0.\n";
    let tied = write(
        "midside",
        "tied.bdf",
        &quad8_strip("MPC = 1\n", "13", "17", &format!("{grids}{mpc}")),
    );
    let free = write("midside", "free.bdf", &quad8_strip("", "13", "17", grids));
    let (fb, ft, ff) = (
        built_hz(&blank, 6, &[]),
        built_hz(&tied, 6, &[]),
        built_hz(&free, 6, &[]),
    );
    println!(
        "blank {fb:?}\nMPC-tied {ft:?}: {:.1e}\nfree {ff:?}",
        rel(&fb, &ft)
    );
    assert!(rel(&fb, &ft) < 1e-9);
    assert!(rel(&fb, &ff) > 1e-4);
    let notes = read(&blank).deck.notes.join("\n");
    assert!(notes.contains("2 edges made straight"), "{notes}");
}

/// A rectangular CSHEAR panel (a × b, thickness t), its bottom edge clamped, its top edge
/// carried rigidly (RBE2) by a mass M that moves in the panel's plane: along the edge the
/// stiffness is the closed form's shear G t a / b, across it (F2 = 1, the panel fully effective
/// for extension between the edges) the rods' E t a / b; the moving mass is M plus the half of
/// the panel's lumped mass on the top grids. Frequencies through the CLI, measured 1.4e-16.
#[test]
fn cshear_panel_equals_the_closed_form_shear_and_extension() {
    let (e, nu, rho, t, a, b, mass) = (7.0e10, 0.3, 2700.0, 0.001, 0.2, 0.1, 2.0);
    let g = e / (2.0 * (1.0 + nu));
    let moving = mass + rho * t * a * b / 2.0;
    let f = |k: f64| (k / moving).sqrt() / (2.0 * std::f64::consts::PI);
    let mut exact = [f(g * t * a / b), f(e * t * a / b)];
    exact.sort_by(f64::total_cmp);
    let deck = format!(
        "BEGIN BULK\nMAT1,1,{e:?},,{nu:?},{rho:?}\nPSHEAR,5,1,{t:?},,0.,1.\n\
         GRID,1,,0.,0.,0.,,123456\nGRID,2,,{a:?},0.,0.,,123456\nGRID,3,,{a:?},{b:?},0.\n\
         GRID,4,,0.,{b:?},0.\nGRID,10,,.1,{b:?},0.,,3456\nCSHEAR,7,5,1,2,3,4\n\
         RBE2,8,10,123456,3,4\nCONM2,9,10,,{mass:?}\nENDDATA\n"
    );
    let hz = built_hz(&write("cshear", "panel.bdf", &deck), 2, &[]);
    println!(
        "CSHEAR {hz:?} vs closed form {exact:?}: {:.1e}",
        rel(&hz, &exact)
    );
    assert!(rel(&hz, &exact) < 1e-10);
}
