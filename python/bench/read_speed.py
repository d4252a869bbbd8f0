#!/usr/bin/env python3
"""Benchmark (not a test): time the numpy package against the stdlib reference reader on a
synthetic valid body of N nodes and M modes (default 500,000 and 6), mixed triangle/quad faces,
random mode shapes in all six components.

    python3 python/bench/read_speed.py [N] [M]
    python3 python/bench/read_speed.py --file BODY.flexbody    # a real file, as written

Three times: entries as flexbody writes them (deflate level 6, except that an entry of at least
1 MiB whose deflate saves less than 1/16 is stored: `Compression::Auto`, SPEC.md §2 — here the
random mode shapes are stored), every entry deflated (as flexbody wrote before that rule, and
`Compression::Deflate(6)` still does), and every entry stored. Also prints the container floor
both readers share (zlib inflate of the deflated entries + SHA-256 of every entry).
"""
import hashlib
import io
import json
import math
import struct
import sys
import time
import zipfile
import zlib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "format-spec"))
import reference_reader  # noqa: E402

import flexbody  # noqa: E402


def vec(a, dtype):
    a = np.ascontiguousarray(a, dtype=dtype)
    return struct.pack("<Q", len(a)) + a.tobytes()


# The writer's rule (src/write/mod.rs: AUTO_STORE_MIN_BYTES, AUTO_STORE_MIN_SAVING).
AUTO_STORE_MIN_BYTES = 1 << 20
AUTO_STORE_MIN_SAVING = 16
AUTO = "auto"


def auto_stores(raw):
    """Compression::Auto's decision: store an entry of n >= 1 MiB whose level-6 deflate has c
    bytes with 16 (n - c) < n. (zlib here, zlib-rs in the writer: sizes agree to a few bytes.)"""
    n = len(raw)
    if n < AUTO_STORE_MIN_BYTES:
        return False
    c = zlib.compressobj(6, zlib.DEFLATED, -15)
    return AUTO_STORE_MIN_SAVING * (n - len(c.compress(raw) + c.flush())) < n


def body_bytes(n, m, seed=1, compression=zipfile.ZIP_DEFLATED):
    rng = np.random.default_rng(seed)
    title = b"synthetic"
    header = (struct.pack("<Q", len(title)) + title + b"\x00" + struct.pack("<I", 0) + b"\x00"
              + b"\x01" + struct.pack("<Q", m) + struct.pack("<I", 0) + struct.pack("<I", 3)
              + struct.pack("<I", 0))
    xyz = rng.uniform(-1, 1, (n, 3))
    nodes = np.zeros(n, dtype=[("id", "<u8"), ("xyz", "<f8", (3,)), ("interface", "u1")])
    nodes["id"] = np.arange(1, n + 1)
    nodes["xyz"] = xyz
    nf = n // 2
    quad = rng.random(nf) < 0.5
    idx = rng.integers(0, n, (nf, 4)).astype("<u4")
    parts = [struct.pack("<Q", nf)]
    rows = np.zeros((nf, 5), dtype="<u4")
    rows[:, 0] = quad
    rows[:, 1:] = idx
    flat = rows.ravel()
    keep = np.ones((nf, 5), dtype=bool)
    keep[~quad, 4] = False
    parts.append(flat[keep.ravel()].tobytes())
    faces = b"".join(parts)
    nodal = np.zeros((n, 10))
    nodal[:, 0] = 1.0
    f = 100.0 * np.arange(1, m + 1)
    w2 = (2 * math.pi * f) ** 2
    fr = np.sqrt(np.maximum(w2, 0)) / (2 * math.pi)
    modes = (vec(w2, "<f8") + vec(fr, "<f8") + vec(np.ones(m), "<u4") + vec(np.eye(m).ravel(), "<f8")
             + vec(np.diag(w2).ravel(), "<f8") + vec(rng.standard_normal(m * n * 6), "<f8"))
    s2 = xyz.sum(axis=0)
    ss = (xyz * xyz).sum(axis=1)
    i7 = ss.sum() * np.eye(3) - xyz.T @ xyz
    inv = bytes([1, 1, 0, 0, 0, 0, 1, 0, 0]) + vec([float(n)], "<f8") + vec(s2, "<f8")
    for k in range(3, 10):
        inv += vec(i7.ravel() if k == 7 else [], "<f8")
    method = (struct.pack("<II", 0, 0) + struct.pack("<Q", 0) + struct.pack("<Q", 0)
              + struct.pack("<6Q", 0, m, 0, 0, 0, 0) + b"\x00\x00\x00")
    entries = [("header.bin", True, header), ("nodes.bin", True, struct.pack("<Q", n) + nodes.tobytes()),
               ("faces.bin", True, faces), ("nodal_mass.bin", True, vec(nodal.ravel(), "<f8")[0:8]
                                             [:0] + struct.pack("<Q", n) + nodal.tobytes()),
               ("modes.bin", True, modes), ("invariants.bin", True, inv), ("method.bin", True, method),
               ("label_shares.bin", False, vec(np.ones(m), "<f8"))]
    unit = lambda name: {"name": name, "si": 1.0}  # noqa: E731
    manifest = {"format": "flexbody-reduced-body", "version": {"major": 1, "minor": 2},
                "generator": {"name": "read_speed.py", "version": "0"},
                "units": {"mass": unit("kg"), "length": unit("m"), "time": unit("s"), "force": unit("N")},
                "entries": [{"name": e, "size": len(b), "sha256": hashlib.sha256(b).hexdigest(), "required": r}
                            for e, r, b in entries]}
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED, compresslevel=6) as z:
        for e, b in [("manifest.json", json.dumps(manifest).encode())] + [(e, b) for e, _, b in entries]:
            method = compression
            if compression == AUTO:
                method = zipfile.ZIP_STORED if auto_stores(b) else zipfile.ZIP_DEFLATED
            z.writestr(e, b, compress_type=method)
    return out.getvalue()


def best(f, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--file":
        data = Path(sys.argv[2]).read_bytes()
        print(f"{sys.argv[2]} ({stored_summary(data)}):")
        run(data)
        return
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 500_000
    m = int(sys.argv[2]) if len(sys.argv) > 2 else 6
    for compression, how in ((AUTO, "as flexbody writes (Compression::Auto)"),
                             (zipfile.ZIP_DEFLATED, "all deflated (level 6, Compression::Deflate(6))"),
                             (zipfile.ZIP_STORED, "all stored (Compression::Stored)")):
        data = body_bytes(n, m, compression=compression)
        print(f"entries {how} ({stored_summary(data)}):")
        run(data)


def stored_summary(data):
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        stored = [i.filename for i in z.infolist() if i.compress_type == zipfile.ZIP_STORED]
    return "stored: " + (", ".join(stored) or "none")


def run(data):
    ref = reference_reader.summarize(*reference_reader.read_bytes(data))
    got = flexbody.read_bytes_body(data).summary()
    diff = reference_reader.close(got, ref)
    assert diff is None, diff
    c = ref["counts"]
    t_np = best(lambda: flexbody.read_bytes_body(data), 3)
    t_ref = best(lambda: reference_reader.read_bytes(data), 1)
    t_zip = best(lambda: inflate_and_hash(data), 3)
    print(f"{c['nodes']} nodes, {c['modes']} modes, {c['faces']} faces, {len(data) / 1e6:.1f} MB file: "
          f"reference reader {t_ref:.2f} s, numpy package {t_np:.3f} s, {t_ref / t_np:.1f}x faster "
          f"(numpy {np.__version__}, Python {sys.version.split()[0]}); "
          f"inflating and hashing the entries alone (zlib, hashlib; one thread) {t_zip:.3f} s")


def inflate_and_hash(data):
    """The container floor both readers share: every entry inflated (if deflated) and hashed."""
    view = memoryview(data)
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        for info in z.infolist():
            off = info.header_offset  # local header: 30 bytes, name, extra, data
            start = off + 30 + int.from_bytes(data[off + 26:off + 28], "little") \
                + int.from_bytes(data[off + 28:off + 30], "little")
            raw = view[start:start + info.compress_size]
            if info.compress_type == zipfile.ZIP_DEFLATED:
                raw = zlib.decompress(raw, -15, info.file_size)
            hashlib.sha256(raw).hexdigest()


if __name__ == "__main__":
    main()
