#version 450
#extension GL_GOOGLE_include_directive : require
// y = b - A x for the advective cut-cell operator (CUT_ADV) on a multigrid
// level, exactly 0 on Dirichlet nodes (as mg_residual.comp).
#define CUT_TEXEL 1
#define CUT_ADV 1
#include "stencil7_cut.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  y[node] = ct_mask(node) != 0u ? REAL(0) : texel_real(b_t, node) - ct_apply(node);
}
