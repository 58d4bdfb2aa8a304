"""The one-limb model's length and width from a run's frames (issue 13).

Length along the tip's axis +x: L(t) = (max x - min x) - 2 R0, the body's
extent along the axis less its starting diameter (R0 = 1, the icosphere);
width W(t) = the largest extent across the axis less 2 R0.  Used by
tests/sds/test_sds_limb.sh and tools/sds/step_study.sh; reads sessile's
binary PLY frames (sds/frame_NNNN.ply)."""
import numpy as np


def read_ply(path):
    """sessile's binary PLY: float vertex properties, then faces."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    head = data[:end].decode().splitlines()
    assert "format binary_little_endian 1.0" in head, head[:3]
    nv = int([h for h in head if h.startswith("element vertex")][0].split()[2])
    fields, invert = [], False  # (name, numpy type); the colours are uchar
    types = {"float": "<f4", "uchar": "u1"}
    for h in head:
        if h.startswith("element vertex"): invert = True
        elif h.startswith("element face"): invert = False
        elif invert and h.startswith("property") and h.split()[1] in types:
            fields.append((h.split()[2], types[h.split()[1]]))
        elif invert and h.startswith("property"): raise SystemExit("unexpected vertex property " + h)
    v = np.frombuffer(data, dtype=np.dtype(fields), count=nv, offset=end)
    return {p: v[p].astype(float) for p, t in fields if t == "<f4"}


def measure(sds_dir, nframes, r0=1.0):
    """Per frame 0..nframes: (L, W, tip x, front x, tip radius)."""
    out = []
    for i in range(nframes + 1):
        p = read_ply("%s/frame_%04d.ply" % (sds_dir, i))
        x = np.stack([p["x"], p["y"], p["z"]], 1)
        tips = np.flatnonzero(p["tip"] == 1)
        assert len(tips) == 1, "one tip cell, found %d" % len(tips)
        t = tips[0]
        out.append((np.ptp(x[:, 0]) - 2 * r0, max(np.ptp(x[:, 1]), np.ptp(x[:, 2])) - 2 * r0,
                    x[t, 0], x[:, 0].max(), p["radius"][t]))
    return out
