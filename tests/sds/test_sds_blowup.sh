#!/usr/bin/env bash
# Blow-ups end `sessile sds run` with exit 3, one line on stderr (what, when,
# what to try), the frames before it kept and readable, none after it, and
# the manifest's sds.status "blow-up" with the time and step.  Two models
# that really blow up, nothing injected:
#  - the limb model under gravity 1e9 (free fall at 1e9 u/s^2): the step
#    control halves dt until a cell moves no more than 0.05 radii a step, and
#    the speed grows until that needs a step below dt_min (1e-7 s) near
#    t = 6e-5 s, after frame 2 of 40 (every 2.5e-5 s);
#  - a growth rule of dr/dt = 1e300 from t = 0.55: the radius reaches 1e298
#    in one step and the mass 4/3 pi r^3 overflows to inf.  Frame 5 is the
#    first step at or past t = 0.5 (frames do not cut steps), so the rule
#    starts a step or more after it, not at 0.5 itself.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
LIMB="$(dirname "$0")/../../host/sds/models/limb.sds"
one_line() { [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "error" "$T/err" && [ ! -s "$T/out" ]; }

# the kept frames: each listed in the records and the series, each PLY read
# back whole (header, vertex and face counts, the bytes they take), none
# past the last good one; the manifest's blow-up after the last frame's time
kept() { # dir cause
  "$PY" - "$1" "$2" <<'PYEOF'
import json, os, re, struct, sys
d, cause = sys.argv[1], sys.argv[2]
m = json.load(open(d + "/manifest.json"))
recs = [json.loads(l) for l in open(d + "/records.jsonl")]
b = m["sds"].get("blowup", {})
n = len(recs)
ok = m["state"] == "failed" and m["sds"]["status"] == "blow-up" and re.search(cause, b.get("cause", ""))
ok = ok and [r["frame"] for r in recs] == list(range(n)) and n >= 2 and b["last_good_frame"] == n - 1
ok = ok and b["time"] >= recs[-1]["time"] and b["step"] > 0 and "blow-up" in m["error"]
files = sorted(f for f in os.listdir(d + "/sds") if f.startswith("frame_"))
ok = ok and files == sorted(["frame_%04d.%s" % (i, e) for i in range(n) for e in ("ply", "vtp", "vtu")])
ok = ok and not os.path.exists(d + "/sds/final.ply")
pvd = open(d + "/sds/series.pvd").read()
ok = ok and pvd.count("<DataSet") == n and ("frame_%04d.vtu" % (n - 1)) in pvd
for i in range(n):
    raw = open(d + "/sds/frame_%04d.ply" % i, "rb").read()
    head, body = raw.split(b"end_header\n", 1)
    h = head.decode().splitlines()
    nv = int([l for l in h if l.startswith("element vertex")][0].split()[2])
    nf = int([l for l in h if l.startswith("element face")][0].split()[2])
    props = [l for l in h if l.startswith("property float")]
    rgb = [l for l in h if l.startswith("property uchar")]  # the colour view: red green blue
    size = nv * (4 * len(props) + len(rgb)) + nf * 13
    xs = [] if rgb else struct.unpack_from("<%df" % (nv * len(props)), body)
    if rgb:  # floats then 3 bytes per vertex
        rec = struct.Struct("<%df%dB" % (len(props), len(rgb)))
        xs = [x for k in range(nv) for x in rec.unpack_from(body, k * rec.size)[:len(props)]]
    ok = ok and h[0] == "ply" and nv > 0 and nf > 0 and len(body) == size and all(x == x and abs(x) < 1e30 for x in xs)
print("frames", n, "blow-up at t", b.get("time"), "step", b.get("step"), ":", b.get("cause"))
sys.exit(0 if ok else 1)
PYEOF
}

sed 's/^gravity = .*/gravity = 1e9/' "$LIMB" >"$T/fall.sds"
run sds run "$T/fall.sds" --t-end 1e-3 --frames 40 --out "$T/a" --quiet
check "gravity 1e9: exit 3 and one line: blow-up, step, time, the last good frame, what to try" eval \
  'rc_is 3 && one_line && grep -q "blow-up in step [0-9]* from t = " "$T/err" && grep -q "dt_min" "$T/err" && grep -q "last good frame is frame_" "$T/err" && grep -q "try weaker forces" "$T/err"'
check "... the frames before it kept and readable, none after, manifest status blow-up" kept "$T/a" "dt_min"

sed 's/^rule r2: .*/rule r2: tip == 0 \&\& time > 0.55 -> grow 1e300/' "$LIMB" >"$T/grow.sds"
run sds run "$T/grow.sds" --t-end 1 --frames 10 --out "$T/b" --quiet
check "a runaway growth rule: exit 3, one line naming the radius" eval \
  'rc_is 3 && one_line && grep -q "blow-up in step" "$T/err" && grep -q "radius .* not positive and finite" "$T/err"'
check "... frames 0-5 (t < 0.55) kept and readable, none after, manifest status blow-up" eval \
  'kept "$T/b" "radius" && test -s "$T/b/sds/frame_0005.ply" && test ! -e "$T/b/sds/frame_0006.ply"'
finish
