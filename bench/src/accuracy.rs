//! Accuracy suite: every reduction method × several mode counts on one model (default: the
//! bundled tet10 conrod with RBE2 spiders on both bores = 2 interface nodes, 12 dofs), through
//! the library API on the same assembled, eliminated K and M:
//!
//! * wall time of the reduction call;
//! * frequency error: max_j |f_j − f_j,FE| / f_j,FE over the full model's flexible modes up to
//!   fmax (the 10th flexible free-free frequency); a mode the reduced model lacks counts 1.
//!   Free bodies (normal, CB, Craig–Chang, Dietz) against the free-free spectrum; the improved
//!   CB methods (reference conditions = the big-end interface node's 6 dofs) against the spectrum
//!   with those dofs held;
//! * static error at the interfaces: with the reference dofs held, the compliance G = K_c⁻¹ at
//!   the small-end interface node (6 unit loads) against Φ_c(Φ_cᵀKΦ_c)⁻¹Φ_cᵀ on the basis
//!   restricted to u_ref = 0; reported as max_ij |ΔG_ij| / √(G_ii G_jj) (unit-free);
//! * the mode set's checked orthonormality and stiffness-diagonality.
//!
//! Result: `bench/results/accuracy_<model>.json`.

use std::path::Path;
use std::time::Instant;

use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec};
use flexbody::import::{read_model, ImportOptions};
use flexbody::interface::{resolve_interfaces, SpiderKind};
use flexbody::reduce::select::ModeCount;
use flexbody::reduce::{craig_bampton, craig_chang, dietz, normal, reference, ModeSet};
use flexbody::solve::{dense, sparse_ops, EigenSpec, Mat, SparseColMat, SparseLlt};
use serde_json::{json, Value};

use crate::{loadavg, num, write_result, Res};

type Sparse = SparseColMat<usize, f64>;

/// Fixed-interface / flexible mode counts of the sweep.
const COUNTS: [usize; 6] = [4, 8, 12, 16, 24, 32];
/// Number of flexible modes the frequency error covers.
const FLEX_COVERED: usize = 10;

fn hz(w2: f64) -> f64 {
    w2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// Flexible frequencies (Hz) of a set: ω² above 1e-6 of the largest.
fn flexible_hz(omega2: &[f64]) -> Vec<f64> {
    let top = omega2.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    omega2
        .iter()
        .filter(|&&w| w > 1e-6 * top)
        .map(|&w| hz(w))
        .collect()
}

fn freq_error(reduced: &[f64], reference: &[f64]) -> f64 {
    reference
        .iter()
        .enumerate()
        .map(|(j, &f)| reduced.get(j).map_or(1.0, |&r| (r - f).abs() / f))
        .fold(0.0, f64::max)
}

fn complement(of: &[usize], n: usize) -> Vec<usize> {
    let mut mark = vec![false; n];
    for &d in of {
        mark[d] = true;
    }
    (0..n).filter(|&i| !mark[i]).collect()
}

/// G = K_c⁻¹ at `probe` (K_c: `held` dofs removed), 6 × 6.
fn full_compliance(k: &Sparse, held: &[usize], probe: &[usize]) -> Res<Mat<f64>> {
    let free = complement(held, k.nrows());
    let mut pos = vec![usize::MAX; k.nrows()];
    for (i, &d) in free.iter().enumerate() {
        pos[d] = i;
    }
    let kc = sparse_ops::submatrix(k.as_ref(), &free, &free).map_err(|e| e.to_string())?;
    let llt = SparseLlt::factor(kc.as_ref(), None, flexbody::solve::faer::Par::Seq)
        .map_err(|e| e.to_string())?;
    let mut rhs = Mat::<f64>::zeros(free.len(), probe.len());
    for (c, &d) in probe.iter().enumerate() {
        rhs[(pos[d], c)] = 1.0;
    }
    llt.solve_in_place(rhs.as_mut());
    Ok(Mat::from_fn(probe.len(), probe.len(), |i, j| {
        rhs[(pos[probe[i]], j)]
    }))
}

/// The same compliance from the basis Φ restricted to Φ[held, :] y = 0.
fn reduced_compliance(
    k: &Sparse,
    phi: &Mat<f64>,
    held: &[usize],
    probe: &[usize],
) -> Res<Mat<f64>> {
    let m = phi.ncols();
    let c = Mat::from_fn(held.len(), m, |i, j| phi[(held[i], j)]);
    let ctc = c.transpose() * &c;
    let (s, u) = dense::eigh(ctc.as_ref()).map_err(|e| e.to_string())?;
    let top = s.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let null: Vec<usize> = (0..m)
        .filter(|&i| s[i] <= 1e-12 * top.max(1e-300))
        .collect();
    let nb = Mat::from_fn(m, null.len(), |i, j| u[(i, null[j])]);
    let phic = phi * &nb;
    let kphic = sparse_ops::spmm(k.as_ref(), phic.as_ref());
    let kr = phic.transpose() * &kphic;
    let l = dense::cholesky(kr.as_ref())
        .ok_or("reduced constrained stiffness not positive definite")?;
    // G_red = P (L Lᵀ)⁻¹ Pᵀ with P = Φ_c[probe, :]: solve L Z = Pᵀ, G = Zᵀ Z
    let p = Mat::from_fn(probe.len(), phic.ncols(), |i, j| phic[(probe[i], j)]);
    let mut z = p.transpose().to_owned();
    flexbody::solve::faer::linalg::triangular_solve::solve_lower_triangular_in_place(
        l.as_ref(),
        z.as_mut(),
        flexbody::solve::faer::Par::Seq,
    );
    Ok(z.transpose() * &z)
}

fn static_error(g: &Mat<f64>, gr: &Mat<f64>) -> f64 {
    let mut e = 0.0f64;
    for i in 0..g.nrows() {
        for j in 0..g.ncols() {
            let s = (g[(i, i)] * g[(j, j)]).sqrt();
            e = e.max((gr[(i, j)] - g[(i, j)]).abs() / s);
        }
    }
    e
}

/// Runs the suite on `model` (default: the bundled conrod).
pub fn run(model_path: Option<&str>) -> Res<Value> {
    let default =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/models/conrod/conrod.inp");
    let path = model_path.map_or(default, |p| Path::new(p).to_path_buf());
    let mut model = read_model(&path, &ImportOptions::default()).map_err(|e| e.to_string())?;
    let itf = resolve_interfaces(
        &mut model,
        &["BIG_END".into(), "SMALL_END".into()],
        SpiderKind::Rbe2,
    )
    .map_err(|e| e.to_string())?;
    let asm = assemble(&model, &AssemblySpec::default()).map_err(|e| e.to_string())?;
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec::default(),
    )
    .map_err(|e| e.to_string())?;
    let mut pos = vec![usize::MAX; asm.dofs.n_dofs];
    for (i, &p) in red.retained.iter().enumerate() {
        pos[p] = i;
    }
    let node_dofs =
        |node: usize| -> Vec<usize> { (0..6).map(|c| pos[asm.dofs.first[node] + c]).collect() };
    let big = node_dofs(itf[0].nodes[0]);
    let small = node_dofs(itf[1].nodes[0]);
    let interface: Vec<usize> = big.iter().chain(&small).copied().collect();
    if interface.contains(&usize::MAX) {
        return Err("interface dof not independent".into());
    }
    let (k, m) = (&red.k, &red.m);
    let n = k.nrows();
    let eig = EigenSpec {
        dofs_per_node: Some(3),
        ..Default::default()
    };
    // full FE references
    let t = Instant::now();
    let ff = normal::normal_modes(k, m, ModeCount::Count(6 + FLEX_COVERED + 6), &[], &eig)
        .map_err(|e| e.to_string())?;
    let ref_free: Vec<f64> = flexible_hz(&ff.omega2)[..FLEX_COVERED].to_vec();
    let fmax = ref_free[FLEX_COVERED - 1];
    let held = normal::normal_modes(k, m, ModeCount::Count(FLEX_COVERED + 8), &big, &eig)
        .map_err(|e| e.to_string())?;
    let ref_held: Vec<f64> = flexible_hz(&held.omega2)
        .into_iter()
        .filter(|&f| f <= fmax)
        .collect();
    let g = full_compliance(k, &big, &small)?;
    let t_ref = t.elapsed().as_secs_f64();
    let fa = craig_chang::unit_loads(n, &interface).map_err(|e| e.to_string())?;
    type Runner<'a> = Box<dyn Fn(usize) -> Result<ModeSet, flexbody::reduce::ReduceError> + 'a>;
    let methods: Vec<(&str, bool, Runner)> = vec![
        (
            "normal modes",
            false,
            Box::new(|c| normal::normal_modes(k, m, ModeCount::Count(c + 6), &[], &eig)),
        ),
        (
            "Craig-Bampton",
            false,
            Box::new(|c| craig_bampton::craig_bampton(k, m, &interface, ModeCount::Count(c), &eig)),
        ),
        (
            "Craig-Chang",
            false,
            Box::new(|c| craig_chang::craig_chang(k, m, &fa, ModeCount::Count(c + 6), &eig)),
        ),
        (
            "Dietz",
            false,
            Box::new(|c| dietz::dietz(k, m, &fa, ModeCount::Count(c + 6), None, &eig)),
        ),
        (
            "improved CB 1",
            true,
            Box::new(|c| {
                reference::improved_cb_method1(k, m, &interface, &big, ModeCount::Count(c), &eig)
            }),
        ),
        (
            "improved CB 2",
            true,
            Box::new(|c| {
                reference::improved_cb_method2(k, m, &interface, &big, ModeCount::Count(c), &eig)
            }),
        ),
    ];
    let mut series = Vec::new();
    for (name, with_reference, f) in &methods {
        let mut points = Vec::new();
        for &c in &COUNTS {
            let t = Instant::now();
            let set = match f(c) {
                Ok(s) => s,
                Err(e) => {
                    points.push(json!({"modes": c, "error": e.to_string()}));
                    continue;
                }
            };
            let secs = t.elapsed().as_secs_f64();
            let reference = if *with_reference {
                &ref_held
            } else {
                &ref_free
            };
            let fe = freq_error(&flexible_hz(&set.omega2), reference);
            let se = reduced_compliance(k, &set.phi, &big, &small)
                .map(|gr| static_error(&g, &gr))
                .map_or(Value::Null, num);
            eprintln!("  {name} {c}: {secs:.2} s, freq err {fe:.2e}, static err {se}");
            points.push(json!({
                "modes": c,
                "basis_size": set.len(),
                "seconds": secs,
                "freq_error": num(fe),
                "static_error": se,
                "orthonormality": num(set.diagnostics.orthonormality),
                "stiffness_diag": num(set.diagnostics.stiffness_diag),
                "removed_dependent": set.diagnostics.removed.len(),
            }));
        }
        series.push(
            json!({"method": name, "reference_conditions": with_reference, "points": points}),
        );
    }
    let stem = path
        .file_stem()
        .map_or("model".into(), |s| s.to_string_lossy().to_string());
    let json = json!({
        "suite": "accuracy",
        "model": path
            .display()
            .to_string()
            .replace(concat!(env!("CARGO_MANIFEST_DIR"), "/../"), ""),
        "dofs": n,
        "interfaces": "RBE2 spiders on BIG_END and SMALL_END (12 dofs); reference conditions = the BIG_END node's 6 dofs",
        "mass": "lumped (the build default)",
        "fmax_hz": fmax,
        "reference_free_hz": ref_free,
        "reference_held_hz": ref_held,
        "reference_seconds": t_ref,
        "mode_counts": "flexible / fixed-interface modes; normal, Craig-Chang and Dietz get 6 rigid modes more",
        "series": series,
        "loadavg": loadavg(),
    });
    write_result(&format!("accuracy_{stem}.json"), &json)?;
    Ok(json)
}
