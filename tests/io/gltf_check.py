"""A .glb read with Python's json and struct and numpy only (no code shared
with sessile), checked against a PLY read by meshio or against the sample
scene's known contents.  Prints PASS/FAIL lines; exits 1 on any FAIL.

  gltf_check.py ply GLB PLY    the .glb of a generator's final.ply
  gltf_check.py sample DIR     DIR/instanced.glb and DIR/cube.glb (test_gltf --samples)
"""
import json
import struct
import sys

import numpy as np

fails = 0


def check(what, ok):
    global fails
    print(("PASS " if ok else "FAIL ") + what)
    fails += 0 if ok else 1


def read_glb(path):
    b = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<4sII", b, 0)
    jl, jt = struct.unpack_from("<I4s", b, 12)
    doc = json.loads(b[20:20 + jl])
    bl, bt = struct.unpack_from("<I4s", b, 20 + jl)
    check(f"{path}: GLB container (magic, version 2, length, JSON then BIN, 4-byte aligned)",
          magic == b"glTF" and version == 2 and length == len(b) and jt == b"JSON" and bt == b"BIN\0"
          and jl % 4 == 0 and bl % 4 == 0 and 28 + jl + bl == len(b))
    return doc, b[28 + jl:28 + jl + bl]


def accessor(doc, binc, i):
    a = doc["accessors"][i]
    v = doc["bufferViews"][a["bufferView"]]
    dt = {5126: "<f4", 5125: "<u4"}[a["componentType"]]
    n = {"SCALAR": 1, "VEC3": 3}[a["type"]]
    off = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    return np.frombuffer(binc, dtype=dt, count=a["count"] * n, offset=off).reshape(a["count"], n).squeeze()


def ply_case(glb, ply):
    import meshio
    doc, binc = read_glb(glb)
    m = meshio.read(ply)
    check(f"{glb}: one mesh, one node, one material",
          len(doc["meshes"]) == 1 and len(doc["nodes"]) == 1 and len(doc["materials"]) == 1
          and doc["scenes"][doc["scene"]]["nodes"] == [0])
    prim = doc["meshes"][0]["primitives"][0]
    pos = accessor(doc, binc, prim["attributes"]["POSITION"]).astype(np.float64)
    idx = accessor(doc, binc, prim["indices"]).reshape(-1, 3)
    tri = m.cells_dict["triangle"]
    check(f"{glb}: vertices {len(pos)} and triangles {len(idx)} = the PLY's ({len(m.points)}, {len(tri)})",
          len(pos) == len(m.points) and len(idx) == len(tri) and np.array_equal(idx, tri))
    p = m.points.astype(np.float64)
    want = np.stack([p[:, 0], p[:, 2], -p[:, 1]], axis=1) / 100  # cm, z up -> m, +Y up
    err = np.abs(pos - want).max() / max(np.abs(want).max(), 1e-30)
    check(f"{glb}: vertices = PLY / 100 as (x, z, -y) (rel. error {err:.1e} <= 1e-6)", err <= 1e-6)
    ext, pext = pos.max(0) - pos.min(0), p.max(0) - p.min(0)
    check(f"{glb}: extent {ext} m = the PLY's {pext} cm / 100, y and z swapped",
          np.allclose(ext, [pext[0] / 100, pext[2] / 100, pext[1] / 100], rtol=1e-6))
    n = accessor(doc, binc, prim["attributes"]["NORMAL"]).astype(np.float64)
    check(f"{glb}: unit normals", np.abs(np.linalg.norm(n, axis=1) - 1).max() < 1e-5)
    if "nx" in m.point_data:
        pn = np.stack([m.point_data[k] for k in ("nx", "ny", "nz")], axis=1).astype(np.float64)
        pn /= np.linalg.norm(pn, axis=1)[:, None]
        check(f"{glb}: normals = the PLY's turned", np.abs(n - np.stack([pn[:, 0], pn[:, 2], -pn[:, 1]], 1)).max() < 1e-5)
    acc = doc["accessors"][prim["attributes"]["POSITION"]]
    check(f"{glb}: POSITION min/max = the data's", acc["min"] == list(pos.min(0)) and acc["max"] == list(pos.max(0)))
    for k, v in m.point_data.items():
        if k in ("nx", "ny", "nz", "red", "green", "blue", "alpha"):
            continue  # normals are checked above; colours are a view of a scalar, not carried
        name = "_" + k.upper()
        got = accessor(doc, binc, prim["attributes"][name]) if name in prim["attributes"] else None
        check(f"{glb}: attribute {name} = the PLY's '{k}'",
              got is not None and np.array_equal(got, np.asarray(v, dtype=np.float32)))


def sample_case(d):
    doc, binc = read_glb(d + "/instanced.glb")
    nodes = doc["nodes"]
    check("instanced.glb: 3 nodes on 1 mesh, all in the scene",
          len(nodes) == 3 and len(doc["meshes"]) == 1 and all(n["mesh"] == 0 for n in nodes)
          and doc["scenes"][0]["nodes"] == [0, 1, 2])
    prim = doc["meshes"][0]["primitives"][0]
    th = accessor(doc, binc, prim["attributes"]["_THICKNESS"])
    check("instanced.glb: _THICKNESS = 0.25 + 0.5 v", np.array_equal(th, 0.25 + 0.5 * np.arange(8, dtype=np.float32)))
    # node 'moved' is a translation by (10, 20, 30) cm in sessile's frame
    t = nodes[1]["matrix"][12:15]
    check(f"instanced.glb: (10, 20, 30) cm, z up, is {t} m, y up", np.allclose(t, [0.1, 0.3, -0.2], rtol=0, atol=1e-15))
    check("instanced.glb: the identity node has no matrix", "matrix" not in nodes[0])
    # cube centred at (1, 2, 3) cm, half side 1 -> glTF centre (0.01, 0.03, -0.02) m
    pos = accessor(doc, binc, prim["attributes"]["POSITION"]).astype(np.float64)
    check("instanced.glb: the cube in m, +Y up", np.allclose(pos.mean(0), [0.01, 0.03, -0.02]) and
          np.allclose(pos.max(0) - pos.min(0), 0.02))
    doc1, _ = read_glb(d + "/cube.glb")
    check("cube.glb: no node list given: one node for the mesh", len(doc1["nodes"]) == 1 and doc1["nodes"][0]["mesh"] == 0)


if __name__ == "__main__":  # tests/reef/reef_glb_check.py imports the readers
    if sys.argv[1] == "ply":
        ply_case(sys.argv[2], sys.argv[3])
    else:
        sample_case(sys.argv[2])
    sys.exit(1 if fails else 0)
