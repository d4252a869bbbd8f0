//! The Abaqus/CalculiX `.inp` importer (run with -rss_limit_mb=500 and a -timeout).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = flexbody_fuzz::scratch_file("deck.inp", data);
    let _ = flexbody::import::abaqus::read(&path);
});
