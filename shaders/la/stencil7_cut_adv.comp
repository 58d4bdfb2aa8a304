#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x for the advective cut-cell operator (stencil7_cut.glsl with
// CUT_ADV: the weighted neighbours of host/la/stencil_cut_adv.c), texel reads.
#define CUT_TEXEL 1
#define CUT_ADV 1
#include "stencil7_cut.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  y[pc.yoff + node] = ct_apply(node);
}
