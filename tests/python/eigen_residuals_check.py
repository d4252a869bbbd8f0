"""The stored eigen residuals recomputed with numpy/SciPy (run by tests/eigen_residuals.rs).

Reads a .flexbody with the numpy package (`flexbody.read`) and the constrained K and M the build
reduced (`build --write-matrices`: Matrix Market and its dof table), puts the file's shapes on
those dofs (node id, component), and computes SPEC §5.17's residual of each stored eigenpair:
r_j = |K phi_j - lambda_j M phi_j| / max(|K phi_j|, 1e-8 s |M phi_j|), s the median of K_ii/M_ii
over the dofs with both > 0. Also s, and |Phi^T M Phi - I|.

usage: eigen_residuals_check.py BODY MATS_DIR
Prints one JSON line: {"max_diff_over_floor" (|r - stored| over the rounding floor
eps |K||phi| / denominator), "max_rel_diff_above_floor" (relative, over the modes whose residual
is above 1000 floors), "modes", "scale", "scale_stored", "max_rel_diff", "max_abs_diff",
"residuals", "stored", "orthonormality"}.
"""
import json
import sys

import numpy as np
import scipy.io

import flexbody

body = flexbody.read(sys.argv[1])
folder = sys.argv[2]
k = scipy.io.mmread(f"{folder}/K.mtx").tocsr()  # "symmetric" files come back with both triangles
m = scipy.io.mmread(f"{folder}/M.mtx").tocsr()
rows = [line.split() for line in open(f"{folder}/dofs.txt") if not line.startswith("#")]
index = {int(i): p for p, i in enumerate(body.node_ids)}
node = np.array([index[int(r[1])] for r in rows])
comp = np.array([int(r[2]) - 1 for r in rows])
(problem,) = body.eigen_residuals
assert problem["kind"] == "NormalModes", problem["kind"]
lam = problem["omega2"]
phi = body.shapes[:, node, comp].T  # dofs x modes
kd, md = k.diagonal(), m.diagonal()
ok = (kd > 0) & (md > 0)
ratios = np.sort(kd[ok] / md[ok])
s = float(ratios[len(ratios) // 2])  # the upper median, as SPEC §5.17 defines it
kphi, mphi = k @ phi, m @ phi
r = np.linalg.norm(kphi - mphi * lam, axis=0) / np.maximum(
    np.linalg.norm(kphi, axis=0), 1e-8 * s * np.linalg.norm(mphi, axis=0))
stored = problem["residual"]
# the rounding of |K phi - lambda M phi|: eps |K| |phi| over the same denominator
denominator = np.maximum(np.linalg.norm(kphi, axis=0), 1e-8 * s * np.linalg.norm(mphi, axis=0))
floor = np.finfo(float).eps * np.linalg.norm(abs(k) @ abs(phi), axis=0) / denominator
print(json.dumps({
    "max_diff_over_floor": float(np.max(np.abs(r - stored) / floor)),
    "max_rel_diff_above_floor": float(np.max(np.abs(r - stored) / stored * (stored > 1e3 * floor))),
    "modes": len(lam),
    "scale": s,
    "scale_stored": problem["scale"],
    "max_rel_diff": float(np.max(np.abs(r - stored) / stored)),
    "max_abs_diff": float(np.max(np.abs(r - stored))),
    "residuals": r.tolist(),
    "stored": stored.tolist(),
    "orthonormality": float(np.max(np.abs(phi.T @ mphi - np.eye(len(lam))))),
}))
