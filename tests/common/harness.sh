# Shared by the shell tests: a temporary folder removed on exit, and checks
# that print PASS/FAIL lines and the closing "N passed, N failed" line.
# Usage: S=<sessile binary>; . harness.sh; check "what" command...; finish
fails=0 passes=0
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
check() { # description, command...
  local what="$1"; shift
  if "$@"; then echo "PASS $what"; passes=$((passes + 1)); else echo "FAIL $what"; fails=$((fails + 1)); fi
}
# Runs sessile with the arguments, keeping stdout, stderr and the exit code in $T.
run() { "$S" "$@" >"$T/out" 2>"$T/err"; echo $? >"$T/rc"; }
rc_is() { [ "$(cat "$T/rc")" = "$1" ]; }
finish() {
  echo "$passes passed, $fails failed"
  [ "$fails" -eq 0 ]
}
