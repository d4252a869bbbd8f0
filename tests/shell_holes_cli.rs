//! A sheet-metal part through the CLI: a 200 × 100 × 2 mm steel plate with two Ø40 mm holes,
//! meshed with S4 shells (generated here as an Abaqus deck), reduced by Craig–Bampton on RBE2
//! spiders to the two holes (cylinder-fit centres), then `flexbody check --model` passes; the
//! same with RBE3 spiders.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::process::Command;

/// Abaqus deck of the plate: two square cells of side 0.1 m, each a ring mesh from its hole
/// (radius 0.02 m) to the cell boundary (`n` divisions per side, `m` radial layers).
fn plate_with_two_holes(n: usize, m: usize) -> String {
    let (h, r) = (0.05, 0.02);
    let mut ids: HashMap<(i64, i64), usize> = HashMap::new();
    let mut xy: Vec<[f64; 2]> = Vec::new();
    let mut node = |p: [f64; 2]| -> usize {
        let key = ((p[0] * 1e9).round() as i64, (p[1] * 1e9).round() as i64);
        *ids.entry(key).or_insert_with(|| {
            xy.push(p);
            xy.len()
        })
    };
    let mut quads = Vec::new();
    let mut holes = [Vec::new(), Vec::new()];
    for (c, cx) in [0.05, 0.15].into_iter().enumerate() {
        let cy = 0.05;
        let boundary = |k: usize| -> [f64; 2] {
            let f = (k % n) as f64 / n as f64;
            match (k / n) % 4 {
                0 => [h, -h + 2.0 * h * f],
                1 => [h - 2.0 * h * f, h],
                2 => [-h, h - 2.0 * h * f],
                _ => [-h + 2.0 * h * f, -h],
            }
        };
        let mut grid = vec![vec![0usize; m + 1]; 4 * n];
        for (k, col) in grid.iter_mut().enumerate() {
            let b = boundary(k);
            let th = b[1].atan2(b[0]);
            let a = [r * th.cos(), r * th.sin()];
            for (j, g) in col.iter_mut().enumerate() {
                let t = j as f64 / m as f64;
                *g = node([cx + a[0] + t * (b[0] - a[0]), cy + a[1] + t * (b[1] - a[1])]);
            }
            holes[c].push(col[0]);
        }
        for k in 0..4 * n {
            let k1 = (k + 1) % (4 * n);
            for j in 0..m {
                quads.push([grid[k][j], grid[k][j + 1], grid[k1][j + 1], grid[k1][j]]);
            }
        }
    }
    let mut s = String::from("*HEADING\nplate with two holes, S4 shells\n*NODE\n");
    for (i, p) in xy.iter().enumerate() {
        writeln!(s, "{}, {:.12}, {:.12}, 0.0", i + 1, p[0], p[1]).unwrap();
    }
    s.push_str("*ELEMENT, TYPE=S4, ELSET=PLATE\n");
    for (e, q) in quads.iter().enumerate() {
        writeln!(s, "{}, {}, {}, {}, {}", e + 1, q[0], q[1], q[2], q[3]).unwrap();
    }
    for (c, hole) in holes.iter().enumerate() {
        writeln!(s, "*NSET, NSET=HOLE{}", c + 1).unwrap();
        for chunk in hole.chunks(8) {
            let line: Vec<String> = chunk.iter().map(|i| i.to_string()).collect();
            writeln!(s, "{}", line.join(", ")).unwrap();
        }
    }
    s.push_str(
        "*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL\n0.002, 5\n\
         *MATERIAL, NAME=STEEL\n*ELASTIC\n210e9, 0.3\n*DENSITY\n7850.\n",
    );
    s
}

#[test]
fn shell_plate_with_two_holes_cb_on_hole_spiders_passes_check() {
    let exe = env!("CARGO_BIN_EXE_flexbody");
    let dir = std::env::temp_dir().join(format!("flexbody-shell-holes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let inp = dir.join("plate.inp");
    std::fs::write(&inp, plate_with_two_holes(6, 4)).unwrap();
    let out = dir.join("plate.flexbody");
    let build = Command::new(exe)
        .args(["build", inp.to_str().unwrap()])
        .args([
            "--interface",
            "HOLE1,HOLE2",
            "--modes",
            "30",
            "--units",
            "si",
            // flexbody's MITC4 shells (ccx expands S4 into its own C3D8I, which is refused);
            // the recipe records it and `check --model` rebuilds the same
            "--inp-shells",
            "native",
        ])
        .args(["-q", "--json", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&build.stdout);
    assert!(
        build.status.success(),
        "{report}\n{}",
        String::from_utf8_lossy(&build.stderr)
    );
    // the section-points note is reported, not silently dropped
    assert!(report.contains("section points"), "{report}");
    let body = flexbody_reader::read(&out).unwrap();
    assert_eq!(body.nodes.iter().filter(|n| n.interface).count(), 2);
    // mass 7850 · 0.002 · (0.02 − 2π·0.02²) kg
    let area = 0.02 - 2.0 * std::f64::consts::PI * 0.02f64.powi(2);
    let want = 7850.0 * 0.002 * area;
    let mass = body.invariants.i1[0];
    // the ring meshes are polygons inscribed in the holes: a little more area than the disk
    assert!((mass - want).abs() < 0.01 * want, "mass {mass} vs {want}");
    let check = Command::new(exe)
        .arg("check")
        .arg(&out)
        .args(["--model", inp.to_str().unwrap()])
        .args(["--interface", "HOLE1,HOLE2"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&check.stdout);
    eprintln!("{text}");
    assert!(
        check.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&check.stderr)
    );
    // RBE3 spiders on the holes (no added stiffness, centres stay independent): check passes too
    let rbe3 = dir.join("rbe3.flexbody");
    let b3 = Command::new(exe)
        .args(["build", inp.to_str().unwrap()])
        .args([
            "--interface",
            "HOLE1,HOLE2",
            "--spider",
            "rbe3",
            "--modes",
            "30",
            "--inp-shells",
            "native",
        ])
        .args(["--units", "si", "-q", "-o"])
        .arg(&rbe3)
        .output()
        .unwrap();
    assert!(
        b3.status.success(),
        "{}",
        String::from_utf8_lossy(&b3.stderr)
    );
    let c3 = Command::new(exe)
        .arg("check")
        .arg(&rbe3)
        .args(["--model", inp.to_str().unwrap()])
        .args(["--interface", "HOLE1,HOLE2", "--spider", "rbe3"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&c3.stdout);
    assert!(c3.status.success(), "{text}");
    // shell fibre stress shapes (format 1.5): the top fibre in stress_shapes.bin, the bottom in
    // stress_shapes_bottom.bin, at every shell node
    let stress = Command::new(exe)
        .args(["build", inp.to_str().unwrap()])
        .args([
            "--interface",
            "HOLE1,HOLE2",
            "--modes",
            "4",
            "--units",
            "si",
            "--inp-shells",
            "native",
        ])
        .args(["--stress-modes", "-q", "--json", "-o"])
        .arg(dir.join("stress.flexbody"))
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&stress.stdout);
    assert!(stress.status.success(), "{report}");
    assert!(!report.contains("shell elements have none"), "{report}");
    let body = flexbody_reader::read(dir.join("stress.flexbody")).unwrap();
    assert_eq!((body.version.major, body.version.minor), (1, 9));
    let mut bare = body.clone();
    bare.eigen_residuals = None; // 1.9, in every build: the bottom fibre alone is 1.5
    let v = flexbody_reader::version_for(&bare);
    assert_eq!((v.major, v.minor), (1, 5));
    let (top, bottom) = (
        body.stress_shapes.as_ref().unwrap(),
        body.stress_shapes_bottom.as_ref().unwrap(),
    );
    assert!(body.strain_shapes_bottom.is_some());
    // every stored node but the two spider centres is a shell node
    assert_eq!(bottom.nodes.len(), body.nodes.len() - 2);
    assert_eq!(top.nodes, bottom.nodes);
    // a flat plate's modes are either bending (top = −bottom) or membrane (top = bottom)
    // (rigid modes have no stress: skipped)
    let k = top.nodes.len();
    let peak = top.values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for j in 0..body.modes.omega2.len() {
        let sj = top.values[j * k * 6..(j + 1) * k * 6]
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()));
        if sj < 1e-6 * peak {
            continue;
        }
        let r = |sign: f64| {
            let (mut d, mut s) = (0.0f64, 0.0f64);
            for i in j * k * 6..(j + 1) * k * 6 {
                d = d.max((top.values[i] + sign * bottom.values[i]).abs());
                s = s.max(top.values[i].abs());
            }
            d / s
        };
        let (bending, membrane) = (r(1.0), r(-1.0));
        eprintln!("mode {j}: |top + bottom| {bending:.1e}, |top − bottom| {membrane:.1e}");
        assert!(
            bending.min(membrane) < 1e-6,
            "mode {j}: {bending} {membrane}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
