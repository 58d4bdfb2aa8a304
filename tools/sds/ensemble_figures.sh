#!/usr/bin/env bash
# Figures 9 and 12's criteria over an ensemble of rock runs (issue 33,
# docs/sds_figures.md "The Figure 9 ensemble re-measured"): for each run s1..sN of
# the folder rock_ensemble.sh made, `figures.py` measures the stripes per
# limb at the time given, the R^2 of a line through cells against time from
# t = 100 to 400, and the six limbs' first divisions (the spread of each
# rank against the median interval); then the ensemble's mean and standard
# error of each, and how many realisations meet each criterion.  Reads the
# runs only; writes ensemble_figures.txt (and each run's measures,
# .fig_*.json) beside them.
#
#   tools/sds/ensemble_figures.sh DIR [TIME [FROM TO]]
#     DIR        a rock_ensemble.sh folder (s1, s2, ... inside)
#     TIME       the stripes' time (default 400)
#     FROM, TO   the line's window (default 100 400, the issue's)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
DIR="${1:?usage: ensemble_figures.sh DIR [TIME]}"
TIME="${2:-400}"
FROM="${3:-100}"
TO="${4:-400}"
[ -d "$DIR/s1" ] || { echo "ensemble_figures: $DIR has no s1 (a rock_ensemble.sh folder?)" >&2; exit 2; }
FIG="/usr/bin/python3 -B $here/figures.py"
n=0
for d in "$DIR"/s[0-9]*; do
  s="${d##*/s}"
  $FIG stripes "$d" --time "$TIME" | tail -n 1 >"$DIR/.fig_stripes_$s.json"
  $FIG cells "$d" --from "$FROM" --to "$TO" | tail -n 1 >"$DIR/.fig_cells_$s.json"
  $FIG divisions "$d" | tail -n 1 >"$DIR/.fig_divisions_$s.json"
  n=$((n + 1))
done
/usr/bin/python3 - "$DIR" "$TIME" <<'PYEOF' | tee "$DIR/ensemble_figures.txt"
import glob, json, math, os, re, sys
d, time = sys.argv[1], sys.argv[2]
seeds = sorted(int(re.sub(r".*_", "", os.path.splitext(p)[0])) for p in glob.glob(os.path.join(d, ".fig_cells_*.json")))
def load(kind, s):
    return json.load(open(os.path.join(d, ".fig_%s_%d.json" % (kind, s))))
def stat(v):
    v = [x for x in v if x is not None]  # R^2 is undefined where the cells did not change
    if not v:
        return None, None
    m = sum(v) / len(v)
    se = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1) / len(v)) if len(v) > 1 else None
    return m, se
print("Figures 9 and 12 over %d realisations (%s)" % (len(seeds), d))
print("%5s %26s %8s %8s %14s %10s" % ("seed", "stripes per limb, t=" + time, "R2", "slope", "rank-1 spread", "simult."))
f = lambda v, d: "-" if v is None else "%.*f" % (d, v)
rows = []
for s in seeds:
    st, ce, dv = load("stripes", s), load("cells", s), load("divisions", s)
    spl = [l["stripes"] for l in st["limbs"]]
    r1 = dv["ranks"][0]["spread"] if dv.get("ranks") else None  # None: no division yet
    sim = bool(dv["criteria"]["limbs_divide_near_simultaneously"])
    rows.append({"seed": s, "stripes": spl, "r2": ce["r2"], "slope": ce["slope"], "spread1": r1, "simultaneous": sim,
                 "three_stripes": all(k >= 3 for k in spl), "linear": ce["r2"] is not None and ce["r2"] >= 0.98})
    print("%5d %26s %8s %8s %14s %10s" % (s, ",".join(map(str, spl)), f(ce["r2"], 4), f(ce["slope"], 2), f(r1, 2), sim))
m_r2, se_r2 = stat([r["r2"] for r in rows])
m_sl, se_sl = stat([r["slope"] for r in rows])
m_sp, se_sp = stat([r["spread1"] for r in rows])
print("mean  R2 %s +- %s, slope %s +- %s cells per time unit, rank-1 spread %s +- %s" %
      (f(m_r2, 4), f(se_r2, 4), f(m_sl, 2), f(se_sl, 2), f(m_sp, 2), f(se_sp, 2)))
print("criteria met: three stripes on every limb %d of %d; R2 >= 0.98 %d of %d; near-simultaneous divisions %d of %d" %
      (sum(r["three_stripes"] for r in rows), len(rows), sum(r["linear"] for r in rows), len(rows),
       sum(r["simultaneous"] for r in rows), len(rows)))
print(json.dumps({"figures": [9, 12], "time": float(time), "runs": rows, "r2_mean": m_r2, "r2_se": se_r2,
                  "slope_mean": m_sl, "slope_se": se_sl, "spread1_mean": m_sp, "spread1_se": se_sp}, allow_nan=False))
PYEOF
