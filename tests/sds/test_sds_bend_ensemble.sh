#!/usr/bin/env bash
# The Figure 8 ensemble study (tools/sds/bend_ensemble.sh, issue 33) pairs
# what it says it pairs and computes what it prints: each seed's boxed and
# unboxed runs share their start (the excess at t = 0 is exactly 0), the
# seeds' starts differ (start_jitter), the summary's mean, standard error
# and Student-t interval are those of the per-seed excesses (recomputed here
# with numpy), and a folder that is not the
# study's own is refused and left as it was.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
STUDY="$(dirname "$0")/../../tools/sds/bend_ensemble.sh"

mkdir -p "$T/keep" && echo precious >"$T/keep/file"
"$STUDY" "$S" "$T/keep" 2 0.1 0,4 >"$T/refuse.out" 2>&1
rc=$?
check "a folder that is not the study's own is refused (exit 2) and kept" \
  sh -c '[ "$1" = 2 ] && [ "$(cat "$2/keep/file")" = precious ] && grep -q "not this study" "$2/refuse.out"' _ "$rc" "$T"

"$STUDY" "$S" "$T/e" 3 0.1 0,4 10 >"$T/study.out" 2>"$T/study.err"
rc=$?
check "the study runs three seeds, boxed and unboxed, to t = 4" [ "$rc" = 0 ]
tail -n 4 "$T/study.out"
check "pairs share their start, seeds differ, the summary is the per-seed excesses' statistics" \
  /usr/bin/python3 -B - "$T/e" "$T/study.out" <<'PYEOF'
import json, math, sys
import numpy as np
out, txt = sys.argv[1], sys.argv[2]
summary = json.loads(open(txt).read().strip().splitlines()[-1])
ok = summary["seeds"] == 3 and [t["time"] for t in summary["times"]] == [0.0, 4.0]
per = {t: [json.load(open("%s/bend_s%d_t%s.json" % (out, s, t))) for s in (1, 2, 3)] for t in ("0", "4")}
# t = 0: the same start in both runs of a seed, so the same turns
ok &= all(m["excess_deg"] == 0 and m["turn_deg"] == m["ref_turn_deg"] for m in per["0"])
# start_jitter: the seeds' starts are different realisations
starts = [tuple(m["turn_deg"]) for m in per["0"]]
ok &= len(set(starts)) == 3
# the summary is the statistics of the per-seed excesses (t quantile for 2 degrees of freedom: 4.303)
for t, row in zip(("0", "4"), summary["times"]):
    ex = np.array([m["excess_deg"] for m in per[t]])
    mean, se = ex.mean(), ex.std(ddof=1) / math.sqrt(3)
    ok &= np.allclose(row["excess_deg"], ex, rtol=0, atol=1e-12)
    ok &= abs(row["mean_excess_deg"] - mean) < 1e-9 and abs(row["se_deg"] - se) < 1e-9
    ok &= abs(row["ci95_deg"][0] - (mean - 4.303 * se)) < 1e-9 and abs(row["ci95_deg"][1] - (mean + 4.303 * se)) < 1e-9
    ok &= row["limbs_bent"] == bool(mean >= 10 and mean - 4.303 * se > 0)
    print("t = %s: excess %s, mean %.3f, se %.3f" % (t, ex.round(3).tolist(), mean, se))
ok &= summary["times"][0]["limbs_bent"] is False  # no excess at the start
sys.exit(0 if ok else 1)
PYEOF
finish
