//! Broken (and forward-compatible) files derived from the 3-node golden body, each with the
//! error a reader must give. Entries are re-encoded after the mutation, and the manifest is
//! rebuilt from the mutated bytes unless the point is a stale manifest.
mod container;
mod eigen;
mod geometric;
mod json;
mod round3;
mod rules;

use flexbody::write::{zip_entries, Compression};
use flexbody_reader::codec;
use flexbody_reader::*;
use serde_json::{json, Value};

/// One generated file: stem, bytes, and either `Some((variant, message fragment))` for a file
/// that must be refused or `None` for one that must be accepted.
pub struct Case {
    /// File stem.
    pub name: &'static str,
    /// File bytes.
    pub bytes: Vec<u8>,
    /// Expected error (variant, fragment) or None to accept.
    pub expect: Option<(&'static str, &'static str)>,
}

type Entries = Vec<(String, bool, Vec<u8>)>;

/// What `cases` hands its topic modules: adds one case (stem, bytes, expected error).
type Add<'a> = dyn FnMut(&'static str, Vec<u8>, Option<(&'static str, &'static str)>) + 'a;

fn entries(body: &ReducedBody) -> Entries {
    encode_entries(body)
        .into_iter()
        .map(|(n, r, b)| (n.to_string(), r, b))
        .collect()
}

fn manifest(body: &ReducedBody, e: &Entries) -> Value {
    let refs: Vec<(&str, bool, Vec<u8>)> = e
        .iter()
        .map(|(n, r, b)| (n.as_str(), *r, b.clone()))
        .collect();
    serde_json::to_value(manifest_for(body, &refs)).expect("manifest is plain JSON")
}

fn pack_raw(manifest: Option<Vec<u8>>, e: &Entries) -> Vec<u8> {
    let mut all: Vec<(String, Vec<u8>)> = manifest
        .map(|m| vec![(codec::MANIFEST.to_string(), m)])
        .unwrap_or_default();
    all.extend(e.iter().map(|(n, _, b)| (n.clone(), b.clone())));
    zip_entries(&all, Compression::Deflate(6)).expect("in-memory zip")
}

fn pack(m: &Value, e: &Entries) -> Vec<u8> {
    let mut text = serde_json::to_vec_pretty(m).expect("json");
    text.push(b'\n');
    pack_raw(Some(text), e)
}

/// Re-encodes a mutated body (no validation) with a matching manifest.
fn from_body(body: &ReducedBody) -> Vec<u8> {
    let e = entries(body);
    pack(&manifest(body, &e), &e)
}

fn set_entry(e: &mut Entries, name: &str, bytes: Vec<u8>) {
    if let Some(x) = e.iter_mut().find(|x| x.0 == name) {
        x.2 = bytes;
    }
}

/// The offsets in `zip` of entry `name`'s local header (APPNOTE 4.3.7) and central-directory
/// header (4.3.12), in that order.
fn headers(zip: &[u8], name: &str) -> [usize; 2] {
    let n = name.as_bytes();
    [(0x04034b50u32, 30usize), (0x02014b50, 46)].map(|(sig, name_at)| {
        let sig = sig.to_le_bytes();
        (0..zip.len().saturating_sub(name_at + n.len()))
            .find(|&i| zip[i..i + 4] == sig && &zip[i + name_at..i + name_at + n.len()] == n)
            .expect("entry header present")
    })
}

/// Applies `f` to the `len`-byte field at offset `local` of entry `name`'s local header and at
/// `central` of its central-directory header.
fn patch(
    mut zip: Vec<u8>,
    name: &str,
    [local, central]: [usize; 2],
    len: usize,
    f: impl Fn(&mut [u8]),
) -> Vec<u8> {
    let [l, c] = headers(&zip, name);
    f(&mut zip[l + local..l + local + len]);
    f(&mut zip[c + central..c + central + len]);
    zip
}

/// Rewrites the compression-method field of entry `name` in both its headers.
fn patch_method(zip: Vec<u8>, name: &str, method: u16) -> Vec<u8> {
    patch(zip, name, [8, 10], 2, |b| {
        b.copy_from_slice(&method.to_le_bytes())
    })
}

/// Flips the low bit of entry `name`'s CRC-32 in both its headers: the zip layer's own
/// integrity check must fail.
fn patch_crc(zip: Vec<u8>, name: &str) -> Vec<u8> {
    patch(zip, name, [14, 16], 1, |b| b[0] ^= 1)
}

/// Renames entry `from` to `to` (same length) in both its headers: the zip writer refuses
/// duplicate names, so a file with two entries of one name is made by renaming a uniquely
/// named one.
fn patch_name(zip: Vec<u8>, from: &str, to: &str) -> Vec<u8> {
    assert_eq!(from.len(), to.len());
    patch(zip, from, [30, 46], to.len(), |b| {
        b.copy_from_slice(to.as_bytes())
    })
}

/// Sets the general-purpose "encrypted" flag (bit 0) of entry `name` in both its headers
/// (APPNOTE 4.4.4).
fn patch_encrypted(zip: Vec<u8>, name: &str) -> Vec<u8> {
    patch(zip, name, [6, 8], 1, |b| b[0] |= 1)
}

/// Every case, in a fixed order.
pub fn cases(base: &ReducedBody) -> Vec<Case> {
    let mut out = Vec::new();
    let mut add = |name, bytes, expect| {
        out.push(Case {
            name,
            bytes,
            expect,
        })
    };
    let good = entries(base);
    let good_manifest = manifest(base, &good);

    add(
        "not_a_zip",
        b"solid rod\n  facet normal 0 0 1\nendsolid\n".to_vec(),
        Some(("NotZip", "not a zip container")),
    );
    add(
        "missing_manifest",
        pack_raw(None, &good),
        Some(("MissingEntry", "manifest.json")),
    );
    add(
        "manifest_not_json",
        pack_raw(
            Some(b"{ \"format\": \"flexbody-reduced-body\", ".to_vec()),
            &good,
        ),
        Some(("Manifest", "not valid manifest JSON")),
    );

    let mut m = good_manifest.clone();
    m["format"] = json!("adams-mnf");
    add(
        "wrong_format_name",
        pack(&m, &good),
        Some(("WrongFormat", "adams-mnf")),
    );

    let mut e = good.clone();
    let modes = &mut e.iter_mut().find(|x| x.0 == codec::MODES).expect("modes").2;
    let last = modes.len() - 1;
    modes[last] ^= 0x01; // same size, one bit flipped in the last shape value
    add(
        "checksum_mismatch",
        pack(&good_manifest, &e),
        Some(("Checksum", "modes.bin")),
    );

    let mut e = good.clone();
    let nodes = e
        .iter()
        .find(|x| x.0 == codec::NODES)
        .expect("nodes")
        .2
        .clone();
    set_entry(&mut e, codec::NODES, nodes[..nodes.len() - 5].to_vec());
    add(
        "size_mismatch_stale_manifest",
        pack(&good_manifest, &e),
        Some(("SizeMismatch", "nodes.bin")),
    );
    add(
        "truncated_entry",
        pack(&manifest(base, &e), &e),
        Some(("Decode", "nodes.bin: cannot decode (record ends early")),
    );

    let mut m = good_manifest.clone();
    m["version"] = json!({"major": 2, "minor": 0});
    add(
        "newer_major_version",
        pack(&m, &good),
        Some(("UnsupportedVersion", "format version 2.0 is newer")),
    );
    // A 2.0 manifest whose other members changed shape: still UnsupportedVersion (the version
    // is judged before the rest of the manifest, SPEC §7.1 step 3).
    m["entries"] = json!({"payload": "a later layout"});
    m.as_object_mut().expect("object").remove("units");
    add(
        "newer_major_version_other_manifest",
        pack(&m, &good),
        Some(("UnsupportedVersion", "format version 2.0 is newer")),
    );

    let mut e = good.clone();
    e.push((
        "future_thing.bin".into(),
        false,
        b"opaque bytes of a later minor version".to_vec(),
    ));
    let mut m = manifest(base, &e);
    m["version"] = json!({"major": 1, "minor": 3});
    add("newer_minor_unknown_optional", pack(&m, &e), None);

    let mut m = good_manifest.clone();
    m["version"] = json!({"major": 1, "minor": 1});
    m["source_model"] = json!({"sha256": "0".repeat(64)});
    m["units"]["temperature"] = json!({"name": "K", "si": 1.0});
    m["entries"][0]["media_type"] = json!("application/octet-stream");
    add(
        "newer_minor_unknown_manifest_members",
        pack(&m, &good),
        None,
    );

    let mut m = good_manifest.clone();
    m["units"]["mass"]
        .as_object_mut()
        .expect("object")
        .remove("si");
    add(
        "manifest_member_missing",
        pack(&m, &good),
        Some(("Manifest", "missing field `si`")),
    );

    let mut e = good.clone();
    e.push((
        "future_thing.bin".into(),
        true,
        b"must be understood".to_vec(),
    ));
    add(
        "unknown_required_entry",
        pack(&manifest(base, &e), &e),
        Some(("UnknownRequiredEntry", "future_thing.bin")),
    );

    let mut e = good.clone();
    e.push(("stray.txt".into(), false, b"not listed".to_vec()));
    add(
        "unlisted_entry",
        pack(&good_manifest, &e),
        Some(("UnlistedEntry", "stray.txt")),
    );
    // A folder entry is an entry like any other (SPEC §2): not listed → UnlistedEntry.
    let mut e = good.clone();
    e.push(("extras/".into(), false, Vec::new()));
    add(
        "folder_entry",
        pack(&good_manifest, &e),
        Some(("UnlistedEntry", "extras/")),
    );
    // Bytes before the first entry are not looked at (SPEC §2): the file is accepted.
    let mut prefixed = b"#!self-extracting stub\n".to_vec();
    prefixed.extend(pack(&good_manifest, &good));
    add("data_before_first_entry", prefixed, None);

    let e: Entries = good
        .iter()
        .filter(|x| x.0 != codec::METHOD)
        .cloned()
        .collect();
    add(
        "missing_required_entry",
        pack(&manifest(base, &e), &e),
        Some(("MissingEntry", "method.bin")),
    );

    let mut b = base.clone();
    b.nodal_mass.pop();
    add(
        "count_mismatch_nodal_mass",
        from_body(&b),
        Some((
            "CountMismatch",
            "nodal_mass.bin: nodal masses has length 2, expected 3",
        )),
    );

    let mut b = base.clone();
    b.modes.shapes[6] = f64::NAN;
    add(
        "nan_in_shape",
        from_body(&b),
        Some(("NonFinite", "modes.bin: shapes[6] is not finite")),
    );

    let mut b = base.clone();
    b.modes.omega2[2] = f64::INFINITY;
    add(
        "inf_in_eigenvalue",
        from_body(&b),
        Some(("NonFinite", "modes.bin: omega2[2]")),
    );

    let mut b = base.clone();
    b.faces = vec![Face::Tri([0, 1, 7])];
    add(
        "face_index_out_of_range",
        from_body(&b),
        Some(("IndexOutOfRange", "faces.bin: faces[0][2] node index 7")),
    );

    let mut b = base.clone();
    b.lines = Some(vec![[0, 1], [2, 3]]);
    add(
        "line_index_out_of_range",
        from_body(&b),
        Some(("IndexOutOfRange", "lines.bin: lines[1][1] node index 3")),
    );

    let mut e = good.clone();
    let mut nodes = e
        .iter()
        .find(|x| x.0 == codec::NODES)
        .expect("nodes")
        .2
        .clone();
    nodes[..8].copy_from_slice(&(1u64 << 60).to_le_bytes());
    set_entry(&mut e, codec::NODES, nodes);
    add(
        "length_prefix_2_pow_60",
        pack(&manifest(base, &e), &e),
        Some(("Decode", "nodes.bin: cannot decode (record ends early")),
    );

    let mut e = good.clone();
    let mut header = e
        .iter()
        .find(|x| x.0 == codec::HEADER)
        .expect("header")
        .2
        .clone();
    header[..8].copy_from_slice(&(1u64 << 40).to_le_bytes()); // title length: 1 TiB string
    set_entry(&mut e, codec::HEADER, header);
    add(
        "string_length_2_pow_40",
        pack(&manifest(base, &e), &e),
        Some(("Decode", "header.bin: cannot decode")),
    );

    let mut m = good_manifest.clone();
    m["entries"][4]["size"] = json!(1u64 << 40);
    add(
        "entry_size_over_limit",
        pack(&m, &good),
        Some((
            "LimitExceeded",
            "modes.bin: declared size (bytes) 1099511627776 exceeds the limit",
        )),
    );

    let mut e = good.clone();
    let mut header = e
        .iter()
        .find(|x| x.0 == codec::HEADER)
        .expect("header")
        .2
        .clone();
    header.extend_from_slice(&[0, 0, 0]);
    set_entry(&mut e, codec::HEADER, header);
    add(
        "trailing_bytes",
        pack(&manifest(base, &e), &e),
        Some(("TrailingBytes", "header.bin: 3 trailing bytes")),
    );

    let mut e = good.clone();
    let mut nodes = e
        .iter()
        .find(|x| x.0 == codec::NODES)
        .expect("nodes")
        .2
        .clone();
    nodes[8 + 32] = 2; // interface flag of node 0: bool must be 0 or 1
    set_entry(&mut e, codec::NODES, nodes);
    add(
        "bad_bool_byte",
        pack(&manifest(base, &e), &e),
        Some(("Decode", "nodes.bin: cannot decode")),
    );

    let mut e = good.clone();
    let mut faces = e
        .iter()
        .find(|x| x.0 == codec::FACES)
        .expect("faces")
        .2
        .clone();
    faces[8] = 7; // face tag 7: only 0 (Tri) and 1 (Quad) exist
    set_entry(&mut e, codec::FACES, faces);
    add(
        "bad_enum_tag",
        pack(&manifest(base, &e), &e),
        Some(("Decode", "faces.bin: cannot decode")),
    );

    let mut b = base.clone();
    b.modes.generalized_mass[1] = 0.5;
    add(
        "generalized_mass_not_symmetric",
        from_body(&b),
        Some((
            "NotSymmetric",
            "modes.bin: generalized_mass not symmetric at (0, 1)",
        )),
    );

    let mut b = base.clone();
    b.modes.frequency_hz[1] *= 1.01;
    add(
        "frequency_disagrees_with_omega2",
        from_body(&b),
        Some(("Inconsistent", "modes.bin: frequency_hz[1]")),
    );

    let mut b = base.clone();
    b.invariants.mask[8] = false;
    b.invariants.i9.clear();
    add(
        "invariant_mask_not_the_set",
        from_body(&b),
        Some(("Inconsistent", "invariants.bin: mask")),
    );

    let mut b = base.clone();
    b.invariants.i5.pop();
    add(
        "invariant_wrong_length",
        from_body(&b),
        Some((
            "CountMismatch",
            "invariants.bin: i5 has length 26, expected 27",
        )),
    );

    let mut m = good_manifest.clone();
    let first = m["entries"][0].clone();
    m["entries"].as_array_mut().expect("array").push(first);
    add(
        "duplicate_manifest_entry",
        pack(&m, &good),
        Some(("DuplicateEntry", "header.bin")),
    );

    let mut b = base.clone();
    b.method.interface[0].frame[0][0] = 0.9;
    add(
        "interface_frame_not_orthonormal",
        from_body(&b),
        Some((
            "Inconsistent",
            "method.bin: interface[0].frame is not orthonormal",
        )),
    );
    add(
        "zip_crc_mismatch",
        patch_crc(pack(&good_manifest, &good), codec::NODES),
        Some(("Container", "nodes.bin: damaged zip data")),
    );
    // Method 12 (bzip2) on damping.bin: v1 allows only stored (0) and deflate (8).
    add(
        "unsupported_compression",
        patch_method(pack(&good_manifest, &good), codec::DAMPING, 12),
        Some(("Compression", "damping.bin: compression method")),
    );

    add(
        "encrypted_entry",
        patch_encrypted(pack(&good_manifest, &good), codec::DAMPING),
        Some(("Container", "damping.bin")),
    );
    // Two zip entries named damping.bin (SPEC §7.1 step 1): the second is a renamed copy.
    let mut dup = good.clone();
    let copy = dup
        .iter()
        .find(|e| e.0 == codec::DAMPING)
        .expect("base has damping")
        .clone();
    dup.push(("damping.bix".to_string(), false, copy.2));
    add(
        "duplicate_zip_entry",
        patch_name(pack(&good_manifest, &dup), "damping.bix", codec::DAMPING),
        Some(("DuplicateEntry", "damping.bin")),
    );

    // recipe.json (format 1.2): JSON that is not a recipe, and a recipe naming a node that is not
    // a stored interface node.
    let mut b = base.clone();
    b.recipe = Some(super::recipe_3node());
    let recipe_bytes = codec::encode_recipe(&super::recipe_3node());
    let cut = recipe_bytes[..recipe_bytes.len() / 2].to_vec();
    add(
        "recipe_not_json",
        with_entry(&b, codec::RECIPE, cut),
        Some(("Decode", "recipe.json: cannot decode")),
    );
    let mut c = base.clone();
    c.method.counts.normal = 5;
    add(
        "counts_do_not_add_up",
        from_body(&c),
        Some((
            "Inconsistent",
            "method.bin: counts give 6 basis vectors (after 0 removed) for 3 modes",
        )),
    );
    let mut c = base.clone();
    c.method.cutoffs.fmax_hz = Some(300.0);
    add(
        "cutoff_fmax_not_the_request",
        from_body(&c),
        Some((
            "Inconsistent",
            "method.bin: cutoffs.fmax_hz Some(300.0) differs",
        )),
    );
    let mut s = base.clone();
    s.label_shares = Some(vec![1.0, 1.5, 1.0]);
    add(
        "label_share_above_one",
        from_body(&s),
        Some(("Inconsistent", "label_shares.bin: share[1] = 1.5")),
    );
    let mut ml = base.clone();
    ml.modal_loads = Some(ModalLoads {
        loads: vec![ModalLoad {
            name: "TIP".into(),
            source: "--load TIP:103:10,0,0".into(),
            values: vec![1.0, 2.0],
        }],
        residual: vec![],
    });
    add(
        "modal_load_values_not_one_per_mode",
        from_body(&ml),
        Some(("CountMismatch", "modal_loads.bin")),
    );
    if let Some(m) = ml.modal_loads.as_mut() {
        m.loads[0].values = vec![1.0, 2.0, 3.0];
        m.residual = vec![0, 2, 0];
    }
    add(
        "modal_load_residual_flag_not_0_or_1",
        from_body(&ml),
        Some(("Inconsistent", "modal_loads.bin: residual[1] = 2")),
    );
    if let Some(r) = b.recipe.as_mut() {
        r.interfaces[0].nodes = vec![102];
    }
    add(
        "recipe_interface_node_not_stored",
        from_body(&b),
        Some((
            "Inconsistent",
            "recipe.json: interfaces[0] (101) names node 102",
        )),
    );
    let mut b = super::body_3node_interfaces();
    if let Some(f) = b.interfaces.as_mut().and_then(|i| i[1].fit.as_mut()) {
        f.centre = [2.0, 0.001, 0.0];
    }
    add(
        "interface_centre_not_at_node",
        from_body(&b),
        Some((
            "Inconsistent",
            "interfaces.bin: interfaces[1] (RIGHT_END): centre [2.0, 0.001, 0.0] is not node 103's position",
        )),
    );
    // Issue 37, round 2: container reading, JSON, and the rules settled there.
    container::cases(base, &mut add);
    json::cases(base, &mut add);
    rules::cases(base, &mut add);
    geometric::cases(&mut add);
    // Issue 46: format 1.9.
    eigen::cases(&mut add);
    // Issue 49, round 3.
    round3::cases(base, &mut add);
    out
}

/// `base` written with entry `name` replaced by `bytes` and a manifest that matches, so the
/// mutation reaches the decoder and the consistency rules instead of the checksum.
pub fn with_entry(base: &ReducedBody, name: &str, bytes: Vec<u8>) -> Vec<u8> {
    let mut e = entries(base);
    set_entry(&mut e, name, bytes);
    pack(&manifest(base, &e), &e)
}

/// The encoded payload entries of `base`: (name, bytes).
pub fn payloads(base: &ReducedBody) -> Vec<(String, Vec<u8>)> {
    entries(base).into_iter().map(|(n, _, b)| (n, b)).collect()
}
