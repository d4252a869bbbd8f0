#!/usr/bin/env python3
"""Decks for the real-file rows of python/README.md's speed table (benchmark input, not tests):

    python3 python/bench/make_decks.py tet10 72 14 14 block.inp   # free tet10 block, 6 tets/brick
    python3 python/bench/make_decks.py plate 200 plate.bdf        # free CQUAD4 plate
    flexbody build block.inp --method normal --modes 20 --units si [--stress-modes] -o block.flexbody
    python3 python/bench/read_speed.py --file block.flexbody

tet10: a 0.5 x 0.1 x 0.1 m steel block of nx x ny x nz bricks, each split into 6 tets along its
main diagonal (conforming), C3D10 with mid-side nodes on the 2x grid. plate: 1 m square, 5 mm
steel, n x n CQUAD4.
"""
import itertools
import sys


def tet10(nx, ny, nz, out):
    size = (0.5, 0.1, 0.1)
    dims = (2 * nx + 1, 2 * ny + 1, 2 * nz + 1)

    def nid(i, j, k):
        return 1 + i + dims[0] * (j + dims[1] * k)

    with open(out, "w") as f:
        f.write("*NODE, NSET=NALL\n")
        for k, j, i in itertools.product(range(dims[2]), range(dims[1]), range(dims[0])):
            xyz = [size[d] * (i, j, k)[d] / (dims[d] - 1) for d in range(3)]
            f.write(f"{nid(i, j, k)}, {xyz[0]!r}, {xyz[1]!r}, {xyz[2]!r}\n")
        f.write("*ELEMENT, TYPE=C3D10, ELSET=EALL\n")
        e = 0
        for k, j, i in itertools.product(range(nz), range(ny), range(nx)):
            for perm in itertools.permutations(range(3)):
                v = [(0, 0, 0)]
                for a in perm:
                    p = list(v[-1])
                    p[a] += 1
                    v.append(tuple(p))
                c = [(2 * i + 2 * q[0], 2 * j + 2 * q[1], 2 * k + 2 * q[2]) for q in v]
                a_, b_, w = ([c[n][d] - c[0][d] for d in range(3)] for n in (1, 2, 3))
                cross = (a_[1] * b_[2] - a_[2] * b_[1], a_[2] * b_[0] - a_[0] * b_[2],
                         a_[0] * b_[1] - a_[1] * b_[0])
                if sum(cross[d] * w[d] for d in range(3)) < 0:  # corner 4 above face 1-2-3
                    c[1], c[2] = c[2], c[1]

                def mid(p, q):
                    return tuple((c[p][d] + c[q][d]) // 2 for d in range(3))

                nodes = c + [mid(0, 1), mid(1, 2), mid(2, 0), mid(0, 3), mid(1, 3), mid(2, 3)]
                e += 1
                f.write(f"{e}, " + ", ".join(str(nid(*p)) for p in nodes) + "\n")
        f.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n210e9, 0.3\n*DENSITY\n7850\n"
                "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n")
    print(f"{out}: {dims[0] * dims[1] * dims[2]} nodes, {e} C3D10")


def plate(n, out):
    with open(out, "w") as f:
        f.write("SOL 103\nCEND\nBEGIN BULK\n")
        for j, i in itertools.product(range(n + 1), range(n + 1)):
            f.write(f"GRID,{1 + i + (n + 1) * j},,{i / n!r},{j / n!r},0.0\n")
        e = 0
        for j, i in itertools.product(range(n), range(n)):
            a = 1 + i + (n + 1) * j
            e += 1
            f.write(f"CQUAD4,{e},1,{a},{a + 1},{a + n + 2},{a + n + 1}\n")
        f.write("PSHELL,1,1,0.005,1,,1\nMAT1,1,2.1e11,,0.3,7850.0\nENDDATA\n")
    print(f"{out}: {(n + 1) ** 2} nodes, {e} CQUAD4")


if __name__ == "__main__":
    if len(sys.argv) == 6 and sys.argv[1] == "tet10":
        tet10(*map(int, sys.argv[2:5]), sys.argv[5])
    elif len(sys.argv) == 4 and sys.argv[1] == "plate":
        plate(int(sys.argv[2]), sys.argv[3])
    else:
        sys.exit(__doc__)
