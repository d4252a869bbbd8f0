"""A flexbody file as an exudyn flexible body in one call.

    import exudyn as exu, flexbody.exudyn
    mbs = exu.SystemContainer().AddSystem()
    obj = flexbody.exudyn.add_body(mbs, "rod.flexbody", gravity=[0, 0, -9.81])
    obj["oFFRFreducedOrder"], obj["nRigidBody"], obj["interface"]   # exudyn's items + interface

The arrays are the ones `flexbody export --to exudyn` writes into its NPZ (src/export/exudyn.rs,
same conventions): flexible modes only (picked by label, not by omega^2), exudyn's inertia
terms from the file's invariants with exudyn's signs (its x~^T is the spec's -x~):

    mPhitTPsi[a][j]               =  I3[a][j]
    mXRefTildePsi[a][j]           = -I4[a][j]
    mPsiTildePsi[3j+a][k]         = -I5[j][a][k]
    massMatrixReduced[j][k]       =  I6[j][k]
    inertiaLocal                  =  I7
    mXRefTildePsiTilde[a][3j+b]   = -I8[j][a][b]
    mPsiTildePsiTilde[3j+a][3k+b] = -I9[j][k][a][b]
    mPhitTPsiTilde[a][3j+b]       =  skew(I3[:, j])[a][b]

stress (else strain) modes in exudyn's component order xx yy zz yz xz xy (tensor shear
strains), surface triangles (6-node where every face is a triangle with a stored mid node on
each edge), and the modal damping as the object's dampingMatrixReduced = diag(2 zeta omega).
exudyn is imported only when a function here is called.
"""
import numpy as np

from . import Body, read

# exudyn's stress component order xx yy zz yz xz xy as indices into the file's xx yy zz xy yz zx
EXUDYN_FROM_FILE_COMPONENT = [0, 1, 2, 4, 5, 3]
RIGID_BODY_NODE_TYPE = "NodeType.RotationEulerParameters"


def _body(body):
    return body if isinstance(body, Body) else read(body)


def _skew(v):
    v = np.asarray(v, dtype=float)
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def flexible_modes(body):
    """Indices of the flexible modes (every mode not labelled Rigid), ascending."""
    return np.flatnonzero(np.asarray(body.labels) != "Rigid")


def interface_data(body):
    """The dict `ObjectFFRFreducedOrderInterface.SetWithDictionary` takes (the NPZ's exudyn
    keys plus flexbody's own: FLEXBODY_KEYS, and with damping dampingMatrixReduced,
    modalDampingRatio)."""
    body = _body(body)
    missing = [k for k in range(1, 10) if body.invariants[f"I{k}"] is None]
    if missing:
        raise ValueError("exudyn's ObjectFFRFreducedOrder needs all nine invariants; the file "
                         f"lacks {', '.join(f'I{k}' for k in missing)} (build with --invariants full)")
    n = body.node_count
    flex = flexible_modes(body)
    m = len(flex)
    if m == 0:
        raise ValueError("the file has no flexible modes")
    if n == 0:
        raise ValueError("the file stores no nodes")
    inv = {k: np.asarray(v) for k, v in body.invariants.items()}
    total_mass = float(inv["I1"][0])
    if not total_mass > 0:
        raise ValueError(f"the body's mass I1 = {total_mass} is not positive")
    chi_u = inv["I2"] / total_mass
    sub = np.ix_(flex, flex)
    i3 = inv["I3"][:, flex]                                   # (3, m)
    d = {
        "modeBasis": np.ascontiguousarray(
            body.shapes[flex][:, :, :3].transpose(1, 2, 0).reshape(3 * n, m)),
        "trigList": surface_triangles(body),
        "postProcessingModes": _post_processing(body, flex),
        "massMatrixReduced": np.array(inv["I6"][sub]),
        "stiffnessMatrixReduced": np.array(body.generalized_stiffness[sub]),
        "infoList": np.array([m, n, 3, 4, 7, 7 + m], dtype=np.int64),
        "rigidBodyNodeType": RIGID_BODY_NODE_TYPE,
        "xRef": np.array(body.xyz, dtype=float).reshape(3 * n),
        "inertiaLocal": np.array(inv["I7"], dtype=float).reshape(3, 3),
        "Mtt": total_mass * np.eye(3),
        "totalMass": np.array(total_mass),
        "chiU": chi_u,
        "chiUtilde": _skew(chi_u),
        "mPsiTildePsi": -inv["I5"][flex][:, :, flex].reshape(3 * m, m),
        "mPsiTildePsiTilde": -inv["I9"][sub].transpose(0, 2, 1, 3).reshape(3 * m, 3 * m),
        "mPhitTPsi": np.array(i3),
        "mPhitTPsiTilde": _skew(i3.T).transpose(1, 0, 2).reshape(3, 3 * m),
        "mXRefTildePsi": -inv["I4"][:, flex],
        "mXRefTildePsiTilde": -inv["I8"][flex].transpose(1, 0, 2).reshape(3, 3 * m),
        "fileVersion": np.array(1, dtype=np.int64),
        "type": "ObjectFFRFreducedOrderInterface",
        "nodeIds": np.array(body.node_ids, dtype=np.int64),
        "interfaceNodeIndices": np.array([i["node"] for i in body.method["interface"]], dtype=np.int64),
        **_dependent_nodes(body),
        "nodalMass": np.array(body.mass),
        "flexibleModeIndices": flex.astype(np.int64),
        "eigenFrequenciesHz": np.array(body.frequency_hz[flex]),
        "units": " ".join(body.units[k]["name"] for k in ("mass", "length", "time", "force")),
    }
    if body.damping_ratio is not None:
        zeta = np.asarray(body.damping_ratio)[flex]
        d["dampingMatrixReduced"] = np.diag(2.0 * zeta * np.sqrt(np.maximum(body.omega2[flex], 0.0)))
        d["modalDampingRatio"] = zeta
    return d


def _dependent_nodes(body):
    """Each interface's dependent (bore) nodes, flat in interface order as the export writes
    them: interface k's are [offsets[k], offsets[k+1]) of the node indices (-1 for a node the
    file does not store) and ids; names and kinds newline-joined."""
    ids, offsets, names, kinds = [], [0], [], []
    if body.interfaces is not None:
        for i in body.interfaces:
            ids.extend(int(d) for d in i["dependent"])
            offsets.append(len(ids))
            names.append(i["name"])
            kinds.append(i["kind"])
    else:
        for i in body.method["interface"]:
            offsets.append(0)
            names.append(f"NODE{int(body.node_ids[i['node']])}")
            kinds.append("Node")
    index_of = {int(d): k for k, d in enumerate(body.node_ids)}
    return {
        "interfaceDependentOffsets": np.array(offsets, dtype=np.int64),
        "interfaceDependentNodeIndices": np.array([index_of.get(d, -1) for d in ids], dtype=np.int64),
        "interfaceDependentNodeIds": np.array(ids, dtype=np.int64),
        "interfaceNames": "\n".join(names),
        "interfaceKinds": "\n".join(kinds),
    }


def interfaces_of(data):
    """Per interface (in --interface order) a dict from the NPZ's (or :func:`interface_data`'s)
    flexbody keys: name, kind (Rbe2, Rbe3, Node), node (the interface node's index),
    dependentNodes (indices of its bore nodes, for MarkerSuperElementRigid/Position;
    -1 for a node the file does not store), dependentIds (their ids)."""
    get = data.__getitem__
    off = np.asarray(get("interfaceDependentOffsets"))
    idx, ids = np.asarray(get("interfaceDependentNodeIndices")), np.asarray(get("interfaceDependentNodeIds"))
    names, kinds = str(get("interfaceNames")).split("\n"), str(get("interfaceKinds")).split("\n")
    return [{"name": names[k], "kind": kinds[k], "node": int(node),
             "dependentNodes": [int(i) for i in idx[off[k]:off[k + 1]]],
             "dependentIds": [int(i) for i in ids[off[k]:off[k + 1]]]}
            for k, node in enumerate(np.asarray(get("interfaceNodeIndices")))]


FLEXBODY_KEYS = ("nodeIds", "interfaceNodeIndices", "interfaceDependentOffsets",
                 "interfaceDependentNodeIndices", "interfaceDependentNodeIds", "interfaceNames",
                 "interfaceKinds", "nodalMass", "flexibleModeIndices", "eigenFrequenciesHz", "units")


def interface(body):
    """An `exudyn.FEM.ObjectFFRFreducedOrderInterface` holding the file's body, set up as its
    `LoadFromFile` sets it up from the NPZ of `flexbody export --to exudyn`. `body`: a path or
    a :class:`flexbody.Body`."""
    from exudyn.FEM import ObjectFFRFreducedOrderInterface
    d = interface_data(body)
    cms = ObjectFFRFreducedOrderInterface()
    cms.SetWithDictionary(d)
    # What LoadFromFile does after SetWithDictionary: the constant blocks of the FFRF mass matrix.
    cms.massMatrixFFRFreduced = np.zeros((cms.nODE2FFRFreduced, cms.nODE2FFRFreduced))
    cms.massMatrixFFRFreduced[0:3, 0:3] = cms.Mtt
    cms.massMatrixFFRFreduced[cms.nODE2rigid:, cms.nODE2rigid:] = cms.massMatrixReduced
    cms.flexbody = {k: d[k] for k in FLEXBODY_KEYS
                    + (("dampingMatrixReduced", "modalDampingRatio") if "dampingMatrixReduced" in d else ())}
    return cms


def add_body(mbs, body, **kwargs):
    """Adds the file's body to exudyn's `mbs` as an ObjectFFRFreducedOrder in one call: builds
    the :func:`interface`, calls its `AddObjectFFRFreducedOrder(mbs, **kwargs)` (positionRef,
    initialVelocity, rotationMatrixRef, initialAngularVelocity, gravity, color, name, ...) and,
    when the file has modal damping, sets the object's dampingMatrixReduced = diag(2 zeta
    omega). Returns exudyn's dict (oFFRFreducedOrder, nRigidBody, nGenericODE2, ...) with
    "interface" (the ObjectFFRFreducedOrderInterface), "interfaceNodes" (node indices of the
    file's interface nodes in --interface order, for markers and joints) and "interfaces" (per
    interface a dict: name, kind, node, dependentNodes = its bore nodes' indices, dependentIds;
    see :func:`interfaces_of`) added."""
    import exudyn as exu
    cms = interface(body)
    obj = cms.AddObjectFFRFreducedOrder(mbs, **kwargs)
    if "dampingMatrixReduced" in cms.flexbody:
        damping = exu.MatrixContainer()
        damping.SetWithDenseMatrix(cms.flexbody["dampingMatrixReduced"], useDenseMatrix=False)
        mbs.SetObjectParameter(obj["oFFRFreducedOrder"], "dampingMatrixReduced", damping)
    obj["interface"] = cms
    obj["interfaceNodes"] = [int(i) for i in cms.flexbody["interfaceNodeIndices"]]
    obj["interfaces"] = interfaces_of(cms.flexbody)
    return obj


def _post_processing(body, flex):
    """exudyn's postProcessingModes: matrix (nodes x 6 modes, exudyn's component order, zero rows
    for nodes without values) and outputVariableType; {} without field shapes."""
    if body.stress_shapes is not None:
        values, nodes, kind, shear = body.stress_shapes, body.stress_nodes, "StressLocal", 1.0
    elif body.strain_shapes is not None:  # exudyn's StrainLocal is the tensor strain: gamma / 2
        values, nodes, kind, shear = body.strain_shapes, body.strain_nodes, "StrainLocal", 0.5
    else:
        return {}
    n, m = body.node_count, len(flex)
    v = np.asarray(values)[flex][:, :, EXUDYN_FROM_FILE_COMPONENT] * np.array([1, 1, 1, shear, shear, shear])
    matrix = np.zeros((n, m, 6))
    matrix[np.asarray(nodes, dtype=np.int64)] = v.transpose(1, 0, 2)
    return {"matrix": matrix.reshape(n, 6 * m), "outputVariableType": f"OutputVariableType.{kind}"}


def surface_triangles(body):
    """exudyn's trigList as a list of lists: quads split in two (0 1 2, 0 2 3); 6-node
    triangles (corners, then the mid nodes of edges 0-1, 1-2, 2-0) when every face is a
    triangle and every edge has exactly one stored mid node near its middle (a quadratic mesh),
    3-node otherwise — the rule of `flexbody export --to exudyn`."""
    faces, quad = np.asarray(body.faces), np.asarray(body.face_is_quad)
    if len(faces) == 0:
        return []
    tris = np.concatenate([faces[~quad, :3], faces[quad][:, [0, 1, 2]], faces[quad][:, [0, 2, 3]]])
    # the export's order: faces in file order, a quad's two triangles one after the other
    order = np.concatenate([np.flatnonzero(~quad) * 2, np.flatnonzero(quad) * 2,
                            np.flatnonzero(quad) * 2 + 1])
    tris = tris[np.argsort(order, kind="stable")]
    if not quad.any():
        mids = _mid_nodes(np.asarray(body.xyz, dtype=float), tris)
        if mids is not None:
            return np.concatenate([tris, mids], axis=1).tolist()
    return tris.tolist()


def _mid_nodes(xyz, tris):
    """For each triangle the mid nodes of its edges 0-1, 1-2, 2-0: the stored node (not a face
    corner) nearest each edge's midpoint, within a quarter of the edge length; None unless every
    edge has one and no node serves two edges."""
    e = np.stack([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]], axis=1).reshape(-1, 2)
    e.sort(axis=1)
    edges, inverse = np.unique(e, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    length = np.linalg.norm(xyz[edges[:, 0]] - xyz[edges[:, 1]], axis=1)
    cell = 0.5 * length.sum() / len(edges)
    if not (cell > 0 and np.isfinite(cell)):
        return None
    corner = np.zeros(len(xyz), dtype=bool)
    corner[tris.ravel()] = True
    candidates = np.flatnonzero(~corner)
    grid = {}
    for i, k in zip(candidates.tolist(), map(tuple, np.floor(xyz[candidates] / cell).astype(np.int64).tolist())):
        grid.setdefault(k, []).append(i)
    mid = 0.5 * (xyz[edges[:, 0]] + xyz[edges[:, 1]])
    radius = 0.25 * length
    keys = np.floor(mid / cell).astype(np.int64)
    found = np.empty(len(edges), dtype=np.int64)
    for q in range(len(edges)):
        reach = int(np.ceil(radius[q] / cell))
        kx, ky, kz = keys[q].tolist()
        best, best_d = -1, np.inf
        for dx in range(-reach, reach + 1):
            for dy in range(-reach, reach + 1):
                for dz in range(-reach, reach + 1):
                    cands = grid.get((kx + dx, ky + dy, kz + dz))
                    if not cands:
                        continue
                    d = np.linalg.norm(xyz[cands] - mid[q], axis=1)
                    j = int(np.argmin(d))
                    if d[j] <= radius[q] and d[j] < best_d:
                        best, best_d = cands[j], d[j]
        if best < 0:
            return None
        found[q] = best
    if len(np.unique(found)) != len(found):
        return None
    return found[inverse].reshape(-1, 3)
