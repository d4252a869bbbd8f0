"""Checks the Python package's one-call exudyn helper (python/flexbody/exudyn.py) against the
NPZ of `flexbody export --to exudyn` of the same file (run by tests/export_exudyn.rs).

1. `flexbody.exudyn.interface(FILE)` equals exudyn's own `LoadFromFile(NPZ)`: every inertia term,
   mode basis, reduced matrices, reference positions, FFRF mass matrix, triangles, stress or
   strain modes and the sizes, exactly (the same numbers with the same signs).
2. `flexbody.exudyn.add_body(mbs, FILE)` adds the same ObjectFFRFreducedOrder as
   `LoadFromFile` + `AddObjectFFRFreducedOrder` (every array parameter equal) and applies the
   file's modal damping as dampingMatrixReduced = the NPZ's diag(2 zeta omega).
3. The frequencies of the object exudyn holds (its reduced K and M) equal the file's stored
   flexible-mode frequencies (read by format-spec/reference_reader.py) to 1e-10.

usage: exudyn_helper_check.py BODY.npz BODY.flexbody   (with python/ on PYTHONPATH)
Prints one line per measured figure; exits non-zero on any failure.
"""
import sys
from pathlib import Path

import numpy as np

import exudyn as exu
from exudyn.FEM import ObjectFFRFreducedOrderInterface

import flexbody
import flexbody.exudyn

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "format-spec"))
import reference_reader  # noqa: E402

npz, path = sys.argv[1], sys.argv[2]
failures = []


def check(name, value, limit):
    ok = value <= limit
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {value:.3e} (limit {limit:.0e})")
    if not ok:
        failures.append(name)


def diff(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape:
        return np.inf
    return float(np.abs(a - b).max()) if a.size else 0.0


assert flexbody.__file__.startswith(str(Path(__file__).resolve().parents[2] / "python")), flexbody.__file__

# 1. the helper's interface object against exudyn's loader
loaded = ObjectFFRFreducedOrderInterface()
loaded.LoadFromFile(npz)
built = flexbody.exudyn.interface(path)
print(f"{npz}: {int(loaded.nNodes)} nodes, {int(loaded.nModes)} flexible modes, "
      f"{len(loaded.trigList)} triangles of {len(loaded.trigList[0]) if loaded.trigList else 0} nodes, "
      f"post-processing {loaded.postProcessingModes.get('outputVariableType', 'none')}")
for key in ["modeBasis", "massMatrixReduced", "stiffnessMatrixReduced", "xRef", "inertiaLocal", "Mtt",
            "totalMass", "chiU", "chiUtilde", "mPsiTildePsi", "mPsiTildePsiTilde", "mPhitTPsi",
            "mPhitTPsiTilde", "mXRefTildePsi", "mXRefTildePsiTilde", "massMatrixFFRFreduced"]:
    check(f"interface {key} = LoadFromFile's (max abs difference)", diff(getattr(built, key), getattr(loaded, key)), 0.0)
sizes = ["nModes", "nNodes", "dim3D", "nODE2rot", "nODE2rigid", "nODE2FFRFreduced", "rigidBodyNodeType"]
check("sizes and node type differing", sum(getattr(built, k) != getattr(loaded, k) for k in sizes), 0)
check("triangles differing", sum(a != b for a, b in zip(built.trigList, loaded.trigList))
      + abs(len(built.trigList) - len(loaded.trigList)), 0)
pb, pl = built.postProcessingModes, loaded.postProcessingModes
check("post-processing keys/type differing", (set(pb) != set(pl)) + (pb.get("outputVariableType") != pl.get("outputVariableType")), 0)
if "matrix" in pl:
    check("post-processing matrix (max abs difference)", diff(pb["matrix"], pl["matrix"]), 0.0)
raw = np.load(npz, allow_pickle=True)
for key in ["nodeIds", "interfaceNodeIndices", "nodalMass", "eigenFrequenciesHz", "flexibleModeIndices",
            "interfaceDependentOffsets", "interfaceDependentNodeIndices", "interfaceDependentNodeIds"]:
    check(f"flexbody key {key} = NPZ's", diff(built.flexbody[key], raw[key]), 0.0)
for key in ["interfaceNames", "interfaceKinds", "units"]:
    check(f"flexbody key {key} = NPZ's (differing)", int(str(built.flexbody[key]) != str(raw[key])), 0)
itf = flexbody.exudyn.interfaces_of(raw)
check("interfaces_of(NPZ) differing from the file's interfaces (node, name, kind, dependent ids)",
      sum(int(a["node"] != b["node"] or a["name"] != b["name"] or a["kind"] != b["kind"]
              or a["dependentIds"] != [int(d) for d in b["dependent"]])
          for a, b in zip(itf, flexbody.read(path).interfaces or []))
      + abs(len(itf) - len(flexbody.read(path).interfaces or [])), 0)

# 2. the object in an mbs: add_body against LoadFromFile + AddObjectFFRFreducedOrder
def added(helper):
    mbs = exu.SystemContainer().AddSystem()
    if helper:
        obj = flexbody.exudyn.add_body(mbs, path, positionRef=[0.1, 0.2, 0.3], gravity=[0, 0, -9.81])
    else:
        obj = loaded.AddObjectFFRFreducedOrder(mbs, positionRef=[0.1, 0.2, 0.3], gravity=[0, 0, -9.81])
    return mbs, obj, mbs.GetObject(obj["oFFRFreducedOrder"])


mbs_h, obj_h, par_h = added(True)
mbs_l, obj_l, par_l = added(False)
compared = 0
for k, v in par_l.items():
    if isinstance(v, np.ndarray) or k in ("massMatrixReduced", "stiffnessMatrixReduced"):
        a, b = par_h[k], v
        if k in ("massMatrixReduced", "stiffnessMatrixReduced"):
            a, b = a.Convert2DenseMatrix(), b.Convert2DenseMatrix()
        check(f"object parameter {k} = LoadFromFile's", diff(a, b), 0.0)
        compared += 1
assert compared >= 10, compared
check("object mass, node position differing",
      diff(par_h["mass"], par_l["mass"]) + diff(mbs_h.GetNode(obj_h["nRigidBody"])["referenceCoordinates"],
                                               mbs_l.GetNode(obj_l["nRigidBody"])["referenceCoordinates"]), 0.0)
check("add_body's interfaces differing from interfaces_of(NPZ)", int(obj_h["interfaces"] != itf), 0)
if "dampingMatrixReduced" in raw.files:
    check("object dampingMatrixReduced = NPZ's diag(2 zeta omega)",
          diff(par_h["dampingMatrixReduced"].Convert2DenseMatrix(), raw["dampingMatrixReduced"]), 0.0)

# 3. frequencies of the object exudyn holds against the file's
ref, _ = reference_reader.read_bytes(Path(path).read_bytes())
modes = ref["modes.bin"]
flex = [j for j, label in enumerate(modes["labels"]) if label != "Rigid"]
k = par_h["stiffnessMatrixReduced"].Convert2DenseMatrix()
m = par_h["massMatrixReduced"].Convert2DenseMatrix()
w2 = np.sort(np.linalg.eigvals(np.linalg.solve(m, k)).real)
f_obj = np.sqrt(np.maximum(w2, 0)) / (2 * np.pi)
f_file = np.array([modes["frequency_hz"][j] for j in flex])
check(f"object frequencies = file's ({len(flex)} flexible modes, relative)",
      float(np.abs(f_obj - f_file).max() / f_file.max()), 1e-10)

if failures:
    print(f"FAILED: {', '.join(failures)}")
    sys.exit(1)
print("all helper checks passed")
