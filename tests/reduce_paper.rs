//! Wang, Niu & Feng 2023 planar beam (Table 1 values, 12 elements): normal modes, Craig–Bampton
//! and the improved CB methods 1 and 2 against the paper's Tables 2–4 and against each other.

use flexbody::fe::elements::planar_frame::{
    straight_beam, FrameMass, FrameSection, PAPER_ELEMENTS, PAPER_LENGTH,
};
use flexbody::reduce::craig_bampton::craig_bampton;
use flexbody::reduce::normal::normal_modes;
use flexbody::reduce::reference::{improved_cb_method1, improved_cb_method2};
use flexbody::reduce::select::ModeCount;
use flexbody::reduce::{ModeLabel, ModeSet};
use flexbody::solve::{EigenSpec, SparseColMat};

type Sparse = SparseColMat<usize, f64>;

fn beam(kind: FrameMass) -> (Sparse, Sparse) {
    straight_beam(
        &FrameSection::paper_table1(),
        PAPER_LENGTH,
        PAPER_ELEMENTS,
        kind,
    )
}

fn eig() -> EigenSpec {
    EigenSpec::default()
}

/// Node 1 of the paper = index 0; node 13 = index 12; node 9 (point A) = index 8.
const U1: usize = 0;
const V1: usize = 1;
const V13: usize = 3 * 12 + 1;
const V9: usize = 3 * 8 + 1;

fn flexible_hz(s: &ModeSet) -> Vec<f64> {
    s.frequencies_hz()
        .into_iter()
        .zip(&s.labels)
        .filter(|(_, l)| **l != ModeLabel::Rigid)
        .map(|(f, _)| f)
        .collect()
}

/// The paper's printed values sit a uniform +1.2e-4 … +1.7e-4 above this model with the Table 1
/// values (a 3e-4 difference in EI/ρA, i.e. the 4-digit rounding of Table 1); the exact
/// Euler–Bernoulli free-free value 138.887 Hz is below our 138.8885 Hz as it must be.
const PAPER_REL: f64 = 2.5e-4;

fn assert_close(got: &[f64], want: &[f64], rel: f64, what: &str) {
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= rel * w,
            "{what} mode {i}: {g:.4} vs {w:.2} (all: {got:?})"
        );
    }
}

fn checks(s: &ModeSet) {
    assert!(
        s.diagnostics.orthonormality <= 1e-10,
        "{}",
        s.diagnostics.orthonormality
    );
    assert!(
        s.diagnostics.stiffness_diag <= 1e-10,
        "{}",
        s.diagnostics.stiffness_diag
    );
}

#[test]
fn table2_free_free_and_simply_supported_normal_modes() {
    let (k, m) = beam(FrameMass::Consistent);
    let ff = normal_modes(&k, &m, ModeCount::Count(9), &[], &eig()).unwrap();
    checks(&ff);
    assert_eq!(
        ff.labels.iter().filter(|l| **l == ModeLabel::Rigid).count(),
        3
    );
    let f = flexible_hz(&ff);
    println!("free-free consistent: {f:?}");
    assert_close(&f, &[138.91, 382.94, 750.97], PAPER_REL, "free-free");
    // exact Euler–Bernoulli free-free: (4.7300408)²/(2πL²)·√(EI/ρA), FE converges from above
    let sec = FrameSection::paper_table1();
    let exact = 4.730_040_7f64.powi(2) / (2.0 * std::f64::consts::PI * PAPER_LENGTH * PAPER_LENGTH)
        * (sec.e * sec.inertia / (sec.density * sec.area)).sqrt();
    assert!(
        f[0] > exact && f[0] < exact * (1.0 + 5e-5),
        "{} vs exact {exact}",
        f[0]
    );
    let ss = normal_modes(&k, &m, ModeCount::Count(6), &[U1, V1, V13], &eig()).unwrap();
    checks(&ss);
    let f = ss.frequencies_hz();
    println!("simply supported consistent: {f:?}");
    assert_close(
        &f,
        &[61.28, 245.11, 551.62, 981.19, 1534.85, 2214.60],
        PAPER_REL,
        "simply supported",
    );
}

#[test]
fn table3_extended_beam_simply_supported_normal_modes() {
    let (k, m) = beam(FrameMass::Consistent);
    let ss = normal_modes(&k, &m, ModeCount::Count(6), &[U1, V1, V9], &eig()).unwrap();
    checks(&ss);
    let f = ss.frequencies_hz();
    println!("extended simply supported consistent: {f:?}");
    assert_close(
        &f,
        &[88.64, 209.40, 606.26, 1014.15, 1403.73, 2318.76],
        PAPER_REL,
        "extended",
    );
    // the values of this model to 2 decimals (issue 5 acceptance): 88.62, 209.38, 606.18 Hz
    assert_close(
        &f[..3],
        &[88.62, 209.38, 606.18],
        0.006 / 88.0,
        "extended (Table 1 model)",
    );
}

#[test]
fn table2_craig_bampton_free_free() {
    let (k, m) = beam(FrameMass::Consistent);
    let iface = [0, 1, 2, 36, 37, 38];
    let full = normal_modes(&k, &m, ModeCount::Count(39), &[], &eig()).unwrap();
    // all fixed-interface modes: the CB set is the full spectrum
    let all = craig_bampton(&k, &m, &iface, ModeCount::All, &eig()).unwrap();
    checks(&all);
    assert_eq!(all.len(), 39);
    let lmax = full.omega2[38];
    for j in 0..39 {
        assert!(
            (all.omega2[j] - full.omega2[j]).abs() <= 1e-9 * full.omega2[j].abs().max(1e-3 * lmax),
            "{j}"
        );
    }
    // truncated: Rayleigh–Ritz upper bounds, and the paper's first three flexible modes
    for nq in [3, 6, 10, 20] {
        let cb = craig_bampton(&k, &m, &iface, ModeCount::Count(nq), &eig()).unwrap();
        checks(&cb);
        for j in 0..cb.len() {
            assert!(
                cb.omega2[j] >= full.omega2[j] * (1.0 - 1e-10) - 1e-9 * lmax,
                "nq {nq} mode {j}"
            );
        }
        println!("CB nq={nq}: {:?}", flexible_hz(&cb));
        if nq >= 10 {
            assert_close(
                &flexible_hz(&cb)[..3],
                &[138.91, 382.94, 750.97],
                2.0 * PAPER_REL,
                "CB free-free",
            );
        }
    }
}

#[test]
fn table4_improved_cb_methods_agree_and_equal_simply_supported_modes() {
    let (k, m) = beam(FrameMass::Consistent);
    let iface = [0, 1, 2, 24, 25, 26];
    let reference = [U1, V1, V9];
    let ss = normal_modes(&k, &m, ModeCount::Count(36), &reference, &eig()).unwrap();
    let m1 = improved_cb_method1(&k, &m, &iface, &reference, ModeCount::All, &eig()).unwrap();
    let m2 = improved_cb_method2(&k, &m, &iface, &reference, ModeCount::All, &eig()).unwrap();
    checks(&m1);
    checks(&m2);
    assert_eq!(m1.len(), 36);
    assert_eq!(m2.len(), 36);
    assert_eq!(m1.reference_dofs, reference.to_vec());
    let lmax = ss.omega2[35];
    for j in 0..36 {
        assert!(
            (m1.omega2[j] - m2.omega2[j]).abs() <= 1e-10 * lmax,
            "methods differ at {j}"
        );
        assert!(
            (m1.omega2[j] - ss.omega2[j]).abs() <= 1e-9 * lmax,
            "vs normal modes at {j}"
        );
    }
    println!("improved CB, all modes: {:?}", &m1.frequencies_hz()[..6]);
    for nq in [1, 2, 3, 4, 5, 6, 8, 10] {
        let a =
            improved_cb_method1(&k, &m, &iface, &reference, ModeCount::Count(nq), &eig()).unwrap();
        let b =
            improved_cb_method2(&k, &m, &iface, &reference, ModeCount::Count(nq), &eig()).unwrap();
        let lmax = a.omega2.last().copied().unwrap();
        for j in 0..a.len() {
            assert!(
                (a.omega2[j] - b.omega2[j]).abs() <= 1e-10 * lmax,
                "nq {nq}: methods differ at {j}"
            );
            assert!(
                a.omega2[j] >= ss.omega2[j] * (1.0 - 1e-10),
                "nq {nq}: below the exact value at {j}"
            );
        }
        println!(
            "improved CB nq={nq}: {:?}",
            &a.frequencies_hz()[..6.min(a.len())]
        );
    }
}

#[test]
fn lumped_mass_variant() {
    let (k, m) = beam(FrameMass::Lumped);
    let ff = normal_modes(&k, &m, ModeCount::Count(6), &[], &eig()).unwrap();
    let ss = normal_modes(&k, &m, ModeCount::Count(3), &[U1, V1, V9], &eig()).unwrap();
    checks(&ff);
    println!(
        "lumped free-free {:?}, extended simply supported {:?}",
        flexible_hz(&ff),
        ss.frequencies_hz()
    );
    // HRZ lumping lowers the bending frequencies below the consistent-mass values of the paper
    // (Wang, Niu & Feng 2023, normal mode approach: Table 2 free-free 138.91 Hz, Table 3
    // extended simply supported 88.64 Hz), by less than 3 % (measured 135.40 Hz, −2.5 %;
    // 87.30 Hz, −1.5 %)
    let (paper_free, paper_supported) = (138.91, 88.64);
    let (fl, sl) = (flexible_hz(&ff)[0], ss.frequencies_hz()[0]);
    assert!(fl < paper_free && fl > 0.97 * paper_free, "{fl}");
    assert!(sl < paper_supported && sl > 0.97 * paper_supported, "{sl}");
}
