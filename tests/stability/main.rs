//! The stability matrix (issue 8, table in docs/stability.md): one test per (method × hazard)
//! row, each asserting the documented outcome — an error variant and message naming the entity,
//! or an accuracy bound against an independent reference — and, for the failing command-line
//! runs, that no output file is left behind.

// Index loops mirror the matrix formulas.
#![allow(clippy::needless_range_loop)]

mod rows_7_11;
mod support;

use faer::Mat;
use flexbody::fe::{assemble, AssemblySpec, BeamLumping, MassKind};
use flexbody::reduce::craig_bampton::craig_bampton;
use flexbody::reduce::craig_chang::{craig_chang, unit_loads};
use flexbody::reduce::dietz::{dietz, dietz_modified};
use flexbody::reduce::normal::normal_modes;
use flexbody::reduce::select::ModeCount;
use flexbody::reduce::ReduceError;
use support::*;

// ---------------------------------------------------------------------------------------------
// Row 1 — Craig–Bampton, interior not restrained by the interface.

/// One interface node with only its 3 translations on a solid: K_ii is singular (3 rotations
/// about the node are free). Detected at the zero pivot; the region is the whole interior and it
/// touches the interface.
#[test]
fn row01_cb_single_translational_node_leaves_rotations_free() {
    let (model, k, m) = system(&block([6, 2, 2], [0.3, 0.05, 0.05]));
    let iface = node_dofs(&model, &[0], 3);
    let e = craig_bampton(&k, &m, &iface, ModeCount::Count(4), &eig()).unwrap_err();
    match &e {
        ReduceError::UnrestrainedInterior {
            region, connected, ..
        } => {
            assert!(*connected, "{e}");
            assert_eq!(*region, k.nrows() - 3, "{e}");
        }
        other => panic!("expected UnrestrainedInterior, got {other}"),
    }
    assert!(e.to_string().contains("RBE2"), "{e}");
    // the positive control: the whole x = 0 face as interface holds the body
    let x0 = set_dofs(&model, "X0");
    let cb = craig_bampton(&k, &m, &x0, ModeCount::Count(4), &eig()).unwrap();
    assert!(cb.omega2.iter().all(|w| w.is_finite()));
}

/// A singular K_ii whose rounding leaves a tiny *positive* pivot (interior block [[1, 1], [1, 1 +
/// δ]]): δ = 1e-15 is below the 1e-14 pivot threshold and reported as unrestrained, δ = 1e-12
/// (an ill-conditioned but regular interior, like a 1e10 stiffness contrast) factors.
#[test]
fn row01_cb_tiny_positive_pivot_is_a_zero_pivot() {
    let system3 = |delta: f64| {
        let t = |i, j, v| flexbody::solve::Triplet::new(i, j, v);
        let k = Sparse::try_new_from_triplets(
            3,
            3,
            &[
                t(0, 0, 2.0),
                t(0, 1, -1.0),
                t(1, 0, -1.0),
                t(1, 1, 1.0),
                t(1, 2, 1.0),
                t(2, 1, 1.0),
                t(2, 2, 1.0 + delta),
            ],
        )
        .unwrap();
        let m = Sparse::try_new_from_triplets(3, 3, &[t(0, 0, 1.0), t(1, 1, 1.0), t(2, 2, 1.0)])
            .unwrap();
        (k, m)
    };
    let (k, m) = system3(1e-15);
    let e = craig_bampton(&k, &m, &[0], ModeCount::Count(0), &eig()).unwrap_err();
    match &e {
        ReduceError::UnrestrainedInterior {
            pivot,
            region,
            connected,
            ..
        } => {
            assert!(*pivot > 0.0 && *pivot < 1e-14, "{e}");
            assert_eq!((*region, *connected), (2, true), "{e}");
        }
        other => panic!("expected UnrestrainedInterior, got {other}"),
    }
    let (k, m) = system3(1e-12);
    assert!(craig_bampton(&k, &m, &[0], ModeCount::Count(0), &eig()).is_ok());
}

/// A second block not connected to the first: the interior region of the zero pivot is exactly
/// the second block's dofs and it does not touch the interface.
#[test]
fn row01_cb_disconnected_part_is_its_own_region() {
    let two = two_blocks(Joint::Gap);
    let (model, k, m) = system(&two);
    let iface = set_dofs(&model, "A_X0");
    let e = craig_bampton(&k, &m, &iface, ModeCount::Count(4), &eig()).unwrap_err();
    let b_nodes = model.node_sets["B_ALL"].len();
    match &e {
        ReduceError::UnrestrainedInterior {
            region, connected, ..
        } => {
            assert!(!*connected, "{e}");
            assert_eq!(*region, 3 * b_nodes, "{e}");
        }
        other => panic!("expected UnrestrainedInterior, got {other}"),
    }
}

/// The command line names the part (element ids and element set) or the free rotations before
/// any factorization, exits 2 and writes nothing.
#[test]
fn row01_cli_names_the_unrestrained_part_and_writes_nothing() {
    let dir = TempDir::new("row01");
    let two = dir.write_inp("two.inp", &two_blocks(Joint::Gap));
    let err = fail_run(&dir, &[&two, "--interface", "A_X0", "--units", "si"], &[]);
    assert_contains(
        &err,
        &[
            "part 2 of 2",
            "PART_B",
            "not connected to any interface node",
        ],
    );
    let one = dir.write_inp("one.inp", &block([6, 2, 2], [0.3, 0.05, 0.05]));
    let err = fail_run(&dir, &[&one, "--interface", "1", "--units", "si"], &[]);
    assert_contains(
        &err,
        &[
            "not held by its interface dofs",
            "rotation about",
            "--spider rbe2",
        ],
    );
}

// ---------------------------------------------------------------------------------------------
// Row 2 — free-free analysis with more than 6 zero modes.

/// Two separate blocks: 12 zero modes; touching at one node: 9 (3 relative rotations); along an
/// edge: 7 (1 hinge rotation). Normal modes and Craig–Chang report the count.
#[test]
fn row02_free_free_counts_zero_modes_of_parts_and_mechanisms() {
    for (joint, zeros) in [(Joint::Gap, 12), (Joint::Corner, 9), (Joint::Edge, 7)] {
        let (_, k, m) = system(&two_blocks(joint));
        let e = normal_modes(&k, &m, ModeCount::Count(16), &[], &eig()).unwrap_err();
        assert!(
            matches!(e, ReduceError::Mechanism { zero_modes, at_least: false } if zero_modes == zeros),
            "{joint:?}: {e}"
        );
        let fa = unit_loads(k.nrows(), &[0, 1, 2]).unwrap();
        let e = craig_chang(&k, &m, &fa, ModeCount::Count(16), &eig()).unwrap_err();
        assert!(
            matches!(e, ReduceError::Mechanism { zero_modes, .. } if zero_modes == zeros),
            "{joint:?}: {e}"
        );
    }
}

/// Control: a slender free beam on a fine mesh (1000 elements, λ₁ ≈ 1e-10 of the median
/// K_ii/M_ii) has exactly 6 zero modes and its first bending mode meets Euler–Bernoulli — the
/// zero-mode threshold must not swallow genuine low modes (with the former threshold 1e-9 the
/// bending pair counted as zero modes: `Mechanism` with 8).
#[test]
fn row02_fine_slender_beam_is_not_a_mechanism() {
    let model = beam_model(1000);
    let a = assemble(&model, &AssemblySpec::default()).unwrap();
    let spec = flexbody::solve::EigenSpec {
        dofs_per_node: Some(6),
        ..eig()
    };
    let s = normal_modes(&a.k, &a.m, ModeCount::Count(10), &[], &spec).unwrap();
    let rigid = s
        .labels
        .iter()
        .filter(|l| **l == flexbody::reduce::ModeLabel::Rigid)
        .count();
    assert_eq!(rigid, 6, "{:?}", s.omega2);
    let (e, rho, area, i): (f64, f64, f64, f64) = (210e9, 7850.0, 1e-4, 1e-8 / 12.0);
    let w1 = 4.730_040_745f64.powi(2) * (e * i / (rho * area)).sqrt();
    let err = (s.omega2[6].sqrt() / w1 - 1.0).abs();
    // the lumped section rotary inertia lowers the frequency by about (β₁r)² = 4.73²·I/A = 1.9e-4
    // (Rayleigh beam) below Euler–Bernoulli
    assert!(
        err < 5e-4,
        "first bending {} vs {w1}: {err:e}",
        s.omega2[6].sqrt()
    );
    record(
        "2",
        "fine free beam (1000 el.): first bending vs Euler–Bernoulli (rel.)",
        err,
    );
}

/// The command line names both parts of a disconnected model (element ids and sets), and the
/// element groups of a mechanism inside one connected part (solids sharing only a node or an
/// edge) with the joint nodes — for free-free methods, and for Craig–Bampton when a group is not
/// held by the interface.
#[test]
fn row02_cli_names_disconnected_parts_and_counts_mechanism_modes() {
    let dir = TempDir::new("row02");
    let two = dir.write_inp("two.inp", &two_blocks(Joint::Gap));
    let err = fail_run(&dir, &[&two, "--method", "normal", "--units", "si"], &[]);
    assert_contains(
        &err,
        &[
            "2 disconnected parts",
            "12 zero-frequency",
            "PART_A",
            "PART_B",
            "ids 1–",
        ],
    );
    let corner = dir.write_inp("corner.inp", &two_blocks(Joint::Corner));
    let err = fail_run(&dir, &[&corner, "--method", "normal", "--units", "si"], &[]);
    assert_contains(
        &err,
        &[
            "is a mechanism",
            "2 groups that share no face, only node(s) 20",
            "group 1: 4 elements, ids 1–4, element sets PART_A",
            "group 2: 4 elements, ids 5–8, element sets PART_B",
        ],
    );
    let edge = dir.write_inp("edge.inp", &two_blocks(Joint::Edge));
    let err = fail_run(
        &dir,
        &[
            &edge,
            "--method",
            "dietz",
            "--interface",
            "A_X0",
            "--units",
            "si",
        ],
        &[],
    );
    assert_contains(&err, &["is a mechanism", "only node(s) 10, 20"]);
    let err = fail_run(
        &dir,
        &[&corner, "--interface", "A_X0", "--units", "si"],
        &[],
    );
    assert_contains(
        &err,
        &[
            "Craig–Bampton",
            "group 2 of 2 solid groups",
            "PART_B",
            "only node(s) 20",
            "left free",
        ],
    );
    let err = fail_run(
        &dir,
        &[
            &two,
            "--method",
            "craig-chang",
            "--interface",
            "A_X0",
            "--units",
            "si",
        ],
        &[],
    );
    assert_contains(&err, &["2 disconnected parts"]);
}

// ---------------------------------------------------------------------------------------------
// Row 3 — Craig–Chang / Dietz with dependent attachment vectors.

/// Loads at dofs a, b, a again and a + 2b: two dependent vectors removed and reported, the set
/// still M-orthonormal and K-diagonal against the full matrices (checked here independently).
#[test]
fn row03_dependent_attachments_are_removed_and_reported() {
    let (model, k, m) = system(&block([6, 2, 2], [0.3, 0.05, 0.05]));
    let xl = set_dofs(&model, "XL");
    let (a, b) = (xl[0], xl[4]);
    let n = k.nrows();
    let mut fa = unit_loads(n, &[a, b, a, a]).unwrap();
    fa[(b, 3)] = 2.0;
    let cc = craig_chang(&k, &m, &fa, ModeCount::Count(10), &eig()).unwrap();
    assert_eq!(
        cc.diagnostics.removed.len(),
        2,
        "{:?}",
        cc.diagnostics.removed
    );
    assert_eq!(cc.len(), 10 + 4 - 2);
    assert!(cc
        .diagnostics
        .notes
        .iter()
        .any(|s| s.contains("2 dependent vector(s) removed")));
    let (orth, kdiag) = orthonormality(&k, &m, &cc.phi, &cc.omega2);
    assert!(
        orth < 1e-9 && kdiag < 1e-9,
        "Craig–Chang: {orth:e} {kdiag:e}"
    );
    record("3", "Craig–Chang |ΦᵀMΦ−I|, |ΦᵀKΦ−Λ|/λmax", orth.max(kdiag));
    let dz = dietz(&k, &m, &fa, ModeCount::Count(10), None, &eig()).unwrap();
    assert_eq!(dz.diagnostics.removed.len(), 2);
    let (orth, kdiag) = orthonormality(&k, &m, &dz.phi, &dz.omega2);
    assert!(orth < 1e-9 && kdiag < 1e-9, "Dietz: {orth:e} {kdiag:e}");
    record("3", "Dietz |ΦᵀMΦ−I|, |ΦᵀKΦ−Λ|/λmax", orth.max(kdiag));
}

/// Interface nodes coupled by an RBE2 (an interface node set's spider plus one of its own nodes):
/// the node's dofs are dependent, so it cannot be an interface node — a clear error, no file.
#[test]
fn row03_cli_rbe2_coupled_interface_node_is_an_error() {
    let dir = TempDir::new("row03");
    let one = dir.write_inp("one.inp", &block([6, 2, 2], [0.3, 0.05, 0.05]));
    let err = fail_run(&dir, &[&one, "--interface", "X0,1", "--units", "si"], &[]);
    assert_contains(&err, &["node 1", "not independent"]);
}

// ---------------------------------------------------------------------------------------------
// Row 4 — Dietz with ℓ near an eigenvalue.

/// ℓ ≥ 0.9 λ₁ (and ℓ = λ₁, ℓ above it, ℓ ≤ 0) is refused with the ratio and the remedy; ℓ = ½λ₁
/// gives a set whose free-free part reproduces the normal modes.
#[test]
fn row04_dietz_shift_near_first_eigenvalue_is_refused() {
    let (_, k, m) = system(&block([6, 2, 2], [0.3, 0.05, 0.05]));
    let ff = normal_modes(&k, &m, ModeCount::Count(12), &[], &eig()).unwrap();
    let l1 = ff.omega2[6];
    let fa = unit_loads(k.nrows(), &[0, 1, 2]).unwrap();
    for ratio in [0.95, 1.0, 1.5, -0.1] {
        let e = dietz(&k, &m, &fa, ModeCount::Count(12), Some(ratio * l1), &eig()).unwrap_err();
        assert!(
            matches!(
                &e,
                ReduceError::Dofs {
                    what: "Dietz shift",
                    ..
                }
            ),
            "{ratio}: {e}"
        );
        let e2 = dietz_modified(&k, &m, &fa, 12, 24, Some(ratio * l1), &eig()).unwrap_err();
        assert!(
            matches!(
                &e2,
                ReduceError::Dofs {
                    what: "Dietz shift",
                    ..
                }
            ),
            "{e2}"
        );
    }
    let e = dietz(&k, &m, &fa, ModeCount::Count(12), Some(0.95 * l1), &eig()).unwrap_err();
    assert_contains(
        &e.to_string(),
        &["0.9500 x the first flexible eigenvalue", "singular"],
    );
    let ok = dietz(&k, &m, &fa, ModeCount::Count(12), Some(0.5 * l1), &eig()).unwrap();
    let worst = (6..12)
        .map(|j| (ok.omega2[j] / ff.omega2[j] - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-9, "Dietz ℓ = λ1/2 vs normal modes: {worst:e}");
    record(
        "4",
        "Dietz ℓ=λ1/2: first 6 flexible ω² vs normal modes (rel.)",
        worst,
    );
}

// ---------------------------------------------------------------------------------------------
// Row 5 — repeated and near-repeated eigenvalues.

/// Square-section block: the bending pairs are exactly repeated (y ↔ z symmetry of the mesh).
/// The sparse solver's eigenspaces match a dense reference by principal angles, and each returned
/// pair is M-orthonormal. A 1e-6 aspect change splits the pairs; the subspaces still match.
#[test]
fn row05_repeated_eigenvalues_match_as_subspaces() {
    for (aspect, label) in [(1.0, "repeated"), (1.0 + 1e-6, "near-repeated")] {
        let (_, k, m) = system(&block([12, 3, 3], [0.6, 0.05, 0.05 * aspect]));
        let count = 16;
        let s = normal_modes(&k, &m, ModeCount::Count(count), &[], &eig()).unwrap();
        let (vals, vecs) = dense_reference(&k, &m);
        let groups = clusters(&vals[..count], 1e-4);
        let mut worst = 0.0f64;
        let mut pairs = 0;
        for g in &groups {
            if g.len() < 2 || vals[g[0]] < 1e-6 * vals[count - 1] {
                continue; // single modes and the rigid cluster
            }
            pairs += 1;
            let a = Mat::from_fn(k.nrows(), g.len(), |i, j| s.phi[(i, g[j])]);
            let b = Mat::from_fn(k.nrows(), g.len(), |i, j| vecs[(i, g[j])]);
            worst = worst.max(max_principal_angle(&m, &a, &b));
        }
        assert!(
            pairs >= 3,
            "{label}: expected bending pairs, clusters {groups:?}"
        );
        let (orth, _) = orthonormality(&k, &m, &s.phi, &s.omega2);
        assert!(orth < 1e-9, "{label}: {orth:e}");
        assert!(
            worst < 1e-6,
            "{label}: largest principal angle {worst:e} rad"
        );
        record(
            "5",
            &format!("{label} pairs: largest principal angle (rad)"),
            worst,
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Row 6 — massless dofs.

/// A free beam with lumped mass and torsional inertia only (Nastran CBEAM lumped): the bending
/// rotations are massless (infinite eigenvalues). The lowest modes are finite and the first
/// bending frequency meets Euler–Bernoulli; the complete dense spectrum holds exactly the finite
/// ones (4 per node). Without any rotational inertia the free beam's torsional rigid mode has
/// neither stiffness nor mass (K and M share a null vector): an error, not a NaN.
#[test]
fn row06_massless_rotations_give_finite_modes_only() {
    let (model, ne, len) = (beam_model(40), 40, 1.0f64);
    let spec = AssemblySpec {
        mass: MassKind::Lumped,
        beam_lumping: BeamLumping::TorsionOnly,
        ..Default::default()
    };
    let a = assemble(&model, &spec).unwrap();
    let s = normal_modes(&a.k, &a.m, ModeCount::Count(10), &[], &eig()).unwrap();
    assert!(s.omega2.iter().all(|w| w.is_finite()));
    // free-free Euler–Bernoulli: ω₁ = (4.7300407)² √(EI/(ρA L⁴))
    let (e, rho, area, i) = (210e9, 7850.0, 1e-4, 1e-4f64.powi(2) / 12.0);
    let w1 = 4.730_040_745f64.powi(2) * (e * i / (rho * area * len.powi(4))).sqrt();
    let bend: Vec<f64> = s.omega2[6..].iter().map(|w| w.sqrt()).collect();
    let err = (bend[0] / w1 - 1.0).abs();
    assert!(err < 5e-3, "first bending {} vs EB {w1}: {err:e}", bend[0]);
    record(
        "6",
        "massless rotations, 40 beams: first bending vs Euler–Bernoulli (rel.)",
        err,
    );
    let all = normal_modes(&a.k, &a.m, ModeCount::All, &[], &eig()).unwrap();
    assert_eq!(all.len(), 4 * (ne + 1));
    assert!(all.omega2.iter().all(|w| w.is_finite()));
    let none = assemble(
        &model,
        &AssemblySpec {
            beam_lumping: BeamLumping::TranslationsOnly,
            ..spec
        },
    )
    .unwrap();
    let e = normal_modes(&none.k, &none.m, ModeCount::Count(10), &[], &eig()).unwrap_err();
    println!("row 6, no rotational inertia: {e}");
}

/// RBE2 spider centre nodes carry no mass of their own: the CB file built with node-set
/// interfaces has only finite numbers and passes `flexbody check` against the model.
#[test]
fn row06_cli_spider_centres_without_mass_give_a_finite_checked_file() {
    let dir = TempDir::new("row06");
    let one = dir.write_inp("one.inp", &block([6, 2, 2], [0.3, 0.05, 0.05]));
    let out = dir.path("one.flexbody");
    let run = run_cli(
        &[
            "build",
            &one,
            "--interface",
            "X0,XL",
            "--units",
            "si",
            "--modes",
            "20",
            "-q",
            "-o",
            &out,
        ],
        &[],
    );
    assert_eq!(run.0, Some(0), "{}", run.2);
    let body = flexbody_reader::read(std::path::Path::new(&out)).unwrap();
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    assert!(finite(&body.modes.frequency_hz) && finite(&body.modes.omega2));
    assert!(finite(&body.modes.shapes) && finite(&body.invariants.i3));
    let check = run_cli(
        &["check", &out, "--model", &one, "--interface", "X0,XL"],
        &[],
    );
    assert_eq!(check.0, Some(0), "{}", check.1);
}
