#!/usr/bin/env bash
# Runs a bundle of tools/gpu/bundle.sh on a machine with a GPU, from the
# root of a copy of the source tree (the shell tests and tools read it):
# the device list, a short run under the validation layer, the Figure 9
# bench (both loops, one process), then the SDS and GPU tests under the
# validation layer, several at a time, each with a time limit.  Writes
# machine.txt, bench.txt, summary.txt (one line a test: rc and seconds) and
# logs.tgz to RESULTS_DIR.  It unpacks the bundle's .deb files into / (the
# Vulkan loader and the validation layer), so run it as root on a machine
# that is given back afterwards, never on one you keep.
#
# usage: tools/gpu/check.sh BUNDLE_DIR RESULTS_DIR
# environment:
#   JOBS         tests at a time (default: processors - 4, at least 1)
#   TEST_LIMIT   seconds a test may take (default 200)
#   TESTS_LIMIT  seconds for all the tests together (default 280)
#   BENCH_T      simulated time of the bench's rock runs (default 400; 0 skips)
set -u
case "${1:-}" in -h|--help) sed -n 2,17p "$0" | sed 's/^# \{0,1\}//'; exit 0;; esac
[ $# -eq 2 ] || { echo "usage: tools/gpu/check.sh BUNDLE_DIR RESULTS_DIR" >&2; exit 2; }
BUNDLE=$(cd "$1" && pwd) || exit 2
RES=$2
ROOT=$PWD
[ -f "$ROOT/tests/sds/test_sds_frames.sh" ] || { echo "check.sh: run it from the source tree's root" >&2; exit 2; }
if [ -e "$RES" ] && [ -n "$(ls -A "$RES")" ]; then
  echo "check.sh: $RES is not empty (an earlier check's results stay as they are)" >&2; exit 2
fi
mkdir -p "$RES" && RES=$(cd "$RES" && pwd)
JOBS=${JOBS:-$(( $(nproc) > 5 ? $(nproc) - 4 : 1 ))}
TEST_LIMIT=${TEST_LIMIT:-200}
TESTS_LIMIT=${TESTS_LIMIT:-280}
BENCH_T=${BENCH_T:-400}
T0=$(date +%s)
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
for f in "$BUNDLE"/debs/*.deb; do dpkg -x "$f" /; done
ldconfig
tar xJf "$BUNDLE/bin.tar.xz" -C "$W" && tar xJf "$BUNDLE/lib.tar.xz" -C "$W" || exit 1
export LD_LIBRARY_PATH=$W/lib VK_LAYER_PATH=/usr/share/vulkan/explicit_layer.d XDG_CACHE_HOME=$W/cache
B=$W/bin
S=$B/sessile
# The tests call /usr/bin/python3 and need numpy: where it lacks numpy and
# another Python of the same version has it, lend its packages.
if ! /usr/bin/python3 -c 'import numpy' 2>/dev/null; then
  for p in $(command -v -a python3) /opt/*/.venv/bin/python3; do
    [ -x "$p" ] || continue
    if "$p" -c 'import numpy' 2>/dev/null &&
       [ "$("$p" -c 'import sys; print(sys.version_info[:2])')" = "$(/usr/bin/python3 -c 'import sys; print(sys.version_info[:2])')" ]; then
      PYTHONPATH=$("$p" -c 'import numpy, os; print(os.path.dirname(os.path.dirname(numpy.__file__)))')
      export PYTHONPATH
      break
    fi
  done
fi
{ echo "bundle of $(cat "$BUNDLE/commit" 2>/dev/null)"; uname -srm; nproc; uptime
  /usr/bin/python3 -c 'import numpy; print("numpy", numpy.__version__)' 2>&1
  command -v nvidia-smi > /dev/null && nvidia-smi --query-gpu=name,driver_version --format=csv
} 2>&1 | tee "$RES/machine.txt"
# Where the loader finds no driver by its own search, NVIDIA's ICD by name.
if ! "$S" devices 2>&1 | grep -q "type: \(discrete\|integrated\)"; then
  for icd in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json; do
    [ -f "$icd" ] && export VK_DRIVER_FILES=$icd && break
  done
fi
"$S" devices 2>&1 | tee -a "$RES/machine.txt"
"$S" --validation sds run rock --t-end 10 --set device_loop=true --out "$W/val" 2>&1 | tail -2 | tee -a "$RES/machine.txt"

if [ "$BENCH_T" != 0 ]; then
  timeout 300 "$S" bench sds --no-physics --rock-t "$BENCH_T" > "$RES/bench.txt" 2>&1
  cat "$RES/bench.txt"
fi

mkdir -p "$W/logs"
export SESSILE_VALIDATION=1 W TEST_LIMIT
run_one() {  # NAME COMMAND...
  local n=$1; shift
  local t; t=$(date +%s)
  timeout "$TEST_LIMIT" "$@" > "$W/logs/$n.log" 2>&1; local rc=$?
  echo "$n rc=$rc $(( $(date +%s) - t ))s" >> "$W/logs/summary.txt"
}
export -f run_one
{
  for t in "$B"/test_*; do  # the test binaries bundle.sh packed
    echo "$(basename "$t") $t"
  done
  for t in test_sds_collide test_sds_forces test_sds_dynamics test_sds_lists test_morph_gpu; do
    echo "${t}_fp32 $B/$t --fp32"
  done
  echo "fuzz_rules_device $B/fuzz_rules_device -n 3000 -t 120 -s 3 $ROOT/tools/fuzz/corpus_sds"
  for t in device_loop frames resume extension models params cli blowup oriented limb figures; do
    echo "sds_$t $ROOT/tests/sds/test_sds_$t.sh $S"
  done
} | timeout "$TESTS_LIMIT" xargs -P "$JOBS" -L 1 bash -c 'run_one "$@"' _
for l in "$W"/logs/*.log; do
  n=$(basename "$l" .log)
  grep -q "^$n " "$W/logs/summary.txt" 2>/dev/null || echo "$n unfinished" >> "$W/logs/summary.txt"
done
sort "$W/logs/summary.txt" | tee "$RES/summary.txt"
tar czf "$RES/logs.tgz" -C "$W" logs
echo "check.sh: $(grep -c ' rc=0 ' "$RES/summary.txt") of $(wc -l < "$RES/summary.txt") tests passed, $(( $(date +%s) - T0 )) s" | tee -a "$RES/machine.txt"
