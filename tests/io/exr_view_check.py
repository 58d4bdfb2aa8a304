#!/usr/bin/python3
"""A sessile EXR slice read with OpenImageIO (python3-openimageio) against
the field it was written from:
    exr_view_check.py SAMPLES_DIR COLORMAP_C
slice_z.exr (c = 1+2x+3y+4z, ux = x-y on z = 0.6, origin (-1, 0.5),
spacing 0.25, 9 x 7), plane.exr (the oblique plane, 8 x 4) and signed.exr
(s = (i-2)(j+1), NaN at (7, 0)), each checked:
  - rows top-down as EXR expects: image row y holds the plane's row
    j = height-1-y, so the top row is the highest coordinate along v;
  - R, G, B (half) = the colour map `render --color-by` picks for the view
    channel (viridis; coolwarm symmetric about 0 for a range across 0; NaN
    grey 128) with sRGB decoded to linear, to half precision.
The map's tables are read from COLORMAP_C (the ones render uses); their
ends are checked against matplotlib's published colours first."""
import math
import re
import sys

import numpy as np
import OpenImageIO as oiio

d, cmap_c = sys.argv[1:3]
fails = 0


def check(what, ok, detail=""):
    global fails
    print(("PASS " if ok else "FAIL ") + what + (f"  ({detail})" if detail else ""))
    fails += 0 if ok else 1


def tables(path):
    text = open(path).read()
    out = {}
    for name in ("viridis", "coolwarm"):
        body = re.search(name + r"_table\[256\]\[3\] = \{(.*?)\};", text, re.S)[1]
        out[name] = np.array([int(v) for v in re.findall(r"\d+", body)]).reshape(256, 3)
    return out


T = tables(cmap_c)
check("the tables' ends are matplotlib's: viridis #440154..#fde725, coolwarm #3b4cc0..#b40426",
      T["viridis"][0].tolist() == [68, 1, 84] and T["viridis"][255].tolist() == [253, 231, 37] and
      T["coolwarm"][0].tolist() == [59, 76, 192] and T["coolwarm"][255].tolist() == [180, 4, 38])


def linear(c):
    v = c / 255.0
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def expected_rgb(vals):
    """What --color-by shows for vals (float32 as stored), linear light."""
    fin = vals[np.isfinite(vals)].astype(np.float64)
    lo, hi = (fin.min(), fin.max()) if fin.size else (0.0, 0.0)
    name = "coolwarm" if lo < 0 < hi else "viridis"
    if name == "coolwarm":
        lo, hi = -max(-lo, hi), max(-lo, hi)
    t = (vals.astype(np.float64) - lo) / (hi - lo) if hi > lo else np.full(vals.shape, 0.5)
    idx = np.clip(np.floor(np.nan_to_num(t) * 256), 0, 255).astype(int)
    rgb = T[name][idx].astype(np.float64)
    rgb[~np.isfinite(vals)] = 128
    return linear(rgb), name, lo, hi


def read(name):
    inp = oiio.ImageInput.open(f"{d}/{name}")
    if not inp:
        check(f"OpenImageIO opens {name}", False, oiio.geterror())
        return None, None
    spec = inp.spec()
    px = inp.read_image(oiio.FLOAT)  # [row y][column x][channel]
    inp.close()
    return spec, px


def check_file(name, view, formula, w, h):
    """formula(i, j) -> {channel: value} at the plane's pixel (i, j)."""
    spec, px = read(name)
    if spec is None:
        return
    ch = list(spec.channelnames)
    check(f"{name}: {w} x {h}, R G B half first, top-down, view of '{view}'",
          spec.width == w and spec.height == h and ch[:3] == ["R", "G", "B"] and
          [spec.channelformat(k) for k in range(3)] == [oiio.HALF] * 3 and
          spec.getattribute("sessile:row_order") == "top-down" and
          spec.getattribute("sessile:view_channel") == view, f"{spec.width} x {spec.height} {ch}")
    err, top = 0.0, None
    for y in range(h):
        for i in range(w):
            j = h - 1 - y  # image row 0 is the plane's top row
            for c, want in formula(i, j).items():
                got = px[y, i, ch.index(c)]
                if math.isnan(want):
                    err = max(err, 0 if math.isnan(got) else math.inf)
                else:
                    err = max(err, abs(got - want) / max(1.0, abs(want)))
    check(f"{name}: pixel (x, y) holds the field at the plane's (x, height-1-y): the top row is the highest v",
          err <= 1e-6, f"max relative error {err:.1e}")
    vals = px[:, :, ch.index(view)]
    want, mapname, lo, hi = expected_rgb(vals)
    got = px[:, :, 0:3]
    e = np.abs(got - want) / np.maximum(want, 2.0**-14)
    check(f"{name}: R, G, B == {mapname} over [{lo:g}, {hi:g}] of '{view}' (linear, to half precision)",
          e.max() <= 2.0**-11 and spec.getattribute("sessile:view_colormap") == mapname,
          f"max relative error {e.max():.1e}")
    r = spec.getattribute("sessile:view_range")
    check(f"{name}: sessile:view_range == [{lo:g}, {hi:g}]", r is not None and tuple(r) == (lo, hi), f"{r}")


def slice_z(i, j):
    x, y, z = -1 + 0.25 * i, 0.5 + 0.25 * j, 0.6
    return {"c": 1 + 2 * x + 3 * y + 4 * z, "ux": x - y}


def oblique(i, j):
    s = 0.125 * i / math.sqrt(2)
    x, y, z = -0.5 + s, 0.25 + s, 1 + 0.25 * j
    return {"c": 1 + 2 * x + 3 * y + 4 * z, "d": x - y}


check_file("slice_z.exr", "c", slice_z, 9, 7)
check_file("plane.exr", "c", oblique, 8, 4)
check_file("signed.exr", "s", lambda i, j: {"s": math.nan if (i, j) == (7, 0) else (i - 2.0) * (j + 1)}, 8, 4)
sys.exit(1 if fails else 0)
