#!/usr/bin/env bash
# Every generator's surfaces as ParaView, MeshLab and Blender meet them, read
# by code that shares nothing with sessile (tests/io/mesh_data_check.py:
# numpy for the PLY, VTK's XML readers for the .vtp and the PVD's files):
# the .vtp beside each PLY with the PLY's counts, points, triangles and every
# scalar as a point array; header lines (generator, version with commit,
# seed, units); the PLY's red green blue = the colour map of its main scalar
# recomputed from the published table; the grow and sds series' times.
# usage: test_mesh_data.sh SESSILE COLORMAP_C
set -u
S="$1"
MAPS="$2"
PY=/usr/bin/python3
. "$(dirname "$0")/../common/harness.sh"
CHECK="$(dirname "$0")/mesh_data_check.py"
"$PY" -c "import vtkmodules.vtkIOXML, numpy" 2>/dev/null || { echo "FAIL python3-vtk9 and python3-numpy are needed (tools/install.sh)"; exit 1; }

gen() { # description, run folder, checker's PVDs (quoted), sessile arguments...
  local what="$1" dir="$T/$2" pvds="$3"; shift 3
  run "$@" --out "$dir" --quiet --no-preview
  if ! check "$what: the run completes" rc_is 0; then cat "$T/err"; return; fi
  "$PY" "$CHECK" "$MAPS" "$dir" $pvds >"$T/py" 2>&1
  check "$what: its surfaces read by numpy and VTK agree (tests/io/mesh_data_check.py)" test $? = 0
  grep -v '^PASS' "$T/py"
}

gen "sphere" sp "" sphere --set level=2 --iterations 4 --every 2
GROW="--set box_resolution=1 --set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3
      --set fluid_newton_max_it=3 --set fluid_at_snapshots=false"
gen "grow" g "sponge/series.pvd fields/series.pvd" grow $GROW --iterations 2 --every 1 --slices y
check "grow: sponge/series.pvd lists iterations 1 and 2" \
  grep -q 'timestep="2" group="" part="0" file="iter_0002.vtp"' "$T/g/sponge/series.pvd"
check "grow: the snapshot's PLY says which surface its fields were solved on" \
  grep -q "^comment state surface after iteration 2 .*solved on the surface before it grew" "$T/g/sponge/iter_0002.ply"
check "grow: final.obj carries the header lines" grep -q "^# seed 1$" "$T/g/sponge/final.obj"
gen "sponge particles" pp "" sponge particles --iterations 4 --every 2
gen "coral lsystem" ls "" coral lsystem --iterations 3
gen "coral venation" vn "" coral venation --iterations 20 --every 10
gen "sds run limb" sds "sds/series.pvd" sds run limb --t-end 2 --frames 2
check "sds: model units and time in the header" \
  eval 'grep -aq "^comment units length u time s$" "$T/sds/sds/frame_0001.ply" &&
        t=$(sed -n "s/^comment time //p" "$T/sds/sds/frame_0001.ply" | head -1) && [ -n "$t" ] &&
        grep -q "timestep=\"$t\" .*file=\"frame_0001.vtu\"" "$T/sds/sds/series.pvd"'
gen "reef" reef "" reef "$(dirname "$0")/../reef/scene_small.json" --seed 5
finish
