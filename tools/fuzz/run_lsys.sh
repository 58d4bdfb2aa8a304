#!/usr/bin/env bash
# Builds the libFuzzer version of the L-system grammar fuzz target
# (fuzz_lsys.c) with clang, ASan and UBSan, and runs it over corpus_lsys/.
#
#   tools/fuzz/run_lsys.sh [SECONDS] [WORK_DIR]   (default 600 s, /tmp/sessile-fuzz-lsys)
#
# The grammar's sources (lsys_parse.c, lsys_expr.c, lsys_derive.c, turtle.c,
# skeleton.c, status.c) are compiled here with coverage and sanitizers; the
# rest comes from the gcc-built build/libsessile.a (SESSILE_LIB overrides).
# muparser is the system's library (not instrumented).  Crashes, leaks and
# timeouts go to WORK_DIR/crashes; the log is WORK_DIR/fuzz.log.  Exit
# status: 0 when the run found nothing, 1 otherwise.
set -eu
SECONDS_ARG="${1:-600}"
WORK="${2:-/tmp/sessile-fuzz-lsys}"
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
CC="${CC:-clang}"
LIB="${SESSILE_LIB:-$ROOT/build/libsessile.a}"
case "$SECONDS_ARG" in '' | *[!0-9]*) echo "run_lsys.sh: SECONDS must be a whole number" >&2; exit 2 ;; esac
command -v "$CC" >/dev/null || { echo "run_lsys.sh: $CC not found (Debian: apt-get install clang)" >&2; exit 2; }
[ -f "$LIB" ] || { echo "run_lsys.sh: $LIB not found: build sessile first" >&2; exit 2; }
mkdir -p "$WORK/obj" "$WORK/corpus" "$WORK/crashes"
cp -n "$HERE"/corpus_lsys/* "$WORK/corpus/" 2>/dev/null || true

SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
CFLAGS="-std=c17 -O1 -g -D_POSIX_C_SOURCE=200809L -I$ROOT/host/include -I$ROOT/host $SAN"
"$CC" --version | head -1
objs=()
for src in host/coral/lsys_parse.c host/coral/lsys_expr.c host/coral/lsys_derive.c host/coral/turtle.c \
  host/mesh/skeleton.c host/status.c; do
  o="$WORK/obj/$(basename "$src" .c).o"
  "$CC" $CFLAGS -fsanitize=fuzzer-no-link -c "$ROOT/$src" -o "$o"
  objs+=("$o")
done
"$CC" $CFLAGS -fsanitize=fuzzer -c "$HERE/fuzz_lsys.c" -o "$WORK/obj/fuzz_lsys.o"
# shellcheck disable=SC2046
"$CC" $SAN -fsanitize=fuzzer -o "$WORK/fuzz_lsys" "$WORK/obj/fuzz_lsys.o" "${objs[@]}" "$LIB" \
  $(pkg-config --libs muparser OpenEXR libcjson vulkan zlib) -ltet -lgomp -lstdc++ -lm -lpthread

# A dictionary: directives, syntax, turtle symbols, muparser words.
DICT="$WORK/lsys.dict"
printf '%s\n' '"axiom:"' '"iterations:"' '"angle:"' '"width_factor:"' '"ignore:"' '"define "' '"homomorphism:"' '"->"' \
  '"-(0.5)->"' '"<"' '">"' '":"' '"["' '"]"' '"%"' '"#"' '"!"' '"F("' '"uniform("' '"sqrt("' '"?"' \
  '"&&"' '"=="' '"1e308"' '"nan"' '"inf"' | awk '{print "kw" NR "=" $0}' >"$DICT"

echo "fuzzing for $SECONDS_ARG s; log: $WORK/fuzz.log, crashes: $WORK/crashes/"
rc=0
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
  "$WORK/fuzz_lsys" -max_total_time="$SECONDS_ARG" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -dict="$DICT" -artifact_prefix="$WORK/crashes/" -print_final_stats=1 \
  "$WORK/corpus" >"$WORK/fuzz.log" 2>&1 || rc=$?
grep -E '^#[0-9]+[[:space:]]+INITED' "$WORK/fuzz.log" | head -1
grep -E '^#[0-9]+[[:space:]]' "$WORK/fuzz.log" | tail -1
grep -E '^Done|stat::|SUMMARY|ERROR' "$WORK/fuzz.log" | tail -12
n=$(find "$WORK/crashes" -type f | wc -l)
echo "exit status $rc; $n crash/leak/timeout file(s) in $WORK/crashes"
[ "$rc" -eq 0 ] && [ "$n" -eq 0 ]
