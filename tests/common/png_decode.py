"""PNG decoding for the shell tests (8-bit RGBA, every filter), with
Python's zlib, not sessile's code: decode(path) -> (w, h, rows of bytes)."""
import struct, zlib
from itertools import accumulate
def decode(path):
    d = open(path, "rb").read()
    assert d[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    at, idat = 8, b""
    while at < len(d):
        n, = struct.unpack(">I", d[at:at + 4]); kind = d[at + 4:at + 8]; body = d[at + 8:at + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10]); assert depth == 8 and ctype == 6
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw = zlib.decompress(idat); stride = 4 * w; prev = bytearray(stride); rows = []
    for y in range(h):
        f = raw[y * (stride + 1)]; line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 1:  # SUB (what sessile writes): a running sum per channel
            for c in range(4):
                line[c::4] = bytes(accumulate(line[c::4], lambda a, b: (a + b) & 255))
        elif f:
            for i in range(stride):
                a = line[i - 4] if i >= 4 else 0; b = prev[i]; c = prev[i - 4] if i >= 4 else 0
                if f == 2: line[i] = (line[i] + b) & 255
                elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
                elif f == 4:
                    p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line)); prev = line
    return w, h, rows
