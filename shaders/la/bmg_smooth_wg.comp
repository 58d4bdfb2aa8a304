#version 450
#extension GL_GOOGLE_include_directive : require
// A level's smoothing in one workgroup (kernels.def, K_BMG_SMOOTH_WG): the
// start from zero (BMG_ZERO: x = omega D^-1 b), then `sweeps` 8-colour block
// Gauss-Seidel sweeps in place, colour by colour with a barrier between
// them: the passes of bmg_smooth.comp in the same order, so the same bits,
// in one dispatch instead of 1 + 8 sweeps.  One chunk (row0 = 0).
#define BMG_TEXEL 1
#define BMG_X_STORAGE 1
#include "la_kernels.glsl"
#define BMG_ROWS
#include "bmg_common.glsl"

// One node's update from x (zero: from x = 0).
void update(uint node, bool zero) {
  REAL4 bn = bmg_tex4(b_t, node);
  REAL4 r = zero ? bn : bmg_row_residual(node, bn);
  uint d = 4u * node;
  REAL4 dz = REAL4(dot(bmg_tex4(dinv_t, d), r), dot(bmg_tex4(dinv_t, d + 1u), r), dot(bmg_tex4(dinv_t, d + 2u), r),
                   dot(bmg_tex4(dinv_t, d + 3u), r));
  x[node] = (zero ? REAL4(0) : x[node]) + pc.omega * dz;
}

void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return; // the same for every invocation
  uint lid = gl_LocalInvocationID.x, nodes = pc.n0 * pc.n1 * pc.n2;
  if ((pc.flags & BMG_ZERO) != 0u) {
    for (uint node = lid; node < nodes; node += gl_WorkGroupSize.x) update(node, true);
    memoryBarrierBuffer();
    barrier();
  }
  for (uint sw = 0u; sw < pc.sweeps; sw++) {
    bool back = (pc.flags & BMG_BACKWARD) != 0u;
    if ((pc.flags & BMG_ALTERNATE) != 0u && (sw & 1u) != 0u) back = !back;
    for (uint q = 0u; q < 8u; q++) {
      uint colour = back ? 7u - q : q;
      uvec3 par = uvec3(colour & 1u, (colour >> 1u) & 1u, (colour >> 2u) & 1u);
      uvec3 sub = (uvec3(pc.n0, pc.n1, pc.n2) - par + 1u) / 2u;
      uint count = sub.x * sub.y * sub.z;
      for (uint t = lid; t < count; t += gl_WorkGroupSize.x) {
        uint a = t / sub.x, kk = a / sub.y;
        uvec3 ijk = 2u * uvec3(t - a * sub.x, a - kk * sub.y, kk) + par;
        update(ijk.x + pc.n0 * (ijk.y + pc.n1 * ijk.z), false);
      }
      memoryBarrierBuffer();
      barrier();
    }
  }
}
