#!/usr/bin/env bash
# Convergence of the sponge model (docs/science.md; label slow): 20 radiate
# iterations, the volume added (final minus the initial dome's):
#  - box resolution 2 against 3 (nodes 207 k / 1.6 M): differ by < 10 %;
#  - the default box (38.4 x 38.4 x 28.8 cm) against a 1.5x wider and taller
#    one (57.6 x 57.6 x 43.2 cm) with the far field at the same 28.8 cm: < 5 %.
# tools/science/ reruns these and more; this test guards them.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
run() { # name, args...
  local n="$1"; shift
  "$S" grow --preset radiate --iterations 20 --every 0 --set fluid_at_snapshots=false "$@" \
    --out "$T/$n" --quiet >"$T/$n.out" 2>"$T/$n.err"
  local rc=$?
  check "$n: 20 iterations run (exit $rc)" [ "$rc" -eq 0 ]
  [ "$rc" -eq 0 ] || cat "$T/$n.err"
}
run r2
run r3 --set box_resolution=3
run big --set box_cells_x=48 --set box_cells_y=48 --set box_cells_z=36 --set far_field_height=28.8
added() { # run name -> added volume
  "$PY" -c '
import json, sys
m = json.load(open(sys.argv[1] + "/manifest.json"))
its = [json.loads(l) for l in open(sys.argv[1] + "/records.jsonl")]
print(its[-1]["surface"]["volume_cm3"] - m["initial_sponge"]["volume_cm3"])' "$T/$1"
}
V2=$(added r2) V3=$(added r3) VB=$(added big)
echo "volume added in 20 iterations: r2 $V2, r3 $V3, big box $VB cm^3"
check "r2 -> r3: volume added differs by < 10 %" "$PY" -c "import sys; sys.exit(0 if abs($V3 - $V2) < 0.10 * $V2 else 1)"
check "38.4 -> 57.6 cm box (far field at 28.8 cm): volume added differs by < 5 %" \
  "$PY" -c "import sys; sys.exit(0 if abs($VB - $V2) < 0.05 * $V2 else 1)"
finish
