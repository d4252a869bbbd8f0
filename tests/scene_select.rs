//! Issue 19: mode selection by the scene (`--select participation:ε`), checked against the FULL
//! FE frequency response: (K − ω²M) u = f solved densely here at frequencies across the band,
//! H_k(ω) = f_kᵀu (the work-conjugate "load-point" response of load k: for a point force F the
//! displacement under it times F). The reduced body's response is computed from the FILE alone:
//! H_k(ω) = Σ g_jk²/(ω_j² − ω²) over its flexible modes with the stored modal loads g = Φᵀf_k.
//! Errors are relative to the load's full static response f_kᵀK⁻¹f_k.

// Index loops mirror the subscripts of the formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::path::{Path, PathBuf};

use flexbody::build::{build, BuildMethod, BuildSpec};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec};
use flexbody::reduce::residual::ResidualKind;
use flexbody::scene::SceneSpec;
use flexbody_reader as file;

const NX: usize = 16;
const NY: usize = 2;
const NZ: usize = 2;
const L: f64 = 1.2;
/// Width (y) and height (z): a rectangular section, so the vertical and lateral bending modes
/// are distinct (a square one makes them degenerate, any mix of the two an eigenvector).
const BY: f64 = 0.12;
const BZ: f64 = 0.08;
/// The scene's band (Hz).
const FMAX: f64 = 700.0;

fn nid(i: usize, j: usize, k: usize) -> usize {
    (k * (NY + 1) + j) * (NX + 1) + i + 1
}

/// A hex8 steel cantilever clamped at x = 0.
fn deck() -> String {
    let mut d = String::from("SOL 103\nCEND\nTITLE = cantilever\nSPC = 1\nBEGIN BULK\n");
    for k in 0..=NZ {
        for j in 0..=NY {
            for i in 0..=NX {
                d += &format!(
                    "GRID,{},,{},{},{}\n",
                    nid(i, j, k),
                    i as f64 * L / NX as f64,
                    j as f64 * BY / NY as f64,
                    k as f64 * BZ / NZ as f64
                );
            }
        }
    }
    let mut e = 0;
    for k in 0..NZ {
        for j in 0..NY {
            for i in 0..NX {
                e += 1;
                let n = [
                    nid(i, j, k),
                    nid(i + 1, j, k),
                    nid(i + 1, j + 1, k),
                    nid(i, j + 1, k),
                    nid(i, j, k + 1),
                    nid(i + 1, j, k + 1),
                    nid(i + 1, j + 1, k + 1),
                    nid(i, j + 1, k + 1),
                ];
                d += &format!(
                    "CHEXA,{e},1,{},{},{},{},{},{},+\n+,{},{}\n",
                    n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7]
                );
            }
        }
    }
    d += "PSOLID,1,1\nMAT1,1,210e9,,0.3,7850.\n";
    for k in 0..=NZ {
        for j in 0..=NY {
            d += &format!("SPC1,1,123,{}\n", nid(0, j, k));
        }
    }
    d += "ENDDATA\n";
    d
}

fn write_deck(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexbody-select-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("cantilever.bdf");
    std::fs::write(&p, deck()).unwrap();
    p
}

/// Build, write, read back: the body as a solver sees it, with the build's notes.
fn built(s: &BuildSpec, tag: &str) -> (file::ReducedBody, Vec<String>, PathBuf) {
    let out = build(s, &mut |_| {}).unwrap();
    let path = s.model.with_extension(format!("{tag}.flexbody"));
    flexbody::write::write_reduced_body(&path, &out.body, &Default::default()).unwrap();
    let mut notes = out.report.notes.clone();
    notes.extend(out.report.warnings.clone());
    notes.extend(out.report.diagnostics.notes.clone());
    (file::read(&path).unwrap(), notes, path)
}

/// Dense LU with partial pivoting: solves A x = b.
fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap();
        a.swap(c, p);
        b.swap(c, p);
        let piv = a[c][c];
        assert!(piv.abs() > 0.0, "singular system");
        for r in c + 1..n {
            let f = a[r][c] / piv;
            if f != 0.0 {
                let (top, bottom) = a.split_at_mut(r);
                for (x, y) in bottom[0][c..].iter_mut().zip(&top[c][c..]) {
                    *x -= f * y;
                }
                b[r] -= f * b[c];
            }
        }
    }
    let mut x = vec![0.0; n];
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|k| a[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    x
}

fn dense(m: &faer::sparse::SparseColMat<usize, f64>) -> Vec<Vec<f64>> {
    let mut a = vec![vec![0.0; m.ncols()]; m.nrows()];
    for j in 0..m.ncols() {
        for (i, v) in m.row_idx_of_col(j).zip(m.val_of_col(j)) {
            a[i][j] += v;
        }
    }
    a
}

/// The full model's load-point responses: `h[k][s]` = f_kᵀ(K − ω_s²M)⁻¹f_k for each scene load
/// (by name) and frequency (rad/s) — ω = 0 is the static compliance.
fn full_frf(path: &Path, scene: &SceneSpec, omegas: &[f64]) -> Vec<Vec<f64>> {
    let model = flexbody::import::read_model(path, &Default::default()).unwrap();
    let a = assemble(&model, &AssemblySpec::default()).unwrap();
    let r = eliminate(&model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default()).unwrap();
    let loads = flexbody::scene::scene_loads(&model, scene).unwrap();
    let f = flexbody::fe::loads::load_vectors(&model, &a.dofs, &a.m, &loads).unwrap();
    let fr = flexbody::fe::loads::reduce_loads(&r.t, &f);
    let (k, m) = (dense(&r.k), dense(&r.m));
    let n = k.len();
    let mut h = vec![vec![0.0; omegas.len()]; loads.len()];
    for (s, &w) in omegas.iter().enumerate() {
        let a: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| k[i][j] - w * w * m[i][j]).collect())
            .collect();
        for q in 0..loads.len() {
            let b: Vec<f64> = (0..n).map(|i| fr[(i, q)]).collect();
            let u = dense_solve(a.clone(), b.clone());
            h[q][s] = (0..n).map(|i| b[i] * u[i]).sum();
        }
    }
    h
}

/// The file's load-point response of load `name` at ω: Σ g_j²/(ω_j² − ω²) over flexible modes.
fn file_frf(body: &file::ReducedBody, name: &str, w: f64) -> f64 {
    let ml = body.modal_loads.as_ref().expect("modal_loads.bin");
    let g = &ml.loads.iter().find(|l| l.name == name).unwrap().values;
    (0..body.mode_count())
        .filter(|&j| body.modes.labels[j] != file::ModeLabel::Rigid)
        .map(|j| g[j] * g[j] / (body.modes.omega2[j] - w * w))
        .sum()
}

/// Worst |H_file − H_full| / |H_full(0)| over the loads and the frequencies.
fn worst_error(body: &file::ReducedBody, names: &[&str], omegas: &[f64], h: &[Vec<f64>]) -> f64 {
    let mut e = 0.0f64;
    for (q, name) in names.iter().enumerate() {
        for (s, &w) in omegas.iter().enumerate() {
            e = e.max((file_frf(body, name, w) - h[q][s]).abs() / h[q][0].abs());
        }
    }
    e
}

fn flexible(body: &file::ReducedBody) -> usize {
    (body.modes.labels.iter())
        .filter(|l| **l != file::ModeLabel::Rigid)
        .count()
}

fn spec(path: &Path, scene: SceneSpec) -> BuildSpec {
    BuildSpec {
        method: BuildMethod::Normal,
        fmax_hz: Some(FMAX),
        scene,
        ..BuildSpec::new(path.to_path_buf(), file::Units::si(), &[])
    }
}

/// Frequencies of the band at which the full model is solved: 0 (static) and eight more, none
/// at a resonance of the model.
fn band_omegas() -> Vec<f64> {
    let w = 2.0 * std::f64::consts::PI * FMAX;
    [0.0, 0.11, 0.23, 0.37, 0.52, 0.64, 0.77, 0.89, 0.98]
        .iter()
        .map(|x| x * w)
        .collect()
}

/// A vertical scene (gravity and a tip force under the section's centre line) on a clamped
/// cantilever, normal modes with --fmax: the frequency cutoff keeps every mode to 3·fmax; scene
/// selection with residual vectors keeps at most half as many basis vectors for a worst FRF
/// error (full FE, across the band) no larger than the cutoff's, and its own error estimate
/// bounds the measured error.
#[test]
fn selection_halves_the_modes_for_the_cutoff_error() {
    let path = write_deck("vertical");
    let tip = nid(NX, NY / 2, NZ / 2);
    let scene = SceneSpec {
        gravity: Some("0,0,-9.81".into()),
        loads: vec![format!("TIP:{tip}:0,0,-1000")],
        ..Default::default()
    };
    let names = ["GRAVITY", "TIP"];
    let omegas = band_omegas();
    let h = full_frf(&path, &scene, &omegas);
    let (cut, _, _) = built(&spec(&path, scene.clone()), "cutoff");
    let e_cut = worst_error(&cut, &names, &omegas, &h);
    let n_cut = flexible(&cut);
    println!("frequency cutoff (3·fmax): {n_cut} modes, worst FRF error {e_cut:.3e}");
    // residual vectors on the cutoff basis (the chart's middle row)
    let mut s = spec(&path, scene.clone());
    s.scene.residual_vectors = Some(ResidualKind::Loads);
    let (cut_rv, _, _) = built(&s, "cutoff-rv");
    // 11 modes + 2 residual vectors: the static response is exact (a residual vector whose
    // missing part is small in mass but not in compliance is kept, not dropped as dependent)
    let h0: Vec<Vec<f64>> = h.iter().map(|r| vec![r[0]]).collect();
    let e_static = worst_error(&cut_rv, &names, &[0.0], &h0);
    println!("cutoff + residual vectors: static error {e_static:.3e}");
    assert!(e_static < 1e-8, "static error {e_static:e}");
    assert_eq!(flexible(&cut_rv), n_cut + 2);
    println!(
        "cutoff + residual vectors: {} vectors, worst FRF error {:.3e}",
        flexible(&cut_rv),
        worst_error(&cut_rv, &names, &omegas, &h)
    );
    // selection at the cutoff's measured error, with and without residual vectors
    for rv in [None, Some(ResidualKind::Loads)] {
        let mut s = spec(&path, scene.clone());
        // Without residual vectors the cutoff's error is the static part of the modes above
        // 3·fmax, which no selection among the candidates recovers: ε a little above it lets
        // the selection drop what the scene does not excite.
        let eps = if rv.is_some() { e_cut } else { 1.1 * e_cut };
        s.scene.select = Some(eps);
        s.scene.residual_vectors = rv;
        let (sel, notes, p) = built(&s, if rv.is_some() { "sel-rv" } else { "sel" });
        let e_sel = worst_error(&sel, &names, &omegas, &h);
        let estimate = match sel.recipe.as_ref().map(|r| r.options.select.clone()) {
            Some(Some(t)) => t,
            other => panic!("recipe select {other:?}"),
        };
        let note = notes
            .iter()
            .find(|n| n.starts_with("scene selection"))
            .unwrap_or_else(|| panic!("{notes:?}"));
        println!(
            "selection ({estimate}, residual vectors {rv:?}): {} vectors, worst FRF error \
             {e_sel:.3e}\n  {note}",
            flexible(&sel)
        );
        let est: f64 = note
            .split("estimated worst FRF error ")
            .nth(1)
            .and_then(|t| t.split(' ').next())
            .and_then(|t| t.parse().ok())
            .unwrap();
        // the estimate is a bound of the truncation: the full model's error stays below it
        assert!(
            e_sel <= est * 1.05 + 1e-12,
            "measured {e_sel:e} > estimate {est:e}"
        );
        assert!(est <= eps, "estimate {est:e} above ε {eps:e}");
        // at most half the cutoff's vectors (modes + residual vectors) for no larger an error
        assert!(
            e_sel <= e_cut * (1.0 + 1e-6),
            "selection error {e_sel:e} > cutoff error {e_cut:e}"
        );
        assert!(
            2 * flexible(&sel) <= n_cut,
            "{} vectors with selection vs {n_cut} by the cutoff",
            flexible(&sel)
        );
        // `check` passes from the file's recipe (kept modes against the nearest full ones)
        let c = std::process::Command::new(env!("CARGO_BIN_EXE_flexbody"))
            .args([
                "check",
                p.to_str().unwrap(),
                "--model",
                path.to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert!(
            c.status.success(),
            "{}{}",
            String::from_utf8_lossy(&c.stdout),
            String::from_utf8_lossy(&c.stderr)
        );
    }
}

/// Through the CLI: `--select participation:ε` is parsed, its note (what was dropped, the
/// estimate) is printed, the recipe records it, and a bad value is refused naming the option.
#[test]
fn cli_select_is_recorded_and_refused_when_malformed() {
    let path = write_deck("cli");
    let out = path.with_extension("cli.flexbody");
    let tip = nid(NX, NY / 2, NZ / 2);
    let run = |select: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_flexbody"))
            .args([
                "build",
                path.to_str().unwrap(),
                "--method",
                "normal",
                "--fmax",
            ])
            .arg(FMAX.to_string())
            .args([
                "--load",
                &format!("TIP:{tip}:0,0,-1000"),
                "--select",
                select,
            ])
            .args([
                "--residual-vectors",
                "loads",
                "--units",
                "si",
                "-o",
                out.to_str().unwrap(),
            ])
            .output()
            .unwrap()
    };
    let o = run("participation:0.01");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("scene selection (participation, ε = 1.000e-2"),
        "{err}"
    );
    assert!(err.contains("dropped (Hz): "), "{err}");
    let body = file::read(&out).unwrap();
    let recipe = body.recipe.as_ref().unwrap();
    assert_eq!(recipe.options.select.as_deref(), Some("participation:0.01"));
    // TIP excites only the vertical bending modes: fewer flexible vectors than the 11 candidates
    assert!(flexible(&body) < 11, "{}", flexible(&body));
    let o = run("participation:-1");
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("select") && err.contains("participation:EPS"),
        "{err}"
    );
}

/// Craig–Bampton with the tip node as interface: the selection also ranks the unit interface
/// loads; its estimate bounds the full FE error of the scene's load-point responses, and the
/// scene keeps fewer vectors than the 3·fmax basis.
#[test]
fn craig_bampton_selection_estimate_bounds_the_full_error() {
    let path = write_deck("cb");
    let tip = nid(NX, NY / 2, NZ / 2).to_string();
    let scene = SceneSpec {
        gravity: Some("0,0,-9.81".into()),
        loads: vec![format!("TIP:{tip}:0,0,-1000")],
        residual_vectors: Some(ResidualKind::Loads),
        ..Default::default()
    };
    let names = ["GRAVITY", "TIP"];
    let omegas = band_omegas();
    let h = full_frf(&path, &scene, &omegas);
    let cb = |select: Option<f64>| BuildSpec {
        method: BuildMethod::CraigBampton,
        fmax_hz: Some(FMAX),
        scene: SceneSpec {
            select,
            ..scene.clone()
        },
        ..BuildSpec::new(path.to_path_buf(), file::Units::si(), &[tip.as_str()])
    };
    let (all, _, _) = built(&cb(None), "cb-all");
    let e_all = worst_error(&all, &names, &omegas, &h);
    let (sel, notes, _) = built(&cb(Some(1e-2)), "cb-sel");
    let e_sel = worst_error(&sel, &names, &omegas, &h);
    let note = notes
        .iter()
        .find(|n| n.starts_with("scene selection"))
        .unwrap_or_else(|| panic!("{notes:?}"));
    let est: f64 = note
        .split("estimated worst FRF error ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap();
    println!(
        "CB 3·fmax + residual: {} vectors, error {e_all:.3e}; selection ε = 1e-2: {} vectors, \
         error {e_sel:.3e}, estimate {est:.3e}\n  {note}",
        flexible(&all),
        flexible(&sel)
    );
    assert!(
        e_sel <= est * 1.05 + 1e-12,
        "measured {e_sel:e} > estimate {est:e}"
    );
    assert!(est <= 1e-2);
    assert!(flexible(&sel) < flexible(&all));
}
