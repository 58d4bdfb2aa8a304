#!/usr/bin/env bash
# `sessile reef` from the command line (docs/reef.md): a small scene of
# sphere organisms runs, its outputs agree with each other, the same seed
# gives the same bytes, the device's exposure equals the host's, and bad
# scenes exit 2 with one line naming the JSON path and write nothing.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
SCENE="$(dirname "$0")/scene_small.json"
same() { for f in placements.json reef/reef.ply reef/scene.json reef/meshes.ply reef/placements_0002.json checkpoint.bin \
                  preview.png reef.glb; do
  cmp -s "$1/$f" "$2/$f" || return 1; done; }

run reef "$SCENE" --seed 5 --out "$T/a" --quiet
check "a small reef runs" rc_is 0
check "placements.json, the manifest and the records agree; meshes per brush kind" "$PY" - "$T/a" <<'PYEOF'
import json, sys
d = sys.argv[1]; p = json.load(open(d + "/placements.json")); m = json.load(open(d + "/manifest.json"))
recs = [json.loads(l) for l in open(d + "/records.jsonl")]
pl = p["placements"]
ok = p["count"] == len(pl) == m["reef"]["placements"] == recs[-1]["organisms"] and len(recs) == 2
meshes = {q["mesh"] for q in pl}
ok = ok and m["reef"]["meshes"] == len(meshes) + 1 and m["reef"]["materials"] == 3
std = {}
for q in pl:
    if q["brush"] == "standard": std.setdefault(q["entry"], set()).add(q["mesh"])
ok = ok and all(len(v) == 1 for v in std.values()) and std
auto = [q["mesh"] for q in pl if q["brush"] != "standard"]
ok = ok and len(set(auto)) == len(auto) and not (set(auto) & set().union(*std.values()))
ok = ok and all(0.5 <= q["depth"] <= 20 for q in pl) and any(q["exposure"] > 0 for q in pl)
ok = ok and all(abs(q["transform"][12 + i] - q["position"][i]) < 1e-12 for q in pl for i in range(3))
print(len(pl), "placements,", len(meshes), "organism meshes")
sys.exit(0 if ok else 1)
PYEOF
# the preview's instanced scene (docs/reef.md, "Output"): a part per glTF
# mesh, an instance per node with its material's colour (sRGB) and matrix;
# preview.png shows each colour (pixels of its chromaticity: cosine > 0.999
# with the colour; the uncoloured sand of before is 0.997 from "ball"), and
# `sessile render` of the scene gives the preview's bytes
"$S" render "$T/a/reef/scene.json" -o "$T/a_scene.png" --size 640x480 --quiet
check "reef/scene.json: parts, instances, colours, matrices; preview.png in the pool's and the seabed's colours" \
  env PNG_DECODE_DIR="$(cd "$(dirname "$0")/../common" && pwd)" "$PY" - "$T/a" "$SCENE" <<'PYEOF'
import json, math, os, struct, sys
sys.path.insert(0, os.environ["PNG_DECODE_DIR"])
from png_decode import decode
d = sys.argv[1]; sc = json.load(open(d + "/reef/scene.json")); pool = json.load(open(sys.argv[2]))["pool"]
pl = json.load(open(d + "/placements.json"))["placements"]; m = json.load(open(d + "/manifest.json"))
glb = open(d + "/reef.glb", "rb").read(); n, = struct.unpack("<I", glb[12:16]); g = json.loads(glb[20:20 + n])
srgb = lambda c: round(255 * (12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055))
rgb = lambda lin: [srgb(c) for c in lin[:3]]
seabed = rgb(g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"])
colour = {e["name"]: rgb(e["colour"]) for e in pool}
inst = sc["instances"]
ok = sc["format"] == "sessile render scene" and sc["mesh"] == "meshes.ply"
ok = ok and len(sc["parts"]) == m["reef"]["meshes"] and len(inst) == len(pl) + 1
ok = ok and inst[0]["part"] == 0 and inst[0]["rgb"] == seabed
for q, i in zip(pl, inst[1:]):
    ok = ok and i["part"] == q["mesh"] and i["rgb"] == colour[q["entry"]]
    ok = ok and all(abs(i["matrix"][k] - 100 * q["transform"][k]) <= 1e-9 * (1 + abs(i["matrix"][k])) for k in range(15))
w, h, rows = decode(d + "/preview.png")
px = [r[x:x + 3] for r in rows for x in range(0, 4 * w, 4)]
def like(c):
    n = math.sqrt(sum(v * v for v in c))
    return sum(1 for p in px if sum(p) > 60 and sum(a * b for a, b in zip(p, c)) > 0.999 * n * math.sqrt(sum(v * v for v in p)))
counts = {name: like(c) for name, c in list(colour.items()) + [("seabed", seabed)]}
print("pixels of each colour's chromaticity:", counts)
ok = ok and all(v >= 50 for v in counts.values())
ok = ok and open(d + "/preview.png", "rb").read() == open(d + "/../a_scene.png", "rb").read()
sys.exit(0 if ok else 1)
PYEOF
run render "$T/a" -o "$T/a_renders" --size 320x240 --quiet
check "sessile render of the reef's run directory draws its scene" eval 'rc_is 0 && test -s "$T/a_renders/final_top.png"'
# reef.glb by the readers of tests/io/test_gltf_readers.sh (a missing reader fails)
. "$(dirname "$0")/../io/gltf_readers.sh"
check "reef.glb is written and listed in the manifest" eval 'test -s "$T/a/reef.glb" && grep -q "\"reef.glb\"" "$T/a/manifest.json"'
NP=$("$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["count"])' "$T/a/placements.json")
NM=$("$PY" -c 'import json,sys; print(len({p["mesh"] for p in json.load(open(sys.argv[1]))["placements"]}))' "$T/a/placements.json")
check "validator: reef.glb has no errors or warnings" validate "$T/a/reef.glb"
check "validator: 3 materials (2 pool colours + the seabed's)" grep -q " materials=3 " "$T/counts"
# assimp adds a root node above glTF's scene nodes: placements + the seabed's node + 1
check "assimp: $((NM + 1)) meshes ($NM organisms + the seabed), $((NP + 2)) nodes ($NP placements + the seabed + its root)" \
  test "$(count "$T/a/reef.glb" Meshes) $(count "$T/a/reef.glb" Nodes)" = "$((NM + 1)) $((NP + 2))"
# the PLYs the organisms came from: each entry's generator alone, its parameters, seed 1
"$S" sphere --set level=2 --set radius=10 --iterations 3 --seed 1 --out "$T/ball" --quiet --no-preview
"$S" sphere --set level=1 --set noise=0.1 --seed 1 --out "$T/pebble" --quiet --no-preview
check "python: nodes, meshes, materials, transforms and vertices against placements.json and the PLYs" \
  "$PY" "$(dirname "$0")/reef_glb_check.py" "$T/a" "$SCENE" ball="$T/ball/sphere/final.ply" pebble="$T/pebble/sphere/final.ply"
# an organism whose PLY has a scalar (venation's thickness_index): _THICKNESS_INDEX on its mesh
"$PY" - "$SCENE" "$T/ven.json" <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[1]))
d["pool"] = [{"name": "fan", "generator": "coral venation", "parameters": ["search=host", "iterations=12"],
              "size": [0.3, 0.4]}]
d["brushes"] = [{"points": [[10, 16]], "size": 2, "density": 4}]
d["growth"] = {"steps": 0}
json.dump(d, open(sys.argv[2], "w"))
PYEOF
run reef "$T/ven.json" --seed 5 --out "$T/v" --quiet
"$S" coral venation --set search=host --iterations 12 --seed 1 --out "$T/fan" --quiet --no-preview
check "a venation reef: validator 0 errors or warnings" validate "$T/v/reef.glb"
check "a venation reef: python: its mesh carries the PLY's thickness_index as _THICKNESS_INDEX" \
  "$PY" "$(dirname "$0")/reef_glb_check.py" "$T/v" "$T/ven.json" fan="$T/fan/coral/final.ply"
run reef "$SCENE" --seed 5 --out "$T/b" --quiet
check "same scene, same seed: the same bytes" same "$T/a" "$T/b"
run reef "$SCENE" --seed 6 --out "$T/c" --quiet
check "another seed: other placements" eval '! cmp -s "$T/a/placements.json" "$T/c/placements.json"'
run reef "$SCENE" --seed 5 --out "$T/h" --quiet --set device_exposure=false
check "the device's exposure equals the host reference's" "$PY" - "$T/a" "$T/h" <<'PYEOF'
import json, sys
a, h = (json.load(open(d + "/placements.json"))["placements"] for d in sys.argv[1:3])
err = max(abs(x["exposure"] - y["exposure"]) for x, y in zip(a, h))
print("max exposure difference", err)
sys.exit(0 if len(a) == len(h) and err <= 1e-4 else 1)
PYEOF

# the README's example scene runs and its reef.glb validates
run reef "$(dirname "$0")/../../docs/reef_example.json" --out "$T/ex" --seed 3 --quiet
check "docs/reef_example.json runs; its reef.glb has no validator errors or warnings" eval 'rc_is 0 && validate "$T/ex/reef.glb"'

# sessile bench reef --quick: a smoke run; its figures are never checked
run bench reef --quick
check "bench reef --quick runs and prints its lines" eval 'rc_is 0 && grep -q "load average" "$T/out" &&
  ( for l in "placement (brushes)" "growth (one step)" "exposure host ref" "exposure device" "organisms (generate)" \
             "glTF write" "host ref / device" "distinct meshes written alone"; do grep -qF "$l" "$T/out" || exit 1; done )'
run bench reef --quick --organisms 0
check "bench reef --organisms 0: exit 2" rc_is 2

. "$(dirname "$0")/bad_scene.sh"
bad() { bad_scene "$SCENE" "$@"; } # description, JSON path in the message, edit of d
bad "unknown generator" "pool[1].generator" "d['pool'][1]['generator'] = 'nope'"
bad "unknown parameter" "pool[0].parameters[3]" "d['pool'][0]['parameters'].append('bogus=3')"
bad "parameter out of range" "pool[0].parameters[0]" "d['pool'][0]['parameters'][0] = 'level=99'"
bad "negative density" "brushes[1].density" "d['brushes'][1]['density'] = -1"
bad "brush off the seabed" "brushes[0].points[1]" "d['brushes'][0]['points'][1] = [30, 5]"
bad "a 10^9-organism brush" "brushes[0].density" "d['brushes'][0]['density'] = 1e9"
bad "growth past the limit" "growth.steps" "d['growth']['steps'] = 40; d['pool'][0]['size'] = [0.001, 0.002]"
bad "unknown key" "currents[0].colour" "d['currents'][0]['colour'] = 1"
bad "size range upside down" "pool[1].size" "d['pool'][1]['size'] = [0.3, 0.1]"
run reef "$T/missing.json" --out "$T/never"
check "a missing scene: exit 2, nothing written" eval 'rc_is 2 && [ ! -e "$T/never" ]'
finish
