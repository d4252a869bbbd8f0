//! The Gmsh `.msh` importer, ASCII and binary (run with -rss_limit_mb=500 and a -timeout).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = flexbody_fuzz::scratch_file("mesh.msh", data);
    let _ = flexbody::import::gmsh::read(&path, None);
});
