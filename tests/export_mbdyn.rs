//! Issue 18, `flexbody export --to mbdyn`: the modal element's `.fem` file read by a small
//! parser written from MBDyn's input manual ("Modal Element Data — FEM File Format"), not from
//! our writer: `** RECORD GROUP <RID>` starts a record, other `**` lines are comments, every
//! record's size follows from the header (NMODES = NNORMAL + NATTACHED + NCONSTRAINT −
//! NREJECTED), matrices column-major, record 11 six lumped inertia coefficients per node,
//! record 12 mass, centre of mass and inertia about it. The parser is first checked on the
//! manual's own example (its stated mass 3, centre 0, J = diag(11, 3, 11)); then on the bundled
//! conrod (tet10, CB, damping) and the planar beam (beam nodes with rotations and rotary
//! inertia): the manual's constraint m = Xᵀ M X between records 8, 9 and 11, k_ii = ω_i² m_ii
//! against the file's frequencies, record 12 against the inertia computed from records 5–7 and
//! 11, and every value against the `.flexbody` file.
//!
//! Issue 36: the file also reads as Blender's Blendyn add-on reads it (`modallib.py`,
//! `parse_modal_fem_file`, restated below from its logic): that reader walks fixed line counts
//! (a record's title, then its values; a bare `**` line between records, as femgen writes), so
//! the export must have femgen's layout, not only the manual's tokens.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use flexbody_reader as file;

/// A `.fem` file as the manual describes it.
#[derive(Debug)]
struct Fem {
    labels: Vec<String>,
    nmodes: usize,
    x: Vec<[f64; 3]>,
    /// shapes[mode][node][component]
    shapes: Vec<Vec<[f64; 6]>>,
    /// Row-major after reading column-major.
    mass: Vec<f64>,
    stiffness: Vec<f64>,
    lumped: Option<Vec<[f64; 6]>>,
    /// mass, centre of mass, J about the centre of mass (row-major)
    global: Option<(f64, [f64; 3], [f64; 9])>,
    damping: Option<Vec<f64>>,
}

/// Parses the manual's format: tokens of each record group, sizes from the header.
fn parse_fem(text: &str) -> Result<Fem, String> {
    let mut groups: BTreeMap<u32, Vec<String>> = BTreeMap::new();
    let mut current: Option<u32> = None;
    let mut ended = false;
    for (ln, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(rest) = t.strip_prefix("**") {
            let rest = rest.trim();
            if let Some(r) = rest.strip_prefix("RECORD GROUP") {
                let rid: String = r
                    .trim()
                    .chars()
                    .take_while(|c| c.is_ascii_digit())
                    .collect();
                let rid: u32 = rid
                    .parse()
                    .map_err(|_| format!("line {}: bad record id", ln + 1))?;
                if groups.insert(rid, Vec::new()).is_some() {
                    return Err(format!("line {}: record group {rid} twice", ln + 1));
                }
                current = Some(rid);
            } else if rest.starts_with("END OF FILE") {
                ended = true;
                current = None;
            }
            continue;
        }
        if t.is_empty() {
            continue;
        }
        let Some(rid) = current else {
            return Err(format!("line {}: data outside a record group", ln + 1));
        };
        groups
            .get_mut(&rid)
            .unwrap()
            .extend(t.split_whitespace().map(String::from));
    }
    if !ended {
        return Err("no END OF FILE".into());
    }
    let reals = |rid: u32, count: usize| -> Result<Option<Vec<f64>>, String> {
        let Some(tokens) = groups.get(&rid) else {
            return Ok(None);
        };
        if tokens.len() != count {
            return Err(format!(
                "record group {rid}: {} values, expected {count}",
                tokens.len()
            ));
        }
        tokens
            .iter()
            .map(|t| {
                t.parse::<f64>()
                    .map_err(|e| format!("record {rid}: {t}: {e}"))
            })
            .collect::<Result<Vec<_>, _>>()
            .map(Some)
    };
    let header = groups.get(&1).ok_or("no record group 1")?;
    if header.len() != 6 {
        return Err(format!("header has {} fields", header.len()));
    }
    let h: Vec<usize> = header[1..]
        .iter()
        .map(|t| t.parse().map_err(|e| format!("header {t}: {e}")))
        .collect::<Result<_, String>>()?;
    let (nnodes, nmodes) = (h[0], h[1] + h[2] + h[3] - h[4]);
    let labels = groups.get(&2).ok_or("no record group 2")?.clone();
    if labels.len() != nnodes {
        return Err(format!("{} labels for {nnodes} nodes", labels.len()));
    }
    for rid in [3, 4] {
        if let Some(v) = reals(rid, nmodes)? {
            assert!(v.iter().all(|&x| x == 0.0), "initial modal state not zero");
        }
    }
    let xs: Vec<Vec<f64>> = (5..=7)
        .map(|rid| reals(rid, nnodes)?.ok_or(format!("no record group {rid}")))
        .collect::<Result<_, String>>()?;
    let x = (0..nnodes)
        .map(|p| [xs[0][p], xs[1][p], xs[2][p]])
        .collect();
    let s8 = reals(8, nmodes * nnodes * 6)?.ok_or("no record group 8")?;
    let shapes = (0..nmodes)
        .map(|j| {
            (0..nnodes)
                .map(|p| {
                    let o = (j * nnodes + p) * 6;
                    [s8[o], s8[o + 1], s8[o + 2], s8[o + 3], s8[o + 4], s8[o + 5]]
                })
                .collect()
        })
        .collect();
    let col_major = |v: Vec<f64>| -> Vec<f64> {
        let mut out = vec![0.0; nmodes * nmodes];
        for c in 0..nmodes {
            for r in 0..nmodes {
                out[r * nmodes + c] = v[c * nmodes + r];
            }
        }
        out
    };
    let mass = col_major(reals(9, nmodes * nmodes)?.ok_or("no record group 9")?);
    let stiffness = col_major(reals(10, nmodes * nmodes)?.ok_or("no record group 10")?);
    let lumped = reals(11, nnodes * 6)?.map(|v| {
        v.chunks(6)
            .map(|c| [c[0], c[1], c[2], c[3], c[4], c[5]])
            .collect()
    });
    let global = reals(12, 13)?.map(|v| {
        let mut j = [0.0; 9];
        j.copy_from_slice(&v[4..13]);
        (v[0], [v[1], v[2], v[3]], j)
    });
    let damping = reals(13, nmodes * nmodes)?.map(col_major);
    Ok(Fem {
        labels,
        nmodes,
        x,
        shapes,
        mass,
        stiffness,
        lumped,
        global,
        damping,
    })
}

/// Mass, centre and inertia about the centre from records 5–7 and 11 (point masses with
/// diagonal rotary inertia), as MBDyn forms the rigid-body invariants without record 12.
fn inertia_from_nodes(fem: &Fem) -> (f64, [f64; 3], [f64; 9]) {
    let lumped = fem.lumped.as_ref().unwrap();
    let m: f64 = lumped.iter().map(|l| l[0]).sum();
    let mut c = [0.0; 3];
    for (x, l) in fem.x.iter().zip(lumped) {
        for a in 0..3 {
            c[a] += l[0] * x[a] / m;
        }
    }
    let mut j = [0.0; 9];
    for (x, l) in fem.x.iter().zip(lumped) {
        let r = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
        let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        for a in 0..3 {
            for b in 0..3 {
                let delta = if a == b { 1.0 } else { 0.0 };
                j[a * 3 + b] += l[0] * (r2 * delta - r[a] * r[b]);
            }
            j[a * 3 + a] += l[3 + a];
        }
    }
    (m, c, j)
}

/// The manual's "Example: Dynamic Model" (line numbers removed).
const MANUAL_EXAMPLE: &str = "\
** MBDyn MODAL DATA FILE
** NODE SET \"ALL\"


** RECORD GROUP 1, HEADER
**   REVISION,  NODE,  NORMAL, ATTACHMENT, CONSTRAINT, REJECTED MODES.
      REV0         3         2         0         0         0
**
** RECORD GROUP 2, FINITE ELEMENT NODE LIST
     1001 1002 1003

**
** RECORD GROUP 3, INITIAL MODAL DISPLACEMENTS
 0 0
**
** RECORD GROUP 4, INITIAL MODALVELOCITIES
 0 0
**
** RECORD GROUP 5, NODAL X COORDINATES
 0
 0
 0
**
** RECORD GROUP 6, NODAL Y COORDINATES
-2.
 0
 2.
**
** RECORD GROUP 7, NODAL Z COORDINATES
 0
 0
 0
**
** RECORD GROUP 8, MODE SHAPES
**    NORMAL MODE SHAPE #  1
0 0 1 0 0 0
0 0 0 0 0 0
0 0 1 0 0 0
**    NORMAL MODE SHAPE #  2
1 0 0 0 0 0
0 0 0 0 0 0
1 0 0 0 0 0
**
** RECORD GROUP 9, MODAL MASS MATRIX
2 0
0 2
**
** RECORD GROUP 10, MODAL STIFFNESS MATRIX
1 0
0 1e2
**
** RECORD GROUP 11, DIAGONAL OF LUMPED MASS MATRIX
1 1 1 1 1 1
1 1 1 1 1 1
1 1 1 1 1 1
** END OF FILE
";

#[test]
fn the_parser_reads_the_manuals_example_with_its_stated_inertia() {
    let fem = parse_fem(MANUAL_EXAMPLE).unwrap();
    assert_eq!(fem.labels, ["1001", "1002", "1003"]);
    assert_eq!(fem.nmodes, 2);
    assert_eq!(fem.stiffness, [1.0, 0.0, 0.0, 100.0]);
    // The manual: m = 3, x_CM = 0, J = diag(11, 3, 11).
    let (m, c, j) = inertia_from_nodes(&fem);
    assert_eq!(m, 3.0);
    assert_eq!(c, [0.0; 3]);
    assert_eq!(j, [11.0, 0.0, 0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 11.0]);
    // and the constraint m = Xᵀ M X holds for it (modal mass 2 on the diagonal)
    assert_eq!(modal_mass_from_nodes(&fem), fem.mass);
}

/// Xᵀ M X from records 8 and 11 (the manual's constraint on record 9).
fn modal_mass_from_nodes(fem: &Fem) -> Vec<f64> {
    let lumped = fem.lumped.as_ref().unwrap();
    let m = fem.nmodes;
    let mut out = vec![0.0; m * m];
    for r in 0..m {
        for c in 0..m {
            out[r * m + c] = lumped
                .iter()
                .enumerate()
                .map(|(p, l)| {
                    (0..6)
                        .map(|k| fem.shapes[r][p][k] * l[k] * fem.shapes[c][p][k])
                        .sum::<f64>()
                })
                .sum();
        }
    }
    out
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexbody-mbdyn-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(args: &[&str]) {
    let o = Command::new(env!("CARGO_BIN_EXE_flexbody"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "flexbody {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Builds `model` with `build_args`, exports to MBDyn, parses and checks everything.
fn check_export(name: &str, model: &str, build_args: &[&str]) -> (Fem, file::ReducedBody, String) {
    let dir = scratch(name);
    let body_path = dir.join("body.flexbody");
    let fem_path = dir.join("body.fem");
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join(model);
    let mut args = vec!["build", model.to_str().unwrap()];
    args.extend_from_slice(build_args);
    args.extend_from_slice(&["--units", "si", "-q", "-o", body_path.to_str().unwrap()]);
    run(&args);
    run(&[
        "export",
        body_path.to_str().unwrap(),
        "--to",
        "mbdyn",
        "-o",
        fem_path.to_str().unwrap(),
    ]);
    let body = file::read(&body_path).unwrap();
    let text = std::fs::read_to_string(&fem_path).unwrap();
    let fem = parse_fem(&text).unwrap();
    let _ = std::fs::remove_dir_all(&dir);

    // Against the .flexbody file: the flexible modes, every node, exactly.
    let flex: Vec<usize> = (0..body.mode_count())
        .filter(|&j| body.modes.labels[j] != file::ModeLabel::Rigid)
        .collect();
    let n = body.node_count();
    assert_eq!(fem.nmodes, flex.len());
    let ids: Vec<String> = body.nodes.iter().map(|nd| nd.id.to_string()).collect();
    assert_eq!(fem.labels, ids);
    for (p, nd) in body.nodes.iter().enumerate() {
        assert_eq!(fem.x[p], nd.xyz);
        assert_eq!(fem.lumped.as_ref().unwrap()[p][0], body.nodal_mass[p].mass);
    }
    for (i, &j) in flex.iter().enumerate() {
        for p in 0..n {
            assert_eq!(
                fem.shapes[i][p][..],
                body.modes.shapes[(j * n + p) * 6..(j * n + p) * 6 + 6]
            );
        }
    }
    // The manual's constraint m = Xᵀ M X (records 8, 9, 11).
    let m = fem.nmodes;
    let from_nodes = modal_mass_from_nodes(&fem);
    let d = max_abs_diff(&from_nodes, &fem.mass);
    println!("{name}: record 9 vs X^T M X from records 8 and 11: {d:.3e}");
    assert!(d < 1e-12, "{d}");
    // k_ii = ω_i² m_ii, off-diagonals zero (normal modes), ω from the file's frequencies.
    for (i, &j) in flex.iter().enumerate() {
        let w = 2.0 * std::f64::consts::PI * body.modes.frequency_hz[j];
        let k = fem.stiffness[i * m + i];
        assert!(
            (k / (w * w * fem.mass[i * m + i]) - 1.0).abs() < 1e-12,
            "mode {i}: {k} vs {}",
            w * w
        );
    }
    // Record 12 against the inertia MBDyn would form from records 5–7 and 11.
    let (gm, gc, gj) = fem.global.unwrap();
    let (nm, nc, nj) = inertia_from_nodes(&fem);
    let scale = gj.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    println!(
        "{name}: record 12 vs records 5-7 + 11: mass {:.1e}, centre {:.1e}, J {:.1e} (rel.)",
        (gm - nm).abs() / gm,
        max_abs_diff(&gc, &nc),
        max_abs_diff(&gj, &nj) / scale
    );
    assert!((gm - nm).abs() < 1e-12 * gm);
    assert!(max_abs_diff(&gc, &nc) < 1e-12);
    assert!(max_abs_diff(&gj, &nj) < 1e-12 * scale);
    (fem, body, text)
}

#[test]
fn the_conrod_fem_file_follows_the_manual() {
    let (fem, body, text) = check_export(
        "conrod",
        "fixtures/models/conrod/conrod.inp",
        &[
            "--interface",
            "BIG_END,SMALL_END",
            "--fmax",
            "3000",
            "--damping",
            "2%",
        ],
    );
    assert_eq!((fem.labels.len(), fem.nmodes), (6963, 8));
    // Record 13: c_ii = 2 ζ ω_i m_ii with ζ = 2 %.
    let d = fem.damping.unwrap();
    let m = fem.nmodes;
    let flex: Vec<usize> = (0..body.mode_count())
        .filter(|&j| body.modes.labels[j] != file::ModeLabel::Rigid)
        .collect();
    for (i, &j) in flex.iter().enumerate() {
        let w = body.modes.omega2[j].sqrt();
        assert!((d[i * m + i] / (2.0 * 0.02 * w * fem.mass[i * m + i]) - 1.0).abs() < 1e-12);
    }
    // Blendyn reads every node and every mode, equal to the file's.
    let b = blendyn_read(&text).unwrap();
    let n = body.node_count();
    assert_eq!((b.header_nodes, b.header_modes), (n, m));
    let ids: Vec<String> = body.nodes.iter().map(|nd| nd.id.to_string()).collect();
    assert_eq!(b.labels, ids);
    for (p, nd) in body.nodes.iter().enumerate() {
        assert_eq!(b.position[p], nd.xyz);
    }
    assert_eq!(b.shapes.len(), m);
    for (i, &j) in flex.iter().enumerate() {
        assert_eq!(b.shapes[i].0, (i + 1).to_string());
        for p in 0..n {
            assert_eq!(
                b.shapes[i].1[p][..],
                body.modes.shapes[(j * n + p) * 6..(j * n + p) * 6 + 3]
            );
        }
    }
    println!(
        "conrod: Blendyn's reading: {} nodes, {} modes, every value equal to the file",
        b.labels.len(),
        b.shapes.len()
    );
    // Without femgen's bare `**` lines (the layout before issue 36) Blendyn stops as reported.
    let without: String = text
        .lines()
        .filter(|l| l.trim() != "**")
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(
        parse_fem(&without).is_ok(),
        "the manual's tokens alone still parse"
    );
    assert_eq!(
        blendyn_read(&without).unwrap_err(),
        "could not convert string to float: '**'"
    );
}

/// What Blendyn takes from a `.fem`: the header's node and mode counts, the node labels, the
/// positions (records 5–7) and per mode its name and the translations of every node.
#[derive(Debug)]
struct BlendynFem {
    header_nodes: usize,
    header_modes: usize,
    labels: Vec<String>,
    position: Vec<[f64; 3]>,
    shapes: Vec<(String, Vec<[f64; 3]>)>,
}

/// Blendyn's `parse_modal_fem_file` (Blender add-on, `modallib.py`), restated: rows are split
/// on spaces with leading blanks skipped (Python's csv reader, delimiter ' ',
/// skipinitialspace); find "RECORD GROUP 1," in fields 2–4, step two rows to the header (NODE,
/// NORMAL); find group 2 and take labels until an empty row or one starting `**`; find group 5,
/// then for each coordinate read one value per node (first field), stepping two rows between
/// X, Y and Z and before group 8's first mode title; per mode the title's last field names it,
/// then one row per node (first three fields). Running out of rows is a failure (Blendyn's
/// StopIteration does not mark the element ready); a value that is not a number fails as
/// Python's float() does.
fn blendyn_read(text: &str) -> Result<BlendynFem, String> {
    let mut rows = text.lines().map(|l| {
        l.split(' ')
            .filter(|t| !t.is_empty())
            .map(String::from)
            .collect::<Vec<String>>()
    });
    let mut next = || rows.next().ok_or_else(|| "StopIteration".to_string());
    let float = |t: &str| {
        t.parse::<f64>()
            .map_err(|_| format!("could not convert string to float: '{t}'"))
    };
    let int = |t: &str| {
        t.parse::<usize>()
            .map_err(|_| format!("invalid literal for int(): '{t}'"))
    };
    let is_title = |rw: &[String], group: u32| {
        rw.len() >= 4
            && format!("{} {} {}", rw[1], rw[2], rw[3]) == format!("RECORD GROUP {group},")
    };
    let mut rw = next()?;
    while !is_title(&rw, 1) {
        rw = next()?;
    }
    next()?;
    rw = next()?;
    let (header_nodes, header_modes) = (int(&rw[1])?, int(&rw[2])?);
    rw = next()?;
    while !is_title(&rw, 2) {
        rw = next()?;
    }
    rw = next()?;
    let mut labels = Vec::new();
    while !rw.is_empty() && rw[0] != "**" {
        labels.extend(rw.iter().cloned());
        rw = next()?;
    }
    while !is_title(&rw, 5) {
        rw = next()?;
    }
    let mut position = vec![[0.0; 3]; labels.len()];
    rw = next()?;
    for c in 0..3 {
        if c > 0 {
            next()?;
            rw = next()?;
        }
        for p in position.iter_mut() {
            p[c] = float(&rw[0])?;
            rw = next()?;
        }
    }
    next()?;
    rw = next()?;
    let mut shapes = Vec::new();
    for _ in 0..header_modes {
        let name = rw.last().cloned().unwrap_or_default();
        rw = next()?;
        let mut shape = Vec::with_capacity(labels.len());
        for _ in 0..labels.len() {
            shape.push([float(&rw[0])?, float(&rw[1])?, float(&rw[2])?]);
            rw = next()?;
        }
        shapes.push((name, shape));
    }
    Ok(BlendynFem {
        header_nodes,
        header_modes,
        labels,
        position,
        shapes,
    })
}

#[test]
fn blendyns_reading_matches_the_manuals_example() {
    // femgen's layout as the manual prints it: the restated reader takes it whole.
    let b = blendyn_read(MANUAL_EXAMPLE).unwrap();
    assert_eq!((b.header_nodes, b.header_modes), (3, 2));
    assert_eq!(b.labels, ["1001", "1002", "1003"]);
    assert_eq!(b.position, [[0.0, -2.0, 0.0], [0.0; 3], [0.0, 2.0, 0.0]]);
    assert_eq!(b.shapes[0].0, "1");
    assert_eq!(b.shapes[0].1, [[0.0, 0.0, 1.0], [0.0; 3], [0.0, 0.0, 1.0]]);
    assert_eq!(b.shapes[1].0, "2");
    assert_eq!(b.shapes[1].1, [[1.0, 0.0, 0.0], [0.0; 3], [1.0, 0.0, 0.0]]);
}

#[test]
fn the_beam_fem_file_carries_rotations_and_rotary_inertia() {
    let (fem, body, text) = check_export(
        "beam",
        "fixtures/models/planar_beam/planar_beam.bdf",
        &[
            "--method",
            "normal",
            "--modes",
            "6",
            "--mass",
            "lumped",
            "--beam-mass",
            "section",
        ],
    );
    assert_eq!((fem.labels.len(), fem.nmodes), (13, 3));
    // Bending in the x-y plane: rotations about z and rotary inertia Izz are really there.
    let rz = fem.shapes[0].iter().fold(0.0f64, |a, s| a.max(s[5].abs()));
    let izz = fem
        .lumped
        .as_ref()
        .unwrap()
        .iter()
        .map(|l| l[5])
        .sum::<f64>();
    assert!(rz > 0.1 && izz > 0.0, "rz {rz}, Izz {izz}");
    assert!(fem.damping.is_none());
    let b = blendyn_read(&text).unwrap();
    assert_eq!((b.labels.len(), b.shapes.len()), (body.node_count(), 3));
}
