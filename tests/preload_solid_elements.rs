//! The solid elements' initial stress and geometric stiffness, element by element, for every
//! solid kind (tet4, tet10, hex8, hex8 with incompatible modes, hex20, hex20R, prism6, prism6
//! with incompatible modes) on distorted (curved-edge) elements:
//!
//! * K_G against a central finite difference of the internal force of the prestressed
//!   St. Venant–Kirchhoff element, f(u) = Σ_p w_p (I + H) S ∇N, S = S₀ + D : E(u), with the
//!   Green–Lagrange strain E = ½(H + Hᵀ + HᵀH) and S₀ the element's own stress at its
//!   integration points: [f(εv) − f(−εv)]/(2ε) = (K + K_G) v + O(ε²). (The expansion point is the
//!   stressed reference state: about u₀ itself the initial-displacement stiffness, of the same
//!   order as K_G, would enter as well.) The incompatible modes follow u by the element's
//!   linear recovery α = R u, and the force is condensed as f_c + Rᵀ f_i.
//! * Stress of a linear displacement field with a thermal strain: Hooke's law D(ε − αΔT I).
//! * A free thermal expansion u = αΔT x is balanced exactly by the thermal load: K u = f_th.
//! * The incompatible hex8 under pure bending: K_G's energy is the closed form.

use flexbody::fe::elements::{
    hex20, hex8, prism6, solid_incompatible, tet10, tet4, Isotropic, Xyz,
};
use flexbody::fe::geometric::{SolidElement, Stress};
use flexbody::model::ElementKind;

fn mat() -> Isotropic {
    Isotropic::new(200e9, 0.3, 7800.0)
}

/// The element kinds with their reference nodes, incompatible flag and linear stiffness.
struct Variant {
    name: &'static str,
    kind: ElementKind,
    incompatible: bool,
    reference: Vec<Xyz>,
}

fn variants() -> Vec<Variant> {
    let v = |name, kind, incompatible, reference: &[Xyz]| Variant {
        name,
        kind,
        incompatible,
        reference: reference.to_vec(),
    };
    vec![
        v("tet4", ElementKind::Tet4, false, &tet4::NODES),
        v("tet10", ElementKind::Tet10, false, &tet10::NODES),
        v("hex8", ElementKind::Hex8, false, &hex8::NODES),
        v("hex8 incompatible", ElementKind::Hex8, true, &hex8::NODES),
        v("hex20", ElementKind::Hex20, false, &hex20::NODES),
        v("hex20R", ElementKind::Hex20R, false, &hex20::NODES),
        v("prism6", ElementKind::Prism6, false, &prism6::NODES),
        v(
            "prism6 incompatible",
            ElementKind::Prism6,
            true,
            &prism6::NODES,
        ),
    ]
}

/// A distorted image of the reference nodes (curved edges for the quadratic elements).
fn distort(r: &[Xyz]) -> Vec<Xyz> {
    r.iter()
        .map(|p| {
            [
                1.0 + 0.6 * p[0] + 0.1 * p[1] + 0.03 * p[0] * p[1],
                0.5 * p[1] + 0.05 * p[2] - 0.02 * p[0] * p[0],
                0.4 * p[2] + 0.07 * p[0] + 0.02 * p[1] * p[2],
            ]
        })
        .collect()
}

fn stiffness(v: &Variant, x: &[Xyz]) -> Vec<f64> {
    let m = mat();
    let arr = |n: usize| -> Vec<Xyz> { x[..n].to_vec() };
    match (v.kind, v.incompatible) {
        (ElementKind::Tet4, _) => tet4::stiffness(&arr(4).try_into().unwrap(), &m),
        (ElementKind::Tet10, _) => tet10::stiffness(&arr(10).try_into().unwrap(), &m),
        (ElementKind::Hex8, false) => hex8::stiffness(&arr(8).try_into().unwrap(), &m),
        (ElementKind::Hex8, true) => {
            solid_incompatible::hex8_stiffness(&arr(8).try_into().unwrap(), &m)
        }
        (ElementKind::Hex20, _) => hex20::stiffness(&arr(20).try_into().unwrap(), &m, false),
        (ElementKind::Hex20R, _) => hex20::stiffness(&arr(20).try_into().unwrap(), &m, true),
        (ElementKind::Prism6, false) => prism6::stiffness(&arr(6).try_into().unwrap(), &m),
        (ElementKind::Prism6, true) => {
            solid_incompatible::prism6_stiffness(&arr(6).try_into().unwrap(), &m)
        }
        (k, _) => panic!("{k:?}"),
    }
    .unwrap()
}

fn mat_vec(k: &[f64], v: &[f64]) -> Vec<f64> {
    let n = v.len();
    (0..n)
        .map(|i| (0..n).map(|j| k[i * n + j] * v[j]).sum())
        .collect()
}

/// The prestressed St. Venant–Kirchhoff internal force (module doc), condensed.
fn internal_force(el: &SolidElement, s0: &[Stress], u: &[f64]) -> Vec<f64> {
    let m = mat();
    let (lam, mu) = m.lame();
    let nc = u.len();
    let mut amp = u.to_vec();
    if let Some(r) = el.recovery() {
        let ni = r.len() / nc;
        amp.extend((0..ni).map(|k| (0..nc).map(|j| r[k * nc + j] * u[j]).sum::<f64>()));
    }
    let mut f = vec![0.0; amp.len()];
    for (pt, s0) in el.points().iter().zip(s0) {
        let mut h = [[0.0; 3]; 3];
        for (a, g) in pt.grads.iter().enumerate() {
            for i in 0..3 {
                for j in 0..3 {
                    h[i][j] += amp[3 * a + i] * g[j];
                }
            }
        }
        let e: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                0.5 * (h[i][j] + h[j][i] + (0..3).map(|k| h[k][i] * h[k][j]).sum::<f64>())
            })
        });
        let tr = e[0][0] + e[1][1] + e[2][2];
        let s0m = [
            [s0[0], s0[3], s0[5]],
            [s0[3], s0[1], s0[4]],
            [s0[5], s0[4], s0[2]],
        ];
        let s: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                s0m[i][j] + 2.0 * mu * e[i][j] + if i == j { lam * tr } else { 0.0 }
            })
        });
        // first Piola P = F S, F = I + H
        let p: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                (0..3)
                    .map(|k| (if i == k { 1.0 } else { 0.0 } + h[i][k]) * s[k][j])
                    .sum::<f64>()
            })
        });
        for (a, g) in pt.grads.iter().enumerate() {
            for i in 0..3 {
                f[3 * a + i] += pt.w * (0..3).map(|j| p[i][j] * g[j]).sum::<f64>();
            }
        }
    }
    let mut out = f[..nc].to_vec();
    if let Some(r) = el.recovery() {
        for (k, fi) in f[nc..].iter().enumerate() {
            for j in 0..nc {
                out[j] += r[k * nc + j] * fi;
            }
        }
    }
    out
}

/// A smooth, non-polynomial initial displacement (strains of order 1e-3) and a non-uniform
/// temperature: the stress varies over the element.
fn initial_state(x: &[Xyz]) -> (Vec<f64>, Vec<f64>) {
    let u = x
        .iter()
        .flat_map(|p| {
            [
                1e-3 * (p[0] * p[0] + 0.3 * p[1] * p[2]),
                -1e-3 * (p[1] + 0.5 * (2.0 * p[0]).sin()),
                8e-4 * (p[2] * p[0] - p[1] * p[1]),
            ]
        })
        .collect();
    let theta = x.iter().map(|p| 5e-4 * (1.0 + p[0] - p[2])).collect();
    (u, theta)
}

#[test]
fn solid_kg_matches_finite_difference_of_green_lagrange_internal_force() {
    for v in variants() {
        let x = distort(&v.reference);
        let el = SolidElement::new(v.kind, &x, mat(), v.incompatible).unwrap();
        let (u0, theta) = initial_state(&x);
        let s0 = el.stresses(&u0, &theta).unwrap();
        let kg = el.geometric_stiffness(&s0);
        let k = stiffness(&v, &x);
        let nd = 3 * x.len();
        let dir: Vec<f64> = (0..nd)
            .map(|i| ((i as f64) * 0.7).sin() + 0.3 * ((i as f64) * 1.3).cos())
            .collect();
        let eps = 1e-6;
        let plus: Vec<f64> = dir.iter().map(|d| eps * d).collect();
        let minus: Vec<f64> = dir.iter().map(|d| -eps * d).collect();
        let (fp, fm) = (
            internal_force(&el, &s0, &plus),
            internal_force(&el, &s0, &minus),
        );
        let kv = mat_vec(&k, &dir);
        let kgv = mat_vec(&kg, &dir);
        let norm = |a: &[f64]| a.iter().map(|v| v * v).sum::<f64>().sqrt();
        let fd: Vec<f64> = (0..nd)
            .map(|i| (fp[i] - fm[i]) / (2.0 * eps) - kv[i])
            .collect();
        let diff: Vec<f64> = fd.iter().zip(&kgv).map(|(a, b)| a - b).collect();
        let rel = norm(&diff) / norm(&kgv);
        eprintln!(
            "{}: ‖K_G v − FD‖/‖K_G v‖ = {rel:.2e} (‖K_G v‖/‖K v‖ = {:.1e})",
            v.name,
            norm(&kgv) / norm(&kv)
        );
        assert!(rel < 1e-6, "{}: {rel}", v.name);
        // symmetric
        for i in 0..nd {
            for j in 0..i {
                assert!((kg[i * nd + j] - kg[j * nd + i]).abs() <= 1e-12 * norm(&kg));
            }
        }
    }
}

#[test]
fn solid_stress_of_a_linear_field_is_hookes_law_and_free_expansion_is_balanced() {
    let m = mat();
    let (lam, mu) = m.lame();
    let grad = [[1e-3, 2e-4, -3e-4], [5e-4, -2e-3, 1e-4], [0.0, 7e-4, 4e-4]];
    let th = 3e-4;
    let eps = [
        grad[0][0],
        grad[1][1],
        grad[2][2],
        0.5 * (grad[0][1] + grad[1][0]),
        0.5 * (grad[1][2] + grad[2][1]),
        0.5 * (grad[0][2] + grad[2][0]),
    ];
    let tr = eps[0] + eps[1] + eps[2];
    let want: [f64; 6] = std::array::from_fn(|c| {
        if c < 3 {
            lam * tr + 2.0 * mu * eps[c] - (3.0 * lam + 2.0 * mu) * th
        } else {
            2.0 * mu * eps[c]
        }
    });
    for v in variants() {
        let x = distort(&v.reference);
        let el = SolidElement::new(v.kind, &x, m, v.incompatible).unwrap();
        let u: Vec<f64> = x
            .iter()
            .flat_map(|p| (0..3).map(move |i| (0..3).map(|j| grad[i][j] * p[j]).sum::<f64>()))
            .collect();
        let theta = vec![th; x.len()];
        for s in el.stresses(&u, &theta).unwrap() {
            for c in 0..6 {
                assert!(
                    (s[c] - want[c]).abs() < 1e-9 * m.e * 1e-3,
                    "{}: {s:?} vs {want:?}",
                    v.name
                );
            }
        }
        // K (θ x) = f_th: the free expansion is stress free and in equilibrium
        let free: Vec<f64> = x.iter().flat_map(|p| p.map(|c| th * c)).collect();
        let ku = mat_vec(&stiffness(&v, &x), &free);
        let fth = el.thermal_load(&theta);
        let scale = fth.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for (a, b) in ku.iter().zip(&fth) {
            assert!((a - b).abs() < 1e-9 * scale, "{}: {a} vs {b}", v.name);
        }
    }
}

/// A rectangular hex8 [0, L] × [−b/2, b/2] × [−h/2, h/2] in pure bending u = κxz,
/// w = −κx²/2 under a uniform σ_xx: with incompatible modes the displacement gradient is the
/// exact one (∂u/∂x = κz, ∂w/∂x = −κx), so vᵀK_Gv = σ ∫ (κ²z² + κ²x²) dV
/// = σκ² (L b h³/12 + b h L³/3); the compatible element's bilinear w has the secant slope only.
#[test]
fn incompatible_hex8_kg_is_exact_in_pure_bending() {
    let (l, b, h) = (4.0, 1.0, 0.5);
    let m = Isotropic::new(1000.0, 0.0, 1.0);
    let x: Vec<Xyz> = hex8::NODES
        .iter()
        .map(|r| [0.5 * l * (1.0 + r[0]), 0.5 * b * r[1], 0.5 * h * r[2]])
        .collect();
    let kap = 0.01;
    let v: Vec<f64> = x
        .iter()
        .flat_map(|p| [kap * p[0] * p[2], 0.0, -0.5 * kap * p[0] * p[0]])
        .collect();
    let sigma = 3.0;
    let want = sigma * kap * kap * (l * b * h.powi(3) / 12.0 + b * h * l.powi(3) / 3.0);
    for incompatible in [true, false] {
        let el = SolidElement::new(ElementKind::Hex8, &x, m, incompatible).unwrap();
        let s = vec![[sigma, 0.0, 0.0, 0.0, 0.0, 0.0]; el.points().len()];
        let kg = el.geometric_stiffness(&s);
        let e: f64 = v.iter().zip(mat_vec(&kg, &v)).map(|(a, b)| a * b).sum();
        eprintln!("hex8 incompatible = {incompatible}: vᵀK_Gv = {e:.6e}, closed form {want:.6e}");
        if incompatible {
            assert!((e - want).abs() < 1e-10 * want, "{e} vs {want}");
        } else {
            assert!((e - want).abs() > 0.1 * want);
        }
    }
}
