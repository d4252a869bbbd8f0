#!/usr/bin/env python3
"""Benchmark peers of flexbody, run on the inputs the harness writes (see bench/README.md).

One peer per call; prints one JSON object on stdout with per-phase wall times (s), the peak
resident memory of this process (or of the ccx child) in MB, and the eigenvalues found:

  peers.py superlu K.mtx M.mtx MODES        SciPy eigsh shift-invert, sigma = 0, SuperLU factor
  peers.py cholmod K.mtx M.mtx MODES        ARPACK (SciPy eigsh) with a CHOLMOD factor (scikit-sparse)
  peers.py cholmod-factor K.mtx             CHOLMOD (scikit-sparse) analyse + supernodal LLT of K only
                                            (the cb suite's peer row: one f64 factorization of K_ii)
  peers.py hcb K.mtx M.mtx XYZ.txt IFACE.txt MODES
                                            exudyn FEMinterface.ComputeHurtyCraigBamptonModes
                                            (RBE2 static modes, one interface per line of IFACE.txt)
  peers.py ccx JOB.inp                      CalculiX ccx on the deck (a *FREQUENCY step)

Matrices are Matrix Market files with the full symmetric K and M (positive definite K for
superlu/cholmod). Reading the inputs is timed separately ("read") and left out of "total".
Threads: the harness runs the peers with OMP/OPENBLAS threads = 1 unless told otherwise (our
solver runs its dense kernels sequentially too); the value in force is reported.

Setup (Debian bookworm, root): bench/peers/setup.sh
"""

import json
import os
import resource
import subprocess
import sys
import time


def peak_mb(children=False):
    who = resource.RUSAGE_CHILDREN if children else resource.RUSAGE_SELF
    return resource.getrusage(who).ru_maxrss / 1024.0


def threads():
    return {k: os.environ.get(k) for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")}


def read_km(kp, mp):
    import scipy.io
    t = time.perf_counter()
    k = scipy.io.mmread(kp).tocsc()
    m = scipy.io.mmread(mp).tocsc()
    return k, m, time.perf_counter() - t


def arpack(k, m, modes, solve):
    """Lowest `modes` eigenvalues of K x = lam M x by ARPACK shift-invert about 0 with `solve`."""
    from scipy.sparse.linalg import LinearOperator, eigsh
    n = k.shape[0]
    calls = [0]

    def counted(x):
        calls[0] += 1
        return solve(x)

    op = LinearOperator((n, n), matvec=counted, dtype=float)
    vals = eigsh(k, k=modes, M=m, sigma=0.0, which="LM", OPinv=op, tol=1e-10,
                 return_eigenvectors=False)
    return sorted(float(v) for v in vals), calls[0]


def eigen_superlu(kp, mp, modes):
    from scipy.sparse.linalg import splu
    k, m, t_read = read_km(kp, mp)
    t0 = time.perf_counter()
    lu = splu(k)  # SciPy's default COLAMD column ordering, as eigsh(sigma=...) itself does
    t1 = time.perf_counter()
    vals, solves = arpack(k, m, modes, lu.solve)
    t2 = time.perf_counter()
    return {
        "peer": "scipy eigsh shift-invert (ARPACK) + SuperLU",
        "n": k.shape[0],
        "phases_s": {"read": t_read, "analyse_factor": t1 - t0, "eigen": t2 - t1, "total": t2 - t0},
        "solves": solves,
        "peak_rss_mb": peak_mb(),
        "eigenvalues": vals,
    }


def eigen_cholmod(kp, mp, modes):
    from sksparse.cholmod import analyze
    k, m, t_read = read_km(kp, mp)
    t0 = time.perf_counter()
    ordering = os.environ.get("CHOLMOD_ORDERING", "default")
    f = analyze(k, mode="supernodal", ordering_method=ordering)
    t1 = time.perf_counter()
    f.cholesky_inplace(k)
    t2 = time.perf_counter()
    vals, solves = arpack(k, m, modes, f)
    t3 = time.perf_counter()
    return {
        "peer": "ARPACK (scipy eigsh) + CHOLMOD (scikit-sparse)",
        "n": k.shape[0],
        "cholmod_ordering": ordering,
        "phases_s": {"read": t_read, "analyse": t1 - t0, "factor": t2 - t1,
                     "analyse_factor": t2 - t0, "eigen": t3 - t2, "total": t3 - t0},
        "solves": solves,
        "peak_rss_mb": peak_mb(),
        "eigenvalues": vals,
    }


def factor_cholmod(kp):
    import scipy.io
    from sksparse.cholmod import analyze
    t = time.perf_counter()
    k = scipy.io.mmread(kp).tocsc()
    t_read = time.perf_counter() - t
    peak_read = peak_mb()
    t0 = time.perf_counter()
    ordering = os.environ.get("CHOLMOD_ORDERING", "default")
    f = analyze(k, mode="supernodal", ordering_method=ordering)
    t1 = time.perf_counter()
    f.cholesky_inplace(k)
    t2 = time.perf_counter()
    return {
        "peer": "CHOLMOD (scikit-sparse) supernodal LLT, one f64 factorization",
        "n": k.shape[0],
        "nnz_k": int(k.nnz),
        "cholmod_ordering": ordering,
        "phases_s": {"read": t_read, "analyse": t1 - t0, "factor": t2 - t1,
                     "analyse_factor": t2 - t0, "total": t2 - t0},
        "peak_rss_mb": peak_mb(),
        "peak_rss_after_read_mb": peak_read,
    }


def hcb(kp, mp, xyz, iface, modes):
    import numpy as np
    from exudyn.FEM import FEMinterface, HCBstaticModeSelection
    k, m, t_read = read_km(kp, mp)
    fem = FEMinterface()
    fem.nodes = {"Position": np.loadtxt(xyz, ndmin=2)}
    fem.stiffnessMatrix = k.tocsr()
    fem.massMatrix = m.tocsr()
    with open(iface) as fh:
        lists = [[int(s) for s in line.split()] for line in fh if line.strip()]
    t0 = time.perf_counter()
    fem.ComputeHurtyCraigBamptonModes(boundaryNodesList=lists, nEigenModes=modes,
                                      useSparseSolver=True,
                                      computationMode=HCBstaticModeSelection.RBE2,
                                      excludeRigidBodyMotion=False, timerTreshold=10**12)
    t1 = time.perf_counter()
    return {
        "peer": "exudyn FEMinterface.ComputeHurtyCraigBamptonModes (RBE2)",
        "exudyn_version": __import__("exudyn").__version__,
        "n": k.shape[0],
        "phases_s": {"read": t_read, "total": t1 - t0},
        "modes": int(fem.modeBasis["matrix"].shape[1]),
        "peak_rss_mb": peak_mb(),
        "eigenvalues": sorted(float(v) for v in fem.eigenValues),
    }


def ccx(inp):
    job = os.path.splitext(os.path.abspath(inp))[0]
    t0 = time.perf_counter()
    r = subprocess.run(["ccx", "-i", os.path.basename(job)], cwd=os.path.dirname(job),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    t1 = time.perf_counter()
    if r.returncode != 0:
        raise RuntimeError("ccx failed: " + r.stdout[-2000:])
    vals, in_block = [], False
    with open(job + ".dat") as fh:
        for line in fh:
            if "E I G E N V A L U E   O U T P U T" in line:
                in_block = True
                continue
            tok = line.split()
            if in_block and len(tok) == 5 and tok[0].isdigit():
                vals.append(float(tok[1]))
            elif in_block and vals and not tok:
                break
    return {
        "peer": "CalculiX ccx *FREQUENCY",
        "ccx_version": (r.stdout.split("Version")[1].split()[0] if "Version" in r.stdout else "?"),
        "phases_s": {"total": t1 - t0},
        "peak_rss_mb": peak_mb(children=True),
        "eigenvalues": vals,
    }


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    cmd, a = argv[1], argv[2:]
    if cmd == "superlu":
        out = eigen_superlu(a[0], a[1], int(a[2]))
    elif cmd == "cholmod":
        out = eigen_cholmod(a[0], a[1], int(a[2]))
    elif cmd == "cholmod-factor":
        out = factor_cholmod(a[0])
    elif cmd == "hcb":
        out = hcb(a[0], a[1], a[2], a[3], int(a[4]))
    elif cmd == "ccx":
        out = ccx(a[0])
    else:
        sys.exit(__doc__)
    out["threads"] = threads()
    out["loadavg"] = open("/proc/loadavg").read().split()[:3]
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv)
