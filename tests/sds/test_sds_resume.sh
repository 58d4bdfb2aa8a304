#!/usr/bin/env bash
# `sessile sds run --resume`: a limb bud that grows fast (Delta 0.03: cells
# divide and tets invert from t = 4) run to t = 10 in 5 frames at once, and
# again stopped by SIGINT after frame 1, resumed, killed by SIGKILL after
# frame 4 (mid-interval, no checkpoint of its own), resumed again: every file
# under sds/ is the same bytes, the records and the step log (sds/steps.csv)
# equal but for their timings, the manifest's totals equal but for the wall
# time.  Refusals, one line and
# exit 2: nothing to resume (an empty or missing folder), a folder of another
# generator, another model named with --resume, an option a resume must not
# change, and a checkpoint written by another configuration (another seed and t_end,
# or other parameters: --set).  A run made with --set, stopped and resumed,
# ends in the bytes of one that never stopped: the resume takes the stored
# parameters, not the model's own, and refuses --set.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
one_line() { [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "error" "$T/err"; }
sums() { (cd "$1" && find sds -type f ! -name steps.csv | LC_ALL=C sort | xargs sha256sum); }
# waits (up to 60 s) for a file, then sends a signal to a process
signal_after() { # file signal pid
  for _ in $(seq 1 3000); do [ -e "$1" ] && break; sleep 0.02; done
  kill "-$2" "$3" 2>/dev/null
}
sed 's/^const Delta = .*/const Delta = 0.03/' "$(dirname "$0")/../../host/sds/models/limb.sds" >"$T/fast.sds"
ARGS=(sds run "$T/fast.sds" --t-end 10 --frames 5 --quiet)

run "${ARGS[@]}" --out "$T/a"
check "the uninterrupted run completes" rc_is 0

"$S" "${ARGS[@]}" --out "$T/b" >"$T/out" 2>"$T/err" &
pid=$!
signal_after "$T/b/sds/frame_0001.ply" INT $pid
{ wait $pid; } 2>/dev/null
echo $? >"$T/rc"
check "SIGINT after frame 1: exit 130, one line naming --resume, state interrupted, a checkpoint, no final.ply" eval \
  'rc_is 130 && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q -- "--resume" "$T/err" && test -s "$T/b/checkpoint.bin" && test ! -e "$T/b/sds/final.ply" && grep -q "\"state\":[[:space:]]*\"interrupted\"" "$T/b/manifest.json"'

# The kill has the last frame (a few tenths of a second here) to land in: a
# resume that ended first is tried again from a copy of the interrupted run.
cp -a "$T/b" "$T/b.interrupted"
for attempt in 1 2 3 4 5; do
  "$S" sds run --resume "$T/b" --quiet >"$T/out" 2>"$T/err" &
  pid=$!
  signal_after "$T/b/sds/frame_0004.ply" KILL $pid
  { wait $pid; } 2>/dev/null
  echo $? >"$T/rc"
  rc_is 0 || break
  echo "  the resume ended before the kill (attempt $attempt): again"
  rm -rf "$T/b" && cp -a "$T/b.interrupted" "$T/b"
done
check "the first resume, killed (SIGKILL) after frame 4, before its end" eval 'rc_is 137 && test ! -e "$T/b/sds/final.ply"'
# rows appended after the last checkpoint (a run killed between its log's
# append and its checkpoint) are cut by the resume, not kept twice
echo "99999,1,1,1,1,1,0,0" >>"$T/b/sds/steps.csv"
echo "99999,1,2,0,0,0,1" >>"$T/b/sds/divisions.csv"
run sds run --resume "$T/b" --quiet
check "the second resume completes" eval 'rc_is 0 && [ ! -s "$T/err" ]'
# 23 files: frames 0-5 as PLY, .vtp and VTU, the final PLY and .vtp, model.sds, series.pvd,
# the division log (its planted row cut like the step log's)
check "every file under sds/ is the same bytes as the uninterrupted run's" eval \
  'sums "$T/a" >"$T/a.sum"; sums "$T/b" >"$T/b.sum"; [ "$(wc -l <"$T/a.sum")" -eq 23 ] && cmp -s "$T/a.sum" "$T/b.sum"'
check "the step log: each step once, in order (1..steps), the same rows as the uninterrupted run's but for ms" \
  "$PY" - "$T/a" "$T/b" <<'PYEOF'
import csv, json, sys
def rows(d):
    with open(d + "/sds/steps.csv", newline="") as f:
        r = list(csv.DictReader(f))
    return [{k: v for k, v in x.items() if k != "ms"} for x in r], [float(x["ms"]) for x in r]
a, b = sys.argv[1], sys.argv[2]
(ra, ma), (rb, mb) = rows(a), rows(b)
n = json.load(open(b + "/manifest.json"))["sds"]["steps"]
ok = ra == rb and [int(x["step"]) for x in rb] == list(range(1, n + 1)) and all(m > 0 for m in ma + mb)
ok = ok and sum(int(x["divisions"]) for x in rb) == json.load(open(b + "/manifest.json"))["sds"]["divisions"]
print(len(rb), "rows; steps", n)
sys.exit(0 if ok else 1)
PYEOF
check "records equal but ms_per_step; manifest: completed, 3 starts, sds totals equal but wall_s; divisions and inversions happened" \
  "$PY" - "$T/a" "$T/b" <<'PYEOF'
import json, sys
def recs(d): return [{k: v for k, v in json.loads(l).items() if k != "ms_per_step"} for l in open(d + "/records.jsonl")]
def man(d): return json.load(open(d + "/manifest.json"))
a, b = sys.argv[1], sys.argv[2]
ma, mb = man(a), man(b)
sa = {k: v for k, v in ma["sds"].items() if k != "wall_s"}
sb = {k: v for k, v in mb["sds"].items() if k != "wall_s"}
ok = recs(a) == recs(b) and [r["frame"] for r in recs(b)] == list(range(6))
ok = ok and mb["state"] == "completed" and mb["starts"] == 3 and sa == sb and sa["status"] == "completed"
ok = ok and sa["divisions"] > 0 and sa["inversions"] > 0 and mb["config"]["model_text"] == open(a + "/sds/model.sds").read()
print("divisions", sa["divisions"], "inversions", sa["inversions"], "resumed from frame", mb["resumed_from_iteration"])
sys.exit(0 if ok else 1)
PYEOF

mkdir "$T/empty"
run sds run --resume "$T/empty"
check "--resume on an empty folder: exit 2, one line, nothing written" eval 'rc_is 2 && one_line && [ -z "$(ls -A "$T/empty")" ]'
run sds run --resume "$T/nowhere"
check "--resume on a missing folder: exit 2, one line, not created" eval 'rc_is 2 && one_line && [ ! -e "$T/nowhere" ]'
run sphere --iterations 2 --out "$T/sph" --quiet
run sds run --resume "$T/sph"
check "--resume on a run of another generator: exit 2, one line" eval 'rc_is 2 && one_line && grep -q "another generator" "$T/err"'
cp -r "$T/b" "$T/c"
run sds run limb --resume "$T/c"
check "--resume with another model named: exit 2, one line" eval 'rc_is 2 && one_line && grep -q "another model" "$T/err"'
run sds run --resume "$T/c" --seed 2
check "--resume with --seed: exit 2, one line" eval 'rc_is 2 && one_line'
run sds run --resume "$T/c" --t-end 20
check "--resume with --t-end: exit 2, one line" eval 'rc_is 2 && one_line'
run sds run "$T/fast.sds" --t-end 0.5 --frames 1 --seed 2 --out "$T/d" --quiet
cp "$T/d/checkpoint.bin" "$T/c/checkpoint.bin"
run sds run --resume "$T/c"
check "a checkpoint of another configuration (seed 2, t_end 0.5): exit 2, one line" eval \
  'rc_is 2 && one_line && grep -q "another model or configuration" "$T/err"'

# a run with --set, stopped by SIGINT after frame 1 and resumed: the bytes of
# the uninterrupted run with the same --set (the stored parameters, not the
# model's own dt and viscosity)
RA=(sds run "$T/fast.sds" --t-end 6 --frames 3 --quiet --no-preview --set dt=0.0005 --set viscosity=1.5)
run "${RA[@]}" --out "$T/r1"
check "the uninterrupted run with --set completes" rc_is 0
"$S" "${RA[@]}" --out "$T/r2" >"$T/out" 2>"$T/err" &
pid=$!
signal_after "$T/r2/sds/frame_0001.ply" INT $pid
{ wait $pid; } 2>/dev/null
echo $? >"$T/rc"
check "with --set, SIGINT after frame 1: exit 130" eval 'rc_is 130 && test ! -e "$T/r2/sds/final.ply"'
run sds run --resume "$T/r2" --set dt=0.001
check "--resume with --set: exit 2, one line, the run untouched" eval \
  'rc_is 2 && one_line && test ! -e "$T/r2/sds/final.ply"'
run sds run --resume "$T/r2" --quiet --no-preview
check "the resume completes with the stored parameters: every file under sds/ the same bytes" eval \
  'rc_is 0 && sums "$T/r1" >"$T/r1.sum" && sums "$T/r2" >"$T/r2.sum" && cmp -s "$T/r1.sum" "$T/r2.sum"'
# the same run with another viscosity, stopped after its first checkpoint:
# its checkpoint does not fit the run above (the key holds the parameters
# that differ from the model's)
"$S" sds run "$T/fast.sds" --t-end 6 --frames 3 --quiet --no-preview --set dt=0.0005 --set viscosity=2 \
  --out "$T/r3" >"$T/out" 2>"$T/err" &
pid=$!
signal_after "$T/r3/checkpoint.bin" INT $pid
{ wait $pid; } 2>/dev/null
cp -r "$T/r1" "$T/r4"
cp "$T/r3/checkpoint.bin" "$T/r4/checkpoint.bin"
run sds run --resume "$T/r4"
check "a checkpoint of other parameters (viscosity 2 for 1.5): exit 2, one line" eval \
  'rc_is 2 && one_line && grep -q "another model or configuration" "$T/err"'
finish
