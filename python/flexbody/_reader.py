"""numpy reader for .flexbody files (format-spec/SPEC.md, format 1.x).

The container (zip, manifest, checksums), the small records (header, method, interfaces,
recipe) and the rules that look at them are the stdlib reference reader's own code
(`_spec.py` is format-spec/reference_reader.py); the large arrays are numpy views of the
decoded payload (np.frombuffer, no per-value Python loop) and their rules are the reference's,
vectorized, in the same order — so both readers refuse a file with the same error name.
"""
import hashlib
import math
import zlib
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import _spec
from ._spec import LIMITS, MANIFEST, ReadError, REL_TOL, SET_MEMBERS, UNIT_KEYS, FRAME_TOL

NODE_DTYPE = np.dtype([("id", "<u8"), ("xyz", "<f8", (3,)), ("interface", "u1")])  # 33 bytes
LABELS = np.array(_spec.LABELS)


class _Cursor:
    """A position in one entry's bytes; every count is checked against the bytes left before a
    view is made (SPEC §7.2)."""

    def __init__(self, entry, data):
        self.entry, self.data, self.pos = entry, data, 0
        self.dec = _spec.Decoder(entry, data)

    def fail(self, msg):
        raise ReadError("Decode", f"{self.entry}: cannot decode ({msg})")

    def u64(self):
        if len(self.data) - self.pos < 8:
            self.fail("record ends early")
        v = int.from_bytes(self.data[self.pos:self.pos + 8], "little")
        self.pos += 8
        return v

    def array(self, dtype, count, shape=None):
        dtype = np.dtype(dtype)
        if count * dtype.itemsize > len(self.data) - self.pos:
            self.fail("record ends early: count exceeds the entry")
        a = np.frombuffer(self.data, dtype=dtype, count=count, offset=self.pos)
        a.flags.writeable = False  # a view of the payload (a bytearray or the file's bytes)
        self.pos += count * dtype.itemsize
        return a if shape is None else a.reshape(shape)

    def vec(self, dtype, per=1):
        n = self.u64()
        a = self.array(dtype, n * per)
        return a if per == 1 else a.reshape(n, per)

    def bools(self, count):
        a = self.array("u1", count)
        if (a > 1).any():
            self.fail(f"bool byte {int(a[a > 1][0])}")
        return a.astype(bool)

    def end(self):
        if self.pos != len(self.data):
            raise ReadError("TrailingBytes", f"{self.entry}: {len(self.data) - self.pos} trailing bytes")


def _faces(c):
    """Vec<Face>: u32 tag (0 Tri, 1 Quad) then 3 or 4 u32. Face boundaries without a per-face
    loop: all triangles or all quads are recognised at once; a mixed list by pointer doubling
    over "the next face would start at word p + 4 + tag(p)" from word 0."""
    n = c.u64()
    if n * 16 > len(c.data) - c.pos:
        c.fail("record ends early: count exceeds the entry")
    w = (len(c.data) - c.pos) // 4
    words = np.frombuffer(c.data, dtype="<u4", count=w, offset=c.pos)
    if n == 0:
        return np.zeros((0, 4), dtype=np.int64), np.zeros(0, dtype=bool)
    starts = None
    for k, tag in ((4, 0), (5, 1)):
        if n * k <= w and (words[: n * k : k] == tag).all():
            starts, end = np.arange(n, dtype=np.int64) * k, n * k
            break
    if starts is None:
        t = words.astype(np.int64)
        nxt = np.full(w + 2, w + 1, dtype=np.int64)  # w: the end; w + 1: broken (absorbing)
        step = np.arange(w, dtype=np.int64) + 4 + t
        nxt[:w] = np.where((t <= 1) & (step <= w), step, w + 1)
        pos, jump = np.zeros(1, dtype=np.int64), nxt
        while len(pos) < n + 1:
            pos = np.concatenate([pos, jump[pos]])
            jump = jump[jump]
        pos = pos[: n + 1]
        if pos[n] > w:
            bad = words[pos[pos < w]]
            if (bad > 1).any():
                c.fail(f"unknown enum tag {int(bad[bad > 1][0])}")
            c.fail("record ends early")
        starts, end = pos[:n], int(pos[n])
    tags = words[starts]
    quad = tags == 1
    idx = np.minimum(starts[:, None] + 1 + np.arange(4), w - 1)
    faces = words[idx].astype(np.int64)
    faces[~quad, 3] = -1
    c.pos += 4 * end
    return faces, quad


def _decode(name, data):
    c = _Cursor(name, data)
    if name == "nodes.bin":
        out = c.vec(NODE_DTYPE)
        if (out["interface"] > 1).any():
            c.fail("bool byte")
    elif name == "faces.bin":
        out = _faces(c)
    elif name == "nodal_mass.bin":
        out = c.vec("<f8", 10)
    elif name == "modes.bin":
        out = dict(omega2=c.vec("<f8"), frequency_hz=c.vec("<f8"), labels=c.vec("<u4"),
                   generalized_mass=c.vec("<f8"), generalized_stiffness=c.vec("<f8"),
                   shapes=c.vec("<f8"))
        if (out["labels"] >= len(LABELS)).any():
            c.fail(f"unknown enum tag {int(out['labels'].max())}")
    elif name == "invariants.bin":
        out = dict(mask=c.bools(9), i=[c.vec("<f8") for _ in range(9)])
    elif name in ("stress_shapes.bin", "strain_shapes.bin", "stress_shapes_bottom.bin",
                  "strain_shapes_bottom.bin"):
        out = dict(nodes=c.vec("<u4"), values=c.vec("<f8"))
    elif name == "damping.bin":
        out = c.vec("<f8")
    elif name == "lines.bin":
        out = c.vec("<u4", 2)
    else:  # label_shares.bin
        out = c.vec("<f8")
    c.end()
    return out


def read_container(data):
    """SPEC §7.1 steps 1–6: the reference reader opens the container and checks the manifest
    (`open_container`); the listed entries are then inflated and hashed here, in parallel
    threads: (manifest, {entry name: bytes})."""
    entries, m = _spec.open_container(data)

    def entry(e):
        # Returns the bytes or the ReadError the reference would raise for this entry.
        try:
            z = entries[e["name"]]
            b, sha = _inflate(data, z, e["size"]) or (None, None)
            if b is None:  # anything irregular: the reference's own code and errors
                b = _spec.read_entry(data, z, e["size"])
                sha = hashlib.sha256(b).hexdigest()
            if sha != e["sha256"]:
                raise ReadError("Checksum", f"{e['name']}: SHA-256 differs from the manifest")
            return b
        except ReadError as err:
            return err

    # zlib and hashlib release the GIL on large buffers: the entries inflate and hash in
    # parallel; errors are raised below in the manifest's order, as the reference raises them.
    with ThreadPoolExecutor(max_workers=min(4, max(1, len(m["entries"])))) as pool:
        done = list(pool.map(entry, m["entries"]))
    blobs = {}
    for e, b in zip(m["entries"], done):
        if isinstance(b, ReadError):
            raise b
        blobs[e["name"]] = b
    return m, blobs


def _inflate(data, z, declared):
    """(bytes, SHA-256 hex) of entry z straight from the container, or None when anything is
    irregular — then the caller reads it with the reference's code, which raises the reference's
    error. Only a regular entry takes this path: sizes as declared, no encryption or patch
    flags, stored or deflated, its data found through its local header (`_spec.entry_data`),
    and an inflated stream that ends exactly at the declared size with the directory's CRC-32.
    A large entry inflates chunk by chunk into one buffer while another thread hashes the
    chunks already inflated (zlib and hashlib release the GIL); a large stored one is checked in
    place (`_check_stored`)."""
    if z.size != declared or z.flags & 0x61 or z.method not in (0, 8):
        return None
    try:
        raw = _spec.entry_data(data, z)
    except ReadError:
        return None
    try:
        if z.method == 0:
            if declared > _CHUNK and z.name in _NUMPY_DECODED:
                return _check_stored(raw, z.crc, declared)
            out = bytes(raw)
        elif declared <= _CHUNK:
            d = zlib.decompressobj(-15)
            out = d.decompress(raw, declared + 1)
            if not d.eof or d.unconsumed_tail:
                return None
        else:
            return _inflate_hashing(raw, z.crc, declared)
    except zlib.error:
        return None
    if len(out) != declared or zlib.crc32(out) != z.crc:
        return None
    return out, hashlib.sha256(out).hexdigest()


_CHUNK = 1 << 22
# Entries `_decode` reads with numpy (a memoryview does as well as bytes there).
_NUMPY_DECODED = frozenset((
    "nodes.bin", "faces.bin", "nodal_mass.bin", "modes.bin", "invariants.bin", "stress_shapes.bin",
    "strain_shapes.bin", "stress_shapes_bottom.bin", "strain_shapes_bottom.bin", "damping.bin",
    "lines.bin", "label_shares.bin"))


def _check_stored(raw, crc_expected, declared):
    """Large stored entry: not copied (the blob is a read-only view of the container's
    bytes); its CRC-32 is taken in a second thread while this one takes SHA-256."""
    if len(raw) != declared:
        return None
    with ThreadPoolExecutor(max_workers=1) as crc_thread:
        crc = crc_thread.submit(zlib.crc32, raw)
        sha = hashlib.sha256(raw).hexdigest()
        if crc.result() != crc_expected:
            return None
    return raw, sha


def _inflate_hashing(raw, crc_expected, declared):
    """Large deflated entry: inflate `raw` in input chunks into a buffer of `declared` bytes;
    a second thread takes SHA-256 and CRC-32 of each finished piece in order. The output is
    capped at the declared size + 1 (a longer stream is irregular)."""
    buf = bytearray(declared)
    out = memoryview(buf)
    sha = hashlib.sha256()
    crc = [0]

    def digest(piece):
        sha.update(piece)
        crc[0] = zlib.crc32(piece, crc[0])

    d = zlib.decompressobj(-15)
    pos = 0
    with ThreadPoolExecutor(max_workers=1) as hasher:
        for i in range(0, len(raw), _CHUNK):
            piece = d.decompress(raw[i:i + _CHUNK], declared + 1 - pos)
            if d.unconsumed_tail or pos + len(piece) > declared:
                return None
            out[pos:pos + len(piece)] = piece
            hasher.submit(digest, out[pos:pos + len(piece)])
            pos += len(piece)
            if d.eof:
                break
    if not d.eof or pos != declared or crc[0] != crc_expected:
        return None
    return buf, sha.hexdigest()


def decode_all(m, blobs):
    """SPEC §7.1 step 7: decode every known entry in container order (views into `blobs`)."""
    return {name: (_decode(name, blobs[name]) if name in _NUMPY_DECODED else _spec.decode(name, blobs[name]))
            for name, _, _ in _spec.ENTRIES if name in blobs}


def _err(variant, entry, msg):
    raise ReadError(variant, f"{entry}: {msg}")


def _count(entry, field, found, expected):
    if found != expected:
        _err("CountMismatch", entry, f"{field} has length {found}, expected {expected}")


def _finite(entry, field, a):
    a = np.asarray(a, dtype=float).ravel()
    bad = ~np.isfinite(a)
    if bad.any():
        _err("NonFinite", entry, f"{field}[{int(np.argmax(bad))}] is not finite")


def _symmetric(entry, field, a, n):
    a = np.asarray(a, dtype=float).reshape(n, n)
    scale = float(np.abs(a).max()) if a.size else 0.0
    if (np.abs(a - a.T) > REL_TOL * scale).any():
        _err("NotSymmetric", entry, f"{field} not symmetric")


def _index(entry, field, v, n):
    v = np.asarray(v)
    if v.size and (v >= n).any():
        _err("IndexOutOfRange", entry, f"{field} node index {int(v[v >= n][0])} out of range (N = {n})")


class _NodeAt:
    """nodes[i] as the reference's dict, for its per-interface rules (few lookups)."""

    def __init__(self, nodes):
        self.nodes = nodes

    def __getitem__(self, i):
        x = self.nodes[int(i)]
        return dict(id=int(x["id"]), xyz=[float(v) for v in x["xyz"]], interface=bool(x["interface"]))


def validate(b, m):
    """SPEC §6 in the reference's order, vectorized over the large arrays."""
    nodes, (faces, quad), modes = b["nodes.bin"], b["faces.bin"], b["modes.bin"]
    n, nm = len(nodes), len(modes["omega2"])
    if n > LIMITS["max_nodes"]:
        _err("LimitExceeded", "nodes.bin", "node count")
    if len(faces) > LIMITS["max_faces"]:
        _err("LimitExceeded", "faces.bin", "face count")
    if nm > LIMITS["max_modes"]:
        _err("LimitExceeded", "modes.bin", "mode count")
    for k in UNIT_KEYS:
        u = m["units"][k]
        if not (math.isfinite(u["si"]) and u["si"] > 0):
            _err("Inconsistent", MANIFEST, f"units.{k}.si must be finite and > 0")
    req = b["header.bin"]["request"]
    if req["fmax_hz"] is not None and not (math.isfinite(req["fmax_hz"]) and req["fmax_hz"] > 0):
        _err("Inconsistent", "header.bin", "request.fmax_hz must be finite and > 0")
    # Rule 3 in node order: the first node with a non-finite coordinate or a repeated id.
    bad_xyz = ~np.isfinite(nodes["xyz"]).all(axis=1)
    ids = nodes["id"]
    order = np.argsort(ids, kind="stable")
    dup = np.zeros(n, dtype=bool)
    if n > 1:
        same = ids[order][1:] == ids[order][:-1]
        dup[order[1:][same]] = True
    first_bad = np.flatnonzero(bad_xyz | dup)
    if first_bad.size:
        p = int(first_bad[0])
        if bad_xyz[p]:
            _err("NonFinite", "nodes.bin", f"nodes[{p}].xyz is not finite")
        _err("Inconsistent", "nodes.bin", f"node id {int(ids[p])} occurs twice")
    _index("faces.bin", "faces", faces[faces >= 0], n)
    lines = b.get("lines.bin")
    if lines is not None:
        if len(lines) > LIMITS["max_faces"]:
            _err("LimitExceeded", "lines.bin", "line count")
        _index("lines.bin", "lines", lines.ravel(), n)
    masses = b["nodal_mass.bin"]
    _count("nodal_mass.bin", "nodal masses", len(masses), n)
    bad = ~np.isfinite(masses).all(axis=1)
    neg = masses[:, 0] < 0
    inertia = masses[:, 1:].reshape(-1, 3, 3)
    scale = np.abs(inertia).reshape(-1, 9).max(axis=1, initial=0.0)
    asym = (np.abs(inertia - inertia.transpose(0, 2, 1)) > REL_TOL * scale[:, None, None]).any(axis=(1, 2))
    first = np.flatnonzero(bad | neg | asym)
    if first.size:
        p = int(first[0])
        if bad[p]:
            _err("NonFinite", "nodal_mass.bin", f"nodal_mass[{p}] is not finite")
        if neg[p]:
            _err("Inconsistent", "nodal_mass.bin", f"nodal_mass[{p}].mass is negative")
        _err("NotSymmetric", "nodal_mass.bin", f"nodal_mass[{p}].inertia not symmetric")
    _count("modes.bin", "frequency_hz", len(modes["frequency_hz"]), nm)
    _count("modes.bin", "labels", len(modes["labels"]), nm)
    _count("modes.bin", "generalized_mass", len(modes["generalized_mass"]), nm * nm)
    _count("modes.bin", "generalized_stiffness", len(modes["generalized_stiffness"]), nm * nm)
    _count("modes.bin", "shapes", len(modes["shapes"]), nm * n * 6)
    for field in ["omega2", "frequency_hz", "generalized_mass", "generalized_stiffness", "shapes"]:
        _finite("modes.bin", field, modes[field])
    _symmetric("modes.bin", "generalized_mass", modes["generalized_mass"], nm)
    _symmetric("modes.bin", "generalized_stiffness", modes["generalized_stiffness"], nm)
    expect = np.sqrt(np.maximum(modes["omega2"], 0.0)) / (2.0 * math.pi)
    off = np.abs(modes["frequency_hz"] - expect) > REL_TOL * np.maximum(expect, 1.0)
    if off.any():
        _err("Inconsistent", "modes.bin", f"frequency_hz[{int(np.argmax(off))}] disagrees with omega2")
    inv = b["invariants.bin"]
    want = [k in SET_MEMBERS[req["invariant_set"]] for k in range(1, 10)]
    if list(inv["mask"]) != want:
        _err("Inconsistent", "invariants.bin", f"mask differs from the mask of header invariant_set {req['invariant_set']}")
    shapes = [1, 3, 3 * nm, 3 * nm, nm * 3 * nm, nm * nm, 9, nm * 9, nm * nm * 9]
    for k in range(9):
        _count("invariants.bin", f"i{k + 1}", len(inv["i"][k]), shapes[k] if want[k] else 0)
        _finite("invariants.bin", f"i{k + 1}", inv["i"][k])
    if want[5]:
        _symmetric("invariants.bin", "i6", inv["i"][5], nm)
    if want[6]:
        _symmetric("invariants.bin", "i7", inv["i"][6], 3)
    if want[0] and inv["i"][0][0] < 0:
        _err("Inconsistent", "invariants.bin", "i1 (total mass) is negative")
    me = b["method.bin"]
    if me["method"] != req["method"] or me["mass_kind"] != req["mass_kind"]:
        _err("Inconsistent", "method.bin", "method/mass kind differ from the header request")
    for q, itf in enumerate(me["interface"]):
        _index("method.bin", f"interface[{q}].node", [itf["node"]], n)
        if not nodes["interface"][itf["node"]]:
            _err("Inconsistent", "method.bin", f"interface[{q}] names a node whose interface flag is false")
        a = np.array(itf["frame"], dtype=float)
        _finite("method.bin", f"interface[{q}].frame", a)
        if (np.abs(a @ a.T - np.eye(3)) > FRAME_TOL).any():
            _err("Inconsistent", "method.bin", f"interface[{q}].frame is not orthonormal")
        det = (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
               + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
        if det <= 0:
            _err("Inconsistent", "method.bin", f"interface[{q}].frame is left-handed")
    for q, rc in enumerate(me["reference_conditions"]):
        _index("method.bin", f"reference_conditions[{q}].node", [rc["node"]], n)
    _finite("method.bin", "cutoffs", [c for c in me["cutoffs"] if c is not None])
    label_names = list(LABELS[modes["labels"]])
    _spec.counts_and_cutoffs(me, {**modes, "labels": label_names}, req, m["version"], _err)
    for entry in ["stress_shapes.bin", "strain_shapes.bin", "stress_shapes_bottom.bin",
                  "strain_shapes_bottom.bin"]:
        s = b.get(entry)
        if s is None:
            continue
        p = s["nodes"]
        out = np.flatnonzero(p >= n)
        desc = np.flatnonzero(np.diff(p.astype(np.int64)) <= 0) + 1
        if out.size and (not desc.size or out[0] <= desc[0]):
            _index(entry, "nodes", p[out[:1]], n)
        if desc.size:
            _err("Inconsistent", entry, "nodes must be strictly ascending")
        _count(entry, "values", len(s["values"]), nm * len(p) * 6)
        _finite(entry, "values", s["values"])
        if entry.endswith("_bottom.bin"):
            _spec.bottom_fibre_nodes(entry, p, b, _err)
    dmp = b.get("damping.bin")
    if dmp is not None:
        _count("damping.bin", "ratio", len(dmp), nm)
        _finite("damping.bin", "ratio", dmp)
        if (dmp < 0).any():
            _err("Inconsistent", "damping.bin", "negative ratio")
    sh = b.get("label_shares.bin")
    ml = b.get("modal_loads.bin")
    if sh is not None:
        _count("label_shares.bin", "shares", len(sh), nm)
        _finite("label_shares.bin", "shares", sh)
        if ((sh < 0) | (sh > 1)).any():
            _err("Inconsistent", "label_shares.bin", "share outside 0..1")
        if (m["version"]["major"], m["version"]["minor"]) < (1, 6):  # rule 11 before 1.6
            no_residual = ml is None or not any(ml["residual"])
        else:
            no_residual = ml is None or len(ml["residual"]) == 0
        single_stage = me["method"] == "NormalModes" and no_residual
        if ((sh != 1) & ((modes["labels"] == 0) | single_stage)).any():
            _err("Inconsistent", "label_shares.bin", "a share that must be 1 is not")
    if ml is not None:
        _spec.validate_modal_loads(ml, label_names, _err, _count, _finite_list)
    rc = b.get("recipe.json")
    if rc is not None:
        stored = [dict(id=int(i), interface=True) for i in ids[nodes["interface"] == 1]]
        others = {"nodes.bin": stored, "modes.bin": {"labels": label_names}, "method.bin": me}
        if "geometric_stiffness.bin" in b:
            others["geometric_stiffness.bin"] = b["geometric_stiffness.bin"]
        _spec.validate_recipe(rc, others, m, _err, _finite_list)
    itf = b.get("interfaces.bin")
    if itf is not None:
        _spec.validate_interfaces(itf, {"method.bin": me, "nodes.bin": _NodeAt(nodes)}, _err, _finite_list)
    gs = b.get("geometric_stiffness.bin")
    if gs is not None:
        _spec.validate_geometric_stiffness(gs, nm, {"modes.bin": {"labels": label_names}}, m["version"],
                                           _err, _count, _finite, _symmetric)
    er = b.get("eigen_residuals.bin")
    if er is not None:
        _spec.validate_eigen_residuals(er, nm, b, _err, _count, _finite_list)


def _finite_list(entry, field, values):
    _finite(entry, field, list(values))


def read_bytes(data):
    """(body dict of numpy arrays and small records, manifest dict), validated."""
    m, blobs = read_container(data)
    b = decode_all(m, blobs)
    validate(b, m)
    return b, m
