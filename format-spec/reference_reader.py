#!/usr/bin/env python3
"""Reference reader for flexbody reduced-body files, format v1 (1.0 … 1.9), written from SPEC.md alone.

Standard library only (zlib, json, hashlib, struct; the zip container is read by SPEC §7.1's
procedure here, not by zipfile). Usage:

    reference_reader.py FILE                 print the summary JSON of FILE
    reference_reader.py --check-fixtures DIR golden/compat files must match their .json
                                             summaries, broken files must be refused with the
                                             error name of their .expect; exit 1 otherwise
"""
import hashlib
import json
import math
import re
import struct
import sys
import zlib
from pathlib import Path

FORMAT_NAME = "flexbody-reduced-body"
SUPPORTED_MAJOR = 1
MANIFEST = "manifest.json"
ENTRIES = [  # SPEC §2: name, required, the minor version that introduced it
    ("header.bin", True, 0), ("nodes.bin", True, 0), ("faces.bin", True, 0), ("nodal_mass.bin", True, 0),
    ("modes.bin", True, 0), ("invariants.bin", True, 0), ("method.bin", True, 0),
    ("stress_shapes.bin", False, 0), ("strain_shapes.bin", False, 0), ("damping.bin", False, 0),
    ("lines.bin", False, 1), ("recipe.json", False, 2), ("label_shares.bin", False, 2),
    ("interfaces.bin", False, 3), ("modal_loads.bin", False, 4),
    ("stress_shapes_bottom.bin", False, 5), ("strain_shapes_bottom.bin", False, 5),
    ("geometric_stiffness.bin", False, 7), ("eigen_residuals.bin", False, 9),
]
KNOWN = {name: (req, minor) for name, req, minor in ENTRIES}
LIMITS = dict(max_entry_bytes=2 << 30, max_total_bytes=8 << 30, max_manifest_bytes=1 << 20,
              max_entries=64, max_nodes=10_000_000, max_faces=50_000_000, max_modes=100_000,
              max_expansion=64, max_expansion_floor=64 << 20)
STRING_LIMIT = 16 << 20
JSON_DEPTH = 64
REL_TOL, FRAME_TOL = 1e-9, 1e-6
UNIT_KEYS = ["mass", "length", "time", "force"]

METHOD = ["NormalModes", "CraigBampton", "CraigChang", "Dietz"]
MASS_KIND = ["Lumped", "Consistent"]
INVARIANT_SET = ["Full", "Partial", "Constant", "Rigid"]
SET_MEMBERS = {"Full": range(1, 10), "Partial": [1, 2, 3, 4, 6, 7, 8], "Constant": [1, 2, 6, 7],
               "Rigid": [1, 2, 7]}
INTERFACE_KIND = ["Node", "Rbe2", "Rbe3"]
FIT_METHOD = ["CylinderFit", "FaceAreaCentroid", "NodeAverage"]
FIT_TOL = 1e-9
LABELS = ["Rigid", "Normal", "Constraint", "FixedInterface", "Attachment", "FrequencyResponse"]
STATIC_SUPPORT = ["Held", "InertiaRelief"]
UNIT_LOAD = ["Acceleration", "AngularVelocity", "AngularAcceleration"]
EIGEN_PROBLEM = ["NormalModes", "FixedInterface", "FreeFree"]
EIGEN_SOLVER = ["Lanczos", "Amls", "Dense", "Slepc"]
RIGID_FRACTION = 1e-8


class ReadError(Exception):
    """A refused file: `variant` is the SPEC §8 error name."""

    def __init__(self, variant, message):
        super().__init__(f"{variant}: {message}")
        self.variant = variant


class Decoder:
    """SPEC §4: little-endian, fixed-width integers, u64 lengths, u32 enum tags."""

    def __init__(self, entry, data):
        self.entry, self.data, self.pos = entry, data, 0

    def fail(self, msg):
        raise ReadError("Decode", f"{self.entry}: cannot decode ({msg})")

    def take(self, n):
        if n > len(self.data) - self.pos:
            self.fail("record ends early")
        b = self.data[self.pos:self.pos + n]
        self.pos += n
        return b

    def u8(self):
        return self.take(1)[0]

    def u32(self):
        return struct.unpack("<I", self.take(4))[0]

    def u64(self):
        return struct.unpack("<Q", self.take(8))[0]

    def f64(self):
        return struct.unpack("<d", self.take(8))[0]

    def bool(self):
        b = self.u8()
        if b > 1:
            self.fail(f"bool byte {b}")
        return b == 1

    def string(self):
        n = self.u64()
        if n > STRING_LIMIT:
            self.fail("string longer than 16 MiB")
        try:
            return self.take(n).decode("utf-8")
        except UnicodeDecodeError:
            self.fail("string is not UTF-8")

    def option(self, read):
        tag = self.u8()
        if tag > 1:
            self.fail(f"option tag {tag}")
        return read() if tag == 1 else None

    def tag(self, names):
        t = self.u32()
        if t >= len(names):
            self.fail(f"unknown enum tag {t}")
        return t

    def vec(self, read, min_size):
        n = self.u64()
        # Check the count against the bytes left before building anything (SPEC §7.2).
        if n * min_size > len(self.data) - self.pos:
            self.fail("record ends early: count exceeds the entry")
        return [read() for _ in range(n)]

    def f64s(self):
        n = self.u64()
        if n * 8 > len(self.data) - self.pos:
            self.fail("record ends early: count exceeds the entry")
        return list(struct.unpack(f"<{n}d", self.take(8 * n)))

    def arr(self, read, k):
        return [read() for _ in range(k)]

    def end(self):
        if self.pos != len(self.data):
            raise ReadError("TrailingBytes", f"{self.entry}: {len(self.data) - self.pos} trailing bytes")


def decode_header(d):
    if len(d.data) > STRING_LIMIT:
        d.fail("header.bin exceeds the 16 MiB record limit")
    title, created = d.string(), d.option(d.string)
    method, fmax, count = METHOD[d.tag(METHOD)], d.option(d.f64), d.option(d.u64)
    kt = d.tag(["All", "InterfaceAndSurface", "List"])
    keep = ["All", "InterfaceAndSurface", None][kt] or {"List": d.vec(d.u64, 8)}
    iset, mk = INVARIANT_SET[d.tag(INVARIANT_SET)], MASS_KIND[d.tag(MASS_KIND)]
    return dict(title=title, created_utc=created, request=dict(
        method=method, fmax_hz=fmax, mode_count=count, keep_nodes=keep, invariant_set=iset, mass_kind=mk))


def decode_nodes(d):
    return d.vec(lambda: dict(id=d.u64(), xyz=d.arr(d.f64, 3), interface=d.bool()), 33)


def decode_faces(d):
    def face():
        k = [3, 4][d.tag(["Tri", "Quad"])]
        return d.arr(d.u32, k)
    return d.vec(face, 16)


def decode_nodal_mass(d):
    return d.vec(lambda: dict(mass=d.f64(), inertia=[d.arr(d.f64, 3) for _ in range(3)]), 80)


def decode_modes(d):
    return dict(omega2=d.f64s(), frequency_hz=d.f64s(), labels=d.vec(lambda: LABELS[d.tag(LABELS)], 4),
                generalized_mass=d.f64s(), generalized_stiffness=d.f64s(), shapes=d.f64s())


def decode_invariants(d):
    mask = d.arr(d.bool, 9)
    return dict(mask=mask, i=[d.f64s() for _ in range(9)])


def decode_method(d):
    method, mk = METHOD[d.tag(METHOD)], MASS_KIND[d.tag(MASS_KIND)]
    itf = d.vec(lambda: dict(node=d.u32(), dofs=d.arr(d.bool, 6), frame=[d.arr(d.f64, 3) for _ in range(3)]), 82)
    rc = d.vec(lambda: dict(node=d.u32(), dofs=d.arr(d.bool, 6)), 10)
    counts = d.arr(d.u64, 6)
    cutoffs = d.arr(lambda: d.option(d.f64), 3)
    return dict(method=method, mass_kind=mk, interface=itf, reference_conditions=rc, counts=counts, cutoffs=cutoffs)


def decode_field(d):
    return dict(nodes=d.vec(d.u32, 4), values=d.f64s())


def decode_damping(d):
    return dict(ratio=d.f64s())


def decode_lines(d):
    return d.vec(lambda: d.arr(d.u32, 2), 8)


def decode_interfaces(d):
    """SPEC §5.13: Vec<InterfaceInfo>; a record with strings, at most 16 MiB like header.bin."""
    if len(d.data) > STRING_LIMIT:
        d.fail("interfaces.bin exceeds the 16 MiB record limit")

    def fit():
        return dict(method=FIT_METHOD[d.tag(FIT_METHOD)], centre=d.arr(d.f64, 3),
                    axis=d.option(lambda: d.arr(d.f64, 3)), radius=d.option(d.f64),
                    offset_from_node_average=d.f64())

    def one():
        return dict(node=d.u32(), name=d.string(), kind=INTERFACE_KIND[d.tag(INTERFACE_KIND)],
                    dependent=d.vec(d.u64, 8), fit=d.option(fit))
    return d.vec(one, 25)


def decode_modal_loads(d):
    """SPEC §5.14: ModalLoads { loads: Vec<ModalLoad { name, source, values }>, residual: Vec<u8> }."""
    if len(d.data) > STRING_LIMIT:
        d.fail("modal_loads.bin exceeds the 16 MiB record limit")
    loads = d.vec(lambda: dict(name=d.string(), source=d.string(), values=d.f64s()), 24)
    return dict(loads=loads, residual=d.vec(d.u8, 1))


def decode_geometric_stiffness(d):
    """SPEC §5.16: GeometricStiffness { support, fields: Vec<GeometricField { load, matrix }> };
    a load is [kind, axes] with one axis, or two for AngularVelocity."""
    support = STATIC_SUPPORT[d.tag(STATIC_SUPPORT)]

    def field():
        kind = UNIT_LOAD[d.tag(UNIT_LOAD)]
        axes = d.arr(d.u8, 2 if kind == "AngularVelocity" else 1)
        return dict(load=[kind, axes], matrix=d.f64s())
    return dict(support=support, fields=d.vec(field, 13))


def decode_eigen_residuals(d):
    """SPEC §5.17: EigenResiduals { problems: Vec<EigenProblem { kind, solver, scale, omega2,
    residual, inertia: Option<InertiaCount { shift, below }> }> }."""
    def problem():
        kind = EIGEN_PROBLEM[d.tag(EIGEN_PROBLEM)]
        solver = EIGEN_SOLVER[d.tag(EIGEN_SOLVER)]
        scale, omega2, residual = d.f64(), d.f64s(), d.f64s()
        inertia = d.option(lambda: dict(shift=d.f64(), below=d.u64()))
        return dict(kind=kind, solver=solver, scale=scale, omega2=omega2, residual=residual,
                    inertia=inertia)
    return dict(problems=d.vec(problem, 33))


def unit_load_name(load):
    """SPEC §5.16's name of a load: a_x, omega_x*omega_y, alpha_z."""
    kind, axes = load
    ax = ["x", "y", "z"]
    if kind == "Acceleration":
        return f"a_{ax[axes[0]]}"
    if kind == "AngularVelocity":
        return f"omega_{ax[axes[0]]}*omega_{ax[axes[1]]}"
    return f"alpha_{ax[axes[0]]}"


DECODERS = {"header.bin": decode_header, "nodes.bin": decode_nodes, "faces.bin": decode_faces,
            "nodal_mass.bin": decode_nodal_mass, "modes.bin": decode_modes,
            "invariants.bin": decode_invariants, "method.bin": decode_method,
            "stress_shapes.bin": decode_field, "strain_shapes.bin": decode_field,
            "damping.bin": decode_damping, "lines.bin": decode_lines,
            "label_shares.bin": lambda d: d.f64s(), "interfaces.bin": decode_interfaces,
            "modal_loads.bin": decode_modal_loads,
            "stress_shapes_bottom.bin": decode_field, "strain_shapes_bottom.bin": decode_field,
            "geometric_stiffness.bin": decode_geometric_stiffness,
            "eigen_residuals.bin": decode_eigen_residuals}


# SPEC §5.11: recipe.json member types. ("opt", T) may be null or absent; ("omit", T) may be
# absent (then left out of the summary), present it is a T (null is not); ("list", T); a dict
# is an object with those members (unknown members ignored); ("arr", T, k) a fixed-length array.
U64, U8, F64, STR = ("uint", 64), ("uint", 8), "number", "string"
UNITS_T = {k: {"name": STR, "si": F64} for k in UNIT_KEYS}
RECIPE_T = {
    "tool": {"name": STR, "version": STR},
    "model_files": ("list", {"path": STR, "role": STR, "size": U64, "sha256": STR}),
    "options": {"format": ("opt", STR), "material": ("opt", STR), "method": STR, "modes": ("opt", U64),
                "fmax_hz": ("opt", F64), "mass": STR, "beam_mass": STR, "units": UNITS_T,
                "interface": ("list", STR), "spider": STR, "reference_conditions": ("list", STR),
                "reference_method": U8, "keep_nodes": STR, "invariants": STR, "stress_fields": STR,
                "damping": ("opt", STR), "thickness": ("omit", F64), "subcase": ("omit", U64),
                "gravity": ("omit", STR), "loads": ("omit", ("list", STR)), "residual_vectors": ("omit", STR),
                "select": ("omit", STR), "preload": ("omit", ("list", STR)),
                "ignore": ("omit", ("list", STR)), "geometric_stiffness": ("omit", STR),
                "inp_shells": ("omit", STR), "eigensolver": ("omit", STR)},
    "interfaces": ("list", {"entry": STR, "nodes": ("list", U64), "spider": ("opt", {
        "kind": STR, "centre_node": U64, "centre": ("arr", F64, 3), "fit": STR,
        "offset_from_node_average": F64, "set_nodes": ("list", U64)})}),
    "accuracy_band": {"fmax_hz": F64, "rule": STR, "basis_cutoff_hz": ("opt", F64)},
    "preload": ("omit", {"source": STR, "loads": ("list", STR), "max_displacement": F64,
                         "max_displacement_node": U64, "buckling_factor": ("opt", F64)}),
}
RECIPE_KEYS = list(RECIPE_T)  # member order of the summary


def typed(v, t, at):
    """Checks v against the type t of RECIPE_T; returns v with unknown members dropped."""
    def bad(what):
        raise ReadError("Decode", f"recipe.json: cannot decode (not a valid recipe: {at} must be {what})")
    if isinstance(t, dict):
        if not isinstance(v, dict):
            bad("an object")
        out = {}
        for k, tk in t.items():
            if isinstance(tk, tuple) and tk[0] == "omit":  # absent (or an empty list): left out
                if k in v:
                    val = typed(v[k], tk[1], f"{at}.{k}")
                    if not (isinstance(tk[1], tuple) and tk[1][0] == "list" and val == []):
                        out[k] = val
                continue
            if k not in v and not (isinstance(tk, tuple) and tk[0] == "opt"):
                bad(f"an object with member {k}")
            out[k] = typed(v.get(k), tk, f"{at}.{k}")
        return out
    if t == STR:
        if not isinstance(v, str):
            bad("a string")
        return v
    if t == F64:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            bad("a number")
        return float(v)
    if t[0] == "uint":
        if isinstance(v, bool) or not isinstance(v, int) or not 0 <= v < 1 << t[1]:
            bad(f"an integer in 0..2^{t[1]}-1")
        return v
    if t[0] == "opt":
        return None if v is None else typed(v, t[1], at)
    if t[0] == "list" or t[0] == "arr":
        if not isinstance(v, list) or (t[0] == "arr" and len(v) != t[2]):
            bad("an array" if t[0] == "list" else f"an array of {t[2]}")
        return [typed(x, t[1], f"{at}[{i}]") for i, x in enumerate(v)]
    raise AssertionError(t)


# A string (to its closing quote, or to the end of a text that never closes it: every match
# succeeds, so the scan is linear whatever the text) or a bracket outside strings.
_JSON_TOKENS = re.compile(r'"(?:[^"\\]|\\.|\\\Z)*(?:"|\Z)|([][{}])', re.DOTALL)


def load_json(text):
    """SPEC §4.1: strict JSON. At most JSON_DEPTH nested arrays and objects, no member name twice
    in an object, no lone surrogate; integers (no fraction, no exponent) exact, other numbers the
    nearest binary64 (1e999 → inf). Raises ValueError."""
    depth = 0
    for m in _JSON_TOKENS.finditer(text):
        depth += {None: 0, "[": 1, "{": 1, "]": -1, "}": -1}[m.group(1)]
        if depth > JSON_DEPTH:
            raise ValueError(f"arrays and objects nested deeper than {JSON_DEPTH}")

    def no_constants(c):  # JSON has no NaN/Infinity; Python's json would accept them
        raise ValueError(f"{c} is not JSON")

    def unique(pairs):
        out = {}
        for k, v in pairs:
            if k in out:
                raise ValueError(f"member {k!r} occurs twice")
            out[k] = v
        return out

    def no_lone_surrogate(v):
        for x in (v.items() if isinstance(v, dict) else v if isinstance(v, list) else [v]):
            for y in (x if isinstance(x, tuple) else (x,)):
                if isinstance(y, str):
                    y.encode("utf-8")  # UnicodeEncodeError (a ValueError) on a lone surrogate
                elif isinstance(y, (list, dict)):
                    no_lone_surrogate(y)
    # Integers of more than 40 digits are beyond every integer member (u64): read them as the
    # number they are (float() is exact-rounding; int() refuses more than 4300 digits).
    v = json.loads(text, parse_constant=no_constants, object_pairs_hook=unique,
                   parse_int=lambda t: int(t) if len(t) <= 40 else float(t))
    no_lone_surrogate(v)
    return v


def decode_recipe(data):
    """SPEC §5.11: UTF-8 JSON, at most 16 MiB, members of RECIPE_T (unknown ones ignored)."""
    def fail(msg):
        raise ReadError("Decode", f"recipe.json: cannot decode ({msg})")
    if len(data) > STRING_LIMIT:
        fail("exceeds the 16 MiB record limit")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        fail(f"not UTF-8: {e}")
    try:
        v = load_json(text)
    except ValueError as e:
        fail(f"not JSON: {e}")
    return typed(v, RECIPE_T, "recipe")


class ZipEntry:
    """One central-directory record (SPEC §7.1 step 1); `local` is the local header's offset in
    the file (the archive offset added)."""
    __slots__ = ("name", "flags", "method", "crc", "csize", "size", "local")

    def __init__(self, name, flags, method, crc, csize, size, local):
        self.name, self.flags, self.method, self.crc = name, flags, method, crc
        self.csize, self.size, self.local = csize, size, local


def le(data, at, n):
    """The little-endian unsigned integer of n bytes at `at`, or None past the end."""
    return int.from_bytes(data[at:at + n], "little") if 0 <= at and at + n <= len(data) else None


def zip64_values(extra, wanted):
    """The first `wanted` 8-byte values of the Zip64 extra field (id 1), or None."""
    k = 0
    while k < len(extra):
        if k + 4 > len(extra):
            return None
        xid, xlen = struct.unpack("<2H", extra[k:k + 4])
        if k + 4 + xlen > len(extra):
            return None
        if xid == 1:
            values = [le(extra[k + 4:k + 4 + xlen], 8 * j, 8) for j in range(wanted)]
            return None if None in values else values
        k += 4 + xlen
    return None


def open_archive(data):
    """SPEC §7.1 step 1: {name: ZipEntry} in central-directory order."""
    def not_zip(msg):
        raise ReadError("NotZip", f"not a zip container ({msg})")
    n = len(data)
    lo = max(n - 22 - 65535, 0)
    e = data.rfind(b"PK\x05\x06", lo, n - 18) if n >= 22 else -1
    while e >= 0 and le(data, e + 20, 2) != n - e - 22:  # the record must end the file
        e = data.rfind(b"PK\x05\x06", lo, e + 3)
    if e < 0:
        not_zip("no end-of-central-directory record ends the file")
    disk, cd_disk, here, count, size, offset = struct.unpack("<4H2I", data[e + 4:e + 20])
    end = e
    if e < 20 or data[e - 20:e - 16] != b"PK\x06\x07":
        if disk or cd_disk or here != count:
            not_zip("a multi-disk archive (no meaning in v1)")
    else:  # a Zip64 locator: the Zip64 end record before it gives the values
        r = e - 76
        if r < 0 or data[r:r + 4] != b"PK\x06\x06" or le(data, r + 4, 8) != 44:
            not_zip("damaged Zip64 end-of-central-directory record or locator")
        if le(data, e - 16, 4) or le(data, e - 4, 4) > 1 or le(data, r + 16, 4) or le(data, r + 20, 4) \
                or le(data, r + 24, 8) != le(data, r + 32, 8):
            not_zip("a multi-disk archive (no meaning in v1)")
        count, size, offset, end = le(data, r + 32, 8), le(data, r + 40, 8), le(data, r + 48, 8), r
    start = end - size
    if start < offset:
        not_zip("the central directory does not fit before its end record")
    if count > LIMITS["max_entries"] + 1:
        raise ReadError("LimitExceeded", "zip entry count")
    entries, at = {}, start
    for i in range(count):
        head = data[at:at + 46]
        if len(head) != 46 or head[:4] != b"PK\x01\x02":
            not_zip(f"damaged central directory header #{i}")
        flags, method, _, _, crc, csize, usize, nn, nx, nc = struct.unpack("<4H3I3H", head[8:34])
        local = le(head, 42, 4)
        name, extra = data[at + 46:at + 46 + nn], data[at + 46 + nn:at + 46 + nn + nx]
        if at + 46 + nn + nx + nc > n:
            not_zip(f"damaged central directory header #{i}")
        if at + 46 + nn + nx + nc > end:  # inside the directory, not only the file
            not_zip(f"central directory header #{i} runs past the end of the directory")
        sentinels = [v == 0xFFFFFFFF for v in (usize, csize, local)]
        if any(sentinels):  # the Zip64 extra field (id 1) holds those values, 8 bytes each
            values = zip64_values(extra, sum(sentinels))
            if values is None:
                not_zip(f"damaged central directory header #{i}")
            it = iter(values)
            usize, csize, local = [next(it) if big else v for v, big in zip((usize, csize, local), sentinels)]
        try:
            name = name.decode("utf-8")
        except UnicodeDecodeError:
            not_zip(f"entry #{i} has a name that is not UTF-8")
        entries.setdefault(name, []).append(ZipEntry(name, flags, method, crc, csize, usize, local + start - offset))
        at += 46 + nn + nx + nc
    for name, same in entries.items():
        if len(same) > 1:
            raise ReadError("DuplicateEntry", f"{name}: occurs more than once")
    return {name: same[0] for name, same in entries.items()}


def entry_data(data, z):
    """The stored or deflated bytes of entry z, found through its local header (SPEC §7.1 step 6)."""
    sig, nn, nx = data[z.local:z.local + 4], le(data, z.local + 26, 2), le(data, z.local + 28, 2)
    if sig != b"PK\x03\x04" or nn is None or nx is None:
        raise ReadError("Container", f"{z.name}: damaged zip data (no local header where the directory points)")
    if data[z.local + 30:z.local + 30 + nn] != z.name.encode("utf-8"):
        raise ReadError("Container", f"{z.name}: damaged zip data (the local header names another entry)")
    start = z.local + 30 + nn + nx
    if start + z.csize > len(data):
        raise ReadError("Container", f"{z.name}: damaged zip data (its data runs past the end of the file)")
    return memoryview(data)[start:start + z.csize]


def read_entry(data, z, declared):
    """SPEC §7.1 step 6 (step 2 for the manifest, `declared` its directory size): the bytes of z."""
    if z.flags & 0x61:  # bits 0 and 6: encryption; bit 5: patched data
        raise ReadError("Container", f"{z.name}: damaged zip data (encrypted or patched data has no meaning in v1)")
    if z.method not in (0, 8):
        raise ReadError("Compression", f"{z.name}: compression method {z.method} not supported")
    if z.size != declared:  # checked before inflating anything (a bomb's directory lies)
        raise ReadError("SizeMismatch", f"{z.name}: size {z.size} differs from the manifest's {declared}")
    raw = entry_data(data, z)
    if z.method == 0:
        out = bytes(raw[:declared + 1])
    else:  # inflate at most one byte beyond the declared size
        d = zlib.decompressobj(-15)
        try:
            out = d.decompress(raw, declared + 1)
        except zlib.error as e:
            raise ReadError("Container", f"{z.name}: damaged zip data (invalid deflate data: {e})")
        if len(out) <= declared and not d.eof:
            raise ReadError("Container", f"{z.name}: damaged zip data (the deflate data ends before its stream does)")
    if len(out) != declared:
        raise ReadError("SizeMismatch", f"{z.name}: size {len(out)} differs from the manifest's {declared}")
    if zlib.crc32(out) != z.crc:
        raise ReadError("Container", f"{z.name}: damaged zip data (CRC-32 differs from the directory's)")
    return out


def parse_manifest(text):
    def exact(obj, keys, what):
        # Members must be present; unknown members are ignored (a newer minor may add some).
        if not isinstance(obj, dict) or not set(keys) <= set(obj):
            raise ReadError("Manifest", f"{what} must have the members {sorted(keys)}")
        return obj

    def uint(v, what, bits):
        if not isinstance(v, int) or isinstance(v, bool) or not 0 <= v < 1 << bits:
            raise ReadError("Manifest", f"{what} must be an integer in 0..2^{bits}-1")
        return v

    def text_(v, what):
        if not isinstance(v, str):
            raise ReadError("Manifest", f"{what} must be a string")
        return v

    try:
        m = load_json(text)
    except ValueError as e:
        raise ReadError("Manifest", f"not valid manifest JSON: {e}")
    # SPEC §7.1 step 3: format and version first, before the other members (a newer major
    # version may change them).
    if isinstance(m, dict):
        f, v = m.get("format"), m.get("version")
        if isinstance(f, str) and f != FORMAT_NAME:
            raise ReadError("WrongFormat", f"format is {f!r}")
        if isinstance(v, dict):
            major, minor = v.get("major"), v.get("minor")
            ok = all(isinstance(x, int) and not isinstance(x, bool) and 0 <= x < 1 << 32 for x in (major, minor))
            if ok and major > SUPPORTED_MAJOR:
                raise ReadError("UnsupportedVersion", f"format version {major}.{minor} is newer than {SUPPORTED_MAJOR}.x")
    exact(m, ["format", "version", "generator", "units", "entries"], "manifest")
    text_(m["format"], "format")
    exact(m["version"], ["major", "minor"], "version")
    uint(m["version"]["major"], "version.major", 32), uint(m["version"]["minor"], "version.minor", 32)
    exact(m["generator"], ["name", "version"], "generator")
    text_(m["generator"]["name"], "generator.name"), text_(m["generator"]["version"], "generator.version")
    exact(m["units"], UNIT_KEYS, "units")
    for k in UNIT_KEYS:
        u = m["units"][k]
        exact(u, ["name", "si"], f"units.{k}")
        text_(u["name"], f"units.{k}.name")
        if not isinstance(u["si"], (int, float)) or isinstance(u["si"], bool):
            raise ReadError("Manifest", f"units.{k}.si must be a number")
        u["si"] = float(u["si"])
    if not isinstance(m["entries"], list):
        raise ReadError("Manifest", "entries must be a list")
    for e in m["entries"]:
        exact(e, ["name", "size", "sha256", "required"], "entry")
        text_(e["name"], "entry.name"), uint(e["size"], "entry.size", 64), text_(e["sha256"], "entry.sha256")
        if not isinstance(e["required"], bool):
            raise ReadError("Manifest", "entry.required must be a boolean")
    return m


def check_manifest(m, file_bytes):
    cap = max(file_bytes * LIMITS["max_expansion"], LIMITS["max_expansion_floor"])
    if m["format"] != FORMAT_NAME:
        raise ReadError("WrongFormat", f"format is {m['format']!r}")
    major, minor = m["version"]["major"], m["version"]["minor"]
    if major > SUPPORTED_MAJOR:
        raise ReadError("UnsupportedVersion", f"format version {major}.{minor} is newer than {SUPPORTED_MAJOR}.x")
    if major < 1:
        raise ReadError("Manifest", f"version {major}.{minor} was never released")
    if len(m["entries"]) > LIMITS["max_entries"]:
        raise ReadError("LimitExceeded", "too many entries")
    seen, total = set(), 0
    for e in m["entries"]:
        name = e["name"]
        if name == MANIFEST or name in seen:
            raise ReadError("DuplicateEntry", f"{name}: occurs more than once")
        seen.add(name)
        if len(e["sha256"]) != 64 or any(c not in "0123456789abcdef" for c in e["sha256"]):
            raise ReadError("Manifest", f"entry {name}: sha256 must be 64 lowercase hex digits")
        if name in KNOWN and KNOWN[name][0] != e["required"]:
            raise ReadError("Manifest", f"entry {name}: required flag must be {KNOWN[name][0]}")
        if name in KNOWN and KNOWN[name][1] > minor:
            raise ReadError("Manifest", f"entry {name} came with format 1.{KNOWN[name][1]}, but the file says {major}.{minor}")
        if name not in KNOWN and e["required"]:
            raise ReadError("UnknownRequiredEntry", f"{name}: unknown entry marked required")
        if e["size"] > LIMITS["max_entry_bytes"]:
            raise ReadError("LimitExceeded", f"{name}: declared size (bytes) {e['size']} exceeds the limit")
        total += e["size"]
        if total > LIMITS["max_total_bytes"]:
            raise ReadError("LimitExceeded", f"{name}: total declared size exceeds the limit")
        if total > cap:
            raise ReadError("LimitExceeded", f"{name}: total declared size {total} of a {file_bytes}-byte file exceeds {cap}")
    for name, req, _ in ENTRIES:
        if req and name not in seen:
            raise ReadError("MissingEntry", f"{name}: required in v1 but not listed")


def open_container(data):
    """SPEC §7.1 steps 1–5: ({entry name: ZipEntry}, manifest dict), the manifest checked, no
    entry outside it and every listed entry present."""
    entries = open_archive(data)
    if MANIFEST not in entries:
        raise ReadError("MissingEntry", f"{MANIFEST}: absent")
    mz = entries[MANIFEST]
    if mz.size > LIMITS["max_manifest_bytes"]:
        raise ReadError("LimitExceeded", "manifest.json size")
    raw = read_entry(data, mz, mz.size)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ReadError("Manifest", f"not UTF-8: {e}")
    m = parse_manifest(text)
    check_manifest(m, len(data))
    listed = {e["name"] for e in m["entries"]}
    for name in entries:
        if name != MANIFEST and name not in listed:
            raise ReadError("UnlistedEntry", name)
    for e in m["entries"]:
        if e["name"] not in entries:
            raise ReadError("MissingEntry", f"{e['name']}: listed but absent")
    return entries, m


def read_container(data):
    """SPEC §7.1 steps 1–6: (manifest dict, {entry name: verified bytes})."""
    entries, m = open_container(data)
    blobs = {}
    for e in m["entries"]:
        b = read_entry(data, entries[e["name"]], e["size"])
        if hashlib.sha256(b).hexdigest() != e["sha256"]:
            raise ReadError("Checksum", f"{e['name']}: SHA-256 differs from the manifest")
        blobs[e["name"]] = b
    return m, blobs


def decode(name, blob):
    """SPEC §7.1 step 7 for one known entry."""
    if name == "recipe.json":
        return decode_recipe(blob)
    d = Decoder(name, blob)
    out = DECODERS[name](d)
    d.end()
    return out


def read_bytes(data):
    """SPEC §7.1. Returns (body dict, manifest dict)."""
    m, blobs = read_container(data)
    # decoded in container order (§2), so the first record that fails is the one named
    body = {name: decode(name, blobs[name]) for name, _, _ in ENTRIES if name in blobs}
    validate(body, m)
    return body, m


def validate(b, m):
    """SPEC §6, in order."""
    def err(variant, entry, msg):
        raise ReadError(variant, f"{entry}: {msg}")

    def count(entry, field, found, expected):
        if found != expected:
            err("CountMismatch", entry, f"{field} has length {found}, expected {expected}")

    def finite(entry, field, values):
        for i, v in enumerate(values):
            if not math.isfinite(v):
                err("NonFinite", entry, f"{field}[{i}] is not finite")

    def symmetric(entry, field, a, n):
        scale = max((abs(v) for v in a), default=0.0)
        for i in range(n):
            for j in range(i + 1, n):
                if abs(a[i * n + j] - a[j * n + i]) > REL_TOL * scale:
                    err("NotSymmetric", entry, f"{field} not symmetric at ({i}, {j})")

    def index(entry, field, v, n):
        if v >= n:
            err("IndexOutOfRange", entry, f"{field} node index {v} out of range (N = {n})")

    nodes, faces, modes = b["nodes.bin"], b["faces.bin"], b["modes.bin"]
    n, nm = len(nodes), len(modes["omega2"])
    if n > LIMITS["max_nodes"]:
        err("LimitExceeded", "nodes.bin", "node count")
    if len(faces) > LIMITS["max_faces"]:
        err("LimitExceeded", "faces.bin", "face count")
    if nm > LIMITS["max_modes"]:
        err("LimitExceeded", "modes.bin", "mode count")
    for k in UNIT_KEYS:
        u = m["units"][k]
        if not (math.isfinite(u["si"]) and u["si"] > 0):
            err("Inconsistent", MANIFEST, f"units.{k}.si must be finite and > 0")
    req = b["header.bin"]["request"]
    if req["fmax_hz"] is not None and not (math.isfinite(req["fmax_hz"]) and req["fmax_hz"] > 0):
        err("Inconsistent", "header.bin", "request.fmax_hz must be finite and > 0")
    ids = set()
    for p, node in enumerate(nodes):
        finite("nodes.bin", f"nodes[{p}].xyz", node["xyz"])
        if node["id"] in ids:
            err("Inconsistent", "nodes.bin", f"node id {node['id']} occurs twice")
        ids.add(node["id"])
    for f, face in enumerate(faces):
        for k, v in enumerate(face):
            index("faces.bin", f"faces[{f}][{k}]", v, n)
    lines = b.get("lines.bin")
    if lines is not None:
        if len(lines) > LIMITS["max_faces"]:
            err("LimitExceeded", "lines.bin", "line count")
        for li, line in enumerate(lines):
            for k, v in enumerate(line):
                index("lines.bin", f"lines[{li}][{k}]", v, n)
    masses = b["nodal_mass.bin"]
    count("nodal_mass.bin", "nodal masses", len(masses), n)
    for p, x in enumerate(masses):
        flat = [v for row in x["inertia"] for v in row]
        finite("nodal_mass.bin", f"nodal_mass[{p}]", [x["mass"]] + flat)
        if x["mass"] < 0:
            err("Inconsistent", "nodal_mass.bin", f"nodal_mass[{p}].mass is negative")
        symmetric("nodal_mass.bin", f"nodal_mass[{p}].inertia", flat, 3)
    count("modes.bin", "frequency_hz", len(modes["frequency_hz"]), nm)
    count("modes.bin", "labels", len(modes["labels"]), nm)
    count("modes.bin", "generalized_mass", len(modes["generalized_mass"]), nm * nm)
    count("modes.bin", "generalized_stiffness", len(modes["generalized_stiffness"]), nm * nm)
    count("modes.bin", "shapes", len(modes["shapes"]), nm * n * 6)
    for field in ["omega2", "frequency_hz", "generalized_mass", "generalized_stiffness", "shapes"]:
        finite("modes.bin", field, modes[field])
    symmetric("modes.bin", "generalized_mass", modes["generalized_mass"], nm)
    symmetric("modes.bin", "generalized_stiffness", modes["generalized_stiffness"], nm)
    for j, (w2, f) in enumerate(zip(modes["omega2"], modes["frequency_hz"])):
        expect = math.sqrt(max(w2, 0.0)) / (2.0 * math.pi)
        if abs(f - expect) > REL_TOL * max(expect, 1.0):
            err("Inconsistent", "modes.bin", f"frequency_hz[{j}] = {f} but sqrt(max(omega2, 0))/(2 pi) = {expect}")
    inv = b["invariants.bin"]
    want = [k in SET_MEMBERS[req["invariant_set"]] for k in range(1, 10)]
    if inv["mask"] != want:
        err("Inconsistent", "invariants.bin", f"mask differs from the mask of header invariant_set {req['invariant_set']}")
    shapes = [1, 3, 3 * nm, 3 * nm, nm * 3 * nm, nm * nm, 9, nm * 9, nm * nm * 9]
    for k in range(9):
        count("invariants.bin", f"i{k + 1}", len(inv["i"][k]), shapes[k] if want[k] else 0)
        finite("invariants.bin", f"i{k + 1}", inv["i"][k])
    if want[5]:
        symmetric("invariants.bin", "i6", inv["i"][5], nm)
    if want[6]:
        symmetric("invariants.bin", "i7", inv["i"][6], 3)
    if want[0] and inv["i"][0][0] < 0:
        err("Inconsistent", "invariants.bin", "i1 (total mass) is negative")
    me = b["method.bin"]
    if me["method"] != req["method"] or me["mass_kind"] != req["mass_kind"]:
        err("Inconsistent", "method.bin", "method/mass kind differ from the header request")
    for q, itf in enumerate(me["interface"]):
        index("method.bin", f"interface[{q}].node", itf["node"], n)
        if not nodes[itf["node"]]["interface"]:
            err("Inconsistent", "method.bin", f"interface[{q}] names a node whose interface flag is false")
        a = itf["frame"]
        finite("method.bin", f"interface[{q}].frame", [v for row in a for v in row])
        for i in range(3):
            for j in range(3):
                dot = sum(a[i][k] * a[j][k] for k in range(3))
                if abs(dot - (1.0 if i == j else 0.0)) > FRAME_TOL:
                    err("Inconsistent", "method.bin", f"interface[{q}].frame is not orthonormal")
        det = (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
               + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
        if det <= 0:
            err("Inconsistent", "method.bin", f"interface[{q}].frame is left-handed")
    for q, rc in enumerate(me["reference_conditions"]):
        index("method.bin", f"reference_conditions[{q}].node", rc["node"], n)
    finite("method.bin", "cutoffs", [c for c in me["cutoffs"] if c is not None])
    counts_and_cutoffs(me, modes, req, m["version"], err)
    for entry in ["stress_shapes.bin", "strain_shapes.bin", "stress_shapes_bottom.bin", "strain_shapes_bottom.bin"]:
        s = b.get(entry)
        if s is None:
            continue
        for q, p in enumerate(s["nodes"]):
            index(entry, f"nodes[{q}]", p, n)
            if q > 0 and p <= s["nodes"][q - 1]:
                err("Inconsistent", entry, "nodes must be strictly ascending")
        count(entry, "values", len(s["values"]), nm * len(s["nodes"]) * 6)
        finite(entry, "values", s["values"])
        if entry.endswith("_bottom.bin"):
            bottom_fibre_nodes(entry, s["nodes"], b, err)
    dmp = b.get("damping.bin")
    if dmp is not None:
        count("damping.bin", "ratio", len(dmp["ratio"]), nm)
        finite("damping.bin", "ratio", dmp["ratio"])
        if any(r < 0 for r in dmp["ratio"]):
            err("Inconsistent", "damping.bin", "negative ratio")
    sh = b.get("label_shares.bin")
    if sh is not None:
        count("label_shares.bin", "shares", len(sh), nm)
        finite("label_shares.bin", "shares", sh)
        label_shares(sh, modes["labels"], me["method"], b.get("modal_loads.bin"), m["version"], err)
    ml = b.get("modal_loads.bin")
    if ml is not None:
        validate_modal_loads(ml, modes["labels"], err, count, finite)
    rc = b.get("recipe.json")
    if rc is not None:
        validate_recipe(rc, b, m, err, finite)
    itf = b.get("interfaces.bin")
    if itf is not None:
        validate_interfaces(itf, b, err, finite)
    gs = b.get("geometric_stiffness.bin")
    if gs is not None:
        validate_geometric_stiffness(gs, nm, b, m["version"], err, count, finite, symmetric)
    er = b.get("eigen_residuals.bin")
    if er is not None:
        validate_eigen_residuals(er, nm, b, err, count, finite)


def validate_eigen_residuals(er, nm, b, err, count, finite):
    """SPEC §6 rule 16: each problem the method's own, once; scale finite and > 0; residual as
    long as omega2; the length against method.bin's counts; finite; residuals >= 0; an inertia
    count's shift finite and its count at least the stored eigenvalues below it."""
    E = "eigen_residuals.bin"
    me = b["method.bin"]
    rigid, normal, _, fixed, _, _ = me["counts"]
    ml = b.get("modal_loads.bin")
    residual_vectors = ml is not None and len(ml["residual"]) > 0
    own, bound = {"NormalModes": ("NormalModes", nm), "CraigBampton": ("FixedInterface", fixed),
                  "CraigChang": ("FreeFree", rigid + normal), "Dietz": ("FreeFree", rigid + normal)}[me["method"]]
    seen = []
    for q, p in enumerate(er["problems"]):
        if p["kind"] != own:
            err("Inconsistent", E, f"problems[{q}] is {p['kind']}, not the {own} problem of {me['method']}")
        if p["kind"] in seen:
            err("Inconsistent", E, f"problems[{q}]: {p['kind']} appears twice")
        seen.append(p["kind"])
        finite(E, f"problems[{q}].scale", [p["scale"]])
        if p["scale"] <= 0:
            err("Inconsistent", E, f"problems[{q}].scale is not > 0")
        n = len(p["omega2"])
        count(E, f"problems[{q}].residual", len(p["residual"]), n)
        if own == "FreeFree":
            fits = n >= bound
        elif residual_vectors:
            fits = n <= bound
        else:
            fits = n == bound
        if not fits:
            err("CountMismatch", E, f"problems[{q}].omega2 has length {n}, against {bound} from method.bin's counts")
        finite(E, f"problems[{q}].omega2", p["omega2"])
        finite(E, f"problems[{q}].residual", p["residual"])
        for j, r in enumerate(p["residual"]):
            if r < 0:
                err("Inconsistent", E, f"problems[{q}].residual[{j}] is negative")
        i = p["inertia"]
        if i is not None:
            finite(E, f"problems[{q}].inertia.shift", [i["shift"]])
            below = sum(1 for lam in p["omega2"] if lam < i["shift"])
            if i["below"] < below:
                err("Inconsistent", E, f"problems[{q}]: {below} stored eigenvalues lie below the shift, "
                    f"but the inertia count says {i['below']}")


def validate_geometric_stiffness(gs, nm, b, version, err, count, finite, symmetric):
    """SPEC §6 rule 15: a Held body has no Rigid mode; loads valid and not repeated, each matrix
    M·M, finite, symmetric, and (since 1.8) zero for an acceleration field under inertia relief."""
    E = "geometric_stiffness.bin"
    if gs["support"] == "Held" and "Rigid" in b["modes.bin"]["labels"]:
        err("Inconsistent", E, "support is Held, but a mode is labelled Rigid")
    zero_accelerations = gs["support"] == "InertiaRelief" and (version["major"], version["minor"]) >= (1, 8)
    seen = []
    for q, f in enumerate(gs["fields"]):
        kind, axes = f["load"]
        if any(a > 2 for a in axes) or (kind == "AngularVelocity" and axes[0] > axes[1]):
            err("Inconsistent", E, f"fields[{q}]: load {kind}{axes} has an axis out of range")
        if f["load"] in seen:
            err("Inconsistent", E, f"fields[{q}]: load {kind}{axes} appears twice")
        seen.append(f["load"])
        count(E, f"fields[{q}].matrix", len(f["matrix"]), nm * nm)
        finite(E, f"fields[{q}].matrix", f["matrix"])
        symmetric(E, f"fields[{q}].matrix", f["matrix"], nm)
        if zero_accelerations and kind in ("Acceleration", "AngularAcceleration") and any(a != 0 for a in f["matrix"]):
            err("Inconsistent", E, f"fields[{q}].matrix: an acceleration field under InertiaRelief is zero")


def bottom_fibre_nodes(entry, nodes, b, err):
    """SPEC §5.15: a bottom-fibre entry needs its top entry and lists a subset of its nodes."""
    top = entry.replace("_bottom.bin", ".bin")
    if top not in b:
        err("Inconsistent", entry, f"present without {top}")
    missing = set(int(p) for p in nodes) - set(int(p) for p in b[top]["nodes"])
    if missing:
        err("Inconsistent", entry, f"node {min(missing)} has a bottom fibre but no value in {top}")


def label_shares(sh, labels, method, ml, version, err):
    """SPEC §6 rule 11 after the count and finiteness: each share in 0…1, and 1 for a Rigid mode
    and for every mode of normal modes without residual vectors (before 1.6: without a mode
    flagged residual)."""
    if (version["major"], version["minor"]) < (1, 6):
        single_stage = method == "NormalModes" and (ml is None or not any(ml["residual"]))
    else:
        single_stage = method == "NormalModes" and (ml is None or len(ml["residual"]) == 0)
    for j, (v, label) in enumerate(zip(sh, labels)):
        if not 0.0 <= v <= 1.0:
            err("Inconsistent", "label_shares.bin", f"share[{j}] = {v} is outside 0..1")
        if v != 1.0 and (label == "Rigid" or single_stage):
            err("Inconsistent", "label_shares.bin", f"share[{j}] = {v} must be 1")


def validate_modal_loads(ml, labels, err, count, finite):
    """SPEC §6 rule 12: names non-empty and unique, M finite values per load, residual flags
    0 or 1, and 1 only for a mode labelled Attachment."""
    nm = len(labels)
    names = set()
    for q, ld in enumerate(ml["loads"]):
        if not ld["name"]:
            err("Inconsistent", "modal_loads.bin", f"loads[{q}] has an empty name")
        if ld["name"] in names:
            err("Inconsistent", "modal_loads.bin", f"load name {ld['name']} appears twice")
        names.add(ld["name"])
        count("modal_loads.bin", "values", len(ld["values"]), nm)
        finite("modal_loads.bin", "values", ld["values"])
    if len(ml["residual"]):
        count("modal_loads.bin", "residual", len(ml["residual"]), nm)
        for j, (r, label) in enumerate(zip(ml["residual"], labels)):
            if r > 1:
                err("Inconsistent", "modal_loads.bin", f"residual[{j}] = {r} is not 0 or 1")
            if r == 1 and label != "Attachment":
                err("Inconsistent", "modal_loads.bin", f"residual[{j}] = 1 but mode {j} is labelled {label}")


def counts_and_cutoffs(me, modes, req, version, err):
    """SPEC §6 rule 8, second part (§5.7): counts add up (exact sums), cutoffs are the method's."""
    rigid, normal, constraint, fixed, attachment, removed = me["counts"]
    nm = len(modes["omega2"])
    labelled = sum(1 for x in modes["labels"] if x == "Rigid")
    if rigid != labelled:
        err("Inconsistent", "method.bin", f"counts.rigid = {rigid} but {labelled} modes are labelled Rigid")
    method = me["method"]
    if method == "NormalModes":
        zero, basis = [("constraint", constraint), ("fixed_interface", fixed), ("attachment", attachment)], rigid + normal
    elif method == "CraigBampton":
        zero, basis = [("normal", normal), ("attachment", attachment)], constraint + fixed
    else:
        zero, basis = [("constraint", constraint), ("fixed_interface", fixed)], rigid + normal + attachment
    for name, v in zero:
        if v != 0:
            err("Inconsistent", "method.bin", f"counts.{name} = {v} must be 0 for {method}")
    if method == "NormalModes" and removed > 0 and (version["major"], version["minor"]) < (1, 6):
        err("Inconsistent", "method.bin", f"counts.removed_dependent = {removed} must be 0 for NormalModes before 1.6")
    ok = basis == nm + removed if method == "NormalModes" else basis >= nm + removed
    if not ok:
        err("Inconsistent", "method.bin", f"counts give {basis - removed} basis vectors (after {removed} removed) for {nm} modes")
    fmax, shift, dep = me["cutoffs"]
    if fmax != req["fmax_hz"]:
        err("Inconsistent", "method.bin", "cutoffs.fmax_hz differs from the requested fmax")
    for name, v, wanted in [("shift_fraction", shift, method == "Dietz"),
                            ("dependency_tolerance", dep, method != "NormalModes")]:
        if (v is None) == wanted:
            err("Inconsistent", "method.bin", f"cutoffs.{name} {'missing' if wanted else 'present'} for {method}")
        if v is not None and not 0 < v < 1:
            err("Inconsistent", "method.bin", f"cutoffs.{name} must lie in (0, 1)")


def validate_recipe(rc, b, m, err, finite):
    """SPEC §6 rule 13, in order."""
    for q, f in enumerate(rc["model_files"]):
        if len(f["sha256"]) != 64 or any(c not in "0123456789abcdef" for c in f["sha256"]):
            err("Inconsistent", "recipe.json", f"model_files[{q}].sha256 must be 64 lowercase hex digits")
        if f["role"] != ("main" if q == 0 else "include"):
            err("Inconsistent", "recipe.json", f"model_files[{q}].role is wrong")
    if rc["options"]["units"] != {k: {"name": m["units"][k]["name"], "si": m["units"][k]["si"]} for k in UNIT_KEYS}:
        err("Inconsistent", "recipe.json", "options.units differ from the manifest's units")
    f = rc["options"]["fmax_hz"]
    if f is not None:
        finite("recipe.json", "options.fmax_hz", [f])
        if f <= 0:
            err("Inconsistent", "recipe.json", "options.fmax_hz must be > 0")
    finite("recipe.json", "options.thickness", [rc["options"]["thickness"]] if "thickness" in rc["options"] else [])
    stored = {x["id"] for x in b["nodes.bin"] if x["interface"]}
    for q, itf in enumerate(rc["interfaces"]):
        for nid in itf["nodes"]:
            if nid not in stored:
                err("Inconsistent", "recipe.json", f"interfaces[{q}] names node {nid}, not a stored interface node")
        s = itf["spider"]
        if s is not None:
            finite("recipe.json", f"interfaces[{q}].spider.centre", s["centre"])
            finite("recipe.json", f"interfaces[{q}].spider.offset_from_node_average", [s["offset_from_node_average"]])
    band = rc["accuracy_band"]["fmax_hz"]
    finite("recipe.json", "accuracy_band.fmax_hz", [band])
    if band <= 0:
        err("Inconsistent", "recipe.json", "accuracy_band.fmax_hz must be > 0")
    cutoff = rc["accuracy_band"]["basis_cutoff_hz"]
    finite("recipe.json", "accuracy_band.basis_cutoff_hz", [] if cutoff is None else [cutoff])
    pre = rc.get("preload")
    if pre is not None:  # the preload's numbers (§5.11)
        finite("recipe.json", "preload.max_displacement", [pre["max_displacement"]])
        if pre["max_displacement"] < 0:
            err("Inconsistent", "recipe.json", "preload.max_displacement must be >= 0")
        lam = pre["buckling_factor"]
        if lam is not None:
            finite("recipe.json", "preload.buckling_factor", [lam])
            if lam <= 0:
                err("Inconsistent", "recipe.json", "preload.buckling_factor must be > 0 (null: nothing in compression)")
    has_gs = "geometric_stiffness.bin" in b  # the recipe's statements about other entries
    if ("geometric_stiffness" in rc["options"]) != has_gs:
        err("Inconsistent", "recipe.json", "options.geometric_stiffness present exactly when geometric_stiffness.bin is")
    if pre is not None:
        if has_gs:
            err("Inconsistent", "recipe.json", "a preloaded build has no geometric_stiffness.bin (§5.16)")
        if "Rigid" in b["modes.bin"]["labels"]:
            err("Inconsistent", "recipe.json", "a preload needs a held body, but a mode is labelled Rigid (§5.11)")
    me = b["method.bin"]
    if me["method"] == "NormalModes" and me["counts"][5] > 0 and "residual_vectors" not in rc["options"]:
        err("Inconsistent", "recipe.json", "counts.removed_dependent > 0 for normal modes without options.residual_vectors (§5.7)")


def validate_interfaces(itf, b, err, finite):
    """SPEC §6 rule 14: one record per method.bin interface node, attached as it says."""
    E = "interfaces.bin"
    rec, nodes = b["method.bin"]["interface"], b["nodes.bin"]
    if len(itf) != len(rec):
        err("CountMismatch", E, f"interfaces has length {len(itf)}, expected {len(rec)}")
    for i, (info, r) in enumerate(zip(itf, rec)):
        if info["node"] != r["node"]:
            err("Inconsistent", E, f"interfaces[{i}].node differs from method.interface[{i}].node")
        if not info["name"]:
            err("Inconsistent", E, f"interfaces[{i}].name is empty")
        node = nodes[r["node"]]
        spider = info["kind"] != "Node"
        if spider != bool(info["dependent"]) or spider != (info["fit"] is not None):
            err("Inconsistent", E, f"interfaces[{i}]: kind, dependent nodes and centre fit disagree")
        dep = info["dependent"]
        if len(set(dep)) != len(dep):
            err("Inconsistent", E, f"interfaces[{i}]: a dependent node is listed twice")
        if node["id"] in dep:
            err("Inconsistent", E, f"interfaces[{i}]: node depends on itself")
        f = info["fit"]
        if f is None:
            continue
        finite(E, f"interfaces[{i}].fit.centre", f["centre"])
        if f["axis"] is not None:
            finite(E, f"interfaces[{i}].fit.axis", f["axis"])
        if f["radius"] is not None:
            finite(E, f"interfaces[{i}].fit.radius", [f["radius"]])
        finite(E, f"interfaces[{i}].fit.offset_from_node_average", [f["offset_from_node_average"]])
        cyl = f["method"] == "CylinderFit"
        if cyl != (f["axis"] is not None) or cyl != (f["radius"] is not None):
            err("Inconsistent", E, f"interfaces[{i}]: axis and radius must be given exactly for CylinderFit")
        if f["axis"] is not None and abs(math.sqrt(sum(a * a for a in f["axis"])) - 1.0) > FIT_TOL:
            err("Inconsistent", E, f"interfaces[{i}]: axis is not a unit vector")
        if f["radius"] is not None and f["radius"] <= 0:
            err("Inconsistent", E, f"interfaces[{i}]: radius must be > 0")
        if f["offset_from_node_average"] < 0:
            err("Inconsistent", E, f"interfaces[{i}]: offset_from_node_average must be >= 0")
        scale = max(abs(v) for v in f["centre"] + node["xyz"])
        gap = max(abs(f["centre"][k] - node["xyz"][k]) for k in range(3))
        if gap > FIT_TOL * scale:
            err("Inconsistent", E, f"interfaces[{i}]: centre is not the interface node's position")


def mass_properties(b):
    """SPEC §5.6: m = I1, c = I2/I1, J_c = I7 − m((c·c)E − c cᵀ); else from nodal masses."""
    inv = b["invariants.bin"]
    if all(inv["mask"][k] for k in (0, 1, 6)):
        i7 = inv["i"][6]
        source, m, first = "invariants", inv["i"][0][0], inv["i"][1][:]
        io_ = [[i7[0], i7[1], i7[2]], [i7[3], i7[4], i7[5]], [i7[6], i7[7], i7[8]]]
    else:
        source, m, first, io_ = "nodal_mass", 0.0, [0.0] * 3, [[0.0] * 3 for _ in range(3)]
        for node, x in zip(b["nodes.bin"], b["nodal_mass.bin"]):
            s, mp = node["xyz"], x["mass"]
            m += mp
            ss = s[0] * s[0] + s[1] * s[1] + s[2] * s[2]
            for i in range(3):
                first[i] += mp * s[i]
                for j in range(3):
                    io_[i][j] += mp * ((ss if i == j else 0.0) - s[i] * s[j]) + x["inertia"][i][j]
    c = [first[i] / m for i in range(3)] if m > 0 else [0.0] * 3
    cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2]
    ic = [[io_[i][j] - m * ((cc if i == j else 0.0) - c[i] * c[j]) for j in range(3)] for i in range(3)]
    return dict(source=source, total_mass=m, center_of_mass=c, inertia_origin=io_, inertia_center_of_mass=ic)


def summarize(b, m):
    """The JSON of `flexbody inspect --json` (SPEC §9)."""
    h, modes, me = b["header.bin"], b["modes.bin"], b["method.bin"]
    return {
        "format_version": f"{m['version']['major']}.{m['version']['minor']}",
        "generator": f"{m['generator']['name']} {m['generator']['version']}",
        "title": h["title"],
        "created_utc": h["created_utc"],
        "units": {k: {"name": m["units"][k]["name"], "si": m["units"][k]["si"]} for k in UNIT_KEYS},
        "method": me["method"],
        "mass_kind": me["mass_kind"],
        "invariant_set": h["request"]["invariant_set"],
        "invariants_present": [k + 1 for k in range(9) if b["invariants.bin"]["mask"][k]],
        "counts": {"nodes": len(b["nodes.bin"]), "interface_nodes": sum(1 for x in b["nodes.bin"] if x["interface"]),
                   "faces": len(b["faces.bin"]), "lines": len(b.get("lines.bin") or []),
                   "modes": len(modes["omega2"])},
        "mass": mass_properties(b),
        "modes": [{"number": j + 1, "frequency_hz": modes["frequency_hz"][j], "omega2": modes["omega2"][j],
                   "label": modes["labels"][j],
                   "label_share": b["label_shares.bin"][j] if "label_shares.bin" in b else None,
                   "damping_ratio": b["damping.bin"]["ratio"][j] if "damping.bin" in b else None}
                  for j in range(len(modes["omega2"]))],
        "optional": [x in b for x in ("stress_shapes.bin", "strain_shapes.bin", "damping.bin", "lines.bin")],
        "entries": [{k: e[k] for k in ("name", "size", "sha256", "required")} for e in m["entries"]],
        "recipe": b.get("recipe.json"),
        "interfaces": b.get("interfaces.bin"),
        **({"modal_loads": b["modal_loads.bin"]} if "modal_loads.bin" in b else {}),
        **({"geometric_stiffness": geometric_summary(b["geometric_stiffness.bin"])}
           if "geometric_stiffness.bin" in b else {}),
        **({"eigen_residuals": [eigen_summary(p) for p in b["eigen_residuals.bin"]["problems"]]}
           if "eigen_residuals.bin" in b else {}),
    }


def eigen_summary(p):
    """SPEC §9: a problem as decoded, with its largest residual of a flexible mode."""
    flexible = [r for lam, r in zip(p["omega2"], p["residual"]) if lam > RIGID_FRACTION * p["scale"]]
    return {**p, "largest_flexible_residual": max(flexible) if flexible else None}


def geometric_summary(gs):
    """SPEC §9: the support and each field's load name and matrix."""
    return {"support": gs["support"],
            "fields": [{"load": unit_load_name(f["load"]), "matrix": list(f["matrix"])} for f in gs["fields"]]}


def close(a, b, at="$"):
    """Structural equality, numbers to 1e-12 relative; returns a mismatch path or None."""
    if isinstance(a, bool) or isinstance(b, bool) or a is None or b is None or isinstance(a, str):
        return None if a == b else f"{at}: {a!r} vs {b!r}"
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return None if abs(a - b) <= 1e-12 * max(abs(a), abs(b)) else f"{at}: {a} vs {b}"
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            r = close(x, y, f"{at}[{i}]")
            if r:
                return r
        return None
    if isinstance(a, dict) and isinstance(b, dict) and set(a) == set(b):
        for k in a:
            r = close(a[k], b[k], f"{at}.{k}")
            if r:
                return r
        return None
    return f"{at}: {a!r} vs {b!r}"


def check_fixtures(root):
    root, bad, n = Path(root), 0, 0
    for f in sorted(list(root.glob("golden/*/*.flexbody")) + list(root.glob("compat/*.flexbody"))):
        n += 1
        try:
            got = summarize(*read_bytes(f.read_bytes()))
        except ReadError as e:
            print(f"FAIL {f}: refused ({e})")
            bad += 1
            continue
        diff = close(got, json.loads(f.with_suffix(".json").read_text()))
        print(f"{'FAIL' if diff else 'ok  '} {f}{': ' + diff if diff else ''}")
        bad += bool(diff)
    for f in sorted(root.glob("broken/*.flexbody")):
        n += 1
        want = json.loads(f.with_suffix(".expect").read_text())["variant"]
        try:
            read_bytes(f.read_bytes())
            print(f"FAIL {f}: accepted, expected {want}")
            bad += 1
        except ReadError as e:
            ok = e.variant == want
            print(f"{'ok  ' if ok else 'FAIL'} {f}: {e}{'' if ok else f' (expected {want})'}")
            bad += not ok
    print(f"{n - bad}/{n} fixtures conform")
    return 1 if bad or n == 0 else 0


def main(argv):
    if len(argv) == 3 and argv[1] == "--check-fixtures":
        return check_fixtures(argv[2])
    if len(argv) == 2 and not argv[1].startswith("-"):
        try:
            print(json.dumps(summarize(*read_bytes(Path(argv[1]).read_bytes())), indent=2))
            return 0
        except ReadError as e:
            print(f"reference_reader: {argv[1]}: {e}", file=sys.stderr)
            return 2
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
