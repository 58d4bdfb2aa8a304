#!/usr/bin/env bash
# `sessile sds run` and its parameter table (docs/sds.md, "Parameters"):
# --print-config lists every parameter with the model's value, unit, range
# and source (a model line overrides the table's default, --config the model,
# --set the config); --set dt=<the model's own> gives the bytes of a run
# without it, another dt another run, and the manifest records the values;
# bad values (out of range, unknown, not a number, an unknown key in a
# config) exit 2 with one line naming the parameter and write nothing (a
# resume of a run made with --set: tests/sds/test_sds_resume.sh).
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
one_line() { [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "error" "$T/err" && [ ! -s "$T/out" ]; }
sums() { (cd "$1" && find sds -type f ! -name steps.csv | LC_ALL=C sort | xargs sha256sum); }
row() { grep "^$1 " "$T/out"; }
LIMB="$(cd "$(dirname "$0")/../../host/sds/models" && pwd)/limb.sds"
cd "$T" || exit 1 # a default run folder (runs/...) would land here

run sds run limb --print-config
check "--print-config: exit 0, one line per parameter, nothing else written" eval \
  'rc_is 0 && [ ! -s "$T/err" ] && [ "$(grep -c . "$T/out")" -ge 10 ] && [ ! -e runs/sds-limb ]'
check "--print-config: dt with its value, unit s, range and source" eval \
  'row dt | grep -q "^dt  *0.001  *s  *(0, inf)  *ours "'
check "--print-config: the model's own values (limb: self_collide false, volume_stiffness 2, gravity 0)" eval \
  'row self_collide | grep -q " false " && row volume_stiffness | grep -q " 2  *u/s^2 " && row gravity | grep -q " 0 "'
sed 's/^volume_stiffness = .*/volume_stiffness = 3/' "$LIMB" >"$T/k3.sds"
printf '{"volume_stiffness": 4, "dt": 0.002}\n' >"$T/c1.json"
printf '{"dt": 0.003}\n' >"$T/c2.json"
run sds run "$T/k3.sds" --print-config
check "a model line overrides the table's default" eval 'rc_is 0 && row volume_stiffness | grep -q " 3 "'
run sds run "$T/k3.sds" --config "$T/c1.json" --print-config
check "--config overrides the model" eval 'rc_is 0 && row volume_stiffness | grep -q " 4 " && row dt | grep -q " 0.002 "'
run sds run "$T/k3.sds" --config "$T/c1.json" --config "$T/c2.json" --set volume_stiffness=5 --print-config
check "configs in order, then --set" eval 'rc_is 0 && row volume_stiffness | grep -q " 5 " && row dt | grep -q " 0.003 "'

ARGS=(sds run limb --t-end 2 --frames 2 --quiet --no-preview)
run "${ARGS[@]}" --out "$T/a"
check "a short limb run completes" rc_is 0
run "${ARGS[@]}" --out "$T/b" --set dt=0.001
check "--set dt=0.001 (the model's own): the same bytes under sds/" eval \
  'rc_is 0 && sums "$T/a" >"$T/a.sum" && sums "$T/b" >"$T/b.sum" && cmp -s "$T/a.sum" "$T/b.sum"'
run "${ARGS[@]}" --out "$T/c" --set dt=0.0002
check "--set dt=0.0002: another run (its step log's first step differs)" eval \
  'rc_is 0 && ! cmp -s <(cut -d, -f1-5 "$T/a/sds/steps.csv") <(cut -d, -f1-5 "$T/c/sds/steps.csv")'
check "the manifest records the parameters: dt 0.001 and 0.0002 with their unit and source" \
  "$PY" - "$T/a" "$T/c" <<'PYEOF'
import json, sys
a, c = (json.load(open(d + "/manifest.json")) for d in sys.argv[1:3])
pa, pc = a["parameters"], c["parameters"]
ok = pa["dt"]["value"] == 0.001 and pc["dt"]["value"] == 0.0002 and pc["dt"]["unit"] == "s"
ok = ok and pc["dt"]["source"] == "ours" and pa["volume_stiffness"]["value"] == 2
ok = ok and c["config"]["parameters"]["dt"] == 0.0002 and set(pa) == set(c["config"]["parameters"])
print("dt", pa["dt"], pc["dt"])
sys.exit(0 if ok else 1)
PYEOF
run "${ARGS[@]}" --out "$T/d" --config "$T/c2.json"
check "--config applied: the manifest's dt is 0.003" eval \
  'rc_is 0 && "$PY" -c "import json,sys; sys.exit(json.load(open(\"$T/d/manifest.json\"))[\"parameters\"][\"dt\"][\"value\"] != 0.003)"'

refuses() { # description, args...
  local what="$1"; shift
  run sds run limb --out "$T/x" "$@"
  check "$what: exit 2, one line naming the parameter, nothing written" \
    eval "rc_is 2 && one_line && grep -q \"$PARAM\" \"\$T/err\" && [ ! -e \"\$T/x\" ]"
}
PARAM=dt refuses "--set dt=-1" --set dt=-1
PARAM=dt refuses "--set dt=abc" --set dt=abc
PARAM=nosuch refuses "--set nosuch=1" --set nosuch=1
PARAM=self_collide refuses "--set self_collide=2" --set self_collide=2
printf '{"dt": 0.002, "nosuch": 1}\n' >"$T/bad.json"
PARAM=nosuch refuses "a --config with an unknown key" --config "$T/bad.json"
sed 's/^damping = .*/damping = 0.001 0.002/' "$LIMB" >"$T/two.sds"
run sds run "$T/two.sds" --out "$T/x"
check "a model line with two numbers for a table parameter: exit 2, model:line, nothing written" eval \
  'rc_is 2 && one_line && grep -q "two.sds:12: damping takes one number" "$T/err" && [ ! -e "$T/x" ]'

finish
