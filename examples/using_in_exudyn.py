"""The exudyn snippets of docs/using-in-solvers.md, runnable as they stand there.

Each block between `# --- snippet N` and `# --- end` is the docs' code block N of the exudyn
section, line for line (tests/docs_snippets.rs checks they stay equal and runs this script).

usage: python3 examples/using_in_exudyn.py conrod.npz conrod.flexbody
   (made by `flexbody build ... -o conrod.flexbody` and `flexbody export conrod.flexbody --to
   exudyn -o conrod.npz`; with or without --damping; python/ on PYTHONPATH or
   `pip install ./python` for flexbody.exudyn)
Needs exudyn and numpy. Prints one line per snippet and what it made.
"""
import os
import sys

npz_path, flexbody_path = sys.argv[1], sys.argv[2]
os.chdir(os.path.dirname(os.path.abspath(npz_path)) or ".")
# The docs name the files conrod.npz and conrod.flexbody in the current folder.
if os.path.basename(npz_path) != "conrod.npz" or os.path.basename(flexbody_path) != "conrod.flexbody":
    sys.exit("name the files conrod.npz and conrod.flexbody (as the docs do), in one folder")

# --- snippet 1
import exudyn as exu
from exudyn.FEM import ObjectFFRFreducedOrderInterface

SC = exu.SystemContainer()
mbs = SC.AddSystem()
cms = ObjectFFRFreducedOrderInterface()
cms.LoadFromFile("conrod.npz")
obj = cms.AddObjectFFRFreducedOrder(mbs, positionRef=[0, 0, 0], gravity=[0, -9.81, 0])
# --- end
mbs.Assemble()
print(f"snippet 1: LoadFromFile + AddObjectFFRFreducedOrder: {mbs.systemData.NumberOfObjects()} objects, "
      f"{cms.nModes} modes, assembled")

# --- snippet 2
import exudyn as exu
import flexbody.exudyn

SC = exu.SystemContainer()
mbs = SC.AddSystem()
obj = flexbody.exudyn.add_body(mbs, "conrod.flexbody", positionRef=[0, 0, 0], gravity=[0, -9.81, 0])
obj["oFFRFreducedOrder"], obj["interface"], obj["interfaceNodes"]  # + exudyn's other items
# --- end
mbs.Assemble()
print(f"snippet 2: flexbody.exudyn.add_body: object {obj['oFFRFreducedOrder']}, "
      f"interface nodes {list(obj['interfaceNodes'])}, assembled")

# --- snippet 3
import numpy as np

data = np.load("conrod.npz", allow_pickle=True)
if "dampingMatrixReduced" in data.files:  # only when built with --damping
    mc = exu.MatrixContainer()
    mc.SetWithDenseMatrix(data["dampingMatrixReduced"], useDenseMatrix=False)
    mbs.SetObjectParameter(obj["oFFRFreducedOrder"], "dampingMatrixReduced", mc)
# --- end
mbs.Assemble()
if "dampingMatrixReduced" in data.files:
    d = np.asarray(data["dampingMatrixReduced"])
    print(f"snippet 3: dampingMatrixReduced set ({d.shape[0]} modes, max diagonal {float(d.diagonal().max())!r})")
else:
    print("snippet 3: no dampingMatrixReduced in the NPZ (built without --damping): nothing set")
print("all snippets ran")
