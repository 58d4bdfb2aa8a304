#!/usr/bin/env bash
# The paper's literal pipeline as grow options (docs/growth.md, "Parameters";
# the study's `literal` part): translocate_mode=sequential, probe=paper,
# far_field=walls.  Each, set alone, changes the run (its final surface
# differs from the default's), and the manifest records the value it ran
# with; translocate_mode=parallel, set explicitly, is today's default to the
# byte.  Two iterations on the base grid.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
grow() { # name, --set arguments...
  local name="$1"; shift
  "$S" grow --preset radiate --iterations 2 --every 0 --no-fields --slices '' --set fluid_at_snapshots=false \
    --set box_resolution=1 "$@" --out "$T/$name" --quiet >"$T/$name.out" 2>"$T/$name.err"
  local rc=$?
  check "$name: runs (exit $rc)" [ "$rc" -eq 0 ]
  [ "$rc" -eq 0 ] || cat "$T/$name.err"
}
recorded() { # run, parameter, value as the manifest's JSON holds it
  "$PY" -c 'import json, sys; m = json.load(open(sys.argv[1])); v = m["config"]["parameters"].get(sys.argv[2])
sys.exit(0 if str(v).lower() == sys.argv[3] else 1)' "$T/$1/manifest.json" "$2" "$3"
}
grow default
check "default: the manifest records translocate_mode=parallel" recorded default translocate_mode parallel
grow parallel --set translocate_mode=parallel
check "translocate_mode=parallel set explicitly: the default's final surface, byte for byte" \
  cmp -s "$T/default/sponge/final.ply" "$T/parallel/sponge/final.ply"
for opt in translocate_mode=sequential probe=paper far_field=walls; do
  name="${opt%%=*}"
  grow "$name" --set "$opt"
  check "$opt: the manifest records it" recorded "$name" "$name" "${opt#*=}"
  check "$opt: the final surface differs from the default's" \
    bash -c '! cmp -s "$1" "$2"' _ "$T/default/sponge/final.ply" "$T/$name/sponge/final.ply"
done
run grow --preset radiate --set translocate_mode=random --print-config
check "translocate_mode=random: refused with exit 2, naming the parameter" \
  bash -c '[ "$(cat "$1/rc")" = 2 ] && grep -q translocate_mode "$1/err"' _ "$T"
finish
