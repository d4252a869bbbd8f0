//! Reduction benchmark (not a test): Craig–Bampton with 12 interface dofs and 30 fixed-interface
//! modes, timed per phase (ordering + factorization, constraint modes, eigen, orthonormalization)
//! with peak memory, on either a CalculiX matrix dump (`--ccx STEM`) or a synthetic 3D lattice
//! (`--grid NX NY NZ`: 3 dofs per node, springs to all 26 neighbours, i.e. the 27-point pattern
//! of a hex8 mesh; both ends restrained only through the interface).
//!
//! Usage: `reduce_bench [--grid NX NY NZ | --ccx STEM] [--modes 30] [--block B] [--normal] [--seq]`

use flexbody::reduce::craig_bampton::craig_bampton;
use flexbody::reduce::select::ModeCount;
use flexbody::solve::{lowest_modes, EigenSpec, SparseColMat, Triplet};
use std::path::Path;
use std::time::Instant;

type Sparse = SparseColMat<usize, f64>;

/// Spring lattice: unit cube cells of size h, steel-like axial springs on all 26 neighbour links
/// plus a small isotropic link stiffness (no mechanisms), lumped nodal mass.
fn lattice(nx: usize, ny: usize, nz: usize) -> (Sparse, Sparse) {
    let id = |i: usize, j: usize, k: usize| (k * (ny + 1) + j) * (nx + 1) + i;
    let nn = (nx + 1) * (ny + 1) * (nz + 1);
    let (ka, ks, mass) = (1e9, 1e7, 0.01);
    let mut kt = Vec::new();
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let a = id(i, j, k);
                for (di, dj, dk) in neighbours() {
                    let (ii, jj, kk) = (i as i64 + di, j as i64 + dj, k as i64 + dk);
                    if ii < 0
                        || jj < 0
                        || kk < 0
                        || ii > nx as i64
                        || jj > ny as i64
                        || kk > nz as i64
                    {
                        continue;
                    }
                    let b = id(ii as usize, jj as usize, kk as usize);
                    let l = ((di * di + dj * dj + dk * dk) as f64).sqrt();
                    let e = [di as f64 / l, dj as f64 / l, dk as f64 / l];
                    for p in 0..3 {
                        for q in 0..3 {
                            let v = ka / l * e[p] * e[q] + if p == q { ks } else { 0.0 };
                            kt.push(Triplet::new(3 * a + p, 3 * a + q, v));
                            kt.push(Triplet::new(3 * b + p, 3 * b + q, v));
                            kt.push(Triplet::new(3 * a + p, 3 * b + q, -v));
                            kt.push(Triplet::new(3 * b + p, 3 * a + q, -v));
                        }
                    }
                }
            }
        }
    }
    let n = 3 * nn;
    let mt: Vec<_> = (0..n).map(|i| Triplet::new(i, i, mass)).collect();
    (
        SparseColMat::try_new_from_triplets(n, n, &kt).expect("indices in range"),
        SparseColMat::try_new_from_triplets(n, n, &mt).expect("indices in range"),
    )
}

/// Half of the 26 neighbour offsets (each link once).
fn neighbours() -> Vec<(i64, i64, i64)> {
    let mut v = Vec::new();
    for dk in -1..=1i64 {
        for dj in -1..=1i64 {
            for di in -1..=1i64 {
                if (dk, dj, di) > (0, 0, 0) {
                    v.push((di, dj, dk));
                }
            }
        }
    }
    v
}

fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM"))
                .map(|l| l.to_string())
        })
        .and_then(|l| {
            l.split_whitespace()
                .nth(1)
                .and_then(|x| x.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.iter().any(|a| a == "--seq") {
        flexbody::solve::faer::set_global_parallelism(flexbody::solve::faer::Par::Seq);
    }
    let pos = |name: &str| args.iter().position(|a| a == name);
    let modes = pos("--modes").map_or(30, |i| args[i + 1].parse().expect("--modes N"));
    let t0 = Instant::now();
    let (k, m, label) = if let Some(i) = pos("--ccx") {
        let c = flexbody::import::ccx_matrices::read_ccx_matrices(Path::new(&args[i + 1]))
            .expect("ccx dump");
        let tr = |t: &flexbody::import::ccx_matrices::SymmetricTriplets| {
            let v: Vec<_> = t
                .full()
                .into_iter()
                .map(|(i, j, x)| Triplet::new(i, j, x))
                .collect();
            SparseColMat::try_new_from_triplets(t.n, t.n, &v).expect("indices in range")
        };
        let m = tr(c.m.as_ref().expect("mass dump"));
        (tr(&c.k), m, args[i + 1].clone())
    } else {
        let g = pos("--grid").map_or([40, 8, 8], |i| {
            [
                args[i + 1].parse().unwrap(),
                args[i + 2].parse().unwrap(),
                args[i + 3].parse().unwrap(),
            ]
        });
        let (k, m) = lattice(g[0], g[1], g[2]);
        (k, m, format!("lattice {}x{}x{}", g[0], g[1], g[2]))
    };
    let n = k.nrows();
    println!(
        "model: {label}, {n} dofs, nnz(K) = {}, built in {:.2} s",
        k.compute_nnz(),
        t0.elapsed().as_secs_f64()
    );
    let eig = EigenSpec {
        dofs_per_node: Some(3),
        ..Default::default()
    };
    if pos("--normal").is_some() {
        let t = Instant::now();
        let s = lowest_modes(
            &k,
            &m,
            &EigenSpec {
                count: modes,
                ..eig.clone()
            },
        )
        .expect("normal modes");
        println!(
            "normal modes ({modes}): {:.2} s total, factor {:.2} s, eigen {:.2} s, {} solves, {:?}",
            t.elapsed().as_secs_f64(),
            s.info.seconds_factor,
            s.info.seconds_eigen,
            s.info.solves,
            s.info.factor
        );
    }
    // interface: the first 2 and last 2 nodes (12 dofs)
    let interface: Vec<usize> = (0..6).chain(n - 6..n).collect();
    let t = Instant::now();
    let cb =
        craig_bampton(&k, &m, &interface, ModeCount::Count(modes), &eig).expect("Craig-Bampton");
    let total = t.elapsed().as_secs_f64();
    println!("Craig-Bampton: 12 interface dofs, {modes} fixed-interface modes, {} modes, {total:.2} s total", cb.len());
    for note in &cb.diagnostics.notes {
        println!("  {note}");
    }
    println!(
        "  orthonormality {:.1e}, stiffness diag {:.1e}, peak RSS {:.0} MB",
        cb.diagnostics.orthonormality,
        cb.diagnostics.stiffness_diag,
        peak_rss_mb()
    );
    let f = cb.frequencies_hz();
    println!("  first frequencies (Hz): {:?}", &f[..f.len().min(8)]);
}
