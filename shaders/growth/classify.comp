#version 450
#extension GL_GOOGLE_include_directive : require
// Solid classification, one invocation per box column (i, j): the crossings
// of the vertical line through the column with its binned triangles by the
// watertight edge-function rule, then each node's parity of the crossings at
// or below it.  Mirrors host/growth/classify_ref.c operation by operation.
#include "growth_common.glsl"

#define MAXC 64

// Edge function of directed edge i -> j at q, lower index first (so shared
// edges see exactly opposite values), zeros broken by the (eps, eps^2) shift.
REAL edge_fn(uint i, uint j, REAL qx, REAL qy, out int sgn) {
  uint lo = min(i, j), hi = max(i, j);
  REAL ax = pos[3u * lo], ay = pos[3u * lo + 1u];
  precise REAL dx = pos[3u * hi] - ax;
  precise REAL dy = pos[3u * hi + 1u] - ay;
  precise REAL px = qx - ax;
  precise REAL py = qy - ay;
  precise REAL l = dx * py;
  precise REAL r = dy * px;
  precise REAL e = l - r;
  int s = e > REAL(0) ? 1 : (e < REAL(0) ? -1 : (dy != REAL(0) ? (dy > REAL(0) ? -1 : 1) : (dx > REAL(0) ? 1 : -1)));
  if (i > j) {
    e = -e;
    s = -s;
  }
  sgn = s;
  return e;
}

void main() {
  uint c = sessile_gid();
  if (c >= pc.ncols) return;
  uint i = c % pc.n0, j = c / pc.n0;
  precise REAL x = gp[P_OX] + gp[P_H] * REAL(i);
  precise REAL y = gp[P_OY] + gp[P_H] * REAL(j);
  REAL z[MAXC];
  int n = 0;
  for (uint q = col_off[c]; q < col_off[c + 1u]; q++) {
    uint f = col_tri[q];
    uint t0 = tri[3u * f], t1 = tri[3u * f + 1u], t2 = tri[3u * f + 2u];
    int s0, s1, s2;
    REAL e0 = edge_fn(t0, t1, x, y, s0);
    REAL e1 = edge_fn(t1, t2, x, y, s1);
    REAL e2 = edge_fn(t2, t0, x, y, s2);
    if (s0 != s1 || s1 != s2) continue;
    if (n == MAXC) {
      atomicCompSwap(status[0], 0u, c + 1u);
      return;
    }
    precise REAL sum = e0 + e1 + e2;
    REAL za = pos[3u * t0 + 2u], zb = pos[3u * t1 + 2u], zc = pos[3u * t2 + 2u];
    precise REAL num = e1 * za + e2 * zb;
    num = num + e0 * zc;
    precise REAL third = (za + zb + zc) / REAL(3);
    z[n++] = sum != REAL(0) ? num / sum : third;
  }
  for (int a = 1; a < n; a++) {
    REAL v = z[a];
    int b = a - 1;
    while (b >= 0 && z[b] > v) {
      z[b + 1] = z[b];
      b--;
    }
    z[b + 1] = v;
  }
  int below = 0;
  uint layer = pc.n0 * pc.n1;
  for (uint k = 0u; k < pc.n2; k++) {
    precise REAL zk = gp[P_OZ] + gp[P_H] * REAL(k);
    while (below < n && z[below] <= zk) below++;
    solid[c + layer * k] = uint(below & 1);
  }
}
