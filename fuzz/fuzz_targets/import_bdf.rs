//! The Nastran `.bdf` importer (run with -rss_limit_mb=500 and a -timeout).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = flexbody_fuzz::scratch_file("deck.bdf", data);
    let _ = flexbody::import::nastran::read_with_counts(&path);
});
