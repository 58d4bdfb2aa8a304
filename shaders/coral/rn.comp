#version 450
#extension GL_GOOGLE_include_directive : require
// Closed venation's relative neighbourhood (Runions §4): candidate v of
// auxin s is blocked when a candidate u closer to s (cd2[u] < cd2[v]) is
// also closer to v than s is (|u - v|^2 < cd2[v]).  The lists are sorted by
// cd2, so only the entries before v can block it.  Operation by operation as
// relative_neighbourhood in host/coral/venation.c.
#include "coral_kernels.glsl"

const uint RN_SKIP = 0xFFFFFFFFu; // the host handles this entry's auxin

void main() {
  uint k = sessile_gid();
  if (k >= pc.total) return;
  uint b = start[k];
  if (b == RN_SKIP) return;
  uint v = cand[k];
  REAL dv = cd2[k];
  REAL pv[3] = REAL[3](node[3u * v], node[3u * v + 1u], node[3u * v + 2u]);
  uint hit = 0u;
  for (uint t = b; t < k; t++) {
    if (cd2[t] < dv) {
      uint u = cand[t];
      precise REAL dx = node[3u * u] - pv[0];
      precise REAL dy = node[3u * u + 1u] - pv[1];
      precise REAL dz = node[3u * u + 2u] - pv[2];
      precise REAL dd = dx * dx + dy * dy + dz * dz;
      if (dd < dv) {
        hit = 1u;
        break;
      }
    }
  }
  blocked[k] = hit;
}
