#!/usr/bin/env bash
# The one-limb model grows a limb (issue 13): the limb's length measured over
# time from the frames' surfaces.  Length along the tip's axis u = +x:
#   L(t) = (max u·x - min u·x) - 2 R0,
# the body's extent along the axis less its starting diameter (R0 = 1, the
# icosphere); width W(t) = the largest extent across the axis less 2 R0.
# Asserted: L grows frame by frame (a fall of at most 0.05 u: the surface
# breathes) to L(t = 100) >= 1.0 R0; the growth is a limb, not a swelling:
# W(100) <= 0.25 L(100); and the tip leads it: the tip cell (PLY property
# tip = 1, one surface cell) is within two of its radii of the front in every
# frame.  Measured (docs/sds_rules.md, "What the limb model grows"): L =
# 0.17, 0.55, 0.91, 1.19, 1.50 at t = 20..100, W(100) = 0.00 (viscosity 1;
# nearly undamped, 0.001: L(100) = 1.45, W = 0.10).
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3

run sds run limb --t-end 100 --frames 5 --out "$T/l" --quiet
check "the limb model runs to t = 100" rc_is 0
check "the limb's length rises frame by frame to >= 1 body radius, its width <= a quarter of its length, the tip leads" \
  "$PY" - "$T/l/sds" <<'PYEOF'
import sys, struct, numpy as np
d = sys.argv[1]

def read_ply(path):
    """sessile's binary PLY: float vertex properties, then faces."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    head = data[:end].decode().splitlines()
    assert "format binary_little_endian 1.0" in head, head[:3]
    nv = int([h for h in head if h.startswith("element vertex")][0].split()[2])
    props, invert = [], False
    for h in head:
        if h.startswith("element vertex"): invert = True
        elif h.startswith("element face"): invert = False
        elif invert and h.startswith("property float "): props.append(h.split()[2])
        elif invert and h.startswith("property"): raise SystemExit("unexpected vertex property " + h)
    v = np.frombuffer(data, dtype="<f4", count=nv * len(props), offset=end).reshape(nv, len(props))
    return {p: v[:, i].astype(float) for i, p in enumerate(props)}

L, W, lead = [], [], True
for i in range(6):
    p = read_ply("%s/frame_%04d.ply" % (d, i))
    x = np.stack([p["x"], p["y"], p["z"]], 1)
    L.append(np.ptp(x[:, 0]) - 2.0)
    W.append(max(np.ptp(x[:, 1]), np.ptp(x[:, 2])) - 2.0)
    tips = np.flatnonzero(p["tip"] == 1)
    assert len(tips) == 1, "one tip cell, found %d" % len(tips)
    lead &= x[tips[0], 0] >= x[:, 0].max() - 2 * p["radius"][tips[0]]
    print("frame %d: tip at x = %.3f, front at %.3f, tip radius %.3f" % (i, x[tips[0], 0], x[:, 0].max(), p["radius"][tips[0]]))
print("t = 0..100: L =", " ".join("%.2f" % l for l in L), " W =", " ".join("%.2f" % w for w in W))
ok = all(b >= a - 0.05 for a, b in zip(L, L[1:])) and L[-1] >= 1.0 and W[-1] <= 0.25 * L[-1] and lead
sys.exit(0 if ok else 1)
PYEOF
finish
