# Shared by the shell tests: a temporary folder removed on exit, and checks
# that print PASS/FAIL lines and the closing "N passed, N failed" line.
# Usage: S=<sessile binary>; . harness.sh; check "what" command...; finish
fails=0 passes=0
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
check() { # description, command...
  local what="$1"; shift
  if "$@"; then echo "PASS $what"; passes=$((passes + 1)); else echo "FAIL $what"; fails=$((fails + 1)); evidence; fi
}
# After a FAIL: what the last `run` left (exit code, the ends of stderr and
# stdout), so that a failure seen once in a CI log can be read there.
evidence() {
  [ -f "$T/rc" ] && echo "  last run's exit code: $(cat "$T/rc")"
  local f
  for f in err out; do
    [ -s "$T/$f" ] && { echo "  last run's std$f, its last lines:"; tail -n 8 "$T/$f" | cut -c1-300 | sed 's/^/    | /'; }
  done
  return 0
}
# Runs sessile with the arguments, keeping stdout, stderr and the exit code in $T.
run() { "$S" "$@" >"$T/out" 2>"$T/err"; echo $? >"$T/rc"; }
rc_is() { [ "$(cat "$T/rc")" = "$1" ]; }
finish() {
  echo "$passes passed, $fails failed"
  [ "$fails" -eq 0 ]
}
