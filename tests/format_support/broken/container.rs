//! Broken and accepted files of the container procedure (SPEC §7.1, §7.2; issue 37 items 5–7,
//! 13, 16): records over the string-record bound, the order of steps 5 and 6, streams longer
//! than declared, the end record's place, local headers.
use super::*;

/// Sets entry `name`'s uncompressed size (local header offset 22, central 24) to `size`.
fn patch_size(zip: Vec<u8>, name: &str, size: u32) -> Vec<u8> {
    patch(zip, name, [22, 24], 4, |b| {
        b.copy_from_slice(&size.to_le_bytes())
    })
}

/// `bytes` followed by zero bytes up to one byte beyond the 16 MiB string-record bound.
fn over_string_limit(mut bytes: Vec<u8>) -> Vec<u8> {
    bytes.resize(codec::STRING_RECORD_LIMIT + 1, 0);
    bytes
}

pub fn cases(base: &ReducedBody, add: &mut Add) {
    let good = entries(base);
    let good_manifest = manifest(base, &good);
    let bytes_of = |e: &Entries, name: &str| {
        e.iter()
            .find(|x| x.0 == name)
            .expect("entry present")
            .2
            .clone()
    };

    // Item 5: a whole header.bin beyond 16 MiB is Decode, whatever its record says.
    let mut e = good.clone();
    set_entry(
        &mut e,
        codec::HEADER,
        over_string_limit(bytes_of(&good, codec::HEADER)),
    );
    add(
        "header_over_16_mib",
        pack(&manifest(base, &e), &e),
        Some((
            "Decode",
            "header.bin: cannot decode (16777217 bytes exceed the 16777216-byte record limit)",
        )),
    );
    // Item 13: modal_loads.bin holds strings too.
    let b = super::super::body_3node_modal_loads();
    let mut e = entries(&b);
    let loads = bytes_of(&e, codec::MODAL_LOADS);
    set_entry(&mut e, codec::MODAL_LOADS, over_string_limit(loads));
    add(
        "modal_loads_over_16_mib",
        pack(&manifest(&b, &e), &e),
        Some((
            "Decode",
            "modal_loads.bin: cannot decode (16777217 bytes exceed",
        )),
    );

    // Item 6: a listed entry absent from the zip is found (step 5) before any entry is read
    // (step 6), here before nodes.bin's stale size.
    let mut e: Entries = good
        .iter()
        .filter(|x| x.0 != codec::DAMPING)
        .cloned()
        .collect();
    let nodes = bytes_of(&e, codec::NODES);
    set_entry(&mut e, codec::NODES, nodes[..nodes.len() - 5].to_vec());
    add(
        "listed_entry_absent_after_stale_one",
        pack(&good_manifest, &e),
        Some((
            "MissingEntry",
            "damping.bin: listed in manifest.json but absent",
        )),
    );

    // Item 7: a deflate stream longer than the size its directory and the manifest declare is
    // SizeMismatch (read to size + 1 bytes), whatever its CRC-32.
    let damping = bytes_of(&good, codec::DAMPING);
    let short = damping.len() - 1;
    let mut m = good_manifest.clone();
    let listed = m["entries"]
        .as_array_mut()
        .expect("array")
        .iter_mut()
        .find(|x| x["name"] == codec::DAMPING)
        .expect("damping listed");
    listed["size"] = json!(short);
    listed["sha256"] = json!(codec::sha256_hex(&damping[..short]));
    add(
        "entry_inflates_longer_than_declared",
        patch_size(pack(&m, &good), codec::DAMPING, short as u32),
        Some((
            "SizeMismatch",
            "damping.bin: size 32 bytes differs from the manifest's 31",
        )),
    );

    // Item 16: the manifest is read like any entry: too long a stream is SizeMismatch, a
    // CRC-32 that fails is Container.
    let zip = pack(&good_manifest, &good);
    let [l, _] = headers(&zip, codec::MANIFEST);
    let manifest_size = u32::from_le_bytes(zip[l + 22..l + 26].try_into().expect("4 bytes"));
    add(
        "manifest_inflates_longer",
        patch_size(zip.clone(), codec::MANIFEST, manifest_size - 1),
        Some(("SizeMismatch", "manifest.json: size")),
    );
    add(
        "manifest_crc_mismatch",
        patch_crc(zip.clone(), codec::MANIFEST),
        Some(("Container", "manifest.json: damaged zip data (CRC-32")),
    );
    // The end record is the one whose comment reaches the end of the file: a comment that holds
    // the signature changes nothing (accepted); a byte after the record leaves none.
    let mut commented = zip.clone();
    let comment = b"PK\x05\x06: a comment is not an end record";
    let at = commented.len() - 2;
    commented[at..].copy_from_slice(&(comment.len() as u16).to_le_bytes());
    commented.extend_from_slice(comment);
    add("archive_comment_holds_end_signature", commented, None);
    let mut trailing = zip.clone();
    trailing.push(0);
    add(
        "byte_after_end_record",
        trailing,
        Some(("NotZip", "no end-of-central-directory record ends the file")),
    );
    // The local header must name the entry the directory names.
    let [l, _] = headers(&zip, codec::DAMPING);
    let mut renamed = zip.clone();
    renamed[l + 30..l + 30 + 11].copy_from_slice(b"damping.bix");
    add(
        "local_header_names_another_entry",
        renamed,
        Some((
            "Container",
            "damping.bin: damaged zip data (the local header names another entry)",
        )),
    );
}
