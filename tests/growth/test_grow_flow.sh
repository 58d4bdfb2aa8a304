#!/usr/bin/env bash
# diffusion_limited=false: the flow (inlet at x-min, +x) advects the
# nutrient, so the upstream side of the sponge is better fed and grows more:
# the sponge's area-weighted centroid moves upstream (-x) compared with the
# same run in the diffusion-limited (symmetric) setting, in both the immersed
# and the conforming (TetGen) domain.  A small box (19.2 x 19.2 x 14.4 cm,
# 1.2 cm cells), a 3 cm sponge, 8 iterations and at most 4 Newton steps per
# flow solve keep the test short; the flow solver's accuracy is tested in
# tests/fem/test_ns.c.  Also checks the flow's outputs: EXR channels ux, uy,
# uz, umag, p, the VTU's u and p, the records' Newton steps, and
# tools/compare_flow.py (a run against itself: 0; two domains: not 0), and
# that fluid_ksp_type and fluid_pc_type reach the solver (the records).
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
SMALL="--set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3
       --set box_resolution=1 --set fluid_newton_max_it=4 --iterations 8 --quiet --seed 3"
"$S" grow $SMALL --every 0 --out "$T/dl" 2>"$T/dl.err"; check "diffusion-limited control run" [ $? -eq 0 ]
for d in immersed conforming; do
  "$S" grow $SMALL --every 8 --set diffusion_limited=false --set domain=$d --out "$T/$d" 2>"$T/$d.err"
  check "$d: run with the flow advecting the nutrient" [ $? -eq 0 ]
done
check "growth is biased upstream in both domains (centroid shift vs control, tolerance 0.15 cm)" \
  /usr/bin/python3 - "$T" <<'PYEOF'
import json, sys
import numpy as np, meshio
T = sys.argv[1]
def shift(d):
    m = meshio.read(f"{T}/{d}/sponge/final.ply"); p = m.points; t = m.cells_dict["triangle"]
    a, b, c = p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]
    ar = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    cen = (ar[:, None] * (a + b + c) / 3).sum(0) / ar.sum()
    c0 = json.load(open(f"{T}/{d}/manifest.json"))["initial_sponge"]["center_cm"]
    return cen[0] - c0[0]
s0 = shift("dl"); ok = True
for d in ("immersed", "conforming"):
    s = shift(d); print(f"{d}: centroid x shift {s:+.3f} cm, diffusion-limited control {s0:+.3f} cm")
    ok = ok and s < s0 - 0.15
sys.exit(0 if ok else 1)
PYEOF
check "records: every iteration solved the flow, on the requested domain, with Newton records" \
  /usr/bin/python3 - "$T" <<'PYEOF'
import json, sys
T = sys.argv[1]; ok = True
for d in ("immersed", "conforming"):
    its = [json.loads(l) for l in open(f"{T}/{d}/records.jsonl")]
    doms = [i["fluid"]["domain"] for i in its]
    ok = ok and len(its) == 8 and all(i["fluid"]["newton_steps"] >= 1 and len(i["fluid"]["steps"]) == i["fluid"]["newton_steps"] for i in its)
    ok = ok and (all(x == d for x in doms) if d == "immersed" else doms.count("conforming") >= 6)
    print(d, doms)
sys.exit(0 if ok else 1)
PYEOF
# The fluid's solver choices reach the solver: each Newton step records the
# Krylov method and preconditioner it ran (defaults gmres + mg above).
"$S" grow ${SMALL/--iterations 8/--iterations 1} --every 1 --set fluid_ksp_type=bicgstab \
  --set fluid_pc_type=block_jacobi --out "$T/opts" 2>"$T/opts.err"
check "run with fluid_ksp_type=bicgstab, fluid_pc_type=block_jacobi" [ $? -eq 0 ]
check "records: the Newton steps ran the chosen Krylov method and preconditioner" \
  /usr/bin/python3 - "$T" <<'PYEOF'
import json, sys
T = sys.argv[1]
def kinds(d):
    return {(s["krylov"], s["preconditioner"]) for l in open(f"{T}/{d}/records.jsonl")
            for s in json.loads(l).get("fluid", {}).get("steps", [])}
a, b = kinds("immersed"), kinds("opts")
print("default:", a, "chosen:", b)
sys.exit(0 if a == {("gmres", "mg")} and b == {("bicgstab", "block_jacobi")} else 1)
PYEOF
check "EXR slice carries c, ux, uy, uz, umag, p" eval \
  'exrheader "$T/immersed/slices/iter_0008_z.exr" | grep -q "umag, 32-bit floating-point" && exrheader "$T/immersed/slices/iter_0008_z.exr" | grep -q "  p, 32-bit floating-point"'
check "VTK reads u (3 components, inflow along +x at the inlet) and p from the VTU" \
  /usr/bin/python3 - "$T/immersed/fields/iter_0008.vtu" <<'PYEOF'
import sys
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy
r = vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update(); g = r.GetOutput()
u = vtk_to_numpy(g.GetPointData().GetArray("u")); p = vtk_to_numpy(g.GetPointData().GetArray("p"))
x = vtk_to_numpy(g.GetPoints().GetData())
inlet = x[:, 0] == x[:, 0].min(); inner = inlet & (x[:, 2] > x[:, 2].min())
print("u", u.shape, "inlet ux", u[inner, 0].min(), u[inner, 0].max(), "p range", p.min(), p.max())
sys.exit(0 if u.shape[1] == 3 and abs(u[inner, 0] - 0.05).max() < 1e-9 and p.shape[0] == g.GetNumberOfPoints() else 1)
PYEOF
CF="$(dirname "$0")/../../tools/compare_flow.py"
/usr/bin/python3 "$CF" "$T/immersed" "$T/immersed" --iter 8 >"$T/cf_same.txt" 2>&1
check "tools/compare_flow.py: a run against itself differs by 0" \
  eval 'grep -q "all water nodes.*RMS 0.0000  max 0.0000" "$T/cf_same.txt"'
/usr/bin/python3 "$CF" "$T/immersed" "$T/conforming" --iter 8 >"$T/cf_diff.txt" 2>&1
check "tools/compare_flow.py: the immersed and conforming flows differ (RMS > 0)" \
  eval 'grep "all water nodes" "$T/cf_diff.txt" | grep -qv "RMS 0.0000"'
finish
