#!/bin/sh
# Layers include only their own private headers (docs/design.md, "Build and
# layout"): a file in host/X may include "sessile/..." (host/include), its own
# folder's headers ("x.h" or "X/x.h") and system headers; host/bench may also
# read la's and mesh's private headers ("la/...", "mesh/...").  The build's
# include paths stop "Y/y_internal.h" from another layer; this script also
# stops relative escapes ("../Y/...") that no include path can.  Prints each
# offending line; exit 1 when there is one.
# usage: tools/check_layers.sh [SOURCE_ROOT]
cd "${1:-$(dirname "$0")/..}" || exit 2
grep -rn --include='*.c' --include='*.h' --include='*.cpp' --include='*.def' \
  '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' host |
  awk -F: '
    {
      file = $1; n = split(file, part, "/")
      layer = n == 2 ? "base" : part[2]
      inc = $0; sub(/^[^"]*"/, "", inc); sub(/".*$/, "", inc)
      top = index(inc, "/") ? substr(inc, 1, index(inc, "/") - 1) : ""
      ok = 0
      if (inc ~ /(^|\/)\.\.\//) ok = 0
      else if (top == "sessile") ok = 1
      else if (top == "") ok = layer != "include"
      else if (top == layer) ok = 1
      else if (layer == "bench" && (top == "la" || top == "mesh")) ok = 1
      if (!ok) { print file ":" $2 ": \"" inc "\" is not " layer "'"'"'s to include"; bad = 1 }
    }
    END { exit bad }'
