//! Decompression bombs: a small file that declares (and deflates to) hundreds of MB is refused
//! before anything is inflated, and the reader's peak allocation stays small. Measured with a
//! counting allocator (this file holds one test, so no other test shares the process's heap).

use std::alloc::{GlobalAlloc, Layout, System};
use std::io::{Cursor, Read, Write};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

use flexbody_reader::{from_bytes, ReadError};

struct Counting;
static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let now = LIVE.fetch_add(l.size(), Relaxed) + l.size();
        PEAK.fetch_max(now, Relaxed);
        System.alloc(l)
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size(), Relaxed);
        System.dealloc(p, l)
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        if new > l.size() {
            let now = LIVE.fetch_add(new - l.size(), Relaxed) + new - l.size();
            PEAK.fetch_max(now, Relaxed);
        } else {
            LIVE.fetch_sub(l.size() - new, Relaxed);
        }
        System.realloc(p, l, new)
    }
}

#[global_allocator]
static A: Counting = Counting;

const GOLDEN: &[u8] = include_bytes!("../../fixtures/golden/v1.0/three_node_chain.flexbody");
const BOMB: u64 = 256 << 20;

/// The golden file plus an optional entry `bomb.bin` of BOMB zero bytes, deflated (~0.5 MB),
/// listed in the manifest with `listed` as its size and `sha` as its checksum.
fn bomb_file(listed: u64, sha: &str) -> Vec<u8> {
    let mut zip = zip::ZipArchive::new(Cursor::new(GOLDEN)).unwrap();
    let mut entries = Vec::new();
    for i in 0..zip.len() {
        let mut f = zip.by_index(i).unwrap();
        let mut b = Vec::new();
        f.read_to_end(&mut b).unwrap();
        entries.push((f.name().as_ref().unwrap().to_string(), b));
    }
    let mut manifest: serde_json::Value = serde_json::from_slice(&entries[0].1).unwrap();
    manifest["entries"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({
            "name": "bomb.bin", "size": listed, "sha256": sha, "required": false
        }));
    entries[0].1 = serde_json::to_vec(&manifest).unwrap();
    let mut out = Cursor::new(Vec::new());
    let mut w = zip::ZipWriter::new(&mut out);
    let stored =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (name, bytes) in &entries {
        w.start_file(name.as_str(), stored).unwrap();
        w.write_all(bytes).unwrap();
    }
    let deflated = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .compression_level(Some(9));
    w.start_file("bomb.bin", deflated).unwrap();
    let zeros = vec![0u8; 1 << 20];
    for _ in 0..(BOMB >> 20) {
        w.write_all(&zeros).unwrap();
    }
    w.finish().unwrap();
    out.into_inner()
}

/// Peak bytes allocated above the live heap at the start while `f` runs.
fn peak_during<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = LIVE.load(Relaxed);
    PEAK.store(base, Relaxed);
    let t = f();
    (t, PEAK.load(Relaxed) - base)
}

#[test]
fn deflate_bombs_are_refused_before_inflating() {
    let zero_sha = "0".repeat(64);
    // 1. The manifest and the zip directory agree on 512 MiB: over the expansion cap.
    let bomb = bomb_file(BOMB, &zero_sha);
    let file = &bomb;
    assert!(
        file.len() < 2 << 20,
        "the bomb is small: {} bytes",
        file.len()
    );
    let start = std::time::Instant::now();
    let (res, peak) = peak_during(|| from_bytes(file));
    let err = res.expect_err("a bomb");
    assert!(
        matches!(err, ReadError::LimitExceeded { ref entry, .. } if entry == "bomb.bin"),
        "{err}"
    );
    let text = err.to_string();
    assert!(text.contains("-byte file"), "{text}");
    assert!(peak < 16 << 20, "peak allocation {peak} bytes");
    assert!(start.elapsed().as_secs() < 10);

    // 2. The manifest lists a size under the cap but the zip directory says 512 MiB: the two
    //    disagree before anything is inflated.
    let file = bomb_file(1 << 20, &zero_sha);
    let (res, peak) = peak_during(|| from_bytes(&file));
    let err = res.expect_err("sizes disagree");
    assert!(
        matches!(err, ReadError::SizeMismatch { declared, actual, .. }
            if declared == 1 << 20 && actual == BOMB),
        "{err}"
    );
    assert!(peak < 16 << 20, "peak allocation {peak} bytes");

    // 3. The same bomb under raised limits (a caller that trusts the file) still inflates at
    //    most the declared size once, with no doubling: the checksum then fails.
    let limits = flexbody_reader::ReadLimits {
        max_expansion: 10_000,
        ..Default::default()
    };
    let (res, peak) = peak_during(|| flexbody_reader::from_bytes_with_limits(&bomb, &limits));
    let err = res.expect_err("checksum");
    assert!(matches!(err, ReadError::Checksum { .. }), "{err}");
    assert!(
        (peak as u64) < BOMB + (16 << 20),
        "peak allocation {peak} bytes for a {BOMB}-byte entry"
    );
}
