#!/usr/bin/env bash
# How much the one-limb model's result owes to the step control (issue 13,
# docs/sds.md "Integrator"): the limb model to t = 100 with max_move (the
# largest move of a cell per step, as a fraction of its radius) halved from
# 0.2 to 0.00625 at the default stable_safety 0.8, and stable_safety 0.5 and
# 0.25 at the default max_move; for
# each, the limb's length L at t = 20..100 and its width W at t = 100
# (tools/sds/limb.py), the steps and the wall time, and L(100)'s difference
# from the finest max_move's.  A run takes 10 s to a few minutes on lavapipe.
#
#   tools/sds/step_study.sh [SESSILE [OUT_DIR]]
#     SESSILE  the binary (default build/sessile)
#     OUT_DIR  where the runs go (default runs/sds-step-study; must not exist,
#              or be a study's own folder, which is replaced)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
SESSILE="${1:-$root/build/sessile}"
OUT="${2:-runs/sds-step-study}"
. "$here/study_dir.sh"
study_prepare step_study "$SESSILE" "$OUT" .sds_step_study
model="$root/host/sds/models/limb.sds"
cases="0.2:0.8 0.1:0.8 0.05:0.8 0.025:0.8 0.0125:0.8 0.00625:0.8 0.05:0.5 0.05:0.25"
for c in $cases; do
  mm="${c%%:*}" ss="${c##*:}"
  name="mm${mm}_ss${ss}"
  { cat "$model"; printf '\nmax_move = %s\nstable_safety = %s\n' "$mm" "$ss"; } >"$OUT/$name.sds"
  start=$EPOCHREALTIME
  "$SESSILE" sds run "$OUT/$name.sds" --t-end 100 --frames 5 --out "$OUT/$name" --quiet --no-preview
  echo "$name $start $EPOCHREALTIME" >>"$OUT/wall.txt"
done
/usr/bin/python3 - "$OUT" "$here" $cases <<'PYEOF' | tee "$OUT/step_study.txt"
import json, os, sys
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[2])
import limb
out, cases = sys.argv[1], sys.argv[3:]
wall = {l.split()[0]: float(l.split()[2]) - float(l.split()[1]) for l in open(os.path.join(out, "wall.txt"))}
rows = []
for c in cases:
    mm, ss = c.split(":")
    name = "mm%s_ss%s" % (mm, ss)
    m = json.load(open(os.path.join(out, name, "manifest.json")))
    f = limb.measure(os.path.join(out, name, "sds"), 5)
    rows.append((float(mm), float(ss), m["sds"]["steps"], float(wall[name]), [r[0] for r in f], f[-1][1]))
finest = min((r for r in rows if r[1] == 0.8), key=lambda r: r[0])
print("the limb model to t = 100: L(t) and W(100) in body radii (tools/sds/limb.py)")
print("max_move  stable_safety    steps   wall_s   L(20)  L(40)  L(60)  L(80) L(100)  W(100)  L(100) - L_finest(100)")
for mm, ss, steps, w, L, W in rows:
    print("%8.4f  %13.2f  %7d  %7.1f  %s  %6.2f  %+8.3f" % (mm, ss, steps, w, " ".join("%6.2f" % l for l in L[1:]),
                                                         W, L[-1] - finest[4][-1]))
PYEOF
