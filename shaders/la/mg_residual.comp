#version 450
#extension GL_GOOGLE_include_directive : require
// y = b - A x on a multigrid level, exactly 0 on Dirichlet nodes (the
// restriction then needs no mask).
#define CUT_TEXEL 1
#include "stencil7_cut.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  y[node] = ct_mask(node) != 0u ? REAL(0) : texel_real(b_t, node) - ct_apply(node);
}
