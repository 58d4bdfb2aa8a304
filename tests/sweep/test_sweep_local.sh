#!/usr/bin/env bash
# `sessile sweep` with the local engine (docs/sweep.md): malformed sweeps
# exit 2 with one line and write nothing; a 6-point sweep (2 noise values x
# 3 seeds of `sphere`) gives the same bytes with -j 1 and -j 2, after a
# kill -9 of the engine and a rerun, after SIGINT and a rerun, and through
# `sweep task`; a point that fails at run time is reported failed with its
# error while the others complete; status and gather (mean, sd, 95 % interval
# recomputed here from the runs' own records).
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
fatal() { echo "FAIL $*"; fails=$((fails + 1)); finish; exit 1; }

. "$(dirname "$0")/sweep_common.sh"
write_sweep "$T/sweep.json" 60 7

# --- malformed sweeps: exit 2, one line, nothing written ---------------------
bad() { # what, sweep file text
  printf '%s' "$2" >"$T/bad.json"
  run sweep plan "$T/bad.json" --out "$T/bad"
  check "malformed ($1): exit 2, one line, nothing written" eval \
    'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && [ ! -s "$T/out" ] && [ ! -e "$T/bad" ]'
}
bad "unknown generator" '{"generator": "spheroid"}'
bad "unknown parameter" '{"generator": "sphere", "axes": [{"parameter": "colour", "values": [1]}]}'
bad "unknown base parameter" '{"generator": "sphere", "base": {"colour": 1}}'
bad "out-of-range value on one point" '{"generator": "sphere", "axes": [{"parameter": "noise", "values": [0.1, 0.9]}], "seeds": [1, 2]}'
bad "empty axis" '{"generator": "sphere", "axes": [{"parameter": "noise", "values": []}]}'
bad "10^7 points" '{"generator": "sphere", "axes": [{"parameter": "noise", "range": {"from": 0, "to": 0.5, "count": 1000}}, {"parameter": "radius", "range": {"from": 1, "to": 2, "count": 1000}}], "seeds": {"count": 10}}'
bad "duplicate key" '{"generator": "sphere", "generator": "sphere"}'
bad "unknown key" '{"generator": "sphere", "axis": []}'
bad "trailing bytes" '{"generator": "sphere"} {}'
bad "an option the sweep gives" '{"generator": "sphere", "options": ["--seed", "3"]}'
bad "zip of unequal axes" '{"generator": "sphere", "combine": "zip", "axes": [{"parameter": "noise", "values": [0.1, 0.2]}, {"parameter": "level", "values": [2]}]}'
printf '%s' '{"generator": "sphere", "axes": [{"parameter": "noise", "values": [0.1, 0.9]}], "seeds": [1, 2]}' >"$T/bad.json"
run sweep plan "$T/bad.json" --out "$T/bad"
check "the out-of-range refusal names the point and the parameter" eval 'grep -q "point 2 .*noise" "$T/err"'
mkdir -p "$T/full" && touch "$T/full/x"
run sweep plan "$T/sweep.json" --out "$T/full"
check "a folder that is not empty is refused (exit 2)" eval 'rc_is 2 && [ "$(ls "$T/full")" = x ]'

mkdir -p "$T/damaged" && echo '{"width": 4, "combinations": 1, "metrics": [], "points": [{}]}' >"$T/damaged/sweep.json"
for c in run status gather submit; do
  run sweep $c "$T/damaged"
  check "sweep $c of a damaged sweep.json: exit 2, one line" eval 'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ]'
done

# --- plan -------------------------------------------------------------------------
for d in a b d e f; do "$S" sweep plan "$T/sweep.json" --out "$T/$d" >"$T/plan.out" 2>&1; done
check "plan: 6 points and the cost (6 x 60 iterations)" eval \
  'grep -q "6 points (2 combinations x 3 seeds)" "$T/plan.out" && grep -q "= 360 iterations" "$T/plan.out"'
check "plan: sweep.json and one config per point" "$PY" - "$T/a" <<'PYEOF'
import json, sys
d = sys.argv[1]; p = json.load(open(d + "/sweep.json"))
pts = p["points"]
ok = len(pts) == 6 and [q["seed"] for q in pts] == [7, 8, 9] * 2
ok = ok and [q["parameters"]["noise"] for q in pts] == ["0.01"] * 3 + ["0.03"] * 3
for q in pts:
    c = json.load(open("%s/points/%04d.json" % (d, q["index"])))
    ok = ok and c["args"] == q["args"] and "--resume" in c["resume_args"] and "level=4" in c["args"]
sys.exit(0 if ok else 1)
PYEOF

all_completed() { "$S" sweep status "$1" | grep -q "6 points: 6 completed"; }
no_running() { for _ in $(seq 200); do "$S" sweep status "$1" | grep -q "^[0-9]* running" || return 0; sleep 0.05; done; return 1; }
wait_manifest() { for _ in $(seq 400); do [ -e "$1/runs/0000/manifest.json" ] && return 0; sleep 0.02; done; return 1; }

# --- -j 1 and -j 2 ----------------------------------------------------------------
run sweep run "$T/a" -j 1
check "run -j 1 completes every point" eval 'rc_is 0 && all_completed "$T/a"'
run sweep run "$T/b" -j 2
check "run -j 2 completes every point" eval 'rc_is 0 && all_completed "$T/b"'
check "-j 2 gives the bytes of -j 1" same "$T/a" "$T/b"
check "the seeds differ: points 0 and 1 are not the same run" eval '! cmp -s "$T/a/runs/0000/sphere/final.ply" "$T/a/runs/0001/sphere/final.ply"'
run sweep run "$T/a" -j 2
check "a second run skips every completed point" eval 'rc_is 0 && grep -q "6 completed before, 0 to run" "$T/out"'

# --- kill -9 of the engine, then a rerun ---------------------------------------------
# The kill must land while a point runs with its manifest written. A point of
# 60 iterations takes a fraction of a second, so under load one can finish (or
# the next not yet have its manifest) between the poll and the kill: then no
# point is left to resume, and the kill is tried again on a fresh plan.
unfinished() { # DIR: the points with a resumable manifest (it holds the config) not completed
  local m
  for m in "$1"/runs/*/manifest.json; do
    [ -e "$m" ] && grep -q '"config"' "$m" && ! grep -q '"state":[[:space:]]*"completed"' "$m" && basename "$(dirname "$m")"
  done
}
# DIR PID: until a point runs (at most 60 s), or the engine has ended
wait_running() { for _ in $(seq 6000); do grep -qs '"state":[[:space:]]*"running"' "$1"/runs/*/manifest.json && return 0; kill -0 "$2" 2>/dev/null || return 1; sleep 0.01; done; return 1; }
caught=""
for attempt in 1 2 3 4 5; do
  c="$T/c$attempt"
  "$S" sweep plan "$T/sweep.json" --out "$c" >/dev/null 2>&1 || fatal "sweep plan for the kill"
  "$S" sweep run "$c" -j 2 >/dev/null 2>&1 &
  eng=$!
  wait_running "$c" "$eng"
  kill -9 "$eng"; wait "$eng" 2>/dev/null
  no_running "$c" || break # the check below reports it
  caught=$(unfinished "$c" | tr '\n' ' ')
  [ -n "$caught" ] && break
done
echo "  killed mid-run on attempt $attempt: points ${caught:-none}"
check "after kill -9 no point runs on (its children die with it)" no_running "$c"
check "... and a point was caught running with its manifest (in 5 tries)" [ -n "$caught" ]
check "... and the sweep is unfinished" eval '! all_completed "$c"'
run sweep run "$c" -j 2
check "a rerun completes every point" eval 'rc_is 0 && all_completed "$c"'
resumed_all() { local p; [ -n "$caught" ] || return 1; for p in $caught; do grep -q '"starts":[[:space:]]*2' "$c/runs/$p/manifest.json" || return 1; done; }
check "... resuming each killed point (its manifest says starts 2)" resumed_all
check "... to the bytes of the uninterrupted sweep" same "$T/a" "$c"

# --- SIGINT stops the points cleanly ---------------------------------------------------
# The signal must reach the engine before its last point ends (its points take
# a fraction of a second each): a sweep that completed first had nothing to
# stop, and is tried again on a fresh plan.
for attempt in 1 2 3 4 5; do
  "$S" sweep run "$T/e" -j 2 >"$T/e.out" 2>"$T/e.err" &
  eng=$!
  wait_manifest "$T/e"
  kill -INT "$eng" 2>/dev/null; wait "$eng"; rc=$?
  [ $rc = 0 ] && all_completed "$T/e" || break
  echo "  the sweep completed before SIGINT (attempt $attempt): again"
  rm -rf "$T/e"
  "$S" sweep plan "$T/sweep.json" --out "$T/e" >/dev/null 2>&1 || fatal "sweep plan for SIGINT"
done
check "SIGINT: the engine exits 130 and says how to go on" eval '[ $rc = 130 ] && grep -q "sweep run" "$T/e.err"'
check "... no point left running, none failed" eval 'no_running "$T/e" && ! "$S" sweep status "$T/e" | grep -q "^[0-9]* failed"'
run sweep run "$T/e"
check "... a second sweep run goes on to the same bytes" eval 'rc_is 0 && all_completed "$T/e" && same "$T/a" "$T/e"'

# --- a point that fails at run time ---------------------------------------------------
# the generator refuses a folder that holds files but no run: point 4 fails
mkdir -p "$T/d/runs/0004" && echo x >"$T/d/runs/0004/notes.txt"
run sweep run "$T/d" -j 2
check "a failing point: exit 1, reported failed with its error" eval \
  'rc_is 1 && grep -q "0004 failed (exit 2): .*not empty" "$T/out"'
check "... the others complete with their bytes" same "$T/a" "$T/d" 0000 0001 0002 0003 0005
run sweep status "$T/d"
check "... status: 5 completed, 1 failed, with the error" eval \
  'grep -q "5 completed, 0 running, 0 pending, 0 interrupted, 1 failed" "$T/out" && grep -q "^0004 failed: .*not empty" "$T/out"'

# --- sweep task: one point, as a Slurm array task runs it ----------------------------
run sweep task "$T/f" 3
check "sweep task runs one point to the bytes of the engine's" eval 'rc_is 0 && same "$T/a" "$T/f" 0003'
run sweep task "$T/f" 3
check "... and again: already completed, exit 0" eval 'rc_is 0 && grep -q "completed already" "$T/out"'
run sweep task "$T/f" 6
check "... a point the sweep does not have: exit 2" rc_is 2
run sweep status "$T/f"
check "status: 1 completed, 5 pending" eval 'grep -q "6 points: 1 completed, 0 running, 5 pending" "$T/out"'

# --- gather ------------------------------------------------------------------------
run sweep gather "$T/a"
check "gather writes the tables" eval 'rc_is 0 && [ -s "$T/a/gather/points.csv" ] && [ -s "$T/a/gather/summary.jsonl" ]'
check "gather: points and per-combination mean, sd and 95 % interval from the runs' records" "$PY" - "$T/a" <<'PYEOF'
import csv, json, math, statistics, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(d + "/gather/points.csv")))
summ = [json.loads(l) for l in open(d + "/gather/summary.jsonl")]
ok = len(rows) == 6 and all(r["state"] == "completed" for r in rows) and [r["seed"] for r in rows] == ["7", "8", "9"] * 2
ok = ok and all(r["checkpoint.iteration"] == "60" for r in rows) and len(summ) == 2
for c in range(2):
    vals = []
    for r in rows[3 * c: 3 * c + 3]:
        last = open("%s/runs/%04d/records.jsonl" % (d, int(r["index"]))).read().splitlines()[-1]
        v = json.loads(last)["radius_mean_cm"]
        ok = ok and float(r["last_record.radius_mean_cm"]) == v
        vals.append(v)
    m = summ[c]["metrics"]["last_record.radius_mean_cm"]
    mean, sd = statistics.mean(vals), statistics.stdev(vals)
    h = 4.303 * sd / math.sqrt(3)
    ok = ok and m["n"] == 3 and abs(m["mean"] - mean) <= 1e-12 * abs(mean) and abs(m["sd"] - sd) <= 1e-9 * sd
    ok = ok and abs(m["ci95_hi"] - (mean + h)) <= 1e-12 and abs(m["ci95_lo"] - (mean - h)) <= 1e-12 and sd > 0
    ok = ok and summ[c]["parameters"]["noise"] == ["0.01", "0.03"][c]
try:
    import numpy
    a = numpy.genfromtxt(d + "/gather/summary.csv", delimiter=",", names=True)
    ok = ok and a.shape == (2,)
except ImportError:
    pass
print(summ)
sys.exit(0 if ok else 1)
PYEOF
run sweep gather "$T/d"
check "gather of a sweep with a failed point: its state and error, no metrics" eval \
  'grep -q "^4,1,8,failed,4,0.03,," "$T/d/gather/points.csv" && grep -q "\"error\"" "$T/d/gather/points.jsonl"'
finish
