#!/usr/bin/env python3
"""The numpy reader against the conformance fixtures (run: python3 python/tests/check_fixtures.py
fixtures): every golden and compat file gives the summary in its .json (and the same as the
stdlib reference reader's), every broken file is refused with the error name of its .expect.
Everything runs twice: as shipped, and with the chunked inflate of large entries (inflate and
hash in pieces, `_reader._CHUNK`) forced on every entry, so that path meets the broken files
too. Exit 1 on any mismatch."""
import json
import sys
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


if __name__ == "__main__":
    root = sys.argv[1] if len(sys.argv) > 1 else "fixtures"
    status = main(root)
    _reader._CHUNK = 7  # every deflated entry through the chunked inflate, 7-byte input pieces
    print("again, with the chunked inflate on every entry:")
    sys.exit(main(root) or status)
