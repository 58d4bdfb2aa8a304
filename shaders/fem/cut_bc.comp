#version 450
#extension GL_GOOGLE_include_directive : require
// Dirichlet nodes of the cut-cell nutrient around its solve: mode 0 zeroes
// them (the homogenised unknown; free entries keep the warm start), mode 1
// writes their values back (docs/nutrient.md).
#include "fem_kernels.glsl"

void main() {
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2 || mask[node] == CUT_FREE) return;
  c[node] = pc.want_lift == 0u ? REAL(0) : value[node];
}
