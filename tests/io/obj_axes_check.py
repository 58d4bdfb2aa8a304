#!/usr/bin/python3
"""An OBJ that sessile wrote against the PLY beside it, in a convention:
    obj_axes_check.py zup-cm|yup-m FILE.obj FILE.ply "KD_R KD_G KD_B"
zup-cm: the OBJ holds the PLY's coordinates.  yup-m: a PLY point (x, y, z) in
cm is (x, z, -y) / 100 in the OBJ (the glTF writer's frame: +Y up, metres),
a normal (x, z, -y).  Checked: the extents through VTK's OBJ and PLY readers,
every vertex, normal and triangle through a reading by hand, the signed
volume (a rotation keeps the triangles' orientation), and the .mtl that
mtllib names: the material usemtl names, with diffuse colour KD.
Prints PASS/FAIL lines; exits 1 on any failure."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkIOPLY import vtkPLYReader

mode, obj_path, ply_path, kd_text = sys.argv[1:5]
fails = 0


def check(what, ok, detail=""):
    global fails
    print(("PASS " if ok else "FAIL ") + what + (f"  ({detail})" if detail else ""))
    fails += 0 if ok else 1


def to_obj(p, scale):
    """A PLY vector as the OBJ should hold it."""
    return np.stack([p[:, 0], p[:, 2], -p[:, 1]], axis=1) / scale if mode == "yup-m" else p


def by_hand(path):
    v, vn, f, libs, mats = [], [], [], [], []
    for line in open(path):
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            v.append([float(x) for x in t[1:4]])
        elif t[0] == "vn":
            vn.append([float(x) for x in t[1:4]])
        elif t[0] == "f":
            f.append([int(c.split("/")[0]) - 1 for c in t[1:]])
        elif t[0] == "mtllib":
            libs.append(t[1])
        elif t[0] == "usemtl":
            mats.append(t[1])
    return np.array(v), np.array(vn), np.array(f), libs, mats


def signed_volume(p, tri):
    a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6


pr = vtkPLYReader()
pr.SetFileName(ply_path)
pr.Update()
ply = pr.GetOutput()
pp = vtk_to_numpy(ply.GetPoints().GetData()).astype(np.float64)
ptri = vtk_to_numpy(ply.GetPolys().GetConnectivityArray()).reshape(-1, 3)
pn = ply.GetPointData().GetNormals()
pn = vtk_to_numpy(pn).astype(np.float64) if pn is not None else None

orr = vtkOBJReader()
orr.SetFileName(obj_path)
orr.Update()
ob = np.array(orr.GetOutput().GetBounds()).reshape(3, 2)  # [[xmin, xmax], ...]
scale = 100.0 if mode == "yup-m" else 1.0
want = to_obj(pp, scale)
wb = np.stack([want.min(axis=0), want.max(axis=0)], axis=1)
tol = 2.4e-7 * np.abs(pp).max() / scale  # the PLY holds float32
check(f"VTK: the OBJ's extent is the PLY's {'as (x, z, -y) / 100' if mode == 'yup-m' else 'unchanged'}",
      np.abs(ob - wb).max() <= tol, f"OBJ {ob.round(6).tolist()}, want {wb.round(6).tolist()}")
if mode == "yup-m":
    check("the OBJ's height (y) is the PLY's z extent / 100",
          abs((ob[1, 1] - ob[1, 0]) - (pp[:, 2].max() - pp[:, 2].min()) / 100) <= 2 * tol)

v, vn, f, libs, mats = by_hand(obj_path)
check(f"{len(pp)} vertices, {len(ptri)} triangles in both", v.shape == pp.shape and f.shape == ptri.shape)
if v.shape == pp.shape:
    check("every vertex", np.abs(v - want).max() <= tol, f"max difference {np.abs(v - want).max():.2e}")
if f.shape == ptri.shape:
    check("every triangle (the same corners in the same order)", np.array_equal(f, ptri))
    vo, vp = signed_volume(v, f), signed_volume(pp, ptri) / scale**3
    check("the signed volume: the PLY's" + (" / 100^3" if mode == "yup-m" else "") + ", the same sign",
          abs(vo - vp) <= 1e-5 * abs(vp) and vo * vp > 0, f"{vo:.6e} vs {vp:.6e}")
if len(vn):
    check("every normal, rotated as the vertices", pn is not None and vn.shape == pn.shape and
          np.abs(vn - to_obj(pn, 1.0)).max() <= 1e-6)

kd = [float(x) for x in kd_text.split()]
check("one mtllib and one usemtl", len(libs) == 1 and len(mats) == 1, f"{libs} {mats}")
if len(libs) == 1 and len(mats) == 1:
    mtl = os.path.join(os.path.dirname(obj_path), libs[0])
    names, kds = [], []
    if os.path.isfile(mtl):
        for line in open(mtl):
            t = line.split()
            if t and t[0] == "newmtl":
                names.append(t[1])
            elif t and t[0] == "Kd":
                kds.append([float(x) for x in t[1:4]])
    check(f"{libs[0]} beside the OBJ defines '{mats[0]}' with Kd {kd}",
          names == [mats[0]] and len(kds) == 1 and np.abs(np.array(kds[0]) - kd).max() <= 1e-6, f"{names} {kds}")
sys.exit(1 if fails else 0)
