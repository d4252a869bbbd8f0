//! The reader on raw bytes: any input ends in Ok or a named ReadError, never a panic, hang or
//! allocation beyond the ReadLimits.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = flexbody_reader::from_bytes(data);
});
