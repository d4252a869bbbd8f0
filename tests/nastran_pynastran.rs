//! Real decks from pyNastran's model collection (`models/` of SteveDoyle2/pyNastran, BSD-3)
//! that the Nastran importer refused for reasons of its own, not the deck's, and the cards
//! behind those refusals on decks written here (docs/nastran-pynastran.md):
//!
//! * CTUBE/PTUBE: a rod of the tube's A and J against the closed form of a massless rod with a
//!   point mass (axial √(EA/(L m)), torsion √(GJ/(L I))); a tapered or over-thick tube refused.
//! * MDLPRM: a note (HDF5), honoured at MSC's default (OFFDEF LROFF, SHRTOQ4 0: the same
//!   frequencies as without it), refused at another value or an unknown name.
//! * PARAM RSOPT/RSCON/SPARSEDR/OMODES, case control SHELLTHK/GKRESULTS/BGRESULTS/NLOPRM and
//!   `SUBCASE = 1`: notes, the same frequencies.
//! * PELAST, PBEND and a PBUSH1D with mass that no element uses: notes; the mass refused where
//!   a CBUSH1D uses it.
//! * Corner thicknesses T1..T4 ≥ 0, not all 0 (QRG CQUAD4); a refused SOL outranks the choice
//!   among the deck's subcases; a nested INCLUDE found from the main deck's folder.
//! * The real decks (external reference data, `nastran/pynastran/models/…`; skipped without
//!   it): they build, with the total mass and centre of mass of pyNastran 1.4.1's
//!   `mass_properties(model, sym_axis='no')`. None of them has a Nastran SOL 103 result beside
//!   it (their folders hold SOL 101/145 results or none).

use std::f64::consts::PI;
use std::path::Path;

use crate::nastran_support::{build_refused, built_hz, write};

/// E, ν (G = E / 2(1 + ν)), length, end mass and its inertia about the rod's axis.
const E: f64 = 2.0e11;
const NU: f64 = 0.3;
const L: f64 = 2.0;
const MASS: f64 = 10.0;
const INERTIA: f64 = 0.05;

/// A massless tube (ρ = 0) from clamped grid 1 to grid 2 at x = L, grid 2 carrying the CONM2
/// and moving only along and about x: axial and torsional modes. `property` is the PTUBE line;
/// `bulk` extra bulk lines, `case` extra case control lines.
fn tube_deck(property: &str, case: &str, bulk: &str) -> String {
    format!(
        "SOL 103\nCEND\n{case}SPC = 1\nMETHOD = 1\nBEGIN BULK\n\
         GRID,1,,0.,0.,0.\nGRID,2,,{L},0.,0.,,2356\n\
         CTUBE,5,10,1,2\n{property}\n\
         MAT1,1,{E},,{NU},0.\n\
         CONM2,9,2,,{MASS},,,,,+C\n+C,{INERTIA},,{INERTIA},,,{INERTIA}\n\
         SPC1,1,123456,1\nEIGRL,1,,,2\n{bulk}ENDDATA\n"
    )
}

/// Axial and torsional frequencies (Hz) of the massless rod of area `a` and polar moment `j`
/// with the end mass: f = √(k/m)/2π with k = EA/L, GJ/L (ascending).
fn closed_form(a: f64, j: f64) -> Vec<f64> {
    let g = E / (2.0 * (1.0 + NU));
    let mut f = vec![
        (E * a / L / MASS).sqrt() / (2.0 * PI),
        (g * j / L / INERTIA).sqrt() / (2.0 * PI),
    ];
    f.sort_by(f64::total_cmp);
    f
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / y.abs())
        .fold(0.0, f64::max)
}

/// A hollow tube (OD 0.05, T 0.005: d = 0.04) and a solid one (T blank): A = π/4 (D² − d²),
/// J = π/32 (D⁴ − d⁴).
#[test]
fn ctube_is_a_rod_of_the_tube_section() {
    let (d, inner) = (0.05_f64, 0.04_f64);
    let hollow = (
        PI / 4.0 * (d * d - inner * inner),
        PI / 32.0 * (d.powi(4) - inner.powi(4)),
    );
    let solid = (PI / 4.0 * d * d, PI / 32.0 * d.powi(4));
    for (name, ptube, (a, j)) in [
        ("hollow", "PTUBE,10,1,0.05,0.005", hollow),
        ("solid", "PTUBE,10,1,0.05", solid),
        ("solid_t0_od2", "PTUBE,10,1,0.05,0.,,0.05", solid),
    ] {
        let deck = write("ctube", &format!("{name}.bdf"), &tube_deck(ptube, "", ""));
        let built = built_hz(&deck, 2, &[]);
        let expected = closed_form(a, j);
        // measured ≤ 2e-15 (two dofs, exact up to the eigensolver's rounding)
        assert!(
            rel(&built, &expected) < 1e-10,
            "{name}: {built:?} vs {expected:?}"
        );
    }
}

#[test]
fn tapered_or_over_thick_tubes_are_refused_by_field() {
    for (name, ptube, needle) in [
        (
            "tapered",
            "PTUBE,10,1,0.05,0.005,,0.06",
            "OD2 = 0.06 ≠ OD = 0.05: a tapered tube",
        ),
        (
            "thick",
            "PTUBE,10,1,0.05,0.03",
            "T = 0.03: the wall must be 0 ≤ T ≤ OD/2",
        ),
        ("no_od", "PTUBE,10,1,,0.005", "OD must be > 0"),
    ] {
        let text = tube_deck(ptube, "", "");
        let deck = write("ptube_refused", &format!("{name}.bdf"), &text);
        let err = build_refused(&deck);
        let line = crate::nastran_support::line_of(&text, "PTUBE");
        assert!(
            err.contains(&format!("{name}.bdf:{line}: PTUBE 10")) && err.contains(needle),
            "{err}"
        );
    }
}

/// The hollow tube's frequencies (the closed form, checked above).
fn hollow_hz() -> Vec<f64> {
    let (d, inner) = (0.05_f64, 0.04_f64);
    closed_form(
        PI / 4.0 * (d * d - inner * inner),
        PI / 32.0 * (d.powi(4) - inner.powi(4)),
    )
}

const HOLLOW: &str = "PTUBE,10,1,0.05,0.005";

#[test]
fn mdlprm_parameters_are_notes_honoured_defaults_or_refused() {
    // notes and MSC's defaults: the body is unchanged
    let bulk = "MDLPRM,HDF5,1\nMDLPRM  OFFDEF  LROFF   SHRTOQ4 0       QR6ROT\nMDLPRM,PRTMASS,no\n";
    let deck = write("mdlprm", "accepted.bdf", &tube_deck(HOLLOW, "", bulk));
    let built = built_hz(&deck, 2, &[]);
    // measured ≤ 2e-15
    assert!(rel(&built, &hollow_hz()) < 1e-10, "{built:?}");

    // a value other than the default, and a name the table does not know
    let bulk = "MDLPRM,HDF5,0,OFFDEF,NOMASS\nMDLPRM,SHRTOQ4,1\nMDLPRM,NOSUCH,1\n";
    let text = tube_deck(HOLLOW, "", bulk);
    let deck = write("mdlprm", "refused.bdf", &text);
    let err = build_refused(&deck);
    let line = crate::nastran_support::line_of(&text, "MDLPRM,HDF5");
    for needle in [
        format!("refused.bdf:{line}: MDLPRM OFFDEF = NOMASS: only LROFF is honoured"),
        format!(
            "refused.bdf:{}: MDLPRM SHRTOQ4 = 1: SHRTOQ4 forms CSHEAR panels as CQUAD4",
            line + 1
        ),
        format!("refused.bdf:{}: MDLPRM NOSUCH = 1: not read", line + 2),
        "--ignore MDLPRM".to_owned(),
    ] {
        assert!(err.contains(&needle), "{needle} in {err}");
    }
    assert!(err.contains("3 card(s)"), "{err}");
}

#[test]
fn output_params_commands_and_subcase_equals_build_the_same_body() {
    let case = "SUBCASE = 1\nSHELLTHK(PRINT) = ALL\nGKRESULTS(PLOT) = ALL\n\
                BGRESULTS(TRACTION,FORCE,PLOT) = ALL\nNLOPRM OUTCTRL=(SOLUTION,INTERM)\n";
    let bulk = "PARAM,RSOPT,1\nPARAM,RSCON,YES\nPARAM   SPARSEDR      No\nPARAM,OMODES,11\n";
    let deck = write("output_notes", "notes.bdf", &tube_deck(HOLLOW, case, bulk));
    let built = built_hz(&deck, 2, &[]);
    // measured ≤ 2e-15
    assert!(rel(&built, &hollow_hz()) < 1e-10, "{built:?}");
}

#[test]
fn unused_properties_are_notes_and_a_used_bush_mass_is_refused() {
    // PELAST on the deck's PELAS, a PBEND and a PBUSH1D with mass that no element uses
    let bulk = "PELAS,11,100.\nPELAST,11,,,42\nPBEND,70,1,1.0,1.0,0.1,0.1,0.,45.\n\
                PBUSH1D,71,3000.,200.,300.\n";
    let deck = write("unused_props", "unused.bdf", &tube_deck(HOLLOW, "", bulk));
    let built = built_hz(&deck, 2, &[]);
    // measured ≤ 2e-15
    assert!(rel(&built, &hollow_hz()) < 1e-10, "{built:?}");

    // a CBUSH1D on that PBUSH1D: its mass is refused, by the PBUSH1D's field
    let bulk = format!(
        "{bulk}GRID,3,,{},0.,0.,,23456\nCBUSH1D,70,71,2,3\n",
        2.0 * L
    );
    let text = tube_deck(HOLLOW, "", &bulk);
    let deck = write("unused_props", "used.bdf", &text);
    let err = build_refused(&deck);
    let line = crate::nastran_support::line_of(&text, "PBUSH1D");
    assert!(
        err.contains(&format!("used.bdf:{line}: PBUSH1D 71"))
            && err.contains("M = 300, used by CBUSH1D 70"),
        "{err}"
    );
}

/// A clamped strip of two CQUAD4 (1 × 0.5 each, t = 0.01): element 2's corners T1..T4 =
/// 0, 0.01, 0.01, 0 (QRG CQUAD4: Ti ≥ 0, not all zero) build as its mean thickness 0.005,
/// the same body as element 2 with T = 0.005 (the documented rule: each element takes the
/// mean of its corners, with a warning).
#[test]
fn corner_thicknesses_may_be_zero_but_not_all() {
    let strip = |t2: &str| {
        format!(
            "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\n\
             GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,2.,0.,0.\n\
             GRID,4,,0.,.5,0.\nGRID,5,,1.,.5,0.\nGRID,6,,2.,.5,0.\n\
             CQUAD4,1,1,1,2,5,4\nCQUAD4,2,1,2,3,6,5{t2}\n\
             PSHELL,1,1,0.01,1,,1\nMAT1,1,7.e10,,0.33,2700.\n\
             SPC1,1,123456,1,4\nENDDATA\n"
        )
    };
    let tapered = write("corner_t", "tapered.bdf", &strip(",,,\n,,,0.,0.01,0.01,0."));
    let mean = write(
        "corner_t",
        "mean.bdf",
        &strip(",,,\n,,,0.005,0.005,0.005,0.005"),
    );
    let (a, b) = (built_hz(&tapered, 4, &[]), built_hz(&mean, 4, &[]));
    // measured 0 (the same matrices)
    assert!(rel(&a, &b) < 1e-12, "{a:?} vs {b:?}");

    let text = strip(",,,\n,,,0.,0.,0.,0.");
    let zero = write("corner_t", "zero.bdf", &text);
    let err = build_refused(&zero);
    assert!(
        err.contains("element 2") && err.contains("each must be ≥ 0 and not all 0"),
        "{err}"
    );
}

/// SOL 105 with a static and a buckling subcase (bend_A1_105.bdf's layout): the solution's
/// refusal, not a request for --subcase.
#[test]
fn a_refused_solution_outranks_the_subcase_choice() {
    let text = tube_deck(HOLLOW, "", "")
        .replace("SOL 103", "SOL 105")
        .replace(
            "SPC = 1\nMETHOD = 1\n",
            "SUBCASE 1\n SPC = 1\nSUBCASE 2\n SPC = 1\n METHOD = 1\n",
        );
    let deck = write("sol_first", "buckling.bdf", &text);
    let err = build_refused(&deck);
    assert!(
        err.contains("buckling.bdf:1: SOL 105 (executive control): buckling")
            && !err.contains("--subcase"),
        "{err}"
    );
}

/// `JOBS/QS/main.bdf` includes `../../INCLUDE/part.dat`, which includes
/// `../../BULK/tube.blk` written from the job's folder (as pyNastran's models/Satellite_V02):
/// found from the main deck's folder when the including file's folder has no such file.
#[test]
fn nested_include_is_found_from_the_main_decks_folder() {
    let root = crate::common::scratch("include_from_main");
    for sub in ["JOBS/QS", "INCLUDE", "BULK"] {
        std::fs::create_dir_all(root.join(sub)).unwrap();
    }
    let deck = tube_deck(HOLLOW, "", "");
    let (head, tail) = deck.split_once("CTUBE").unwrap();
    let (elements, rest) = tail.split_once("MAT1").unwrap();
    let main = format!("{head}INCLUDE '../../INCLUDE/part.dat'\nMAT1{rest}");
    std::fs::write(root.join("JOBS/QS/main.bdf"), main).unwrap();
    std::fs::write(
        root.join("INCLUDE/part.dat"),
        "INCLUDE '../../BULK/tube.blk'\n",
    )
    .unwrap();
    std::fs::write(root.join("BULK/tube.blk"), format!("CTUBE{elements}")).unwrap();
    let built = built_hz(&root.join("JOBS/QS/main.bdf"), 2, &[]);
    // measured ≤ 2e-15
    assert!(rel(&built, &hollow_hz()) < 1e-10, "{built:?}");
}

/// A real deck of pyNastran's collection: its path in the external reference data.
fn pynastran_deck(test: &str, rel: &str) -> Option<std::path::PathBuf> {
    crate::common::external_reference(test, &format!("nastran/pynastran/{rel}"))
}

/// Build `deck` (`units`, 8 normal modes) and return the file's total mass and centre of mass.
fn mass_and_centre(deck: &Path, units: &str) -> (f64, [f64; 3]) {
    let out = crate::common::scratch("pynastran_real").join(format!(
        "{}.flexbody",
        deck.file_stem().unwrap().to_string_lossy()
    ));
    let run = crate::common::exe()
        .arg("build")
        .arg(deck)
        .args(["--units", units, "--method", "normal", "--modes", "8", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}: {}",
        deck.display(),
        String::from_utf8_lossy(&run.stderr)
    );
    let body = flexbody_reader::read(&out).unwrap();
    let (m, s) = (body.invariants.i1[0], &body.invariants.i2);
    (m, [s[0] / m, s[1] / m, s[2] / m])
}

/// The real decks this work made build, each against pyNastran 1.4.1's
/// `mass_properties(model, sym_axis='no')` (mass, centre of mass).
#[test]
fn real_pynastran_decks_build_with_pynastrans_mass() {
    // (deck, units, pyNastran's mass, centre, tolerance: about 10× the measured difference)
    let cases: [(&str, &str, f64, [f64; 3], f64); 4] = [
        // corner thicknesses 0 at the leading and trailing edges (PARAM WTMASS 0.0025901);
        // measured 5e-16 (mass), 9.4e-10 (centre)
        (
            "models/aero/ha145z.bdf",
            "in-lbf-s",
            1.0360445614227579e-4,
            [1.775495417755802, 2.7625504356607453, 0.0],
            1e-8,
        ),
        // MDLPRM OFFDEF LROFF; measured 9.6e-9 (mass), 2e-16 (centre)
        (
            "models/bugs/msc_RBE_tests/rigid_rbe2.bdf",
            "si",
            43.22120616747973,
            [0.1, 0.1, 0.25],
            1e-7,
        ),
        // PARAM OMODES (its write_modes alter's output); measured 4e-15 (mass), 8.4e-7 (centre)
        (
            "models/iSat/ISat_Launch_Sm_4pt.dat",
            "in-lbf-s",
            1.7746011578443164,
            [
                -0.033850938596997684,
                -2.530614958629112,
                -18.467658950188863,
            ],
            8e-6,
        ),
        // PARAM RSOPT, RSCON (Response Simulation output); the same structure
        (
            "models/iSat/ISat_Launch_Sm_Rgd.dat",
            "in-lbf-s",
            1.7746011578443164,
            [
                -0.033850938596997684,
                -2.530614958629112,
                -18.467658950188863,
            ],
            8e-6,
        ),
    ];
    for (rel_path, units, mass, centre, tol) in cases {
        let Some(deck) =
            pynastran_deck("real_pynastran_decks_build_with_pynastrans_mass", rel_path)
        else {
            return;
        };
        let (m, c) = mass_and_centre(&deck, units);
        let scale = centre.iter().fold(1.0_f64, |a, x| a.max(x.abs()));
        let dc = (0..3).map(|i| (c[i] - centre[i]).abs()).fold(0.0, f64::max) / scale;
        eprintln!("{rel_path}: mass {m:e} (pyNastran {mass:e}), centre {c:?}: {dc:e}");
        assert!(
            (m - mass).abs() <= tol * mass,
            "{rel_path}: mass {m} vs {mass}"
        );
        assert!(dc <= tol, "{rel_path}: centre {c:?} vs {centre:?}");
    }
}
