#version 450
#extension GL_GOOGLE_include_directive : require
// Jacobi inverse diagonal of the masked 7-point operator: 1/(6h) on free
// nodes, 1 on Dirichlet nodes, computed from the device mask (no host copy).
#include "la_kernels.glsl"
#include "stencil7.glsl"
void main() {
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  uint i = node % pc.n0, t = node / pc.n0;
  uint j = t % pc.n1, k = t / pc.n1;
  y[pc.yoff + node] = (st_wall(i, j, k) || mask[node] != 0u) ? REAL(1) : REAL(1) / (REAL(6) * pc.h);
}
