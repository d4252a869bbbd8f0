//! Archives written by other tools (ANSYS MAPDL 2022+, Workbench, Ansys Prime, HyperMesh; copied
//! unchanged under their MIT licence in `tests/data/ansys_public/`, see its README) and the
//! forms of CDWRITE they showed: ETBLOCK and DBLOCK, the unblocked `UNBL` records, per-column
//! format widths, `MP` lines with `!` comments, solution and selection commands, the IGES
//! prologue, SECBLOCK shell layers, the archive's SFE value lines, TB tables and PSTRES.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::ansys_support::writers::{
    block, block_archive, build_body, eblock, frequency_difference, lumped_load_differences,
    material, nblock, response_difference, root, static_response, RESIDUALS, STEEL,
};
use crate::common::{exe, scratch};

/// SOLID186 with full integration (one-element-thick blocks of the reduced 2×2×2 form have
/// zero-energy modes).
const SOLID186_FULL: &str = "ET,1,186\nKEYOPT,1,2,1\n";

fn public(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ansys_public")
        .join(name)
}

/// `flexbody build PATH --units si --method normal --modes N EXTRA…`: exit code and stderr.
fn try_build(path: &Path, modes: usize, extra: &[&str]) -> (Option<i32>, String) {
    try_build_in(path, "si", modes, extra)
}

/// [`try_build`] in other `--units`.
fn try_build_in(path: &Path, units: &str, modes: usize, extra: &[&str]) -> (Option<i32>, String) {
    let o = exe()
        .arg("build")
        .arg(path)
        .args([
            "--units",
            units,
            "--method",
            "normal",
            "--modes",
            &modes.to_string(),
        ])
        .args(extra)
        .arg("-o")
        .arg(path.with_extension("flexbody"))
        .output()
        .unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// The Turek–Hron elastic beam as a Workbench 2022+ archive (ETBLOCK with SOLID186
/// KEYOPT(2)=1, DBLOCK holding UZ everywhere and the clamp, UNBL material records, an SFEBLOCK
/// of FSIN): its first bending frequency is the plane-strain Euler–Bernoulli cantilever's,
/// f₁ = (1.8751²/2π) √(E′h²/(12ρL⁴)), E′ = E/(1 − ν²), h = 0.02, L = 0.35101 (from the
/// cylinder's surface, x = 0.2 + √(0.05² − 0.01²), to x = 0.6), E = 1.4e6, ν = 0.4, ρ = 1e4.
#[test]
fn turek_hron_workbench_archive_gives_the_cantilever_frequency() {
    let path = scratch("ansys-public-turek").join("turek.cdb");
    std::fs::copy(public("turek_hron_benchmark_solid.cdb"), &path).unwrap();
    let body = build_body(&path, 2, &[]);
    let (e, nu, rho, h) = (1.4e6, 0.4, 1.0e4, 0.02);
    let l = 0.6 - (0.2 + (0.05f64 * 0.05 - 0.01 * 0.01).sqrt());
    let beta2 = 1.875_104_068_7f64.powi(2);
    let f1 = beta2 / (2.0 * std::f64::consts::PI)
        * (e / (1.0 - nu * nu) * h * h / (12.0 * rho * l.powi(4))).sqrt();
    let ours = body.modes.frequency_hz[0];
    println!("Turek–Hron beam: {ours:.6} Hz against plane-strain Euler–Bernoulli {f1:.6} Hz");
    // measured +1.8e-3 (the clamp on the curved surface, shear, the mesh)
    assert!(((ours - f1) / f1).abs() < 5e-3, "{ours} {f1}");

    // the ETBLOCK record's fourth column is KEYOPT(2): the same archive with ET/KEYOPT lines
    // gives the same body, and KEYOPT(2)=0 (reduced integration) another
    let text = std::fs::read_to_string(&path).unwrap();
    let etblock = "ETBLOCK,        1,        1\n(2i9,19a9)\n        1      186        0        1        0        0        0        0        0        0        0        0        0        0        0        0        0        0        0        0        0\n       -1\n";
    assert!(text.contains(etblock));
    let with_et = |keyopt2: u32| {
        let p = path.with_file_name(format!("et{keyopt2}.cdb"));
        let et = format!("ET,1,186\nKEYOPT,1,2,{keyopt2}\n");
        std::fs::write(&p, text.replace(etblock, &et)).unwrap();
        build_body(&p, 2, &[])
    };
    let same = frequency_difference(&body, &with_et(1), 2);
    let reduced = frequency_difference(&body, &with_et(0), 2);
    println!("ETBLOCK vs ET,1,186 + KEYOPT,1,2,1: {same:.1e}; vs KEYOPT(2)=0: {reduced:.1e}");
    // measured 0 (the same matrices) and 2.6e-4
    assert!(same < 1e-12, "{same}");
    assert!(reduced > 1e-5, "{reduced}");
}

/// The Turek–Hron archive's `SFEBLOCK` (as ANSYS 2024 R2's `CDWRITE` writes it: element, LKEY,
/// KVAL, VAL1…VAL4) names the beam's wet surface by the Element Reference's SOLID186 face
/// numbers: its 126 FSIN records, read as a pressure (the label turned into PRES), load the
/// body as `SFE` commands on the 126 boundary faces this test finds on the top (y = 0.21), the
/// bottom (y = 0.19) and the tip (x = 0.6) by their coordinates.
#[test]
fn turek_hron_sfeblock_names_the_wet_faces() {
    let text = std::fs::read_to_string(public("turek_hron_benchmark_solid.cdb")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let after = |head: &str| 2 + lines.iter().position(|l| l.starts_with(head)).unwrap();
    // NBLOCK (3i9,6e21.13e3): blank coordinates are zero
    let mut nodes = BTreeMap::new();
    for l in lines[after("NBLOCK")..]
        .iter()
        .take_while(|l| !l.starts_with('N'))
    {
        let x: [f64; 3] = std::array::from_fn(|j| {
            let col = l.get(27 + 21 * j..48 + 21 * j).unwrap_or("").trim();
            if col.is_empty() {
                0.0
            } else {
                col.parse().unwrap()
            }
        });
        nodes.insert(l[..9].trim().parse::<u64>().unwrap(), x);
    }
    // EBLOCK (19i10): 11 attributes, the element's number last, 20 nodes over two lines
    let ints = |l: &str| -> Vec<u64> {
        (0..l.trim_end().len() / 10)
            .map(|k| l[10 * k..10 * k + 10].trim().parse().unwrap())
            .collect()
    };
    let mut bricks = BTreeMap::new();
    let records = &lines[after("EBLOCK")..];
    for pair in records
        .chunks(2)
        .take_while(|p| !p[0].trim().starts_with("-1"))
    {
        let (head, rest) = (ints(pair[0]), ints(pair[1]));
        let corners: Vec<u64> = head[11..].iter().chain(&rest).take(8).copied().collect();
        bricks.insert(head[10], corners);
    }
    assert_eq!(bricks.len(), 360);
    // the boundary faces on the wet planes, by the SOLID186 face list (corners 0-based)
    const FACES: [[usize; 4]; 6] = [
        [1, 0, 3, 2],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
        [4, 5, 6, 7],
    ];
    let key = |c: &[u64], f: &[usize; 4]| {
        let mut k: Vec<u64> = f.iter().map(|&i| c[i]).collect();
        k.sort_unstable();
        k
    };
    let mut uses: BTreeMap<Vec<u64>, usize> = BTreeMap::new();
    for c in bricks.values() {
        for f in &FACES {
            *uses.entry(key(c, f)).or_default() += 1;
        }
    }
    let on = |c: &[u64], f: &[usize; 4], axis: usize, at: f64| {
        f.iter().all(|&i| (nodes[&c[i]][axis] - at).abs() < 1e-9)
    };
    let mut sfe = String::new();
    for (e, c) in &bricks {
        for (k, f) in FACES.iter().enumerate() {
            let wet = on(c, f, 1, 0.21) || on(c, f, 1, 0.19) || on(c, f, 0, 0.6);
            if wet && uses[&key(c, f)] == 1 {
                sfe += &format!("SFE,{e},{},PRES,0,1.0\n", k + 1);
            }
        }
    }
    let found = sfe.lines().count();
    // the archive's block: its label as PRES, or replaced by the SFE commands found
    let begin = text.find("SFEBLOCK,4,FSIN").unwrap();
    let end = begin + text[begin..].find("SFE,end,LOC").unwrap();
    let end = end + text[end..].find('\n').unwrap() + 1;
    let block = &text[begin..end];
    let work = scratch("ansys-public-turek-sfeblock");
    let (a, b) = (work.join("sfeblock.cdb"), work.join("sfe.cdb"));
    std::fs::write(&a, text.replace("SFEBLOCK,4,FSIN", "SFEBLOCK,4,PRES")).unwrap();
    std::fs::write(&b, text.replace(block, &sfe)).unwrap();
    let (ua, ub) = (
        static_response(&build_body(&a, 4, &RESIDUALS), 0),
        static_response(&build_body(&b, 4, &RESIDUALS), 0),
    );
    let worst = response_difference(&ua, &ub);
    let records = block
        .lines()
        .filter(|l| l.get(13..17) == Some("   1"))
        .count();
    println!("Turek–Hron SFEBLOCK: {records} faces in the block, {found} wet faces found; static responses {worst:.2e}");
    assert_eq!((records, found), (126, 126));
    // measured 0: the same pressures, the same body
    assert_eq!(worst, 0.0);
}

/// DBLOCK records are D commands: a block archive clamped by a DBLOCK (CDWRITE's format
/// (i9,a6,2(pg16.9))) equals the same archive clamped by D lines.
#[test]
fn dblock_equals_its_d_commands() {
    let m = block([4, 1, 1], [0.4, 0.1, 0.1], true);
    let clamp = root(&m);
    let d_lines: String = (clamp.iter())
        .flat_map(|n| ["UX", "UY", "UZ"].map(|l| format!("D,{n},{l},0.0,0.0\n")))
        .collect();
    let mut dblock = format!("DBLOCK,{}\n(i9,a6,2(pg16.9))\n", 3 * clamp.len());
    for n in &clamp {
        for l in ["UX", "UY", "UZ"] {
            dblock.push_str(&format!(
                "{n:>9}  {l:<4}{:>16}{:>16}\n",
                "0.00000000", "0.00000000"
            ));
        }
    }
    dblock.push_str("       -1\n");
    let work = scratch("ansys-public-dblock");
    let (a, b) = (work.join("d.cdb"), work.join("dblock.cdb"));
    std::fs::write(
        &a,
        block_archive(&m, SOLID186_FULL, &BTreeMap::new(), &d_lines),
    )
    .unwrap();
    std::fs::write(
        &b,
        block_archive(&m, SOLID186_FULL, &BTreeMap::new(), &dblock),
    )
    .unwrap();
    let diff = frequency_difference(&build_body(&a, 4, &[]), &build_body(&b, 4, &[]), 4);
    assert!(diff < 1e-12, "{diff}");
    // a nonzero value in a record is refused by that record's line
    let bad = work.join("bad.cdb");
    let moved = dblock.replacen(
        "0.00000000      0.00000000",
        "0.00100000      0.00000000",
        1,
    );
    std::fs::write(
        &bad,
        block_archive(&m, SOLID186_FULL, &BTreeMap::new(), &moved),
    )
    .unwrap();
    let (code, err) = try_build(&bad, 4, &[]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("D with a nonzero value"), "{err}");
}

/// Ansys Prime's cube (216 SOLID185, 32 mm, steel by `MP, EX, 1, 2e11, !Pa` lines with unit
/// comments): the body's mass is ρ a³ and its inertia about the centre m a²/6 (MP's C0 was
/// taken for a temperature coefficient before, and every MP refused).
#[test]
fn prime_cube_reads_mp_with_comments() {
    let path = scratch("ansys-public-prime").join("hex.cdb");
    std::fs::copy(public("prime_hex.cdb"), &path).unwrap();
    let body = build_body(&path, 6, &[]);
    let a = 0.032f64;
    let mass = 7850.0 * a.powi(3);
    let inv = &body.invariants;
    let m = inv.i1[0];
    println!("Prime cube: mass {m:.9e} against ρa³ {mass:.9e}");
    // measured 2.3e-9: the file's coordinates are single precision (3.2000001519918e-02)
    assert!(((m - mass) / mass).abs() < 2e-8, "{m} {mass}");
    // about the centre c = I2/m: J = I7 − m (|c|² 1 − c cᵀ)
    let c: Vec<f64> = inv.i2.iter().map(|v| v / m).collect();
    let cc: f64 = c.iter().map(|v| v * v).sum();
    let want = mass * a * a / 6.0;
    for (k, ck) in c.iter().enumerate() {
        let j = inv.i7[4 * k] - m * (cc - ck * ck);
        // measured ~4e-9 (single-precision coordinates)
        assert!(((j - want) / want).abs() < 4e-8, "{j} {want}");
    }
}

/// A HyperMesh export: its selection, component and solution commands (`CM`, `ESEL`, `/SOLU`,
/// `MXPAND`, `EQSLV`, `PSTRES,OFF`, `SOLVE`) are noted, not refused: with SHELL181's
/// KEYOPT(3)=2 set, the archive builds.
#[test]
fn hypermesh_solution_commands_are_noted() {
    let text = std::fs::read_to_string(public("hypermesh.cdb")).unwrap();
    assert!(text.contains("ET,1,181\r\n"));
    let path = scratch("ansys-public-hypermesh").join("hm.cdb");
    std::fs::write(
        &path,
        text.replace("ET,1,181\r\n", "ET,1,181\r\nKEYOPT,1,3,2\r\n"),
    )
    .unwrap();
    // the archive's material is in mm, t, s (E = 72000 MPa, ρ = 2.57e-9 t/mm³); a free plate
    let (code, err) = try_build_in(&path, "mm-t-s", 10, &[]);
    assert_eq!(code, Some(0), "{err}");
    for name in ["CM ", "ESEL", "/SOLU", "MXPAND", "EQSLV", "PSTRES", "SOLVE"] {
        assert!(err.contains(name), "{name} not noted: {err}");
    }
}

/// Workbench 2019 R1 writes the NBLOCK as (1i7,2i9,6e21.13): each column is read by its own
/// width (the 7-wide node number read as 9 cut the coordinates). The archive holds three nodes
/// and no element: the build says so, not a number error.
#[test]
fn workbench_nblock_columns_have_their_own_widths() {
    let path = scratch("ansys-public-wb193").join("wb.cdb");
    std::fs::copy(public("workbench_193.cdb"), &path).unwrap();
    let (code, err) = try_build(&path, 1, &[]);
    assert_eq!(code, Some(2), "{err}");
    assert!(!err.contains("bad number"), "{err}");
    assert!(err.contains("no element"), "{err}");
}

/// `CDWRITE,DB,…,IGES` puts the solid model as an IGES file (S, G, D, P, T sections with
/// sequence numbers in columns 73–80) before the label `:CDWRITE`: the archive after it builds
/// as the archive alone.
#[test]
fn the_iges_prologue_is_skipped() {
    let m = block([3, 1, 1], [0.3, 0.1, 0.1], true);
    let clamp: String = root(&m).iter().map(|n| format!("D,{n},ALL,0\n")).collect();
    let plain = block_archive(&m, SOLID186_FULL, &BTreeMap::new(), &clamp);
    let seq = |s: &str, tag: char, k: usize| format!("{s:<72}{tag}{k:>7}\n");
    let prologue = [
        seq("wbnew--Static Structural", 'S', 1),
        seq("/PREP7", 'S', 2),
        seq("TREF,0.00000000", 'S', 3),
        seq("1H,,1H;,,11HD:/OneDrive,", 'G', 1),
        seq("S      3G      1D      0P      0", 'T', 1),
        ":CDWRITE      ! START OF CDWRITE DATA\n".to_string(),
    ]
    .concat();
    let work = scratch("ansys-public-iges");
    let (a, b) = (work.join("plain.cdb"), work.join("iges.cdb"));
    std::fs::write(&a, &plain).unwrap();
    std::fs::write(&b, format!("{prologue}{plain}")).unwrap();
    let diff = frequency_difference(&build_body(&a, 4, &[]), &build_body(&b, 4, &[]), 4);
    assert!(diff < 1e-12, "{diff}");
}

/// The unblocked archive (`CDWRITE,…,UNBLOCKED`) writes `MPTEMP,UNBL`/`MPDATA,UNBL` where the
/// blocked one writes `R5.0`, and `LOCAL,R5.0,LOC|ANG|PRM,KCN,…`: the same material, and an
/// isotropic element whose ESYS names such a system is the same body.
#[test]
fn unblocked_records_equal_blocked_ones() {
    let m = block([3, 1, 1], [0.3, 0.1, 0.1], true);
    let clamp: String = root(&m).iter().map(|n| format!("D,{n},ALL,0\n")).collect();
    let blocked = block_archive(&m, SOLID186_FULL, &BTreeMap::new(), &clamp);
    let unblocked = blocked.replace("R5.0", "UNBL");
    assert_ne!(blocked, unblocked);
    let work = scratch("ansys-public-unbl");
    let (a, b) = (work.join("r50.cdb"), work.join("unbl.cdb"));
    std::fs::write(&a, &blocked).unwrap();
    std::fs::write(&b, &unblocked).unwrap();
    let diff = frequency_difference(&build_body(&a, 4, &[]), &build_body(&b, 4, &[]), 4);
    assert!(diff < 1e-12, "{diff}");
    // element 1 in system 12, written LOCAL,UNBL as CDWRITE writes it (ESYS is EBLOCK field 5)
    let local = "LOCAL,UNBL,LOC,      12, 0,  0.0    ,  0.0    ,  0.0    \n\
                 LOCAL,UNBL,ANG,      12, 0,  30.0   ,  0.0    ,  0.0    \n\
                 LOCAL,UNBL,PRM,      12, 0,  1.0    ,  1.0    \n";
    let records: Vec<(usize, usize, Vec<u64>)> =
        m.elements.iter().map(|e| (1, 1, e.clone())).collect();
    let mut eb = eblock(&records);
    let first = eb.lines().nth(2).unwrap().to_string();
    let mut fields: Vec<String> = (0..first.len() / 9)
        .map(|k| first[9 * k..9 * k + 9].to_string())
        .collect();
    fields[4] = format!("{:>9}", 12);
    eb = eb.replacen(&first, &fields.concat(), 1);
    let nodes: Vec<(u64, [f64; 3], [f64; 3])> =
        m.nodes.iter().map(|(&id, &x)| (id, x, [0.0; 3])).collect();
    let text = format!(
        "/PREP7\n{SOLID186_FULL}{local}{}{eb}{}{clamp}FINISH\n",
        nblock(&nodes),
        material(STEEL).replace("R5.0", "UNBL")
    );
    let c = work.join("esys.cdb");
    std::fs::write(&c, text).unwrap();
    // an isotropic material: the system changes nothing (tests/ansys_orthotropic.rs orients an
    // orthotropic one by it)
    let diff = frequency_difference(&build_body(&c, 4, &[]), &build_body(&a, 4, &[]), 4);
    assert!(diff < 1e-12, "{diff}");
}

/// A 4 × 3 SHELL181 plate (KEYOPT(3)=2), clamped at x = 0, its section given by `extra`.
fn plate(section: &str, extra: &str) -> String {
    let (nx, ny) = (4usize, 3usize);
    let id = |i: usize, j: usize| (j * (nx + 1) + i + 1) as u64;
    let mut nodes = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            nodes.push((id(i, j), [0.2 * i as f64, 0.2 * j as f64, 0.0], [0.0; 3]));
        }
    }
    let mut records = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            records.push((
                1,
                1,
                vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
            ));
        }
    }
    let clamp: String = (0..=ny)
        .map(|j| format!("D,{},ALL,0\n", id(0, j)))
        .collect();
    format!(
        "/PREP7\nET,1,181\nKEYOPT,1,3,2\nSECTYPE,1,SHELL,,\n{section}{}{}{}{clamp}{extra}FINISH\n",
        nblock(&nodes),
        eblock(&records),
        material(STEEL)
    )
}

/// CDWRITE writes a shell section's layers as `SECBLOCK,NLAYERS` and one record per layer
/// (thickness, material, angle, points): the same shell as `SECDATA`; and the archive's SFE
/// form (`SFE,Elem,LKEY,PRES,KVAL,R5.0` and the values on the next line) the same pressures as
/// the command form.
#[test]
fn secblock_layers_and_sfe_records_equal_their_command_forms() {
    let work = scratch("ansys-public-secblock");
    let secdata = "SECOFFSET,MID\nSECDATA,0.01,1,0.0,3\n";
    let secblock = "SECOFFSET,MID\nSECBLOCK,      1\n     0.010000,         1,     0.000000,         3\n\
                    SECCONTROL,  0.0000    ,  0.0000    ,  0.0000    ,  0.0000    ,  1.0000    ,  1.0000    ,  1.0000    ,,,,,  0.0000    \n";
    let command: String = (1..=12)
        .map(|e| format!("SFE,{e},1,PRES,0,{:e}\n", 1.0e3 * e as f64))
        .collect();
    let record: String = (1..=12)
        .map(|e| {
            let p = format!("{:.6e}", 1.0e3 * e as f64);
            format!("SFE,{e:>8},   1,PRES,1,R5.0\n{p:>16}{p:>16}{p:>16}{p:>16}\n")
        })
        .collect();
    let (a, b) = (work.join("secdata.cdb"), work.join("secblock.cdb"));
    std::fs::write(&a, plate(secdata, &command)).unwrap();
    std::fs::write(&b, plate(secblock, &record)).unwrap();
    let (modes, response) = lumped_load_differences(&b, &a, 6);
    println!("SECBLOCK + SFE records against SECDATA + SFE commands: {modes:.1e}, {response:.1e}");
    assert!(modes < 1e-12 && response < 1e-12, "{modes} {response}");
    // a thermal SFE (CONV) is noted, not refused
    let c = work.join("conv.cdb");
    let conv = "SFE,       1,   1,CONV,1,R5.0\n  300.000000      300.000000      300.000000      300.000000    \n";
    std::fs::write(&c, plate(secdata, conv)).unwrap();
    let (code, err) = try_build(&c, 4, &[]);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("SFE CONV"), "{err}");
}

/// TB tables by label (plasticity and failure criteria noted, an anisotropic elastic table
/// refused), PSTRES (OFF noted, ON refused: the archive's prestress is not formed), CMDEL (the
/// component is gone), a component naming a refused element (the refusal, not "unknown
/// element").
#[test]
fn material_tables_prestress_and_components() {
    let m = block([3, 1, 1], [0.3, 0.1, 0.1], true);
    let clamp: String = root(&m).iter().map(|n| format!("D,{n},ALL,0\n")).collect();
    let work = scratch("ansys-public-tb");
    let build = |name: &str, extra: &str, args: &[&str]| {
        let p = work.join(name);
        std::fs::write(
            &p,
            block_archive(
                &m,
                SOLID186_FULL,
                &BTreeMap::new(),
                &format!("{clamp}{extra}"),
            ),
        )
        .unwrap();
        try_build(&p, 2, args)
    };
    let noted =
        "TB,PLAS,       1,   1,,BISO\nTBTEMP,0\nTBDATA,1,2.5e8,1.0e9\nTB,FCLI,1,1,20,STRS\n\
                 TBFIELD,Temps,0.0\nPSTRES,OFF\n";
    let (code, err) = build("noted.cdb", noted, &[]);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        err.contains("TB,PLAS") && err.contains("TB,FCLI") && err.contains("PSTRES"),
        "{err}"
    );
    let (code, err) = build(
        "anel.cdb",
        "TB,ANEL,1\nTBDATA,1,2e11,1e11,1e11\nPSTRES,ON\n",
        &[],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("TB,ANEL: the table defines or changes the elastic stiffness"),
        "{err}"
    );
    assert!(err.contains("PSTRES,ON"), "{err}");
    // CMDEL removes the component: its name is no interface any more
    let tip: Vec<String> = (m.nodes.iter())
        .filter(|(_, x)| x[0] == 0.3)
        .map(|(id, _)| format!("{id:>10}"))
        .collect();
    let comp = format!(
        "CMBLOCK,TIP,NODE,{:>8}\n(8i10)\n{}\n",
        tip.len(),
        tip.chunks(8)
            .map(|c| c.concat())
            .collect::<Vec<_>>()
            .join("\n")
    );
    let (code, err) = build("kept.cdb", &comp, &["--interface", "TIP"]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = build(
        "deleted.cdb",
        &format!("{comp}CMDEL,TIP\n"),
        &["--interface", "TIP"],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("TIP"), "{err}");
    // an element component naming an element of a refused type: the refusal is what is said
    let refused = format!("ET,2,63\nCMBLOCK,ELS,ELEM,       1\n(8i10)\n{:>10}\n", 1);
    let text = block_archive(&m, SOLID186_FULL, &BTreeMap::new(), &clamp)
        .replace("FINISH\n", &format!("{refused}FINISH\n"));
    let text = text.replacen(
        "        1        1        1        1",
        "        1        2        1        1",
        1,
    );
    let p = work.join("refused.cdb");
    std::fs::write(&p, text).unwrap();
    let (code, err) = try_build(&p, 2, &[]);
    assert_eq!(code, Some(2), "{err}");
    assert!(!err.contains("unknown element"), "{err}");
    assert!(err.contains("element type 63"), "{err}");
}
