// One edge per invocation: the force of the scale-free edge spring
// E = k/2 ((L - R')/R')^2, R' = s_m (r_a + r_b), k = k_edge R' (m_a + m_b)
// (k = k_edge alone with uniform stiffness, sp[SP_UNIFORM] = 1: the paper's
// "same stiffnesses throughout"), times the surface multiplier and the
// spring's own edge_k on surface edges, on its second cell b
// (cell a gets the opposite); in mode 2 also the edge's term of the stable
// bound (stable.glsl).  Mirrors edge_force in host/sds/sds_physics.c.
#include "sds_common.glsl"
#include "sds_load.glsl"

void edge_force_at(uint e) {
  if (e >= pc.nedges || (pc.batch != 0u && ev[0] != 0u)) return; // a batch that stopped
  uint a = LD_TOPO(o_edge() + 2u * e), b = LD_TOPO(o_edge() + 2u * e + 1u);
  REAL esm = LD_SM(pc.ntets + e);
  REAL d0 = LD_X(3u * b) - LD_X(3u * a), d1 = LD_X(3u * b + 1u) - LD_X(3u * a + 1u), d2 = LD_X(3u * b + 2u) - LD_X(3u * a + 2u);
  REAL L = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
  REAL R = esm * (R_OF(a) + R_OF(b));
  bool uni = sp[SP_UNIFORM] != REAL(0);
  REAL mult = LD_TOPO(o_esurf() + e) != 0u ? sp[SP_SURF] * LD_SM(pc.ntets + pc.nedges + e) : REAL(1);
  REAL kk = sp[SP_K_EDGE] * mult * (uni ? REAL(1) : esm * (R_OF(a) + R_OF(b)) * (M_OF(a) + M_OF(b)));
  REAL g = kk * (L - R) / (R * R) / L;
  elf[12u * pc.ntets + 3u * e] = -g * d0;
  elf[12u * pc.ntets + 3u * e + 1u] = -g * d1;
  elf[12u * pc.ntets + 3u * e + 2u] = -g * d2;
  if (pc.mode == 2u) { // the stable bound's term of both cells, 2 K_e, K_e = s_k / R'^2 (sessile_sds_stable_dt's order)
    precise REAL ks = sp[SP_K_EDGE] * mult;
    precise REAL K = uni ? ks / (R * R) : ks * (M_OF(a) + M_OF(b)) / R;
    elf[20u * pc.ntets + 3u * pc.nedges + e] = REAL(2) * K;
  }
}

#ifndef SDS_ELEM_FUSED
void main() { edge_force_at(sessile_gid()); }
#endif
