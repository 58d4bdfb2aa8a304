#!/usr/bin/env bash
# `sessile render RUN_DIR`, `sessile render FILE.exr`, the text over mesh
# pictures, and every generator's preview.png (docs/render.md "Runs",
# "Preview").  A tiny grow run, a short sds run and a sphere run: preview.png
# after each (640x480, many colours), none with --no-preview (and the other
# outputs unchanged); renders/ holds the expected pictures (PNG signature,
# size, more than N distinct colours, decoded here with Python's zlib, not
# sessile's code), listed in the manifest so --force removes them; a rerun
# gives identical bytes; -o DIR writes elsewhere and leaves the run alone; a
# locked run is refused for renders/ but read for -o DIR; the annotation
# touches only its corner and the colour bar, which runs from viridis(1) to
# viridis(0); an sds run's sds/steps.csv gives plot_step_times.png (a note
# when it is missing or malformed); bad input exits 2 with one line and
# writes nothing.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3

# PNG -> "W H COLOURS" (8-bit RGBA); with a second PNG of the same size:
# "W H DIFFS X0 Y0 X1 Y1 HAS_TOP HAS_BOTTOM" (bounding box of the differing
# pixels, and whether viridis(1) and viridis(0) are among the first's pixels there)
export PNG_DECODE_DIR="$(cd "$(dirname "$0")/../common" && pwd)" # png_decode.py
cat >"$T/png.py" <<'PYEOF'
import os, sys
sys.path.insert(0, os.environ["PNG_DECODE_DIR"])
from png_decode import decode
if sys.argv[1] == "check":  # check W H N FILE...: each W x H with more than N colours
    W, H, N = map(int, sys.argv[2:5]); ok = True
    for path in sys.argv[5:]:
        try:
            w, h, rows = decode(path); n = len({r[i:i + 3] for r in rows for i in range(0, 4 * w, 4)})
        except Exception as e:
            w = h = n = str(e)
        if not (w == W and h == H and n > N):
            print("  %s: %s %s %s colours (want %d %d > %d)" % (path, w, h, n, W, H, N)); ok = False
    sys.exit(not ok)
w, h, rows = decode(sys.argv[1])
if len(sys.argv) == 2:
    print(w, h, len({r[i:i + 3] for r in rows for i in range(0, 4 * w, 4)}))
else:
    w2, h2, rows2 = decode(sys.argv[2]); assert (w, h) == (w2, h2)
    box = [w, h, -1, -1]; n = 0; seen = set()
    for y in range(h):
        if rows[y] == rows2[y]: continue
        for x in range(w):
            if rows[y][4 * x:4 * x + 4] != rows2[y][4 * x:4 * x + 4]:
                n += 1; box = [min(box[0], x), min(box[1], y), max(box[2], x), max(box[3], y)]
                seen.add(rows[y][4 * x:4 * x + 3])
    print(w, h, n, *box, int(bytes((253, 231, 37)) in seen), int(bytes((68, 1, 84)) in seen))
PYEOF
pic() { "$PY" "$T/png.py" "$@" 2>/dev/null; }
# pictures W H MINCOLOURS FILE...: each a PNG of W x H with more than MINCOLOURS colours
pictures() { "$PY" "$T/png.py" check "$@"; }
listed() { "$PY" -c 'import json,sys; m=json.load(open(sys.argv[1] + "/manifest.json")); sys.exit(not all(("renders/" + f) in m["files"] for f in sys.argv[2:]))' "$@"; }
sums() { (cd "$1" && find . -type f | LC_ALL=C sort | xargs sha256sum); }

# --- generators: preview.png -------------------------------------------------------
GROW="--set box_resolution=1 --set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3 --set fluid_newton_max_it=3 --set fluid_at_snapshots=false --no-fields --iterations 2 --every 1 --quiet"
run grow $GROW --out "$T/g"
check "grow (tiny) runs" rc_is 0
check "... preview.png: 640x480, > 200 colours, listed in the manifest" eval \
  'pictures 640 480 200 "$T/g/preview.png" && "$PY" -c "import json,sys; sys.exit(\"preview.png\" not in json.load(open(\"$T/g/manifest.json\"))[\"files\"])"'
run grow $GROW --out "$T/g0" --no-preview
check "grow --no-preview: no preview.png, the same meshes and slices" eval \
  'rc_is 0 && test ! -e "$T/g0/preview.png" && cmp -s "$T/g/sponge/final.ply" "$T/g0/sponge/final.ply" && cmp -s "$T/g/slices/iter_0002_y.exr" "$T/g0/slices/iter_0002_y.exr"'
run sds run limb --t-end 2 --frames 2 --out "$T/s" --quiet
check "sds run limb (t 2, 2 frames): preview.png 640x480, > 200 colours" eval 'rc_is 0 && pictures 640 480 200 "$T/s/preview.png"'
run sphere --out "$T/p" --iterations 2 --quiet
check "sphere: preview.png 640x480, > 200 colours" eval 'rc_is 0 && pictures 640 480 200 "$T/p/preview.png"'
run sphere --out "$T/p2" --iterations 2 --quiet
check "... the same preview bytes from a second run" cmp -s "$T/p/preview.png" "$T/p2/preview.png"

run sphere --out "$T/w" --iterations 1 --quiet
rm "$T/w/preview.png" && mkdir "$T/w/preview.png" # the picture cannot be renamed over a folder
run sphere --out "$T/w" --iterations 1 --quiet --force
check "a preview that fails: one warning line, exit 0, the run complete, preview.png not listed" eval \
  'rc_is 0 && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "^sessile sphere: warning: no preview.png" "$T/err" && grep -q "\"completed\"" "$T/w/manifest.json" && ! grep -q "\"preview.png\"" "$T/w/manifest.json"'

# --- sessile render RUN_DIR ------------------------------------------------------------
run render "$T/g" --size 320x240
GF="final_oblique.png final_side.png final_top.png final_front.png snap_iter_0001.png snap_iter_0002.png snapshots.png plot_solver.png plot_time.png"
for i in 0001 0002; do for a in x y z; do GF="$GF slice_iter_${i}_${a}_c.png"; done; done
check "render the grow run: exit 0, one line per picture (the tiles with the sheet)" eval 'rc_is 0 && [ "$(grep -c "^wrote " "$T/out")" = 13 ]'
check "... renders/ holds exactly the 17 expected pictures" eval \
  '[ "$(cd "$T/g/renders" && ls | LC_ALL=C sort | tr "\n" " ")" = "$(echo $GF | tr " " "\n" | LC_ALL=C sort | tr "\n" " ")" ]'
check "... the four views: 320x240, > 200 colours each" eval \
  '(cd "$T/g/renders" && pictures 320 240 200 final_oblique.png final_side.png final_top.png final_front.png)'
check "... snapshot tiles 320x240; the sheet 2 tiles wide (8 + 2 x 328 by 8 + 270)" eval \
  '(cd "$T/g/renders" && pictures 320 240 200 snap_iter_0001.png snap_iter_0002.png && pictures 664 278 200 snapshots.png)'
check "... six slices (c) of 800x600 with > 100 colours, plots of 800x600" eval \
  '(cd "$T/g/renders" && pictures 800 600 100 slice_iter_000*_c.png && pictures 800 600 10 plot_solver.png plot_time.png)'
check "... every picture listed in the run's manifest" eval 'listed "$T/g" $GF'
sums "$T/g/renders" >"$T/g1.sum"
cp "$T/g/manifest.json" "$T/g1.manifest"
run render "$T/g" --size 320x240 --quiet
check "... a rerun: identical bytes, and the manifest unchanged" eval \
  'rc_is 0 && sums "$T/g/renders" | cmp -s - "$T/g1.sum" && cmp -s "$T/g/manifest.json" "$T/g1.manifest"'

run render "$T/s" --size 320x240 --quiet
SF="final_oblique.png final_side.png final_top.png final_front.png snap_frame_0000.png snap_frame_0001.png snap_frame_0002.png snapshots.png plot_steps.png"
SN=9 # and plot_step_times.png where the generator wrote its per-step log
if [ -f "$T/s/sds/steps.csv" ]; then SF="$SF plot_step_times.png" SN=10; fi
check "render the sds run: views, 3 frame tiles, the sheet (3 wide), ms per step against cells (and against time with sds/steps.csv)" eval \
  '(cd "$T/s/renders" && rc_is 0 && [ "$(ls | wc -l)" = $SN ] && pictures 320 240 100 final_*.png snap_frame_*.png && pictures 992 278 100 snapshots.png && pictures 800 600 10 plot_steps.png && { [ $SN = 9 ] || pictures 800 600 10 plot_step_times.png; }) && listed "$T/s" $SF'

# the per-step log sds/steps.csv (written here, so this holds whatever the generator writes)
cp -r "$T/s" "$T/st" && rm -rf "$T/st/renders"
{ echo "step,time,dt,cells,tets,ms,divisions,inversions"
  for k in $(seq 1 300); do echo "$k,$k.5,0.5,$((180 + k)),$((700 + 4 * k)),$((1 + k % 4)).25,0,0"; done; } >"$T/st/sds/steps.csv"
run render "$T/st" --size 160x120
check "an sds run with sds/steps.csv: plot_step_times.png 800x600, one line for it, listed in the manifest" eval \
  'rc_is 0 && grep -q "^wrote .*/plot_step_times.png: " "$T/out" && pictures 800 600 10 "$T/st/renders/plot_step_times.png" && listed "$T/st" plot_step_times.png'
echo "301,300.5,0.5,481,1904,fast,0,0" >>"$T/st/sds/steps.csv"
rm -rf "$T/st/renders"
run render "$T/st" --size 160x120
check "... a malformed row: no plot_step_times.png, a note naming its line, the rest drawn, exit 0" eval \
  'rc_is 0 && grep -q "^no plot_step_times.png: .*steps.csv.* line 302" "$T/out" && test ! -e "$T/st/renders/plot_step_times.png" && test -s "$T/st/renders/plot_steps.png"'
rm -rf "$T/st/renders" "$T/st/sds/steps.csv"
run render "$T/st" --size 160x120
check "... no sds/steps.csv: a note, no plot_step_times.png, exit 0" eval \
  'rc_is 0 && grep -q "^no plot_step_times.png: the run has no sds/steps.csv" "$T/out" && test ! -e "$T/st/renders/plot_step_times.png" && test -s "$T/st/renders/plot_steps.png"'

run render "$T/p" --size 320x240 --quiet
check "render the sphere run: 4 views, 1 tile, the sheet" eval \
  'rc_is 0 && [ "$(ls "$T/p/renders" | wc -l)" = 6 ] && (cd "$T/p/renders" && pictures 320 240 100 final_*.png snap_iter_0002.png)'
run sphere --out "$T/p" --iterations 2 --force --quiet
check "sphere --force over the rendered run removes renders/* (listed files)" eval \
  'rc_is 0 && [ -z "$(ls -A "$T/p/renders" 2>/dev/null)" ] && test -s "$T/p/preview.png"'

# the other generators' layouts (docs/render.md "Runs"): preview, views, snapshots
V="final_front.png final_oblique.png final_side.png final_top.png"
layout() { # description, run dir, expected pictures besides the views, generator args...
  local what="$1" dir="$2" want="$3"; shift 3
  run "$@" --out "$dir" --quiet
  local gen_rc; gen_rc=$(cat "$T/rc")
  run render "$dir" --size 160x120 --quiet
  check "$what: preview.png, then renders/ holds the views and $want" eval \
    '[ "$gen_rc" = 0 ] && rc_is 0 && pictures 640 480 100 "$dir/preview.png" && [ "$(ls "$dir/renders" | tr "\n" " ")" = "$(echo $V $want | tr " " "\n" | LC_ALL=C sort | tr "\n" " ")" ]'
}
layout "sponge particles (10 iterations)" "$T/pv" "snap_iter_0010.png snapshots.png" sponge particles --iterations 10
layout "coral venation" "$T/vn" "snap_iter_0020.png snap_iter_0040.png snap_iter_0060.png snapshots.png" coral venation
layout "coral lsystem (4 iterations; no snapshots)" "$T/ls" "" coral lsystem --iterations 4

mkdir "$T/elsewhere"
cp "$T/s/manifest.json" "$T/s.manifest"
run render "$T/s" -o "$T/elsewhere/sds" --size 320x240 --quiet
check "-o DIR: the pictures go there (created), the run's manifest is untouched" eval \
  'rc_is 0 && [ "$(ls "$T/elsewhere/sds" | wc -l)" = $SN ] && cmp -s "$T/s/manifest.json" "$T/s.manifest" && cmp -s "$T/elsewhere/sds/final_top.png" "$T/s/renders/final_top.png"'

echo precious >"$T/precious"
rm "$T/s/renders/final_top.png"
ln -s "$T/precious" "$T/s/renders/final_top.png"
run render "$T/s" --size 320x240 --quiet
check "a symlink planted at a picture's name is replaced by the picture, its target untouched" eval \
  'rc_is 0 && [ "$(cat "$T/precious")" = precious ] && test ! -L "$T/s/renders/final_top.png" && cmp -s "$T/s/renders/final_top.png" "$T/elsewhere/sds/final_top.png"'

# a run holding its folder's lock (flock on the folder, as the run framework takes it)
rm -rf "$T/p2/renders"
# The holder says when it has the lock (a fixed pause may end before a loaded
# machine has run flock) and keeps it until killed below.
(exec 9<"$T/p2" && flock -x 9 && : >"$T/p2.locked" && exec sleep 300) >/dev/null 2>&1 &
holder=$! # the subshell becomes the sleep holding the lock: killing it frees the lock
for _ in $(seq 1 1200); do [ -e "$T/p2.locked" ] && break; sleep 0.05; done
check "the holder has the run's lock" test -e "$T/p2.locked"
run render "$T/p2" --quiet
check "a locked run: renders/ refused (exit 2, one line naming the run), nothing written" eval \
  'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "in use by a running sessile run" "$T/err" && test ! -e "$T/p2/renders"'
run render "$T/p2" -o "$T/elsewhere/p2" --size 320x240
check "... but read for -o DIR (noted on stdout)" eval 'rc_is 0 && grep -q "still writing" "$T/out" && [ "$(ls "$T/elsewhere/p2" | wc -l)" = 6 ]'
kill "$holder" 2>/dev/null
wait "$holder" 2>/dev/null

# --- sessile render FILE.exr -------------------------------------------------------------
run render "$T/g/slices/iter_0002_y.exr" -o "$T/y.png"
check "an EXR slice: the first channel (c) by default, 800x600" eval \
  'rc_is 0 && grep -q "channel c (the file.s first)" "$T/out" && pictures 800 600 100 "$T/y.png"'
check "... equals the run's picture but for the outline (no mesh given)" eval '! cmp -s "$T/y.png" "$T/g/renders/slice_iter_0002_y_c.png"'
run render "$T/g/slices/iter_0002_y.exr" -o "$T/y2.png" --outline "$T/g/sponge/iter_0002.ply" --channel c
check "... with --outline the snapshot's mesh: the run's picture, byte for byte" cmp -s "$T/y2.png" "$T/g/renders/slice_iter_0002_y_c.png"
run render "$T/g/slices/iter_0002_y.exr" -o "$T/y3.png" --range 0 2 --colormap magma --size 400x300
check "... --range, --colormap, --size: 400x300" eval 'rc_is 0 && pictures 400 300 50 "$T/y3.png"'

# --- text over mesh pictures --------------------------------------------------------------
M="$T/s/sds/final.ply"
run render "$M" -o "$T/a.png" --size 400x300
run render "$M" -o "$T/na.png" --size 400x300 --no-annotate
check "the grid label: pixels differ only in the lower left corner (x < 200, y > 240)" eval \
  'pic "$T/a.png" "$T/na.png" | awk "{print; exit !(\$3 > 50 && \$4 >= 0 && \$6 < 200 && \$5 > 240)}"'
run render "$M" -o "$T/c.png" --size 400x300 --color-by radius --colormap viridis
run render "$M" -o "$T/nc.png" --size 400x300 --color-by radius --colormap viridis --no-annotate
check "--color-by: the label and a colour bar on the right holding viridis(1) and viridis(0)" eval \
  'pic "$T/c.png" "$T/nc.png" | awk "{print; exit !(\$3 > 200 && \$8 == 1 && \$9 == 1 && \$6 > 300)}"'
run render "$M" -o "$T/c2.png" --size 400x300 --color-by radius --colormap viridis
check "... identical bytes on a rerun" cmp -s "$T/c.png" "$T/c2.png"

# --- bad input: exit 2, one line, nothing written -----------------------------------------
mkdir -p "$T/bad/empty" "$T/bad/alien" "$T/bad/none/sponge" "$T/victim"
echo '{"generator": "teapot", "files": []}' >"$T/bad/alien/manifest.json"
echo '{"generator": "grow", "files": []}' >"$T/bad/none/manifest.json"
cp -r "$T/p2" "$T/bad/link"
cp -r "$T/p2" "$T/bad/meshlink"
ln -s "$T/p2/sphere/final.ply" "$T/bad/meshlink/sphere/iter_0009.ply"
ln -s "$T/victim" "$T/bad/link/renders"
cp -r "$T/st" "$T/bad/stepslink" && rm -rf "$T/bad/stepslink/renders"
ln -s "$T/precious" "$T/bad/stepslink/sds/steps.csv"
bad() { # description, expected words, args...
  local what="$1" words="$2"; shift 2
  local before after
  before=$(sums "$T/bad"; sums "$T/victim")
  rm -f "$T/bad.png"
  run render "$@"
  after=$(sums "$T/bad"; sums "$T/victim")
  check "bad input exits 2 with one line, writes nothing: $what" eval \
    'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "^sessile render: error: .*$words" "$T/err" && test ! -e "$T/bad.png" && [ "$before" = "$after" ] && [ ! -s "$T/out" ]'
}
bad "a folder without manifest" "not a sessile run directory" "$T/bad/empty"
bad "an unknown generator" "does not know" "$T/bad/alien"
bad "an empty run" "nothing to draw" "$T/bad/none"
bad "a symlink planted as renders/" "symlink" "$T/bad/link"
bad "a symlink planted as a snapshot mesh" "symlink" "$T/bad/meshlink"
bad "a symlink planted as sds/steps.csv" "steps.csv' is not a regular file (a symlink)" "$T/bad/stepslink"
bad "-o X.png for a run" "folder" "$T/bad/link" -o "$T/bad.png"
bad "a mesh option for a run" "not an option for a run" "$T/bad/none" --view top
bad "an unknown channel" "no channel 'q'" "$T/g/slices/iter_0002_y.exr" -o "$T/bad.png" --channel q
bad "a slice of 10x10 pixels" "outside" "$T/g/slices/iter_0002_y.exr" -o "$T/bad.png" --size 10x10
bad "a missing outline mesh" "cannot read --outline .*none.ply.: No such file" "$T/g/slices/iter_0002_y.exr" -o "$T/bad.png" --outline "$T/none.ply"
bad "--range with LO >= HI" "range" "$T/g/slices/iter_0002_y.exr" -o "$T/bad.png" --range 2 1
bad "a mesh option for a slice" "for meshes" "$T/g/slices/iter_0002_y.exr" -o "$T/bad.png" --view top
bad "a slice option for a mesh" "for EXR slices" "$M" -o "$T/bad.png" --channel c
echo "not an image" >"$T/text.exr"
bad "an EXR that is not one" "not an EXR" "$T/text.exr" -o "$T/bad.png"
finish
