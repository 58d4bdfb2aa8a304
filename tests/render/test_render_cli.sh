#!/usr/bin/env bash
# `sessile render` from the command line: --help; a unit cube seen from the
# top (orthographic, 1 sample, black background) covers (w / (2 * 0.5 *
# 1.1))^2 pixels within 1 % (the projected bounds fill 1/1.1 of the
# picture, docs/render.md "Camera"), decoded here with Python's zlib, not
# with sessile's code; the same command twice gives the same PNG bytes; a
# turntable writes N frames of the asked size; a `sessile sphere` mesh
# renders; bad input exits 2 with one line and writes nothing; `bench
# render --quick` runs.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3

# PNG -> "W H NONBLACK" (8-bit RGBA, any of the five row filters: tests/common/png_decode.py)
cat >"$T/png.py" <<PYEOF
import sys
sys.path.insert(0, "$(cd "$(dirname "$0")/../common" && pwd)")
from png_decode import decode
w, h, rows = decode(sys.argv[1])
print(w, h, sum(1 for line in rows for x in range(w) if line[4 * x] or line[4 * x + 1] or line[4 * x + 2]))
PYEOF

cat >"$T/cube.obj" <<'OBJ'
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
OBJ

run render --help
check "--help answers with the usage" eval 'rc_is 0 && grep -q "^usage: sessile render" "$T/out"'

run render "$T/cube.obj" -o "$T/top.png" --view top --ortho --no-grid --samples 1 --background black --size 200x200 --quiet
check "a cube from the top renders (exit 0, a PNG)" eval 'rc_is 0 && test -s "$T/top.png"'
check "... covers (200 / 1.1)^2 pixels within 1 %" eval \
  '"$PY" "$T/png.py" "$T/top.png" | awk "{e = (200 / 1.1)^2; d = \$3 - e; if (d < 0) d = -d; print \"covered\", \$3, \"expected\", e; exit !(\$1 == 200 && \$2 == 200 && d <= 0.01 * e)}"'
run render "$T/cube.obj" -o "$T/top2.png" --view top --ortho --no-grid --samples 1 --background black --size 200x200 --quiet
check "the same command twice: identical PNG bytes" cmp -s "$T/top.png" "$T/top2.png"

run render "$T/cube.obj" -o "$T/turn.png" --turntable 3 --size 96x64 --quiet
check "--turntable 3 writes turn_000..002.png of 96x64" eval \
  'rc_is 0 && for k in 000 001 002; do "$PY" "$T/png.py" "$T/turn_$k.png" | grep -q "^96 64 " || exit 1; done; test ! -e "$T/turn.png"'
check "... frames differ (the camera turns)" eval '! cmp -s "$T/turn_000.png" "$T/turn_001.png"'

run sphere --out "$T/sph" --iterations 2 --quiet
run render "$T/sph/sphere/final.ply" -o "$T/sphere.png" --size 320x240
check "a sessile sphere mesh renders (oblique, grid, 4 samples)" eval \
  'rc_is 0 && grep -q "grid" "$T/out" && "$PY" "$T/png.py" "$T/sphere.png" | grep -q "^320 240 "'

# bad input: exit 2, one line on stderr, nothing written
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float c\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1\n1 nan 0 2\n0 1 0 3\n3 0 1 2\n' >"$T/nan.ply"
sed 's/1 nan 0 2/1 0 0 2/' "$T/nan.ply" >"$T/tri.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n' >"$T/empty.ply"
: >"$T/slice.exr"
bad() { # description, args...
  local what="$1"; shift
  rm -f "$T/bad.png"
  run render "$@"
  check "bad input exits 2 with one line, writes nothing: $what" eval \
    'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "^sessile render: error: " "$T/err" && test ! -e "$T/bad.png" && [ ! -s "$T/out" ]'
}
bad "missing file" "$T/none.ply" -o "$T/bad.png"
bad "NaN coordinate" "$T/nan.ply" -o "$T/bad.png"
bad "empty mesh" "$T/empty.ply" -o "$T/bad.png"
bad "unknown property" "$T/tri.ply" -o "$T/bad.png" --color-by thickness
bad "size 0" "$T/tri.ply" -o "$T/bad.png" --size 0x10
bad "size 100000" "$T/tri.ply" -o "$T/bad.png" --size 100000x10
bad "unknown view" "$T/tri.ply" -o "$T/bad.png" --view below
bad "samples 3" "$T/tri.ply" -o "$T/bad.png" --samples 3
bad "unknown colour map" "$T/tri.ply" -o "$T/bad.png" --color-by c --colormap jet
bad "no -o" "$T/tri.ply"
bad "output not .png" "$T/tri.ply" -o "$T/bad.jpg"
bad "output folder missing" "$T/tri.ply" -o "$T/no/bad.png"
bad "an empty .exr file" "$T/slice.exr" -o "$T/bad.png"
bad "a run directory with -o X.png" "$T/sph" -o "$T/bad.png"
run render "$T/tri.ply" -o "$T/c.png" --color-by c --size 64x48
check "--color-by an existing property works (viridis over [1, 3])" eval 'rc_is 0 && grep -q "viridis by c over \[1, 3\]" "$T/out"'

run bench render --quick --runs 1
check "bench render --quick prints the split and the ratio" eval \
  'rc_is 0 && grep -q "^median: " "$T/out" && grep -q "ratio to the 2 s target" "$T/out" && grep -q "^load average" "$T/out"'
finish
