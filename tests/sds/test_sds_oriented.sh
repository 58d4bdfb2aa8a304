#!/usr/bin/env bash
# The oriented growth (axial_growth; docs/sds.md, "Oriented growth"): a
# growing cell's edges share its growth out by their direction against the
# gradient of the morphogen declared axis=1.
#  - a ball whose cells all grow (no division) for 40 time units, its axis
#    phi's gradient from a tip at +x: its extent along x over the mean of y
#    and z. Measured (2026-12-01): 0.93 isotropic (A = 0; the tip does not
#    grow), 1.56 with A = 1 (all along the axis), 0.72 with A = -0.5 (all
#    across). Asserted: A = 1 at least 1.3 x the isotropic ratio, A = -0.5
#    at most 0.85 x; both far outside what the isotropic run's own x and y
#    differ by;
#  - the fast limb (Delta 0.03) to t = 6 with A = 0.5: another run than
#    A = 0, and a run stopped by SIGINT after frame 2 and resumed gives the
#    same bytes (the springs' s_m in the checkpoint);
#  - refusals before the run folder exists: with device_loop (the loop on
#    the device does not run it), without an axis morphogen, A out of
#    [-0.5, 1].
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
. "$(dirname "$0")/sds_runs.sh"
PY=/usr/bin/python3
M="$(dirname "$0")/../../host/sds/models"

cat >"$T/ball.sds" <<'SDS'
model ball growing along an axis
sphere_radius = 1
sphere_subdivisions = 1
gravity = 0
self_collide = 0
t_end = 40
frames = 2
morphogen phi diffusion=0.05 decay=0.3 axis=1
state tip = 0
tip 1 0 0
rule r1: tip == 1 -> set phi = volume
rule r2: tip == 0 -> grow 0.004
SDS
# extent along x over the mean extent along y and z, the surface cells of a PLY
aspect() {
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
e = np.array([np.ptp(v["x"]), np.ptp(v["y"]), np.ptp(v["z"])], dtype=float)
print("%.6f %.6f" % (e[0] / (0.5 * (e[1] + e[2])), abs(e[1] - e[2]) / e[1]))
PYEOF
}
for A in 0 1 -0.5; do
  run sds run "$T/ball.sds" --set axial_growth=$A --out "$T/ball$A" --quiet --no-preview
  check "the growing ball, axial_growth $A: completes" rc_is 0
  aspect "$T/ball$A/sds/final.ply" >"$T/asp$A"
  echo "axial_growth $A: x / yz, |y - z| / y = $(cat "$T/asp$A")"
done
read -r a0 n0 <"$T/asp0"
read -r a1 _ <"$T/asp1"
read -r am _ <"$T/asp-0.5"
check "isotropic: the ball keeps its shape across the axis (|y - z| / y <= 0.02)" \
  "$PY" -c 'import sys; sys.exit(0 if float(sys.argv[1]) <= 0.02 else 1)' "$n0"
check "A = 1: the ball lengthens along the axis (x / yz >= 1.3 x the isotropic)" \
  "$PY" -c 'import sys; sys.exit(0 if float(sys.argv[1]) >= 1.3 * float(sys.argv[2]) else 1)' "$a1" "$a0"
check "A = -0.5: it widens across it (x / yz <= 0.85 x the isotropic)" \
  "$PY" -c 'import sys; sys.exit(0 if float(sys.argv[1]) <= 0.85 * float(sys.argv[2]) else 1)' "$am" "$a0"

# the fast limb with its axis
sed 's/^const Delta = .*/const Delta = 0.03/; s/^morphogen phi diffusion=0.05 decay=0.3/morphogen phi diffusion=0.05 decay=0.3 axis=1/' \
  "$M/limb.sds" >"$T/fast.sds"
check "the fast limb with an axis was made" grep -q "axis=1" "$T/fast.sds"
run sds run "$T/fast.sds" --t-end 6 --frames 5 --out "$T/iso" --quiet
check "fast limb, isotropic: completes" rc_is 0
run sds run "$T/fast.sds" --t-end 6 --frames 5 --out "$T/og" --quiet --set axial_growth=0.5
check "fast limb, axial_growth 0.5: completes" rc_is 0
check "... another run than the isotropic one (the last frame differs)" eval \
  '! cmp -s "$T/og/sds/frame_0005.ply" "$T/iso/sds/frame_0005.ply"'
interrupt_resume "axial_growth 0.5" "$T/fast.sds" "$T/ir" 2 "$T/og" --set axial_growth=0.5

# refusals
run sds run "$T/fast.sds" --t-end 1 --frames 1 --out "$T/r1" --quiet --set axial_growth=0.5 --set device_loop=true
check "with device_loop: refused (exit 2), one line naming both, no run folder" eval \
  'rc_is 2 && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "axial_growth" "$T/err" && grep -q "device_loop" "$T/err" && test ! -e "$T/r1"'
sed 's/ axis=1//' "$T/fast.sds" >"$T/noaxis.sds"
run sds run "$T/noaxis.sds" --t-end 1 --frames 1 --out "$T/r2" --quiet --set axial_growth=0.5
check "without a morphogen declared axis=1: refused (exit 2), naming both, no run folder" eval \
  'rc_is 2 && grep -q "axial_growth" "$T/err" && grep -q "axis=1" "$T/err" && test ! -e "$T/r2"'
for bad in 1.5 -0.6 nan; do
  run sds run "$T/fast.sds" --t-end 1 --frames 1 --out "$T/r3" --quiet --set axial_growth=$bad
  check "axial_growth $bad: refused (exit 2), naming it, no run folder" eval \
    'rc_is 2 && grep -q "axial_growth" "$T/err" && test ! -e "$T/r3"'
done
finish
