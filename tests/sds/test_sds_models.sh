#!/usr/bin/env bash
# The four multi-limb models of the paper's Figures 8-11 (six limbs in a box,
# limbs over a rock, an attraction point, budded tips), each run from the
# command line to t = 30: every run completes, its cells divide and grow in
# number, and its last complex (the VTU) is valid: every face in one or two
# tets, the boundary closed and consistently oriented, no tet inverted.  The
# environment holds: every cell of the box model within its box (the walls are
# penalty springs: 0.05 u of give; without the floor gravity would take the
# body about 1.5 u down by t = 30), and every cell of the rock model outside
# its boulder.  The whole runs (t = 400-500) take 6-45 minutes here and are
# in docs/sds_rules.md, not in the suite.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
M="$(dirname "$0")/../../host/sds/models"

for m in six_limbs_box rock attractor budded; do
  run sds run "$m" --t-end 30 --frames 2 --out "$T/$m" --quiet --no-preview
  check "$m to t = 30 completes" rc_is 0
  check "$m: cells divide and grow in number; the last complex is valid; its environment holds" \
    "$PY" - "$T/$m" "$m" "$M/$m.sds" <<'PYEOF'
import collections, json, re, sys
import numpy as np, vtk
from vtk.util.numpy_support import vtk_to_numpy
d, name, model = sys.argv[1:4]
m = json.load(open(d + "/manifest.json"))
recs = [json.loads(l) for l in open(d + "/records.jsonl")]
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(d + "/sds/frame_0002.vtu"); r.Update(); g = r.GetOutput()
X = vtk_to_numpy(g.GetPoints().GetData()).astype(float)
T = vtk_to_numpy(g.GetCells().GetData()).reshape(-1, 5)[:, 1:]
a, b, c, e = (X[T[:, k]] for k in range(4))
vol = np.einsum("ij,ij->i", b - a, np.cross(c - a, e - a)) / 6
faces, edges = collections.Counter(), collections.Counter()
sides = lambda t: ((t[1], t[2], t[3]), (t[0], t[3], t[2]), (t[0], t[1], t[3]), (t[0], t[2], t[1]))
for t in T:
    for f in sides(t): faces[tuple(sorted(f))] += 1
for t in T:
    for f in sides(t):
        if faces[tuple(sorted(f))] == 1:
            for i in range(3): edges[(f[i], f[(i + 1) % 3])] += 1
closed = all(n == 1 and edges.get((q[1], q[0]), 0) == 1 for q, n in edges.items())
ok = m["state"] == "completed" and m["sds"]["divisions"] > 0 and recs[-1]["cells"] > recs[0]["cells"]
ok = ok and len(X) == recs[-1]["cells"] and closed and all(n <= 2 for n in faces.values()) and (vol > 0).all()
params = {}
for line in open(model):
    k = re.match(r"^(\w+)\s*=\s*([-0-9. ]+)", line)
    if k: params[k.group(1)] = [float(v) for v in k.group(2).split()]
env = "none"
if "box" in params:
    lo, hi = np.array(params["box"][:3]), np.array(params["box"][3:])
    out = max((lo - X).max(), (X - hi).max())
    env = "deepest past a wall %.4f u (<= 0.05)" % out
    ok = ok and out <= 0.05
if "rock" in params:
    cx, cy, cz, rr = params["rock"]
    gap = (np.linalg.norm(X - [cx, cy, cz], axis=1) - rr).min()
    env = "closest to the boulder's surface %.4f u (>= 0)" % gap
    ok = ok and gap >= 0
print(name, "cells", recs[0]["cells"], "->", recs[-1]["cells"], "divisions", m["sds"]["divisions"], "tets", len(T),
      "inverted", int((vol <= 0).sum()), "closed", closed, "|", env)
sys.exit(0 if ok else 1)
PYEOF
done
finish
