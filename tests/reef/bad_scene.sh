# Sourced by the reef's shell tests (after tests/common/harness.sh, with $PY
# and $T set): bad_scene SCENE DESCRIPTION JSON_PATH EDIT copies SCENE, edits
# it with the Python statement EDIT on its JSON d, runs `sessile reef` on it
# and checks exit 2, one line naming JSON_PATH, and nothing written.
bad_scene() {
  "$PY" - "$1" "$T/bad.json" "$4" <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[1])); exec(sys.argv[3]); json.dump(d, open(sys.argv[2], "w"))
PYEOF
  run reef "$T/bad.json" --out "$T/never"
  want="$3"
  check "$2: exit 2, one line naming $3, nothing written" eval \
    'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -qF "$want" "$T/err" && [ ! -e "$T/never" ]'
}
