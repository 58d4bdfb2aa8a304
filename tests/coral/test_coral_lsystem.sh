#!/usr/bin/env bash
# `sessile coral lsystem` from the command line: the default run and its
# files (PLY with the per-vertex 'value', OBJ, grammar copy, manifest,
# records), the same seed giving byte-identical meshes, every shipped
# grammar, --define, and bad input (a malformed grammar with
# file:line:column, parameters out of range, --resume, a derivation beyond
# max_modules, the weld placeholder) exiting with one stderr line and
# nothing written.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3

one_line() { [ "$(wc -l <"$T/err")" -eq 1 ]; }
nothing_at() { [ ! -e "$1" ]; }

run coral lsystem --out "$T/a" --quiet
check "the default run completes" rc_is 0
check "... writes final.ply (with 'property float value'), final.obj and the grammar" eval \
  'grep -aq "^property float value" "$T/a/coral/final.ply" && test -s "$T/a/coral/final.obj" && cmp -s "$T/a/coral/grammar.lsys" "$(dirname "$0")/../../host/coral/grammars/lophelia1.lsys"'
check "... manifest (completed, grammar, parameters with the paper's names) and one record per step" \
  "$PY" - "$T/a" <<'PYEOF'
import json, sys
d = sys.argv[1]; m = json.load(open(d + "/manifest.json"))
recs = [json.loads(l) for l in open(d + "/records.jsonl")]
it = m["grammar"]["iterations"]
ok = m["state"] == "completed" and m["generator"] == "coral lsystem" and m["grammar"]["name"] == "lophelia1"
ok = ok and m["parameters"]["thickness"]["source"] == "Thickness" and m["parameters"]["mesh_detail"]["source"] == "Mesh Detail"
ok = ok and [r["iteration"] for r in recs] == list(range(0, it + 1)) and recs[-1]["modules"] == m["result"]["modules"]
ok = ok and m["result"]["segments"] > 100 and "coral/final.ply" in m["files"]
print(m["state"], it, m["result"]["modules"], m["result"]["segments"])
sys.exit(0 if ok else 1)
PYEOF
check "the PLY: 4 x mesh_detail triangles per segment, 'value' = branch depth from 0 to the manifest's maximum" \
  "$PY" - "$T/a" <<'PYEOF'
import json, struct, sys
d = sys.argv[1]; m = json.load(open(d + "/manifest.json")); r = m["result"]
data = open(d + "/coral/final.ply", "rb").read()
head, body = data.split(b"end_header\n", 1)
props = [l.split()[2] for l in head.decode().splitlines() if l.startswith("property float")]
nv = int([l for l in head.decode().splitlines() if l.startswith("element vertex")][0].split()[2])
rec = 4 * len(props) + (3 if b"property uchar red" in head else 0)  # the colours follow the floats
vals = [struct.unpack_from("<%df" % len(props), body, rec * i)[props.index("value")] for i in range(nv)]
sides = m["parameters"]["mesh_detail"]["value"]
ok = r["triangles"] == 4 * sides * r["segments"] and nv == r["vertices"] == (2 * sides + 2) * r["segments"]
ok = ok and min(vals) == 0 and max(vals) == r["max_branch_order"] and all(v == int(v) for v in vals)
print(nv, r["triangles"], r["segments"], min(vals), max(vals), r["max_branch_order"])
sys.exit(0 if ok else 1)
PYEOF
run coral lsystem --out "$T/b" --quiet
run coral lsystem --out "$T/c" --seed 2 --quiet
check "the same seed gives byte-identical PLY and OBJ; another seed another coral" eval \
  'cmp -s "$T/a/coral/final.ply" "$T/b/coral/final.ply" && cmp -s "$T/a/coral/final.obj" "$T/b/coral/final.obj" && ! cmp -s "$T/a/coral/final.ply" "$T/c/coral/final.ply"'
for g in lophelia2 flat; do
  run coral lsystem --grammar "$g" --out "$T/$g" --quiet
  check "grammar $g runs" eval 'rc_is 0 && test -s "$T/$g/coral/final.ply"'
done
run coral lsystem --set grammar=flat --define p_fork=0.9 --iterations 5 --out "$T/d" --quiet
check "--define overrides a grammar's define, --iterations its steps" eval \
  'rc_is 0 && "$PY" -c "import json,sys; m=json.load(open(sys.argv[1])); sys.exit(not (m[\"grammar\"][\"defines\"][\"p_fork\"] == 0.9 and m[\"grammar\"][\"iterations\"] == 5))" "$T/d/manifest.json"'
run coral lsystem --print-config --define len=2
check "--print-config lists the table and the grammar's defines" eval \
  'rc_is 0 && grep -q "^thickness_variance .*Thickness Variance" "$T/out" && grep -q "define len .*2$" "$T/out"'

# bad input: exit 2, one line on stderr, nothing written
printf 'axiom: A\nA(x) -> B(x +* 2)\n' >"$T/bad.lsys"
run coral lsystem --grammar "$T/bad.lsys" --out "$T/x1"
check "a malformed grammar: exit 2, 'file:line:column:', one line, nothing written" eval \
  'rc_is 2 && grep -q "bad.lsys:2:1[0-9]: " "$T/err" && one_line && nothing_at "$T/x1"'
run coral lsystem --grammar "$T/missing.lsys" --out "$T/x2"
check "a missing grammar file: exit 2, nothing written" eval 'rc_is 2 && one_line && nothing_at "$T/x2"'
run coral lsystem --grammar coralline --out "$T/x3"
check "an unknown grammar name: exit 2" eval 'rc_is 2 && one_line && nothing_at "$T/x3"'
for kv in thickness=0 thickness_variance=1 mesh_detail=2 mesh_detail=65 step=-1 max_modules=0 tropism_x=2 \
  weld_cells=8 min_radius=0 geometry=blob; do
  run coral lsystem --set "$kv" --out "$T/x4"
  check "--set $kv: exit 2, one line, nothing written" eval 'rc_is 2 && one_line && nothing_at "$T/x4"'
done
run coral lsystem --set tropism_x=0 --set tropism_y=0 --set tropism_z=0 --out "$T/x5"
check "tropism strength without a direction: exit 2" eval 'rc_is 2 && one_line && nothing_at "$T/x5"'
run coral lsystem --define nope=1 --out "$T/x6"
check "--define of an unknown name: exit 2" eval 'rc_is 2 && one_line && nothing_at "$T/x6"'
run coral lsystem --resume "$T/a"
check "--resume is refused (no iterations to resume)" eval 'rc_is 2 && one_line'
run coral lsystem --every 3 --out "$T/x7"
check "--every is refused" eval 'rc_is 2 && one_line && nothing_at "$T/x7"'
run coral lsystem --iterations 30 --set max_modules=100000 --out "$T/x8"
check "a derivation beyond max_modules: exit 2 with the estimate, nothing written" eval \
  'rc_is 2 && one_line && grep -q estimate "$T/err" && nothing_at "$T/x8"'
run coral lsystem --set geometry=weld --set weld_cells=64 --iterations 3 --out "$T/x9" # a coarse grid: the weld's own tests are test_coral_weld's
check "geometry=weld exits cleanly (0, or one line and nothing written)" eval \
  'rc_is 0 || { { rc_is 1 || rc_is 2; } && one_line && nothing_at "$T/x9"; }'

# SIGINT and SIGTERM stop a long run (a 200 000-module axiom: a minute of
# meshing and writing) at once: exit 130/143, nothing half-written (no
# temporary left), the folder absent or an interrupted run.  Started in the
# background, as a script does, where SIGINT arrives ignored.
python3 -c 'print("iterations: 0\naxiom:" + " F" * 200000)' >"$T/long.lsys"
for sig in INT TERM; do
  "$S" coral lsystem --grammar "$T/long.lsys" --out "$T/sig$sig" --no-preview >"$T/out" 2>"$T/err" &
  pid=$!
  sleep 2
  kill -"$sig" "$pid"
  wait "$pid"
  echo $? >"$T/rc"
  want=$([ "$sig" = INT ] && echo 130 || echo 143)
  check "SIG$sig during a long run: exit $want, no temporary file, nothing or an interrupted run" eval \
    'rc_is $want && [ -z "$(find "$T/sig$sig" -name "*sessile-tmp*" 2>/dev/null)" ] &&
     { [ ! -e "$T/sig$sig" ] || grep -Eq "\"state\":[[:space:]]*\"interrupted\"" "$T/sig$sig/manifest.json"; }'
done
finish
