#!/usr/bin/env bash
# Frames do not change the physics (issue 33): a limb bud that grows fast
# (Delta 0.03: cells divide and tets invert from t = 4) run to t = 6 in 5
# frames and in 50, and to t = 3 in 25.  The step sequence is the same
# whatever --frames and --t-end ask (sds/steps.csv equal but for the wall
# ms, the shorter run's a prefix of the longer's), the frames at shared
# times are the same bytes (frame k of 5 is frame 10 k of 50, frame k of
# the t = 3 run frame k of 50, its final surface frame 25's), and each frame
# is the state at the first step at or past its time, that step's exact
# time in the series (series.pvd) and in the records.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
sed 's/^const Delta = .*/const Delta = 0.03/' "$(dirname "$0")/../../host/sds/models/limb.sds" >"$T/fast.sds"

run sds run "$T/fast.sds" --t-end 6 --frames 5 --out "$T/f5" --quiet
check "t_end 6, 5 frames: completes" rc_is 0
run sds run "$T/fast.sds" --t-end 6 --frames 50 --out "$T/f50" --quiet
check "t_end 6, 50 frames: completes" rc_is 0
run sds run "$T/fast.sds" --t-end 3 --frames 25 --out "$T/h25" --quiet
check "t_end 3, 25 frames: completes" rc_is 0

same_frame() { # dir_a frame_a dir_b frame_b
  for e in ply vtu; do
    cmp -s "$1/sds/$(printf 'frame_%04d' "$2").$e" "$3/sds/$(printf 'frame_%04d' "$4").$e" || return 1
  done
}
check "5 frames against 50: frame k is frame 10 k, the same bytes (PLY and VTU), final.ply too" eval \
  'for k in 0 1 2 3 4 5; do same_frame "$T/f5" $k "$T/f50" $((10 * k)) || exit 1; done; cmp -s "$T/f5/sds/final.ply" "$T/f50/sds/final.ply"'
check "... and the 45 frames between differ from their neighbours (the frames are states, not copies)" eval \
  '! same_frame "$T/f50" 11 "$T/f50" 10 && ! same_frame "$T/f50" 49 "$T/f50" 50'
check "t_end 3 against t_end 6: frame k of 25 is frame k of 50 (k = 0..25), its final surface frame 25's" eval \
  'for k in $(seq 0 25); do same_frame "$T/h25" $k "$T/f50" $k || exit 1; done; cmp -s "$T/h25/sds/final.ply" "$T/f50/sds/frame_0025.ply"'

check "the step log, series and records: one step sequence; each frame the first step at or past its time" \
  "$PY" - "$T" <<'PYEOF'
import csv, json, re, sys
T = sys.argv[1]
def steps(d):
    with open(T + "/" + d + "/sds/steps.csv", newline="") as f:
        return [{k: v for k, v in r.items() if k != "ms"} for r in csv.DictReader(f)]
def pvd(d):  # (timestep text, file) per data set
    return re.findall(r'timestep="([^"]*)" group="" part="0" file="([^"]*)"', open(T + "/" + d + "/sds/series.pvd").read())
def recs(d): return [json.loads(l) for l in open(T + "/" + d + "/records.jsonl")]
s5, s50, s25 = steps("f5"), steps("f50"), steps("h25")
ok = s5 == s50 and len(s25) < len(s5) and s25 == s50[:len(s25)]
div = sum(int(r["divisions"]) for r in s5)
inv = sum(int(r["inversions"]) for r in s5)
ok = ok and div > 0 and inv > 0
print("steps", len(s5), len(s50), len(s25), "divisions", div, "inversions", inv, "equal:", ok)
for d, t_end, n in (("f5", 6.0, 5), ("f50", 6.0, 50), ("h25", 3.0, 25)):
    times = [float(r["time"]) for r in steps(d)]
    texts = {float(r["time"]): r["time"] for r in steps(d)}
    p, rc = pvd(d), recs(d)
    good = len(p) == n + 1 and [f for _, f in p] == ["frame_%04d.vtu" % k for k in range(n + 1)]
    good = good and p[0][0] == "0" and [r["frame"] for r in rc] == list(range(n + 1))
    for k in range(1, n + 1):
        nominal = t_end * (k / n)
        first = next(t for t in times if t >= nominal)
        # the step's time, to the bit, in the series as the step log writes it
        good = good and float(p[k][0]) == first and p[k][0] == texts[first] and rc[k]["time"] == first
    # the run ends at the first step at or past t_end: no step after it, none cut
    good = good and times[-1] >= t_end and times[-2] < t_end and float(p[-1][0]) == times[-1]
    print(d, "frames", len(p), "last", p[-1][0], "ok:", good)
    ok = ok and good
sys.exit(0 if ok else 1)
PYEOF
finish
