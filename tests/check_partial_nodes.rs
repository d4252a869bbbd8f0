//! `flexbody check` on a file that stores only some nodes (`build --keep-nodes interface`): it
//! runs only the checks the stored data supports and names the ones it skipped (issue 20). The
//! centre of mass of a block whose one interface node sits on an end face lies outside that
//! node's bounding box, which used to fail a sound file.

use std::path::Path;

use flexbody::build::{build, BuildMethod, BuildSpec, KeepNodes};
use flexbody::check::{check, ModelInput};
use flexbody::interface::SpiderKind;
use flexbody_reader as file;

#[test]
fn check_on_a_partial_node_file_skips_what_the_nodes_cannot_support() {
    let model =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/reference/a_block_hex8/ccx_free.inp");
    let mut s = BuildSpec {
        method: BuildMethod::CraigBampton,
        ..BuildSpec::new(model.clone(), file::Units::si(), &["FIXED"])
    };
    s.fmax_hz = Some(3000.0);
    s.keep_nodes = KeepNodes::Interface;
    let out = build(&s, &mut |_| {}).unwrap();
    assert_eq!(
        out.body.node_count(),
        1,
        "only the spider's centre node is stored"
    );
    let input = ModelInput {
        path: model,
        format: None,
        material: None,
        thickness: None,
        interface: s.interface.clone(),
        spider: SpiderKind::Rbe2,
        beam_mass: None,
        subcase: None,
        ignore: Vec::new(),
        inp_shells: Default::default(),
        scene: Default::default(),
    };
    for model in [None, Some(&input)] {
        let report = check(&out.body, model).unwrap();
        for i in &report.items {
            assert!(
                i.pass,
                "`{}` failed: {} > {} ({})",
                i.name, i.value, i.limit, i.detail
            );
        }
        assert!(
            report
                .items
                .iter()
                .all(|i| !i.name.starts_with("centre of mass")),
            "the bounding-box test needs every node"
        );
        let skipped = report.skipped.join("\n");
        assert!(skipped.contains("centre of mass inside the body's bounding box: the file stores only the interface nodes (1 nodes)"), "{skipped}");
        assert!(
            skipped.contains("invariants recomputed from the stored nodal masses"),
            "{skipped}"
        );
        assert_eq!(
            skipped.contains("Φᵀ M Φ, Φᵀ K Φ and eigen residuals against the model"),
            model.is_some(),
            "{skipped}"
        );
        // The rigid-body checks from the invariants still run.
        assert!(report.items.iter().any(|i| i.name == "total mass I1 > 0"));
        assert!(report
            .items
            .iter()
            .any(|i| i.name == "rigid-body modes as expected"));
    }
    // A file with every node skips nothing.
    s.keep_nodes = KeepNodes::All;
    let full = build(&s, &mut |_| {}).unwrap();
    let report = check(&full.body, None).unwrap();
    assert!(report.skipped.is_empty(), "{:?}", report.skipped);
    assert!(report.passed());
}
