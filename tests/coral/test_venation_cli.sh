#!/usr/bin/env bash
# `sessile coral venation` from the command line: the parameter table
# (--print-config with units and the paper's names, --set, --config), the
# default run (snapshots, final PLY with a thickness_index property and OBJ,
# records), the same seed giving the same bytes and another seed others, the
# GPU and host searches giving the same bytes, closed venation, resume (after
# a clean stop and after SIGINT) giving the bytes of an uninterrupted run, and
# bad input: every parameter out of range, an empty blade, crossed curves,
# too much work: exit 2, one line on stderr, nothing written.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
sums() { (cd "$1" && find coral -type f | LC_ALL=C sort | xargs sha256sum); }
same() { cmp -s <(sums "$1") <(sums "$2"); }
PY=/usr/bin/python3
V="coral venation"

run coral venation --set auxins_per_iteration=12 --print-config
check "--print-config: the table with units and the paper's names, --set applied" eval \
  'rc_is 0 && grep -q "^auxins_per_iteration *12 " "$T/out" && grep -q "Auxin Kill Radius" "$T/out" && grep -q "^vein_step .*cm.*Vein Radius" "$T/out" && grep -q "Open Ended" "$T/out"'

# Its time is printed for the record, not asserted (tests never assert
# times: `sessile bench coral` measures it; ctest's TIMEOUT catches a hang).
TIMEFORMAT='%R %U %S'
{ time run coral venation --out "$T/a" --quiet; } 2>"$T/time"
read -r wall user sys <"$T/time"
echo "  the default run: $wall s wall, $user + $sys s CPU"
check "the default run completes (exit 0)" rc_is 0
check "snapshots every 20, final.ply and final.obj" eval \
  'for f in iter_0020.ply iter_0040.ply iter_0060.ply final.ply final.obj; do test -s "$T/a/coral/$f" || exit 1; done'
check "PLY: a per-vertex thickness_index whose maximum is the node count; records per iteration" \
  "$PY" - "$T/a" <<'PYEOF'
import json, struct, sys
d = sys.argv[1]
b = open(d + "/coral/final.ply", "rb").read()
h = b.index(b"end_header\n") + 11
head = b[:h].decode()
props = [l.split()[-1] for l in head.splitlines() if l.startswith("property float")]
nv = int(head.split("element vertex ")[1].split()[0])
k = props.index("thickness_index")
rec = 4 * len(props) + (3 if "property uchar red" in head else 0)  # the colours follow the floats
vals = [struct.unpack_from("<%df" % len(props), b, h + rec * i)[k] for i in range(nv)]
recs = [json.loads(l) for l in open(d + "/records.jsonl")]
m = json.load(open(d + "/manifest.json"))
ok = [r["iteration"] for r in recs] == list(range(1, 61)) and max(vals) == recs[-1]["nodes"]
ok = ok and all(r["edges"] == r["nodes"] - 1 for r in recs) and m["state"] == "completed"
ok = ok and m["parameters"]["vein_step"]["source"] == "Vein Radius"
ok = ok and open(d + "/coral/final.obj").read().count("\nf ") > 1000
print(nv, max(vals), recs[-1])
sys.exit(0 if ok else 1)
PYEOF

run coral venation --out "$T/b" --quiet
check "the same seed gives the same bytes" eval 'rc_is 0 && same "$T/a" "$T/b"'
run coral venation --out "$T/c" --seed 2 --quiet
check "another seed gives another coral" eval 'rc_is 0 && ! cmp -s "$T/a/coral/final.ply" "$T/c/coral/final.ply"'
run coral venation --out "$T/h" --set search=host --quiet
check "search=host gives the GPU search's bytes" eval 'rc_is 0 && same "$T/a" "$T/h"'

run coral venation --out "$T/cl" --set open=false --quiet
check "closed venation: more edges than nodes (cycles) in the records" eval \
  'rc_is 0 && tail -1 "$T/cl/records.jsonl" | "$PY" -c "import json,sys; r=json.load(sys.stdin); sys.exit(0 if r[\"edges\"] >= r[\"nodes\"] else 1)"'
run coral venation --out "$T/clh" --set open=false --set search=host --quiet
check "closed venation: search=host (host relative neighbourhood) gives the GPU's bytes" eval 'rc_is 0 && same "$T/cl" "$T/clh"'
run coral venation --out "$T/box" --set planar=false --set auxins_per_iteration=20 --iterations 30 --quiet
check "a 3-D box run completes" eval 'rc_is 0 && test -s "$T/box/coral/final.ply"'

run coral venation --out "$T/r" --iterations 30 --quiet
run coral venation --resume "$T/r" --iterations 60 --quiet
check "--resume from 30 to 60 gives the bytes of 60 at once" eval 'rc_is 0 && same "$T/a" "$T/r"'

"$S" coral venation --out "$T/full" --iterations 200 --every 1000 --quiet >/dev/null 2>&1
"$S" coral venation --out "$T/int" --iterations 200 --every 1000 --quiet >/dev/null 2>"$T/int.err" &
pid=$!
sleep 1
kill -INT $pid 2>/dev/null
wait $pid
rc=$?
if [ $rc = 130 ]; then
  check "SIGINT: the run stops (130) and says how to resume" grep -q "resume" "$T/int.err"
  run coral venation --resume "$T/int" --quiet
  check "... --resume gives the bytes of the uninterrupted run" eval 'rc_is 0 && same "$T/full" "$T/int"'
else
  check "the run finished before SIGINT (rc $rc): the same bytes" eval '[ $rc = 0 ] && same "$T/full" "$T/int"'
fi

# every parameter out of range, and the cross-parameter checks
bad=(open=2 planar=maybe auxins_per_iteration=0 auxins_per_iteration=100001 initial_width=0 width_increment=-1
     aspect=0 depth_ratio=0 left_1x=11 left_1z=1.5 left_2x=-11 left_2z=-0.1 right_1x=11 right_1z=2 right_2x=-10.5
     right_2z=1.01 kill_radius=0 birth_distance=0 vein_step=0 influence_radius=0 merge_distance=-1
     thickness_0=0 thickness_1=0 thickness_2=101 thickness_3=-1 mesh_detail=2 mesh_detail=65 geometry=sdf
     weld_cell=0 weld_blend=-1 search=cpu birth_distance=0.1 vein_step=0.3 merge_distance=0.2 nonsense=1)
n=0
for kv in "${bad[@]}"; do
  run coral venation --out "$T/bad" --set "$kv" --quiet
  if ! rc_is 2 || [ "$(wc -l <"$T/err")" != 1 ] || [ -e "$T/bad" ]; then echo "  not refused cleanly: $kv"; n=$((n + 1)); fi
done
check "every parameter out of range (${#bad[@]} cases): exit 2, one line, nothing written" [ $n = 0 ]
run coral venation --out "$T/bad" --set left_1x=0 --set left_2x=0 --set right_1x=0 --set right_2x=0
check "an empty blade (degenerate curves): exit 2, one line, nothing written" eval \
  'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "blade is empty" "$T/err" && [ ! -e "$T/bad" ]'
run coral venation --out "$T/bad" --set left_1x=0.7 --set left_2x=0.75 --set right_1x=-0.7 --set right_2x=-0.75
check "crossed curves: exit 2, one line, nothing written" eval 'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && [ ! -e "$T/bad" ]'
run coral venation --out "$T/bad" --iterations 1000000 --set auxins_per_iteration=100000
check "too much work: refused with the estimate, nothing written" eval \
  'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "GB" "$T/err" && [ ! -e "$T/bad" ]'
run coral venation --out "$T/bad" --bogus
check "an unknown option: exit 2, nothing written" eval 'rc_is 2 && [ ! -e "$T/bad" ]'
finish
