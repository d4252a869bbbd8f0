//! Files of the consistency rules settled by issue 37 (items 1, 2, 10–13, 17): exact count
//! sums, record-by-record order inside a rule, bottom fibres, label shares, residual flags and
//! the version a file's contents need.
use super::*;

/// `base` as a Craig–Chang body (its three modes kept, a dependency tolerance recorded).
fn craig_chang(base: &ReducedBody) -> ReducedBody {
    let mut b = base.clone();
    b.header.request.method = Method::CraigChang;
    b.method.method = Method::CraigChang;
    b.method.cutoffs.dependency_tolerance = Some(1e-8);
    b.method.counts = ModeCounts {
        rigid: 1,
        normal: 2,
        attachment: 2,
        removed_dependent: 1,
        ..Default::default()
    };
    b
}

pub fn cases(base: &ReducedBody, add: &mut Add) {
    // Item 10: the sums of rule 8 are exact: 1 + (2⁶⁴−1) + 2 − (2⁶⁴−1) = 3 basis vectors for
    // 3 modes (accepted), not a saturated 0.
    let mut b = craig_chang(base);
    b.method.counts.normal = u64::MAX;
    b.method.counts.removed_dependent = u64::MAX;
    add("counts_sum_beyond_u64", from_body(&b), None);

    // Item 11: a rule over the records of an array runs record by record. Each file breaks
    // an earlier record with a later check and a later record with an earlier check.
    let mut b = base.clone();
    b.nodes[1].id = b.nodes[0].id;
    b.nodes[2].xyz[0] = f64::NAN;
    add(
        "order_rule3_record_by_record",
        from_body(&b),
        Some((
            "Inconsistent",
            "nodes.bin: node id 101 occurs twice (nodes[1])",
        )),
    );
    let mut b = base.clone();
    b.nodal_mass[1].mass = -1.0;
    b.nodal_mass[2].inertia[0][0] = f64::NAN;
    add(
        "order_rule5_record_by_record",
        from_body(&b),
        Some((
            "Inconsistent",
            "nodal_mass.bin: nodal_mass[1].mass is negative",
        )),
    );
    let mut b = base.clone();
    b.method.interface[0].frame[0][0] = 0.9;
    b.method.interface[1].node = 7;
    add(
        "order_rule8_record_by_record",
        from_body(&b),
        Some((
            "Inconsistent",
            "method.bin: interface[0].frame is not orthonormal",
        )),
    );
    let mut b = base.clone();
    b.strain_shapes = Some(FieldShapes {
        nodes: vec![1, 0, 5],
        values: vec![0.0; 3 * 3 * 6],
    });
    add(
        "order_rule9_record_by_record",
        from_body(&b),
        Some((
            "Inconsistent",
            "strain_shapes.bin: nodes must be strictly ascending (nodes[1] = 0)",
        )),
    );
    let mut b = base.clone();
    b.modal_loads = Some(ModalLoads {
        loads: vec![
            ModalLoad {
                name: "TIP".into(),
                source: "--load TIP:103:10,0,0".into(),
                values: vec![1.0, 2.0],
            },
            ModalLoad {
                name: String::new(),
                source: "--load".into(),
                values: vec![1.0, 2.0, 3.0],
            },
        ],
        residual: vec![],
    });
    add(
        "order_rule12_record_by_record",
        from_body(&b),
        Some((
            "CountMismatch",
            "modal_loads.bin: values has length 2, expected 3",
        )),
    );
    let good = entries(base);
    let mut m = manifest(base, &good);
    m["entries"][1]["size"] = json!(1u64 << 40);
    m["entries"][3]["sha256"] = json!("AB".repeat(32));
    add(
        "order_manifest_entries_entry_by_entry",
        pack(&m, &good),
        Some((
            "LimitExceeded",
            "nodes.bin: declared size (bytes) 1099511627776 exceeds the limit",
        )),
    );

    // Item 12: the bottom-fibre rules are rule 9's.
    let mut b = super::super::body_3node_shell_fibres();
    if let Some(s) = b.strain_shapes_bottom.as_mut() {
        s.nodes = vec![0, 1];
    }
    if let Some(t) = b.strain_shapes.as_mut() {
        let k = 6 * 3;
        t.nodes = vec![1, 2];
        t.values = t.values[..2 * k].to_vec();
    }
    add(
        "bottom_fibre_node_without_top_value",
        from_body(&b),
        Some((
            "Inconsistent",
            "strain_shapes_bottom.bin: node 0 has a bottom fibre but no value in strain_shapes.bin",
        )),
    );

    // Item 13: modal_loads.bin's smallest load encoding is 24 bytes: a count beyond the entry.
    let b = super::super::body_3node_modal_loads();
    let mut e = entries(&b);
    if let Some(x) = e.iter_mut().find(|x| x.0 == codec::MODAL_LOADS) {
        x.2[..8].copy_from_slice(&(1u64 << 40).to_le_bytes());
    }
    add(
        "modal_loads_count_beyond_entry",
        pack(&manifest(&b, &e), &e),
        Some((
            "Decode",
            "modal_loads.bin: cannot decode (record ends early",
        )),
    );

    // Item 17: what a file holds ties it to the version it states.
    let mut b = base.clone();
    b.lines = Some(vec![[0, 1]]);
    let e = entries(&b);
    let mut m = manifest(&b, &e);
    m["version"] = json!({"major": 1, "minor": 0});
    add(
        "entry_newer_than_stated_version",
        pack(&m, &e),
        Some((
            "Manifest",
            "entry lines.bin came with format 1.1, but the file says 1.0",
        )),
    );
    let b = super::super::body_3node_residual_vectors();
    let e = entries(&b);
    let mut m = manifest(&b, &e);
    m["version"] = json!({"major": 1, "minor": 5});
    add(
        "normal_modes_removed_dependent_in_1_5",
        pack(&m, &e),
        Some((
            "Inconsistent",
            "method.bin: counts.removed_dependent = 1 must be 0 for NormalModes in a 1.5 file",
        )),
    );
    // (a 1.4 file: the flag marks mode 2 as a residual-vector mode, its label says Normal)
    let mut b = super::super::body_3node_modal_loads();
    if let Some(ml) = b.modal_loads.as_mut() {
        ml.residual = vec![0, 0, 1];
    }
    add(
        "modal_load_residual_not_attachment",
        from_body(&b),
        Some((
            "Inconsistent",
            "modal_loads.bin: residual[2] = 1 but mode 2 is labelled Normal, not Attachment",
        )),
    );

    // Item 1: a share is 1 for a Rigid mode and for every mode of a single-stage basis.
    let mut b = base.clone();
    b.label_shares = Some(vec![1.0, 0.9, 1.0]);
    add(
        "label_share_of_normal_mode_not_one",
        from_body(&b),
        Some((
            "Inconsistent",
            "label_shares.bin: share[1] = 0.9 must be 1 (normal modes without residual vectors)",
        )),
    );
    // Rule 11 before 1.6: a normal-modes file with residual vectors but no mode flagged is
    // single-stage, so its shares must be 1 (since 1.6 a normal mode may mix with the residual
    // vectors below half: the same content is valid when the file says 1.6)
    let mut b = super::super::body_3node_residual_vectors();
    b.modes.labels[2] = flexbody_reader::ModeLabel::Normal;
    b.method.counts.normal = 2;
    b.method.counts.removed_dependent = 0;
    b.label_shares = Some(vec![1.0, 1.0, 27.0 / 55.0]);
    if let Some(ml) = b.modal_loads.as_mut() {
        ml.residual = vec![0, 0, 0];
    }
    assert!(
        flexbody_reader::validate(&b, &Default::default()).is_ok(),
        "valid as 1.6"
    );
    let e = entries(&b);
    let mut m = manifest(&b, &e);
    m["version"] = json!({"major": 1, "minor": 5});
    add(
        "label_share_mixed_without_flag_in_1_5",
        pack(&m, &e),
        Some((
            "Inconsistent",
            "label_shares.bin: share[2] = 0.4909090909090909 must be 1 (normal modes without residual vectors)",
        )),
    );
    let mut b = craig_chang(base);
    b.label_shares = Some(vec![0.5, 0.7, 0.8]);
    add(
        "label_share_of_rigid_mode_not_one",
        from_body(&b),
        Some((
            "Inconsistent",
            "label_shares.bin: share[0] = 0.5 must be 1 (a Rigid mode)",
        )),
    );
}
