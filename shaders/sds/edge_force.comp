#version 450
#extension GL_GOOGLE_include_directive : require
// One edge per invocation: the force of the scale-free edge spring
// E = k/2 ((L - R')/R')^2, R' = s_m (r_a + r_b), k = k_edge R' (m_a + m_b)
// (times the surface multiplier on surface edges), on its second cell b
// (cell a gets the opposite).  Mirrors edge_force in host/sds/sds_physics.c.
#include "sds_common.glsl"

void main() {
  uint e = sessile_gid();
  if (e >= pc.nedges) return;
  uint a = topo[o_edge() + 2u * e], b = topo[o_edge() + 2u * e + 1u];
  REAL esm = sm[pc.ntets + e];
  REAL d0 = x[3u * b] - x[3u * a], d1 = x[3u * b + 1u] - x[3u * a + 1u], d2 = x[3u * b + 2u] - x[3u * a + 2u];
  REAL L = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
  REAL R = esm * (R_OF(a) + R_OF(b));
  REAL kk = sp[SP_K_EDGE] * (topo[o_esurf() + e] != 0u ? sp[SP_SURF] : REAL(1)) * (esm * (R_OF(a) + R_OF(b)) * (M_OF(a) + M_OF(b)));
  REAL g = kk * (L - R) / (R * R) / L;
  elf[12u * pc.ntets + 3u * e] = -g * d0;
  elf[12u * pc.ntets + 3u * e + 1u] = -g * d1;
  elf[12u * pc.ntets + 3u * e + 2u] = -g * d2;
}
