#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x for the masked 7-point operator (common/stencil7.glsl): the P1
// Laplacian of the Kuhn box with Dirichlet rows/columns eliminated.
#include "la_kernels.glsl"
#include "stencil7.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  y[pc.yoff + node] = st_apply(node);
}
