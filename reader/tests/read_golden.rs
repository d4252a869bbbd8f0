//! The reader on its own (no flexbody crate): the golden 3-node chain reads back with its
//! closed-form content, and its modes are mass-orthonormal w.r.t. the stored nodal masses.
use std::path::Path;

fn golden(name: &str) -> std::path::PathBuf {
    golden_in("v1.0", name)
}

fn golden_in(version: &str, name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures/golden")
        .join(version)
        .join(name)
}

/// Format 1.1 adds the optional `lines.bin`: the 3-node chain drawn as two lines.
#[test]
fn v1_1_golden_reads_with_its_lines() {
    let b = flexbody_reader::read(golden_in("v1.1", "three_node_chain_lines.flexbody"))
        .expect("golden file reads");
    assert_eq!(b.version, flexbody_reader::Version { major: 1, minor: 1 });
    assert_eq!(b.lines, Some(vec![[0, 1], [1, 2]]));
    assert_eq!(b.modes.omega2, vec![0.0, 400.0, 1200.0]);
}

#[test]
fn three_node_chain_reads_with_closed_form_content() {
    let b = flexbody_reader::read(golden("three_node_chain.flexbody")).expect("golden file reads");
    assert_eq!(b.version, flexbody_reader::Version { major: 1, minor: 0 });
    assert_eq!(b.lines, None);
    assert_eq!(
        b.nodes.iter().map(|n| n.id).collect::<Vec<_>>(),
        vec![101, 102, 103]
    );
    // Three 2 kg masses on two 800 N/m springs: ω² = 0, k/m = 400, 3k/m = 1200.
    assert_eq!(b.modes.omega2, vec![0.0, 400.0, 1200.0]);
    assert_eq!(b.invariants.i1, vec![6.0]);
    assert_eq!(
        b.damping.as_ref().map(|d| d.ratio.clone()),
        Some(vec![0.0, 0.02, 0.02])
    );
    let (n, m) = (b.node_count(), b.mode_count());
    for i in 0..m {
        for j in 0..m {
            let mij: f64 = (0..n)
                .map(|p| {
                    b.nodal_mass[p].mass
                        * b.modes.shapes[(i * n + p) * 6]
                        * b.modes.shapes[(j * n + p) * 6]
                })
                .sum();
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((mij - want).abs() < 1e-14, "phi_{i}' M phi_{j} = {mij}");
        }
    }
}

#[test]
fn a_missing_file_is_an_io_error_naming_the_path() {
    let err = flexbody_reader::read(golden("no_such.flexbody")).expect_err("missing");
    assert_eq!(err.variant(), "Io");
    assert!(err.to_string().contains("no_such.flexbody"), "{err}");
}

/// Format 1.6: normal modes that count a residual vector removed as dependent read back (a
/// 1.5 reader refused them: its rule 8 wanted `removed_dependent` = 0 for normal modes).
#[test]
fn v1_6_golden_counts_the_removed_residual_vector() {
    let b = flexbody_reader::read(golden_in(
        "v1.6",
        "three_node_chain_residual_vectors.flexbody",
    ))
    .expect("golden file reads");
    assert_eq!(b.version, flexbody_reader::Version { major: 1, minor: 6 });
    assert_eq!(flexbody_reader::version_for(&b), b.version);
    let c = b.method.counts;
    assert_eq!((c.rigid, c.normal, c.removed_dependent), (1, 3, 1));
    assert_eq!(b.modal_loads.map(|m| m.residual), Some(vec![0, 0, 1]));
    let share = b.label_shares.expect("shares")[2];
    assert!((share - 28.0 / 55.0).abs() < 1e-15, "{share}");
}

/// Format 1.7: the modal geometric stiffness of the twelve unit inertia loads reads back, in
/// flexbody's order, with the golden body's synthetic terms ((k + 1)/8 + (r + c)/4, diagonal
/// + 1), and the file says 1.7.
#[test]
fn v1_7_golden_holds_the_geometric_stiffness_of_twelve_unit_loads() {
    use flexbody_reader::{StaticSupport, UnitLoad};
    let b = flexbody_reader::read(golden_in(
        "v1.7",
        "three_node_chain_geometric_stiffness.flexbody",
    ))
    .expect("golden file reads");
    assert_eq!(b.version, flexbody_reader::Version { major: 1, minor: 7 });
    assert_eq!(flexbody_reader::version_for(&b), b.version);
    let g = b.geometric_stiffness.expect("geometric_stiffness.bin");
    assert_eq!(g.support, StaticSupport::InertiaRelief);
    let loads: Vec<UnitLoad> = g.fields.iter().map(|f| f.load).collect();
    assert_eq!(loads, UnitLoad::inertia());
    assert_eq!(g.fields[6].load.name().as_deref(), Some("omega_y*omega_y"));
    let f = &g.fields[8];
    assert_eq!(f.load, UnitLoad::AngularVelocity([2, 2]));
    assert_eq!(f.matrix[2 * 3 + 1], 9.0 / 8.0 + 3.0 / 4.0);
    assert_eq!(f.matrix[4], 9.0 / 8.0 + 2.0 / 4.0 + 1.0);
}

/// A refusal printed for people carries its SPEC §8 name (issue 37): `ReadError::named`.
#[test]
fn a_named_error_prints_its_spec_name_first() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/broken/checksum_mismatch.flexbody");
    let err = flexbody_reader::read(path).expect_err("refused");
    assert_eq!(err.variant(), "Checksum");
    let text = err.to_string();
    assert_eq!(err.named().to_string(), format!("Checksum: {text}"));
    let io = flexbody_reader::read(golden("no_such.flexbody")).expect_err("missing");
    let named = io.named();
    assert!(named.to_string().starts_with("Io: cannot read "));
    assert!(
        std::error::Error::source(&named).is_some(),
        "the io::Error stays the source"
    );
}
