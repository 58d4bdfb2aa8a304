// Shared GLSL of the SDS kernels: vector helpers and the rest size of a
// tetrahedron (Appendix A), operation by operation as host/sds/sds_rest.c.
#ifndef SDS_COMMON_GLSL
#define SDS_COMMON_GLSL
#include "sds_kernels.glsl"

// Offsets into topo (kernels.def); the host's are in sds_gpu_buffers.c.
uint o_tet() { return 0u; }
uint o_edge() { return 4u * pc.ntets; }
uint o_ceo() { return o_edge() + 2u * pc.nedges; }
uint o_cto() { return o_ceo() + pc.ncells + 1u; }
uint o_ce() { return o_cto() + pc.ncells + 1u; }
uint o_ct() { return o_ce() + 2u * pc.nedges; }
uint o_tsurf() { return o_ct() + 4u * pc.ntets; }
uint o_esurf() { return o_tsurf() + pc.ntets; }
uint o_face() { return o_esurf() + pc.nedges; }
uint o_csurf() { return o_face() + 3u * pc.nfaces; }
// 1 when a tet's signed volume (eq 1, times 6) is <= 0 or not finite: an
// inverted tet (§3.1.2), from its edge vectors a, b, c from its first
// corner.  precise (no fused multiply-adds), so that inverted.glsl and
// tet_force.glsl (a batch's flags) give the same bits.
uint tet_inverted(REAL a[3], REAL b[3], REAL c[3]) {
  precise REAL V = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  return (V > REAL(0) && is_finite(V)) ? 0u : 1u;
}
#define R_OF(c) LD_RM(2u * (c)) // LD_*: sds_load.glsl
#define M_OF(c) LD_RM(2u * (c) + 1u)

REAL tet_rest(REAL a, REAL b, REAL c, REAL d) {
  REAL w = a * b * c;
  REAL x = d * sqrt(b * c * (a + b + d) * (a + c + d));
  REAL y = d * sqrt(a * c * (a + b + d) * (b + c + d));
  REAL z = d * sqrt(a * b * (a + c + d) * (b + c + d));
  REAL A = w + x + y - z, B = w + x - y + z, C = w - x + y + z, D = -w + x + y + z;
  return sqrt(A * B * C * D) / (REAL(3) * (a + d) * (b + d) * (c + d));
}
#endif
