#!/usr/bin/env bash
# A reef on a heightfield image (docs/reef.md, "Seabed"): a 16-bit PNG and a
# one-channel EXR of a known analytic surface, the bases on that surface,
# and bad images refused with exit 2, one line naming the JSON path,
# nothing written.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3
command -v oiiotool >/dev/null || { echo "FAIL oiiotool (openimageio-tools) is needed"; exit 1; }

# The surface f(x, y) in [0, 1] on a 41 x 31 grid over 4 x 3 m, sample (i, j)
# at (i dx, j dy).  The PNG holds round(65535 f), its top row y = 3 m; the
# PFM (for oiiotool's EXR) holds f as float, its first row y = 0.
"$PY" - "$T" <<'PYEOF'
import math, struct, sys, zlib
d = sys.argv[1]; W, H = 41, 31
f = lambda i, j: 0.5 + 0.3 * math.sin(0.31 * i) * math.cos(0.17 * j) + 0.15 * j / (H - 1)
def png(path, w, h, depth, colour, rows):
    chunk = lambda t, b: struct.pack(">I", len(b)) + t + b + struct.pack(">I", zlib.crc32(t + b))
    raw = b"".join(b"\0" + r for r in rows)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, 0))
                            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
q = [[round(65535 * f(i, H - 1 - r)) for i in range(W)] for r in range(H)]  # image row r: j = H - 1 - r
png(d + "/h.png", W, H, 16, 0, [b"".join(struct.pack(">H", v) for v in row) for row in q])
open(d + "/h.pfm", "wb").write(b"Pf\n%d %d\n-1.0\n" % (W, H) +
                               b"".join(struct.pack("<f", f(i, j)) for j in range(H) for i in range(W)))
png(d + "/h8.png", W, H, 8, 0, [bytes(100 for _ in range(W)) for _ in range(H)])
png(d + "/rgb.png", W, H, 16, 2, [bytes(6 * W) for _ in range(H)])
png(d + "/thin.png", 1, 5, 16, 0, [bytes(2) for _ in range(5)])
png(d + "/huge.png", 5000, 2, 16, 0, [bytes(10000) for _ in range(2)])
open(d + "/rgb.pfm", "wb").write(b"PF\n4 4\n-1.0\n" + struct.pack("<f", 0.5) * 48)
open(d + "/text.png", "w").write("not an image\n")
PYEOF
oiiotool "$T/h.pfm" -d float -o "$T/h.exr" && oiiotool "$T/rgb.pfm" -o "$T/rgb.exr"
mkfifo "$T/fifo.png"

scene() { # image path, output scene
  "$PY" - "$1" "$2" <<'PYEOF'
import json, sys
json.dump({"seabed": {"image": {"path": sys.argv[1], "extent": [4, 3], "height_scale": 2, "base": -5}},
           "pool": [{"name": "ball", "generator": "sphere", "parameters": ["level=1", "iterations=1"],
                     "size": [0.05, 0.08], "depth": [0, 10]}],
           "brushes": [{"points": [[0.5, 0.5], [3.5, 2.5]], "size": 0.6, "density": 6, "kind": "automatic"}]},
          open(sys.argv[2], "w"))
PYEOF
}
# Every base against the bilinear interpolation of the exact samples:
# z = -5 + 2 f.  Tolerance: the PNG's quantisation, half a level times the
# height scale (2 * 0.5 / 65535 = 1.5e-5 m); the EXR's float samples,
# 2 * 2^-24 relative (1e-6 m covers both) plus rounding.
on_surface() { # run folder, tolerance (m)
  "$PY" - "$1" "$2" <<'PYEOF'
import json, math, sys
W, H, ex, ey = 41, 31, 4.0, 3.0
f = lambda i, j: 0.5 + 0.3 * math.sin(0.31 * i) * math.cos(0.17 * j) + 0.15 * j / (H - 1)
pl = json.load(open(sys.argv[1] + "/placements.json"))["placements"]
err = 0
for p in pl:
    x, y, z = p["position"]
    gx, gy = x / (ex / (W - 1)), y / (ey / (H - 1))
    i, j = min(int(gx), W - 2), min(int(gy), H - 2)
    u, v = gx - i, gy - j
    h = (f(i, j) * (1 - u) + f(i + 1, j) * u) * (1 - v) + (f(i, j + 1) * (1 - u) + f(i + 1, j + 1) * u) * v
    err = max(err, abs(z - (-5 + 2 * h)))
print(len(pl), "placements, largest height error", err, "m")
sys.exit(0 if len(pl) >= 10 and err <= float(sys.argv[2]) else 1)
PYEOF
}
scene "$T/h.png" "$T/png.json"
run reef "$T/png.json" --seed 2 --out "$T/p" --quiet --no-preview --set device_exposure=false
check "a 16-bit PNG seabed: the reef runs" rc_is 0
check "PNG: every base on the surface within the quantisation (1.5e-5 m)" on_surface "$T/p" 1.6e-5
scene "$T/h.exr" "$T/exr.json"
run reef "$T/exr.json" --seed 2 --out "$T/e" --quiet --no-preview --set device_exposure=false
check "a one-channel EXR seabed: the reef runs" rc_is 0
check "EXR: every base on the surface within float rounding (1e-6 m)" on_surface "$T/e" 1e-6

bad() { # description, image, text the one line must hold
  scene "$2" "$T/bad.json"
  run reef "$T/bad.json" --out "$T/never"
  want="$3"
  check "$1: exit 2, one line naming seabed.image.path ($3), nothing written" eval \
    'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -qF "seabed.image.path" "$T/err" && grep -qF "$want" "$T/err" && [ ! -e "$T/never" ]'
}
bad "an 8-bit PNG" "$T/h8.png" "8-bit"
bad "a colour PNG" "$T/rgb.png" "not a greyscale PNG"
bad "a text file named .png" "$T/text.png" "not a PNG"
bad "a 1 x 5 PNG" "$T/thin.png" "at least 2 x 2"
bad "a 5000 x 2 PNG" "$T/huge.png" "MiB of heights"
bad "a three-channel EXR" "$T/rgb.exr" "3 channels (B, G, R)"
bad "a FIFO (never waited on)" "$T/fifo.png" "not a regular file"
bad "a missing file" "$T/none.png" "cannot open"
bad "another format" "$T/h.pfm" "must name a .png"
"$PY" - "$T/png.json" "$T/bad.json" <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[1])); d["seabed"]["image"]["colour"] = 1; json.dump(d, open(sys.argv[2], "w"))
PYEOF
run reef "$T/bad.json" --out "$T/never"
check "an unknown key: exit 2 naming seabed.image.colour" eval 'rc_is 2 && grep -qF "seabed.image.colour" "$T/err" && [ ! -e "$T/never" ]'
finish
