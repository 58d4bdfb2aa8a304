#!/usr/bin/env bash
# `sessile grow` as a user meets it: --help and --print-config answer; bad
# input (malformed JSON, unknown key, wrong type, negative or NaN value, an
# unwritable output folder) gives one clear line, exit 2 and no files; a short
# run writes every promised file atomically (no temporaries left); the same
# seed gives a byte-identical final.ply and two seeds give different crella
# meshes.  Runs use a coarse box (box_resolution=1) to keep the suite short.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
one_line_error() { [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "error" "$T/err"; }
# A small box (19.2 x 19.2 x 14.4 cm at 1.2 cm, a 3 cm sponge) keeps each run to seconds.
COARSE="--set box_resolution=1 --set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3 --quiet"

run grow --help
check "'sessile grow --help' answers" eval 'rc_is 0 && grep -q "usage: sessile grow" "$T/out" && grep -q -- "--print-config" "$T/out"'
run grow --print-config
check "--print-config lists parameters with units and sources" eval \
  'rc_is 0 && grep -q "^vertex_insertion_threshold *0.6 *cm *\[0, 1e+06\] *Table 1" "$T/out" && grep -q "^t_give .* ours" "$T/out"'
run grow --preset crella --print-config
check "--preset crella selects Halichondrid" eval 'rc_is 0 && grep -q "^skeletal_growth *halichondrid" "$T/out"'
run grow --set t_give=0.2 --print-config
check "--set overrides a parameter" eval 'rc_is 0 && grep -q "^t_give *0.2 " "$T/out"'
printf '{"t_give": 0.25, "skeletal_growth": "halichondrid", "diffusion_limited": true}\n' >"$T/good.json"
run grow --config "$T/good.json" --print-config
check "--config applies a JSON file" eval 'rc_is 0 && grep -q "^t_give *0.25 " "$T/out" && grep -q "^skeletal_growth *halichondrid" "$T/out"'

bad() { # description, expected message regex, args...
  local what="$1" msg="$2"; shift 2
  rm -rf "$T/o"
  run grow --out "$T/o" $COARSE --iterations 1 "$@"
  check "$what: exit 2, one line naming it, nothing written" eval \
    'rc_is 2 && one_line_error && grep -q -- "$msg" "$T/err" && [ ! -e "$T/o" ]'
}
printf '{"t_give": 0.1,,}\n' >"$T/malformed.json"
printf '{"no_such_key": 1}\n' >"$T/unknown.json"
printf '{"t_give": "lots"}\n' >"$T/type.json"
printf '[1, 2]\n' >"$T/array.json"
printf '{"l_max": -3}\n' >"$T/negative.json"
bad "malformed JSON" "not valid JSON" --config "$T/malformed.json"
bad "unknown key in JSON" "unknown parameter 'no_such_key'" --config "$T/unknown.json"
bad "wrong type in JSON" "t_give must be a number" --config "$T/type.json"
bad "JSON that is not an object" "one JSON object" --config "$T/array.json"
bad "negative value in JSON" "l_max" --config "$T/negative.json"
bad "missing config file" "cannot read config file" --config "$T/none.json"
bad "negative --set value" "t_give" --set t_give=-1
bad "NaN --set value" "l_max" --set l_max=nan
bad "unknown --set key" "unknown parameter 'wat'" --set wat=1
bad "non-integer resolution" "box_resolution" --set box_resolution=1.5
bad "bad enum" "radiate, halichondrid" --set skeletal_growth=axinellid
bad "unknown preset" "unknown preset" --preset coral
bad "bad slice plane" "slices" --slices "w=3"
bad "sponge outside the box" "does not fit" --set sponge_radius=40
echo "not a folder" >"$T/file"
run grow --out "$T/file/run" $COARSE --iterations 1
check "an unwritable output folder: exit 2, one line" eval 'rc_is 2 && one_line_error && grep -q "run directory" "$T/err"'

# A short run writes every promised file, atomically.
run grow --out "$T/r1" $COARSE --preset crella --seed 7 --iterations 2 --every 1
check "a 2-iteration crella run succeeds" rc_is 0
for f in manifest.json records.jsonl checkpoint.bin sponge/iter_0001.ply sponge/iter_0002.ply sponge/final.ply sponge/final.obj sponge/final.mtl \
         slices/iter_0002_x.exr slices/iter_0002_y.exr slices/iter_0002_z.exr \
         fields/iter_0001.vtu fields/iter_0002.vtu fields/series.pvd; do
  check "run directory holds $f" test -s "$T/r1/$f"
done
check "the manifest names the preset crella (top level and config)" eval \
  '[ "$(grep -c "\"preset\":[[:space:]]*\"crella\"" "$T/r1/manifest.json")" = 2 ]'
check "no temporary files are left behind" eval '[ -z "$(find "$T/r1" -name "*.tmp*" -o -name "*sessile-tmp*")" ]'
check "the manifest says completed, with seed, device, command and times; records hold the solves" eval \
  'grep -q "\"state\":.*\"completed\"" "$T/r1/manifest.json" && grep -q "\"seed\":.*\"7\"" "$T/r1/manifest.json" && grep -q "\"driver\"" "$T/r1/manifest.json" && grep -q "\"end_time\":.*Z\"" "$T/r1/manifest.json" && grep -q "true_relres" "$T/r1/records.jsonl" && [ "$(wc -l <"$T/r1/records.jsonl")" = 2 ]'
# The run's own files through independent readers (VTK, meshio, exrheader).
check "VTK reads the run's VTU: one point per box node, c in [0,1], c = 0 on solid nodes" \
  /usr/bin/python3 - "$T/r1/fields/iter_0002.vtu" "$T/r1/manifest.json" <<'PYEOF'
import json, sys
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy
r = vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update()
g = r.GetOutput(); m = json.load(open(sys.argv[2]))
c = vtk_to_numpy(g.GetPointData().GetArray("c")); solid = vtk_to_numpy(g.GetPointData().GetArray("solid"))
ok = g.GetNumberOfPoints() == m["box"]["nodes"] and g.GetNumberOfCells() == m["box"]["tetrahedra"]
ok = ok and c.min() >= -1e-9 and c.max() <= 1 + 1e-9 and solid.sum() > 0 and abs(c[solid == 1]).max() == 0
print("points", g.GetNumberOfPoints(), "cells", g.GetNumberOfCells(), "solid", int(solid.sum()), "c range", c.min(), c.max())
sys.exit(0 if ok else 1)
PYEOF
check "meshio reads final.ply and final.obj with the manifest's vertex count" \
  /usr/bin/python3 - "$T/r1/sponge/final.ply" "$T/r1/sponge/final.obj" "$T/r1/manifest.json" <<'PYEOF'
import json, sys, meshio
m = json.load(open(sys.argv[3])); nv = m["totals"]["surface"]["vertices"]
a = meshio.read(sys.argv[1]); b = meshio.read(sys.argv[2])
print("ply", len(a.points), "obj", len(b.points), "manifest", nv)
sys.exit(0 if len(a.points) == nv == len(b.points) and abs(a.points - b.points).max() < 1e-5 else 1)
PYEOF
check "exrheader reads a slice with its sessile attributes" eval \
  'exrheader "$T/r1/slices/iter_0002_z.exr" | grep -q "sessile:iteration (type int): 2"'
run grow --out "$T/r2" $COARSE --preset crella --seed 7 --iterations 2 --every 0 --set fluid_at_snapshots=false
check "same seed, same device: byte-identical final.ply" cmp -s "$T/r1/sponge/final.ply" "$T/r2/sponge/final.ply"
check "--every 0 still snapshots the last iteration" test -s "$T/r2/slices/iter_0002_z.exr"
run grow --out "$T/r2" $COARSE --preset crella --seed 7 --iterations 2 --every 0 --set fluid_at_snapshots=false
check "the same command again is refused: the folder holds a run (exit 2)" eval 'rc_is 2 && one_line_error'
run grow --out "$T/r2" $COARSE --preset crella --seed 7 --iterations 2 --every 0 --set fluid_at_snapshots=false --force
check "... and with --force it runs again to the same bytes" eval 'rc_is 0 && cmp -s "$T/r1/sponge/final.ply" "$T/r2/sponge/final.ply"'
run grow --out "$T/r6" $COARSE --iterations 6 --every 10 --set fluid_at_snapshots=false
check "a 6-iteration run with --every 10 writes iter_0006 slices and fields" eval \
  'rc_is 0 && test -s "$T/r6/slices/iter_0006_x.exr" && test -s "$T/r6/fields/iter_0006.vtu" && test -s "$T/r6/sponge/iter_0006.ply"'
run grow --out "$T/deg" $COARSE --iterations 2 --every 0 --set fluid_at_snapshots=false --set sponge_radius=0.01
check "a sponge fused to a few vertices warns" eval 'rc_is 0 && grep -q "warning: .*degenerated" "$T/err"'
run grow --out "$T/r3" $COARSE --preset crella --seed 8 --iterations 2 --every 0 --set fluid_at_snapshots=false
check "two seeds give different crella meshes" eval '! cmp -s "$T/r1/sponge/final.ply" "$T/r3/sponge/final.ply"'

finish
