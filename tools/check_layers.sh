#!/bin/sh
# Layers include only their own private headers (docs/design.md, "Build and
# layout"): a file in host/X may include "sessile/..." (host/include), its own
# folder's headers ("x.h" or "X/x.h") and system headers; host/bench may also
# read la's and mesh's private headers ("la/...", "mesh/...").  The build's
# include paths stop "Y/y_internal.h" from another layer; this script also
# stops relative escapes ("../Y/...") that no include path can.  Prints each
# offending line; exit 1 when there is one.
# usage: tools/check_layers.sh [SOURCE_ROOT]
root=${1:-$(dirname "$0")/..}
cd "$root" || exit 2
bad=0
for f in $(find host -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.def' | sort); do
  case $f in
  host/include/*) layer=include ;;
  host/*/*) layer=${f#host/}; layer=${layer%%/*} ;;
  *) layer=base ;;
  esac
  grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f" | while IFS= read -r line; do
    inc=$(printf '%s\n' "$line" | sed 's/^[^"]*"\([^"]*\)".*/\1/')
    ok=0
    case $inc in
    ../*|*/../*) ok=0 ;;
    sessile/*) ok=1 ;;
    */*)
      top=${inc%%/*}
      [ "$top" = "$layer" ] && ok=1
      [ "$layer" = bench ] && { [ "$top" = la ] || [ "$top" = mesh ]; } && ok=1 ;;
    *) [ "$layer" != include ] && ok=1 ;; # a header of the file's own folder
    esac
    if [ $ok = 0 ]; then
      echo "$f:$line: '$inc' is not $layer's to include"
      echo bad
    fi
  done
done | { out=$(cat); printf '%s\n' "$out" | grep -v '^bad$' | grep . ; ! printf '%s\n' "$out" | grep -q '^bad$'; }
