"""Checks a `flexbody export --to sid` file (run by tests/export_sid.rs).

The .SID_FEM text is parsed here from the layout of Wallrapp's Standard Input Data (blocks
`refmod`, `frame` / `new node`, Taylor terms with `order nrow ncol nq nqn structure` and entries
`m0(row, col)`, `m1(row, mode, col)`, Fortran `D` exponents, omitted entries zero), not from our
writer. Every term is then recomputed from the .flexbody file's stored nodes, nodal masses and
mode shapes (read by format-spec/reference_reader.py) with the rigid-body/flexible coupling
integrals written out directly (sums over the nodes, no invariant used), and compared to 1e-12
relative to the term's largest entry:

  mass = Σ m;  mdCM = Σ m (s + u);  J = Σ m s̃ᵀs̃ + I_p and its first order Σ m (s̃ᵀũ + ũᵀs̃);
  Ct = Σ m φᵀ;  Cr = Σ (m (s̃ φ)ᵀ + (I_p ψ)ᵀ), first order Σ m (φ̃_k φ_j)ᵀ;  Me = Σ m φᵀφ + ψᵀ I_p ψ;
  Gr = −2 Σ m s̃ φ̃_j;  Ge(j, 3k+a) = −2 Σ m (φ_jᵀ φ̃_k)_a;  Oe: ωᵀ S_j ω with
  S_j = Σ m (sym(φ_j sᵀ) − (φ_j·s) E) and its first order S_jk = Σ m (sym(φ_j φ_kᵀ) − φ_j·φ_k E);
  Ke = the file's generalized stiffness; De = 2 ζ ω m; frames: position, φ, ψ, AP = E + ψ̃.
With the file's geometric_stiffness.bin (format 1.7, SPEC §5.16) the first-order terms carry
its K̂_G between the flexible modes on top: Ct¹(r, k, a) = K̂_G of Acceleration(a), Cr¹ + K̂_G of
AngularAcceleration(a), Oe¹ + K̂_G of the column's AngularVelocity product — read from the file
by the reference reader, so the SID terms minus the node sums must equal the file's K̂_G.

This needs every mass node of the model stored in the file (the invariants the exporter uses sum
over all of them): the tests build with all nodes kept.

With welib importable (CI installs it), welib's own `generalizedMassMatrix` (welib.FEM.fem_beam;
welib has a SID writer but no SID reader) recomputes mass, m·c, J, Ct, Cr and Me from a mass
matrix built from the nodal masses and inertias; they must equal the file's SID terms to 1e-12.
Skipped above 3,000 nodes (welib takes a dense mass matrix).

With a third argument, the JSON that tests/python/embslib/sid_dump.c prints after loading the
file with EMBSlib's own SID reader (ReadSID_C.h): EMBSlib's mass, every body term and every
frame's terms must equal this parse to 1e-14 (EMBSlib scales mantissas by pow(10, exponent)).

usage: sid_export_check.py BODY.SID_FEM BODY.flexbody [EMBSLIB_DUMP.json]
Prints one line per measured figure; exits non-zero on any failure.
"""
import re
import sys
from pathlib import Path

import numpy as np

sid_path, body_path = sys.argv[1], sys.argv[2]
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "format-spec"))
import reference_reader as rr  # noqa: E402

failures = []


def check(name, value, limit):
    ok = value <= limit
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {value:.3e} (limit {limit:.0e})")
    if not ok:
        failures.append(name)


def rel(a, b, floor):
    """Largest difference over the term's largest entry, or over `floor` when that is larger:
    terms that vanish for mean-axis modes (Σ m φ, Σ m s̃ φ) are compared with the bound that
    Cauchy–Schwarz gives them, not with their own rounding noise."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert a.shape == b.shape, (a.shape, b.shape)
    scale = max(np.abs(b).max(), floor, 1e-300)
    return float(np.abs(a - b).max() / scale)


# --- the SID text, parsed from the standard's layout ---------------------------------------
NUM = r"[-+]?\d*\.?\d+(?:[DdEe][-+]?\d+)?"


def number(text):
    return float(text.strip().replace("D", "e").replace("d", "e"))


class Term:
    def __init__(self, name):
        self.name, self.head, self.m0, self.m1 = name, {}, {}, {}

    def arrays(self):
        h = self.head
        nrow, ncol, nq, structure = h["nrow"], h["ncol"], h["nq"], h["structure"]
        a0 = np.zeros((nrow, ncol))
        a1 = np.zeros((nrow, nq, ncol))
        if structure == 4:
            a0[:] = np.eye(nrow, ncol)
        for (r, c), v in self.m0.items():
            a0[r - 1, c - 1] = v
            if structure == 2:
                a0[c - 1, r - 1] = v
        for (r, q, c), v in self.m1.items():
            a1[r - 1, q - 1, c - 1] = v
        return a0, a1


def parse_sid(text):
    lines = [ln.strip() for ln in text.splitlines()]
    first = lines[0].split()
    counts = (int(first[0]), int(first[1]))
    sid = {"counts": counts, "frames": [], "terms": {}, "ielastq": []}
    term, node, block = None, None, None
    for ln in lines[1:]:
        if not ln:
            continue
        key = ln.split("=")[0].strip()
        if ln == "refmod":
            block = "refmod"
        elif ln == "end refmod":
            block = None
        elif block == "refmod":
            if key == "mass":
                sid["mass"] = number(ln.split("=", 1)[1])
            elif key == "nelastq":
                sid["nelastq"] = int(ln.split("=", 1)[1])
            elif key.startswith("ielastq"):
                sid["ielastq"].append(ln.split("=", 1)[1].strip())
        elif key == "new node":
            node = {"id": int(ln.split("=", 1)[1]), "terms": {}}
            sid["frames"].append(node)
        elif ln == "end node":
            node = None
        elif key == "rframe":
            node["rframe"] = ln.split("=", 1)[1].strip()
        elif term is None and re.fullmatch(r"[A-Za-z]\w*", ln) and ln not in ("part", "frame"):
            term = Term(ln)
        elif term is not None and ln == f"end {term.name}":
            (node["terms"] if node is not None else sid["terms"])[term.name] = term
            term = None
        elif term is not None:
            m = re.fullmatch(r"(m[01])\(\s*([\d,\s]+)\)\s*=\s*(" + NUM + r")", ln)
            if m:
                idx = tuple(int(x) for x in m.group(2).split(","))
                (term.m0 if m.group(1) == "m0" else term.m1)[idx] = number(m.group(3))
            else:
                k, v = (x.strip() for x in ln.split("="))
                term.head[k] = int(v)
    return sid


sid = parse_sid(Path(sid_path).read_text())
T = {name: t.arrays() for name, t in sid["terms"].items()}
for name in ["mdCM", "J", "Ct", "Cr", "Me", "Gr", "Ge", "Oe", "ksigma", "Ke", "De"]:
    assert name in T, f"term {name} missing"

# --- the file, and the terms recomputed from its nodes ------------------------------------
with open(body_path, "rb") as f:
    body, _ = rr.read_bytes(f.read())
nodes = body["nodes.bin"]
n = len(nodes)
modes = body["modes.bin"]
big_m = len(modes["omega2"])
flex = [j for j, lab in enumerate(modes["labels"]) if lab != "Rigid"]
nq = len(flex)
assert sid["counts"][1] == nq and sid["nelastq"] == nq, (sid["counts"], nq)
shapes = np.asarray(modes["shapes"]).reshape(big_m, n, 6)[flex]  # [q][p][c]
phi = shapes[:, :, :3].transpose(1, 2, 0)  # [p][a][q]
psi = shapes[:, :, 3:].transpose(1, 2, 0)
x = np.array([nd["xyz"] for nd in nodes])
m = np.array([nm["mass"] for nm in body["nodal_mass.bin"]])
ip = np.array([nm["inertia"] for nm in body["nodal_mass.bin"]])
E = np.eye(3)


def skew(v):
    """[..., 3] -> [..., 3, 3] with skew(a) b = a x b."""
    v = np.asarray(v)
    z = np.zeros(v.shape[:-1])
    return np.stack(
        [np.stack([z, -v[..., 2], v[..., 1]], -1),
         np.stack([v[..., 2], z, -v[..., 0]], -1),
         np.stack([-v[..., 1], v[..., 0], z], -1)], -2)


xs = skew(x)  # [p][3][3]
ps = skew(phi.transpose(0, 2, 1))  # [p][q][3][3]
mass = m.sum()
mdcm0 = (m[:, None] * x).sum(0)
mdcm1 = np.einsum("p,paq->aq", m, phi)
j0 = np.einsum("p,pba,pbc->ac", m, xs, xs) + ip.sum(0)
j1 = np.einsum("p,pba,pqbc->qac", m, xs, ps)
j1 = j1 + j1.transpose(0, 2, 1)  # Σ m (s̃ᵀ φ̃_q + φ̃_qᵀ s̃)
ct = mdcm1.T
cr0 = np.einsum("p,pab,pbq->qa", m, xs, phi) + np.einsum("pab,pbq->qa", ip, psi)
cr1 = np.einsum("p,pkab,pbj->jka", m, ps, phi)  # row j, mode k, axis a: Σ m φ̃_k φ_j
me = np.einsum("p,paq,par->qr", m, phi, phi) + np.einsum("paq,pab,pbr->qr", psi, ip, psi)
gr = -2 * np.einsum("p,pab,pqbc->qac", m, xs, ps)  # block q: 3x3
ge = -2 * np.einsum("p,paj,pkab->jkb", m, phi, ps)  # (j, k, a): Σ m (φ_jᵀ φ̃_k)_a
s0 = np.einsum("p,paj,pb->jab", m, phi, x)
s0 = 0.5 * (s0 + s0.transpose(0, 2, 1)) - np.einsum("p,paj,pa->j", m, phi, x)[:, None, None] * E
s1 = np.einsum("p,paj,pbk->jkab", m, phi, phi)
s1 = 0.5 * (s1 + s1.transpose(0, 1, 3, 2)) - np.einsum("p,paj,pak->jk", m, phi, phi)[:, :, None, None] * E


def six_j(t):
    return np.stack([t[..., 0, 0], t[..., 1, 1], t[..., 2, 2], t[..., 0, 1], t[..., 0, 2], t[..., 1, 2]], -1)


def six_oe(t):
    return np.stack([t[..., 0, 0], t[..., 1, 1], t[..., 2, 2], 2 * t[..., 0, 1], 2 * t[..., 1, 2], 2 * t[..., 0, 2]], -1)


gk = np.asarray(modes["generalized_stiffness"]).reshape(big_m, big_m)[np.ix_(flex, flex)]
gm = np.asarray(modes["generalized_mass"]).reshape(big_m, big_m)[np.ix_(flex, flex)]
omega = np.sqrt(np.maximum(np.asarray(modes["omega2"])[flex], 0.0))
damping = body.get("damping.bin")
de = np.diag(2 * np.asarray(damping["ratio"])[flex] * omega * np.diag(gm)) if damping else np.zeros((nq, nq))

# the file's modal geometric stiffness between the flexible modes (zero without the entry)
gs = body.get("geometric_stiffness.bin")


def kg(kind, axes):
    for f in (gs or {"fields": []})["fields"]:
        if f["load"] == [kind, axes]:
            return np.asarray(f["matrix"]).reshape(big_m, big_m)[np.ix_(flex, flex)]
    return np.zeros((nq, nq))


OE_PRODUCTS = [[0, 0], [1, 1], [2, 2], [0, 1], [1, 2], [0, 2]]
kg_ct = np.stack([kg("Acceleration", [a]) for a in range(3)], -1)  # [r][k][a]
kg_cr = np.stack([kg("AngularAcceleration", [a]) for a in range(3)], -1)
kg_oe = np.stack([kg("AngularVelocity", c) for c in OE_PRODUCTS], -1)

TOL = 1e-12
# Scales (mass-orthonormal modes, Σ m |φ|² <= 1): |Σ m φ| <= √m, |Σ m s φ| <= √(Σ m |s|²).
S_M = np.sqrt(mass)
S_S = np.sqrt((m * (x * x).sum(1)).sum())
S_X = mass * np.abs(x).max()
check("refmod mass", abs(sid["mass"] - mass) / mass, TOL)
check("mdCM m0", rel(T["mdCM"][0][:, 0], mdcm0, S_X), TOL)
check("mdCM m1", rel(T["mdCM"][1][:, :, 0], mdcm1, S_M), TOL)
check("J m0", rel(T["J"][0][:, 0], six_j(j0), 0.0), TOL)
check("J m1", rel(T["J"][1][:, :, 0], six_j(j1).T, S_S), TOL)
check("Ct m0", rel(T["Ct"][0], ct, S_M), TOL)
check("Cr m0", rel(T["Cr"][0], cr0, S_S), TOL)
check("Cr m1", rel(T["Cr"][1], cr1 + kg_cr, 1.0), TOL)
if gs is not None:
    check("Ct m1 = the file's K̂_G of the accelerations", rel(T["Ct"][1], kg_ct, 0.0), TOL)
    scale = float(np.abs(kg_oe).max())
    print(f"geometric stiffness: largest |K̂_G| of the ω products {scale:.6e}, of the "
          f"accelerations {np.abs(kg_ct).max():.6e}, of the angular accelerations {np.abs(kg_cr).max():.6e}")
    check("the file's K̂_G of the ω products is not zero", 1.0 if scale == 0.0 else 0.0, 0.0)
    check("Oe m1 − Σ m terms = the file's K̂_G", rel(T["Oe"][1] - six_oe(s1), kg_oe, 0.0), 1e-9)
    check("Cr m1 − Σ m terms = the file's K̂_G", rel(T["Cr"][1] - cr1, kg_cr, 1.0), 1e-9)
else:
    check("Ct has no first order", float(np.abs(T["Ct"][1]).max()), 0.0)
check("Me m0", rel(T["Me"][0], me, 1.0), TOL)
check("Gr m0", rel(T["Gr"][0], np.concatenate(list(gr), axis=1), S_S), TOL)
check("Ge m0", rel(T["Ge"][0], ge.reshape(nq, 3 * nq), 1.0), TOL)
check("Oe m0", rel(T["Oe"][0], six_oe(s0), S_S), TOL)
check("Oe m1", rel(T["Oe"][1], six_oe(s1) + kg_oe, 1.0), TOL)
check("Ke m0", rel(T["Ke"][0], gk, 0.0), TOL)
check("De m0", rel(T["De"][0], de, 0.0) if damping else float(np.abs(T["De"][0]).max()), TOL)
check("ksigma is zero", float(np.abs(T["ksigma"][0]).max()), 0.0)
for name in ["mdCM", "J", "Cr", "Oe"]:
    assert sid["terms"][name].head["order"] == 1, name

# frames: the interface nodes (or all nodes when none is flagged)
index = {nd["id"]: p for p, nd in enumerate(nodes)}
want = [nd["id"] for nd in nodes if nd["interface"]] or [nd["id"] for nd in nodes]
assert [f["id"] for f in sid["frames"]] == want, "frames are not the interface nodes"
assert sid["counts"][0] == len(want)
worst = 0.0
for fr in sid["frames"]:
    p = index[fr["id"]]
    t = {k: v.arrays() for k, v in fr["terms"].items()}
    scale = max(np.abs(phi[p]).max(), np.abs(psi[p]).max(), 1e-300)
    worst = max(worst, np.abs(t["origin"][0][:, 0] - x[p]).max() / max(np.abs(x[p]).max(), 1e-300),
                np.abs(t["origin"][1][:, :, 0] - phi[p]).max() / scale,
                np.abs(t["phi"][0] - phi[p]).max() / scale,
                np.abs(t["psi"][0] - psi[p]).max() / scale,
                np.abs(t["AP"][0] - E).max(),
                np.abs(t["AP"][1] - skew(psi[p].T).transpose(1, 0, 2)).max() / scale)
    assert fr["rframe"] == "body ref"
check(f"{len(sid['frames'])} frames: origin, phi, psi, AP", worst, TOL)
print(f"parsed {sid_path}: {len(sid['frames'])} frames, {nq} modes, {n} nodes in the file")

# --- welib's own generalized mass matrix ----------------------------------------------------
try:
    from welib.FEM.fem_beam import generalizedMassMatrix
except ImportError as e:
    print(f"welib check skipped: cannot import welib ({e}); CI installs it (.ci/run)")
else:
    if n > 3000:
        print(f"welib check skipped: {n} nodes (welib takes a dense mass matrix; the beam test runs it)")
    else:
        mm = np.zeros((6 * n, 6 * n))
        for p in range(n):
            mm[6 * p:6 * p + 3, 6 * p:6 * p + 3] = m[p] * E
            mm[6 * p + 3:6 * p + 6, 6 * p + 3:6 * p + 6] = ip[p]
        se = shapes.transpose(1, 2, 0).reshape(6 * n, nq)
        mtt, w_j0, mrt, mgt, mgr, mgg, _, _ = generalizedMassMatrix(x.T, mm, se)
        # welib's Mrt = Srᵀ M St = −(m c)~ : m c from its skew part
        w_mdcm = np.array([mrt[2, 1], mrt[0, 2], mrt[1, 0]])
        check("welib mass", abs(sid["mass"] - mtt[0, 0]) / mtt[0, 0], TOL)
        check("welib m c (mdCM m0)", rel(T["mdCM"][0][:, 0], w_mdcm, S_X), TOL)
        check("welib J0 (J m0)", rel(T["J"][0][:, 0], six_j(w_j0), 0.0), TOL)
        check("welib Mgt (Ct m0)", rel(T["Ct"][0], mgt, S_M), TOL)
        check("welib Mgr (Cr m0)", rel(T["Cr"][0], mgr, S_S), TOL)
        check("welib Mgg (Me m0)", rel(T["Me"][0], mgg, 1.0), TOL)

# --- EMBSlib's reader ----------------------------------------------------------------------
if len(sys.argv) > 3:
    import json

    dump = json.loads(Path(sys.argv[3]).read_text())
    assert (dump["nodes_count"], dump["modes"]) == sid["counts"], (dump["nodes_count"], dump["modes"])

    def embs(term):
        a0 = np.array(term["m0"]).reshape(term["nrow"], term["ncol"])
        a1 = np.array(term["m1"]).reshape(term["nrow"], term["nq"], term["ncol"])
        return a0, a1

    worst = abs(dump["mass"] - sid["mass"]) / sid["mass"]
    for name, (a0, a1) in T.items():
        e0, e1 = embs(dump["terms"][name])
        worst = max(worst, rel(e0, a0, 0.0) if a0.any() else np.abs(e0).max(),
                    rel(e1, a1, 0.0) if a1.any() else np.abs(e1).max())
    for fr, ef in zip(sid["frames"], dump["frames"]):
        assert fr["id"] == ef["id"], (fr["id"], ef["id"])
        for name, t in fr["terms"].items():
            a0, a1 = t.arrays()
            e0, e1 = embs(ef["terms"][name])
            worst = max(worst, rel(e0, a0, 0.0) if a0.any() else np.abs(e0).max(),
                        rel(e1, a1, 0.0) if a1.any() else np.abs(e1).max())
    check(f"EMBSlib's reader: mass, 11 terms, {len(dump['frames'])} frames", worst, 1e-14)

if failures:
    print("FAILED:", ", ".join(failures))
    sys.exit(1)
