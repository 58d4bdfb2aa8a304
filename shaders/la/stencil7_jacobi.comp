#version 450
#extension GL_GOOGLE_include_directive : require
// Jacobi inverse diagonal of the masked 7-point operator: 1/(6h) on free
// nodes, 1 on Dirichlet nodes, computed from the device mask (no host copy).
#include "../common/sessile.glsl"
layout(std430, binding = 0) buffer Scalars { REAL s[]; };
layout(std430, binding = 1) readonly buffer M { uint mask[]; };
layout(std430, binding = 2) readonly buffer X { REAL x[]; };  // unused (same layout as stencil7)
layout(std430, binding = 3) writeonly buffer Y { REAL y[]; };
#include "stencil7.glsl"
void main() {
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  uint i = node % pc.n0, t = node / pc.n0;
  uint j = t % pc.n1, k = t / pc.n1;
  y[pc.yoff + node] = (st_wall(i, j, k) || mask[node] != 0u) ? REAL(1) : REAL(1) / (REAL(6) * pc.h);
}
