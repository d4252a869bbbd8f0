"""A slider-crank in exudyn: rigid crank, the bundled conrod as a flexible body, rigid slider.

1. `flexbody build` reduces fixtures/models/conrod/conrod.inp (Craig-Bampton on both bores, 2 %
   modal damping) and `flexbody.exudyn.add_body` adds it to exudyn (no NPZ needed);
2. the crank (a rigid flywheel, crank radius r = 40 mm) turns about z at (-r, 0, 0); its pin
   holds the conrod's BIG_END centre node (spherical joint); the slider moves along x
   (prismatic: a GenericJoint holding all but x) and holds the SMALL_END centre node (spherical
   joint). Two spherical joints leave the rod free to spin about the line through its centres,
   so z is also held at one BIG_END bore node off that line (u_z = theta_x r_y = 0 there, exact
   for the RBE2 bore); the rod's tilt about y is held by the two centres' z. The plane is
   horizontal (no gravity); the crank starts at top dead centre (theta = 0, slider at r + l)
   with 3000 rpm and the rod and slider with the matching rigid velocities.
3. The check: the slider's position against the rigid slider-crank's closed form
   x(theta) = r cos(theta) + sqrt(l^2 - r^2 sin^2(theta)) at the simulated crank angle; they
   differ by the rod's elastic stretch dL (the change of its centre distance, from the file's
   mode shapes) times dx/dl = l / sqrt(l^2 - r^2 sin^2(theta)), to first order.

usage: python3 examples/slider_crank_exudyn.py [T_END [OUT.png]]
   (T_END default 0.04 s = two crank turns; the plot, when matplotlib is there and OUT.png is
   given, shows the slider position and the rod's deflection; the docs' plot is
   `python3 examples/slider_crank_exudyn.py 0.04 docs/slider_crank_exudyn.png`)
   (FLEXBODY=path/to/flexbody; default target/release/flexbody; python/ on PYTHONPATH or
   `pip install ./python`)
Needs exudyn and numpy (matplotlib for the plot).
"""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import exudyn as exu
import exudyn.itemInterface as eii
from exudyn.utilities import InertiaCuboid

import flexbody
import flexbody.exudyn

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
flexbody_exe = os.environ.get("FLEXBODY", os.path.join(root, "target", "release", "flexbody"))
t_end = float(sys.argv[1]) if len(sys.argv) > 1 else 0.04
png = sys.argv[2] if len(sys.argv) > 2 else None
work = tempfile.mkdtemp(prefix="flexbody-slider-crank-")
body_path = os.path.join(work, "conrod.flexbody")
subprocess.run([flexbody_exe, "build", os.path.join(root, "fixtures/models/conrod/conrod.inp"),
                "--interface", "BIG_END,SMALL_END", "--fmax", "3000", "--units", "si",
                "--damping", "2%", "-q", "-o", body_path], check=True)
file = flexbody.read(body_path)

r = 0.04                       # crank radius [m]
omega = 2 * np.pi * 50         # 3000 rpm
SC = exu.SystemContainer()
mbs = SC.AddSystem()
ground = mbs.AddObject(eii.ObjectGround())

# the conrod: the file's frame at the FE origin = the BIG_END centre, SMALL_END at (l, 0, 0)
probe = flexbody.exudyn.interface(file)
xref = probe.xRef.reshape(-1, 3)
big_node, small_node = (int(i) for i in probe.flexbody["interfaceNodeIndices"])
l = float(np.linalg.norm(xref[small_node] - xref[big_node]))
rod = flexbody.exudyn.add_body(mbs, file, positionRef=[0, 0, 0], initialVelocity=[0, omega * r, 0],
                               initialAngularVelocity=[0, 0, -omega * r / l])
big_end, small_end = rod["interfaces"]
ffrf = rod["oFFRFreducedOrder"]


def rod_marker(node):
    return mbs.AddMarker(eii.MarkerSuperElementPosition(bodyNumber=ffrf, meshNodeNumbers=[node],
                                                        weightingFactors=[1.0]))


# the crank: a steel flywheel (200 x 200 x 50 mm) turning about z at (-r, 0, 0)
crank = mbs.CreateRigidBody(inertia=InertiaCuboid(7850, [0.2, 0.2, 0.05]),
                            referencePosition=[-r + xref[big_node][0], xref[big_node][1], 0],
                            initialAngularVelocity=[0, 0, omega])
crank_node = mbs.GetObject(crank)["nodeNumber"]
on_ground = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[-r + xref[big_node][0], xref[big_node][1], 0]))
on_crank = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=crank, localPosition=[0, 0, 0]))
mbs.AddObject(eii.GenericJoint(markerNumbers=[on_ground, on_crank], constrainedAxes=[1, 1, 1, 1, 1, 0]))
crank_pin = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=crank, localPosition=[r, 0, xref[big_node][2]]))
mbs.AddObject(eii.SphericalJoint(markerNumbers=[crank_pin, rod_marker(big_node)]))

# the slider: 0.5 kg, moving along x only, holding the SMALL_END centre
slider = mbs.CreateRigidBody(inertia=InertiaCuboid(7850, [0.05, 0.04, 0.032]),
                             referencePosition=list(xref[small_node]))
slider_node = mbs.GetObject(slider)["nodeNumber"]
guide = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=list(xref[small_node])))
on_slider = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=slider, localPosition=[0, 0, 0]))
mbs.AddObject(eii.GenericJoint(markerNumbers=[guide, on_slider], constrainedAxes=[0, 1, 1, 1, 1, 1]))
slider_pin = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=slider, localPosition=[0, 0, 0]))
mbs.AddObject(eii.SphericalJoint(markerNumbers=[slider_pin, rod_marker(small_node)]))

# no spin of the rod about its own axis: z held at the BIG_END bore node farthest off that axis
bore = big_end["dependentNodes"]
off_axis = bore[int(np.argmax(np.abs(xref[bore, 1] - xref[big_node, 1])))]
held_z = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground, localPosition=list(xref[off_axis])))
mbs.AddObject(eii.SphericalJoint(markerNumbers=[held_z, rod_marker(off_axis)], constrainedAxes=[0, 0, 1]))

sensors = {
    "slider": mbs.AddSensor(eii.SensorNode(nodeNumber=slider_node, storeInternal=True,
                                           outputVariableType=exu.OutputVariableType.Position)),
    "crank": mbs.AddSensor(eii.SensorNode(nodeNumber=crank_node, storeInternal=True,
                                          outputVariableType=exu.OutputVariableType.RotationMatrix)),
    "rod": mbs.AddSensor(eii.SensorNode(nodeNumber=rod["nRigidBody"], storeInternal=True,
                                        outputVariableType=exu.OutputVariableType.RotationMatrix)),
    "modal": mbs.AddSensor(eii.SensorNode(nodeNumber=rod["nGenericODE2"], storeInternal=True,
                                          outputVariableType=exu.OutputVariableType.Coordinates)),
}
mbs.Assemble()
s = exu.SimulationSettings()
step = 1e-5
s.timeIntegration.numberOfSteps = int(round(t_end / step))
s.timeIntegration.endTime = t_end
s.timeIntegration.generalizedAlpha.spectralRadius = 0.9
s.timeIntegration.newton.useModifiedNewton = True
s.timeIntegration.verboseMode = 0
s.solution.file.write = False
s.solution.sensors.writePeriod = 5e-5
clock = time.perf_counter()
exu.SolveDynamic(mbs, s)
solve_seconds = time.perf_counter() - clock

x_slider = mbs.GetSensorStoredData(sensors["slider"])
t = x_slider[:, 0]
x = x_slider[:, 1] - (-r + xref[big_node][0])            # from the crank's centre
rot = mbs.GetSensorStoredData(sensors["crank"])[:, 1:]
theta = np.unwrap(np.arctan2(rot[:, 3], rot[:, 0]))      # crank angle: its x axis from +x to +y
rigid = r * np.cos(theta) + np.sqrt(l ** 2 - (r * np.sin(theta)) ** 2)

# the rod's elastic deformation from the file's shapes: stretch dL = change of the centre
# distance, and the small end's transverse deflection relative to the big-end spider
shapes = file.shapes[flexbody.exudyn.flexible_modes(file)]
q = mbs.GetSensorStoredData(sensors["modal"])[:, 1:]
u_b, theta_b, u_s = q @ shapes[:, big_node, :3], q @ shapes[:, big_node, 3:], q @ shapes[:, small_node, :3]
relative = u_s - u_b - np.cross(theta_b, xref[small_node] - xref[big_node])
axis = (xref[small_node] - xref[big_node]) / l
stretch = relative @ axis
transverse = relative[:, 1]
first_order = rigid + stretch * l / np.sqrt(l ** 2 - (r * np.sin(theta)) ** 2)
difference = np.abs(x - rigid).max()
residual = np.abs(x - first_order).max()
# the rod stays in the plane: its frame's z axis stays global z (no spin about its own axis)
spin = float(np.degrees(np.arccos(np.clip(mbs.GetSensorStoredData(sensors["rod"])[:, 9], -1, 1))).max())
print(f"slider-crank to t = {t_end} s ({theta[-1] / (2 * np.pi):.3f} crank turns) in {solve_seconds:.2f} s; "
      f"crank speed {np.degrees(theta[-1] - theta[0]) / 360 / (t[-1] - t[0]) * 60:.1f} rpm on average")
print(f"slider vs rigid closed form: max |x - x_rigid(theta)| = {difference:.3e} m; rod stretch "
      f"max |dL| = {np.abs(stretch).max():.3e} m; after the first-order stretch correction: "
      f"{residual:.3e} m; small end's transverse deflection relative to the big end: max "
      f"{np.abs(transverse).max():.3e} m")
print(f"rod's z axis off global z: max {spin:.3e} deg")

if png:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(7, 5.5))
    ax1.plot(t, x * 1e3, color="k", label="exudyn: slider (flexible conrod)")
    ax1.plot(t[::8], rigid[::8] * 1e3, "o", mfc="none", color="C3", label="rigid slider-crank, closed form")
    ax1.set_ylabel("slider x [mm]")
    ax1.legend(loc="lower right", fontsize=8)
    ax1.set_title("bundled conrod in a slider-crank (exudyn, 3000 rpm, r = 40 mm)", fontsize=10)
    ax1.grid(True, alpha=0.3)
    ax2.plot(t, stretch * 1e6, label="rod stretch dL (centre distance)")
    ax2.plot(t, transverse * 1e6, label="small end transverse, relative to the big end")
    ax2.plot(t, (x - rigid) * 1e6, "--", label="slider: x - x_rigid(theta)")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("elastic effect [µm]")
    ax2.legend(fontsize=8)
    ax2.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    print(f"wrote {png}")
