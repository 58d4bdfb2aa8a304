#!/usr/bin/env bash
# `sessile sponge particles` from the command line: help, --print-config
# (units, the paper's names), a short run's files (snapshots, final PLY with
# the per-vertex growth_count, OBJ, manifest, records), the same seed giving
# the same bytes, resume to the same bytes, and bad input: every parameter
# out of range, and each cross-parameter check, exits 2 with one line on
# stderr and writes nothing.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
sums() { (cd "$1" && find sponge -type f | LC_ALL=C sort | xargs sha256sum); }
PY=/usr/bin/python3
SMALL="--set mesh_detail=3 --set nutrients_per_iteration=120 --set cube_size=3"

run sponge --help
check "sponge --help lists the generator 'particles'" eval 'rc_is 0 && grep -q "^  particles " "$T/out"'
run sponge particles --print-config --set particle_feed=4
check "--print-config: units, the paper's names, --set applied" eval \
  'rc_is 0 && grep -q "^particle_feed *4 .*Particle feed" "$T/out" && grep -q "^nutrient_radius .* cm .*Nutrient radius" "$T/out" && grep -q "^mesh_detail .*Mesh detail" "$T/out" && grep -q "^splitting_threshold .*Splitting threshold" "$T/out" && grep -q "^feeding_iterations .*Feeding iterations" "$T/out"'

run sponge particles $SMALL --seed 5 --iterations 25 --every 10 --out "$T/a" --quiet --check
check "a 25-iteration run (with --check) completes" rc_is 0
check "snapshots every 10 and at the last; final.ply and final.obj" eval \
  'for i in 0010 0020 0025; do test -s "$T/a/sponge/iter_$i.ply" || exit 1; done; test -s "$T/a/sponge/final.ply" && grep -q "^v " "$T/a/sponge/final.obj" && grep -q "^f " "$T/a/sponge/final.obj"'
check "the PLY carries the per-vertex growth_count property" eval \
  'head -c 600 "$T/a/sponge/final.ply" | grep -aq "property float growth_count"'
check "manifest and 25 records (vertices, particles alive, hits, times, no self-intersection)" \
  "$PY" - "$T/a" <<'PYEOF'
import json, sys
d = sys.argv[1]; m = json.load(open(d + "/manifest.json"))
recs = [json.loads(l) for l in open(d + "/records.jsonl")]
ok = m["state"] == "completed" and "sponge/final.ply" in m["files"] and "sponge/final.obj" in m["files"]
ok = ok and m["parameters"]["particle_feed"]["source"] == "Particle feed" and m["config"]["seed"] == "5"
ok = ok and [r["iteration"] for r in recs] == list(range(1, 26))
ok = ok and all(r["vertices"] > 0 and "particles_alive" in r and "hits" in r and r["collide_s"] >= 0 and r["self_intersections"] == 0 for r in recs)
ok = ok and sum(r["hits"] for r in recs) > 0
print(m["state"], len(recs), sum(r["hits"] for r in recs))
sys.exit(0 if ok else 1)
PYEOF

run sponge particles $SMALL --seed 5 --iterations 25 --every 10 --out "$T/b" --quiet --check
check "the same seed gives byte-identical meshes" eval 'sums "$T/a" >"$T/a.sum"; sums "$T/b" >"$T/b.sum"; cmp -s "$T/a.sum" "$T/b.sum"'
run sponge particles $SMALL --seed 5 --iterations 13 --every 10 --out "$T/c" --quiet --check
run sponge particles --resume "$T/c" --iterations 25 --quiet
check "--resume from 13 to 25 completes" rc_is 0
check "... byte-identical to the uninterrupted run; the final-only snapshot at 13 gone" eval \
  'sums "$T/c" >"$T/c.sum"; cmp -s "$T/a.sum" "$T/c.sum" && test ! -e "$T/c/sponge/iter_0013.ply"'
run sponge particles $SMALL --seed 6 --iterations 25 --every 10 --out "$T/d" --quiet
check "another seed gives another mesh" eval '! cmp -s "$T/a/sponge/final.ply" "$T/d/sponge/final.ply"'

# Every parameter out of range (below and above), then the cross checks and
# the memory refusal: exit 2, one line on stderr, nothing written.
bad() { # description, --set arguments...
  local what="$1"; shift
  rm -rf "$T/bad"
  run sponge particles "$@" --out "$T/bad" --quiet
  check "$what: exit 2, one line, nothing written" eval \
    'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "^sessile sponge particles: error: " "$T/err" && test ! -e "$T/bad"'
}
for kv in mesh_detail=1 mesh_detail=7 radius=0 radius=101 cube_size=0 cube_size=1001 \
          nutrients_per_iteration=0 nutrients_per_iteration=1000001 nutrient_radius=0 nutrient_radius=101 \
          nutrient_lifetime=0 nutrient_lifetime=100001 particle_feed=0 particle_feed=17 \
          fall_speed=0 fall_speed=101 current_x=-101 current_x=101 current_y=-101 current_y=101 \
          current_z=-101 current_z=101 growth_fraction=-0.1 growth_fraction=2.1 \
          feeding_iterations=-1 feeding_iterations=9 falloff_sigma=0 falloff_sigma=101 \
          splitting_threshold=0 splitting_threshold=101 collapse_threshold=0 collapse_threshold=101 \
          max_vertices=99 max_vertices=20000001 collider=cuda mesh_detail=3.5 radius=nan; do
  bad "$kv" --set "$kv"
done
bad "cube no wider than the hemisphere" --set cube_size=2
bad "collapse_threshold above splitting_threshold" --set collapse_threshold=0.3
bad "a step longer than the particle's diameter" --set fall_speed=0.5
bad "particles rising" --set current_z=0.2 --set fall_speed=0.1
bad "a nutrient radius of half the cube" --set nutrient_radius=2.5
bad "too many particles for a storage buffer" --set nutrients_per_iteration=1000000 --set nutrient_lifetime=100
check "... the refusal states the estimate" grep -q "MiB" "$T/err"
bad "an unknown parameter" --set nutrient_colour=3
finish
