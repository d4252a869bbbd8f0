//! The writer's default compression (`Compression::Auto`, SPEC.md §2): a large entry that
//! deflate does not shrink is stored, everything else is deflated exactly as `Deflate(6)`
//! writes it. Checked by opening the written container with the `zip` crate, reading it back
//! with `flexbody-reader` and with the stdlib reference reader (`format-spec/reference_reader.py`).

use std::io::Cursor;
use std::path::Path;
use std::process::Command;

use flexbody::write::{
    to_bytes, Compression, WriteOptions, AUTO_STORE_MIN_BYTES, AUTO_STORE_MIN_SAVING,
};
use flexbody_reader::*;
use zip::{CompressionMethod, ZipArchive};

/// Nodes of the large bodies: modes.bin holds 3 × 40,000 × 6 doubles = 5.76 MB.
const NODES: usize = 40_000;

/// splitmix64 (Steele, Lea & Flood 2014): deterministic pseudo-random doubles in [−1, 1).
fn random_doubles(len: usize, mut state: u64) -> Vec<f64> {
    (0..len)
        .map(|_| {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        })
        .collect()
}

/// The 3-node chain's records (3 modes, interfaces at nodes 0 and 2) on `NODES` nodes of a
/// 1 mm grid with equal masses and the given mode-major shapes; invariants computed from them.
fn large_body(shapes: Vec<f64>) -> ReducedBody {
    let mut b = crate::format_support::body_3node();
    let template_mass = b.nodal_mass[0].clone();
    b.nodes = (0..NODES)
        .map(|p| Node {
            id: 1 + p as u64,
            xyz: [
                (p % 40) as f64 * 1e-3,
                (p / 40 % 40) as f64 * 1e-3,
                (p / 1600) as f64 * 1e-3,
            ],
            interface: p == 0 || p == 2,
        })
        .collect();
    b.nodal_mass = vec![template_mass; NODES];
    assert_eq!(shapes.len(), 3 * NODES * 6);
    b.modes.shapes = shapes;
    b.invariants = crate::format_support::invariants(
        &b.nodes,
        &b.nodal_mass,
        &b.modes.shapes,
        3,
        InvariantSet::Full,
    );
    b
}

/// Smooth solid-like shapes: translations sin/cos of the position, rotations zero.
fn smooth_shapes() -> Vec<f64> {
    let mut s = vec![0.0; 3 * NODES * 6];
    for j in 0..3 {
        for p in 0..NODES {
            let x = (p % 40) as f64 / 40.0 + (p / 1600) as f64 / 25.0;
            for c in 0..3 {
                s[(j * NODES + p) * 6 + c] = ((j + 1) as f64 * x + c as f64).sin() * 1e-2;
            }
        }
    }
    s
}

/// (name, method, uncompressed size, compressed size) per entry, in file order.
fn entries(bytes: &[u8]) -> Vec<(String, CompressionMethod, u64, u64)> {
    let mut z = ZipArchive::new(Cursor::new(bytes)).expect("zip");
    (0..z.len())
        .map(|i| {
            let f = z.by_index_raw(i).expect("entry");
            (
                f.name().expect("utf-8 name").to_string(),
                f.compression(),
                f.size(),
                f.compressed_size(),
            )
        })
        .collect()
}

fn auto() -> WriteOptions {
    WriteOptions::default()
}

#[test]
fn default_is_auto_at_level_6() {
    assert_eq!(auto().compression, Compression::Auto { level: 6 });
}

#[test]
fn store_rule_is_exact_at_its_bounds() {
    let n = AUTO_STORE_MIN_BYTES as u64; // 1 MiB
    assert_eq!(AUTO_STORE_MIN_SAVING, 16);
    // Saving exactly 1/16 (65,536 bytes) keeps the deflated form; one byte less stores.
    assert!(!Compression::auto_stores(n, n - n / 16));
    assert!(Compression::auto_stores(n, n - n / 16 + 1));
    // Deflate that grows the entry: stored.
    assert!(Compression::auto_stores(n, n + 100));
    // Below 1 MiB nothing is stored, however badly it deflates.
    assert!(!Compression::auto_stores(n - 1, n + 100));
}

#[test]
fn incompressible_shapes_are_stored_the_rest_deflated_and_read_back() {
    let body = large_body(random_doubles(3 * NODES * 6, 42));
    let bytes = to_bytes(&body, &auto()).expect("write");
    assert!(
        bytes == to_bytes(&body, &auto()).expect("write again"),
        "two writes differ"
    );
    let got = entries(&bytes);
    let method = |name: &str| got.iter().find(|e| e.0 == name).expect(name).1;
    assert_eq!(method("modes.bin"), CompressionMethod::Stored);
    for name in ["manifest.json", "header.bin", "nodes.bin", "nodal_mass.bin"] {
        assert_eq!(method(name), CompressionMethod::Deflated, "{name}");
    }
    // The decision per entry is the rule applied to what Deflate(6) makes of it.
    let d6 = to_bytes(
        &body,
        &WriteOptions {
            compression: Compression::Deflate(6),
        },
    )
    .expect("write deflate 6");
    let deflated = entries(&d6);
    assert_eq!(deflated.len(), got.len());
    for ((name, m, size, csize), (name6, _, size6, csize6)) in got.iter().zip(&deflated) {
        assert_eq!((name, size), (name6, size6));
        let stores = Compression::auto_stores(*size6, *csize6);
        assert_eq!(*m == CompressionMethod::Stored, stores, "{name}");
        if !stores {
            assert_eq!(
                csize, csize6,
                "{name}: deflated differently from Deflate(6)"
            );
        }
    }
    let (modes_size, modes_deflated) = deflated
        .iter()
        .find(|e| e.0 == "modes.bin")
        .map(|e| (e.2, e.3))
        .expect("modes.bin");
    assert!(modes_size >= 5_760_000 && modes_deflated * 16 > modes_size * 15);

    let back = from_bytes(&bytes).expect("flexbody-reader reads the mixed file");
    assert_eq!(back, body);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&back.modes.shapes), bits(&body.modes.shapes));

    // The stdlib reference reader reads it too and agrees on the counts.
    let dir = std::env::temp_dir().join(format!("flexbody-auto-store-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("mkdir");
    let path = dir.join("mixed.flexbody");
    std::fs::write(&path, &bytes).expect("write file");
    let py = Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("format-spec/reference_reader.py"))
        .arg(&path)
        .output()
        .expect("python3 runs");
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        py.status.success(),
        "{}",
        String::from_utf8_lossy(&py.stderr)
    );
    let summary: serde_json::Value = serde_json::from_slice(&py.stdout).expect("json");
    assert_eq!(summary["counts"]["nodes"], NODES);
    assert_eq!(summary["counts"]["interface_nodes"], 2);
    // Total mass from the stored invariant I1: the sum of the equal nodal masses.
    let total: f64 = body.nodal_mass.iter().map(|x| x.mass).sum();
    let m = summary["mass"]["total_mass"].as_f64().expect("total mass");
    assert!((m - total).abs() <= 1e-12 * total, "{m} vs {total}");
    // Its SHA-256 check of modes.bin covered the stored bytes.
    let sha = summary["entries"]
        .as_array()
        .expect("entries")
        .iter()
        .find(|e| e["name"] == "modes.bin")
        .map(|e| e["size"].as_u64());
    assert_eq!(sha, Some(Some(modes_size)));
}

#[test]
fn compressible_shapes_stay_deflated_byte_identical_to_deflate_6() {
    let body = large_body(smooth_shapes());
    let bytes = to_bytes(&body, &auto()).expect("write");
    let got = entries(&bytes);
    let modes = got.iter().find(|e| e.0 == "modes.bin").expect("modes.bin");
    assert!(modes.2 >= AUTO_STORE_MIN_BYTES as u64);
    assert_eq!(modes.1, CompressionMethod::Deflated);
    assert!(got.iter().all(|e| e.1 == CompressionMethod::Deflated));
    // Deflated once in memory and copied in: the same bytes the plain deflate path writes.
    let d6 = to_bytes(
        &body,
        &WriteOptions {
            compression: Compression::Deflate(6),
        },
    )
    .expect("write deflate 6");
    assert!(
        bytes == d6,
        "Auto differs from Deflate(6) on a compressible body"
    );
    assert_eq!(from_bytes(&bytes).expect("read"), body);
}
