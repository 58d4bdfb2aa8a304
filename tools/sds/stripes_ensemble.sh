#!/usr/bin/env bash
# Figure 9's stripes over realisations of the start (issue 33,
# docs/sds_figures.md "The Figure 9 stripes over starts"): one run cannot
# say whether a model lays three stripes on every limb, or spaces them twice
# as far when its timer's decay halves, because which limbs fall short
# changes from start to start.  This runs the rock model (or MODEL) from the
# exact start and from start_jitter J realisations with seeds 1..N, each
# start twice: as it is, and with its timer's decay halved (the period
# doubled; the same start), measures every run with `figures.py stripes` at
# TIME (the halved one --ref the other: the ratio of their mean spacings),
# and prints per start the stripes per limb of both, the ratio and the two
# criteria (three stripes on every limb; the ratio 2 within 30 %), then how
# many limbs and starts meet them.  The same runs give Figure 12's line: per
# start the R² of cells against time over the last three quarters of the run
# (t = 100-400 at the default TIME; `figures.py cells`), since a change to
# the rock model that helps the stripes must not cost Figure 12.  Two runs
# at a time; about 2-4 minutes a pair to t = 400 on 2 cores (lavapipe), by
# the machine.
#
#   tools/sds/stripes_ensemble.sh [SESSILE [OUT_DIR [SEEDS [JITTER [MODEL [TIME]]]]]]
#     SESSILE  the binary (default build/sessile)
#     OUT_DIR  where the runs go (default runs/sds-stripes-ensemble; must not
#              exist, or be this study's own folder, which is replaced)
#     SEEDS    realisations beside the exact start (default 6; 0: the exact start alone)
#     JITTER   start_jitter of the realisations (default 0.1)
#     MODEL    a model file with a `timer clock decay=D` line (default the shipped rock.sds)
#     TIME     when the stripes are counted; the runs end there (default 400)
#   MASK=NAME (environment): count only the cells whose state NAME is set
#     (`figures.py stripes --mask`: the limb's own tissue, the body left out)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
SESSILE="${1:-$root/build/sessile}"
OUT="${2:-runs/sds-stripes-ensemble}"
SEEDS="${3:-6}"
JITTER="${4:-0.1}"
MODEL="${5:-$root/host/sds/models/rock.sds}"
TIME="${6:-400}"
[[ "$SEEDS" =~ ^[0-9]+$ ]] || { echo "stripes_ensemble: SEEDS must be an integer >= 0" >&2; exit 2; }
[[ "$TIME" =~ ^[0-9]+(\.[0-9]+)?$ ]] && [ "$TIME" != 0 ] ||
  { echo "stripes_ensemble: TIME must be a positive number, e.g. 400" >&2; exit 2; }
[ -f "$MODEL" ] || { echo "stripes_ensemble: no model file $MODEL" >&2; exit 2; }
grep -Eq '^timer clock decay=[0-9.eE+-]+' "$MODEL" ||
  { echo "stripes_ensemble: $MODEL has no 'timer clock decay=D' line (the stripes' timer)" >&2; exit 2; }
. "$here/study_dir.sh"
study_prepare stripes_ensemble "$SESSILE" "$OUT" .sds_stripes_ensemble
cp -- "$MODEL" "$OUT/model.sds"
awk '/^timer clock decay=/ { d = $3; sub(/^decay=/, "", d); sub(/decay=[0-9.eE+-]+/, "decay=" d / 2)
                             sub(/#.*/, "# the decay halved by stripes_ensemble.sh") } { print }' \
  "$OUT/model.sds" >"$OUT/model_half.sds"
cmp -s "$OUT/model.sds" "$OUT/model_half.sds" && { echo "stripes_ensemble: the timer's decay is unchanged" >&2; exit 1; }
# a frame every 25 time units, four at least (Figure 12's line needs points)
FRAMES=$(/usr/bin/python3 -c "import math,sys; print(max(4, math.ceil(float(sys.argv[1]) / 25)))" "$TIME")
# start 0 is the exact start (no jitter); start s > 0 the realisation of seed s;
# a line on stderr as each run ends (the study takes minutes a pair)
for s in $(seq 0 "$SEEDS"); do printf '%s %s\n' model "$s" model_half "$s"; done |
  xargs -P 2 -L 1 sh -c 'j=""; [ "$6" != 0 ] && j="--set start_jitter=$4";
    "$0" sds run "$1/$5.sds" --seed "$(( $6 > 0 ? $6 : 1 ))" $j --t-end "$2" --frames "$3" --out "$1/$5_s$6" \
      --quiet --progress none --no-preview && echo "stripes_ensemble: $5, start $6 done" >&2' \
    "$SESSILE" "$OUT" "$TIME" "$FRAMES" "$JITTER"
FIG="/usr/bin/python3 -B $here/figures.py"
MASKARG=()
[ -n "${MASK:-}" ] && MASKARG=(--mask "$MASK")
LINE_FROM=$(/usr/bin/python3 -c 'import sys; print(float(sys.argv[1]) / 4)' "$TIME")  # Figure 12's line: the last 3/4
for s in $(seq 0 "$SEEDS"); do
  $FIG stripes "$OUT/model_s$s" --time "$TIME" "${MASKARG[@]}" | tail -n 1 >"$OUT/stripes_s$s.json"
  $FIG stripes "$OUT/model_half_s$s" --ref "$OUT/model_s$s" --time "$TIME" "${MASKARG[@]}" |
    tail -n 1 >"$OUT/stripes_half_s$s.json"
  $FIG cells "$OUT/model_s$s" --from "$LINE_FROM" --to "$TIME" | tail -n 1 >"$OUT/cells_s$s.json"
done
/usr/bin/python3 - "$OUT" "$SEEDS" "$JITTER" "$TIME" <<'PYEOF' | tee "$OUT/stripes_ensemble.txt"
import json, os, sys
out, seeds, jitter, time = sys.argv[1], int(sys.argv[2]), sys.argv[3], float(sys.argv[4])
rows = []
for s in range(seeds + 1):
    m = json.load(open(os.path.join(out, "stripes_s%d.json" % s)))
    h = json.load(open(os.path.join(out, "stripes_half_s%d.json" % s)))
    cells = [json.loads(l)["cells"] for l in open(os.path.join(out, "model_s%d" % s, "records.jsonl"))][-1]
    line = json.load(open(os.path.join(out, "cells_s%d.json" % s)))
    rows.append({"start": "exact" if s == 0 else "seed %d" % s, "cells": cells,
                 "stripes": [l["stripes"] for l in m["limbs"]], "spacing": m["spacing_mean"],
                 "stripes_half": [l["stripes"] for l in h["limbs"]], "spacing_half": h["spacing_mean"],
                 "ratio": h.get("spacing_ratio"), "three_every_limb": m["criteria"]["three_stripes_per_limb"],
                 "ratio_holds": h["criteria"].get("spacing_doubles_over_ref", False), "r2": line["r2"],
                 "linear": line["criteria"]["linear_r2_at_least_0.98"]})
fmt = lambda v: "-" if v is None else "%.3f" % v
print("Figure 9's stripes at t = %g: %s, the exact start and %d realisation%s (start_jitter %s)" %
      (time, os.path.join(out, "model.sds"), seeds, "" if seeds == 1 else "s", jitter))
print("%-8s %6s  %-22s %-22s %8s %8s %7s %7s  %s" % ("start", "cells", "stripes per limb", "with the decay halved",
                                                    "spacing", "halved", "ratio", "R2", "criteria (three, doubling, line)"))
for r in rows:
    print("%-8s %6d  %-22s %-22s %8s %8s %7s %7s  %s, %s, %s" % (
        r["start"], r["cells"], ",".join(map(str, r["stripes"])), ",".join(map(str, r["stripes_half"])),
        fmt(r["spacing"]), fmt(r["spacing_half"]), fmt(r["ratio"]), fmt(r["r2"]),
        "holds" if r["three_every_limb"] else "no", "holds" if r["ratio_holds"] else "no",
        "holds" if r["linear"] else "no"))
limbs = [n for r in rows for n in r["stripes"]]
ratios = [r["ratio"] for r in rows if r["ratio"] is not None]
summary = {"figure": 9, "time": time, "starts": len(rows), "limbs": len(limbs),
           "limbs_with_three": sum(n >= 3 for n in limbs),
           "starts_three_every_limb": sum(r["three_every_limb"] for r in rows),
           "starts_ratio_holds": sum(r["ratio_holds"] for r in rows),
           "starts_linear": sum(r["linear"] for r in rows),
           "mean_ratio": sum(ratios) / len(ratios) if ratios else None, "rows": rows}
print("limbs with three stripes or more: %d of %d; starts with three on every limb: %d of %d; "
      "starts whose spacing doubles (2 +- 30 %%): %d of %d; mean ratio %s; "
      "starts whose cells fit a line (R2 >= 0.98, t = %g-%g): %d of %d" % (
          summary["limbs_with_three"], summary["limbs"], summary["starts_three_every_limb"], len(rows),
          summary["starts_ratio_holds"], len(rows), fmt(summary["mean_ratio"]), time / 4, time,
          summary["starts_linear"], len(rows)))
print(json.dumps(summary))
PYEOF
