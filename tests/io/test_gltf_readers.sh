#!/usr/bin/env bash
# The .glb files read by readers that share no code with sessile:
#   the Khronos glTF validator (npm gltf-validator, tests/io/gltf_validate.mjs): 0 errors, 0 warnings
#   assimp (assimp-utils, `assimp info -r`): meshes, nodes, vertices, faces
#   Python's json + struct + numpy (tests/io/gltf_check.py) against meshio's PLY:
#     positions = PLY / 100 as (x, z, -y), attributes = the PLY's properties
# on the writer's sample scenes (test_gltf --samples: 3 nodes on 1 mesh) and on
# every generator's --glb.  A missing reader is a failure, not a skip: install
# the readers with tools/install.sh.
set -u
GEN="$1" S="$2"
HERE="$(cd "$(dirname "$0")" && pwd)"
PY=/usr/bin/python3
. "$HERE/../common/harness.sh" # check, finish, the temporary folder $T

missing=()
[ -x "$PY" ] || missing+=("/usr/bin/python3 (apt-get install python3)")
for m in "meshio python3-meshio" "numpy python3-numpy"; do
  set -- $m
  "$PY" -c "import $1" 2>/dev/null || missing+=("python module $1 (apt-get install $2)")
done
command -v assimp >/dev/null || missing+=("assimp (apt-get install assimp-utils)")
command -v node >/dev/null || missing+=("node (apt-get install nodejs npm)")
if command -v node >/dev/null; then
  node "$HERE/gltf_validate.mjs" >"$T/v.out" 2>&1
  [ $? -eq 2 ] && missing+=("gltf-validator (npm, under tools/node: tools/install.sh)")
fi
if [ ${#missing[@]} -gt 0 ]; then
  for m in "${missing[@]}"; do echo "FAIL missing reader: $m"; done
  echo "install the readers with tools/install.sh"
  exit 1
fi

. "$HERE/gltf_readers.sh"

# --- the writer's sample scenes -------------------------------------------------
mkdir -p "$T/s"
check "test_gltf --samples writes the scenes" "$GEN" --samples "$T/s"
for f in instanced cube; do check "validator: $f.glb has no errors or warnings" validate "$T/s/$f.glb"; done
check "validator: instanced.glb has 8 vertices, 12 triangles, 2 materials" \
  grep -q "vertices=8 triangles=12 materials=2" "$T/counts"
check "assimp: instanced.glb: 1 mesh of 8 vertices and 12 faces" \
  test "$(count "$T/s/instanced.glb" Meshes) $(count "$T/s/instanced.glb" Vertices) $(count "$T/s/instanced.glb" Faces)" = "1 8 12"
check "assimp: instanced.glb: 3 nodes show mesh 0 (instancing)" \
  test "$(assimp info "$T/s/instanced.glb" -r 2>/dev/null | grep -c '(mesh 0)')" = 3
check "python: the sample scenes' contents" "$PY" "$HERE/gltf_check.py" sample "$T/s"

# --- every generator's --glb -------------------------------------------------------
SMALL="--set mesh_detail=3 --set nutrients_per_iteration=120 --set cube_size=3 --iterations 5"
COARSE="--set box_resolution=1 --set box_cells_x=16 --set box_cells_y=16 --set box_cells_z=12 --set sponge_radius=3 --iterations 1"
gen() { # name, mesh (relative), command...
  local name="$1" mesh="$2"; shift 2
  local d="$T/$name" glb
  check "$name: runs with --glb" "$S" "$@" --out "$d" --glb --quiet --no-preview
  glb="$d/${mesh%.ply}.glb"
  check "$name: ${mesh%.ply}.glb beside the PLY, listed in the manifest" \
    eval "test -s '$glb' && grep -q '\"${mesh%.ply}.glb\"' '$d/manifest.json'"
  [ -s "$glb" ] || return
  local nv nf
  nv=$(ply_count "$d/$mesh" vertex) nf=$(ply_count "$d/$mesh" face)
  check "$name: validator: no errors or warnings" validate "$glb"
  check "$name: validator: $nv vertices, $nf triangles (the PLY's), 1 material" \
    grep -q "vertices=$nv triangles=$nf materials=1 " "$T/counts"
  check "$name: assimp: 1 mesh, 1 node, $nv vertices, $nf faces" \
    test "$(count "$glb" Meshes) $(count "$glb" Nodes) $(count "$glb" Vertices) $(count "$glb" Faces)" = "1 1 $nv $nf"
  check "$name: python: vertices, extent (PLY / 100, y up), normals, attributes" "$PY" "$HERE/gltf_check.py" ply "$glb" "$d/$mesh"
}
gen sphere sphere/final.ply sphere
gen venation coral/final.ply coral venation --iterations 30
gen lsystem coral/final.ply coral lsystem
gen particles sponge/final.ply sponge particles $SMALL
gen grow sponge/final.ply grow $COARSE
gen sds sds/final.ply sds run limb --t-end 5 --frames 1

# --- same input, same bytes; off by default; with --resume ---------------------------
"$S" sphere --out "$T/sphere2" --glb --quiet --no-preview
check "sphere twice: the same .glb bytes" cmp "$T/sphere/sphere/final.glb" "$T/sphere2/sphere/final.glb"
"$S" sphere --out "$T/plain" --quiet --no-preview --iterations 5
check "without --glb: no .glb" test -z "$(find "$T/plain" -name '*.glb')"
"$S" sphere --resume "$T/plain" --iterations 10 --glb --quiet --no-preview
check "--glb with --resume: the resumed run's .glb, as a fresh run's" cmp "$T/plain/sphere/final.glb" "$T/sphere/sphere/final.glb"

finish
