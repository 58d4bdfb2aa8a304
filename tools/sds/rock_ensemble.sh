#!/usr/bin/env bash
# The Figure 9 model (rock) over realisations of its start (issue 13,
# docs/sds.md "Status"): its history is discrete (which cell divides at
# which step), so its cell count at t = 400 is a random variable of the
# start; this runs the shipped rock model with start_jitter J for seeds
# 1..N and prints, per seed and as mean +- standard error, the cells, tets,
# steps, divisions, inversions and the inversions no transformation removed
# (the manifests' sds block).  Two runs at a time; about 5 minutes a pair
# on 2 cores (lavapipe).
#
#   tools/sds/rock_ensemble.sh [SESSILE [OUT_DIR [SEEDS [JITTER [EXTRA]]]]]
#     SESSILE  the binary (default build/sessile)
#     OUT_DIR  where the runs go (default runs/sds-rock-ensemble; must not
#              exist, or be this study's own folder, which is replaced)
#     SEEDS    realisations (default 6)
#     JITTER   start_jitter (default 0.1)
#     EXTRA    model lines appended, quoted (default none; e.g. "max_move = 0.1")
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
SESSILE="${1:-$root/build/sessile}"
OUT="${2:-runs/sds-rock-ensemble}"
SEEDS="${3:-6}"
JITTER="${4:-0.1}"
EXTRA="${5:-}"
[[ "$SEEDS" =~ ^[0-9]+$ ]] && [ "$SEEDS" -ge 2 ] || { echo "rock_ensemble: SEEDS must be an integer >= 2" >&2; exit 2; }
. "$here/study_dir.sh"
study_prepare rock_ensemble "$SESSILE" "$OUT" .sds_rock_ensemble
{ cat "$root/host/sds/models/rock.sds"; printf '\nstart_jitter = %s\n%s\n' "$JITTER" "$EXTRA"; } >"$OUT/rock.sds"
seq 1 "$SEEDS" | xargs -P 2 -I{} "$SESSILE" sds run "$OUT/rock.sds" --seed {} --out "$OUT/s{}" --quiet --no-preview
/usr/bin/python3 - "$OUT" "$SEEDS" "$JITTER" "$EXTRA" <<'PYEOF' | tee "$OUT/rock_ensemble.txt"
import json, math, os, sys
out, seeds, jitter, extra = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
keys = ["cells", "tets", "steps", "divisions", "inversions", "inversions_resisted", "sliver_steps", "repairs"]
rows = []
for sd in range(1, seeds + 1):
    m = json.load(open(os.path.join(out, "s%d" % sd, "manifest.json")))["sds"]
    if m.get("status") != "completed":
        sys.exit("rock_ensemble: seed %d did not complete (%s)" % (sd, m.get("status")))
    rows.append([m[k] for k in keys])
print("the rock model to t = 400, %d realisations (start_jitter %s, seeds 1..%d)%s" %
      (seeds, jitter, seeds, (", with: " + extra) if extra else ""))
print("seed  " + " ".join("%10s" % k[:10] for k in keys))
for sd, r in enumerate(rows, 1):
    print("%4d  " % sd + " ".join("%10d" % v for v in r))
line_m, line_se = [], []
for j in range(len(keys)):
    v = [r[j] for r in rows]
    m = sum(v) / len(v)
    sd_ = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))
    line_m.append("%10.0f" % m)
    line_se.append("%10.0f" % (sd_ / math.sqrt(len(v))))
print("mean  " + " ".join(line_m))
print("se    " + " ".join(line_se))
PYEOF
