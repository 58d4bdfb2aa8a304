#version 450
#extension GL_GOOGLE_include_directive : require
// The skeleton's signed distance at every grid node, one workgroup per
// brick of 8^3 nodes (each invocation a column of 8 along z): the fold (in
// segment order) of the capsules listed for the brick, by min or the smooth
// union, clamped to at most clampv, and the nearest capsule (ties to the
// lowest index); boundary nodes are outside (clampv) so the surface is
// closed.  The brick, hence every list and capsule load, is uniform in the
// workgroup: lavapipe then loads once per subgroup instead of per lane, and
// each capsule is loaded once for 8 nodes.  As weld_node_value (weld_grid.c).
#include "mesh_kernels.glsl"
#include "weld_common.glsl"

void main() {
  uint b = sessile_group();
  if (b >= pc.bx * pc.by * pc.bz) return;
  uint l = gl_LocalInvocationID.x;
  uint bxi = b % pc.bx, byi = (b / pc.bx) % pc.by, bzi = b / (pc.bx * pc.by);
  uint x = bxi * 8u + (l & 7u), y = byi * 8u + ((l >> 3) & 7u), z0 = bzi * 8u;
  bool interior_xy = x > 0u && y > 0u && x + 1u < pc.nx && y + 1u < pc.ny;
  precise REAL px = pc.lox + pc.h * REAL(x), py = pc.loy + pc.h * REAL(y);
  REAL pz[8], f[8], bd[8];
  uint best[8];
  for (uint j = 0u; j < 8u; j++) {
    pz[j] = pc.loz + pc.h * REAL(z0 + j);
    f[j] = REAL(1e30);
    bd[j] = REAL(0);
    best[j] = 0xFFFFFFFFu;
  }
  // a capsule nearer by under 2^-30 h is a tie (to the first listed): a
  // GPU contracts a*b+c into FMA, which moves exact ties (a ring's joints)
  // by an ulp either way (docs/weld.md, "Vertex value")
  REAL tie = REAL(9.313225746154785e-10) * pc.h;
  uint e1 = boff[b + 1u];
  for (uint e = boff[b]; e < e1; e++) {
    uint c = blist[e];
    for (uint j = 0u; j < 8u; j++) {
      REAL d = capsule_sdf(c, px, py, pz[j]);
      f[j] = pc.blend > REAL(0) ? weld_smin(f[j], d, pc.blend) : min(f[j], d);
      if (best[j] == 0xFFFFFFFFu || d < bd[j] - tie) best[j] = c, bd[j] = d;
    }
  }
  for (uint j = 0u; j < 8u; j++) {
    uint z = z0 + j;
    if (x >= pc.nx || y >= pc.ny || z >= pc.nz) continue;
    bool interior = interior_xy && z > 0u && z + 1u < pc.nz;
    uint i = x + pc.nx * (y + pc.ny * z);
    field[i] = interior ? min(f[j], pc.clampv) : pc.clampv;
    nnear[i] = best[j];
  }
}
