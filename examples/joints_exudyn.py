"""Joints at a flexbody interface in exudyn: the docs' recipe (docs/using-in-solvers.md,
"Joints at interfaces in exudyn") on the bundled conrod, as a gravity pendulum.

The block between `# --- snippet 1` and `# --- end` is the docs' code block line for line
(tests/docs_snippets.rs checks it and runs this script): a revolute joint about z at the
BIG_END interface of the default (mean-axis, free) file, built from point constraints only —
the spider centre held in x y z (a spherical joint) and z held at two bore nodes. The bore is an
RBE2 spider, so its nodes move rigidly with the centre: u = u_c + theta x r. With u_c = 0 and
u_z = 0 at two bore nodes whose offsets r are not parallel, theta_x = theta_y = 0: the joint is
an exact revolute, and costs three one-node markers.

After the snippet the script swings the rod from rest (horizontal, gravity -y) and prints the
small end's position at the end and its deflection relative to the pinned end (the elastic
displacement of the SMALL_END centre minus the rigid motion of the BIG_END spider, from the
file's translational and rotational mode shapes).

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


# revolute about z at BIG_END: its centre node held in x y z (a spherical joint), and z held at
# two bore nodes off the axis in different directions (no tilt about x or y)
big_end = obj["interfaces"][0]
bore = big_end["dependentNodes"]
offset = xref[bore] - xref[big_end["node"]]
hold(big_end["node"], [1, 1, 1])
hold(bore[int(np.argmax(offset[:, 0]))], [0, 0, 1])
hold(bore[int(np.argmax(offset[:, 1]))], [0, 0, 1])
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
