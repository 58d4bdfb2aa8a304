#!/bin/sh
# Layers include only their own private headers and the public headers of
# layers below them (docs/design.md, "Build and layout").
# - A file in host/X may include "sessile/..." (host/include), its own
#   folder's headers ("x.h" or "X/x.h") and system headers; host/bench may
#   also read la's and mesh's private headers ("la/...", "mesh/...").  The
#   build's include paths stop "Y/y_internal.h" from another layer; this
#   script also stops relative escapes ("../Y/...") that no include path can.
# - Public headers are grouped by layer (host/include/sessile/Y/, the base's
#   at host/include/sessile/): a file of layer X (in host/X or in
#   host/include/sessile/X) may include "sessile/Y/..." only when Y sits
#   below X in the order below, or Y = X.  Layers of one rank (the
#   generators) never include each other.
# Prints each offending line; exit 1 when there is one.
# usage: tools/check_layers.sh [SOURCE_ROOT]
cd "${1:-$(dirname "$0")/..}" || exit 2
grep -rn --include='*.c' --include='*.h' --include='*.cpp' --include='*.def' \
  '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' host |
  awk -F: '
    BEGIN {
      # the dependency order, bottom to top
      rank["base"] = 0; rank["gpu"] = 1; rank["la"] = 2; rank["mesh"] = 3
      rank["fem"] = 4; rank["io"] = 4; rank["run"] = 5; rank["render"] = 5
      rank["growth"] = 6
      rank["sphere"] = 7; rank["coral"] = 7; rank["sponge"] = 7; rank["sds"] = 7; rank["reef"] = 7
      rank["bench"] = 8; rank["cli"] = 9
    }
    function bad_line(msg) { print file ":" line ": \"" inc "\" " msg; bad = 1 }
    {
      file = $1; line = $2; n = split(file, part, "/")
      layer = n == 2 ? "base" : part[2]
      public = layer == "include"
      if (public) layer = n == 4 ? "base" : part[4]
      inc = $0; sub(/^[^"]*"/, "", inc); sub(/".*$/, "", inc)
      top = index(inc, "/") ? substr(inc, 1, index(inc, "/") - 1) : ""
      if (!(layer in rank)) { bad_line("is in " file ", which is no known layer"); next }
      if (inc ~ /(^|\/)\.\.\//) { bad_line("escapes its folder"); next }
      if (top == "sessile") {
        rest = substr(inc, 9)
        to = index(rest, "/") ? substr(rest, 1, index(rest, "/") - 1) : "base"
        if (!(to in rank)) bad_line("names no layer")
        else if (to != layer && rank[to] >= rank[layer])
          bad_line("is " to "'"'"'s public header, not below " layer)
        next
      }
      ok = 0
      if (top == "") ok = !public
      else if (top == layer && !public) ok = 1
      else if (layer == "bench" && (top == "la" || top == "mesh")) ok = 1
      if (!ok) bad_line("is not " layer "'"'"'s to include")
    }
    END { exit bad }'
