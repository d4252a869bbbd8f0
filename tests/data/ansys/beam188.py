"""Regenerate `beam188_frame.cdb`/`.json` and `beam189_frame.cdb`/`.json`: references for BEAM188
with linear shape functions (KEYOPT(3)=0) and BEAM189, computed here independently of flexbody
with numpy from what the MAPDL Theory Reference §13.188 and §13.189 state:

- displacements u, v, w and rotations θx, θy, θz interpolated linearly between I and J
  (equations 11-6…11-11);
- Timoshenko kinematics (first-order shear deformation): generalized strains ε = u', the
  torsion κx = θx', the curvatures κy = θy', κz = θz', the shear strains γxy = v' − θz and
  γxz = w' + θy, with the section rigidities EA, GJ, EIyy, EIzz, k_y GA, k_z GA;
- the stiffness integrated on 1 point along the length, the consistent mass on 2 points with
  the section's translational (ρA + added mass) and rotary (ρIyy, ρIzz, ρ(Iyy + Izz)) inertia,
  the lumped mass from the translations' functions only (equations 11-6…11-8);
- BEAM189: the same strains with quadratic functions through I, the mid node and J (equations
  11-19…11-24), the stiffness on 2 points, the consistent mass on 3;
- the element x axis from I to J, its z axis in the plane of I, J and the orientation node K,
  toward K (what VM2's input shows: K at +y, the I section's strong axis bending under face-1
  pressure deflecting along global y), y = z × x.

Section constants: RECT B × H (B along y): A = BH, Iyy = BH³/12, Izz = HB³/12, J by
Saint-Venant's series; CTUBE Ri, Ro: A = π(Ro² − Ri²), I = π(Ro⁴ − Ri⁴)/4, J = 2I; ASEC the
values given; shear factors Cowper's (rectangle 10(1+ν)/(12+11ν), tube
6(1+ν)(1+m²)²/((7+6ν)(1+m²)² + (20+12ν)m²), m = Ri/Ro) and 1 for ASEC.

The frame (BEAM189: the same, a mid node at each element's middle): three skewed elements 1-2-3-4 of three sections (RECT with an added mass, CTUBE,
ASEC), each with its own orientation node, clamped at node 1. The json holds the free dofs
(node, component 0…5) and the assembled K, consistent M and lumped M over them.

Usage: python3 beam188.py (numpy).
"""
import json

import numpy as np

E, NU, RHO = 2.1e11, 0.29, 7800.0
G = E / (2 * (1 + NU))
NODES = {1: (0.0, 0.0, 0.0), 2: (0.31, 0.07, -0.02), 3: (0.55, 0.21, 0.13), 4: (0.62, 0.48, 0.22),
         101: (0.1, 0.4, 0.3), 102: (0.2, -0.3, 0.5), 103: (1.0, 0.3, -0.4)}
ELEMENTS = [(1, 2, 101, 1), (2, 3, 102, 2), (3, 4, 103, 3)]  # I, J, K, section
RECT = (0.03, 0.05)
CTUBE = (0.012, 0.02)
ASEC = (6.1e-4, 4.2e-8, 0.0, 7.3e-8, 0.0, 5.5e-8)  # A, Iyy, Iyz, Izz, Iw, J
ADDMAS = 0.7  # on the RECT section (mass per length)


def rect_torsion(b, h):
    a, c = max(b, h), min(b, h)
    n = np.arange(1, 200, 2, dtype=float)
    return a * c ** 3 * (1 / 3 - 64 / np.pi ** 5 * (c / a) * np.sum(np.tanh(n * np.pi * a / (2 * c)) / n ** 5))


def sections():
    b, h = RECT
    kr = 10 * (1 + NU) / (12 + 11 * NU)
    ri, ro = CTUBE
    m2 = (ri / ro) ** 2
    kt = 6 * (1 + NU) * (1 + m2) ** 2 / ((7 + 6 * NU) * (1 + m2) ** 2 + (20 + 12 * NU) * m2)
    it = np.pi * (ro ** 4 - ri ** 4) / 4
    a, iyy, _, izz, _, j = ASEC
    # A, Iyy, Izz, J, k_y, k_z, added mass
    return {1: (b * h, b * h ** 3 / 12, h * b ** 3 / 12, rect_torsion(b, h), kr, kr, ADDMAS),
            2: (np.pi * (ro ** 2 - ri ** 2), it, it, 2 * it, kt, kt, 0.0),
            3: (a, iyy, izz, j, 1.0, 1.0, 0.0)}


def frame(i, j, k):
    xi, xj, xk = (np.array(NODES[n]) for n in (i, j, k))
    ex = (xj - xi) / np.linalg.norm(xj - xi)
    t = xk - xi
    ez = t - t.dot(ex) * ex
    ez /= np.linalg.norm(ez)
    ey = np.cross(ez, ex)
    return np.array([ex, ey, ez]), np.linalg.norm(xj - xi)


def element(i, j, k, sec, lumped):
    a, iyy, izz, jt, ky, kz, addmas = sec
    r, length = frame(i, j, k)
    d = np.diag([E * a, G * jt, E * iyy, E * izz, ky * G * a, kz * G * a])
    kl = np.zeros((12, 12))
    ml = np.zeros((12, 12))

    def n_and_b(s):
        """Shape functions' matrix N (6 x 12) and strain matrix B (6 x 12) at s in [0, 1]."""
        n = [1 - s, s]
        dn = [-1 / length, 1 / length]
        nm = np.zeros((6, 12))
        bm = np.zeros((6, 12))
        for a_ in range(2):
            o = 6 * a_
            nm[:, o:o + 6] = n[a_] * np.eye(6)
            bm[0, o + 0] = dn[a_]            # u'
            bm[1, o + 3] = dn[a_]            # θx'
            bm[2, o + 4] = dn[a_]            # θy'
            bm[3, o + 5] = dn[a_]            # θz'
            bm[4, o + 1] = dn[a_]            # v' − θz
            bm[4, o + 5] = -n[a_]
            bm[5, o + 2] = dn[a_]            # w' + θy
            bm[5, o + 4] = n[a_]
        return nm, bm

    _, b = n_and_b(0.5)  # one point along the length, weight L
    kl += length * b.T @ d @ b
    mu = np.diag([RHO * a + addmas] * 3 + [RHO * (iyy + izz), RHO * iyy, RHO * izz])
    if lumped:
        mu_t = np.diag([RHO * a + addmas] * 3 + [0.0] * 3)
        for s in (0.0, 1.0):  # nodal quadrature of the translations' functions
            nm, _ = n_and_b(s)
            ml += 0.5 * length * nm.T @ mu_t @ nm
    else:
        for g in (-1 / np.sqrt(3), 1 / np.sqrt(3)):  # two Gauss points
            nm, _ = n_and_b(0.5 * (1 + g))
            ml += 0.5 * length * nm.T @ mu @ nm
    t = np.kron(np.eye(4), r)
    return t.T @ kl @ t, t.T @ ml @ t


def element189(i, j, k, sec):
    a, iyy, izz, jt, ky, kz, addmas = sec
    r, length = frame(i, j, k)
    d = np.diag([E * a, G * jt, E * iyy, E * izz, ky * G * a, kz * G * a])
    mu = np.diag([RHO * a + addmas] * 3 + [RHO * (iyy + izz), RHO * iyy, RHO * izz])
    kl = np.zeros((18, 18))
    ml = np.zeros((18, 18))

    def n_and_b(xi):
        # nodes I (xi = -1), J (xi = 1), mid (xi = 0)
        n = [xi * (xi - 1) / 2, xi * (xi + 1) / 2, 1 - xi * xi]
        dn = [(xi - 0.5) * 2 / length, (xi + 0.5) * 2 / length, -2 * xi * 2 / length]
        nm = np.zeros((6, 18))
        bm = np.zeros((6, 18))
        for a_ in range(3):
            o = 6 * a_
            nm[:, o:o + 6] = n[a_] * np.eye(6)
            bm[0, o + 0] = dn[a_]
            bm[1, o + 3] = dn[a_]
            bm[2, o + 4] = dn[a_]
            bm[3, o + 5] = dn[a_]
            bm[4, o + 1] = dn[a_]
            bm[4, o + 5] = -n[a_]
            bm[5, o + 2] = dn[a_]
            bm[5, o + 4] = n[a_]
        return nm, bm

    xs, ws = np.polynomial.legendre.leggauss(2)
    for xi, w in zip(xs, ws):
        _, b = n_and_b(xi)
        kl += w * length / 2 * b.T @ d @ b
    xs, ws = np.polynomial.legendre.leggauss(3)
    for xi, w in zip(xs, ws):
        nm, _ = n_and_b(xi)
        ml += w * length / 2 * nm.T @ mu @ nm
    t = np.kron(np.eye(6), r)
    return t.T @ kl @ t, t.T @ ml @ t


def assemble189():
    secs = sections()
    ids = [1, 2, 3, 4, 11, 12, 13]  # corners, then the mid nodes of elements 1, 2, 3
    n = 6 * len(ids)
    k = np.zeros((n, n))
    m = np.zeros((n, n))
    for e, (i, j, o, s) in enumerate(ELEMENTS):
        ke, me = element189(i, j, o, secs[s])
        nodes = [i, j, 11 + e]
        dofs = [6 * ids.index(q) + c for q in nodes for c in range(6)]
        k[np.ix_(dofs, dofs)] += ke
        m[np.ix_(dofs, dofs)] += me
    free = list(range(6, n))
    return ids[1:], k[np.ix_(free, free)], m[np.ix_(free, free)]


def assemble(lumped):
    secs = sections()
    ids = [1, 2, 3, 4]
    n = 6 * len(ids)
    k = np.zeros((n, n))
    m = np.zeros((n, n))
    for i, j, o, s in ELEMENTS:
        ke, me = element(i, j, o, secs[s], lumped)
        dofs = [6 * ids.index(i) + c for c in range(6)] + [6 * ids.index(j) + c for c in range(6)]
        k[np.ix_(dofs, dofs)] += ke
        m[np.ix_(dofs, dofs)] += me
    free = list(range(6, n))  # node 1 clamped
    return k[np.ix_(free, free)], m[np.ix_(free, free)]


def write_cdb(path, quadratic=False):
    nodes = dict(NODES)
    if quadratic:
        for e, (i, j, _, _) in enumerate(ELEMENTS):
            nodes[11 + e] = tuple((a + b) / 2 for a, b in zip(NODES[i], NODES[j]))
    with open(path, "w") as out:
        out.write(f"/COM, written by beam188.py\n/PREP7\nET,        1,{189 if quadratic else 188}\n")
        out.write(f"MPTEMP,R5.0, 1, 1,  0.00000000    ,\n")
        for lab, v in (("EX  ", E), ("NUXY", NU), ("DENS", RHO)):
            out.write(f"MPDATA,R5.0, 1,{lab},       1, 1, {v:.16e},\n")
        out.write(f"SECTYPE,       1,BEAM,RECT,rect,   0\nSECOFFSET, CENT\n")
        out.write(f"SECDATA,{RECT[0]!r},{RECT[1]!r},2,2\nSECCONTROL,0,0,{ADDMAS!r}\n")
        out.write(f"SECTYPE,       2,BEAM,CTUBE,tube,   0\nSECOFFSET, CENT\n")
        out.write(f"SECDATA,{CTUBE[0]!r},{CTUBE[1]!r},16\n")
        out.write(f"SECTYPE,       3,BEAM,ASEC,asec,   0\nSECOFFSET, CENT\n")
        out.write("SECDATA," + ",".join(repr(v) for v in ASEC) + "\n")
        out.write(f"NBLOCK,6,SOLID,{len(nodes):>10},{len(nodes):>10}\n(3i9,6e21.13e3)\n")
        for nid, x in sorted(nodes.items()):
            out.write(f"{nid:9d}{0:9d}{0:9d}" + "".join(f"{v:21.13E}" for v in x) + "\n")
        out.write("N,R5.3,LOC,       -1,\n")
        out.write(f"EBLOCK,19,SOLID,{len(ELEMENTS):>10},{len(ELEMENTS):>10}\n(19i10)\n")
        for e, (i, j, k, s) in enumerate(ELEMENTS, start=1):
            fields = [1, 1, 1, s, 0, 0, 0, 0, 3, 0, e, i, j, k]
            if quadratic:
                fields = [1, 1, 1, s, 0, 0, 0, 0, 4, 0, e, i, j, 10 + e, k]
            out.write("".join(f"{v:10d}" for v in fields) + "\n")
        out.write(f"{-1:10d}\n")
        out.write("D,1,ALL,0\n")


def main():
    write_cdb("beam188_frame.cdb")
    k, m = assemble(False)
    _, ml = assemble(True)
    dofs = [(n, c) for n in (2, 3, 4) for c in range(6)]
    with open("beam188_frame.json", "w") as out:
        json.dump({"dofs": dofs, "K": k.tolist(), "M": m.tolist(), "M_lumped": ml.tolist()}, out)
    write_cdb("beam189_frame.cdb", quadratic=True)
    ids, k, m = assemble189()
    dofs = [(n, c) for n in ids for c in range(6)]
    with open("beam189_frame.json", "w") as out:
        json.dump({"dofs": dofs, "K": k.tolist(), "M": m.tolist()}, out)
    # the one-point cantilever: n elements, tip load P, deflection PL³/(3EI)(1 − 1/(4n²)) + PL/(kGA)
    a, _, izz, _, ky, _, _ = sections()[1]
    for n in (1, 2, 4):
        length = 1.0
        h = length / n
        kk = np.zeros((2 * n + 2, 2 * n + 2))
        for e in range(n):
            b = np.array([-1 / h, -0.5, 1 / h, -0.5])  # (v1, θz1, v2, θz2) shear at the centre
            kb = np.array([[0, 0, 0, 0], [0, 1, 0, -1], [0, 0, 0, 0], [0, -1, 0, 1]]) * E * izz / h
            ke = kb + ky * G * a * h * np.outer(b, b)
            kk[2 * e:2 * e + 4, 2 * e:2 * e + 4] += ke
        f = np.zeros(2 * n + 2)
        f[-2] = 1.0
        u = np.linalg.solve(kk[2:, 2:], f[2:])
        want = length ** 3 / (3 * E * izz) * (1 - 1 / (4 * n * n)) + length / (ky * G * a)
        print(f"n = {n}: tip {u[-2]:.15e}, closed form {want:.15e}, {abs(u[-2] / want - 1):.1e}")


if __name__ == "__main__":
    main()
