#!/usr/bin/env bash
# The pool's generators beyond the registry's first four (docs/reef.md,
# "Organisms"): coral lsystem, sds run (its model as an argument) and grow in
# one small reef (a standard brush: one mesh per entry, its placements
# enough that each entry is drawn): it runs, reef.glb holds one mesh per entry, each equal to
# the PLY its generator's own command writes with the same parameters and
# seed 1; exposure is listed; bad arguments are refused naming the JSON path.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
GROW="box_resolution=1 box_cells_x=16 box_cells_y=16 box_cells_z=12 sponge_radius=3 fluid_at_snapshots=false"
"$PY" - "$T/pool.json" "$GROW" <<'PYEOF'
import json, sys
json.dump({"seabed": {"noise": {"seed": 1, "resolution": [17, 17], "extent": [6, 4], "height_scale": 0.2, "base": -3}},
           "pool": [{"name": "stony", "generator": "coral lsystem", "parameters": ["grammar=lophelia1", "iterations=3"],
                     "colour": [0.9, 0.8, 0.7, 1], "size": [0.3, 0.3]},
                    {"name": "limb", "generator": "sds run", "arguments": ["limb", "--t-end", "5", "--frames", "1"],
                     "colour": [0.8, 0.3, 0.3, 1], "size": [0.3, 0.3]},
                    {"name": "sponge", "generator": "grow", "parameters": sys.argv[2].split() + ["iterations=2"],
                     "colour": [0.9, 0.7, 0.2, 1], "size": [0.3, 0.3]}],
           "brushes": [{"points": [[1, 2], [5, 2]], "size": 1, "density": 8}],
           "currents": [{"origin": [0, 2, -3], "direction": [1, 0, 0], "strength": 8, "nutrition_range": 0.5}]},
          open(sys.argv[1], "w"))
PYEOF
run reef "$T/pool.json" --seed 4 --out "$T/a" --quiet --no-preview
check "a reef of an L-system coral, an SDS limb and a grown sponge runs" rc_is 0
check "placements.json: every entry placed; the SDS entry lists its arguments" "$PY" - "$T/a" <<'PYEOF'
import json, sys
pl = json.load(open(sys.argv[1] + "/placements.json"))["placements"]
print([(p["entry"], p["mesh"]) for p in pl])
ok = sorted({p["entry"] for p in pl}) == ["limb", "sponge", "stony"]
ok = ok and all(p.get("arguments") == ["limb", "--t-end", "5", "--frames", "1"] for p in pl if p["entry"] == "limb")
ok = ok and all("arguments" not in p for p in pl if p["entry"] != "limb")
sys.exit(0 if ok else 1)
PYEOF
# each generator alone, by its own command, seed 1: the standard brushes' meshes
"$S" coral lsystem --grammar lophelia1 --iterations 3 --seed 1 --out "$T/stony" --quiet --no-preview
"$S" sds run limb --t-end 5 --frames 1 --seed 1 --out "$T/limb" --quiet --no-preview
"$S" grow $(for s in $GROW; do echo --set "$s"; done) --iterations 2 --seed 1 --out "$T/sponge" --quiet --no-preview
. "$(dirname "$0")/../io/gltf_readers.sh"
check "validator: reef.glb has no errors or warnings" validate "$T/a/reef.glb"
check "python: each entry's mesh equals its own command's PLY (vertices, triangles, attributes)" \
  "$PY" "$(dirname "$0")/reef_glb_check.py" "$T/a" "$T/pool.json" stony="$T/stony/coral/final.ply" \
  limb="$T/limb/sds/final.ply" sponge="$T/sponge/sponge/final.ply"

. "$(dirname "$0")/bad_scene.sh"
bad() { bad_scene "$T/pool.json" "$@"; } # description, JSON path in the message, edit of d
bad "an unknown SDS model" "pool[1].arguments: no shipped model" "d['pool'][1]['arguments'][0] = 'nosuchmodel'"
bad "an SDS option twice" "pool[1].arguments[5]: --t-end given twice" "d['pool'][1]['arguments'] += ['--t-end', '2']"
bad "SDS without a model" "pool[1].arguments" "del d['pool'][1]['arguments']"
bad "iterations for SDS" "pool[1].parameters[0]" "d['pool'][1]['parameters'] = ['iterations=3']"
bad "arguments for the L-system" "pool[0].arguments[0]" "d['pool'][0]['arguments'] = ['--grammar']"
bad "an L-system grammar not shipped" "pool[0].parameters[0]" "d['pool'][0]['parameters'][0] = 'grammar=nosuch'"
bad "arguments not strings" "pool[1].arguments" "d['pool'][1]['arguments'] = [1]"
run reef "$T/pool.json" --out "$T/never" --set device_exposure=false
check "SDS without the reef's device: exit 2 naming pool[1].generator" eval \
  'rc_is 2 && grep -qF "pool[1].generator" "$T/err" && [ ! -e "$T/never" ]'
finish
