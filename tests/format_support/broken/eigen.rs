//! Files of rule 16 (SPEC §5.17, format 1.9): each check of `eigen_residuals.bin`, its
//! decoding and the version it needs.
use super::*;

pub fn cases(add: &mut Add) {
    let base = super::super::body_3node_eigen_residuals();
    let with = |f: &dyn Fn(&mut EigenProblem)| {
        let mut b = base.clone();
        if let Some(p) = b.eigen_residuals.as_mut().map(|e| &mut e.problems[0]) {
            f(p);
        }
        from_body(&b)
    };
    add(
        "eigen_residuals_wrong_kind",
        with(&|p| p.kind = EigenProblemKind::FixedInterface),
        Some((
            "Inconsistent",
            "eigen_residuals.bin: problems[0] is FixedInterface, not the NormalModes problem",
        )),
    );
    add(
        "eigen_residuals_scale_zero",
        with(&|p| p.scale = 0.0),
        Some((
            "Inconsistent",
            "eigen_residuals.bin: problems[0].scale = 0 is not > 0",
        )),
    );
    add(
        "eigen_residuals_residual_wrong_length",
        with(&|p| {
            p.residual.pop();
        }),
        Some((
            "CountMismatch",
            "eigen_residuals.bin: problems[0].residual has length 2, expected 3",
        )),
    );
    add(
        "eigen_residuals_fewer_than_modes",
        with(&|p| {
            p.residual.pop();
            p.omega2.pop();
        }),
        Some((
            "CountMismatch",
            "eigen_residuals.bin: problems[0].omega2 has length 2, expected 3 (the modes M)",
        )),
    );
    add(
        "eigen_residuals_residual_nan",
        with(&|p| p.residual[1] = f64::NAN),
        Some((
            "NonFinite",
            "eigen_residuals.bin: problems[0].residual[1] is not finite",
        )),
    );
    add(
        "eigen_residuals_residual_negative",
        with(&|p| p.residual[2] = -1e-12),
        Some((
            "Inconsistent",
            "eigen_residuals.bin: problems[0].residual[2] is negative",
        )),
    );
    add(
        "eigen_residuals_inertia_below_stored",
        with(&|p| {
            if let Some(i) = p.inertia.as_mut() {
                i.below = 2;
            }
        }),
        Some((
            "Inconsistent",
            "eigen_residuals.bin: problems[0]: 3 stored eigenvalues lie below the shift",
        )),
    );
    // truncated: the last residual's 8 bytes and the inertia option are cut
    let mut e = entries(&base);
    if let Some(x) = e.iter_mut().find(|x| x.0 == codec::EIGEN_RESIDUALS) {
        let keep = x.2.len() - 8 - 17;
        x.2.truncate(keep);
    }
    add(
        "eigen_residuals_truncated",
        pack(&manifest(&base, &e), &e),
        Some((
            "Decode",
            "eigen_residuals.bin: cannot decode (record ends early",
        )),
    );
    // an unknown solver tag (4): the record starts with the problem count (8 bytes) and the
    // kind tag (4)
    let mut e = entries(&base);
    if let Some(x) = e.iter_mut().find(|x| x.0 == codec::EIGEN_RESIDUALS) {
        x.2[12..16].copy_from_slice(&4u32.to_le_bytes());
    }
    add(
        "eigen_residuals_unknown_solver",
        pack(&manifest(&base, &e), &e),
        Some(("Decode", "eigen_residuals.bin: cannot decode")),
    );
    let e = entries(&base);
    let mut m = manifest(&base, &e);
    m["version"] = json!({"major": 1, "minor": 8});
    add(
        "eigen_residuals_in_1_8_file",
        pack(&m, &e),
        Some((
            "Manifest",
            "entry eigen_residuals.bin came with format 1.9, but the file says 1.8",
        )),
    );
}
