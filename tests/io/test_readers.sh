#!/usr/bin/env bash
# The io writers' files opened by readers that share no code with sessile:
#   .vtu/.pvd  VTK's own XML reader (python3-vtk9) and meshio (python3-meshio)
#   .exr       exrheader (openexr), OpenImageIO's iinfo (openimageio-tools) and its
#              Python module (python3-openimageio, tests/io/exr_view_check.py)
#   .ply/.obj  meshio (python3-meshio), VTK's PLY and OBJ readers
# io_samples writes files with analytic content (see tests/io/io_samples.c);
# the expected values are recomputed here from the same formulas.  A missing
# reader is a failure, not a skip: install it with tools/install.sh.
set -u
GEN="$1"
PY=/usr/bin/python3
fails=0 passes=0
check() { # description, command...
  local what="$1"; shift
  if "$@"; then echo "PASS $what"; passes=$((passes + 1)); else echo "FAIL $what"; fails=$((fails + 1)); fi
}

missing=()
[ -x "$PY" ] || missing+=("/usr/bin/python3 (apt-get install python3)")
for m in "vtkmodules.vtkIOXML python3-vtk9" "meshio python3-meshio" "numpy python3-numpy" \
  "OpenImageIO python3-openimageio"; do
  set -- $m
  "$PY" -c "import $1" 2>/dev/null || missing+=("python module $1 (apt-get install $2)")
done
command -v exrheader >/dev/null || missing+=("exrheader (apt-get install openexr)")
command -v iinfo >/dev/null || missing+=("iinfo (apt-get install openimageio-tools)")
if [ ${#missing[@]} -gt 0 ]; then
  for m in "${missing[@]}"; do echo "FAIL missing reader: $m"; done
  echo "install the readers with tools/install.sh"
  exit 1
fi

T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
if ! "$GEN" "$T/out"; then
  echo "FAIL io_samples could not write the sample files"
  exit 1
fi

# --- EXR: exrheader ------------------------------------------------------------
exrheader "$T/out/slice_z.exr" >"$T/exrheader.txt" 2>&1
has() { grep -qF -- "$2" "$1"; }
check "exrheader reads slice_z.exr" test -s "$T/exrheader.txt"
check "exrheader: channel c is 32-bit float" has "$T/exrheader.txt" "c, 32-bit floating-point"
check "exrheader: channel ux is 32-bit float" has "$T/exrheader.txt" "ux, 32-bit floating-point"
check "exrheader: the colour view R, G, B is 16-bit float" eval 'has "$T/exrheader.txt" "R, 16-bit floating-point" &&
  has "$T/exrheader.txt" "G, 16-bit floating-point" && has "$T/exrheader.txt" "B, 16-bit floating-point"'
check "exrheader: sessile:row_order top-down" has "$T/exrheader.txt" 'sessile:row_order (type string): "top-down"'
check "exrheader: sessile:view_channel c, viridis" eval 'has "$T/exrheader.txt" "sessile:view_channel (type string): \"c\"" &&
  has "$T/exrheader.txt" "sessile:view_colormap (type string): \"viridis\""'
check "exrheader: zip compression" has "$T/exrheader.txt" "compression (type compression): zip"
check "exrheader: data window 9 x 7" has "$T/exrheader.txt" "dataWindow (type box2i): (0 0) - (8 6)"
check "exrheader: sessile:plane" has "$T/exrheader.txt" 'sessile:plane (type string): "z=0.6"'
check "exrheader: sessile:origin" has "$T/exrheader.txt" "sessile:origin (type v3f): (-1 0.5 0.6)"
check "exrheader: sessile:spacing" has "$T/exrheader.txt" "sessile:spacing (type v2f): (0.25 0.25)"
check "exrheader: sessile:iteration" has "$T/exrheader.txt" "sessile:iteration (type int): 12"

# --- EXR: OpenImageIO --------------------------------------------------------------
iinfo -v "$T/out/slice_z.exr" >"$T/iinfo.txt" 2>&1
check "iinfo: 9 x 7, half R, G, B and float c, ux" eval 'has "$T/iinfo.txt" "9 x    7, 5 channel, half/half/half/float/float openexr" &&
  has "$T/iinfo.txt" "channel list: R (half), G (half), B (half), c (float), ux (float)"'
check "iinfo: sessile:plane, origin, spacing, iteration" eval 'has "$T/iinfo.txt" "sessile:plane: \"z=0.6\"" &&
  has "$T/iinfo.txt" "sessile:origin: -1, 0.5, 0.6" && has "$T/iinfo.txt" "sessile:spacing: 0.25, 0.25" &&
  has "$T/iinfo.txt" "sessile:iteration: 12"'
# --- EXR on an oblique plane: exrheader, OpenImageIO ------------------------------
exrheader "$T/out/plane.exr" >"$T/exrheader_plane.txt" 2>&1
check "exrheader plane.exr: 8 x 4, channels c and d float, zip" eval 'has "$T/exrheader_plane.txt" "dataWindow (type box2i): (0 0) - (7 3)" &&
  has "$T/exrheader_plane.txt" "c, 32-bit floating-point" && has "$T/exrheader_plane.txt" "d, 32-bit floating-point" &&
  has "$T/exrheader_plane.txt" "compression (type compression): zip"'
check "exrheader plane.exr: sessile:plane/origin/spacing/iteration/axis_u/axis_v" eval 'has "$T/exrheader_plane.txt" "sessile:plane (type string): \"oblique\"" &&
  has "$T/exrheader_plane.txt" "sessile:origin (type v3f): (-0.5 0.25 1)" &&
  has "$T/exrheader_plane.txt" "sessile:spacing (type v2f): (0.125 0.25)" &&
  has "$T/exrheader_plane.txt" "sessile:iteration (type int): 4" &&
  has "$T/exrheader_plane.txt" "sessile:axis_u (type v3f): (0.707107 0.707107 0)" &&
  has "$T/exrheader_plane.txt" "sessile:axis_v (type v3f): (0 0 1)"'
iinfo -v "$T/out/plane.exr" >"$T/iinfo_plane.txt" 2>&1
check "iinfo plane.exr: 8 x 4, R, G, B and 2 float channels, sessile:axis_u/axis_v" eval 'has "$T/iinfo_plane.txt" "8 x    4, 5 channel, half/half/half/float/float openexr" &&
  has "$T/iinfo_plane.txt" "sessile:axis_u: 0.707107, 0.707107, 0" && has "$T/iinfo_plane.txt" "sessile:axis_v: 0, 0, 1"'
# every pixel against its field, rows top-down, the colour view (OpenImageIO's Python module)
check "OpenImageIO: slice_z.exr, plane.exr, signed.exr: the field at each pixel, top row highest, R G B the colour map" \
  "$PY" "$(dirname "$0")/exr_view_check.py" "$T/out" "$(dirname "$0")/../../host/io/colormap.c"

# --- VTU / PVD / PLY / OBJ: VTK and meshio ----------------------------------------
"$PY" - "$T/out" <<'PYEOF'
import os, sys, xml.etree.ElementTree as ET
import numpy as np
import meshio
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy

d = sys.argv[1]
fails = 0
def check(what, ok, detail=""):
    global fails
    print(("PASS " if ok else "FAIL ") + what + (f"  ({detail})" if detail else ""))
    fails += 0 if ok else 1

def lin(p): return 1 + 2 * p[:, 0] + 3 * p[:, 1] + 4 * p[:, 2]
N, M = 17 * 13 * 9, 6 * 16 * 12 * 8   # nodes, tets of the 16 x 12 x 8 box, h = 0.125

def read_vtk(path):
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r, r.GetOutput()

def check_vtu(name, step):
    r, g = read_vtk(os.path.join(d, name))
    check(f"VTK reads {name} without errors", r.GetErrorCode() == 0 and g is not None)
    check(f"VTK {name}: {N} points, {M} cells", g.GetNumberOfPoints() == N and g.GetNumberOfCells() == M,
          f"{g.GetNumberOfPoints()} points, {g.GetNumberOfCells()} cells")
    pts = vtk_to_numpy(g.GetPoints().GetData())
    types = vtk_to_numpy(g.GetCellTypesArray())
    check(f"VTK {name}: every cell is a tetra (type 10)", types.size == M and np.all(types == 10))
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 4)
    a, b, c, e = (pts[conn[:, q]] for q in range(4))
    vol = np.einsum("ij,ij->i", np.cross(b - a, c - a), e - a) / 6
    check(f"VTK {name}: all tets positively oriented, volumes sum to the box (3.0)",
          vol.min() > 0 and abs(vol.sum() - 3.0) < 1e-12, f"min {vol.min():.3e}, sum {vol.sum():.15g}")
    faces = np.sort(np.concatenate([conn[:, [0, 1, 2]], conn[:, [0, 1, 3]], conn[:, [0, 2, 3]], conn[:, [1, 2, 3]]]), axis=1)
    _, counts = np.unique(faces, axis=0, return_counts=True)
    bnd = 4 * (16 * 12 + 16 * 8 + 12 * 8)
    check(f"VTK {name}: conforming (faces shared by 2 tets, {bnd} boundary triangles)",
          counts.max() == 2 and np.sum(counts == 1) == bnd, f"boundary {np.sum(counts == 1)}")
    pd = g.GetPointData()
    cc, u, s = (pd.GetArray(k) for k in ("c", "u", "solid"))
    check(f"VTK {name}: arrays c Float64, u Float64 x3, solid UInt8",
          cc is not None and u is not None and s is not None and cc.GetDataTypeAsString() == "double" and
          u.GetNumberOfComponents() == 3 and u.GetDataTypeAsString() == "double" and
          s.GetDataTypeAsString() == "unsigned char")
    if cc is None or u is None or s is None: return pts, None
    ec = np.abs(vtk_to_numpy(cc) - (lin(pts) + step)).max()
    eu = np.abs(vtk_to_numpy(u) - np.stack([pts[:, 1], -pts[:, 0], pts[:, 2]], axis=1)).max()
    check(f"VTK {name}: c == 1+2x+3y+4z+{step} at the points", ec <= 1e-12, f"max abs error {ec:.1e}, tol 1e-12")
    check(f"VTK {name}: u == (y, -x, z) at the points", eu <= 1e-15, f"max abs error {eu:.1e}")
    check(f"VTK {name}: solid == (z < 0.5)", np.array_equal(vtk_to_numpy(s), (pts[:, 2] < 0.5).astype(np.uint8)))
    return pts, conn

pts0, conn0 = check_vtu("fields_0000.vtu", 0)

# meshio: a second reader of the same file
m = meshio.read(os.path.join(d, "fields_0000.vtu"))
tet = [cb.data for cb in m.cells if cb.type == "tetra"]
check("meshio reads fields_0000.vtu: same points and tets as VTK",
      len(m.cells) == 1 and len(tet) == 1 and np.array_equal(m.points, pts0) and np.array_equal(tet[0], conn0))
check("meshio fields_0000.vtu: c, u, solid equal the analytic fields",
      np.abs(m.point_data["c"].reshape(-1) - lin(m.points)).max() <= 1e-12 and
      np.array_equal(m.point_data["u"], np.stack([m.points[:, 1], -m.points[:, 0], m.points[:, 2]], axis=1)) and
      np.array_equal(m.point_data["solid"].reshape(-1), (m.points[:, 2] < 0.5).astype(np.uint8)))

# PVD: an XML collection; every data set read with VTK, its c offset = its timestep
root = ET.parse(os.path.join(d, "series.pvd")).getroot()
ds = root.findall("./Collection/DataSet")
check("series.pvd is a VTKFile Collection with 2 data sets",
      root.tag == "VTKFile" and root.get("type") == "Collection" and len(ds) == 2)
for e in ds:
    step = int(e.get("timestep"))
    r, g = read_vtk(os.path.join(d, e.get("file")))
    p = vtk_to_numpy(g.GetPoints().GetData())
    off = vtk_to_numpy(g.GetPointData().GetArray("c")) - lin(p)
    check(f"series.pvd timestep {step} -> {e.get('file')}: VTK reads it, c - (1+2x+3y+4z) == {step}",
          g.GetNumberOfCells() == M and np.abs(off - step).max() <= 1e-12)

# PLY and OBJ (meshio); the OBJ holds exact doubles, the PLY float32
ply = meshio.read(os.path.join(d, "sponge.ply"))
obj = meshio.read(os.path.join(d, "sponge.obj"))
center, r = np.array([0.5, -0.25, 1.0]), 0.75
ptri = [cb.data for cb in ply.cells if cb.type == "triangle"]
otri = [cb.data for cb in obj.cells if cb.type == "triangle"]
check("meshio reads sponge.ply: 162 vertices, 320 triangles",
      ply.points.shape == (162, 3) and len(ptri) == 1 and ptri[0].shape == (320, 3))
check("meshio reads sponge.obj: 162 vertices, 320 triangles, the PLY's triangles",
      obj.points.shape == (162, 3) and len(otri) == 1 and np.array_equal(otri[0], ptri[0]))
rad = np.linalg.norm(obj.points - center, axis=1)
check("OBJ vertices lie on the sphere (|p - c| == 0.75)", np.abs(rad - r).max() <= 1e-12,
      f"max error {np.abs(rad - r).max():.1e}")
check("PLY positions == float32 of the OBJ's", np.abs(ply.points - obj.points).max() <= 6e-8 * 2,
      f"max abs diff {np.abs(ply.points - obj.points).max():.1e}, tol 1.2e-7")
pn = np.stack([ply.point_data[k].reshape(-1) for k in ("nx", "ny", "nz")], axis=1)
on = obj.point_data.get("obj:vn")
check("PLY normals == OBJ normals (float32), unit length, outward",
      on is not None and np.abs(pn - on).max() <= 1.2e-7 and np.abs(np.linalg.norm(on, axis=1) - 1).max() <= 1e-12 and
      np.min(np.einsum("ij,ij->i", on, (obj.points - center) / r)) > 0.99)
check("PLY extra property c == 1+2x+3y+4z (float32)",
      np.abs(ply.point_data["c"].reshape(-1) - lin(obj.points)).max() <= 1e-6 * 8,
      f"max abs diff {np.abs(ply.point_data['c'].reshape(-1) - lin(obj.points)).max():.1e}")
p = obj.points[otri[0]]
vol = np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6
check("OBJ triangles are counter-clockwise from outside (enclosed volume > 0, < the sphere's)",
      0.9 * 4 / 3 * np.pi * r ** 3 < vol < 4 / 3 * np.pi * r ** 3, f"volume {vol:.4f}")

# --- the writers for any generator --------------------------------------------------
# tets.vtu: a general tet mesh with point data and cell data (VTK, then meshio)
r, g = read_vtk(os.path.join(d, "tets.vtu"))
NT, MT = 5 * 4 * 3, 6 * 4 * 3 * 2
check("VTK reads tets.vtu without errors", r.GetErrorCode() == 0 and g is not None)
check(f"VTK tets.vtu: {NT} points, {MT} tets (type 10)",
      g.GetNumberOfPoints() == NT and g.GetNumberOfCells() == MT and np.all(vtk_to_numpy(g.GetCellTypesArray()) == 10),
      f"{g.GetNumberOfPoints()} points, {g.GetNumberOfCells()} cells")
pts = vtk_to_numpy(g.GetPoints().GetData())
conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 4)
ref = np.array([[i * 0.25, j * 0.25, k * 0.25] for k in range(3) for j in range(4) for i in range(5)])
moved = np.stack([ref[:, 0] + 0.1 * ref[:, 1] ** 2, ref[:, 1], ref[:, 2] + 0.05 * ref[:, 0]], axis=1)
check("VTK tets.vtu: the points are the moved box nodes", np.abs(pts - moved).max() <= 1e-15)
cd = g.GetCellData()
vol_a, cen_a, id_a, kind_a = (cd.GetArray(k) for k in ("volume", "centroid", "id", "kind"))
check("VTK tets.vtu: cell arrays volume double, centroid double x3, id int, kind unsigned char",
      None not in (vol_a, cen_a, id_a, kind_a) and vol_a.GetDataTypeAsString() == "double" and
      cen_a.GetDataTypeAsString() == "double" and cen_a.GetNumberOfComponents() == 3 and
      id_a.GetDataTypeAsString() == "int" and kind_a.GetDataTypeAsString() == "unsigned char" and
      cd.GetNumberOfArrays() == 4)
if None not in (vol_a, cen_a, id_a, kind_a):
    a, b, c, e = (pts[conn[:, q]] for q in range(4))
    vol = np.einsum("ij,ij->i", np.cross(b - a, c - a), e - a) / 6
    ev = np.abs(vtk_to_numpy(vol_a) - vol).max()
    ec = np.abs(vtk_to_numpy(cen_a) - (a + b + c + e) / 4).max()
    check("VTK tets.vtu: cell volume == the tet's volume from VTK's points (all > 0)",
          ev <= 1e-15 and vol.min() > 0, f"max abs error {ev:.1e}")
    check("VTK tets.vtu: cell centroid == the mean of the tet's points", ec <= 1e-15, f"max abs error {ec:.1e}")
    check("VTK tets.vtu: id == tet - 5 (negative ones too), kind == tet % 6",
          np.array_equal(vtk_to_numpy(id_a), np.arange(MT) - 5) and
          np.array_equal(vtk_to_numpy(kind_a), (np.arange(MT) % 6).astype(np.uint8)))
pc = g.GetPointData().GetArray("c")
check("VTK tets.vtu: point data c == 1+2x+3y+4z", pc is not None and np.abs(vtk_to_numpy(pc) - lin(pts)).max() <= 1e-12)
m = meshio.read(os.path.join(d, "tets.vtu"))
check("meshio reads tets.vtu: same points, tets and cell data as VTK",
      np.array_equal(m.points, pts) and len(m.cells) == 1 and np.array_equal(m.cells[0].data, conn) and
      np.array_equal(m.cell_data["id"][0].reshape(-1), np.arange(MT) - 5) and
      np.array_equal(m.cell_data["volume"][0].reshape(-1), vtk_to_numpy(vol_a)))

# parts.ply / parts.obj: the union of 12 + 0 + 42 vertices, 20 + 0 + 80 triangles
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOGeometry import vtkOBJReader
NV, NF = 12 + 42, 20 + 80
pp = meshio.read(os.path.join(d, "parts.ply"))
ptri = np.concatenate([cb.data for cb in pp.cells if cb.type == "triangle"])
check(f"meshio reads parts.ply: {NV} vertices, {NF} triangles", pp.points.shape == (NV, 3) and ptri.shape == (NF, 3),
      f"{pp.points.shape[0]} vertices, {ptri.shape[0]} triangles")
part = pp.point_data["part"].reshape(-1)
check("parts.ply field part == 0 for the 12 small vertices, 2 for the 42 big ones",
      np.array_equal(part, np.r_[np.zeros(12), np.full(42, 2.0)]))
ec = np.abs(pp.point_data["c"].reshape(-1) - lin(pp.points)).max()
check("parts.ply field c == 1+2x+3y+4z (float32)", ec <= 1e-6 * 16, f"max abs error {ec:.1e}")
rad = np.r_[np.linalg.norm(pp.points[:12], axis=1) / 0.5, np.linalg.norm(pp.points[12:] - [2.5, -1, 0.5], axis=1)]
check("parts.ply: the small sphere's vertices come first, then the big one's", np.abs(rad - 1).max() <= 1e-6)
check("parts.ply: faces 0..19 use vertices 0..11, faces 20..99 vertices 12..53 (offset per part)",
      ptri[:20].max() < 12 and ptri[20:].min() >= 12 and ptri[20:].max() < NV and
      len(np.unique(ptri[:20])) == 12 and len(np.unique(ptri[20:])) == 42)
rd = vtkPLYReader()
rd.SetFileName(os.path.join(d, "parts.ply"))
rd.Update()
pv = rd.GetOutput()
check(f"VTK's PLY reader: {NV} points, {NF} triangles, same points and triangles as meshio",
      pv.GetNumberOfPoints() == NV and pv.GetNumberOfCells() == NF and
      np.array_equal(vtk_to_numpy(pv.GetPoints().GetData()), pp.points.astype(np.float32)) and
      np.array_equal(vtk_to_numpy(pv.GetPolys().GetConnectivityArray()).reshape(-1, 3), ptri),
      f"{pv.GetNumberOfPoints()} points, {pv.GetNumberOfCells()} cells")
po = meshio.read(os.path.join(d, "parts.obj"))
otri = [cb.data for cb in po.cells if cb.type == "triangle"]
check("meshio reads parts.obj: 2 non-empty groups (20 and 80 triangles), the PLY's triangles",
      len(otri) == 2 and otri[0].shape == (20, 3) and otri[1].shape == (80, 3) and
      np.array_equal(np.concatenate(otri), ptri) and po.points.shape == (NV, 3))
check("parts.obj: the group ids are 0 and 2 (the empty part is group 1)",
      [int(np.unique(gid)[0]) for gid in po.cell_data.get("obj:group_ids", [])] == [0, 2])
check("parts.obj positions == float32 PLY positions", np.abs(po.points - pp.points).max() <= 2.4e-7)
ro = vtkOBJReader()
ro.SetFileName(os.path.join(d, "parts.obj"))
ro.Update()
ov = ro.GetOutput()
check(f"VTK's OBJ reader: {NF} triangles", ov.GetNumberOfCells() == NF, f"{ov.GetNumberOfCells()} cells")

print(f"python: {fails} failed")
sys.exit(1 if fails else 0)
PYEOF
py=$?
check "VTK / meshio checks (lines above)" test "$py" -eq 0
echo "$passes passed, $fails failed"
[ "$fails" -eq 0 ]
