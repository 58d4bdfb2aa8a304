#version 450
#extension GL_GOOGLE_include_directive : require
// One explicit Euler step of the morphogens (Porter & McCormack §3.3):
//   lap = sum_n (min(n_phi, vol(c)) - min(c_phi, vol(n))) / |c_x - n_x|
//   out = clamp(phi + dt (D lap - C phi + src), 0, vol(c) or +inf)
// Operation for operation as sessile_morph_step (host/sds/morph.c); the
// neighbour sum runs in CSR order so every run gives the same bytes.
#include "sdsproc_kernels.glsl"

REAL vol_of(REAL r) {
  precise REAL v = REAL(4.0lf / 3.0lf * 3.14159265358979311600lf) * r * r * r;
  return v;
}

void main() {
  uint c = sessile_gid();
  if (c >= pc.ncells) return;
  uint nm = pc.nmorph;
  REAL cx = pos[3u * c], cy = pos[3u * c + 1u], cz = pos[3u * c + 2u];
  REAL vc = vol_of(radius[c]);
  uint a = nbr_off[c], b = nbr_off[c + 1u];
  // one pass over the neighbours for all morphogens (the distance and the
  // neighbour's volume once per neighbour); each morphogen's sum still runs
  // in CSR order, the same operations as one morphogen at a time
  precise REAL s[SDSPROC_MAX_MORPH];
  REAL p[SDSPROC_MAX_MORPH];
  for (uint k = 0u; k < nm; k++) s[k] = REAL(0), p[k] = phi_in[c * nm + k];
  for (uint q = a; q < b; q++) {
    uint n = nbr[q];
    precise REAL dx = cx - pos[3u * n], dy = cy - pos[3u * n + 1u], dz = cz - pos[3u * n + 2u];
    precise REAL d = sqrt(dx * dx + dy * dy + dz * dz);
    REAL vn = vol_of(radius[n]);
    for (uint k = 0u; k < nm; k++) {
      precise REAL t = min(phi_in[n * nm + k], vc) - min(p[k], vn);
      s[k] += t / d;
    }
  }
  for (uint k = 0u; k < nm; k++) {
    uint i = c * nm + k;
    precise REAL rate = coef[3u * k] * s[k] - coef[3u * k + 1u] * p[k];
    rate += src[i];
    precise REAL v = p[k] + pc.dt * rate;
    v = max(v, REAL(0));
    if (coef[3u * k + 2u] != REAL(0)) v = min(v, vc);
    phi_out[i] = v;
  }
}
