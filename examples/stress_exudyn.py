"""Stresses through exudyn's sensor: the docs' recipe (docs/using-in-solvers.md, "Stresses
through exudyn's sensor") on the bundled conrod.

The conrod is built with `--stress-modes` (a stress shape per mode at the solid nodes) and with
its frame attached at the BIG_END centre (`--reference-conditions 6962:123456`), so a clamp is
one rigid joint on the frame node. Under gravity -y it sags statically; exudyn's
`SensorSuperElement` with `OutputVariableType.StressLocal` gives the stress at a mesh node in the
body frame: sum_j q_j times the exported stress mode (exudyn's component order xx yy zz yz xz xy).
The block between `# --- snippet 1` and `# --- end` is the docs' block line for line
(tests/docs_snippets.rs checks it and runs this script).

After the solve the script recomputes the same stress from the file itself (the reference reader
format-spec/reference_reader.py: the stress shapes in the file's order xx yy zz xy yz zx, the
flexible modes picked by label) and prints both.

usage: python3 examples/stress_exudyn.py
   (FLEXBODY=path/to/flexbody; default target/release/flexbody; python/ on PYTHONPATH or
   `pip install ./python`)
Needs exudyn and numpy.
"""
import os
import subprocess
import sys
import tempfile

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
flexbody_exe = os.environ.get("FLEXBODY", os.path.join(root, "target", "release", "flexbody"))
work = tempfile.mkdtemp(prefix="flexbody-stress-")
os.chdir(work)
subprocess.run([flexbody_exe, "build", os.path.join(root, "fixtures/models/conrod/conrod.inp"),
                "--interface", "BIG_END,SMALL_END", "--fmax", "3000", "--units", "si",
                "--stress-modes", "--reference-conditions", "6962:123456", "-q",
                "-o", "conrod_stress.flexbody"], check=True)

# --- snippet 1
import numpy as np
import exudyn as exu
import exudyn.itemInterface as eii
import flexbody.exudyn

SC = exu.SystemContainer()
mbs = SC.AddSystem()
obj = flexbody.exudyn.add_body(mbs, "conrod_stress.flexbody", gravity=[0, -9.81, 0])
ffrf = obj["oFFRFreducedOrder"]
# clamped at BIG_END: the frame is attached there (--reference-conditions), so hold the frame node
ground = mbs.AddObject(eii.ObjectGround())
on_ground = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
on_frame = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=obj["nRigidBody"]))
mbs.AddObject(eii.GenericJoint(markerNumbers=[on_ground, on_frame], constrainedAxes=[1, 1, 1, 1, 1, 1]))
# the stress at a mesh node (body frame, xx yy zz yz xz xy): here where mode 1's xx stress peaks
modes = obj["interface"].postProcessingModes["matrix"]  # nodes x (6 per flexible mode)
node = int(np.argmax(np.abs(modes[:, 0])))
stress = mbs.AddSensor(eii.SensorSuperElement(bodyNumber=ffrf, meshNodeNumber=node, storeInternal=True,
                                              outputVariableType=exu.OutputVariableType.StressLocal))
mbs.Assemble()
exu.SolveStatic(mbs)
sigma = mbs.GetSensorValues(stress)
# --- end

# the same stress from the file: its stress shapes (xx yy zz xy yz zx) times the modal coordinates
sys.path.insert(0, os.path.join(root, "format-spec"))
import reference_reader  # noqa: E402

with open("conrod_stress.flexbody", "rb") as f:
    file, _ = reference_reader.read_bytes(f.read())
labels = file["modes.bin"]["labels"]
flexible = [j for j, label in enumerate(labels) if label != "Rigid"]
shapes = file["stress_shapes.bin"]
k = len(shapes["nodes"])
values = np.array(shapes["values"]).reshape(len(labels), k, 6)
row = list(shapes["nodes"]).index(node)
q = np.array(mbs.GetNodeOutput(obj["nGenericODE2"], exu.OutputVariableType.Coordinates))
xx, yy, zz, xy, yz, zx = q @ values[flexible, row, :]
from_file = np.array([xx, yy, zz, yz, zx, xy])  # exudyn's order
node_id = int(file["nodes.bin"][node]["id"])
print(f"stress at node index {node} (id {node_id}) of the clamped conrod under gravity, body frame "
      f"xx yy zz yz xz xy [Pa]: sensor {' '.join(f'{v:.6e}' for v in sigma)}")
print(f"from the file's stress shapes: {' '.join(f'{v:.6e}' for v in from_file)}; largest difference "
      f"{np.abs(np.asarray(sigma) - from_file).max() / np.abs(from_file).max():.1e} (relative)")
