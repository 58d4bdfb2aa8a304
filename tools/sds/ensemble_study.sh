#!/usr/bin/env bash
# Does the one-limb model's result converge as the step is refined, seed
# statistics aside?  (issue 13, docs/sds.md "Integrator").  One run of the
# limb model is a discrete history (which cell divides at which step), so its
# length L(100) jumps between settings of max_move; the statement to test is
# about the distribution.  Each seed gives a realisation of the start
# (start_jitter: the icosphere's vertices moved along their radii, drawn from
# the seed, docs/sds_rules.md); for each max_move the study runs every seed
# to t = 100 and prints the mean, standard deviation and standard error of
# L(t) (tools/sds/limb.py), and each mean's difference from the finest
# setting's with its standard error.  About 10 minutes on 2 cores (lavapipe).
#
#   tools/sds/ensemble_study.sh [SESSILE [OUT_DIR [SEEDS [JITTER [MAX_MOVES]]]]]
#     SESSILE    the binary (default build/sessile)
#     OUT_DIR    where the runs go (default runs/sds-ensemble-study; must not
#                exist, or be a study's own folder, which is replaced)
#     SEEDS      realisations per setting (default 6)
#     JITTER     start_jitter (default 0.1)
#     MAX_MOVES  quoted list (default "0.05 0.025 0.0125 0.00625")
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
SESSILE="${1:-$root/build/sessile}"
OUT="${2:-runs/sds-ensemble-study}"
SEEDS="${3:-6}"
JITTER="${4:-0.1}"
MOVES="${5:-0.05 0.025 0.0125 0.00625}"
[[ "$SEEDS" =~ ^[0-9]+$ ]] && [ "$SEEDS" -ge 2 ] || { echo "ensemble_study: SEEDS must be an integer >= 2" >&2; exit 2; }
. "$here/study_dir.sh"
study_prepare ensemble_study "$SESSILE" "$OUT" .sds_ensemble_study
model="$root/host/sds/models/limb.sds"
jobs=()
for mm in $MOVES; do
  { cat "$model"; printf '\nmax_move = %s\nstart_jitter = %s\n' "$mm" "$JITTER"; } >"$OUT/mm$mm.sds"
  for ((sd = 1; sd <= SEEDS; sd++)); do jobs+=("$mm $sd"); done
done
# two runs at a time (the machine's cores); each run is deterministic on its own
printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 sh -c \
  '"$0" sds run "$1/mm$2.sds" --t-end 100 --frames 5 --seed "$3" --out "$1/mm$2_s$3" --quiet --no-preview' \
  "$SESSILE" "$OUT"
/usr/bin/python3 - "$OUT" "$here" "$SEEDS" "$JITTER" $MOVES <<'PYEOF' | tee "$OUT/ensemble_study.txt"
import json, math, os, sys
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[2])
import limb
out, seeds, jitter, moves = sys.argv[1], int(sys.argv[3]), sys.argv[4], sys.argv[5:]
rows = []
for mm in moves:
    L, steps = [], []
    for sd in range(1, seeds + 1):
        d = os.path.join(out, "mm%s_s%d" % (mm, sd))
        L.append([r[0] for r in limb.measure(os.path.join(d, "sds"), 5)])
        steps.append(json.load(open(os.path.join(d, "manifest.json")))["sds"]["steps"])
    stats = []
    for k in range(6):
        v = [l[k] for l in L]
        m = sum(v) / len(v)
        sd_ = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))
        stats.append((m, sd_, sd_ / math.sqrt(len(v))))
    rows.append((float(mm), sum(steps) / len(steps), stats, [l[5] for l in L]))
fin = min(rows, key=lambda r: r[0])
print("the limb model to t = 100, %d realisations per setting (start_jitter %s, seeds 1..%d)" % (seeds, jitter, seeds))
print("L(t): the body's extent along the limb's axis less the start's diameter, body radii (tools/sds/limb.py)")
print("max_move  mean steps   L(0) mean   L(60) mean +- se   L(100) mean +- se   sd(L(100))  L(100) - finest (+- se)")
for mm, st, s, l100 in rows:
    dm = s[5][0] - fin[2][5][0]
    dse = math.sqrt(s[5][2] ** 2 + fin[2][5][2] ** 2)
    print("%8.5f  %10.0f  %10.3f   %7.3f +- %5.3f     %7.3f +- %5.3f     %7.3f     %+7.3f (+- %5.3f)" %
          (mm, st, s[0][0], s[3][0], s[3][2], s[5][0], s[5][2], s[5][1], dm, dse))
print("per seed, L(100):")
for mm, st, s, l100 in rows:
    print("%8.5f  %s" % (mm, " ".join("%5.2f" % x for x in l100)))
PYEOF
