#!/usr/bin/env bash
# The command line as a user meets it: every --help answers, bad usage gives
# one line on stderr and exit 2, `devices` lists what matters, a tiny
# `bench la` runs, and nothing says a word from the validation layer.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"

one_line_error() { [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "error" "$T/err" && [ ! -s "$T/out" ]; }
no_validation() { ! grep -qi "validation \(error\|warning\)" "$T/err"; }

for args in "--help" "help" "devices --help" "bench --help" "bench la --help" "bench coral --help" "bench sponge --help" \
            "coral --help" "coral lsystem --help" "coral venation --help" "sponge --help" "sponge particles --help" \
            "sds --help" "sds run --help" "bench sds --help"; do
  run $args
  check "'sessile $args' exits 0 with usage text" eval 'rc_is 0 && grep -q "usage: sessile" "$T/out"'
done
run --version
check "'sessile --version' prints the version and the commit" eval \
  'rc_is 0 && [ "$(wc -l <"$T/out")" -eq 1 ] && grep -qE "^sessile [0-9]+\.[0-9]+\.[0-9]+ \(commit [0-9A-Za-z._-]+\)$" "$T/out"'
version_line=$(cat "$T/out")
commit=$(sed -n 's/.*(commit \(.*\))$/\1/p' "$T/out")
# the commit is this checkout's (git describe: a hash, maybe after a tag and
# before -dirty), or "unknown" where the source holds no .git
src="$(cd "$(dirname "$0")/../.." && pwd)"
if [ -e "$src/.git" ] && command -v git >/dev/null; then
  hash=$(echo "$commit" | sed -E 's/-dirty$//; s/.*-g([0-9a-f]+)$/\1/')
  check "the version's commit '$commit' is a commit of this repository" \
    git -C "$src" cat-file -e "$hash^{commit}"
else
  check "outside a git checkout the commit is 'unknown'" test "$commit" = unknown
fi

# every command and subcommand answers -h, --help and --version with exit 0:
# the fixed list, and whatever `sessile --help` lists as commands and generators
run --help
listed=$(sed -n '/^commands:/,/^$/p' "$T/out" | sed -n 's/^  \([a-z]\+\) .*/\1/p'
         sed -n '/^generators/,/^$/p' "$T/out" | sed 1d | cut -c3-18 | sed 's/ *$//' | grep .)
all=$(printf '%s\n' "help" "version" "devices" "render" "bench" "bench la" "bench grow" "bench fluid" \
        "bench coral" "bench sponge" "bench sds" "bench render" "coral" "coral lsystem" "coral venation" \
        "sponge" "sponge particles" "sds" "sds run" "sds models" "grow" "sphere" "$listed" | sort -u)
while IFS= read -r c; do
  for h in --help -h; do
    run $c $h
    check "'sessile $c $h' exits 0 with usage text" eval 'rc_is 0 && grep -q "usage: sessile" "$T/out" && [ ! -s "$T/err" ]'
  done
  run $c --version
  check "'sessile $c --version' prints the version" eval 'rc_is 0 && [ "$(cat "$T/out")" = "$version_line" ] && [ ! -s "$T/err" ]'
done <<<"$all"
run -h
check "'sessile -h' exits 0 with usage text" eval 'rc_is 0 && grep -q "usage: sessile" "$T/out"'
run --device=0 devices
check "'sessile --device=0 devices' works" eval 'rc_is 0 && grep -q "^\* \[0\]" "$T/out"'

# --opt=value and --opt value give the same run, byte for byte (all but the
# manifest and the records, which hold times and the command line, and the
# lock, which holds the pid); the
# manifest records the version and commit of --version
"$S" sphere --iterations 3 --every 2 --seed 5 --out "$T/sp" --quiet --no-preview >/dev/null 2>&1
"$S" sphere --iterations=3 --every=2 --seed=5 --out="$T/se" --quiet --no-preview >/dev/null 2>"$T/err"
same=1
files=$(cd "$T/sp" && find . -type f ! -name manifest.json ! -name records.jsonl ! -name .sessile.lock | sort)
[ -n "$files" ] && [ "$files" = "$(cd "$T/se" && find . -type f ! -name manifest.json ! -name records.jsonl ! -name .sessile.lock | sort)" ] || same=0
for f in $files; do cmp -s "$T/sp/$f" "$T/se/$f" || same=0; done
check "'sphere --iterations=3 --seed=5 --out=DIR' writes the bytes of '--iterations 3 --seed 5 --out DIR'" \
  eval '[ "$same" = 1 ] && [ ! -s "$T/err" ]'
check "manifest.json records the version and the commit" python3 -c '
import json, sys
m = json.load(open(sys.argv[1]))
line = "sessile %s (commit %s)" % (m["version"], m["commit"])
sys.exit(0 if line == sys.argv[2] and m["command"][1:3] == ["sphere", "--iterations=3"] else 1)' "$T/se/manifest.json" "$version_line"

for args in "" "--bogus" "frobnicate" "bench" "bench nope" "bench la --size 1" "bench la --size x" \
            "bench la --repeat 0" "bench la --mg 4" "bench la --wat" "devices --wat" "--precision 16 devices" \
            "--device" "--device 99 devices" "--device no-such-gpu bench la --size 4" \
            "coral" "coral reef" "sponge" "sponge accretive" "bench coral nope" "bench coral particles" "bench sponge nope" "sds" "sds grow" "sds run" "bench sds --x" \
            "bench sds --kernels --rock-t 0" "bench sds --repeat 0" "bench sds --repeat 10" \
            "bench sds --rock-t 0 --repeat 2" "bench sds --repeat 2 --repeat 2" "bench fluid --mg-precision 48" "bench fluid --mg-precision 16" \
            "bench fluid --set fluid_mg_precision=40"; do
  run $args
  check "'sessile $args' gives one error line and exit 2" eval 'rc_is 2 && one_line_error'
done

run devices
check "'sessile devices' lists a chosen device with its limits" eval \
  'rc_is 0 && grep -q "^\* \[0\]" "$T/out" && grep -q maxStorageBufferRange "$T/out" && grep -q "fp64" "$T/out" && grep -q "subgroup size" "$T/out"'
run --device 0 devices
check "'sessile --device 0 devices' works" eval 'rc_is 0'

run --validation bench la --size 8 --repeat 2 --mg 1
check "'sessile bench la --size 8' prints kernels, solves and ratios" eval \
  'rc_is 0 && grep -q "^spmv csr P1-tet 8^3" "$T/out" && grep -q "^pcg 7-point 8^3" "$T/out" && grep -q "C/gpu" "$T/out"'
check "'sessile bench la --mg 1' compares multigrid and Jacobi-PCG on 33x33x25" eval \
  'rc_is 0 && grep -q "^33x33x25 " "$T/out" && grep -q "mg/jacobi" "$T/out" && grep -q "load average" "$T/out"'
check "bench under the validation layer is silent" no_validation

run --validation bench sds --no-physics --rock-t 0.05 --kernels
check "'sessile bench sds --rock-t 0.05 --kernels' prints the rock run's kernels and their sum" eval \
  'rc_is 0 && grep -q "^sds rock (Figure 9)" "$T/out" && grep -q "^sds/gather" "$T/out" && grep -q "^all kernels" "$T/out"'
check "bench sds --kernels under the validation layer is silent" no_validation
# A validation message fails the command (the shell tests run under the layer
# and need not read stderr): the layer's best-practices warnings as a source.
VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_BEST_PRACTICES_EXT run --validation bench la --size 8 --repeat 1 --mg 0
check "a validation message fails the command: exit 1, its messages and their count on stderr" eval \
  'rc_is 1 && grep -q "vulkan validation warning" "$T/err" && grep -q "^sessile: error: the Vulkan validation layer printed [0-9]* messages" "$T/err" && grep -q "^spmv csr" "$T/out"'
# the processor beside the figures: /proc/cpuinfo's first model name and
# family, read here by another route (awk), and the CPUs online (getconf)
cpu_named() {
  local name fam
  name=$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)
  fam=$(awk -F': ' '/^cpu family/ {print $2; exit}' /proc/cpuinfo)
  [ -n "$name" ] && [ -n "$fam" ] &&
    grep -qxF "machine: $name (cpu family $fam, model $(awk -F': ' '/^model\t/ {print $2; exit}' /proc/cpuinfo)), $(getconf _NPROCESSORS_ONLN) CPUs online" "$T/out"
}
check "'sessile bench sds' names the processor it ran on" cpu_named
# --repeat: the runs alternate, and the summary is over all of them (the
# rock runs are deterministic, so a repeat that took other steps is a bug)
run bench sds --no-physics --rock-t 0.05 --repeat 2
check "'sessile bench sds --repeat 2' runs each loop twice, then their medians and minima" eval \
  'rc_is 0 && [ $(grep -c "^sds rock (Figure 9)" "$T/out") -eq 4 ] && grep -q "^repeat 2 of 2" "$T/out" &&
   grep -q "^over 2 repeats" "$T/out" && grep -q "the loop on the device, to t = .*: median .* minimum" "$T/out" &&
   grep -q "EXTRAPOLATED to t = 400" "$T/out" && grep -q "median ratio" "$T/out"'
check "bench sds --repeat: every repeat took the same steps to the same cells" \
  grep -q "every repeat took the same steps to the same cells" "$T/out"
# bench fluid's rounds: the same deterministic solves each round, the table
# their medians with the range (loose tolerances: one Newton step a solve,
# 5 s instead of the paper's tolerances' 12; the rounds are what is tested)
run bench fluid --no-compare --repeat 2 --set fluid_newton_rtol=0.05 --set fluid_ksp_rtol=1e-3
check "'sessile bench fluid --repeat 2' runs two rounds of the same steps and gives medians" eval \
  'rc_is 0 && grep -q "^2 rounds, alternated" "$T/out" && grep -q "^round 2, mg: from rest" "$T/out" &&
   grep -q "seconds the median over the rounds" "$T/out" && grep -Eq "^  mg +rest .* [0-9.]+-[0-9.]+$" "$T/out" &&
   ! grep -q "different steps" "$T/out"'
run --precision=32 bench la --size=8 --repeat=1 --no-solvers
check "'--precision=32 bench la --size=8' runs the fp32 kernels" eval 'rc_is 0 && grep -q "fp32" "$T/out"'

# a benchmark stopped by a signal removes its temporary folder and exits 143
for b in "render --runs 20" "sds --no-physics --rock-t 400"; do
  mkdir -p "$T/tmp"
  TMPDIR="$T/tmp" "$S" bench $b >"$T/out" 2>"$T/err" &
  pid=$!
  sleep 3
  kill -TERM "$pid"
  wait "$pid"
  echo $? >"$T/rc"
  check "'bench $b' stopped by SIGTERM: exit 143, no temporary folder left" eval \
    'rc_is 143 && [ -z "$(ls -A "$T/tmp")" ]'
  rm -rf "$T/tmp"
done

# under an address-space limit too small for a Vulkan driver (lavapipe died
# by SIGSEGV inside device creation at ulimit -v 400000): one line, exit 1
if [ -z "${SESSILE_TEST_SANITIZED:-}" ]; then
  "$S" sphere --iterations 1 --out "$T/ul" --quiet --no-preview >/dev/null 2>&1
  (ulimit -v 400000; "$S" render "$T/ul/sphere/final.ply" -o "$T/ul.png" >"$T/out" 2>"$T/err"; echo $? >"$T/rc")
  check "render under ulimit -v 400000: exit 1, one line naming the limit, no picture" eval \
    'rc_is 1 && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "ulimit -v" "$T/err" && [ ! -e "$T/ul.png" ]'
else # not counted: ASan's shadow memory cannot live under any ulimit -v
  echo "note: the ulimit -v check is not run in the sanitizer build (ASan needs an unlimited address space)"
fi

finish
