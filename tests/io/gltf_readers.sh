# The independent .glb readers' helpers, shared by tests/io/test_gltf_readers.sh
# and tests/reef/test_reef_cli.sh.  Needs $T (a temporary folder).
GLTF_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
validate() { # file: 0 errors and warnings, its counts in $T/counts
  node "$GLTF_DIR/gltf_validate.mjs" "$1" >"$T/v.out" 2>&1
  local rc=$?
  cat "$T/v.out"
  grep '^counts' "$T/v.out" >"$T/counts"
  return $rc
}
count() { # assimp's "Label:   N"
  assimp info "$1" -r 2>/dev/null | sed -n "s/^$2: *\([0-9]*\).*/\1/p" | head -1
}
ply_count() { sed -n "s/^element $2 \([0-9]*\).*/\1/p" "$1" | head -1; }
