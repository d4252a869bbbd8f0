"""The bundled steel connecting rod as a flexible gravity pendulum in exudyn.

From the FE model to a plot, in three steps:

1. `flexbody build` reduces fixtures/models/conrod/conrod.inp (Craig-Bampton on the two bores,
   RBE2 spiders to their centre nodes, 2 % modal damping);
2. `flexbody export --to exudyn` writes the NPZ that exudyn's
   ObjectFFRFreducedOrderInterface.LoadFromFile reads (flexible modes only);
3. exudyn simulates the rod pinned at the big-end centre node (a spherical joint on the
   interface node), released horizontally under gravity; the plot shows the small end's elastic
   deflection in the body frame (the modal part of its motion), its deflection relative to the
   pinned end (the big-end bore's rigid motion subtracted, from the NPZ's bore node list) and
   the swing angle.

usage: python3 examples/pendulum_exudyn.py [OUT.png]
   (default OUT.png: pendulum_exudyn.png in the current folder; the plot in the docs is made
   with `python3 examples/pendulum_exudyn.py docs/pendulum_exudyn.png`)
   (FLEXBODY=path/to/flexbody; default target/release/flexbody, built by `cargo build --release`)
Needs exudyn, numpy, matplotlib (pip install exudyn matplotlib). Runs in a few seconds.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

import exudyn as exu
import exudyn.itemInterface as eii
from exudyn.FEM import ObjectFFRFreducedOrderInterface

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
flexbody = os.environ.get("FLEXBODY", os.path.join(root, "target", "release", "flexbody"))
png = sys.argv[1] if len(sys.argv) > 1 else "pendulum_exudyn.png"
work = tempfile.mkdtemp(prefix="flexbody-pendulum-")
body = os.path.join(work, "conrod.flexbody")
npz = os.path.join(work, "conrod.npz")

# 1. build, 2. export
subprocess.run([flexbody, "build", os.path.join(root, "fixtures/models/conrod/conrod.inp"),
                "--interface", "BIG_END,SMALL_END", "--fmax", "3000", "--units", "si",
                "--damping", "2%", "-q", "-o", body], check=True)
subprocess.run([flexbody, "export", body, "--to", "exudyn", "-o", npz], check=True)

# 3. exudyn
cms = ObjectFFRFreducedOrderInterface()
cms.LoadFromFile(npz)
data = np.load(npz, allow_pickle=True)
big_end, small_end = (int(i) for i in data["interfaceNodeIndices"])  # in --interface order
print(f"{cms.nNodes} nodes, {cms.nModes} flexible modes "
      f"({', '.join(f'{f:.0f}' for f in data['eigenFrequenciesHz'][:4])} ... Hz); "
      f"pivot node {data['nodeIds'][big_end]}, small-end node {data['nodeIds'][small_end]}")

SC = exu.SystemContainer()
mbs = SC.AddSystem()
g = [0, -9.81, 0]
obj = cms.AddObjectFFRFreducedOrder(mbs, positionRef=[0, 0, 0], gravity=g)
ffrf = obj["oFFRFreducedOrder"]
# The file's modal damping: ObjectFFRFreducedOrder's reduced damping matrix.
damping = exu.MatrixContainer()
damping.SetWithDenseMatrix(data["dampingMatrixReduced"], useDenseMatrix=False)
mbs.SetObjectParameter(ffrf, "dampingMatrixReduced", damping)

# Pin: a spherical joint between ground and the big-end interface (spider centre) node.
ground = mbs.AddObject(eii.ObjectGround(referencePosition=[0, 0, 0]))
m_ground = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground,
                                                localPosition=list(cms.xRef[3 * big_end:3 * big_end + 3])))
m_pivot = mbs.AddMarker(eii.MarkerSuperElementPosition(bodyNumber=ffrf, meshNodeNumbers=[big_end],
                                                       weightingFactors=[1.0]))
mbs.AddObject(eii.SphericalJoint(markerNumbers=[m_ground, m_pivot]))

s_modal = mbs.AddSensor(eii.SensorNode(nodeNumber=obj["nGenericODE2"], storeInternal=True,
                                       outputVariableType=exu.OutputVariableType.Coordinates))
s_rot = mbs.AddSensor(eii.SensorNode(nodeNumber=obj["nRigidBody"], storeInternal=True,
                                     outputVariableType=exu.OutputVariableType.RotationMatrix))
mbs.Assemble()

t_end, h = 0.25, 2e-5
s = exu.SimulationSettings()
s.timeIntegration.numberOfSteps = int(round(t_end / h))
s.timeIntegration.endTime = t_end
s.timeIntegration.generalizedAlpha.spectralRadius = 0.9
s.timeIntegration.newton.useModifiedNewton = True
s.timeIntegration.verboseMode = 0
if hasattr(s, "solution"):
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 1e-4
else:
    s.solutionSettings.writeSolutionToFile = False
    s.solutionSettings.sensorsWritePeriod = 1e-4
exu.SolveDynamic(mbs, s)

q = mbs.GetSensorStoredData(s_modal)
rot = mbs.GetSensorStoredData(s_rot)
t = q[:, 0]
psi = cms.modeBasis[3 * small_end:3 * small_end + 3, :]
deflection = (psi @ q[:, 1:].T).T * 1e6  # µm, body frame
angle = np.degrees(np.arctan2(rot[:, 1 + 3], rot[:, 1 + 0]))  # body x axis, from +x towards +y
stretch = (psi - cms.modeBasis[3 * big_end:3 * big_end + 3, :]) @ q[:, 1:].T * 1e6  # µm
print(f"swing angle at t = {t[-1]:.3f} s: {angle[-1]:.3f} deg; small end's transverse "
      f"deflection in the body frame: max |v| = {np.abs(deflection[:, 1]).max():.4f} um; "
      f"rod stretch (small end - big end, body x): max {np.abs(stretch[0]).max():.4f} um")

# Deflection relative to the pinned end. The mean-axis frame moves the pin too; relative to the
# big end, subtract its spider's rigid motion u_c + theta x r. The bore nodes (NPZ key
# interfaceDependentNodeIndices) move rigidly with the centre (RBE2): u_i - u_c = -skew(r_i) theta,
# so theta per unit modal coordinate is a least-squares fit over them (exact for the RBE2 bore).
offsets = data["interfaceDependentOffsets"]
bore = data["interfaceDependentNodeIndices"][offsets[0]:offsets[1]]
modes_of = lambda nodes: cms.modeBasis.reshape(-1, 3, cms.nModes)[nodes]  # (nodes, 3, modes)
x_ref = cms.xRef.reshape(-1, 3)
r_bore = x_ref[bore] - x_ref[big_end]
skew = np.zeros((len(bore), 3, 3))
skew[:, 0, 1], skew[:, 0, 2], skew[:, 1, 2] = -r_bore[:, 2], r_bore[:, 1], -r_bore[:, 0]
skew -= skew.transpose(0, 2, 1)
fit = -skew.reshape(-1, 3)                                  # u_i - u_c = fit @ theta
rigid_bore = (modes_of(bore) - modes_of([big_end])).reshape(-1, cms.nModes)
theta_modes, *_ = np.linalg.lstsq(fit, rigid_bore, rcond=None)  # (3, modes)
fit_residual = np.linalg.norm(fit @ theta_modes - rigid_bore) / np.linalg.norm(rigid_bore)
arm = x_ref[small_end] - x_ref[big_end]
relative_modes = modes_of([small_end])[0] - modes_of([big_end])[0] - np.cross(theta_modes.T, arm).T
pinned = (relative_modes @ q[:, 1:].T).T * 1e6             # µm, relative to the pinned end
print(f"small end's transverse deflection relative to the pinned end: max |v| = "
      f"{np.abs(pinned[:, 1]).max():.4f} um (the big-end bore's rigid fit over {len(bore)} nodes: "
      f"residual {fit_residual:.1e})")

# Reference: the rigid physical pendulum with the file's mass properties (the elastic part
# changes the swing by far less than the plotted resolution): J phi'' = -m g d cos(phi).
from scipy.integrate import solve_ivp

m, c = float(cms.totalMass), np.asarray(cms.chiU)
pivot = cms.xRef[3 * big_end:3 * big_end + 3]
i_origin = np.asarray(cms.inertiaLocal)
r_c, r_p = c, c - pivot
j_pivot = (i_origin[2, 2] - m * (r_c[0] ** 2 + r_c[1] ** 2)) + m * (r_p[0] ** 2 + r_p[1] ** 2)
d = np.hypot(r_p[0], r_p[1])
phi0 = np.arctan2(r_p[1], r_p[0])
ref = solve_ivp(lambda _, y: [y[1], -m * 9.81 * d * np.cos(y[0] + phi0) / j_pivot], [0, t[-1]],
                [0.0, 0.0], t_eval=t, rtol=1e-12, atol=1e-14)
rigid = np.degrees(ref.y[0])
print(f"rigid pendulum from the file's mass properties: {rigid[-1]:.3f} deg at t = {t[-1]:.3f} s; "
      f"largest difference to exudyn's flexible body: {np.abs(rigid - angle).max():.2e} deg")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(7, 5.5))
ax1.plot(t, angle, color="k", label="exudyn, flexible body")
ax1.plot(t[::100], rigid[::100], "o", mfc="none", color="C3", label="rigid pendulum (file's I1, I2, I7)")
ax1.legend()
ax1.set_ylabel("swing angle [deg]")
ax1.set_title("bundled conrod in exudyn (flexbody build + export), pinned at the big end", fontsize=10)
ax1.grid(True, alpha=0.3)
ax2.plot(t, deflection[:, 1], label="small end, transverse (body y, mean-axis frame)")
ax2.plot(t, pinned[:, 1], label="small end, transverse, relative to the pinned end")
ax2.plot(t, stretch[0], label="rod stretch: small end - big end (body x)")
ax2.set_xlabel("time [s]")
ax2.set_ylabel("elastic deflection [µm]")
ax2.legend()
ax2.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(png, dpi=110)
print(f"wrote {png}")
