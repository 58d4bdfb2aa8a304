#!/usr/bin/env bash
# Builds the libFuzzer version of the parameter-parser fuzz target
# (fuzz_params.c) with clang, ASan and UBSan, and runs it over the corpus.
#
#   tools/fuzz/run.sh [SECONDS] [WORK_DIR]      (default 600 s, /tmp/sessile-fuzz)
#
# The parser's sources (param_table.c, the two tables, status.c) are compiled
# here with coverage and sanitizer instrumentation; whatever else they pull in
# (the sphere generator's I/O, the run directory) comes from the gcc-built,
# sanitizer-free build/libsessile.a (SESSILE_LIB overrides; build it first:
# cmake --build build --target sessile_lib).  Crashes, leaks and timeouts go
# to WORK_DIR/crashes; the corpus grows in WORK_DIR/corpus (seeded from
# tools/fuzz/corpus, which is never written); the log is WORK_DIR/fuzz.log.
# Exit status: 0 when the run found nothing, 1 otherwise.
set -eu
SECONDS_ARG="${1:-600}"
WORK="${2:-/tmp/sessile-fuzz}"
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
CC="${CC:-clang}"
LIB="${SESSILE_LIB:-$ROOT/build/libsessile.a}"
case "$SECONDS_ARG" in '' | *[!0-9]*) echo "run.sh: SECONDS must be a whole number" >&2; exit 2 ;; esac
command -v "$CC" >/dev/null || { echo "run.sh: $CC not found (Debian: apt-get install clang)" >&2; exit 2; }
[ -f "$LIB" ] || { echo "run.sh: $LIB not found: build sessile first" >&2; exit 2; }
mkdir -p "$WORK/obj" "$WORK/corpus" "$WORK/crashes"
cp -n "$HERE"/corpus/* "$WORK/corpus/" 2>/dev/null || true

SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
CFLAGS="-std=c17 -O1 -g -D_POSIX_C_SOURCE=200809L -I$ROOT/host/include -I$ROOT/host $SAN"
"$CC" --version | head -1
objs=()
for src in host/run/param_table.c host/growth/params.c host/sphere/sphere.c host/status.c; do
  o="$WORK/obj/$(basename "$src" .c).o"
  "$CC" $CFLAGS -fsanitize=fuzzer-no-link -c "$ROOT/$src" -o "$o"
  objs+=("$o")
done
"$CC" $CFLAGS -fsanitize=fuzzer -c "$HERE/fuzz_params.c" -o "$WORK/obj/fuzz_params.o"
# libsessile.a supplies the rest; the objects above come first, so its own
# copies of them are never pulled in.  (pkg-config's words split on purpose.)
# shellcheck disable=SC2046
"$CC" $SAN -fsanitize=fuzzer -o "$WORK/fuzz_params" "$WORK/obj/fuzz_params.o" "${objs[@]}" "$LIB" \
  $(pkg-config --libs OpenEXR libcjson vulkan zlib) -ltet -lgomp -lstdc++ -lm -lpthread

# A dictionary: every parameter name (both tables), enum names, JSON tokens.
DICT="$WORK/params.dict"
{
  sed -n 's/^ *X(\([a-z_0-9]*\),.*/"\1"/p' "$ROOT/host/include/sessile/growth/grow_params.h"
  sed -n 's/^ *{"\([a-z_0-9]*\)", SESSILE_PT_.*/"\1"/p' "$ROOT/host/sphere/sphere.c"
  printf '"%s"\n' radiate halichondrid immersed conforming true false null nan inf 1e999 0x1p3 \
    "{" "}" "[" "]" ":" "," "=" "\\\"" "-1" "2147483648" "18446744073709551616"
} | awk '{print "kw" NR "=" $0}' >"$DICT"

echo "fuzzing for $SECONDS_ARG s; log: $WORK/fuzz.log, crashes: $WORK/crashes/"
rc=0
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
  "$WORK/fuzz_params" -max_total_time="$SECONDS_ARG" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -dict="$DICT" -artifact_prefix="$WORK/crashes/" -print_final_stats=1 \
  "$WORK/corpus" >"$WORK/fuzz.log" 2>&1 || rc=$?
grep -E '^#[0-9]+[[:space:]]+INITED' "$WORK/fuzz.log" | head -1
grep -E '^#[0-9]+[[:space:]]' "$WORK/fuzz.log" | tail -1
grep -E '^Done|stat::|SUMMARY|ERROR' "$WORK/fuzz.log" | tail -12
n=$(find "$WORK/crashes" -type f | wc -l)
echo "exit status $rc; $n crash/leak/timeout file(s) in $WORK/crashes"
[ "$rc" -eq 0 ] && [ "$n" -eq 0 ]
