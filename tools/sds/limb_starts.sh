#!/usr/bin/env bash
# Figure 7's three criteria (issue 33) from many starts of one limb model:
# seeds FIRST to FIRST + N - 1 (default 1 to N), seed 1 the exact sphere
# (no jitter), every other a realisation of it (start_jitter 0.1), each run
# to the last time asked, two at a
# time, then `figures.py limb` at each time: length / neck, distal / neck,
# the tip's lag behind the front against its radius, and whether all three
# criteria hold.  Prints a row per start and time and, per time, how many
# starts meet all three; writes limb_starts.txt and limb_starts.json in OUT.
# docs/sds_figures.md, "Convergent extension" and "The refit with the
# section width", reports its numbers.
#
#   tools/sds/limb_starts.sh MODEL OUT [N [TIME...]]
#     MODEL  a shipped model name or a .sds file (default to use: limb_extension)
#     OUT    a new folder for the runs
#     N      starts (default 20)
#     TIME   the times measured (default 200); the runs go to the largest
#   SESSILE  the binary (default build/sessile beside this tool)
#   JOBS     runs at a time (default 2)
#   SETS     parameters over the model's for every run, "KEY=VALUE ..."
#            (e.g. SETS="max_move=0.025": the same starts at a finer step)
#   FIRST    the first seed (default 1, the exact sphere): `FIRST=21
#            limb_starts.sh MODEL OUT 20` runs seeds 21-40, all realisations,
#            to check a point chosen on seeds 1-20
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
usage() { sed -n '2,24p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[ $# -ge 2 ] || usage
MODEL="$1" OUT="$2" N="${3:-20}"
shift $(($# < 3 ? $# : 3))
TIMES=("$@")
[ ${#TIMES[@]} -gt 0 ] || TIMES=(200)
BIN="${SESSILE:-$here/../../build/sessile}"
JOBS="${JOBS:-2}"
FIRST="${FIRST:-1}"
[[ "$FIRST" =~ ^[1-9][0-9]*$ ]] || { echo "limb_starts: FIRST must be a positive integer (got $FIRST)" >&2; exit 2; }
[ -x "$BIN" ] || { echo "limb_starts: no sessile binary at $BIN (build first, or set SESSILE)" >&2; exit 2; }
[[ "$N" =~ ^[1-9][0-9]*$ ]] || { echo "limb_starts: N must be a positive integer (got $N)" >&2; exit 2; }
for t in "${TIMES[@]}"; do
  [[ "$t" =~ ^[0-9]+([.][0-9]+)?$ ]] || { echo "limb_starts: a time must be a number (got $t)" >&2; exit 2; }
done
SETS="${SETS:-}"
for kv in $SETS; do
  [[ "$kv" =~ ^[a-z_0-9]+=[^[:space:]]+$ ]] || { echo "limb_starts: SETS takes KEY=VALUE words (got $kv)" >&2; exit 2; }
done
[ ! -e "$OUT" ] || { echo "limb_starts: $OUT exists; give a new folder" >&2; exit 2; }
mkdir -p "$OUT"
TEND=$(printf '%s\n' "${TIMES[@]}" | sort -g | tail -n 1)
# a frame every 5 time units, so that each time asked has its frame
FRAMES=$(/usr/bin/python3 -c 'import math,sys; print(max(1, math.ceil(float(sys.argv[1]) / 5)))' "$TEND")
run_one() { # seed
  local s="$1" jit=() kv
  [ "$s" -eq 1 ] || jit=(--set start_jitter=0.1)
  for kv in $SETS; do jit+=(--set "$kv"); done
  "$BIN" sds run "$MODEL" --t-end "$TEND" --frames "$FRAMES" --seed "$s" "${jit[@]}" \
    --out "$OUT/s$s" --quiet --no-preview >"$OUT/s$s.log" 2>&1 || echo "limb_starts: seed $s failed ($OUT/s$s.log)" >&2
}
export -f run_one
export BIN MODEL TEND FRAMES OUT SETS
echo "limb_starts: $N starts of $MODEL to t = $TEND${SETS:+ ($SETS)}, $JOBS at a time" >&2
seq "$FIRST" $((FIRST + N - 1)) | xargs -P "$JOBS" -I{} bash -c 'run_one {}'
/usr/bin/python3 - "$here" "$OUT" "$FIRST" "$N" "${TIMES[@]}" <<'PYEOF'
import json, os, subprocess, sys
here, out, first, n, times = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5:]
num = lambda v, f: "-" if v is None else f % v  # a limb too short for a neck has no ratios
rows, lines = [], []
def say(s):
    print(s)
    lines.append(s)
say("%5s %7s %9s %10s %9s %8s %5s" % ("seed", "t", "L/neck", "dist/neck", "tip lag", "tip r", "all3"))
for t in times:
    met = 0
    for s in range(first, first + n):
        run = os.path.join(out, "s%d" % s)
        r = subprocess.run(["/usr/bin/python3", "-B", os.path.join(here, "figures.py"), "limb", run, "--time", t],
                           capture_output=True, text=True)
        if r.returncode != 0 or not r.stdout.strip():
            say("%5d %7s  (no measure: the run failed or has no frame)" % (s, t))
            rows.append({"seed": s, "time": float(t), "measured": False})
            continue
        m = json.loads(r.stdout.strip().splitlines()[-1])
        ok = all(m["criteria"].values())
        met += ok
        rows.append({"seed": s, "time": float(t), "measured": True, "length_over_neck": m["length_over_neck"],
                     "distal_over_neck": m["distal_over_neck"], "tip_behind_front": m["tip_behind_front"],
                     "tip_radius": m["tip_radius"], "criteria": m["criteria"], "all": ok})
        say("%5d %7s %9s %10s %9.2f %8.3f %5s" % (s, t, num(m["length_over_neck"], "%.2f"),
                                                 num(m["distal_over_neck"], "%.2f"), m["tip_behind_front"],
                                                 m["tip_radius"], "yes" if ok else "no"))
    say("t = %s: all three criteria from %d of %d starts" % (t, met, n))
json.dump(rows, open(os.path.join(out, "limb_starts.json"), "w"), indent=1)
open(os.path.join(out, "limb_starts.txt"), "w").write("\n".join(lines) + "\n")
PYEOF
