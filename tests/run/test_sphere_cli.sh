#!/usr/bin/env bash
# `sessile sphere`, the smallest generator, as the run framework's own test
# from the command line: parameters (--print-config, --set, --config),
# manifest (state, pid, host, command, version, times, files, config),
# records, lock (a folder held by another process is refused with exit 2),
# --force, and resume: 4 iterations then --resume to 10 equals 10 at once,
# byte for byte, the final-only snapshot at 4 removed.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
sums() { (cd "$1" && find sphere -type f | LC_ALL=C sort | xargs sha256sum); }
PY=/usr/bin/python3

run sphere --set level=2 --set noise=0.05 --print-config
check "--print-config shows the table with --set applied" eval \
  'rc_is 0 && grep -q "^level *2 " "$T/out" && grep -q "^noise *0.05 " "$T/out" && grep -q "^radius *1 *cm *(0, 1e+06]" "$T/out"'
run sphere --seed 11 --iterations 10 --every 3 --out "$T/a" --quiet
check "a 10-iteration run completes" rc_is 0
check "snapshots every 3 and at the last, and the final mesh" eval \
  'for i in 0003 0006 0009 0010; do test -s "$T/a/sphere/iter_$i.ply" || exit 1; done; test -s "$T/a/sphere/final.ply"'
check "the manifest: state, pid, host, command, version, times, files, config; 10 records" \
  "$PY" - "$T/a" <<'PYEOF'
import json, sys
d = sys.argv[1]; m = json.load(open(d + "/manifest.json"))
recs = [json.loads(l) for l in open(d + "/records.jsonl")]
ok = m["state"] == "completed" and m["generator"] == "sphere" and isinstance(m["pid"], (int, float))
ok = ok and m["host"] and m["command"][1:3] == ["sphere", "--seed"] and m["command"][0].endswith("sessile") and m["version"]
ok = ok and m["start_time"].endswith("Z") and m["end_time"].endswith("Z")
ok = ok and "sphere/final.ply" in m["files"] and m["config"]["seed"] == "11" and m["checkpoint"]["iteration"] == 10
ok = ok and [r["iteration"] for r in recs] == list(range(1, 11))
print(m["state"], m["files"], len(recs))
sys.exit(0 if ok else 1)
PYEOF

run sphere --seed 11 --iterations 4 --every 3 --out "$T/b" --quiet
run sphere --resume "$T/b" --iterations 10 --quiet
check "--resume continues to 10 iterations" rc_is 0
check "... byte-identical to the uninterrupted run" eval 'sums "$T/a" | sed "s#$T/a##" >"$T/a.sum"; sums "$T/b" >"$T/b.sum"; cmp -s "$T/a.sum" "$T/b.sum"'
check "... the final-only snapshot at 4 is gone" test ! -e "$T/b/sphere/iter_0004.ply"

printf '{"noise": 0.1}\n' >"$T/c1.json"
printf '{"noise": 0.2, "level": 2}\n' >"$T/c2.json"
run sphere --config "$T/c1.json" --config "$T/c2.json" --set level=1 --print-config
check "--config files merge in order, then --set" eval 'rc_is 0 && grep -q "^noise *0.2 " "$T/out" && grep -q "^level *1 " "$T/out"'

if command -v flock >/dev/null; then
  mkdir "$T/held"
  # The holder says when it has the lock (a fixed pause may end before a
  # loaded machine has run flock) and keeps it until killed below (the
  # subshell becomes the sleep: killing it frees the lock).
  (exec 9<"$T/held" && flock -x 9 && : >"$T/held.locked" && exec sleep 300) >/dev/null 2>&1 &
  holder=$!
  for _ in $(seq 1 1200); do [ -e "$T/held.locked" ] && break; sleep 0.05; done
  check "the holder has the folder's lock" test -e "$T/held.locked"
  run sphere --out "$T/held" --quiet
  check "a folder locked by another process is refused (exit 2, 'in use')" eval 'rc_is 2 && grep -q "in use" "$T/err"'
  check "... and nothing is written into it" eval '[ -z "$(ls -A "$T/held")" ]'
  kill $holder 2>/dev/null; wait $holder 2>/dev/null
fi
run sphere --out "$T/a" --quiet
check "a folder holding a run is refused without --force" rc_is 2
run sphere --out "$T/a" --force --iterations 2 --quiet
check "--force replaces it: the old run's snapshots are gone" eval \
  'rc_is 0 && test ! -e "$T/a/sphere/iter_0009.ply" && test -s "$T/a/sphere/iter_0002.ply"'
finish
