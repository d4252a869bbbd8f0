"""Checks a `flexbody export --to exudyn` NPZ with exudyn itself (run by tests/export_exudyn.rs).

1. exudyn.FEM.ObjectFFRFreducedOrderInterface.LoadFromFile reads it.
2. exudyn's own constructor (ObjectFFRFreducedOrderInterface(femInterface)) recomputes the
   inertia terms from the exported nodes, nodal masses and mode shapes; they must equal the
   exported ones (from the file's invariants) to 1e-12 relative to each term's largest entry.
3. Free vibration of each of the first 3 flexible modes in an exudyn simulation of the
   ObjectFFRFreducedOrder (free floating body, initial modal coordinate): the frequency from the
   simulated modal coordinate, corrected for the trapezoidal rule's known period error
   (theta = 2 atan(omega h / 2) per step), equals the stored one to 1e-6.

4. With the .flexbody file as a second argument (read by format-spec/reference_reader.py):
   stress modes in exudyn's component order xx yy zz yz xz xy, the damping matrix diag(2 zeta
   omega), the flexible-mode frequencies, and the 6-node triangles' mid nodes at their edges'
   middles in exudyn's order (edges 0-1, 1-2, 2-0).

usage: exudyn_export_check.py BODY.npz [BODY.flexbody]
Prints one line per measured figure; exits non-zero on any failure.
"""
import sys

import numpy as np
import scipy.sparse as sp

import exudyn as exu
import exudyn.itemInterface as eii
from exudyn.FEM import FEMinterface, ObjectFFRFreducedOrderInterface

npz = sys.argv[1]
failures = []


def check(name, value, limit):
    ok = value <= limit
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {value:.3e} (limit {limit:.0e})")
    if not ok:
        failures.append(name)


# 1. exudyn's loader
cms = ObjectFFRFreducedOrderInterface()
cms.LoadFromFile(npz)
raw = np.load(npz, allow_pickle=True)
m = int(cms.nModes)
n = int(cms.nNodes)
print(f"loaded {npz}: {n} nodes, {m} flexible modes, {len(cms.trigList)} triangles")
assert cms.modeBasis.shape == (3 * n, m)
assert all(t >= 0 and t < n for tri in cms.trigList for t in tri)

# 2. exudyn's own inertia terms from nodes, nodal masses and shapes
fem = FEMinterface()
fem.nodes = {"Position": cms.xRef.reshape(n, 3)}
fem.modeBasis = {"matrix": cms.modeBasis, "type": "flexbody"}
fem.massMatrix = sp.diags(np.repeat(raw["nodalMass"], 3)).tocsr()
fem.stiffnessMatrix = sp.csr_matrix((3 * n, 3 * n))
fem.surface = [{"Name": "surface", "Trigs": np.array(cms.trigList)[:, :3]}]
ref = ObjectFFRFreducedOrderInterface(fem)
for key in [
    "massMatrixReduced",
    "inertiaLocal",
    "Mtt",
    "totalMass",
    "chiU",
    "mPsiTildePsi",
    "mPsiTildePsiTilde",
    "mPhitTPsi",
    "mPhitTPsiTilde",
    "mXRefTildePsi",
    "mXRefTildePsiTilde",
]:
    ours = np.asarray(getattr(cms, key), dtype=float)
    theirs = np.asarray(getattr(ref, key), dtype=float)
    assert ours.shape == theirs.shape, (key, ours.shape, theirs.shape)
    # Terms that vanish for mean-axis modes (I3, I4) are compared to the body's scale.
    scale = {
        "mPhitTPsi": cms.totalMass,
        "mPhitTPsiTilde": cms.totalMass,
        "chiU": np.abs(cms.xRef).max(),
        "mXRefTildePsi": np.sqrt(np.abs(np.asarray(cms.inertiaLocal)).max() * cms.totalMass),
    }.get(key, np.abs(theirs).max())
    check(f"exudyn recomputed {key} (rel.)", np.abs(ours - theirs).max() / scale, 1e-12)

# 3. free vibration of the first 3 flexible modes
freq = raw["eigenFrequenciesHz"]
for j in range(min(3, m)):
    omega = 2 * np.pi * freq[j]
    h = (2 * np.pi / omega) / 40  # 40 steps per period
    steps = 400
    mbs = exu.SystemContainer().AddSystem()
    obj = cms.AddObjectFFRFreducedOrder(mbs, positionRef=[0, 0, 0], gravity=[0, 0, 0])
    q0 = [0.0] * m
    # A small amplitude (1e-6 of the body's size per unit modal mass) keeps the FFRF terms,
    # quadratic in the modal velocities, far below the tolerance.
    q0[j] = 1e-6 * np.abs(cms.xRef).max() * np.sqrt(cms.totalMass)
    mbs.SetNodeParameter(obj["nGenericODE2"], "initialCoordinates", q0)
    sensor = mbs.AddSensor(
        eii.SensorNode(nodeNumber=obj["nGenericODE2"], storeInternal=True,
                       outputVariableType=exu.OutputVariableType.Coordinates)
    )
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = steps
    s.timeIntegration.endTime = steps * h
    s.timeIntegration.generalizedAlpha.useNewmark = True
    s.timeIntegration.generalizedAlpha.newmarkBeta = 0.25
    s.timeIntegration.generalizedAlpha.newmarkGamma = 0.5
    s.timeIntegration.generalizedAlpha.useIndex2Constraints = True
    s.timeIntegration.newton.relativeTolerance = 1e-14
    s.timeIntegration.newton.absoluteTolerance = 1e-20
    s.timeIntegration.verboseMode = 0
    if hasattr(s, "solution"):  # exudyn >= 1.13 names
        s.solution.file.write = False
        s.solution.sensors.writePeriod = h
    else:
        s.solutionSettings.writeSolutionToFile = False
        s.solutionSettings.sensorsWritePeriod = h
    exu.SolveDynamic(mbs, s)
    data = mbs.GetSensorStoredData(sensor)
    q = data[:, 1 + j]
    # A sampled sinusoid satisfies q[k+1] + q[k-1] = 2 cos(theta) q[k] exactly.
    cos_theta = np.dot(q[1:-1], q[2:] + q[:-2]) / (2 * np.dot(q[1:-1], q[1:-1]))
    theta = np.arccos(cos_theta)
    omega_sim = 2 / h * np.tan(theta / 2)  # undo the trapezoidal rule's period error
    others = np.abs(np.delete(data[:, 1:], j, axis=1)).max() / np.abs(q).max()
    print(f"mode {j + 1}: stored {freq[j]:.9f} Hz, simulated {omega_sim / 2 / np.pi:.9f} Hz; "
          f"other modes' amplitude {others:.1e}")
    check(f"free vibration mode {j + 1} frequency (rel.)", abs(omega_sim / omega - 1), 1e-6)

# 4. against the .flexbody file itself
if len(sys.argv) > 2:
    import os

    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "format-spec"))
    import reference_reader as rr

    with open(sys.argv[2], "rb") as f:
        body, _ = rr.read_bytes(f.read())
    modes = body["modes.bin"]
    M = len(modes["omega2"])
    flex = [j for j in range(M) if modes["labels"][j] != "Rigid"]
    check("flexible-mode frequencies (abs. Hz)",
          np.abs(np.array([modes["frequency_hz"][j] for j in flex]) - freq).max(), 0.0)
    if "stress_shapes.bin" in body:
        st = body["stress_shapes.bin"]
        K = len(st["nodes"])
        vals = np.array(st["values"]).reshape(M, K, 6)  # file: xx yy zz xy yz zx
        want = np.zeros((n, 6 * m))
        for i, j in enumerate(flex):
            for q, node in enumerate(st["nodes"]):
                xx, yy, zz, xy, yz, zx = vals[j, q]
                want[node, 6 * i:6 * i + 6] = [xx, yy, zz, yz, zx, xy]  # exudyn's order
        got = cms.postProcessingModes["matrix"]
        assert str(cms.postProcessingModes["outputVariableType"]) == "OutputVariableType.StressLocal"
        check("stress modes in exudyn's order (rel.)", np.abs(got - want).max() / np.abs(want).max(), 0.0)
    if "damping.bin" in body:
        zeta = np.array([body["damping.bin"]["ratio"][j] for j in flex])
        om = np.sqrt([modes["omega2"][j] for j in flex])
        d = raw["dampingMatrixReduced"]
        check("damping matrix diag(2 zeta omega) (rel.)",
              np.abs(d - np.diag(2 * zeta * om)).max() / (2 * zeta * om).max(), 1e-15)
    # the interfaces' dependent (bore) nodes: the file's interfaces.bin, flat with offsets
    itf = body.get("interfaces.bin") or []
    off, idx = raw["interfaceDependentOffsets"], raw["interfaceDependentNodeIndices"]
    ids, node_ids = raw["interfaceDependentNodeIds"], raw["nodeIds"]
    names, kinds = str(raw["interfaceNames"]).split("\n"), str(raw["interfaceKinds"]).split("\n")
    bad = int(len(off) != len(itf) + 1 or off[0] != 0 or len(names) != len(itf) or len(kinds) != len(itf))
    for k, rec in enumerate(itf):
        want_ids = np.array(rec["dependent"], dtype=np.int64)
        bad += int(not np.array_equal(ids[off[k]:off[k + 1]], want_ids))
        got = idx[off[k]:off[k + 1]]
        stored = got >= 0
        bad += int(not np.array_equal(node_ids[got[stored]], want_ids[stored]))
        bad += int(names[k] != rec["name"]) + int(kinds[k] != rec["kind"])
        print(f"interface {k} {names[k]} ({kinds[k]}): {len(want_ids)} dependent nodes, "
              f"{int(stored.sum())} stored")
    check("interfaces' dependent nodes differing from the file's interfaces.bin", bad, 0)
    # What the bore nodes are for: an RBE2 bore moves rigidly with its centre, u_i - u_c =
    # theta x r_i, so a least-squares fit over the NPZ's bore nodes (translations only) gives the
    # centre's rotation per mode — equal to the file's rotational shapes of the centre node.
    all_shapes = np.array(modes["shapes"]).reshape(M, n, 6)
    worst = 0.0
    for k, rec in enumerate(itf):
        got = idx[off[k]:off[k + 1]]
        if rec["kind"] != "Rbe2" or len(got) < 3 or (got < 0).any():
            continue
        c = int(raw["interfaceNodeIndices"][k])
        x = cms.xRef.reshape(n, 3)
        r = x[got] - x[c]
        skew = np.zeros((len(got), 3, 3))
        skew[:, 0, 1], skew[:, 0, 2], skew[:, 1, 2] = -r[:, 2], r[:, 1], -r[:, 0]
        skew -= skew.transpose(0, 2, 1)
        basis = cms.modeBasis.reshape(n, 3, m)
        theta, *_ = np.linalg.lstsq(-skew.reshape(-1, 3), (basis[got] - basis[[c]]).reshape(-1, m), rcond=None)
        want = all_shapes[flex][:, c, 3:].T
        worst = max(worst, float(np.abs(theta - want).max() / np.abs(want).max()))
    check("RBE2 centre rotations fitted over the NPZ's bore nodes vs the file's rotational shapes (rel.)",
          worst, 1e-12)
    trig = np.array(cms.trigList)
    if trig.shape[1] == 6:
        x = cms.xRef.reshape(n, 3)
        worst = 0.0
        for e, (a, b) in enumerate([(0, 1), (1, 2), (2, 0)]):
            mid = 0.5 * (x[trig[:, a]] + x[trig[:, b]])
            length = np.linalg.norm(x[trig[:, a]] - x[trig[:, b]], axis=1)
            worst = max(worst, (np.linalg.norm(x[trig[:, 3 + e]] - mid, axis=1) / length).max())
        check("6-node triangles: mid node off its edge's middle (rel. to edge length)", worst, 0.1)

if failures:
    print("FAILED:", ", ".join(failures))
    sys.exit(1)
print("all exudyn checks passed")
