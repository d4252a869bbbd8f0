//! Stability rows 7–11 (docs/stability.md): ill-conditioning, reference conditions, mode
//! requests, bad elements and materials, memory.

use faer::Mat;
use flexbody::fe::{assemble, AssemblySpec, FeError};
use flexbody::reduce::craig_bampton::craig_bampton;
use flexbody::reduce::craig_chang::{craig_chang, unit_loads};
use flexbody::reduce::normal::normal_modes;
use flexbody::reduce::select::ModeCount;
use flexbody::reduce::ModeLabel;

use super::support::*;

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

    // The sparse iterative path (1872 dofs) against a dense reference: exact to 1e-8 at 1e4;
    // at 1e8 (the build's limit) the residual needs the subspace-iteration refinement of
    // `lowest_modes_factored` and the agreement is what rounding leaves.
    for (contrast, bound) in [(1e4, 1e-8), (1e8, 1e-4)] {
        let (_, k, m) = system(&insert_block_of([12, 3, 3], contrast));
        let s = normal_modes(&k, &m, ModeCount::Count(12), &[], &eig()).unwrap();
        let (vals, _) = dense_reference(&k, &m);
        let d = (6..12)
            .map(|j| (s.omega2[j] / vals[j] - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(d < bound, "sparse path, contrast {contrast:e}: {d:e}");
        record(
            "7",
            &format!(
                "contrast {contrast:.0e} (sparse path, 1872 dofs): ω² vs dense reference (rel.)"
            ),
            d,
        );
    }

    let dir = TempDir::new("row07");
    let inp = dir.write_inp("insert.inp", &insert_block(1e10));
    let err = fail_run(&dir, &[&inp, "--interface", "X0", "--units", "si"], &[]);
    assert_contains(
        &err,
        &["stiffness contrast 1.0e10", "material 2 'INSERT'", "RBE2"],
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

/// The library backstop of row 8: with reference dofs that leave rigid motion free, normal
/// modes and both improved CB methods return `ReduceError::Rigid` (zero modes remain) instead of
/// a set with zero-frequency modes and no body frame.
#[test]
fn row08_library_reference_leaving_zero_modes_is_an_error() {
    let (model, k, m) = system(&block([6, 2, 2], [0.3, 0.05, 0.05]));
    let by_id = model.node_index_by_id();
    let corners: Vec<usize> = corner_ids(&model).iter().map(|id| by_id[id]).collect();
    let iface = node_dofs(&model, &corners, 3);
    let reference = node_dofs(&model, &corners[..1], 3);
    let check = |e: flexbody::reduce::ReduceError| {
        let t = e.to_string();
        assert!(matches!(e, flexbody::reduce::ReduceError::Rigid(_)), "{t}");
        assert_contains(
            &t,
            &["3 reference dofs held, 3 zero-frequency mode(s) remain"],
        );
    };
    check(normal_modes(&k, &m, ModeCount::Count(8), &reference, &eig()).unwrap_err());
    use flexbody::reduce::reference::{improved_cb_method1, improved_cb_method2};
    check(
        improved_cb_method1(&k, &m, &iface, &reference, ModeCount::Count(4), &eig()).unwrap_err(),
    );
    check(
        improved_cb_method2(&k, &m, &iface, &reference, ModeCount::Count(4), &eig()).unwrap_err(),
    );
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

/// A deck with many bad elements names the first of them, every time: the elements are computed
/// in parallel, and the error was whichever a thread met first. Here element 2000 of 4000 and all
/// past it have a bad material: a second thread starts in the bad half at once, while the first
/// works through 1999 good elements.
#[test]
fn row10_many_bad_elements_name_the_first_every_time() {
    use flexbody::model::{Material, Property, Section};
    let mut model = block([40, 10, 10], [0.4, 0.1, 0.1]);
    let mut bad = Material::steel();
    (bad.id, bad.name, bad.e) = (2, "BAD".into(), -1e9);
    model.materials.push(bad);
    model.properties.push(Property {
        id: 2,
        name: "BAD".into(),
        material: 1,
        section: Section::Solid,
    });
    let n = model.elements.len();
    for e in n / 2 - 1..n {
        model.elements[e].property = Some(1);
    }
    let first = model.elements[n / 2 - 1].id;
    for run in 0..6 {
        let e = assemble(&model, &AssemblySpec::default()).unwrap_err();
        assert!(
            matches!(&e, FeError::Element { id, .. } if *id == first),
            "run {run}: {e} (the first bad element is {first})"
        );
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
    // The same limit from the command line.
    let err = fail_run(
        &dir,
        &[
            &inp,
            "--interface",
            "X0",
            "--units",
            "si",
            "--max-memory",
            "16K",
        ],
        &[],
    );
    assert_contains(
        &err,
        &["16.0 KiB are available", "stopped before factoring"],
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

// ---------------------------------------------------------------------------------------------
// Row 7 (mixed precision) — an f32 factor of K_ii under stiffness contrast.

/// `--precision mixed` on the sparse Craig–Bampton path of the insert block (3087 dofs) at
/// contrasts 1 … 1e8: up to 1e2 the f32 factor with refined solves gives the f64 build's
/// fixed-interface frequencies and constraint modes (to 1e-9); from 1e3 K_ii is too
/// ill-conditioned for f32 (a pivot keeps < 1e-5 of its diagonal, or the f32 factorization meets a
/// non-positive one) and the build says so and factors in f64 — never an f32-accurate answer.
#[test]
fn row07_mixed_precision_matches_f64_or_falls_back_under_contrast() {
    use flexbody::reduce::craig_bampton::craig_bampton_basis;
    use flexbody::solve::Precision;
    for contrast in [1.0f64, 1e2, 1e3, 1e4, 1e8] {
        let (model, k, m) = system(&insert_block_of([20, 6, 6], contrast));
        let x0 = set_dofs(&model, "X0");
        let run = |precision| {
            let spec = flexbody::solve::EigenSpec { precision, ..eig() };
            craig_bampton_basis(&k, &m, &x0, ModeCount::Count(10), &spec).unwrap()
        };
        let (f64_run, mixed) = (run(Precision::F64), run(Precision::Mixed));
        let d = f64_run
            .fixed_omega2
            .iter()
            .zip(&mixed.fixed_omega2)
            .map(|(a, b)| (a - b).abs() / a)
            .fold(0.0, f64::max);
        let x = |b: &flexbody::reduce::craig_bampton::CbBasis| {
            b.t.as_ref().subcols(0, x0.len()).to_owned()
        };
        let dx = (x(&f64_run) - x(&mixed)).norm_max() / x(&f64_run).norm_max();
        let used = mixed
            .notes
            .iter()
            .any(|n| n.contains("factored in mixed precision"));
        let abandoned = mixed.notes.iter().any(|n| n.contains("abandoned"));
        println!(
            "contrast {contrast:.0e}: mixed {} ; ω² vs f64 {d:.2e}, constraint modes {dx:.2e}; notes {:?}",
            if used { "used" } else { "abandoned" },
            mixed.notes
        );
        assert!(used != abandoned, "{:?}", mixed.notes);
        assert_eq!(
            used,
            contrast <= 1e2,
            "contrast {contrast:e}: {:?}",
            mixed.notes
        );
        assert!(d < 1e-9, "contrast {contrast:e}: fixed-interface ω² {d:e}");
        assert!(dx < 1e-9, "contrast {contrast:e}: constraint modes {dx:e}");
        record(
            "7",
            &format!(
                "contrast {contrast:.0e} (CB, 3087 dofs, --precision mixed): ω² vs f64 (rel.)"
            ),
            d,
        );
    }
}
