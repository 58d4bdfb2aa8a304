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

for m in six_limbs_box rock rock_stripes attractor budded; do
  run sds run "$m" --t-end 30 --frames 2 --out "$T/$m" --quiet --no-preview
  check "$m to t = 30 completes" rc_is 0
  check "$m: cells divide and grow in number; the last complex is valid; its environment holds" \
    "$PY" - "$T/$m" "$m" "$M/$m.sds" "$(dirname "$0")/../.." <<'PYEOF'
import json, os, re, sys
import numpy as np
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(sys.argv[4], "tools", "sds"))
import complex_check
d, name, model = sys.argv[1:4]
m = json.load(open(d + "/manifest.json"))
recs = [json.loads(l) for l in open(d + "/records.jsonl")]
k = complex_check.check(d + "/sds/frame_0002.vtu")
X, T, vol, closed = k["X"], k["T"], k["vol"], k["closed"]
ok = m["state"] == "completed" and m["sds"]["divisions"] > 0 and recs[-1]["cells"] > recs[0]["cells"]
ok = ok and len(X) == recs[-1]["cells"] and closed and not k["faces_over_2"] and (vol > 0).all()
params = {}
for line in open(model):
    kv = re.match(r"^(\w+)\s*=\s*([-0-9. ]+)", line)
    if kv: params[kv.group(1)] = [float(v) for v in kv.group(2).split()]
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
