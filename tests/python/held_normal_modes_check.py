"""Normal modes with reference conditions against SciPy (run by tests/reference_normal_modes.rs).

Reads the constrained K and M of `flexbody export --to mtx --model` (Matrix Market and its dof
table), removes every dof of the held node, solves the lowest eigenpairs with ARPACK
(shift-invert at 0) and compares the frequencies with the file's, given on the command line.

usage: held_normal_modes_check.py MATS_DIR HELD_NODE_ID F1,F2,...
Prints the largest relative difference; exits non-zero above 1e-8.
"""
import sys

import numpy as np
import scipy.io
import scipy.sparse.linalg as sla

folder, held, freqs = sys.argv[1], int(sys.argv[2]), np.array([float(x) for x in sys.argv[3].split(",")])
k = scipy.io.mmread(f"{folder}/K.mtx").tocsc()  # "symmetric" files come back with both triangles
m = scipy.io.mmread(f"{folder}/M.mtx").tocsc()
rows = [line.split() for line in open(f"{folder}/dofs.txt") if not line.startswith("#")]
keep = np.array([i for i, r in enumerate(rows) if int(r[1]) != held])
assert len(keep) < len(rows), f"node {held} is not in the dof table"
kc, mc = k[keep][:, keep], m[keep][:, keep]
w = sla.eigsh(kc, k=len(freqs), M=mc, sigma=0, which="LM", return_eigenvectors=False, tol=1e-12)
f = np.sqrt(np.sort(w)) / (2 * np.pi)
diff = float(np.max(np.abs(f - freqs) / freqs))
print(f"{len(freqs)} modes with node {held} held, {len(keep)} free dofs: max relative difference {diff:.3e}")
sys.exit(0 if diff <= 1e-8 else 1)
