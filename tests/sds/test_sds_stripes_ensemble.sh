#!/usr/bin/env bash
# The Figure 9 stripes study (tools/sds/stripes_ensemble.sh, issue 33) runs
# what it says and sums what it measured: the halved model differs from the
# model in the timer's decay alone, and by half; each start's two runs share
# their start (frame 0 the same bytes) and the starts differ (the exact
# start unjittered, the realisation jittered); the runs reach the time
# asked; the summary's counts are those of the per-run measures, its R2 a
# line through each run's cells; and a
# folder that is not the study's own, or a model without the stripes'
# timer, is refused.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
STUDY="$(dirname "$0")/../../tools/sds/stripes_ensemble.sh"
M="$(dirname "$0")/../../host/sds/models"

mkdir -p "$T/keep" && echo precious >"$T/keep/file"
"$STUDY" "$S" "$T/keep" 1 0.1 "" 5 >"$T/refuse.out" 2>&1
rc=$?
check "a folder that is not the study's own is refused (exit 2) and kept" \
  sh -c '[ "$1" = 2 ] && [ "$(cat "$2/keep/file")" = precious ] && grep -q "not this study" "$2/refuse.out"' _ "$rc" "$T"

"$STUDY" "$S" "$T/nt" 1 0.1 "$M/limb.sds" 5 >"$T/notimer.out" 2>&1
rc=$?
check "a model without the stripes' timer is refused (exit 2), naming the line, no runs" \
  sh -c '[ "$1" = 2 ] && grep -q "timer clock decay" "$2/notimer.out" && ! ls "$2/nt" 2>/dev/null | grep -q model_s' _ "$rc" "$T"

"$STUDY" "$S" "$T/e" 1 0.1 "" 24 >"$T/study.out" 2>"$T/study.err"
rc=$?
check "the study runs the exact start and one realisation, both decays, to t = 24" [ "$rc" = 0 ]
tail -n 5 "$T/study.out"
check "the halved model is the model with the timer's decay halved, nothing else" \
  /usr/bin/python3 -B - "$T/e" <<'PYEOF'
import re, sys
a = open(sys.argv[1] + "/model.sds").read().splitlines()
b = open(sys.argv[1] + "/model_half.sds").read().splitlines()
diff = [(x, y) for x, y in zip(a, b) if x != y]
ok = len(a) == len(b) and len(diff) == 1
if ok:
    da = float(re.match(r"timer clock decay=([0-9.eE+-]+)", diff[0][0]).group(1))
    db = float(re.match(r"timer clock decay=([0-9.eE+-]+)", diff[0][1]).group(1))
    ok = abs(db - da / 2) < 1e-15 and diff[0][0].split()[3] == diff[0][1].split()[3]  # start= kept
    print("decay %g -> %g" % (da, db))
sys.exit(0 if ok else 1)
PYEOF
check "each start's pair shares its start; the two starts differ" eval \
  'cmp -s "$T/e/model_s0/sds/frame_0000.ply" "$T/e/model_half_s0/sds/frame_0000.ply" &&
   cmp -s "$T/e/model_s1/sds/frame_0000.ply" "$T/e/model_half_s1/sds/frame_0000.ply" &&
   ! cmp -s "$T/e/model_s0/sds/frame_0000.ply" "$T/e/model_s1/sds/frame_0000.ply"'
check "the summary is the per-run measures' counts; the runs reach t = 24, jittered as said" \
  /usr/bin/python3 -B - "$T/e" "$T/study.out" <<'PYEOF'
import json, sys
out, txt = sys.argv[1], sys.argv[2]
summary = json.loads(open(txt).read().strip().splitlines()[-1])
ok = summary["starts"] == 2 and summary["time"] == 24
limbs, three, every, doubles, ratios = 0, 0, 0, 0, []
for s in (0, 1):
    m = json.load(open("%s/stripes_s%d.json" % (out, s)))
    h = json.load(open("%s/stripes_half_s%d.json" % (out, s)))
    row = summary["rows"][s]
    n = [l["stripes"] for l in m["limbs"]]
    ok &= row["stripes"] == n and row["stripes_half"] == [l["stripes"] for l in h["limbs"]]
    ok &= h["ref"].rstrip("/").endswith("model_s%d" % s) and h["ref_spacing_mean"] == m["spacing_mean"]
    limbs += len(n); three += sum(x >= 3 for x in n); every += all(x >= 3 for x in n)
    doubles += bool(h["criteria"].get("spacing_doubles_over_ref"))
    if h.get("spacing_ratio") is not None: ratios.append(h["spacing_ratio"])
    for run in ("model_s%d" % s, "model_half_s%d" % s):
        man = json.load(open("%s/%s/manifest.json" % (out, run)))
        recs = [json.loads(l) for l in open("%s/%s/records.jsonl" % (out, run))]
        ok &= recs[-1]["time"] >= 24 and man["sds"]["status"] == "completed"
        ok &= row["cells"] == [json.loads(l) for l in open("%s/model_s%d/records.jsonl" % (out, s))][-1]["cells"]
ok &= limbs == 12 and summary["limbs"] == limbs and summary["limbs_with_three"] == three
ok &= summary["starts_three_every_limb"] == every and summary["starts_ratio_holds"] == doubles
ok &= summary["mean_ratio"] == (sum(ratios) / len(ratios) if ratios else None)
print("limbs %d, with three %d, every limb %d, doubling %d, ratios %s" % (limbs, three, every, doubles, ratios))
sys.exit(0 if ok else 1)
PYEOF
check "each start's R2 is a line fitted to its own cells from t = 6 to 24 (recomputed here), and counted" \
  /usr/bin/python3 -B - "$T/e" "$T/study.out" <<'PYEOF'
import json, sys
import numpy as np
out, txt = sys.argv[1], sys.argv[2]
summary = json.loads(open(txt).read().strip().splitlines()[-1])
ok, linear = True, 0
for s in (0, 1):
    rec = [json.loads(l) for l in open("%s/model_s%d/records.jsonl" % (out, s))]
    tc = np.array([(r["time"], r["cells"]) for r in rec if "time" in r and "cells" in r and 6 - 1e-9 <= r["time"] <= 25])
    fit = np.polyval(np.polyfit(tc[:, 0], tc[:, 1], 1), tc[:, 0])
    ss = ((tc[:, 1] - tc[:, 1].mean()) ** 2).sum()
    r2 = 1 - ((tc[:, 1] - fit) ** 2).sum() / ss if ss > 0 else None
    row = summary["rows"][s]
    ok &= len(tc) >= 3 and (r2 is None and row["r2"] is None or abs(row["r2"] - r2) < 1e-9)
    ok &= row["linear"] == (r2 is not None and r2 >= 0.98)
    linear += row["linear"]
    print("start %d: %d points, R2 %s (the study's %s)" % (s, len(tc), r2, row["r2"]))
ok &= summary["starts_linear"] == linear
sys.exit(0 if ok else 1)
PYEOF
check "the exact start is not jittered, the realisation is (start_jitter in the manifests)" \
  /usr/bin/python3 -B - "$T/e" <<'PYEOF'
import json, sys
def jitter(run):
    m = json.load(open("%s/%s/manifest.json" % (sys.argv[1], run)))
    def find(o):
        if isinstance(o, dict):
            for k, v in o.items():
                if k == "start_jitter" and isinstance(v, (int, float)): return v
                r = find(v)
                if r is not None: return r
        return None
    return find(m)
j = [jitter(r) for r in ("model_s0", "model_half_s0", "model_s1", "model_half_s1")]
print("start_jitter:", j)
sys.exit(0 if j[0] == 0 and j[1] == 0 and abs(j[2] - 0.1) < 1e-12 and abs(j[3] - 0.1) < 1e-12 else 1)
PYEOF
finish
