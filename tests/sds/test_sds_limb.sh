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
# 0.17, 0.50, 0.80, 1.16, 1.26 at t = 20..100, W(100) = 0.00 (viscosity 1;
# 1.60 at t = 100 while frames cut steps; nearly undamped, 0.001, then:
# L(100) = 1.45, W = 0.10).
# Usage: test_sds_limb.sh SESSILE [--precision 32|64]: the fp32 kernels of a
# device without shaderFloat64 must grow the same limb (the manifest's device
# is checked to have run at the precision asked).
set -u
S="$1"
shift
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
bits=any # the device's default: 64 where it has shaderFloat64
[ "${1:-}" = "--precision" ] && bits="$2"

run "$@" sds run limb --t-end 100 --frames 5 --out "$T/l" --quiet
check "the limb model runs to t = 100" rc_is 0
check "the manifest names the device and its precision ($bits bits)" \
  "$PY" -c 'import json, sys; d = json.load(open(sys.argv[1]))["device"]; print(d); sys.exit(0 if str(d["precision_bits"]) in (("32", "64") if sys.argv[2] == "any" else (sys.argv[2],)) and d["name"] else 1)' \
  "$T/l/manifest.json" "$bits"
check "the limb's length rises frame by frame to >= 1 body radius, its width <= a quarter of its length, the tip leads" \
  "$PY" - "$T/l/sds" "$(dirname "$0")/../.." <<'PYEOF'
import os, sys
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(sys.argv[2], "tools", "sds"))
import limb
d = sys.argv[1]
L, W, lead = [], [], True
for i, (l, w, tx, front, tr) in enumerate(limb.measure(d, 5)):
    L.append(l), W.append(w)
    lead &= tx >= front - 2 * tr
    print("frame %d: tip at x = %.3f, front at %.3f, tip radius %.3f" % (i, tx, front, tr))
print("t = 0..100: L =", " ".join("%.2f" % l for l in L), " W =", " ".join("%.2f" % w for w in W))
ok = all(b >= a - 0.05 for a, b in zip(L, L[1:])) and L[-1] >= 1.0 and W[-1] <= 0.25 * L[-1] and lead
sys.exit(0 if ok else 1)
PYEOF
finish
