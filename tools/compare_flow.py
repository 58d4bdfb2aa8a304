#!/usr/bin/python3
"""Compares the velocity of two sessile runs on the same nutrient box, e.g. the
flow solved at fluid_resolution 1 (interpolated to the box) against level 2.

usage: tools/compare_flow.py RUN_A RUN_B [--iter N] [--png FILE]

Reads fields/iter_NNNN.vtu of both runs (VTK's reader: Debian python3-vtk9,
run with /usr/bin/python3), and prints, over the water nodes of both runs
(solid mask 0 in both), the RMS and largest |u_A - u_B| relative to the inlet
speed, also split into nodes near the sponge (within 2 cm of a solid node) and
the rest.  --png writes |u| of both runs and |u_A - u_B| on the y-plane through
the sponge's centre, side by side (needs python3-pil).  Reference figures:
docs/fluid.md, "Flow resolution".
"""
import argparse
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def load(run, it):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(f"{run}/fields/iter_{it:04d}.vtu")
    r.Update()
    g = r.GetOutput()
    if g.GetNumberOfPoints() == 0:
        sys.exit(f"compare_flow: no points in {run}/fields/iter_{it:04d}.vtu")
    pd = g.GetPointData()
    if pd.GetArray("u") is None:
        sys.exit(f"compare_flow: {run} has no velocity at iteration {it} (flow not solved there)")
    x = vtk_to_numpy(g.GetPoints().GetData()).astype(float)
    return x, vtk_to_numpy(pd.GetArray("u")).astype(float), vtk_to_numpy(pd.GetArray("solid"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run_a")
    ap.add_argument("run_b")
    ap.add_argument("--iter", type=int, default=1)
    ap.add_argument("--inlet", type=float, default=0.05, help="inlet speed in m/s (default 0.05)")
    ap.add_argument("--png")
    a = ap.parse_args()
    xa, ua, sa = load(a.run_a, a.iter)
    xb, ub, sb = load(a.run_b, a.iter)
    if xa.shape != xb.shape or np.abs(xa - xb).max() > 1e-9:
        sys.exit("compare_flow: the two runs are not on the same nutrient box")
    water = (sa == 0) & (sb == 0)
    d = np.linalg.norm(ua - ub, axis=1) / a.inlet
    # distance to the nearest solid node (either run), on the box grid
    solid = (sa != 0) | (sb != 0)
    xs = xa[solid]
    near = np.zeros(len(xa), bool)
    if len(xs):
        lo, hi = xs.min(0) - 2.0, xs.max(0) + 2.0
        box = np.all((xa >= lo) & (xa <= hi), axis=1)
        cand = np.nonzero(box & water)[0]
        for k in range(0, len(cand), 4096):
            c = cand[k:k + 4096]
            dist = np.sqrt(((xa[c, None, :] - xs[None, :, :]) ** 2).sum(-1)).min(1)
            near[c] = dist <= 2.0
    for name, sel in (("all water nodes", water), ("within 2 cm of the sponge", water & near),
                      ("farther than 2 cm", water & ~near)):
        if sel.any():
            print(f"{name:28s} {sel.sum():8d} nodes: |u_A - u_B| / U  RMS {np.sqrt((d[sel]**2).mean()):.4f}"
                  f"  max {d[sel].max():.4f}")
    if a.png:
        try:
            from PIL import Image
        except ImportError:
            sys.exit("compare_flow: --png needs PIL (apt-get install python3-pil)")
        yc = np.median(xa[solid][:, 1]) if solid.any() else np.median(xa[:, 1])
        ys = np.unique(xa[:, 1])
        y0 = ys[np.abs(ys - yc).argmin()]
        on = np.abs(xa[:, 1] - y0) < 1e-9
        xs_, zs_ = np.unique(xa[on, 0]), np.unique(xa[on, 2])
        ix = np.searchsorted(xs_, xa[on, 0])
        iz = np.searchsorted(zs_, xa[on, 2])

        def img(v, vmax):
            m = np.zeros((len(zs_), len(xs_)))
            m[iz, ix] = v
            m = np.clip(m / vmax, 0, 1)[::-1]  # z up
            return (255 * m).astype(np.uint8)

        ma = np.linalg.norm(ua[on], axis=1)
        mb = np.linalg.norm(ub[on], axis=1)
        vmax = max(ma.max(), mb.max())
        tiles = [img(ma, vmax), img(mb, vmax), img(d[on] * a.inlet, 0.25 * vmax)]
        gap = np.full((len(zs_), 4), 255, np.uint8)
        row = np.concatenate([tiles[0], gap, tiles[1], gap, tiles[2]], axis=1)
        im = Image.fromarray(row).resize((row.shape[1] * 4, row.shape[0] * 4), Image.NEAREST)
        im.save(a.png)
        print(f"wrote {a.png}: |u| of A and B (0..{vmax:.3f} m/s) and |u_A - u_B| (0..{0.25*vmax:.3f}) "
              f"on y = {y0:.2f} cm")


if __name__ == "__main__":
    main()
