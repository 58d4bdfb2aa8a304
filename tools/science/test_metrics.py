#!/usr/bin/python3
"""Tests of tools/science/metrics.py on shapes with known answers.

usage: tools/science/test_metrics.py [SPHERE.ply]

SPHERE.ply: an icosphere of radius 2 centred at the origin without noise
(`sessile sphere --set level=5 --set radius=2 --set noise=0`); without it
the test builds the same icosphere itself.  Prints PASS/FAIL lines and exits
non-zero on any failure.
"""
import math
import os
import struct
import sys
import tempfile

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import metrics  # noqa: E402

fails = 0


def check(what, ok, detail=""):
    global fails
    print(("PASS " if ok else "FAIL ") + what + (f" ({detail})" if detail else ""))
    if not ok:
        fails += 1


def write_ply(path, V, F):
    """The PLY layout sessile writes: float x y z nx ny nz; uchar count + uint indices."""
    with open(path, "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\ncomment test\nelement vertex {len(V)}\n"
                 "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                 f"property float nz\nelement face {len(F)}\nproperty list uchar uint vertex_indices\n"
                 "end_header\n").encode())
        vv = np.zeros((len(V), 6), dtype="<f4")
        vv[:, :3] = V
        f.write(vv.tobytes())
        for t in F:
            f.write(struct.pack("<BIII", 3, *map(int, t)))


def icosphere(level, r):
    """Level 1 = the icosahedron; every level splits each triangle in 4."""
    p = (1 + 5 ** 0.5) / 2
    V = [(-1, p, 0), (1, p, 0), (-1, -p, 0), (1, -p, 0), (0, -1, p), (0, 1, p), (0, -1, -p), (0, 1, -p),
         (p, 0, -1), (p, 0, 1), (-p, 0, -1), (-p, 0, 1)]
    V = [np.array(v, float) / np.linalg.norm(v) for v in V]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    for _ in range(level - 1):
        mid = {}

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                v = V[a] + V[b]
                V.append(v / np.linalg.norm(v))
                mid[k] = len(V) - 1
            return mid[k]
        G = []
        for a, b, c in F:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            G += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        F = G
    return np.array(V) * r, np.array(F, dtype=np.int64)


def heightfield(n, h, f):
    """A closed solid: the surface z = f(x, y) over [0, (n-1)h]^2 on top, z = 0
    below, vertical walls around; every quad split along the same diagonal."""
    xs = np.arange(n) * h
    X, Y = np.meshgrid(xs, xs, indexing="ij")
    Z = f(X, Y)
    top = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    bot = np.stack([X.ravel(), Y.ravel(), np.zeros(n * n)], axis=1)
    V = np.concatenate([top, bot])
    idx = np.arange(n * n).reshape(n, n)
    F = []
    for i in range(n - 1):
        for j in range(n - 1):
            a, b, c, d = idx[i, j], idx[i + 1, j], idx[i + 1, j + 1], idx[i, j + 1]
            F += [(a, b, c), (a, c, d)]                              # top, normal +z
            F += [(a + n * n, c + n * n, b + n * n), (a + n * n, d + n * n, c + n * n)]  # bottom, -z
    ring = ([idx[i, 0] for i in range(n - 1)] + [idx[n - 1, j] for j in range(n - 1)]
            + [idx[i, n - 1] for i in range(n - 1, 0, -1)] + [idx[0, j] for j in range(n - 1, 0, -1)])
    for k in range(len(ring)):  # the ring runs counter-clockwise seen from +z
        a, b = ring[k], ring[(k + 1) % len(ring)]
        F += [(a, a + n * n, b + n * n), (a, b + n * n, b)]
    return V, np.array(F, dtype=np.int64), Z


def main():
    sphere_ply = sys.argv[1] if len(sys.argv) > 1 else None
    tmp = tempfile.mkdtemp()

    # 1. A unit cube, through the PLY reader: volume, area, centroid, base.
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    V += [2.0, 3.0, 0.0]
    F = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5],
                  [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    write_ply(os.path.join(tmp, "cube.ply"), V, F)
    V2, F2 = metrics.read_ply(os.path.join(tmp, "cube.ply"))
    check("PLY reader: the cube's vertices and faces back", np.allclose(V2, V) and np.array_equal(F2, F))
    m = metrics.surface_metrics(V2, F2)
    check("cube: volume 1", abs(m["volume_cm3"] - 1) < 1e-12, m["volume_cm3"])
    check("cube: area 6", abs(m["area_cm2"] - 6) < 1e-12, m["area_cm2"])
    check("cube: centroid (2.5, 3.5, 0.5)", np.allclose(m["centroid_cm"], [2.5, 3.5, 0.5]), m["centroid_cm"])
    check("cube: base area 1, hull 1", abs(m["base_area_cm2"] - 1) < 1e-12 and abs(m["base_hull_area_cm2"] - 1) < 1e-12)
    check("cube: closed, height 1, S/V 6", m["closed"] and m["height_cm"] == 1 and abs(m["surface_to_volume_per_cm"] - 6) < 1e-12)
    check("cube turned inside out: volume -1", abs(metrics.volume(V, F[:, ::-1]) + 1) < 1e-12)
    check("cube: spread sqrt(1/2) (a corner from the centroid's axis)", abs(m["spread_cm"] - math.sqrt(0.5)) < 1e-12,
          m["spread_cm"])
    check("cube with a face missing: not closed", not metrics.surface_metrics(V, F[:-1])["closed"])

    # 2. The icosphere (sessile's, or ours), radius 2.  The polyhedron lies
    # between the sphere through its vertices and the ball touching its
    # nearest face plane, so its volume and area lie between those balls'.
    R = 2.0
    if sphere_ply:
        V, F = metrics.read_ply(sphere_ply)
        src = "sessile sphere"
        r_mean = np.linalg.norm(V, axis=1)
        check(f"{src}: vertices on the sphere of radius 2", np.all(np.abs(r_mean - R) < 1e-5), r_mean.max())
    else:
        V, F = icosphere(5, R)
        src = "icosphere level 5"
    v0, v1, v2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    n = np.cross(v1 - v0, v2 - v0)
    dmin = np.min(np.abs(np.einsum("ij,ij->i", n / np.linalg.norm(n, axis=1)[:, None], v0)))
    vol, ar = metrics.volume(V, F), metrics.area(V, F)
    check(f"{src}: volume between the inscribed and circumscribed balls' ({len(V)} vertices)",
          4 / 3 * math.pi * dmin ** 3 <= vol <= 4 / 3 * math.pi * R ** 3,
          f"{vol:.5f} in [{4 / 3 * math.pi * dmin ** 3:.5f}, {4 / 3 * math.pi * R ** 3:.5f}]")
    check(f"{src}: area between the balls'", 4 * math.pi * dmin ** 2 <= ar <= 4 * math.pi * R ** 2,
          f"{ar:.5f} in [{4 * math.pi * dmin ** 2:.5f}, {4 * math.pi * R ** 2:.5f}]")
    check(f"{src}: volume and area within 0.5 % of the sphere's",
          abs(vol / (4 / 3 * math.pi * R ** 3) - 1) < 5e-3 and abs(ar / (4 * math.pi * R ** 2) - 1) < 5e-3)
    check(f"{src}: centroid at the centre", np.allclose(metrics.centroid(V, F), 0, atol=1e-9))

    # 3. The same icosphere as a dome on the substratum (the lower half
    # flattened onto z = 0, as sessile starts a sponge): half the volume, a
    # base of area about pi R^2.
    D = V.copy()
    D[:, 2] = np.maximum(D[:, 2], 0)
    D[:, :2] += 10.0
    m = metrics.surface_metrics(D, F)
    check("dome: volume about half the sphere's (within 1 %)", abs(m["volume_cm3"] / (2 / 3 * math.pi * R ** 3) - 1) < 1e-2,
          m["volume_cm3"])
    check("dome: base area and hull area within 1 % of pi R^2",
          abs(m["base_area_cm2"] / (math.pi * R ** 2) - 1) < 1e-2 and abs(m["base_hull_area_cm2"] / (math.pi * R ** 2) - 1) < 1e-2,
          f"{m['base_area_cm2']:.4f}, {m['base_hull_area_cm2']:.4f}, pi R^2 = {math.pi * R * R:.4f}")
    check("dome: height R, one tip at the top", abs(m["height_cm"] - R) < 1e-9 and m["tips"] == 1
          and abs(m["tip_positions_cm"][0][2] - R) < 1e-9)
    check("dome: spread R (the base's rim)", abs(m["spread_cm"] / R - 1) < 1e-6, m["spread_cm"])
    check("dome: centroid 3R/8 above the base (within 1 %)", abs(m["centroid_cm"][2] / (3 * R / 8) - 1) < 1e-2,
          m["centroid_cm"][2])

    # 4. Extrusions on a height field: 3 x 3 spikes 4 cm apart on a plateau
    # of height 1, each a Gaussian of height 3 centred on a grid vertex.
    h = 0.25
    cs = [2.0 + 4.0 * k for k in range(3)]

    def spikes(X, Y):
        Z = np.ones_like(X)
        for cx in cs:
            for cy in cs:
                Z += 3.0 * np.exp(-((X - cx) ** 2 + (Y - cy) ** 2) / (2 * 0.6 ** 2))
        return Z
    V, F, Z = heightfield(49, h, spikes)
    m = metrics.surface_metrics(V, F)
    # Volume under a triangulated height field: each top triangle's xy area times its mean z.
    top = F[np.all(F < 49 * 49, axis=1)]
    p = V[top]
    axy = 0.5 * np.abs((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    vref = float(np.sum(axy * p[:, :, 2].mean(axis=1)))
    check("height field: closed; volume = sum of prisms under the top triangles",
          m["closed"] and abs(m["volume_cm3"] - vref) < 1e-9 * vref, f"{m['volume_cm3']:.9f} vs {vref:.9f}")
    check("height field: base area = the square's", abs(m["base_area_cm2"] - (48 * h) ** 2) < 1e-9)
    check("height field: 9 tips, at the spike centres", m["tips"] == 9 and sorted(
        (round(t[0], 6), round(t[1], 6)) for t in m["tip_positions_cm"]) == sorted((x, y) for x in cs for y in cs),
        f"{m['tips']} tips")
    check("height field: tip spacing 4 cm", abs(m["tip_spacing_cm"] - 4.0) < 1e-9, m["tip_spacing_cm"])

    # 5. The tip search (one-ring maxima, Dijkstra from those only) against
    # the definition applied to every vertex, on a rough random height field.
    from scipy.sparse.csgraph import dijkstra
    rng = np.random.default_rng(5)
    bumps = [(rng.uniform(0, 7), rng.uniform(0, 7), rng.uniform(0.5, 3), rng.uniform(0.3, 1.2)) for _ in range(25)]

    def rough(X, Y):
        Z = 0.5 + 0.05 * np.sin(7 * X) * np.cos(5 * Y)
        for bx, by, a, s in bumps:
            Z += a * np.exp(-((X - bx) ** 2 + (Y - by) ** 2) / (2 * s * s))
        return Z
    V, F, _ = heightfield(29, 0.25, rough)
    got = set(metrics.tips(V, F).tolist())
    D = dijkstra(metrics.edge_graph(V, F), directed=False)
    rank = metrics.height_rank(V)
    hmax = V[:, 2].max()
    want = {i for i in range(len(V)) if V[i, 2] > 0.5 * hmax and not np.any((D[i] <= 2.0) & (rank > rank[i]))}
    check("tips: the fast search finds exactly the vertices the definition picks", got == want,
          f"{len(got)} found, {len(want)} by brute force")
    check("tips: every tip is above half the height", all(V[i, 2] > 0.5 * hmax for i in got))

    print(f"{'all passed' if fails == 0 else f'{fails} failed'}")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
