#version 450
#extension GL_GOOGLE_include_directive : require
// Eq 6: probed = (1/S) sum_k w(d_k) c(x + d_k offset N), d_k = k/(S-1),
// w(d) = 1/(20 d + 1); c is the P1 interpolant of the nutrient field on the
// box (point location mirrors sessile_box_locate).
#include "growth_common.glsl"

void main() {
  uint v = sessile_gid();
  if (v >= pc.nv) return;
  precise REAL sum = REAL(0);
  for (uint k = 0u; k < pc.samples; k++) {
    precise REAL d = REAL(k) / REAL(pc.samples - 1u);
    precise REAL s = d * gp[P_OFFSET];
    REAL p[3];
    for (uint a = 0u; a < 3u; a++) {
      precise REAL t = s * nrm[3u * v + a];
      p[a] = pos[3u * v + a] + t;
    }
    uint nd[4];
    REAL w[4];
    box_locate(p, nd, w);
    precise REAL c = w[0] * field[nd[0]] + w[1] * field[nd[1]];
    c = c + w[2] * field[nd[2]];
    c = c + w[3] * field[nd[3]];
    precise REAL att = REAL(1) / (REAL(20) * d + REAL(1));
    sum += att * c;
  }
  probed[v] = sum / REAL(pc.samples);
}
