"""flexbody's `--engine slepc` on PETSc/SLEPc, run as
`mpirun -np N python3 slepc_engine.py DIR COUNT TOL SHIFT UPPER`.

Reads K and M from DIR (PETSc binary, written by flexbody; for a Craig-Bampton interior these are
K_ii and M_ii, and DIR/Kib.petsc holds K_ib). Factors K - SHIFT*M once with MUMPS (Cholesky,
inside SLEPc's shift-and-invert spectral transformation) and with that one factorization
  * when Kib.petsc exists, solves K X = K_ib column by column (at SHIFT = 0: flexbody's
    constraint modes are Psi = -X),
  * finds the COUNT eigenpairs of K x = lambda M x nearest SHIFT (below the spectrum: the lowest)
    with SLEPc's Krylov-Schur (generalized Hermitian problem, relative tolerance TOL);
    with UPPER a number (a band, lambda <= UPPER) and every one of them <= UPPER, the count is
    doubled and the eigenproblem solved again (same factorization) until one lies above UPPER
    or the whole problem is found. UPPER `none`: a count only.
Writes DIR/values.txt (one eigenvalue per line, 17 digits, ascending), DIR/vectors.petsc (the
eigenvectors as consecutive PETSc Vecs, same order) and DIR/psi.petsc (the columns of X), and
prints one JSON line of timings and solver facts. Any failure exits non-zero with the reason on
stderr.
"""
import json
import os
import sys
import time

import petsc4py

petsc4py.init(sys.argv[:1])
from petsc4py import PETSc  # noqa: E402
import slepc4py  # noqa: E402

slepc4py.init(sys.argv[:1])
from slepc4py import SLEPc  # noqa: E402

folder, count, tol, shift = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
upper = None if sys.argv[5] == "none" else float(sys.argv[5])
comm = PETSc.COMM_WORLD
t0 = time.perf_counter()


def load(name):
    viewer = PETSc.Viewer().createBinary(f"{folder}/{name}", "r", comm=comm)
    a = PETSc.Mat().create(comm=comm)
    a.setType(PETSc.Mat.Type.AIJ)
    a.load(viewer)
    viewer.destroy()
    return a


k, m = load("K.petsc"), load("M.petsc")
kib = load("Kib.petsc") if os.path.exists(f"{folder}/Kib.petsc") else None
k.setOption(PETSc.Mat.Option.SYMMETRIC, True)
m.setOption(PETSc.Mat.Option.SYMMETRIC, True)
n = k.getSize()[0]
t_read = time.perf_counter() - t0

eps = SLEPc.EPS().create(comm=comm)
eps.setOperators(k, m)
eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
eps.setType(SLEPc.EPS.Type.KRYLOVSCHUR)
eps.setDimensions(count, PETSc.DECIDE, PETSc.DECIDE)
eps.setTolerances(tol, 1000)
eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
eps.setTarget(shift)
st = eps.getST()
st.setType(SLEPc.ST.Type.SINVERT)
st.setShift(shift)
ksp = st.getKSP()
ksp.setType(PETSc.KSP.Type.PREONLY)
pc = ksp.getPC()
pc.setType(PETSc.PC.Type.CHOLESKY)
pc.setFactorSolverType("mumps")
eps.setFromOptions()
t1 = time.perf_counter()
eps.setUp()  # the one MUMPS factorization of K - shift M, inside the ST
t_factor = time.perf_counter() - t1

t_constraint = 0.0
if kib is not None:
    # constraint modes with the same factorization (shift 0: K_ii itself)
    t2 = time.perf_counter()
    x, b = k.createVecs()
    psi_viewer = PETSc.Viewer().createBinary(f"{folder}/psi.petsc", "w", comm=comm)
    for c in range(kib.getSize()[1]):
        kib.getColumnVector(c, b)
        ksp.solve(b, x)
        x.view(psi_viewer)
    psi_viewer.destroy()
    t_constraint = time.perf_counter() - t2

t3 = time.perf_counter()
nev, runs, its = count, 0, 0
while True:
    eps.setDimensions(nev, PETSc.DECIDE, PETSc.DECIDE)
    eps.solve()
    runs += 1
    its += eps.getIterationNumber()
    nconv = eps.getConverged()
    if nconv < nev:
        sys.stderr.write(f"SLEPc converged {nconv} of {nev} eigenpairs\n")
        sys.exit(3)
    values = sorted((eps.getEigenvalue(i).real, i) for i in range(nev))
    if upper is None or values[-1][0] > upper or 2 * nev >= n:
        break
    nev = min(2 * nev, n - 1)
t_eigen = time.perf_counter() - t3

vec_viewer = PETSc.Viewer().createBinary(f"{folder}/vectors.petsc", "w", comm=comm)
xr, _ = k.createVecs()
for _, i in values:
    eps.getEigenvector(i, xr)
    xr.view(vec_viewer)
vec_viewer.destroy()
if comm.getRank() == 0:
    with open(f"{folder}/values.txt", "w") as f:
        f.write("".join(f"{v:.17e}\n" for v, _ in values))
    print(json.dumps({"ranks": comm.getSize(), "read_s": t_read, "factor_s": t_factor,
                      "constraint_s": t_constraint, "eigen_s": t_eigen, "eigen_runs": runs,
                      "converged": nconv, "iterations": its,
                      "total_s": time.perf_counter() - t0}))
