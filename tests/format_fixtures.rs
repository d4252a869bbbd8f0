//! The fixture generator's output is what is on disk (regenerate with
//! `FLEXBODY_REGEN_FIXTURES=1 cargo test --release --test integration format_fixtures::`), and the golden bodies are
//! physically what they claim: closed-form frequencies, K-orthogonal and mass-orthonormal
//! modes, invariants consistent with the nodal masses.

use crate::format_support::*;

#[test]
fn fixtures_on_disk_equal_regenerated_bytes() {
    let dir = fixtures_dir();
    let files = generate_all();
    if std::env::var_os("FLEXBODY_REGEN_FIXTURES").is_some() {
        for (rel, bytes) in &files {
            let path = dir.join(rel);
            std::fs::create_dir_all(path.parent().expect("has parent")).expect("mkdir");
            std::fs::write(&path, bytes).expect("write fixture");
        }
    }
    // Generating twice gives identical bytes (determinism of writer and generator).
    assert!(
        files == generate_all(),
        "fixture generation is not deterministic"
    );
    for (rel, bytes) in &files {
        let on_disk = std::fs::read(dir.join(rel))
            .unwrap_or_else(|e| panic!("fixtures/{rel}: {e}; run with FLEXBODY_REGEN_FIXTURES=1"));
        assert!(
            &on_disk == bytes,
            "fixtures/{rel} differs from the generator's output"
        );
    }
    assert!(
        files
            .iter()
            .filter(|(r, _)| r.starts_with("broken/") && r.ends_with(".flexbody"))
            .count()
            >= 12
    );
}

#[test]
fn three_node_chain_matches_closed_form() {
    let b = body_3node();
    // ω² = 0, k/m, 3k/m for three equal masses on two equal springs.
    assert_eq!(b.modes.omega2, vec![0.0, 400.0, 1200.0]);
    assert!(
        (b.modes.frequency_hz[2] - 1200f64.sqrt() / (2.0 * std::f64::consts::PI)).abs() < 1e-12
    );
    // Hand-computed inertia about the origin for masses 2 kg at (0,0,0), (1,0.5,0), (2,0,0)
    // plus 0.01 kg·m² rotary inertia per node: Ixx = 2·0.25 + 0.03, Iyy = 2·(1+4) + 0.03,
    // Izz = 2·(1.25+4) + 0.03, Ixy = −2·1·0.5.
    let i7 = &b.invariants.i7;
    let hand = [0.53, -1.0, 0.0, -1.0, 10.03, 0.0, 0.0, 0.0, 10.53];
    for k in 0..9 {
        assert!(
            (i7[k] - hand[k]).abs() < 1e-12,
            "I7[{k}] = {} vs {}",
            i7[k],
            hand[k]
        );
    }
    assert_eq!(b.invariants.i1, vec![6.0]);
    assert_eq!(b.invariants.i2, vec![6.0, 1.0, 0.0]);
}

fn check_orthogonality(b: &flexbody_reader::ReducedBody, k_dof: &[Vec<f64>], dofs_per_node: usize) {
    let (n, m) = (b.node_count(), b.mode_count());
    let phi =
        |j: usize, d: usize| b.modes.shapes[(j * n + d / dofs_per_node) * 6 + d % dofs_per_node];
    for i in 0..m {
        for j in 0..m {
            let mass: f64 = (0..n * dofs_per_node)
                .map(|d| phi(i, d) * b.nodal_mass[d / dofs_per_node].mass * phi(j, d))
                .sum();
            let stiff: f64 = (0..n * dofs_per_node)
                .map(|d| {
                    phi(i, d)
                        * (0..n * dofs_per_node)
                            .map(|e| k_dof[d][e] * phi(j, e))
                            .sum::<f64>()
                })
                .sum();
            let (want_m, want_k) = if i == j {
                (1.0, b.modes.omega2[i])
            } else {
                (0.0, 0.0)
            };
            assert!((mass - want_m).abs() < 1e-10, "phi_{i}' M phi_{j} = {mass}");
            let scale = b.modes.omega2.iter().fold(1.0f64, |a, w| a.max(*w));
            assert!(
                (stiff - want_k).abs() < 1e-9 * scale,
                "phi_{i}' K phi_{j} = {stiff} vs {want_k}"
            );
        }
    }
}

#[test]
fn golden_modes_are_mass_orthonormal_and_k_orthogonal() {
    let k3 = vec![
        vec![K3, -K3, 0.0],
        vec![-K3, 2.0 * K3, -K3],
        vec![0.0, -K3, K3],
    ];
    check_orthogonality(&body_3node(), &k3, 1);
    check_orthogonality(&body_20node(), &stiffness20(), 2);
}

#[test]
fn twenty_node_invariants_follow_from_masses_and_modes() {
    let b = body_20node();
    let (n, m) = (b.node_count(), b.mode_count());
    let inv = &b.invariants;
    let total: f64 = (0..n).map(mass20).sum();
    assert!((inv.i1[0] - total).abs() < 1e-15);
    // Lumped mass and no rotational shape components: I6 = Φᵀ M Φ = identity.
    for j in 0..m {
        for k in 0..m {
            let want = if j == k { 1.0 } else { 0.0 };
            assert!(
                (inv.i6[j * m + k] - want).abs() < 1e-10,
                "I6[{j}][{k}] = {}",
                inv.i6[j * m + k]
            );
        }
    }
    // Elastic modes are M-orthogonal to rigid translations: their I3 columns vanish.
    for j in 0..m {
        if b.modes.labels[j] == flexbody_reader::ModeLabel::Normal {
            for a in 0..3 {
                assert!(
                    inv.i3[a * m + j].abs() < 1e-10,
                    "I3[{a}][{j}] = {}",
                    inv.i3[a * m + j]
                );
            }
        }
    }
    assert_eq!(
        b.modes
            .labels
            .iter()
            .filter(|l| **l == flexbody_reader::ModeLabel::Rigid)
            .count(),
        2
    );
    assert!(
        inv.i5.is_empty() && inv.i9.is_empty(),
        "Partial set stores no I5, I9"
    );
}
