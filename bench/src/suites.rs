//! Speed suites against the peers, on identical inputs, in the same run:
//!
//! * `eigen NX NY NZ [--modes N]`: the tet10 block clamped at x = 0, consistent mass. We write
//!   K and M as Matrix Market; ours (`ours-eigen`, own process) and the peers (SciPy eigsh with
//!   SuperLU, ARPACK with CHOLMOD) read the same files and find the lowest N eigenpairs with a
//!   factorization at σ = 0; ccx solves the same mesh and clamp from a deck. Ratios ours/peer per
//!   phase (analyse+factor, eigen, total) and eigenvalue agreement.
//! * `cb NX NY NZ [--modes N]`: the whole Craig–Bampton build (generate, RBE2 spiders on both
//!   end faces = 2 interface nodes, assembly, elimination, CB with N fixed-interface modes,
//!   orthonormalization) against exudyn's HCB (RBE2 interfaces on the same end-face nodes, our
//!   assembled K, M) and ccx's frequency-only run of N modes with both end faces clamped, and
//!   against one CHOLMOD factorization (analyse + factor) of the same K_ii in the same run
//!   (`--repeat R` alternates ours and CHOLMOD R times).
//!
//! * `eigen ... --modes 300 --baseline 30 --inertia`: many modes — ours also with the baseline
//!   count in the same run (the ratio of the eigen phases), and Sylvester's inertia count of
//!   K − σM at σ just above the highest eigenvalue found, against how many eigenvalues ours and
//!   ARPACK returned below σ.
//!
//! Results: `bench/results/eigen_<dofs>.json` (30 modes; `eigen_<dofs>_<N>modes.json`
//! otherwise), `bench/results/cb_<dofs>.json`.

use std::time::Instant;

use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec, MassKind};
use flexbody::interface::{resolve_interfaces, SpiderKind};
use flexbody::model::DofMask;
use flexbody::reduce::craig_bampton::{
    craig_bampton_basis, craig_bampton_basis_owned, orthonormalize_basis,
};
use flexbody::reduce::select::ModeCount;
use flexbody::solve::{lowest_modes_iterative, EigenSpec, SparseColMat, Triplet};
use serde_json::{json, Value};

use crate::{
    data_dir, loadavg, max_rel_diff, num, peak_rss_mb, run_peer, run_self, tet10_block,
    write_ccx_deck, write_mtx, write_result, Res,
};

fn consistent() -> AssemblySpec {
    AssemblySpec {
        mass: MassKind::Consistent,
        ..Default::default()
    }
}

fn node_set(model: &flexbody::model::Model, name: &str) -> Res<Vec<usize>> {
    model
        .node_sets
        .get(name)
        .cloned()
        .ok_or_else(|| format!("generated block has no node set {name}"))
}

/// A symmetric Matrix Market file as a full (both triangles) sparse matrix.
pub(crate) fn read_full_mtx(p: &str) -> Res<SparseColMat<usize, f64>> {
    let s = flexbody::import::matrix_market::read_matrix(std::path::Path::new(p))
        .map_err(|e| e.to_string())?;
    let v: Vec<_> = s
        .full()
        .into_iter()
        .map(|(i, j, x)| Triplet::new(i, j, x))
        .collect();
    SparseColMat::try_new_from_triplets(s.n, s.n, &v).map_err(|e| format!("{p}: {e:?}"))
}

/// `ours-eigen K.mtx M.mtx MODES [BLOCK [TOL [BASIS]]]`: our solver on the files (prints one JSON
/// line); BLOCK, TOL and BASIS (largest Krylov basis) override the defaults (for tuning).
pub fn ours_eigen(
    kp: &str,
    mp: &str,
    modes: usize,
    block: Option<usize>,
    tol: Option<f64>,
    max_basis: Option<usize>,
) -> Res<Value> {
    let t = Instant::now();
    let (k, m) = (read_full_mtx(kp)?, read_full_mtx(mp)?);
    let t_read = t.elapsed().as_secs_f64();
    let t0 = Instant::now();
    let spec = EigenSpec {
        count: modes,
        shift: Some(0.0),
        dofs_per_node: Some(3),
        block,
        max_basis,
        tol: tol.unwrap_or(EigenSpec::default().tol),
        par: threads(),
        precision: Default::default(),
        upper: None,
        verify_band: false,
        engine: None,
        method: flexbody::solve::EigenMethod::Lanczos,
    };
    let s = lowest_modes_iterative(&k, &m, &spec).map_err(|e| e.to_string())?;
    let total = t0.elapsed().as_secs_f64();
    let f = s.info.factor.clone();
    Ok(json!({
        "peer": "flexbody (faer supernodal LLT, METIS NodeND; block Krylov-Schur shift-invert)",
        "n": k.nrows(),
        "phases_s": {"read": t_read, "analyse_factor": s.info.seconds_factor,
                     "eigen": s.info.seconds_eigen, "total": total,
                     "eigen_solves": s.info.seconds_solve,
                     "eigen_orthogonalization": s.info.seconds_orth,
                     "eigen_restarts": s.info.seconds_restart},
        "gram_schmidt": gram_schmidt_json(&s.info.gram_schmidt),
        "solves": s.info.solves, "steps": s.info.steps, "restarts": s.info.restarts,
        "ritz_solves": s.info.ritz_solves,
        "block": spec.block.unwrap_or(modes.min(flexbody::solve::DEFAULT_BLOCK)),
        "max_basis": spec.max_basis.unwrap_or_else(|| flexbody::solve::default_basis(
            modes,
            spec.block.unwrap_or(modes.min(flexbody::solve::DEFAULT_BLOCK)),
        )),
        "tol": spec.tol,
        "nnz_l": f.as_ref().map(|f| f.nnz_l), "factor_flops": f.as_ref().map(|f| f.flops),
        "orthonormality": num(s.info.orthonormality),
        "max_residual": num(s.residuals.iter().copied().fold(0.0, f64::max)),
        "peak_rss_mb": peak_rss_mb(),
        "eigenvalues": s.eigenvalues,
        "threads": format!("faer {:?}", threads()),
        "loadavg": loadavg(),
    }))
}

/// The eigen phase's Gram–Schmidt tally as JSON (blocks, second-pass coefficients formed,
/// second-pass updates made).
fn gram_schmidt_json(t: &flexbody::solve::eigen::GsTally) -> Value {
    json!({"blocks": t.blocks, "measured": t.measured, "second_passes": t.second_passes})
}

/// `solve-kernel K.mtx [B ...]`: times the ordering, the symbolic and the numeric factorization of
/// K, then for blocks of B random columns (default 1 4 6 8 12 16) faer's multi-RHS solve against
/// ours (ms per solved vector, GFlop/s = 4·nnz(L)·B per block, largest relative difference) and
/// the product K·X; best of 5 each. A tuning tool: prints to stderr, JSON to stdout.
pub fn solve_kernel(kp: &str, blocks: &[usize]) -> Res<Value> {
    let k = read_full_mtx(kp)?;
    // faer's kernels under the same global parallelism as in the eigensolver
    let _par = flexbody::solve::ParGuard::new(threads());
    let t = Instant::now();
    let ord = flexbody::solve::ordering::nested_dissection(k.symbolic(), Some(3))
        .map_err(|e| e.to_string())?;
    let t_order = t.elapsed().as_secs_f64();
    drop(ord);
    let t = Instant::now();
    let (sym, stats) =
        flexbody::solve::cholesky::analyze(k.as_ref(), Some(3)).map_err(|e| e.to_string())?;
    let t_analyse = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let llt = flexbody::solve::SparseLlt::factor_with(sym, stats, k.as_ref(), threads())
        .map_err(|e| e.to_string())?;
    let t_factor = t.elapsed().as_secs_f64();
    eprintln!(
        "ordering {t_order:.2} s, analyse (ordering + symbolic) {t_analyse:.2} s, numeric {t_factor:.2} s, nnz(L) {}, flops {:.3e}",
        llt.stats.nnz_l, llt.stats.flops
    );
    let nnz_l = llt.stats.nnz_l as f64;
    // the same analysis factored in f32 (a mixed-precision factor), solved in f32 arithmetic
    let (sym32, stats32) =
        flexbody::solve::cholesky::analyze(k.as_ref(), Some(3)).map_err(|e| e.to_string())?;
    let t = Instant::now();
    let llt32 =
        flexbody::solve::SparseLlt::factor_mixed_with(sym32, stats32, k.as_ref(), threads())
            .map_err(|e| e.to_string())?;
    let t_factor32 = t.elapsed().as_secs_f64();
    eprintln!("f32 numeric factorization {t_factor32:.2} s");
    let blocks = if blocks.is_empty() {
        vec![1, 4, 6, 8, 12, 16]
    } else {
        blocks.to_vec()
    };
    let mut rows = Vec::new();
    for &b in &blocks {
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let rhs = flexbody::solve::eigen::random_block(k.nrows(), b, &mut seed);
        let time =
            |f: &dyn Fn(&mut flexbody::solve::Mat<f64>)| -> (f64, flexbody::solve::Mat<f64>) {
                let mut best = f64::INFINITY;
                let mut x = rhs.clone();
                for _ in 0..5 {
                    x = rhs.clone();
                    let t = Instant::now();
                    f(&mut x);
                    best = best.min(t.elapsed().as_secs_f64());
                }
                (best, x)
            };
        let (t_spmm, _) = time(&|x| {
            let y = flexbody::solve::sparse_ops::spmm(k.as_ref(), x.as_ref());
            x[(0, 0)] = y[(0, 0)];
        });
        let (t_faer, x_faer) = time(&|x| llt.solve_in_place_faer(x.as_mut()));
        let (t_ours, x_ours) = time(&|x| llt.solve_in_place(x.as_mut()));
        let (t_f32, x_f32) = time(&|x| llt32.solve_in_place(x.as_mut()));
        let diff = (&x_faer - &x_ours).norm_max() / x_faer.norm_max();
        let diff32 = (&x_f32 - &x_ours).norm_max() / x_ours.norm_max();
        let gf = |t: f64| 4.0 * nnz_l * b as f64 / t / 1e9;
        eprintln!(
            "b={b:2}: faer {:7.3} ms/vec {:5.2} GFlop/s | ours {:7.3} ms/vec {:5.2} GFlop/s | x{:.2} | diff {diff:.1e} | K·X {:.2} ms",
            1e3 * t_faer / b as f64,
            gf(t_faer),
            1e3 * t_ours / b as f64,
            gf(t_ours),
            t_faer / t_ours,
            1e3 * t_spmm
        );
        eprintln!(
            "      f32 factor, f32 arithmetic: {:7.3} ms/vec, {:.2}× ours f64 | one solve off by {diff32:.1e}",
            1e3 * t_f32 / b as f64,
            t_f32 / t_ours
        );
        rows.push(json!({"block": b, "faer_s": t_faer, "ours_s": t_ours,
            "faer_gflops": gf(t_faer), "ours_gflops": gf(t_ours), "max_rel_diff": diff,
            "spmm_s": t_spmm, "f32_s": t_f32, "f32_one_solve_error": diff32}));
    }
    Ok(
        json!({"n": k.nrows(), "nnz_l": llt.stats.nnz_l, "ordering_s": t_order,
        "analyse_s": t_analyse, "factor_s": t_factor, "factor_f32_s": t_factor32,
        "threads": format!("faer {:?}", threads()), "loadavg": loadavg(), "blocks": rows}),
    )
}

/// Threads of our solver: `FLEXBODY_THREADS` (default 1, `Par::Seq`; the peers get the same
/// count through `FLEXBODY_PEER_THREADS`).
pub fn threads() -> flexbody::solve::faer::Par {
    match std::env::var("FLEXBODY_THREADS")
        .ok()
        .and_then(|s| s.parse::<usize>().ok())
    {
        Some(t) if t > 1 => flexbody::solve::faer::Par::rayon(t),
        _ => flexbody::solve::faer::Par::Seq,
    }
}

fn ratios(ours: &Value, peer: &Value, modes: usize) -> Value {
    let mut r = serde_json::Map::new();
    for ph in ["analyse_factor", "eigen", "total"] {
        if let (Some(a), Some(b)) = (ours["phases_s"][ph].as_f64(), peer["phases_s"][ph].as_f64()) {
            r.insert(ph.into(), num(a / b));
        }
    }
    let ev = |v: &Value| -> Vec<f64> {
        v["eigenvalues"]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_f64).collect())
            .unwrap_or_default()
    };
    if let Some(d) = max_rel_diff(&ev(ours), &ev(peer), modes) {
        r.insert("eigenvalue_max_rel_diff".into(), num(d));
    }
    Value::Object(r)
}

/// `inertia K.mtx M.mtx SIGMA`: Sylvester's count of the eigenvalues of K x = λ M x below σ
/// (negative pivots of the LDLᵀ of K − σM, `flexbody::solve::inertia`), with its time.
pub fn inertia_count(kp: &str, mp: &str, sigma: f64) -> Res<Value> {
    let (k, m) = (read_full_mtx(kp)?, read_full_mtx(mp)?);
    let t = Instant::now();
    let count = flexbody::solve::inertia::count_below(&k, &m, sigma, None, threads())
        .map_err(|e| e.to_string())?;
    Ok(
        json!({"sigma": sigma, "count_below": count, "seconds": t.elapsed().as_secs_f64(),
              "peak_rss_mb": peak_rss_mb()}),
    )
}

/// Optional parts of the `eigen` suite for many-mode runs.
#[derive(Clone, Copy, Debug, Default)]
pub struct EigenExtras {
    /// Also run ours with this many modes in the same run (the many-mode ratio's baseline).
    pub baseline: Option<usize>,
    /// Count the eigenvalues below σ just above the highest one found (Sylvester's inertia) and
    /// compare with how many ours and ARPACK returned below it.
    pub inertia: bool,
}

/// The `eigen` suite's system: the generated block clamped at x = 0, assembled and eliminated,
/// with K and M written to `eigen_<dofs>/K.mtx` and `M.mtx` (the peers and our child processes
/// read them there).
pub(crate) struct EigenSystem {
    pub(crate) model: flexbody::model::Model,
    /// Nodes of the clamped face.
    pub(crate) fixed: Vec<usize>,
    pub(crate) dofs: usize,
    pub(crate) dir: std::path::PathBuf,
    pub(crate) kp: std::path::PathBuf,
    pub(crate) mp: std::path::PathBuf,
}

pub(crate) fn eigen_system(n: [usize; 3]) -> Res<EigenSystem> {
    let model = tet10_block(n);
    let fixed = node_set(&model, "X0")?;
    let asm = assemble(&model, &consistent()).map_err(|e| e.to_string())?;
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec {
            fixed: fixed.iter().map(|&i| (i, DofMask::ALL)).collect(),
            ..Default::default()
        },
    )
    .map_err(|e| e.to_string())?;
    let dofs = red.k.nrows();
    let dir = data_dir(&format!("eigen_{dofs}"))?;
    let (kp, mp) = (dir.join("K.mtx"), dir.join("M.mtx"));
    write_mtx(&kp, &red.k)?;
    write_mtx(&mp, &red.m)?;
    Ok(EigenSystem {
        model,
        fixed,
        dofs,
        dir,
        kp,
        mp,
    })
}

/// The `modes` suite: our eigen phase on the `eigen` suite's clamped block (same K, M) for each
/// mode count in `counts`, one child process each (peak memory per run): eigen time, solved
/// vectors, orthogonalization time and peak memory against the mode count, and each count's
/// eigen time over the smallest count's (issue 22's many-mode target: ≤ 3× from 30 to 300).
pub fn modes(n: [usize; 3], counts: &[usize]) -> Res<Value> {
    let EigenSystem { dofs, kp, mp, .. } = eigen_system(n)?;
    let load_before = loadavg();
    let mut runs = Vec::new();
    for &c in counts {
        runs.push(run_self(&[
            "ours-eigen".into(),
            kp.display().to_string(),
            mp.display().to_string(),
            c.to_string(),
        ])?);
    }
    let base = runs
        .first()
        .and_then(|r| r["phases_s"]["eigen"].as_f64())
        .unwrap_or(f64::NAN);
    let rows: Vec<Value> = counts
        .iter()
        .zip(&runs)
        .map(|(c, r)| {
            json!({
                "modes": c,
                "eigen_s": r["phases_s"]["eigen"],
                "eigen_over_first": r["phases_s"]["eigen"].as_f64().map(|e| num(e / base)),
                "orthogonalization_s": r["phases_s"]["eigen_orthogonalization"],
                "solves": r["solves"],
                "restarts": r["restarts"],
                "peak_rss_mb": r["peak_rss_mb"],
                "analyse_factor_s": r["phases_s"]["analyse_factor"],
                "max_residual": r["max_residual"],
            })
        })
        .collect();
    let json = json!({
        "suite": "modes",
        "model": format!("tet10 block {}x{}x{} bricks, x=0 clamped, consistent mass (the eigen suite's K, M)", n[0], n[1], n[2]),
        "dofs": dofs,
        "counts": counts,
        "loadavg_before": load_before,
        "loadavg_after": loadavg(),
        "rows": rows,
        "runs": runs,
    });
    write_result(&format!("modes_{dofs}.json"), &json)?;
    Ok(json)
}

/// Eigenvalues of a suite part's JSON.
pub(crate) fn eigenvalues(v: &Value) -> Vec<f64> {
    v["eigenvalues"]
        .as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default()
}

/// The `eigen` suite.
pub fn eigen(n: [usize; 3], modes: usize, with_ccx: bool, with_superlu: bool) -> Res<Value> {
    eigen_with(n, modes, with_ccx, with_superlu, EigenExtras::default())
}

/// The `eigen` suite with the many-mode extras; results in `eigen_<dofs>.json` for 30 modes,
/// `eigen_<dofs>_<modes>modes.json` otherwise.
pub fn eigen_with(
    n: [usize; 3],
    modes: usize,
    with_ccx: bool,
    with_superlu: bool,
    extras: EigenExtras,
) -> Res<Value> {
    let EigenSystem {
        mut model,
        fixed,
        dofs,
        dir,
        kp,
        mp,
    } = eigen_system(n)?;
    let deck = dir.join("freq.inp");
    write_ccx_deck(&deck, &model, &fixed, modes)?;
    model.node_sets.clear();
    drop(model);
    let (ks, ms) = (kp.display().to_string(), mp.display().to_string());
    let ms_ = modes.to_string();
    let load_before = loadavg();
    let ours = run_self(&["ours-eigen".into(), ks.clone(), ms.clone(), ms_.clone()])?;
    let superlu = if with_superlu {
        run_peer(&["superlu".into(), ks.clone(), ms.clone(), ms_.clone()])
    } else {
        json!({"skipped": "not asked (--no-superlu)"})
    };
    let cholmod = run_peer(&["cholmod".into(), ks.clone(), ms.clone(), ms_]);
    let ccx = if with_ccx {
        run_peer(&["ccx".into(), deck.display().to_string()])
    } else {
        json!({"skipped": "not asked (--ccx)"})
    };
    let baseline = match extras.baseline {
        Some(b) => {
            let v = run_self(&["ours-eigen".into(), ks.clone(), ms.clone(), b.to_string()])?;
            let ratio = |ph: &str| {
                ours["phases_s"][ph]
                    .as_f64()
                    .zip(v["phases_s"][ph].as_f64())
                    .map(|(a, b)| a / b)
            };
            json!({"modes": b, "phases_s": v["phases_s"], "solves": v["solves"],
                   "steps": v["steps"], "peak_rss_mb": v["peak_rss_mb"],
                   "eigen_ratio": ratio("eigen"), "total_ratio": ratio("total")})
        }
        None => Value::Null,
    };
    let inertia = if extras.inertia {
        let (lo, lp) = (eigenvalues(&ours), eigenvalues(&cholmod));
        let top = lo.iter().chain(lp.iter()).copied().fold(0.0f64, f64::max);
        // just above the highest eigenvalue either side found: the band [0, σ) must hold
        // exactly the count of both
        let sigma = top * (1.0 + 1e-8);
        let v = run_self(&["inertia".into(), ks.clone(), ms.clone(), sigma.to_string()])?;
        let below = |l: &[f64]| l.iter().filter(|&&x| x < sigma).count();
        json!({"sigma": sigma, "count_below": v["count_below"], "seconds": v["seconds"],
               "ours_below": below(&lo), "arpack_below": if lp.is_empty() { Value::Null } else { json!(below(&lp)) }})
    } else {
        Value::Null
    };
    let json = json!({
        "suite": "eigen",
        "baseline": baseline,
        "inertia": inertia,
        "model": format!("tet10 block {}x{}x{} bricks (6 tets each), 0.5x0.1x0.1 m steel, clamped at x=0, consistent mass", n[0], n[1], n[2]),
        "dofs": dofs,
        "modes": modes,
        "loadavg_before": load_before,
        "loadavg_after": loadavg(),
        "ours": ours,
        "peers": {"scipy_superlu": superlu, "arpack_cholmod": cholmod, "ccx": ccx},
        "ratios_ours_over": {
            "scipy_superlu": ratios(&ours, &superlu, modes),
            "arpack_cholmod": ratios(&ours, &cholmod, modes),
            "ccx": ratios(&ours, &ccx, modes),
        },
    });
    let name = if modes == 30 {
        format!("eigen_{dofs}.json")
    } else {
        format!("eigen_{dofs}_{modes}modes.json")
    };
    write_result(&name, &json)?;
    Ok(json)
}

/// (K, M, interface dofs ascending) of an assembled, eliminated system.
pub type System = (
    SparseColMat<usize, f64>,
    SparseColMat<usize, f64>,
    Vec<usize>,
);

/// The CB suite's assembled system: the generated block with RBE2 spiders on both end faces,
/// assembled and eliminated.
pub fn cb_system(n: [usize; 3]) -> Res<System> {
    let mut model = tet10_block(n);
    let itf = resolve_interfaces(&mut model, &["X0".into(), "XL".into()], SpiderKind::Rbe2)
        .map_err(|e| e.to_string())?;
    let asm = assemble(&model, &consistent()).map_err(|e| e.to_string())?;
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
    let mut interface: Vec<usize> = itf
        .iter()
        .flat_map(|r| r.nodes.iter())
        .flat_map(|&node| (0..6).map(move |c| (node, c)))
        .map(|(node, c)| pos[asm.dofs.first[node] + c])
        .collect();
    interface.sort_unstable();
    Ok((red.k, red.m, interface))
}

/// The CB suite's K_ii and M_ii: [`cb_system`]'s K and M restricted to the non-interface dofs
/// (K_ii is the matrix the CB build factors; `ours-eigen K_ii.mtx M_ii.mtx MODES BLOCK TOL
/// BASIS` runs the CB build's eigen phase alone, σ = 0 as CB, for tuning).
pub fn cb_interior(n: [usize; 3]) -> Res<(SparseColMat<usize, f64>, SparseColMat<usize, f64>)> {
    let (k, m, interface) = cb_system(n)?;
    let inner: Vec<usize> = (0..k.nrows())
        .filter(|i| interface.binary_search(i).is_err())
        .collect();
    let sub = |a: &SparseColMat<usize, f64>| {
        flexbody::solve::sparse_ops::submatrix(a.as_ref(), &inner, &inner)
            .map_err(|e| e.to_string())
    };
    Ok((sub(&k)?, sub(&m)?))
}

/// `ours-cb NX NY NZ MODES`: our whole CB build on the generated block (prints one JSON line).
pub fn ours_cb(n: [usize; 3], modes: usize, precision: &str) -> Res<Value> {
    let precision: flexbody::solve::Precision = precision.parse()?;
    let mut phases = serde_json::Map::new();
    let t_all = Instant::now();
    let mut t = Instant::now();
    let mut lap = |name: &str, phases: &mut serde_json::Map<String, Value>| {
        let s = t.elapsed().as_secs_f64();
        eprintln!("  {name}: {s:.2} s (peak {:.0} MB)", peak_rss_mb());
        phases.insert(name.into(), num(s));
        t = Instant::now();
    };
    let mut model = tet10_block(n);
    lap("generate", &mut phases);
    let itf = resolve_interfaces(&mut model, &["X0".into(), "XL".into()], SpiderKind::Rbe2)
        .map_err(|e| e.to_string())?;
    lap("interfaces", &mut phases);
    let asm = assemble(&model, &consistent()).map_err(|e| e.to_string())?;
    lap("assembly", &mut phases);
    let red = eliminate(
        &model,
        &asm.dofs,
        &asm.k,
        &asm.m,
        &ConstraintSpec::default(),
    )
    .map_err(|e| e.to_string())?;
    lap("elimination", &mut phases);
    let mut pos = vec![usize::MAX; asm.dofs.n_dofs];
    for (i, &p) in red.retained.iter().enumerate() {
        pos[p] = i;
    }
    let interface: Vec<usize> = itf
        .iter()
        .flat_map(|r| r.nodes.iter())
        .flat_map(|&node| (0..6).map(move |c| (node, c)))
        .map(|(node, c)| pos[asm.dofs.first[node] + c])
        .collect();
    drop(asm);
    let eig = EigenSpec {
        dofs_per_node: Some(3),
        par: threads(),
        precision,
        ..Default::default()
    };
    // K and M handed over, as the build does: not resident beside K_ii, M_ii and L
    let (basis, k, m) =
        craig_bampton_basis_owned(red.k, red.m, &interface, ModeCount::Count(modes), &eig)
            .map_err(|e| e.to_string())?;
    for note in &basis.notes {
        eprintln!("  note: {note}");
    }
    for (name, s) in &basis.timings {
        phases.insert(format!("cb {name}"), num(*s));
    }
    phases.insert("cb eigen solves".into(), num(basis.eigen.seconds_solve));
    phases.insert(
        "cb eigen orthogonalization".into(),
        num(basis.eigen.seconds_orth),
    );
    phases.insert("cb eigen restarts".into(), num(basis.eigen.seconds_restart));
    lap("craig-bampton basis", &mut phases);
    let o = {
        let _par = flexbody::solve::ParGuard::new(threads());
        orthonormalize_basis(&k, &m, &basis).map_err(|e| e.to_string())?
    };
    lap("orthonormalization", &mut phases);
    phases.insert("total".into(), num(t_all.elapsed().as_secs_f64()));
    Ok(json!({
        "peer": "flexbody CB build (generate, RBE2 spiders, assembly, elimination, CB, orthonormalization)",
        "n": k.nrows(),
        "nodes": model.nodes.len(),
        "interface_dofs": interface.len(),
        "phases_s": phases,
        "modes": o.omega2.len(),
        "orthonormality": num(o.diagnostics.orthonormality),
        "peak_rss_mb": peak_rss_mb(),
        "eigenvalues": basis.fixed_omega2,
        "eigen_solved_vectors": basis.eigen.solves,
        "eigen_steps": basis.eigen.steps,
        "eigen_restarts": basis.eigen.restarts,
        "eigen_ritz_solves": basis.eigen.ritz_solves,
        "eigen_gram_schmidt": gram_schmidt_json(&basis.eigen.gram_schmidt),
        "nnz_l": basis.eigen.factor.as_ref().map(|f| f.nnz_l),
        "factor_bytes": basis.eigen.factor.as_ref().map(|f| f.factor_bytes),
        "precision": format!("{precision:?}"),
        "eigen_refinement_solves": basis.eigen.refinement_solves,
        "notes": basis.notes,
        "threads": format!("faer {:?}", threads()),
        "loadavg": loadavg(),
    }))
}

/// `ours-build NX NY NZ MODES PRECISION`: the command line's whole build (`build::build_model`:
/// interfaces X0 and XL with RBE2 spiders, consistent mass, invariants, faces, verification; no
/// file written) on the generated block, for the peak memory a user's build reaches beside the
/// `ours-cb` reduction alone (prints one JSON line).
pub fn ours_build(n: [usize; 3], modes: usize, precision: &str) -> Res<Value> {
    let t = Instant::now();
    let model = tet10_block(n);
    let mut spec = flexbody::build::BuildSpec::new(
        "generated-tet10-block.inp".into(),
        flexbody_reader::Units::si(),
        &["X0", "XL"],
    );
    spec.spider = SpiderKind::Rbe2;
    spec.modes = Some(modes);
    spec.mass = MassKind::Consistent;
    spec.threads = 1;
    spec.precision = precision.parse()?;
    let out = flexbody::build::build_model(&spec, model, &mut |stage| {
        eprintln!("  {stage} (peak {:.0} MB)", peak_rss_mb())
    })
    .map_err(|e| e.to_string())?;
    let stages: serde_json::Map<String, Value> = out
        .report
        .stages
        .iter()
        .map(|(name, s)| (name.clone(), num(*s)))
        .collect();
    Ok(json!({
        "peer": "flexbody build (build_model: the command line's pipeline without writing the file)",
        "n": out.report.dofs.1,
        "modes": out.body.modes.frequency_hz.len(),
        "stages_s": stages,
        "total_s": num(t.elapsed().as_secs_f64()),
        "peak_rss_mb": peak_rss_mb(),
        "notes": out.report.diagnostics.notes,
        "precision": precision,
        "threads": 1,
        "loadavg": loadavg(),
    }))
}

/// Ratio of our whole CB build's time and peak memory to one CHOLMOD factorization of the same
/// K_ii (analyse + factor), from one repeat of the alternating pair.
fn cholmod_ratio(ours: &Value, chol: &Value) -> Value {
    let q = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => num(a / b),
        _ => Value::Null,
    };
    json!({
        "total_over_factor": q(ours["phases_s"]["total"].as_f64(), chol["phases_s"]["analyse_factor"].as_f64()),
        "our_factorization_over_factor": q(ours["phases_s"]["cb factorization"].as_f64(), chol["phases_s"]["analyse_factor"].as_f64()),
        "peak_memory": q(ours["peak_rss_mb"].as_f64(), chol["peak_rss_mb"].as_f64()),
    })
}

/// The `cb` suite. `repeats` alternates ours and the CHOLMOD factorization of the same K_ii
/// (ours, CHOLMOD, ours, CHOLMOD, ...), so each pair shares the machine's load; the result keeps
/// every pair and reports the fastest run of each side as `ours` and `cholmod_factor_kii`.
pub fn cb(
    n: [usize; 3],
    modes: usize,
    with_exudyn: bool,
    with_ccx: bool,
    repeats: usize,
    precision: &str,
) -> Res<Value> {
    let load_before = loadavg();
    let ms = modes.to_string();
    let run_ours = || {
        run_self(&[
            "ours-cb".into(),
            n[0].to_string(),
            n[1].to_string(),
            n[2].to_string(),
            ms.clone(),
            precision.into(),
        ])
    };
    let mut ours = run_ours()?;
    let dofs = ours["n"].as_u64().unwrap_or(0);
    let dir = data_dir(&format!("cb_{dofs}"))?;
    // The CHOLMOD peer row: the same K_ii (interface dofs removed), written once.
    let kii_path = dir.join("K_ii.mtx");
    {
        let (kii, mii) = cb_interior(n)?;
        write_mtx(&kii_path, &kii)?;
        write_mtx(&dir.join("M_ii.mtx"), &mii)?;
    }
    let kii_s = kii_path.display().to_string();
    let mut pairs = Vec::new();
    let mut chol_best: Option<Value> = None;
    let total = |v: &Value, k: &str| v["phases_s"][k].as_f64().unwrap_or(f64::INFINITY);
    for r in 0..repeats.max(1) {
        let o = if r == 0 { ours.clone() } else { run_ours()? };
        let c = run_peer(&["cholmod-factor".into(), kii_s.clone()]);
        pairs.push(json!({"ours": o.clone(), "cholmod_factor_kii": c.clone(),
                          "ratio": cholmod_ratio(&o, &c)}));
        if total(&o, "total") < total(&ours, "total") {
            ours = o;
        }
        if chol_best
            .as_ref()
            .is_none_or(|b| total(&c, "analyse_factor") < total(b, "analyse_factor"))
        {
            chol_best = Some(c);
        }
    }
    let cholmod = chol_best.unwrap_or(Value::Null);
    let model = tet10_block(n);
    let (x0, xl) = (node_set(&model, "X0")?, node_set(&model, "XL")?);
    let exudyn = if with_exudyn {
        let asm = assemble(&model, &consistent()).map_err(|e| e.to_string())?;
        if (0..model.nodes.len()).any(|i| asm.dofs.first[i] != 3 * i || asm.dofs.count[i] != 3) {
            return Err("generated block: dofs are not 3 per node in node order".into());
        }
        let (kp, mp) = (dir.join("K_free.mtx"), dir.join("M_free.mtx"));
        write_mtx(&kp, &asm.k)?;
        write_mtx(&mp, &asm.m)?;
        let xyz: String = model
            .nodes
            .iter()
            .map(|p| format!("{:.17e} {:.17e} {:.17e}\n", p.x[0], p.x[1], p.x[2]))
            .collect();
        let iface = format!(
            "{}\n{}\n",
            x0.iter()
                .map(|i| i.to_string())
                .collect::<Vec<_>>()
                .join(" "),
            xl.iter()
                .map(|i| i.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        );
        let (xp, ip) = (dir.join("nodes.xyz"), dir.join("interfaces.txt"));
        std::fs::write(&xp, xyz).map_err(|e| e.to_string())?;
        std::fs::write(&ip, iface).map_err(|e| e.to_string())?;
        drop(asm);
        run_peer(&[
            "hcb".into(),
            kp.display().to_string(),
            mp.display().to_string(),
            xp.display().to_string(),
            ip.display().to_string(),
            ms.clone(),
        ])
    } else {
        json!({"skipped": "not asked (--exudyn)"})
    };
    let ccx = if with_ccx {
        let deck = dir.join("freq_clamped.inp");
        let both: Vec<usize> = x0.iter().chain(&xl).copied().collect();
        write_ccx_deck(&deck, &model, &both, modes)?;
        run_peer(&["ccx".into(), deck.display().to_string()])
    } else {
        json!({"skipped": "not asked (--ccx)"})
    };
    let json = json!({
        "suite": "cb",
        "precision": precision,
        "model": format!("tet10 block {}x{}x{} bricks (6 tets each), 0.5x0.1x0.1 m steel, RBE2 spiders on x=0 and x=L (exudyn: RBE2 interfaces on the same nodes; ccx: both faces clamped, frequency only), consistent mass", n[0], n[1], n[2]),
        "dofs": dofs,
        "modes": modes,
        "loadavg_before": load_before,
        "loadavg_after": loadavg(),
        "ours": ours,
        "peers": {"exudyn_hcb": exudyn, "ccx": ccx, "cholmod_factor_kii": cholmod},
        "ratios_ours_over": {
            "exudyn_hcb": ratios(&ours, &exudyn, modes),
            "ccx": ratios(&ours, &ccx, modes),
            "cholmod_factor_kii": cholmod_ratio(&ours, &cholmod),
        },
        "repeats": pairs,
    });
    let suffix = if precision == "auto" {
        String::new()
    } else {
        format!("_{precision}")
    };
    write_result(&format!("cb_{dofs}{suffix}.json"), &json)?;
    Ok(json)
}

/// The `slepc` suite: the CB block's interior (K_ii, M_ii, K_ib of `cb`'s model) solved by our
/// engine (factorization, constraint modes, fixed-interface modes: `craig_bampton_basis`) and by
/// `--engine slepc` (MUMPS + SLEPc Krylov–Schur under `mpirun -np ranks`), in the same run:
/// fixed-interface eigenvalue agreement, constraint-mode agreement, wall times.
pub fn slepc(n: [usize; 3], modes: usize, ranks: usize) -> Res<Value> {
    let (k, m, interface) = cb_system(n)?;
    let nb = interface.len();
    let eig = flexbody::solve::EigenSpec {
        dofs_per_node: Some(3),
        par: threads(),
        ..Default::default()
    };
    let t = Instant::now();
    let ours = craig_bampton_basis(&k, &m, &interface, ModeCount::Count(modes), &eig)
        .map_err(|e| e.to_string())?;
    let t_ours = t.elapsed().as_secs_f64();
    let inner: Vec<usize> = (0..k.nrows())
        .filter(|i| interface.binary_search(i).is_err())
        .collect();
    let sub = |a: &SparseColMat<usize, f64>, r: &[usize], c: &[usize]| {
        flexbody::solve::sparse_ops::submatrix(a.as_ref(), r, c).map_err(|e| e.to_string())
    };
    let (kii, mii, kib) = (
        sub(&k, &inner, &inner)?,
        sub(&m, &inner, &inner)?,
        sub(&k, &inner, &interface)?,
    );
    let t = Instant::now();
    let s = flexbody::solve::slepc::fixed_interface(
        kii.as_ref(),
        mii.as_ref(),
        kib.as_ref(),
        flexbody::solve::slepc::Request {
            count: modes,
            upper: None,
            shift: 0.0,
            tol: eig.tol,
        },
        &flexbody::solve::slepc::SlepcEngine { ranks },
    )
    .map_err(|e| e.to_string())?;
    let t_slepc = t.elapsed().as_secs_f64();
    let freq_diff = max_rel_diff(&s.eigenvalues, &ours.fixed_omega2, modes);
    // constraint modes: ours T[inner, c] = −X[:, c]
    let mut x_diff = 0.0f64;
    let mut x_max = 0.0f64;
    for c in 0..nb {
        for (r, &i) in inner.iter().enumerate() {
            x_diff = x_diff.max((ours.t[(i, c)] + s.x[(r, c)]).abs());
            x_max = x_max.max(s.x[(r, c)].abs());
        }
    }
    let report: Value = serde_json::from_str(&s.report).unwrap_or(Value::Null);
    let json = json!({
        "suite": "slepc",
        "model": format!("tet10 block {}x{}x{} bricks, RBE2 spiders on both end faces (the cb suite's model), consistent mass", n[0], n[1], n[2]),
        "dofs": k.nrows(), "interior_dofs": inner.len(), "interface_dofs": nb, "modes": modes,
        "loadavg_before": loadavg(),
        "ours": {"seconds": t_ours, "timings": ours.timings.iter().map(|(n, s)| json!({"phase": n, "s": s})).collect::<Vec<_>>(),
                 "threads": format!("faer {:?}", threads())},
        "slepc": {"ranks": ranks, "seconds_incl_io": t_slepc, "script": report},
        "fixed_interface_eigenvalue_max_rel_diff": freq_diff,
        "constraint_modes_max_rel_diff": x_diff / x_max.max(f64::MIN_POSITIVE),
        "eigenvalues_ours": ours.fixed_omega2, "eigenvalues_slepc": s.eigenvalues,
    });
    write_result(&format!("slepc_{}.json", k.nrows()), &json)?;
    Ok(json)
}
