#version 450
#extension GL_GOOGLE_include_directive : require
// Solid classification and cut cells, one invocation per box line along
// pc.axis (indexed by the two other axes in cyclic order u, v): the crossings
// of the line with its binned triangles by the watertight edge-function
// rule; along z each node's parity of the crossings at or below it is the
// solid mask; with pc.want_theta each node's fractions of h to the nearest
// crossing towards its two neighbours on the line (1: none).  Mirrors
// cut_line in host/growth/classify_ref.c operation by operation.
#include "growth_common.glsl"

#define MAXC 64

// Edge function of directed edge i -> j at q, lower index first (so shared
// edges see exactly opposite values), zeros broken by the (eps, eps^2) shift.
REAL edge_fn(uint u, uint v, uint i, uint j, REAL qx, REAL qy, out int sgn) {
  uint lo = min(i, j), hi = max(i, j);
  REAL ax = pos[3u * lo + u], ay = pos[3u * lo + v];
  precise REAL dx = pos[3u * hi + u] - ax;
  precise REAL dy = pos[3u * hi + v] - ay;
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
  uint ax = pc.axis, u = (ax + 1u) % 3u, v = (ax + 2u) % 3u;
  uint nn[3] = uint[3](pc.n0, pc.n1, pc.n2);
  uint i = c % nn[u], j = c / nn[u];
  precise REAL x = gp[P_OX + u] + gp[P_H] * REAL(i);
  precise REAL y = gp[P_OX + v] + gp[P_H] * REAL(j);
  REAL z[MAXC];
  int n = 0;
  for (uint q = col_off[c]; q < col_off[c + 1u]; q++) {
    uint f = col_tri[q];
    uint t0 = tri[3u * f], t1 = tri[3u * f + 1u], t2 = tri[3u * f + 2u];
    int s0, s1, s2;
    REAL e0 = edge_fn(u, v, t0, t1, x, y, s0);
    REAL e1 = edge_fn(u, v, t1, t2, x, y, s1);
    REAL e2 = edge_fn(u, v, t2, t0, x, y, s2);
    if (s0 != s1 || s1 != s2) continue;
    if (n == MAXC) {
      atomicCompSwap(status[ax], 0u, c + 1u);
      return;
    }
    precise REAL sum = e0 + e1 + e2;
    REAL za = pos[3u * t0 + ax], zb = pos[3u * t1 + ax], zc = pos[3u * t2 + ax];
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
  uint cc[3];
  cc[u] = i;
  cc[v] = j;
  uint stride = ax == 0u ? 1u : (ax == 1u ? pc.n0 : pc.n0 * pc.n1);
  for (uint k = 0u; k < nn[ax]; k++) {
    cc[ax] = k;
    uint node = cc[0] + pc.n0 * (cc[1] + pc.n1 * cc[2]);
    precise REAL tk = gp[P_OX + ax] + gp[P_H] * REAL(k);
    int prev = below;
    while (below < n && z[below] <= tk) below++;
    if (ax == 2u) solid[node] = uint(below & 1);
    if (pc.want_theta == 0u) continue;
    theta[6u * node + 2u * ax] = REAL(1);
    theta[6u * node + 2u * ax + 1u] = REAL(1);
    if (k > 0u && below > prev) {
      uint pn = node - stride;
      precise REAL tp = gp[P_OX + ax] + gp[P_H] * REAL(k - 1u);
      precise REAL dp = z[prev] - tp;
      precise REAL dm = tk - z[below - 1];
      theta[6u * pn + 2u * ax + 1u] = dp / gp[P_H];
      theta[6u * node + 2u * ax] = dm / gp[P_H];
    }
  }
}
