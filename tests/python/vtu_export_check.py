"""Checks `flexbody export --to vtu` with meshio, a third-party VTK reader, against the
.flexbody file read by this repository's numpy package (python/flexbody) (run by
tests/export_vtu.rs).

1. Points are the stored nodes' coordinates; cells are the file's faces (triangles, quads),
   lines, and a vertex per interface node outside them; `node id` and `interface` point data
   are the file's.
2. Per flexible mode j: `mode j, F Hz, LABEL` equals the translations and `mode j rotation`
   the rotations of the file's shape; the name carries the mode number, frequency and label.
3. Per stored stress/strain field: `mode j stress` (…) equals the file's 6 components at the
   listed nodes and is NaN elsewhere.
4. Field data: mode numbers, frequencies, damping ratios.

usage: vtu_export_check.py BODY.vtu BODY.flexbody   (with python/ on PYTHONPATH)
Prints one line per measured figure; exits non-zero on any failure.
"""
import sys

import meshio
import numpy as np

import flexbody

vtu_path, body_path = sys.argv[1], sys.argv[2]
failures = []


def check(name, value, limit):
    ok = value <= limit
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {value:.3e} (limit {limit:.0e})")
    if not ok:
        failures.append(name)


def same(name, ok):
    print(f"{'ok  ' if ok else 'FAIL'} {name}")
    if not ok:
        failures.append(name)


mesh = meshio.read(vtu_path)
body = flexbody.read(body_path)
n = len(body.node_ids)
LABEL_WORDS = {
    "Rigid": "rigid",
    "Normal": "normal",
    "Constraint": "constraint",
    "FixedInterface": "fixed-interface",
    "Attachment": "attachment",
    "FrequencyResponse": "frequency-response",
}

# 1. Mesh.
check("points vs node coordinates", float(np.max(np.abs(mesh.points - body.xyz))), 1e-15)
cells = {}
for block in mesh.cells:
    cells.setdefault(block.type, []).append(block.data)
cells = {k: np.concatenate(v) for k, v in cells.items()}
tris = body.faces[~body.face_is_quad][:, :3]
quads = body.faces[body.face_is_quad]
same(f"triangles ({len(tris)}) are the file's", np.array_equal(cells.get("triangle", np.zeros((0, 3), int)), tris))
same(f"quads ({len(quads)}) are the file's", np.array_equal(cells.get("quad", np.zeros((0, 4), int)), quads))
lines = body.lines if body.lines is not None else np.zeros((0, 2), int)
same(f"lines ({len(lines)}) are the file's", np.array_equal(cells.get("line", np.zeros((0, 2), int)), lines))
used = np.zeros(n, bool)
for a in (tris, quads, lines):
    used[a.reshape(-1)] = True
if len(tris) + len(quads) + len(lines) == 0:
    expected_vertices = np.arange(n)
else:
    expected_vertices = np.flatnonzero(body.interface_flags & ~used)
vertices = cells.get("vertex", np.zeros((0, 1), int)).reshape(-1)
same(f"vertices ({len(vertices)}) are the interface nodes outside faces and lines", np.array_equal(vertices, expected_vertices))
same("node id", np.array_equal(mesh.point_data["node id"].reshape(-1), body.node_ids))
same("interface", np.array_equal(mesh.point_data["interface"].reshape(-1).astype(bool), body.interface_flags))

# 2. Mode shapes.
flexible = [j for j, label in enumerate(body.labels) if label != "Rigid"]
worst_shape = 0.0
for j in flexible:
    names = [k for k in mesh.point_data if k.startswith(f"mode {j + 1}, ")]
    same(f"mode {j + 1}: one translation array ({names})", len(names) == 1)
    if len(names) != 1:
        continue
    name = names[0]
    _, hz, word = name.split(", ")
    f = body.frequency_hz[j]
    same(f"mode {j + 1}: name's label {word!r}", word == LABEL_WORDS[body.labels[j]])
    same(f"mode {j + 1}: name's frequency {hz}", abs(float(hz.removesuffix(" Hz")) - f) <= 1e-4 * f)
    worst_shape = max(worst_shape, float(np.max(np.abs(mesh.point_data[name] - body.shapes[j][:, :3]))))
    rotation = mesh.point_data[f"mode {j + 1} rotation"]
    worst_shape = max(worst_shape, float(np.max(np.abs(rotation - body.shapes[j][:, 3:]))))
check(f"{len(flexible)} mode shapes (translations, rotations) vs the file", worst_shape, 1e-15)
modes_written = sorted({k.split(",")[0].split()[1] for k in mesh.point_data if k.startswith("mode ")}, key=int)
same("only the flexible modes are written", modes_written == [str(j + 1) for j in flexible])

# 3. Stress and strain shapes.
for suffix, nodes, values in [
    ("stress", body.stress_nodes, body.stress_shapes),
    ("strain", body.strain_nodes, body.strain_shapes),
    ("stress bottom", body.stress_bottom_nodes, body.stress_shapes_bottom),
    ("strain bottom", body.strain_bottom_nodes, body.strain_shapes_bottom),
]:
    present = [k for k in mesh.point_data if k.endswith(f" {suffix}")]
    if values is None:
        same(f"no {suffix} arrays (the file has none)", not present)
        continue
    worst = 0.0
    others = np.setdiff1d(np.arange(n), nodes)
    nan_elsewhere = True
    for j in flexible:
        a = mesh.point_data[f"mode {j + 1} {suffix}"]
        worst = max(worst, float(np.max(np.abs(a[nodes] - values[j]))))
        nan_elsewhere &= bool(np.all(np.isnan(a[others])))
    check(f"{suffix} shapes at {len(nodes)} nodes vs the file", worst, 1e-15)
    same(f"{suffix}: NaN at the {len(others)} nodes without a value", nan_elsewhere)

# 4. Field data.
fd = mesh.field_data
same("field data: mode numbers", np.array_equal(np.asarray(fd["mode number"]).reshape(-1), np.array(flexible) + 1))
check("field data: frequencies", float(np.max(np.abs(np.asarray(fd["frequency_hz"]).reshape(-1) - body.frequency_hz[flexible]))), 1e-15)
if body.damping_ratio is not None:
    check("field data: damping ratios", float(np.max(np.abs(np.asarray(fd["damping ratio"]).reshape(-1) - body.damping_ratio[flexible]))), 1e-15)
else:
    same("field data: no damping ratio (the file has none)", "damping ratio" not in fd)

if failures:
    print("FAILED:", ", ".join(failures))
    sys.exit(1)
print(f"all checks passed: {n} points, {len(flexible)} modes")
