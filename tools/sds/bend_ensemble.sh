#!/usr/bin/env bash
# Figure 8 (the box bends the limbs) over realisations of the start (issue
# 33, docs/sds_figures.md "Figure 8 over realisations"): one run of the boxed model
# and one of the same model without its box cannot separate the box's
# bending from the limbs' own curling (50-100 degrees in every run), so this
# runs six_limbs_box.sds with start_jitter J for seeds 1..N, boxed and
# unboxed with the same seed (the same start), measures each pair with
# `figures.py bend` at the times given, and prints per time the paired
# excess (boxed mean turn minus unboxed), its mean, standard error and 95 %
# confidence interval (Student's t), and the criterion: the mean excess at
# least MIN_BEND degrees and resolved (the interval's lower end above 0).  Two runs at a time; about 3 minutes a pair
# to t = 250 on 2 cores (lavapipe).
#
#   tools/sds/bend_ensemble.sh [SESSILE [OUT_DIR [SEEDS [JITTER [TIMES [MIN_BEND]]]]]]
#     SESSILE   the binary (default build/sessile)
#     OUT_DIR   where the runs go (default runs/sds-bend-ensemble; must not
#               exist, or be this study's own folder, which is replaced)
#     SEEDS     realisations (default 6)
#     JITTER    start_jitter (default 0.1)
#     TIMES     the times measured, comma-separated; the runs end at the last
#               (default 150,200,250)
#     MIN_BEND  the criterion's margin in degrees (default 10, figures.py's)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
SESSILE="${1:-$root/build/sessile}"
OUT="${2:-runs/sds-bend-ensemble}"
SEEDS="${3:-6}"
JITTER="${4:-0.1}"
TIMES="${5:-150,200,250}"
MIN_BEND="${6:-10}"
[[ "$SEEDS" =~ ^[0-9]+$ ]] && [ "$SEEDS" -ge 2 ] || { echo "bend_ensemble: SEEDS must be an integer >= 2" >&2; exit 2; }
[[ "$TIMES" =~ ^[0-9]+(\.[0-9]+)?(,[0-9]+(\.[0-9]+)?)*$ ]] ||
  { echo "bend_ensemble: TIMES must be comma-separated numbers, e.g. 150,200,250" >&2; exit 2; }
. "$here/study_dir.sh"
study_prepare bend_ensemble "$SESSILE" "$OUT" .sds_bend_ensemble
M="$root/host/sds/models"
{ cat "$M/six_limbs_box.sds"; printf '\nstart_jitter = %s\n' "$JITTER"; } >"$OUT/box.sds"
sed 's/^box = .*/# (no box: the reference of Figure 8)/' "$OUT/box.sds" >"$OUT/nobox.sds"
grep -q '^box' "$OUT/nobox.sds" && { echo "bend_ensemble: the box is still in the reference" >&2; exit 1; }
grep -q '^box' "$OUT/box.sds" || { echo "bend_ensemble: the model has no box line" >&2; exit 1; }
T_END="${TIMES##*,}"
FRAMES=$(/usr/bin/python3 -c "import math,sys; print(max(1, math.ceil(float(sys.argv[1]) / 10)))" "$T_END")
for s in $(seq 1 "$SEEDS"); do printf '%s %s\n' box "$s" nobox "$s"; done |
  xargs -P 2 -L 1 sh -c '"$0" sds run "$1/$4.sds" --seed "$5" --t-end "$2" --frames "$3" --out "$1/$4_s$5" --quiet --progress none --no-preview' \
    "$SESSILE" "$OUT" "$T_END" "$FRAMES"
FIG="/usr/bin/python3 -B $here/figures.py"
for s in $(seq 1 "$SEEDS"); do
  for t in ${TIMES//,/ }; do
    $FIG bend "$OUT/box_s$s" --ref "$OUT/nobox_s$s" --time "$t" --min-bend "$MIN_BEND" | tail -n 1 >"$OUT/bend_s${s}_t$t.json"
  done
done
/usr/bin/python3 - "$OUT" "$SEEDS" "$JITTER" "$TIMES" "$MIN_BEND" <<'PYEOF' | tee "$OUT/bend_ensemble.txt"
import json, math, os, sys
out, seeds, jitter, times, min_bend = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4].split(","), float(sys.argv[5])
# Student's t, two-sided 95 %, for n - 1 degrees of freedom (1..30; beyond, the normal's 1.96)
T95 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
       2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042]
for s in range(1, seeds + 1):
    for run in ("box_s%d" % s, "nobox_s%d" % s):
        m = json.load(open(os.path.join(out, run, "manifest.json")))["sds"]
        if m.get("status") != "completed":
            sys.exit("bend_ensemble: %s did not complete (%s)" % (run, m.get("status")))
print("Figure 8: six_limbs_box against itself without the box, %d realisations (start_jitter %s, seeds 1..%d)"
      % (seeds, jitter, seeds))
print("%6s  %s  %8s %8s %8s %8s %18s  %s" % ("t", " ".join("%7s" % ("s%d" % s) for s in range(1, seeds + 1)),
                                           "box", "no box", "excess", "se", "95 % CI", "criterion"))
summary = []
for t in times:
    ex, bx, nb = [], [], []
    for s in range(1, seeds + 1):
        m = json.load(open(os.path.join(out, "bend_s%d_t%s.json" % (s, t))))
        ex.append(m["excess_deg"]); bx.append(m["mean_turn_deg"]); nb.append(m["ref_mean_turn_deg"])
    n = len(ex)
    mean = sum(ex) / n
    sd = math.sqrt(sum((v - mean) ** 2 for v in ex) / (n - 1))
    se = sd / math.sqrt(n)
    q = T95[n - 2] if n - 1 <= len(T95) else 1.96
    lo, hi = mean - q * se, mean + q * se
    holds = mean >= min_bend and lo > 0
    print("%6s  %s  %8.1f %8.1f %8.1f %8.1f   [%6.1f, %6.1f]  %s" % (
        t, " ".join("%7.1f" % v for v in ex), sum(bx) / n, sum(nb) / n, mean, se, lo, hi,
        "holds" if holds else "does not hold"))
    summary.append({"time": float(t), "excess_deg": ex, "box_mean_deg": sum(bx) / n, "nobox_mean_deg": sum(nb) / n,
                    "mean_excess_deg": mean, "se_deg": se, "ci95_deg": [lo, hi], "limbs_bent": holds})
print("criterion: the mean paired excess at least %g degrees, its 95 %% interval above 0" % min_bend)
print(json.dumps({"figure": 8, "seeds": seeds, "start_jitter": float(jitter), "min_bend_deg": min_bend,
                  "times": summary}))
PYEOF
