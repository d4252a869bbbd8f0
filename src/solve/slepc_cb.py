"""The fixed-interface part of a Craig-Bampton reduction on PETSc/SLEPc (flexbody's
`--engine slepc`, run under `mpirun -np N python3 slepc_cb.py DIR COUNT TOL`).

Reads K_ii, M_ii and K_ib from DIR (PETSc binary, written by flexbody), factors K_ii once with
MUMPS (Cholesky), and with that one factorization
  * solves K_ii X = K_ib column by column (flexbody's constraint modes are Psi = -X),
  * finds the COUNT lowest eigenpairs of K_ii x = lambda M_ii x with SLEPc's Krylov-Schur,
    shift-and-invert at sigma = 0 (generalized Hermitian problem, relative tolerance TOL).
Writes DIR/values.txt (one eigenvalue per line, 17 digits), DIR/vectors.petsc (the M-normalized
eigenvectors as consecutive PETSc Vecs) and DIR/psi.petsc (the columns of X), and prints one
JSON line of timings and solver facts. Any failure exits non-zero with the reason on stderr.
"""
import json
import sys
import time

import petsc4py

petsc4py.init(sys.argv[:1])
from petsc4py import PETSc  # noqa: E402
import slepc4py  # noqa: E402

slepc4py.init(sys.argv[:1])
from slepc4py import SLEPc  # noqa: E402

folder, count, tol = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
comm = PETSc.COMM_WORLD
t0 = time.perf_counter()


def load(name):
    viewer = PETSc.Viewer().createBinary(f"{folder}/{name}", "r", comm=comm)
    a = PETSc.Mat().create(comm=comm)
    a.setType(PETSc.Mat.Type.AIJ)
    a.load(viewer)
    viewer.destroy()
    return a


kii, mii, kib = load("Kii.petsc"), load("Mii.petsc"), load("Kib.petsc")
kii.setOption(PETSc.Mat.Option.SPD, True)
mii.setOption(PETSc.Mat.Option.SYMMETRIC, True)
t_read = time.perf_counter() - t0

eps = SLEPc.EPS().create(comm=comm)
eps.setOperators(kii, mii)
eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
eps.setType(SLEPc.EPS.Type.KRYLOVSCHUR)
eps.setDimensions(count, PETSc.DECIDE, PETSc.DECIDE)
eps.setTolerances(tol, 1000)
eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
eps.setTarget(0.0)
st = eps.getST()
st.setType(SLEPc.ST.Type.SINVERT)
st.setShift(0.0)
ksp = st.getKSP()
ksp.setType(PETSc.KSP.Type.PREONLY)
pc = ksp.getPC()
pc.setType(PETSc.PC.Type.CHOLESKY)
pc.setFactorSolverType("mumps")
eps.setFromOptions()
t1 = time.perf_counter()
eps.setUp()  # the one MUMPS factorization of K_ii - 0 M_ii, inside the ST
t_factor = time.perf_counter() - t1

# constraint modes with the same factorization
t2 = time.perf_counter()
nb = kib.getSize()[1]
x, b = kii.createVecs()
psi_viewer = PETSc.Viewer().createBinary(f"{folder}/psi.petsc", "w", comm=comm)
for c in range(nb):
    kib.getColumnVector(c, b)
    ksp.solve(b, x)
    x.view(psi_viewer)
psi_viewer.destroy()
t_constraint = time.perf_counter() - t2

t3 = time.perf_counter()
eps.solve()
t_eigen = time.perf_counter() - t3
nconv = eps.getConverged()
if nconv < count:
    sys.stderr.write(f"SLEPc converged {nconv} of {count} eigenpairs\n")
    sys.exit(3)
values = []
vec_viewer = PETSc.Viewer().createBinary(f"{folder}/vectors.petsc", "w", comm=comm)
xr, _ = kii.createVecs()
for i in range(count):
    lam = eps.getEigenpair(i, xr)
    values.append(lam.real)
    xr.view(vec_viewer)
vec_viewer.destroy()
if comm.getRank() == 0:
    with open(f"{folder}/values.txt", "w") as f:
        f.write("".join(f"{v:.17e}\n" for v in values))
    its = eps.getIterationNumber()
    print(json.dumps({"ranks": comm.getSize(), "read_s": t_read, "factor_s": t_factor,
                      "constraint_s": t_constraint, "eigen_s": t_eigen, "converged": nconv,
                      "iterations": its, "total_s": time.perf_counter() - t0}))
