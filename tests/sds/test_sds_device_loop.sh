#!/usr/bin/env bash
# The loop on the device (device_loop, issue 33; docs/sds.md "The loop on
# the device") against the host-driven loop: the same run gives the same
# bytes.  Steps in batches on the device, each step's rules, morphogens and
# growth there too; the host wakes for divisions, inversions (it completes
# such a step with its own code), stale contact lists and frames.
#  - a limb bud that grows fast (Delta 0.03: cells divide and tets invert
#    from t = 4) to t = 6: every file under sds/ the same bytes, the step
#    log equal but for its wall ms;
#  - the limb with diffusion so fast that most steps need more morphogen
#    sub-steps than a batch records (those steps' rules then the host's);
#  - the fast limb with diffusion 2: several sub-steps a step, on the device
#    (the count from step_check's bound: halving its rates fails this);
#  - the rock model (an obstacle: the contact lists and their skin) to t = 5;
#  - lasting slivers a batch keeps going over (the repairs' backoff table),
#    and a run with them stopped by SIGINT at t = 15 and resumed;
#  - a run stopped by SIGINT after frame 1 and resumed: the same bytes;
#  - a discrete GPU's paths (SESSILE_STAGED=1): a batch's transfers ride in
#    its own submission, so the loop on the device makes under half the
#    host-driven loop's submissions a step (counted by `bench sds`);
#  - the interpreted rules (device_rules = bytecode) the same bytes too, and
#    lavapipe on one thread or three (the fused kernels' last subgroup), and
#    with a discrete GPU's paths (one item an invocation in the fused kernels);
#  - the fused kernels taken (bench sds --kernels names them);
#  - the axial stiffness (springs born along phi's gradient 0.3 x as stiff
#    on the surface): the same bytes both loops, another run than without
#    it, and a resume after SIGINT (the springs' edge_k in the checkpoint);
#  - refusals: a rule the device cannot run (exp), a bad value, an axial
#    stiffness without an axis morphogen.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
. "$(dirname "$0")/sds_runs.sh"
PY=/usr/bin/python3
M="$(dirname "$0")/../../host/sds/models"
sed 's/^const Delta = .*/const Delta = 0.03/' "$M/limb.sds" >"$T/fast.sds"
sed 's/^morphogen phi diffusion=0.05/morphogen phi diffusion=400/' "$M/limb.sds" >"$T/diffuse.sds"
sed 's/^const Delta = .*/const Delta = 0.03/; s/^morphogen phi diffusion=0.05/morphogen phi diffusion=2/' "$M/limb.sds" >"$T/subs.sds"

counts() { "$PY" -c 'import csv,sys; r=list(csv.DictReader(open(sys.argv[1]))); print(sum(int(x["divisions"]) for x in r), sum(int(x["inversions"]) for x in r))' "$1/sds/steps.csv"; }

# the manifest's device_loop member: batches, steps whose rules the host completed
loop_stat() { "$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["sds"]["device_loop"][sys.argv[2]])' "$1/manifest.json" "$2"; }
for m in fast diffuse subs; do
  t=6
  [ $m = diffuse ] && t=1
  [ $m = subs ] && t=3
  run sds run "$T/$m.sds" --t-end $t --frames 5 --out "$T/$m-h" --quiet
  check "$m: the host-driven loop completes" rc_is 0
  run sds run "$T/$m.sds" --t-end $t --frames 5 --out "$T/$m-d" --quiet --set device_loop=true
  check "$m: the loop on the device completes" rc_is 0
  check "$m: the same bytes (frames, surfaces, series), the same steps" same_run "$T/$m-h" "$T/$m-d"
done
check "fast: the run divides cells and inverts tets; the host completed steps (the inversions')" eval \
  '[ "$(counts "$T/fast-h" | cut -d" " -f1)" -gt 0 ] && [ "$(counts "$T/fast-h" | cut -d" " -f2)" -gt 0 ] && [ "$(loop_stat "$T/fast-d" host_completed_steps)" -gt 0 ]'
check "fast: batches of many steps (fewer batches than a quarter of the steps)" eval \
  '[ $(( $(loop_stat "$T/fast-d" batches) * 4 )) -lt "$(($(wc -l <"$T/fast-d/sds/steps.csv") - 1))" ]'
check "subs: several morphogen sub-steps a step, most of them on the device (the host completed under a tenth)" eval \
  '[ $(( $(loop_stat "$T/subs-d" host_completed_steps) * 10 )) -lt "$(($(wc -l <"$T/subs-d/sds/steps.csv") - 1))" ]'
check "diffuse: most steps' sub-steps beyond a batch's: the host completed more than half the steps" eval \
  '[ $(( $(loop_stat "$T/diffuse-d" host_completed_steps) * 2 )) -gt "$(($(wc -l <"$T/diffuse-d/sds/steps.csv") - 1))" ]'

# lavapipe on one thread and on three: which subgroup finishes a fused
# dispatch last (and takes its minimum and checks) varies; the bytes do not
LP_NUM_THREADS=0 "$S" sds run "$T/fast.sds" --t-end 6 --frames 5 --out "$T/fast-t0" --quiet --set device_loop=true
check "fast, lavapipe on its queue thread alone: the same bytes" same_run "$T/fast-d" "$T/fast-t0"
LP_NUM_THREADS=3 "$S" sds run "$T/fast.sds" --t-end 6 --frames 5 --out "$T/fast-t3" --quiet --set device_loop=true
check "fast, lavapipe on three threads: the same bytes" same_run "$T/fast-d" "$T/fast-t3"
# a discrete GPU's launches: the fused kernels one item an invocation, not a
# loop over their items on a few workgroups as on a CPU device (docs/sds.md,
# "Tails that every subgroup runs")
SESSILE_STAGED=1 "$S" sds run "$T/fast.sds" --t-end 6 --frames 5 --out "$T/fast-st" --quiet --set device_loop=true
check "fast, a discrete GPU's paths and launches: the same bytes" same_run "$T/fast-d" "$T/fast-st"

# the interpreted rules (device_rules = bytecode: rules_morph.comp) as well
run sds run "$T/fast.sds" --t-end 6 --frames 5 --out "$T/fast-b" --quiet --set device_loop=true --set device_rules=bytecode
check "fast, the interpreted rules: the loop on the device completes" rc_is 0
check "fast, the interpreted rules: the same bytes, the same steps" same_run "$T/fast-h" "$T/fast-b"

# a step's dispatches fused where the views fit (docs/sds.md, "Fewer
# dispatches a step"): stable + stable_min, the check with the inverted flags
# and the morphogens' bound, the rules with their first sub-step
"$S" bench sds --no-physics --rock-t 2 --kernels >"$T/kern" 2>&1
check "bench sds --kernels runs" grep -q "kernels of the rock run" "$T/kern"
check "the fused kernels ran (stable_all, step_check, rules_morph)" eval \
  'grep -q "sds/stable_all" "$T/kern" && grep -q "sds/step_check" "$T/kern" && grep -q "sds/rules_morph" "$T/kern"'
check "and not the dispatches they replace (morph_bound, morph_step_batch; stable_tex)" eval \
  '! grep -q "sds/morph_bound" "$T/kern" && ! grep -q "sds/morph_step_batch" "$T/kern" && ! grep -q "sds/stable_tex" "$T/kern"'

run sds run rock --t-end 5 --frames 2 --out "$T/rock-h" --quiet
check "rock: the host-driven loop completes" rc_is 0
run sds run rock --t-end 5 --frames 2 --out "$T/rock-d" --quiet --set device_loop=true
check "rock: the loop on the device completes" rc_is 0
check "rock: the same bytes, the same steps" same_run "$T/rock-h" "$T/rock-d"
# the dispatches the fused kernels replace (device_fuse = never: what a large
# complex takes, docs/sds.md "Fewer dispatches a step")
run sds run rock --t-end 5 --frames 2 --out "$T/rock-n" --quiet --set device_loop=true --set device_fuse=never
check "rock, no fused kernels: the loop on the device completes" rc_is 0
check "rock, no fused kernels: the same bytes, the same steps" same_run "$T/rock-h" "$T/rock-n"

# lasting slivers (docs/sds.md, "The loop on the device"): rock_stripes with
# limbs ten times as fast keeps inverted tets its repairs failed on, which
# the host's loop only counts while their backoff runs; a batch keeps going
# over such a step (the tets in the table, none due, none inverting within
# the step) instead of stopping for the host.  The same bytes, the same
# count of sliver-steps, and the host completes under half as many steps as
# there were sliver-steps (2026-12-03: 696 of 2 311; 1 406 when every step
# with an inverted tet stopped its batch).  Stopped after frame 3 (t = 15:
# 604 sliver-steps before, 1 707 after, the backoff table in the checkpoint)
# and resumed: the same bytes and the same count.
sed 's/^const Delta = .*/const Delta = 0.03/' "$M/rock_stripes.sds" >"$T/slivers.sds"
check "the slivers model was made" grep -q '^const Delta = 0.03' "$T/slivers.sds"
run sds run "$T/slivers.sds" --t-end 20 --frames 4 --out "$T/sl-h" --quiet
check "slivers: the host-driven loop completes" rc_is 0
run sds run "$T/slivers.sds" --t-end 20 --frames 4 --out "$T/sl-d" --quiet --set device_loop=true
check "slivers: the loop on the device completes" rc_is 0
check "slivers: the same bytes, the same steps" same_run "$T/sl-h" "$T/sl-d"
sds_stat() { "$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["sds"][sys.argv[2]])' "$1/manifest.json" "$2"; }
check "slivers: lasting slivers kept (sliver_steps > 100), the same count both loops" eval \
  '[ "$(sds_stat "$T/sl-h" sliver_steps)" -gt 100 ] && [ "$(sds_stat "$T/sl-h" sliver_steps)" = "$(sds_stat "$T/sl-d" sliver_steps)" ]'
check "slivers: the host completed fewer steps than half the sliver-steps" eval \
  '[ $(( $(loop_stat "$T/sl-d" host_completed_steps) * 2 )) -lt "$(sds_stat "$T/sl-d" sliver_steps)" ]'
IR_T_END=20 IR_FRAMES=4 interrupt_resume slivers "$T/slivers.sds" "$T/slr" 3 "$T/sl-h" --set device_loop=true
check "slivers, resumed: the same count of sliver-steps" eval \
  '[ "$(sds_stat "$T/slr" sliver_steps)" = "$(sds_stat "$T/sl-h" sliver_steps)" ]'

# stopped by SIGINT after frame 1 and resumed (sds_runs.sh)
interrupt_resume "device loop" "$T/fast.sds" "$T/b" 1 "$T/fast-h" --set device_loop=true

# a discrete GPU's paths: every blocking transfer is a submission of its own
# unless it rides in a recording (the batch's inputs, results and state)
SESSILE_STAGED=1 "$S" bench sds --no-physics --rock-t 1 >"$T/bench" 2>&1
check "staged: bench sds runs both loops" eval '[ $(grep -c "submissions (" "$T/bench") -eq 2 ]'
check "staged: the loop on the device, under half the host-driven loop's submissions a step" \
  "$PY" -c 'import re,sys; a=[float(x) for x in re.findall(r"submissions \(([0-9.]+) a step\)", open(sys.argv[1]).read())]; print("submissions a step:", a); sys.exit(0 if len(a) == 2 and a[1] < 0.5 * a[0] else 1)' "$T/bench"

# the axial stiffness (docs/sds.md, "Axial stiffness")
sed 's/^morphogen phi diffusion=0.05 decay=0.3/morphogen phi diffusion=0.05 decay=0.3 axis=1/; $a axial_stiffness = 0.3' \
  "$T/fast.sds" >"$T/axial.sds"
check "the axial model was made" eval 'grep -q "axis=1" "$T/axial.sds" && grep -q "^axial_stiffness = 0.3" "$T/axial.sds"'
run sds run "$T/axial.sds" --t-end 6 --frames 5 --out "$T/axial-h" --quiet
check "axial: the host-driven loop completes" rc_is 0
run sds run "$T/axial.sds" --t-end 6 --frames 5 --out "$T/axial-d" --quiet --set device_loop=true
check "axial: the loop on the device completes" rc_is 0
check "axial: the same bytes, the same steps" same_run "$T/axial-h" "$T/axial-d"
check "axial: another run than without it (the last frame differs)" eval \
  '! cmp -s "$T/axial-h/sds/frame_0005.ply" "$T/fast-h/sds/frame_0005.ply"'
interrupt_resume axial "$T/axial.sds" "$T/ab" 2 "$T/axial-h" --set device_loop=true

# refusals
sed 's/ axis=1//' "$T/axial.sds" >"$T/noaxis.sds"
run sds run "$T/noaxis.sds" --t-end 1 --frames 1 --out "$T/na" --quiet
check "axial_stiffness without a morphogen declared axis=1: refused (exit 2), one line naming both, no run folder" eval \
  'rc_is 2 && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "axial_stiffness" "$T/err" && grep -q "axis=1" "$T/err" && test ! -e "$T/na"'
sed 's/^rule r2: tip == 0 \&\& phi > K \* volume -> grow Delta/rule r2: tip == 0 \&\& phi > K * volume -> grow Delta * exp(phi)/' \
  "$T/fast.sds" >"$T/exp.sds"
check "the exp model was made" grep -q 'exp(phi)' "$T/exp.sds"
run sds run "$T/exp.sds" --t-end 1 --frames 1 --out "$T/e" --quiet --set device_loop=true
check "a rule with exp: refused (exit 2) before the run folder exists, naming device_loop and exp" eval \
  'rc_is 2 && grep -q "device_loop" "$T/err" && grep -q "exp" "$T/err" && test ! -e "$T/e"'
run sds run "$T/fast.sds" --t-end 1 --frames 1 --out "$T/v" --quiet --set device_loop=2
check "device_loop=2: refused (exit 2)" rc_is 2
finish
