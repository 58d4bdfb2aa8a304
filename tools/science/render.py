"""A shaded picture of a surface as a PNG, with numpy and zlib only.

Orthographic view from an azimuth and elevation, Lambert shading of the
face normals under a light over the viewer's shoulder, a z-buffer built by
sampling every triangle densely (at least one sample per pixel it covers).
Good enough to see the sponge's shape; not a renderer.
"""
import struct
import zlib

import numpy as np


def write_png(path, rgb):
    """rgb: H x W x 3 uint8."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, payload):
        c = kind + payload
        return struct.pack(">I", len(payload)) + c + struct.pack(">I", zlib.crc32(c) & 0xFFFFFFFF)

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def render(V, F, width=480, height=360, azimuth=-55.0, elevation=25.0, extent=None, label_rows=None):
    """Returns an H x W x 3 uint8 picture of the surface.  extent: the half-width
    of the view in cm (default: fitted to the surface), so that pictures of
    several sponges can share a scale."""
    az, el = np.radians(azimuth), np.radians(elevation)
    fwd = -np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])  # view direction
    right = np.cross(fwd, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    c = 0.5 * (V.min(axis=0) + V.max(axis=0))
    P = V - c
    x, y, d = P @ right, P @ up, P @ fwd
    if extent is None:
        extent = 1.05 * max(np.abs(x).max(), np.abs(y).max() * width / height, 1e-9)
    s = 0.5 * width / extent
    px = x * s + 0.5 * width
    py = 0.5 * height - y * s
    # Flat shading: face normals, a light from above and behind the viewer.
    v0, v1, v2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    n = np.cross(v1 - v0, v2 - v0)
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-30)[:, None]
    light = -fwd + 0.6 * up - 0.3 * right
    light /= np.linalg.norm(light)
    facing = n @ -fwd > 0
    lam = np.clip(n @ light, 0, 1)
    shade = 0.25 + 0.75 * lam
    base = np.array([236, 196, 120], dtype=np.float64)  # sponge orange-yellow
    F = F[facing]
    shade = shade[facing]
    # Samples per triangle edge: enough to cover every pixel of it.
    tx, ty = px[F], py[F]
    span = np.max(np.hypot(tx - np.roll(tx, 1, axis=1), ty - np.roll(ty, 1, axis=1)), axis=1)
    k = np.clip(np.ceil(span * 1.5).astype(int), 1, 64)
    pix_all, dep_all, col_all = [], [], []
    for kk in np.unique(k):
        sel = np.nonzero(k == kk)[0]
        i, j = np.meshgrid(np.arange(kk + 1), np.arange(kk + 1), indexing="ij")
        keep = i + j <= kk
        a, b = i[keep] / kk, j[keep] / kk
        w = np.stack([1 - a - b, a, b], axis=1)  # samples x 3
        sx = tx[sel] @ w.T
        sy = ty[sel] @ w.T
        sd = d[F[sel]] @ w.T
        ix, iy = np.floor(sx).astype(np.int64), np.floor(sy).astype(np.int64)
        ok = (ix >= 0) & (ix < width) & (iy >= 0) & (iy < height)
        pix_all.append((iy * width + ix)[ok])
        dep_all.append(sd[ok])
        col_all.append(np.broadcast_to(shade[sel][:, None], sd.shape)[ok])
    img = np.empty((height * width, 3), dtype=np.float64)
    # Background: a vertical grey gradient.
    g = np.linspace(250, 205, height)[:, None].repeat(width, axis=1).reshape(-1)
    img[:] = g[:, None]
    if pix_all:
        pix, dep, col = np.concatenate(pix_all), np.concatenate(dep_all), np.concatenate(col_all)
        order = np.lexsort((dep, pix))  # by pixel, nearest (smallest depth) first
        pix, col = pix[order], col[order]
        first = np.unique(pix, return_index=True)[1]
        img[pix[first]] = col[first][:, None] * base[None, :]
    return np.clip(img.reshape(height, width, 3), 0, 255).astype(np.uint8)


def sheet(pictures, columns, pad=4):
    """Tiles equally sized pictures into rows of `columns`, white padding."""
    h, w, _ = pictures[0].shape
    rows = (len(pictures) + columns - 1) // columns
    out = np.full((rows * (h + pad) + pad, columns * (w + pad) + pad, 3), 255, dtype=np.uint8)
    for k, p in enumerate(pictures):
        r, c = divmod(k, columns)
        out[pad + r * (h + pad):pad + r * (h + pad) + h, pad + c * (w + pad):pad + c * (w + pad) + w] = p
    return out
