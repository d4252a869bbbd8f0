//! The Matrix Market importer: the input is a matrix file and a node table, split at the first
//! line `%%NODES` (absent: the whole input is tried as both).
#![no_main]
use libfuzzer_sys::fuzz_target;

use flexbody::import::matrix_market;

fuzz_target!(|data: &[u8]| {
    let split = data.windows(8).position(|w| w == b"%%NODES\n");
    let (matrix, nodes) = match split {
        Some(i) => (&data[..i], &data[i + 8..]),
        None => (data, data),
    };
    let m = flexbody_fuzz::scratch_file("k.mtx", matrix);
    let n = flexbody_fuzz::scratch_file("nodes.txt", nodes);
    let _ = matrix_market::read_matrix(&m);
    let _ = matrix_market::read_node_table(&n);
    let _ = matrix_market::read(&m, &m, &n);
});
