#version 450
#extension GL_GOOGLE_include_directive : require
// The nearest vein node of every auxin: the rings of grid cells outward from
// the auxin's cell until no unvisited node can be as close; ties go to the
// lowest node index.  Operation by operation as grid_one in
// host/coral/venation_grid.c, so the fp64 build returns the host's node.
#include "coral_kernels.glsl"

const uint NN_NONE = 0xFFFFFFFFu; // SESSILE_VENATION_NONE

void main() {
  uint i = sessile_gid();
  if (i >= pc.m) return;
  REAL p[3] = REAL[3](pts[3u * i], pts[3u * i + 1u], pts[3u * i + 2u]);
  int d[3] = int[3](int(pc.d0), int(pc.d1), int(pc.d2));
  REAL h = gp[NN_H];
  int c[3];
  for (int a = 0; a < 3; a++) {
    precise REAL x = (p[a] - gp[NN_LO + a]) / h;
    c[a] = x <= REAL(0) ? 0 : x >= REAL(d[a] - 1) ? d[a] - 1 : int(x);
  }
  REAL best = REAL(0);
  uint bi = NN_NONE;
  REAL tol = gp[NN_TOL];
  for (int r = 0;; r++) {
    for (int z = c[2] - r; z <= c[2] + r; z++) {
      if (z < 0 || z >= d[2]) continue;
      for (int y = c[1] - r; y <= c[1] + r; y++) {
        if (y < 0 || y >= d[1]) continue;
        bool full = abs(z - c[2]) == r || abs(y - c[1]) == r;
        int stp = full || r == 0 ? 1 : 2 * r;
        for (int x = c[0] - r; x <= c[0] + r; x += stp) {
          if (x < 0 || x >= d[0]) continue;
          uint cell = uint(x) + pc.d0 * (uint(y) + pc.d1 * uint(z));
          uint e1 = cell_off[cell + 1u];
          for (uint e = cell_off[cell]; e < e1; e++) {
            uint j = cell_node[e];
            precise REAL dx = p[0] - node[3u * j];
            precise REAL dy = p[1] - node[3u * j + 1u];
            precise REAL dz = p[2] - node[3u * j + 2u];
            precise REAL dd = dx * dx + dy * dy + dz * dz;
            if (bi == NN_NONE || dd < best || (dd == best && j < bi)) {
              best = dd;
              bi = j;
            }
          }
        }
      }
    }
    bool bounded = false;
    REAL lb = REAL(0);
    for (int a = 0; a < 3; a++) {
      if (c[a] - r > 0) {
        precise REAL f = p[a] - (gp[NN_LO + a] + REAL(c[a] - r) * h);
        lb = bounded ? min(lb, f) : f;
        bounded = true;
      }
      if (c[a] + r + 1 < d[a]) {
        precise REAL f = gp[NN_LO + a] + REAL(c[a] + r + 1) * h - p[a];
        lb = bounded ? min(lb, f) : f;
        bounded = true;
      }
    }
    if (!bounded) break;
    if (bi != NN_NONE && best < lb * lb * (REAL(1) - tol)) break;
  }
  near[i] = bi;
  dist2[i] = best;
}
