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
