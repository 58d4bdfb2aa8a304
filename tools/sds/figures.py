"""The paper's figures as measured outcomes (issue 33), from a run's own output.

  figures.py limb RUN_DIR [--frame K | --time T] [--axis X Y Z] [--slice H] [--width section|extent]
      Figure 7: the profile along the limb's axis (width and interior cells
      per slice), distal width / neck width, the tip's lead, length / neck;
      the width the complex's cross-section (section, the default) or the
      centres' extent per slice (the measure before 2026-12-04).
  figures.py stripes RUN_DIR [--frame K | --time T] [--field NAME] [--threshold F] [--bin H] [--mask NAME]
                     [--ref REF]
      Figures 9, 12: per limb, the stripe state along the limb (graph distance
      from its tip through the complex), stripes counted and their spacing;
      with --ref (the model with the timer's decay doubled) the ratio of the
      mean spacings, which should be 2 (+- --tolerance).
      With --mask NAME only the cells whose state NAME is set (a state the
      rules set in the growth zone: the limb's own tissue) fill the bins.
  figures.py cells RUN_DIR [--from T0] [--to T1]
      Figure 12: cells against time from records.jsonl, a line fitted over
      [T0, T1] and its R^2.
  figures.py bend RUN_DIR [--ref REF_DIR] [--frame K | --time T] [--min-bend DEG]
      Figure 8: the angle each limb turns between its middle and its tip,
      against the same in an unboxed run REF_DIR.
  figures.py attract RUN_DIR [--ref REF_DIR] [--frame K | --time T] [--point X Y Z]
      Figure 10: the tips' mean distance to the attraction point, against the
      same in a run without the attraction (REF_DIR) or at the start.
  figures.py buds RUN_DIR [--frame K | --time T] [--field NAME] [--min-growth F] [--max-distance F]
      Figure 11: the bud cells' total volume, at the frame chosen against
      the first frame that has bud cells; and where they are (their mean
      distance to the nearest tip through the complex against every cell's).
  figures.py rock RUN_DIR [--frame K | --time T]
      Figure 9: the body upon its rock (the cells' centroid within the body's
      starting radius of the rock's vertical axis) and its limbs over it
      (the tips' mean height below the rock's top).
  figures.py divisions RUN_DIR [--first K] [--window W]
      Figure 12: which limb divided when (sds/divisions.csv; each dividing
      cell goes to the limb of the tip nearest it through the complex in the
      first frame at or after the division): per limb its divisions per
      window of W time units, and whether the limbs' k-th divisions (k <= K)
      fall within one inter-division interval of each other.

Each prints a small table, then one JSON line (the last line) with the
metrics and the acceptance criteria of issue 33.  The definitions and the
reasons for them are in docs/sds_figures.md.  Reads
sessile's frames: sds/frame_NNNN.vtu (every cell, its `surface` flag and
fields) and, without a VTU, sds/frame_NNNN.ply (the surface alone: no
interior counts)."""
import argparse
import heapq
import json
import os
import re
import sys
import zlib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import limb  # noqa: E402  (the PLY reader)

VTK_TYPES = {"Float64": "<f8", "Float32": "<f4", "UInt8": "u1", "Int32": "<i4", "Int64": "<i8"}


def read_vtu(path):
    """sessile's VTU (appended raw, vtkZLibDataCompressor, UInt64 headers):
    {'x': points (n, 3), 'tets': (m, 4), point fields by name}."""
    with open(path, "rb") as f:
        data = f.read()
    mark = data.index(b'<AppendedData encoding="raw">')
    base = data.index(b"_", mark) + 1
    head = data[:mark].decode()
    assert 'header_type="UInt64"' in head and "vtkZLibDataCompressor" in head, path

    def blob(dtype, offset):
        nb, _, _ = np.frombuffer(data, "<u8", 3, base + offset)
        sizes = np.frombuffer(data, "<u8", int(nb), base + offset + 24)
        p, raw = base + offset + 24 + 8 * int(nb), b""
        for s in sizes:
            raw += zlib.decompress(data[p:p + int(s)])
            p += int(s)
        return np.frombuffer(raw, dtype)

    out, section = {}, None
    for line in head.splitlines():
        tag = re.match(r"\s*<(\w+)", line)
        if tag and tag.group(1) in ("PointData", "CellData", "Points", "Cells"):
            section = tag.group(1)
        if not (tag and tag.group(1) == "DataArray"):
            continue
        a = dict(re.findall(r'(\w+)="([^"]*)"', line))
        v = blob(VTK_TYPES[a["type"]], int(a["offset"]))
        k = int(a["NumberOfComponents"])
        if section == "Points":
            out["x"] = v.reshape(-1, 3).astype(float)
        elif section == "Cells" and a["Name"] == "connectivity":
            out["tets"] = v.reshape(-1, 4).astype(np.int64)
        elif section == "PointData":
            out[a["Name"]] = v.reshape(-1, k).astype(float) if k > 1 else v.astype(float)
    return out


def load_frame(run, k):
    """Frame k's cells: x, surface (bool), radius, tip and the model's fields;
    'complex' says whether the interior is known (the VTU) or not (a PLY)."""
    vtu = "%s/sds/frame_%04d.vtu" % (run, k)
    if os.path.exists(vtu):
        c = read_vtu(vtu)
        used = np.zeros(len(c["x"]), bool)
        used[c["tets"].ravel()] = True  # cells of no tet are not part of the body
        c.update(surface=c["surface"] > 0, used=used, complex=True)
        return c
    p = limb.read_ply("%s/sds/frame_%04d.ply" % (run, k))
    p["x"] = np.stack([p["x"], p["y"], p["z"]], 1)
    p.update(surface=np.ones(len(p["x"]), bool), used=np.ones(len(p["x"]), bool), complex=False)
    return p


def frames(run):
    """[(frame, time)] from records.jsonl (frame 0 at t = 0 when it has none)."""
    out = {}
    path = run + "/records.jsonl"
    if os.path.exists(path):
        for line in open(path):
            r = json.loads(line)
            if "frame" in r and "time" in r:
                out[int(r["frame"])] = float(r["time"])
    if not out:  # a synthetic run: the files alone
        names = sorted(f for f in os.listdir(run + "/sds") if re.match(r"frame_\d{4}\.(ply|vtu)$", f))
        out = {int(f[6:10]): float(f[6:10]) for f in names}
    return sorted(out.items())


def pick_frame(run, args):
    fr = frames(run)
    if args.frame is not None:
        return [f for f in fr if f[0] == args.frame][0]
    if args.time is not None:
        return min(fr, key=lambda f: abs(f[1] - args.time))
    return fr[-1]


def model_value(run, key, default):
    """A plain key of the run's model (sds/model.sds), e.g. sphere_radius."""
    try:
        for line in open(run + "/sds/model.sds"):
            m = re.match(r"\s*%s\s*=\s*([-+0-9.eE]+)" % key, line)
            if m:
                return float(m.group(1))
    except OSError:
        pass
    return default


def diameter(p):
    """The largest distance between two of the points (0 for fewer than 2)."""
    if len(p) < 2:
        return 0.0
    d = p[:, None, :] - p[None, :, :]
    return float(np.sqrt((d * d).sum(-1)).max())


# the six edges of a tet
TET_EDGES = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))


def section_areas(x, tets, axis, origin, us):
    """The area of the complex's section by each plane (x - origin) . axis = u,
    u in us: over the tets the plane cuts, the area of each one's section, a
    convex triangle or quadrilateral whose corners are where the plane
    crosses the tet's edges (a corner on the plane counts as above it, so a
    face in the plane is counted once).  Sum over a fine grid of planes times
    the spacing is the complex's volume (test_sds_figures checks it)."""
    P = x[tets]                                   # (m, 4, 3)
    U = (P - origin) @ axis                       # (m, 4)
    e1 = np.cross(axis, [1.0, 0, 0] if abs(axis[0]) < 0.9 else [0, 1.0, 0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    lo, hi = U.min(1), U.max(1)
    out = np.zeros(len(us))
    for j, u0 in enumerate(us):
        cut = (lo < u0) & (hi >= u0)
        if not cut.any():
            continue
        Pj, Uj = P[cut], U[cut] - u0
        a1 = np.full((len(Pj), 6), np.nan)
        a2 = np.full((len(Pj), 6), np.nan)
        for k, (a, b) in enumerate(TET_EDGES):
            ua, ub = Uj[:, a], Uj[:, b]
            cross = (ua >= 0) != (ub >= 0)
            t = np.where(cross, ua / np.where(cross, ua - ub, 1.0), 0.0)
            q = Pj[:, a] + t[:, None] * (Pj[:, b] - Pj[:, a])
            a1[cross, k], a2[cross, k] = q[cross] @ e1, q[cross] @ e2
        n = (~np.isnan(a1)).sum(1)                # 3 or 4 corners
        m1 = np.nanmean(a1, 1)[:, None]
        m2 = np.nanmean(a2, 1)[:, None]
        order = np.argsort(np.where(np.isnan(a1), np.inf, np.arctan2(a2 - m2, a1 - m1)), 1)
        b1 = np.take_along_axis(a1, order, 1)     # the corners round their mean, then the NaNs
        b2 = np.take_along_axis(a2, order, 1)
        nxt = (np.arange(6)[None, :] + 1) % n[:, None]
        c1, c2 = np.take_along_axis(b1, nxt, 1), np.take_along_axis(b2, nxt, 1)
        term = np.where(np.arange(6)[None, :] < n[:, None], b1 * c2 - b2 * c1, 0.0)
        out[j] = 0.5 * np.abs(term.sum(1)).sum()
    return out


def slab_widths(c, axis, origin, centres, h, per=8):
    """The width of the complex round each centre: the diameter of the disc
    whose area is the mean section over the slab [u - h/2, u + h/2] (about
    its volume over h: the mean of `per` planes at the slab's midpoints)."""
    off = (np.arange(per) + 0.5) / per * h - h / 2
    us = (np.asarray(centres, float)[:, None] + off[None, :]).ravel()
    # centres h/per apart share their planes: each distinct plane cut once
    uq, inv = np.unique(np.round(us, 12), return_inverse=True)
    A = section_areas(c["x"], c["tets"], axis, origin, uq)[inv].reshape(-1, per).mean(1)
    return 2 * np.sqrt(A / np.pi)


def limb_profile(c, axis, origin, r0, h=None, width="section"):
    """Figure 7's metrics of one frame (docs/sds_figures.md, "How the limb's
    width is measured").  width "section": the complex's cross-section as
    the diameter of a disc of its area, averaged over one cell diameter
    along the axis, on a grid of an eighth of that; the neck is its least in
    the limb's proximal half, the distal width its largest in the distal
    half.  width "extent" (before 2026-12-04, and the only one for PLY
    frames, which have no tets): per slice one cell thick the largest
    distance between two cell centres in it; its distal / neck ratio swung
    by 0.19 on average (up to 0.45) between frames 10 time units apart on
    limb_extension's limbs, the section's by 0.042."""
    if width == "section" and not c["complex"]:
        width = "extent"
    keep = c["used"]
    x, surf, rad = c["x"][keep], c["surface"][keep], c["radius"][keep]
    tips = np.flatnonzero(c["tip"][keep] >= 0.5)
    assert len(tips) == 1, "one tip cell, found %d" % len(tips)
    u = (x - origin) @ axis
    perp = (x - origin) - np.outer(u, axis)
    h = h or 2 * float(np.median(rad))  # one cell thick
    front, tu, rt = u.max(), u[tips[0]], rad[tips[0]]
    length = float(np.ptp(u) - 2 * r0)  # limb.py's L: the extent less the starting diameter
    rows = []  # slices from the front backwards: [front - (i + 1) h, front - i h)
    for i in range(int(np.ceil(np.ptp(u) / h))):
        lo, hi = front - (i + 1) * h, front - i * h
        s = (u >= lo) & ((u < hi) | (i == 0))
        rows.append({"u": float(hi - h / 2), "cells": int(s.sum()), "extent": diameter(perp[s]),
                     "interior": int((s & ~surf).sum()) if c["complex"] else None,
                     "limb": bool(hi - h / 2 >= front - length)})
    if width == "section":
        sw = slab_widths(c, axis, origin, [r["u"] for r in rows], h)
        for r, w in zip(rows, sw):
            r["width"] = float(w)
    else:
        for r in rows:
            r["width"] = r["extent"]
    m = {"width_measure": width, "slice": h, "front": float(front), "tip_u": float(tu), "tip_radius": float(rt),
         "tip_behind_front": float(front - tu), "length": length}
    if width == "section":
        # slab centres every h/8 over the limb, each slab inside it
        centres = np.arange(front - length + h / 2, front - h / 2 + 1e-12, h / 8)
        half = front - length / 2
        prox, dist = centres[centres < half], centres[centres >= half]
        have = length >= 2 * h and len(prox) > 0 and len(dist) > 0
        if have:
            w = slab_widths(c, axis, origin, centres, h)
            wp, wd = w[centres < half], w[centres >= half]
            k = int(np.argmin(wp))
            neck_u, neck_w, distal_w = float(prox[k]), float(wp[k]), float(wd.max())
    else:
        limb_rows = [r for r in rows if r["limb"]]
        # the distal half (nearer the tip) and the proximal half (nearer the body)
        distal = [r for r in limb_rows if r["u"] >= front - length / 2]
        proximal = [r for r in limb_rows if r["u"] < front - length / 2]
        have = bool(distal and proximal)
        if have:
            neck = min(proximal, key=lambda r: r["width"])
            neck_u, neck_w, distal_w = neck["u"], neck["width"], max(r["width"] for r in distal)
    if have:
        # the neck's interior cells: those of the slice [front - (i + 1) h, front - i h) that holds it
        row = rows[min(len(rows) - 1, max(0, int(np.ceil((front - neck_u) / h)) - 1))]
        m.update(neck_u=neck_u, neck_width=neck_w, neck_interior=row["interior"], distal_width=distal_w)
        m["distal_over_neck"] = distal_w / neck_w if neck_w > 0 else None
        m["length_over_neck"] = length / neck_w if neck_w > 0 else None
    else:  # a limb shorter than two slices has no neck to measure
        m.update(neck_u=None, neck_width=None, neck_interior=None, distal_width=None,
                 distal_over_neck=None, length_over_neck=None)
    m["criteria"] = {  # issue 33's acceptance for Figure 7 (t = 200)
        "distal_at_most_1.2_neck": m["distal_over_neck"] is not None and m["distal_over_neck"] <= 1.2,
        "tip_within_one_radius_of_front": bool(m["tip_behind_front"] <= rt),
        "length_at_least_3_necks": m["length_over_neck"] is not None and m["length_over_neck"] >= 3}
    return m, rows


def cmd_limb(args):
    k, t = pick_frame(args.run, args)
    c = load_frame(args.run, k)
    c0 = load_frame(args.run, frames(args.run)[0][0])
    origin = c0["x"][c0["used"]].mean(0)
    if args.axis:
        axis = np.array(args.axis, float)
    else:  # the tip's starting direction from the starting body's centre
        axis = c0["x"][np.flatnonzero(c0["tip"] >= 0.5)[0]] - origin
    axis /= np.linalg.norm(axis)
    m, rows = limb_profile(c, axis, origin, model_value(args.run, "sphere_radius", 1.0), args.slice, args.width)
    print("frame %d, t = %.3f; slices of %.3f u along the axis, from the front back; width: %s" % (
        k, t, m["slice"], "the section's (a disc's diameter of its mean area)" if m["width_measure"] == "section"
        else "the centres' extent"))
    print("%8s %6s %8s %8s %9s %5s" % ("u", "cells", "width", "extent", "interior", "limb"))
    for r in rows:
        print("%8.3f %6d %8.3f %8.3f %9s %5s" % (r["u"], r["cells"], r["width"], r["extent"],
                                                 "-" if r["interior"] is None else r["interior"],
                                                 "*" if r["limb"] else ""))
    print(json.dumps(dict(figure=7, frame=k, time=t, axis=axis.tolist(), profile=rows, **m)))


def graph_distance(x, tets, sources):
    """Distance through the complex's edges from the nearest source, and which."""
    n = len(x)
    nb = [set() for _ in range(n)]
    for t in tets:
        for a in t:
            nb[a].update(int(b) for b in t if b != a)
    dist, owner = np.full(n, np.inf), np.full(n, -1)
    heap = [(0.0, int(s), i) for i, s in enumerate(sources)]
    while heap:
        d, a, i = heapq.heappop(heap)
        if d >= dist[a]:
            continue
        dist[a], owner[a] = d, i
        for b in nb[a]:
            nd = d + float(np.linalg.norm(x[a] - x[b]))
            if nd < dist[b]:
                heapq.heappush(heap, (nd, b, i))
    return dist, owner


def stripe_runs(frac, centres, threshold):
    """Stripes: maximal runs of bins whose stripe fraction passes the threshold;
    each stripe's place is the mean of its bins' centres weighted by fraction."""
    out, run = [], []
    for f, s in list(zip(frac, centres)) + [(0.0, None)]:
        if f >= threshold:
            run.append((f, s))
        elif run:
            w = np.array([r[0] for r in run])
            out.append(float((w * np.array([r[1] for r in run])).sum() / w.sum()))
            run = []
    return out


def stripes_of(run, args, quiet=False):
    """Figure 9's stripes of one run's frame: the metrics and per-limb rows."""
    say = (lambda *a: None) if quiet else print
    k, t = pick_frame(run, args)
    c = load_frame(run, k)
    assert c["complex"], "stripes need the VTU frames (the complex's edges)"
    assert args.field in c, "no field %r in frame %d" % (args.field, k)
    tips = np.flatnonzero((c["tip"] >= 0.5) & c["used"])
    dist, owner = graph_distance(c["x"], c["tets"], tips)
    h = args.bin or 2 * float(np.median(c["radius"][c["used"]]))
    limbs = []
    say("frame %d, t = %.3f; field %s > %.3g, bins of %.3f u from each tip; a stripe: fraction >= %.2f"
        % (k, t, args.field, args.on, h, args.threshold))
    if args.mask:  # the limb's own tissue: cells whose mask state is set (the body's left out)
        assert args.mask in c, "no field %r in frame %d (the mask)" % (args.mask, k)
    for i, tip in enumerate(tips):
        mine = (owner == i) & c["used"]
        if args.mask:  # distances still run through every cell; only the bins leave the others out
            mine &= (c[args.mask] > 0.5) | (np.arange(len(mine)) == tip)
        s, on = dist[mine], c[args.field][mine] > args.on
        nb = int(np.ceil((s.max() + 1e-12) / h))
        idx = np.minimum(np.floor(s / h + 1e-9).astype(int), nb - 1)  # a cell on a bin's edge: the upper bin
        cnt = np.bincount(idx, minlength=nb)
        frac = np.bincount(idx, weights=on, minlength=nb) / np.maximum(cnt, 1)
        centres = (np.arange(nb) + 0.5) * h
        places = stripe_runs(frac, centres, args.threshold)
        sp = np.diff(places)
        limbs.append({"tip_cell": int(tip), "tip": c["x"][tip].tolist(), "cells": int(mine.sum()),
                      "profile": [round(float(f), 4) for f in frac], "stripes": len(places),
                      "places": places, "spacing": float(sp.mean()) if len(sp) else None})
        say("limb %d (tip cell %d, %d cells): %d stripes at %s; spacing %s" % (
            i, tip, mine.sum(), len(places), " ".join("%.2f" % p for p in places),
            "%.3f" % sp.mean() if len(sp) else "-"))
        say("  profile: " + " ".join("%.2f" % f for f in frac))
    sps = [l["spacing"] for l in limbs if l["spacing"] is not None]
    m = {"figure": 9, "frame": k, "time": t, "field": args.field, "mask": args.mask, "on": args.on,
         "threshold": args.threshold,
         "bin": h, "limbs": limbs, "stripes_min": min((l["stripes"] for l in limbs), default=0),
         "spacing_mean": float(np.mean(sps)) if sps else None,
         "criteria": {"three_stripes_per_limb": bool(limbs) and all(l["stripes"] >= 3 for l in limbs)}}
    return m


def cmd_stripes(args):
    m = stripes_of(args.run, args)
    if args.ref:  # RUN has the timer's decay halved against REF: its spacing should double
        r = stripes_of(args.ref, args, quiet=True)
        ratio = (m["spacing_mean"] / r["spacing_mean"]
                 if m["spacing_mean"] is not None and r["spacing_mean"] else None)
        m.update(ref=args.ref, ref_spacing_mean=r["spacing_mean"], ref_stripes_min=r["stripes_min"],
                 spacing_ratio=ratio)
        m["criteria"]["spacing_doubles_over_ref"] = ratio is not None and abs(ratio / 2 - 1) <= args.tolerance
        print("mean spacing %s against the reference's %s: ratio %s" % (
            m["spacing_mean"], r["spacing_mean"], "-" if ratio is None else "%.3f" % ratio))
    print(json.dumps(m))


def cmd_cells(args):
    rec = [json.loads(line) for line in open(args.run + "/records.jsonl")]
    tc = np.array([(float(r["time"]), r["cells"]) for r in rec if "time" in r and "cells" in r])
    w = (tc[:, 0] >= args.t0 - 1e-9) & (tc[:, 0] <= args.t1 + 1.0)  # a frame is up to one step late
    print("%10s %7s" % ("t", "cells"))
    for ti, n in tc:
        print("%10.3f %7d%s" % (ti, n, "" if (ti >= args.t0 - 1e-9 and ti <= args.t1 + 1.0) else "  (outside)"))
    m = {"figure": 12, "from": args.t0, "to": args.t1, "points": int(w.sum()), "slope": None, "intercept": None,
         "r2": None}
    if w.sum() >= 3:
        tt, nn = tc[w, 0], tc[w, 1]
        slope, icpt = np.polyfit(tt, nn, 1)
        res = nn - (slope * tt + icpt)
        ss = ((nn - nn.mean()) ** 2).sum()
        m.update(slope=float(slope), intercept=float(icpt), r2=float(1 - (res ** 2).sum() / ss) if ss > 0 else None)
    m["criteria"] = {"linear_r2_at_least_0.98": m["r2"] is not None and m["r2"] >= 0.98}
    print(json.dumps(m))


def tip_cells(c):
    """The tip cells of a frame, in index order (a tip keeps its index: the
    loop gives a dividing tip's index to the daughter that stays the tip)."""
    return np.flatnonzero((c["tip"] >= 0.5) & c["used"])


def tips_now_and_then(run, args):
    """(frame, time, tips at that frame, tips at frame 0, centroid now, centroid at frame 0)."""
    k, t = pick_frame(run, args)
    c, c0 = load_frame(run, k), load_frame(run, frames(run)[0][0])
    i, i0 = tip_cells(c), tip_cells(c0)
    assert len(i) == len(i0) and (i == i0).all(), "the tips changed index between frame 0 and frame %d" % k
    return k, t, c["x"][i], c0["x"][i0], c["x"][c["used"]].mean(0), c0["x"][c0["used"]].mean(0)


def limb_turns(run, args):
    """Per tip the angle (degrees) its limb turns: between the direction from
    the body's centroid to the limb's middle and from the middle to the tip.
    The limb is the cells nearest its tip through the complex (as `stripes`);
    its middle is the mean of those within half a cell diameter of half the
    tip's graph distance to the one nearest the centroid (a cross-section).  0 for a straight limb, whatever its direction;
    a turn of the whole organism does not change it."""
    k, t = pick_frame(run, args)
    c = load_frame(run, k)
    assert c["complex"], "bend needs the VTU frames (the complex's edges)"
    tips = tip_cells(c)
    dist, owner = graph_distance(c["x"], c["tets"], tips)
    ctr = c["x"][c["used"]].mean(0)
    h = 2 * float(np.median(c["radius"][c["used"]]))
    out = []
    for i, tip in enumerate(tips):
        mine = np.flatnonzero((owner == i) & c["used"])
        base = mine[np.argmin(np.linalg.norm(c["x"][mine] - ctr, axis=1))]
        band = mine[np.abs(dist[mine] - dist[base] / 2) <= h / 2]  # a cross-section: its mean is on the axis
        mid = c["x"][band].mean(0) if len(band) else c["x"][mine[np.argmin(np.abs(dist[mine] - dist[base] / 2))]]
        a, b = mid - ctr, c["x"][tip] - mid
        cosv = a @ b / (np.linalg.norm(a) * np.linalg.norm(b))
        out.append(float(np.degrees(np.arccos(np.clip(cosv, -1, 1)))))
    return k, t, np.array(out)


def cmd_bend(args):
    k, t, dev = limb_turns(args.run, args)
    m = {"figure": 8, "frame": k, "time": t, "turn_deg": dev.tolist(), "mean_turn_deg": float(dev.mean())}
    ref = 0.0  # a straight limb's turn
    print("frame %d, t = %.3f: the limbs' turns (deg): %s; mean %.1f" % (k, t, " ".join("%.1f" % d for d in dev),
                                                                           dev.mean()))
    if args.ref:
        rk, rt, rdev = limb_turns(args.ref, args)
        ref = float(rdev.mean())
        m.update(ref_frame=rk, ref_time=rt, ref_turn_deg=rdev.tolist())
        print("reference frame %d, t = %.3f: %s; mean %.1f" % (rk, rt, " ".join("%.1f" % d for d in rdev), ref))
    m["ref_mean_turn_deg"] = ref
    m["excess_deg"] = m["mean_turn_deg"] - ref
    m["criteria"] = {"limbs_bent": bool(m["excess_deg"] >= args.min_bend)}
    print(json.dumps(m))


def attractor_point(run):
    """The model's `attractor = x y z strength` line (sds/model.sds)."""
    for line in open(run + "/sds/model.sds"):
        f = re.match(r"\s*attractor\s*=\s*([-+0-9.eE\s]+)", line)
        if f:
            return np.array([float(v) for v in f.group(1).split()[:3]])
    raise SystemExit("%s: the model has no attractor; give --point" % run)


def cmd_attract(args):
    point = np.array(args.point, float) if args.point else attractor_point(args.run)
    k, t, tp, tp0, _, _ = tips_now_and_then(args.run, args)
    d, d0 = np.linalg.norm(tp - point, axis=1), np.linalg.norm(tp0 - point, axis=1)
    m = {"figure": 10, "frame": k, "time": t, "point": point.tolist(), "distance": d.tolist(),
         "mean_distance": float(d.mean()), "start_mean_distance": float(d0.mean())}
    print("frame %d, t = %.3f: tips' distances to (%g, %g, %g): %s; mean %.3f (at the start %.3f)" % (
        k, t, *point, " ".join("%.2f" % v for v in d), d.mean(), d0.mean()))
    if args.ref:
        rk, rt, rp, _, _, _ = tips_now_and_then(args.ref, args)
        rd = np.linalg.norm(rp - point, axis=1)
        m.update(ref_frame=rk, ref_time=rt, ref_distance=rd.tolist(), ref_mean_distance=float(rd.mean()))
        print("reference frame %d, t = %.3f: %s; mean %.3f" % (rk, rt, " ".join("%.2f" % v for v in rd), rd.mean()))
    base = m.get("ref_mean_distance", m["start_mean_distance"])
    m["closer_by"] = base - m["mean_distance"]
    m["criteria"] = {"tips_drawn_to_point": bool(m["closer_by"] > 0)}
    print(json.dumps(m))


def bud_volume(c, field):
    on = (c[field] >= 0.5) & c["used"]
    return int(on.sum()), float((4.0 / 3.0 * np.pi * c["radius"][on] ** 3).sum())


def cmd_buds(args):
    k, t = pick_frame(args.run, args)
    c = load_frame(args.run, k)
    assert args.field in c, "no field %r in frame %d" % (args.field, k)
    n, vol = bud_volume(c, args.field)
    first = None
    for fk, ft in frames(args.run):
        if fk > k:
            break
        n0, v0 = bud_volume(load_frame(args.run, fk), args.field)
        if n0:
            first = (fk, ft, n0, v0)
            break
    m = {"figure": 11, "frame": k, "time": t, "field": args.field, "bud_cells": n, "bud_volume": vol,
         "first_frame": None, "first_time": None, "first_bud_cells": 0, "first_bud_volume": 0.0, "growth": None}
    if first:
        m.update(first_frame=first[0], first_time=first[1], first_bud_cells=first[2], first_bud_volume=first[3],
                 growth=vol / first[3])
    print("frame %d, t = %.3f: %d bud cells, volume %.4f; first buds at %s" % (
        k, t, n, vol, "frame %d, t = %.3f: %d cells, volume %.4f" % first if first else "no frame"))
    # where the buds are: their graph distance to the nearest tip against
    # every cell's (the paper's buds are at the limbs' ends)
    tips, at_ends = tip_cells(c) if c["complex"] else [], False
    m.update(bud_fraction=n / max(int(c["used"].sum()), 1), bud_cells_per_limb=None, bud_tip_distance=None,
             cell_tip_distance=None)
    if n and len(tips):
        dist, owner = graph_distance(c["x"], c["tets"], tips)
        on, used = (c[args.field] >= 0.5) & c["used"], c["used"] & np.isfinite(dist)
        per = [int((on & (owner == i)).sum()) for i in range(len(tips))]
        bd, cd = float(dist[on & used].mean()), float(dist[used].mean())
        m.update(bud_cells_per_limb=per, bud_tip_distance=bd, cell_tip_distance=cd)
        at_ends = min(per) > 0 and bd <= args.max_distance * cd
        print("bud cells per limb %s (%.0f %% of the cells); mean distance to their tip %.3f against every cell's %.3f"
              % (per, 100 * m["bud_fraction"], bd, cd))
    m["criteria"] = {"buds_expand": m["growth"] is not None and m["growth"] >= args.min_growth,
                     "buds_at_limb_ends": bool(at_ends)}
    print(json.dumps(m))


def read_divisions(run):
    """sds/divisions.csv as (times, cells), in the order the run divided."""
    rows = np.loadtxt(run + "/sds/divisions.csv", delimiter=",", skiprows=1, ndmin=2)
    if rows.size == 0:
        return np.zeros(0), np.zeros(0, int)
    return rows[:, 0], rows[:, 1].astype(int)


def cmd_divisions(args):
    times, cells = read_divisions(args.run)
    fr = frames(args.run)
    tips0 = tip_cells(load_frame(args.run, fr[0][0]))
    limb_of = np.full(len(times), -1)
    # each division to the limb owning its cell in the first frame at or after it
    for j, (k, t) in enumerate(fr):
        t_prev = fr[j - 1][1] if j else -np.inf
        pick = (times > t_prev + 1e-12) & (times <= t + 1e-9) if j else times <= t + 1e-9
        if j == len(fr) - 1:
            pick |= times > t + 1e-9  # past the last frame: its owners
        if not pick.any():
            continue
        c = load_frame(args.run, k)
        tips = tip_cells(c)
        assert len(tips) == len(tips0) and (tips == tips0).all(), "the tips changed index by frame %d" % k
        _, owner = graph_distance(c["x"], c["tets"], tips)
        limb_of[pick] = owner[cells[pick]]
    nl = len(tips0)
    per = [np.sort(times[limb_of == i]) for i in range(nl)]
    w = args.window
    t_end = fr[-1][1]
    nb = max(1, int(np.ceil(t_end / w - 1e-3)))  # the last frame is up to a step past its time: no window for it
    print("divisions per limb (tip cell) in windows of %g time units; %d divisions in all" % (w, len(times)))
    print("%-12s" % "window" + "".join("%8s" % ("limb %d" % i) for i in range(nl)))
    for b in range(nb):
        lo, hi = b * w, (b + 1) * w if b + 1 < nb else np.inf
        print("%-12s" % ("%g-%g" % (lo, (b + 1) * w)) + "".join("%8d" % int(((p > lo) & (p <= hi)).sum()) for p in per))
    kmax = min([len(p) for p in per] + [args.first])
    ranks = []
    for k in range(kmax):
        tk = [float(p[k]) for p in per]
        ranks.append({"rank": k + 1, "times": tk, "spread": max(tk) - min(tk)})
    gaps = [float(np.mean(np.diff(p[:kmax]))) for p in per if kmax >= 2]
    interval = float(np.median(gaps)) if gaps else None
    for r in ranks:
        print("division %d of each limb at t = %s: spread %.3f" % (
            r["rank"], " ".join("%.3f" % x for x in r["times"]), r["spread"]))
    print("median interval between a limb's first %d divisions: %s" % (kmax, "%.3f" % interval if interval else "-"))
    m = {"figure": 12, "divisions": int(len(times)), "limbs": nl, "tip_cells": tips0.tolist(),
         "per_limb": [int(len(p)) for p in per], "ranks": ranks, "interval": interval,
         "criteria": {"limbs_divide_near_simultaneously": bool(ranks) and interval is not None and
                      all(r["spread"] <= interval for r in ranks)}}
    print(json.dumps(m))


def rock_of(run):
    """The model's `rock = x y z radius` line (sds/model.sds)."""
    for line in open(run + "/sds/model.sds"):
        f = re.match(r"\s*rock\s*=\s*([-+0-9.eE\s]+)", line)
        if f:
            v = [float(w) for w in f.group(1).split()[:4]]
            if len(v) == 4:
                return np.array(v[:3]), v[3]
    raise SystemExit("%s: the model has no rock" % run)


def cmd_rock(args):
    ctr, rad = rock_of(args.run)
    k, t = pick_frame(args.run, args)
    c = load_frame(args.run, k)
    cen = c["x"][c["used"]].mean(0)
    tips = c["x"][tip_cells(c)]
    top = ctr[2] + rad
    off = float(np.hypot(*(cen[:2] - ctr[:2])))
    r0 = model_value(args.run, "sphere_radius", 1.0)
    h = tips[:, 2] - top
    m = {"figure": 9, "frame": k, "time": t, "rock": ctr.tolist() + [rad], "centroid": cen.tolist(),
         "centroid_offset": off, "body_radius": r0, "tip_height_over_top": h.tolist(),
         "mean_tip_height_over_top": float(h.mean()),
         "tip_axis_distance": np.hypot(tips[:, 0] - ctr[0], tips[:, 1] - ctr[1]).tolist()}
    print("frame %d, t = %.3f: the cells' centroid (%.2f, %.2f, %.2f), %.2f u from the rock's axis (body radius %g)" % (
        k, t, *cen, off, r0))
    print("  the tips' heights over the rock's top (z = %.2f): %s; mean %.2f" % (
        top, " ".join("%.2f" % v for v in h), h.mean()))
    m["criteria"] = {"upon_rock": bool(off <= r0), "limbs_over_rock": bool(h.mean() < 0)}
    print(json.dumps(m))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    for name in ("limb", "stripes", "bend", "attract", "buds", "rock"):
        p = sub.add_parser(name)
        p.add_argument("run")
        p.add_argument("--frame", type=int)
        p.add_argument("--time", type=float, help="the frame nearest this time (default: the last)")
    sub.choices["limb"].add_argument("--axis", type=float, nargs=3, help="default: the tip's starting direction")
    sub.choices["limb"].add_argument("--slice", type=float, help="slice thickness (default: the median cell diameter)")
    sub.choices["limb"].add_argument("--width", choices=("section", "extent"), default="section",
                                     help="section (default): the diameter of a disc of the complex's mean section "
                                     "over one slice; extent: the largest distance between two centres of a slice "
                                     "(the measure before 2026-12-04; PLY frames have only this)")
    st = sub.choices["stripes"]
    st.add_argument("--field", default="stripe", help="the stripe state or morphogen (default: stripe)")
    st.add_argument("--on", type=float, default=0.5, help="a cell is a stripe cell when the field passes this")
    st.add_argument("--threshold", type=float, default=0.5, help="a stripe: bins with at least this fraction on")
    st.add_argument("--bin", type=float, help="bin width along the limb (default: the median cell diameter)")
    st.add_argument("--mask", metavar="NAME", help="count only cells whose state NAME passes 0.5 (and the tip), e.g. a state the "
                    "rules set in the growth zone, so that body cells nearest a tip stay out of its bins "
                    "(default: every cell)")
    st.add_argument("--ref", help="the same model with the timer's decay twice RUN's: RUN's mean spacing "
                    "should be twice the reference's")
    st.add_argument("--tolerance", type=float, default=0.3, help="the doubling's relative tolerance (default 0.3)")
    for name in ("bend", "attract"):
        sub.choices[name].add_argument("--ref", help="the same model without the box / the attraction")
    sub.choices["bend"].add_argument("--min-bend", type=float, default=10,
                                     help="degrees the mean turn must exceed the reference's by (default 10)")
    sub.choices["attract"].add_argument("--point", type=float, nargs=3, help="default: the model's attractor")
    sub.choices["buds"].add_argument("--field", default="budcell", help="the bud state (default: budcell)")
    sub.choices["buds"].add_argument("--min-growth", type=float, default=2,
                                     help="the bud volume's growth over its first frame (default 2)")
    sub.choices["buds"].add_argument("--max-distance", type=float, default=0.5,
                                     help="buds at the ends: their mean distance to the nearest tip at most this "
                                          "fraction of every cell's (default 0.5)")
    p = sub.add_parser("divisions")
    p.add_argument("run")
    p.add_argument("--first", type=int, default=5, help="compare the limbs' first K divisions (default 5)")
    p.add_argument("--window", type=float, default=50, help="the table's window in time units (default 50)")
    p = sub.add_parser("cells")
    p.add_argument("run")
    p.add_argument("--from", dest="t0", type=float, default=100)
    p.add_argument("--to", dest="t1", type=float, default=400)
    args = ap.parse_args(argv)
    {"limb": cmd_limb, "stripes": cmd_stripes, "cells": cmd_cells, "bend": cmd_bend, "attract": cmd_attract,
     "buds": cmd_buds, "divisions": cmd_divisions, "rock": cmd_rock}[args.cmd](args)


if __name__ == "__main__":
    main()
