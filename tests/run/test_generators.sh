#!/usr/bin/env bash
# Every registered generator (the list `sessile --help` prints, here from a
# binary that also holds the test-only generator of tests/run/testgen)
# through the generic command's contract:
#   --help and --print-config answer; a bad --set exits 2 with one line and
#   creates nothing; the same seed gives the same bytes; a refused resume
#   (--iterations below the checkpoint, another run's checkpoint) leaves the
#   run's files as they were, and the right resume then gives the bytes of
#   the uninterrupted run; a resume without its checkpoint restarts and keeps
#   none of the stopped run's later snapshots; --force never touches a folder
#   whose manifest sessile did not write; an unknown --device creates
#   nothing; over its --max-memory a run stops with its state saved and
#   resumes to the same bytes.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
one_line() { [ "$(wc -l <"$T/err")" -eq 1 ]; }
# the run's outputs (not what describes the process: manifest, records, lock, checkpoint)
sums() { (cd "$1" && find . -type f ! -name manifest.json ! -name records.jsonl ! -name .sessile.lock \
            ! -name checkpoint.bin ! -name preview.png | LC_ALL=C sort | xargs -r sha256sum); }
state() { (cd "$1" && find . -type f | LC_ALL=C sort | xargs -r sha256sum); }

"$S" --help >"$T/help"
gens=$(awk '/^generators/ {on = 1; next} on && /^$/ {exit} on' "$T/help" | cut -c3-18 | sed 's/ *$//')
check "the registry lists the generators, the test-only one among them" eval \
  'echo "$gens" | grep -qx sphere && echo "$gens" | grep -qx "coral venation" && echo "$gens" | grep -qx testwalk'

while IFS= read -r g; do
  [ -n "$g" ] || continue
  read -r -a G <<<"$g"
  n=$(echo "$g" | tr ' ' '_')
  # a generator whose default size takes minutes per run is run small
  # (its size is the same parameters for every run and resume below)
  case "$g" in
    grow) SMALL="--set box_resolution=1 --set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3 --set fluid_at_snapshots=false" ;;
    *) SMALL="" ;;
  esac
  R="--iterations 4 --every 2 --quiet --no-preview $SMALL"
  run "${G[@]}" --help
  check "$g: --help answers" eval 'rc_is 0 && grep -q "usage: sessile $g" "$T/out" && grep -q -- "--print-config" "$T/out"'
  run "${G[@]}" --print-config
  check "$g: --print-config answers" eval 'rc_is 0 && [ -s "$T/out" ]'
  run "${G[@]}" --set nosuch=1 --out "$T/$n-x"
  check "$g: an unknown --set exits 2, one line, nothing created" eval 'rc_is 2 && one_line && [ ! -e "$T/$n-x" ]'

  run "${G[@]}" $R --device nosuchdevice --out "$T/$n-dev"
  check "$g: an unknown --device exits 2, one line, nothing created" eval 'rc_is 2 && one_line && [ ! -e "$T/$n-dev" ]'
  run "${G[@]}" --seed 3 $R --out "$T/$n-a"
  check "$g: a 4-iteration run completes" rc_is 0
  run "${G[@]}" --seed 3 $R --out "$T/$n-a2"
  check "$g: the same seed gives the same bytes" eval 'cmp -s <(sums "$T/$n-a") <(sums "$T/$n-a2")'

  run "${G[@]}" --seed 3 --iterations 2 --every 2 --quiet --no-preview $SMALL --out "$T/$n-b"
  cp -r "$T/$n-b" "$T/$n-b2"
  state "$T/$n-b" >"$T/before"
  run "${G[@]}" --resume "$T/$n-b" --iterations 1 --quiet
  check "$g: --resume below the checkpoint exits 2, one line, the run untouched" eval \
    'rc_is 2 && one_line && grep -q "at least 2" "$T/err" && state "$T/$n-b" | cmp -s "$T/before" -'
  run "${G[@]}" --resume "$T/$n-b" --iterations 4 --quiet
  check "$g: ... then --resume to 4 gives the bytes of the uninterrupted run" eval \
    'rc_is 0 && cmp -s <(sums "$T/$n-a") <(sums "$T/$n-b")'

  run "${G[@]}" --seed 4 --iterations 2 --every 2 --quiet --no-preview $SMALL --out "$T/$n-c"
  cp "$T/$n-c/checkpoint.bin" "$T/$n-b2/checkpoint.bin"
  state "$T/$n-b2" >"$T/before"
  run "${G[@]}" --resume "$T/$n-b2" --iterations 4 --quiet
  check "$g: another run's checkpoint (seed 4) is refused, the run untouched" eval \
    'rc_is 2 && one_line && grep -q "another model or configuration" "$T/err" && state "$T/$n-b2" | cmp -s "$T/before" -'

  run "${G[@]}" --seed 3 --iterations 4 --every 1 --quiet --no-preview $SMALL --out "$T/$n-d"
  mv "$T/$n-d/checkpoint.bin" "$T/$n-moved.bin"
  run "${G[@]}" --resume "$T/$n-d" --iterations 2 --quiet
  run "${G[@]}" --seed 3 --iterations 2 --every 1 --quiet --no-preview $SMALL --out "$T/$n-e"
  check "$g: a resume without its checkpoint restarts; no later snapshot of the old run stays" eval \
    'rc_is 0 && cmp -s <(sums "$T/$n-e") <(sums "$T/$n-d")'

  run "${G[@]}" --seed 3 $R --max-memory 0.000001 --out "$T/$n-m"
  check "$g: over --max-memory the run stops after iteration 1 with its state saved (exit 1, one line)" eval \
    'rc_is 1 && one_line && grep -q "memory budget" "$T/err" && grep -q "\"iteration\":[[:space:]]*1" "$T/$n-m/manifest.json"'
  run "${G[@]}" --resume "$T/$n-m" --quiet
  check "$g: ... and its resume gives the bytes of the uninterrupted run" eval \
    'rc_is 0 && cmp -s <(sums "$T/$n-a") <(sums "$T/$n-m")'

  mkdir -p "$T/$n-f"
  echo '{"files": ["index.html", "notes.txt"]}' >"$T/$n-f/manifest.json"
  echo page >"$T/$n-f/index.html"; echo mine >"$T/$n-f/notes.txt"
  state "$T/$n-f" >"$T/before"
  run "${G[@]}" $R --out "$T/$n-f" --force
  check "$g: --force refuses a folder whose manifest sessile did not write; nothing deleted" eval \
    'rc_is 2 && one_line && state "$T/$n-f" | cmp -s "$T/before" -'
done <<<"$gens"
finish
