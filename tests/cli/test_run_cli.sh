#!/usr/bin/env bash
# The run framework through `sessile grow`, as faults and other users meet it:
# - SIGKILL at 5 random moments, each followed by --resume, ends with every
#   output byte equal to an uninterrupted run (the flow solved at snapshots
#   included); the moments come from a printed seed (SESSILE_TEST_SEED);
# - SIGINT leaves state "interrupted", exit 130, a checkpoint and no
#   temporary; SIGTERM exits 143; both resume to the same bytes;
# - two concurrent runs into one folder: the second exits 2 naming the
#   first's pid, the first completes untouched;
# - symlinks planted at every temporary name the old writer used and at the
#   final names change no file outside the run; one planted as a subfolder
#   is refused;
# - a completed run is refused without --force, replaced with it.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
# A small box (19.2 x 19.2 x 14.4 cm at 1.2 cm) keeps each run to seconds.
# At most 3 Newton steps per flow solve (the flow's accuracy is test_ns's
# business; here it only has to be solved, warm-started and checkpointed).
SMALL="--set box_resolution=1 --set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3 --set fluid_newton_max_it=3 --quiet"
ITS=6
outputs() { (cd "$1" && find sponge slices fields -type f | LC_ALL=C sort | xargs sha256sum); }
temps() { find "$1" -name '*.sessile-tmp.*' | wc -l; }
state() { /usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["state"])' "$1/manifest.json"; }

# The reference: one uninterrupted run, timed to place the kills.
t0=$(date +%s.%N)
"$S" grow $SMALL --iterations $ITS --every 3 --out "$T/ref" >/dev/null 2>"$T/err"
check "the reference run completes" eval '[ "$(state "$T/ref")" = completed ]'
t1=$(date +%s.%N)
outputs "$T/ref" >"$T/ref.sum"
check "the reference has the final-iteration snapshot and the finals" eval \
  'grep -q "sponge/iter_0006.ply" "$T/ref.sum" && grep -q "sponge/final.ply" "$T/ref.sum"'

# SIGKILL at 5 random moments of the run (each restart continues the chain).
seed=${SESSILE_TEST_SEED:-$(( $(date +%s) % 100000 ))}
echo "kill moments from seed $seed (rerun with SESSILE_TEST_SEED=$seed)"
RANDOM=$seed
dur=$(/usr/bin/python3 -c "print(max(1.0, $t1 - $t0))")
"$S" grow $SMALL --iterations $ITS --every 3 --out "$T/k" >/dev/null 2>>"$T/kerr" &
pid=$!
for k in 1 2 3 4 5; do
  at=$(/usr/bin/python3 -c "print(0.1 + ($RANDOM / 32767.0) * $dur)")
  sleep "$at"
  kill -KILL $pid 2>/dev/null
  wait $pid 2>/dev/null
  echo "  kill $k after ${at}s: $(wc -l <"$T/k/records.jsonl" 2>/dev/null || echo 0) records"
  # killed before its manifest existed, the run has nothing to resume: the
  # user starts it again (into the leftovers of its start, if any)
  if [ -f "$T/k/manifest.json" ]; then again=(--resume "$T/k" --quiet)
  else echo "  (no manifest yet: started again)"; again=($SMALL --iterations $ITS --every 3 --out "$T/k"); fi
  "$S" grow "${again[@]}" >/dev/null 2>>"$T/kerr" &
  pid=$!
done
wait $pid
check "the run resumed after 5 SIGKILLs completes" eval '[ "$(state "$T/k")" = completed ]'
outputs "$T/k" >"$T/k.sum"
check "every output byte equals the uninterrupted run's" cmp -s "$T/ref.sum" "$T/k.sum"
check "records: one line per iteration, none repeated" eval \
  '[ "$(/usr/bin/python3 -c "import json,sys; print([json.loads(l)[\"iteration\"] for l in open(sys.argv[1])])" "$T/k/records.jsonl")" = "[1, 2, 3, 4, 5, 6]" ]'
check "no temporary left" eval '[ "$(temps "$T/k")" = 0 ]'

# SIGINT and SIGTERM: stop after the current iteration, saved, resumable.
for sig in INT TERM; do
  rm -rf "$T/s"
  "$S" grow $SMALL --iterations $ITS --every 3 --out "$T/s" >/dev/null 2>"$T/serr" &
  pid=$!
  for _ in $(seq 1 600); do [ -s "$T/s/records.jsonl" ] && break; sleep 0.1; done
  kill -$sig $pid
  wait $pid
  rc=$?
  want=$([ $sig = INT ] && echo 130 || echo 143)
  check "SIG$sig: exit $want" [ "$rc" = "$want" ]
  check "SIG$sig: state interrupted, a checkpoint, no temporary" eval \
    '[ "$(state "$T/s")" = interrupted ] && [ -s "$T/s/checkpoint.bin" ] && [ "$(temps "$T/s")" = 0 ]'
  check "SIG$sig: the message says how to resume" grep -q -- "--resume" "$T/serr"
  "$S" grow --resume "$T/s" --quiet >/dev/null 2>&1
  outputs "$T/s" >"$T/s.sum"
  check "SIG$sig: the resumed run's outputs equal the uninterrupted run's" cmp -s "$T/ref.sum" "$T/s.sum"
done

# The rest needs no flow (it dominates the time of these runs): a longer
# run without it, and its own reference.
NOFLOW="$SMALL --set fluid_at_snapshots=false --iterations 20 --every 10"
"$S" grow $NOFLOW --out "$T/ref2" >/dev/null 2>&1
outputs "$T/ref2" >"$T/ref2.sum"

# Two runs into one folder.  The first is held stopped (SIGSTOP; it keeps its
# lock) while the others try: running on, it could end before a loaded
# machine has started them, and --force would then replace it.
"$S" grow $NOFLOW --out "$T/c" >/dev/null 2>"$T/c1err" &
pid=$!
for _ in $(seq 1 1200); do [ -s "$T/c/manifest.json" ] && break; sleep 0.05; done
kill -STOP $pid
check "the first run is held while it runs (state running)" eval '[ "$(state "$T/c")" = running ]'
run grow $SMALL --iterations 2 --out "$T/c"
check "a second run into a folder in use exits 2 naming the first's pid" eval \
  'rc_is 2 && grep -q "in use by another sessile run (pid $pid on host" "$T/err" && [ "$(wc -l <"$T/err")" = 1 ]'
run grow $SMALL --iterations 2 --out "$T/c" --force
check "... --force does not break the lock either" rc_is 2
kill -CONT $pid
wait $pid
rc=$?
check "the first run completes" eval '[ $rc = 0 ] && [ "$(state "$T/c")" = completed ]'
outputs "$T/c" >"$T/c.sum"
check "the first run's outputs are untouched" cmp -s "$T/ref2.sum" "$T/c.sum"

# Earlier runs: refused without --force, replaced with it.
run grow $SMALL --iterations 2 --out "$T/c"
check "a folder holding a run is refused without --force (exit 2)" eval 'rc_is 2 && grep -q -- "--force" "$T/err"'
check "... and left as it was" eval 'outputs "$T/c" | cmp -s "$T/ref2.sum" -'

# Planted symlinks: at the old writer's temporary names for the next pids, at
# the final names, and one as a subfolder.
mkdir -p "$T/outside"
echo precious >"$T/outside/victim"
cp -r "$T/ref2" "$T/p"
last=$(sh -c 'echo $$')
for f in $(cd "$T/p" && find sponge slices fields -type f) manifest.json records.jsonl checkpoint.bin; do
  for p in $(seq $((last + 1)) $((last + 40))); do ln -sf "$T/outside/victim" "$T/p/$f.tmp.$p"; done
  ln -sf "$T/outside/victim" "$T/p/.$(basename "$f").sessile-tmp.0000000000000000"
done
for f in sponge/final.ply sponge/iter_0010.ply slices/iter_0020_x.exr fields/series.pvd; do
  rm -f "$T/p/$f"; ln -s "$T/outside/victim" "$T/p/$f"
done
"$S" grow $NOFLOW --out "$T/p" --force >/dev/null 2>"$T/perr"
rc=$?
check "a run among planted symlinks completes" eval '[ $rc = 0 ]'
check "the file outside is unchanged" eval '[ "$(cat "$T/outside/victim")" = precious ]'
check "the final names hold the run's own files again" eval \
  '[ -f "$T/p/sponge/final.ply" ] && [ ! -L "$T/p/sponge/final.ply" ] && [ ! -L "$T/p/fields/series.pvd" ]'
outputs "$T/p" >"$T/p.sum"
check "... with the same bytes as the reference" cmp -s "$T/ref2.sum" "$T/p.sum"
rm -rf "$T/p/slices"
ln -s "$T/outside" "$T/p/slices"
run grow $SMALL --set fluid_at_snapshots=false --iterations 2 --out "$T/p" --force
check "a symlink planted as a subfolder is refused (exit 1, one line)" eval \
  'rc_is 1 && grep -q "refused" "$T/err" && [ "$(ls "$T/outside")" = victim ]'

run grow --out --print-config
check "--out --print-config: exit 2, no folder named --print-config" eval \
  'rc_is 2 && grep -q -- "--out needs a value" "$T/err" && [ ! -e ./--print-config ]'
finish
