"""Joints at a flexbody interface in exudyn: the docs' recipe (docs/using-in-solvers.md,
"Joints at interfaces in exudyn") on the bundled conrod, as a gravity pendulum.

The blocks between `# --- snippet N` and `# --- end` are the docs' code blocks line for line
(tests/docs_snippets.rs checks them and runs this script): block 1 adds the conrod and a
`hold` helper; blocks 2, 3, 4 make a revolute, a prismatic and a rigid joint at the BIG_END
interface of the default (mean-axis, free) file from point constraints only. The revolute: the
spider centre held in x y z (a spherical joint) and z held at two bore nodes. The bore is an
RBE2 spider, so its nodes move rigidly with the centre: u = u_c + theta x r. With u_c = 0 and
u_z = 0 at two bore nodes whose offsets r are not parallel, theta_x = theta_y = 0: the joint is
an exact revolute, and costs three one-node markers.

After block 2 the script swings the rod from rest (horizontal, gravity -y) and prints the
small end's position at the end and its deflection relative to the pinned end (the elastic
displacement of the SMALL_END centre minus the rigid motion of the BIG_END spider, from the
file's translational and rotational mode shapes). Then, each in a fresh system (block 1 run
again): the prismatic joint with the rod pushed along x (its slide against F t^2 / 2m), and the
rigid joint solved statically under gravity (the clamped rod's sag).

usage: python3 examples/joints_exudyn.py conrod.flexbody [T_END]
   (conrod.flexbody from `flexbody build fixtures/models/conrod/conrod.inp --interface
   BIG_END,SMALL_END --fmax 3000 --units si -o conrod.flexbody`; T_END default 0.25 s;
   python/ on PYTHONPATH or `pip install ./python`)
Needs exudyn and numpy.
"""
import os
import sys
import time

body_path = sys.argv[1]
t_end = float(sys.argv[2]) if len(sys.argv) > 2 else 0.25
os.chdir(os.path.dirname(os.path.abspath(body_path)) or ".")
if os.path.basename(body_path) != "conrod.flexbody":
    sys.exit("name the file conrod.flexbody (as the docs do)")

# --- snippet 1
import numpy as np
import exudyn as exu
import exudyn.itemInterface as eii
import flexbody.exudyn

SC = exu.SystemContainer()
mbs = SC.AddSystem()
obj = flexbody.exudyn.add_body(mbs, "conrod.flexbody", gravity=[0, -9.81, 0])
ffrf, xref = obj["oFFRFreducedOrder"], obj["interface"].xRef.reshape(-1, 3)
ground = mbs.AddObject(eii.ObjectGround())


def hold(node, axes):
    """Holds the global components `axes` (1 = held) of body node `node` where it starts."""
    on_body = mbs.AddMarker(eii.MarkerSuperElementPosition(bodyNumber=ffrf, meshNodeNumbers=[node],
                                                           weightingFactors=[1.0]))
    on_ground = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground, localPosition=list(xref[node])))
    return mbs.AddObject(eii.SphericalJoint(markerNumbers=[on_ground, on_body], constrainedAxes=axes))


big_end = obj["interfaces"][0]  # BIG_END: its centre node and its 510 bore nodes
bore = big_end["dependentNodes"]
offset = xref[bore] - xref[big_end["node"]]
along_x = bore[int(np.argmax(offset[:, 0]))]  # the bore node farthest along +x from the centre
along_y = bore[int(np.argmax(offset[:, 1]))]  # and along +y
# --- end

# --- snippet 2
# revolute about z: the centre held in x y z (a spherical joint), z held at two bore nodes off
# the axis in different directions (no tilt about x or y)
hold(big_end["node"], [1, 1, 1])
hold(along_x, [0, 0, 1])
hold(along_y, [0, 0, 1])
# --- end


def settings(t_end, step=2e-5):
    """The pendulum examples' integrator: generalized-alpha (spectral radius 0.9), h = 2e-5 s."""
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = int(round(t_end / step))
    s.timeIntegration.endTime = t_end
    s.timeIntegration.generalizedAlpha.spectralRadius = 0.9
    s.timeIntegration.newton.useModifiedNewton = True
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 1e-4
    return s


def global_positions(mbs, obj, nodes):
    """Global positions of body nodes now: R + A (x_ref + Psi q)."""
    cms = obj["interface"]
    r = np.array(mbs.GetNodeOutput(obj["nRigidBody"], exu.OutputVariableType.Position))
    a = np.array(mbs.GetNodeOutput(obj["nRigidBody"], exu.OutputVariableType.RotationMatrix)).reshape(3, 3)
    q = np.array(mbs.GetNodeOutput(obj["nGenericODE2"], exu.OutputVariableType.Coordinates))
    local = cms.xRef.reshape(-1, 3)[nodes] + (cms.modeBasis @ q).reshape(-1, 3)[nodes]
    return r + local @ a.T


small_end = obj["interfaces"][1]
s_modal = mbs.AddSensor(eii.SensorNode(nodeNumber=obj["nGenericODE2"], storeInternal=True,
                                       outputVariableType=exu.OutputVariableType.Coordinates))
mbs.Assemble()
clock = time.perf_counter()
exu.SolveDynamic(mbs, settings(t_end))
solve_seconds = time.perf_counter() - clock
tip = global_positions(mbs, obj, small_end["dependentNodes"]).mean(axis=0)

# Deflection relative to the pinned end: the SMALL_END centre's elastic displacement minus the
# rigid motion of the BIG_END spider (its translation and rotation, from the file's shapes;
# exudyn's modeBasis holds translations only), in the body frame: u_s - u_b - theta_b x (x_s - x_b).
file = flexbody.read("conrod.flexbody")
shapes = file.shapes[flexbody.exudyn.flexible_modes(file)]
q = mbs.GetSensorStoredData(s_modal)[:, 1:]
b, s = big_end["node"], small_end["node"]
u_b, theta_b, u_s = q @ shapes[:, b, :3], q @ shapes[:, b, 3:], q @ shapes[:, s, :3]
relative = u_s - u_b - np.cross(theta_b, xref[s] - xref[b])
print(f"revolute pendulum to t = {t_end} s in {solve_seconds:.2f} s: small end (mean of "
      f"{len(small_end['dependentNodes'])} bore nodes) at {tip[0]:.9f} {tip[1]:.9f} {tip[2]:.9e} m")
print(f"deflection relative to the pinned end: max |transverse| {np.abs(relative[:, 1]).max():.3e} m; "
      f"in the body frame (mean axes): max |transverse| {np.abs(u_s[:, 1]).max():.3e} m")


def snippet(k):
    """The text of this file's block `# --- snippet k` (the docs' block k)."""
    with open(os.path.abspath(__file__)) as f:
        return f.read().split(f"# --- snippet {k}\n")[1].split("# --- end\n")[0]


# The prismatic joint: a fresh system (block 1 again) with block 3, the rod pushed along x by
# 1 N at the BIG_END centre, gravity -y. It slides freely: x of its centre of mass (the mean-axis
# frame's origin) = F t^2 / (2 m), and turns only elastically.
exec(snippet(1))
# --- snippet 3
# prismatic along x: the centre and the bore node along +x held in y z, the bore node along +y
# held in z (no rotation at all, free sliding along x)
hold(big_end["node"], [0, 1, 1])
hold(along_x, [0, 1, 1])
hold(along_y, [0, 0, 1])
# --- end
push = mbs.AddMarker(eii.MarkerSuperElementPosition(bodyNumber=ffrf, meshNodeNumbers=[big_end["node"]],
                                                    weightingFactors=[1.0]))
mbs.AddLoad(eii.LoadForceVector(markerNumber=push, loadVector=[1.0, 0, 0]))
mbs.Assemble()
exu.SolveDynamic(mbs, settings(t_end))
frame = np.array(mbs.GetNodeOutput(obj["nRigidBody"], exu.OutputVariableType.Position))
turn = np.array(mbs.GetNodeOutput(obj["nRigidBody"], exu.OutputVariableType.RotationMatrix)).reshape(3, 3)
slide_expected = 1.0 * t_end ** 2 / (2 * obj["interface"].totalMass)
slide_error = abs(frame[0] - slide_expected) / slide_expected
slide_turn = float(np.abs(turn - np.eye(3)).max())
print(f"prismatic: slid {frame[0]:.9e} m in {t_end} s (F t^2 / 2m = {slide_expected:.9e} m, relative "
      f"difference {slide_error:.1e}); frame off its start: y {frame[1]:.1e} m, rotation {slide_turn:.1e}")

# The rigid joint: a fresh system with block 4, gravity -y, solved statically: the conrod as a
# cantilever clamped at BIG_END; the small end's sag (mean of its bore nodes).
exec(snippet(1))
# --- snippet 4
# rigid: the centre held in x y z, the bore node along +x held in y z, the bore node along +y in z
hold(big_end["node"], [1, 1, 1])
hold(along_x, [0, 1, 1])
hold(along_y, [0, 0, 1])
# --- end
mbs.Assemble()
static = exu.SimulationSettings()
static.staticSolver.verboseMode = 0
exu.SolveStatic(mbs, static)
small_end = obj["interfaces"][1]
sag = (global_positions(mbs, obj, small_end["dependentNodes"]) - xref[small_end["dependentNodes"]]).mean(axis=0)
print(f"rigid (clamped at BIG_END, gravity -y): small end's static displacement {sag[0]:.4e} {sag[1]:.6e} "
      f"{sag[2]:.4e} m")

# The marker-based revolute (block 5) against the node-based one (block 2): the same pendulum
# for 100 steps each, in fresh systems; the solve times are printed, not checked.
exec(snippet(1))
# --- snippet 5
# revolute about z through a rigid marker over all bore nodes (dearer, see the docs)
centre = xref[big_end["node"]]
on_bore = mbs.AddMarker(eii.MarkerSuperElementRigid(
    bodyNumber=ffrf, meshNodeNumbers=bore, weightingFactors=[1 / len(bore)] * len(bore),
    offset=list(centre - xref[bore].mean(axis=0))))
on_ground = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=list(centre)))
mbs.AddObject(eii.GenericJoint(markerNumbers=[on_ground, on_bore], constrainedAxes=[1, 1, 1, 1, 1, 0]))
# --- end


def solve_100_steps():
    """Seconds for 100 steps of the pendulum in `mbs`, and the small end's position then."""
    mbs.Assemble()
    clock = time.perf_counter()
    exu.SolveDynamic(mbs, settings(0.002))
    seconds = time.perf_counter() - clock
    return seconds, global_positions(mbs, obj, obj["interfaces"][1]["dependentNodes"]).mean(axis=0)


marker_seconds, marker_tip = solve_100_steps()
exec(snippet(1))
exec(snippet(2))
node_seconds, node_tip = solve_100_steps()
print(f"revolute, 100 steps: node-based (3 one-node markers) {node_seconds:.3f} s, marker-based "
      f"(MarkerSuperElementRigid over {len(bore)} bore nodes) {marker_seconds:.3f} s, "
      f"{marker_seconds / node_seconds:.0f} times; small ends {np.linalg.norm(node_tip - marker_tip):.1e} m apart")
