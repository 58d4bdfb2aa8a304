#version 450
#extension GL_GOOGLE_include_directive : require
// Growth (eqs 9-10, 1-2): g = clamp(Gr Lmax C^n / (K + C^n), 0, maxgrowth);
// a vertex moves by g along N (radiate accretive) or normalize(N + r),
// r uniform in [-R, R]^3 from the counter-based hash (Halichondrid), only
// where C > nutrient threshold (Iroquois) and g > growth threshold; the new
// position is clamped into the box.  Reference: sessile_growth_ref_grow.
#include "growth_common.glsl"

void main() {
  uint v = sessile_gid();
  if (v >= pc.nv) return;
  REAL dir[3] = REAL[3](nrm[3u * v], nrm[3u * v + 1u], nrm[3u * v + 2u]);
  if (pc.halichondrid != 0u) {
    REAL d[3];
    for (uint a = 0u; a < 3u; a++) {
      precise REAL u = growth_uniform(v, a);
      precise REAL r = gp[P_R] * (REAL(2) * u - REAL(1));
      d[a] = dir[a] + r;
    }
    precise REAL l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (l > REAL(0))
      for (int a = 0; a < 3; a++) dir[a] = d[a] / l;
  }
  REAL c = ctr[v];
  REAL g = REAL(0);
  if (c > REAL(0)) {
    precise REAL cn = real_pow(c, gp[P_N]);
    precise REAL num = gp[P_GR] * gp[P_LMAX] * cn;
    g = clamp(num / (gp[P_K] + cn), REAL(0), gp[P_MAXG]);
  }
  if (!(c > gp[P_NTHR] && g > gp[P_GTHR])) g = REAL(0);
  REAL lo[3] = REAL[3](gp[P_OX], gp[P_OY], gp[P_OZ]);
  REAL hi[3] = REAL[3](gp[P_MX], gp[P_MY], gp[P_MZ]);
  for (uint a = 0u; a < 3u; a++) {
    precise REAL x = pos[3u * v + a] + g * dir[a];
    new_pos[3u * v + a] = clamp(x, lo[a], hi[a]);
    dir_out[3u * v + a] = dir[a];
  }
  len[v] = g;
}
