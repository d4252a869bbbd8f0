"""Issue 36's acceptance (run by tests/docs_snippets.rs): the conrod pendulum with the docs'
revolute recipe (examples/joints_exudyn.py, run here as it stands) equals exudyn's own
Hurty-Craig-Bampton pendulum with reference conditions at the big end.

The reference is exudyn's, not ours: `FEMinterface.ComputeHurtyCraigBamptonModes` (RBE2 static
modes, the first boundary excluded = the body frame attached to the big-end bore) on the
conrod's K and M (`flexbody export --to mtx --spider none`: the bare mesh, every bore node free),
boundaries = the file's two bore node lists, as many fixed-interface modes as the file's
Craig-Bampton build kept (so both span the same subspace); `ObjectFFRFreducedOrderInterface(fem)`
computes its own inertia terms; the pin is a revolute (GenericJoint, rotation z free) on the
floating frame's node, exact because the bore has no deformation in that frame. Same gravity,
integrator and end time. Compared: the small end's position (mean of its 240 bore nodes, the same
mesh nodes in both bodies) at T_END, relative to its distance from the pin; and the difference
against the pin-relative elastic deflection, so the figure says how much of the elastic effect
differs.

With a --reference-conditions build of the conrod (frame at the BIG_END centre) as a fourth
argument, the same pendulum with a revolute on that body's frame node against the same reference.
Then exudyn's built-in gravity in the attached frame: the clamped HCB body's static modal
coordinates equal K^-1 Psi^T M g (the modal gravity load is applied). Last, the docs' other two
recipes as the example runs them: the rigid joint's static sag of the small end against the
clamped HCB body's, and the prismatic joint's free slide (F t^2 / 2m) without rotation.

usage: revolute_hcb_check.py conrod.flexbody MESH_DIR T_END [conrod_rc.flexbody]
   (python/ on PYTHONPATH)
Prints one line per measured figure; exits non-zero on any failure.
"""
import csv
import os
import runpy
import sys
import time

import numpy as np
import scipy.io

import exudyn.itemInterface as eii
import exudyn as exu
from exudyn.FEM import FEMinterface, HCBstaticModeSelection, ObjectFFRFreducedOrderInterface

body_path, mesh, t_end = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
rc_path = os.path.abspath(sys.argv[4]) if len(sys.argv) > 4 else None
example = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "joints_exudyn.py")
failures = []


def check(name, value, limit):
    ok = value <= limit
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {value:.3e} (limit {limit:.0e})")
    if not ok:
        failures.append(name)


# ours: the docs' recipe, as the example runs it
sys.argv = [example, body_path, t_end]
ours = runpy.run_path(example, run_name="__main__")
tip, small_end, big_end = ours["tip"], ours["small_end"], ours["big_end"]
file = ours["file"]

# the reference: exudyn's HCB on the bare mesh's K, M
clock = time.perf_counter()
k = scipy.io.mmread(os.path.join(mesh, "K.mtx")).tocsr()  # symmetric files come back whole
m = scipy.io.mmread(os.path.join(mesh, "M.mtx")).tocsr()
with open(os.path.join(mesh, "coords.csv")) as f:
    rows = list(csv.reader(f))[1:]
ids = [int(r[0]) for r in rows]
dofs = np.loadtxt(os.path.join(mesh, "dofs.txt"), dtype=np.int64, comments="#")
assert np.array_equal(dofs[:, 1], np.repeat(ids, 3)) and np.array_equal(dofs[:, 2], np.tile([1, 2, 3], len(ids)))
at = {node_id: i for i, node_id in enumerate(ids)}
fem = FEMinterface()
fem.nodes = {"Position": np.array([[float(v) for v in r[1:]] for r in rows])}
fem.stiffnessMatrix, fem.massMatrix = k, m
fixed_interface = int(np.sum(np.asarray(file.labels) == "FixedInterface"))
fem.ComputeHurtyCraigBamptonModes(boundaryNodesList=[[at[i] for i in big_end["dependentIds"]],
                                                     [at[i] for i in small_end["dependentIds"]]],
                                  nEigenModes=fixed_interface, useSparseSolver=True,
                                  computationMode=HCBstaticModeSelection.RBE2, timerTreshold=10**9)
cms = ObjectFFRFreducedOrderInterface(fem)
print(f"exudyn HCB: {cms.nModes} modes (6 static + {fixed_interface} fixed-interface) of {k.shape[0]} dofs "
      f"in {time.perf_counter() - clock:.1f} s")
mbs = exu.SystemContainer().AddSystem()
ref = cms.AddObjectFFRFreducedOrder(mbs, positionRef=[0, 0, 0], gravity=[0, -9.81, 0])
ref["interface"] = cms
ground = mbs.AddObject(eii.ObjectGround())
on_ground = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
on_frame = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=ref["nRigidBody"]))
mbs.AddObject(eii.GenericJoint(markerNumbers=[on_ground, on_frame], constrainedAxes=[1, 1, 1, 1, 1, 0]))
mbs.Assemble()
clock = time.perf_counter()
exu.SolveDynamic(mbs, ours["settings"](float(t_end)))
print(f"reference pendulum solved in {time.perf_counter() - clock:.2f} s; ours in {ours['solve_seconds']:.2f} s")
tip_ref = ours["global_positions"](mbs, ref, [at[i] for i in small_end["dependentIds"]]).mean(axis=0)
pin = file.xyz[big_end["node"]]
difference = float(np.linalg.norm(tip - tip_ref))
deflection = float(np.linalg.norm(ours["relative"][-1]))
print(f"small end at t = {t_end} s: recipe {tip}, exudyn HCB {tip_ref}; difference {difference:.3e} m; "
      f"pin-relative elastic deflection now {deflection:.3e} m")
check("recipe's revolute pendulum vs exudyn's HCB pendulum: small end position (relative)",
      difference / float(np.linalg.norm(tip_ref - pin)), 1e-6)
check("the same difference as a share of the pin-relative elastic deflection", difference / deflection, 0.1)

# the same pendulum from a --reference-conditions build (frame attached at the BIG_END centre)
# with the revolute on its frame node, when given
if rc_path is not None:
    import flexbody.exudyn

    mbs_rc = exu.SystemContainer().AddSystem()
    rc = flexbody.exudyn.add_body(mbs_rc, rc_path, gravity=[0, -9.81, 0])
    ground = mbs_rc.AddObject(eii.ObjectGround())
    on_ground = mbs_rc.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
    on_frame = mbs_rc.AddMarker(eii.MarkerNodeRigid(nodeNumber=rc["nRigidBody"]))
    mbs_rc.AddObject(eii.GenericJoint(markerNumbers=[on_ground, on_frame], constrainedAxes=[1, 1, 1, 1, 1, 0]))
    mbs_rc.Assemble()
    exu.SolveDynamic(mbs_rc, ours["settings"](float(t_end)))
    tip_rc = ours["global_positions"](mbs_rc, rc, rc["interfaces"][1]["dependentNodes"]).mean(axis=0)
    check("--reference-conditions build with a frame-node revolute vs exudyn's HCB pendulum (m)",
          float(np.linalg.norm(tip_rc - tip_ref)), 1e-11)

# exudyn's built-in gravity in the attached (HCB) frame: the body clamped at its frame node, the
# static modal coordinates K^-1 Psi^T M g (Psi^T M = mPhitTPsi^T) — the modal gravity load is there
mbs_g = exu.SystemContainer().AddSystem()
held = cms.AddObjectFFRFreducedOrder(mbs_g, positionRef=[0, 0, 0], gravity=[0, -9.81, 0])
held["interface"] = cms
ground = mbs_g.AddObject(eii.ObjectGround())
on_ground = mbs_g.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
on_frame = mbs_g.AddMarker(eii.MarkerNodeRigid(nodeNumber=held["nRigidBody"]))
mbs_g.AddObject(eii.GenericJoint(markerNumbers=[on_ground, on_frame], constrainedAxes=[1, 1, 1, 1, 1, 1]))
mbs_g.Assemble()
static = exu.SimulationSettings()
static.staticSolver.verboseMode = 0
exu.SolveStatic(mbs_g, static)
q_static = np.array(mbs_g.GetNodeOutput(held["nGenericODE2"], exu.OutputVariableType.Coordinates))
q_exact = np.linalg.solve(cms.stiffnessMatrixReduced, cms.mPhitTPsi.T @ np.array([0, -9.81, 0]))
check("built-in gravity in the attached frame: static modal coordinates vs K^-1 Psi^T M g (relative)",
      float(np.linalg.norm(q_static - q_exact) / np.linalg.norm(q_exact)), 1e-12)

# the docs' rigid joint (block 4, default file, node-based) against the clamped HCB body: the
# small end's static sag under gravity
small_ref = [at[i] for i in small_end["dependentIds"]]
sag_ref = (ours["global_positions"](mbs_g, held, small_ref) - fem.nodes["Position"][small_ref]).mean(axis=0)
print(f"rigid joint: small end's sag {ours['sag']} m; exudyn's clamped HCB body {sag_ref} m")
check("docs' rigid joint vs exudyn's clamped HCB body: small end's static sag (relative)",
      float(np.linalg.norm(ours["sag"] - sag_ref) / np.linalg.norm(sag_ref)), 1e-5)

# the docs' prismatic joint (block 3): pushed by 1 N along x it slides as a free mass and turns
# only elastically (a free pendulum turns 0.1 rad in 0.05 s)
check("docs' prismatic joint: slide vs F t^2 / 2m (relative)", float(ours["slide_error"]), 1e-6)
check("docs' prismatic joint: rotation of the frame (largest entry of A - I)", float(ours["slide_turn"]), 1e-5)

if failures:
    print("FAILED:", ", ".join(failures))
    sys.exit(1)
print("revolute acceptance passed")
