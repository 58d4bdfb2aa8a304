#version 450
#extension GL_GOOGLE_include_directive : require
// The nearest vein node of every auxin: the rings of grid cells outward from
// the auxin's cell until no unvisited node can be as close; ties go to the
// lowest node index.  Operation by operation as grid_one in
// host/coral/venation_grid.c, so the fp64 build returns the host's node.
// Each pass runs at most NN_BUDGET loop iterations per auxin, saves where it
// stopped (ring, cell, node entry) and counts itself in todo[0]; the host
// repeats the pass until none is left (see NN_BUDGET in kernels.def).
#include "coral_kernels.glsl"

const uint NN_NONE = 0xFFFFFFFFu; // SESSILE_VENATION_NONE

void main() {
  uint i = sessile_gid();
  if (i >= pc.m) return;
  uint sb = uint(NN_ST_COUNT) * i;
  uint status = st[sb + NN_ST_STATUS];
  if (status == 2u) return;
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
  int r = 0, rz = 0, ry = 0, rx = 0;
  uint re = 0u;
  bool resume = false;
  if (status == 1u) {
    best = dist2[i];
    bi = near[i];
    r = int(st[sb + NN_ST_R]);
    rz = int(st[sb + NN_ST_Z]);
    ry = int(st[sb + NN_ST_Y]);
    rx = int(st[sb + NN_ST_X]);
    re = st[sb + NN_ST_E];
    resume = true;
  }
  REAL tol = gp[NN_TOL];
  int work = 0;
  bool out_of_budget = false;
  for (;; r++) {
    int zlo = max(0, c[2] - r), zhi = min(d[2] - 1, c[2] + r);
    for (int z = resume ? rz : zlo; z <= zhi && !out_of_budget; z++) {
      int ylo = max(0, c[1] - r), yhi = min(d[1] - 1, c[1] + r);
      for (int y = resume ? ry : ylo; y <= yhi && !out_of_budget; y++) {
        // on the shell only: the two x ends unless y or z is on it
        bool full = abs(z - c[2]) == r || abs(y - c[1]) == r;
        int stp = full || r == 0 ? 1 : 2 * r;
        int xa = full ? max(0, c[0] - r) : c[0] - r, xb = full ? min(d[0] - 1, c[0] + r) : c[0] + r;
        for (int x = resume ? rx : xa; x <= xb && !out_of_budget; x += stp) {
          if (++work > NN_BUDGET) {
            out_of_budget = true;
            rz = z, ry = y, rx = x, re = NN_NONE; // this cell from its start
            break;
          }
          if (x < 0 || x >= d[0]) {
            resume = false;
            continue;
          }
          uint cell = uint(x) + pc.d0 * (uint(y) + pc.d1 * uint(z));
          uint e1 = cell_off[cell + 1u];
          uint e = resume && re != NN_NONE ? re : cell_off[cell];
          resume = false;
          for (; e < e1; e++) {
            if (++work > NN_BUDGET) {
              out_of_budget = true;
              rz = z, ry = y, rx = x, re = e;
              break;
            }
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
        resume = false;
      }
      resume = false;
    }
    if (out_of_budget) break;
    resume = false;
    // the nearest face of the visited box that has cells beyond it
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
  if (out_of_budget) {
    st[sb + NN_ST_R] = uint(r);
    st[sb + NN_ST_Z] = uint(rz);
    st[sb + NN_ST_Y] = uint(ry);
    st[sb + NN_ST_X] = uint(rx);
    st[sb + NN_ST_E] = re;
    st[sb + NN_ST_STATUS] = 1u;
    atomicAdd(todo[0], 1u);
  } else {
    st[sb + NN_ST_STATUS] = 2u;
  }
}
