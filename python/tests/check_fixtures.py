#!/usr/bin/env python3
"""The numpy reader against the conformance fixtures (run: python3 python/tests/check_fixtures.py
fixtures): every golden and compat file gives the summary in its .json (and the same as the
stdlib reference reader's), every broken file is refused with the error name of its .expect.
Everything runs twice: as shipped, and with the chunked inflate of large entries (inflate and
hash in pieces, `_reader._CHUNK`) forced on every entry, so that path meets the broken files
too. Then stored entries (the writer stores large incompressible ones, SPEC §2): every golden
file re-zipped with its entries stored reads as the reference reads it, and with one byte of
an entry flipped (CRC-32 left as it was, or made to match) the numpy reader refuses it with
the reference's error name — with the in-place check of large stored entries forced on every
entry. Exit 1 on any mismatch."""
import io
import json
import sys
import zipfile
from pathlib import Path

import flexbody
from flexbody import _reader, _spec


def main(root):
    root, bad, n = Path(root), 0, 0
    for f in sorted(list(root.glob("golden/*/*.flexbody")) + list(root.glob("compat/*.flexbody"))):
        n += 1
        try:
            got = flexbody.read(f).summary()
        except flexbody.ReadError as e:
            print(f"FAIL {f}: refused ({e})")
            bad += 1
            continue
        want = json.loads(f.with_suffix(".json").read_text())
        ref = _spec.summarize(*_spec.read_bytes(f.read_bytes()))
        diff = _spec.close(got, want) or _spec.close(got, ref)
        print(f"{'FAIL' if diff else 'ok  '} {f}{': ' + diff if diff else ''}")
        bad += bool(diff)
    for f in sorted(root.glob("broken/*.flexbody")):
        n += 1
        want = json.loads(f.with_suffix(".expect").read_text())["variant"]
        try:
            flexbody.read(f)
            print(f"FAIL {f}: accepted, expected {want}")
            bad += 1
        except flexbody.ReadError as e:
            ok = e.variant == want
            print(f"{'ok  ' if ok else 'FAIL'} {f}: {e}{'' if ok else f' (expected {want})'}")
            bad += not ok
    print(f"{n - bad}/{n} fixtures: numpy reader conforms")
    return 1 if bad or n == 0 else 0


def restored(data, flip=None, fix_crc=False):
    """`data` re-zipped with every entry stored; `flip`: the entry whose middle byte is
    inverted, after zipping (its CRC-32 no longer matches) or before (`fix_crc`: it matches)."""
    src = zipfile.ZipFile(io.BytesIO(data))
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_STORED) as z:
        for info in src.infolist():
            b = bytearray(src.read(info.filename))
            if info.filename == flip and fix_crc:
                b[len(b) // 2] ^= 0xFF
            z.writestr(info.filename, bytes(b))
    data = bytearray(out.getvalue())
    if flip is not None and not fix_crc:
        info = zipfile.ZipFile(io.BytesIO(bytes(data))).getinfo(flip)
        off = info.header_offset
        start = off + 30 + int.from_bytes(data[off + 26:off + 28], "little") \
            + int.from_bytes(data[off + 28:off + 30], "little")
        data[start + info.file_size // 2] ^= 0xFF
    return bytes(data)


def outcome(read, data):
    try:
        read(data)
        return "accepted"
    except flexbody.ReadError as e:
        return e.variant


def stored(root):
    root, bad, n = Path(root), 0, 0
    for f in sorted(root.glob("golden/*/*.flexbody")):
        data = f.read_bytes()
        names = [i.filename for i in zipfile.ZipFile(io.BytesIO(data)).infolist()
                 if i.filename in _reader._NUMPY_DECODED and i.file_size > 0]
        cases = [("all stored", restored(data))]
        for name in names:
            cases.append((f"{name} flipped", restored(data, name)))
            cases.append((f"{name} flipped, CRC-32 matching", restored(data, name, fix_crc=True)))
        for what, case in cases:
            n += 1
            want = outcome(_spec.read_bytes, case)
            got = outcome(flexbody.read_bytes_body, case)
            ok = got == want and (what == "all stored") == (want == "accepted")
            if ok and want == "accepted":
                diff = _spec.close(flexbody.read_bytes_body(case).summary(),
                                   _spec.summarize(*_spec.read_bytes(case)))
                ok = diff is None
            if not ok:
                print(f"FAIL {f} {what}: numpy reader {got}, reference {want}")
            bad += not ok
    print(f"{n - bad}/{n} stored-entry cases: numpy reader conforms")
    return 1 if bad or n == 0 else 0


def interface_ids(root):
    """`interfaces[k]["node_id"]` is the id of the stored node `interfaces[k]["node"]` indexes,
    and the fixture's interfaces name it as the reference reader does."""
    bad = n = 0
    for f in sorted(Path(root).glob("golden/*/*.flexbody")):
        body = flexbody.read(f)
        for itf in body.interfaces or []:
            n += 1
            ok = itf["node_id"] == int(body.node_ids[itf["node"]]) and body.interface_flags[itf["node"]]
            if not ok:
                print(f"FAIL {f}: interface {itf['name']}: node_id {itf['node_id']}, node index {itf['node']}")
            bad += not ok
    print(f"{n - bad}/{n} interface records: node_id is the indexed node's id")
    return 1 if bad or n == 0 else 0


def geometric_arrays(root):
    """`geometric_stiffness["fields"][name]` (format 1.7) is the (M, M) array of the summary's
    row-major matrix of that load, for every golden file that has the entry."""
    import numpy as np
    bad = n = 0
    for f in sorted(Path(root).glob("golden/*/*.flexbody")):
        body = flexbody.read(f)
        if body.geometric_stiffness is None:
            continue
        nm = body.mode_count
        for field in body.summary()["geometric_stiffness"]["fields"]:
            n += 1
            a = body.geometric_stiffness["fields"][field["load"]]
            ok = a.shape == (nm, nm) and np.array_equal(a.ravel(), np.asarray(field["matrix"]))
            if not ok:
                print(f"FAIL {f}: geometric stiffness {field['load']}")
            bad += not ok
    print(f"{n - bad}/{n} geometric-stiffness fields: (M, M) arrays of the summary's matrices")
    return 1 if bad or n == 0 else 0


if __name__ == "__main__":
    root = sys.argv[1] if len(sys.argv) > 1 else "fixtures"
    status = main(root)
    status = interface_ids(root) or status
    status = geometric_arrays(root) or status
    _reader._CHUNK = 7  # every deflated entry through the chunked inflate, 7-byte input pieces
    print("again, with the chunked inflate on every entry:")
    status = main(root) or status
    _reader._CHUNK = 0  # every stored numpy-decoded entry checked in place (`_check_stored`)
    sys.exit(stored(root) or status)
