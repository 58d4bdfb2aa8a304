#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x for the cut-cell 7-point operator (stencil7_cut.glsl), storage-buffer reads.
#define CUT_TEXEL 0
#include "stencil7_cut.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  y[pc.yoff + node] = ct_apply(node);
}
