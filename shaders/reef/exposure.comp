#version 450
#extension GL_GOOGLE_include_directive : require
// Exposure of an organism to the currents (Coralize §4.3; docs/reef.md,
// "Currents"), operation by operation as host/reef/currents.c: inside the
// hemisphere (radius strength, on the current's side of its origin) and
// not sheltered: 1 within the nutrition range of the current's ray, range /
// distance beyond it; sheltered when a sample of the segment to the source
// lies below the seabed.
#include "reef_kernels.glsl"

REAL height(REAL x, REAL y, out bool inside) {
  inside = x >= REAL(0) && x <= pc.ex && y >= REAL(0) && y <= pc.ey;
  if (!inside) return REAL(0);
  precise REAL gx = x / pc.dx;
  precise REAL gy = y / pc.dy;
  uint i = min(uint(gx), pc.nx - 2u), j = min(uint(gy), pc.ny - 2u);
  precise REAL u = gx - REAL(i);
  precise REAL v = gy - REAL(j);
  uint r0 = j * pc.nx + i, r1 = r0 + pc.nx;
  precise REAL z = (h[r0] * (REAL(1) - u) + h[r0 + 1u] * u) * (REAL(1) - v) + (h[r1] * (REAL(1) - u) + h[r1 + 1u] * u) * v;
  return z;
}

bool sheltered(REAL p[3], REAL o[3]) {
  precise REAL ax = abs(o[0] - p[0]) / pc.dx;
  precise REAL ay = abs(o[1] - p[1]) / pc.dy;
  precise REAL steps = ceil(REAL(2) * max(ax, ay));
  uint n = uint(min(steps, REAL(RC_MAX_MARCH))) + 1u;
  n = max(n, 2u);
  for (uint k = 1u; k < n; k++) {
    precise REAL t = REAL(k) / REAL(n);
    precise REAL x = p[0] + t * (o[0] - p[0]);
    precise REAL y = p[1] + t * (o[1] - p[1]);
    precise REAL z = p[2] + t * (o[2] - p[2]);
    bool inside;
    REAL hz = height(x, y, inside);
    if (inside && hz > z + REAL(1e-6)) return true;
  }
  return false;
}

void main() {
  uint k = sessile_gid();
  if (k >= pc.n) return;
  REAL p[3] = REAL[3](pos[3u * k], pos[3u * k + 1u], pos[3u * k + 2u]);
  precise REAL sum = REAL(0);
  for (uint c = 0u; c < pc.ncur; c++) {
    uint b = c * uint(RC_COUNT);
    REAL o[3] = REAL[3](cur[b], cur[b + 1u], cur[b + 2u]);
    precise REAL vx = p[0] - o[0];
    precise REAL vy = p[1] - o[1];
    precise REAL vz = p[2] - o[2];
    precise REAL along = vx * cur[b + 3u] + vy * cur[b + 4u] + vz * cur[b + 5u];
    precise REAL d2 = vx * vx + vy * vy + vz * vz;
    REAL R = cur[b + uint(RC_STRENGTH)], r = cur[b + uint(RC_RANGE)];
    if (d2 > R * R || along < REAL(0)) continue;
    precise REAL g2 = max(d2 - along * along, REAL(0));
    precise REAL e = g2 <= r * r ? REAL(1) : r / sqrt(g2);
    if (!sheltered(p, o)) sum += e;
  }
  expo[k] = sum;
}
