//! The CalculiX test-suite decks in `ccx_tests/` of the external reference data
//! (`FLEXBODY_REFERENCE`), else from Debian's `calculix-ccx-test` (`crate::common::ccx_suite`; skipped
//! visibly without either, a failure under `CI=true`) (real ccx inputs: C3D8,
//! C3D8I, C3D20R, C3D10, S8/S8R, B32R, SPRINGA, cyclic symmetry): node and element counts
//! (counted from the decks' data lines; B32R as the bricks ccx expands them into).

use crate::common::ccx_suite;
use flexbody::import::{abaqus, ImportOptions};
use flexbody::model::ElementKind;

#[test]
fn ccx_test_decks_node_and_element_counts() {
    let decks = [
        "beam8f.inp",
        "beamdy1.inp",
        "beamf.inp",
        "beamfsh1.inp",
        "beampsensfreq.inp",
        "dloadlinIf.inp",
        "segmenttet.inp",
        "shellf.inp",
    ];
    let Some(dir) = ccx_suite("ccx_test_decks_node_and_element_counts", &decks) else {
        return;
    };
    let deck = |name: &str| dir.join(name);
    for (name, nodes, elements) in [
        ("beam8f.inp", 425, 256),
        ("beamdy1.inp", 261, 32),
        ("beamf.inp", 261, 32),
        ("beamfsh1.inp", 261, 34),
        ("beampsensfreq.inp", 261, 32),
        ("dloadlinIf.inp", 188, 15),
        ("segmenttet.inp", 2756, 1489),
        ("shellf.inp", 21, 4),
    ] {
        // refused, dropped here to count the mesh: beampsensfreq's frequency step is a
        // perturbation of a *STATIC step; segmenttet is tied and cyclic
        let opts = ImportOptions {
            ignore_cards: [
                "PERTURBATION",
                "*TIE",
                "cyclic symmetry model",
                "SELECTCYCLICSYMMETRYMODES",
            ]
            .map(String::from)
            .to_vec(),
            // the deck's own elements (expanded, shells become bricks with new nodes)
            inp_shells: flexbody::import::InpShells::Native,
            ..Default::default()
        };
        let m =
            abaqus::read_with_options(&deck(name), &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(
            (m.nodes.len(), m.elements.len()),
            (nodes, elements),
            "{name}"
        );
    }
    // by default the deck's two S8R shells are expanded into C3D20R bricks as ccx does: 32 + 2
    let m = abaqus::read(&deck("beamfsh1.inp")).unwrap();
    let count = |m: &flexbody::model::Model, k: ElementKind| {
        m.elements.iter().filter(|e| e.kind == k).count()
    };
    assert_eq!(
        (
            count(&m, ElementKind::Hex20R),
            count(&m, ElementKind::Quad8)
        ),
        (34, 0)
    );
    let native = ImportOptions {
        inp_shells: flexbody::import::InpShells::Native,
        ..Default::default()
    };
    let m = abaqus::read_with_options(&deck("beamfsh1.inp"), &native).unwrap();
    assert_eq!(
        (
            count(&m, ElementKind::Hex20R),
            count(&m, ElementKind::Quad8)
        ),
        (32, 2)
    );
    // C3D8 lines carrying 10 node ids: ccx uses the first 8; so do we, with a warning.
    let opts = ImportOptions {
        ignore_cards: vec!["perturbation".into()],
        ..Default::default()
    };
    let m = abaqus::read_with_options(&deck("beampsensfreq.inp"), &opts).unwrap();
    assert!(m
        .warnings
        .iter()
        .any(|w| w.message.starts_with("32 C3D8 elements list more node ids")));
    let ids: Vec<u64> = m.elements[0].nodes.iter().map(|&i| m.nodes[i].id).collect();
    assert_eq!(ids, vec![1, 10, 95, 19, 61, 105, 222, 192]);
}

/// simplebeampipe3's B32R beams with *BEAM GENERAL SECTION, SECTION=PIPE read as ccx expands
/// them: 10 C3D20R bricks at the pipe's 16 points, 8 expanded nodes around each of the 11 end
/// nodes and 4 around each of the 10 middle nodes, every beam node tied by 6 equations and the
/// clamped node's mid-side nodes by 12 more; spring5's SPRINGA, *SPRING and *EQUATION read (a
/// bush of k = 10 on the x axis, one equation).
#[test]
fn expanded_beams_and_springs_read() {
    let decks = ["simplebeampipe3.inp", "spring5.inp"];
    let Some(dir) = ccx_suite("expanded_beams_and_springs_read", &decks) else {
        return;
    };
    let m = abaqus::read(&dir.join("simplebeampipe3.inp")).unwrap();
    let kinds = |k: ElementKind| m.elements.iter().filter(|e| e.kind == k).count();
    assert_eq!((kinds(ElementKind::Hex20R), m.elements.len()), (10, 10));
    assert_eq!(m.nodes.len(), 21 + 11 * 8 + 10 * 4);
    assert_eq!(m.mpcs.len(), 21 * 6 + 12);
    assert_eq!(
        m.beam_bricks.get(&0),
        Some(&flexbody::model::BeamBrickSection::Pipe {
            ratio: (0.11 - 0.01) / 0.11
        })
    );
    let m = abaqus::read(&dir.join("spring5.inp")).unwrap();
    assert_eq!((m.bushes.len(), m.mpcs.len()), (1, 1));
    assert_eq!(m.bushes[0].k, [10.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    assert_eq!(m.bushes[0].axes[0], [1.0, 0.0, 0.0]);
}
