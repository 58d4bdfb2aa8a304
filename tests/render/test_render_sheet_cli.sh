#!/usr/bin/env bash
# `sessile render --sheet COLS -o OUT.png A.png [--caption T] B.png ...`: the
# tiles are PNGs written here by Python (RGBA and RGB, patterns that differ
# in every pixel); the sheet must have the size of the layout formula of
# sessile/render/render2d.h (PAD 8, caption strip 22), every tile must equal its
# source pixel for pixel at the formula's offset, captions draw only where
# given, a rerun gives the same bytes, COLS above the count is reduced to it,
# and bad input exits 2 with one line and writes nothing.  PNGs are decoded
# by Python's zlib here, not by sessile's code.  No device is used.
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
PY=/usr/bin/python3

cat >"$T/png.py" <<'PYEOF'
import struct, sys, zlib

def chunk(kind, body):
    c = kind + body
    return struct.pack(">I", len(body)) + c + struct.pack(">I", zlib.crc32(c) & 0xFFFFFFFF)

def write(path, w, h, ch, seed):
    """A w x h picture of ch channels (3: RGB, 4: RGBA opaque) whose pixels differ."""
    rows = []
    for y in range(h):
        row = bytearray([0])
        for x in range(w):
            px = [(x * 7 + seed * 40) & 255, (y * 5 + seed * 90) & 255, (x * y + seed) & 255]
            row += bytes(px + ([255] if ch == 4 else []))
        rows.append(bytes(row))
    ctype = 6 if ch == 4 else 2
    d = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, ctype, 0, 0, 0))
         + chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b""))
    open(path, "wb").write(d)

def read(path):
    """-> (w, h, channels, rows of bytes), 8-bit RGB or RGBA, any row filter."""
    d = open(path, "rb").read()
    assert d[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat = 8, b""
    while at < len(d):
        n, = struct.unpack(">I", d[at:at + 4]); kind = d[at + 4:at + 8]; body = d[at + 8:at + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10]); assert depth == 8 and ctype in (2, 6)
            ch = 4 if ctype == 6 else 3
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw = zlib.decompress(idat); stride = ch * w; prev = bytearray(stride); out = []
    for y in range(h):
        f = raw[y * (stride + 1)]; line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0; b = prev[i]; c = prev[i - ch] if i >= ch else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out.append(bytes(line)); prev = line
    return w, h, ch, out

def rgba(img, x, y):
    w, h, ch, rows = img
    p = rows[y][ch * x:ch * x + ch]
    return tuple(p) + ((255,) if ch == 3 else ())

def check(sheet, cols, tiles, captioned):
    """Size, tiles at the formula's offsets, caption strips: exit 1 on a difference."""
    PAD, CAP = 8, 22
    imgs = [read(t) for t in tiles]
    n = len(imgs); cols = min(cols, n); rows = (n + cols - 1) // cols
    cw = max(i[0] for i in imgs); th = max(i[1] for i in imgs); chh = th + CAP
    W, H = PAD + cols * (cw + PAD), PAD + rows * (chh + PAD)
    s = read(sheet)
    print(f"sheet {s[0]}x{s[1]}, formula {W}x{H}")
    if (s[0], s[1]) != (W, H) or s[2] != 4:
        return 1
    bad = 0
    for k, img in enumerate(imgs):
        col, row = k % cols, k // cols
        cx, cy = PAD + col * (cw + PAD), PAD + row * (chh + PAD)
        x0 = cx + (cw - img[0]) // 2
        for y in range(img[1]):
            for x in range(img[0]):
                if rgba(s, x0 + x, cy + y) != rgba(img, x, y):
                    bad += 1
        ink = sum(1 for y in range(cy + th, cy + chh) for x in range(cx, cx + cw) if rgba(s, x, y) != (255, 255, 255, 255))
        print(f"tile {k}: {img[0]}x{img[1]} at ({x0}, {cy}); caption strip: {ink} non-white pixels")
        if (ink > 0) != (k in captioned):
            bad += 1
    print(f"{bad} differences")
    return 1 if bad else 0

if __name__ == "__main__":
    if sys.argv[1] == "write":
        write(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6]))
    else:
        sys.exit(check(sys.argv[2], int(sys.argv[3]), sys.argv[4].split(","),
                       [int(k) for k in sys.argv[5].split(",") if k]))
PYEOF

"$PY" "$T/png.py" write "$T/a.png" 100 60 4 1
"$PY" "$T/png.py" write "$T/b.png" 70 90 3 2
"$PY" "$T/png.py" write "$T/c.png" 120 50 4 3
"$PY" "$T/png.py" write "$T/wide.png" 9000 4 4 4
printf 'not a picture\n' >"$T/text.png"

run render --help
check "--help documents --sheet and --caption" eval 'rc_is 0 && grep -q "^  --sheet COLS" "$T/out" && grep -q "^  --caption TEXT" "$T/out"'

run render --sheet 2 -o "$T/sheet.png" "$T/a.png" --caption "tile a" "$T/b.png" "$T/c.png" --caption "tile c"
check "a sheet of 3 tiles (RGBA and RGB) in 2 columns: exit 0, one line" eval \
  'rc_is 0 && [ "$(wc -l <"$T/out")" = 1 ] && grep -q "3 pictures in 2 columns, 2 rows" "$T/out" && [ ! -s "$T/err" ]'
check "... 264x248 as the formula gives, tiles equal their sources, captions only under a and c" \
  "$PY" "$T/png.py" check "$T/sheet.png" 2 "$T/a.png,$T/b.png,$T/c.png" 0,2
run render --sheet 2 -o "$T/sheet2.png" "$T/a.png" --caption "tile a" "$T/b.png" "$T/c.png" --caption "tile c"
check "the same command twice: identical PNG bytes" cmp -s "$T/sheet.png" "$T/sheet2.png"
run render --sheet 5 --quiet -o "$T/row.png" "$T/c.png" "$T/a.png" "$T/b.png"
check "--sheet 5 with 3 tiles: one row of 3 (392x128), tiles equal, no caption ink, --quiet prints nothing" eval \
  'rc_is 0 && [ ! -s "$T/out" ] && "$PY" "$T/png.py" check "$T/row.png" 5 "$T/c.png,$T/a.png,$T/b.png" "" >/dev/null'

# bad input: exit 2, one line on stderr, nothing written, nothing on stdout
bad() { # description, args...
  local what="$1"; shift
  rm -f "$T/bad.png"
  run render "$@"
  check "bad input exits 2 with one line, writes nothing: $what" eval \
    'rc_is 2 && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "^sessile render: error: " "$T/err" && test ! -e "$T/bad.png" && [ ! -s "$T/out" ]'
}
bad "a missing tile" --sheet 2 -o "$T/bad.png" "$T/a.png" "$T/none.png"
bad "a tile that is not a PNG" --sheet 2 -o "$T/bad.png" "$T/a.png" "$T/text.png"
bad "--sheet 0" --sheet 0 -o "$T/bad.png" "$T/a.png"
bad "--sheet 1001" --sheet 1001 -o "$T/bad.png" "$T/a.png"
bad "--sheet abc" --sheet abc -o "$T/bad.png" "$T/a.png"
bad "no tiles" --sheet 2 -o "$T/bad.png"
bad "no -o" --sheet 2 "$T/a.png"
bad "-o not .png" --sheet 2 -o "$T/bad.jpg" "$T/a.png"
bad "-o in a missing folder" --sheet 2 -o "$T/no/bad.png" "$T/a.png"
bad "--caption before any tile" --sheet 2 --caption x -o "$T/bad.png" "$T/a.png"
bad "two captions for one tile" --sheet 2 -o "$T/bad.png" "$T/a.png" --caption x --caption y
bad "a mesh option" --sheet 2 -o "$T/bad.png" "$T/a.png" --view top
bad "a sheet over 16384 pixels" --sheet 2 -o "$T/bad.png" "$T/wide.png" "$T/wide.png"
check "... the last names the size and the limit" grep -q "18024 x .* (at most 16384 a side)" "$T/err"
finish
