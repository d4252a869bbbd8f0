"""Read flexbody reduced flexible-body files (.flexbody) into numpy arrays.

    import flexbody
    body = flexbody.read("rod.flexbody")
    body.shapes.shape          # (modes, nodes, 6): ux uy uz rx ry rz per unit modal coordinate
    body.frequency_hz, body.labels, body.invariants["I9"].shape   # (M, M, 3, 3)

The large arrays are numpy views of the file's decoded payload (read-only; copy to modify).
Every rule of format-spec/SPEC.md is checked, with the stdlib reference reader's error names
(`flexbody.ReadError.variant`). Only numpy is needed.
"""
import math
from pathlib import Path

import numpy as np

from . import _spec
from ._reader import read_bytes
from ._spec import ReadError, SET_MEMBERS, UNIT_KEYS

__all__ = ["read", "read_bytes_body", "Body", "ReadError"]
__version__ = "0.1.0"


class Body:
    """One reduced body. N stored nodes, M modes; shapes follow SPEC §5.

    Attributes: ``version`` (major, minor), ``generator``, ``units`` (manifest dict), ``title``,
    ``created_utc``, ``request`` (header request dict), ``node_ids`` (N,) uint64, ``xyz`` (N, 3),
    ``interface_flags`` (N,) bool, ``faces`` (F, 4) int64 node indices (-1 pads triangles),
    ``face_is_quad`` (F,), ``lines`` (L, 2) or None, ``mass`` (N,), ``nodal_inertia`` (N, 3, 3),
    ``omega2`` (M,), ``frequency_hz`` (M,), ``labels`` (M,) str, ``generalized_mass`` and
    ``generalized_stiffness`` (M, M), ``shapes`` (M, N, 6), ``invariant_mask`` (9,) bool,
    ``invariants`` {"I1": (1,), "I2": (3,), "I3": (3, M), "I4": (3, M), "I5": (M, 3, M),
    "I6": (M, M), "I7": (3, 3), "I8": (M, 3, 3), "I9": (M, M, 3, 3)} (None when not stored),
    ``method`` (method.bin dict), ``stress_nodes``/``stress_shapes`` (K,), (M, K, 6) or None
    (likewise ``strain_*``; ``stress_bottom_nodes``/``stress_shapes_bottom`` the shells' bottom
    fibre, SPEC §5.15), ``damping_ratio`` (M,) or None, ``label_shares`` (M,) or None,
    ``recipe`` (dict) or None, ``interfaces`` (list of dicts: ``node`` the interface node's index
    into the stored nodes, ``node_id`` its id, ``name``, ``kind``, ``dependent`` the ids of the
    mesh nodes it depends on, ``fit``) or None, ``modal_loads`` (dict with
    ``loads`` [{name, source, values}] and ``residual``) or None, ``geometric_stiffness``
    (dict: ``support`` and ``fields`` {load name: (M, M) K̂_G per unit load, SPEC §5.16}) or
    None, ``eigen_residuals`` (list, one dict per eigenproblem behind the basis: ``kind``,
    ``solver``, ``scale``, ``omega2`` (L,), ``residual`` (L,) relative residuals, ``inertia``
    {shift, below} or None; SPEC §5.17, format 1.9) or None, ``entries`` (manifest).
    """

    def __init__(self, b, m):
        self._b, self._m = b, m
        h, modes = b["header.bin"], b["modes.bin"]
        self.version = (m["version"]["major"], m["version"]["minor"])
        self.generator = m["generator"]
        self.units = m["units"]
        self.entries = m["entries"]
        self.title, self.created_utc, self.request = h["title"], h["created_utc"], h["request"]
        nodes = b["nodes.bin"]
        n, nm = len(nodes), len(modes["omega2"])
        self.node_ids = nodes["id"]
        self.xyz = nodes["xyz"]
        self.interface_flags = nodes["interface"].astype(bool)
        self.faces, self.face_is_quad = b["faces.bin"]
        self.lines = b.get("lines.bin")
        nm_ = b["nodal_mass.bin"]
        self.mass = nm_[:, 0]
        self.nodal_inertia = nm_[:, 1:].reshape(n, 3, 3)
        self.omega2, self.frequency_hz = modes["omega2"], modes["frequency_hz"]
        self.label_codes = modes["labels"]
        self.labels = np.array(["Rigid", "Normal", "Constraint", "FixedInterface", "Attachment",
                                "FrequencyResponse"])[modes["labels"]]
        self.generalized_mass = modes["generalized_mass"].reshape(nm, nm)
        self.generalized_stiffness = modes["generalized_stiffness"].reshape(nm, nm)
        self.shapes = modes["shapes"].reshape(nm, n, 6)
        inv = b["invariants.bin"]
        self.invariant_mask = inv["mask"]
        shapes = [(1,), (3,), (3, nm), (3, nm), (nm, 3, nm), (nm, nm), (3, 3), (nm, 3, 3), (nm, nm, 3, 3)]
        self.invariants = {f"I{k + 1}": (inv["i"][k].reshape(shapes[k]) if inv["mask"][k] else None)
                           for k in range(9)}
        self.method = b["method.bin"]
        for kind in ("stress", "strain"):
            for part in ("", "_bottom"):  # "_bottom": shells' bottom fibre (format 1.5)
                s = b.get(f"{kind}_shapes{part}.bin")
                setattr(self, f"{kind}{part}_nodes", None if s is None else s["nodes"])
                setattr(self, f"{kind}_shapes{part}",
                        None if s is None else s["values"].reshape(nm, len(s["nodes"]), 6))
        self.damping_ratio = b.get("damping.bin")
        self.label_shares = b.get("label_shares.bin")
        self.recipe = b.get("recipe.json")
        # SPEC §5.13 stores each interface's node as a stored-node index (`node`) and the mesh
        # nodes it depends on by id (`dependent`); `node_id` gives the interface node's id too,
        # so that ids can be compared with ids.
        itf = b.get("interfaces.bin")
        self.interfaces = None if itf is None else [
            dict(i, node_id=int(self.node_ids[i["node"]])) for i in itf]
        self.modal_loads = b.get("modal_loads.bin")
        gs = b.get("geometric_stiffness.bin")
        self.geometric_stiffness = None if gs is None else dict(
            support=gs["support"],
            fields={_spec.unit_load_name(f["load"]): np.asarray(f["matrix"], dtype=float).reshape(nm, nm)
                    for f in gs["fields"]})
        er = b.get("eigen_residuals.bin")
        self.eigen_residuals = None if er is None else [
            dict(p, omega2=np.asarray(p["omega2"], dtype=float), residual=np.asarray(p["residual"], dtype=float))
            for p in er["problems"]]

    @property
    def node_count(self):
        return len(self.node_ids)

    @property
    def mode_count(self):
        return len(self.omega2)

    def interface(self, name):
        """The interface records named `name` (case-insensitive; `NODE<id>` for plain nodes)."""
        return [i for i in (self.interfaces or []) if i["name"].lower() == name.lower()]

    def mass_properties(self):
        """SPEC §5.6/§9: from I1, I2, I7 when stored, else from the nodal masses."""
        inv = self.invariants
        if all(self.invariant_mask[k] for k in (0, 1, 6)):
            source, m, first, jo = "invariants", float(inv["I1"][0]), inv["I2"].astype(float), inv["I7"].astype(float)
        else:
            s, mp = self.xyz, self.mass
            m, first = float(mp.sum()), (mp[:, None] * s).sum(axis=0)
            ss = (s * s).sum(axis=1)
            jo = (np.einsum("p,pij->ij", mp, ss[:, None, None] * np.eye(3) - s[:, :, None] * s[:, None, :])
                  + self.nodal_inertia.sum(axis=0))
            source = "nodal_mass"
        c = first / m if m > 0 else np.zeros(3)
        jc = jo - m * ((c @ c) * np.eye(3) - np.outer(c, c))
        return dict(source=source, total_mass=m, center_of_mass=[float(v) for v in c],
                    inertia_origin=jo.tolist(), inertia_center_of_mass=jc.tolist())

    def summary(self):
        """The summary of `flexbody inspect --json` (SPEC §9), as the reference reader gives it."""
        m, nm = self._m, self.mode_count
        return {
            "format_version": f"{self.version[0]}.{self.version[1]}",
            "generator": f"{self.generator['name']} {self.generator['version']}",
            "title": self.title,
            "created_utc": self.created_utc,
            "units": {k: {"name": m["units"][k]["name"], "si": m["units"][k]["si"]} for k in UNIT_KEYS},
            "method": self.method["method"],
            "mass_kind": self.method["mass_kind"],
            "invariant_set": self.request["invariant_set"],
            "invariants_present": [k + 1 for k in range(9) if self.invariant_mask[k]],
            "counts": {"nodes": self.node_count, "interface_nodes": int(self.interface_flags.sum()),
                       "faces": len(self.faces), "lines": 0 if self.lines is None else len(self.lines),
                       "modes": nm},
            "mass": self.mass_properties(),
            "modes": [{"number": j + 1, "frequency_hz": float(self.frequency_hz[j]),
                       "omega2": float(self.omega2[j]), "label": str(self.labels[j]),
                       "label_share": None if self.label_shares is None else float(self.label_shares[j]),
                       "damping_ratio": None if self.damping_ratio is None else float(self.damping_ratio[j])}
                      for j in range(nm)],
            "optional": [self.stress_shapes is not None, self.strain_shapes is not None,
                         self.damping_ratio is not None, self.lines is not None],
            "entries": [{k: e[k] for k in ("name", "size", "sha256", "required")} for e in m["entries"]],
            "recipe": self.recipe,
            "interfaces": None if self.interfaces is None else [
                {k: v for k, v in i.items() if k != "node_id"} for i in self.interfaces],
            **({"modal_loads": self.modal_loads} if self.modal_loads is not None else {}),
            **({"geometric_stiffness": _spec.geometric_summary(self._b["geometric_stiffness.bin"])}
               if self.geometric_stiffness is not None else {}),
            **({"eigen_residuals": [_spec.eigen_summary(p) for p in self._b["eigen_residuals.bin"]["problems"]]}
               if self.eigen_residuals is not None else {}),
        }


def read_bytes_body(data):
    """A validated :class:`Body` from the bytes of a file."""
    return Body(*read_bytes(bytes(data)))


def read(path):
    """A validated :class:`Body` from a .flexbody file; :class:`ReadError` names the rule broken."""
    try:
        data = Path(path).read_bytes()
    except OSError as e:
        raise ReadError("Io", f"{path}: {e}") from e
    return read_bytes_body(data)


del math, SET_MEMBERS
