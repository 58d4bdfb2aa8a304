"""Surface metrics of a sessile sponge, from its PLY file (numpy and scipy only).

Every length is in cm, as in sessile.  The functions take V (n x 3 float64
vertex positions) and F (m x 3 int64 triangles, consistently oriented,
outward normals) and are tested on shapes with known answers by
tools/science/test_metrics.py.

Definitions (tools/science/README.md repeats them):
- volume: divergence theorem, V = 1/6 sum over triangles of v0 . (v1 x v2)
  (exact for a closed, consistently oriented triangle surface);
- area: sum of the triangle areas (the base on the substratum included);
- height: the largest z (the substratum is z = 0);
- surface/volume: area / volume, in 1/cm;
- centroid: the centroid of the enclosed solid (divergence theorem again);
- base area: the area of the triangles lying on the substratum, all three
  vertices at z < BASE_Z (0.05 cm); base hull area: the area of the 2-D convex
  hull of the vertices at z < BASE_Z (the footprint with its gaps filled);
- tips (extrusions): a vertex is a tip when it is higher (larger z; equal z:
  the smaller vertex index counts as higher) than every other vertex within a
  graph-geodesic distance of TIP_RADIUS (2 cm: shortest paths along the mesh
  edges, Dijkstra), and its z is above half the sponge's height; tip spacing:
  the mean over tips of the straight-line (3-D) distance to the nearest other
  tip (undefined with fewer than two tips).
"""
import numpy as np

BASE_Z = 0.05
TIP_RADIUS = 2.0
TIP_MIN_FRACTION = 0.5

_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1",
    "short": "i2", "int16": "i2", "ushort": "u2", "uint16": "u2",
    "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}


class PlyError(Exception):
    pass


def read_ply(path):
    """Reads a binary little-endian PLY (sessile's: float x y z nx ny nz; faces
    as uchar count + uint indices).  Returns (V, F): float64 positions and
    int64 triangles (polygons are split into fans)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise PlyError(f"{path}: not a PLY file")
    body_at = data.index(b"\n", end) + 1
    elements = []  # (name, count, [(prop name, dtype) | (prop name, count dtype, item dtype, 'list')])
    fmt = None
    for line in data[:end].decode("ascii", "replace").splitlines():
        w = line.split()
        if not w or w[0] in ("ply", "comment", "obj_info"):
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w[0] == "property":
            if not elements:
                raise PlyError(f"{path}: property before any element")
            if w[1] == "list":
                elements[-1][2].append((w[4], _PLY_TYPES[w[2]], _PLY_TYPES[w[3]], "list"))
            else:
                elements[-1][2].append((w[2], _PLY_TYPES[w[1]]))
    if fmt != "binary_little_endian":
        raise PlyError(f"{path}: format {fmt}, only binary_little_endian is read")
    at = body_at
    V = F = None
    for name, count, props in elements:
        lists = [p for p in props if len(p) == 4]
        if not lists:
            dt = np.dtype([(p[0], "<" + p[1]) for p in props])
            arr = np.frombuffer(data, dtype=dt, count=count, offset=at)
            at += count * dt.itemsize
            if name == "vertex":
                V = np.stack([arr["x"], arr["y"], arr["z"]], axis=1).astype(np.float64)
            continue
        if len(props) != 1:
            raise PlyError(f"{path}: element {name}: only a single list property is read")
        _, ct, it, _ = props[0]
        cs, isz = np.dtype(ct).itemsize, np.dtype(it).itemsize
        # Fast path: every face a triangle.
        dt = np.dtype([("n", "<" + ct), ("i", "<" + it, (3,))])
        tri = None
        if at + count * dt.itemsize <= len(data):
            arr = np.frombuffer(data, dtype=dt, count=count, offset=at)
            if count == 0 or np.all(arr["n"] == 3):
                tri = arr["i"].astype(np.int64)
                at += count * dt.itemsize
        if tri is None:  # general polygons: walk them, fan-triangulate
            out = []
            for _ in range(count):
                n = int(np.frombuffer(data, dtype="<" + ct, count=1, offset=at)[0])
                at += cs
                idx = np.frombuffer(data, dtype="<" + it, count=n, offset=at).astype(np.int64)
                at += n * isz
                for k in range(1, n - 1):
                    out.append((idx[0], idx[k], idx[k + 1]))
            tri = np.array(out, dtype=np.int64).reshape(-1, 3)
        if name == "face":
            F = tri
    if V is None or F is None:
        raise PlyError(f"{path}: no vertex or face element")
    if len(F) and (F.min() < 0 or F.max() >= len(V)):
        raise PlyError(f"{path}: a face index is out of range")
    return V, F


def edges(F):
    """Unique undirected edges (k x 2, sorted pairs) and how many triangles share each."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    e.sort(axis=1)
    u, counts = np.unique(e, axis=0, return_counts=True)
    return u, counts


def triangle_areas(V, F):
    v0, v1, v2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return 0.5 * np.linalg.norm(np.cross(v1 - v0, v2 - v0), axis=1)


def area(V, F):
    return float(triangle_areas(V, F).sum())


def volume(V, F):
    v0, v1, v2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return float(np.einsum("ij,ij->i", v0, np.cross(v1, v2)).sum() / 6.0)


def centroid(V, F):
    """Centroid of the solid the closed surface encloses (a sum over the
    tetrahedra origin-v0-v1-v2, signed; a point near the surface is taken as
    origin to keep the sums well conditioned)."""
    o = V.mean(axis=0)
    v0, v1, v2 = V[F[:, 0]] - o, V[F[:, 1]] - o, V[F[:, 2]] - o
    w = np.einsum("ij,ij->i", v0, np.cross(v1, v2)) / 6.0
    return (w[:, None] * (v0 + v1 + v2)).sum(axis=0) / 4.0 / w.sum() + o


def base_area(V, F, z=BASE_Z):
    on = np.all(V[F][:, :, 2] < z, axis=1)
    return float(triangle_areas(V, F[on]).sum())


def base_hull_area(V, z=BASE_Z):
    p = V[V[:, 2] < z][:, :2]
    if len(p) < 3:
        return 0.0
    from scipy.spatial import ConvexHull
    try:
        return float(ConvexHull(p).volume)  # in 2-D, qhull's "volume" is the area
    except Exception:  # all points on a line
        return 0.0


def edge_graph(V, F):
    from scipy.sparse import csr_matrix
    e, _ = edges(F)
    w = np.linalg.norm(V[e[:, 0]] - V[e[:, 1]], axis=1)
    n = len(V)
    return csr_matrix((np.concatenate([w, w]), (np.concatenate([e[:, 0], e[:, 1]]),
                                                np.concatenate([e[:, 1], e[:, 0]]))), shape=(n, n))


def height_rank(V):
    """A strict order of the vertices by height: larger z is higher; at equal z
    the smaller index is higher.  rank[i] > rank[j] means i is higher than j."""
    n = len(V)
    order = np.lexsort((-np.arange(n), V[:, 2]))
    rank = np.empty(n, dtype=np.int64)
    rank[order] = np.arange(n)
    return rank


def tips(V, F, radius=TIP_RADIUS, min_fraction=TIP_MIN_FRACTION, graph=None):
    """Indices of the tip vertices (see the module's definition).  A tip must be
    higher than its one-ring, so only those local maxima are searched, each
    by a Dijkstra limited to the radius."""
    from scipy.sparse.csgraph import dijkstra
    n = len(V)
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    rank = height_rank(V)
    e, _ = edges(F)
    nbr = np.full(n, -1, dtype=np.int64)
    np.maximum.at(nbr, e[:, 0], rank[e[:, 1]])
    np.maximum.at(nbr, e[:, 1], rank[e[:, 0]])
    h = V[:, 2].max()
    cand = np.nonzero((rank > nbr) & (V[:, 2] > min_fraction * h))[0]
    if graph is None:
        graph = edge_graph(V, F)
    out = []
    for s in range(0, len(cand), 256):
        c = cand[s:s + 256]
        d = dijkstra(graph, directed=False, indices=c, limit=radius)
        near = d <= radius
        higher = rank[None, :] > rank[c][:, None]
        ok = ~np.any(near & higher, axis=1)
        out.append(c[ok])
    return np.concatenate(out) if out else np.zeros(0, dtype=np.int64)


def tip_spacing(V, t):
    """Mean straight-line distance from each tip to its nearest other tip (NaN below two tips)."""
    if len(t) < 2:
        return float("nan")
    p = V[t]
    d = np.linalg.norm(p[:, None, :] - p[None, :, :], axis=2)
    np.fill_diagonal(d, np.inf)
    return float(d.min(axis=1).mean())


def spread(V, F, c=None):
    """The sponge's horizontal reach: the largest x-y distance of a vertex
    from the vertical axis through the solid's centroid (cm).  How far the
    sponge spreads out sideways, whatever its number of tips."""
    if c is None:
        c = centroid(V, F)
    return float(np.hypot(V[:, 0] - c[0], V[:, 1] - c[1]).max())


def surface_metrics(V, F):
    """Every metric of one surface, as a JSON-ready dict."""
    e, counts = edges(F)
    vol = volume(V, F)
    a = area(V, F)
    t = tips(V, F)
    c = centroid(V, F) if vol != 0 else np.full(3, np.nan)
    ba = base_area(V, F)
    return {
        "vertices": int(len(V)),
        "triangles": int(len(F)),
        "closed": bool(len(counts) and np.all(counts == 2)),
        "volume_cm3": vol,
        "area_cm2": a,
        "height_cm": float(V[:, 2].max()),
        "surface_to_volume_per_cm": a / vol if vol > 0 else float("nan"),
        "base_area_cm2": ba,
        "base_hull_area_cm2": base_hull_area(V),
        "spread_cm": spread(V, F, c) if vol != 0 else float("nan"),
        "exposed_area_cm2": a - ba,
        "centroid_cm": [float(x) for x in c],
        "bbox_min_cm": [float(x) for x in V.min(axis=0)],
        "bbox_max_cm": [float(x) for x in V.max(axis=0)],
        "tips": int(len(t)),
        "tip_spacing_cm": tip_spacing(V, t),
        "tip_positions_cm": [[float(x) for x in V[i]] for i in t],
    }
