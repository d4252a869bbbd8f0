"""Regenerate `solid186_full.cdb` and `solid186_full.json`: a reference for SOLID186 with full
integration (KEYOPT(2)=1) and for the archived SOLID95, computed here independently of flexbody
with numpy.

ANSYS forms SOLID186's stiffness with KEYOPT(2)=1 on 14 points and with KEYOPT(2)=0 on 2 x 2 x 2,
its mass on the same 14 points (MAPDL Theory Reference §13.186; the 14-point mass is also what
the K and M of ansys-mapdl-reader's file.full show, tests/ansys_archive.rs). The 14-point rule
on [-1, 1]^3 is Irons' (Int. J. Numer. Meth. Eng. 3 (1971) 213): the six points (±b, 0, 0)… with
weight 320/361 and the eight (±c, ±c, ±c) with weight 121/361, b² = 19/30, c² = 19/33.

The mesh: a steel cantilever 0.6 x 0.1 x 0.1 m of 3 x 2 x 2 twenty-node bricks with curved
(moved) mid-side nodes and skewed corners, clamped at x = 0. The json holds its first 8
frequencies (Hz) with the stiffness on 14 points (KEYOPT(2)=1), on 2 x 2 x 2 (KEYOPT(2)=0) and,
for contrast, on 3 x 3 x 3 (what KEYOPT(2)=1 would be with the standard Gauss rule); all with
the 14-point mass. SOLID95 (MAPDL Archived Elements Theory Reference §1.17) forms stiffness and
mass on "14 if KEYOPT(11) = 0, 2 x 2 x 2 if KEYOPT(11) = 1": KEYOPT(11)=0 is the first list,
and the json's `solid95_keyopt11_1_gauss2` holds the frequencies with stiffness and mass both on
2 x 2 x 2.

Usage: python3 solid186_full.py (numpy).
"""
import json

import numpy as np

E, NU, RHO = 2.1e11, 0.3, 7850.0
NX, NY, NZ, LX, B, H = 3, 2, 2, 0.6, 0.1, 0.1

# ANSYS's 20-node order: corners I J K L (ζ = -1), M N O P (ζ = +1), mid-sides Q R S T, U V W X,
# then the vertical ones Y Z A B
CORNERS = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
           (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
         (0, 4), (1, 5), (2, 6), (3, 7)]
NAT = CORNERS + [tuple((a + b) / 2 for a, b in zip(CORNERS[i], CORNERS[j])) for i, j in EDGES]


def shape(p):
    """The 20-node serendipity functions and their natural derivatives at p."""
    n, dn = np.zeros(20), np.zeros((20, 3))
    for a, r in enumerate(NAT):
        if a < 8:
            f = [1 + r[k] * p[k] for k in range(3)]
            s = sum(r[k] * p[k] for k in range(3)) - 2
            n[a] = f[0] * f[1] * f[2] * s / 8
            for k in range(3):
                o = [f[m] for m in range(3) if m != k]
                dn[a, k] = r[k] * o[0] * o[1] * (s + f[k]) / 8
        else:
            k0 = [k for k in range(3) if r[k] == 0][0]
            o1, o2 = [k for k in range(3) if k != k0]
            f1, f2 = 1 + r[o1] * p[o1], 1 + r[o2] * p[o2]
            b = 1 - p[k0] ** 2
            n[a] = b * f1 * f2 / 4
            dn[a, k0] = -2 * p[k0] * f1 * f2 / 4
            dn[a, o1] = b * r[o1] * f2 / 4
            dn[a, o2] = b * f1 * r[o2] / 4
    return n, dn


def gauss(m):
    x, w = np.polynomial.legendre.leggauss(m)
    return [((x[i], x[j], x[k]), w[i] * w[j] * w[k])
            for i in range(m) for j in range(m) for k in range(m)]


def irons14():
    b, c = np.sqrt(19 / 30), np.sqrt(19 / 33)
    pts = []
    for k in range(3):
        for s in (-1, 1):
            p = [0.0, 0.0, 0.0]
            p[k] = s * b
            pts.append((tuple(p), 320 / 361))
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                pts.append(((sx * c, sy * c, sz * c), 121 / 361))
    return pts


def elasticity():
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    d = np.zeros((6, 6))
    d[:3, :3] = lam
    d[range(3), range(3)] += 2 * mu
    d[3:, 3:] = mu * np.eye(3)
    return d


def element(x, krule, mrule):
    d = elasticity()
    k, m = np.zeros((60, 60)), np.zeros((60, 60))
    for p, w in krule:
        _, dn = shape(p)
        j = dn.T @ x
        g = dn @ np.linalg.inv(j).T
        bm = np.zeros((6, 60))
        for a in range(20):
            gx, gy, gz = g[a]
            c = 3 * a
            bm[0, c], bm[1, c + 1], bm[2, c + 2] = gx, gy, gz
            bm[3, c], bm[3, c + 1] = gy, gx
            bm[4, c + 1], bm[4, c + 2] = gz, gy
            bm[5, c], bm[5, c + 2] = gz, gx
        k += bm.T @ d @ bm * w * np.linalg.det(j)
    for p, w in mrule:
        n, dn = shape(p)
        ms = np.outer(n, n) * RHO * w * np.linalg.det(dn.T @ x)
        for c in range(3):
            m[c::3, c::3] += ms
    return k, m


def mesh():
    """Nodes (id → xyz) and elements (20 ids each, ANSYS's order)."""
    ids, coords, elements = {}, [], []

    def place(p):
        # lattice point p in half-cells → a skewed, curved brick
        x, y, z = LX * p[0] / (2 * NX), B * p[1] / (2 * NY), H * p[2] / (2 * NZ)
        return (x + (0.01 * y / B + 0.004 * np.sin(7 * z / H)) * (p[0] > 0),
                y + 0.006 * np.sin(3 * x / LX) + 0.003 * (p[1] % 2) * (p[0] % 2),
                z + 0.004 * x / LX * (z / H))

    def nid(p):
        if p not in ids:
            ids[p] = len(ids) + 1
            coords.append(place(p))
        return ids[p]

    for k in range(NZ):
        for j in range(NY):
            for i in range(NX):
                pts = [(2 * i + 1 + r[0], 2 * j + 1 + r[1], 2 * k + 1 + r[2]) for r in NAT]
                elements.append([nid(tuple(int(v) for v in p)) for p in pts])
    return np.array(coords), elements


def frequencies(coords, elements, krule, mrule=None):
    n = 3 * len(coords)
    kg, mg = np.zeros((n, n)), np.zeros((n, n))
    for e in elements:
        ix = np.array([[3 * (v - 1) + c for c in range(3)] for v in e]).ravel()
        k, m = element(coords[np.array(e) - 1], krule, mrule or irons14())
        kg[np.ix_(ix, ix)] += k
        mg[np.ix_(ix, ix)] += m
    free = np.array([i for i in range(n) if abs(coords[i // 3][0]) > 1e-12])
    kf, mf = kg[np.ix_(free, free)], mg[np.ix_(free, free)]
    # the 14-point mass is singular (rank 14 of 20 per brick; 2 x 2 x 2: rank 8): K⁻¹M's largest
    # eigenvalues 1/ω²
    li = np.linalg.inv(np.linalg.cholesky(kf))
    mu = np.sort(np.linalg.eigvalsh(li @ mf @ li.T))[::-1]
    return [float(np.sqrt(1 / v) / (2 * np.pi)) for v in mu[:8]]


if __name__ == "__main__":
    coords, elements = mesh()
    result = {
        "_about": "written by solid186_full.py (numpy): first 8 frequencies (Hz), mass on Irons' 14 points but for solid95_keyopt11_1_gauss2 (mass on 2 x 2 x 2)",
        "keyopt2_1_irons14": frequencies(coords, elements, irons14()),
        "keyopt2_0_gauss2": frequencies(coords, elements, gauss(2)),
        "gauss3_for_contrast": frequencies(coords, elements, gauss(3)),
        "solid95_keyopt11_1_gauss2": frequencies(coords, elements, gauss(2), gauss(2)),
    }
    with open("solid186_full.json", "w") as out:
        json.dump(result, out, indent=2)
        out.write("\n")
    with open("solid186_full.cdb", "w") as out:
        out.write("/COM, written by solid186_full.py\nET,        1,186\nKEYOP,        1, 2,        1\n")
        out.write(f"NBLOCK,6,SOLID,{len(coords):>10},{len(coords):>10}\n(3i9,6e21.13e3)\n")
        for i, p in enumerate(coords):
            out.write(f"{i + 1:>9}{0:>9}{0:>9}" + "".join(f"{v:>21.13E}" for v in p) + "\n")
        out.write("N,R5.3,LOC,       -1,\n")
        out.write(f"EBLOCK,19,SOLID,{len(elements):>10},{len(elements):>10}\n(19i10)\n")
        for eid, e in enumerate(elements):
            head = [1, 1, 1, 1, 0, 0, 0, 0, 20, 0, eid + 1]
            rec = head + e
            out.write("".join(f"{v:>10}" for v in rec[:19]) + "\n")
            out.write("".join(f"{v:>10}" for v in rec[19:]) + "\n")
        out.write("        -1\n")
        out.write("MPTEMP,R5.0, 1, 1,  0.00000000    ,\n")
        for label, v in [("EX", E), ("NUXY", NU), ("DENS", RHO)]:
            out.write(f"MPDATA,R5.0, 1,{label:<4},       1, 1, {v:.16e},\n")
        for i, p in enumerate(coords):
            if abs(p[0]) < 1e-12:
                out.write(f"D,{i + 1},ALL,0\n")
