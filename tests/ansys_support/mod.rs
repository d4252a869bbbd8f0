//! What the ANSYS tests share: ansys-mapdl-reader's example files (`pip install
//! ansys-mapdl-reader`, MIT licence; read from the installed package, not committed), HexBeam
//! with the material its full file was solved with, the package's frequencies, and a normal
//! modes build through the CLI.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::common::{exe, skipped_install};

pub mod writers;
use flexbody::import::ansys::full;
use flexbody::import::matrix_market::read_matrix;

pub const INSTALL: &str = "pip install ansys-mapdl-reader";

/// The first 20 frequencies of `file.full` as the package states them (Hz;
/// `ansys/mapdl/reader/examples/examples.py`, `load_km`'s known result).
pub const PACKAGE_HZ: [f64; 20] = [
    1283.20036921,
    1283.20036921,
    5781.97486169,
    6919.39887714,
    6919.39887714,
    10172.61497694,
    16497.85701889,
    16497.85701889,
    17343.9939669,
    27457.18472747,
    27457.18472747,
    28908.52552073,
    30326.16886062,
    39175.76412419,
    39175.76412419,
    40503.70406456,
    49819.91597612,
    51043.03965541,
    51043.03965541,
    52193.86143879,
];

/// `python3 -c CODE`'s stdout, or `None` when it fails (package not installed).
pub fn python(code: &str) -> Option<String> {
    let o = Command::new("python3").args(["-c", code]).output().ok()?;
    o.status
        .success()
        .then(|| String::from_utf8_lossy(&o.stdout).trim().to_owned())
}

/// The installed package's `examples/` folder.
pub fn examples(what: &str) -> Option<PathBuf> {
    let dir =
        python("import ansys.mapdl.reader.examples as e, os; print(os.path.dirname(e.__file__))");
    match dir {
        Some(d) if Path::new(&d).join("HexBeam.cdb").is_file() => Some(PathBuf::from(d)),
        _ => {
            skipped_install(what, INSTALL);
            None
        }
    }
}

/// EX, NUXY, DENS of material 1 in `file.rst`, as ansys-mapdl-reader reads them.
pub fn rst_material(dir: &Path) -> [f64; 3] {
    let code = format!(
        "import ansys.mapdl.reader as r; m = r.read_binary(r'{}').materials[1]; \
         print(repr(float(m['EX'])), repr(float(m['NUXY'])), repr(float(m['DENS'])))",
        dir.join("file.rst").display()
    );
    let out = python(&code).expect("file.rst's materials");
    let v: Vec<f64> = out.split_whitespace().map(|s| s.parse().unwrap()).collect();
    [v[0], v[1], v[2]]
}

/// HexBeam.cdb with its three MPDATA values replaced by `file.rst`'s material, and `extra`
/// lines appended.
pub fn hexbeam_as_solved(dir: &Path, extra: &str) -> String {
    let text = std::fs::read_to_string(dir.join("HexBeam.cdb")).unwrap();
    let [ex, nu, rho] = rst_material(dir);
    let mut out = String::new();
    for line in text.lines() {
        let replaced = match line.get(..20) {
            Some("MPDATA,R5.0, 1,EX  ,") => format!("MPDATA,R5.0, 1,EX  ,       1, 1, {ex:e},"),
            Some("MPDATA,R5.0, 1,NUXY,") => format!("MPDATA,R5.0, 1,NUXY,       1, 1, {nu:e},"),
            Some("MPDATA,R5.0, 1,DENS,") => format!("MPDATA,R5.0, 1,DENS,       1, 1, {rho:e},"),
            _ => line.to_owned(),
        };
        out.push_str(&replaced);
        out.push('\n');
    }
    assert_eq!(out.matches("MPDATA").count(), 3);
    out.push_str(extra);
    out
}

/// `D,node,ALL,0` for every node the full file constrains (all its dofs are: the clamp).
pub fn clamp_lines(f: &full::FullFile) -> String {
    let mut nodes: Vec<u64> = (f.dofs.iter().zip(&f.constrained))
        .filter(|(_, c)| **c)
        .map(|(d, _)| d.node)
        .collect();
    nodes.dedup();
    for n in &nodes {
        let all = (f.dofs.iter().zip(&f.constrained)).filter(|(d, _)| d.node == *n);
        assert!(
            all.clone().all(|(_, c)| *c),
            "node {n} is clamped in every dof"
        );
    }
    nodes.iter().map(|n| format!("D,{n},ALL,0\n")).collect()
}

/// The relative differences of `ours` to the package's 20 frequencies.
pub fn against_package(ours: &[f64]) -> f64 {
    assert_eq!(ours.len(), 20, "{ours:?}");
    (ours.iter().zip(PACKAGE_HZ))
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(0.0, f64::max)
}

/// `flexbody build FILE --units si --method normal --modes N EXTRA… -o OUT` → frequencies.
pub fn build_modes(path: &Path, modes: usize, extra: &[&str]) -> Vec<f64> {
    let o = build(path, "si", modes, extra);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    flexbody_reader::read(path.with_extension("flexbody"))
        .unwrap()
        .modes
        .frequency_hz
}

/// `flexbody build FILE --units UNITS --method normal --modes N EXTRA… -o FILE.flexbody`: the
/// process output.
pub fn build(path: &Path, units: &str, modes: usize, extra: &[&str]) -> Output {
    exe()
        .arg("build")
        .arg(path)
        .args(["--units", units, "--method", "normal", "--modes"])
        .arg(modes.to_string())
        .args(extra)
        .arg("-o")
        .arg(path.with_extension("flexbody"))
        .output()
        .unwrap()
}

/// The 1-based number of the first line of `text` that contains `needle`.
pub fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("no line holds {needle:?}"))
        + 1
}

/// Writes `archive` as `refused.cdb` in the scratch folder `folder`, builds it and asserts that
/// the build exits 2 saying every `(line, what)` as `refused.cdb:LINE: …what…`.
pub fn assert_refused_at(archive: &str, folder: &str, units: &str, expected: &[(usize, &str)]) {
    let dir = crate::common::scratch(folder);
    let cdb = dir.join("refused.cdb");
    std::fs::write(&cdb, archive).unwrap();
    let o = build(&cdb, units, 4, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    for (line, what) in expected {
        let want = format!("refused.cdb:{line}: ");
        assert!(
            err.lines().any(|l| l.contains(&want) && l.contains(what)),
            "{want} {what}\n{err}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A file of the committed ANSYS data (`tests/data/ansys/`, MIT, its LICENSE beside it).
pub fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ansys")
        .join(name)
}

/// `(node id, component 0…5)` of each equation of `build --write-matrices`'s `dofs.txt`.
pub fn read_dofs(path: &Path) -> Vec<(u64, usize)> {
    let text = std::fs::read_to_string(path).unwrap();
    (text.lines())
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let f: Vec<u64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            (f[1], f[2] as usize - 1)
        })
        .collect()
}

/// y = A x for the symmetric matrix of a Matrix Market file.
pub fn multiply(path: &Path, x: &[f64]) -> Vec<f64> {
    let a = read_matrix(path).unwrap();
    let mut y = vec![0.0; a.n];
    for (r, c, v) in a.full() {
        y[r] += v * x[c];
    }
    y
}

/// The rows of a solution csv after its `skip` header lines: node id → its N numbers.
pub fn node_table<const N: usize>(text: &str, skip: usize) -> HashMap<u64, [f64; N]> {
    (text.lines().skip(skip))
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|t| t.parse().unwrap()).collect();
            (f[0] as u64, std::array::from_fn(|i| f[i + 1]))
        })
        .collect()
}

/// Nodes of a mesh: (id, xyz).
pub type Nodes = Vec<(u64, [f64; 3])>;

/// Nodes and elements (node ids) of one of our own small ccx decks (an element line ending in a
/// comma continues on the next).
pub fn read_inp(path: &Path) -> (Nodes, Vec<Vec<u64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let (mut nodes, mut elements, mut section) = (Vec::new(), Vec::new(), "");
    let mut pending: Vec<u64> = Vec::new();
    for line in text.lines() {
        if line.starts_with('*') {
            section = if line.starts_with("*NODE") {
                "node"
            } else if line.starts_with("*ELEMENT") {
                "element"
            } else {
                ""
            };
            continue;
        }
        let f: Vec<&str> = (line.split(','))
            .map(str::trim)
            .filter(|t| !t.is_empty())
            .collect();
        match section {
            "node" => nodes.push((
                f[0].parse().unwrap(),
                std::array::from_fn(|i| f[i + 1].parse().unwrap()),
            )),
            "element" => {
                pending.extend(f.iter().map(|t| t.parse::<u64>().unwrap()));
                if !line.trim_end().ends_with(',') {
                    elements.push(pending.split_off(1));
                    pending.clear();
                }
            }
            _ => {}
        }
    }
    (nodes, elements)
}

/// The ccx deck `fixtures/FOLDER/STEM.inp`'s nodes and its 15-node wedges and 10-node
/// tetrahedra as ANSYS's degenerate 20-node bricks ([`wedge_as_brick`], [`tet_as_brick`]).
pub fn ccx_deck_as_bricks(folder: &str, stem: &str) -> (Nodes, Vec<Vec<u64>>) {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join(folder)
        .join(format!("{stem}.inp"));
    let (nodes, elements) = read_inp(&deck);
    let bricks = (elements.iter())
        .map(|n| match n.len() {
            15 => wedge_as_brick(n),
            10 => tet_as_brick(n),
            other => panic!("{}: {other} nodes", deck.display()),
        })
        .collect();
    (nodes, bricks)
}

/// A C3D15 wedge as ANSYS writes a degenerate SOLID186 (I J K K M N O O, Q R K T, U V O X,
/// Y Z A A): corners 1–6, edges 12, 23, 31, 45, 56, 64, 14, 25, 36.
pub fn wedge_as_brick(n: &[u64]) -> Vec<u64> {
    vec![
        n[0], n[1], n[2], n[2], n[3], n[4], n[5], n[5], n[6], n[7], n[2], n[8], n[9], n[10], n[5],
        n[11], n[12], n[13], n[14], n[14],
    ]
}

/// A C3D10 tetrahedron as ANSYS writes a degenerate SOLID186 (I J K K M M M M, Q R K T,
/// M M M M, Y Z A A): corners 1–4, edges 12, 23, 31, 14, 24, 34.
pub fn tet_as_brick(n: &[u64]) -> Vec<u64> {
    vec![
        n[0], n[1], n[2], n[2], n[3], n[3], n[3], n[3], n[4], n[5], n[2], n[6], n[3], n[3], n[3],
        n[3], n[7], n[8], n[9], n[9],
    ]
}

/// The NBLOCK of `nodes` and an EBLOCK of `elements` (type, material, real and section 1, ESYS
/// `esys`, ids 1, 2, …; records of 19 ten-wide fields per line) as CDWRITE writes solids.
pub fn solid_blocks<'a>(
    nodes: impl ExactSizeIterator<Item = (&'a u64, &'a [f64; 3])>,
    elements: &[Vec<u64>],
    esys: u64,
) -> String {
    let mut s = format!(
        "NBLOCK,6,SOLID,{0:>10},{0:>10}\n(3i9,6e21.13e3)\n",
        nodes.len()
    );
    for (id, p) in nodes {
        s += &format!(
            "{id:>9}{:>9}{:>9}{:>21.13E}{:>21.13E}{:>21.13E}\n",
            0, 0, p[0], p[1], p[2]
        );
    }
    s += "N,R5.3,LOC,       -1,\n";
    s += &format!("EBLOCK,19,SOLID,{0:>10},{0:>10}\n(19i10)\n", elements.len());
    for (e, n) in elements.iter().enumerate() {
        let head = [1, 1, 1, 1, esys, 0, 0, 0, n.len() as u64, 0, e as u64 + 1];
        let record: Vec<u64> = head.iter().chain(n).copied().collect();
        for line in record.chunks(19) {
            s += &line.iter().map(|v| format!("{v:>10}")).collect::<String>();
            s.push('\n');
        }
    }
    s + "        -1\n"
}

/// An archive of SOLID186 (KEYOPT(2)=`keyopt2`) records on `nodes`, steel as the ccx decks,
/// clamped at x = 0.
pub fn solid186_archive(nodes: &[(u64, [f64; 3])], bricks: &[Vec<u64>], keyopt2: u32) -> String {
    let mut s = format!("ET,        1,186\nKEYOP,        1, 2,        {keyopt2}\n");
    s += &solid_blocks(nodes.iter().map(|(id, p)| (id, p)), bricks, 0);
    s += "MPTEMP,R5.0, 1, 1,  0.00000000    ,\n";
    for (label, v) in [("EX", 2.1e11), ("NUXY", 0.3), ("DENS", 7850.0)] {
        s += &format!("MPDATA,R5.0, 1,{label:<4},       1, 1, {v:e},\n");
    }
    for (id, p) in nodes {
        if p[0] == 0.0 {
            s += &format!("D,{id},ALL,0\n");
        }
    }
    s
}
