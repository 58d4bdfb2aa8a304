"""Checks a run directory's surface files with readers that share no code
with sessile (tests/io/test_mesh_data.sh): every PLY with a .vtp beside it
is parsed here (numpy) and its .vtp read by VTK's XML reader; the counts,
arrays and values must agree, the header must name generator, version with
commit, seed and units, and the PLY's colours must be the colour map of its
main scalar, recomputed here.  A PVD's timesteps are read from its XML and
each listed file is opened by VTK.
usage: mesh_data_check.py COLORMAP_C RUN_DIR [PVD...]"""
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np
from vtkmodules.vtkIOXML import vtkXMLGenericDataObjectReader, vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy

fails = 0


def check(ok, what):
    global fails
    print(("PASS " if ok else "FAIL ") + what)
    fails += 0 if ok else 1
    return ok


def tables(path):
    """The 256-entry maps as published data (matplotlib's), read from the
    table file; checked against samples of matplotlib's float data below."""
    text = open(path).read()
    out = {}
    for name in ("viridis", "magma", "coolwarm"):
        body = re.search(name + r"_table\[256\]\[3\] = \{(.*?)\n\};", text, re.S).group(1)
        rows = [tuple(int(v) for v in m) for m in re.findall(r"\{(\d+), (\d+), (\d+)\}", body)]
        out[name] = np.array(rows, dtype=np.int32)
    return out


# matplotlib's own float data (_cm_listed.py, _cm.py's coolwarm), entries 0 and 255
PUBLISHED = {"viridis": {0: (0.267004, 0.004874, 0.329415), 255: (0.993248, 0.906157, 0.143936)},
             "magma": {0: (0.001462, 0.000466, 0.013866), 255: (0.987053, 0.991438, 0.749504)},
             "coolwarm": {0: (0.2298057, 0.298717966, 0.753683153), 255: (0.705673158, 0.01555616, 0.150232812)}}


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    head = data[:end].decode().splitlines()
    comments = [l[8:] for l in head if l.startswith("comment ")]
    props, nv, nf, elem = [], 0, 0, None
    for l in head:
        w = l.split()
        if w[0] == "element":
            elem = w[1]
            if elem == "vertex":
                nv = int(w[2])
            else:
                nf = int(w[2])
        elif w[0] == "property" and elem == "vertex":
            props.append((w[2], {"float": "<f4", "uchar": "u1"}[w[1]]))
    vt = np.dtype(props)
    verts = np.frombuffer(data, dtype=vt, count=nv, offset=end)
    faces = np.frombuffer(data, dtype=np.dtype([("n", "u1"), ("i", "<u4", 3)]), count=nf, offset=end + nv * vt.itemsize)
    return comments, verts, faces


def expected_colors(tab, map_name, v):
    """render --color-by's rule: finite min..max, symmetric about 0 for a
    diverging map on a range across 0; entry floor(256 t) clamped; NaN grey."""
    fin = v[np.isfinite(v)].astype(np.float64)
    lo, hi = (fin.min(), fin.max()) if fin.size else (0.0, 0.0)
    if map_name == "coolwarm" and lo < 0 < hi:
        a = max(-lo, hi)
        lo, hi = -a, a
    t = (v.astype(np.float64) - lo) / (hi - lo) if hi > lo else np.full(v.shape, 0.5)
    t = np.nan_to_num(np.clip(t, 0, 1))
    rgb = tab[map_name][np.minimum((t * 256).astype(np.int64), 255)]
    rgb[~np.isfinite(v)] = 128
    return rgb, lo, hi


def field_strings(fd):
    out = {}
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        # numbers exactly (a variant's text keeps 6 digits), strings as they are
        out[a.GetName()] = repr(a.GetTuple1(0)) if a.IsNumeric() else a.GetVariantValue(0).ToString()
    return out


def check_surface(tab, ply, rel):
    comments, verts, faces = read_ply(ply)
    names = verts.dtype.names
    scalars = [n for n in names if n not in ("x", "y", "z", "nx", "ny", "nz", "red", "green", "blue")]
    info = {c.split(" ", 1)[0]: c.split(" ", 1)[1] if " " in c else "" for c in comments}
    check(all(k in info for k in ("generator", "version", "seed", "units")) and " commit " in info["version"]
          and info["units"].startswith("length "), f"{rel}: header names generator, version+commit, seed, units")
    check(all(c in names for c in ("red", "green", "blue")) and len(scalars) >= 1,
          f"{rel}: red green blue and at least one scalar")
    m = re.match(r"red green blue: (\w+) of (\S+) over \[(\S+), (\S+)\]", info.get("colors", ""))
    if check(m is not None and m.group(2) in scalars, f"{rel}: the colours name their scalar and map"):
        rgb, lo, hi = expected_colors(tab, m.group(1), verts[m.group(2)])
        got = np.stack([verts["red"], verts["green"], verts["blue"]], axis=1).astype(np.int32)
        check(np.abs(got - rgb).max(initial=0) <= 1,
              f"{rel}: colours = {m.group(1)}({m.group(2)}) over [{lo:.6g}, {hi:.6g}] (within 1 step)")
        check(math.isclose(float(m.group(3)), lo, rel_tol=1e-6, abs_tol=1e-30)
              and math.isclose(float(m.group(4)), hi, rel_tol=1e-6, abs_tol=1e-30), f"{rel}: the stated range")
    r = vtkXMLPolyDataReader()
    r.SetFileName(ply[:-4] + ".vtp")
    r.Update()
    pd = r.GetOutput()
    check(pd.GetNumberOfPoints() == len(verts) and pd.GetNumberOfPolys() == len(faces),
          f"{rel[:-4]}.vtp: {len(verts)} points, {len(faces)} triangles as the PLY")
    pts = vtk_to_numpy(pd.GetPoints().GetData()) if len(verts) else np.zeros((0, 3))
    xyz = np.stack([verts["x"], verts["y"], verts["z"]], axis=1)
    check(np.array_equal(pts, xyz), f"{rel[:-4]}.vtp: the PLY's points")
    conn = vtk_to_numpy(pd.GetPolys().GetConnectivityArray()).reshape(-1, 3) if len(faces) else np.zeros((0, 3))
    check(np.array_equal(conn, faces["i"]), f"{rel[:-4]}.vtp: the PLY's triangles in order")
    pdata = pd.GetPointData()
    ok = all(pdata.GetArray(n) is not None and np.array_equal(vtk_to_numpy(pdata.GetArray(n)), verts[n])
             for n in scalars)
    check(ok, f"{rel[:-4]}.vtp: every scalar ({', '.join(scalars)}) as a point array with the PLY's values")
    if "nx" in names:
        nrm = vtk_to_numpy(pdata.GetNormals())
        check(np.array_equal(nrm, np.stack([verts["nx"], verts["ny"], verts["nz"]], axis=1)),
              f"{rel[:-4]}.vtp: the PLY's normals")
    fs = field_strings(pd.GetFieldData())
    check(all(k in fs for k in ("generator", "version", "seed", "length_unit", "main_scalar"))
          and fs["generator"] == info["generator"] and m is not None and fs["main_scalar"] == m.group(2),
          f"{rel[:-4]}.vtp: field data generator, version, seed, units, main scalar")
    if "time" in info:
        check("TimeValue" in fs and float(fs["TimeValue"]) == float(info["time"]),
              f"{rel[:-4]}.vtp: TimeValue {fs.get('TimeValue')} = the PLY's time")


def check_pvd(pvd):
    root = ET.parse(pvd).getroot()
    sets = root.findall("./Collection/DataSet")
    times = [float(d.get("timestep")) for d in sets]
    check(len(sets) >= 1 and times == sorted(times) and len(set(times)) == len(times),
          f"{os.path.basename(os.path.dirname(pvd))}/{os.path.basename(pvd)}: {len(sets)} increasing times {times}")
    ok = True
    for d, t in zip(sets, times):
        f = os.path.join(os.path.dirname(pvd), d.get("file"))
        r = vtkXMLGenericDataObjectReader()
        r.SetFileName(f)
        r.Update()
        out = r.GetOutput()
        ok &= out is not None and out.GetNumberOfPoints() > 0
        if f.endswith(".vtp"):
            fs = field_strings(out.GetFieldData())
            ok &= float(fs.get("TimeValue", "nan")) == t
    check(ok, f"{os.path.basename(pvd)}: every listed file opens (a .vtp's TimeValue is its timestep)")


def main():
    tab = tables(sys.argv[1])
    for name, samples in PUBLISHED.items():
        check(all(np.abs(tab[name][i] - np.round(np.array(c) * 255)).max() <= 1 for i, c in samples.items()),
              f"the {name} table matches matplotlib's published data")
    run = sys.argv[2]
    n = 0
    for dirpath, _, files in sorted(os.walk(run)):
        for f in sorted(files):
            if f.endswith(".ply"):
                p = os.path.join(dirpath, f)
                if check(os.path.exists(p[:-4] + ".vtp"), f"{os.path.relpath(p, run)} has its .vtp"):
                    check_surface(tab, p, os.path.relpath(p, run))
                    n += 1
    check(n > 0, f"{run}: {n} surfaces checked")
    for pvd in sys.argv[3:]:
        check_pvd(os.path.join(run, pvd))
    sys.exit(1 if fails else 0)


main()
