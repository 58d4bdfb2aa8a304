#!/bin/sh
# tools/check_layers.sh refuses what it must: on a copy of host/, each planted
# include below is a violation (exit 1, the file named); the copy untouched
# passes.  Without this, a checker that accepts everything would keep
# layers_includes green.
set -u
SRC=$1
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
plant() { # plant FILE LINE WHAT
  rm -rf "$T/root" && mkdir -p "$T/root" && cp -r "$SRC/host" "$T/root/host"
  printf '%s\n' "$2" >>"$T/root/$1"
  if sh "$SRC/tools/check_layers.sh" "$T/root" >"$T/out" 2>&1; then
    echo "FAIL: $3 passed the check"; fails=$((fails + 1))
  elif ! grep -q "^$1:" "$T/out"; then
    echo "FAIL: $3: the message does not name $1"; cat "$T/out"; fails=$((fails + 1))
  else
    echo "ok: $3 refused"
  fi
}
rm -rf "$T/root" && mkdir -p "$T/root" && cp -r "$SRC/host" "$T/root/host"
if sh "$SRC/tools/check_layers.sh" "$T/root" >"$T/out" 2>&1; then echo "ok: the tree as it is passes"
else echo "FAIL: the untouched copy is refused"; cat "$T/out"; fails=$((fails + 1)); fi
plant host/la/axpy_probe.c '#include "sessile/growth/grow.h"' "la including a generator's public header"
plant host/coral/probe.c '#include "sessile/sds/sds.h"' "one generator including another's public header"
plant host/include/sessile/gpu/gpu.h '#include "sessile/run/run.h"' "a gpu public header including run's"
plant host/load.c '#include "sessile/gpu/gpu.h"' "the base including a layer"
plant host/render/probe.c '#include "../mesh/mesh_internal.h"' "a relative escape"
plant host/sds/probe.c '#include "mesh/mesh_internal.h"' "another layer's private header"
plant host/include/sessile/mesh/surface.h '#include "mesh_internal.h"' "a public header including a private one"
[ "$fails" -eq 0 ] || exit 1
