//! The stability matrix (issue 8, table in docs/stability.md): one test per (method × hazard)
//! row, each asserting the documented outcome — an error variant and message naming the entity,
//! or an accuracy bound against an independent reference — and, for the failing command-line
//! runs, that no output file is left behind.

// Index loops mirror the matrix formulas.
#![allow(clippy::needless_range_loop)]

mod support;

use faer::Mat;
use flexbody::fe::{assemble, AssemblySpec, BeamLumping, FeError, MassKind};
use flexbody::reduce::craig_bampton::craig_bampton;
use flexbody::reduce::craig_chang::{craig_chang, unit_loads};
use flexbody::reduce::dietz::{dietz, dietz_modified};
use flexbody::reduce::normal::normal_modes;
use flexbody::reduce::select::ModeCount;
use flexbody::reduce::{ModeLabel, ReduceError};
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

/// The command line names both parts of a disconnected model (element ids and sets), and the
/// zero-mode count of a mechanism inside one connected part.
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
    assert_contains(&err, &["found 9 zero-frequency modes", "mechanisms"]);
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

// ---------------------------------------------------------------------------------------------
// Row 7 — ill-conditioning: units and stiffness contrast.

/// The same block in m–kg–s and in mm–t–s (lengths ×1e3, E ×1e-6, ρ ×1e-12): normal-mode and
/// Craig–Bampton frequencies agree to 1e-8 relative.
#[test]
fn row07_units_m_kg_s_and_mm_t_s_agree() {
    let si = block([8, 2, 2], [0.4, 0.05, 0.05]);
    let mut mm = si.clone();
    mm.nodes.iter_mut().for_each(|n| n.x = n.x.map(|v| v * 1e3));
    mm.materials[0].e *= 1e-6;
    mm.materials[0].g *= 1e-6;
    mm.materials[0].rho *= 1e-12;
    let (ms, ks, mss) = system(&si);
    let (_, km, mmm) = system(&mm);
    let x0 = set_dofs(&ms, "X0");
    let mut worst = [0.0f64; 2];
    let n_si = normal_modes(&ks, &mss, ModeCount::Count(16), &[], &eig()).unwrap();
    let n_mm = normal_modes(&km, &mmm, ModeCount::Count(16), &[], &eig()).unwrap();
    let c_si = craig_bampton(&ks, &mss, &x0, ModeCount::Count(8), &eig()).unwrap();
    let c_mm = craig_bampton(&km, &mmm, &x0, ModeCount::Count(8), &eig()).unwrap();
    for (w, (a, b)) in worst.iter_mut().zip([(&n_si, &n_mm), (&c_si, &c_mm)]) {
        let (fa, fb) = (a.frequencies_hz(), b.frequencies_hz());
        assert_eq!(fa.len(), fb.len());
        for j in 0..fa.len() {
            if a.labels[j] != ModeLabel::Rigid {
                *w = w.max((fa[j] / fb[j] - 1.0).abs());
            }
        }
    }
    assert!(worst[0] < 1e-8 && worst[1] < 1e-8, "{worst:?}");
    record("7", "normal modes m-kg-s vs mm-t-s (rel.)", worst[0]);
    record("7", "Craig–Bampton m-kg-s vs mm-t-s (rel.)", worst[1]);
}

/// A near-rigid insert (the middle quarter of the block 1e10 times stiffer): the engine's
/// residual and orthonormality checks pass (the ΦᵀKΦ check at its rounding floor), the six
/// rigid modes are still found, and the frequencies match the rigid-insert limit extrapolated
/// from contrasts 1e6 and 1e8 (f(c) = f∞ + a/c). The sparse iterative path (a finer block) meets
/// a dense reference at contrast 1e4. At 1e12 the command line refuses the model, naming both
/// materials.
#[test]
fn row07_stiffness_contrast_meets_the_engine_bounds() {
    let run = |contrast: f64| {
        let (model, k, m) = system(&insert_block(contrast));
        let x0 = set_dofs(&model, "X0");
        let nm = normal_modes(&k, &m, ModeCount::Count(12), &[], &eig()).unwrap();
        let cb = craig_bampton(&k, &m, &x0, ModeCount::Count(6), &eig()).unwrap();
        (nm, cb)
    };
    let (n6, c6) = run(1e6);
    let (n8, c8) = run(1e8);
    let limit = |a: &[f64], b: &[f64]| -> Vec<f64> {
        a.iter()
            .zip(b)
            .map(|(x6, x8)| x8 + (x8 - x6) / 99.0)
            .collect()
    };
    let fn_inf = limit(&n6.frequencies_hz(), &n8.frequencies_hz());
    let fc_inf = limit(&c6.frequencies_hz(), &c8.frequencies_hz());
    let (nm, cb) = run(1e10);
    let rigid = nm.labels.iter().filter(|l| **l == ModeLabel::Rigid).count();
    assert_eq!(rigid, 6);
    // the engine's residual bound: 1e-8, or the rounding floor of computing Kφ itself,
    // 1e3·ε·‖|K||φ|‖/‖Kφ‖ (recomputed here from the dense matrices)
    let (_, k10, _) = system(&insert_block(1e10));
    let kd = dense(&k10);
    let kabs = Mat::from_fn(kd.nrows(), kd.ncols(), |i, j| kd[(i, j)].abs());
    let mut worst_ratio = 0.0f64;
    let mut res = 0.0f64;
    for j in 6..nm.len() {
        let phi = nm.phi.col(j);
        let kphi = &kd * phi;
        let aphi = &kabs * Mat::from_fn(phi.nrows(), 1, |i, _| phi[i].abs());
        let floor = 1e3 * f64::EPSILON * aphi.norm_l2() / kphi.norm_l2();
        let r = nm.diagnostics.residuals[j];
        worst_ratio = worst_ratio.max(r / floor.max(1e-8));
        res = res.max(r);
    }
    assert!(
        worst_ratio <= 1.0,
        "residual above the rounding floor: {worst_ratio}"
    );
    let dev = |f: &[f64], r: &[f64], from: usize| {
        (from..f.len())
            .map(|j| (f[j] / r[j] - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let dn = dev(&nm.frequencies_hz(), &fn_inf, 6);
    let dc = dev(&cb.frequencies_hz(), &fc_inf, 6);
    assert!(dn < 2e-4 && dc < 2e-4, "normal {dn:e}, CB {dc:e}");
    record(
        "7",
        "contrast 1e10 (dense path): normal modes vs rigid-insert limit (rel.)",
        dn,
    );
    record(
        "7",
        "contrast 1e10 (dense path): CB vs rigid-insert limit (rel.)",
        dc,
    );
    record(
        "7",
        "contrast 1e10 (dense path): max flexible residual",
        res,
    );
    record(
        "7",
        "contrast 1e10 (dense path): max residual / its rounding floor",
        worst_ratio,
    );

    let mut big = block([12, 3, 3], [0.4, 0.05, 0.05]);
    big.materials.push(insert_block(1e4).materials[1].clone());
    big.properties.push(insert_block(1e4).properties[1].clone());
    for e in 0..big.elements.len() {
        let xc = big.elements[e]
            .nodes
            .iter()
            .map(|&n| big.nodes[n].x[0])
            .sum::<f64>()
            / 8.0;
        if xc > 0.15 && xc < 0.25 {
            big.elements[e].property = Some(1);
        }
    }
    let (_, k, m) = system(&big);
    let s = normal_modes(&k, &m, ModeCount::Count(12), &[], &eig()).unwrap();
    let (vals, _) = dense_reference(&k, &m);
    let d = (6..12)
        .map(|j| (s.omega2[j] / vals[j] - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(d < 1e-8, "sparse path, contrast 1e4: {d:e}");
    record(
        "7",
        "contrast 1e4 (sparse path, 1872 dofs): ω² vs dense reference (rel.)",
        d,
    );

    let dir = TempDir::new("row07");
    let inp = dir.write_inp("insert.inp", &insert_block(1e12));
    let err = fail_run(&dir, &[&inp, "--interface", "X0", "--units", "si"], &[]);
    assert_contains(
        &err,
        &["stiffness contrast 1.0e12", "material 2 'INSERT'", "RBE2"],
    );
}

// ---------------------------------------------------------------------------------------------
// Row 8 — reference conditions that under- or over-constrain.

/// Three corner nodes as interface; reference conditions 1:123 leave rotations free, 1:123 +
/// 2:123 + 3:123 repeat three rigid motions. Normal modes and improved CB methods 1 and 2 all
/// stop with the free motions or the redundant dofs named; 1:123, 2:23, 3:3 is determinate and
/// builds with both methods to the same frequencies.
#[test]
fn row08_reference_conditions_under_and_over_constrained() {
    let dir = TempDir::new("row08");
    let model = block([6, 2, 2], [0.3, 0.05, 0.05]);
    let ids = corner_ids(&model);
    let inp = dir.write_inp("one.inp", &model);
    let iface: Vec<String> = ids.iter().map(|i| i.to_string()).collect();
    let refs = |spec: &[(usize, &str)]| -> Vec<(u64, flexbody::model::DofMask)> {
        spec.iter()
            .map(|&(c, d)| (ids[c], flexbody::model::DofMask::from_digits(d).unwrap()))
            .collect()
    };
    let under = refs(&[(0, "123")]);
    let over = refs(&[(0, "123"), (1, "123"), (2, "123")]);
    let exact = refs(&[(0, "123"), (1, "23"), (2, "3")]);
    for (method, rm) in [
        (flexbody::build::BuildMethod::Normal, 1),
        (flexbody::build::BuildMethod::CraigBampton, 1),
        (flexbody::build::BuildMethod::CraigBampton, 2),
    ] {
        let mut s = build_spec(&inp, method, &iface);
        s.reference_method = rm;
        s.modes = Some(6);
        s.reference_conditions = under.clone();
        let e = flexbody::build::build(&s, &mut |_| {})
            .unwrap_err()
            .to_string();
        assert_contains(&e, &["do not remove all rigid motion", "rotation about"]);
        s.reference_conditions = over.clone();
        let e = flexbody::build::build(&s, &mut |_| {})
            .unwrap_err()
            .to_string();
        assert_contains(&e, &["over-constrain", &format!("node {} dof 1", ids[1])]);
    }
    let mut freqs = vec![];
    for rm in [1, 2] {
        let mut s = build_spec(&inp, flexbody::build::BuildMethod::CraigBampton, &iface);
        s.reference_method = rm;
        s.modes = Some(6);
        s.reference_conditions = exact.clone();
        let out = flexbody::build::build(&s, &mut |_| {}).unwrap();
        freqs.push(out.body.modes.frequency_hz.clone());
    }
    let d = freqs[0]
        .iter()
        .zip(&freqs[1])
        .filter(|(a, _)| **a > 1.0)
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(d < 1e-8, "methods 1 and 2 differ by {d:e}");
    record(
        "8",
        "determinate reference: improved CB method 1 vs 2 (rel.)",
        d,
    );
    let err = fail_run(
        &dir,
        &[
            &inp,
            "--interface",
            &iface.join(","),
            "--reference-conditions",
            &format!("{}:123", ids[0]),
            "--units",
            "si",
        ],
        &[],
    );
    assert_contains(&err, &["do not remove all rigid motion"]);
}

// ---------------------------------------------------------------------------------------------
// Row 9 — mode requests the problem cannot meet.

/// More fixed-interface modes than interior dofs, zero normal modes, more normal modes than
/// dofs, and a cutoff below the first flexible mode: errors that say what to do. Craig–Bampton
/// with a cutoff below its first fixed-interface mode is a Guyan reduction, noted.
#[test]
fn row09_impossible_mode_requests_are_clear_errors() {
    let (model, k, m) = system(&block([4, 1, 1], [0.2, 0.05, 0.05]));
    let x0 = set_dofs(&model, "X0");
    let ni = k.nrows() - x0.len();
    let e = craig_bampton(&k, &m, &x0, ModeCount::Count(ni + 1), &eig()).unwrap_err();
    assert_contains(
        &e.to_string(),
        &[
            &format!("{} modes requested", ni + 1),
            &format!("only {ni} dofs"),
            "interior",
        ],
    );
    let e = normal_modes(&k, &m, ModeCount::Count(0), &[], &eig()).unwrap_err();
    assert_contains(&e.to_string(), &["0 modes requested"]);
    let e = normal_modes(&k, &m, ModeCount::Count(k.nrows() + 1), &[], &eig()).unwrap_err();
    assert_contains(&e.to_string(), &["modes requested", "only"]);
    let e = normal_modes(&k, &m, ModeCount::BelowHz(1.0), &[], &eig()).unwrap_err();
    assert_contains(
        &e.to_string(),
        &[
            "no flexible mode below the cutoff 1.000000 Hz",
            "first one is at",
        ],
    );
    let fa = unit_loads(k.nrows(), &[0]).unwrap();
    let e = craig_chang(&k, &m, &fa, ModeCount::BelowHz(1.0), &eig()).unwrap_err();
    assert_contains(&e.to_string(), &["no flexible mode below the cutoff"]);
    let cb = craig_bampton(&k, &m, &x0, ModeCount::BelowHz(1.0), &eig()).unwrap();
    assert_eq!(cb.len(), x0.len());
    assert!(cb.diagnostics.notes.iter().any(|n| n.contains("Guyan")));
    let dir = TempDir::new("row09");
    let inp = dir.write_inp("b.inp", &block([4, 1, 1], [0.2, 0.05, 0.05]));
    let err = fail_run(
        &dir,
        &[&inp, "--method", "normal", "--modes", "0", "--units", "si"],
        &[],
    );
    assert_contains(&err, &["0 modes requested"]);
    let err = fail_run(
        &dir,
        &[&inp, "--method", "normal", "--fmax", "0.1", "--units", "si"],
        &[],
    );
    assert_contains(&err, &["no flexible mode below the cutoff", "raise --fmax"]);
    let err = fail_run(
        &dir,
        &[
            &inp,
            "--interface",
            "X0",
            "--modes",
            "100000",
            "--units",
            "si",
        ],
        &[],
    );
    assert_contains(&err, &["100000 modes requested", "interior"]);
}

// ---------------------------------------------------------------------------------------------
// Row 10 — distorted, inverted and zero-volume elements; bad material constants.

/// Each bad element or material is an `FeError::Element` naming the element id (and the
/// material id and name for constants).
#[test]
fn row10_bad_elements_and_materials_name_the_entity() {
    let base = block([2, 1, 1], [0.1, 0.05, 0.05]);
    let el = |m: &flexbody::model::Model| assemble(m, &AssemblySpec::default()).unwrap_err();
    // inverted: mirror node order of element 2
    let mut inv = base.clone();
    inv.elements[1].nodes.swap(1, 3);
    inv.elements[1].nodes.swap(5, 7);
    let e = el(&inv);
    assert!(
        matches!(
            &e,
            FeError::Element {
                id: 2,
                err: flexbody::fe::elements::ElementError::NonPositiveJacobian { .. },
                ..
            }
        ),
        "{e}"
    );
    // distorted: one node of element 1 pulled through the opposite face
    let mut dist = base.clone();
    let n = dist.elements[0].nodes[6];
    dist.nodes[n].x[0] = -0.2;
    let e = el(&dist);
    assert!(
        matches!(
            &e,
            FeError::Element {
                err: flexbody::fe::elements::ElementError::NonPositiveJacobian { .. },
                ..
            }
        ),
        "{e}"
    );
    // zero volume: flatten element 2 (its x-extent collapsed onto x = 0.05)
    let mut flat = base.clone();
    for &n in &flat.elements[1].nodes.clone() {
        flat.nodes[n].x[0] = 0.05;
    }
    let e = el(&flat);
    assert!(
        matches!(
            &e,
            FeError::Element {
                err: flexbody::fe::elements::ElementError::NonPositiveJacobian { .. },
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("element "), "{e}");
    for (what, f) in [
        (
            "nu = 0.5",
            Box::new(|m: &mut flexbody::model::Material| m.nu = 0.5) as Box<dyn Fn(&mut _)>,
        ),
        (
            "nu = 0.6",
            Box::new(|m: &mut flexbody::model::Material| m.nu = 0.6),
        ),
        (
            "E = 0",
            Box::new(|m: &mut flexbody::model::Material| m.e = 0.0),
        ),
        (
            "E < 0",
            Box::new(|m: &mut flexbody::model::Material| m.e = -1e9),
        ),
        (
            "rho < 0",
            Box::new(|m: &mut flexbody::model::Material| m.rho = -1.0),
        ),
    ] {
        let mut bad = base.clone();
        f(&mut bad.materials[0]);
        let e = el(&bad);
        assert!(
            matches!(
                &e,
                FeError::Element {
                    id: 1,
                    err: flexbody::fe::elements::ElementError::BadConstants(_),
                    ..
                }
            ),
            "{what}: {e}"
        );
        assert_contains(&e.to_string(), &["element 1", "material 1 'STEEL'"]);
    }
}

/// ρ = 0 for a whole part: the command line names the part and the material and writes nothing.
#[test]
fn row10_cli_massless_part_names_the_material() {
    let dir = TempDir::new("row10");
    let mut model = block([4, 1, 1], [0.2, 0.05, 0.05]);
    model.materials[0].rho = 0.0;
    let inp = dir.write_inp("massless.inp", &model);
    let err = fail_run(&dir, &[&inp, "--interface", "X0", "--units", "si"], &[]);
    assert_contains(&err, &["has no mass", "ρ = 0 in material 1 'STEEL'"]);
    let err = fail_run(&dir, &[&inp, "--method", "normal", "--units", "si"], &[]);
    assert_contains(&err, &["has no mass"]);
}

// ---------------------------------------------------------------------------------------------
// Row 11 — memory.

/// The factor's memory is estimated from the symbolic analysis (≥ 8 bytes per non-zero of L);
/// above the limit the build stops before factoring with the figures, and writes nothing.
#[test]
fn row11_factor_memory_is_estimated_and_limited() {
    use flexbody::solve::cholesky::{analyze, factor_memory, parse_bytes};
    assert_eq!(parse_bytes("4096"), Some(4096));
    assert_eq!(parse_bytes("64K"), Some(65536));
    assert_eq!(parse_bytes("1.5G"), Some(3 << 29));
    assert_eq!(parse_bytes("lots"), None);
    let (_, k, _) = system(&block([6, 2, 2], [0.3, 0.05, 0.05]));
    let (sym, stats) = analyze(k.as_ref(), Some(3)).unwrap();
    let bytes = factor_memory(&sym, faer::Par::Seq);
    assert!(bytes >= 8 * stats.nnz_l, "{bytes} < 8·{}", stats.nnz_l);
    record(
        "11",
        "estimated factor bytes / (8·nnz(L)), 6x2x2 hex8 block",
        bytes as f64 / (8 * stats.nnz_l) as f64,
    );
    let dir = TempDir::new("row11");
    let inp = dir.write_inp("b.inp", &block([6, 2, 2], [0.3, 0.05, 0.05]));
    let err = fail_run(
        &dir,
        &[&inp, "--interface", "X0", "--units", "si"],
        &[("FLEXBODY_MAX_MEMORY", "16K")],
    );
    assert_contains(
        &err,
        &[
            "needs about",
            "16.0 KiB are available (FLEXBODY_MAX_MEMORY)",
            "stopped before factoring",
        ],
    );
    let out = dir.path("ok.flexbody");
    let ok = run_cli(
        &[
            "build",
            &inp,
            "--interface",
            "X0",
            "--units",
            "si",
            "-q",
            "-o",
            &out,
        ],
        &[("FLEXBODY_MAX_MEMORY", "1G")],
    );
    assert_eq!(ok.0, Some(0), "{}", ok.2);
}
