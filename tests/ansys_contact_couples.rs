//! ANSYS bonded MPC contact written as a symmetric couple (two real constant sets, contact and
//! target swapped: how Workbench writes bonded contact), archives written here in CDWRITE's
//! layout, through the CLI:
//! - on congruent meshes (every contact node of both sets a target node's twin) the couple is
//!   read, formed once: it equals the same two parts tied by `*TIE` (ccx importer) and the two
//!   parts meshed as one block (shared nodes);
//! - a couple on meshes that are not congruent, or whose two sets tie different node pairs,
//!   stays refused, both sets named, as does a shell-solid assembly.

use crate::ansys_contact::{
    against_ccx, bonded_archive, bonded_ccx, faces_at, glue_faces, parts_meshing_a_as, refused,
    two_parts,
};
use crate::ansys_support::writers::{
    block, build_body as build, ccx_deck, frequency_difference, Block,
};
use crate::common::scratch;

/// Two parts meshed alike: 3 × 3 × 3 SOLID186 over [0, 0.3] and again over [0.3, 0.6] (ids
/// from 10 001), their x = 0.3 nodes twins; with the first part's element count.
fn congruent_parts() -> (Block, usize) {
    parts_meshing_a_as([3, 3, 3])
}

/// [`bonded_archive`] of `m` (set 3: CONTA174 on the second part's x = 0.3 faces, TARGE170 on
/// the first's) with its mirror, set 5: CONTA174 on the first `mirror_faces` of the first
/// part's faces, TARGE170 QUA8 on the second's.
fn couple_archive(m: &Block, first_part: usize, mirror_faces: usize) -> String {
    let glue = glue_faces(m, first_part, 0.3);
    let text = bonded_archive(m, &glue, 1e-3);
    let mirror: Vec<(usize, usize, usize, Vec<u64>)> = (faces_at(m, 0.3, false).into_iter())
        .take(mirror_faces)
        .map(|(_, f)| (3, 5, 0, f))
        .chain(glue.iter().map(|f| (2, 5, 9, f.clone())))
        .collect();
    with_records(&text, &mirror, "R,5,0,0,0,0,0,-1e-3\n")
}

/// A symmetric couple on congruent meshes ties the same node pairs whichever set ANSYS keeps:
/// read, formed once (a note says so). It equals the two parts tied by `*TIE` with ADJUST=NO
/// (frequencies and the static response node by node) and the parts meshed as one 6 × 3 × 3
/// block sharing the x = 0.3 nodes (frequencies).
#[test]
fn congruent_symmetric_couple_equals_the_tie_and_the_merged_block() {
    let (m, first_part) = congruent_parts();
    let text = couple_archive(&m, first_part, usize::MAX);
    let (modes, static_) = against_ccx(
        "ansys-couple-congruent",
        &text,
        &bonded_ccx(&m, first_part, 1e-3),
    );
    println!("congruent couple against *TIE: frequencies {modes:.2e}, static {static_:.2e}");
    // measured 6.1e-13 and 7.4e-12
    assert!(modes < 3.4e-11, "{modes:e}");
    assert!(static_ < 4e-11, "{static_:e}");

    // the merged block: one mesh, the interface nodes shared
    let work = scratch("ansys-couple-merged");
    let (cdb, inp) = (work.join("couple.cdb"), work.join("merged.inp"));
    std::fs::write(&cdb, &text).unwrap();
    let merged = block([6, 3, 3], [0.6, 0.1, 0.1], true);
    std::fs::write(&inp, ccx_deck(&merged, "")).unwrap();
    let (ours, one) = (
        build(&cdb, 8, &["--mass", "lumped"]),
        build(&inp, 8, &["--mass", "lumped"]),
    );
    let merged_modes = frequency_difference(&ours, &one, 8);
    println!("congruent couple against the merged block: frequencies {merged_modes:.2e}");
    // measured 2.5e-12
    assert!(merged_modes < 2.5e-11, "{merged_modes:e}");

    // the note: set 5 is set 3's mirror, formed once
    let o = crate::ansys_support::build(&cdb, "si", 4, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("set 5"), "{err}");
    assert!(err.contains("formed once (by set 3)"), "{err}");
    assert!(err.contains("40 contact nodes tied"), "{err}");
}

/// A couple on congruent meshes whose two sets tie different node pairs (the mirror, set 5,
/// takes contact faces on 4 of the 9 target faces only): which set ANSYS keeps changes the
/// body, so it is refused, both sets named.
#[test]
fn congruent_couple_tying_different_node_pairs_is_refused() {
    let (m, first_part) = congruent_parts();
    let err = refused("ansys-couple-partial", &couple_archive(&m, first_part, 4));
    assert!(
        err.contains("real constant set 3 and its mirror, set 5"),
        "{err}"
    );
    assert!(err.contains("the meshes are not congruent"), "{err}");
}

/// The assemblies flexbody does not form are refused by line: a symmetric couple on meshes that
/// are not congruent (the parts meshed apart, 3 × 3 contact faces on 2 × 2, bonded both ways,
/// real constant sets 3 and 5: ANSYS keeps one and ignores the other, which one not stated,
/// and here the choice changes the body), and a shell-solid assembly (SHELL181 quadrilaterals on the first
/// part's x = 0.3 face as CONTA174 contact faces, the bricks' faces their target: ANSYS ties
/// the shell nodes' rotations too).
#[test]
fn symmetric_pairs_and_shell_solid_assemblies_are_refused() {
    let (m, first_part) = two_parts();
    let err = refused(
        "ansys-bonded-symmetric",
        &couple_archive(&m, first_part, usize::MAX),
    );
    assert!(
        err.contains("real constant set 3 and its mirror, set 5"),
        "{err}"
    );
    assert!(
        err.contains("real constant set 5 and its mirror, set 3"),
        "{err}"
    );
    assert!(err.contains("the meshes are not congruent"), "{err}");

    // 2 × 2 SHELL181 on the x = 0.3 face (nodes 20 001…, 0.01 thick), bonded to the bricks
    let text = bonded_archive(&m, &glue_faces(&m, first_part, 0.3), 1e-3);
    let mut nodes = String::new();
    let id = |j: u64, k: u64| 20_001 + 3 * j + k;
    for j in 0..3u64 {
        for k in 0..3u64 {
            let (y, z) = (0.05 * j as f64, 0.05 * k as f64);
            nodes += &format!("{:>9}{:>9}{:>9}", id(j, k), 0, 0);
            nodes += &format!("{:>21.13E}{y:>21.13E}{z:>21.13E}\n", 0.3);
        }
    }
    let quads: Vec<Vec<u64>> = (0..2u64)
        .flat_map(|j| {
            (0..2u64).map(move |k| vec![id(j, k), id(j + 1, k), id(j + 1, k + 1), id(j, k + 1)])
        })
        .collect();
    let shell: Vec<(usize, usize, usize, Vec<u64>)> = (quads.iter())
        .map(|q| (5, 6, 0, q.clone()))
        .chain(quads.iter().map(|q| (3, 7, 0, q.clone())))
        .chain(
            (faces_at(&m, 0.3, false).into_iter())
                .filter(|(e, _)| *e <= first_part)
                .map(|(_, f)| (2, 7, 9, f)),
        )
        .collect();
    let shell_solid = with_records(
        &text.replace(
            "ET,        2,170",
            "ET,        5,181\nKEYOP,        5, 3,        2\nET,        2,170",
        ),
        &shell,
        "R,6,0.01\nR,7,0,0,0,0,0,-1e-3\n",
    )
    .replacen("N,R5.3,LOC", &format!("{nodes}N,R5.3,LOC"), 1);
    let err = refused("ansys-bonded-shell-solid", &shell_solid);
    assert!(err.contains("shell-solid or shell-shell assembly"), "{err}");
    assert!(
        err.contains("real constant set 7 on contact node 2000"),
        "{err}"
    );
}

/// `text` (a [`bonded_archive`]) with `records` appended to its EBLOCK (ids after the last) and
/// `reals` after its real constants.
fn with_records(text: &str, records: &[(usize, usize, usize, Vec<u64>)], reals: &str) -> String {
    let start = text.find("EBLOCK").unwrap();
    let end = start + text[start..].find("       -1\n").unwrap();
    let old: Vec<&str> = text[start..end].lines().skip(2).collect();
    // the header's record count (a brick's record takes two lines)
    let count: usize = text[start..]
        .lines()
        .next()
        .unwrap()
        .split(',')
        .nth(3)
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    let first = count + 1;
    let mut added = String::new();
    for (k, (etype, real, shape, nodes)) in records.iter().enumerate() {
        let head = [
            1,
            *etype,
            *real,
            1,
            0,
            0,
            0,
            *shape,
            nodes.len(),
            0,
            first + k,
        ];
        let fields: Vec<String> = (head.iter().map(|v| format!("{v:>9}")))
            .chain(nodes.iter().map(|v| format!("{v:>9}")))
            .collect();
        added += &fields[..fields.len().min(19)].concat();
        added.push('\n');
        if fields.len() > 19 {
            added += &fields[19..].concat();
            added.push('\n');
        }
    }
    let total = count + records.len();
    let header = format!("EBLOCK,19,SOLID,{0},{0}\n(19i9)\n", total);
    let body: String = old.iter().map(|l| format!("{l}\n")).collect();
    let real_at = text.find("R,3,").unwrap();
    format!(
        "{}{header}{body}{added}{}{reals}{}",
        &text[..start],
        &text[end..real_at],
        &text[real_at..]
    )
}
