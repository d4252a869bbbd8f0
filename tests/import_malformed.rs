//! Malformed input across all formats: each case must give an `Err` naming the file, the line
//! and the entity (card/keyword and id) — never a panic, never a silent success.

use std::path::PathBuf;

use flexbody::import::{matrix_market, read_model, ImportOptions};

struct Case {
    name: &'static str,
    file: &'static str,
    text: &'static [u8],
    line: usize,
    entity: &'static str,
    message: &'static str,
}

fn cases() -> Vec<Case> {
    vec![
        Case { name: "inp bad number", file: "a.inp", text: b"*NODE\n1, 0, 0, 0\n2, 1.0.0, 0, 0\n", line: 3, entity: "*NODE 2", message: "bad number" },
        Case { name: "inp unknown node", file: "a.inp",
            text: b"*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n*ELEMENT, TYPE=C3D4\n10, 1, 2, 3, 99\n", line: 6, entity: "C3D4 10", message: "unknown node 99" },
        Case { name: "inp duplicate node", file: "a.inp", text: b"*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n1, 0, 1, 0\n", line: 4, entity: "*NODE 1", message: "duplicate node id" },
        Case { name: "inp missing continuation", file: "a.inp",
            text: b"*NODE\n1, 0, 0, 0\n*ELEMENT, TYPE=C3D10\n7, 1, 1, 1, 1, 1, 1, 1, 1,\n*NSET, NSET=A\n1\n", line: 4, entity: "*ELEMENT 7", message: "missing continuation" },
        Case { name: "inp duplicate element", file: "a.inp",
            text: b"*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n*ELEMENT, TYPE=C3D4\n5, 1, 2, 3, 4\n5, 1, 2, 4, 3\n", line: 8, entity: "C3D4 5", message: "duplicate element id" },
        Case { name: "inp unknown material", file: "a.inp",
            text: b"*NODE\n1, 0, 0, 0\n*ELSET, ELSET=E\n*SOLID SECTION, ELSET=E, MATERIAL=NOPE\n", line: 4, entity: "*SECTION ELSET=E", message: "unknown material NOPE" },
        Case { name: "inp unsupported element", file: "a.inp", text: b"*NODE\n1, 0, 0, 0\n*ELEMENT, TYPE=C3D27\n1, 1\n", line: 3, entity: "*ELEMENT", message: "unsupported element type C3D27" },
        Case { name: "inp missing include", file: "a.inp", text: b"** x\n*INCLUDE, INPUT=does_not_exist.inp\n", line: 2, entity: "*INCLUDE", message: "cannot read" },
        Case { name: "inp empty file", file: "a.inp", text: b"\n  \n", line: 1, entity: "file", message: "empty file" },
        Case { name: "inp binary file", file: "a.inp", text: b"*NODE\n1, 0, 0, 0\n\x00\x01\x02\xff", line: 3, entity: "file", message: "binary" },
        Case { name: "inp bad GENERATE", file: "a.inp", text: b"*NODE\n1, 0, 0, 0\n*NSET, NSET=G, GENERATE\n5, 1, 1\n", line: 4, entity: "*NSET G", message: "GENERATE" },
        Case { name: "bdf bad number", file: "a.bdf", text: b"GRID    1               0.      0.      0.\nGRID    2               1.2.3   0.      0.\n", line: 2, entity: "GRID 2", message: "bad number '1.2.3'" },
        Case { name: "bdf missing continuation", file: "a.bdf",
            text: b"MAT1,1,1.,,.3\nPSOLID,1,1\nGRID,1,,0.,0.,0.\nCHEXA   1       1       1       1       1       1       1       1\n", line: 4, entity: "CHEXA 1", message: "missing continuation" },
        Case { name: "bdf unknown node", file: "a.bdf",
            text: b"MAT1,1,1.,,.3\nPSOLID,1,1\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nCTETRA,7,1,1,2,3,42\n", line: 6, entity: "CTETRA 7", message: "unknown node 42" },
        Case { name: "bdf unknown property", file: "a.bdf",
            text: b"MAT1,1,1.,,.3\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,0.,0.,1.\nCTETRA,7,5,1,2,3,4\n", line: 6, entity: "CTETRA 7", message: "unknown property 5" },
        Case { name: "bdf duplicate grid", file: "a.bdf", text: b"GRID,1,,0.,0.,0.\n$ c\nGRID,1,,1.,0.,0.\n", line: 3, entity: "GRID 1", message: "duplicate node id" },
        Case { name: "bdf unknown coordinate system", file: "a.bdf", text: b"GRID,1,,0.,0.,0.\nGRID,2,7,1.,0.,0.\n", line: 2, entity: "GRID 2", message: "unknown coordinate system CP 7" },
        Case { name: "bdf coordinate system cycle", file: "a.bdf",
            text: b"CORD2R,1,2,0.,0.,0.,0.,0.,1.,+\n+,1.,0.,0.\nCORD2R,2,1,0.,0.,0.,0.,0.,1.,+\n+,1.,0.,0.\n", line: 3, entity: "CORD2R 2", message: "cycle" },
        Case { name: "bdf unknown material", file: "a.bdf", text: b"PSOLID,1,9\nGRID,1,,0.,0.,0.\n", line: 1, entity: "PSOLID 1", message: "unknown material 9" },
        Case { name: "bdf orphan continuation", file: "a.bdf", text: b"+       1.      2.\nGRID,1,,0.,0.,0.\n", line: 1, entity: "card", message: "without a parent" },
        Case { name: "bdf binary file", file: "a.bdf", text: b"GRID,1,,0.,0.,0.\n\x00\x00\x00", line: 2, entity: "file", message: "binary" },
        Case { name: "msh wrong version", file: "a.msh", text: b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", line: 2, entity: "$MeshFormat", message: "only MSH 4.1" },
        Case { name: "msh bad node coordinate", file: "a.msh",
            text: b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n3 1 0 2\n1\n2\n0 0 0\n1 x 0\n$EndNodes\n", line: 10, entity: "$Nodes", message: "bad number 'x'" },
        Case { name: "msh element with unknown node", file: "a.msh",
            text: b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n3 1 0 1\n1\n0 0 0\n$EndNodes\n$Elements\n1 1 4 4\n3 1 4 1\n4 1 1 1 9\n$EndElements\n", line: 13, entity: "element 4", message: "unknown node 9" },
        Case { name: "msh truncated", file: "a.msh", text: b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n3 1 0 2\n1\n", line: 5, entity: "$Nodes", message: "claims 2 nodes (at least 16 bytes), but only 15 bytes remain" },
        Case { name: "msh truncated after the counts", file: "a.msh", text: b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n3 1 0 2\n1\n2\n0 0 0\n1 0.000000\n", line: 11, entity: "$Nodes", message: "end of file" },
        Case { name: "msh truncated binary", file: "a.msh", text: b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n$Nodes\n\x01\x00\x00\x00", line: 6, entity: "$Nodes", message: "end of file" },
    ]
}

fn tmp_dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("flexbody_malformed_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn malformed_inputs_name_file_line_and_entity() {
    let dir = tmp_dir();
    let cases = cases();
    assert!(cases.len() >= 15);
    let mut failures = Vec::new();
    for (k, c) in cases.iter().enumerate() {
        let sub = dir.join(format!("case{k}"));
        std::fs::create_dir_all(&sub).unwrap();
        let path = sub.join(c.file);
        std::fs::write(&path, c.text).unwrap();
        let err = match read_model(&path, &ImportOptions::default()) {
            Ok(_) => panic!("{}: accepted malformed input", c.name),
            Err(e) => e,
        };
        let text = err.to_string();
        let ok = err.file().is_some_and(|f| f.ends_with(c.file))
            && err.line() == Some(c.line)
            && err.entity().is_some_and(|e| e.contains(c.entity))
            && text.contains(c.message);
        if !ok {
            failures.push(format!(
                "{}: want line {} entity '{}' message '{}', got: {text}",
                c.name, c.line, c.entity, c.message
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn malformed_matrix_market_and_node_table() {
    let dir = tmp_dir();
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let p = write(
        "bad_header.mtx",
        "%%MatrixMarket matrix array real general\n2 2\n1\n",
    );
    let e = matrix_market::read_matrix(&p).unwrap_err();
    assert_eq!((e.line(), e.entity()), (Some(1), Some("header")));
    let p = write(
        "range.mtx",
        "%%MatrixMarket matrix coordinate real symmetric\n% c\n2 2 2\n1 1 1.0\n3 1 2.0\n",
    );
    let e = matrix_market::read_matrix(&p).unwrap_err();
    assert_eq!((e.line(), e.entity()), (Some(5), Some("entry 2")));
    assert!(e.to_string().contains("outside"));
    let p = write(
        "unsym.mtx",
        "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 2 1.0\n2 1 2.0\n",
    );
    assert!(matrix_market::read_matrix(&p)
        .unwrap_err()
        .to_string()
        .contains("not symmetric"));
    // the later of two equal entries is named, by line
    let p = write(
        "dup.mtx",
        "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n2 1 1.0\n1 1 4.0\n2 1 1.0\n",
    );
    let e = matrix_market::read_matrix(&p).unwrap_err();
    assert_eq!((e.line(), e.entity()), (Some(5), Some("entry (2,1)")));
    assert!(e.to_string().contains("duplicate"));
    let p = write(
        "both.mtx",
        "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 2 1.0\n1 1 4.0\n2 1 1.0\n",
    );
    let e = matrix_market::read_matrix(&p).unwrap_err();
    assert_eq!((e.line(), e.entity()), (Some(5), Some("entry (2,1)")));
    assert!(e.to_string().contains("both triangles"));
    // a general file with both triangles equal gives the upper triangle, column by column
    let p = write(
        "general.mtx",
        "%%MatrixMarket matrix coordinate real general\n3 3 6\n3 1 2.0\n1 1 4.0\n1 3 2.0\n\
         2 2 5.0\n3 3 6.0\n2 3 0.0\n",
    );
    let t = matrix_market::read_matrix(&p).unwrap();
    assert_eq!(
        t.upper,
        vec![
            (0, 0, 4.0),
            (1, 1, 5.0),
            (0, 2, 2.0),
            (1, 2, 0.0),
            (2, 2, 6.0)
        ]
    );
    let p = write("nodes.txt", "1 0 0 0 3\n2 0 0 x 3\n");
    let e = matrix_market::read_node_table(&p).unwrap_err();
    assert_eq!((e.line(), e.entity()), (Some(2), Some("node 2")));
    let p = write("nodes2.txt", "1 0 0 0 4\n");
    assert!(matrix_market::read_node_table(&p)
        .unwrap_err()
        .to_string()
        .contains("3 or 6"));
}

/// Truncated and byte-corrupted versions of real files (deterministic pseudo-random edits)
/// must come back as `Ok` or `Err`, never as a panic.
#[test]
fn corrupted_files_never_panic() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = [
        root.join("fixtures/reference/e_matrices/hex8_single/mesh.inp"),
        root.join("fixtures/reference/e_matrices/hex8_single/mesh.bdf"),
        root.join("fixtures/reference/e_matrices/tet10_single/mesh.msh"),
        root.join("fixtures/import/nastran/free_cbar_line_cd30.bdf"),
        root.join("fixtures/models/planar_beam/beam.blk"),
        root.join("fixtures/import/hex8_block_coarse_bin.msh"),
    ];
    let dir = tmp_dir().join("corrupt");
    std::fs::create_dir_all(&dir).unwrap();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut rand = move |n: usize| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n as u64) as usize
    };
    let mut errors = 0;
    for f in &files {
        let bytes = std::fs::read(f).unwrap();
        let ext = f.extension().unwrap().to_str().unwrap();
        for k in 0..150 {
            let mut b = bytes.clone();
            match k % 3 {
                0 => b.truncate(rand(b.len())),
                1 => {
                    for _ in 0..1 + rand(4) {
                        let i = rand(b.len());
                        b[i] = [b'x', b',', b'\n', b' ', b'9', b'-', 0xff, b'*', b'+'][rand(9)];
                    }
                }
                _ => {
                    let i = rand(b.len());
                    let j = (i + 1 + rand(64)).min(b.len());
                    b.drain(i..j);
                }
            }
            let path = dir.join(format!("c.{ext}"));
            std::fs::write(&path, &b).unwrap();
            if read_model(&path, &ImportOptions::default()).is_err() {
                errors += 1;
            }
        }
    }
    // Most edits break something; the point is that none of them panicked.
    assert!(errors > 100, "{errors}");
}

/// Huge id ranges (a corrupted GENERATE or THRU bound) are refused instead of exhausting memory.
#[test]
fn huge_ranges_are_refused() {
    let dir = tmp_dir();
    let p = dir.join("range.inp");
    std::fs::write(
        &p,
        "*NODE\n1, 0, 0, 0\n*NSET, NSET=A, GENERATE\n1, 999999999999, 1\n",
    )
    .unwrap();
    let e = read_model(&p, &ImportOptions::default()).unwrap_err();
    assert_eq!((e.line(), e.entity()), (Some(4), Some("*NSET A")));
    let p = dir.join("range.bdf");
    std::fs::write(&p, "GRID,1,,0.,0.,0.\nSPC1,1,123,1,THRU,999999999999\n").unwrap();
    let e = read_model(&p, &ImportOptions::default()).unwrap_err();
    assert_eq!((e.line(), e.entity()), (Some(2), Some("SPC1 1")));
}
