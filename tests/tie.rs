//! `*TIE` (issue 32): slave nodes held on the master faces by the faces' shape functions, as
//! CalculiX ties them. Our decks in `fixtures/ccx_tie/` (a cantilever cut in two meshes, linear
//! and quadratic hexahedra, conforming and non-conforming faces, a gap inside and one outside
//! ccx's default position tolerance) are built as ccx solves them and compared with ccx 2.20's
//! frequencies (`fixtures/ccx_tie/results.json`, `fixtures/ccx_frequencies.py` runs ccx): ccx prints 7
//! significant digits.

use std::path::{Path, PathBuf};

use crate::common::{build_as_ccx, scratch};
use flexbody_reader as file;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/ccx_tie")
        .join(name)
}

/// ccx 2.20's frequencies of `key` (`crate::common::ccx_frequencies`).
fn ccx(key: &str) -> Vec<f64> {
    crate::common::ccx_frequencies("ccx_tie", key)
}

/// Builds `deck` as ccx solves it; the body and the build's stderr.
fn build(deck: &Path, dir: &Path) -> (file::ReducedBody, String) {
    let out = dir.join(deck.with_extension("flexbody").file_name().unwrap());
    let o = build_as_ccx(deck, &[], &out);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{}: {err}", deck.display());
    (file::read(&out).unwrap(), err)
}

/// Asserts `body` has ccx's modes: as many, the same rigid ones (ccx's zero modes, labelled
/// rigid here), the elastic ones within 1e-6 (ccx prints 7 significant digits); the worst
/// relative difference.
fn assert_ccx(what: &str, body: &file::ReducedBody, theirs: &[f64]) -> f64 {
    let top = theirs.iter().cloned().fold(0.0, f64::max);
    let rigid = theirs.iter().filter(|f| **f < 1e-4 * top).count();
    let labelled = (body.modes.labels.iter())
        .filter(|l| **l == file::ModeLabel::Rigid)
        .count();
    assert_eq!(
        labelled, rigid,
        "{what}: {:?} against {theirs:?}",
        body.modes.frequency_hz
    );
    crate::common::assert_frequencies(what, &body.modes.frequency_hz, theirs, rigid, 1e-6)
}

#[test]
fn a_conforming_tie_is_the_merged_mesh() {
    let dir = scratch("tie-conforming");
    let (merged, _) = build(&fixture("tie_merged.inp"), &dir);
    let (tied, _) = build(&fixture("tie_conforming.inp"), &dir);
    crate::common::assert_frequencies(
        "tied against merged",
        &tied.modes.frequency_hz,
        &merged.modes.frequency_hz,
        0,
        1e-9,
    );
    assert_ccx("tie_merged", &merged, &ccx("tie_merged"));
    assert_ccx("tie_conforming", &tied, &ccx("tie_conforming"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn non_conforming_and_quadratic_ties_match_calculix() {
    let dir = scratch("tie-ccx");
    for stem in [
        "tie_nonconforming",
        "tie20_conforming",
        "tie20_nonconforming",
    ] {
        let (body, _) = build(&fixture(&format!("{stem}.inp")), &dir);
        assert_ccx(stem, &body, &ccx(stem));
    }
    // flexbody's non-conforming tie is a little softer than its conforming one (the slave
    // face's extra nodes follow the master face's bilinear field): every one of the ten modes
    // lower, by at most 3 % (2.4 % on the ninth)
    let (nonconforming, _) = build(&fixture("tie_nonconforming.inp"), &dir);
    let (conforming, _) = build(&fixture("tie_conforming.inp"), &dir);
    let (a, b) = (
        nonconforming.modes.frequency_hz,
        conforming.modes.frequency_hz,
    );
    assert_eq!((a.len(), b.len()), (10, 10), "{a:?} against {b:?}");
    assert!(
        a.iter().zip(&b).all(|(x, y)| x < y && (y - x) / y < 3e-2),
        "{a:?} against {b:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_default_position_tolerance_ties_a_small_gap_and_not_a_larger_one() {
    let dir = scratch("tie-gap");
    // 0.3 mm: within ccx's 2.5 % of the typical element size (0.05 m / 3 → 0.42 mm); the
    // slave nodes move onto the master faces (ADJUST=YES)
    let (body, err) = build(&fixture("tie_gap0003.inp"), &dir);
    assert!(!err.contains("not tied"), "{err}");
    assert_ccx("tie_gap0003", &body, &ccx("tie_gap0003"));
    // 0.5 mm: no slave node is tied, said in a warning; the right part is free (6 rigid modes)
    let (body, err) = build(&fixture("tie_gap0005.inp"), &dir);
    assert!(
        err.contains("*TIE T1: 16 slave node(s) not tied")
            && err.contains(
                "16 opposite a master face but farther from it than the position tolerance"
            ),
        "{err}"
    );
    assert_eq!(untied(&err), ccx("tie_gap0005:untied")[0] as usize);
    assert_ccx("tie_gap0005", &body, &ccx("tie_gap0005"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The slave nodes the build's warnings count as untied, over every tie.
fn untied(err: &str) -> usize {
    err.lines()
        .filter_map(|l| l.split_once(" slave node(s) not tied"))
        .map(|(head, _)| head.rsplit(' ').next().unwrap().parse::<usize>().unwrap())
        .sum()
}

#[test]
fn slave_nodes_beyond_calculix_tolerances_stay_untied_as_ccx_leaves_them() {
    // tie_untied (make_decks.py): a C3D10 part, wider than the C3D20 master (slave nodes with no
    // master face opposite) and bulging by up to 0.5 mm at the tie (ADJUST=NO), its other end
    // tied to a coarse C3D8 part (ADJUST=YES, bulging by up to 0.6 mm): ccx 2.20's default
    // tolerances (2.5 % of the mean centroid-to-edge distance of both ties' master triangles,
    // 0.25 mm) leave 46 slave nodes untied and list them in WarnNodeMissTiedContact.nam
    let dir = scratch("tie-untied");
    let (body, err) = build(&fixture("tie_untied.inp"), &dir);
    assert_eq!(untied(&err), ccx("tie_untied:untied")[0] as usize, "{err}");
    assert!(err.contains("with no master face opposite"), "{err}");
    // measured: 2.5e-7 (ccx prints 7 digits); the untied node ids are ccx's, one for one
    assert_ccx("tie_untied", &body, &ccx("tie_untied"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_node_surface_slave_ties_as_the_element_faces_do() {
    let dir = scratch("tie-nodes");
    let text = std::fs::read_to_string(fixture("tie_nonconforming.inp")).unwrap();
    // the right part's nodes at x = 0.5 as a node set, the slave surface of TYPE=NODE
    let mut slaves = Vec::new();
    let mut in_nodes = false;
    for line in text.lines() {
        if line.starts_with('*') {
            in_nodes = line.starts_with("*NODE");
            continue;
        }
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if in_nodes && f[0].parse::<u64>().unwrap() > 1000 && f[1].parse::<f64>().unwrap() == 0.5 {
            slaves.push(f[0].to_owned());
        }
    }
    assert_eq!(slaves.len(), 16);
    let nodes: Vec<String> = slaves.chunks(8).map(|c| c.join(", ")).collect();
    let deck = dir.join("tie_nodes.inp");
    let text = text.replace(
        "*SURFACE, NAME=SLAVE\nSFACE, S6\n",
        &format!(
            "*NSET, NSET=SNODES\n{}\n*SURFACE, NAME=SLAVE, TYPE=NODE\nSNODES\n",
            nodes.join("\n")
        ),
    );
    std::fs::write(&deck, text).unwrap();
    let (body, _) = build(&deck, &dir);
    assert_ccx("tie_nodes", &body, &ccx("tie_nonconforming"));
    let _ = std::fs::remove_dir_all(&dir);
}
