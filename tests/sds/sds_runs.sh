# Helpers for the SDS tests that compare whole runs (sourced after
# harness.sh; S, T, PY, check, run and rc_is are the harness's).

# every file under sds/ the same bytes but the step log, which must be equal but for ms
same_run() { # dir_a dir_b
  for f in $(cd "$1/sds" && ls); do
    [ "$f" = steps.csv ] && continue
    cmp -s "$1/sds/$f" "$2/sds/$f" || { echo "differs: $f"; return 1; }
  done
  [ "$(cd "$1/sds" && ls | wc -l)" -eq "$(cd "$2/sds" && ls | wc -l)" ] || return 1
  "$PY" - "$1/sds/steps.csv" "$2/sds/steps.csv" <<'PYEOF'
import csv, sys
def rows(p):
    with open(p, newline="") as f:
        return [{k: v for k, v in r.items() if k != "ms"} for r in csv.DictReader(f)]
a, b = rows(sys.argv[1]), rows(sys.argv[2])
div = sum(int(r["divisions"]) for r in a)
inv = sum(int(r["inversions"]) for r in a)
print("steps", len(a), len(b), "divisions", div, "inversions", inv)
sys.exit(0 if a == b and len(a) > 0 else 1)
PYEOF
}

# stopped by SIGINT after frame N, resumed: the bytes of the uninterrupted run
# (to t = IR_T_END with IR_FRAMES frames: 6 and 5 unless set, as the reference's)
interrupt_resume() { # label model dir frame reference [options of the run...]
  local label="$1" model="$2" dir="$3" frame="$4" ref="$5"
  shift 5
  "$S" sds run "$model" --t-end "${IR_T_END:-6}" --frames "${IR_FRAMES:-5}" --quiet "$@" --out "$dir" >"$T/out" 2>"$T/err" &
  local pid=$!
  for _ in $(seq 1 3000); do [ -e "$dir/sds/frame_000$frame.ply" ] && break; sleep 0.02; done
  kill -INT $pid 2>/dev/null
  { wait $pid; } 2>/dev/null
  echo $? >"$T/rc"
  check "$label, SIGINT after frame $frame: exit 130 (or it finished first: 0)" eval 'rc_is 130 || rc_is 0'
  run sds run --resume "$dir" --quiet
  check "... resumed: completes" rc_is 0
  check "... the bytes of the uninterrupted runs" same_run "$ref" "$dir"
}

# the extents along x, y and z of the vertices of a PLY frame (sessile's:
# float, double, uchar or int vertex properties), one line "X Y Z"
ply_extents() { # file
  "$PY" - "$1" <<'PYEOF'
import sys
import numpy as np
d = open(sys.argv[1], "rb").read()
i = d.index(b"end_header\n") + 11
head = d[:i].decode().splitlines()
n = int(next(l for l in head if l.startswith("element vertex")).split()[2])
props = []
for l in head:
    if l.startswith("element face"):
        break
    if l.startswith("property"):
        props.append(l.split())
types = {"float": "<f4", "double": "<f8", "uchar": "u1", "int": "<i4"}
v = np.frombuffer(d[i:], dtype=np.dtype([(p[2], types[p[1]]) for p in props]), count=n)
print("%.6f %.6f %.6f" % (np.ptp(v["x"]), np.ptp(v["y"]), np.ptp(v["z"])))
PYEOF
}
