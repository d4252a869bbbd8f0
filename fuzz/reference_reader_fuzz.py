#!/usr/bin/env python3
"""Mutation fuzzer for format-spec/reference_reader.py: every input must end in a summary or a
named ReadError, never another exception (SPEC §7: a reader never crashes).

    reference_reader_fuzz.py [--iterations N] [--seed S] [--time SECONDS] [FILE_OR_DIR ...]

Inputs: every file given (e.g. fuzz/corpus/reader_raw, fuzz/artifacts) run as-is, then N
mutants of the fixtures' .flexbody files: byte flips, truncations, splices, and structure-aware
ones (one entry replaced/overwritten/truncated or a manifest value changed, the manifest's
sizes and SHA-256 rebuilt). A crashing input is saved under fuzz/artifacts/reference_reader/
and the exit status is 1. Standard library only (atheris is not needed).
"""
import hashlib
import io
import json
import random
import sys
import time
import traceback
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "format-spec"))
import reference_reader as rr  # noqa: E402

OUT = HERE / "artifacts" / "reference_reader"


def run_one(data):
    """None if the input ended in a summary or a named ReadError, else the traceback."""
    try:
        body, m = rr.read_bytes(data)
        rr.summarize(body, m)
        return None
    except rr.ReadError:
        return None
    except Exception:  # noqa: BLE001 - the point is to catch everything else
        return traceback.format_exc()


def entries_of(data):
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        return [(i.filename, z.read(i)) for i in z.infolist()]


def rebuild(entries, fix_manifest=True):
    entries = [list(e) for e in entries]
    if fix_manifest:
        for e in entries:
            if e[0] == "manifest.json":
                try:
                    m = json.loads(e[1])
                    blobs = dict((n, b) for n, b in entries)
                    for it in m.get("entries", []):
                        b = blobs.get(it.get("name")) if isinstance(it, dict) else None
                        if b is not None:
                            it["size"] = len(b)
                            it["sha256"] = hashlib.sha256(b).hexdigest()
                    e[1] = json.dumps(m).encode()
                except (ValueError, TypeError, AttributeError):
                    pass
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_STORED) as z:
        for n, b in entries:
            z.writestr(n, b)
    return buf.getvalue()


INTERESTING = [0, 1, 2, 3, 7, 8, 0x7F, 0x80, 0xFF, 0xFE]
JSON_VALUES = [None, True, -1, 0, 1, 2**32, 2**64, 1.5, 1e308, "", "x", [], {}, [1], {"a": 1}]


def mutate_bytes(rng, b):
    b = bytearray(b)
    for _ in range(rng.randint(1, 8)):
        op = rng.randrange(6)
        if op == 0 and b:
            b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
        elif op == 1 and b:
            b[rng.randrange(len(b))] = rng.choice(INTERESTING)
        elif op == 2 and b:
            del b[rng.randrange(len(b)):]
        elif op == 3:
            at = rng.randrange(len(b) + 1)
            b[at:at] = bytes(rng.choice(INTERESTING) for _ in range(rng.randint(1, 16)))
        elif op == 4 and len(b) >= 8:  # a length prefix / count set to a large value
            at = rng.randrange(len(b) - 7)
            b[at:at + 8] = rng.choice([2**32 - 1, 2**40, 2**63, 1, 0]).to_bytes(8, "little")
        elif op == 5 and b:
            at, n = rng.randrange(len(b)), rng.randint(1, 64)
            b[at:at] = b[at:at + n]
    return bytes(b)


def mutate_json(rng, v, depth=0):
    if isinstance(v, dict) and v:
        k = rng.choice(list(v))
        if rng.random() < 0.2:
            del v[k]
        else:
            v[k] = mutate_json(rng, v[k], depth + 1)
        return v
    if isinstance(v, list) and v:
        i = rng.randrange(len(v))
        if rng.random() < 0.2:
            del v[i]
        else:
            v[i] = mutate_json(rng, v[i], depth + 1)
        return v
    return rng.choice(JSON_VALUES)


def mutant(rng, seeds):
    data = rng.choice(seeds)
    kind = rng.randrange(4)
    if kind == 0:
        return mutate_bytes(rng, data)
    try:
        entries = entries_of(data)
    except Exception:  # noqa: BLE001 - broken seeds mutate as bytes
        return mutate_bytes(rng, data)
    i = rng.randrange(len(entries))
    name, b = entries[i]
    if name in ("manifest.json", "recipe.json") and kind == 1:
        try:
            entries[i] = (name, json.dumps(mutate_json(rng, json.loads(b))).encode())
            return rebuild(entries, fix_manifest=name != "manifest.json")
        except ValueError:
            pass
    entries[i] = (name, mutate_bytes(rng, b))
    return rebuild(entries, fix_manifest=kind != 3)


def main(argv):
    iterations, seed, limit, paths = 20000, 1, None, []
    args = iter(argv[1:])
    for a in args:
        if a == "--iterations":
            iterations = int(next(args))
        elif a == "--seed":
            seed = int(next(args))
        elif a == "--time":
            limit = float(next(args))
        else:
            paths.append(Path(a))
    crashes, done = 0, 0
    start = time.time()

    def check(data, label):
        nonlocal crashes
        tb = run_one(data)
        if tb:
            crashes += 1
            OUT.mkdir(parents=True, exist_ok=True)
            out = OUT / f"crash-{hashlib.sha1(data).hexdigest()[:16]}"
            out.write_bytes(data)
            print(f"CRASH {label} → {out}\n{tb}")

    for p in paths:
        for f in sorted(p.rglob("*") if p.is_dir() else [p]):
            if f.is_file():
                check(f.read_bytes(), str(f))
                done += 1
    fixtures = HERE.parent / "fixtures"
    seeds = [f.read_bytes() for f in sorted(fixtures.rglob("*.flexbody"))]
    rng = random.Random(seed)
    for k in range(iterations):
        if limit is not None and time.time() - start > limit:
            break
        data = mutant(rng, seeds)
        check(data, f"mutant {k} (seed {seed})")
        done += 1
    el = time.time() - start
    print(f"reference_reader fuzz: {done} inputs in {el:.0f} s ({done / max(el, 1e-9):.0f}/s), {crashes} crashes")
    return 1 if crashes else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
