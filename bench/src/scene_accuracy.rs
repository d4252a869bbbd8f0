//! Scene accuracy suite (`harness scene`): the error of the reduced body's response to the
//! scene's loads against the full FE model, versus the number of basis vectors, for normal modes
//! and Craig–Bampton with and without residual vectors and for scene selection
//! (`--select participation:ε`).
//!
//! Model: a clamped hex8 steel cantilever 1.2 × 0.12 × 0.08 m (16 × 2 × 2 bricks) with three
//! loads: gravity (−z), a vertical tip force at the end face's centre and a lateral force at
//! mid-span; Craig–Bampton's interface is the tip node. Each body is built through the library's
//! `build` (the CLI's pipeline) and read from its modes and modal loads only:
//!
//! * static error: max over loads |H_red(0) − H(0)| / H(0), H(0) = fᵀK⁻¹f the load's static
//!   work-conjugate response (for a point force: its displacement times the force);
//! * FRF error: max over loads and 9 frequencies in [0, fmax] (none at a resonance) of
//!   |H_red(ω) − H(ω)| / H(0), with H(ω) = fᵀ(K − ω²M)⁻¹f solved densely on the full model and
//!   H_red(ω) = Σ g_j²/(ω_j² − ω²) from the body's modal loads g = Φᵀf.
//!
//! Result: `bench/results/scene_cantilever.json`.

// Index loops mirror the subscripts of the formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::path::{Path, PathBuf};

use flexbody::build::{build, BuildMethod, BuildSpec};
use flexbody::fe::{assemble, eliminate, AssemblySpec, ConstraintSpec};
use flexbody::reduce::residual::ResidualKind;
use flexbody::scene::SceneSpec;
use flexbody_reader as file;
use serde_json::{json, Value};

use crate::{loadavg, num, write_result, Res};

const NX: usize = 16;
const NY: usize = 2;
const NZ: usize = 2;
const L: f64 = 1.2;
const BY: f64 = 0.12;
const BZ: f64 = 0.08;
/// The scene's band (Hz).
const FMAX: f64 = 700.0;
/// Mode counts of the sweeps (flexible / fixed-interface modes).
const COUNTS: [usize; 7] = [2, 3, 4, 6, 8, 12, 16];
/// ε of the selection sweep.
const EPSILONS: [f64; 6] = [1e-1, 3e-2, 1e-2, 1e-3, 1e-4, 1e-5];
/// Fractions of the band at which the full model is solved (0 = static).
const BAND_POINTS: [f64; 9] = [0.0, 0.11, 0.23, 0.37, 0.52, 0.64, 0.77, 0.89, 0.98];

fn nid(i: usize, j: usize, k: usize) -> usize {
    (k * (NY + 1) + j) * (NX + 1) + i + 1
}

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

/// Dense LU with partial pivoting, several right-hand sides: A X = B (columns of `b`).
fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let n = a.len();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap_or(c);
        a.swap(c, p);
        b.swap(c, p);
        let piv = a[c][c];
        for r in c + 1..n {
            let f = a[r][c] / piv;
            if f != 0.0 {
                let (top, bottom) = a.split_at_mut(r);
                for (x, y) in bottom[0][c..].iter_mut().zip(&top[c][c..]) {
                    *x -= f * y;
                }
                let (bt, bb) = b.split_at_mut(r);
                for (x, y) in bb[0].iter_mut().zip(&bt[c]) {
                    *x -= f * y;
                }
            }
        }
    }
    let nr = b.first().map_or(0, Vec::len);
    let mut x = vec![vec![0.0; nr]; n];
    for c in (0..n).rev() {
        for q in 0..nr {
            let s: f64 = (c + 1..n).map(|k| a[c][k] * x[k][q]).sum();
            x[c][q] = (b[c][q] - s) / a[c][c];
        }
    }
    x
}

fn dense(m: &flexbody::solve::SparseColMat<usize, f64>) -> Vec<Vec<f64>> {
    let mut a = vec![vec![0.0; m.ncols()]; m.nrows()];
    for j in 0..m.ncols() {
        for (i, v) in m.row_idx_of_col(j).zip(m.val_of_col(j)) {
            a[i][j] += v;
        }
    }
    a
}

/// H[k][s] = f_kᵀ(K − ω_s²M)⁻¹f_k of the full model.
fn full_frf(path: &Path, scene: &SceneSpec, omegas: &[f64]) -> Res<Vec<Vec<f64>>> {
    let model =
        flexbody::import::read_model(path, &Default::default()).map_err(|e| e.to_string())?;
    let a = assemble(&model, &AssemblySpec::default()).map_err(|e| e.to_string())?;
    let r = eliminate(&model, &a.dofs, &a.k, &a.m, &ConstraintSpec::default())
        .map_err(|e| e.to_string())?;
    let loads = flexbody::scene::scene_loads(&model, scene).map_err(|e| e.to_string())?;
    let f = flexbody::fe::loads::load_vectors(&model, &a.dofs, &a.m, &loads)
        .map_err(|e| e.to_string())?;
    let fr = flexbody::fe::loads::reduce_loads(&r.t, &f);
    let (k, m) = (dense(&r.k), dense(&r.m));
    let n = k.len();
    let nl = loads.len();
    let mut h = vec![vec![0.0; omegas.len()]; nl];
    let b: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..nl).map(|q| fr[(i, q)]).collect())
        .collect();
    for (s, &w) in omegas.iter().enumerate() {
        let a: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| k[i][j] - w * w * m[i][j]).collect())
            .collect();
        let u = dense_solve(a, b.clone());
        for q in 0..nl {
            h[q][s] = (0..n).map(|i| b[i][q] * u[i][q]).sum();
        }
    }
    Ok(h)
}

/// (basis vectors, static error, FRF error) of a body against the full responses `h`.
fn errors(body: &file::ReducedBody, omegas: &[f64], h: &[Vec<f64>]) -> (usize, f64, f64) {
    let flex: Vec<usize> = (0..body.modes.omega2.len())
        .filter(|&j| body.modes.labels[j] != file::ModeLabel::Rigid)
        .collect();
    let (mut st, mut fr) = (0.0f64, 0.0f64);
    if let Some(ml) = &body.modal_loads {
        for (q, l) in ml.loads.iter().enumerate() {
            for (s, &w) in omegas.iter().enumerate() {
                let hr: f64 = flex
                    .iter()
                    .map(|&j| l.values[j].powi(2) / (body.modes.omega2[j] - w * w))
                    .sum();
                let e = (hr - h[q][s]).abs() / h[q][0].abs();
                fr = fr.max(e);
                if s == 0 {
                    st = st.max(e);
                }
            }
        }
    }
    (flex.len(), st, fr)
}

/// Runs the suite.
pub fn run() -> Res<Value> {
    let dir: PathBuf =
        std::env::temp_dir().join(format!("flexbody-scene-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let path = dir.join("cantilever.bdf");
    std::fs::write(&path, deck()).map_err(|e| e.to_string())?;
    let tip = nid(NX, NY / 2, NZ / 2);
    let scene = SceneSpec {
        gravity: Some("0,0,-9.81".into()),
        loads: vec![
            format!("TIP:{tip}:0,0,-1000"),
            format!("SIDE:{}:0,500,0", nid(NX / 2, NY / 2, NZ / 2)),
        ],
        ..Default::default()
    };
    let w = 2.0 * std::f64::consts::PI * FMAX;
    let omegas: Vec<f64> = BAND_POINTS.iter().map(|x| x * w).collect();
    let h = full_frf(&path, &scene, &omegas)?;
    let tip_s = tip.to_string();
    let base = |method: BuildMethod| -> BuildSpec {
        let itf: Vec<&str> = if method == BuildMethod::CraigBampton {
            vec![tip_s.as_str()]
        } else {
            vec![]
        };
        BuildSpec {
            method,
            scene: scene.clone(),
            ..BuildSpec::new(path.clone(), file::Units::si(), &itf)
        }
    };
    let point = |s: &BuildSpec, label: String| -> Value {
        match build(s, &mut |_| {}) {
            Ok(out) => {
                let (n, st, fr) = errors(&out.body, &omegas, &h);
                eprintln!("  {label}: {n} vectors, static {st:.2e}, FRF {fr:.2e}");
                json!({"label": label, "vectors": n, "static_error": num(st), "frf_error": num(fr)})
            }
            Err(e) => json!({"label": label, "error": e.to_string()}),
        }
    };
    let mut series = Vec::new();
    for (name, method) in [
        ("normal modes", BuildMethod::Normal),
        ("Craig-Bampton", BuildMethod::CraigBampton),
    ] {
        for rv in [None, Some(ResidualKind::Loads)] {
            let points: Vec<Value> = COUNTS
                .iter()
                .map(|&c| {
                    let mut s = base(method);
                    s.modes = Some(c);
                    s.scene.residual_vectors = rv;
                    point(&s, c.to_string())
                })
                .collect();
            let name = format!("{name}{}", if rv.is_some() { " + residual" } else { "" });
            series.push(json!({"series": name, "points": points}));
        }
    }
    // the frequency cutoff (every mode to 3·fmax) and the selection among those candidates
    let mut cut = base(BuildMethod::Normal);
    cut.fmax_hz = Some(FMAX);
    series.push(json!({"series": "cutoff 3*fmax", "points": [point(&cut, "cutoff".into())]}));
    for rv in [None, Some(ResidualKind::Loads)] {
        let points: Vec<Value> = EPSILONS
            .iter()
            .map(|&e| {
                let mut s = cut.clone();
                s.scene.select = Some(e);
                s.scene.residual_vectors = rv;
                point(&s, format!("{e:.0e}"))
            })
            .collect();
        let name = format!("selection{}", if rv.is_some() { " + residual" } else { "" });
        series.push(json!({"series": name, "points": points}));
    }
    let _ = std::fs::remove_dir_all(&dir);
    let json = json!({
        "suite": "scene",
        "model": "hex8 cantilever 1.2 x 0.12 x 0.08 m, 16 x 2 x 2 bricks, clamped at x = 0",
        "loads": "GRAVITY (0,0,-9.81); TIP 1000 N -z at the end face's centre; SIDE 500 N +y at mid-span",
        "craig_bampton_interface": "the tip node (3 dofs)",
        "fmax_hz": FMAX,
        "band_points": BAND_POINTS,
        "errors": "relative to each load's static response f^T K^-1 f; max over loads (and band points for frf_error)",
        "series": series,
        "loadavg": loadavg(),
    });
    write_result("scene_cantilever.json", &json)?;
    Ok(json)
}
