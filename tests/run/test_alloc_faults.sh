#!/usr/bin/env bash
# Every allocation failure of sessile's own code is a one-line error
# (docs/design.md, "Errors and diagnostics").  $1 is sessile_faultinj, the
# CLI with its allocator calls wrapped (tests/common/faultinj.c).  For small
# commands of every generator, render and sds run: a count run says how many
# allocations the command makes; then the N-th is failed for every N (or an
# even sample of MAX_TRIES when there are more), and each run must exit 1
# (not a signal; 0 only where the allocation is optional, see faults()) with
# exactly one stderr line that names memory (no sanitizer report besides),
# and its run directory must take a --force rerun.
set -u
S="$1" ONLY="${2:-}" # ONLY: the names of the commands to try (all when empty)
. "$(dirname "$0")/../common/harness.sh"
# The suite's sample (alloc_faults_wide tries more); the sanitizer build,
# where each run costs several times more, tries 4 (ASan still checks every
# failure path it reaches, and the release build covers the other four).
DEFAULT_TRIES=8
[ "${SESSILE_TEST_SANITIZED:-0}" = 1 ] && DEFAULT_TRIES=4
MAX_TRIES=${SESSILE_FAULT_TRIES:-$DEFAULT_TRIES}
# One thread: allocations made inside OpenMP loops come in one order, so the
# N-th is the same allocation on every run.  Validation off: these runs test
# the host's failure paths, which the other tests run with the layer on.
export OMP_NUM_THREADS=1 SESSILE_VALIDATION=0
unset SESSILE_FAULT_ALLOC

# The even sample of 1..count: all of them, or MAX_TRIES spread over the range.
tries() {
  local count="$1"
  if [ "$count" -le "$MAX_TRIES" ]; then seq 1 "$count"; return; fi
  awk -v c="$count" -v m="$MAX_TRIES" 'BEGIN { for (i = 0; i < m; i++) print 1 + int(i * (c - 1) / (m - 1)) }' | uniq
}

# Whether run $1 wrote what the reference run $2 wrote, byte for byte (but
# the files that hold wall times or pids: manifest, records, checkpoint, lock
# owner, sds's steps.csv).
same_outputs() {
  if [ -d "$2" ]; then
    diff -rq -x manifest.json -x records.jsonl -x checkpoint.bin -x .sessile.lock -x steps.csv "$1" "$2" >/dev/null
  else cmp -s "$1.png" "$2.png"; fi
}

# faults NAME RERUN_EVERY ARGS...: the count run (also the reference), then
# each tried N.  ARGS may hold @D@, the run directory (or @D@.png, the
# picture), fresh for every N.  A failed run must exit 1 with one stderr line
# naming memory.  Exit 0 is right only for an optional allocation: silent
# with every output the reference's (the pipeline cache; the sanitizer
# build's library pinning), or one warning naming memory that says what is
# missing (the preview; a diffusion-limited grow's flow channels).  Every
# RERUN_EVERY-th try that failed is rerun with --force and no fault, which
# must complete.
faults() {
  local name="$1" every="$2"; shift 2
  [ -n "$ONLY" ] && [[ " $ONLY " != *" $name "* ]] && return
  local d="$T/$name" ref="$T/$name.ref" bad=0 tried=0 optional=0 n count rc
  local args=("${@//@D@/$d}") refargs=("${@//@D@/$ref}")
  SESSILE_FAULT_ALLOC=0 "$S" "${refargs[@]}" >"$T/out" 2>"$T/err"
  count=$(sed -n 's/^faultinj: \([0-9]*\) allocations$/\1/p' "$T/err")
  if [ "$(wc -l <"$T/err")" != 1 ] || [ -z "$count" ] || [ "$count" -lt 1 ]; then
    echo "FAIL $name: the count run failed or printed more:"; cat "$T/err"
    fails=$((fails + 1)); return
  fi
  for n in $(tries "$count"); do
    rm -rf "$d" "$d.png"
    SESSILE_FAULT_ALLOC=$n "$S" "${args[@]}" >"$T/out" 2>"$T/err"
    rc=$?
    tried=$((tried + 1))
    if [ "$rc" = 0 ] && { { [ ! -s "$T/err" ] && same_outputs "$d" "$ref"; } ||
                          { [ "$(wc -l <"$T/err")" = 1 ] && grep -q "warning:.*memory" "$T/err"; }; }; then
      optional=$((optional + 1))
      continue
    fi
    if [ "$rc" != 1 ] || [ "$(wc -l <"$T/err")" != 1 ] || ! grep -qi "error.*memory" "$T/err"; then
      [ "$bad" -lt 8 ] && { echo "  $name N=$n: exit $rc, stderr:"; head -5 "$T/err" | sed 's/^/    /'
        [ "$rc" = 0 ] && diff -rq "$d" "$ref" | head -3; }
      bad=$((bad + 1))
      continue
    fi
    if [ "$every" -gt 0 ] && [ $((tried % every)) = 0 ] && [ -d "$d" ]; then
      if ! "$S" "${args[@]}" --force >"$T/out" 2>"$T/err"; then
        [ "$bad" -lt 8 ] && { echo "  $name N=$n: the --force rerun failed:"; head -3 "$T/err" | sed 's/^/    /'; }
        bad=$((bad + 1))
      fi
    fi
  done
  echo "  $name: $count allocations, $tried failed in turn ($optional optional), $bad wrong"
  check "$name: each failed allocation is exit 1 and one line naming memory" [ "$bad" = 0 ]
}

# A PLY to render, and a tiny grammar (two derivation steps).
"$S" sphere --seed 3 --iterations 1 --out "$T/ply" --quiet --no-preview >/dev/null 2>&1
check "the sphere to render is written" test -s "$T/ply/sphere/final.ply"
printf 'iterations: 2\nangle: 30\naxiom: F(1, 0.1) A\nA -> F(0.5, 0.05) [ +(30) A ] -(30) A\n' >"$T/tiny.lsys"
# The smallest sponge and grow boxes of their CLI tests.
SMALL="--set mesh_detail=3 --set nutrients_per_iteration=120 --set cube_size=3"
COARSE="--set box_resolution=1 --set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3"

faults sphere 2 sphere --seed 1 --iterations 2 --out @D@ --quiet
faults venation 4 coral venation --iterations 2 --out @D@ --quiet --no-preview
faults lsystem 4 coral lsystem --grammar "$T/tiny.lsys" --out @D@ --quiet --no-preview
faults sponge 4 sponge particles $SMALL --iterations 2 --out @D@ --quiet --no-preview
faults sds 4 sds run limb --t-end 1 --frames 1 --out @D@ --quiet --no-preview
faults render 0 render "$T/ply/sphere/final.ply" -o @D@.png --size 64x48 --samples 1 --quiet
faults grow 4 grow $COARSE --iterations 1 --out @D@ --quiet --no-preview
finish
