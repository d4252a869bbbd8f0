//! Writer ↔ reader: round trip with bit-exact floats, deterministic bytes, no partial file on
//! error, limits, and the v1 byte layout checked against hand-computed bytes (SPEC.md §4).

use flexbody::write::{to_bytes, write_reduced_body, Compression, WriteError, WriteOptions};
use flexbody_reader::codec::encode;
use flexbody_reader::*;

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// The 3-node body with every optional entry and awkward floats (−0, subnormal, huge).
fn awkward_body() -> ReducedBody {
    let mut b = crate::format_support::body_3node();
    b.modes.shapes[1] = -0.0;
    b.modes.shapes[2] = f64::MIN_POSITIVE / 8.0;
    b.modes.shapes[3] = 1.0e300;
    b.stress_shapes = Some(FieldShapes {
        nodes: vec![0, 2],
        values: (0..3 * 2 * 6).map(|i| i as f64 * 0.1 - 1.0).collect(),
    });
    b.strain_shapes = Some(FieldShapes {
        nodes: vec![1],
        values: vec![1e-7; 3 * 6],
    });
    b.header.created_utc = Some("2026-11-22T05:00:00Z".into());
    b.method.reference_conditions = vec![ReferenceCondition {
        node: 1,
        dofs: [true, false, false, false, false, false],
    }];
    b
}

#[test]
fn round_trip_is_bit_exact_for_every_entry() {
    for compression in [
        Compression::Deflate(6),
        Compression::Stored,
        Compression::Deflate(9),
        Compression::Auto { level: 6 },
    ] {
        let body = awkward_body();
        let bytes = to_bytes(&body, &WriteOptions { compression }).expect("write");
        let back = from_bytes(&bytes).expect("read");
        assert_eq!(back, body);
        assert_eq!(bits(&back.modes.shapes), bits(&body.modes.shapes));
        assert_eq!(back.modes.shapes[1].to_bits(), (-0.0f64).to_bits());
        assert_eq!(bits(&back.invariants.i9), bits(&body.invariants.i9));
        let (s, t) = (
            back.stress_shapes.as_ref().expect("stress"),
            body.stress_shapes.as_ref().expect("stress"),
        );
        assert_eq!(bits(&s.values), bits(&t.values));
    }
    for (_, body) in crate::format_support::golden() {
        let back =
            from_bytes(&to_bytes(&body, &WriteOptions::default()).expect("write")).expect("read");
        assert_eq!(back, body);
        assert_eq!(bits(&back.modes.shapes), bits(&body.modes.shapes));
    }
}

#[test]
fn writing_twice_gives_identical_bytes_and_files() {
    let dir = std::env::temp_dir().join(format!("flexbody-determinism-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("mkdir");
    let body = crate::format_support::body_20node();
    let (a, b) = (dir.join("a.flexbody"), dir.join("b.flexbody"));
    write_reduced_body(&a, &body, &WriteOptions::default()).expect("write a");
    write_reduced_body(&b, &body, &WriteOptions::default()).expect("write b");
    let (ba, bb) = (std::fs::read(&a).expect("a"), std::fs::read(&b).expect("b"));
    assert!(ba == bb, "two writes of the same body differ");
    assert!(ba == to_bytes(&body, &WriteOptions::default()).expect("bytes"));
    // Overwriting an existing file replaces it whole.
    write_reduced_body(
        &a,
        &crate::format_support::body_3node(),
        &WriteOptions::default(),
    )
    .expect("overwrite");
    assert_eq!(read(&a).expect("read").node_count(), 3);
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .expect("ls")
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(leftovers.len(), 2, "temp files left: {leftovers:?}");
    std::fs::remove_dir_all(&dir).expect("cleanup");
}

#[test]
fn writer_errors_name_the_path_and_leave_no_file() {
    let dir = std::env::temp_dir().join(format!("flexbody-nopartial-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("mkdir");
    let target = dir.join("bad.flexbody");
    // 1. An invalid body (NaN in a shape) is refused before anything is written.
    let mut body = crate::format_support::body_3node();
    body.modes.shapes[0] = f64::NAN;
    let err =
        write_reduced_body(&target, &body, &WriteOptions::default()).expect_err("NaN refused");
    assert!(
        matches!(
            &err,
            WriteError::Invalid {
                source: ReadError::NonFinite { .. },
                ..
            }
        ),
        "{err:?}"
    );
    assert!(
        err.to_string().contains("bad.flexbody") && err.to_string().contains("shapes[0]"),
        "{err}"
    );
    // 2. The target is a directory: rename fails, the temp file is removed.
    let as_dir = dir.join("taken.flexbody");
    std::fs::create_dir_all(as_dir.join("inside")).expect("mkdir");
    let err = write_reduced_body(
        &as_dir,
        &crate::format_support::body_3node(),
        &WriteOptions::default(),
    )
    .expect_err("dir target");
    assert!(
        matches!(&err, WriteError::Io { .. }) && err.to_string().contains("taken.flexbody"),
        "{err}"
    );
    // 3. The folder does not exist.
    let missing = dir.join("no/such/folder/x.flexbody");
    let err = write_reduced_body(
        &missing,
        &crate::format_support::body_3node(),
        &WriteOptions::default(),
    )
    .expect_err("no folder");
    assert!(err.to_string().contains("folder"), "{err}");
    let left: Vec<_> = std::fs::read_dir(&dir)
        .expect("ls")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        left,
        vec!["taken.flexbody".to_string()],
        "only the pre-existing directory may remain"
    );
    std::fs::remove_dir_all(&dir).expect("cleanup");
}

#[test]
fn read_limits_refuse_oversized_counts() {
    let bytes = to_bytes(
        &crate::format_support::body_20node(),
        &WriteOptions::default(),
    )
    .expect("write");
    let limits = ReadLimits {
        max_nodes: 10,
        ..Default::default()
    };
    let err = from_bytes_with_limits(&bytes, &limits).expect_err("20 nodes > 10");
    assert!(
        matches!(
            err,
            ReadError::LimitExceeded {
                value: 20,
                limit: 10,
                ..
            }
        ),
        "{err}"
    );
    let limits = ReadLimits {
        max_entry_bytes: 1000,
        ..Default::default()
    };
    // nodal_mass.bin is the first entry over 1000 bytes: 8 + 20 × (8 + 9 × 8) = 1608.
    let err = from_bytes_with_limits(&bytes, &limits).expect_err("nodal_mass.bin > 1000 bytes");
    assert!(
        err.to_string()
            .contains("nodal_mass.bin: declared size (bytes) 1608 exceeds the limit 1000"),
        "{err}"
    );
}

/// Hand-computed bytes of SPEC.md §4: u64 LE lengths, u32 LE enum tags, 1-byte Option and
/// bool tags, f64 LE, no prefix for fixed arrays and structs.
#[test]
fn layout_matches_hand_computed_bytes() {
    let header = Header {
        title: "ab".into(),
        created_utc: None,
        request: Request {
            method: Method::CraigBampton,
            fmax_hz: Some(2.0),
            mode_count: None,
            keep_nodes: KeepNodes::List(vec![7]),
            invariant_set: InvariantSet::Rigid,
            mass_kind: MassKind::Consistent,
        },
    };
    #[rustfmt::skip]
    let want: Vec<u8> = vec![
        2, 0, 0, 0, 0, 0, 0, 0, b'a', b'b',          // title: u64 length 2, UTF-8
        0,                                           // created_utc: None
        1, 0, 0, 0,                                  // method: tag 1 CraigBampton
        1, 0, 0, 0, 0, 0, 0, 0, 0x40,                // fmax_hz: Some(2.0) = 0x4000000000000000 LE
        0,                                           // mode_count: None
        2, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 7, 0, 0, 0, 0, 0, 0, 0, // keep_nodes: List([7])
        3, 0, 0, 0,                                  // invariant_set: tag 3 Rigid
        1, 0, 0, 0,                                  // mass_kind: tag 1 Consistent
    ];
    assert_eq!(encode(&header), want);

    let nodes = vec![Node {
        id: 258,
        xyz: [1.0, -2.0, 0.5],
        interface: true,
    }];
    #[rustfmt::skip]
    let want: Vec<u8> = vec![
        1, 0, 0, 0, 0, 0, 0, 0,                      // count 1
        2, 1, 0, 0, 0, 0, 0, 0,                      // id 258 = 0x0102
        0, 0, 0, 0, 0, 0, 0xf0, 0x3f,                // 1.0
        0, 0, 0, 0, 0, 0, 0, 0xc0,                   // -2.0
        0, 0, 0, 0, 0, 0, 0xe0, 0x3f,                // 0.5
        1,                                           // interface: true
    ];
    assert_eq!(encode(&nodes), want);

    let faces = vec![Face::Quad([1, 2, 3, 65536])];
    #[rustfmt::skip]
    let want: Vec<u8> = vec![
        1, 0, 0, 0, 0, 0, 0, 0,                      // count 1
        1, 0, 0, 0,                                  // tag 1 Quad
        1, 0, 0, 0, 2, 0, 0, 0, 3, 0, 0, 0, 0, 0, 1, 0, // u32 indices
    ];
    assert_eq!(encode(&faces), want);

    let damping = Damping { ratio: vec![0.25] };
    assert_eq!(
        encode(&damping),
        vec![1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xd0, 0x3f]
    );
    let labels = vec![ModeLabel::Rigid, ModeLabel::FrequencyResponse];
    assert_eq!(
        encode(&labels),
        vec![2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 5, 0, 0, 0]
    );
    let mask = [true, false, true, false, false, false, false, false, true];
    assert_eq!(encode(&mask), vec![1, 0, 1, 0, 0, 0, 0, 0, 1]);
    // Decoding the hand bytes gives the values back.
    let back: Header =
        flexbody_reader::codec::decode("header.bin", &encode(&header), true).expect("decode");
    assert_eq!(back, header);
}

#[test]
fn writer_refuses_a_header_the_reader_would_refuse() {
    let mut body = crate::format_support::body_3node();
    body.header.title = "x".repeat(flexbody_reader::codec::STRING_RECORD_LIMIT + 1);
    let err = to_bytes(&body, &WriteOptions::default()).expect_err("17 MiB title");
    assert!(
        matches!(
            &err,
            WriteError::Invalid {
                source: ReadError::LimitExceeded { .. },
                ..
            }
        ),
        "{err:?}"
    );
    // 8 + (2^24 + 1) title, 1 None, request: 4 method + 1 None + 9 Some(u64) + 4 + 4 + 4.
    let size = 8 + (1 << 24) + 1 + 1 + 4 + 1 + 9 + 4 + 4 + 4;
    assert!(
        err.to_string().contains(&format!(
            "header.bin: encoded size (bytes) {size} exceeds the limit 16777216"
        )),
        "{err}"
    );
}

/// SPEC §4: every record that holds strings, and `recipe.json`, is at most 16 MiB; the writer
/// refuses what the reader would refuse, naming the entry.
#[test]
fn writer_refuses_string_records_and_recipe_over_16_mib() {
    let limit = flexbody_reader::codec::STRING_RECORD_LIMIT;
    // interfaces.bin: 2^21 + 1 dependent ids of 8 bytes are just over 16 MiB
    let mut body = crate::format_support::body_3node_interfaces();
    if let Some(interfaces) = body.interfaces.as_mut() {
        interfaces[1].dependent = (1000..1000 + (limit / 8 + 1) as u64).collect();
    }
    let refused = |body: &ReducedBody, entry: &str| {
        let err = to_bytes(body, &WriteOptions::default()).expect_err(entry);
        let text = err.to_string();
        assert!(
            text.contains(&format!("{entry}: encoded size (bytes)"))
                && text.contains(&format!("exceeds the limit {limit}")),
            "{err}"
        );
    };
    refused(&body, "interfaces.bin");
    // recipe.json: a model path of 16 MiB + 1
    let mut body = crate::format_support::body_3node_recipe();
    if let Some(recipe) = body.recipe.as_mut() {
        recipe.model_files[0].path = "p".repeat(limit + 1);
    }
    refused(&body, "recipe.json");
    // just under the limit still writes and reads back
    let mut body = crate::format_support::body_3node_recipe();
    if let Some(recipe) = body.recipe.as_mut() {
        recipe.model_files[0].path = "p".repeat(limit / 2);
    }
    let bytes = to_bytes(&body, &WriteOptions::default()).expect("an 8 MiB path writes");
    let back = flexbody_reader::from_bytes(&bytes).expect("and reads back");
    assert_eq!(back.recipe, body.recipe);
}
