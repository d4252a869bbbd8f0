//! Files of rule 15 (SPEC §5.16, format 1.7): each check of `geometric_stiffness.bin`, its
//! decoding and the version it needs.
use super::*;

pub fn cases(add: &mut Add) {
    let base = super::super::body_3node_geometric_stiffness();
    let field = |b: &mut ReducedBody| -> Vec<GeometricField> {
        b.geometric_stiffness
            .take()
            .map(|g| g.fields)
            .unwrap_or_default()
    };
    let with = |b: &ReducedBody, fields: Vec<GeometricField>| {
        let mut b = b.clone();
        b.geometric_stiffness = Some(GeometricStiffness {
            support: StaticSupport::InertiaRelief,
            fields,
        });
        from_body(&b)
    };
    let mut b = base.clone();
    let mut f = field(&mut b);
    f[0].load = UnitLoad::Acceleration(3);
    add(
        "geometric_axis_out_of_range",
        with(&b, f),
        Some((
            "Inconsistent",
            "geometric_stiffness.bin: fields[0]: load Acceleration(3) has an axis out of range",
        )),
    );
    let mut f = field(&mut base.clone());
    f[4].load = UnitLoad::AngularVelocity([1, 0]);
    add(
        "geometric_angular_velocity_axes_descending",
        with(&base, f),
        Some((
            "Inconsistent",
            "geometric_stiffness.bin: fields[4]: load AngularVelocity([1, 0]) has an axis out of range",
        )),
    );
    let mut f = field(&mut base.clone());
    f[11].load = UnitLoad::Acceleration(1);
    add(
        "geometric_load_twice",
        with(&base, f),
        Some((
            "Inconsistent",
            "geometric_stiffness.bin: fields[11]: load Acceleration(1) appears twice",
        )),
    );
    let mut f = field(&mut base.clone());
    f[2].matrix.pop();
    add(
        "geometric_matrix_not_modes_by_modes",
        with(&base, f),
        Some((
            "CountMismatch",
            "geometric_stiffness.bin: fields[2].matrix has length 8, expected 9",
        )),
    );
    let mut f = field(&mut base.clone());
    f[5].matrix[7] = f64::INFINITY;
    add(
        "geometric_matrix_not_finite",
        with(&base, f),
        Some((
            "NonFinite",
            "geometric_stiffness.bin: fields[5].matrix[7] is not finite",
        )),
    );
    let mut f = field(&mut base.clone());
    f[8].matrix[1] += 1e-6;
    add(
        "geometric_matrix_not_symmetric",
        with(&base, f),
        Some((
            "NotSymmetric",
            "geometric_stiffness.bin: fields[8].matrix not symmetric at (0, 1)",
        )),
    );
    // an unknown UnitLoad tag (3) in field 0: the record starts with the support tag (4
    // bytes) and the field count (8)
    let mut e = entries(&base);
    if let Some(x) = e.iter_mut().find(|x| x.0 == codec::GEOMETRIC_STIFFNESS) {
        x.2[12..16].copy_from_slice(&3u32.to_le_bytes());
    }
    add(
        "geometric_unknown_load_tag",
        pack(&manifest(&base, &e), &e),
        Some(("Decode", "geometric_stiffness.bin: cannot decode")),
    );
    // the smallest field encoding is 13 bytes: a count beyond the entry
    let mut e = entries(&base);
    if let Some(x) = e.iter_mut().find(|x| x.0 == codec::GEOMETRIC_STIFFNESS) {
        x.2[4..12].copy_from_slice(&(1u64 << 40).to_le_bytes());
    }
    add(
        "geometric_count_beyond_entry",
        pack(&manifest(&base, &e), &e),
        Some((
            "Decode",
            "geometric_stiffness.bin: cannot decode (record ends early",
        )),
    );
    let e = entries(&base);
    let mut m = manifest(&base, &e);
    m["version"] = json!({"major": 1, "minor": 6});
    add(
        "geometric_stiffness_in_1_6_file",
        pack(&m, &e),
        Some((
            "Manifest",
            "entry geometric_stiffness.bin came with format 1.7, but the file says 1.6",
        )),
    );
}
