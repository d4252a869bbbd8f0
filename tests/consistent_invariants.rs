//! Issue 16, consistent-mass invariants: with `--mass consistent` all nine invariants come from the
//! consistent M the modes are orthonormal in (SPEC §5.6), so I6 = ΦᵀMΦ = I, and I1, I2, I7 are
//! the rigid-body projections of that M. On the straight-edged tet10 block of
//! fixtures/reference/b_block_tet10 (0.5 × 0.05 × 0.05 m steel, ρ = 7850 kg/m³) those
//! projections are the box's exact mass, first moment and inertia tensor: the isoparametric
//! integrands are polynomials of degree ≤ 2 on straight tets, which the 4-point rule integrates
//! exactly. Lumped builds keep the lumped nodal-mass invariants.

// Index loops mirror the tensor formulas.
#![allow(clippy::needless_range_loop)]

use std::path::Path;

use flexbody::build::{build, BuildMethod, BuildSpec};
use flexbody_reader as file;

const RHO: f64 = 7850.0;
const DIMS: [f64; 3] = [0.5, 0.05, 0.05];

/// Mass, first moment and inertia tensor about the origin of the box [0, a]×[0, b]×[0, c].
fn box_properties() -> (f64, [f64; 3], [[f64; 3]; 3]) {
    let [a, b, c] = DIMS;
    let m = RHO * a * b * c;
    let centre = [a / 2.0, b / 2.0, c / 2.0];
    // ∫ x_i x_j dm over the box: m·d_i²/3 on the diagonal, m·d_i d_j/4 off it.
    let second = |i: usize, j: usize| {
        if i == j {
            m * DIMS[i] * DIMS[i] / 3.0
        } else {
            m * DIMS[i] * DIMS[j] / 4.0
        }
    };
    let trace = second(0, 0) + second(1, 1) + second(2, 2);
    let inertia = std::array::from_fn(|i| {
        std::array::from_fn(|j| if i == j { trace } else { 0.0 } - second(i, j))
    });
    (m, centre.map(|x| m * x), inertia)
}

fn block_body(method: BuildMethod, mass: flexbody::fe::MassKind) -> file::ReducedBody {
    let model =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/reference/b_block_tet10/ccx_free.inp");
    let interface: &[&str] = if method == BuildMethod::Normal {
        &[]
    } else {
        &["FIXED", "TIP"]
    };
    let mut spec = BuildSpec::new(model, file::Units::si(), interface);
    spec.method = method;
    spec.modes = Some(10);
    spec.mass = mass;
    build(&spec, &mut |_| {}).unwrap().body
}

#[test]
fn consistent_invariants_are_the_consistent_mass_projections() {
    let (m_box, first_box, inertia_box) = box_properties();
    for method in [BuildMethod::CraigBampton, BuildMethod::Normal] {
        let body = block_body(method, flexbody::fe::MassKind::Consistent);
        let inv = &body.invariants;
        let nm = body.mode_count();
        // ‖I6 − I‖_max ≤ 1e-10
        let i6_err = (0..nm * nm)
            .map(|i| (inv.i6[i] - if i / nm == i % nm { 1.0 } else { 0.0 }).abs())
            .fold(0.0, f64::max);
        assert!(i6_err <= 1e-10, "{method:?}: |I6 − I| = {i6_err:e}");
        // I1 = ρV, I2 = ρV·centre, I7 = the box's inertia tensor about the origin.
        assert!(
            (inv.i1[0] / m_box - 1.0).abs() <= 1e-10,
            "{method:?}: I1 {} vs {m_box}",
            inv.i1[0]
        );
        for a in 0..3 {
            assert!(
                (inv.i2[a] - first_box[a]).abs() <= 1e-10 * m_box * DIMS[0],
                "{method:?}: I2[{a}] {} vs {}",
                inv.i2[a],
                first_box[a]
            );
        }
        let scale = inertia_box[1][1];
        for a in 0..3 {
            for b in 0..3 {
                assert!(
                    (inv.i7[3 * a + b] - inertia_box[a][b]).abs() <= 1e-10 * scale,
                    "{method:?}: I7[{a}][{b}] {} vs {}",
                    inv.i7[3 * a + b],
                    inertia_box[a][b]
                );
            }
        }
        // I3 = Tᵀ M Φ: the free body's elastic modes carry no momentum, the rigid ones all of it
        // (Σ over modes of (I3_aj)² = t_aᵀ M t_a = I1 for a complete rigid set).
        let rigid: Vec<usize> = (0..nm)
            .filter(|&j| body.modes.labels[j] == file::ModeLabel::Rigid)
            .collect();
        assert_eq!(rigid.len(), 6, "{method:?}");
        for a in 0..3 {
            let rigid_sq: f64 = rigid.iter().map(|&j| inv.i3[a * nm + j].powi(2)).sum();
            assert!(
                (rigid_sq / m_box - 1.0).abs() < 1e-8,
                "{method:?}: Σ_rigid I3[{a}]² = {rigid_sq} vs I1 {m_box}"
            );
            for j in (0..nm).filter(|j| !rigid.contains(j)) {
                assert!(inv.i3[a * nm + j].abs() < 1e-8 * m_box.sqrt());
            }
        }
        // I5, I8, I9 from the node-pair masses agree with the projections of the full M (solid
        // elements: translational blocks m_pq·E): tr I9_jj = −2 φ_jᵀMφ_j = −2; I5_j has no
        // j-th column (φ_j × φ_j = 0); the skew part of I8_j is I4_j (Σ m s × φ_j, from R and M).
        for j in 0..nm {
            let tr: f64 = (0..3).map(|a| inv.i9[((j * nm + j) * 3 + a) * 3 + a]).sum();
            assert!((tr + 2.0).abs() < 1e-9, "{method:?}: tr I9_{j}{j} = {tr}");
            for a in 0..3 {
                assert!(inv.i5[(j * 3 + a) * nm + j].abs() < 1e-12);
                let (b, c) = ((a + 1) % 3, (a + 2) % 3);
                let skew = inv.i8[(j * 3 + c) * 3 + b] - inv.i8[(j * 3 + b) * 3 + c];
                let i4 = inv.i4[a * nm + j];
                assert!(
                    (skew - i4).abs() <= 1e-9 * (m_box.sqrt() * DIMS[0]),
                    "{method:?}: I8_{j} skew {skew} vs I4 {i4}"
                );
            }
        }
        // The file's own check agrees: I6 equals the stored generalized mass.
        let report = flexbody::check::check(&body, None).unwrap();
        assert!(report.passed(), "{:?}", report.items);
    }
}

/// Lumped builds are unchanged: their invariants still come from the lumped nodal masses, so
/// I1 equals the sum of the stored nodal masses and `check` recomputes I1, I2, I6, I7 from them.
#[test]
fn lumped_invariants_still_come_from_the_nodal_masses() {
    let body = block_body(BuildMethod::Normal, flexbody::fe::MassKind::Lumped);
    let total: f64 = body.nodal_mass.iter().map(|n| n.mass).sum();
    assert!((body.invariants.i1[0] / total - 1.0).abs() < 1e-12);
    let report = flexbody::check::check(&body, None).unwrap();
    let item = report
        .items
        .iter()
        .find(|i| i.name == "stored invariants = recomputation from stored nodes")
        .expect("lumped files are recomputed from the nodal masses");
    assert!(item.pass, "{item:?}");
}
