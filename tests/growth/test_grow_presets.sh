#!/usr/bin/env bash
# 50-iteration runs of both presets: the pipeline checks the surface
# invariants (closed, consistently oriented 2-manifold, Euler characteristic
# 2, no degenerate or duplicate triangles) after every remesh and fails the
# run otherwise; here we also read the records to see that all 50 checks ran
# and passed (no self-intersection either), that every nutrient solve
# converged to the paper's 1e-6, and that the sponge grew.  Argument 2: the
# box resolution (the suite runs the base grid, 27 225 nodes; the slow label
# the default resolution 2).
set -u
S="$1"
RES="${2:-2}"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
for preset in radiate crella; do
  "$S" grow --preset "$preset" --seed 7 --iterations 50 --every 0 --set fluid_at_snapshots=false --set box_resolution="$RES" \
    --out "$T/$preset" --quiet >"$T/$preset.out" 2>"$T/$preset.err"
  rc=$?
  check "$preset: 50 iterations run (exit $rc)" [ "$rc" -eq 0 ]
  [ "$rc" -eq 0 ] || cat "$T/$preset.err"
  check "$preset: records show 50 surface checks passed, converged solves, growth" \
    "$PY" - "$T/$preset/manifest.json" "$T/$preset/records.jsonl" <<'PYEOF'
import json, sys
m = json.load(open(sys.argv[1]))
its = [json.loads(l) for l in open(sys.argv[2])]
ok = len(its) == 50 and all(i.get("surface_check") == "passed" for i in its)
ok = ok and all(i["nutrient_solve"]["status"] == "converged" and i["nutrient_solve"]["true_relres"] <= 1e-6 for i in its)
# contact inhibition: no self-intersection after any iteration
ok = ok and all(i.get("self_intersections") == 0 for i in its)
v0 = m["initial_sponge"]["volume_cm3"]; v1 = its[-1]["surface"]["volume_cm3"]
print("iterations %d, volume %.1f -> %.1f cm^3, vertices %d -> %d, vertices held back %d" % (len(its), v0, v1,
      m["initial_sponge"]["vertices"], its[-1]["surface"]["vertices"],
      sum(i["growth"]["held_back_vertices"] for i in its)))
sys.exit(0 if ok and v1 > 1.2 * v0 else 1)
PYEOF
done
finish
