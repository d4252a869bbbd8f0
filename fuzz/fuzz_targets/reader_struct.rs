//! The reader, structure-aware: a golden file with one entry replaced (or spliced, or a new
//! entry added) by the fuzz bytes and the manifest's sizes and SHA-256 rebuilt, so the input
//! gets past the container checks into the entry decoding and the consistency rules.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some(file) = flexbody_fuzz::structured(data) {
        let _ = flexbody_reader::from_bytes(&file);
    }
});
