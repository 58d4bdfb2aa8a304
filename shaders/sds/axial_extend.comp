#version 450
#extension GL_GOOGLE_include_directive : require
// Convergent extension in a batch step, one edge per invocation
// (kernels.def, SDS_AXIAL_EXTEND): sds_axial_extend_edges
// (host/sds/sds_axial.c) operation for operation, `precise` against fused
// multiply-adds, so that the batch gives the host-driven loop's s_m to the
// bit.
#include "sds_kernels.glsl"

REAL dot3(REAL a0, REAL a1, REAL a2, REAL b0, REAL b1, REAL b2) {
  precise REAL d = a0 * b0 + a1 * b1 + a2 * b2;
  return d;
}

void main() {
  uint e = sessile_gid();
  if (e >= pc.nedges) return;
  if (event[SDS_EV_SKIP] != 0u) return; // the host makes this step's rules, the extension with them
  uint a = topo[4u * pc.ntets + 2u * e], b = topo[4u * pc.ntets + 2u * e + 1u];
  if (state[a * pc.nstate + pc.sext] == REAL(0) || state[b * pc.nstate + pc.sext] == REAL(0)) return;
  precise REAL g0 = grad[3u * a] + grad[3u * b], g1 = grad[3u * a + 1u] + grad[3u * b + 1u],
               g2 = grad[3u * a + 2u] + grad[3u * b + 2u];
  precise REAL d0 = x[3u * a] - x[3u * b], d1 = x[3u * a + 1u] - x[3u * b + 1u], d2 = x[3u * a + 2u] - x[3u * b + 2u];
  REAL dd = dot3(d0, d1, d2, d0, d1, d2), gg = dot3(g0, g1, g2, g0, g1, g2);
  if (!(dd > REAL(0) && gg > REAL(0))) return; // no axis here
  REAL c = dot3(d0, d1, d2, g0, g1, g2);
  precise REAL c2 = c * c / (dd * gg);
  REAL dt = konst[pc.kctl + 3u]; // the step's dt (morph_bound's control, SDS_CTL)
  precise REAL f = REAL(1) + pc.extend * dt * (REAL(3) * c2 - REAL(1));
  sm[pc.ntets + e] *= f;
}
