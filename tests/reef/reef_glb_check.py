"""reef.glb read by tests/io/gltf_check.py's reader (Python's json, struct and
numpy: no code shared with sessile), checked against the run's
placements.json, the scene file, reef/reef.ply and the organisms' own PLYs.
Prints PASS/FAIL lines; exits 1 on any FAIL.

  reef_glb_check.py RUN_DIR SCENE.json ENTRY=PLY...

Each ENTRY=PLY is the entry's generator run alone with the entry's parameters
and seed 1: the PLY its standard-brush mesh came from.
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "io"))
import gltf_check as g  # noqa: E402

d, scene = sys.argv[1], json.load(open(sys.argv[2]))
own = dict(a.split("=", 1) for a in sys.argv[3:])
doc, binc = g.read_glb(d + "/reef.glb")
pl = json.load(open(d + "/placements.json"))["placements"]
pool = scene["pool"]
nodes, meshes, mats = doc["nodes"], doc["meshes"], doc["materials"]
used = sorted({p["mesh"] for p in pl})

g.check(f"nodes: {len(nodes)} = {len(pl)} placements + the seabed's node 0, all in the scene",
        len(nodes) == len(pl) + 1 and nodes[0]["mesh"] == 0 and "matrix" not in nodes[0]
        and sorted(doc["scenes"][doc["scene"]]["nodes"]) == list(range(len(nodes))))
g.check(f"meshes: {len(meshes)} = {len(used)} distinct organisms + the seabed (mesh 0)",
        len(meshes) == len(used) + 1 and used == list(range(1, len(meshes))))
g.check(f"node k + 1 shows placement k's mesh", all(nodes[k + 1]["mesh"] == p["mesh"] for k, p in enumerate(pl)))
g.check(f"materials: {len(mats)} = {len(pool)} pool colours + the seabed's",
        len(mats) == len(pool) + 1 and all(
            np.allclose(mats[e + 1]["pbrMetallicRoughness"]["baseColorFactor"], pool[e].get("colour", [0.8, 0.5, 0.4, 1]))
            for e in range(len(pool))))
names = [e["name"] for e in pool]
g.check("each organism mesh has its entry's material",
        all(meshes[p["mesh"]]["primitives"][0]["material"] == names.index(p["entry"]) + 1 for p in pl))


def mesh(m):
    prim = meshes[m]["primitives"][0]
    return (g.accessor(doc, binc, prim["attributes"]["POSITION"]).astype(np.float64),
            g.accessor(doc, binc, prim["indices"]).reshape(-1, 3), prim["attributes"])


def sessile(p):  # glTF m, +Y up -> sessile cm, z up
    return np.stack([p[:, 0], -p[:, 2], p[:, 1]], axis=1) * 100


res = scene["seabed"]["noise"]["resolution"]
g.check(f"the seabed mesh: {res[0]} x {res[1]} samples", len(mesh(0)[0]) == res[0] * res[1])

# reef/reef.ply merges the seabed and every placement's organism: its counts
# are the sums over the nodes of their meshes' counts
hdr = open(d + "/reef/reef.ply", "rb").read(4096).split(b"end_header")[0].decode()
nv_ply = int(hdr.split("element vertex ")[1].split()[0])
nf_ply = int(hdr.split("element face ")[1].split()[0])
nv = sum(len(mesh(n["mesh"])[0]) for n in nodes)
nf = sum(len(mesh(n["mesh"])[1]) for n in nodes)
g.check(f"vertices {nv} and triangles {nf} over the nodes = reef/reef.ply's ({nv_ply}, {nf_ply})",
        (nv, nf) == (nv_ply, nf_ply))

# every node's world positions = placements.json's transform of its mesh, to
# float precision: io writes node matrices as floats (what engines store,
# docs/io.md), so the bound is 2 float ulps (2 x 1.2e-7, relative) of the
# scene's largest world coordinate
err = 0
scale = 0
for k, p in enumerate(pl):
    m = np.array(nodes[k + 1]["matrix"]).reshape(4, 4).T
    pos = mesh(p["mesh"])[0]
    world = (m[:3, :3] @ pos.T).T + m[:3, 3]
    t = np.array(p["transform"]).reshape(4, 4).T
    want = (t[:3, :3] @ sessile(pos).T).T + t[:3, 3]  # metres, z up
    err = max(err, np.abs(sessile(world) / 100 - want).max())
    scale = max(scale, np.abs(want).max())
tol = 2.4e-7 * max(scale, 1.0)
g.check(f"node matrices = placements.json's transforms (max error {err:.1e} m <= {tol:.1e}, 2 float ulps at {scale:.1f} m)",
        err <= tol)

# each organism mesh against the PLY it came from
for name, ply in own.items():
    import meshio
    o = meshio.read(ply)
    q, tri = o.points.astype(np.float64), o.cells_dict["triangle"]
    base = np.array([(q[:, 0].min() + q[:, 0].max()) / 2, (q[:, 1].min() + q[:, 1].max()) / 2, q[:, 2].min()])
    ms = sorted({p["mesh"] for p in pl if p["entry"] == name})
    std = sorted({p["mesh"] for p in pl if p["entry"] == name and p["brush"] == "standard"})
    counts = all(len(mesh(m)[0]) == len(q) and np.array_equal(mesh(m)[1], tri) for m in ms)
    g.check(f"{name}: its {len(ms)} meshes have the PLY's {len(q)} vertices and its triangles", bool(ms) and counts)
    for m in std:
        e = np.abs(sessile(mesh(m)[0]) - (q - base)).max() / np.abs(q).max()
        g.check(f"{name}: the standard mesh {m} = the PLY moved to its base (rel. error {e:.1e} <= 1e-6)", e <= 1e-6)
    # the PLY's vertex scalars as custom attributes, named as --glb names them
    # (its uchar colours are a view of the main scalar, docs/io.md: not carried)
    props = {"_" + "".join(c.upper() if c.isalnum() else "_" for c in k): k
             for k in o.point_data if k not in ("nx", "ny", "nz", "red", "green", "blue", "alpha")}
    attrs = all({a for a in mesh(m)[2] if a.startswith("_")} == set(props) for m in ms)
    g.check(f"{name}: its meshes carry the PLY's scalars as {sorted(props) or 'no attributes'}", attrs)
    for m in std:
        for a, k in props.items():
            got = g.accessor(doc, binc, mesh(m)[2][a])
            g.check(f"{name}: mesh {m}'s {a} = the PLY's '{k}'", np.array_equal(got, np.asarray(o.point_data[k], np.float32)))
sys.exit(1 if g.fails else 0)
