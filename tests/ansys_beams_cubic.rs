//! BEAM188 with KEYOPT(3)=3 (cubic: ANSYS adds two internal nodes per element, at 1/3 and 2/3
//! of IJ, which the archive does not hold) from archives written here, against closed forms:
//!
//! - one element clamped at I: an end load and an end moment give the Timoshenko beam's
//!   deflections and rotations (PL³/(3EI) + PL/(kGA); ML²/(2EI)) at J and at the internal
//!   nodes — the cubic functions hold the exact solution (θ quadratic, w cubic) and three points
//!   integrate the shear energy of its constant shear strain exactly;
//! - a clamped-free beam through the CLI: its bending frequencies (Timoshenko's frequency
//!   equation, both planes), axial and torsional ones (closed form), converged with the mesh;
//! - the mass: ρAL, ρ(Iyy + Izz)L about the axis and ρAL³/3 + ρI L about a transverse axis at
//!   I (consistent); ρAL and no rotary inertia (`--mass lumped`);
//! - a free frame through the CLI: six zero frequencies; the internal nodes numbered after the
//!   archive's largest node id, two per element in element order, at 1/3 and 2/3;
//! - KEYOPT(3)=2 and BEAM189 on the same beam: equal to the cubic where both are exact (the end
//!   moment), and converging together with the mesh (frequencies);
//! - `LUMPM,ON` with it refused by line.

use std::collections::HashMap;
use std::f64::consts::PI;

use crate::ansys_support::writers::{eblock, material, nblock, STEEL};
use crate::ansys_support::{assert_refused_at, build_modes, line_of};
use crate::common::{assert_frequencies, scratch};
use faer::linalg::solvers::Solve;
use faer::Mat;
use flexbody::fe::{assemble, AssemblySpec, MassKind};
use flexbody::import::{read_model, ImportOptions};
use flexbody::model::{ElementKind, Model};

/// The orientation node of the archives: the element z axis toward it (global z), y = global y.
const ORIENTATION: u64 = 1000;

/// An archive of `n` BEAM188 (KEYOPT(3)=`keyopt3`) along x over [0, `length`] on `section`
/// (its `SECTYPE`/`SECDATA` lines), steel, nodes 1…n+1 and the orientation node, `extra`
/// lines after the elements.
fn straight(keyopt3: i64, n: u64, length: f64, section: &str, extra: &str) -> String {
    let mut nodes: Vec<(u64, [f64; 3], [f64; 3])> = (0..=n)
        .map(|i| (i + 1, [length * i as f64 / n as f64, 0.0, 0.0], [0.0; 3]))
        .collect();
    nodes.push((ORIENTATION, [0.3 * length, 0.0, 1.0], [0.0; 3]));
    let records: Vec<(usize, usize, Vec<u64>)> = (1..=n)
        .map(|i| (1, 1, vec![i, i + 1, ORIENTATION]))
        .collect();
    format!(
        "/PREP7\nET,1,188\nKEYOPT,1,3,{keyopt3}\n{}{section}{}{}{extra}",
        material(STEEL),
        nblock(&nodes),
        eblock(&records)
    )
}

/// The same beam as BEAM189, its mid nodes (ids 2001…) given at the middles.
fn straight_beam189(n: u64, length: f64, section: &str, extra: &str) -> String {
    let at = |t: f64| [length * t / n as f64, 0.0, 0.0];
    let mut nodes: Vec<(u64, [f64; 3], [f64; 3])> =
        (0..=n).map(|i| (i + 1, at(i as f64), [0.0; 3])).collect();
    nodes.extend((1..=n).map(|i| (2000 + i, at(i as f64 - 0.5), [0.0; 3])));
    nodes.push((ORIENTATION, [0.3 * length, 0.0, 1.0], [0.0; 3]));
    let records: Vec<(usize, usize, Vec<u64>)> = (1..=n)
        .map(|i| (1, 1, vec![i, i + 1, 2000 + i, ORIENTATION]))
        .collect();
    format!(
        "/PREP7\nET,1,189\n{}{section}{}{}{extra}",
        material(STEEL),
        nblock(&nodes),
        eblock(&records)
    )
}

/// The model of `archive`, written as `name` in the scratch folder `folder`.
fn model_of(archive: &str, folder: &str, name: &str) -> Model {
    let path = scratch(folder).join(name);
    std::fs::write(&path, archive).unwrap();
    read_model(&path, &ImportOptions::default()).unwrap()
}

/// The static displacements of `model` held in every dof of node id 1 under `loads` ((node id,
/// component 0…5) → force or moment): (node id, component) → displacement.
fn clamped_response(model: &Model, loads: &[((u64, usize), f64)]) -> HashMap<(u64, usize), f64> {
    let a = assemble(model, &AssemblySpec::default()).unwrap();
    let k = a.k.to_dense();
    let dofs = &a.dofs;
    let free: Vec<(usize, (u64, usize))> = (model.nodes.iter().enumerate())
        .filter(|(_, node)| node.id != 1)
        .flat_map(|(ix, node)| (0..6).filter_map(move |c| Some((dofs.dof(ix, c)?, (node.id, c)))))
        .collect();
    let n = free.len();
    let kf = Mat::from_fn(n, n, |i, j| k[(free[i].0, free[j].0)]);
    let f = Mat::from_fn(n, 1, |i, _| {
        (loads.iter())
            .filter(|(at, _)| *at == free[i].1)
            .map(|(_, v)| v)
            .sum()
    });
    let u = kf.as_ref().partial_piv_lu().solve(&f);
    (free.iter().enumerate())
        .map(|(i, (_, key))| (*key, u[(i, 0)]))
        .collect()
}

/// A RECT section b × h (b along the element y) and its constants: (lines, A, Izz = h b³/12,
/// Iyy = b h³/12, Cowper's k = 10(1+ν)/(12+11ν)).
fn rect(b: f64, h: f64) -> (String, [f64; 4]) {
    let nu = STEEL[1];
    (
        format!("SECTYPE,1,BEAM,RECT\nSECDATA,{b},{h}\n"),
        [
            b * h,
            h * b.powi(3) / 12.0,
            b * h.powi(3) / 12.0,
            10.0 * (1.0 + nu) / (12.0 + 11.0 * nu),
        ],
    )
}

/// One element clamped at I. End load P along y and along z: v(x) = P/(EI)(Lx²/2 − x³/6) +
/// Px/(kGA) with the section rotation P/(EI)(Lx − x²/2) (θz for v; −θy for w); end moment M
/// about z and y: θ = Mx/(EI), deflection Mx²/(2EI) (Timoshenko beam theory; e.g. Timoshenko &
/// Gere, *Mechanics of Materials*, the cantilever with shear). Checked at J and at the two
/// internal nodes (x = L/3, 2L/3), every dof. (Four points would give the same — the exact
/// solution lies in the functions either way; the frequency tests here and the element's unit
/// test pin the three points: with four both fail.)
#[test]
fn beam188_cubic_one_element_cantilever_is_the_timoshenko_beam() {
    let [e, nu, _] = STEEL;
    let g = e / (2.0 * (1.0 + nu));
    let (b, h, length) = (0.02, 0.05, 0.8);
    let (section, [area, izz, iyy, k]) = rect(b, h);
    let model = model_of(
        &straight(3, 1, length, &section, ""),
        "ansys-beam188-cubic-cantilever",
        "one.cdb",
    );
    assert_eq!(model.elements.len(), 1);
    assert_eq!(model.elements[0].kind, ElementKind::Beam4Cubic);
    // node id and x of J and the internal nodes
    let ids = [
        (2, length),
        (1001, length / 3.0),
        (1002, 2.0 * length / 3.0),
    ];
    let (p, m) = (1000.0, 50.0);
    // (load, expected dofs at x: [u, v, w, θx, θy, θz])
    type Field = Box<dyn Fn(f64) -> [f64; 6]>;
    type Load = ((u64, usize), f64);
    let cases: Vec<(Load, Field)> = vec![
        (
            ((2, 1), p),
            Box::new(move |x: f64| {
                let bend = p / (e * izz);
                let v = bend * (length * x * x / 2.0 - x.powi(3) / 6.0) + p * x / (k * g * area);
                [0.0, v, 0.0, 0.0, 0.0, bend * (length * x - x * x / 2.0)]
            }),
        ),
        (
            ((2, 2), p),
            Box::new(move |x: f64| {
                let bend = p / (e * iyy);
                let w = bend * (length * x * x / 2.0 - x.powi(3) / 6.0) + p * x / (k * g * area);
                [0.0, 0.0, w, 0.0, -bend * (length * x - x * x / 2.0), 0.0]
            }),
        ),
        (
            ((2, 5), m),
            Box::new(move |x: f64| {
                let c = m / (e * izz);
                [0.0, c * x * x / 2.0, 0.0, 0.0, 0.0, c * x]
            }),
        ),
        (
            ((2, 4), m),
            Box::new(move |x: f64| {
                let c = m / (e * iyy);
                [0.0, 0.0, -c * x * x / 2.0, 0.0, c * x, 0.0]
            }),
        ),
    ];
    let mut worst = 0.0f64;
    for (load, want) in &cases {
        let u = clamped_response(&model, &[*load]);
        let scale = want(length).iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for &(id, x) in &ids {
            let w = want(x);
            for c in 0..6 {
                worst = worst.max((u[&(id, c)] - w[c]).abs() / scale);
            }
        }
    }
    println!("BEAM188 KEYOPT(3)=3, one element: worst {worst:.1e} of the largest dof");
    // measured 6.1e-13 (the solve's rounding)
    assert!(worst < 1e-11, "{worst:e}");
}

/// The clamped-free Timoshenko beam's angular frequencies (the first `count`), the roots of
/// its frequency equation: w = Σ A_k f_k with f = cosh αx, sinh αx, cos βx, sin βx, the
/// section rotation ψ from kGA(w″ − ψ′) + ρAω²w = 0, α² and −β² the roots s of
/// kGA·EI s² + (kGA ρI + ρA EI)ω² s + ρAω²(ρIω² − kGA) = 0 (the second equation,
/// EIψ″ + kGA(w′ − ψ) + ρIω²ψ = 0, holding for them); held: w(0) = ψ(0) = 0, free: ψ′(L) = 0,
/// w′(L) − ψ(L) = 0 (Timoshenko, *Vibration Problems in Engineering*, §5.12's equations; the
/// determinant's sign changes, bisected). Below the cutoff ω² < kGA/(ρI).
fn timoshenko_clamped_free(l: f64, [ei, kga, ra, ri]: [f64; 4], count: usize) -> Vec<f64> {
    let det = |w: f64| {
        let w2 = w * w;
        let (qa, qb, qc) = (
            kga * ei,
            (kga * ri + ra * ei) * w2,
            ra * w2 * (ri * w2 - kga),
        );
        let root = (qb * qb - 4.0 * qa * qc).sqrt();
        let (alpha, beta) = (
            ((root - qb) / (2.0 * qa)).sqrt(),
            ((qb + root) / (2.0 * qa)).sqrt(),
        );
        let p = (kga * alpha * alpha + ra * w2) / (kga * alpha);
        let r = (ra * w2 - kga * beta * beta) / (kga * beta);
        let (ch, sh) = ((alpha * l).cosh(), (alpha * l).sinh());
        let (cs, sn) = ((beta * l).cos(), (beta * l).sin());
        // rows: w(0), ψ(0), ψ′(L), w′(L) − ψ(L); columns: cosh, sinh, cos, sin
        let a = [
            [1.0, 0.0, 1.0, 0.0],
            [0.0, p, 0.0, -r],
            [p * alpha * ch, p * alpha * sh, r * beta * cs, r * beta * sn],
            [
                (alpha - p) * sh,
                (alpha - p) * ch,
                -(beta + r) * sn,
                (beta + r) * cs,
            ],
        ];
        let m = Mat::from_fn(4, 4, |i, j| a[i][j] / ch.max(1.0));
        m.determinant()
    };
    let cutoff = (kga / ri).sqrt();
    // steps of a fiftieth of the Euler–Bernoulli beam's first root (the roots lie further apart)
    let step = 3.5 * (ei / ra).sqrt() / (l * l) / 50.0;
    let (mut out, mut w) = (vec![], step / 10.0);
    let mut last = det(w);
    while out.len() < count && w < cutoff {
        let next = w + step;
        let d = det(next);
        if d.signum() != last.signum() {
            let (mut lo, mut hi) = (w, next);
            for _ in 0..100 {
                let mid = (lo + hi) / 2.0;
                if det(mid).signum() == last.signum() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            out.push((lo + hi) / 2.0);
        }
        (w, last) = (next, d);
    }
    assert_eq!(out.len(), count, "{count} roots below the cutoff");
    out
}

/// The section of the frequency tests: ASEC (the user's constants, shear factor 1) of a 0.04 ×
/// 0.06 rectangle with J = 4e-7: (lines, [A, Izz, Iyy, J]).
fn asec() -> (String, [f64; 4]) {
    let (b, h, j) = (0.04f64, 0.06f64, 4.0e-7);
    let (a, izz, iyy) = (b * h, h * b.powi(3) / 12.0, b * h.powi(3) / 12.0);
    (
        format!("SECTYPE,1,BEAM,ASEC\nSECDATA,{a},{iyy},0,{izz},0,{j}\n"),
        [a, izz, iyy, j],
    )
}

/// The clamped-free beam's lowest `count` frequencies (Hz) in closed form, sorted: bending in
/// both planes (Timoshenko, shear factor 1, rotary inertia), extension and torsion (polar
/// inertia ρ(Iyy + Izz)): ω = (2m − 1)π/(2L)·√(stiffness/inertia).
fn clamped_free_hz(length: f64, [a, izz, iyy, j]: [f64; 4], count: usize) -> Vec<f64> {
    let [e, nu, rho] = STEEL;
    let g = e / (2.0 * (1.0 + nu));
    let mut want = vec![];
    for i in [izz, iyy] {
        // six per plane: more than the lowest `count` (≤ 12) hold
        want.extend(timoshenko_clamped_free(
            length,
            [e * i, g * a, rho * a, rho * i],
            6,
        ));
    }
    for m in 1..=count {
        let c = (2 * m - 1) as f64 * PI / (2.0 * length);
        want.push(c * (e / rho).sqrt());
        want.push(c * (g * j / (rho * (iyy + izz))).sqrt());
    }
    let mut hz: Vec<f64> = want.iter().map(|w| w / (2.0 * PI)).collect();
    hz.sort_by(f64::total_cmp);
    hz.truncate(count);
    hz
}

/// A clamped-free beam (L = 1, ASEC of a 0.04 × 0.06 rectangle: L/h ≈ 17, so shear and rotary
/// inertia count) of n = 4, 8, 16 cubic elements through the CLI: the 12 lowest frequencies
/// (33.4 to 1805 Hz: bending in both planes — five in the weak one, four in the strong —, the
/// first extension and the first two torsion modes) converge to the closed forms, the worst
/// difference (the highest bending mode's) falling about 2⁶ per halving: the cubic element's
/// O(h⁶) eigenvalue error.
#[test]
fn beam188_cubic_clamped_free_frequencies_converge_to_the_closed_forms() {
    // the frequency equation's Euler–Bernoulli limit (shear rigid, no rotary inertia): the
    // clamped-free roots (βL)² = 1.875104², 4.694091², 7.854757² (Blevins, *Formulas for
    // Natural Frequency and Mode Shape*, Table 8-1), ω = (βL)²√(EI/ρA)/L²
    let eb = timoshenko_clamped_free(2.0, [3.0, 1e9, 5.0, 1e-12], 3);
    for (w, bl) in eb.iter().zip([1.875_104_07f64, 4.694_091_13, 7.854_757_44]) {
        let want = bl * bl * (3.0f64 / 5.0).sqrt() / 4.0;
        assert!((w / want - 1.0).abs() < 1e-7, "{w} {want}");
    }
    let (section, constants) = asec();
    let length = 1.0;
    let want = clamped_free_hz(length, constants, 12);
    let dir = scratch("ansys-beam188-cubic-frequencies");
    let mut worst = vec![];
    for n in [4u64, 8, 16] {
        let path = dir.join(format!("clamped{n}.cdb"));
        std::fs::write(&path, straight(3, n, length, &section, "D,1,ALL,0\n")).unwrap();
        let ours = build_modes(&path, 12, &[]);
        let rel = (ours.iter().zip(&want))
            .map(|(a, b)| (a / b - 1.0).abs())
            .fold(0.0, f64::max);
        println!(
            "BEAM188 KEYOPT(3)=3, {n} elements: worst {rel:.2e}\n  ours {ours:?}\n  want {want:?}"
        );
        worst.push(rel);
    }
    // measured: 4 elements 2.09e-2, 8: 3.53e-4, 16: 6.06e-6 (ratios 59 and 58)
    assert!(
        worst[0] < 3e-2 && worst[1] < 5e-4 && worst[2] < 1e-5,
        "{worst:?}"
    );
    assert!(
        worst[1] < worst[0] / 40.0 && worst[2] < worst[1] / 40.0,
        "{worst:?}"
    );
}

/// Three cubic elements along x over [0, L] (RECT 0.02 × 0.05): the consistent mass gives ρAL
/// to a translation, ρ(Iyy + Izz)L to the rotation about the axis, ρAL³/3 + ρIzz L to the
/// rotation about z through I (the cubic functions hold the linear motion; four points
/// integrate it exactly); the lumped mass (`--mass lumped`'s, the HRZ diagonal) ρAL and none
/// to the rotation about the axis.
#[test]
fn beam188_cubic_mass_is_rho_a_l_with_the_rotary_inertia() {
    let rho = STEEL[2];
    let (section, [area, izz, iyy, _]) = rect(0.02, 0.05);
    let length = 0.9;
    let model = model_of(
        &straight(3, 3, length, &section, ""),
        "ansys-beam188-cubic-mass",
        "mass.cdb",
    );
    let mut worst = 0.0f64;
    for mass in [MassKind::Consistent, MassKind::Lumped] {
        let a = assemble(
            &model,
            &AssemblySpec {
                mass,
                ..AssemblySpec::default()
            },
        )
        .unwrap();
        let m = a.m.to_dense();
        let nd = m.nrows();
        let motion = |f: &dyn Fn([f64; 3]) -> [f64; 6]| {
            let mut u = vec![0.0; nd];
            for (ix, node) in model.nodes.iter().enumerate() {
                for (c, v) in f(node.x).into_iter().enumerate() {
                    if let Some(d) = a.dofs.dof(ix, c) {
                        u[d] = v;
                    }
                }
            }
            (0..nd)
                .map(|i| u[i] * (0..nd).map(|j| m[(i, j)] * u[j]).sum::<f64>())
                .sum::<f64>()
        };
        let translation = motion(&|_| [0.0, 1.0, 0.0, 0.0, 0.0, 0.0]);
        let about_axis = motion(&|_| [0.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
        let about_z = motion(&|x| [0.0, x[0], 0.0, 0.0, 0.0, 1.0]);
        let total = rho * area * length;
        worst = worst.max((translation / total - 1.0).abs());
        match mass {
            MassKind::Consistent => {
                let axis = rho * (iyy + izz) * length;
                let z = rho * area * length.powi(3) / 3.0 + rho * izz * length;
                worst = worst.max((about_axis / axis - 1.0).abs());
                worst = worst.max((about_z / z - 1.0).abs());
            }
            MassKind::Lumped => assert_eq!(about_axis, 0.0),
        }
        println!("{mass:?}: {translation} vs ρAL {total}; about the axis {about_axis}; about z {about_z}");
    }
    println!("mass: worst {worst:.1e}");
    // measured 2.2e-16
    assert!(worst < 1e-13, "{worst:e}");
}

/// A free frame of three cubic elements bent in space (RECT 0.02 × 0.05, each its orientation
/// node) through the CLI: six zero frequencies first (measured ≤ 6.3e-5 Hz against the first
/// flexible one's 48.8 Hz), and the internal nodes as the importer makes them: ids after the
/// archive's largest (1000), two per element in element order, at 1/3 and 2/3 of IJ; the
/// body's graphics lines I–K, K–L, L–J through them.
#[test]
fn beam188_cubic_free_frame_has_six_rigid_modes() {
    let corners = [
        [0.0, 0.0, 0.0],
        [0.4, 0.1, 0.2],
        [0.7, 0.5, 0.1],
        [0.9, 0.6, 0.6],
    ];
    let mut nodes: Vec<(u64, [f64; 3], [f64; 3])> = (corners.iter().enumerate())
        .map(|(i, x)| (i as u64 + 1, *x, [0.0; 3]))
        .collect();
    nodes.push((ORIENTATION, [0.2, 0.9, -0.4], [0.0; 3]));
    let records: Vec<(usize, usize, Vec<u64>)> = (1..=3)
        .map(|i| (1, 1, vec![i, i + 1, ORIENTATION]))
        .collect();
    let (section, _) = rect(0.02, 0.05);
    let archive = format!(
        "/PREP7\nET,1,BEAM188\nKEYOPT,1,3,3\n{}{section}{}{}",
        material(STEEL),
        nblock(&nodes),
        eblock(&records)
    );
    let path = scratch("ansys-beam188-cubic-free").join("frame.cdb");
    std::fs::write(&path, &archive).unwrap();
    let model = read_model(&path, &ImportOptions::default()).unwrap();
    let mut placed = 0.0f64;
    for (e, el) in model.elements.iter().enumerate() {
        assert_eq!(el.kind, ElementKind::Beam4Cubic);
        let [xi, xj] = [corners[e], corners[e + 1]];
        for (q, t) in [1.0 / 3.0, 2.0 / 3.0].into_iter().enumerate() {
            let node = &model.nodes[el.nodes[2 + q]];
            assert_eq!(node.id, 1001 + 2 * e as u64 + q as u64, "element {}", el.id);
            let want: [f64; 3] = std::array::from_fn(|c| xi[c] + t * (xj[c] - xi[c]));
            placed = placed.max(
                (0..3)
                    .map(|c| (node.x[c] - want[c]).abs())
                    .fold(0.0, f64::max),
            );
        }
    }
    assert!(placed < 1e-15, "{placed:e}");
    let ours = build_modes(&path, 10, &[]);
    println!("free frame: {ours:?}");
    assert!(ours[5] < 1e-5 * ours[6], "six rigid modes first: {ours:?}");
    assert!(ours[6] > 1.0, "{ours:?}");
    // the body draws each element as three segments I–K–L–J through its internal nodes
    let body = flexbody_reader::read(path.with_extension("flexbody")).unwrap();
    let id = |k: u32| body.nodes[k as usize].id;
    let mut lines: Vec<[u64; 2]> = (body.lines.as_ref().expect("lines.bin").iter())
        .map(|&[a, b]| [id(a).min(id(b)), id(a).max(id(b))])
        .collect();
    lines.sort();
    let mut want: Vec<[u64; 2]> = (0..3u64)
        .flat_map(|e| {
            let (i, j, k, l) = (e + 1, e + 2, 1001 + 2 * e, 1002 + 2 * e);
            [[i, k], [k.min(l), k.max(l)], [j.min(l), j.max(l)]]
        })
        .collect();
    want.sort();
    assert_eq!(lines, want);
}

/// KEYOPT(3)=3 against KEYOPT(3)=2 and BEAM189 on the same beam (the ASEC section of the
/// frequency test, clamped at x = 0):
/// - an end moment: the quadratic element holds its exact solution too (θ linear, w
///   quadratic, no shear), so one element of each gives ML²/(2EI) and ML/(EI) at J alike;
/// - the 12 lowest frequencies through the CLI with n = 4, 8, 16, 32 elements: KEYOPT(3)=2
///   equals BEAM189 (its mid nodes given) to the last bit, the cubic is closer to the closed
///   forms than the quadratic on every mesh, and the two approach each other as the mesh is
///   refined — the quadratic's error falling toward 2⁴ per halving, the cubic's 2⁶.
#[test]
fn beam188_cubic_agrees_with_quadratic_and_beam189_in_the_limit() {
    let (section, constants) = asec();
    let [_, izz, ..] = constants;
    let e = STEEL[0];
    let length = 1.0;
    let m = 50.0;
    let mut tips = vec![];
    for keyopt3 in [2, 3] {
        let model = model_of(
            &straight(keyopt3, 1, length, &section, ""),
            "ansys-beam188-cubic-limit",
            &format!("moment{keyopt3}.cdb"),
        );
        let u = clamped_response(&model, &[((2, 5), m)]);
        tips.push([u[&(2, 1)], u[&(2, 5)]]);
    }
    let want = [
        m * length * length / (2.0 * e * izz),
        m * length / (e * izz),
    ];
    let moment = (tips.iter().flatten().zip(want.iter().cycle()))
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0, f64::max);
    println!("end moment: {tips:?} vs {want:?}: {moment:.1e}");
    // measured 3.2e-13 (the solve's rounding)
    assert!(moment < 1e-11, "{moment:e}");

    let closed = clamped_free_hz(length, constants, 12);
    let dir = scratch("ansys-beam188-cubic-limit");
    let mut rows = vec![];
    for n in [4u64, 8, 16, 32] {
        let mut hz = vec![];
        for (name, text) in [
            ("cubic", straight(3, n, length, &section, "D,1,ALL,0\n")),
            ("quadratic", straight(2, n, length, &section, "D,1,ALL,0\n")),
            (
                "beam189",
                straight_beam189(n, length, &section, "D,1,ALL,0\n"),
            ),
        ] {
            let path = dir.join(format!("{name}{n}.cdb"));
            std::fs::write(&path, text).unwrap();
            hz.push(build_modes(&path, 12, &[]));
        }
        let same = assert_frequencies("KEYOPT(3)=2 vs BEAM189", &hz[1], &hz[2], 0, 1e-12);
        let worst = |a: &[f64], b: &[f64]| {
            (a.iter().zip(b))
                .map(|(x, y)| (x / y - 1.0).abs())
                .fold(0.0, f64::max)
        };
        let row = [
            worst(&hz[0], &hz[1]),
            worst(&hz[0], &closed),
            worst(&hz[1], &closed),
        ];
        println!(
            "{n} elements: cubic vs quadratic {:.2e}, cubic vs closed {:.2e}, quadratic vs \
             closed {:.2e}; quadratic vs BEAM189 {same:.1e}",
            row[0], row[1], row[2]
        );
        rows.push(row);
    }
    // the cubic is the closer at each mesh, and the two meet as the mesh is refined
    for row in &rows {
        assert!(row[1] < row[2], "{rows:?}");
    }
    for pair in rows.windows(2) {
        assert!(pair[1][0] < pair[0][0] / 6.0, "{rows:?}");
    }
    // measured: cubic vs quadratic 1.29e-1, 1.63e-2, 1.13e-3, 7.31e-5 (the cubic against the
    // closed forms 2.09e-2, 3.53e-4, 6.06e-6, 9.68e-8; the quadratic 1.72e-1, 1.69e-2, 1.14e-3,
    // 7.32e-5)
    assert!(rows[3][0] < 1e-4, "{rows:?}");
}

/// `LUMPM,ON` with a KEYOPT(3)=3 beam is refused at its line, as with KEYOPT(3)=2 and BEAM189
/// (ANSYS's lumping of the cubic functions' mass is not established).
#[test]
fn beam188_cubic_lumped_mass_is_refused_by_line() {
    let (section, _) = rect(0.02, 0.05);
    let archive = straight(3, 2, 1.0, &section, "LUMPM,ON\n");
    let line = line_of(&archive, "LUMPM");
    assert_refused_at(
        &archive,
        "ansys-beam188-cubic-lumpm",
        "si",
        &[(line, "LUMPM,ON with BEAM189 or BEAM188 KEYOPT(3)=2 or 3")],
    );
}
