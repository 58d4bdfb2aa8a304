#!/usr/bin/env bash
# OBJ for DCC tools: every generator that writes an OBJ, run with
# --obj-axes yup-m, against the PLY it wrote beside it (sessile's z-up cm),
# read with VTK's PLY and OBJ readers and by hand (tests/io/obj_axes_check.py):
#   the extent is the PLY's with (x, y, z) -> (x, z, -y) and / 100, vertex by
#   vertex too; normals rotated the same way; the triangles' orientation kept;
#   the .mtl named by mtllib holds the material usemtl names, coloured as the
#   command's glTF material.
# Without the option the OBJ holds the PLY's numbers (z up, cm) with the same
# .mtl; a wrong --obj-axes is a usage error.  A missing reader is a failure.
set -u
S="$1"
HERE="$(cd "$(dirname "$0")" && pwd)"
PY=/usr/bin/python3
. "$HERE/../common/harness.sh" # check, run, rc_is, finish, the temporary folder $T

if ! "$PY" -c "import vtkmodules.vtkIOPLY, vtkmodules.vtkIOGeometry, numpy" 2>/dev/null; then
  echo "FAIL missing reader: python modules vtkmodules and numpy (apt-get install python3-vtk9 python3-numpy; tools/install.sh)"
  exit 1
fi

SMALL="--set mesh_detail=3 --set nutrients_per_iteration=120 --set cube_size=3 --iterations 5"
COARSE="--set box_resolution=1 --set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3 --iterations 1"
gen() { # name, obj (relative), Kd, command...
  local name="$1" obj="$2" kd="$3"; shift 3
  local d="$T/$name"
  check "$name: runs with --obj-axes yup-m" "$S" "$@" --out "$d" --obj-axes yup-m --quiet --no-preview
  check "$name: ${obj%.obj}.mtl listed in the manifest" grep -q "\"${obj%.obj}.mtl\"" "$d/manifest.json"
  check "$name: y up, metres: the PLY's extent with axes swapped and / 100; normals, orientation, .mtl" \
    "$PY" "$HERE/obj_axes_check.py" yup-m "$d/$obj" "$d/${obj%.obj}.ply" "$kd"
}
gen venation coral/final.obj "0.9 0.45 0.4" coral venation --iterations 30
gen lsystem coral/final.obj "0.92 0.78 0.62" coral lsystem
gen particles sponge/final.obj "0.85 0.55 0.2" sponge particles $SMALL
gen grow sponge/final.obj "0.8 0.3 0.12" grow $COARSE

"$S" coral venation --iterations 30 --out "$T/plain" --quiet --no-preview
check "without --obj-axes: the OBJ holds the PLY's numbers (z up, cm), with the .mtl" \
  "$PY" "$HERE/obj_axes_check.py" zup-cm "$T/plain/coral/final.obj" "$T/plain/coral/final.ply" "0.9 0.45 0.4"
check "zup-cm spelled out: the same bytes as the default" eval \
  '"$S" coral venation --iterations 30 --out "$T/zup" --quiet --no-preview --obj-axes zup-cm &&
   cmp "$T/plain/coral/final.obj" "$T/zup/coral/final.obj" && cmp "$T/plain/coral/final.mtl" "$T/zup/coral/final.mtl"'

run coral venation --iterations 3 --out "$T/bad" --obj-axes y-up
check "--obj-axes y-up: a usage error naming both conventions, nothing written" \
  eval 'rc_is 2 && grep -q "zup-cm" "$T/err" && grep -q "yup-m" "$T/err" && test ! -e "$T/bad"'
run coral lsystem --out "$T/bad2" --obj-axes yup-m --obj-axes zup-cm
check "--obj-axes twice: a usage error" eval 'rc_is 2 && grep -q "given twice" "$T/err" && test ! -e "$T/bad2"'
finish
